"""Dynamics of the CFCS, Eqs. (11)-(25) of the CFCS paper.

One degree of freedom, the crank angle theta2.  Lagrange's equation (10) with
``T = M(theta2) theta2'^2 / 2`` and ``V = K3 theta_K3^2 / 2`` gives::

    M theta2'' + M'/2 theta2'^2 + dV/dtheta2 + tau_d = F G

with ``G = dx/dtheta2`` (minus Eq. (25)), F the slider force (positive in compression)
and tau_d the dissipative torques opposing the motion.  The inverse problem (slider
driven along x(t)) solves it for F (correction CFCS-1 of docs/references.md corrects the signs of
Eqs. (20)/(24)); the forward problem integrates it for theta2(t) under a given force.
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError, SolverError
from .kinematics import (
    crank_rates,
    deflection_from_theta2,
    slider_jacobian,
    spring_angle_rate_derivative,
    spring_angle_rate_ratio,
)
from .statics import (
    axial_force_torque,
    dissipative_torque,
    frozen_jacobian,
    pin_friction_torque,
    spring_energy,
    spring_torque,
    static_force,
)

__all__ = [
    "generalized_mass",
    "generalized_mass_eq19",
    "generalized_mass_derivative",
    "kinetic_energy",
    "inertia_force",
    "TOGGLE_FLOOR",
    "drive_force_components",
    "toggle_inertia_limit",
    "inverse_dynamics",
    "crank_terms",
    "forward_rhs",
    "integrate_forward",
    "energy",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    theta2 : float or array_like
        Crank angle theta2 [rad], 0 at the toggle.
    r2 : float
        Crank length r2 [m].
    r3 : float
        Coupler length r3 [m], longer than r2.
    m2 : float
        Crank mass [kg].
    m3 : float
        Coupler mass [kg].
    ms : float
        Slider mass [kg].
    theta2dot : float or array_like
        Crank angular speed [rad/s].
    sign_smoothing : float
        Speed v_s of the smoothed Coulomb sign tanh(v/v_s) [rad/s].
    p : CFCSParams
        The mechanism.
    rtol : float
        Relative tolerance [-].
    """,
    p_values="p : mapping\n    Mechanism values as in :func:`drive_force_components` (SI).",
)


def generalized_mass(theta2, m2, m3, ms, r2, r3):
    """Generalized mass ``M(theta2)`` [kg*m^2], compact form of Eq. (19) (docs/references.md).

    ``M = m2 r2^2/3 + m3 [r2^2 s^2 (1 + u) + r3^2 u^2 / 3] + ms r2^2 s^2 (1 + u)^2``
    with ``s = sin theta2`` and ``u = r2 cos theta2 / D``; slender links
    (``I_Ci = m_i r_i^2 / 12``, Eq. (16)).  Equal to the printed bracket of Eq. (19),
    which the notes confirm is correct (see :func:`generalized_mass_eq19`).

    Parameters
    ----------
    theta2 : float or array
        Crank angle [rad].
    m2, m3, ms : float
        Crank, coupler and slider masses [kg].
    r2, r3 : float
        Crank and coupler lengths [m].
    """
    s = np.sin(theta2)
    u = spring_angle_rate_ratio(theta2, r2, r3)
    return (
        m2 * r2 * r2 / 3.0
        + m3 * (r2 * r2 * s * s * (1.0 + u) + r3 * r3 * u * u / 3.0)
        + ms * r2 * r2 * s * s * (1.0 + u) ** 2
    )


