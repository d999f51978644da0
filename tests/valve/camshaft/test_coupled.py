"""Valves on a twisting camshaft (springdyn.valve.camshaft.coupled): the rigid-shaft limit
reproduces each valve alone to the float (and its drive torque with friction); the distorted table is the chain rule; the drive
torque's mean balances the lobes' and the bearings' (the periodic chain stores no energy over
a revolution); the example converges.

Tolerances: the rigid limit is exact (the same engine run on the same set-up); the distorted
table's derivatives against central differences of its own lift, O(h^2) with h = 1e-5 rad
(1e-6 relative); the mean torque balance is the FFT's round-off (1e-9 N m).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from springdyn.valve import Cam, CamshaftModel, ValveModel
from springdyn.valve.camshaft.coupled import distorted_table, valve_events
from tests.paths import example

FILE = example("valve/camshaft_4lobe.toml")


@pytest.fixture(scope="module")
def model():
    return CamshaftModel.from_toml(FILE)


def test_rigid_shaft_runs_each_valve_exactly_as_alone(model):
    rigid = model.replace(rigid=True)
    run = rigid.simulate(2000.0)
    alone = ValveModel.from_files(
        example("valve/one_step_spring.toml"),
        example("valve/cam_polydyne_ramps.toml"),
        example("valve/valve_train_with_follower.toml"),
    )
    sim_alone = alone.simulate(2000.0)
    for sim in run.simulations:
        assert np.array_equal(sim.cam_contact_force, sim_alone.cam_contact_force)
        assert np.array_equal(sim.valve_lift, sim_alone.valve_lift)
        assert np.array_equal(sim.retainer_force, sim_alone.retainer_force)
    # lobe 1's torque is the valve's drive torque with its friction, as `valve friction` gives it
    np.testing.assert_allclose(run.lobe_torque[0], alone.friction(2000.0).drive_torque, rtol=1e-12, atol=1e-12)
    assert not run.twist.any() and run.iterations == 0
    assert not run.timing_error.any()
    # the lobes' torques in the shaft's angle: lobe 3 (phase 90 deg) is lobe 1's, 90 deg later
    q1, q3 = run.lobe_torque[0], run.lobe_torque[2]
    np.testing.assert_array_equal(np.roll(q1, run.cam_angle.size // 4), q3)


def test_the_distorted_table_is_the_chain_rule():
    cam = Cam(law="polydyne", lift=9e-3, duration=math.radians(110))
    m = 3600
    u = np.arange(m) * 2 * math.pi / m
    a, w = 0.01, 4.0
    phi, dphi, ddphi = a * np.sin(w * u), a * w * np.cos(w * u), -a * w * w * np.sin(w * u)
    t = distorted_table(cam, phi, dphi, ddphi)
    np.testing.assert_allclose(t.h, cam.lift_at(u + phi), rtol=0, atol=1e-15)

    def lift(x):
        return cam.lift_at(x + a * np.sin(w * x))

    h = 1e-5
    np.testing.assert_allclose(t.dh, (lift(u + h) - lift(u - h)) / (2 * h), rtol=0, atol=1e-6 * 9e-3 / 0.96)
    fd2 = (lift(u + h) - 2 * lift(u) + lift(u - h)) / h**2
    np.testing.assert_allclose(t.ddh, fd2, rtol=0, atol=2e-4 * np.abs(t.ddh).max())


def test_valve_events_of_a_hand_made_lift():
    n = 720
    psi = np.arange(n) * 2 * math.pi / n
    z = np.maximum(0.0, 5e-3 * np.sin(psi - 1.0))  # open from 1 rad to 1 + pi, peak at 1 + pi/2
    o, c, p = valve_events(z, 1e-3)
    assert o == pytest.approx(1.0 + math.asin(0.2), abs=2e-4)
    assert c == pytest.approx(1.0 + math.pi - math.asin(0.2), abs=2e-4)
    assert p == pytest.approx(1.0 + math.pi / 2, abs=1e-4)


def test_the_example_converges_and_balances_its_mean_torque(model):
    run = model.simulate(3000.0)
    assert run.converged and run.iterations <= 6
    assert run.residual <= model.shaft.tolerance
    mean_lobes = float(np.mean(run.lobe_torque.sum(axis=0)))
    assert np.mean(run.drive_torque) == pytest.approx(mean_lobes + run.bearing_drag, abs=1e-9)
    # a twisting shaft moves the timing, by less than its own largest twist (plus the valve's own settling)
    assert 0 < run.summary["max_timing_error_deg"] < 2 * run.summary["max_twist_deg"] + 0.05


def test_a_stiffer_shaft_and_drive_approach_the_rigid_limit(model):
    stiff = model.replace(shear_modulus=80e12, drive_stiffness=1e7, drive_damping=1e2)
    run = stiff.simulate(3000.0)
    assert run.summary["max_twist_deg"] < 1e-3
    assert run.summary["max_timing_error_deg"] < 2e-3


def test_quasi_static_timing_error_is_the_twist_at_the_event(model):
    """Slow and with a stiff shaft on a soft drive (first mode 233 Hz, 28 cam orders above
    500 cam rpm), each valve follows its lobe, so its event moves by the lobe's twist there,
    against it: a lobe ``phi`` ahead opens and closes ``phi`` earlier (kinematics, independent
    of the shaft's solution).  Tolerance: the valve's own dynamics and the grid, 0.002 deg."""
    soft = model.replace(shear_modulus=80e12, drive_stiffness=3e3, drive_damping=2.0)
    run = soft.simulate(500.0)
    for i in range(4):
        for k in (0, 1):  # opening, closing
            psi = (run.events[i, k] + run.lobe_phase[i]) % (2 * math.pi)
            phi = np.interp(psi, run.cam_angle, run.twist[i], period=2 * math.pi)
            assert math.degrees(run.timing_error[i, k]) == pytest.approx(-math.degrees(phi), abs=2e-3)
