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
  The kind of train (``vt[VT_KIND]``, ``TRAIN_*`` of :mod:`.layout`) has its own function
  (:func:`direct_acting_rhs`, :func:`lever_rhs`, :func:`lever_hla_rhs`, :func:`pushrod_rhs`,
  :func:`bucket_hla_rhs`) and NumPy twin (:data:`RESPONSES`); its states are named by
  ``S_*`` and ``H_*`` of :mod:`.layout`.  A new kind: a ``TRAIN_*`` code, its states in
  :data:`.layout.TRAIN_STATES`, a ``*_rhs`` and a ``*_response`` here, and its branch in
  :func:`train_rhs` and entry in :data:`RESPONSES`.

The functions are plain Python on floats and arrays: :data:`spring_rhs_hot`,
:data:`train_rhs_hot` and :data:`rhs_call` are their compiled twins (the first two inlined
into the integration step, the last called), and the SciPy reference (:mod:`.reference`)
runs them as they are.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from ...core.docstrings import ParameterDocs
from ...numerics.jit import kernel, rebind, twins
from .hydraulics import effective_bulk_modulus, orifice_flow
from .layout import (
    DAMPER_FORCE,
    DAMPER_NODE,
    DAMPER_OTHER,
    DAMPER_VREG,
    H_INFLOW,
    H_LEAK,
    H_PLUNGER,
    H_PRESSURE,
    N_TAIL,
    P_CAVITATION,
    S_BUCKET,
    S_BUCKET_HLA,
    S_LEVER,
    S_LEVER_HLA,
    S_LIFTER,
    S_PIVOT,
    S_VALVE,
    TRAIN_BUCKET_HLA,
    TRAIN_DIRECT,
    TRAIN_DOF,
    TRAIN_KINDS,
    TRAIN_LEVER,
    TRAIN_LEVER_HLA,
    TRAIN_PUSHROD,
    TRAIN_SPRING_ALONE,
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
    VT_KIND,
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
    XT_CAM_GAP,
    XT_DAMPER_FORCE,
    XT_DAMPER_SLIP,
    XT_DISSIPATION,
    XT_HLA_CHECK,
    XT_HLA_COLLAPSE,
    XT_HLA_INFLOW,
    XT_HLA_LEAK,
    XT_HLA_PRESSURE,
    XT_RETAINER_COMPRESSION,
    XT_RETAINER_TOTAL,
    XT_SEAT_COMPRESSION,
    XT_SEAT_TOTAL,
    XT_SOCKET_FORCE,
)

__all__ = [
    "EngineModel",
    "model_of",
    "train_of",
    "hermite5",
    "cam_at",
    "element_force",
    "chain_forces",
    "damper_friction",
    "NO_DAMPER",
    "spring_rhs",
    "train_rhs",
    "CamDrive",
    "contact_force",
    "seat_force",
    "direct_acting_rhs",
    "lever_rhs",
    "lever_hla_rhs",
    "pushrod_rhs",
    "bucket_hla_rhs",
    "kind_of",
    "RESPONSES",
    "train_response",
    "chain_rhs",
    "spring_rhs_hot",
    "train_rhs_hot",
    "cam_at_hot",
    "rhs_call",
    "rhs_call_pack",
    "rhs_kernel",
    "spring_rhs_hot_pack",
    "train_rhs_hot_pack",
    "NO_EXTRA",
    "hla_forces",
    "gas_force_at",
]

#: The parameters several right-hand sides share, described once (springdyn.core.docstrings).
_DOCS = ParameterDocs(
    """
    cam : CamDrive
        The cam [rad, rad/s, m, m/s].
    extra : ndarray
        Empty, or receives the extra outputs [N, m, m/s] (:func:`chain_rhs`).
    lift, dlift : ndarray (..., n_t)
        Lobe lift [m] and its rate [m/s].
    m : EngineModel
        The chain and cam arrays [kg, m, N, N s/m, rad].
    ne, nm : int
        Chain elements and masses [-].
    nfree : int
        Degrees of freedom [-]: the velocities start at ``s[nfree]``.
    nm : int
        Chain masses [-].
    omega : float
        Cam speed [rad/s].
    out : ndarray
        Receives ``ds/dt`` [m/s, m/s^2].
    s : ndarray
        State [m, m/s, Pa, m^3].
    t : float
        Time [s].
    theta : float
        Cam angle [rad].
    vt : ndarray (VT_SIZE,)
        The train's parameters [kg, N/m, N s/m, m, m^3, Pa, -] (layout ``VT_*``).
""",
    out_hla="""
out : ndarray
    Receives ``ds/dt`` [m/s, m/s^2, Pa/s, m^3/s].
""",
    hla_kind_args="""
s, nm, nfree, vt, cam, out, extra : as for :func:`direct_acting_rhs`
    State [m, m/s, Pa, m^3], chain masses [-], degrees of freedom [-], the train's
    parameters, the cam [rad, rad/s, m, m/s], ``ds/dt``, extra outputs (the adjuster's).
""",
    kind_returns="""
f_cam, f_valve, gap : float
    Cam contact force [N], force on the valve [N], smallest signed gap [m].
""",
    chain_args="""
s : ndarray
    State: displacements [m] then velocities [m/s].
m : EngineModel
    The chains' arrays [kg, m, N, N s/m] (one spring's: one chain).
nfree : int
    Degrees of freedom [-]: the velocities start at ``s[nfree]``.
u_top, v_top : float
    Displacement [m] and velocity [m/s] of the retainer end (node N + 1).
out : ndarray
    Receives the derivatives of the masses' states [m/s, m/s^2].
""",
    kind_args="""
s, nm, nfree, vt, cam, out, extra : as for :func:`direct_acting_rhs`
    State [m, m/s], chain masses [-], degrees of freedom [-], the train's parameters,
    the cam [rad, rad/s, m, m/s], ``ds/dt`` [m/s, m/s^2], extra outputs.
""",
)

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
    #: the first mass of each parallel chain, then the mass count (C + 1,) [-]: ``[0, N]`` for
    #: one spring; a spring pack's chains lie one after the other (:func:`chain_forces`)
    chains: np.ndarray
    #: the friction dampers, one row each (R, :data:`.layout.DAMPER_SIZE`; layout ``DAMPER_*``)
    #: [-, -, N, m/s]: a flat-wound damper, the rubbing of interfering springs; a spring pack's
    #: (:data:`NO_DAMPER` for none), None for one spring, which selects its own compiled chain
    #: (:func:`chain_forces`)
    damper: np.ndarray | None


#: The chains of one spring of ``n`` masses (:attr:`EngineModel.chains`), cached by ``n``.
_ONE_CHAIN: dict = {}
#: No friction damper (:attr:`EngineModel.damper`).
NO_DAMPER = np.array([[0.0, -1.0, 0.0, 1.0]])


#: What the engine says of a parameter vector whose ``VT_KIND`` names no kind of train.
UNKNOWN_KIND = "vt[VT_KIND] names no kind of valve train the engine knows (springdyn.valve.engine.layout.TRAIN_KINDS)"