@_DOCS.fill
def generalized_mass_eq19(theta2, m2, m3, ms, r2, r3):
    """The coefficient of theta2'' in Eq. (19) of the CFCS paper, term by term as printed [kg*m^2].

    Kept separate from :func:`generalized_mass` so tests can check the compact form
    against the printed one.

    Parameters
    ----------
    {theta2 m2 m3 ms r2 r3}
    """
    s, c = np.sin(theta2), np.cos(theta2)
    d2 = r3 * r3 - r2 * r2 * s * s
    d = np.sqrt(d2)
    ic2 = m2 * r2 * r2 / 12.0  # Eq. (16)
    ic3 = m3 * r3 * r3 / 12.0
    return (
        m2 * (0.25 * r2 * r2)
        + m3 * (r2**3 * s * s * c / d + 0.25 * r2 * r2 * r3 * r3 * c * c / d2 + r2 * r2 * s * s)
        + ms * (r2**4 * s * s * c * c / d2 + 2.0 * r2**3 * s * s * c / d + r2 * r2 * s * s)
        + ic2
        + ic3 * r2 * r2 * c * c / d2
    )


@_DOCS.fill
def generalized_mass_derivative(theta2, m2, m3, ms, r2, r3):
    """``dM/dtheta2`` [kg*m^2/rad]; ``M'/2`` is the coefficient of theta2'^2 in Eq. (19).

    Differentiated from :func:`generalized_mass` with ``du/dtheta2`` of
    :func:`springdyn.cfcs.kinematics.spring_angle_rate_derivative` (docs/references.md: the
    velocity-squared coefficient is ``M'/2``).

    Parameters
    ----------
    {theta2 m2 m3 ms r2 r3}
    """
    s, c = np.sin(theta2), np.cos(theta2)
    u = spring_angle_rate_ratio(theta2, r2, r3)
    du = spring_angle_rate_derivative(theta2, r2, r3)
    return m3 * (r2 * r2 * (2.0 * s * c * (1.0 + u) + s * s * du) + 2.0 * r3 * r3 * u * du / 3.0) + ms * r2 * r2 * (
        2.0 * s * c * (1.0 + u) ** 2 + 2.0 * s * s * (1.0 + u) * du
    )


@_DOCS.fill
def kinetic_energy(theta2, theta2dot, m2, m3, ms, r2, r3):
    """``T = M(theta2) theta2'^2 / 2`` [J], Eq. (11) of the CFCS paper.

    Parameters
    ----------
    {theta2 theta2dot m2 m3 ms r2 r3}
    """
    return 0.5 * generalized_mass(theta2, m2, m3, ms, r2, r3) * theta2dot * theta2dot


@_DOCS.fill
def inertia_force(theta2, theta2dot, theta2ddot, jacobian, m2, m3, ms, r2, r3):
    """Slider force of the links' inertia ``(M th2'' + M'/2 th2'^2) / G`` [N] (Eq. (19) over G).

    Parameters
    ----------
    {theta2 theta2dot}
    theta2ddot : float or array_like
        Crank angular acceleration [rad/s^2].
    jacobian : float or array_like
        ``G = dx/dtheta2`` at ``theta2`` [m/rad] (0 at the toggle, where the result is 0/0).
    {m2 m3 ms r2 r3}
    """
    m = generalized_mass(theta2, m2, m3, ms, r2, r3)
    dm = generalized_mass_derivative(theta2, m2, m3, ms, r2, r3)
    return (m * theta2ddot + 0.5 * dm * theta2dot * theta2dot) / jacobian


#: Crank angle [rad] below which the exact inertia formula loses accuracy (0/0 at the toggle);
#: the inertia force there is replaced by its limit (:func:`inverse_dynamics`).
TOGGLE_FLOOR = 2e-3


