"""Forward dynamics of the CFCS driven through a compliant drive: through the toggle, no cut-off.

The prescribed motion ``x_d(t)`` does not move the slider itself but the far end of the drive
(whatever pushes the slider: a cam follower, a linkage, a test machine's load train), which
acts on the slider through a spring ``k_d`` and a damper ``c_d``::

    F = k_d (x_d - x) + c_d (x_d' - x')            (drive force, positive in compression)

The mechanism keeps its one degree of freedom, the crank angle theta2, now *signed*: the
slider position ``x(theta2)`` is even, so the crank passes the toggle ``theta2 = 0`` into the
mirror branch with the inertia of the crank and the coupler (the generalized mass is
finite there, ``M(0) = (m2 + m3) r2^2 / 3``).  Lagrange's equation (10) of the CFCS paper::

    M th2'' + M'/2 th2'^2 + dV/dth2 + tau_d sgn~(th2') + F_s sgn~(x') G = F G

with ``G = dx/dtheta2`` (odd in theta2) is integrated as it stands: nothing is divided by G,
so the toggle needs no cut-off.  The Coulomb signs are smoothed, ``sgn~(v) = tanh(v / v_s)``
(as in :func:`springdyn.cfcs.dynamics.forward_rhs`); ``v_s`` is a numerical setting whose
halving and doubling the tests check.

Energy: the state carries three running integrals, the work the actuator does on the drive
``W = int F x_d' dt``, the heat of the mechanism's friction ``D_f = int (tau_d sgn~ th2' +
F_s sgn~ x') dt`` and that of the drive's damper ``D_c = int c_d (x_d' - x')^2 dt``, so that
``W = Delta(T + V + V_d) + D_f + D_c`` with ``V_d = k_d (x_d - x)^2 / 2`` closes to the
integrator's tolerance (:func:`energy_balance`).

Sticking at the toggle: a slider force F turns into a crank torque only through ``G ~ r2 (1 +
r2/r3) th2``, so a crank that stops within the shear angle alpha of the toggle is held there by
the axial-force torque tau_AF of Eq. (22) until ``F |G(th2)| = tau_AF + tau_CF + |dV/dth2|``,
about ``F_static alpha / |th2|`` (docs/cfcs.md).  Inside alpha (22) is not a model of the mechanism
(read as a friction angle it would lock it), so a driven run whose crank rests there has a peak set
by that reading; :func:`toggle_sticking` measures it.
"""

from __future__ import annotations

import numpy as np

from ..core.docstrings import ParameterDocs
from .dynamics import crank_terms, generalized_mass, integrate_crank, kinetic_energy
from .kinematics import deflection_from_theta2, slider_jacobian
from .statics import spring_energy

