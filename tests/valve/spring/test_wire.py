"""Wire cross-sections (springdyn.valve.spring.wire) against the published closed forms, and the
ovate-wire beehive example against a continuum of the same drawing.

Every reference here is written in this file from its source, not called from the code under
test: Saint-Venant's series for the rectangle and the ellipse's torsion (Timoshenko & Goodier,
*Theory of Elasticity*, 3rd ed., 1970, secs. 105 and 109, and their Table 7), a finite-difference
solution of Prandtl's stress function (the same sections, numerically), Roark's rectangular-wire
stress factor and EN 13906-1's Bergstraesser factor, the spring's rate ``4 G J/(pi D^3 n)`` and a
continuum (the wave equation of the wire with properties varying along it) of the beehive.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
import scipy.sparse as sps
from scipy.linalg import eigh_tridiagonal
from scipy.sparse.linalg import spsolve

from springdyn.core.errors import FactWarning, InputError
from springdyn.valve import ValveModel, ValveSpring
from springdyn.valve.spring import wire as wire_module
from tests.paths import EXAMPLES

#: Timoshenko & Goodier, Table 7: side ratio l/t -> (alpha, beta) of tau_max = T/(alpha l t^2),
#: J = beta l t^3 (three digits printed).
TIMOSHENKO_TABLE_7 = {
    1.0: (0.208, 0.141),
    1.5: (0.231, 0.196),
    2.0: (0.246, 0.229),
    2.5: (0.258, 0.249),
    3.0: (0.267, 0.263),
    4.0: (0.282, 0.281),
    5.0: (0.291, 0.291),
    10.0: (0.312, 0.312),
}

#: The one-step example's coils and steel (docs/references.md [MMS]) with a section of its own.
ONE_STEP = dict(
    type="one-step",
    mean_diameter="22 mm",
    free_length="48 mm",
    installed_length="38 mm",
    dead_coils=1.0,
    low_pitch_coils=0.0,
    high_pitch_coils=7.5,
    youngs_modulus="206 GPa",
    shear_modulus="78.5 GPa",
    density="7850 kg/m^3",
    damping_ratio=0.05,
)


# ---------------------------------------------------------------------- the references, written here
def saint_venant_rectangle(long, short, terms=200):
    """(J, T/tau_max) of a rectangle: Timoshenko & Goodier sec. 109, Eqs. (166)-(170)."""
    n = np.arange(1, 2 * terms, 2)
    k1 = (1 - 192 / math.pi**5 * short / long * sum(math.tanh(m * math.pi * long / (2 * short)) / m**5 for m in n)) / 3
    k = 1 - 8 / math.pi**2 * sum(1 / (m * m * math.cosh(min(m * math.pi * long / (2 * short), 700))) for m in n)
    j = k1 * long * short**3
    return j, j / (short * k)


def ellipse(width, height):
    """(J, T/tau_max) of an ellipse of axes ``width`` and ``height``: Timoshenko & Goodier sec. 105."""
    a, b = width / 2, height / 2
    return math.pi * a**3 * b**3 / (a * a + b * b), math.pi * max(a, b) * min(a, b) ** 2 / 2


def prandtl(inside, half_width, half_height, n=161):
    """(J, T/tau_max) of a section by finite differences of Prandtl's stress function:
    ``lap(phi) = -2`` inside, ``phi = 0`` outside; ``J = 2 int phi dA``, ``tau = |grad phi|`` at G
    theta = 1 (Timoshenko & Goodier sec. 101; five-point Laplacian on an n x n grid)."""
    x = np.linspace(-half_width, half_width, n)
    y = np.linspace(-half_height, half_height, n)
    hx, hy = x[1] - x[0], y[1] - y[0]
    xx, yy = np.meshgrid(x, y, indexing="ij")
    mask = inside(xx, yy)
    mask[0, :] = mask[-1, :] = mask[:, 0] = mask[:, -1] = False
    idx = -np.ones(mask.shape, dtype=int)
    idx[mask] = np.arange(mask.sum())
    rows, cols, vals = [], [], []
    for i, j in zip(*np.nonzero(mask)):
        k = idx[i, j]
        rows.append(k)
        cols.append(k)
        vals.append(-2 / hx**2 - 2 / hy**2)
        for di, dj, h in ((1, 0, hx), (-1, 0, hx), (0, 1, hy), (0, -1, hy)):
            if mask[i + di, j + dj]:
                rows.append(k)
                cols.append(idx[i + di, j + dj])
                vals.append(1 / h**2)
    a = sps.csr_matrix((vals, (rows, cols)), shape=(mask.sum(), mask.sum()))
    phi = np.zeros(mask.shape)
    phi[mask] = spsolve(a, -2 * np.ones(mask.sum()))
    j = 2 * phi.sum() * hx * hy
    # the largest stress of these sections is at the middle of the longer side (x = 0, y = the
    # edge): the slope of phi there from a quartic through the central column and phi = 0 at the edge
    column = phi[n // 2, mask[n // 2]]
    ys = y[mask[n // 2]]
    edge = half_height  # the section's edge on its shorter axis
    near = ys > 0.5 * edge
    fit = np.polynomial.Polynomial.fit(np.append(ys[near], edge), np.append(column[near], 0.0), 4)
    return j, j / abs(fit.deriv()(edge))


def roark_rectangular_factor(w):
    """Roark's factor of rectangular wire, ``1 + 1.2 (c/R) + 0.56 (c/R)^2 + 0.5 (c/R)^3``, c/R = 1/w."""
    return 1 + 1.2 / w + 0.56 / w**2 + 0.5 / w**3


