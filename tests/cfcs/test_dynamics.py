"""Dynamics, Eqs. (11)-(25) of the CFCS paper with reading notes 2.1-2.2."""

import numpy as np
import pytest
from scipy.integrate import quad

from springdyn.cfcs import CFCS, SinusoidMotion, statics
from springdyn.cfcs import dynamics as dyn
from springdyn.cfcs.kinematics import deflection_from_theta2, theta2_from_deflection

from .conftest import R2, R3

M2, M3, MS = 0.025, 0.028, 0.087


def test_generalized_mass_eq19_equals_compact_form():
    # reading notes 2.1: Eq. (19) as printed equals the compact form; agreement to round-off
    th = np.linspace(-1.5, 1.5, 301)
    np.testing.assert_allclose(
        dyn.generalized_mass_eq19(th, M2, M3, MS, R2, R3), dyn.generalized_mass(th, M2, M3, MS, R2, R3), rtol=1e-13
    )


def _kinetic_energy_from_points(th, m2, m3, ms, h=1e-6):
    """2T / theta2'^2 from the positions of the mass centres, differentiated numerically (theta2' = 1)."""

    def points(t):
        a = np.array([R2 * np.cos(t), R2 * np.sin(t)])
        b = np.array([R2 + R3 - deflection_from_theta2(t, R2, R3), 0.0])
        phi3 = np.arctan2(b[1] - a[1], b[0] - a[0])  # coupler direction from the joint positions
        return a / 2, (a + b) / 2, b[0], phi3

    p, q = points(th + h), points(th - h)
    v2 = (p[0] - q[0]) / (2 * h)
    v3 = (p[1] - q[1]) / (2 * h)
    vs = (p[2] - q[2]) / (2 * h)
    w3 = (p[3] - q[3]) / (2 * h)
    ic2, ic3 = m2 * R2**2 / 12, m3 * R3**2 / 12  # Eq. (16)
    return m2 * v2 @ v2 + ic2 + m3 * v3 @ v3 + ic3 * w3**2 + ms * vs**2


@pytest.mark.parametrize("th", [0.0, 0.3, 0.8046, 1.2, 1.5])
def test_generalized_mass_from_point_velocities(th):
    # Eq. (11) evaluated from the joint positions (no loop-closure formulas); FD error ~1e-10 relative
    assert dyn.generalized_mass(th, M2, M3, MS, R2, R3) == pytest.approx(
        _kinetic_energy_from_points(th, M2, M3, MS), rel=1e-8
    )


def test_mass_derivative_by_finite_differences():
    th = np.linspace(-1.5, 1.5, 61)
    h = 1e-6  # truncation ~1e-12, round-off ~1e-19/1e-6
    fd = (dyn.generalized_mass(th + h, M2, M3, MS, R2, R3) - dyn.generalized_mass(th - h, M2, M3, MS, R2, R3)) / (2 * h)
    np.testing.assert_allclose(dyn.generalized_mass_derivative(th, M2, M3, MS, R2, R3), fd, rtol=1e-7, atol=1e-12)


def test_power_balance_frictionless(table1):
    # F dx/dt = d(T + V)/dt (frictionless, outside the toggle zone); d/dt by a 4th-order central
    # difference of T + V evaluated on the exact motion: relative 1e-6 as the issue asks
    p = table1.without_dissipation()
    mot = SinusoidMotion(omega=14.7, amplitude=0.06, offset=0.006)
    model = CFCS(p)
    r = model.dynamic(motion=mot, cycles=1, samples_per_cycle=64)
    assert r.summary["toggle_zone_samples"] == 0
    vals = p.values()

    def e(t):
        x, xd, _ = mot(t)
        th = theta2_from_deflection(x, R2, R3)
        from springdyn.cfcs.kinematics import slider_jacobian

        return dyn.energy(th, xd / slider_jacobian(th, R2, R3), vals)

    h = 1e-4 * mot.period
    t = r.time
    de = (-e(t + 2 * h) + 8 * e(t + h) - 8 * e(t - h) + e(t - 2 * h)) / (12 * h)
    power = r.force * r.velocity
    scale = np.max(np.abs(power))
    np.testing.assert_allclose(power, de, rtol=0, atol=1e-6 * scale)


