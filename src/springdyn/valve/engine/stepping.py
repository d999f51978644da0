"""One step of an embedded Runge-Kutta pair on the valve chain: stages, error, dense output.

For each pair of :data:`springdyn.numerics.erk.TABLEAUS` a step function (``<pair>_step``:
the stages, each with the right-hand side ``rhs_hot`` inlined, and the scaled error norm)
and a dense-output function (``<pair>_dense``).  They are plain Python: :func:`step_kernels`
makes their compiled twins for one pair and one right-hand side (the spring alone or the
valve train, :mod:`.equations`), inlined into the integration loop before typing
(:func:`springdyn.numerics.jit.twins`).  So a loop variant types the code of its own pair
and equations only: a Type C run compiles no Bogacki-Shampine, Tsitouras or valve-train code.
Which pair goes with which right-hand side in which variant: the table
:data:`springdyn.valve.engine.loop.VARIANTS`.

- Dormand-Prince 5(4) and Tsitouras 5(4): the fused kernels of :mod:`springdyn.numerics.erk`.
- Bogacki-Shampine 3(2): the generic kernels on its arrays.
"""

from __future__ import annotations

from ...core.docstrings import ParameterDocs
from ...numerics import erk
from ...numerics.jit import twins
from .equations import FASTMATH

__all__ = ["dopri5_step", "dopri5_dense", "tsit5_step", "tsit5_dense", "bs3_step", "bs3_dense", "step_kernels"]

#: The parameters several functions share, described once (springdyn.core.docstrings).
_DOCS = ParameterDocs(
    """
    h : float
        Step size [s].
    tab : BogackiShampine
        The pair's tableau [-].
""",
    step_args="""
t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work : as for :func:`dopri5_step`
    Time [s], state [m, m/s], step [s], stages, new state, model, speed [rad/s], train,
    tolerances [-, m, m/s], extra outputs, the empty array, scratch.
""",
    dense_args="""
y, y_new, k, h, rc : as for :func:`dopri5_dense`
    States [m, m/s], stage derivatives, step [s], coefficients.
""",
)


def rhs_hot(t, s, m, omega, vt, out, extra):
    """The right-hand side the step functions' stages call: a name that :func:`step_kernels`
    binds, per variant (:data:`springdyn.valve.engine.loop.VARIANTS`), to a compiled twin of
    :mod:`.equations` (``spring_rhs_hot`` or ``train_rhs_hot``), inlined; never called itself.

    Parameters
    ----------
    t, s, m, omega, vt, out, extra
        Those of :func:`.equations.chain_rhs`: time [s], state [m, m/s], model, speed
        [rad/s], train, ``ds/dt``, extra outputs.
    """
    raise RuntimeError(
        "stepping.rhs_hot is bound per variant by step_kernels (the table loop.VARIANTS): "
        "run a step through loop.integrate_kernel"
    )


@_DOCS.fill
def dopri5_step(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
    """Stages of a Dormand-Prince step of size ``h`` from ``(t, y)``; returns the scaled error norm [-].

    Parameters
    ----------
    tab : DormandPrince
        The pair's tableau [-].
    t : float
        Start of the step [s].
    y : ndarray
        State at ``t`` [m, m/s].
    {h}
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
    for stage in range(1, 7):
        erk.dopri5_stage_state(y, h, k, stage, ytmp)
        rhs_hot(t + tab.c[stage] * h, ytmp, m, omega, vt, k[stage], last_extra if stage == 6 else no_extra)
    return erk.dopri5_error_norm(y, ytmp, k, h, rtol, atol)


@_DOCS.fill
def tsit5_step(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
    """Stages of a Tsitouras step; returns the scaled error norm [-] (parameters of :func:`dopri5_step`).

    Parameters
    ----------
    tab : Tsitouras
        The pair's tableau [-].
    {step_args}
    """
    for stage in range(1, 7):
        erk.tsit5_stage_state(y, h, k, stage, ytmp)
        rhs_hot(t + tab.c[stage] * h, ytmp, m, omega, vt, k[stage], last_extra if stage == 6 else no_extra)
    return erk.tsit5_error_norm(y, ytmp, k, h, rtol, atol)


@_DOCS.fill
def bs3_step(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
    """Stages of a Bogacki-Shampine step; returns the scaled error norm [-] (parameters of :func:`dopri5_step`).

    Parameters
    ----------
    {tab step_args}
    """
    last = tab.c.shape[0] - 1
    for stage in range(1, last + 1):
        erk.stage_state(y, h, k, stage, ytmp, tab.a)
        rhs_hot(t + tab.c[stage] * h, ytmp, m, omega, vt, k[stage], last_extra if stage == last else no_extra)
    return erk.error_norm(y, ytmp, k, h, rtol, atol, work, tab.e)


@_DOCS.fill
def dopri5_dense(tab, y, y_new, k, h, rc):
    """The dense-output coefficients of an accepted Dormand-Prince step.

    Parameters
    ----------
    tab : DormandPrince
        The pair's tableau [-].
    y, y_new : ndarray
        State at the step's start and end [m, m/s].
    k : ndarray (stages, n)
        Stage derivatives [m/s, m/s^2].
    {h}
    rc : ndarray (5, n)
        Receives the coefficients [m, m/s] (:func:`springdyn.numerics.erk.dense_eval`).
    """
    erk.dopri5_dense_coefficients(y, y_new, k, h, rc)


@_DOCS.fill
def tsit5_dense(tab, y, y_new, k, h, rc):
    """The dense-output coefficients of an accepted Tsitouras step (parameters of :func:`dopri5_dense`).

    Parameters
    ----------
    tab : Tsitouras
        The pair's tableau [-].
    {dense_args}
    """
    erk.tsit5_dense_coefficients(y, k, h, rc)


@_DOCS.fill
def bs3_dense(tab, y, y_new, k, h, rc):
    """The dense-output coefficients of an accepted Bogacki-Shampine step (parameters of :func:`dopri5_dense`).

    Parameters
    ----------
    {tab dense_args}
    """
    erk.dense_coefficients(y, y_new, k, h, rc, tab.d)


def step_kernels(step, dense, rhs) -> tuple:
    """The compiled twins (inlined where called) of a pair's step and dense-output functions,
    the step's stages calling the right-hand side ``rhs`` (bound to the name ``rhs_hot``).

    Parameters
    ----------
    step, dense : function
        The pair's ``<pair>_step`` and ``<pair>_dense`` of this module.
    rhs : numba dispatcher
        The right-hand side's compiled twin, inlined into the stages
        (:data:`.equations.spring_rhs_hot` or :data:`.equations.train_rhs_hot`).

    Returns
    -------
    attempt_step, dense_coefficients
        Twins of ``step`` and ``dense``.
    """
    namespace = dict(globals(), rhs_hot=rhs)
    made = twins(namespace, [step.__name__, dense.__name__], fastmath=FASTMATH)
    return made[step.__name__], made[dense.__name__]
