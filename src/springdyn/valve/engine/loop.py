"""The integration loops: adaptive steps with landings on breakpoints, outputs, the monitor.

- :func:`integrate_loop`: one run from ``t0`` to ``t_end`` of the chain (and valve train)
  with the pair of ``tab``; outputs at given times from the dense output, optionally
  monitored (:mod:`.monitor`).  Outputs and monitor are runtime choices (empty arrays for
  none), so one compiled variant serves them all.
- :func:`integrate_kernel`: that loop compiled for one pair and one model (the spring
  alone, or the valve train), with the pair's step and the model's right-hand side
  inlined (:mod:`.stepping`): the only compiled variants, made on first use.
- :func:`run_speeds_loop`: many speeds, each from the same initial state: the revolutions
  before the last for the retainer force of the one before (periodicity), then the last
  one with every output, monitored.  Plain Python around the compiled loop, which releases
  the GIL (so threads run speeds in parallel).
"""

from __future__ import annotations

import threading
from typing import NamedTuple

import numpy as np

from ...numerics import erk
from ...numerics.jit import kernel, rebind
from .equations import FASTMATH, rhs_call
from .monitor import finish_monitor, monitor_step, new_monitor
from .stepping import step_kernels

__all__ = [
    "Tolerances",
    "Workspace",
    "workspace",
    "integrate_loop",
    "integrate_kernel",
    "run_speeds_loop",
    "stop_times",
]

#: The step and dense-output functions :func:`integrate_loop` calls: bound, per pair and
#: model, to inlined twins of :mod:`.stepping` by :func:`integrate_kernel`.
attempt_step = dense_coefficients = None


class Tolerances(NamedTuple):
    """Step control of a run."""

    rtol: float  #: relative tolerance [-]
    atol: np.ndarray  #: absolute tolerance per state component [m, m/s]
    h_max: float  #: largest step [s] (run_speeds_loop: as a fraction of a revolution [-])
    max_steps: int  #: step budget, accepted and rejected [-]


class Workspace(NamedTuple):
    """Scratch arrays of :func:`integrate_loop` (allocated by its caller: the loop itself
    allocates nothing, so it runs without numba's reference counting)."""

    k: np.ndarray  #: stage derivatives (stages, n)
    ytmp: np.ndarray  #: the stage state, then the new solution (n,)
    rc: np.ndarray  #: dense-output coefficients of the step (5, n)
    rc_prev: np.ndarray  #: those of the previous step (5, n)
    ybuf: np.ndarray  #: an interpolated state (n,)
    dbuf: np.ndarray  #: its derivative (n,)
    work: np.ndarray  #: scratch (n,)
    ebuf: np.ndarray  #: extra outputs (extra size,)
    eend: np.ndarray  #: extra outputs at the step's end (extra size,)
    no_extra: np.ndarray  #: the empty array: no extra outputs (0,)


def workspace(n, size, stages):
    """A :class:`Workspace` for a state of ``n``, extra outputs of ``size`` and a pair of ``stages``.

    Parameters
    ----------
    n : int
        State size [-].
    size : int
        Extra outputs per sample [-] (:func:`.layout.extra_layout`).
    stages : int
        Stages of the pair [-] (its ``c.shape[0]``).
    """
    return Workspace(
        np.empty((stages, n)),
        np.empty(n),
        np.empty((5, n)),
        np.empty((5, n)),
        np.empty(n),
        np.empty(n),
        np.empty(n),
        np.empty(size),
        np.empty(size),
        np.empty(0),
    )