def test_static_limit_as_omega_goes_to_zero(table1):
    # without dissipation the dynamic force tends to the static force like omega^2
    ideal = CFCS(table1.without_dissipation())
    err = []
    for w in (1e-2, 2e-2):
        r = ideal.dynamic(w, cycles=1, samples_per_cycle=200)
        err.append(np.max(np.abs(r.force - r.force_static)))
    assert err[0] < 1e-5
    assert err[1] / err[0] == pytest.approx(4.0, rel=1e-3)  # omega^2 scaling
    # with the dissipative terms the slow cycle tends to the compression/extension branches
    r = CFCS(table1).dynamic(1e-3, cycles=1, samples_per_cycle=400)
    # (the quasi-static compression branch of the statics, evaluated at the same deflections; the
    # inertia left at omega = 1e-3 rad/s is ~1e-7 N)
    up = r.velocity > 1e-9 * np.max(r.velocity)  # strictly moving (turning points excluded)
    p = table1
    th = theta2_from_deflection(r.deflection[up], R2, R3)
    fs = statics.static_force(th, p.k3, R2, R3)
    comp = (
        fs
        + statics.dissipative_torque(th, fs, p.pin_friction, p.friction_model, p.shear_angle, p.axial_force, R2, R3)
        / statics.frozen_jacobian(th, R2, R3, p.toggle_cutoff)
        + p.slider_friction
    )
    np.testing.assert_allclose(r.force[up], comp, rtol=1e-6)


@pytest.mark.parametrize("friction_model", ["constant", "paper"])
def test_hysteresis_equals_friction_work(table1, friction_model):
    # loop energy  int F dx  per cycle (trapezoid over 4000 samples, relative error ~1e-6) equals twice the
    # work of the dissipative terms over the stroke, integrated in theta2 with quad (independent path)
    p = table1.replace(friction_model=friction_model, slider_friction=0.3)
    off, amp = 0.006, 0.06
    r = CFCS(p).dynamic(motion=SinusoidMotion(5.0, amp, off), cycles=1, samples_per_cycle=4000)
    assert r.summary["toggle_zone_samples"] == 0
    ta, tb = theta2_from_deflection(off, R2, R3), theta2_from_deflection(off + amp, R2, R3)

    def tau(t):
        return statics.dissipative_torque(
            t,
            statics.static_force(t, p.k3, R2, R3),
            p.pin_friction,
            p.friction_model,
            p.shear_angle,
            p.axial_force,
            R2,
            R3,
        )

    work = 2 * quad(tau, ta, tb, epsabs=0, epsrel=1e-12)[0] + 2 * p.slider_friction * amp
    assert r.summary["hysteresis_energy_per_cycle_J"] == pytest.approx(work, rel=1e-5)


def test_forward_and_inverse_agree_frictionless(table1):
    # the inverse force replayed in the forward model reproduces the motion (LSODA rtol 1e-10)
    p = table1.without_dissipation()
    mot = SinusoidMotion(omega=14.7, amplitude=0.05, offset=0.01)
    vals = p.values()

    def f_inv(t):
        x, xd, xdd = mot(np.atleast_1d(t))
        return dyn.drive_force_components(x, xd, xdd, theta2_cutoff=p.toggle_cutoff, **vals)["force"][0]

    res = CFCS(p).forward(mot.period, force=f_inv, x0=0.01, v0=0.0, n=101, rtol=1e-10)
    x_ref = mot(res.time)[0]
    np.testing.assert_allclose(res.deflection, x_ref, atol=1e-7)  # 0.1 um on a 50 mm stroke


def test_forward_and_inverse_agree_with_friction(table1):
    # compression half-cycle (x' > 0 strictly) with pin friction, tau_AF and slider friction; the smoothed
    # sign tanh(theta2'/1e-6) equals sgn to machine precision away from the turning points
    p = table1.replace(friction_model="constant", slider_friction=0.2)
    mot = SinusoidMotion(omega=10.0, amplitude=0.05, offset=0.01)
    vals = p.values()
    t0 = 0.1 * mot.period

    def f_inv(t):
        x, xd, xdd = mot(np.atleast_1d(t + t0))
        return dyn.drive_force_components(x, xd, xdd, theta2_cutoff=p.toggle_cutoff, **vals)["force"][0]

    x0, v0, _ = mot(t0)
    res = CFCS(p).forward(
        0.3 * mot.period, force=f_inv, x0=float(x0), v0=float(v0), n=51, sign_smoothing=1e-6, rtol=1e-10
    )
    np.testing.assert_allclose(res.deflection, mot(res.time + t0)[0], atol=1e-7)


@pytest.mark.parametrize("force, x0, crossings", [(12.8, 0.005, False), (12.0, 0.01, True)])
def test_forward_conserves_energy_without_friction(table1, force, x0, crossings):
    # constant force F0: T + V - F0 x is conserved (relative 1e-6 with rtol 1e-10).  With F0 = 12 N, below
    # the 12.58 N of the toggle, the slider extends and the crank passes through the toggle into the
    # mirror branch: the forward problem needs no cut-off there
    p = table1.without_dissipation()
    res = CFCS(p).forward(0.5, force=force, x0=x0, n=501, rtol=1e-10)
    h = res.energy - force * res.deflection
    assert np.ptp(h) < 1e-6 * np.max(np.abs(res.energy))
    assert (res.summary["toggle_crossings"] > 0) == crossings
    assert res.summary["toggle_cutoff_rad"] is None


