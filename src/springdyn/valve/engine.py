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

Backends: :func:`integrate` (compiled: numba, adaptive Dormand-Prince 5(4) with dense
output, :mod:`springdyn.integration`) and :func:`integrate_scipy` (the reference:
``scipy.integrate.solve_ivp`` with the same right-hand side run as plain Python).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numba.extending import register_jitable

from ..numerics import dopri as _ig

__all__ = ["hermite5", "rhs", "rhs_compiled", "integrate", "integrate_scipy", "run_speeds", "hermite_eval", "STATUS", "EXTRA"]

#: Status codes of :func:`integrate`.
STATUS = {0: "ok", 1: "too many steps", 2: "step size collapsed", 3: "the solution is not finite (NaN/inf)"}


#: Layout of the optional ``extra`` output of :func:`rhs`.
EXTRA = ("f1", "f2", "f3", "f4", "f5", "f6", "x1", "x2", "x3", "x4", "x5", "x6", "lift", "dlift",
         "cam_contact_force", "valve_seat_force", "top_displacement", "u1", "u2", "u3", "u4", "u5")
N_EXTRA = len(EXTRA)


@register_jitable
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
    x2 = x * x
    x3 = x2 * x
    x4 = x3 * x
    x5 = x4 * x
    value = (
        (1 - 10 * x3 + 15 * x4 - 6 * x5) * p0
        + (x - 6 * x3 + 8 * x4 - 3 * x5) * v0
        + 0.5 * (x2 - 3 * x3 + 3 * x4 - x5) * a0
        + 0.5 * (x3 - 2 * x4 + x5) * a1
        + (-4 * x3 + 7 * x4 - 3 * x5) * v1
        + (10 * x3 - 15 * x4 + 6 * x5) * p1
    )
    slope = (
        (-30 * x2 + 60 * x3 - 30 * x4) * p0
        + (1 - 18 * x2 + 32 * x3 - 15 * x4) * v0
        + 0.5 * (2 * x - 9 * x2 + 12 * x3 - 5 * x4) * a0
        + 0.5 * (3 * x2 - 8 * x3 + 5 * x4) * a1
        + (-12 * x2 + 28 * x3 - 15 * x4) * v1
        + (30 * x2 - 60 * x3 + 30 * x4) * p1
    )
    return value, slope


def rhs(t, s, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, out, extra):
    """Right-hand side ``ds/dt`` of the chain (plain Python; compiled as :data:`rhs_compiled`).

    Parameters
    ----------
    t : float
        Time [s]; the cam angle is ``omega t``.
    s : ndarray
        State: node displacements [m] then velocities [m/s] (5 each, 6 with a valve train).
    masses : ndarray (5,)
        Chain masses [kg].
    laws : ndarray (6, 3, 4)
        Element laws [m, N]: per element, segments ``x_start [m], a [N/m^2], b [N/m], c [N]``
        (see :mod:`springdyn.valve.elements`).
    xset : ndarray (6,)
        Element compressions at set-up [m].
    c0 : float
        Damping coefficient C0 [N s/m].
    cam_h, cam_dh, cam_ddh : ndarray (N,)
        Lift [m] and its first two derivatives per radian at ``k * dth``, one revolution.
    dth : float
        Table step [rad].
    omega : float
        Cam angular speed [rad/s].
    vt : ndarray (7,)
        ``enabled, M_v [kg], k_c [N/m], c_c [N s/m], k_s [N/m], c_s [N s/m], lash [m]``.
    out : ndarray
        Receives ``ds/dt`` [m/s, m/s^2].
    extra : ndarray or None
        None (numba then compiles a variant without these outputs), or an array of length
        :data:`N_EXTRA` that receives the element forces [N] and
        compressions [m], lift [m] and lift rate [m/s], cam contact and valve-seat forces
        [N], the displacement of the retainer end [m] and of the five masses [m] (layout
        :data:`EXTRA`).
    """
    nfree = 5 + (1 if vt[0] > 0.5 else 0)
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
    # element forces, from the seat (node 0) to the retainer end (node 6)
    f_prev = 0.0
    u_lo = 0.0
    v_lo = 0.0
    for j in range(6):
        if j < 5:
            u_hi = s[j]
            v_hi = s[nfree + j]
        elif nfree == 6:
            u_hi = s[5]
            v_hi = s[11]
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
        stiff = 2.0 * a * xj + b
        force += c0 * math.sqrt(stiff / laws[j, 0, 2]) * (v_hi - v_lo)
        if extra is not None:
            extra[j] = force
            extra[6 + j] = xj
            if j < 5:
                extra[17 + j] = u_hi
        if j > 0:
            out[j - 1] = s[nfree + j - 1]
            out[nfree + j - 1] = (force - f_prev) / masses[j - 1]
        f_prev = force
        u_lo = u_hi
        v_lo = v_hi
    if nfree == 6:
        z = s[5]
        zd = s[11]
        f_cam = 0.0
        pen = lift - z - vt[6]
        if pen > 0.0:
            f_cam = vt[2] * pen + vt[3] * (dlift - zd)
            if f_cam < 0.0:
                f_cam = 0.0
        f_seat = 0.0
        if z < 0.0:
            f_seat = -vt[4] * z - vt[5] * zd
            if f_seat < 0.0:
                f_seat = 0.0
        out[5] = zd
        out[11] = (f_cam + f_seat - f_prev) / vt[1]
        if extra is not None:
            extra[14] = f_cam
            extra[15] = f_seat
            extra[16] = z
    if extra is not None:
        if nfree == 5:
            extra[14] = 0.0
            extra[15] = 0.0
            extra[16] = lift
        extra[12] = lift
        extra[13] = dlift