def integrate_loop(y, t0, t_end, t_out, m, omega, vt, tab, tol, ctl, stops, out, xout, fout, mon, ws):
    """Adaptive embedded Runge-Kutta loop from ``t0`` to ``t_end``.

    ``y`` holds the state at ``t0`` and receives the state reached.  A step never crosses a
    time in ``stops`` (ascending) or ``t_end``: it lands on it (the cam's breakpoints, where
    the lift law is not smooth).  ``ctl`` = (step to try, or 0 to choose one; previous error
    norm; 1 if the last step was accepted) continues the step-size control across calls and
    is updated.

    The outputs at the times ``t_out`` (ascending, within [t0, t_end]) come from the dense
    output as the integration passes them: ``out`` (the states), ``xout`` (the right-hand
    side's extra outputs) and ``fout`` (the retainer force alone) each have a row per time,
    or none.  With a non-empty ``mon.ext`` the run is monitored (:func:`.monitor.monitor_step`);
    an output time within a step then serves as the step's interior sample.  ``ws``: the
    scratch arrays (:func:`workspace`).

    It allocates nothing and is compiled without numba's reference counting (``_nrt=False``,
    like every kernel it calls): the atomic increments and decrements on each array passed
    to a callee cost as much as the monitor's work.

    Parameters
    ----------
    y : ndarray
        State at ``t0`` [m, m/s]; receives the state reached.
    t0, t_end : float
        Start and end [s].
    t_out : ndarray
        Output times [s], ascending.
    m : EngineModel
        The chain and cam arrays [kg, m, N, N s/m, rad].
    omega : float
        Cam speed [rad/s].
    vt : None or ndarray
        The valve train [kg, N/m, N s/m, m, -] (None: the spring alone).
    tab : DormandPrince, BogackiShampine or Tsitouras
        The pair's tableau [-].
    tol : Tolerances
        Step control [-, m, m/s, s].
    ctl : ndarray (3,)
        Step-size control carried across calls [s, -, -].
    stops : ndarray
        Times [s] a step lands on, ascending.
    out, xout, fout : ndarray
        Receive the states [m, m/s], extra outputs [N, m, m/s] and retainer force [N] at
        ``t_out`` (empty: none).
    mon : Monitor
        The monitor's arrays (empty ``mon.ext``: not monitored) [N, s, m/s].
    ws : Workspace
        Scratch arrays [m, m/s].

    Returns
    -------
    status, t, steps, rejected
        Status (:data:`.layout.STATUS`), time reached [s], accepted and rejected steps.
    """
    n = y.shape[0]
    ne = m.laws.shape[0]
    nm = ne - 1
    last = tab.c.shape[0] - 1  # stages; the last is the step's end (FSAL)
    monitor = mon.ext.shape[0] > 0
    want_out = out.shape[0] > 0
    want_x = xout.shape[0] > 0
    want_f = fout.shape[0] > 0
    k = ws.k
    ytmp = ws.ytmp
    rc = ws.rc
    rc_prev = ws.rc_prev
    ybuf = ws.ybuf
    dbuf = ws.dbuf
    work = ws.work
    ebuf = ws.ebuf
    no_extra = ws.no_extra
    eend = ws.eend if monitor else no_extra
    rtol = tol.rtol
    atol = tol.atol
    h_max = tol.h_max
    t = t0
    rhs_call(t, y, m, omega, vt, k[0], no_extra)
    h = ctl[0]
    if not h > 0.0:
        h = erk.initial_step(y, k[0], rtol, atol, h_max)
    h = min(h, h_max)
    err_old = ctl[1]
    accepted_before = ctl[2] > 0.5
    nout = t_out.shape[0]
    iout = 0
    while iout < nout and t_out[iout] <= t:
        if want_out:
            for i in range(n):
                out[iout, i] = y[i]
        if want_x:
            rhs_call(t, y, m, omega, vt, dbuf, xout[iout])
        if want_f:
            rhs_call(t, y, m, omega, vt, dbuf, ebuf)
            fout[iout] = ebuf[nm]
        iout += 1
    istop = 0
    nstops = stops.shape[0]
    nsteps = 0
    nrejected = 0
    while t < t_end:
        if nsteps + nrejected >= tol.max_steps:
            return 1, t, nsteps, nrejected
        if h <= 1e-15 * max(abs(t), 1e-6) + 1e-18:
            return 2, t, nsteps, nrejected
        while istop < nstops and stops[istop] <= t + 1e-9 * h:  # reached (or within round-off)
            istop += 1
        target = t_end
        if istop < nstops and stops[istop] < t_end:
            target = stops[istop]
        landing = t + h >= target
        if landing:
            h = target - t  # land on the breakpoint or the end
        err = attempt_step(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, eend, no_extra, work)
        if not (err == err) or err > 1e300:
            if h < 1e-13:
                return 3, t, nsteps, nrejected
            h *= 0.1
            accepted_before = False
            nrejected += 1
            continue
        if err <= 1.0:
            t_new = target if landing else t + h
            if monitor or (iout < nout and t_out[iout] <= t_new):
                dense_coefficients(tab, y, ytmp, k, h, rc)
            th_m = 0.5  # the interior sample: the output time nearest the middle, else the middle
            mid_row = -1
            while iout < nout and t_out[iout] <= t_new:
                fr = (t_out[iout] - t) / h
                erk.dense_eval(rc, fr, ybuf)
                if want_out:
                    for i in range(n):
                        out[iout, i] = ybuf[i]
                if want_x:
                    rhs_call(t_out[iout], ybuf, m, omega, vt, dbuf, xout[iout])
                    # an output inside the step is its interior sample
                    if 0.0 < fr < 1.0 and (mid_row < 0 or abs(fr - 0.5) < abs(th_m - 0.5)):
                        mid_row = iout
                        th_m = fr
                if want_f:
                    rhs_call(t_out[iout], ybuf, m, omega, vt, dbuf, ebuf)
                    fout[iout] = ebuf[nm]
                iout += 1
            if monitor:
                monitor_step(mon, rc, rc_prev, t, h, t_new, th_m, mid_row, m, omega, vt, ybuf, dbuf, ebuf, eend, xout)
                rc, rc_prev = rc_prev, rc  # this step's interpolant is the previous one now
            for i in range(n):  # (plain loops: numba's slice assignment costs a second to compile)
                y[i] = ytmp[i]
                k[0, i] = k[last, i]
            t = t_new
            h_new = erk.next_step(h, err, err_old, accepted_before, tab.q)
            err_old = max(err, 1e-4)
            accepted_before = True
            nsteps += 1
            h = min(h_new, h_max)
        else:
            h = min(h, erk.next_step(h, err, err_old, False, tab.q))
            accepted_before = False
            nrejected += 1
    ctl[0] = h
    ctl[1] = err_old
    ctl[2] = 1.0 if accepted_before else 0.0
    if monitor:
        finish_monitor(mon)
    return 0, t, nsteps, nrejected


