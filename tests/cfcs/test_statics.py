"""Statics: virtual-work force, PCF, dissipative branches (reading notes 2.2, 2.3)."""

import numpy as np
import pytest
from scipy.integrate import quad

from springdyn.cfcs import CFCS, statics
from springdyn.cfcs.kinematics import deflection_from_theta2, slider_jacobian, theta2_from_deflection

from .conftest import K3_TABLE1, R2, R3


def test_reading_notes_reference_values(table1_k3):
    # reading notes 2.3 (K3 = 2.5308 as printed): 12.580 N at the toggle, max 12.970 N at x = 48.5 mm
    # (theta2 = 46.1 deg), Fmin/Fmax over 0-72 mm = 97.0 %; tolerances = half a unit of the last printed digit
    s = CFCS(table1_k3).static(0.072).summary
    assert s["force_at_zero_N"] == pytest.approx(12.580, abs=5e-4)
    assert s["force_max_N"] == pytest.approx(12.970, abs=5e-4)
    assert s["deflection_at_force_max_m"] == pytest.approx(0.0485, abs=5e-5)
    th_max = theta2_from_deflection(s["deflection_at_force_max_m"], R2, R3)
    assert np.degrees(th_max) == pytest.approx(46.1, abs=0.05)
    assert s["pcf_percent"] == pytest.approx(97.0, abs=0.05)
    assert s["stroke_m"] == 0.072
    assert s["max_stress_Pa"] is None  # no flexure dimensions: no stress claimed


def test_force_at_toggle_is_the_limit_of_the_closed_form():
    # the closed form at tiny angles tends to K3 r2 / (r3 (r2 + r3)) (continuity, relative error O(th^2))
    f0 = statics.static_force_at_toggle(K3_TABLE1, R2, R3)
    assert statics.static_force(0.0, K3_TABLE1, R2, R3) == pytest.approx(f0, rel=1e-15)
    for th in (1e-3, 1e-5, 1e-7):
        assert statics.static_force(th, K3_TABLE1, R2, R3) == pytest.approx(f0, rel=2 * th)


def test_static_force_is_the_derivative_of_the_spring_energy():
    # virtual work: F = dV/dx, checked by a central difference of V(x) (independent of the closed form);
    # h = 1e-7 m -> truncation ~1e-12, round-off ~1e-16 J / 1e-7 m -> 1e-9 N
    x = np.linspace(0.002, 0.13, 40)
    h = 1e-7
    v = lambda xx: statics.spring_energy(theta2_from_deflection(xx, R2, R3), K3_TABLE1, R2, R3)  # noqa: E731
    fd = (v(x + h) - v(x - h)) / (2 * h)
    f = statics.static_force(theta2_from_deflection(x, R2, R3), K3_TABLE1, R2, R3)
    np.testing.assert_allclose(f, fd, rtol=1e-7)


def test_energy_pcf_is_stored_energy_over_ideal_work(table1_k3):
    # PCF_E = 100 (V(stroke) - V(0)) / (Fmax stroke): the trapezoid of 721 points vs the exact energy (1e-5)
    s = CFCS(table1_k3).static(0.072).summary
    v_end = statics.spring_energy(theta2_from_deflection(0.072, R2, R3), K3_TABLE1, R2, R3)
    assert s["pcf_energy_percent"] == pytest.approx(100 * v_end / (s["force_max_N"] * 0.072), rel=1e-5)


def test_branches_are_symmetric_and_opposing(model):
    # compression = static + F_d, extension = static - F_d, F_d >= 0 (reading notes 2.2 item 1)
    r = model.static()
    fd = r.force_compression - r.force
    np.testing.assert_allclose(r.force - r.force_extension, fd, rtol=1e-12)
    assert np.all(fd > 0)


def test_branches_without_dissipation_equal_static(table1):
    r = CFCS(table1.without_dissipation()).static()
    np.testing.assert_array_equal(r.force_compression, r.force)
    np.testing.assert_array_equal(r.force_extension, r.force)


def test_friction_models():
    # Eq. (21): paper form = |theta2| * constant form; "none" gives zero
    th = np.linspace(0.0, 1.2, 7)
    c = statics.pin_friction_torque(th, 0.02, "constant", R2, R3)
    np.testing.assert_allclose(statics.pin_friction_torque(th, 0.02, "paper", R2, R3), th * c, rtol=1e-15)
    np.testing.assert_array_equal(statics.pin_friction_torque(th, 0.02, "none", R2, R3), 0.0)
    # constant form: the work over a stroke is C (2 dtheta2 + dtheta_K3) (two pins, reading notes 2.2 item 2)
    w, _ = quad(lambda t: statics.pin_friction_torque(t, 0.02, "constant", R2, R3), 0.1, 1.0)
    dk3 = np.arcsin(R2 * np.sin(1.0) / R3) - np.arcsin(R2 * np.sin(0.1) / R3)
    assert w == pytest.approx(0.02 * (2 * 0.9 + dk3), rel=1e-10)
    with pytest.raises(ValueError):
        statics.pin_friction_torque(th, 0.02, "viscous", R2, R3)


def test_dissipative_force_is_capped_in_the_toggle_zone(model):
    # the Jacobian is frozen below the cut-off: the dissipative force is bounded and constant in G there
    p = model.params
    g_c = slider_jacobian(p.toggle_cutoff, R2, R3)
    th = np.array([0.0, 1e-6, 0.5 * p.toggle_cutoff])
    np.testing.assert_array_equal(statics.frozen_jacobian(th, R2, R3, p.toggle_cutoff), g_c)


def test_pcf_definitions():
    assert statics.percent_constant_force([10.0, 12.5, 8.0]) == pytest.approx(64.0)
    assert np.isnan(statics.percent_constant_force([-1.0, 0.0]))
    # a linear spring F = k x over [0, s]: PCF_E = 50 % exactly (trapezoid is exact on a line)
    x = np.linspace(0, 0.1, 11)
    assert statics.percent_constant_force_energy(x, 3.0 * x) == pytest.approx(50.0, rel=1e-12)


def test_deflection_grid_runs_from_toggle(model):
    r = model.static(0.05, n=101)
    assert r.deflection[0] == 0.0 and r.deflection[-1] == pytest.approx(0.05)
    np.testing.assert_allclose(deflection_from_theta2(r.theta2, R2, R3), r.deflection, atol=1e-15)