__all__ = [
    "DRIVE_SIGN_SMOOTHING",
    "drive_force",
    "drive_spring_energy",
    "driven_rhs",
    "integrate_driven",
    "energy_balance",
    "toggle_sticking",
    "TOGGLE_REST_FACTOR",
    "slider_effective_mass",
    "RIGID_DRIVE_FREQUENCY_RATIO",
    "RIGID_DRIVE_LAG",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    k_d : float
        Drive stiffness [N/m].
    c_d : float
        Drive damping [N*s/m].
    theta2dot : array_like
        Crank speed [rad/s].
    motion : callable
        ``motion(t) -> (x_d, x_d', ...)`` [m, m/s].
    p : mapping
        Mechanism values [SI].
    x_d : float or array_like
        Prescribed position of the drive's far end [m].
    x : float or array_like
        Slider deflection [m].
    """
)

#: Default speed v_s [rad/s] of the smoothed Coulomb sign in the driven model: halving and doubling it
#: moves the statistics of the seed's case (Table 1 through the toggle at 14.7 rad/s, 20 kN/m) by
#: less than 1 % (a test).
DRIVE_SIGN_SMOOTHING = 1e-3


@_DOCS.fill
def drive_force(x_d, v_d, x, v, k_d, c_d):
    """Force of the drive on the slider ``k_d (x_d - x) + c_d (x_d' - x')`` [N], positive in compression.

    Parameters
    ----------
    {x_d}
    v_d : float or array_like
        Its velocity [m/s].
    {x}
    v : float or array_like
        Slider velocity [m/s].
    {k_d c_d}
    """
    return k_d * (np.asarray(x_d) - x) + c_d * (np.asarray(v_d) - v)


@_DOCS.fill
def drive_spring_energy(x_d, x, k_d):
    """Strain energy of the drive ``k_d (x_d - x)^2 / 2`` [J].

    Parameters
    ----------
    {x_d x k_d}
    """
    d = np.asarray(x_d) - x
    return 0.5 * k_d * d * d


@_DOCS.fill
def driven_rhs(t, y, motion, k_d, c_d, p, sign_smoothing):
    """Right-hand side of the driven problem; state ``(theta2, theta2', W, D_f, D_c)``.

    Parameters
    ----------
    t : float
        Time [s].
    y : ndarray
        Crank angle [rad], crank speed [rad/s], actuator work [J], friction heat [J], damper heat [J].
    {motion k_d c_d}
    p : mapping
        Mechanism values (:meth:`springdyn.cfcs.params.CFCSParams.values`; with the beam model,
        ``spring_force`` the elastica's quasi-static force of x) [SI].
    sign_smoothing : float
        Speed v_s of the smoothed Coulomb sign tanh(v/v_s) [rad/s].
    """
    th, thd = y[0], y[1]
    g, x, v, m, dm, torque, pin, slider = crank_terms(th, thd, p, sign_smoothing)
    md = motion(t)
    xd, vd = float(md[0]), float(md[1])
    f = drive_force(xd, vd, x, v, k_d, c_d)
    friction = pin + slider
    acc = (f * g - 0.5 * dm * thd * thd - torque - friction) / m
    return np.array([thd, acc, f * vd, friction * thd, c_d * (vd - v) ** 2])


#: A drive is taken as rigid (the slider follows x_d, :meth:`springdyn.cfcs.model.CFCS.dynamic`) when
#: ``k_d / (m_eff omega^2)``, the squared ratio of the slider's natural frequency on the drive to the
#: motion's, is at least this (with :data:`RIGID_DRIVE_LAG`).  The driven result differs from the rigid
#: one as ``1/k_d`` (tests/cfcs/test_drive.py: 0.095 % of the peak-to-peak at 1e6 N/m, 14.7 rad/s), so at
#: the bound the difference is below 0.1 % of the peak-to-peak for a damped drive; integrating a stiffer
#: drive only costs time (1e9 N/m: 49 s, 1e15 N/m: without end, issue 40).
RIGID_DRIVE_FREQUENCY_RATIO = 1e5

#: ... and when the drive's deflection under the mechanism's largest static force is at most this share
#: of the motion's stroke [-].
RIGID_DRIVE_LAG = 1e-4


def slider_effective_mass(theta2, m2, m3, ms, r2, r3):
    """Mass of the mechanism seen at the slider ``M(theta2) / G(theta2)^2`` [kg], ``G = dx/dtheta2``.

    The kinetic energy ``M theta2'^2 / 2 = (M / G^2) x'^2 / 2`` (Eq. (19) of the CFCS paper with
    ``x' = G theta2'``); infinite at the toggle, where G vanishes.

    Parameters
    ----------
    theta2 : float or array_like
        Crank angle [rad], not zero.
    m2, m3, ms : float
        Crank, coupler and slider masses [kg].
    r2, r3 : float
        Crank and coupler lengths [m].
    """
    g = slider_jacobian(theta2, r2, r3)
    return generalized_mass(theta2, m2, m3, ms, r2, r3) / (g * g)


#: The crank is "at rest" when ``|theta2'|`` is below this many times the sign smoothing v_s (the smoothed
#: Coulomb sign lets a held crank creep at speeds of order v_s; the seed's case rests at 1e-4 rad/s and
#: leaves at 1-10 rad/s, so the share of the period it sticks moves from 0.079 to 0.097 between 1 and
#: 150 times v_s).
TOGGLE_REST_FACTOR = 10.0


@_DOCS.fill
def toggle_sticking(theta2, theta2dot, force, shear_angle, rest_speed):
    """Where the crank rests within the shear angle of the toggle: share, stop angle, release force.

    A sample sticks when ``|theta2| < alpha`` and ``|theta2'| < rest_speed``.  The stop angle is the
    median crank angle of those samples (signed); the release force the largest drive force on them
    (the force at which the crank leaves: it rises while the crank is held).

    Parameters
    ----------
    theta2 : array_like
        Crank angle over the samples (equally spaced in time) [rad].
    {theta2dot}
    force : array_like
        Drive force on the slider [N].
    shear_angle : float
        Shear angle alpha of Eq. (22) [rad].
    rest_speed : float
        Crank speed below which the crank is at rest [rad/s].

    Returns
    -------
    tuple
        Share of the samples that stick [-], stop angle [rad] and release force [N] (both ``None``
        when no sample sticks).
    """
    th = np.asarray(theta2, dtype=float)
    stuck = (np.abs(th) < abs(shear_angle)) & (np.abs(np.asarray(theta2dot, dtype=float)) < rest_speed)
    if not np.any(stuck):
        return 0.0, None, None
    return float(np.mean(stuck)), float(np.median(th[stuck])), float(np.max(np.asarray(force)[stuck]))


#: Right-hand-side budget of a driven run.
MAX_DRIVEN_CALLS = 4_000_000


@_DOCS.fill
def integrate_driven(
    motion, k_d, c_d, p, t_eval, theta2_0, theta2dot_0, *, sign_smoothing, rtol, max_step, energy_scale
):
    """Integrate :func:`driven_rhs` over ``t_eval`` (LSODA); stop at the kinematic limit.

    Parameters
    ----------
    {motion k_d c_d p}
    t_eval : array_like
        Output times [s], increasing.
    theta2_0 : float
        Initial crank angle [rad].
    theta2dot_0 : float
        Initial crank speed [rad/s].
    sign_smoothing : float
        Speed v_s of the smoothed Coulomb sign [rad/s].
    rtol : float
        Relative tolerance [-]; the absolute tolerances are ``rtol`` times 1e-3 rad, 1e-3 rad/s
        and 1e-3 ``energy_scale``.
    max_step : float
        Largest step of the integrator [s].
    energy_scale : float
        A typical energy of the motion [J] (for the tolerance of the running integrals).

    Returns
    -------
    ndarray
        The state at ``t_eval``, shape (5, n): theta2 [rad], theta2' [rad/s], W, D_f, D_c [J].
    """
    return integrate_crank(
        driven_rhs,
        [theta2_0, theta2dot_0, 0.0, 0.0, 0.0],
        t_eval,
        (motion, k_d, c_d, p, sign_smoothing),
        rtol=rtol,
        atol=rtol * 1e-3 * np.array([1.0, 1.0, energy_scale, energy_scale, energy_scale]),
        max_step=max_step,
        budget=MAX_DRIVEN_CALLS,
        what="driven dynamics",
        too_long="the drive is too stiff for the motion to be followed (check drive_stiffness and its unit) or the "
        "run too long",
        past_limit="the drive pushes the slider past the end of its travel (a smaller amplitude, or a stiffer drive "
        "that follows the motion more closely)",
    )


@_DOCS.fill
def energy_balance(theta2, theta2dot, x_d, work, heat_friction, heat_damper, k_d, p, strain_energy=None):
    """Residual of ``W = Delta(T + V + V_d) + D_f + D_c`` along a driven run [J].

    Parameters
    ----------
    theta2 : array_like
        Crank angle [rad].
    {theta2dot}
    x_d : array_like
        Drive position [m].
    work : array_like
        Running work of the actuator on the drive [J].
    heat_friction : array_like
        Running heat of the mechanism's friction [J].
    heat_damper : array_like
        Running heat of the drive's damper [J].
    {k_d p}
    strain_energy : callable, optional
        ``V(x)`` [J] of another flexure model (the elastica's integrated force); default the PRBM's
        ``K3 theta_K3^2 / 2``.

    Returns
    -------
    ndarray
        The residual at each sample, zero at the start [J].
    """
    th = np.asarray(theta2, dtype=float)
    x = deflection_from_theta2(th, p["r2"], p["r3"])
    v = spring_energy(th, p["k3"], p["r2"], p["r3"]) if strain_energy is None else strain_energy(x)
    stored = (
        kinetic_energy(th, theta2dot, p["m2"], p["m3"], p["ms"], p["r2"], p["r3"])
        + v
        + drive_spring_energy(x_d, x, k_d)
    )
    return np.asarray(work) - (stored - stored[0]) - np.asarray(heat_friction) - np.asarray(heat_damper)
