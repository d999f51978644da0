"""Compiled building blocks of adaptive embedded explicit Runge-Kutta pairs.

Three pairs, each with a free continuous extension (dense output) and first-same-as-last
stages:

- **Dormand-Prince 5(4)** (Dormand & Prince 1980) with the 4th-order dense output of
  Hairer, Norsett & Wanner (*Solving ODEs I*, 2nd ed., Sec. II.5-6; their ``dopri5``
  code): 6 new right-hand sides per step, stability interval on the negative real axis
  about [-3.3, 0].  Efficient where the step is set by accuracy.
- **Bogacki-Shampine 3(2)** (Bogacki & Shampine 1989, the pair of MATLAB's ``ode23``) with
  its cubic Hermite dense output: 3 new right-hand sides per step, stability interval about
  [-2.5, 0].  Where the step is set by stability (stiff, strongly damped modes) it takes
  about as many steps as Dormand-Prince for half the work.
- **Tsitouras 5(4)** (Tsitouras 2011) with its 4th-order interpolant: Dormand-Prince's cost
  per step with coefficients tuned for a smaller principal error; about 13 % fewer steps on
  the valve-spring study at the same tolerances, with a larger error estimate-to-error
  ratio (docs/valve-dynamics.md, "Which pair, measured").

Dormand-Prince and Tsitouras also have fused kernels (``dopri5_*``, ``tsit5_*``): each
stage, error estimate and set of dense-output coefficients in one pass over the state with
the coefficients compiled in; the tests check them against the generic kernels.

Step-size control is the PI controller of Gustafsson (ibid. Sec. IV.2) with exponents
``0.7/q`` and ``0.4/q`` for a pair whose error estimate is of order ``q - 1``.

Every function here is a small cached kernel (:func:`springdyn.numerics.jit.kernel`) with no
callable arguments (numba cannot disk-cache a function that takes another jitted function).
A pair is passed as its tableau (:data:`TABLEAUS`), a named tuple whose *class* names the
pair: a model's stepping code dispatches on that type at compile time, so a run compiles
the kernels of its own pair only (see :mod:`springdyn.valve.engine.stepping`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .jit import kernel

__all__ = [
    "PAIRS",
    "pair_arrays",
    "TABLEAUS",
    "DormandPrince",
    "BogackiShampine",
    "Tsitouras",
    "stage_state",
    "error_norm",
    "next_step",
    "dense_coefficients",
    "dense_eval",
    "initial_step",
    "dopri5_stage_state",
    "dopri5_error_norm",
    "dopri5_dense_coefficients",
    "dense_coefficients_matrix",
    "tsit5_stage_state",
    "tsit5_error_norm",
    "tsit5_dense_coefficients",
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
#: Tsitouras 5(4) (Tsitouras 2011, the pair of OrdinaryDiffEq.jl's ``Tsit5``): the same
#: stage count as Dormand-Prince, with coefficients optimised for a smaller principal error
#: (it drops the simplifying assumptions except the first column's).  The dense output is
#: Tsitouras' 4th-order interpolant ``y0 + h sum_i b_i(theta) k_i``; ``dense`` holds the
#: monomial coefficients of ``b_i(theta)`` (stages x degree 0-4) and ``d`` the same
#: interpolant in the basis of :func:`dense_eval` (rows 1-4 of ``rc`` per unit ``h k_i``).
_TS_C = np.array([0.0, 0.161, 0.327, 0.9, 0.9800255409045096857298102862870245954942, 1.0, 1.0])
_TS_A = np.zeros((7, 6))
_TS_A[1, 0] = 0.161
_TS_A[2, :2] = [-0.8480655492356988544426874250230774675121e-2, 0.3354806554923569885444268742502307746751]
_TS_A[3, :3] = [
    2.897153057105493432130432594192938764925,
    -6.359448489975074843148159912383825625953,
    4.362295432869581411017727318190886861028,
]
_TS_A[4, :4] = [
    5.325864828439256604428877920840511317836,
    -11.74888356406282787774717033978577296189,
    7.495539342889836208304604784564358155659,
    -0.9249506636175524925650207933207191611350e-1,
]
_TS_A[5, :5] = [
    5.861455442946420028659251486982647890394,
    -12.92096931784710929170611868178335939542,
    8.159367898576158643180400794539253485182,
    -0.7158497328140099722453054252582973869127e-1,
    -0.2826905039406838290900305721271224146718e-1,
]
_TS_A[6, :6] = [
    0.9646076681806522951816731316512876333712e-1,
    0.01,
    0.4798896504144995747752495322905965199130,
    1.379008574103741893192274821856872770756,
    -3.290069515436080679901047585711363850116,
    2.324710524099773982415355918398765796109,
]
_TS_BHAT = np.array(
    [
        0.9468075576583945807478876255758922856118e-1,
        0.9183565540343253096776363936645313759814e-2,
        0.4877705284247615707855642599631228241517,
        1.234297566930478985655109673884237654036,
        -2.707712349983525454881109975059321670690,
        1.866628418170587035753719399566211498666,
        1.0 / 66.0,
    ]
)
_TS_DENSE = np.array(
    [
        [0.0, 1.0, -2.763706197274826, 2.9132554618219126, -1.0530884977290216],
        [0.0, 0.0, 0.13169999999999998, -0.2234, 0.1017],
        [0.0, 0.0, 3.9302962368947516, -5.941033872131505, 2.490627285651253],
        [0.0, 0.0, -12.411077166933676, 30.33818863028232, -16.548102889244902],
        [0.0, 0.0, 37.50931341651104, -88.1789048947664, 47.37952196281928],
        [0.0, 0.0, -27.896526289197286, 65.09189467479366, -34.87065786149661],
        [0.0, 0.0, 1.5, -4.0, 2.5],
    ]
)


def _monomial_to_rc(m: np.ndarray) -> np.ndarray:
    """Rows 1-4 of the :func:`dense_eval` basis ``1, x, x(1-x), x^2(1-x), x^2(1-x)^2`` from the
    monomial coefficients ``m`` (stages x degree 0-4) of a quartic with no constant term."""
    r4 = m[:, 4]
    r3 = -m[:, 3] - 2.0 * r4
    r2 = r3 + r4 - m[:, 2]
    r1 = m[:, 1] - r2
    return np.array([r1, r2, r3, r4])


TSIT5 = dict(
    c=_TS_C, a=_TS_A, e=np.append(_TS_A[6], 0.0) - _TS_BHAT, dense=_TS_DENSE, d=_monomial_to_rc(_TS_DENSE), q=5.0
)
#: The pairs by name.
PAIRS = {"dopri5": DOPRI5, "bs3": BS3, "tsit5": TSIT5}


def pair_arrays(name: str) -> tuple:
    """The arrays ``(c, a, e, d, q)`` of pair ``name`` (a key of :data:`PAIRS`) for the kernels.

    ``c`` has one entry per stage (the last is the step's end, first-same-as-last), ``a``
    is (stages, stages - 1), ``e`` has one weight per stage, ``q`` [-] is the controller
    order.  ``d``: for Dormand-Prince and Bogacki-Shampine one weight per stage
    (:func:`dense_coefficients`); for Tsitouras a (4, stages) matrix
    (:func:`dense_coefficients_matrix`).
    """
    p = PAIRS[name]
    return p["c"], np.ascontiguousarray(p["a"], dtype=float), p["e"], p["d"], float(p["q"])


class DormandPrince(NamedTuple):
    """Dormand-Prince 5(4) as the engines read it (arrays of :func:`pair_arrays`)."""

    c: np.ndarray  #: nodes [-]
    a: np.ndarray  #: coupling matrix [-]
    e: np.ndarray  #: error weights [-]
    d: np.ndarray  #: dense-output weights [-]
    q: float  #: controller order [-]


class BogackiShampine(NamedTuple):
    """Bogacki-Shampine 3(2) as the engines read it (arrays of :func:`pair_arrays`)."""

    c: np.ndarray  #: nodes [-]
    a: np.ndarray  #: coupling matrix [-]
    e: np.ndarray  #: error weights [-]
    d: np.ndarray  #: dense-output weights [-] (zero: cubic Hermite)
    q: float  #: controller order [-]


class Tsitouras(NamedTuple):
    """Tsitouras 5(4) as the engines read it (arrays of :func:`pair_arrays`)."""

    c: np.ndarray  #: nodes [-]
    a: np.ndarray  #: coupling matrix [-]
    e: np.ndarray  #: error weights [-]
    d: np.ndarray  #: dense-output matrix (4, stages) [-]
    q: float  #: controller order [-]


#: The pairs' tableaus by name; the class of each selects its compiled kernels.
TABLEAUS = {
    "dopri5": DormandPrince(*pair_arrays("dopri5")),
    "bs3": BogackiShampine(*pair_arrays("bs3")),
    "tsit5": Tsitouras(*pair_arrays("tsit5")),
}


@kernel(_nrt=False)
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


@kernel(_nrt=False)
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
    return math.sqrt(acc / n)


@kernel(_nrt=False)
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


@kernel(_nrt=False)
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


@kernel(_nrt=False)
def dense_eval(rc, theta, out):
    """Evaluate the dense output at the fraction ``theta`` in [0, 1] of the step."""
    t1 = 1.0 - theta
    for i in range(out.shape[0]):
        out[i] = rc[0, i] + theta * (rc[1, i] + t1 * (rc[2, i] + theta * (rc[3, i] + t1 * rc[4, i])))


@kernel(_nrt=False)
def initial_step(y, f0, rtol, atol, h_max):
    """A first step from the size of ``y`` and its derivative (Hairer's heuristic, first part)."""
    n = y.shape[0]
    d0 = 0.0
    d1 = 0.0
    for i in range(n):
        sc = atol[i] + rtol * abs(y[i])
        d0 += (y[i] / sc) ** 2
        d1 += (f0[i] / sc) ** 2
    d0 = math.sqrt(d0 / n)
    d1 = math.sqrt(d1 / n)
    if d0 < 1e-5 or d1 < 1e-5:
        h = 1e-6
    else:
        h = 0.01 * d0 / d1
    return min(h, h_max)


# --- Dormand-Prince 5(4) with its coefficients written into the code -------------------
# The generic kernels above loop over the tableau's rows; these fused ones form each stage,
# the error estimate and the dense-output coefficients in one pass over the state with the
# coefficients as compile-time constants (about a third less time per step for the 5-mass
# chain, where the step's bookkeeping costs as much as its right-hand sides).  The tests
# check them against the generic kernels on the arrays of DOPRI5.
_A21 = 1 / 5
_A31, _A32 = 3 / 40, 9 / 40
_A41, _A42, _A43 = 44 / 45, -56 / 15, 32 / 9
_A51, _A52, _A53, _A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
_A61, _A62, _A63, _A64, _A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
_A71, _A73, _A74, _A75, _A76 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
_E1, _E3, _E4, _E5, _E6, _E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40
_D1, _D3, _D4 = -12715105075 / 11282082432, 87487479700 / 32700410799, -10690763975 / 1880347072
_D5, _D6, _D7 = 701980252875 / 199316789632, -1453857185 / 822651844, 69997945 / 29380423


@kernel(_nrt=False)
def dopri5_stage_state(y, h, k, row, out):
    """:func:`stage_state` for Dormand-Prince 5(4), row ``row`` (1 to 6) of its tableau."""
    n = y.shape[0]
    if row == 1:
        for i in range(n):
            out[i] = y[i] + h * (_A21 * k[0, i])
    elif row == 2:
        for i in range(n):
            out[i] = y[i] + h * (_A31 * k[0, i] + _A32 * k[1, i])
    elif row == 3:
        for i in range(n):
            out[i] = y[i] + h * (_A41 * k[0, i] + _A42 * k[1, i] + _A43 * k[2, i])
    elif row == 4:
        for i in range(n):
            out[i] = y[i] + h * (_A51 * k[0, i] + _A52 * k[1, i] + _A53 * k[2, i] + _A54 * k[3, i])
    elif row == 5:
        for i in range(n):
            out[i] = y[i] + h * (_A61 * k[0, i] + _A62 * k[1, i] + _A63 * k[2, i] + _A64 * k[3, i] + _A65 * k[4, i])
    else:
        for i in range(n):
            out[i] = y[i] + h * (_A71 * k[0, i] + _A73 * k[2, i] + _A74 * k[3, i] + _A75 * k[4, i] + _A76 * k[5, i])


@kernel(_nrt=False)
def dopri5_error_norm(y, y_new, k, h, rtol, atol):
    """:func:`error_norm` for Dormand-Prince 5(4)."""
    n = y.shape[0]
    acc = 0.0
    for i in range(n):
        sc = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
        r = h * (_E1 * k[0, i] + _E3 * k[2, i] + _E4 * k[3, i] + _E5 * k[4, i] + _E6 * k[5, i] + _E7 * k[6, i]) / sc
        acc += r * r
    return math.sqrt(acc / n)


@kernel(_nrt=False)
def dopri5_dense_coefficients(y, y_new, k, h, rc):
    """:func:`dense_coefficients` for Dormand-Prince 5(4)."""
    n = y.shape[0]
    for i in range(n):
        dy = y_new[i] - y[i]
        bspl = h * k[0, i] - dy
        rc[0, i] = y[i]
        rc[1, i] = dy
        rc[2, i] = bspl
        rc[3, i] = dy - h * k[6, i] - bspl
        rc[4, i] = h * (_D1 * k[0, i] + _D3 * k[2, i] + _D4 * k[3, i] + _D5 * k[4, i] + _D6 * k[5, i] + _D7 * k[6, i])


@kernel(_nrt=False)
def dense_coefficients_matrix(y, k, h, rc, d):
    """Fill ``rc`` (5, n) for :func:`dense_eval` from a (4, stages) matrix ``d`` (row ``j`` gives
    ``rc[j + 1] = h sum_i d[j, i] k_i``; ``rc[0] = y``): any quartic continuous extension
    (Tsitouras' interpolant, :data:`TSIT5`)."""
    n = y.shape[0]
    for i in range(n):
        rc[0, i] = y[i]
    for r in range(4):
        for i in range(n):
            rc[r + 1, i] = 0.0
        for j in range(d.shape[1]):
            c = h * d[r, j]
            if c != 0.0:
                for i in range(n):
                    rc[r + 1, i] += c * k[j, i]


# --- Tsitouras 5(4), fused like Dormand-Prince: the indices into its module-level arrays are
# literal, so numba freezes the coefficients into the code as constants.
_TS_E = TSIT5["e"]
_TS_D = TSIT5["d"]


@kernel(_nrt=False)
def tsit5_stage_state(y, h, k, row, out):
    """:func:`stage_state` for Tsitouras 5(4), row ``row`` (1 to 6) of its tableau."""
    n = y.shape[0]
    if row == 1:
        for i in range(n):
            out[i] = y[i] + h * (_TS_A[1, 0] * k[0, i])
    elif row == 2:
        for i in range(n):
            out[i] = y[i] + h * (_TS_A[2, 0] * k[0, i] + _TS_A[2, 1] * k[1, i])
    elif row == 3:
        for i in range(n):
            out[i] = y[i] + h * (_TS_A[3, 0] * k[0, i] + _TS_A[3, 1] * k[1, i] + _TS_A[3, 2] * k[2, i])
    elif row == 4:
        for i in range(n):
            out[i] = y[i] + h * (
                _TS_A[4, 0] * k[0, i] + _TS_A[4, 1] * k[1, i] + _TS_A[4, 2] * k[2, i] + _TS_A[4, 3] * k[3, i]
            )
    elif row == 5:
        for i in range(n):
            out[i] = y[i] + h * (
                _TS_A[5, 0] * k[0, i]
                + _TS_A[5, 1] * k[1, i]
                + _TS_A[5, 2] * k[2, i]
                + _TS_A[5, 3] * k[3, i]
                + _TS_A[5, 4] * k[4, i]
            )
    else:
        for i in range(n):
            out[i] = y[i] + h * (
                _TS_A[6, 0] * k[0, i]
                + _TS_A[6, 1] * k[1, i]
                + _TS_A[6, 2] * k[2, i]
                + _TS_A[6, 3] * k[3, i]
                + _TS_A[6, 4] * k[4, i]
                + _TS_A[6, 5] * k[5, i]
            )


@kernel(_nrt=False)
def tsit5_error_norm(y, y_new, k, h, rtol, atol):
    """:func:`error_norm` for Tsitouras 5(4)."""
    n = y.shape[0]
    acc = 0.0
    for i in range(n):
        sc = atol[i] + rtol * max(abs(y[i]), abs(y_new[i]))
        r = (
            h
            * (
                _TS_E[0] * k[0, i]
                + _TS_E[1] * k[1, i]
                + _TS_E[2] * k[2, i]
                + _TS_E[3] * k[3, i]
                + _TS_E[4] * k[4, i]
                + _TS_E[5] * k[5, i]
                + _TS_E[6] * k[6, i]
            )
            / sc
        )
        acc += r * r
    return math.sqrt(acc / n)


@kernel(_nrt=False)
def tsit5_dense_coefficients(y, k, h, rc):
    """:func:`dense_coefficients_matrix` for Tsitouras 5(4)."""
    n = y.shape[0]
    for i in range(n):
        rc[0, i] = y[i]
        for r in range(4):
            rc[r + 1, i] = h * (
                _TS_D[r, 0] * k[0, i]
                + _TS_D[r, 1] * k[1, i]
                + _TS_D[r, 2] * k[2, i]
                + _TS_D[r, 3] * k[3, i]
                + _TS_D[r, 4] * k[4, i]
                + _TS_D[r, 5] * k[5, i]
                + _TS_D[r, 6] * k[6, i]
            )
