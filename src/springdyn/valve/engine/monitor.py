"""The event monitor: true extremes and events of a run, found on the integrator's dense output.

Each accepted step of a monitored run is sampled at its start, an interior point and its end
(:func:`monitor_step`).  Around a new record of an extreme signal (end forces, cam contact
force while the valve is open) a golden-section search on the step's interpolant finds the
true extreme (:func:`golden_max`); a sign change of an event channel (end separation, coil
contact, lift-off) or a valve landing is located by bisection (:func:`bisect_crossing`).
Results go into the monitor's arrays (:class:`Monitor`; layouts ``EXT_*``, ``EV_*`` of
:mod:`.layout`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ...numerics import erk
from ...numerics.jit import kernel, rebind
from .equations import FASTMATH, rhs_call, rhs_call_pack
from .layout import (
    CH_RETAINER,
    CH_SEAT,
    CH_TRAIN,
    EV_END,
    EV_INDEX,
    EV_KIND,
    EV_START,
    EXT_IMPACT_TIME,
    EXT_IMPACT_VELOCITY,
    EXT_LANDINGS,
    EXT_LOST,
    EXT_MAX_RETAINER,
    EXT_MAX_SEAT,
    EXT_MIN_CAM,
    EXT_MIN_RETAINER,
    EXT_MIN_SEAT,
    KIND_COIL_CONTACT,
    KIND_LANDING,
    KIND_LIFT_OFF,
    KIND_SEPARATION,
    N_FIXED_CHANNELS,
    N_SIG,
    SIG_CAM_MIN,
    SIG_RETAINER_MAX,
    SIG_RETAINER_MIN,
    SIG_SEAT_MAX,
    SIG_SEAT_MIN,
    VT_ENABLED,
    VT_LOBE_LASH,
    X_CAM_FORCE,
    X_DISP,
    X_LIFT,
    X_TOP,
    XT_CAM_GAP,
    XT_RETAINER_COMPRESSION,
    XT_RETAINER_TOTAL,
    XT_SEAT_COMPRESSION,
    XT_SEAT_TOTAL,
)

__all__ = ["Monitor", "new_monitor", "monitor_step", "monitor_step_pack", "finish_monitor"]

# scalars of the monitor's state (Monitor.sc)
SC_HAVE_PREV = 0  #: 1 once a step has been monitored
SC_STARTED = 1  #: 1 once the window's first sample is seen
SC_Z_PREV = 2  #: the valve lift at the previous sample [m]
SC_T_PREV = 3  #: start of the previous step [s]
SC_H_PREV = 4  #: size of the previous step [s]
SC_MID_PREV = 5  #: the previous step's interior sample [-]
SC_OPEN_LIFT = 6  #: the lobe lift past which the valve train is open [m] (inf: spring alone)
SC_T0 = 7  #: start of the window [s]
N_SC = 8


class Monitor(NamedTuple):
    """The monitor's outputs and working arrays for one run (empty ``ext``: no monitor)."""

    ext: np.ndarray  #: extremes (N_EXT,), layout EXT_*
    events: np.ndarray  #: event table (rows, 4), columns EV_*
    nev: np.ndarray  #: events written (1,) [-]
    gaps: np.ndarray  #: compression of each element at which its coils touch (N + 1,) [m]
    best: np.ndarray  #: record of each extreme signal (N_SIG,)
    best_t: np.ndarray  #: its time [s]
    sval: np.ndarray  #: the signals at the step's three samples (3, N_SIG)
    slast: np.ndarray  #: the signals at the previous step's end (N_SIG,)
    vprev: np.ndarray  #: event channels at the previous sample
    vcur: np.ndarray  #: event channels at this sample
    open_row: np.ndarray  #: the open event's row per channel (-1: none)
    sc: np.ndarray  #: scalars SC_*