def en13906_k(w):
    """EN 13906-1 Eq. (22): k = (w + 0.5)/(w - 0.75)."""
    return (w + 0.5) / (w - 0.75)


# ---------------------------------------------------------------------- sections
@pytest.mark.parametrize("ratio", sorted(TIMOSHENKO_TABLE_7))
def test_rectangle_against_timoshenko_table_7(ratio):
    """alpha and beta of the rectangle within the table's printed digits (half a unit of the third
    decimal, 0.0005, plus 1e-4 for the table's own rounding of its series)."""
    alpha, beta = TIMOSHENKO_TABLE_7[ratio]
    j, z = wire_module.rectangle_torsion(ratio, 1.0)  # radial long side
    assert j / ratio == pytest.approx(beta, abs=6e-4)
    assert z / ratio == pytest.approx(alpha, abs=6e-4)
    j2, z2 = wire_module.rectangle_torsion(1.0, ratio)  # axial long side: the same bar
    assert (j2, z2) == pytest.approx((j, z), abs=0, rel=1e-12)
    ref_j, ref_z = saint_venant_rectangle(ratio * 3e-3, 3e-3)
    j3, z3 = wire_module.rectangle_torsion(ratio * 3e-3, 3e-3)
    assert j3 == pytest.approx(ref_j, abs=0, rel=1e-10) and z3 == pytest.approx(
        ref_z, abs=0, rel=1e-10
    )  # the series converged


@pytest.mark.parametrize("width,height", [(4.0e-3, 3.2e-3), (3.0e-3, 4.5e-3), (3.5e-3, 3.5e-3)])
def test_ellipse_against_its_closed_form(width, height):
    """The ovate section is Timoshenko & Goodier's ellipse (round when the axes agree), to 1e-12."""
    sec = wire_module.WireSection("ovate", width, height)
    j, z = ellipse(width, height)
    assert sec.torsion_constant == pytest.approx(j, abs=0, rel=1e-12)
    assert sec.stress_modulus == pytest.approx(z, abs=0, rel=1e-12)
    assert sec.area == pytest.approx(math.pi * width * height / 4, abs=0, rel=1e-12)


