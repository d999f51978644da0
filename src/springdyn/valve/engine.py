"""Time integration of the valve-spring chain (and optional valve train).

The equations of motion ([MMS], "Model variable" and "Initial condition & position";
corrections MMS-7 to MMS-10 of docs/references.md): nodes are numbered from the seat
(node 0, fixed) over the five masses (nodes 1-5) to the retainer end (node 6).  ``u`` is the
displacement of a node towards the seat, measured from its set-up position.  Element
``j`` joins nodes ``j`` and ``j + 1`` and is compressed by
``x_j = x_j,set + u_(j+1) - u_j``; it carries ``f_j = F_j(x_j) + c_j(x_j) dx_j/dt``
(element law and damping of :mod:`springdyn.valve.elements`).  Mass ``i`` (node
``i + 1``) obeys ``m_i d2u/dt2 = f_(i+1) - f_i``.

- Spring alone: the retainer end follows the cam, ``u_6 = h(omega t)``.
- Valve train: node 6 is the valve body (valve + retainer + follower, mass ``M_v``,
  displacement ``z`` = valve lift) with ``M_v z'' = F_cam + F_seat - f_5``; the cam
  contact ``F_cam = max(0, k_c p + c_c p')`` for ``p = h - z - lash > 0`` and the valve
  seat ``F_seat = max(0, -k_s z - c_s z')`` for ``z < 0`` are unilateral.

The cam enters through a periodic table of lift, velocity and acceleration sampled
finely over one revolution and interpolated by quintic Hermite polynomials (C2), the same
in every backend.

Backends: :func:`integrate` and :func:`run_speeds` (compiled: numba, an adaptive embedded
Runge-Kutta pair with dense output, :mod:`springdyn.numerics.erk`: Dormand-Prince 5(4) or
Bogacki-Shampine 3(2)) and :func:`integrate_scipy` (the reference:
``scipy.integrate.solve_ivp`` with the same right-hand side run as plain Python).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numba.extending import register_jitable

from ..numerics import erk as _ig

__all__ = ["hermite5", "rhs", "rhs_compiled", "integrate", "integrate_scipy", "run_speeds", "stop_angles", "hermite_eval", "STATUS", "EXTRA",
           "EXT", "EVENT_KINDS", "extra_layout"]

#: Status codes of :func:`integrate`.
STATUS = {0: "ok", 1: "too many steps", 2: "step size collapsed", 3: "the solution is not finite (NaN/inf)"}


#: Layout of the optional ``extra`` output of :func:`rhs` for the 5-mass Type C chain (see
#: :func:`extra_layout` for any number of masses).
EXTRA = ("f1", "f2", "f3", "f4", "f5", "f6", "x1", "x2", "x3", "x4", "x5", "x6", "lift", "dlift",
         "cam_contact_force", "valve_seat_force", "top_displacement", "u1", "u2", "u3", "u4", "u5", "cam_gap")
N_EXTRA = len(EXTRA)

#: Layout of the per-speed ``ext`` output of the monitored integration (true extremes of
#: the last revolution from the dense output, see :func:`run_speeds`).
EXT = ("max_retainer_force", "t_max_retainer_force", "min_retainer_force", "t_min_retainer_force",
       "max_seat_force", "t_max_seat_force", "min_seat_force", "t_min_seat_force",
       "min_cam_contact_force", "t_min_cam_contact_force", "seat_impact_velocity", "t_seat_impact",
       "seat_landings", "events_lost")
N_EXT = len(EXT)
#: Event kinds of the monitored integration (column 0 of the event table).
EVENT_KINDS = {0: "end separation", 1: "coil contact", 2: "lift-off", 3: "valve landing"}
#: Event table rows per speed (further events are counted in ``events_lost``).
MAX_EVENTS = 512
_N_SIG = 5  # extreme signals: retainer max/min, seat max/min, cam contact min


def extra_layout(n_masses: int) -> dict:
    """Slices / indices of the ``extra`` output of :func:`rhs` for a chain of ``n_masses``.

    Parameters
    ----------
    n_masses : int
        Number of chain masses (5 for Type C) [-].

    Returns
    -------
    dict
        ``force`` and ``compression`` (slices over the ``n_masses + 1`` elements), ``lift``,
        ``dlift``, ``cam_contact_force``, ``valve_seat_force``, ``top_displacement`` (ints),
        ``displacement`` (slice over the masses), ``cam_gap`` (int) and ``size``.
    """
    ne = n_masses + 1
    b = 2 * ne
    return dict(force=slice(0, ne), compression=slice(ne, b), lift=b, dlift=b + 1, cam_contact_force=b + 2,
                valve_seat_force=b + 3, top_displacement=b + 4, displacement=slice(b + 5, b + 5 + n_masses),
                cam_gap=b + 5 + n_masses, size=b + 6 + n_masses)


@register_jitable(inline="always")
def hermite5(x, p0, v0, a0, p1, v1, a1):
    """Quintic Hermite interpolation on one table interval and its derivative.

    ``x`` in [0, 1] is the position in the interval; ``p, v, a`` are value, first and
    second derivative at its ends, the derivatives already scaled by the interval length.
    Plain arithmetic, so the same function serves scalars, NumPy arrays and compiled code.

    Parameters
    ----------
    x : float or ndarray
        Position in the interval [-], 0 to 1.
    p0, v0, a0 : float or ndarray
        Value [m], first [m] and second [m] derivative (scaled by the interval) at the start.
    p1, v1, a1 : float or ndarray
        The same at the end [m].

    Returns
    -------
    value, derivative : float or ndarray
        The derivative is per unit ``x``.
    """
    # the quintic in monomial form (Horner): the same polynomial as the Hermite basis
    # sum, with a third of the operations
    dp = p1 - p0
    c2 = 0.5 * a0
    c3 = 10.0 * dp - 6.0 * v0 - 4.0 * v1 - 1.5 * a0 + 0.5 * a1
    c4 = -15.0 * dp + 8.0 * v0 + 7.0 * v1 + 1.5 * a0 - a1
    c5 = 6.0 * dp - 3.0 * v0 - 3.0 * v1 - 0.5 * a0 + 0.5 * a1
    value = p0 + x * (v0 + x * (c2 + x * (c3 + x * (c4 + x * c5))))
    slope = v0 + x * (2.0 * c2 + x * (3.0 * c3 + x * (4.0 * c4 + x * (5.0 * c5))))
    return value, slope


def rhs(t, s, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, out, extra):
    """Right-hand side ``ds/dt`` of a chain of N masses (plain Python; compiled as :data:`rhs_compiled`).

    The two end elements (element 0 on the seat, the last one on the retainer) are
    contacts that carry compression only: in tension, or when their spring-damper force
    would pull, they carry nothing and the end separates (correction MMS-7 of
    docs/references.md).

    Parameters
    ----------
    t : float
        Time [s]; the cam angle is ``omega t``.
    s : ndarray
        State: node displacements [m] then velocities [m/s] (N each, N + 1 with a valve train).
    masses : ndarray (N,)
        Chain masses [kg].
    laws : ndarray (N + 1, 3, 4)
        Element laws [m, N]: per element, segments ``x_start [m], a [N/m^2], b [N/m], c [N]``
        (see :mod:`springdyn.valve.elements`).
    xset : ndarray (N + 1,)
        Element compressions at set-up [m].
    c0 : ndarray (N + 1,)
        Damping coefficient of each element at its initial rate [N s/m].
    cam_h, cam_dh, cam_ddh : ndarray (M,)
        Lift [m] and its first two derivatives per radian at ``k * dth``, one revolution.
    dth : float
        Table step [rad].
    omega : float
        Cam angular speed [rad/s].
    vt : ndarray (16,) or None
        The valve train (:meth:`springdyn.valve.valvetrain.ValveTrain.kernel_parameters`):
        ``enabled, M_v [kg], k_c [N/m], c_c [N s/m], k_s [N/m], c_s [N s/m], lash [m], dof [-],
        r [-], M_r [kg], k_t [N/m], c_t [N s/m], M_f [kg], k_p [N/m], c_p [N s/m],
        lobe_lash [m]``; all zero, or None, without a train (with None numba compiles a
        variant without the train's code).  Train states follow the chain's masses: valve,
        lever tip (rocker, pushrod), lifter (pushrod).
    out : ndarray
        Receives ``ds/dt`` [m/s, m/s^2].
    extra : ndarray or None
        None (numba then compiles a variant without these outputs), or an array of
        length ``extra_layout(N)["size"]`` that receives the element forces [N] and
        compressions [m], lift [m] and lift rate [m/s], cam contact and valve-seat forces
        [N], the displacement of the retainer end [m], of the masses [m] and the signed
        cam-contact gap [m] (positive in contact; layout :func:`extra_layout`).
    """
    nm = masses.shape[0]
    ne = nm + 1
    # every use of vt sits under "vt is not None": numba compiles a variant without the
    # valve train's code for vt = None (12 % less time per step for the spring alone)
    vtrain = False
    nfree = nm
    if vt is not None:
        if vt[0] > 0.5:
            vtrain = True
            nfree = nm + int(vt[7])
    # cam lift and velocity (quintic Hermite on the periodic table)
    theta = omega * t
    n = cam_h.shape[0]
    period = n * dth
    th = theta - period * math.floor(theta / period)
    i0 = int(th / dth)
    if i0 >= n:
        i0 = n - 1
    i1 = i0 + 1 if i0 + 1 < n else 0
    lift, slope = hermite5(th / dth - i0, cam_h[i0], cam_dh[i0] * dth, cam_ddh[i0] * dth * dth,
                           cam_h[i1], cam_dh[i1] * dth, cam_ddh[i1] * dth * dth)
    dlift = slope / dth * omega
    # element forces, from the seat (node 0) to the retainer end (node N + 1)
    f_prev = 0.0
    u_lo = 0.0
    v_lo = 0.0
    for j in range(ne):
        if j < nm:
            u_hi = s[j]
            v_hi = s[nfree + j]
        elif vtrain:
            u_hi = s[nm]
            v_hi = s[nfree + nm]
        else:
            u_hi = lift
            v_hi = dlift
        xj = xset[j] + u_hi - u_lo
        seg = 0
        if xj >= laws[j, 1, 0]:
            seg = 1
            if xj >= laws[j, 2, 0]:
                seg = 2
        a = laws[j, seg, 1]
        b = laws[j, seg, 2]
        force = (a * xj + b) * xj + laws[j, seg, 3]
        if seg == 0:
            force += c0[j] * (v_hi - v_lo)
        else:
            force += c0[j] * math.sqrt((2.0 * a * xj + b) / laws[j, 0, 2]) * (v_hi - v_lo)
        if j == 0 or j == ne - 1:  # unilateral end contacts (MMS-7)
            if xj <= 0.0 or force < 0.0:
                force = 0.0
        if extra is not None:
            extra[j] = force
            extra[ne + j] = xj
            if j < nm:
                extra[2 * ne + 5 + j] = u_hi
        if j > 0:
            out[j - 1] = s[nfree + j - 1]
            out[nfree + j - 1] = (force - f_prev) / masses[j - 1]
        f_prev = force
        u_lo = u_hi
        v_lo = v_hi
    if vt is not None and vtrain:
        # the valve train (layouts of springdyn.valve.valvetrain): every link unilateral
        ntr = int(vt[7])
        r = vt[8]
        z = s[nm]
        zd = s[nfree + nm]
        f_seat = 0.0
        if z < 0.0:
            f_seat = -vt[4] * z - vt[5] * zd
            if f_seat < 0.0:
                f_seat = 0.0
        if ntr == 1:  # direct-acting: the cam on the valve body, lash at the cam
            pen = lift - z - vt[6]
            raw = vt[2] * pen + vt[3] * (dlift - zd)
            f_cam = 0.0
            if pen > 0.0:
                f_cam = raw if raw > 0.0 else 0.0
            gap = min(pen, raw / vt[2])
            f_valve = f_cam
        else:
            zr = s[nm + 1]
            zrd = s[nfree + nm + 1]
            pen_t = zr - z - vt[6]  # the lever tip on the valve, lash here
            raw_t = vt[10] * pen_t + vt[11] * (zrd - zd)
            f_valve = 0.0
            if pen_t > 0.0:
                f_valve = raw_t if raw_t > 0.0 else 0.0
            gap = min(pen_t, raw_t / vt[10])
            if ntr == 2:  # finger follower / rocker: the follower rides on the lever
                pen = lift - zr / r
                raw = vt[2] * pen + vt[3] * (dlift - zrd / r)
                f_cam = 0.0
                if pen > 0.0:
                    f_cam = raw if raw > 0.0 else 0.0
                gap = min(gap, min(pen, raw / vt[2]))
                f_lever = f_cam / r
            else:  # pushrod: lifter on the cam, pushrod to the lever
                zf = s[nm + 2]
                zfd = s[nfree + nm + 2]
                pen = lift - zf
                raw = vt[2] * pen + vt[3] * (dlift - zfd)
                f_cam = 0.0
                if pen > 0.0:
                    f_cam = raw if raw > 0.0 else 0.0
                xp = zf - zr / r
                raw_p = vt[13] * xp + vt[14] * (zfd - zrd / r)
                f_push = 0.0
                if xp > 0.0:
                    f_push = raw_p if raw_p > 0.0 else 0.0
                gap = min(gap, min(min(pen, raw / vt[2]), min(xp, raw_p / vt[13])))
                out[nm + 2] = zfd
                out[nfree + nm + 2] = (f_cam - f_push) / vt[12]
                f_lever = f_push / r
            out[nm + 1] = zrd
            out[nfree + nm + 1] = (f_lever - f_valve) / vt[9]
        out[nm] = zd
        out[nfree + nm] = (f_valve + f_seat - f_prev) / vt[1]
        if extra is not None:
            extra[2 * ne + 2] = f_cam
            extra[2 * ne + 3] = f_seat
            extra[2 * ne + 4] = z
            extra[2 * ne + 5 + nm] = gap
    if extra is not None:
        if not vtrain:
            extra[2 * ne + 2] = 0.0
            extra[2 * ne + 3] = 0.0
            extra[2 * ne + 4] = lift
            extra[2 * ne + 5 + nm] = 1.0
        extra[2 * ne] = lift
        extra[2 * ne + 1] = dlift


#: Floating-point licences of the compiled kernels: fused multiply-add (``contract``),
#: division by a reciprocal (``arcp``) and no signed zeros (``nsz``).  Each changes a result
#: by at most an ulp per operation (round-off, far below the tolerances); together they cut
#: the Type C step by ~12 % (divisions by masses and table steps dominate the right-hand
#: side).  No licence that assumes finite values: the NaN/inf checks must stay.
FASTMATH = {"contract", "arcp", "nsz"}

#: Dormand-Prince steps use the fused kernels of :mod:`springdyn.numerics.erk` (the generic
#: ones when False: the same arithmetic, reordered; Tsitouras steps always use its fused ones).
FUSED_DOPRI5 = True

#: The compiled right-hand side (numba, cached on disk).
rhs_compiled = njit(cache=True, inline="always", fastmath=FASTMATH, error_model="numpy")(rhs)


@register_jitable
def _eval_at(rc, theta, t, h, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, ybuf, dbuf, ebuf):
    """Dense output at the fraction ``theta`` of the step [t, t + h] into ``ybuf``, and the
    right-hand side's ``extra`` outputs there into ``ebuf``."""
    _ig.dense_eval(rc, theta, ybuf)
    rhs_compiled(t + theta * h, ybuf, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, dbuf, ebuf)


@register_jitable(inline="always")
def _signal(k, ebuf, ne, nm, open_lift):
    """Extreme signal ``k`` (maximised): retainer force, -retainer force, seat force,
    -seat force, -cam contact force while the valve is open (off its seat, the lobe lift
    past ``open_lift`` [m], the lash; ``inf`` without a valve train: the float margin; ramp
    impacts on the seated valve are not float)."""
    if k == 0:
        return ebuf[ne - 1]
    if k == 1:
        return -ebuf[ne - 1]
    if k == 2:
        return ebuf[0]
    if k == 3:
        return -ebuf[0]
    if ebuf[2 * ne] > open_lift and ebuf[2 * ne + 4] > 0.0:
        return -ebuf[2 * ne + 2]
    return -np.inf


@register_jitable(inline="always")
def _channel(c, ebuf, ne, nm, open_lift, gaps):
    """Event channel ``c``, active while negative: 0/1 seat/retainer end compression,
    2 smallest gap of the train's links while the valve is open (lift-off; ``open_lift`` as
    for :func:`_signal`), 3 + j coil gap left in element j."""
    if c == 0:
        return ebuf[ne]
    if c == 1:
        return ebuf[2 * ne - 1]
    if c == 2:
        if ebuf[2 * ne] > open_lift and ebuf[2 * ne + 4] > 0.0:
            return ebuf[2 * ne + 5 + nm]
        return 1.0
    return gaps[c - 3] - ebuf[ne + c - 3]


@register_jitable(inline="always")
def _channels(ebuf, ne, nm, open_lift, gaps, vcur):
    """All event channels of :func:`_channel` into ``vcur``, the coil gaps in one plain loop
    (a call per channel cost ~16 ns each: most of the monitor's time for 50 elements)."""
    for c in range(3):
        vcur[c] = _channel(c, ebuf, ne, nm, open_lift, gaps)
    for j in range(ne):
        vcur[3 + j] = gaps[j] - ebuf[ne + j]


@register_jitable
def _golden(rc, t, h, lo, hi, k, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, open_lift, ybuf,
            dbuf, ebuf):
    """Golden-section maximum of extreme signal ``k`` over step fractions [lo, hi]."""
    ne = laws.shape[0]
    nm = ne - 1
    g = 0.6180339887498949
    a = lo
    b = hi
    c = b - g * (b - a)
    d = a + g * (b - a)
    _eval_at(rc, c, t, h, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, ybuf, dbuf, ebuf)
    fc = _signal(k, ebuf, ne, nm, open_lift)
    _eval_at(rc, d, t, h, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, ybuf, dbuf, ebuf)
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
            _eval_at(rc, c, t, h, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, ybuf, dbuf, ebuf)
            fc = _signal(k, ebuf, ne, nm, open_lift)
        else:
            a = c
            c = d
            fc = fd
            d = a + g * (b - a)
            _eval_at(rc, d, t, h, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, ybuf, dbuf, ebuf)
            fd = _signal(k, ebuf, ne, nm, open_lift)
    if fc >= fd:
        return fc, c
    return fd, d


@register_jitable
def _bisect(rc, t, h, lo, hi, c, landing, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, open_lift,
            gaps, ybuf, dbuf, ebuf):
    """Step fraction in [lo, hi] where channel ``c`` (or, with ``landing``, the valve lift)
    changes sign, to 6e-8 of the step (the state at ``lo`` is on the old side)."""
    ne = laws.shape[0]
    nm = ne - 1
    _eval_at(rc, lo, t, h, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, ybuf, dbuf, ebuf)
    if landing:
        neg_lo = ebuf[2 * ne + 4] <= 0.0
    else:
        neg_lo = _channel(c, ebuf, ne, nm, open_lift, gaps) < 0.0
    a = lo
    b = hi
    for _ in range(24):
        m = 0.5 * (a + b)
        _eval_at(rc, m, t, h, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, ybuf, dbuf, ebuf)
        if landing:
            neg = ebuf[2 * ne + 4] <= 0.0
        else:
            neg = _channel(c, ebuf, ne, nm, open_lift, gaps) < 0.0
        if neg == neg_lo:
            a = m
        else:
            b = m
    return b


@njit(cache=True, nogil=True, fastmath=FASTMATH, error_model="numpy")
def _integrate(y, t0, t_end, t_out, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt,
               rtol, atol, h_max, max_steps, ctl, stops, pc, pa, pe, pd, pq, kernels, out, xout, fout, gaps, ext,
               events, nev):
    """Adaptive embedded Runge-Kutta loop from ``t0`` to ``t_end`` (the pair ``pc, pa, pe, pd,
    pq`` of :func:`springdyn.numerics.erk.pair_arrays`).  ``y`` holds the state at ``t0`` and
    receives the state reached.  A step never crosses a time in ``stops`` (ascending) or
    ``t_end``: it lands on it (the cam's breakpoints, where the lift law is not smooth).
    ``ctl`` = (step to try, or 0 to choose one; previous error norm; 1 if the last step was
    accepted) continues the step-size control across calls and is updated.

    The outputs at the times ``t_out`` (ascending, within [t0, t_end]) come from the dense
    output as the integration passes them; each of ``out`` (the states), ``xout`` (the
    right-hand side's ``extra`` outputs) and ``fout`` (the retainer force alone) is an
    array with a row per time, or None for none.  numba compiles a variant per
    combination, without the code of the absent ones: the revolutions before the last run
    in a lean loop.

    With ``ext`` (and ``events``, ``nev``; None for none) it also monitors the whole call on
    the dense output: true extremes of the end forces and of the cam contact force
    (golden-section search on the step's interpolant around each new record), and the
    events (end separation, coil contact, lift-off, valve landing) located by bisection on
    the interpolant.  An output time within a step then serves as the step's interior
    sample (no evaluation of its own).
    """
    n = y.shape[0]
    ne = laws.shape[0]
    nm = ne - 1
    nfree = n // 2
    nch = 3 + ne
    ns_ = pc.shape[0]  # stages; the last is the step's end (FSAL)
    last = ns_ - 1
    k = np.empty((ns_, n))
    ytmp = np.empty(n)
    rc = np.empty((5, n))
    rc_prev = np.empty((5, n))
    ybuf = np.empty(n)
    dbuf = np.empty(n)
    ebuf = np.empty(2 * ne + 6 + nm)
    eend = np.empty(2 * ne + 6 + nm)
    vprev = np.empty(nch)
    vcur = np.empty(nch)
    open_row = np.full(nch, -1)
    best = np.full(_N_SIG, -np.inf)
    best_t = np.zeros(_N_SIG)
    sval = np.empty((3, _N_SIG))
    slast = np.full(_N_SIG, -np.inf)
    open_lift = np.inf  # the lobe lift [m] past the lash: beyond it the valve train is open
    if vt is not None:
        if vt[0] > 0.5:
            open_lift = vt[15] + 1e-6
    have_prev = False
    started = False
    z_prev = 0.0
    t_prev = 0.0
    h_prev = 0.0
    mid_prev = 0.5
    t = t0
    rhs_compiled(t, y, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, k[0], None)
    h = ctl[0]
    if not h > 0.0:
        h = _ig.initial_step(y, k[0], rtol, atol, h_max)
    h = min(h, h_max)
    err_old = ctl[1]
    accepted_before = ctl[2] > 0.5
    nout = t_out.shape[0]
    iout = 0
    while iout < nout and t_out[iout] <= t:
        if out is not None:
            out[iout, :] = y
        if xout is not None:
            rhs_compiled(t, y, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, dbuf, xout[iout])
        if fout is not None:
            rhs_compiled(t, y, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, dbuf, ebuf)
            fout[iout] = ebuf[nm]
        iout += 1
    istop = 0
    nstops = stops.shape[0]
    nsteps = 0
    nrejected = 0
    while t < t_end:
        if nsteps + nrejected >= max_steps:
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
        for stage in range(1, last + 1):
            if kernels == 1:
                _ig.dopri5_stage_state(y, h, k, stage, ytmp)
            elif kernels == 2:
                _ig.tsit5_stage_state(y, h, k, stage, ytmp)
            else:
                _ig.stage_state(y, h, k, stage, ytmp, pa)
            if stage < last:
                rhs_compiled(t + pc[stage] * h, ytmp, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth,
                             omega, vt, k[stage], None)
            elif ext is not None:  # the last stage is the step's end (FSAL): its outputs are the end sample
                rhs_compiled(t + h, ytmp, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, k[last],
                             eend)
            else:
                rhs_compiled(t + h, ytmp, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, k[last],
                             None)
        if kernels == 1:
            err = _ig.dopri5_error_norm(y, ytmp, k, h, rtol, atol)
        elif kernels == 2:
            err = _ig.tsit5_error_norm(y, ytmp, k, h, rtol, atol)
        else:
            err = _ig.error_norm(y, ytmp, k, h, rtol, atol, dbuf, pe)
        if not (err == err) or err > 1e300:
            if h < 1e-13:
                return 3, t, nsteps, nrejected
            h *= 0.1
            accepted_before = False
            nrejected += 1
            continue
        if err <= 1.0:
            t_new = target if landing else t + h
            if ext is not None or (iout < nout and t_out[iout] <= t_new):
                if kernels == 1:
                    _ig.dopri5_dense_coefficients(y, ytmp, k, h, rc)
                elif kernels == 2:
                    _ig.tsit5_dense_coefficients(y, k, h, rc)
                else:
                    _ig.dense_coefficients(y, ytmp, k, h, rc, pd)
            th_m = 0.5  # the interior sample: the output time nearest the middle, else the middle
            mid_row = -1
            while iout < nout and t_out[iout] <= t_new:
                fr = (t_out[iout] - t) / h
                _ig.dense_eval(rc, fr, ybuf)
                if out is not None:
                    out[iout, :] = ybuf
                if xout is not None:
                    rhs_compiled(t_out[iout], ybuf, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt,
                                 dbuf, xout[iout])
                    # an output inside the step is its interior sample
                    if 0.0 < fr < 1.0 and (mid_row < 0 or abs(fr - 0.5) < abs(th_m - 0.5)):
                        mid_row = iout
                        th_m = fr
                if fout is not None:
                    rhs_compiled(t_out[iout], ybuf, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt,
                                 dbuf, ebuf)
                    fout[iout] = ebuf[nm]
                iout += 1
            if ext is not None:
                ths = (0.0, th_m, 1.0)
                for isamp in range(3):
                    if isamp == 0 and started:
                        continue  # the step start is the previous step's end, already seen
                    if isamp == 2:
                        src = eend  # the end of the step: already evaluated as its last stage
                    elif isamp == 1 and mid_row >= 0:
                        src = xout[mid_row]  # an output sample: already evaluated
                    else:
                        # _eval_at written out: a call passing twenty arrays costs more than the work
                        _ig.dense_eval(rc, ths[isamp], ybuf)
                        rhs_compiled(t + ths[isamp] * h, ybuf, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth,
                                     omega, vt, dbuf, ebuf)
                        src = ebuf
                    # (src is read before any search below overwrites ebuf)
                    for sg in range(_N_SIG):
                        sval[isamp, sg] = _signal(sg, src, ne, nm, open_lift)
                    _channels(src, ne, nm, open_lift, gaps, vcur)
                    if ext[12] > 0.0:
                        # after the valve's first landing in the window, separations are seat
                        # bounces, not float: no lift-off and no cam-contact minimum there
                        sval[isamp, 4] = -np.inf
                        vcur[2] = 1.0
                    z_cur = src[2 * ne + 4]
                    if not started:
                        started = True
                        for c in range(nch):
                            if vcur[c] < 0.0:  # active at the window start
                                if nev[0] < events.shape[0]:
                                    r = nev[0]
                                    events[r, 0] = 0.0 if c < 2 else (2.0 if c == 2 else 1.0)
                                    events[r, 1] = float(c if c < 2 else (0 if c == 2 else c - 3))
                                    events[r, 2] = t0
                                    events[r, 3] = np.nan
                                    open_row[c] = r
                                    nev[0] += 1
                                else:
                                    ext[13] += 1.0
                    else:
                        lo = ths[isamp - 1]
                        changed = False  # a plain pass first: most samples change no channel
                        for c in range(nch):
                            changed |= (vcur[c] < 0.0) != (vprev[c] < 0.0)
                        for c in range(nch if changed else 0):
                            if (vcur[c] < 0.0) != (vprev[c] < 0.0):
                                if nev[0] >= events.shape[0] and open_row[c] < 0:
                                    ext[13] += 1.0
                                    continue
                                fr = _bisect(rc, t, h, lo, ths[isamp], c, False, masses, laws, xset, c0, cam_h,
                                             cam_dh, cam_ddh, dth, omega, vt, open_lift, gaps, ybuf, dbuf, ebuf)
                                tc = t + fr * h
                                if vcur[c] < 0.0:
                                    r = nev[0]
                                    events[r, 0] = 0.0 if c < 2 else (2.0 if c == 2 else 1.0)
                                    events[r, 1] = float(c if c < 2 else (0 if c == 2 else c - 3))
                                    events[r, 2] = tc
                                    events[r, 3] = np.nan
                                    open_row[c] = r
                                    nev[0] += 1
                                else:
                                    if open_row[c] >= 0:
                                        events[open_row[c], 3] = tc
                                    open_row[c] = -1
                        if vt is not None and vt[0] > 0.5 and z_prev > 0.0 and z_cur <= 0.0:
                            fr = _bisect(rc, t, h, lo, ths[isamp], 0, True, masses, laws, xset, c0, cam_h, cam_dh,
                                         cam_ddh, dth, omega, vt, open_lift, gaps, ybuf, dbuf, ebuf)
                            _ig.dense_eval(rc, fr, ybuf)
                            v_imp = -ybuf[nfree + nm]  # the valve's velocity
                            if ext[12] == 0.0:
                                ext[10] = v_imp
                                ext[11] = t + fr * h
                            ext[12] += 1.0
                            if nev[0] < events.shape[0]:
                                r = nev[0]
                                events[r, 0] = 3.0
                                events[r, 1] = 0.0
                                events[r, 2] = t + fr * h
                                events[r, 3] = v_imp
                                nev[0] += 1
                            else:
                                ext[13] += 1.0
                    for c in range(nch):
                        vprev[c] = vcur[c]
                    z_prev = z_cur
                    if isamp == 0:
                        for sg in range(_N_SIG):
                            if sval[0, sg] > best[sg]:
                                best[sg] = sval[0, sg]
                                best_t[sg] = t
                # true extremes: refine around a new record on the interpolant
                for sg in range(_N_SIG):
                    if have_prev:
                        sval[0, sg] = slast[sg]
                    va = sval[0, sg]
                    vm = sval[1, sg]
                    vb = sval[2, sg]
                    slast[sg] = vb
                    if vm == -np.inf and vb == -np.inf and va == -np.inf:
                        continue
                    if vm >= va and vm >= vb and vm > best[sg]:  # a local maximum inside the step
                        v, fr = _golden(rc, t, h, 0.0, 1.0, sg, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh,
                                        dth, omega, vt, open_lift, ybuf, dbuf, ebuf)
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
                        v1, f1 = _golden(rc_prev, t_prev, h_prev, mid_prev, 1.0, sg, masses, laws, xset, c0,
                                         cam_h, cam_dh, cam_ddh, dth, omega, vt, open_lift, ybuf, dbuf, ebuf)
                        v2, f2 = _golden(rc, t, h, 0.0, th_m, sg, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh,
                                         dth, omega, vt, open_lift, ybuf, dbuf, ebuf)
                        if v1 > best[sg] and v1 >= v2:
                            best[sg] = v1
                            best_t[sg] = t_prev + f1 * h_prev
                        elif v2 > best[sg]:
                            best[sg] = v2
                            best_t[sg] = t + f2 * h
                rc, rc_prev = rc_prev, rc  # this step's interpolant is the previous one now
                t_prev = t
                h_prev = h
                mid_prev = th_m
                have_prev = True
            y[:] = ytmp
            k[0, :] = k[last, :]
            t = t_new
            h_new = _ig.next_step(h, err, err_old, accepted_before, pq)
            err_old = max(err, 1e-4)
            accepted_before = True
            nsteps += 1
            h = min(h_new, h_max)
        else:
            h = min(h, _ig.next_step(h, err, err_old, False, pq))
            accepted_before = False
            nrejected += 1
    ctl[0] = h
    ctl[1] = err_old
    ctl[2] = 1.0 if accepted_before else 0.0
    if ext is not None:
        ext[0] = best[0]
        ext[1] = best_t[0]
        ext[2] = -best[1]
        ext[3] = best_t[1]
        ext[4] = best[2]
        ext[5] = best_t[2]
        ext[6] = -best[3]
        ext[7] = best_t[3]
        ext[8] = -best[4] if best[4] > -np.inf else np.nan
        ext[9] = best_t[4]
    return 0, t, nsteps, nrejected


@register_jitable
def _stop_times(stop_angles, omega, r0, r1):
    """The times [s] of the stop angles [rad] in revolutions ``r0`` to ``r1 - 1``."""
    nb = stop_angles.shape[0]
    out = np.empty(max(r1 - r0, 0) * nb)
    for r in range(r0, r1):
        for b in range(nb):
            out[(r - r0) * nb + b] = (2.0 * np.pi * r + stop_angles[b]) / omega
    return out


@njit(cache=True, nogil=True, fastmath=FASTMATH, error_model="numpy")
def _run_speeds(y0, omegas, revolutions, points, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, vt,
                rtol, atol, max_step_fraction, max_steps, gaps, extra_out, prev_out, status, t_end, steps, ext, events,
                nev, pc, pa, pe, pd, pq, kernels, stop_angles):
    n = y0.shape[0]
    y = np.empty(n)
    ctl = np.empty(3)
    t_rev = np.empty(points)
    for i in range(omegas.shape[0]):
        omega = omegas[i]
        period = 2.0 * np.pi / omega
        h_max = period * max_step_fraction
        y[:] = y0
        ctl[0] = 0.0
        ctl[1] = 1e-4
        ctl[2] = 0.0
        t1 = (revolutions - 1) * period
        st = 0
        t = 0.0
        ns = 0
        nr = 0
        if revolutions > 1:
            # the revolutions before the last, in the lean loop: the retainer force over the
            # one before the last only (for the periodicity check)
            for j in range(points):
                t_rev[j] = (revolutions - 2 + j / points) * period
            st, t, ns, nr = _integrate(y, 0.0, t1, t_rev, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega,
                                       vt, rtol, atol, h_max, max_steps, ctl,
                                       _stop_times(stop_angles, omega, 0, revolutions - 1), pc, pa, pe, pd, pq, kernels,
                                       None, None, prev_out[i], gaps, None, None, None)
        if st == 0:
            # the last revolution: every output, monitored
            for j in range(points):
                t_rev[j] = (revolutions - 1 + j / points) * period
            st, t, ns2, nr2 = _integrate(y, t1, revolutions * period, t_rev, masses, laws, xset, c0, cam_h, cam_dh,
                                         cam_ddh, dth, omega, vt, rtol, atol, h_max, max_steps - ns - nr, ctl,
                                         _stop_times(stop_angles, omega, revolutions - 1, revolutions),
                                         pc, pa, pe, pd, pq, kernels, None, extra_out[i], None, gaps, ext[i], events[i],
                                         nev[i])
            ns += ns2
        status[i] = st
        t_end[i] = t
        steps[i] = ns
        if st != 0:  # no partial outputs
            extra_out[i, :, :] = np.nan
            prev_out[i, :] = np.nan


def atol_vector(n_state: int, atol: float, atol_velocity: float | None = None) -> np.ndarray:
    """Absolute tolerance per state component: ``atol`` [m] on the displacements,
    ``atol_velocity`` [m/s] (default ``atol``) on the velocities.

    Parameters
    ----------
    n_state : int
        State size (displacements then velocities) [-].
    atol : float
        Absolute tolerance of the displacements [m].
    atol_velocity : float or ndarray (n_state // 2,), optional
        Absolute tolerance of the velocities [m/s], one for all or one per velocity.
    """
    half = n_state // 2
    out = np.full(n_state, float(atol))
    out[half:] = atol if atol_velocity is None else np.asarray(atol_velocity, dtype=float)
    return out


def run_speeds(y0, omegas, revolutions, points, args, *, rtol, atol, max_step_fraction, max_steps=10_000_000,
               gaps=None, monitor=False, atol_velocity=None, method="dopri5", stop_angles=None):
    """Integrate several speeds in one compiled call (the GIL is released throughout).

    For each speed the last revolution is sampled at ``points`` per revolution, where
    :func:`rhs` evaluates its ``extra`` outputs, and so is the revolution before it (with
    two revolutions or more) for its retainer force alone, which judges periodicity.
    ``args`` is the usual argument tuple of :func:`rhs`; its speed is ignored.  The last
    revolution is also monitored on the integrator's dense output (true extremes and
    events, see :func:`_integrate`).

    Parameters
    ----------
    y0 : ndarray
        Initial state: displacements [m] then velocities [m/s].
    omegas : array_like
        Cam speeds [rad/s].
    revolutions : int
        Revolutions to integrate per speed [-].
    points : int
        Output samples per revolution [-].
    args : tuple
        The argument tuple of :func:`rhs` (masses [kg], laws [m, N], set-up compressions
        [m], damping [N s/m], cam table [m, m/rad, m/rad^2], table step [rad], speed
        [rad/s], valve train parameters); its speed is ignored.
    rtol, atol : float
        Relative [-] and absolute [m] tolerances.
    max_step_fraction : float
        Largest step as a fraction of a revolution [-].
    max_steps : int
        Step budget per speed [-].
    gaps : ndarray (N + 1,), optional
        Compression [m] of each element beyond which its coils touch (``inf``: never);
        crossings are located as coil-contact events.
    monitor : bool
        Also return the monitor outputs [-].
    atol_velocity : float or ndarray, optional
        Absolute tolerance of the velocities [m/s], one for all or one per velocity
        (default ``atol``).
    method : {"dopri5", "tsit5", "bs3"}
        The embedded Runge-Kutta pair (:data:`springdyn.numerics.erk.PAIRS`).
    stop_angles : array_like, optional
        Cam angles [rad] in [0, 2 pi), ascending, on which a step lands in every revolution
        (:func:`stop_angles` of the cam's breakpoints).

    Returns
    -------
    extra : ndarray (n_speeds, points, extra size)
        The last revolution's ``extra`` outputs (layout :func:`extra_layout`).
    previous : ndarray (n_speeds, points) or (n_speeds, 0)
        The retainer force [N] over the revolution before (none with one revolution).
    status, t_end, steps : ndarray (n_speeds,)
    monitor : dict, with ``monitor=True`` only
        ``ext`` (n_speeds, :data:`N_EXT`) true extremes (layout :data:`EXT`), ``events``
        (n_speeds, :data:`MAX_EVENTS`, 4) rows ``kind, index, t_start, t_end`` (a landing
        has its impact velocity [m/s] in the last column), ``n_events`` (n_speeds,).
    """
    omegas = np.ascontiguousarray(omegas, dtype=float)
    masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, _omega, vt = args  # omega comes from omegas
    size = extra_layout(masses.shape[0])["size"]
    extra = np.empty((omegas.size, points, size))  # every row written, NaN on a failed speed
    previous = np.empty((omegas.size, points if int(revolutions) > 1 else 0))
    status = np.zeros(omegas.size, dtype=np.int64)
    t_end = np.zeros(omegas.size)
    steps = np.zeros(omegas.size, dtype=np.int64)
    ext = np.zeros((omegas.size, N_EXT))
    events = np.full((omegas.size, MAX_EVENTS, 4), np.nan)
    nev = np.zeros((omegas.size, 1), dtype=np.int64)
    gaps = np.full(laws.shape[0], np.inf) if gaps is None else np.ascontiguousarray(gaps, dtype=float)
    _run_speeds(np.ascontiguousarray(y0, dtype=float), omegas, int(revolutions), int(points), masses, laws, xset,
                _c0_array(c0, laws), cam_h, cam_dh, cam_ddh, float(dth), _train(vt), float(rtol),
                atol_vector(len(y0), atol, atol_velocity),
                float(max_step_fraction), int(max_steps), gaps, extra, previous, status, t_end, steps, ext, events, nev,
                *_pair(method), _angles(stop_angles))
    if monitor:
        return extra, previous, status, t_end, steps, dict(ext=ext, events=events, n_events=nev[:, 0].copy())
    return extra, previous, status, t_end, steps


def _train(vt):
    """The valve train's parameters for the compiled loop: None for the spring alone
    (``vt[0]`` zero), which selects the variant compiled without the train's code."""
    return vt if vt is not None and vt[0] > 0.5 else None


def _c0_array(c0, laws) -> np.ndarray:
    """The damping coefficients [N s/m], one per element, as a writable contiguous array
    (one array type for numba: a read-only one would compile the loop again)."""
    if (isinstance(c0, np.ndarray) and c0.dtype == np.float64 and c0.shape == laws.shape[:1]
            and c0.flags.c_contiguous and c0.flags.writeable):
        return c0
    return np.array(np.broadcast_to(np.asarray(c0, dtype=float), (laws.shape[0],)))


def stop_angles(breakpoints, dth: float) -> np.ndarray:
    """The cam-table nodes around each breakpoint, on which the engine lands its steps.

    The table (step ``dth``) smooths a jump of the lift law over the interval that holds
    it; landing on the nodes from one before to two after each breakpoint lets the
    integrator take that interval as a step of its own.

    Parameters
    ----------
    breakpoints : array_like
        Cam angles [rad] where the lift law is not smooth (:attr:`springdyn.valve.cam.Cam.breakpoints`).
    dth : float
        Table step [rad].

    Returns
    -------
    ndarray
        Ascending cam angles [rad] in [0, 2 pi).
    """
    b = np.asarray(breakpoints, dtype=float)
    if b.size == 0:
        return np.empty(0)
    n = int(round(2.0 * math.pi / dth))
    k = np.floor(b / dth).astype(np.int64)
    nodes = np.mod((k[:, None] + np.arange(-1, 3)[None, :]).ravel(), n)
    return np.unique(nodes) * dth


def _angles(a) -> np.ndarray:
    return np.empty(0) if a is None else np.ascontiguousarray(a, dtype=float)


def _pair(method: str) -> tuple:
    """The pair's arrays for :func:`_integrate` and its kernels: 0 the generic ones on the
    arrays, 1 and 2 the fused ones of Dormand-Prince and Tsitouras (which has only those)."""
    if method not in _ig.PAIRS:
        raise ValueError(f"method = {method!r} must be one of {sorted(_ig.PAIRS)}")
    c, a, e, d, q = _ig.pair_arrays(method)
    if method == "tsit5":
        return c, a, e, np.zeros(c.size), q, 2
    return c, a, e, d, q, (1 if method == "dopri5" and FUSED_DOPRI5 else 0)


def integrate(y0, t_out, args, *, rtol, atol, h_max, max_steps=10_000_000, atol_velocity=None, method="dopri5",
              stops=None):
    """Integrate with the compiled engine; states at ``t_out`` (ascending, from ``t_out[0]``).

    ``args`` = ``(masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt)``.

    Parameters
    ----------
    y0 : ndarray
        Initial state [m, m/s].
    t_out : ndarray
        Output times [s], ascending.
    args : tuple
        Arguments of :func:`rhs` after the state.
    rtol, atol : float
        Relative [-] and absolute [m] tolerances (velocities: ``atol_velocity``).
    h_max : float
        Largest step [s].
    max_steps : int
        Most steps [-] (the loop is bounded).
    atol_velocity : float or ndarray, optional
        Velocity tolerance [m/s], as for :func:`run_speeds`.
    method : {"dopri5", "tsit5", "bs3"}
        Runge-Kutta pair, as for :func:`run_speeds`.
    stops : array_like, optional
        Times [s], ascending, on which a step lands.

    Returns
    -------
    states : ndarray (len(t_out), n)
    info : dict
        ``status`` (0 ok, see :data:`STATUS`), ``t`` (time reached [s]), ``steps``, ``rejected``.
    """
    out = np.full((t_out.size, y0.size), np.nan)
    args = tuple(args)
    args = args[:3] + (_c0_array(args[3], args[1]),) + args[4:9] + (_train(args[9]),)
    t_out = np.ascontiguousarray(t_out, dtype=float)
    status, t, steps, rejected = _integrate(
        np.array(y0, dtype=float), float(t_out[0]), float(t_out[-1]), t_out, *args, float(rtol),
        atol_vector(len(y0), atol, atol_velocity), float(h_max), int(max_steps), np.array([0.0, 1e-4, 0.0]),
        _angles(stops), *_pair(method), out, None, None, np.full(args[1].shape[0], np.inf), None, None, None,
    )
    return out, dict(status=int(status), t=float(t), steps=int(steps), rejected=int(rejected))


def integrate_scipy(y0, t_out, args, *, rtol, atol, method="DOP853", compiled_rhs=False, h_max=np.inf,
                    atol_velocity=None):
    """Reference backend: ``scipy.integrate.solve_ivp`` with the plain-Python :func:`rhs`.

    With ``compiled_rhs=True`` the compiled right-hand side is used instead (same model,
    faster); the plain one is the independent reference of the benchmarks.

    Parameters
    ----------
    y0 : ndarray
        Initial state [m, m/s].
    t_out : ndarray
        Output times [s], ascending.
    args : tuple
        Arguments of :func:`rhs` after the state.
    rtol, atol : float
        Relative [-] and absolute [m] tolerances (velocities: ``atol_velocity``).
    method : str
        ``solve_ivp`` method name [-] (default ``"DOP853"``).
    compiled_rhs : bool
        Use the compiled right-hand side.
    h_max : float
        Largest step [s].
    atol_velocity : float or ndarray, optional
        Absolute tolerance of the velocities [m/s], one for all or one per velocity
        (default ``atol``).
    """
    from scipy.integrate import solve_ivp

    f = rhs_compiled if compiled_rhs else rhs
    buf = np.empty(len(y0))
    args = tuple(args)
    args = args[:3] + (_c0_array(args[3], args[1]),) + args[4:]

    def fun(t, y):
        d = np.empty_like(buf)
        f(t, y, *args, d, None)
        return d

    sol = solve_ivp(fun, (float(t_out[0]), float(t_out[-1])), np.asarray(y0, float), method=method, t_eval=t_out,
                    rtol=rtol, atol=atol_vector(len(y0), atol, atol_velocity), max_step=h_max)
    out = np.full((t_out.size, len(y0)), np.nan)
    out[: sol.y.shape[1]] = sol.y.T
    status = 0 if sol.status == 0 else 2
    t_reached = float(sol.t[-1]) if sol.t.size else float(t_out[0])
    return out, dict(status=status, t=t_reached, steps=int(sol.nfev), rejected=0, message=sol.message)


def hermite_eval(theta, cam_h, cam_dh, cam_ddh, dth):
    """Vectorised quintic Hermite evaluation of the cam table used by :func:`rhs`.

    Returns lift [m], ``dh/dtheta`` [m/rad] at cam angles ``theta`` [rad].

    Parameters
    ----------
    theta : float or array_like
        Cam angles [rad].
    cam_h, cam_dh, cam_ddh : ndarray
        Lift [m], ``dh/dtheta`` [m/rad] and ``d2h/dtheta2`` [m/rad^2] at ``k * dth``.
    dth : float
        Table step [rad].
    """
    theta = np.asarray(theta, dtype=float)
    n = cam_h.size
    th = np.mod(theta, n * dth)
    i0 = np.minimum((th / dth).astype(np.intp), n - 1)
    i1 = (i0 + 1) % n
    lift, slope = hermite5(th / dth - i0, cam_h[i0], cam_dh[i0] * dth, cam_ddh[i0] * dth**2,
                           cam_h[i1], cam_dh[i1] * dth, cam_ddh[i1] * dth**2)
    dlift = slope / dth
    return lift, dlift


@njit(cache=True)
def series_force_compiled(total_compression, laws, out, table_x, table_f):
    """Compiled twin of :func:`springdyn.valve.statics.series_force` (Newton's method).

    For each total compression [m], the common force [N] of the series chain, by Newton's
    method on each element's closed-form inverse law.  The total compression is a concave
    function of the force (every law stiffens), so from any start the iterates fall below
    the root after one step and rise to it monotonically.  The start is the linear
    interpolation of the force table ``table_x`` [m], ``table_f`` [N] (ascending; it lies
    above the convex force curve), or the all-linear force, below the root, outside the
    table or when it is empty.  Each point's start depends on its compression alone, so a
    result does not depend on the other points (sweeps chunked differently agree bit for
    bit); a compression equal to its predecessor's (the base circle) repeats its force.
    Used for the static force along a cam; the tests check it against the NumPy
    implementation.
    """
    n_el = laws.shape[0]
    k_lin = 0.0
    for j in range(n_el):
        k_lin += 1.0 / laws[j, 0, 2]
    k_lin = 1.0 / k_lin
    nt = table_x.shape[0]
    for i in range(total_compression.shape[0]):
        dl = total_compression[i]
        if i > 0 and dl == total_compression[i - 1]:
            out[i] = out[i - 1]
            continue
        force = dl * k_lin
        if nt > 1 and table_x[0] <= dl < table_x[nt - 1]:
            k = np.searchsorted(table_x, dl, side="right") - 1
            w = (dl - table_x[k]) / (table_x[k + 1] - table_x[k])
            force = table_f[k] + w * (table_f[k + 1] - table_f[k])
        for _ in range(100):
            total = 0.0
            comp = 0.0
            for j in range(n_el):
                seg = 0
                for s in (1, 2):
                    xs = laws[j, s, 0]
                    if xs < np.inf:
                        fs = (laws[j, s, 1] * xs + laws[j, s, 2]) * xs + laws[j, s, 3]
                        if force >= fs:
                            seg = s
                a = laws[j, seg, 1]
                b = laws[j, seg, 2]
                d = force - laws[j, seg, 3]
                x = 2.0 * d / (b + np.sqrt(max(b * b + 4.0 * a * d, 0.0)))
                total += x
                comp += 1.0 / (2.0 * a * x + b)
            step = (dl - total) / comp
            force += step
            if abs(step) <= 1e-12 * abs(force) + 1e-300:
                break
        out[i] = force