def new_monitor(ext, events, nev, gaps, t0, vt):
    """A fresh :class:`Monitor` writing into ``ext``, ``events`` and ``nev`` for a window from ``t0`` [s].

    Plain Python (allocation only: compiling it would cost more than it ever runs).

    Parameters
    ----------
    ext : ndarray (N_EXT,)
        Receives the extremes [N, s, m/s, -] (zeroed here); empty for no monitor.
    events : ndarray (rows, 4)
        Receives the events [-, -, s, s or m/s].
    nev : ndarray (1,) of int
        Receives the number of events written [-].
    gaps : ndarray (N + 1,)
        Coil-contact compressions [m] (``inf``: never).
    t0 : float
        Start of the monitored window [s].
    vt : ndarray or None
        The valve train's parameters [kg, N/m, N s/m, m, -] (None: the spring alone).
    """
    nch = N_FIXED_CHANNELS + gaps.shape[0]
    sc = np.zeros(N_SC)
    sc[SC_OPEN_LIFT] = np.inf
    if vt is not None and vt[VT_ENABLED] > 0.5:
        sc[SC_OPEN_LIFT] = vt[VT_LOBE_LASH] + 1e-6
    sc[SC_T0] = t0
    ext[:] = 0.0
    return Monitor(
        ext,
        events,
        nev,
        gaps,
        np.full(N_SIG, -np.inf),
        np.zeros(N_SIG),
        np.empty((3, N_SIG)),
        np.full(N_SIG, -np.inf),
        np.empty(nch),
        np.empty(nch),
        np.full(nch, -1, dtype=np.int64),
        sc,
    )


@kernel(inline="always")
def _signal(k, e, ne, nm, open_lift):
    """Extreme signal ``k`` (maximised) of the extra outputs ``e``: retainer force, -retainer
    force, seat force, -seat force, -cam contact force while the valve is open (off its
    seat, the lobe lift past ``open_lift`` [m]; ramp impacts on the seated valve are not
    float)."""
    tail = 2 * ne + X_DISP + nm  # the pack's totals (one spring: its end elements' forces)
    if k == SIG_RETAINER_MAX:
        return e[tail + XT_RETAINER_TOTAL]
    if k == SIG_RETAINER_MIN:
        return -e[tail + XT_RETAINER_TOTAL]
    if k == SIG_SEAT_MAX:
        return e[tail + XT_SEAT_TOTAL]
    if k == SIG_SEAT_MIN:
        return -e[tail + XT_SEAT_TOTAL]
    if e[2 * ne + X_LIFT] > open_lift and e[2 * ne + X_TOP] > 0.0:
        return -e[2 * ne + X_CAM_FORCE]
    return -np.inf


@kernel(inline="always")
def _channel(c, e, ne, nm, open_lift, gaps):
    """Event channel ``c``, active while negative: the seat / retainer end compression, the
    smallest gap of the train's links while the valve is open (lift-off), then the coil gap
    left in each element."""
    if c == CH_SEAT:  # the smallest compression of the chains' end contacts
        return e[2 * ne + X_DISP + nm + XT_SEAT_COMPRESSION]
    if c == CH_RETAINER:
        return e[2 * ne + X_DISP + nm + XT_RETAINER_COMPRESSION]
    if c == CH_TRAIN:
        if e[2 * ne + X_LIFT] > open_lift and e[2 * ne + X_TOP] > 0.0:
            return e[2 * ne + X_DISP + nm + XT_CAM_GAP]
        return 1.0
    return gaps[c - N_FIXED_CHANNELS] - e[ne + c - N_FIXED_CHANNELS]


@kernel(inline="always")
def _eval_at(rc, theta, t, h, m, omega, vt, ybuf, dbuf, ebuf):
    """The dense output at the fraction ``theta`` of the step [t, t + h] into ``ybuf``, and the
    right-hand side's extra outputs there into ``ebuf``."""
    erk.dense_eval(rc, theta, ybuf)
    rhs_call(t + theta * h, ybuf, m, omega, vt, dbuf, ebuf)


