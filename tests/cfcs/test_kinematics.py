"""Kinematics of the slider-crank (reading notes 2, 2.1; Eqs. (14), (15), (25) of the CFCS paper)."""

import numpy as np
import pytest

from springdyn.cfcs import kinematics as k

from .conftest import R2, R3


def test_inverse_is_exact_roundtrip():
    # theta2 -> x -> theta2 over the whole range; tolerance: a few ulps of pi/2 (closed-form inverse)
    th = np.linspace(0.0, np.pi / 2, 2001)
    x = k.deflection_from_theta2(th, R2, R3)
    np.testing.assert_allclose(k.theta2_from_deflection(x, R2, R3), th, atol=1e-12)


def test_inverse_keeps_precision_near_toggle():
    # near theta2 = 0, x ~ k th^2/2 with k = r2 (1 + r2/r3); the asin form must recover tiny angles
    # to relative 1e-9 (an arccos form would lose ~half the digits)
    th = np.array([1e-7, 1e-6, 1e-5])
    x = k.deflection_from_theta2(th, R2, R3)
    x_series = 0.5 * R2 * (1 + R2 / R3) * th**2  # leading term of the series (independent), next term O(th^2)
    np.testing.assert_allclose(x, x_series, rtol=1e-9)
    np.testing.assert_allclose(k.theta2_from_deflection(x_series, R2, R3), th, rtol=1e-9)


def test_loop_closure_holds():
    # r1 = r2 cos th2 + r3 cos th3 and r2 sin th2 + r3 sin th3 = 0 (reading notes 2.1); machine precision
    th2 = np.linspace(-1.5, 1.5, 301)
    th3 = k.coupler_angle(th2, R2, R3)
    np.testing.assert_allclose(R2 * np.sin(th2) + R3 * np.sin(th3), 0.0, atol=1e-15)
    np.testing.assert_allclose(R2 * np.cos(th2) + R3 * np.cos(th3), k.slider_position(th2, R2, R3), atol=1e-15)
    np.testing.assert_allclose(k.spring_angle(th2, R2, R3), -th3, atol=0)


def test_jacobian_matches_eq25_and_finite_differences():
    # G = -dr1/dth2 (Eq. 25 and reading notes 2.1: -r1 r2 sin th2 / D); FD step 1e-6 -> error ~1e-11
    th = np.linspace(0.01, 1.55, 50)
    g = k.slider_jacobian(th, R2, R3)
    np.testing.assert_allclose(g, -k.dr1_dtheta2(th, R2, R3), rtol=1e-13)
    np.testing.assert_allclose(
        g, k.slider_position(th, R2, R3) * R2 * np.sin(th) / k.coupler_root(th, R2, R3), rtol=1e-13
    )
    h = 1e-5  # truncation ~h^2 = 1e-10 relative, round-off ~1e-17/h / G < 1e-9
    fd = (k.deflection_from_theta2(th + h, R2, R3) - k.deflection_from_theta2(th - h, R2, R3)) / (2 * h)
    np.testing.assert_allclose(g, fd, rtol=1e-8)
    fd2 = (k.slider_jacobian(th + h, R2, R3) - k.slider_jacobian(th - h, R2, R3)) / (2 * h)
    np.testing.assert_allclose(k.slider_jacobian_derivative(th, R2, R3), fd2, rtol=1e-7, atol=1e-8)


def test_toggle_and_kinematic_limit():
    # reading notes 2: theta2 = 0 -> r1 = r2 + r3, G = 0; theta2 = 90 deg -> r1 = sqrt(r3^2 - r2^2)
    assert k.slider_position(0.0, R2, R3) == pytest.approx(R2 + R3, abs=1e-16)
    assert k.slider_jacobian(0.0, R2, R3) == 0.0
    assert k.kinematic_limit_deflection(R2, R3) == pytest.approx(0.180 - np.sqrt(0.095**2 - 0.085**2), rel=1e-14)
    assert k.theta2_from_deflection(k.kinematic_limit_deflection(R2, R3), R2, R3) == pytest.approx(np.pi / 2, abs=2e-8)
    # the deflection grows monotonically up to the limit (G > 0 inside)
    assert np.all(k.slider_jacobian(np.linspace(1e-6, np.pi / 2, 500), R2, R3) > 0)
    # outside the range: NaN, never a silent wrong angle
    assert np.isnan(k.theta2_from_deflection(-1e-3, R2, R3))
    assert np.isnan(k.theta2_from_deflection(k.kinematic_limit_deflection(R2, R3) + 1e-3, R2, R3))


def test_crank_rates_exact_outside_toggle_zone():
    # theta2(t) of a smooth motion differentiated numerically (independent of the formulas); FD h = 1e-6 s
    w, a, off = 9.0, 0.05, 0.01
    t = np.linspace(0.05, 0.6, 23)

    def th_of(tt):
        return k.theta2_from_deflection(off + a * (1 - np.cos(w * tt)) / 2, R2, R3)

    x = off + a * (1 - np.cos(w * t)) / 2
    xd, xdd = a * w * np.sin(w * t) / 2, a * w * w * np.cos(w * t) / 2
    th, thd, thdd, jac = k.crank_rates(x, xd, xdd, R2, R3)
    h = 1e-5
    np.testing.assert_allclose(thd, (th_of(t + h) - th_of(t - h)) / (2 * h), rtol=1e-7, atol=1e-8)
    np.testing.assert_allclose(thdd, (th_of(t + h) - 2 * th + th_of(t - h)) / h**2, rtol=1e-4, atol=1e-4)


def test_crank_rates_at_the_toggle_are_undefined_not_wrong():
    # at G = 0 the rates are 0/0: crank_rates returns non-finite values (never a silent number);
    # the inverse dynamics replaces the inertia there by its limit (test_dynamics)
    th, thd, thdd, jac = k.crank_rates(np.array([0.0]), [0.0], [1.0], R2, R3)
    assert th[0] == 0.0 and jac[0] == 0.0
    assert not np.isfinite(thd[0]) and not np.isfinite(thdd[0])