_METHOD_OF = {type(tab): name for name, tab in erk.TABLEAUS.items()}
_VARIANTS: dict = {}
_VARIANTS_LOCK = threading.Lock()


def integrate_kernel(tab, vt):
    """The compiled :func:`integrate_loop` for the pair ``tab`` and the model of ``vt``.

    One variant per pair and model (``vt`` None: the spring alone; else the valve train),
    each with its own step and right-hand side inlined (:func:`.stepping.step_kernels`) and
    its own cache entry; made on first use, so a run compiles its own variant only.

    Parameters
    ----------
    tab : DormandPrince, BogackiShampine or Tsitouras
        The pair's tableau (:data:`springdyn.numerics.erk.TABLEAUS`).
    vt : None or ndarray
        The valve train's parameters [kg, N/m, N s/m, m, -] (None: the spring alone).

    Returns
    -------
    numba dispatcher
        ``integrate_loop`` compiled with ``nogil``, :data:`.equations.FASTMATH` and without
        numba's reference counting.
    """
    key = (_METHOD_OF[type(tab)], vt is not None)
    with _VARIANTS_LOCK:
        if key not in _VARIANTS:
            step, dense = step_kernels(*key)
            fn = rebind(integrate_loop, dict(globals(), attempt_step=step, dense_coefficients=dense))
            fn.__qualname__ = f"integrate_loop_{key[0]}_{'train' if key[1] else 'spring'}"
            _VARIANTS[key] = kernel(fn, nogil=True, fastmath=FASTMATH, _nrt=False)
        return _VARIANTS[key]


def stop_times(stop_angles, omega, r0, r1):
    """The times [s] of the stop angles in revolutions ``r0`` to ``r1 - 1``.

    Parameters
    ----------
    stop_angles : ndarray
        Cam angles [rad] in [0, 2 pi), ascending.
    omega : float
        Cam speed [rad/s].
    r0, r1 : int
        First revolution and the one after the last [-].
    """
    r = np.arange(r0, max(r1, r0))
    return ((2.0 * np.pi * r[:, None] + stop_angles[None, :]) / omega).ravel()