@kernel(fastmath=FASTMATH, _nrt=False)
def golden_max(rc, t, h, lo, hi, k, m, omega, vt, open_lift, ybuf, dbuf, ebuf):
    """Golden-section maximum of extreme signal ``k`` over the step fractions [lo, hi]; returns
    (value, fraction)."""
    ne = m.laws.shape[0]
    nm = m.masses.shape[0]
    g = 0.6180339887498949
    a = lo
    b = hi
    c = b - g * (b - a)
    d = a + g * (b - a)
    _eval_at(rc, c, t, h, m, omega, vt, ybuf, dbuf, ebuf)
    fc = _signal(k, ebuf, ne, nm, open_lift)
    _eval_at(rc, d, t, h, m, omega, vt, ybuf, dbuf, ebuf)
    fd = _signal(k, ebuf, ne, nm, open_lift)
    # 16 reductions leave a bracket of 4.6e-4 of the step: with the signal's curvature
    # bounded by the fastest mode resolved by the step (|F''| h^2 < ~0.2 of its amplitude at
    # the default tolerances) the value is then within ~1e-8 of that amplitude.
    for _ in range(16):
        if fc >= fd:
            b = d
            d = c
            fd = fc
            c = b - g * (b - a)
            _eval_at(rc, c, t, h, m, omega, vt, ybuf, dbuf, ebuf)
            fc = _signal(k, ebuf, ne, nm, open_lift)
        else:
            a = c
            c = d
            fc = fd
            d = a + g * (b - a)
            _eval_at(rc, d, t, h, m, omega, vt, ybuf, dbuf, ebuf)
            fd = _signal(k, ebuf, ne, nm, open_lift)
    if fc >= fd:
        return fc, c
    return fd, d


@kernel(fastmath=FASTMATH, _nrt=False)
def bisect_crossing(rc, t, h, lo, hi, c, landing, m, omega, vt, open_lift, gaps, ybuf, dbuf, ebuf):
    """Step fraction in [lo, hi] where channel ``c`` (or, with ``landing``, the valve lift)
    changes sign, to 6e-8 of the step (the state at ``lo`` is on the old side)."""
    ne = m.laws.shape[0]
    nm = m.masses.shape[0]
    _eval_at(rc, lo, t, h, m, omega, vt, ybuf, dbuf, ebuf)
    if landing:
        neg_lo = ebuf[2 * ne + X_TOP] <= 0.0
    else:
        neg_lo = _channel(c, ebuf, ne, nm, open_lift, gaps) < 0.0
    a = lo
    b = hi
    for _ in range(24):
        mid = 0.5 * (a + b)
        _eval_at(rc, mid, t, h, m, omega, vt, ybuf, dbuf, ebuf)
        if landing:
            neg = ebuf[2 * ne + X_TOP] <= 0.0
        else:
            neg = _channel(c, ebuf, ne, nm, open_lift, gaps) < 0.0
        if neg == neg_lo:
            a = mid
        else:
            b = mid
    return b


@kernel(inline="always")
def _open_event(mon, c, t_start):
    """Record the start of an event on channel ``c`` at ``t_start`` [s] (or count it as lost)."""
    r = mon.nev[0]
    if r >= mon.events.shape[0]:
        mon.ext[EXT_LOST] += 1.0
        return
    mon.events[r, EV_KIND] = (
        KIND_SEPARATION if c < CH_TRAIN else (KIND_LIFT_OFF if c == CH_TRAIN else KIND_COIL_CONTACT)
    )
    mon.events[r, EV_INDEX] = float(c if c < CH_TRAIN else (0 if c == CH_TRAIN else c - N_FIXED_CHANNELS))
    mon.events[r, EV_START] = t_start
    mon.events[r, EV_END] = np.nan
    mon.open_row[c] = r
    mon.nev[0] += 1