def test_forward_stops_at_the_kinematic_limit(table1):
    from springdyn.core.errors import SolverError

    with pytest.raises(SolverError, match="kinematic limit"):
        CFCS(table1.without_dissipation()).forward(2.0, force=200.0, x0=0.01)


def test_forward_friction_dissipates(table1):
    # with friction, a launched slider loses energy: T + V - F0 x decreases (never increases by > rounding)
    res = CFCS(table1.replace(friction_model="constant")).forward(0.5, force=12.8, x0=0.02, v0=0.3, n=501)
    h = res.energy - 12.8 * res.deflection
    assert h[-1] < h[0]
    assert np.all(np.diff(h) < 1e-9)


def test_dynamic_force_components_add_up(model):
    r = model.dynamic(14.7, offset=0.0)
    total = r.force_static + sum(r.components.values())
    np.testing.assert_allclose(r.force, total, rtol=1e-13)
    assert np.all(np.isfinite(r.force))
    assert r.summary["toggle_cutoff_rad"] == model.params.toggle_cutoff
    assert r.summary["toggle_zone_samples"] > 0  # this input starts at the toggle
    assert model.dynamic(14.7).summary["toggle_zone_samples"] == 0  # the default starts from a preload


def test_dynamic_periodic(model):
    # prescribed periodic motion: the inverse force repeats exactly cycle after cycle
    r = model.dynamic(14.7, cycles=2, samples_per_cycle=200)
    np.testing.assert_allclose(r.force[:200], r.force[200:400], rtol=1e-9, atol=1e-9)


def test_running_pcf(model):
    r = model.dynamic(4.19, cycles=1)
    pcf = r.pcf_vs_time
    assert pcf[0] == pytest.approx(100.0)
    assert np.all(np.diff(pcf) <= 1e-12)
    assert pcf[-1] == pytest.approx(r.summary["pcf_percent"], rel=1e-12)


def test_inertia_is_continuous_through_the_toggle(table1):
    # the default input touches the toggle at t = 0, T: the inertia force there comes from its limit
    # (Richardson extrapolation, dynamics.toggle_inertia_limit) and joins the exact values of the
    # neighbouring samples; the force is even about the touch point, so the step to the next sample
    # is ~F'' dt^2 / 2 < 1e-3 N with 4000 samples per cycle
    ideal = CFCS(table1.without_dissipation())
    r = ideal.dynamic(14.7, offset=0.0, cycles=1, samples_per_cycle=4000)
    n_lim = r.summary["toggle_limit_samples"]
    assert n_lim == np.count_nonzero(r.theta2 < dyn.TOGGLE_FLOOR) >= 2  # around t = 0 and t = T
    f = r.force
    assert np.max(np.abs(np.diff(f[:12]))) < 1e-3 and np.max(np.abs(np.diff(f[-12:]))) < 1e-3
    assert f[0] == pytest.approx(f[-1], abs=1e-9)
    # and the exact formula a hair away from the touch point tends to the same value (relative 1e-6)
    p = table1.without_dissipation()
    mot = SinusoidMotion(14.7, 0.072, 0.0)
    t = np.array([4.0, 2.0, 1.0]) * 5e-3 * mot.period  # theta2 = 0.06, 0.03, 0.015 rad: beyond the floor
    c = dyn.drive_force_components(*mot(t), theta2_cutoff=p.toggle_cutoff, **p.values())
    assert not c["at_toggle"].any()
    f4, f2, f1 = c["force"]
    # the force is even in t about the touch point: two Richardson steps remove the t^2 and t^4 terms,
    # leaving O((omega t)^6) ~ 1e-9
    r1, r2 = (4 * f1 - f2) / 3, (4 * f2 - f4) / 3
    f_lim = (16 * r1 - r2) / 15
    assert f[0] == pytest.approx(f_lim, rel=1e-6)


def test_forward_and_inverse_agree_through_the_toggle(table1):
    # frictionless motion touching the toggle at t = T: replaying the inverse force in the forward model,
    # the crank passes into the mirror branch and the slider follows x(t) (reading notes 2: x(theta2) even)
    p = table1.without_dissipation()
    mot = SinusoidMotion(omega=14.7, amplitude=0.04, offset=0.0)
    vals = p.values()
    t0 = 0.25 * mot.period

    def f_inv(t):
        return dyn.inverse_dynamics(mot, np.atleast_1d(t + t0), mot.period, theta2_cutoff=p.toggle_cutoff, **vals)[
            "force"
        ][0]

    x0, v0, _ = mot(t0)
    res = CFCS(p).forward(mot.period, force=f_inv, x0=float(x0), v0=float(v0), n=201, rtol=1e-10)
    assert res.summary["toggle_crossings"] == 1
    np.testing.assert_allclose(res.deflection, mot(res.time + t0)[0], atol=2e-6)  # 2 um on 40 mm
