"""The embedded Runge-Kutta pairs of springdyn.numerics.erk.

References: the order conditions of Butcher (Hairer, Norsett & Wanner, *Solving ODEs I*,
Sec. II.2, Table 2.2) for the tableaux as published (Dormand & Prince 1980; Bogacki &
Shampine 1989; Tsitouras 2011), the same conditions in ``theta`` for the continuous
extensions (ibid. Sec. II.6), and the exact solution of a damped oscillator ``x'' + 2 z w x' + w^2 x = 0``
for the kernels in a stepping loop.
"""

import math

import numpy as np
import pytest

from springdyn.numerics import erk


def _conditions(c, a, b):
    """Residuals of the order conditions up to order 4 (the tall trees of order 5 below)."""
    ac = a @ c
    return {
        1: [b.sum() - 1],
        2: [b @ c - 1 / 2],
        3: [b @ c**2 - 1 / 3, b @ ac - 1 / 6],
        4: [b @ c**3 - 1 / 4, b @ (c * ac) - 1 / 8, b @ (a @ c**2) - 1 / 12, b @ (a @ ac) - 1 / 24],
        5: [b @ c**4 - 1 / 5, b @ (a @ (a @ ac)) - 1 / 120, b @ (c**2 * ac) - 1 / 10],
    }


@pytest.mark.parametrize("name, order", [("dopri5", 5), ("tsit5", 5), ("bs3", 3)])
def test_tableau_order_conditions(name, order):
    c, a, e, d, q = erk.pair_arrays(name)
    s = c.size
    A = np.zeros((s, s))
    A[:, : a.shape[1]] = a
    b = A[-1]  # first same as last: the weights are the last row
    np.testing.assert_allclose(A.sum(axis=1), c, atol=1e-15)  # row sums are the nodes
    res = _conditions(c, A, b)
    for p in range(1, order + 1):
        np.testing.assert_allclose(res[p], 0.0, atol=1e-14, err_msg=f"{name} order {p}")
    if order < 5:  # and not of the next order (the error estimate relies on it)
        assert max(abs(r) for r in res[order + 1]) > 1e-3
    # the embedded solution b_hat = b - e has one order less
    res_hat = _conditions(c, A, b - e)
    for p in range(1, order):
        np.testing.assert_allclose(res_hat[p], 0.0, atol=1e-14, err_msg=f"{name} embedded order {p}")
    assert max(abs(r) for r in res_hat[order]) > 1e-4
    assert q == order


def _oscillator(name, rtol, w=2 * math.pi * 50.0, z=0.05, t_end=0.1):
    """Integrate the damped oscillator with the kernels; return (error at t_end, steps)."""
    c, a, e, d, q = erk.pair_arrays(name)
    jac = np.array([[0.0, 1.0], [-w * w, -2 * z * w]])
    y = np.array([1.0, 0.0])
    k = np.zeros((c.size, 2))
    k[0] = jac @ y
    atol = np.full(2, rtol * 1e-3)
    ytmp, work, rc, out = np.empty(2), np.empty(2), np.empty((5, 2)), np.empty(2)
    t, h, steps, err_old, acc = 0.0, 1e-5, 0, 1e-4, False
    while t < t_end:
        h = min(h, t_end - t)
        for st in range(1, c.size):
            erk.stage_state(y, h, k, st, ytmp, a)
            k[st] = jac @ ytmp
        err = erk.error_norm(y, ytmp, k, h, rtol, atol, work, e)
        if err <= 1.0:
            if d.ndim == 2:
                erk.dense_coefficients_matrix(y, k, h, rc, d)
            else:
                erk.dense_coefficients(y, ytmp, k, h, rc, d)
            erk.dense_eval(rc, 1.0, out)  # the interpolant ends on the step's solution
            np.testing.assert_allclose(out, ytmp, rtol=1e-12, atol=1e-12 * np.abs(ytmp).max())
            t += h
            y = ytmp.copy()
            k[0] = k[-1]
            steps += 1
            h = erk.next_step(h, err, err_old, acc, q)
            err_old, acc = max(err, 1e-4), True
        else:
            h = erk.next_step(h, err, err_old, False, q)
            acc = False
    wd = w * math.sqrt(1 - z * z)
    exact = math.exp(-z * w * t_end) * (math.cos(wd * t_end) + z * w / wd * math.sin(wd * t_end))
    return abs(y[0] - exact), steps