@kernel(fastmath=FASTMATH, nogil=True, _nrt=False)
def monitor_step(mon, rc, rc_prev, t, h, t_new, th_m, mid_row, m, omega, vt, ybuf, dbuf, ebuf, eend, xout):
    """Monitor the accepted step [t, t + h] (interpolant ``rc``; ``rc_prev`` the previous step's).

    The step's samples: its start (the previous step's end, seen already), the interior
    fraction ``th_m`` (the output row ``mid_row`` of ``xout`` when one lies inside, else
    evaluated here) and its end (``eend``, the extra outputs of the last stage).
    """
    ne = m.laws.shape[0]
    nm = m.masses.shape[0]
    nfree = ybuf.shape[0] // 2
    nch = N_FIXED_CHANNELS + ne
    sc = mon.sc
    open_lift = sc[SC_OPEN_LIFT]
    ext = mon.ext
    sval = mon.sval
    vcur = mon.vcur
    vprev = mon.vprev
    gaps = mon.gaps
    best = mon.best
    best_t = mon.best_t
    ths = (0.0, th_m, 1.0)
    for isamp in range(3):
        if isamp == 0 and sc[SC_STARTED] > 0.5:
            continue  # the step start is the previous step's end, already seen
        if isamp == 2:
            src = eend  # the end of the step: already evaluated as its last stage
        elif isamp == 1 and mid_row >= 0:
            src = xout[mid_row]  # an output sample: already evaluated
        else:
            _eval_at(rc, ths[isamp], t, h, m, omega, vt, ybuf, dbuf, ebuf)
            src = ebuf
        # (src is read before any search below overwrites ebuf)
        for sg in range(N_SIG):
            sval[isamp, sg] = _signal(sg, src, ne, nm, open_lift)
        for c in range(N_FIXED_CHANNELS):
            vcur[c] = _channel(c, src, ne, nm, open_lift, gaps)
        for j in range(ne):
            vcur[N_FIXED_CHANNELS + j] = gaps[j] - src[ne + j]
        if ext[EXT_LANDINGS] > 0.0:
            # after the valve's first landing in the window, separations are seat bounces,
            # not float: no lift-off and no cam-contact minimum there
            sval[isamp, SIG_CAM_MIN] = -np.inf
            vcur[CH_TRAIN] = 1.0
        z_cur = src[2 * ne + X_TOP]
        if sc[SC_STARTED] < 0.5:
            sc[SC_STARTED] = 1.0
            for c in range(nch):
                if vcur[c] < 0.0:  # active at the window start
                    _open_event(mon, c, sc[SC_T0])
        else:
            lo = ths[isamp - 1]
            changed = False  # a plain pass first: most samples change no channel
            for c in range(nch):
                changed |= (vcur[c] < 0.0) != (vprev[c] < 0.0)
            for c in range(nch if changed else 0):
                if (vcur[c] < 0.0) != (vprev[c] < 0.0):
                    if mon.nev[0] >= mon.events.shape[0] and mon.open_row[c] < 0:
                        ext[EXT_LOST] += 1.0
                        continue
                    fr = bisect_crossing(
                        rc, t, h, lo, ths[isamp], c, False, m, omega, vt, open_lift, gaps, ybuf, dbuf, ebuf
                    )
                    tc = t + fr * h
                    if vcur[c] < 0.0:
                        _open_event(mon, c, tc)
                    else:
                        if mon.open_row[c] >= 0:
                            mon.events[mon.open_row[c], EV_END] = tc
                        mon.open_row[c] = -1
            if vt is not None and vt[VT_ENABLED] > 0.5 and sc[SC_Z_PREV] > 0.0 and z_cur <= 0.0:
                fr = bisect_crossing(rc, t, h, lo, ths[isamp], 0, True, m, omega, vt, open_lift, gaps, ybuf, dbuf, ebuf)
                erk.dense_eval(rc, fr, ybuf)
                v_imp = -ybuf[nfree + nm]  # the valve's velocity
                if ext[EXT_LANDINGS] == 0.0:
                    ext[EXT_IMPACT_VELOCITY] = v_imp
                    ext[EXT_IMPACT_TIME] = t + fr * h
                ext[EXT_LANDINGS] += 1.0
                r = mon.nev[0]
                if r < mon.events.shape[0]:
                    mon.events[r, EV_KIND] = KIND_LANDING
                    mon.events[r, EV_INDEX] = 0.0
                    mon.events[r, EV_START] = t + fr * h
                    mon.events[r, EV_END] = v_imp
                    mon.nev[0] += 1
                else:
                    ext[EXT_LOST] += 1.0
        for c in range(nch):
            vprev[c] = vcur[c]
        sc[SC_Z_PREV] = z_cur
        if isamp == 0:
            for sg in range(N_SIG):
                if sval[0, sg] > best[sg]:
                    best[sg] = sval[0, sg]
                    best_t[sg] = t
    # true extremes: refine around a new record on the interpolant
    have_prev = sc[SC_HAVE_PREV] > 0.5
    t_prev = sc[SC_T_PREV]
    h_prev = sc[SC_H_PREV]
    for sg in range(N_SIG):
        if have_prev:
            sval[0, sg] = mon.slast[sg]
        va = sval[0, sg]
        vm = sval[1, sg]
        vb = sval[2, sg]
        mon.slast[sg] = vb
        if vm == -np.inf and vb == -np.inf and va == -np.inf:
            continue
        if vm >= va and vm >= vb and vm > best[sg]:  # a local maximum inside the step
            v, fr = golden_max(rc, t, h, 0.0, 1.0, sg, m, omega, vt, open_lift, ybuf, dbuf, ebuf)
            if v < vm:
                v = vm
                fr = th_m
            best[sg] = v
            best_t[sg] = t + fr * h
        elif vb > vm and vb > best[sg]:  # rising at the step end: the next step refines
            best[sg] = vb
            best_t[sg] = t_new
        elif have_prev and va > vm and best_t[sg] == t:
            # the record sits at the step boundary: search both sides of it
            v1, f1 = golden_max(
                rc_prev, t_prev, h_prev, sc[SC_MID_PREV], 1.0, sg, m, omega, vt, open_lift, ybuf, dbuf, ebuf
            )
            v2, f2 = golden_max(rc, t, h, 0.0, th_m, sg, m, omega, vt, open_lift, ybuf, dbuf, ebuf)
            if v1 > best[sg] and v1 >= v2:
                best[sg] = v1
                best_t[sg] = t_prev + f1 * h_prev
            elif v2 > best[sg]:
                best[sg] = v2
                best_t[sg] = t + f2 * h
    sc[SC_T_PREV] = t
    sc[SC_H_PREV] = h
    sc[SC_MID_PREV] = th_m
    sc[SC_HAVE_PREV] = 1.0


