"""The integration loops: adaptive steps with landings on breakpoints, outputs, the monitor.

- :func:`integrate_loop`: one run from ``t0`` to ``t_end`` of the chain (and valve train)
  with the pair of ``tab``; outputs at given times from the dense output, optionally
  monitored (:mod:`.monitor`).  Outputs and monitor are runtime choices (empty arrays for
  none), so one compiled variant serves them all.
- :func:`integrate_kernel`: that loop compiled for one pair and one model (the spring
  alone, or the valve train), with the pair's step and the model's right-hand side
  inlined (:mod:`.stepping`): the only compiled variants, listed in :data:`VARIANTS` and
  made on first use.
- :func:`run_speeds_loop`: many speeds, revolution by revolution: a given number of
  revolutions, or until two revolutions repeat (the periodic steady state), each speed from
  the initial state or from the state the speed before ended in; the last revolution with
  every output, monitored.  Plain Python around the compiled loop, which releases the GIL
  (so threads run speeds in parallel).
"""

from __future__ import annotations

import threading
from typing import NamedTuple

import numpy as np

from ...core.docstrings import ParameterDocs
from ...numerics import erk
from ...numerics.jit import kernel, rebind
from . import stepping
from .equations import (
    FASTMATH,
    rhs_call,
    rhs_call_pack,
    spring_rhs_hot,
    spring_rhs_hot_pack,
    train_rhs_hot,
    train_rhs_hot_pack,
)
from .layout import (
    CHK_CAM,
    CHK_HLA,
    CHK_RETAINER,
    CHK_SEAT,
    CHK_VALVE_SEAT,
    EXT_VALUES,
    N_CHECK,
    N_EXT,
    X_CAM_FORCE,
    X_DISP,
    X_SEAT_FORCE,
    XT_HLA_CHECK,
    XT_RETAINER_TOTAL,
    XT_SEAT_TOTAL,
)
from .monitor import finish_monitor, monitor_step, monitor_step_pack, new_monitor

__all__ = [
    "Tolerances",
    "Workspace",
    "workspace",
    "integrate_loop",
    "integrate_kernel",
    "VARIANTS",
    "Variant",
    "run_speeds_loop",
    "Revolutions",
    "SpeedOutputs",
    "MIN_PERIODIC_REVOLUTIONS",
    "stop_times",
]

#: The parameters several functions share, described once (springdyn.core.docstrings).
_DOCS = ParameterDocs(
    """
    m : EngineModel
        The chain and cam arrays [kg, m, N, N s/m, rad].
    omega : float
        Cam speed [rad/s].
    tab : DormandPrince, BogackiShampine or Tsitouras
        The pair's tableau [-].
    vt : None or ndarray
        The valve train [kg, N/m, N s/m, m, -] (None: the spring alone).
"""
)

_UNBOUND = (
    "integrate_loop is a template: attempt_step and dense_coefficients are bound per variant by "
    "integrate_kernel (the table loop.VARIANTS); run the loop through integrate_kernel(tab, vt)"
)


def attempt_step(tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work):
    """The step :func:`integrate_loop` takes: a name that :func:`integrate_kernel` binds, per
    variant (:data:`VARIANTS`), to an inlined twin of a pair's ``<pair>_step`` of
    :mod:`.stepping` (whose parameters these are); never called itself.

    Parameters
    ----------
    tab, t, y, h, k, ytmp, m, omega, vt, rtol, atol, last_extra, no_extra, work
        Those of :func:`.stepping.dopri5_step`.
    """
    raise RuntimeError(_UNBOUND)


def dense_coefficients(tab, y, y_new, k, h, rc):
    """The dense output of an accepted step: a name that :func:`integrate_kernel` binds, per
    variant (:data:`VARIANTS`), to an inlined twin of a pair's ``<pair>_dense`` of
    :mod:`.stepping` (whose parameters these are); never called itself.

    Parameters
    ----------
    tab, y, y_new, k, h, rc
        Those of :func:`.stepping.dopri5_dense`.
    """
    raise RuntimeError(_UNBOUND)


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