def test_prandtl_stress_function_confirms_the_closed_forms():
    """A numerical solution of the torsion problem (finite differences, 161 x 161 nodes) agrees
    with the ellipse's closed form (J within 2 %, the largest stress within 3 %: the staircase of
    grid nodes stands for the curved boundary, an O(h) error, found 1.5 % and 2.7 %) and with the
    rectangle's series (0.1 %: its boundary lies on the grid, an O(h^2) error, found 0.02 %)."""
    b, h = 4.0e-3, 3.2e-3
    j, z = prandtl(lambda x, y: (x / (b / 2)) ** 2 + (y / (h / 2)) ** 2 < 1, b / 2, h / 2)
    sec = wire_module.WireSection("ovate", b, h)
    assert j == pytest.approx(sec.torsion_constant, abs=0, rel=0.02)
    assert z == pytest.approx(sec.stress_modulus, abs=0, rel=0.03)
    j, z = prandtl(lambda x, y: (np.abs(x) < b / 2) & (np.abs(y) < h / 2), b / 2, h / 2)
    sec = wire_module.WireSection("rectangular", b, h)
    assert j == pytest.approx(sec.torsion_constant, abs=0, rel=1e-3)
    assert z == pytest.approx(sec.stress_modulus, abs=0, rel=1e-3)


def test_round_wire_is_unchanged():
    """Round wire keeps EN 13906-1 exactly: J = pi d^4/32, tau = k 8 F D/(pi d^3), its rate diameter d."""
    from springdyn.valve.spring.stress import corrected_shear_stress

    sec = wire_module.WireSection("round", 3.5e-3, 3.5e-3)
    assert sec.shear_stress(500.0, 22e-3) == pytest.approx(
        float(corrected_shear_stress(500.0, 22e-3, 3.5e-3)), rel=1e-14
    )
    assert sec.rate_diameter == sec.mass_diameter == sec.surge_diameter == 3.5e-3
    s = ValveSpring.example("one-step")
    assert s.spring_model.internal_parameters()["K1"] == pytest.approx(25143.23272402842, abs=0, rel=1e-14)


# ---------------------------------------------------------------------- springs of each wire
@pytest.mark.parametrize(
    "shape,width,height", [("rectangular", 3.6e-3, 3.0e-3), ("rectangular", 3.0e-3, 4.2e-3), ("ovate", 4.0e-3, 3.2e-3)]
)
def test_type_c_rate_mass_surge_and_stress_of_profiled_wire(shape, width, height):
    """Type C of an ovate or rectangular wire: K1 = 4 G J/(pi D^3 n) (Wahl ch. 12: the torsion of the
    wire), M = rho A pi D (N - 0.7) ([MMS]'s mass with the section's area), f1 = sqrt(G J/(rho A))/(pi
    (n + n1') D^2) (the wave equation; Wahl's round-wire form with J and A), the solid length of the
    axial height, and the installed stress with Roark's (rectangular) or Bergstraesser's (ovate)
    factor at w = D/b: each to 1e-9 (round-off)."""
    spring = ValveSpring.from_dict(
        {**ONE_STEP, "wire_shape": shape, "wire_width": f"{width * 1e3} mm", "wire_height": f"{height * 1e3} mm"}
    )
    g, rho, d_mean, n = 78.5e9, 7850.0, 22e-3, 5.5
    j, z = (
        ellipse(width, height) if shape == "ovate" else saint_venant_rectangle(max(width, height), min(width, height))
    )
    area = math.pi * width * height / 4 if shape == "ovate" else width * height
    p = spring.spring_model.internal_parameters()
    assert p["K1"] == pytest.approx(4 * g * j / (math.pi * d_mean**3 * n), abs=0, rel=1e-9)
    assert p["M"] == pytest.approx(rho * area * math.pi * d_mean * (7.5 - 0.7), abs=0, rel=1e-9)
    n1p = (48e-3 - height * (7.5 - 1)) / (n * d_mean)  # [MMS] n1' with the axial height
    assert p["f1"] == pytest.approx(
        math.sqrt(g * j / (rho * area)) / (math.pi * (n + n1p) * d_mean**2), abs=0, rel=1e-9
    )
    assert spring.solid_length == pytest.approx(height * 8.0, abs=0, rel=1e-12)  # the document's (N + 0.5) h
    fig = spring.spring_model.design_figures()
    w = d_mean / width
    factor = roark_rectangular_factor(w) if shape == "rectangular" else en13906_k(w)
    tau = factor * fig["installed"]["force_N"] * d_mean / 2 / z
    assert fig["installed"]["shear_stress_Pa"] == pytest.approx(tau, abs=0, rel=1e-9)
    assert fig["stress_factor"] == pytest.approx(factor, abs=0, rel=1e-12)
    # the factor is named by what it is: Goehner's (Roark) for rectangular wire, never "Bergstraesser"
    named = "Goehner" if shape == "rectangular" else "Bergstraesser"
    assert named in fig["stress_factor_name"] and named in spring.wire.stress_factor_name
    text = ValveModel(spring).design_figures(lift=2e-3).describe().splitlines()[0]
    assert f"stress factor {factor:.4f} ({fig['stress_factor_name']})" in text
    assert ("Bergstraesser" in text) == (shape == "ovate")