@kernel(inline="always")
def finish_monitor(mon):
    """Write the records of the extreme signals into the extremes ``mon.ext`` (layout EXT_*)."""
    ext = mon.ext
    best = mon.best
    best_t = mon.best_t
    ext[EXT_MAX_RETAINER] = best[SIG_RETAINER_MAX]
    ext[EXT_MAX_RETAINER + 1] = best_t[SIG_RETAINER_MAX]
    ext[EXT_MIN_RETAINER] = -best[SIG_RETAINER_MIN]
    ext[EXT_MIN_RETAINER + 1] = best_t[SIG_RETAINER_MIN]
    ext[EXT_MAX_SEAT] = best[SIG_SEAT_MAX]
    ext[EXT_MAX_SEAT + 1] = best_t[SIG_SEAT_MAX]
    ext[EXT_MIN_SEAT] = -best[SIG_SEAT_MIN]
    ext[EXT_MIN_SEAT + 1] = best_t[SIG_SEAT_MIN]
    ext[EXT_MIN_CAM] = -best[SIG_CAM_MIN] if best[SIG_CAM_MIN] > -np.inf else np.nan
    ext[EXT_MIN_CAM + 1] = best_t[SIG_CAM_MIN]


def _pack_monitor():
    """:func:`monitor_step` for a spring pack's models: the same code with its searches
    evaluating :data:`.equations.rhs_call_pack` (kernels named ``*_pack``, compiled only when a
    pack runs)."""
    ns = dict(globals(), rhs_call=rhs_call_pack)
    made = {}
    for fn, options in (
        (_eval_at, dict(inline="always")),
        (golden_max, dict(fastmath=FASTMATH, _nrt=False)),
        (bisect_crossing, dict(fastmath=FASTMATH, _nrt=False)),
        (monitor_step, dict(fastmath=FASTMATH, nogil=True, _nrt=False)),
    ):
        copy = rebind(fn.py_func, ns)
        copy.__qualname__ += "_pack"
        made[fn.py_func.__name__] = ns[fn.py_func.__name__] = kernel(copy, **options)
    return made["monitor_step"]


#: :func:`monitor_step` of a spring pack (:data:`.loop.VARIANTS`).
monitor_step_pack = _pack_monitor()