#: The compiled right-hand side (numba, cached on disk).
rhs_compiled = njit(cache=True, inline="always")(rhs)


@njit(cache=True, nogil=True)
def _integrate(y0, t0, t_out, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt,
               rtol, atol, h_max, max_steps, out):
    n = y0.shape[0]
    k = np.empty((7, n))
    ytmp = np.empty(n)
    rc = np.empty((5, n))
    y = y0.copy()
    t = t0
    rhs_compiled(t, y, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt, k[0], None)
    h = _ig.initial_step(y, k[0], rtol, atol, h_max)
    nout = t_out.shape[0]
    iout = 0
    while iout < nout and t_out[iout] <= t:
        out[iout, :] = y
        iout += 1
    err_old = 1e-4
    accepted_before = False
    nsteps = 0
    nrejected = 0
    while iout < nout:
        if nsteps + nrejected >= max_steps:
            return 1, t, nsteps, nrejected
        if h <= 1e-15 * max(abs(t), 1e-6) + 1e-18:
            return 2, t, nsteps, nrejected
        for stage in range(1, 7):
            _ig.stage_state(y, h, k, stage, ytmp)
            rhs_compiled(t + _ig.C[stage] * h, ytmp, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth,
                         omega, vt, k[stage], None)
        err = _ig.error_norm(y, ytmp, k, h, rtol, atol)
        if not (err == err) or err > 1e300:
            if h < 1e-13:
                return 3, t, nsteps, nrejected
            h *= 0.1
            accepted_before = False
            nrejected += 1
            continue
        if err <= 1.0:
            _ig.dense_coefficients(y, ytmp, k, h, rc)
            t_new = t + h
            while iout < nout and t_out[iout] <= t_new:
                _ig.dense_eval(rc, (t_out[iout] - t) / h, out[iout])
                iout += 1
            y[:] = ytmp
            k[0, :] = k[6, :]
            t = t_new
            h_new = _ig.next_step(h, err, err_old, accepted_before)
            err_old = max(err, 1e-4)
            accepted_before = True
            nsteps += 1
            h = min(h_new, h_max)
        else:
            h = min(h, _ig.next_step(h, err, err_old, False))
            accepted_before = False
            nrejected += 1
    return 0, t, nsteps, nrejected


@njit(cache=True, nogil=True)
def _run_speeds(y0, omegas, revolutions, points, keep, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, vt,
                rtol, atol, max_step_fraction, max_steps, extra_out, status, t_end, steps):
    n = y0.shape[0]
    nkeep = keep * points
    d = np.empty(n)
    for i in range(omegas.shape[0]):
        omega = omegas[i]
        period = 2.0 * np.pi / omega
        first = revolutions - keep
        pad = 1 if first > 0 else 0
        t_out = np.empty(nkeep + pad)
        t_out[0] = 0.0
        for j in range(nkeep):
            t_out[pad + j] = (first + j / points) * period
        states = np.empty((nkeep + pad, n))
        st, t, ns, nr = _integrate(y0, 0.0, t_out, masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt,
                                   rtol, atol, period * max_step_fraction, max_steps, states)
        status[i] = st
        t_end[i] = t
        steps[i] = ns
        if st != 0:
            continue
        for j in range(nkeep):
            rhs_compiled(t_out[pad + j], states[pad + j], masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth,
                         omega, vt, d, extra_out[i, j])


