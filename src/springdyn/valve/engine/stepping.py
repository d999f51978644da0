"""One step of the embedded Runge-Kutta pair on the valve chain: stages, error, dense output.

:func:`attempt_step` and :func:`dense_coefficients` are typed on the pair's tableau
(:data:`springdyn.numerics.erk.TABLEAUS`): numba sees the tableau's class when it compiles
the integration loop and types the chosen pair's code only, so a Type C run compiles no
Bogacki-Shampine or Tsitouras kernel.  :func:`attempt_step` holds the one hot call site of
the right-hand side (:data:`.equations.spring_rhs_hot` or :data:`.equations.train_rhs_hot`,
inlined), for every stage.

- Dormand-Prince 5(4) and Tsitouras 5(4): the fused kernels of :mod:`springdyn.numerics.erk`.
- Bogacki-Shampine 3(2): the generic kernels on its arrays.
"""

from __future__ import annotations

from numba import types
from numba.extending import overload

from ...numerics import erk
from .equations import FASTMATH, spring_rhs_hot, train_rhs_hot

__all__ = ["attempt_step", "dense_coefficients"]


def attempt_step(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
    """Stages of a step of size ``h`` from ``(t, y)``; returns the scaled error norm [-].

    Compiled code only (an implementation per tableau class).

    Parameters
    ----------
    tab : DormandPrince, BogackiShampine or Tsitouras
        The pair's tableau [-].
    t : float
        Start of the step [s].
    y : ndarray
        State at ``t`` [m, m/s].
    h : float
        Step size [s].
    k : ndarray (stages, n)
        Stage derivatives; ``k[0]`` holds the derivative at ``t`` (first same as last).
    ytmp : ndarray
        Receives the new solution at ``t + h`` [m, m/s].
    m : EngineModel
        The chain and cam arrays.
    omega : float
        Cam speed [rad/s].
    vt : None or ndarray
        The valve train [kg, N/m, N s/m, m, -] (None: the spring alone).
    rtol : float
        Relative tolerance [-].
    atol : ndarray
        Absolute tolerance per component [m, m/s].
    last_extra : ndarray
        Receives the extra outputs at ``t + h`` [N, m, m/s] (empty: none).
    no_extra : ndarray
        The empty array [-].
    work : ndarray
        Scratch of the state's size [m, m/s].
    """
    raise NotImplementedError("attempt_step is compiled code: call it from a kernel")


def dense_coefficients(tab, y, y_new, k, h, rc):
    """The dense-output coefficients of an accepted step (compiled code only).

    Parameters
    ----------
    tab : DormandPrince, BogackiShampine or Tsitouras
        The pair's tableau [-].
    y, y_new : ndarray
        State at the step's start and end [m, m/s].
    k : ndarray (stages, n)
        Stage derivatives [m/s, m/s^2].
    h : float
        Step size [s].
    rc : ndarray (5, n)
        Receives the coefficients [m, m/s] (:func:`springdyn.numerics.erk.dense_eval`).
    """
    raise NotImplementedError("dense_coefficients is compiled code: call it from a kernel")


def _class(tab):
    return getattr(tab, "instance_class", None)


@overload(attempt_step, jit_options=dict(fastmath=FASTMATH, error_model="numpy", _nrt=False))
def _attempt_step(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
    cls = _class(tab)
    # the spring alone (vt None) or the valve train: chosen here, by type, so that each
    # variant types the equations it runs only
    rhs_hot = spring_rhs_hot if isinstance(vt, types.NoneType) else train_rhs_hot
    if cls is erk.DormandPrince:
        def dopri5(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
            for stage in range(1, 7):
                erk.dopri5_stage_state(y, h, k, stage, ytmp)
                rhs_hot(t + tab.c[stage] * h, ytmp, m, omega, vt, k[stage], last_extra if stage == 6 else no_extra)
            return erk.dopri5_error_norm(y, ytmp, k, h, rtol, atol)
        return dopri5
    if cls is erk.Tsitouras:
        def tsit5(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
            for stage in range(1, 7):
                erk.tsit5_stage_state(y, h, k, stage, ytmp)
                rhs_hot(t + tab.c[stage] * h, ytmp, m, omega, vt, k[stage], last_extra if stage == 6 else no_extra)
            return erk.tsit5_error_norm(y, ytmp, k, h, rtol, atol)
        return tsit5
    if cls is erk.BogackiShampine:
        def bs3(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
            last = tab.c.shape[0] - 1
            for stage in range(1, last + 1):
                erk.stage_state(y, h, k, stage, ytmp, tab.a)
                rhs_hot(t + tab.c[stage] * h, ytmp, m, omega, vt, k[stage], last_extra if stage == last else no_extra)
            return erk.error_norm(y, ytmp, k, h, rtol, atol, work, tab.e)
        return bs3
    return None


@overload(dense_coefficients, jit_options=dict(error_model="numpy", _nrt=False))
def _dense_coefficients(tab, y, y_new, k, h, rc):
    cls = _class(tab)
    if cls is erk.DormandPrince:
        def dopri5(tab, y, y_new, k, h, rc):
            erk.dopri5_dense_coefficients(y, y_new, k, h, rc)
        return dopri5
    if cls is erk.Tsitouras:
        def tsit5(tab, y, y_new, k, h, rc):
            erk.tsit5_dense_coefficients(y, k, h, rc)
        return tsit5
    if cls is erk.BogackiShampine:
        def bs3(tab, y, y_new, k, h, rc):
            erk.dense_coefficients(y, y_new, k, h, rc, tab.d)
        return bs3
    return None
