"""Leaf pack statics against READING-NOTES section 3.1 and independent checks."""

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.lsd import LSDModel, LSDParameters
from springdyn.lsd.leafpack import (
    load_ratios,
    load_ratios_direct,
    pack_stiffness,
    second_moment_of_area,
    stiffness_factor,
    tip_deflection_ratios,
)

E, NU = 206e9, 0.3


@pytest.mark.parametrize(
    "name, phi, xi, kp_N_per_mm",
    [
        # READING-NOTES 3.1 reference values (E 206 GPa, nu 0.3, a 0), given to 4 digits
        ("A", [1.0, 0.5], 0.5, 241.3),
        ("B", [1.0, 0.5], 0.5, 246.7),
        ("C", [1.0, 0.7696, 0.5926], 0.3514, 106.9),
    ],
)
def test_reference_pack_values(name, phi, xi, kp_N_per_mm):
    m = LSDModel(LSDParameters.example(name))
    # tolerance: the notes print 4 significant digits -> half a unit in the last digit
    np.testing.assert_allclose(m.load_ratios, phi, atol=5e-5)
    assert m.stiffness_factor == pytest.approx(xi, abs=5e-5)
    assert m.pack_stiffness_unclamped / 1e3 == pytest.approx(kp_N_per_mm, abs=0.05)
    assert m.pack_stiffness == m.pack_stiffness_unclamped  # clamp_overhang 0 in the examples


@pytest.mark.parametrize("n", [1, 2, 3, 4, 7])
def test_equal_leaves_identity(n):
    # n equal leaves deflect together: P_i = (n - i + 1)/n P_1, xi = 1/n, k_p = n k_single
    # (closed form; tolerance: round-off of a banded solve)
    L, t, b = 30e-3, 1.2e-3, 14e-3
    EI = E * second_moment_of_area(b, np.full(n, t))
    phi = load_ratios([L] * n, EI)
    np.testing.assert_allclose(phi, (n - np.arange(n)) / n, rtol=1e-12)
    assert stiffness_factor([L] * n, EI) == pytest.approx(1.0 / n, rel=1e-12)
    single = 3 * EI[0] / ((1 - NU**2) * L**3)
    assert pack_stiffness([L] * n, EI, NU) == pytest.approx(n * single, rel=1e-12)
    np.testing.assert_allclose(tip_deflection_ratios([L] * n, EI), 1.0, rtol=1e-12)


def test_tridiagonal_equals_direct_compatibility():
    # Eq. (2.7) (typo fixed) against a dense solve of the compatibility conditions built
    # from the cantilever influence function; any leaf count, unequal thicknesses.
    rng = np.random.default_rng(3)
    for n in range(2, 9):
        L = np.sort(rng.uniform(10e-3, 60e-3, n))[::-1]
        EI = E * second_moment_of_area(15e-3, rng.uniform(0.8e-3, 1.6e-3, n))
        np.testing.assert_allclose(load_ratios(L, EI), load_ratios_direct(L, EI), rtol=1e-10)


def test_printed_a_i_typo_gives_other_ratios():
    # The printed a_i = (3L_(i-1) - L_i) L_i^2 / L_i^3 (READING-NOTES 3.1: typo).  For Type C
    # it would change phi_2 away from the value the direct compatibility check gives.
    L = np.array([38e-3, 34e-3, 25e-3])
    EI = E * second_moment_of_area(14.8e-3, np.full(3, 1.35e-3))
    a_printed = (3 * L[0] - L[1]) * L[1] ** 2 / L[1] ** 3
    a_fixed = (3 * L[0] - L[1]) * L[1] ** 2 / L[0] ** 3
    assert abs(a_printed - a_fixed) / a_fixed > 0.3
    assert load_ratios_direct(L, EI)[1] == pytest.approx(0.7696, abs=5e-5)


def test_stiffness_factor_is_tip_deflection_of_leaf_one():
    # xi of (2.9) is the tip deflection of leaf 1 under P1 and the contact load P2,
    # relative to a lone leaf: recompute it from the influence function.
    L = np.array([38e-3, 34e-3, 25e-3])
    EI = E * second_moment_of_area(14.8e-3, np.full(3, 1.35e-3))
    phi = load_ratios(L, EI)
    lone = L[0] ** 3 / (3 * EI[0])
    with_contact = lone - phi[1] * L[1] ** 2 * (3 * L[0] - L[1]) / (6 * EI[0])
    assert stiffness_factor(L, EI) == pytest.approx(with_contact / lone, rel=1e-12)


def test_clamp_overhang_softens_pack():
    p = LSDParameters.example("C").replace(clamp_overhang=3.8e-3)
    m = LSDModel(p)
    # Eq. (2.10): k_s = k_p / (1 + a/L1), a/L1 = 0.1
    assert m.pack_stiffness == pytest.approx(m.pack_stiffness_unclamped / 1.1, rel=1e-12)


def test_bad_leaves():
    EI = [1.0, 1.0]
    with pytest.raises(InputError, match="non-increasing"):
        load_ratios([20e-3, 30e-3], EI)
    with pytest.raises(InputError, match="positive"):
        load_ratios([20e-3, -1e-3], EI)
    with pytest.raises(InputError, match="one per leaf"):
        load_ratios([20e-3, 10e-3], [1.0])


def test_leaf_bending_beam_drops_the_plate_factor():
    # leaf_bending = "beam": E I without 1/(1 - nu^2) of (2.8), i.e. (1 - nu^2) = 0.91 of the
    # printed pack stiffness; an independent plate model of the pack lies between the two
    # (4-6 % below the printed value), which is why both bounds are offered
    from springdyn.lsd import LSDModel, LSDParameters

    for kind in "ABC":
        plate = LSDModel(LSDParameters.example(kind))
        beam = LSDModel(LSDParameters.example(kind).replace(leaf_bending="beam"))
        assert beam.pack_stiffness == pytest.approx((1 - 0.3**2) * plate.pack_stiffness, rel=1e-12)
        assert beam.stiffness_matrix[0, 0] == pytest.approx(3 * beam.pack_stiffness, rel=1e-12)