def test_roark_factor_against_hand_values():
    """Roark's rectangular-wire factor at w = 4, 6, 10 by hand (1 + 0.3 + 0.035 + 0.0078125 = 1.3428125 ...)."""
    assert wire_module.rectangular_curvature_factor(4.0) == pytest.approx(1.3428125, abs=0, rel=1e-14)
    assert wire_module.rectangular_curvature_factor(6.0) == pytest.approx(1.2178703703703704, abs=0, rel=1e-14)
    assert wire_module.rectangular_curvature_factor(10.0) == pytest.approx(1.1261, abs=0, rel=1e-14)


def test_ovate_of_equal_axes_is_round_wire():
    """An ovate wire of equal axes is round wire: the same model figures to 1e-9."""
    ovate = ValveSpring.from_dict({**ONE_STEP, "wire_shape": "ovate", "wire_width": "3.5 mm", "wire_height": "3.5 mm"})
    round_ = ValveSpring.from_dict({**ONE_STEP, "wire_diameter": "3.5 mm"})
    a, b = ovate.spring_model.internal_parameters(), round_.spring_model.internal_parameters()
    for key in ("K1", "M", "f1", "f2", "Fset", "Fcon", "m1", "m2"):
        assert a[key] == pytest.approx(b[key], abs=0, rel=1e-9)
    fa, fb = ovate.spring_model.design_figures(lift=8e-3), round_.spring_model.design_figures(lift=8e-3)
    assert fa["open"]["shear_stress_Pa"] == pytest.approx(fb["open"]["shear_stress_Pa"], abs=0, rel=1e-9)


@pytest.mark.parametrize(
    "keys,message",
    [
        ({"wire_diameter": "3.5 mm", "wire_width": "4 mm"}, "wire_width applies to ovate and rectangular"),
        ({"wire_shape": "ovate", "wire_width": "4 mm"}, "needs wire_width .* missing wire_height"),
        ({"wire_shape": "ovate", "wire_diameter": "3.5 mm"}, "takes wire_width .* not wire_diameter"),
        (
            {"wire_shape": "rectangular", "wire_width": "4 mm", "wire_height": "3 mm", "wire_diameter": "3.5 mm"},
            "disagree",
        ),
        ({"wire_shape": "rectangular", "wire_width": "40 mm", "wire_height": "3 mm"}, "between 0.2 and 5"),
        ({"wire_shape": "oval", "wire_width": "4 mm", "wire_height": "3 mm"}, "wire_shape"),
        (
            {
                "wire_shape": "ovate",
                "wire_width": "4 mm",
                "wire_height": "3 mm",
                "wire_diameter_profile": [[0, "3 mm"], [7.5, "3 mm"]],
            },
            "wire_diameter_profile is a round wire",
        ),
    ],
)
def test_inconsistent_wire_keys_are_refused(keys, message):
    """Each inconsistent combination of the wire's keys is one InputError naming them."""
    with pytest.raises(InputError, match=message):
        ValveSpring.from_dict({**ONE_STEP, **keys})