def run_speeds(y0, omegas, revolutions, points, args, *, rtol, atol, max_step_fraction, max_steps=10_000_000):
    """Integrate several speeds in one compiled call (the GIL is released throughout).

    For each speed the last ``keep = min(2, revolutions)`` revolutions are sampled at
    ``points`` per revolution, and :func:`rhs` evaluates there its ``extra`` outputs.
    ``args`` is the usual argument tuple of :func:`rhs`; its speed is ignored.

    Parameters
    ----------
    y0 : ndarray
        Initial state [m, m/s].
    omegas : array_like
        Cam speeds [rad/s].
    revolutions : int
        Revolutions per speed [-].
    points : int
        Output samples per revolution [-].
    args : tuple
        Arguments of :func:`rhs` after the state.
    rtol, atol : float
        Relative [-] and absolute [m, m/s] tolerances.
    max_step_fraction : float
        Largest step as a fraction of a revolution [-].
    max_steps : int
        Most steps per speed [-] (the loop is bounded).

    Returns
    -------
    extra : ndarray (n_speeds, keep * points, N_EXTRA)
    status, t_end, steps : ndarray (n_speeds,)
    """
    omegas = np.ascontiguousarray(omegas, dtype=float)
    keep = min(2, int(revolutions))
    extra = np.full((omegas.size, keep * points, N_EXTRA), np.nan)
    status = np.zeros(omegas.size, dtype=np.int64)
    t_end = np.zeros(omegas.size)
    steps = np.zeros(omegas.size, dtype=np.int64)
    masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, _omega, vt = args  # omega comes from omegas
    _run_speeds(np.ascontiguousarray(y0, dtype=float), omegas, int(revolutions), int(points), keep, masses, laws, xset,
                float(c0), cam_h, cam_dh, cam_ddh, float(dth), vt, float(rtol), float(atol), float(max_step_fraction),
                int(max_steps), extra, status, t_end, steps)
    return extra, status, t_end, steps


def integrate(y0, t_out, args, *, rtol, atol, h_max, max_steps=10_000_000):
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
        Relative [-] and absolute [m, m/s] tolerances.
    h_max : float
        Largest step [s].
    max_steps : int
        Most steps [-] (the loop is bounded).

    Returns
    -------
    states : ndarray (len(t_out), n)
    info : dict
        ``status`` (0 ok, see :data:`STATUS`), ``t`` (time reached [s]), ``steps``, ``rejected``.
    """
    out = np.full((t_out.size, y0.size), np.nan)
    status, t, steps, rejected = _integrate(
        np.ascontiguousarray(y0, dtype=float), float(t_out[0]), np.ascontiguousarray(t_out, dtype=float), *args,
        float(rtol), float(atol), float(h_max), int(max_steps), out,
    )
    return out, dict(status=int(status), t=float(t), steps=int(steps), rejected=int(rejected))


def integrate_scipy(y0, t_out, args, *, rtol, atol, method="DOP853", compiled_rhs=False, h_max=np.inf):
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
        Relative [-] and absolute [m, m/s] tolerances.
    method : str
        ``solve_ivp`` method name [-] (default ``"DOP853"``).
    compiled_rhs : bool
        Use the compiled right-hand side.
    h_max : float
        Largest step [s].
    """
    from scipy.integrate import solve_ivp

    f = rhs_compiled if compiled_rhs else rhs
    buf = np.empty(len(y0))

    def fun(t, y):
        d = np.empty_like(buf)
        f(t, y, *args, d, None)
        return d

    sol = solve_ivp(fun, (float(t_out[0]), float(t_out[-1])), np.asarray(y0, float), method=method, t_eval=t_out,
                    rtol=rtol, atol=atol, max_step=h_max)
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
def series_force_compiled(total_compression, laws, out):
    """Compiled twin of :func:`springdyn.valve.statics.series_force` (same Newton scheme).

    For each total compression [m], the common force [N] of the series chain: Newton's
    method from the all-linear force, which lies below the root, using each element's
    closed-form inverse law.  Used for the static force along a cam; the tests check it
    against the NumPy implementation.
    """
    n_el = laws.shape[0]
    k_lin = 0.0
    for j in range(n_el):
        k_lin += 1.0 / laws[j, 0, 2]
    k_lin = 1.0 / k_lin
    for i in range(total_compression.shape[0]):
        dl = total_compression[i]
        force = dl * k_lin
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