def kind_of(vt) -> int:
    """The kind of valve train of a parameter vector (``TRAIN_*`` of :mod:`.layout`), checked.

    Parameters
    ----------
    vt : ndarray (VT_SIZE,) or None
        The train's parameter vector [mixed units, layout ``VT_*``]; None, or
        ``vt[VT_ENABLED]`` zero, for the spring alone.

    Returns
    -------
    int
        ``TRAIN_SPRING_ALONE`` for the spring alone, else the enabled train's kind.

    Raises
    ------
    ValueError
        An enabled train whose ``VT_KIND`` is no kind of train, or whose ``VT_DOF`` is not
        its kind's (:data:`.layout.TRAIN_DOF`).
    """
    if vt is None or not vt[VT_ENABLED] > 0.5:
        return TRAIN_SPRING_ALONE
    code = float(vt[VT_KIND])
    if code == TRAIN_SPRING_ALONE or code not in TRAIN_KINDS:
        known = ", ".join(f"{k} {name}" for k, name in TRAIN_KINDS.items() if k != TRAIN_SPRING_ALONE)
        raise ValueError(f"{UNKNOWN_KIND}: {code:g} (an enabled train is one of {known})")
    kind = int(code)
    if vt[VT_DOF] != TRAIN_DOF[kind]:
        raise ValueError(
            f"vt[VT_DOF] = {vt[VT_DOF]:g}, but a {TRAIN_KINDS[kind]} train (VT_KIND {kind}) has "
            f"{TRAIN_DOF[kind]} degrees of freedom (springdyn.valve.engine.layout.TRAIN_DOF)"
        )
    return kind


def train_of(vt):
    """The valve train's parameters for the compiled code: None for the spring alone
    (``vt[VT_ENABLED]`` zero), which selects the variant compiled without the train's code.

    Parameters
    ----------
    vt : ndarray (VT_SIZE,) or None
        The train's parameter vector [mixed units, layout ``VT_*``].

    Raises
    ------
    ValueError
        An enabled train of no known kind (:func:`kind_of`).
    """
    return None if kind_of(vt) == TRAIN_SPRING_ALONE else vt


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
        (:func:`springdyn.valve.run.runner.engine_args`); a spring pack's add its chains'
        first masses and its friction damper (:attr:`EngineModel.chains`, :attr:`EngineModel.damper`).
    """
    masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth = args[:8]
    if len(args) > 10:
        chains = np.ascontiguousarray(args[10], dtype=np.int64)
        damper = np.array(np.reshape(args[11], (-1, 4)), dtype=float)
    else:
        n = masses.shape[0]
        chains = _ONE_CHAIN.get(n)
        if chains is None:
            chains = _ONE_CHAIN[n] = np.array([0, n], dtype=np.int64)
        damper = None  # one spring: its own compiled chain (chain_forces)
    if chains[-1] != masses.shape[0] or laws.shape[0] != masses.shape[0] + chains.shape[0] - 1:
        raise ValueError(
            f"chains {chains.tolist()} do not fit {masses.shape[0]} masses and {laws.shape[0]} elements "
            "(each chain has one element more than masses)"
        )
    return EngineModel(masses, laws, xset, _c0_array(c0, laws), cam_h, cam_dh, cam_ddh, float(dth), chains, damper)


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


def damper_friction(force, slip, v_reg):
    """The friction damper's force [N] on its node at the sliding velocity ``slip`` [m/s]: Coulomb
    friction regularised by ``tanh``, ``-F tanh(v / v_reg)`` ([Andersson], the smooth Coulomb
    model; exact Coulomb as ``v_reg`` -> 0).

    Parameters
    ----------
    force : float
        The Coulomb force, normal load times friction coefficient [N].
    slip : float
        The node's velocity less its counterpart's [m/s].
    v_reg : float
        Regularising velocity [m/s].
    """
    return -force * math.tanh(slip / v_reg)


@_DOCS.fill
def chain_forces(s, m, nfree, u_top, v_top, out, extra):
    """The element forces and the accelerations of the masses ([MMS], MMS-7): one spring's
    chain (:func:`one_chain_forces`, ``m.damper`` None) or a spring pack's chains
    (:func:`pack_chain_forces`).

    The compiled engine has two sets of twins (:data:`_TWINS`, :data:`_PACK_TWINS`): one spring's
    inlines :func:`one_chain_forces`, a pack's calls :func:`pack_chain_forces`, and a run takes
    the set of its model (:func:`rhs_kernel`, :data:`.loop.VARIANTS`), so a single spring's
    kernels hold no code of the pack's and a pack's compile only when a pack runs (issue 41: the
    cold first result of one spring is not slowed by packs).

    Parameters
    ----------
    {chain_args}
    extra : ndarray
        Empty, or receives the outputs [N, m, m/s, W] (:func:`.layout.extra_layout`).

    Returns
    -------
    float
        Force on the retainer end [N].
    """
    if m.damper is None:
        return one_chain_forces(s, m, nfree, u_top, v_top, out, extra)
    return pack_chain_forces(s, m, nfree, u_top, v_top, out, extra)


@_DOCS.fill
def one_chain_forces(s, m, nfree, u_top, v_top, out, extra):
    """The element forces of one spring's chain and the accelerations of its masses ([MMS], MMS-7).

    Element ``j`` joins nodes ``j`` and ``j + 1``; the two end elements are contacts that carry
    compression only (correction MMS-7).  The chain of :func:`pack_chain_forces` with one chain
    and no damper, written for it alone: the engine of a single spring compiles this one.

    Parameters
    ----------
    {chain_args}
    extra : ndarray
        Empty, or receives element forces [N], compressions [m], mass displacements [m], the
        end forces as the seat and retainer totals [N] and the end elements' compressions [m]
        (no damper, and no dissipation recorded: 0).

    Returns
    -------
    float
        Force on the retainer end, the last element's [N].
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
    if rec:
        b = 2 * ne + X_DISP + nm
        extra[b + XT_SEAT_TOTAL] = extra[0]
        extra[b + XT_RETAINER_TOTAL] = f_prev
        extra[b + XT_SEAT_COMPRESSION] = extra[ne]
        extra[b + XT_RETAINER_COMPRESSION] = extra[2 * ne - 1]
        extra[b + XT_DAMPER_FORCE] = 0.0
        extra[b + XT_DAMPER_SLIP] = 0.0
        extra[b + XT_DISSIPATION] = 0.0
    return f_prev