def test_outer_diameter_of_profiled_wire_uses_the_radial_width():
    """outer_diameter gives D = De - b with the radial width b of profiled wire."""
    s = ValveSpring.from_dict(
        {
            **{k: v for k, v in ONE_STEP.items() if k != "mean_diameter"},
            "outer_diameter": "26 mm",
            "wire_shape": "rectangular",
            "wire_width": "4 mm",
            "wire_height": "3 mm",
        }
    )
    assert s.mean_diameter == pytest.approx(22e-3, abs=1e-12)


# ---------------------------------------------------------------------- a wire diameter along the coil
def _open_turn_compliance(d_mean, pitch, g, e, j, i_bend):
    """Axial compliance per turn of an open helix, torsion and bending (Wahl ch. 3, energy method)."""
    a = np.arctan2(pitch, np.pi * d_mean)
    return np.pi * d_mean**3 / (4 * np.cos(a)) * (np.cos(a) ** 2 / (g * j) + np.sin(a) ** 2 / (e * i_bend))


def test_varying_wire_diameter_enters_the_distributed_model_coil_by_coil():
    """A round wire tapering from 3.7 mm at the seat to 3.3 mm at the retainer: the distributed
    model's rate at free length is the continuum's series of its turns with the end contacts,
    ``1/K1 = int c(s) ds + 1/K_seat + 1/K_ret``, to 1e-5 (the model's 64 midpoint slices per
    element against 20000 here); its mass ``rho int pi d^2/4 sqrt((pi D)^2 + p^2) ds`` to 1e-4 (the
    dead coils' 65-point trapezoid); its solid length ``int d ds + 0.5 d_ends`` exactly; a constant
    profile reproduces the spring without one to 1e-9."""
    base = {**ONE_STEP, "model": "distributed", "wire_diameter": "3.5 mm"}
    flat = ValveSpring.from_dict({**base, "wire_diameter_profile": [[0, "3.5 mm"], [7.5, "3.5 mm"]]})
    plain = ValveSpring.from_dict(base)
    np.testing.assert_allclose(
        flat.spring_model.modes(38e-3, 3), plain.spring_model.modes(38e-3, 3), rtol=1e-9
    )  # the same spring
    taper = ValveSpring.from_dict(
        {
            **{k: v for k, v in base.items() if k != "wire_diameter"},
            "wire_diameter_profile": [[0, "3.7 mm"], [7.5, "3.3 mm"]],
        }
    )
    assert taper.wire_diameter == pytest.approx(3.7e-3, abs=0, rel=1e-12)  # the largest: the nominal wire
    geo = taper.spring_model.geometry  # the drawing's pitch (the spring's input)
    g, e, rho = 78.5e9, 206e9, 7850.0
    s = np.linspace(1.0, 6.5, 20001)
    mid, ds = 0.5 * (s[1:] + s[:-1]), np.diff(s)
    d = 3.7e-3 + (3.3e-3 - 3.7e-3) * mid / 7.5
    c = _open_turn_compliance(22e-3, geo.pitch(mid), g, e, math.pi * d**4 / 32, math.pi * d**4 / 64)
    k_end = math.pi * 22e-3 * e / 1e3
    k1 = 1 / (np.sum(c * ds) + 2 / k_end)
    p = taper.spring_model.internal_parameters()
    assert p["K1"] == pytest.approx(k1, abs=0, rel=1e-5)
    s_all = np.linspace(0.0, 7.5, 60001)
    mid, ds = 0.5 * (s_all[1:] + s_all[:-1]), np.diff(s_all)
    d = 3.7e-3 + (3.3e-3 - 3.7e-3) * mid / 7.5
    mass = rho * np.sum(math.pi * d**2 / 4 * np.hypot(math.pi * 22e-3, geo.pitch(mid)) * ds)
    assert p["M"] == pytest.approx(mass, abs=0, rel=1e-4)
    assert taper.solid_length == pytest.approx(
        0.5 * (3.7e-3 + 3.3e-3) * 7.5 + 0.5 * 0.5 * (3.7e-3 + 3.3e-3), abs=0, rel=1e-12
    )
    assert p["Lc"] == pytest.approx(taper.solid_length, abs=0, rel=1e-12)
    # the thinnest wire on its coil judges the stress
    fig = taper.spring_model.design_figures()
    s_active = np.linspace(1.0, 6.5, 401)
    d_active = 3.7e-3 + (3.3e-3 - 3.7e-3) * s_active / 7.5
    tau = np.max(en13906_k(22e-3 / d_active) * 8 * fig["installed"]["force_N"] * 22e-3 / (math.pi * d_active**3))
    assert fig["installed"]["shear_stress_Pa"] == pytest.approx(tau, abs=0, rel=1e-12)


