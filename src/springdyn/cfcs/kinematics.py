"""Kinematics of the pseudo-rigid-body slider-crank of the CFCS.

Topology ([CFCS], see docs/references.md): crank ``r2`` pinned to ground, coupler
``r3`` pinned to the crank, a small-length flexural pivot (torsional spring K3)
joining coupler and slider.  Loop closure, consistent with Eqs. (14), (15) and (25)
of the CFCS paper::

    r1 = r2 cos(theta2) + r3 cos(theta3),    r2 sin(theta2) + r3 sin(theta3) = 0

At ``theta2 = 0`` the links are straight (``r1 = r2 + r3``, the toggle); compressing
the slider increases ``theta2`` up to the kinematic limit ``theta2 = pi/2``
(``r1 = sqrt(r3^2 - r2^2)``).  The slider deflection is ``x = r2 + r3 - r1 >= 0``.

All functions take SI floats or numpy arrays.  Angles may be negative (the mirror
branch of the crank); every function is written so that it stays valid there, which
the forward dynamics uses when the crank passes through the toggle.
"""

from __future__ import annotations

import numpy as np

from ..core.docstrings import ParameterDocs

__all__ = [
    "coupler_root",
    "slider_position",
    "deflection_from_theta2",
    "theta2_from_deflection",
    "coupler_angle",
    "spring_angle",
    "spring_angle_rate_ratio",
    "spring_angle_rate_derivative",
    "slider_jacobian",
    "slider_jacobian_derivative",
    "dr1_dtheta2",
    "kinematic_limit_deflection",
    "kinematic_limit_theta2",
    "crank_rates",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    r3 : float
        Coupler length r3 [m], longer than r2.
    r2 : float
        Crank length r2 [m].
    theta2 : float or array_like
        Crank angle theta2 [rad], 0 at the toggle.
    """
)


def coupler_root(theta2, r2, r3):
    """``D = sqrt(r3^2 - r2^2 sin^2 theta2)`` [m], the root that recurs in Eqs. (19)-(25).

    Parameters
    ----------
    theta2 : float or array
        Crank angle [rad].
    r2, r3 : float
        Crank and coupler lengths [m] (``r2 < r3``, so ``D > 0`` for every angle).
    """
    s = np.sin(theta2)
    return np.sqrt(r3 * r3 - (r2 * s) ** 2)


@_DOCS.fill
def slider_position(theta2, r2, r3):
    """Distance ``r1`` [m] from the ground pin to the slider pivot (loop closure).

    ``r1 = r2 cos theta2 + D`` (the loop closure under Eq. (14) of the CFCS paper,
    written with ``r3 cos theta3 = D``).

    Parameters
    ----------
    {theta2 r2 r3}
    """
    return r2 * np.cos(theta2) + coupler_root(theta2, r2, r3)


@_DOCS.fill
def deflection_from_theta2(theta2, r2, r3):
    """Slider deflection ``x = r2 + r3 - r1`` [m] for a crank angle ``theta2`` [rad].

    Written without cancellation as ``2 r2 sin^2(theta2/2) + r2^2 sin^2 theta2 / (r3 + D)``
    (``r3 - D = r2^2 sin^2 theta2 / (r3 + D)``), so it keeps full precision at the toggle.

    Parameters
    ----------
    {theta2 r2 r3}
    """
    s = np.sin(theta2)
    return 2.0 * r2 * np.sin(0.5 * np.asarray(theta2)) ** 2 + (r2 * s) ** 2 / (r3 + coupler_root(theta2, r2, r3))


def theta2_from_deflection(x, r2, r3):
    """Exact inverse of :func:`deflection_from_theta2` on ``0 <= theta2 <= pi/2``.

    From the cosine rule, ``1 - cos theta2 = x (2 r3 - x) / (2 r1 r2)`` with
    ``r1 = r2 + r3 - x``, so ``theta2 = 2 asin(sqrt(x (2 r3 - x) / (4 r1 r2)))``.
    This form keeps full precision near the toggle (no ``arccos`` of a number
    close to 1).

    Parameters
    ----------
    x : float or array
        Slider deflection [m], ``0 <= x <=`` :func:`kinematic_limit_deflection`.
    r2, r3 : float
        Crank and coupler lengths [m].

    Returns
    -------
    float or array
        Crank angle [rad].  Values outside the range give NaN; callers validate.
    """
    x = np.asarray(x, dtype=float)
    r1 = r2 + r3 - x
    arg = x * (2.0 * r3 - x) / (4.0 * r1 * r2)
    with np.errstate(invalid="ignore"):
        out = 2.0 * np.arcsin(np.sqrt(arg))
    out = np.where((x < 0) | (arg > 0.5 + 1e-15), np.nan, out)
    return out if out.ndim else float(out)


@_DOCS.fill
def coupler_angle(theta2, r2, r3):
    """Coupler angle ``theta3 = -asin(r2 sin theta2 / r3)`` [rad] (loop closure).

    Parameters
    ----------
    {theta2 r2 r3}
    """
    return -np.arcsin(r2 * np.sin(theta2) / r3)


@_DOCS.fill
def spring_angle(theta2, r2, r3):
    """Deflection of the pivot spring ``theta_K3 = -theta3`` [rad].

    Eq. (18) of the CFCS paper gives ``asin(r2 sin theta2 / r3)``, which is this
    value (docs/references.md: the paper's sign is immaterial since V is quadratic).

    Parameters
    ----------
    {theta2 r2 r3}
    """
    return np.arcsin(r2 * np.sin(theta2) / r3)


@_DOCS.fill
def spring_angle_rate_ratio(theta2, r2, r3):
    """``u = d theta_K3 / d theta2 = r2 cos theta2 / D`` [-].

    It is also ``-theta3'/theta2'`` (Eq. (15) of the CFCS paper) and the second term of
    the bracket of Eq. (21): the crank-coupler pin turns at ``theta2' (1 + u)``.

    Parameters
    ----------
    {theta2 r2 r3}
    """
    return r2 * np.cos(theta2) / coupler_root(theta2, r2, r3)


@_DOCS.fill
def spring_angle_rate_derivative(theta2, r2, r3):
    """``du/dtheta2 = -r2 sin theta2 (r3^2 - r2^2) / D^3`` [1/rad], the derivative of
    :func:`spring_angle_rate_ratio` (``D^2 - r2^2 cos^2 theta2 = r3^2 - r2^2``).

    Parameters
    ----------
    {theta2 r2 r3}
    """
    return -r2 * np.sin(theta2) * (r3 * r3 - r2 * r2) / coupler_root(theta2, r2, r3) ** 3


@_DOCS.fill
def slider_jacobian(theta2, r2, r3):
    """``G = dx/dtheta2 = -dr1/dtheta2 = r2 sin theta2 (1 + u)`` [m/rad].

    The negative of Eq. (25) of the CFCS paper (``dr1/dtheta2 = -r1 r2 sin theta2 / D``,
    docs/references.md).  It vanishes at the toggle ``theta2 = 0``.

    Parameters
    ----------
    {theta2 r2 r3}
    """
    return r2 * np.sin(theta2) * (1.0 + spring_angle_rate_ratio(theta2, r2, r3))


@_DOCS.fill
def dr1_dtheta2(theta2, r2, r3):
    """Eq. (25) of the CFCS paper: ``dr1/dtheta2 = -r2 sin th2 - r2^2 sin th2 cos th2 / D`` [m/rad].

    Parameters
    ----------
    {theta2 r2 r3}
    """
    s, c = np.sin(theta2), np.cos(theta2)
    return -r2 * s - r2 * r2 * s * c / coupler_root(theta2, r2, r3)


@_DOCS.fill
def slider_jacobian_derivative(theta2, r2, r3):
    """``dG/dtheta2 = r2 cos th2 (1 + u) + r2 sin th2 du/dth2`` [m/rad^2].

    With ``u`` of :func:`spring_angle_rate_ratio` and ``du/dtheta2`` of
    :func:`spring_angle_rate_derivative`.

    Parameters
    ----------
    {theta2 r2 r3}
    """
    s, c = np.sin(theta2), np.cos(theta2)
    u = spring_angle_rate_ratio(theta2, r2, r3)
    du = spring_angle_rate_derivative(theta2, r2, r3)
    return r2 * c * (1.0 + u) + r2 * s * du


def kinematic_limit_theta2() -> float:
    """Crank angle of the kinematic limit, ``pi/2`` [rad] ([CFCS]: the links are square to each other)."""
    return np.pi / 2


@_DOCS.fill
def kinematic_limit_deflection(r2, r3):
    """Largest slider deflection ``r2 + r3 - sqrt(r3^2 - r2^2)`` [m] (``theta2 = pi/2``).

    Parameters
    ----------
    {r2 r3}
    """
    return r2 + r3 - np.sqrt(r3 * r3 - r2 * r2)


@_DOCS.fill
def crank_rates(x, xdot, xddot, r2, r3):
    """Crank angle, rate and acceleration from the slider motion (exact inverse kinematics).

    ``theta2' = x'/G`` and ``theta2'' = (x'' - G' theta2'^2)/G`` with G from
    :func:`slider_jacobian`.  At the toggle (G = 0) both are 0/0: the values there are
    not finite, and :func:`springdyn.cfcs.dynamics.inverse_dynamics` replaces the
    inertia force at such instants by its limit.

    Parameters
    ----------
    x : float or array_like
        Slider deflection from the toggle [m].
    xdot : float or array_like
        Slider speed [m/s].
    xddot : float or array_like
        Slider acceleration [m/s^2].
    {r2 r3}

    Returns
    -------
    theta2, theta2dot, theta2ddot : arrays
        [rad], [rad/s], [rad/s^2].
    jac : array
        ``G`` [m/rad].
    """
    x = np.asarray(x, dtype=float)
    th = np.asarray(theta2_from_deflection(x, r2, r3), dtype=float)
    jac = slider_jacobian(th, r2, r3)
    djac = slider_jacobian_derivative(th, r2, r3)
    with np.errstate(divide="ignore", invalid="ignore"):
        thd = np.asarray(xdot, dtype=float) / jac
        thdd = (np.asarray(xddot, dtype=float) - djac * thd * thd) / jac
    return th, thd, thdd, jac
