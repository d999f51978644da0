"""The equations of motion the engine integrates: the spring's chain, its contacts, the valve train.

One place for each (the element laws themselves are :mod:`springdyn.valve.spring.elements`, whose
piecewise-quadratic tables ``laws`` the chain reads):

- :func:`hermite5`: the cam as the engine sees it, a quintic Hermite interpolant (C2) of the
  periodic lift table; :func:`cam_at` evaluates it at a cam angle.
- :func:`chain_rhs`: the right-hand side ``ds/dt`` of the chain of N masses between the seat
  and the retainer ([MMS], "Model variable" and "Initial condition & position"; corrections
  MMS-7 to MMS-10 of docs/references.md), with the unilateral end contacts (MMS-7) and, with
  a valve train, its unilateral links (cam, lever tip, pushrod, valve seat).

Nodes are numbered from the seat (node 0, fixed) to the retainer end (node N + 1).  ``u``
is the displacement of a node towards the seat from its set-up position.  Element ``j``
joins nodes ``j`` and ``j + 1``, is compressed by ``x_j = x_j,set + u_(j+1) - u_j`` and
carries ``f_j = F_j(x_j) + c_j(x_j) dx_j/dt``.  Mass ``i`` (node ``i + 1``) obeys
``m_i d2u/dt2 = f_(i+1) - f_i``.

- Spring alone: the retainer end follows the cam, ``u_(N+1) = h(omega t)``.
- Valve train: node N + 1 is the valve body (mass ``M_v``, displacement ``z`` = valve lift)
  with ``M_v z'' = F_cam + F_seat - f_N``; the cam contact ``F_cam = max(0, k_c p + c_c p')``
  for ``p = h - z - lash > 0`` and the seat ``F_seat = max(0, -k_s z - c_s z')`` for ``z < 0``.

The functions are plain Python on floats and arrays: :data:`spring_rhs_hot`,
:data:`train_rhs_hot` and :data:`rhs_call` are their compiled twins (the first two inlined
into the integration step, the last called), and the SciPy reference (:mod:`.reference`)
runs them as they are.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ...numerics.jit import kernel, rebind, twins
from .layout import (
    VT_ALPHA,
    VT_C_CAM,
    VT_C_PUSH,
    VT_C_SEAT,
    VT_C_TIP,
    VT_DOF,
    VT_ENABLED,
    VT_GAS_N,
    VT_GEOM,
    VT_GEOM_N,
    VT_HLA_AIR,
    VT_HLA_AREA,
    VT_HLA_BETA,
    VT_HLA_CS,
    VT_HLA_CSTOP,
    VT_HLA_DRAG,
    VT_HLA_FS,
    VT_HLA_G,
    VT_HLA_KCHK,
    VT_HLA_KCV,
    VT_HLA_KS,
    VT_HLA_KSTOP,
    VT_HLA_MA,
    VT_HLA_MP,
    VT_HLA_N,
    VT_HLA_PCRACK,
    VT_HLA_PS,
    VT_HLA_V0,
    VT_HLA_Y0,
    VT_HLA_YMAX,
    VT_HLA_YMIN,
    VT_K_CAM,
    VT_K_PUSH,
    VT_K_SEAT,
    VT_K_TIP,
    VT_LASH,
    VT_LEVER_J,
    VT_M_LEVER,
    VT_M_LIFTER,
    VT_MASS,
    VT_PAD_A,
    VT_PAD_R2,
    VT_RATIO,
    VT_SIZE,
    X_CAM_FORCE,
    X_DISP,
    X_DLIFT,
    X_LIFT,
    X_SEAT_FORCE,
    X_TOP,
)

__all__ = [
    "EngineModel",
    "model_of",
    "train_of",
    "hermite5",
    "cam_at",
    "element_force",
    "chain_forces",
    "spring_rhs",
    "train_rhs",
    "train_response",
    "chain_rhs",
    "spring_rhs_hot",
    "train_rhs_hot",
    "cam_at_hot",
    "rhs_call",
    "NO_EXTRA",
    "air_oil_bulk_modulus",
    "hla_forces",
    "gas_force_at",
]

#: Floating-point licences of the compiled kernels: fused multiply-add (``contract``),
#: division by a reciprocal (``arcp``) and no signed zeros (``nsz``).  Each changes a result
#: by at most an ulp per operation (round-off, far below the tolerances); together they cut
#: the Type C step by ~12 % (divisions by masses and table steps dominate the right-hand
#: side).  No licence that assumes finite values: the NaN/inf checks must stay.
FASTMATH = {"contract", "arcp", "nsz"}

#: The ``extra`` argument that asks for no extra outputs.
NO_EXTRA = np.empty(0)


class EngineModel(NamedTuple):
    """The speed-independent arrays of one spring and cam, as the compiled engine reads them."""

    masses: np.ndarray  #: chain masses (N,) [kg]
    laws: np.ndarray  #: element laws (N + 1, S, 4): segments ``x_start [m], a [N/m^2], b [N/m], c [N]``
    xset: np.ndarray  #: element compressions at set-up (N + 1,) [m]
    c0: np.ndarray  #: element damping at the initial rate (N + 1,) [N s/m]
    cam_h: np.ndarray  #: lift table over one revolution (M,) [m]
    cam_dh: np.ndarray  #: its first derivative [m/rad]
    cam_ddh: np.ndarray  #: its second derivative [m/rad^2]
    dth: float  #: table step [rad]


def train_of(vt):
    """The valve train's parameters for the compiled code: None for the spring alone
    (``vt[VT_ENABLED]`` zero), which selects the variant compiled without the train's code.

    Parameters
    ----------
    vt : ndarray (VT_SIZE,) or None
        The train's parameter vector [mixed units, layout ``VT_*``].
    """
    return vt if vt is not None and vt[VT_ENABLED] > 0.5 else None


def _c0_array(c0, laws) -> np.ndarray:
    """The damping coefficients [N s/m], one per element, as a writable contiguous array
    (one array type for numba: a read-only one would compile the loop again)."""
    if (
        isinstance(c0, np.ndarray)
        and c0.dtype == np.float64
        and c0.shape == laws.shape[:1]
        and c0.flags.c_contiguous
        and c0.flags.writeable
    ):
        return c0
    return np.array(np.broadcast_to(np.asarray(c0, dtype=float), (laws.shape[0],)))


def model_of(args) -> EngineModel:
    """The engine's model arrays from the argument tuple of a simulation set-up.

    Parameters
    ----------
    args : tuple
        ``(masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt)``: masses [kg],
        element laws [m, N], set-up compressions [m], damping [N s/m], cam table [m, m/rad,
        m/rad^2], table step [rad], speed [rad/s] and valve-train parameters
        (:meth:`springdyn.valve.run.setup.SimulationSetup.args`).
    """
    masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth = args[:8]
    return EngineModel(masses, laws, xset, _c0_array(c0, laws), cam_h, cam_dh, cam_ddh, float(dth))


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


def cam_at(theta, cam_h, cam_dh, cam_ddh, dth):
    """Lift [m] and ``dh/dtheta`` [m/rad] of the periodic cam table at the cam angle ``theta`` [rad].

    Parameters
    ----------
    theta : float
        Cam angle [rad], any real (the table repeats every revolution).
    cam_h, cam_dh, cam_ddh : ndarray (M,)
        Lift [m] and its first two derivatives [m/rad, m/rad^2] at ``k * dth``.
    dth : float
        Table step [rad].
    """
    n = cam_h.shape[0]
    period = n * dth
    th = theta - period * math.floor(theta / period)
    i0 = int(th / dth)
    if i0 >= n:
        i0 = n - 1
    i1 = i0 + 1 if i0 + 1 < n else 0
    lift, slope = hermite5(
        th / dth - i0,
        cam_h[i0],
        cam_dh[i0] * dth,
        cam_ddh[i0] * dth * dth,
        cam_h[i1],
        cam_dh[i1] * dth,
        cam_ddh[i1] * dth * dth,
    )
    return lift, slope / dth


def element_force(laws, c0, j, xj, rate, unilateral):
    """The force [N] of element ``j`` at compression ``xj`` [m] and compression rate ``rate`` [m/s].

    ``F_j(x) + c_j(x) x'``: the piecewise-quadratic law (:mod:`springdyn.valve.spring.elements`)
    and its damping, ``c0`` on the linear segment and ``c0 sqrt(k(x)/k0)`` beyond
    (:func:`springdyn.valve.spring.elements.damping_coefficient`): the scalar twin of
    :func:`springdyn.valve.spring.elements.law_force` for compiled code, which the tests compare
    with it.  An end element is a contact (``unilateral``, MMS-7): compression only.

    Parameters
    ----------
    laws : ndarray (N + 1, S, 4)
        Element laws [m, N/m^2, N/m, N], ``S >= 3`` segments each.
    c0 : ndarray (N + 1,)
        Damping coefficients at the initial rate [N s/m].
    j : int
        The element [-].
    xj : float
        Its compression [m].
    rate : float
        Its compression rate [m/s].
    unilateral : bool
        An end contact (compression only) [-].
    """
    seg = 0
    last = laws.shape[1] - 1
    while seg < last and xj >= laws[j, seg + 1, 0]:
        seg += 1
    a = laws[j, seg, 1]
    b = laws[j, seg, 2]
    force = (a * xj + b) * xj + laws[j, seg, 3]
    if seg == 0:
        force += c0[j] * rate
    else:
        force += c0[j] * math.sqrt((2.0 * a * xj + b) / laws[j, 0, 2]) * rate
    if unilateral and (xj <= 0.0 or force < 0.0):
        force = 0.0
    return force


def chain_forces(s, m, nfree, u_top, v_top, out, extra):
    """The element forces of the chain and the accelerations of its masses ([MMS], MMS-7).

    The two end elements carry compression only (correction MMS-7).

    Parameters
    ----------
    s : ndarray
        State: displacements [m] then velocities [m/s].
    m : EngineModel
        The chain's arrays [kg, m, N, N s/m].
    nfree : int
        Degrees of freedom [-]: the velocities start at ``s[nfree]``.
    u_top, v_top : float
        Displacement [m] and velocity [m/s] of the retainer end (node N + 1).
    out : ndarray
        Receives the derivatives of the masses' states [m/s, m/s^2].
    extra : ndarray
        Empty, or receives element forces [N], compressions [m] and mass displacements [m].

    Returns
    -------
    float
        Force of the last element, on the retainer end [N].
    """
    masses = m.masses
    laws = m.laws
    xset = m.xset
    c0 = m.c0
    nm = masses.shape[0]
    ne = nm + 1
    rec = extra.shape[0] > 0
    f_prev = 0.0
    u_lo = 0.0
    v_lo = 0.0
    for j in range(ne):
        if j < nm:
            u_hi = s[j]
            v_hi = s[nfree + j]
        else:
            u_hi = u_top
            v_hi = v_top
        xj = xset[j] + u_hi - u_lo
        force = element_force(laws, c0, j, xj, v_hi - v_lo, j == 0 or j == ne - 1)
        if rec:
            extra[j] = force
            extra[ne + j] = xj
            if j < nm:
                extra[2 * ne + X_DISP + j] = u_hi
        if j > 0:
            out[j - 1] = s[nfree + j - 1]
            out[nfree + j - 1] = (force - f_prev) / masses[j - 1]
        f_prev = force
        u_lo = u_hi
        v_lo = v_hi
    return f_prev


def _record_tail(extra, ne, nm, lift, dlift, f_cam, f_seat, z, gap):
    if extra.shape[0] > 0:
        b = 2 * ne
        extra[b + X_LIFT] = lift
        extra[b + X_DLIFT] = dlift
        extra[b + X_CAM_FORCE] = f_cam
        extra[b + X_SEAT_FORCE] = f_seat
        extra[b + X_TOP] = z
        extra[b + X_DISP + nm] = gap


def _record_hla(extra, ne, nm, collapse, pressure, socket, inflow, leak, check):
    if extra.shape[0] > 0:
        b = 2 * ne + X_DISP + nm
        extra[b + 1] = collapse
        extra[b + 2] = pressure
        extra[b + 3] = socket
        extra[b + 4] = inflow
        extra[b + 5] = leak
        extra[b + 6] = check


def gas_force_at(vt, theta):
    """The gas force on the valve [N] at the cam angle ``theta`` [rad]: linear and periodic in
    the samples after the train's parameters (:class:`springdyn.valve.train.gas_force.GasForce`);
    0 without them.

    Parameters
    ----------
    vt : ndarray
        The train's parameters [mixed units], the force samples [N] after ``VT_SIZE``.
    theta : float
        Cam angle [rad].
    """
    n = int(vt[VT_GAS_N])
    if n == 0:
        return 0.0
    x = theta / (2.0 * math.pi)
    x = (x - math.floor(x)) * n
    i0 = int(x)
    if i0 >= n:
        i0 = n - 1
    i1 = i0 + 1 if i0 + 1 < n else 0
    frac = x - i0
    return vt[VT_SIZE + i0] * (1.0 - frac) + vt[VT_SIZE + i1] * frac


def lever_ratio_at(vt, theta):
    """The lever's ratio correction ``c = r_0 / r``, ``dc/dtheta`` [1/rad], the pivot factor
    ``n . d`` and its derivative [1/rad] at the cam angle ``theta`` [rad]: cubic Hermite and
    periodic in the table after the gas force's samples (:mod:`springdyn.valve.train.lever`).

    Parameters
    ----------
    vt : ndarray
        The train's parameters [mixed units], the table after ``VT_SIZE`` and the gas samples.
    theta : float
        Cam angle [rad].
    """
    n = int(vt[VT_GEOM_N])
    base = VT_SIZE + int(vt[VT_GAS_N])
    step = 2.0 * math.pi / n
    x = theta / (2.0 * math.pi)
    x = (x - math.floor(x)) * n
    i0 = int(x)
    if i0 >= n:
        i0 = n - 1
    i1 = i0 + 1 if i0 + 1 < n else 0
    u = x - i0
    j0 = base + 4 * i0
    j1 = base + 4 * i1
    # cubic Hermite basis and its derivative (per unit u)
    h00 = (1.0 + 2.0 * u) * (1.0 - u) * (1.0 - u)
    h10 = u * (1.0 - u) * (1.0 - u)
    h01 = u * u * (3.0 - 2.0 * u)
    h11 = u * u * (u - 1.0)
    d00 = 6.0 * u * (u - 1.0)
    d10 = (1.0 - u) * (1.0 - 3.0 * u)
    d11 = u * (3.0 * u - 2.0)
    c = h00 * vt[j0] + h10 * step * vt[j0 + 1] + h01 * vt[j1] + h11 * step * vt[j1 + 1]
    dc = (d00 * vt[j0] + d10 * step * vt[j0 + 1] - d00 * vt[j1] + d11 * step * vt[j1 + 1]) / step
    k = h00 * vt[j0 + 2] + h10 * step * vt[j0 + 3] + h01 * vt[j1 + 2] + h11 * step * vt[j1 + 3]
    dk = (d00 * vt[j0 + 2] + d10 * step * vt[j0 + 3] - d00 * vt[j1 + 2] + d11 * step * vt[j1 + 3]) / step
    return c, dc, k, dk


def lever_mass(vt, x):
    """The lever's mass at its valve-side tip [kg] and ``dM/dx`` [kg/m] at the tip's lift ``x`` [m]
    relative to the pivot: ``M = J / L_v^2``, ``L_v^2 = A^2 + B^2 - (x + A)^2``
    (:func:`springdyn.valve.train.lever.lever_mass_at_valve`); the constant ``M_r`` without geometry.

    Parameters
    ----------
    vt : ndarray
        The train's parameters [mixed units].
    x : float
        The tip's lift relative to the pivot [m].
    """
    if vt[VT_GEOM] < 0.5:
        return vt[VT_M_LEVER], 0.0
    xa = x + vt[VT_PAD_A]
    lv2 = vt[VT_PAD_R2] - xa * xa
    return vt[VT_LEVER_J] / lv2, 2.0 * vt[VT_LEVER_J] * xa / (lv2 * lv2)


def air_oil_bulk_modulus(p_abs, beta_oil, air, n):
    """Bulk modulus [Pa] of oil with free air at an absolute pressure: the scalar twin of
    :func:`springdyn.valve.train.hla.effective_bulk_modulus` for compiled code (the tests compare
    them; a compiled kernel calls code of the engine's folder only, whose contents key its
    cache, :func:`springdyn.numerics.jit.source_group`).

    Parameters
    ----------
    p_abs : float
        Absolute pressure [Pa].
    beta_oil : float
        Bulk modulus of the air-free oil [Pa].
    air : float
        Free-air volume fraction at atmospheric pressure [-].
    n : float
        Polytropic index [-].
    """
    p = p_abs if p_abs > 2000.0 else 2000.0
    v_air = air * (101325.0 / p) ** (1.0 / n)
    v_oil = 1.0 - air
    return (v_oil + v_air) / (v_oil / beta_oil + v_air / (n * p))


def hla_chamber(vt, y, yd, p, out, k, kv):
    """The adjuster's chamber, plunger spring and travel stops (:mod:`springdyn.valve.train.hla`).

    The plunger's collapse ``y`` (its travel into the body from the initial position, the
    direction that loses valve lift) and collapse rate ``yd``; the chamber pressure ``p``
    [Pa, absolute].  The chamber follows oil continuity
    (:func:`springdyn.valve.train.hla.chamber_pressure_rate`) with the check valve as an orifice and
    laminar leakage with the Couette drag of the moving plunger; it holds at the cavitation
    pressure.  Writes ``dp/dt`` and the flows in and out [m^3/s] into ``out[k:k + 3]`` (the
    first-order states; zeros into ``out[kv:kv + 3]``) and returns the force that pushes the
    plunger out of its body [N]: the chamber's pressure above the supply, the plunger spring,
    less the travel stops and the plunger's damping.

    Parameters
    ----------
    vt : ndarray (VT_SIZE,)
        The train's parameters [kg, N/m, N s/m, m, m^3, Pa, -] (layout ``VT_*``).
    y, yd : float
        Collapse [m] and its rate [m/s].
    p : float
        Chamber pressure, absolute [Pa].
    out : ndarray
        Receives the rates [Pa/s, m^3/s].
    k, kv : int
        Index of the pressure in the state and of its (unused) velocity slot [-].
    """
    stop = -vt[VT_HLA_CSTOP] * yd
    if y > vt[VT_HLA_YMAX]:
        stop -= vt[VT_HLA_KSTOP] * (y - vt[VT_HLA_YMAX])
    elif y < vt[VT_HLA_YMIN]:
        stop += vt[VT_HLA_KSTOP] * (vt[VT_HLA_YMIN] - y)
    ps = vt[VT_HLA_PS]
    area = vt[VT_HLA_AREA]
    # the chamber: check-valve inflow, leakage, the plunger's displacement of oil
    dp_cv = ps - vt[VT_HLA_PCRACK] - p
    q_in = 0.0
    if dp_cv > 0.0:
        if dp_cv < 2000.0:  # laminarised (springdyn.valve.train.hla.CHECK_VALVE_TRANSITION)
            q_in = vt[VT_HLA_KCV] * dp_cv / math.sqrt(2000.0)
        else:
            q_in = vt[VT_HLA_KCV] * math.sqrt(dp_cv)
    q_leak = vt[VT_HLA_G] * (p - ps) - vt[VT_HLA_DRAG] * yd
    volume = vt[VT_HLA_V0] - area * y
    beta = air_oil_bulk_modulus(p, vt[VT_HLA_BETA], vt[VT_HLA_AIR], vt[VT_HLA_N])
    dp = beta / volume * (area * yd + q_in - q_leak)
    if p <= 2000.0 and dp < 0.0:  # cavitation: the pressure holds (springdyn.valve.train.hla.P_CAVITATION)
        dp = 0.0
    out[k] = dp
    out[k + 1] = q_in
    out[k + 2] = q_leak
    out[kv] = 0.0
    out[kv + 1] = 0.0
    out[kv + 2] = 0.0
    return (p - ps) * area + vt[VT_HLA_FS] - stop


def hla_forces(s, nm, nfree, vt, out):
    """The hydraulic lash adjuster at the finger follower's pivot (:mod:`springdyn.valve.train.hla`).

    States (after the chain's, the valve's and the lever tip's): the finger's pivot end
    ``y_a`` (its collapse direction positive), the plunger ``y_p`` in its fixed body, then
    three first-order states: the chamber pressure ``p`` [Pa, absolute] and the oil volumes
    that entered through the check valve and left through the clearance since the start
    [m^3].  The socket (the finger on the plunger) is a unilateral contact; the plunger
    carries the socket force against the chamber (:func:`hla_chamber`).  Writes the
    derivatives of the adjuster's states into ``out`` and returns the socket force [N] on
    the finger's pivot end.

    Parameters
    ----------
    s : ndarray
        State [m, m/s, Pa, m^3].
    nm : int
        Chain masses [-].
    nfree : int
        Degrees of freedom [-].
    vt : ndarray (VT_SIZE,)
        The train's parameters [kg, N/m, N s/m, m, m^3, Pa, -] (layout ``VT_*``).
    out : ndarray
        Receives ``ds/dt`` [m/s, m/s^2, Pa/s, m^3/s].
    """
    ya = s[nm + 2]
    yp = s[nm + 3]
    yad = s[nfree + nm + 2]
    ypd = s[nfree + nm + 3]
    # the socket: the finger's pivot end on the plunger (compression only)
    pen = ya - yp
    sock = vt[VT_HLA_KS] * pen + vt[VT_HLA_CS] * (yad - ypd)
    if pen <= 0.0 or sock < 0.0:
        sock = 0.0
    f_out = hla_chamber(vt, yp - vt[VT_HLA_Y0], ypd, s[nm + 4], out, nm + 4, nfree + nm + 4)
    out[nfree + nm + 3] = (sock - f_out) / vt[VT_HLA_MP]
    out[nm + 3] = ypd
    out[nm + 2] = yad
    return sock


def bucket_hla_forces(s, nm, nfree, vt, out):
    """A hydraulic bucket tappet (:mod:`springdyn.valve.train.hla`): the adjuster inside the bucket.

    States (after the chain's and the valve's ``z``): the bucket body ``y_b`` on the cam, the
    plunger ``y_p`` on the valve stem (both in the valve's opening direction), then the
    chamber pressure and the oil volumes in and out.  The chamber lies between body and
    plunger: the collapse is ``y_b - y_p`` from its initial value.  The plunger pushes the
    stem through a unilateral contact (the socket).  Writes the body's and the plunger's
    derivatives (the body's acceleration without the cam force, which the caller adds) and
    the chamber's, and returns the socket force on the valve [N].

    Parameters
    ----------
    s : ndarray
        State [m, m/s, Pa, m^3].
    nm : int
        Chain masses [-].
    nfree : int
        Degrees of freedom [-].
    vt : ndarray (VT_SIZE,)
        The train's parameters [kg, N/m, N s/m, m, m^3, Pa, -] (layout ``VT_*``).
    out : ndarray
        Receives ``ds/dt`` [m/s, m/s^2, Pa/s, m^3/s].
    """
    z = s[nm]
    yb = s[nm + 1]
    yp = s[nm + 2]
    zd = s[nfree + nm]
    ybd = s[nfree + nm + 1]
    ypd = s[nfree + nm + 2]
    pen = yp - z  # the plunger on the stem tip (compression only)
    sock = vt[VT_HLA_KS] * pen + vt[VT_HLA_CS] * (ypd - zd)
    if pen <= 0.0 or sock < 0.0:
        sock = 0.0
    f_out = hla_chamber(vt, yb - yp - vt[VT_HLA_Y0], ybd - ypd, s[nm + 3], out, nm + 3, nfree + nm + 3)
    out[nm + 1] = ybd
    out[nm + 2] = ypd
    out[nfree + nm + 1] = -f_out / vt[VT_HLA_MA]  # the cam's force follows (train_rhs)
    out[nfree + nm + 2] = (f_out - sock) / vt[VT_HLA_MP]
    return sock


def spring_rhs(t, s, m, omega, vt, out, extra):
    """Right-hand side of the spring alone: the retainer end follows the cam, ``u_(N+1) = h(omega t)``.

    Parameters
    ----------
    t : float
        Time [s].
    s : ndarray
        State [m, m/s].
    m : EngineModel
        The chain and cam arrays [kg, m, N, N s/m, rad].
    omega : float
        Cam speed [rad/s].
    vt : None or ndarray
        Not read [-].
    out : ndarray
        Receives ``ds/dt`` [m/s, m/s^2].
    extra : ndarray
        Empty, or receives the extra outputs [N, m, m/s] (:func:`chain_rhs`).
    """
    nm = m.masses.shape[0]
    lift, slope = cam_at(omega * t, m.cam_h, m.cam_dh, m.cam_ddh, m.dth)
    dlift = slope * omega
    chain_forces(s, m, nm, lift, dlift, out, extra)
    _record_tail(extra, nm + 1, nm, lift, dlift, 0.0, 0.0, lift, 1.0)
    _record_hla(extra, nm + 1, nm, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


def train_rhs(t, s, m, omega, vt, out, extra):
    """Right-hand side of the spring in its valve train: node N + 1 is the valve body, and the
    train's links (cam, lever tip, pushrod, valve seat) are unilateral.

    Parameters
    ----------
    t : float
        Time [s].
    s : ndarray
        State: the chain's, then the train's degrees of freedom [m, m/s].
    m : EngineModel
        The chain and cam arrays [kg, m, N, N s/m, rad].
    omega : float
        Cam speed [rad/s].
    vt : ndarray (VT_SIZE,)
        An enabled valve train's parameters [kg, N/m, N s/m, m, -] (layout ``VT_*``).
    out : ndarray
        Receives ``ds/dt`` [m/s, m/s^2].
    extra : ndarray
        Empty, or receives the extra outputs [N, m, m/s] (:func:`chain_rhs`).
    """
    nm = m.masses.shape[0]
    ntr = int(vt[VT_DOF])
    nfree = nm + ntr
    # the cam angle and speed: constant speed, or a speed ramp of acceleration alpha
    alpha = vt[VT_ALPHA]
    theta = omega * t + 0.5 * alpha * t * t
    lift, slope = cam_at(theta, m.cam_h, m.cam_dh, m.cam_ddh, m.dth)
    dlift = slope * (omega + alpha * t)
    z = s[nm]
    zd = s[nfree + nm]
    f_spring = chain_forces(s, m, nfree, z, zd, out, extra)
    _record_hla(extra, nm + 1, nm, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # an adjuster overwrites them
    r = vt[VT_RATIO]
    f_cam = 0.0
    f_seat = 0.0
    if z < 0.0:
        f_seat = -vt[VT_K_SEAT] * z - vt[VT_C_SEAT] * zd
        if f_seat < 0.0:
            f_seat = 0.0
    if ntr == 1:  # direct-acting: the cam on the valve body, lash at the cam
        pen = lift - z - vt[VT_LASH]
        raw = vt[VT_K_CAM] * pen + vt[VT_C_CAM] * (dlift - zd)
        if pen > 0.0:
            f_cam = raw if raw > 0.0 else 0.0
        gap = min(pen, raw / vt[VT_K_CAM])
        f_valve = f_cam
    elif ntr == 6:  # a hydraulic bucket: the cam on the bucket body, the adjuster's plunger on the stem
        yb = s[nm + 1]
        ybd = s[nfree + nm + 1]
        pen = lift - yb
        raw = vt[VT_K_CAM] * pen + vt[VT_C_CAM] * (dlift - ybd)
        if pen > 0.0:
            f_cam = raw if raw > 0.0 else 0.0
        f_valve = bucket_hla_forces(s, nm, nfree, vt, out)
        out[nfree + nm + 1] += f_cam / vt[VT_HLA_MA]
        pen_s = s[nm + 2] - z
        raw_s = vt[VT_HLA_KS] * pen_s + vt[VT_HLA_CS] * (s[nfree + nm + 2] - zd)
        gap = min(min(pen, raw / vt[VT_K_CAM]), min(pen_s, raw_s / vt[VT_HLA_KS]))
        collapse = yb - s[nm + 2] - vt[VT_HLA_Y0]
        _record_hla(
            extra,
            nm + 1,
            nm,
            collapse,
            s[nm + 3] - vt[VT_HLA_PS],
            f_valve,
            s[nm + 4],
            s[nm + 5],
            collapse * vt[VT_HLA_KCHK],
        )
    else:
        zr = s[nm + 1]
        zrd = s[nfree + nm + 1]
        pen_t = zr - z - vt[VT_LASH]  # the lever tip on the valve, lash here
        raw_t = vt[VT_K_TIP] * pen_t + vt[VT_C_TIP] * (zrd - zd)
        f_valve = 0.0
        if pen_t > 0.0:
            f_valve = raw_t if raw_t > 0.0 else 0.0
        gap = min(pen_t, raw_t / vt[VT_K_TIP])
        if ntr == 2 or ntr == 7:  # finger follower / rocker: the follower rides on the lever
            ya = 0.0
            yad = 0.0
            if ntr == 7:  # on a hydraulic lash adjuster: its pivot end moves
                ya = s[nm + 2]
                yad = s[nfree + nm + 2]
            # the lever's geometry (springdyn.valve.train.lever): the ratio correction c = r_0 / r(theta)
            # and the pivot's share n . d of the contact normal; 1 for the constant ratio
            c = 1.0
            dc = 0.0
            kap = 1.0
            dkap = 0.0
            if vt[VT_GEOM] > 0.5:
                c, dc, kap, dkap = lever_ratio_at(vt, theta)
            thd = omega + alpha * t
            q = lift - (zr - ya) / r
            pen = c * q - kap * ya
            raw = vt[VT_K_CAM] * pen + vt[VT_C_CAM] * (
                c * (dlift - (zrd - yad) / r) + dc * thd * q - kap * yad - dkap * thd * ya
            )
            if pen > 0.0:
                f_cam = raw if raw > 0.0 else 0.0
            gap = min(gap, min(pen, raw / vt[VT_K_CAM]))
            m_lever, dm_lever = lever_mass(vt, zr - ya)
            f_lever = f_cam * c / r - 0.5 * dm_lever * (zrd - yad) * (zrd - yad)
            if ntr == 7:
                # the finger's pivot end: the cam's share (n . d - c/r) against the socket
                sock = hla_forces(s, nm, nfree, vt, out)
                out[nfree + nm + 2] = (f_cam * (kap - c / r) - sock) / vt[VT_HLA_MA]
                _record_hla(
                    extra,
                    nm + 1,
                    nm,
                    s[nm + 3] - vt[VT_HLA_Y0],
                    s[nm + 4] - vt[VT_HLA_PS],
                    sock,
                    s[nm + 5],
                    s[nm + 6],
                    (s[nm + 3] - vt[VT_HLA_Y0]) * vt[VT_HLA_KCHK],
                )
            out[nfree + nm + 1] = (f_lever - f_valve) / m_lever
        else:  # pushrod: lifter on the cam, pushrod to the lever
            zf = s[nm + 2]
            zfd = s[nfree + nm + 2]
            pen = lift - zf
            raw = vt[VT_K_CAM] * pen + vt[VT_C_CAM] * (dlift - zfd)
            if pen > 0.0:
                f_cam = raw if raw > 0.0 else 0.0
            xp = zf - zr / r
            raw_p = vt[VT_K_PUSH] * xp + vt[VT_C_PUSH] * (zfd - zrd / r)
            f_push = 0.0
            if xp > 0.0:
                f_push = raw_p if raw_p > 0.0 else 0.0
            gap = min(gap, min(min(pen, raw / vt[VT_K_CAM]), min(xp, raw_p / vt[VT_K_PUSH])))
            out[nm + 2] = zfd
            out[nfree + nm + 2] = (f_cam - f_push) / vt[VT_M_LIFTER]
            out[nfree + nm + 1] = (f_push / r - f_valve) / vt[VT_M_LEVER]
        out[nm + 1] = zrd
    out[nm] = zd
    # the gas force pushes the valve towards its seat (springdyn.valve.train.gas_force)
    out[nfree + nm] = (f_valve + f_seat - f_spring - gas_force_at(vt, theta)) / vt[VT_MASS]
    _record_tail(extra, nm + 1, nm, lift, dlift, f_cam, f_seat, z, gap)


def train_response(vt: np.ndarray, lift, dlift, u, v, theta=None, omega=None) -> dict:
    """Contact forces of the valve train from its states (vectorised NumPy).

    The NumPy twin of the contact laws of :func:`train_rhs` (above), vectorised over
    output samples for the reference backend's outputs; the tests compare the two.

    Parameters
    ----------
    vt : ndarray (16,)
        Engine parameters of the train [kg, N/m, N s/m, m, -] (layout ``VT_*``, :meth:`ValveTrain.kernel_parameters`).
    lift, dlift : ndarray (..., n_t)
        Lobe lift [m] and its rate [m/s].
    u, v : ndarray (..., dof, n_t)
        Positions [m] and velocities [m/s] of valve, lever tip, lifter.
    theta : ndarray (n_t,), optional
        Cam angles [rad] (needed with a lever's geometry, ``vt[VT_GEOM]``).
    omega : float or ndarray (..., 1), optional
        Cam speed [rad/s] (needed with a lever's geometry).

    Returns
    -------
    dict
        ``cam_contact_force``, ``valve_seat_force``, ``valve_lift`` [N, N, m]; with a
        hydraulic lash adjuster also ``hla_collapse`` [m], ``hla_pressure`` [Pa above the
        supply], ``socket_force`` [N], ``hla_inflow`` and ``hla_leak`` [m^3].
    """

    def contact(k, c, pen, rate):
        return np.where(pen > 0, np.maximum(k * pen + c * rate, 0.0), 0.0)

    dof = int(vt[VT_DOF])
    z, zd = u[..., 0, :], v[..., 0, :]
    seat = np.where(z < 0, np.maximum(-vt[VT_K_SEAT] * z - vt[VT_C_SEAT] * zd, 0.0), 0.0)
    if dof == 1:
        cam = contact(vt[VT_K_CAM], vt[VT_C_CAM], lift - z - vt[VT_LASH], dlift - zd)
    elif dof == 6:  # a hydraulic bucket: body, plunger, chamber
        cam = contact(vt[VT_K_CAM], vt[VT_C_CAM], lift - u[..., 1, :], dlift - v[..., 1, :])
        socket = contact(vt[VT_HLA_KS], vt[VT_HLA_CS], u[..., 2, :] - z, v[..., 2, :] - zd)
        return dict(
            cam_contact_force=cam,
            valve_seat_force=seat,
            valve_lift=z,
            hla_collapse=u[..., 1, :] - u[..., 2, :] - vt[VT_HLA_Y0],
            hla_pressure=u[..., 3, :] - vt[VT_HLA_PS],
            socket_force=socket,
            hla_inflow=u[..., 4, :],
            hla_leak=u[..., 5, :],
        )
    elif dof == 3:  # pushrod: the lifter on the cam
        cam = contact(vt[VT_K_CAM], vt[VT_C_CAM], lift - u[..., 2, :], dlift - v[..., 2, :])
    else:  # the lever; on a hydraulic lash adjuster (dof 7) its pivot end moves
        r = vt[VT_RATIO]
        ya = u[..., 2, :] if dof == 7 else 0.0
        yad = v[..., 2, :] if dof == 7 else 0.0
        c, dc, kap, dkap = 1.0, 0.0, 1.0, 0.0
        if vt[VT_GEOM] > 0.5:
            c, dc, kap, dkap = np.array([lever_ratio_at(vt, th) for th in np.ravel(theta)]).T
        thd = 0.0 if omega is None else omega
        q = lift - (u[..., 1, :] - ya) / r
        rate = c * (dlift - (v[..., 1, :] - yad) / r) + dc * thd * q - kap * yad - dkap * thd * ya
        cam = contact(vt[VT_K_CAM], vt[VT_C_CAM], c * q - kap * ya, rate)
    if dof == 7:
        socket = contact(vt[VT_HLA_KS], vt[VT_HLA_CS], u[..., 2, :] - u[..., 3, :], v[..., 2, :] - v[..., 3, :])
        return dict(
            cam_contact_force=cam,
            valve_seat_force=seat,
            valve_lift=z,
            hla_collapse=u[..., 3, :] - vt[VT_HLA_Y0],
            hla_pressure=u[..., 4, :] - vt[VT_HLA_PS],
            socket_force=socket,
            hla_inflow=u[..., 5, :],
            hla_leak=u[..., 6, :],
        )
    return dict(cam_contact_force=cam, valve_seat_force=seat, valve_lift=z)


def chain_rhs(t, s, m, omega, vt, out, extra):
    """Right-hand side ``ds/dt`` of a chain of N masses, with or without a valve train.

    The two end elements (element 0 on the seat, the last one on the retainer) are
    contacts that carry compression only: in tension, or when their spring-damper force
    would pull, they carry nothing and the end separates (correction MMS-7 of
    docs/references.md).  Calls :func:`spring_rhs` or :func:`train_rhs`.

    Parameters
    ----------
    t : float
        Time [s]; the cam angle is ``omega t``.
    s : ndarray
        State: node displacements [m] then velocities [m/s] (N each, N + dof with a valve train).
    m : EngineModel
        The chain's masses [kg], element laws [m, N], set-up compressions [m], damping
        [N s/m] and the cam table [m, m/rad, m/rad^2] with its step [rad].
    omega : float
        Cam angular speed [rad/s].
    vt : ndarray (VT_SIZE,) or None
        The valve train's parameters (layout ``VT_*`` of :mod:`.layout`); None, or
        ``vt[VT_ENABLED] = 0``, for the spring alone.  Train states follow the chain's
        masses: valve, lever tip (rocker, pushrod), lifter (pushrod).
    out : ndarray
        Receives ``ds/dt`` [m/s, m/s^2].
    extra : ndarray
        Empty for none, or an array of ``extra_layout(N)["size"]`` that receives the element
        forces [N] and compressions [m], then (offsets ``X_*``) lift [m] and lift rate
        [m/s], cam contact and valve-seat forces [N], the displacement of the retainer end
        [m], of the masses [m] and the signed cam-contact gap [m] (positive in contact).
    """
    if vt is not None:
        if vt[VT_ENABLED] > 0.5:
            train_rhs(t, s, m, omega, vt, out, extra)
            return
    spring_rhs(t, s, m, omega, vt, out, extra)


_TWINS = twins(
    globals(),
    [
        "hermite5",
        "cam_at",
        "element_force",
        "chain_forces",
        "_record_tail",
        "_record_hla",
        "gas_force_at",
        "lever_mass",
        "air_oil_bulk_modulus",
        "hla_chamber",
        "hla_forces",
        "bucket_hla_forces",
        "spring_rhs",
        "train_rhs",
    ],
    fastmath=FASTMATH,
)
# the adjuster's equations are called, not inlined: the integration step evaluates the
# right-hand side at every stage, and inlining this rarely used branch into each of them
# cost 2.4 s of the train engine's compilation (11.4 against 9 s)
for _name in ("hla_forces", "bucket_hla_forces"):
    _TWINS["__globals__"][_name] = kernel(
        rebind(globals()[_name], _TWINS["__globals__"]), fastmath=FASTMATH, nogil=True, _nrt=False
    )
# the same for the drawn lever's table (springdyn.valve.train.lever), used by lever trains only
_TWINS["__globals__"]["lever_ratio_at"] = kernel(
    rebind(lever_ratio_at, _TWINS["__globals__"]), fastmath=FASTMATH, nogil=True, _nrt=False
)
#: :func:`spring_rhs` and :func:`train_rhs` compiled to be inlined into the integration step
#: (their one hot call site, :mod:`.stepping`, chooses by the type of ``vt``).
spring_rhs_hot = _TWINS["spring_rhs"]
train_rhs_hot = _TWINS["train_rhs"]
#: The cam table's interpolant compiled to be inlined (:mod:`.static_force`, the monitor).
cam_at_hot = _TWINS["cam_at"]
#: :func:`chain_rhs` compiled as a function of its own: outputs, monitor, static checks.
rhs_call = kernel(rebind(chain_rhs, _TWINS["__globals__"]), fastmath=FASTMATH, nogil=True, _nrt=False)