# ---------------------------------------------------------------------- the ovate beehive against a continuum
def beehive_continuum(spring, geometry, slices=4000, modes=3):
    """Rate [N/m] and first natural frequencies [Hz] of the beehive at its free length, from the
    wave equation of its active wire ``mu(s) u_tt = d/ds (u_s / c(s))`` (s in turns; c the open
    turn's compliance with the ellipse's J and I, mu the wire's mass per turn ``rho A sqrt((pi D)^2
    + p^2)``), the dead coils' masses at the ends, held by the end contacts ``pi D E/1000``:
    linear finite elements over ``slices`` equal slices, masses lumped, the tridiagonal
    eigenproblem solved exactly."""
    g, e, rho = spring.shear_modulus, spring.youngs_modulus, spring.density
    b, h = spring.wire_width, spring.wire_height
    j = ellipse(b, h)[0]
    i_bend = math.pi * b**3 * h / 64  # bending across the coil's radius
    area = math.pi * b * h / 4
    nb, n = spring.dead_coils, spring.low_pitch_coils + spring.high_pitch_coils
    s = np.linspace(nb, n - nb, slices + 1)
    mid, ds = 0.5 * (s[1:] + s[:-1]), np.diff(s)
    k = 1 / (_open_turn_compliance(geometry.diameter(mid), geometry.pitch(mid), g, e, j, i_bend) * ds)
    m_el = rho * area * np.hypot(np.pi * geometry.diameter(mid), geometry.pitch(mid)) * ds
    mass = np.zeros(slices + 1)
    mass[:-1] += m_el / 2
    mass[1:] += m_el / 2
    for end, x in ((0, np.linspace(0, nb, 2001)), (-1, np.linspace(n - nb, n, 2001))):
        xm, dx = 0.5 * (x[1:] + x[:-1]), np.diff(x)
        mass[end] += rho * area * np.sum(np.hypot(np.pi * geometry.diameter(xm), geometry.pitch(xm)) * dx)
    k_seat = math.pi * geometry.diameter(0.0) * e / 1e3
    k_ret = math.pi * geometry.diameter(n) * e / 1e3
    springs = np.concatenate([[k_seat], k, [k_ret]])
    diag = (springs[:-1] + springs[1:]) / mass
    off = -springs[1:-1] / np.sqrt(mass[:-1] * mass[1:])
    w2 = eigh_tridiagonal(diag, off, select="i", select_range=(0, modes - 1), eigvals_only=True)
    return 1 / np.sum(1 / springs), np.sqrt(w2) / (2 * np.pi)


