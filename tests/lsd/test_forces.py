"""The time-domain force laws (lsd/forces.py) on their own: lift-off, inter-leaf and O-ring Coulomb friction."""

import numpy as np
import pytest

from springdyn.lsd.forces import interleaf_friction_forces, oring_friction_force, pack_spring_forces
from springdyn.lsd.stiffness import equally_spaced_angles, stiffness_matrix

KS, PRE = 2.0e5, 100e-6
PHI = equally_spaced_angles(4, 0.3)


def test_within_the_preload_the_packs_are_the_linear_stiffness():
    # |delta_i| < delta_pre for every pack: the force is K (3.4) times the displacement, and
    # each pack carries k_s (delta_pre + delta_i)
    rng = np.random.default_rng(3)
    x, y = rng.uniform(-60e-6, 60e-6, (2, 50))
    fx, fy, loads = pack_spring_forces(PHI, KS, PRE, x, y)
    K = stiffness_matrix(KS, PHI)
    np.testing.assert_allclose(np.array([fx, fy]), K @ np.array([x, y]), atol=1e-9 * KS * PRE)
    np.testing.assert_allclose(loads, KS * (PRE + np.outer(x, np.cos(PHI)) + np.outer(y, np.sin(PHI))))


def test_a_pack_left_by_more_than_the_preload_lifts_off():
    # packs at 0, 90, 180, 270 deg, ring 3 preloads along +x: the pack at 180 deg lifts off (no
    # load), the one at 0 deg carries 4 preloads, so F_x = k_s (3 delta_pre) + k_s delta_pre
    phi = equally_spaced_angles(4)
    fx, fy, loads = pack_spring_forces(phi, KS, PRE, np.array([3 * PRE]), np.array([0.0]))
    np.testing.assert_allclose(loads[0], KS * PRE * np.array([4.0, 1.0, 0.0, 1.0]), atol=1e-9 * KS * PRE)
    assert fx[0] == pytest.approx(4 * KS * PRE, rel=1e-12)
    assert abs(fy[0]) < 1e-9 * KS * PRE


def test_inter_leaf_friction_is_coulomb_on_the_instantaneous_load_and_a_still_pack_sticks():
    # a y shake at the packs 0, 90, 180, 270 deg: the packs on the x axis are not deflected
    # (round-off rate) and carry no friction; the two on the y axis give 1.5 mu S P_i each,
    # along the motion whatever the speed (2.25)-(2.27)
    phi = equally_spaced_angles(4)
    mu, S = 0.2, 0.4
    loads = np.array([[10.0, 30.0, 12.0, 50.0], [10.0, 30.0, 12.0, 50.0]])
    vx, vy = np.array([0.0, 0.0]), np.array([1e-3, -5.0])
    fx, fy = interleaf_friction_forces(phi, loads, mu, S, vx, vy)
    assert np.abs(fx).max() < 1e-12
    np.testing.assert_allclose(fy, 1.5 * mu * S * (30.0 + 50.0) * np.sign(vy))


def test_oring_friction_opposes_the_velocity_with_a_constant_magnitude_and_is_zero_at_rest():
    mu, FN = 0.3, 40.0
    vx, vy = np.array([0.0, 1e-6, -2.0, 0.3]), np.array([0.0, 0.0, 1.0, -0.4])
    fx, fy = oring_friction_force(mu, FN, vx, vy)
    assert fx[0] == 0.0 and fy[0] == 0.0
    np.testing.assert_allclose(np.hypot(fx, fy)[1:], mu * FN)
    np.testing.assert_allclose(np.arctan2(fy, fx)[1:], np.arctan2(vy, vx)[1:])
    fx, fy = oring_friction_force(mu, FN, 0.5, 0.0)  # floats in, 0-d arrays out
    assert float(fx) == pytest.approx(mu * FN) and float(fy) == 0.0