@_DOCS.fill
def pack_chain_forces(s, m, nfree, u_top, v_top, out, extra):
    """The element forces of a spring pack's chains and the accelerations of their masses ([MMS], MMS-7).

    One spring is one chain; a spring pack's chains (``m.chains``) stand side by side between
    the seat (node 0 of each) and the one retainer end, each with its own two end contacts,
    which carry compression only (correction MMS-7).  A friction damper (``m.damper``) acts
    on one mass against the seat or a mass of another chain (:func:`damper_friction`); so does
    each further row of ``m.damper`` (springs that rub where their diameters interfere).

    Parameters
    ----------
    {chain_args}
    extra : ndarray
        Empty, or receives element forces [N], compressions [m], mass displacements [m], the
        totals at the seat and the retainer [N], the end contacts' smallest compressions [m],
        the damper's force [N] and slip [m/s] and the power dissipated [W].

    Returns
    -------
    float
        Force on the retainer end, every chain's last element's [N].
    """
    masses = m.masses
    laws = m.laws
    xset = m.xset
    c0 = m.c0
    chains = m.chains
    f_top = 0.0
    for k in range(chains.shape[0] - 1):
        first = chains[k]
        last = chains[k + 1]  # the chain's masses first .. last - 1, its elements first + k .. last + k
        f_prev = 0.0
        u_lo = 0.0
        v_lo = 0.0
        for i in range(first, last + 1):
            if i < last:
                u_hi = s[i]
                v_hi = s[nfree + i]
            else:
                u_hi = u_top
                v_hi = v_top
            force = element_force(laws, c0, i + k, xset[i + k] + u_hi - u_lo, v_hi - v_lo, i == first or i == last)
            if i > first:
                out[i - 1] = s[nfree + i - 1]
                out[nfree + i - 1] = (force - f_prev) / masses[i - 1]
            f_prev = force
            u_lo = u_hi
            v_lo = v_hi
        f_top += f_prev
    dampers = m.damper
    for r in range(dampers.shape[0]):
        if dampers[r, DAMPER_FORCE] > 0.0:
            node, other, f_r, _ = _damper_row(s, nfree, dampers, r)
            out[nfree + node] += f_r / masses[node]
            if other >= 0:
                out[nfree + other] -= f_r / masses[other]
    if extra.shape[0] > 0:  # (the record is called, not inlined: see _RECORDS)
        _record_chains(s, m, nfree, u_top, v_top, extra)
    return f_top


def _damper_row(s, nfree, dampers, r):
    """Friction row ``r`` of ``dampers`` (layout ``DAMPER_*``) at the state ``s``: its node, its
    counterpart (-1: the seat), its force on the node [N] and the sliding velocity [m/s]."""
    node = int(dampers[r, DAMPER_NODE])
    other = int(dampers[r, DAMPER_OTHER])
    v_rel = s[nfree + node] - (s[nfree + other] if other >= 0 else 0.0)
    return node, other, damper_friction(dampers[r, DAMPER_FORCE], v_rel, dampers[r, DAMPER_VREG]), v_rel


@_DOCS.fill
def _record_chains(s, m, nfree, u_top, v_top, extra):
    """Record the chains' element forces, compressions and mass displacements, the totals at
    the seat and the retainer, the end contacts' smallest compressions, the first damper's
    force and slip and the power dissipated by the elements' damping and every damper into
    ``extra`` (:func:`.layout.extra_layout`; the forces as :func:`chain_forces` computes them).

    Parameters
    ----------
    s : ndarray
        State: displacements [m] then velocities [m/s].
    {m nfree}
    u_top, v_top : float
        Displacement [m] and velocity [m/s] of the retainer end.
    extra : ndarray
        Receives the outputs [N, m, m/s, W].
    """
    laws = m.laws
    xset = m.xset
    c0 = m.c0
    chains = m.chains
    nm = m.masses.shape[0]
    ne = laws.shape[0]
    f_seat = 0.0
    f_ret = 0.0
    power = 0.0
    x_seat = np.inf
    x_top = np.inf
    for k in range(chains.shape[0] - 1):
        first = chains[k]
        last = chains[k + 1]
        for i in range(first, last + 1):
            j = i + k
            lo = i > first
            hi = i < last
            xj = xset[j] + (s[i] if hi else u_top) - (s[i - 1] if lo else 0.0)
            rate = (s[nfree + i] if hi else v_top) - (s[nfree + i - 1] if lo else 0.0)
            force = element_force(laws, c0, j, xj, rate, not (lo and hi))
            extra[j] = force
            extra[ne + j] = xj
            if hi:
                extra[2 * ne + X_DISP + i] = s[i]
            if force != 0.0:  # the damping's share: the force less the elastic law's
                power += (force - element_force(laws, c0, j, xj, 0.0, False)) * rate
            if not lo:
                f_seat += force
                x_seat = min(x_seat, xj)
            if not hi:
                f_ret += force
                x_top = min(x_top, xj)
    b = 2 * ne + X_DISP + nm
    extra[b + XT_DAMPER_FORCE] = 0.0
    extra[b + XT_DAMPER_SLIP] = 0.0
    dampers = m.damper
    for r in range(dampers.shape[0] - 1, -1, -1):  # the first row's force and slip are recorded
        if dampers[r, DAMPER_FORCE] > 0.0:
            _, _, f_r, v_rel = _damper_row(s, nfree, dampers, r)
            power -= f_r * v_rel
            extra[b + XT_DAMPER_FORCE] = f_r
            extra[b + XT_DAMPER_SLIP] = v_rel
    extra[b + XT_SEAT_TOTAL] = f_seat
    extra[b + XT_RETAINER_TOTAL] = f_ret
    extra[b + XT_SEAT_COMPRESSION] = x_seat
    extra[b + XT_RETAINER_COMPRESSION] = x_top
    extra[b + XT_DISSIPATION] = power


@_DOCS.fill
def _record_tail(extra, ne, nm, lift, dlift, f_cam, f_seat, z, gap):
    """Record the cam, the contact forces, the valve's lift and the train's gap (offsets ``X_*``
    and :data:`.layout.XT_CAM_GAP`) into ``extra`` unless it is empty.

    Parameters
    ----------
    extra : ndarray
        Empty, or the extra outputs [N, m, m/s] (:func:`.layout.extra_layout`).
    {ne_nm}
    lift, dlift : float
        Cam lift [m] and lift rate [m/s].
    f_cam, f_seat : float
        Cam contact and valve-seat forces [N].
    z : float
        Displacement of the retainer end (the valve lift with a train) [m].
    gap : float
        The train's smallest signed gap [m] (positive in contact).
    """
    if extra.shape[0] > 0:
        b = 2 * ne
        extra[b + X_LIFT] = lift
        extra[b + X_DLIFT] = dlift
        extra[b + X_CAM_FORCE] = f_cam
        extra[b + X_SEAT_FORCE] = f_seat
        extra[b + X_TOP] = z
        extra[b + X_DISP + nm + XT_CAM_GAP] = gap


@_DOCS.fill
def _record_hla(extra, s, h, vt, collapse, socket):
    """Record an adjuster's outputs (offsets ``XT_HLA_*`` of :mod:`.layout`) into ``extra``
    unless it is empty: its collapse, chamber pressure above the supply, socket force, the oil
    volumes in and out since the start and the collapse as a periodicity force.

    Parameters
    ----------
    extra : ndarray
        Empty, or the extra outputs [N, m, m/s, Pa, m^3] (:func:`.layout.extra_layout`; its
        tail, :data:`.layout.N_TAIL` values, ends it).
    s : ndarray
        State [m, m/s, Pa, m^3].
    h : int
        Index of the adjuster's first state (``H_*`` from it) [-].
    {vt}
    collapse : float
        The adjuster's collapse from its base-circle position [m].
    socket : float
        Socket force [N].
    """
    if extra.shape[0] > 0:
        b = extra.shape[0] - N_TAIL
        extra[b + XT_HLA_COLLAPSE] = collapse
        extra[b + XT_HLA_PRESSURE] = s[h + H_PRESSURE] - vt[VT_HLA_PS]
        extra[b + XT_SOCKET_FORCE] = socket
        extra[b + XT_HLA_INFLOW] = s[h + H_INFLOW]
        extra[b + XT_HLA_LEAK] = s[h + H_LEAK]
        extra[b + XT_HLA_CHECK] = collapse * vt[VT_HLA_KCHK]