def test_ovate_beehive_example_against_its_continuum():
    """examples/valve/beehive_ovate.toml (a diameter profile from 23 to 17.5 mm, ovate wire 4.0 x
    3.4 mm): the distributed model's rate at free length to 1e-4 (its 64 slices per element and the
    transitions' kinks against 4000 slices here) and its first three natural frequencies at free
    length to 0.5 % (the lumped chain of 50 elements: the surge n's error is about
    (n pi/50)^2/24, 0.15 % for the third)."""
    spring = ValveSpring.from_toml(EXAMPLES / "valve" / "beehive_ovate.toml")
    assert (spring.wire_shape, spring.model) == ("ovate", "distributed")
    model = spring.spring_model
    rate, freqs = beehive_continuum(spring, model.geometry)
    p = model.internal_parameters()
    assert p["K1"] == pytest.approx(rate, abs=0, rel=1e-4)
    np.testing.assert_allclose(model.modes(spring.free_length, 3), freqs, rtol=5e-3)
    assert p["f1"] == pytest.approx(freqs[0], abs=0, rel=5e-3)
    # a realistic valve spring: 200-250 N installed, a first surge mode above 500 Hz
    assert 200 < p["Fset"] < 250 and p["f2"] > 500


def test_wire_diameter_profile_inputs(tmp_path):
    """A CSV profile is the TOML array's spring; a profile that does not span the coils, or whose
    wire reaches the pitch, is refused; Type C takes the round wire of the active coils in series
    (``(mean d^-4)^(-1/4)``, by hand for a linear taper to 1e-6: a trapezoid over 2001 points, 1e-8)."""
    base = {**ONE_STEP, "model": "distributed", "wire_diameter": "3.7 mm"}
    pairs = [[0, "3.7 mm"], [7.5, "3.3 mm"]]
    a = ValveSpring.from_dict({**base, "wire_diameter_profile": pairs})
    (tmp_path / "wire.csv").write_text("turns,wire_diameter_mm\n0,3.7\n7.5,3.3\n")
    b = ValveSpring.from_dict({**base, "wire_diameter_profile": "wire.csv"}, base_dir=tmp_path)
    np.testing.assert_allclose(b.spring_model.modes(38e-3, 3), a.spring_model.modes(38e-3, 3), rtol=1e-12)
    with pytest.raises(InputError, match="turns must run from 0"):
        ValveSpring.from_dict({**base, "wire_diameter_profile": [[0, "3.7 mm"], [6, "3.3 mm"]]})
    with pytest.raises(InputError, match="below the pitch"):
        ValveSpring.from_dict(
            {
                **base,
                "wire_diameter_profile": [
                    [0, "3.7 mm"],
                    [3.9, "3.6 mm"],
                    [4, "7.5 mm"],
                    [4.1, "3.6 mm"],
                    [7.5, "3.3 mm"],
                ],
            }
        )
    typec = a.with_model("type-c").spring_model.internal_parameters()
    # d(s) = 3.7 - 0.4 s/7.5 mm over the active turns 1 to 6.5: mean of d^-4 in closed form
    d1, d2 = 3.7e-3 - 0.4e-3 / 7.5, 3.7e-3 - 0.4e-3 * 6.5 / 7.5
    mean = (d2**-3 - d1**-3) / (3 * (d1 - d2))
    rate_d = mean**-0.25
    assert typec["K1"] == pytest.approx(78.5e9 * rate_d**4 / (8 * 5.5 * 22e-3**3), abs=0, rel=1e-6)


def test_type_c_says_it_takes_one_mean_diameter_for_a_beehive():
    """Type C's closed forms ([MMS]) have one mean diameter: a diameter profile is the
    distributed model's, and Type C says so once (a FactWarning) instead of ignoring it."""
    beehive = ValveSpring.from_toml(EXAMPLES / "valve" / "beehive_ovate.toml")
    with pytest.warns(FactWarning, match="Type C and diameter_profile"):
        beehive.with_model("type-c").spring_model
    with warnings.catch_warnings():
        warnings.simplefilter("error", FactWarning)
        beehive.spring_model  # the distributed model follows the profile: nothing to say
