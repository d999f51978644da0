"""The damper as a ROSS bearing element (optional extra springdyn[ross]): lsd/rotordynamics.py.

The exported table is dense over a stated speed range (0-20 000 rpm by
default), ROSS's interpolated coefficients equal springdyn's over the whole range and are
never extrapolated.
"""

import warnings

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.lsd import LSDModel, LSDParameters

NAMES = {
    "kxx": (0, 0),
    "kxy": (0, 1),
    "kyx": (1, 0),
    "kyy": (1, 1),
    "cxx": (0, 0),
    "cxy": (0, 1),
    "cyx": (1, 0),
    "cyy": (1, 1),
}


@pytest.fixture(scope="module")
def rs():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return pytest.importorskip("ross")


# in the fast tier, so that every run exercises the ross extra (importing ross takes 5-10 s)
@pytest.mark.parametrize("kind", ["A", "C"])
def test_ross_interpolation_matches_over_the_whole_range_and_never_extrapolates(rs, kind):
    # Type C has large friction terms (C ~ 1/omega over 2.5 decades of frequency), Type A a
    # large viscous part: the two shapes of the damping curve
    model = LSDModel(LSDParameters.example(kind).replace(oring_friction=0.2, oring_normal_force=50.0))
    b = model.to_ross(0)
    assert isinstance(b, rs.BearingElement)
    assert b.frequency.size >= 30
    assert b.frequency[-1] == pytest.approx(2 * np.pi * 20000 / 60)
    # 2000 frequencies between and on the table points, 1 Hz to 20 000 rpm
    w = np.linspace(2 * np.pi * 1.0, 2 * np.pi * 20000 / 60, 2000)
    ref = model.coefficients(omega=w)
    for name, (i, j) in NAMES.items():
        expected = (ref.K if name[0] == "k" else ref.C)[:, i, j]
        got = np.array([(b.K(f) if name[0] == "k" else b.C(f))[i, j] for f in w[::50]])
        scale = np.max(np.abs((ref.K if name[0] == "k" else ref.C)[:, i, i]))  # cross terms are round-off
        # Within 0.5 % over the whole stated range (the spline's error is ~2e-4)
        np.testing.assert_allclose(got, expected[::50], rtol=5e-3, atol=1e-9 * scale)
        full = getattr(b, f"{name}_interpolated")(w)
        np.testing.assert_allclose(full, expected, rtol=5e-3, atol=1e-9 * scale)
    # between 0 and the first table point (60 rpm) the 60 rpm values are used: finite, positive
    c0 = b.C(0.0)
    np.testing.assert_allclose(c0[:2, :2], model.coefficients([60.0]).C[0], rtol=1e-9, atol=1e-9 * c0[0, 0])
    # never extrapolated: beyond 20 000 rpm ROSS gets an error naming the frequency and the range
    with pytest.raises(InputError, match="outside the table .*0-20000 rpm"):
        b.C(1.01 * 2 * np.pi * 20000 / 60)
    with pytest.raises(InputError, match="outside the table"):
        b.K(-1.0)
    # with outside="clamp" the end values are held (no extrapolation either)
    bc = model.to_ross(0, rpm_range=(500, 3000), outside="clamp")
    top = model.coefficients([3000.0]).C[0]
    np.testing.assert_allclose(bc.C(1500.0)[:2, :2], top, rtol=1e-9, atol=1e-9 * top[0, 0])
    assert bc.C(1500.0)[0, 0] > 0


@pytest.mark.slow
def test_old_table_keyword_still_works_but_is_guarded(rs):
    model = LSDModel(LSDParameters.example("C"))
    w = 2 * np.pi * np.linspace(500, 3000, 11) / 60
    with pytest.warns(DeprecationWarning, match="frequencies"):
        b = model.to_ross(0, w)
    np.testing.assert_allclose(b.cxx, model.coefficients(omega=w).C[:, 0, 0])
    # the reproducer: 600 and 1500 rad/s used to come back -12 % and negative
    with pytest.raises(InputError, match="outside the table"):
        b.C(1500.0)
    with pytest.raises(InputError, match="rpm_range"):
        model.to_ross(0, rpm_range=(3000, 500))
    with pytest.raises(InputError, match="at least 30"):
        model.to_ross(0, points=11)
    with pytest.raises(InputError, match="outside"):
        model.to_ross(0, outside="extrapolate")