@_DOCS.fill
def _record_no_hla(extra, ne, nm):
    """Record zeros for the adjuster's outputs (a train without one, the spring alone) into
    ``extra`` unless it is empty.

    Parameters
    ----------
    extra : ndarray
        Empty, or the extra outputs [N, m, m/s, Pa, m^3] (:func:`.layout.extra_layout`).
    {ne_nm}
    """
    if extra.shape[0] > 0:
        b = 2 * ne + X_DISP + nm
        for slot in (XT_HLA_COLLAPSE, XT_HLA_PRESSURE, XT_SOCKET_FORCE, XT_HLA_INFLOW, XT_HLA_LEAK, XT_HLA_CHECK):
            extra[b + slot] = 0.0


@_DOCS.fill
def gas_force_at(vt, theta):
    """The gas force on the valve [N] at the cam angle ``theta`` [rad]: linear and periodic in
    the samples after the train's parameters (:class:`springdyn.valve.train.gas_force.GasForce`);
    0 without them.

    Parameters
    ----------
    vt : ndarray
        The train's parameters [mixed units], the force samples [N] after ``VT_SIZE``.
    {theta}
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


@_DOCS.fill
def lever_ratio_at(vt, theta):
    """The lever's ratio correction ``c = r_0 / r``, ``dc/dtheta`` [1/rad], the pivot factor
    ``n . d`` and its derivative [1/rad] at the cam angle ``theta`` [rad]: cubic Hermite and
    periodic in the table after the gas force's samples (:mod:`springdyn.valve.train.lever`).

    Parameters
    ----------
    vt : ndarray
        The train's parameters [mixed units], the table after ``VT_SIZE`` and the gas samples.
    {theta}
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


