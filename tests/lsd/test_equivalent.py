"""Describing-function coefficients of the nonlinear force laws: lsd/equivalent.py."""

import warnings

import numpy as np
import pytest

from springdyn.lsd import LSDModel, LSDParameters, RigData, circular_orbit, identify, linear_shake, simulate_rig
from springdyn.lsd.equivalent import equivalent_matrices, forward_whirl_coefficient
from springdyn.lsd.stiffness import PreloadExceededWarning


def _model(**kw):
    return LSDModel(LSDParameters.example("C").replace(oring_friction=0.2, oring_normal_force=20.0, **kw))


def test_circular_orbit_equals_the_closed_forms_on_the_same_friction_law():
    # On a circular orbit every pack sees the full amplitude and the O-ring force is
    # constant: the describing function must equal the closed forms (2.22) (circular
    # variant) and (2.28) with the instantaneous normal load, and C_visc; 2048-point
    # quadrature of the friction jumps: 1e-3.
    m = _model(leaf_normal_load="instantaneous")
    for rpm, amp in ((500.0, 50e-6), (2500.0, 20e-6)):
        closed = m.coefficients([rpm], amp, motion="circular")
        eq = m.equivalent_coefficients([rpm], amp, motion="circular")
        np.testing.assert_allclose(eq.K[0], closed.K[0], rtol=1e-9, atol=1e-9 * closed.K[0, 0, 0])
        for part in ("oring", "hysteresis", "viscous"):
            np.testing.assert_allclose(
                eq.parts[part][0], closed.parts[part][0], rtol=1e-3, atol=1e-3 * closed.C[0, 0, 0]
            )
    assert eq.summary["model"] == "describing function"


def test_every_mechanism_scales_with_amplitude_as_its_law_says():
    # O-ring and leaf friction equivalents fall as 1/A (Coulomb; instantaneous load with
    # A <= preload), oil is independent of A, stiffness too while the packs stay preloaded
    m = _model()
    a = equivalent_matrices(m, 100.0, 10e-6)
    b = equivalent_matrices(m, 100.0, 40e-6)
    assert b["oring_friction"][1][0, 0] == pytest.approx(a["oring_friction"][1][0, 0] / 4, rel=1e-3)
    assert b["leaf_friction"][1][0, 0] == pytest.approx(a["leaf_friction"][1][0, 0] / 4, rel=1e-3)
    np.testing.assert_allclose(b["oil"][1], a["oil"][1], rtol=1e-12)
    np.testing.assert_allclose(b["spring"][0], a["spring"][0], rtol=1e-9, atol=1e-9 * a["spring"][0][0, 0])


def test_describing_function_is_what_the_rig_identifies():
    # a second, independent path: simulate the rig (sampled, with lift-off at 400 um > 250 um
    # preload) and identify; tolerance 0.5 %: the rig's 10 kHz sampling of the friction jumps
    m = _model()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PreloadExceededWarning)
        for amp in (30e-6, 400e-6):
            rx = simulate_rig(m, linear_shake(1000, amp, "x", 5, 20e3))
            ry = simulate_rig(m, linear_shake(1000, amp, "y", 5, 20e3))
            it = identify(
                RigData(rx.time, rx.x, rx.y, rx.fx, rx.fy),
                RigData(ry.time, ry.x, ry.y, ry.fx, ry.fy),
                mass=m.params.ring_mass,
                rpm=1000,
            )
            eq = m.equivalent_coefficients([1000.0], amp)
            np.testing.assert_allclose(eq.K[0].diagonal(), it.K.diagonal(), rtol=5e-3)
            np.testing.assert_allclose(eq.C[0].diagonal(), it.C.diagonal(), rtol=5e-3)
    # lift-off softens the damper
    assert eq.K[0, 0, 0] < 0.95 * m.stiffness_matrix[0, 0]


def test_forward_whirl_coefficient_matches_a_forward_orbit_record():
    m = _model()
    w = 2 * np.pi * 1500 / 60
    H = forward_whirl_coefficient(m, w, 40e-6)
    r = simulate_rig(m, circular_orbit(1500, 40e-6, 4, 20e3))
    # force phasor of the sampled record against the orbit's: Fz / z over whole periods
    e = np.exp(-1j * w * r.time)
    Fz = np.mean((r.fx - m.params.ring_mass * np.gradient(np.gradient(r.x, r.time), r.time)) * e) * 2
    assert H.real == pytest.approx(m.stiffness_matrix[0, 0], rel=1e-6)
    assert (Fz / 40e-6).imag == pytest.approx(H.imag, rel=5e-3)
