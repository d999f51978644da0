"""Compiled building blocks of adaptive embedded explicit Runge-Kutta pairs.

Two pairs, each with a free continuous extension (dense output) and first-same-as-last
stages:

- **Dormand-Prince 5(4)** (Dormand & Prince 1980) with the 4th-order dense output of
  Hairer, Norsett & Wanner (*Solving ODEs I*, 2nd ed., Sec. II.5-6; their ``dopri5``
  code): 6 new right-hand sides per step, stability interval on the negative real axis
  about [-3.3, 0].  Efficient where the step is set by accuracy.
- **Bogacki-Shampine 3(2)** (Bogacki & Shampine 1989, the pair of MATLAB's ``ode23``) with
  its cubic Hermite dense output: 3 new right-hand sides per step, stability interval about
  [-2.5, 0].  Where the step is set by stability (stiff, strongly damped modes) it takes
  about as many steps as Dormand-Prince for half the work.

Step-size control is the PI controller of Gustafsson (ibid. Sec. IV.2) with exponents
``0.7/q`` and ``0.4/q`` for a pair whose error estimate is of order ``q - 1``.

Every function here is a numba kernel with ``cache=True`` and no callable arguments
(numba cannot disk-cache a function that takes another jitted function); a pair is passed
as its arrays (:data:`PAIRS`), and a model writes its own short stepping loop around its
own right-hand side and calls these pieces for the stages, the error norm, the next step
size and the dense output.  See :func:`springdyn.valve.engine.run_speeds` for such a loop.
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = [
    "PAIRS",
    "pair_arrays",
    "stage_state",
    "error_norm",
    "next_step",
    "dense_coefficients",
    "dense_eval",
    "initial_step",
]

#: Dormand-Prince 5(4): nodes ``c``, coupling ``a`` (row i uses stages 0..i-1), error
#: weights ``e`` (5th- minus 4th-order solution), dense-output weights ``d`` of Hairer's
#: ``dopri5``, and the controller order ``q``.
DOPRI5 = dict(
    c=np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0]),
    a=np.array(
        [
            [0, 0, 0, 0, 0, 0],
            [1 / 5, 0, 0, 0, 0, 0],
            [3 / 40, 9 / 40, 0, 0, 0, 0],
            [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
            [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
            [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0],
            [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
        ]
    ),
    e=np.array([71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40]),
    d=np.array(
        [
            -12715105075 / 11282082432,
            0.0,
            87487479700 / 32700410799,
            -10690763975 / 1880347072,
            701980252875 / 199316789632,
            -1453857185 / 822651844,
            69997945 / 29380423,
        ]
    ),
    q=5.0,
)
#: Bogacki-Shampine 3(2): the 3rd-order weights are the last row of ``a`` (FSAL); the
#: error weights are ``b - b_hat`` with ``b_hat = (7/24, 1/4, 1/3, 1/8)``; the dense output
#: is the cubic Hermite interpolant (``d = 0``).
BS3 = dict(
    c=np.array([0.0, 1 / 2, 3 / 4, 1.0]),
    a=np.array(
        [
            [0, 0, 0],
            [1 / 2, 0, 0],
            [0, 3 / 4, 0],
            [2 / 9, 1 / 3, 4 / 9],
        ]
    ),
    e=np.array([-5 / 72, 1 / 12, 1 / 9, -1 / 8]),
    d=np.zeros(4),
    q=3.0,
)
#: The pairs by name.
PAIRS = {"dopri5": DOPRI5, "bs3": BS3}


def pair_arrays(name: str) -> tuple:
    """The arrays ``(c, a, e, d, q)`` of pair ``name`` (``"dopri5"`` or ``"bs3"``) for the kernels.

    ``c`` has one entry per stage (the last is the step's end, first-same-as-last), ``a``
    is (stages, stages - 1), ``e`` and ``d`` have one weight per stage, ``q`` [-] is the
    controller order.
    """
    p = PAIRS[name]
    return p["c"], np.ascontiguousarray(p["a"], dtype=float), p["e"], p["d"], float(p["q"])


@njit(cache=True, error_model="numpy")
def stage_state(y, h, k, row, out, a):
    """``out = y + h * sum_j a[row, j] k[j]`` for stage ``row`` (k: (stages, n) derivatives).

    The loops run along the rows of ``k`` (contiguous), which lets the compiler vectorise
    them: for the 100-state distributed chain this is several times faster than a sum
    over the stages per component.
    """
    n = y.shape[0]
    for i in range(n):
        out[i] = y[i]
    for j in range(row):
        c = h * a[row, j]
        if c != 0.0:
            for i in range(n):
                out[i] += c * k[j, i]


@njit(cache=True, error_model="numpy")
def error_norm(y, y_new, k, h, rtol, atol, work, e):
    """RMS of the local error estimate ``h sum_j e_j k_j`` scaled by ``atol_i + rtol
    max(|y|, |y_new|)`` (``atol``: one absolute tolerance per component; ``work``: scratch
    of the state's size)."""
    n = y.shape[0]
    for i in range(n):
        work[i] = e[0] * k[0, i]
    for j in range(1, e.shape[0]):
        c = e[j]
        if c != 0.0:
            for i in range(n):
                work[i] += c * k[j, i]
    acc = 0.0
    for i in range(n):
        sc = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
        r = h * work[i] / sc
        acc += r * r
    return np.sqrt(acc / n)


@njit(cache=True, error_model="numpy")
def next_step(h, err, err_old, accepted_before, q):
    """Step-size factor of the PI controller (alpha = 0.7/q, beta = 0.4/q), limited to
    [0.2, 10]; right after a rejection the step does not grow."""
    safety = 0.9
    if err == 0.0:
        return h * 10.0
    if accepted_before:
        fac = safety * err ** (-0.7 / q) * err_old ** (0.4 / q)
    else:
        fac = safety * err ** (-1.0 / q)
    fac = min(10.0, max(0.2, fac))
    return h * fac


@njit(cache=True, error_model="numpy")
def dense_coefficients(y, y_new, k, h, rc, d):
    """Fill ``rc`` (5, n) with the dense-output coefficients of the accepted step.

    ``k[0]`` is f at the step start, ``k[-1]`` f at its end (FSAL).  With ``d = 0`` the
    interpolant is the cubic Hermite one.
    """
    n = y.shape[0]
    last = d.shape[0] - 1
    for i in range(n):
        dy = y_new[i] - y[i]
        bspl = h * k[0, i] - dy
        rc[0, i] = y[i]
        rc[1, i] = dy
        rc[2, i] = bspl
        rc[3, i] = dy - h * k[last, i] - bspl
        rc[4, i] = d[0] * k[0, i]
    for j in range(1, d.shape[0]):
        c = d[j]
        if c != 0.0:
            for i in range(n):
                rc[4, i] += c * k[j, i]
    for i in range(n):
        rc[4, i] *= h


@njit(cache=True, error_model="numpy")
def dense_eval(rc, theta, out):
    """Evaluate the dense output at the fraction ``theta`` in [0, 1] of the step."""
    t1 = 1.0 - theta
    for i in range(out.shape[0]):
        out[i] = rc[0, i] + theta * (rc[1, i] + t1 * (rc[2, i] + theta * (rc[3, i] + t1 * rc[4, i])))


@njit(cache=True, error_model="numpy")
def initial_step(y, f0, rtol, atol, h_max):
    """A first step from the size of ``y`` and its derivative (Hairer's heuristic, first part)."""
    n = y.shape[0]
    d0 = 0.0
    d1 = 0.0
    for i in range(n):
        sc = atol[i] + rtol * abs(y[i])
        d0 += (y[i] / sc) ** 2
        d1 += (f0[i] / sc) ** 2
    d0 = np.sqrt(d0 / n)
    d1 = np.sqrt(d1 / n)
    if d0 < 1e-5 or d1 < 1e-5:
        h = 1e-6
    else:
        h = 0.01 * d0 / d1
    return min(h, h_max)
