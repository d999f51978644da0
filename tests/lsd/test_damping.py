"""Damping: oil network vs corrected (3.5), conductances, friction equivalents."""

import numpy as np
import pytest

from springdyn.lsd import LSDModel, LSDParameters
from springdyn.lsd.damping import (
    boundary_conductance,
    chamber_pressures,
    chamber_volume_matrix,
    coulomb_equivalent_damping,
    hydraulic_diameter,
    leaf_loss_factor,
    passage_conductance_rectangular,
    passage_conductance_thesis,
    viscous_damping_matrix,
    viscous_damping_thesis,
)
from springdyn.lsd.stiffness import equally_spaced_angles

B_RING, D_O, L1 = 15e-3, 71e-3, 38e-3
CD = 2.3e-10


def _layouts():
    rng = np.random.default_rng(11)
    yield equally_spaced_angles(6)
    yield equally_spaced_angles(3, 0.2)
    for n in (2, 4, 5, 7):
        yield np.sort(rng.uniform(0, 2 * np.pi, n))


def test_volume_rows_sum_to_zero():
    # incompressible oil: the chamber volume changes of (2.15) cancel for any layout
    for phi in _layouts():
        B = chamber_volume_matrix(phi, B_RING, D_O, L1)
        np.testing.assert_allclose(B.sum(axis=0), 0.0, atol=1e-15)


def test_c_visc_symmetric_psd_and_equal_to_corrected_3_5():
    # READING-NOTES 3.2: B^T G^+ B is symmetric PSD and equals (3.5) with the C_yy typo fixed
    # (tolerance: round-off of two pseudo-inverses, relative to the largest entry)
    for phi in _layouts():
        B = chamber_volume_matrix(phi, B_RING, D_O, L1)
        C = viscous_damping_matrix(B, CD)
        scale = np.abs(C).max()
        np.testing.assert_allclose(C, C.T, atol=1e-12 * scale)
        assert np.linalg.eigvalsh(C).min() >= -1e-12 * scale
        np.testing.assert_allclose(viscous_damping_thesis(phi, B_RING, D_O, L1, CD), C, atol=1e-10 * scale)


def test_printed_c_yy_typo_is_wrong():
    # (3.5) as printed uses pbar_(x,i-1) in C_yy; for an unequal layout that breaks the
    # energy balance: the power p.(Bv) the oil absorbs must equal v^T C v for v = (0, 1)
    phi = np.array([0.1, 0.9, 2.5, 3.9, 5.0])
    B = chamber_volume_matrix(phi, B_RING, D_O, L1)
    p = chamber_pressures(B, CD, [0.0, 1.0])
    power = p @ (B @ np.array([0.0, 1.0]))
    fixed = viscous_damping_thesis(phi, B_RING, D_O, L1, CD)[1, 1]
    assert fixed == pytest.approx(power, rel=1e-10)
    # reproduce the printed term and show it differs
    lam = 9 * B_RING**2 * L1**2 / (64 * CD)
    pbar = 8 * CD / (3 * B_RING * L1) * (-gauge_pressure_columns(B))  # printed p = -gauge p
    c, s = np.cos(phi), np.sin(phi)
    cn = np.roll(c, -1)
    printed = lam * np.sum((np.roll(pbar[:, 0], 1) - pbar[:, 1]) * s - 4 * D_O / (3 * L1) * pbar[:, 1] * (c - cn))
    assert abs(printed - power) > 0.05 * power


def gauge_pressure_columns(B):
    """Gauge pressure per unit velocity (columns x, y); the printed p of (2.19) is its negative."""
    return np.column_stack([chamber_pressures(B, CD, [1.0, 0.0]), chamber_pressures(B, CD, [0.0, 1.0])])


def test_c_visc_isotropic_and_rotation_invariant():
    # equally spaced packs: C_visc = c I; rotating all packs leaves it unchanged
    C0 = viscous_damping_matrix(chamber_volume_matrix(equally_spaced_angles(6), B_RING, D_O, L1), CD)
    C1 = viscous_damping_matrix(chamber_volume_matrix(equally_spaced_angles(6, 0.37), B_RING, D_O, L1), CD)
    np.testing.assert_allclose(C0, C0[0, 0] * np.eye(2), atol=1e-10 * C0[0, 0])
    np.testing.assert_allclose(C1, C0, rtol=1e-10, atol=1e-10 * C0[0, 0])


def test_thesis_conductance_reproduces_lambda_3_6():
    # (3.6): lambda = 9 b^2 L^2 / (64 C_D) = 639 eta L_h b^2 L^2 / (64 pi d_h^4) with the
    # two-passage C_D of (2.17); 639 = 9 x 142 / 2 (READING-NOTES 3.2)
    eta, Lh, bo, ho = 0.0965, 10e-3, 2.4e-3, 0.9e-3
    cd = boundary_conductance(bo, ho, Lh, eta, passages=2, model="thesis")
    lam = 9 * B_RING**2 * L1**2 / (64 * cd)
    dh = hydraulic_diameter(bo, ho)
    assert lam == pytest.approx(639 * eta * Lh * B_RING**2 * L1**2 / (64 * np.pi * dh**4), rel=1e-12)


@pytest.mark.parametrize(
    "bo, ho, lo, hi", [(2.4e-3, 0.9e-3, 1.6, 1.8), (5.5e-3, 0.10e-3, 13, 15), (5.5e-3, 0.25e-3, 5, 7)]
)
def test_exact_over_thesis_conductance(bo, ho, lo, hi):
    # READING-NOTES 3.2: the exact rectangular duct conducts 1.7-14x more than (2.17)
    # (Type C 1.7, Type B ~14; Type A lies between)
    ratio = passage_conductance_rectangular(bo, ho, 1e-2, 0.1) / passage_conductance_thesis(bo, ho, 1e-2, 0.1)
    assert lo < ratio < hi