@pytest.mark.slow
def test_ross_rotor_modal_analysis_and_whirl_consistency(rs):
    from springdyn.lsd.rotordynamics import bearing_at_frequency, whirl_consistent_mode

    # Type C with 20x the passage conductance: damping ratio ~0.18, so the rigid-body
    # bounce mode is an underdamped pair that run_modal reports cleanly
    model = LSDModel(LSDParameters.example("C").replace(leakage_factor=20.0))
    steel = rs.Material(name="steel_lsd_test", rho=7810, E=211e9, G_s=81.2e9)

    def rotor_with(b0, b1):
        shaft = [
            rs.ShaftElement(0.1, 0.0, 0.08, material=steel, shear_effects=True, rotary_inertia=True, gyroscopic=True)
            for _ in range(2)
        ]
        disk = rs.DiskElement.from_geometry(n=1, material=steel, width=0.05, i_d=0.08, o_d=0.2)
        return rs.Rotor(shaft, [disk], [b0, b1])

    rotor = rotor_with(model.to_ross(0, tag="lsd0"), model.to_ross(2, tag="lsd1"))
    speed = 2 * np.pi * 1000 / 60
    modal = rotor.run_modal(speed=speed, num_modes=8)
    # independent check: a rigid rotor of mass M on two dampers, bounce mode
    # wn = sqrt(2 Kxx / M), zeta = 2 Cxx / (2 sqrt(2 Kxx M)), log dec = 2 pi zeta / sqrt(1 - zeta^2),
    # with the coefficients at the spin speed (what ROSS 2.3 uses). Tolerances 1 % / 2 %: the
    # 0.2 m, 80 mm shaft is nearly rigid (bending modes far higher)
    # (M: the rotor and the passages' oil, the added mass M_a that to_ross gives ROSS as mxx)
    c = model.coefficients([1000.0])
    K, C, M = c.K[0, 0, 0], c.C[0, 0, 0], rotor.m + 2 * model.added_mass[0, 0]
    wn = np.sqrt(2 * K / M)
    zeta = 2 * C / (2 * np.sqrt(2 * K * M))
    assert modal.wn[0] == pytest.approx(wn, rel=0.01)
    assert modal.log_dec[0] == pytest.approx(2 * np.pi * zeta / np.sqrt(1 - zeta**2), rel=0.02)

    # the mode vibrates at ~wd, not at 1000 rpm: coefficients at the mode's own frequency
    def build(omega):
        return rotor_with(
            bearing_at_frequency(model, 0, omega, tag="a"), bearing_at_frequency(model, 2, omega, tag="b")
        )

    wd, modal2 = whirl_consistent_mode(build, speed, omega_guess=speed, mode=0, num_modes=8)
    c = model.coefficients(omega=[wd])
    K, C = c.K[0, 0, 0], c.C[0, 0, 0]
    zeta = C / np.sqrt(2 * K * M)
    # consistency: the rigid-rotor damped frequency with the coefficients at wd is wd itself (1 %)
    assert wd == pytest.approx(np.sqrt(2 * K / M) * np.sqrt(1 - zeta**2), rel=0.01)
    assert modal2.log_dec[0] == pytest.approx(2 * np.pi * zeta / np.sqrt(1 - zeta**2), rel=0.02)
    # and the answer no longer depends on the spin speed (the issue: 0.07 to 1.0 with spin)
    wd_fast, _ = whirl_consistent_mode(build, 3 * speed, omega_guess=speed, mode=0, num_modes=8)
    assert wd_fast == pytest.approx(wd, rel=0.01)


@pytest.mark.slow
def test_nonlinear_force_callback_in_ross_time_response(rs):
    # ROSS 2.3's add_to_RHS: with no friction and no lift-off the damper's force laws are
    # linear (K x + C_visc v), so the rotor with the callback (and zero-coefficient bearings)
    # must respond like the rotor with linear bearing elements. ROSS evaluates the callback
    # with the state of the step before (first order in the step): the difference falls
    # about 4x for 4x smaller steps, and is below 3 % of the amplitude at the finer one.
    from springdyn.lsd.rotordynamics import nonlinear_force

    model = LSDModel(LSDParameters.example("C").replace(leakage_factor=20.0, leaf_friction=0.0))
    steel = rs.Material(name="steel_lsd_nl", rho=7810, E=211e9, G_s=81.2e9)

    def rotor(b0, b1):
        shaft = [rs.ShaftElement(0.1, 0.0, 0.08, material=steel) for _ in range(2)]
        disk = rs.DiskElement.from_geometry(n=1, material=steel, width=0.05, i_d=0.08, o_d=0.2)
        return rs.Rotor(shaft, [disk], [b0, b1])

    K, C = model.stiffness_matrix[0, 0], model.viscous_damping[0, 0]
    lin = rotor(rs.BearingElement(0, kxx=K, cxx=C), rs.BearingElement(2, kxx=K, cxx=C))
    free = rotor(rs.BearingElement(0, kxx=0.0, cxx=0.0), rs.BearingElement(2, kxx=0.0, cxx=0.0))
    f0, f2 = nonlinear_force(model, free, 0), nonlinear_force(model, free, 2)
    speed = 2 * np.pi * 1500 / 60
    d = lin.number_dof * 1
    errors = []
    for steps in (2001, 8001):
        t = np.linspace(0.0, 0.2, steps)
        F = np.zeros((t.size, lin.ndof))
        F[:, d] = 1e-4 * speed**2 * np.cos(speed * t)
        F[:, d + 1] = 1e-4 * speed**2 * np.sin(speed * t)
        _, ref, _ = lin.time_response(speed, F, t)
        _, y, _ = free.time_response(
            speed, F, t, method="newmark", add_to_RHS=lambda step, **kw: f0(step, **kw) + f2(step, **kw)
        )
        errors.append(np.abs(y[:, d] - ref[:, d]).max() / np.abs(ref[:, d]).max())
    assert errors[1] < 0.03
    assert 3.0 < errors[0] / errors[1] < 5.0
    with pytest.raises(InputError, match="not a node"):
        nonlinear_force(model, free, 7)