@pytest.mark.parametrize("name", ["dopri5", "tsit5", "bs3"])
def test_pairs_converge_on_a_damped_oscillator(name):
    """The global error follows the tolerance (within a factor 100 of it), and a tighter
    tolerance costs steps as (1/tol)^(1/order) roughly."""
    e6, n6 = _oscillator(name, 1e-6)
    e9, n9 = _oscillator(name, 1e-9)
    assert e6 < 1e-4 and e9 < 1e-7
    assert e9 < e6 / 30
    order = 3 if name == "bs3" else 5
    assert n9 / n6 == pytest.approx(1000 ** (1 / order), rel=0.5)


def test_bs3_dense_output_is_the_cubic_hermite_interpolant():
    """With d = 0 the dense output through (y0, f0, y1, f1) reproduces any cubic exactly."""
    h = 0.3
    p = np.poly1d([0.7, -1.1, 0.4, 2.0])
    dp = p.deriv()
    k = np.zeros((4, 1))
    k[0, 0], k[-1, 0] = dp(0.0), dp(h)
    rc = np.empty((5, 1))
    erk.dense_coefficients(np.array([p(0.0)]), np.array([p(h)]), k, h, rc, erk.pair_arrays("bs3")[3])
    out = np.empty(1)
    for th in (0.0, 0.25, 0.6, 1.0):
        erk.dense_eval(rc, th, out)
        assert out[0] == pytest.approx(p(th * h), abs=1e-14)


def test_tsit5_interpolant_order_conditions():
    """Tsitouras' continuous extension y0 + h sum_i b_i(theta) k_i is of order 4: the order
    conditions hold for every theta with the right-hand sides theta^p / gamma(tree), and it
    ends on the 5th-order solution (b_i(1) = b_i, to the 16 digits of the published
    coefficients); its basis form (d) is the same polynomial."""
    p = erk.TSIT5
    c, a, dense = p["c"], p["a"], p["dense"]
    s = c.size
    A = np.zeros((s, s))
    A[:, : a.shape[1]] = a
    ac = A @ c
    powers = np.arange(5)
    for th in (0.1, 0.37, 0.8, 1.0):
        b = dense @ th**powers  # b_i(theta)
        res = [
            b.sum() - th,
            b @ c - th**2 / 2,
            b @ c**2 - th**3 / 3,
            b @ ac - th**3 / 6,
            b @ c**3 - th**4 / 4,
            b @ (c * ac) - th**4 / 8,
            b @ (A @ c**2) - th**4 / 12,
            b @ (A @ ac) - th**4 / 24,
        ]
        np.testing.assert_allclose(res, 0.0, atol=1e-13, err_msg=f"theta = {th}")
        basis = np.array([th, th * (1 - th), th**2 * (1 - th), th**2 * (1 - th) ** 2])
        np.testing.assert_allclose(p["d"].T @ basis, b, atol=1e-14)
    np.testing.assert_allclose(dense.sum(axis=1), A[-1], atol=1e-14)


@pytest.mark.parametrize("name", ["dopri5", "tsit5"])
def test_fused_kernels_equal_the_generic_ones(name):
    """The fused Dormand-Prince and Tsitouras kernels (coefficients compiled in) compute what
    the generic kernels compute from the published arrays, for every stage (random data;
    round-off only)."""
    rng = np.random.default_rng(7)
    n = 13
    c, a, e, d, q = erk.pair_arrays(name)
    stage, error, dense = {
        "dopri5": (erk.dopri5_stage_state, erk.dopri5_error_norm, erk.dopri5_dense_coefficients),
        "tsit5": (erk.tsit5_stage_state, erk.tsit5_error_norm, erk.tsit5_dense_coefficients),
    }[name]
    y, k = rng.normal(size=n), rng.normal(size=(c.size, n))
    h = 0.37
    out_f, out_g = np.empty(n), np.empty(n)
    for row in range(1, c.size):
        stage(y, h, k, row, out_f)
        erk.stage_state(y, h, k, row, out_g, a)
        np.testing.assert_allclose(out_f, out_g, rtol=1e-13, atol=1e-13, err_msg=f"row {row}")
    atol = np.full(n, 1e-3)
    generic = erk.error_norm(y, out_g, k, h, 1e-4, atol, np.empty(n), e)
    assert error(y, out_g, k, h, 1e-4, atol) == pytest.approx(generic, rel=1e-12)
    rc_f, rc_g = np.empty((5, n)), np.empty((5, n))
    if name == "dopri5":
        dense(y, out_g, k, h, rc_f)
        erk.dense_coefficients(y, out_g, k, h, rc_g, d)
    else:
        dense(y, k, h, rc_f)
        erk.dense_coefficients_matrix(y, k, h, rc_g, d)
    np.testing.assert_allclose(rc_f, rc_g, rtol=1e-12, atol=1e-12)