def test_rectangular_duct_limits():
    # wide slot: b h^3/(12 eta L) (1 - 0.630 h/b), the known thin-slot side-wall correction;
    # square duct: Q = 0.03514 h^4 dp/(eta L) = 0.4217 h^4/(12 eta L) (Shah & London's
    # fRe = 56.91 for a square duct).  Tolerance 0.1 %: the digits quoted.
    h, L, eta = 1e-4, 1e-2, 1.0
    wide = passage_conductance_rectangular(100 * h, h, L, eta)
    assert wide == pytest.approx(100 * h * h**3 / (12 * eta * L) * (1 - 0.630 / 100), rel=1e-3)
    square = passage_conductance_rectangular(h, h, L, eta)
    assert square == pytest.approx(0.4217 * h**4 / (12 * eta * L), rel=1e-3)


def test_coulomb_equivalents():
    # (2.22) for a straight shake, and the circular-orbit variant; both from equal work per cycle
    mu, fn, w, a = 0.2, 50.0, 100.0, 50e-6
    assert coulomb_equivalent_damping(mu, fn, w, a) == pytest.approx(4 * mu * fn / (np.pi * w * a))
    work_orbit = mu * fn * 2 * np.pi * a  # constant force along the circumference
    c = coulomb_equivalent_damping(mu, fn, w, a, motion="circular")
    assert c * w * a * a * 2 * np.pi == pytest.approx(work_orbit)  # viscous work on the orbit


def test_leaf_loss_factor_from_energy_2_27():
    # zeta = E_d / (pi k_s delta_1^2) with E_d of (2.27): check the closed form (2.28)
    mu, pre, a, S, ks = 0.1, 0.25e-3, 50e-6, 0.08, 1e5
    Ed = 6 * mu * ks * (a + pre) * a * S
    assert leaf_loss_factor(mu, pre, a, S) == pytest.approx(Ed / (np.pi * ks * a * a), rel=1e-12)
    Ed_inst = 1.5 * mu * S * ks * pre * 4 * a  # instantaneous load: the delta(t) part cancels
    assert leaf_loss_factor(mu, pre, a, S, "instantaneous") == pytest.approx(Ed_inst / (np.pi * ks * a * a), rel=1e-12)


def test_model_damping_parts_add_up():
    p = LSDParameters.example("C").replace(oring_friction=0.3, oring_normal_force=20.0)
    m = LSDModel(p)
    rpm = np.array([500.0, 1500.0, 3000.0])
    res = m.coefficients(rpm, 50e-6)
    total = sum(res.parts.values())
    np.testing.assert_allclose(res.C, total)
    w = 2 * np.pi * rpm / 60
    # hysteresis C_h = zeta k_s / w (3 = sum cos^2 over 6 packs), O-ring 4 mu F_N / (pi w A)
    np.testing.assert_allclose(res.parts["hysteresis"][:, 0, 0], 3 * m.loss_factor(50e-6) * m.pack_stiffness / w)
    np.testing.assert_allclose(res.parts["oring"][:, 0, 0], 4 * 0.3 * 20 / (np.pi * w * 50e-6))


def test_leakage_factor_scales_viscous_damping():
    base = LSDModel(LSDParameters.example("C"))
    leaky = LSDModel(LSDParameters.example("C").replace(leakage_factor=4.0))
    np.testing.assert_allclose(
        leaky.viscous_damping, base.viscous_damping / 4.0, rtol=1e-12, atol=1e-12 * base.viscous_damping[0, 0]
    )


def test_viscosity_scaling():
    # Stokes flow: C_visc is proportional to the dynamic viscosity
    base = LSDModel(LSDParameters.example("C"))
    thick = LSDModel(LSDParameters.example("C").replace(oil_viscosity=30 * base.params.oil_viscosity))
    np.testing.assert_allclose(
        thick.viscous_damping, 30 * base.viscous_damping, rtol=1e-12, atol=1e-12 * thick.viscous_damping[0, 0]
    )


def test_compliant_chambers_limits():
    # G p + c dp/dt = B v: incompressible limit is C_visc with no stiffness; stiff-network
    # limit (high frequency) is the spring B^T B / c; damping stays positive (dissipation)
    from springdyn.lsd import LSDModel, LSDParameters
    from springdyn.lsd.damping import compliant_chamber_coefficients

    m = LSDModel(LSDParameters.example("C"))
    B, cd = m.volume_matrix, m.conductance
    K0, C0 = compliant_chamber_coefficients(B, cd, 0.0, 100.0)
    np.testing.assert_allclose(C0, m.viscous_damping)
    assert np.all(K0 == 0)
    K, C = compliant_chamber_coefficients(B, cd, 1e-20, 100.0)
    np.testing.assert_allclose(C, m.viscous_damping, rtol=1e-6, atol=1e-9 * C[0, 0])
    c = 1e-12
    K, C = compliant_chamber_coefficients(B, cd, c, 1e9 * cd / c)
    np.testing.assert_allclose(K, B.T @ B / c, rtol=1e-6, atol=1e-9 * K[0, 0])
    for w in (10.0, 300.0, 3000.0):
        K, C = compliant_chamber_coefficients(B, cd, 2e-13, w)
        assert np.all(np.linalg.eigvalsh(0.5 * (C + C.T)) > 0) and K[0, 0] > 0