def run_speeds_loop(
    y0,
    omegas,
    revolutions,
    points,
    m,
    vt,
    tab,
    tol,
    stop_angles,
    gaps,
    extra_out,
    prev_out,
    status,
    t_end,
    steps,
    ext,
    events,
    nev,
):
    """Every speed of ``omegas`` [rad/s] from ``y0``: ``revolutions`` revolutions, the last
    sampled at ``points`` per revolution into ``extra_out`` and monitored into ``ext``,
    ``events``, ``nev``; the retainer force over the one before into ``prev_out``.  ``tol.h_max``
    is a fraction of a revolution here.  A failed speed has NaN outputs (no partial ones).

    Plain Python around two calls of :func:`integrate_loop` per speed, which release the GIL
    (a compiled loop over the speeds would cost a second and a half of compilation for a few
    microseconds a speed).

    Parameters
    ----------
    y0 : ndarray
        Initial state [m, m/s].
    omegas : ndarray
        Cam speeds [rad/s].
    revolutions, points : int
        Revolutions per speed and output samples per revolution [-].
    m : EngineModel
        The chain and cam arrays [kg, m, N, N s/m, rad].
    vt : None or ndarray
        The valve train [kg, N/m, N s/m, m, -] (None: the spring alone).
    tab : DormandPrince, BogackiShampine or Tsitouras
        The pair's tableau [-].
    tol : Tolerances
        Step control; ``h_max`` as a fraction of a revolution [-, m, m/s, -].
    stop_angles : ndarray
        Cam angles [rad] a step lands on in every revolution.
    gaps : ndarray
        Coil-contact compressions [m] (``inf``: never).
    extra_out, prev_out : ndarray
        Receive the last revolution's extra outputs [N, m, m/s] and the retainer force [N]
        over the one before.
    status, t_end, steps : ndarray
        Receive per speed the status [-], time reached [s] and steps [-].
    ext, events, nev : ndarray
        Receive the monitor's extremes, events and event counts [N, s, m/s, -].
    """
    n = y0.shape[0]
    no_states = np.empty((0, n))
    no_extra = np.empty((0, extra_out.shape[2]))
    no_force = np.empty(0)
    off = new_monitor(np.empty(0), events[0], nev[0], gaps, 0.0, vt)
    ws = workspace(n, extra_out.shape[2], tab.c.shape[0])
    integrate = integrate_kernel(tab, vt)
    frac = np.arange(points) / points
    for i, omega in enumerate(omegas):
        omega = float(omega)
        period = 2.0 * np.pi / omega
        tol_i = Tolerances(tol.rtol, tol.atol, period * tol.h_max, tol.max_steps)
        y = y0.copy()
        ctl = np.array([0.0, 1e-4, 0.0])
        t1 = (revolutions - 1) * period
        st, t, ns, nr = 0, 0.0, 0, 0
        if revolutions > 1:
            # the revolutions before the last: the retainer force over the one before the
            # last only (for the periodicity check)
            st, t, ns, nr = integrate(
                y,
                0.0,
                t1,
                (revolutions - 2 + frac) * period,
                m,
                omega,
                vt,
                tab,
                tol_i,
                ctl,
                stop_times(stop_angles, omega, 0, revolutions - 1),
                no_states,
                no_extra,
                prev_out[i],
                off,
                ws,
            )
        if st == 0:
            # the last revolution: every output, monitored
            mon = new_monitor(ext[i], events[i], nev[i], gaps, t1, vt)
            tol_l = Tolerances(tol.rtol, tol.atol, tol_i.h_max, tol.max_steps - ns - nr)
            st, t, ns2, _ = integrate(
                y,
                t1,
                revolutions * period,
                (revolutions - 1 + frac) * period,
                m,
                omega,
                vt,
                tab,
                tol_l,
                ctl,
                stop_times(stop_angles, omega, revolutions - 1, revolutions),
                no_states,
                extra_out[i],
                no_force,
                mon,
                ws,
            )
            ns += ns2
        status[i] = st
        t_end[i] = t
        steps[i] = ns
        if st != 0:  # no partial outputs
            extra_out[i] = np.nan
            prev_out[i] = np.nan