@_DOCS.fill
def hla_chamber(vt, y, yd, p, out, k, kv):
    """The adjuster's chamber, plunger spring and travel stops (:mod:`springdyn.valve.train.hla`).

    The plunger's collapse ``y`` (its travel into the body from the initial position, the
    direction that loses valve lift) and collapse rate ``yd``; the chamber pressure ``p``
    [Pa, absolute].  The chamber follows oil continuity
    (:func:`springdyn.valve.train.hla.chamber_pressure_rate`) with the check valve as an orifice and
    laminar leakage with the Couette drag of the moving plunger; it holds at the cavitation
    pressure (:data:`.layout.P_CAVITATION`).  Writes ``dp/dt`` [Pa/s] and the flows in and out
    [m^3/s] into the adjuster's first-order states ``out[k + H_PRESSURE]``, ``out[k + H_INFLOW]``,
    ``out[k + H_LEAK]`` (zeros into their velocity slots from ``kv``) and returns the force that
    pushes the plunger out of its body [N]: the chamber's pressure above the supply, the plunger
    spring, less the travel stops and the plunger's damping.

    Parameters
    ----------
    {vt}
    y, yd : float
        Collapse [m] and its rate [m/s].
    p : float
        Chamber pressure, absolute [Pa].
    out : ndarray
        Receives the rates [Pa/s, m^3/s].
    k, kv : int
        Index of the adjuster's first state (``H_*`` from it) and of its velocity [-].
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
    q_in = orifice_flow(dp_cv, vt[VT_HLA_KCV])
    q_leak = vt[VT_HLA_G] * (p - ps) - vt[VT_HLA_DRAG] * yd
    volume = vt[VT_HLA_V0] - area * y
    beta = effective_bulk_modulus(p, vt[VT_HLA_BETA], vt[VT_HLA_AIR], vt[VT_HLA_N])
    dp = beta / volume * (area * yd + q_in - q_leak)
    if p <= P_CAVITATION and dp < 0.0:  # cavitation: the pressure holds
        dp = 0.0
    out[k + H_PRESSURE] = dp
    out[k + H_INFLOW] = q_in
    out[k + H_LEAK] = q_leak
    out[kv + H_PRESSURE] = 0.0
    out[kv + H_INFLOW] = 0.0
    out[kv + H_LEAK] = 0.0
    return (p - ps) * area + vt[VT_HLA_FS] - stop


@_DOCS.fill
def hla_forces(s, nm, nfree, vt, out):
    """The hydraulic lash adjuster at the finger follower's pivot (:mod:`springdyn.valve.train.hla`).

    States (:data:`.layout.TRAIN_STATES` of ``TRAIN_LEVER_HLA``, after the valve's and the lever
    tip's): the finger's pivot end ``y_a`` (``S_PIVOT``, its collapse direction positive), then
    the adjuster's from ``S_LEVER_HLA``: the plunger ``y_p`` in its fixed body and three
    first-order states, the chamber pressure ``p`` [Pa, absolute] and the oil volumes that
    entered through the check valve and left through the clearance since the start [m^3].  The socket (the finger on the plunger) is a unilateral contact; the plunger
    carries the socket force against the chamber (:func:`hla_chamber`).  Writes the
    derivatives of the adjuster's states into ``out`` and returns the socket force [N] on
    the finger's pivot end.

    Parameters
    ----------
    {s nm nfree vt out_hla}
    """
    h = nm + S_LEVER_HLA  # the adjuster's first state
    hv = nfree + h
    ya = s[nm + S_PIVOT]
    yp = s[h + H_PLUNGER]
    yad = s[nfree + nm + S_PIVOT]
    ypd = s[hv + H_PLUNGER]
    # the socket: the finger's pivot end on the plunger (compression only)
    pen = ya - yp
    sock = contact_force(pen, vt[VT_HLA_KS] * pen + vt[VT_HLA_CS] * (yad - ypd))
    f_out = hla_chamber(vt, yp - vt[VT_HLA_Y0], ypd, s[h + H_PRESSURE], out, h, hv)
    out[hv + H_PLUNGER] = (sock - f_out) / vt[VT_HLA_MP]
    out[h + H_PLUNGER] = ypd
    out[nm + S_PIVOT] = yad
    return sock


@_DOCS.fill
def bucket_hla_forces(s, nm, nfree, vt, out):
    """A hydraulic bucket tappet (:mod:`springdyn.valve.train.hla`): the adjuster inside the bucket.

    States (:data:`.layout.TRAIN_STATES` of ``TRAIN_BUCKET_HLA``, after the valve's ``z``): the
    bucket body ``y_b`` on the cam (``S_BUCKET``), then the adjuster's from ``S_BUCKET_HLA``: the
    plunger ``y_p`` on the valve stem (both in the valve's opening direction), the chamber
    pressure and the oil volumes in and out.  The chamber lies between body and
    plunger: the collapse is ``y_b - y_p`` from its initial value.  The plunger pushes the
    stem through a unilateral contact (the socket).  Writes the body's and the plunger's
    derivatives (the body's acceleration without the cam force, which the caller adds) and
    the chamber's, and returns the socket force on the valve [N].

    Parameters
    ----------
    {s nm nfree vt out_hla}
    """
    h = nm + S_BUCKET_HLA  # the adjuster's first state
    hv = nfree + h
    z = s[nm + S_VALVE]
    yb = s[nm + S_BUCKET]
    yp = s[h + H_PLUNGER]
    zd = s[nfree + nm + S_VALVE]
    ybd = s[nfree + nm + S_BUCKET]
    ypd = s[hv + H_PLUNGER]
    pen = yp - z  # the plunger on the stem tip (compression only)
    sock = contact_force(pen, vt[VT_HLA_KS] * pen + vt[VT_HLA_CS] * (ypd - zd))
    f_out = hla_chamber(vt, yb - yp - vt[VT_HLA_Y0], ybd - ypd, s[h + H_PRESSURE], out, h, hv)
    out[nm + S_BUCKET] = ybd
    out[h + H_PLUNGER] = ypd
    out[nfree + nm + S_BUCKET] = -f_out / vt[VT_HLA_MA]  # the cam's force follows (bucket_hla_rhs)
    out[hv + H_PLUNGER] = (f_out - sock) / vt[VT_HLA_MP]
    return sock


@_DOCS.fill
def spring_rhs(t, s, m, omega, vt, out, extra):
    """Right-hand side of the spring alone: the retainer end follows the cam, ``u_(N+1) = h(omega t)``.

    Parameters
    ----------
    {t}
    s : ndarray
        State [m, m/s].
    {m omega}
    vt : None or ndarray
        Not read [-].
    {out extra}
    """
    nm = m.masses.shape[0]
    lift, slope = cam_at(omega * t, m.cam_h, m.cam_dh, m.cam_ddh, m.dth)
    dlift = slope * omega
    chain_forces(s, m, nm, lift, dlift, out, extra)
    if extra.shape[0] > 0:  # (the records are called, not inlined: see _RECORDS)
        ne = m.laws.shape[0]
        _record_tail(extra, ne, nm, lift, dlift, 0.0, 0.0, lift, 1.0)
        _record_no_hla(extra, ne, nm)


class CamDrive(NamedTuple):
    """The cam as the valve train sees it at one instant (an argument of the train's equations)."""

    angle: float  #: cam angle [rad]
    speed: float  #: cam speed [rad/s]
    lift: float  #: lobe lift [m]
    rate: float  #: lobe lift rate [m/s]


def contact_force(pen, raw):
    """The force of a unilateral contact [N]: its spring-damper force while pressed and pushing.

    Parameters
    ----------
    pen : float
        Penetration [m] (positive in contact).
    raw : float
        The contact's spring-damper force ``k pen + c pen'`` [N].
    """
    if pen > 0.0:
        return raw if raw > 0.0 else 0.0
    return 0.0


def seat_force(vt, z, zd):
    """The valve-seat force [N] on the valve body: compression only, below the seat (``z < 0``).

    Parameters
    ----------
    vt : ndarray
        The train's parameters [N/m, N s/m] (``VT_K_SEAT``, ``VT_C_SEAT``).
    z, zd : float
        Valve lift [m] and velocity [m/s].
    """
    f_seat = 0.0
    if z < 0.0:
        f_seat = -vt[VT_K_SEAT] * z - vt[VT_C_SEAT] * zd
        if f_seat < 0.0:
            f_seat = 0.0
    return f_seat


@_DOCS.fill
def tip_force(s, nm, nfree, vt):
    """The lever's valve-side tip on the valve (the lash here): force [N] and signed gap [m].

    Parameters
    ----------
    s : ndarray
        State [m, m/s]: valve ``S_VALVE`` and lever tip ``S_LEVER`` after the chain's masses.
    {nm nfree}
    vt : ndarray
        The train's parameters [N/m, N s/m, m] (``VT_K_TIP``, ``VT_C_TIP``, ``VT_LASH``).
    """
    pen_t = s[nm + S_LEVER] - s[nm + S_VALVE] - vt[VT_LASH]
    raw_t = vt[VT_K_TIP] * pen_t + vt[VT_C_TIP] * (s[nfree + nm + S_LEVER] - s[nfree + nm + S_VALVE])
    return contact_force(pen_t, raw_t), min(pen_t, raw_t / vt[VT_K_TIP])


@_DOCS.fill
def lever_links(s, nm, nfree, vt, cam, out, ya, yad):
    """A lever (finger follower or rocker arm) between the cam and the valve, its pivot end at ``ya``.

    The follower rides on the lever: the cam contact at the follower, the tip contact at the
    valve (:func:`tip_force`).  A drawn lever (``VT_GEOM``, :mod:`springdyn.valve.train.lever`)
    has the ratio correction ``c = r_0 / r(theta)`` and the pivot's share ``n . d`` of the
    contact normal from its table (:func:`lever_ratio_at`), its mass at the tip from its
    inertia (:func:`lever_mass`); the constant-ratio lever has 1, 1 and ``VT_M_LEVER``.
    Writes the lever tip's derivatives (``S_LEVER``).

    Parameters
    ----------
    s : ndarray
        State [m, m/s].
    {nm}
    nfree : int
        Degrees of freedom [-].
    vt : ndarray
        The train's parameters [kg, N/m, N s/m, m, -] (layout ``VT_*``).
    {cam out}
    ya, yad : float
        The pivot end's collapse [m] and its rate [m/s] (0 on a fixed pivot).

    Returns
    -------
    f_cam, f_valve, gap, c, kap : float
        Cam and tip contact forces [N], the smallest signed gap of the two [m], the ratio
        correction and the pivot factor [-].
    """
    zr = s[nm + S_LEVER]
    zrd = s[nfree + nm + S_LEVER]
    f_valve, gap = tip_force(s, nm, nfree, vt)
    r = vt[VT_RATIO]
    c = 1.0
    dc = 0.0
    kap = 1.0
    dkap = 0.0
    if vt[VT_GEOM] > 0.5:
        c, dc, kap, dkap = lever_ratio_at(vt, cam.angle)
    thd = cam.speed
    q = cam.lift - (zr - ya) / r
    pen = c * q - kap * ya
    raw = vt[VT_K_CAM] * pen + vt[VT_C_CAM] * (
        c * (cam.rate - (zrd - yad) / r) + dc * thd * q - kap * yad - dkap * thd * ya
    )
    f_cam = contact_force(pen, raw)
    gap = min(gap, min(pen, raw / vt[VT_K_CAM]))
    m_lever, dm_lever = lever_mass(vt, zr - ya)
    f_lever = f_cam * c / r - 0.5 * dm_lever * (zrd - yad) * (zrd - yad)
    out[nfree + nm + S_LEVER] = (f_lever - f_valve) / m_lever
    out[nm + S_LEVER] = zrd
    return f_cam, f_valve, gap, c, kap


@_DOCS.fill
def direct_acting_rhs(s, nm, nfree, vt, cam, out, extra):
    """The direct-acting train (``TRAIN_DIRECT``): the cam on the valve body, the lash at the cam.

    Each ``*_rhs`` of a kind of train has these parameters and returns: it writes the
    derivatives of the train's states other than the valve's (none here) and returns the
    forces on the valve body, which :func:`train_rhs` adds.

    Parameters
    ----------
    s : ndarray
        State [m, m/s]: the chain's, then the train's (:data:`.layout.TRAIN_STATES`).
    nm : int
        Chain masses [-]: the train's states start at ``s[nm]``.
    {nfree}
    vt : ndarray
        The train's parameters [kg, N/m, N s/m, m, -] (layout ``VT_*``).
    {cam out}
    extra : ndarray
        Empty, or the extra outputs [N, m, m/s, Pa, m^3] (:func:`.layout.extra_layout`; an adjuster's).

    Returns
    -------
    f_cam : float
        Cam contact force [N].
    f_valve : float
        Force of the train on the valve body [N].
    gap : float
        The smallest signed gap of the train's links [m] (positive in contact).
    """
    pen = cam.lift - s[nm + S_VALVE] - vt[VT_LASH]
    raw = vt[VT_K_CAM] * pen + vt[VT_C_CAM] * (cam.rate - s[nfree + nm + S_VALVE])
    f_cam = contact_force(pen, raw)
    return f_cam, f_cam, min(pen, raw / vt[VT_K_CAM])


@_DOCS.fill
def lever_rhs(s, nm, nfree, vt, cam, out, extra):
    """A finger follower or rocker arm on a fixed pivot (``TRAIN_LEVER``), constant-ratio or drawn.

    States: valve, lever tip (:func:`lever_links`).

    Parameters
    ----------
    {kind_args}

    Returns
    -------
    {kind_returns}
    """
    f_cam, f_valve, gap, c, kap = lever_links(s, nm, nfree, vt, cam, out, 0.0, 0.0)
    return f_cam, f_valve, gap


@_DOCS.fill
def lever_hla_rhs(s, nm, nfree, vt, cam, out, extra):
    """A finger follower on a hydraulic lash adjuster (``TRAIN_LEVER_HLA``): its pivot end moves.

    States: valve, lever tip, the pivot end, then the adjuster's (:func:`hla_forces`).  The
    pivot end carries the cam force's share ``n . d - c / r`` against the socket.

    Parameters
    ----------
    {hla_kind_args}

    Returns
    -------
    {kind_returns}
    """
    ya = s[nm + S_PIVOT]
    yad = s[nfree + nm + S_PIVOT]
    f_cam, f_valve, gap, c, kap = lever_links(s, nm, nfree, vt, cam, out, ya, yad)
    sock = hla_forces(s, nm, nfree, vt, out)
    out[nfree + nm + S_PIVOT] = (f_cam * (kap - c / vt[VT_RATIO]) - sock) / vt[VT_HLA_MA]
    if extra.shape[0] > 0:
        h = nm + S_LEVER_HLA
        _record_hla(extra, s, h, vt, s[h + H_PLUNGER] - vt[VT_HLA_Y0], sock)
    return f_cam, f_valve, gap


@_DOCS.fill
def pushrod_rhs(s, nm, nfree, vt, cam, out, extra):
    """An OHV pushrod train (``TRAIN_PUSHROD``): the lifter on the cam, the pushrod to the rocker.

    States: valve, rocker tip, lifter.

    Parameters
    ----------
    {kind_args}

    Returns
    -------
    {kind_returns}
    """
    zr = s[nm + S_LEVER]
    zrd = s[nfree + nm + S_LEVER]
    zf = s[nm + S_LIFTER]
    zfd = s[nfree + nm + S_LIFTER]
    r = vt[VT_RATIO]
    f_valve, gap = tip_force(s, nm, nfree, vt)
    pen = cam.lift - zf
    raw = vt[VT_K_CAM] * pen + vt[VT_C_CAM] * (cam.rate - zfd)
    f_cam = contact_force(pen, raw)
    xp = zf - zr / r
    raw_p = vt[VT_K_PUSH] * xp + vt[VT_C_PUSH] * (zfd - zrd / r)
    f_push = contact_force(xp, raw_p)
    gap = min(gap, min(min(pen, raw / vt[VT_K_CAM]), min(xp, raw_p / vt[VT_K_PUSH])))
    out[nm + S_LIFTER] = zfd
    out[nfree + nm + S_LIFTER] = (f_cam - f_push) / vt[VT_M_LIFTER]
    out[nfree + nm + S_LEVER] = (f_push / r - f_valve) / vt[VT_M_LEVER]
    out[nm + S_LEVER] = zrd
    return f_cam, f_valve, gap


@_DOCS.fill
def bucket_hla_rhs(s, nm, nfree, vt, cam, out, extra):
    """A hydraulic bucket tappet (``TRAIN_BUCKET_HLA``): the cam on the bucket body, the
    adjuster's plunger on the stem (:func:`bucket_hla_forces`).

    States: valve, bucket body, then the adjuster's.

    Parameters
    ----------
    {hla_kind_args}

    Returns
    -------
    f_cam, f_valve, gap : float
        Cam contact force [N], force on the valve (the socket's) [N], smallest signed gap [m].
    """
    h = nm + S_BUCKET_HLA
    yb = s[nm + S_BUCKET]
    pen = cam.lift - yb
    raw = vt[VT_K_CAM] * pen + vt[VT_C_CAM] * (cam.rate - s[nfree + nm + S_BUCKET])
    f_cam = contact_force(pen, raw)
    f_valve = bucket_hla_forces(s, nm, nfree, vt, out)
    out[nfree + nm + S_BUCKET] += f_cam / vt[VT_HLA_MA]
    pen_s = s[h + H_PLUNGER] - s[nm + S_VALVE]
    raw_s = vt[VT_HLA_KS] * pen_s + vt[VT_HLA_CS] * (s[nfree + h + H_PLUNGER] - s[nfree + nm + S_VALVE])
    gap = min(min(pen, raw / vt[VT_K_CAM]), min(pen_s, raw_s / vt[VT_HLA_KS]))
    if extra.shape[0] > 0:
        _record_hla(extra, s, h, vt, yb - s[h + H_PLUNGER] - vt[VT_HLA_Y0], f_valve)
    return f_cam, f_valve, gap


@_DOCS.fill
def train_rhs(t, s, m, omega, vt, out, extra):
    """Right-hand side of the spring in its valve train: node N + 1 is the valve body, and the
    train's links (cam, lever tip, pushrod, valve seat) are unilateral.

    The kind of train (``vt[VT_KIND]``, ``TRAIN_*`` of :mod:`.layout`) chooses its equations,
    one function each: :func:`direct_acting_rhs`, :func:`lever_rhs`, :func:`lever_hla_rhs`,
    :func:`pushrod_rhs`, :func:`bucket_hla_rhs`; a code of no kind is an error.  Here: the
    cam, the chain, the valve seat and the valve body, which all kinds share.

    Parameters
    ----------
    {t}
    s : ndarray
        State: the chain's, then the train's degrees of freedom [m, m/s].
    {m omega}
    vt : ndarray (VT_SIZE,)
        An enabled valve train's parameters [kg, N/m, N s/m, m, -] (layout ``VT_*``).
    {out extra}
    """
    nm = m.masses.shape[0]
    nfree = nm + int(vt[VT_DOF])
    kind = int(vt[VT_KIND])
    # the cam angle and speed: constant speed, or a speed ramp of acceleration alpha
    alpha = vt[VT_ALPHA]
    theta = omega * t + 0.5 * alpha * t * t
    speed = omega + alpha * t
    lift, slope = cam_at(theta, m.cam_h, m.cam_dh, m.cam_ddh, m.dth)
    dlift = slope * speed
    cam = CamDrive(theta, speed, lift, dlift)
    z = s[nm + S_VALVE]
    zd = s[nfree + nm + S_VALVE]
    f_spring = chain_forces(s, m, nfree, z, zd, out, extra)
    if extra.shape[0] > 0:  # an adjuster overwrites them
        _record_no_hla(extra, m.laws.shape[0], nm)
    f_seat = seat_force(vt, z, zd)
    if kind == TRAIN_DIRECT:
        f_cam, f_valve, gap = direct_acting_rhs(s, nm, nfree, vt, cam, out, extra)
    elif kind == TRAIN_LEVER:
        f_cam, f_valve, gap = lever_rhs(s, nm, nfree, vt, cam, out, extra)
    elif kind == TRAIN_PUSHROD:
        f_cam, f_valve, gap = pushrod_rhs(s, nm, nfree, vt, cam, out, extra)
    elif kind == TRAIN_LEVER_HLA:
        f_cam, f_valve, gap = lever_hla_rhs(s, nm, nfree, vt, cam, out, extra)
    elif kind == TRAIN_BUCKET_HLA:
        f_cam, f_valve, gap = bucket_hla_rhs(s, nm, nfree, vt, cam, out, extra)
    else:
        raise ValueError(UNKNOWN_KIND)
    out[nm + S_VALVE] = zd
    # the gas force pushes the valve towards its seat (springdyn.valve.train.gas_force)
    out[nfree + nm + S_VALVE] = (f_valve + f_seat - f_spring - gas_force_at(vt, theta)) / vt[VT_MASS]
    if extra.shape[0] > 0:
        _record_tail(extra, m.laws.shape[0], nm, lift, dlift, f_cam, f_seat, z, gap)


def _contact(k, c, pen, rate):
    """A unilateral contact's force [N], vectorised: stiffness ``k`` [N/m], damping ``c``
    [N s/m], penetration ``pen`` [m] and its rate ``rate`` [m/s] (the NumPy twin of
    :func:`contact_force`)."""
    return np.where(pen > 0, np.maximum(k * pen + c * rate, 0.0), 0.0)


@_DOCS.fill
def direct_acting_response(vt, lift, dlift, u, v, theta, omega) -> dict:
    """The contact forces of a direct-acting train (NumPy twin of :func:`direct_acting_rhs`).

    Each ``*_response`` of a kind of train has these parameters and returns the outputs of
    its kind: the cam contact force, and an adjuster's.

    Parameters
    ----------
    vt : ndarray (VT_SIZE,)
        The train's parameters [kg, N/m, N s/m, m, -] (layout ``VT_*``).
    {lift_dlift}
    u, v : ndarray (..., dof, n_t)
        The train's positions [m, Pa, m^3] and velocities [m/s] (:data:`.layout.TRAIN_STATES`).
    theta : ndarray (n_t,) or None
        Cam angles [rad].
    omega : float or ndarray (..., 1) or None
        Cam speed [rad/s].

    Returns
    -------
    dict
        ``cam_contact_force`` [N].
    """
    cam = _contact(vt[VT_K_CAM], vt[VT_C_CAM], lift - u[..., S_VALVE, :] - vt[VT_LASH], dlift - v[..., S_VALVE, :])
    return dict(cam_contact_force=cam)


def _lever_cam_response(vt, lift, dlift, u, v, theta, omega, ya, yad):
    """The cam contact force [N] on a lever whose pivot end is at ``ya`` [m] moving at ``yad``
    [m/s] (NumPy twin of the cam contact of :func:`lever_links`; other parameters as for
    :func:`direct_acting_response`)."""
    r = vt[VT_RATIO]
    c, dc, kap, dkap = 1.0, 0.0, 1.0, 0.0
    if vt[VT_GEOM] > 0.5:
        c, dc, kap, dkap = np.array([lever_ratio_at(vt, th) for th in np.ravel(theta)]).T
    thd = 0.0 if omega is None else omega
    q = lift - (u[..., S_LEVER, :] - ya) / r
    rate = c * (dlift - (v[..., S_LEVER, :] - yad) / r) + dc * thd * q - kap * yad - dkap * thd * ya
    return _contact(vt[VT_K_CAM], vt[VT_C_CAM], c * q - kap * ya, rate)


def lever_response(vt, lift, dlift, u, v, theta, omega) -> dict:
    """The contact forces of a lever on a fixed pivot (NumPy twin of :func:`lever_rhs`;
    parameters and returns of :func:`direct_acting_response`)."""
    return dict(cam_contact_force=_lever_cam_response(vt, lift, dlift, u, v, theta, omega, 0.0, 0.0))


def pushrod_response(vt, lift, dlift, u, v, theta, omega) -> dict:
    """The contact forces of a pushrod train: the lifter on the cam (NumPy twin of
    :func:`pushrod_rhs`; parameters and returns of :func:`direct_acting_response`)."""
    cam = _contact(vt[VT_K_CAM], vt[VT_C_CAM], lift - u[..., S_LIFTER, :], dlift - v[..., S_LIFTER, :])
    return dict(cam_contact_force=cam)


def _hla_response(vt, u, h, collapse, socket) -> dict:
    """An adjuster's outputs from its first state ``h`` (``S_LEVER_HLA`` or ``S_BUCKET_HLA``):
    ``hla_collapse`` [m], ``hla_pressure`` [Pa above the supply], ``socket_force`` [N],
    ``hla_inflow`` and ``hla_leak`` [m^3]."""
    return dict(
        hla_collapse=collapse,
        hla_pressure=u[..., h + H_PRESSURE, :] - vt[VT_HLA_PS],
        socket_force=socket,
        hla_inflow=u[..., h + H_INFLOW, :],
        hla_leak=u[..., h + H_LEAK, :],
    )


def lever_hla_response(vt, lift, dlift, u, v, theta, omega) -> dict:
    """The contact forces of a finger follower on an adjuster and the adjuster's outputs
    (NumPy twin of :func:`lever_hla_rhs`; parameters of :func:`direct_acting_response`).

    Returns
    -------
    dict
        ``cam_contact_force`` [N], ``hla_collapse`` [m], ``hla_pressure`` [Pa above the
        supply], ``socket_force`` [N], ``hla_inflow`` and ``hla_leak`` [m^3].
    """
    ya, yad = u[..., S_PIVOT, :], v[..., S_PIVOT, :]
    cam = _lever_cam_response(vt, lift, dlift, u, v, theta, omega, ya, yad)
    h = S_LEVER_HLA
    plunger, plunger_v = u[..., h + H_PLUNGER, :], v[..., h + H_PLUNGER, :]
    socket = _contact(vt[VT_HLA_KS], vt[VT_HLA_CS], ya - plunger, yad - plunger_v)
    return dict(cam_contact_force=cam, **_hla_response(vt, u, h, plunger - vt[VT_HLA_Y0], socket))


def bucket_hla_response(vt, lift, dlift, u, v, theta, omega) -> dict:
    """The contact forces of a hydraulic bucket and the adjuster's outputs (NumPy twin of
    :func:`bucket_hla_rhs`; parameters and returns of :func:`lever_hla_response`)."""
    body, body_v = u[..., S_BUCKET, :], v[..., S_BUCKET, :]
    h = S_BUCKET_HLA
    plunger, plunger_v = u[..., h + H_PLUNGER, :], v[..., h + H_PLUNGER, :]
    cam = _contact(vt[VT_K_CAM], vt[VT_C_CAM], lift - body, dlift - body_v)
    socket = _contact(vt[VT_HLA_KS], vt[VT_HLA_CS], plunger - u[..., S_VALVE, :], plunger_v - v[..., S_VALVE, :])
    return dict(cam_contact_force=cam, **_hla_response(vt, u, h, body - plunger - vt[VT_HLA_Y0], socket))


#: The NumPy twin of each kind's equations (:func:`train_response`).
RESPONSES = {
    TRAIN_DIRECT: direct_acting_response,
    TRAIN_LEVER: lever_response,
    TRAIN_PUSHROD: pushrod_response,
    TRAIN_LEVER_HLA: lever_hla_response,
    TRAIN_BUCKET_HLA: bucket_hla_response,
}


@_DOCS.fill
def train_response(vt: np.ndarray, lift, dlift, u, v, theta=None, omega=None) -> dict:
    """Contact forces of the valve train from its states (vectorised NumPy).

    The NumPy twin of the contact laws of :func:`train_rhs` (above), vectorised over
    output samples for the reference backend's outputs; the tests compare the two.  The
    kind of train (``vt[VT_KIND]``) chooses its function (:data:`RESPONSES`).

    Parameters
    ----------
    vt : ndarray (VT_SIZE,)
        Engine parameters of the train [kg, N/m, N s/m, m, -] (layout ``VT_*``, :meth:`ValveTrain.kernel_parameters`).
    {lift_dlift}
    u, v : ndarray (..., dof, n_t)
        The train's positions [m] and velocities [m/s]: valve, lever tip, lifter, ...
        (:data:`.layout.TRAIN_STATES`).
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
    respond = RESPONSES.get(kind_of(vt))
    if respond is None:
        raise ValueError(UNKNOWN_KIND)
    z, zd = u[..., S_VALVE, :], v[..., S_VALVE, :]
    seat = np.where(z < 0, np.maximum(-vt[VT_K_SEAT] * z - vt[VT_C_SEAT] * zd, 0.0), 0.0)
    out = dict(cam_contact_force=None, valve_seat_force=seat, valve_lift=z)
    out.update(respond(vt, lift, dlift, u, v, theta, omega))
    return out


@_DOCS.fill
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
        masses, as its kind has them (:data:`.layout.TRAIN_STATES`): valve, lever tip
        (lever, pushrod), lifter (pushrod), ...
    {out}
    extra : ndarray
        Empty for none, or an array of ``extra_layout(N)["size"]`` that receives the element
        forces [N] and compressions [m], then (offsets ``X_*``) lift [m] and lift rate
        [m/s], cam contact and valve-seat forces [N], the displacement of the retainer end
        [m], of the masses [m] and (offsets ``XT_*``) the signed cam-contact gap [m]
        (positive in contact) and an adjuster's outputs.
    """
    if vt is not None:
        if vt[VT_ENABLED] > 0.5:
            train_rhs(t, s, m, omega, vt, out, extra)
            return
    spring_rhs(t, s, m, omega, vt, out, extra)


#: The records of the extra outputs, called (only where there are outputs), not inlined: inlined
#: into every right-hand side (the train's, the spring's, the step's and rhs_call's) their
#: stores made a sixth of the engine's code for numba to type and compile.
_RECORDS = ("_record_tail", "_record_hla", "_record_no_hla", "_record_chains")

#: The functions with compiled twins, callees first (:func:`springdyn.numerics.jit.twins`).
_TWINNED = (
    "hermite5",
    "cam_at",
    "element_force",
    "damper_friction",
    "_damper_row",
    "_record_chains",
    "one_chain_forces",
    "pack_chain_forces",
    "_record_tail",
    "_record_hla",
    "_record_no_hla",
    "gas_force_at",
    "lever_mass",
    "effective_bulk_modulus",
    "orifice_flow",
    "contact_force",
    "hla_chamber",
    "hla_forces",
    "bucket_hla_forces",
    "seat_force",
    "tip_force",
    "lever_links",
    "direct_acting_rhs",
    "lever_rhs",
    "lever_hla_rhs",
    "pushrod_rhs",
    "bucket_hla_rhs",
    "spring_rhs",
    "train_rhs",
)


def _engine_twins(chains, suffix: str) -> dict:
    """The compiled twins of the equations with ``chains`` as :func:`chain_forces`: one
    spring's chain inlined (``chains`` None: :func:`one_chain_forces`' twin), or a compiled
    kernel (a spring pack's, :data:`_PACK_CHAINS`).  Its kernels' names end in ``suffix``
    (each variant its own cache entries)."""
    made = twins(globals(), _TWINNED, fastmath=FASTMATH)
    g = made["__globals__"]
    g["chain_forces"] = made["one_chain_forces"] if chains is None else chains
    # the adjusters' equations are called, not inlined (the finger's with its kind, which holds a
    # second copy of the lever's): the integration step evaluates the right-hand side at every
    # stage, and inlining these rarely used branches there (and into rhs_call) costs seconds of
    # the train engine's compilation (measured 2.4 s for the finger's adjuster alone); the same
    # for the drawn lever's table (springdyn.valve.train.lever), used by lever trains only
    for name in ("lever_hla_rhs", "bucket_hla_forces", "lever_ratio_at", *_RECORDS):
        g[name] = kernel(_named(rebind(globals()[name], g), suffix), fastmath=FASTMATH, nogil=True, _nrt=False)
    made["rhs_call"] = kernel(_named(rebind(chain_rhs, g), suffix), fastmath=FASTMATH, nogil=True, _nrt=False)
    return made


def _named(fn, suffix: str):
    """``fn`` with ``suffix`` on its qualified name (the kernel's cache entry)."""
    fn.__qualname__ += suffix
    return fn


#: One spring's engine: :func:`one_chain_forces` inlined wherever :func:`chain_forces` is called.
_TWINS = _engine_twins(None, "")
#: A spring pack's chains, compiled on their own and called (inlined into every stage of the
#: step, their loops made numba's inliner warn of variables out of scope and cost compile time;
#: their work per call is far more than a call).
_PACK_CHAINS = kernel(
    _named(rebind(pack_chain_forces, _TWINS["__globals__"]), "_pack"), fastmath=FASTMATH, nogil=True, _nrt=False
)
#: A spring pack's engine: the same equations calling :data:`_PACK_CHAINS`; compiled only when a
#: pack runs (a model whose ``damper`` is an array: :func:`rhs_kernels`), so a single spring's
#: kernels hold none of its code.
_PACK_TWINS = _engine_twins(_PACK_CHAINS, "_pack")

#: :func:`spring_rhs` and :func:`train_rhs` compiled to be inlined into the integration step
#: (their one hot call site, :mod:`.stepping`, chooses by the type of ``vt``), one spring's and a
#: spring pack's.
spring_rhs_hot = _TWINS["spring_rhs"]
train_rhs_hot = _TWINS["train_rhs"]
spring_rhs_hot_pack = _PACK_TWINS["spring_rhs"]
train_rhs_hot_pack = _PACK_TWINS["train_rhs"]
#: The cam table's interpolant compiled to be inlined (:mod:`.static_force`, the monitor).
cam_at_hot = _TWINS["cam_at"]
#: :func:`chain_rhs` compiled as a function of its own (outputs, monitor, static checks): one
#: spring's, and a spring pack's; :func:`rhs_kernel` chooses by the model.
rhs_call = _TWINS["rhs_call"]
rhs_call_pack = _PACK_TWINS["rhs_call"]


def rhs_kernel(m):
    """The compiled :func:`chain_rhs` for the model ``m``: :data:`rhs_call` for one spring
    (``m.damper`` None), :data:`rhs_call_pack` for a spring pack.

    Parameters
    ----------
    m : EngineModel
        The chain and cam arrays [kg, m, N, N s/m, rad].
    """
    return rhs_call if m.damper is None else rhs_call_pack