@_DOCS.fill
def integrate_loop(y, t0, t_end, t_out, m, omega, vt, tab, tol, ctl, stops, out, xout, fout, mon, ws):
    """Adaptive embedded Runge-Kutta loop from ``t0`` to ``t_end``.

    ``y`` holds the state at ``t0`` and receives the state reached.  A step never crosses a
    time in ``stops`` (ascending) or ``t_end``: it lands on it (the cam's breakpoints, where
    the lift law is not smooth).  ``ctl`` = (step to try, or 0 to choose one; previous error
    norm; 1 if the last step was accepted) continues the step-size control across calls and
    is updated.

    The outputs at the times ``t_out`` (ascending, within [t0, t_end]) come from the dense
    output as the integration passes them: ``out`` (the states), ``xout`` (the right-hand
    side's extra outputs) and ``fout`` (the periodicity channels, :func:`check_channels`) each have a row per time,
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
    {m omega vt tab}
    tol : Tolerances
        Step control [-, m, m/s, s].
    ctl : ndarray (3,)
        Step-size control carried across calls [s, -, -].
    stops : ndarray
        Times [s] a step lands on, ascending.
    out, xout, fout : ndarray
        Receive the states [m, m/s], extra outputs [N, m, m/s] and the periodicity channels
        (:data:`.layout.N_CHECK` forces [N]) at ``t_out`` (empty: none).
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
    nm = m.masses.shape[0]
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
                check_channels(xout[iout], ne, nm, fout[iout])
        elif want_f:
            rhs_call(t, y, m, omega, vt, dbuf, ebuf)
            check_channels(ebuf, ne, nm, fout[iout])
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
                    if want_f:
                        check_channels(xout[iout], ne, nm, fout[iout])
                    # an output inside the step is its interior sample
                    if 0.0 < fr < 1.0 and (mid_row < 0 or abs(fr - 0.5) < abs(th_m - 0.5)):
                        mid_row = iout
                        th_m = fr
                elif want_f:
                    rhs_call(t_out[iout], ybuf, m, omega, vt, dbuf, ebuf)
                    check_channels(ebuf, ne, nm, fout[iout])
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


@kernel(inline="always")
def check_channels(e, ne, nm, row):
    """The forces that judge periodicity (columns ``CHK_*`` of :mod:`.layout`) from the extra
    outputs ``e`` of chains of ``ne`` elements and ``nm`` masses: seat and retainer end forces
    (a spring pack's totals), cam contact and valve-seat forces, an adjuster's collapse as a
    force [N]."""
    b = 2 * ne
    tail = b + X_DISP + nm
    row[CHK_SEAT] = e[tail + XT_SEAT_TOTAL]
    row[CHK_RETAINER] = e[tail + XT_RETAINER_TOTAL]
    row[CHK_CAM] = e[b + X_CAM_FORCE]
    row[CHK_VALVE_SEAT] = e[b + X_SEAT_FORCE]
    row[CHK_HLA] = e[tail + XT_HLA_CHECK]  # the adjuster's collapse as a force


class Variant(NamedTuple):
    """One compiled variant of :func:`integrate_loop`: what is bound into its template."""

    step: object  #: the pair's step (``<pair>_step`` of :mod:`.stepping`), bound to ``attempt_step``
    dense: object  #: its dense output (``<pair>_dense``), bound to ``dense_coefficients``
    rhs: object  #: the right-hand side its stages inline (:mod:`.equations`), bound to ``stepping.rhs_hot``


#: Every compiled variant of the engine, by (pair, model): one per Runge-Kutta pair of
#: :data:`springdyn.numerics.erk.TABLEAUS` and model, the spring alone (``"spring"``, the
#: valve train's parameters None) or the valve train (``"train"``, all kinds of train: the
#: kind is a runtime choice, :func:`.equations.train_rhs`), each of one spring or of a spring
#: pack (``"spring-pack"``, ``"train-pack"``: the pack's twins, :data:`.equations.rhs_call_pack`
#: and :data:`.monitor.monitor_step_pack` bound in).  :func:`integrate_kernel` makes a variant on
#: first use (compiled loop ``integrate_loop_<pair>_<model>``, cached on disk), so a run
#: compiles its own variant only.  A new pair or model is a row here.
VARIANTS = {
    (pair, model + pack): Variant(
        getattr(stepping, f"{pair}_step"),
        getattr(stepping, f"{pair}_dense"),
        {
            ("spring", ""): spring_rhs_hot,
            ("train", ""): train_rhs_hot,
            ("spring", "-pack"): spring_rhs_hot_pack,
            ("train", "-pack"): train_rhs_hot_pack,
        }[model, pack],
    )
    for pair in ("dopri5", "bs3", "tsit5")
    for model in ("spring", "train")
    for pack in ("", "-pack")
}
#: What a spring pack's variants bind besides the step: its right-hand side and monitor.
_PACK_BINDINGS = dict(rhs_call=rhs_call_pack, monitor_step=monitor_step_pack)

_METHOD_OF = {type(tab): name for name, tab in erk.TABLEAUS.items()}
#: The variants made in this process, by the keys of :data:`VARIANTS`.
_COMPILED: dict = {}
_COMPILED_LOCK = threading.Lock()


def integrate_kernel(tab, vt, m=None):
    """The compiled :func:`integrate_loop` for the pair ``tab`` and the model of ``vt`` and ``m``.

    One variant per pair and model (``vt`` None: the spring alone; else the valve train; ``m``
    a spring pack's, whose ``damper`` is an array: the pack's twins), each with its own step and
    right-hand side inlined (:data:`VARIANTS`, :func:`.stepping.step_kernels`) and its own cache
    entry; made on first use, so a run compiles its own variant only.

    Parameters
    ----------
    tab : DormandPrince, BogackiShampine or Tsitouras
        The pair's tableau (:data:`springdyn.numerics.erk.TABLEAUS`).
    vt : None or ndarray
        The valve train's parameters [kg, N/m, N s/m, m, -] (None: the spring alone).
    m : EngineModel, optional
        The model [kg, m, N, N s/m, rad]: a spring pack's chooses the pack's variant.

    Returns
    -------
    numba dispatcher
        ``integrate_loop`` compiled with ``nogil``, :data:`.equations.FASTMATH` and without
        numba's reference counting.
    """
    pack = m is not None and m.damper is not None
    key = (_METHOD_OF[type(tab)], ("spring" if vt is None else "train") + ("-pack" if pack else ""))
    with _COMPILED_LOCK:
        if key not in _COMPILED:
            variant = VARIANTS[key]
            step, dense = stepping.step_kernels(variant.step, variant.dense, variant.rhs)
            bound = dict(globals(), attempt_step=step, dense_coefficients=dense, **(_PACK_BINDINGS if pack else {}))
            fn = rebind(integrate_loop, bound)
            fn.__qualname__ = f"integrate_loop_{key[0]}_{key[1].replace('-', '_')}"
            _COMPILED[key] = kernel(fn, nogil=True, fastmath=FASTMATH, _nrt=False)
        return _COMPILED[key]


@_DOCS.fill
def stop_times(stop_angles, omega, r0, r1):
    """The times [s] of the stop angles in revolutions ``r0`` to ``r1 - 1``.

    Parameters
    ----------
    stop_angles : ndarray
        Cam angles [rad] in [0, 2 pi), ascending.
    {omega}
    r0, r1 : int
        First revolution and the one after the last [-].
    """
    r = np.arange(r0, max(r1, r0))
    return ((2.0 * np.pi * r[:, None] + stop_angles[None, :]) / omega).ravel()


class Revolutions(NamedTuple):
    """How many revolutions each speed of :func:`run_speeds_loop` runs."""

    count: int  #: the revolutions (``tol`` 0), else the most [-]
    tol: float  #: periodicity tolerance [N]: stop once two revolutions repeat within it; 0: run ``count``
    warm: bool  #: start each speed from the state the speed before ended in (else every speed from ``y0``)
    band: int  #: a speed that does not settle: its last ``band`` revolutions are monitored for the band [-]


class SpeedOutputs(NamedTuple):
    """What :func:`run_speeds_loop` writes per speed (leading dimension: the speed)."""

    extra: np.ndarray  #: the last revolution's extra outputs (points, extra size) [N, m, m/s]
    status: np.ndarray  #: status (:data:`.layout.STATUS`) [-]
    t_end: np.ndarray  #: time reached [s]
    steps: np.ndarray  #: accepted steps [-]
    ext: np.ndarray  #: the monitor's extremes of the last revolution (N_EXT,) [N, s, m/s, -]
    events: np.ndarray  #: its events (MAX_EVENTS, 4)
    nev: np.ndarray  #: events written (1,) [-]
    periodicity: np.ndarray  #: largest change of a periodicity channel from the revolution before [N]
    revolutions: np.ndarray  #: revolutions run [-]
    settled: np.ndarray  #: 1 if the last two revolutions repeat within ``tol`` (periodic mode) [-]
    band_lo: np.ndarray  #: smallest value of each extreme over the monitored revolutions (N_EXT,)
    band_hi: np.ndarray  #: largest value (N_EXT,)
    state: np.ndarray  #: the state reached [m, m/s]


#: Revolutions from which a periodic run may stop: the last one and the one before [-].
MIN_PERIODIC_REVOLUTIONS = 2
#: The decay of the change from one revolution to the next assumed while only one change is
#: known [-]: the spectral radius of the revolution map measured at the periodic states of the
#: spring alone and the bucket train up to 3500 cam rpm is 0.0002-0.098 (issue 42's prototype,
#: docs/performance.md).  It only chooses which revolution is monitored; the acceptance test
#: is the measured change, so a wrong guess costs a monitored revolution, never a result.
ASSUMED_DECAY = 0.1


def _predicted_change(d, d_before):
    """The next revolution's change [N] if the changes decay geometrically (``d`` the last
    change, ``d_before`` the one before; ``nan`` when not yet known; with one change known,
    by :data:`ASSUMED_DECAY`)."""
    if not d == d:
        return np.inf
    if not d_before == d_before or d_before <= 0.0:
        return d * ASSUMED_DECAY
    return d * min(d / d_before, 1.0)


@_DOCS.fill
def run_speeds_loop(y0, omegas, points, m, vt, tab, tol, revs, stop_angles, gaps, out):
    """Every speed of ``omegas`` [rad/s], revolution by revolution, into ``out``.

    Each revolution samples the periodicity channels (:func:`check_channels`) on the output
    grid; the largest change from the revolution before is the speed's periodicity measure.
    With ``revs.tol`` 0 a speed runs ``revs.count`` revolutions.  Else it runs until two
    revolutions repeat within ``revs.tol`` (at least :data:`MIN_PERIODIC_REVOLUTIONS`, at
    most ``revs.count``).  A revolution that may be the last (the first that could be, one
    whose change is predicted within the tolerance from the decay of the changes before it,
    and the last ``revs.band`` of a speed that does not settle) is also sampled into
    ``out.extra`` and monitored (true extremes and events, :mod:`.monitor`); the monitored
    revolutions' extremes give the band.  With ``revs.warm`` each speed starts from the state
    the speed before ended in (a revolution's start: the cam at angle 0), else from ``y0``.
    ``tol.h_max`` is a fraction of a revolution here.  A failed speed has NaN outputs (no
    partial ones).

    Plain Python around one call of :func:`integrate_loop` per revolution, which releases
    the GIL (a compiled loop over the speeds would cost a second and a half of compilation
    for a few microseconds a speed).

    Parameters
    ----------
    y0 : ndarray
        Initial state [m, m/s].
    omegas : ndarray
        Cam speeds [rad/s].
    points : int
        Output samples per revolution [-].
    {m vt tab}
    tol : Tolerances
        Step control; ``h_max`` as a fraction of a revolution [-, m, m/s, -].
    revs : Revolutions
        How many revolutions [-, N].
    stop_angles : ndarray
        Cam angles [rad] a step lands on in every revolution.
    gaps : ndarray
        Coil-contact compressions [m] (``inf``: never).
    out : SpeedOutputs
        Receives the results.
    """
    n = y0.shape[0]
    no_states = np.empty((0, n))
    no_extra = np.empty((0, out.extra.shape[2]))
    off = new_monitor(np.empty(0), out.events[0], out.nev[0], gaps, 0.0, vt)
    ws = workspace(n, out.extra.shape[2], tab.c.shape[0])
    integrate = integrate_kernel(tab, vt, m)
    frac = np.arange(points) / points
    check = np.empty((2, points, N_CHECK))
    values = np.array(EXT_VALUES)
    periodic = revs.tol > 0.0
    have_start = False
    for i, omega in enumerate(omegas):
        omega = float(omega)
        period = 2.0 * np.pi / omega
        y = out.state[i - 1].copy() if (revs.warm and have_start) else y0.copy()
        ctl = np.array([0.0, 1e-4, 0.0])
        st, t, nsteps, used = 0, 0.0, 0, 0
        d = d_before = np.nan
        lo = np.full(N_EXT, np.inf)
        hi = np.full(N_EXT, -np.inf)
        settled = False
        r = 0
        while r < revs.count:
            if periodic:
                final = (
                    r + 1 == MIN_PERIODIC_REVOLUTIONS
                    or r + 1 == revs.count
                    or r >= revs.count - revs.band
                    or (r >= MIN_PERIODIC_REVOLUTIONS and _predicted_change(d, d_before) <= revs.tol)
                )
            else:
                final = r + 1 == revs.count
            t0 = r * period
            tol_r = Tolerances(tol.rtol, tol.atol, period * tol.h_max, tol.max_steps - used)
            if final:
                out.nev[i, 0] = 0
                mon = new_monitor(out.ext[i], out.events[i], out.nev[i], gaps, t0, vt)
                xo = out.extra[i]
            else:
                mon, xo = off, no_extra
            st, t, ns, nr = integrate(
                y,
                t0,
                t0 + period,
                (r + frac) * period,
                m,
                omega,
                vt,
                tab,
                tol_r,
                ctl,
                stop_times(stop_angles, omega, r, r + 1),
                no_states,
                xo,
                check[r % 2],
                mon,
                ws,
            )
            nsteps += ns
            used += ns + nr
            if st != 0:
                break
            if r >= 1:
                d_before = d
                d = float(np.max(np.abs(check[r % 2] - check[1 - r % 2])))
            if final:
                lo[values] = np.minimum(lo[values], out.ext[i, values])
                hi[values] = np.maximum(hi[values], out.ext[i, values])
            r += 1
            if periodic and final and r >= MIN_PERIODIC_REVOLUTIONS and d <= revs.tol:
                settled = True
                break
        out.status[i] = st
        out.t_end[i] = t
        out.steps[i] = nsteps
        out.revolutions[i] = r
        out.periodicity[i] = d
        out.settled[i] = settled
        if settled:  # a periodic state: its band is its value
            lo[values] = out.ext[i, values]
            hi[values] = out.ext[i, values]
        out.band_lo[i] = lo
        out.band_hi[i] = hi
        out.state[i] = y
        if st != 0:  # no partial outputs; the next speed starts from y0
            out.extra[i] = np.nan
            out.periodicity[i] = np.nan
            have_start = False
        else:
            have_start = True