def drive_force_components(
    x,
    xdot,
    xddot,
    *,
    r2,
    r3,
    m2,
    m3,
    ms,
    k3,
    pin_friction,
    friction_model,
    shear_angle,
    axial_force,
    slider_friction,
    theta2_cutoff,
    spring_force=None,
):
    """Slider force needed to drive the mechanism along x(t) (inverse dynamics) [N].

    ``F = (M th2'' + M'/2 th2'^2 + dV/dth2 + tau_CF + tau_AF) / G + F_slider sgn(x')``,
    positive in compression, dissipative terms against the motion: Eqs. (19)-(24) of
    the CFCS paper with the sign correction of correction CFCS-1 of docs/references.md.

    Treatment of the toggle (theta2 = 0, G = 0):

    - spring term: the exact static force, finite at the toggle (its closed-form limit);
    - dissipative terms: divided by the Jacobian frozen at ``G(theta2_cutoff)`` inside the
      zone ``theta2 < theta2_cutoff`` (:func:`springdyn.cfcs.statics.frozen_jacobian`);
    - inertia: exact.  It is finite at the toggle (the crank passes through it into the
      mirror branch, x(theta2) being even), but 0/0 at the instant itself: samples with
      ``theta2 < TOGGLE_FLOOR`` are flagged in ``at_toggle`` and their inertia force is
      not finite here; :func:`inverse_dynamics` replaces it by its limit.

    Parameters
    ----------
    x, xdot, xddot : arrays
        Slider deflection [m], velocity [m/s], acceleration [m/s^2].
    r2, r3, m2, m3, ms, k3 : float
        Link lengths [m], masses [kg], pivot stiffness [N*m/rad].
    pin_friction : float
        Coulomb torque C [N*m].
    friction_model : {"paper", "constant", "none"}
    shear_angle : float
        alpha [rad].
    axial_force : bool
        Include tau_AF.
    slider_friction : float
        Coulomb friction force of the slider [N].
    theta2_cutoff : float
        Toggle cut-off angle [rad] of the dissipative terms.
    spring_force : callable, optional
        ``spring_force(x) -> F`` [N], the quasi-static force of another flexure model (the
        elastica of :mod:`springdyn.cfcs.beam`) used in place of the PRBM's static force, with
        the PRBM's inertia (see docs/cfcs.md for where this holds).

    Returns
    -------
    dict of arrays
        ``theta2``, ``theta2dot``, ``theta2ddot``, ``force_static``, ``force_inertia``,
        ``force_pin``, ``force_axial``, ``force_slider``, ``force`` [N], ``in_toggle_zone``
        (dissipative terms capped) and ``at_toggle`` (inertia from the limit).
    """
    th, thd, thdd, jac = crank_rates(x, xdot, xddot, r2, r3)
    f_static = static_force(th, k3, r2, r3) if spring_force is None else np.asarray(spring_force(x), dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        f_inertia = inertia_force(th, thd, thdd, jac, m2, m3, ms, r2, r3)
    at_toggle = th < TOGGLE_FLOOR
    f_inertia = np.where(at_toggle, np.nan, f_inertia)
    # x' and theta2' share their sign (G >= 0); a velocity at rounding level (turning points such as
    # sin(2 pi) ~ -2e-16) counts as zero, so the friction sign does not flicker between cycles
    xd = np.asarray(xdot, dtype=float)
    vscale = float(np.max(np.abs(xd))) if xd.size else 0.0
    sgn = np.where(np.abs(xd) <= 1e-12 * vscale, 0.0, np.sign(xd))
    jac_d = frozen_jacobian(th, r2, r3, theta2_cutoff)
    f_pin = sgn * pin_friction_torque(th, pin_friction, friction_model, r2, r3) / jac_d
    f_axial = sgn * axial_force_torque(f_static, shear_angle, r2, r3) / jac_d if axial_force else np.zeros_like(th)
    f_slider = sgn * slider_friction
    force = f_static + f_inertia + f_pin + f_axial + f_slider
    return dict(
        theta2=th,
        theta2dot=thd,
        theta2ddot=thdd,
        force_static=f_static,
        force_inertia=f_inertia,
        force_pin=f_pin,
        force_axial=f_axial,
        force_slider=f_slider,
        force=force,
        in_toggle_zone=th < theta2_cutoff,
        at_toggle=at_toggle,
    )


@_DOCS.fill
def toggle_inertia_limit(motion, t0, period, *, r2, r3, m2, m3, ms):
    """Inertia force [N] at an instant ``t0`` where the crank is at (or within TOGGLE_FLOOR of) the toggle.

    The inertia force is a smooth function of time through the toggle (the crank
    crosses into the mirror branch with finite angular velocity), so it is
    extrapolated from ``t0 +- delta`` and ``t0 +- 2 delta`` (fourth-order Richardson
    combination ``[4 (F(d) + F(-d)) - (F(2d) + F(-2d))] / 6``), with ``delta`` doubled from
    ``1e-4`` period until every point lies beyond ``2 TOGGLE_FLOOR``.  If the slider
    dwells at the toggle (no such delta up to period/16) the crank is at rest there and
    the inertia force is 0.

    Parameters
    ----------
    motion : callable
        ``motion(t) -> (x, x', x'')`` [m, m/s, m/s^2].
    t0, period : float
        Instant and period [s].
    {r2 r3 m2 m3 ms}
    """
    delta = 1e-4 * period
    while delta <= period / 16:
        tt = t0 + delta * np.array([-2.0, -1.0, 1.0, 2.0])
        x, xd, xdd = motion(tt)
        th, thd, thdd, jac = crank_rates(np.clip(x, 0.0, None), xd, xdd, r2, r3)
        if np.all(th >= 2 * TOGGLE_FLOOR):
            f = inertia_force(th, thd, thdd, jac, m2, m3, ms, r2, r3)
            return float((4.0 * (f[1] + f[2]) - (f[0] + f[3])) / 6.0)
        delta *= 2.0
    return 0.0


def inverse_dynamics(motion, t, period, *, theta2_cutoff, **p):
    """:func:`drive_force_components` along ``motion(t)``, with the inertia at the toggle from its limit.

    Parameters
    ----------
    motion : callable
        ``motion(t) -> (x, x', x'')``.
    t : array
        Times [s].
    period : float
        Period of the motion [s] (sets the extrapolation step).
    theta2_cutoff : float
        Toggle cut-off of the dissipative terms [rad].
    **p
        Mechanism values (see :func:`drive_force_components`).
    """
    x, xd, xdd = motion(np.asarray(t, dtype=float))
    x = np.asarray(x, dtype=float)
    c = drive_force_components(x, xd, xdd, theta2_cutoff=theta2_cutoff, **p)
    c["deflection"], c["velocity"] = x, np.asarray(xd, dtype=float)
    idx = np.flatnonzero(c["at_toggle"])
    if idx.size:
        geo = {k: p[k] for k in ("r2", "r3", "m2", "m3", "ms")}
        tt = np.atleast_1d(np.asarray(t, dtype=float))
        for i in idx:
            c["force_inertia"][i] = toggle_inertia_limit(motion, tt[i], period, **geo)
        c["force"] = c["force_static"] + c["force_inertia"] + c["force_pin"] + c["force_axial"] + c["force_slider"]
    return c


@_DOCS.fill
def crank_terms(theta2, theta2dot, p, sign_smoothing):
    """The mechanism's terms of Lagrange's equation at ``(theta2, theta2')``, dissipation smoothed.

    The one home of the crank's equation of motion without the drive, for the forward
    (:func:`forward_rhs`) and the driven (:func:`springdyn.cfcs.drive.driven_rhs`) problems:
    the slider's deflection ``x(theta2)`` and velocity ``x' = G theta2'``, ``M`` and ``M'``, the
    spring torque ``dV/dtheta2`` (the elastica's ``F_spring(x) G`` with ``p["spring_force"]``)
    and the dissipative torques with the Coulomb signs smoothed, ``sgn~(v) = tanh(v / v_s)``:
    ``tau_d sgn~(theta2')`` and ``F_slider sgn~(x') G`` (the slider's in units of ``theta2'``).

    Parameters
    ----------
    theta2 : float
        Crank angle [rad].
    theta2dot : float
        Crank speed [rad/s].
    {p_values sign_smoothing}

    Returns
    -------
    tuple of float
        ``G`` [m/rad], ``x`` [m], ``x'`` [m/s], ``M`` [kg*m^2], ``M'`` [kg*m^2/rad], the spring
        torque, the pin and axial-force torque and the slider friction torque [N*m].
    """
    th, thd = theta2, theta2dot
    r2, r3 = p["r2"], p["r3"]
    g = slider_jacobian(th, r2, r3)
    x = deflection_from_theta2(th, r2, r3)
    xdot = g * thd
    m = generalized_mass(th, p["m2"], p["m3"], p["ms"], r2, r3)
    dm = generalized_mass_derivative(th, p["m2"], p["m3"], p["ms"], r2, r3)
    spring = p.get("spring_force")
    f_spring = static_force(th, p["k3"], r2, r3) if spring is None else float(spring(x))
    torque = spring_torque(th, p["k3"], r2, r3) if spring is None else f_spring * g
    tau_d = dissipative_torque(
        th, f_spring, p["pin_friction"], p["friction_model"], p["shear_angle"], p["axial_force"], r2, r3
    )
    pin = tau_d * np.tanh(thd / sign_smoothing)
    slider = p["slider_friction"] * np.tanh(xdot / (sign_smoothing * max(r2, 1e-300))) * g
    return g, x, xdot, m, dm, torque, pin, slider


@_DOCS.fill
def forward_rhs(t, state, force_fn, p, sign_smoothing):
    """Right-hand side of the forward problem, state ``(theta2, theta2')``.

    ``M th2'' = F G - M'/2 th2'^2 - dV/dth2 - tau_d sgn~(th2') - F_slider sgn~(x') G``
    where ``sgn~(v) = tanh(v / v_s)`` smooths the Coulomb sign (v_s = ``sign_smoothing``
    [rad/s]; the slider velocity is ``G th2'``), the terms of :func:`crank_terms`.  No
    division by G: the forward problem passes through the toggle without a cut-off.

    Parameters
    ----------
    force_fn : callable
        ``force_fn(t, x, xdot) -> F`` [N], positive in compression.
    {p_values}
    t : float
        Time [s].
    state : ndarray
        State: crank angle [rad] and crank speed [rad/s].
    {sign_smoothing}
    """
    th, thd = state
    g, x, xdot, m, dm, torque, pin, slider = crank_terms(th, thd, p, sign_smoothing)
    f = force_fn(t, x, xdot)
    rhs = f * g - 0.5 * dm * thd * thd - torque - pin - slider
    return np.array([thd, rhs / m])


#: Right-hand-side budget of a forward run (about a minute of LSODA on one core).
MAX_FORWARD_CALLS = 2_000_000


class _Budget(Exception):
    """A run's right-hand-side budget is spent (at the time in ``args[0]``)."""


@_DOCS.fill
def integrate_crank(rhs_fn, y0, t_eval, args, *, rtol, atol, max_step=np.inf, budget, what, too_long, past_limit):
    """Integrate a crank's equations ``rhs_fn(t, y, *args)`` (state ``theta2, theta2', ...``)
    over ``t_eval`` with LSODA, stopping at the kinematic limit ``|theta2| = pi/2``: the one
    integration of the forward (:func:`integrate_forward`) and the driven
    (:func:`springdyn.cfcs.drive.integrate_driven`) problems.

    Parameters
    ----------
    rhs_fn : callable
        ``rhs_fn(t, y, *args)`` [rad/s, rad/s^2, ...].
    y0 : array_like
        Initial state [rad, rad/s, ...].
    t_eval : array_like
        Output times [s], increasing, at least two.
    args : tuple
        Extra arguments of ``rhs_fn``.
    {rtol}
    atol : float or array_like
        Absolute tolerances [rad, rad/s, ...].
    max_step : float
        Largest step [s].
    budget : int
        Most right-hand-side calls [-].
    what : str
        The problem's name in messages ("forward dynamics").
    too_long, past_limit : str
        What a spent budget and the kinematic limit mean, for the messages.

    Returns
    -------
    ndarray
        The state at ``t_eval``, shape (len(y0), len(t_eval)).
    """
    t_eval = np.asarray(t_eval, dtype=float)
    if t_eval.size < 2 or np.any(np.diff(t_eval) <= 0):
        raise InputError(f"{what}: the time grid must hold at least two increasing times")

    def limit(t, y, *args):
        return np.pi / 2 - abs(y[0]) - 1e-9

    limit.terminal = True
    calls = [0]

    def rhs(t, y, *args):
        calls[0] += 1
        if calls[0] > budget:
            raise _Budget(t)
        return rhs_fn(t, y, *args)

    try:
        sol = solve_ivp(
            rhs,
            (t_eval[0], t_eval[-1]),
            np.asarray(y0, dtype=float),
            method="LSODA",
            t_eval=t_eval,
            args=args,
            rtol=rtol,
            atol=atol,
            max_step=max_step,
            events=limit,
        )
    except _Budget as exc:
        raise SolverError(
            f"{what}: {budget} right-hand sides reached at t = {exc.args[0]:.6g} s of {t_eval[-1]:.6g} s; {too_long}"
        ) from None
    if sol.status == 1:
        raise SolverError(
            f"{what}: the crank reached the kinematic limit (theta2 = 90 deg) at t = {sol.t_events[0][0]:.6g} s; "
            f"{past_limit}"
        )
    if not sol.success:
        raise SolverError(f"{what}: the integrator failed near t = {sol.t[-1]:.6g} s: {sol.message}")
    if not np.all(np.isfinite(sol.y)):
        raise SolverError(f"{what}: the solution became NaN")
    return sol.y


@_DOCS.fill
def integrate_forward(force_fn, p, t_eval, theta2_0, theta2dot_0, *, sign_smoothing=1e-2, rtol=1e-9, atol=1e-12):
    """Integrate the forward problem over ``t_eval`` (LSODA); stop at the kinematic limit.

    Parameters
    ----------
    force_fn : callable
        Applied slider force F(t, x, x') [N].
    {p}
    t_eval : array_like
        Output times [s].
    theta2_0 : float
        Initial crank angle [rad].
    theta2dot_0 : float
        Initial crank speed [rad/s].
    {sign_smoothing rtol}
    atol : float
        Absolute tolerance [rad, rad/s].

    Returns
    -------
    tuple of arrays
        ``theta2`` [rad] and ``theta2dot`` [rad/s] at ``t_eval``.

    Raises
    ------
    SolverError
        The integrator failed, or the crank reached the kinematic limit ``|theta2| = pi/2``
        (the slider was pushed past the end of its travel).
    """
    y = integrate_crank(
        forward_rhs,
        [theta2_0, theta2dot_0],
        t_eval,
        (force_fn, p, sign_smoothing),
        rtol=rtol,
        atol=atol,
        budget=MAX_FORWARD_CALLS,
        what="forward dynamics",
        too_long="the drive makes the motion too fast to follow (a force far beyond the mechanism's, or a very "
        "stiff base): check the force and its unit, or shorten t_end",
        past_limit="the drive pushes the slider past the end of its travel",
    )
    return y[0], y[1]


@_DOCS.fill
def energy(theta2, theta2dot, p):
    """``T + V`` [J] of the mechanism (for power-balance checks).

    Parameters
    ----------
    {theta2 theta2dot p}
    """
    return kinetic_energy(theta2, theta2dot, p["m2"], p["m3"], p["ms"], p["r2"], p["r3"]) + spring_energy(
        theta2, p["k3"], p["r2"], p["r3"]
    )
