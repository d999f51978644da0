"""Statics of the CFCS: spring energy, force-deflection, dissipative terms, PCF.

The static force is the virtual-work result on the pseudo-rigid-body model
(reference values of docs/references.md; Fig. 2 of the CFCS paper)::

    F = K3 theta_K3 cos(theta2) / (r1 sin(theta2))

which equals ``dV/dtheta2 / (dx/dtheta2)`` with ``V = K3 theta_K3^2 / 2`` (Eq. (17)).

The dissipative terms of Eqs. (20)-(22) always oppose the motion here (correction CFCS-1 of docs/references.md), so a quasi-static stroke has a compression branch ``F + F_d`` and an
extension branch ``F - F_d``.  Their conversion to a slider force divides by the
Jacobian ``G = dx/dtheta2``, which vanishes at the toggle; below the cut-off angle the
Jacobian is frozen at ``G(theta2_cutoff)`` for these terms (:func:`frozen_jacobian`): a
documented regularisation of springdyn's, since the paper does not treat the toggle
(correction CFCS-3 of docs/references.md).
"""

from __future__ import annotations

import numpy as np

from ..core.docstrings import ParameterDocs
from .kinematics import (
    slider_jacobian,
    slider_position,
    spring_angle,
    spring_angle_rate_ratio,
)

__all__ = [
    "FRICTION_MODELS",
    "spring_energy",
    "spring_torque",
    "static_force",
    "static_force_at_toggle",
    "pin_friction_torque",
    "axial_force_torque",
    "dissipative_torque",
    "frozen_jacobian",
    "percent_constant_force",
    "percent_constant_force_energy",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    r2 : float
        Crank length r2 [m].
    r3 : float
        Coupler length r3 [m], longer than r2.
    theta2 : float or array_like
        Crank angle theta2 [rad], 0 at the toggle.
    k3 : float
        Pivot torsional stiffness K3 [N*m/rad].
    r2, r3 : float
        Link lengths [m].
    """,
)

#: Allowed values of ``friction_model``.
FRICTION_MODELS = ("paper", "constant", "none")


@_DOCS.fill
def spring_energy(theta2, k3, r2, r3):
    """Pivot spring energy ``V = K3 theta_K3^2 / 2`` [J], Eq. (17) of the CFCS paper.

    Parameters
    ----------
    {theta2 k3 r2 r3}
    """
    th = spring_angle(theta2, r2, r3)
    return 0.5 * k3 * th * th


@_DOCS.fill
def spring_torque(theta2, k3, r2, r3):
    """``dV/dtheta2 = K3 theta_K3 r2 cos theta2 / D`` [N*m], the last term of Eq. (19).

    Parameters
    ----------
    {theta2 k3 r2 r3}
    """
    return k3 * spring_angle(theta2, r2, r3) * spring_angle_rate_ratio(theta2, r2, r3)


def _asin_ratio(s, a):
    """``asin(a s) / s`` with its series ``a (1 + a^2 s^2/6 + 3 a^4 s^4/40)`` near s = 0."""
    s = np.asarray(s, dtype=float)
    small = np.abs(s) < 1e-4
    safe = np.where(small, 1.0, s)
    exact = np.arcsin(a * safe) / safe
    series = a * (1.0 + (a * s) ** 2 / 6.0 + 3.0 * (a * s) ** 4 / 40.0)
    return np.where(small, series, exact)


@_DOCS.fill
def static_force(theta2, k3, r2, r3):
    """Static slider force by virtual work ``K3 theta_K3 cos th2 / (r1 sin th2)`` [N].

    The reference values of docs/references.md (the paper's Fig. 2).  The limit at the toggle is finite,
    ``K3 r2 / (r3 (r2 + r3))`` (12.580 N for Table 1), and is used there.

    Parameters
    ----------
    {theta2}
    k3 : float
        Pivot stiffness [N*m/rad].
    r2, r3 : float
        Crank and coupler lengths [m].
    """
    theta2 = np.asarray(theta2, dtype=float)
    out = k3 * _asin_ratio(np.sin(theta2), r2 / r3) * np.cos(theta2) / slider_position(theta2, r2, r3)
    return out if out.ndim else float(out)


@_DOCS.fill
def static_force_at_toggle(k3, r2, r3):
    """Static force as ``theta2 -> 0+``: ``K3 r2 / (r3 (r2 + r3))`` [N] (reference values of docs/references.md).

    Parameters
    ----------
    {k3 r2 r3}
    """
    return k3 * r2 / (r3 * (r2 + r3))


@_DOCS.fill
def pin_friction_torque(theta2, pin_friction, model, r2, r3):
    """Magnitude of the pin friction torque tau_CF [N*m], Eq. (21) of the CFCS paper.

    - ``"paper"``: ``C |theta2| (2 + r2 cos th2 / D)``, Eq. (21) as printed (the factor
      theta2 is the paper's, correction CFCS-2 of docs/references.md).
    - ``"constant"``: ``C (2 + r2 cos th2 / D)``, the Coulomb torque C of the ground pin
      (rate theta2') plus that of the crank-coupler pin (rate theta2' (1 + u)).
    - ``"none"``: 0.

    The sign (opposing theta2') is applied by the caller.

    Parameters
    ----------
    {theta2}
    pin_friction : float
        Coulomb torque C of a pin [N*m] (units not given by the paper, correction CFCS-4 of docs/references.md).
    model : {"paper", "constant", "none"}
    {r2_r3}
    """
    theta2 = np.asarray(theta2, dtype=float)
    bracket = 2.0 + spring_angle_rate_ratio(theta2, r2, r3)
    if model == "paper":
        return pin_friction * np.abs(theta2) * bracket
    if model == "constant":
        return pin_friction * bracket
    if model == "none":
        return np.zeros_like(theta2)
    raise ValueError(f"friction model {model!r}: choose one of {FRICTION_MODELS}")


@_DOCS.fill
def axial_force_torque(force_static, shear_angle, r2, r3):
    """Magnitude of the axial-force torque tau_AF [N*m], Eq. (22) of the CFCS paper.

    ``tau_AF = F_static r2 alpha (1 + r2 / sqrt(r3^2 - r2^2 alpha^2))``.  springdyn
    applies it, like tau_CF, against the motion (correction CFCS-1 of docs/references.md).

    Parameters
    ----------
    force_static : float or array
        Static force at the same deflection [N].
    shear_angle : float
        alpha [rad].
    {r2_r3}
    """
    return force_static * r2 * shear_angle * (1.0 + r2 / np.sqrt(r3 * r3 - (r2 * shear_angle) ** 2))


@_DOCS.fill
def dissipative_torque(theta2, force_static, pin_friction, model, shear_angle, axial_force, r2, r3):
    """``|tau_CF| + |tau_AF|`` [N*m] with the options of the mechanism (see above).

    Parameters
    ----------
    {theta2}
    force_static : float or array_like
        Static slider force [N].
    pin_friction : float
        Coulomb pin friction torque C of Eq. (21) [N*m].
    model : str
        Pin friction model: 'paper', 'constant' or 'none' (correction CFCS-2 of docs/references.md).
    shear_angle : float
        Shear angle alpha of Eq. (22) [rad].
    axial_force : bool
        Include the axial-force torque tau_AF of Eq. (22).
    {r2 r3}
    """
    tau = pin_friction_torque(theta2, pin_friction, model, r2, r3)
    if axial_force:
        tau = tau + axial_force_torque(force_static, shear_angle, r2, r3)
    return tau


@_DOCS.fill
def frozen_jacobian(theta2, r2, r3, theta2_cutoff):
    """``G`` [m/rad] frozen at ``G(theta2_cutoff)`` inside the toggle zone ``|theta2| < theta2_cutoff``.

    Used only to turn the dissipative torques tau_CF and tau_AF into a slider force:
    both are non-zero at the toggle (tau_AF always, tau_CF in the constant model) while
    G -> 0, so ``tau / G`` diverges there (correction CFCS-3 of docs/references.md).  Inside the zone
    the dissipative force is ``tau / G(theta2_cutoff)``.

    Parameters
    ----------
    {theta2 r2 r3}
    theta2_cutoff : float
        Toggle cut-off angle [rad] (correction CFCS-3 of docs/references.md).
    """
    theta2 = np.asarray(theta2, dtype=float)
    return slider_jacobian(np.maximum(np.abs(theta2), theta2_cutoff), r2, r3)


def percent_constant_force(force):
    """Percent constant force ``100 F_min / F_max`` [%] of a force record.

    This is springdyn's explicit definition (the CFCS paper does not define it,
    correction CFCS-4 of docs/references.md).  NaN if the largest force is not positive.

    Parameters
    ----------
    force : array_like
        Force record [N].
    """
    force = np.asarray(force, dtype=float)
    fmax = np.max(force)
    return float(100.0 * np.min(force) / fmax) if fmax > 0 else float("nan")


def percent_constant_force_energy(deflection, force):
    """Energy-based PCF ``100 W / (F_max * stroke)`` [%].

    W is the work ``int F dx`` over the stroke; an ideal constant-force spring of force
    F_max would do ``F_max * stroke``.

    Parameters
    ----------
    deflection : array
        Increasing slider deflections [m].
    force : array
        Force at those deflections [N].
    """
    x = np.asarray(deflection, dtype=float)
    f = np.asarray(force, dtype=float)
    stroke = x[-1] - x[0]
    fmax = np.max(f)
    if stroke <= 0 or fmax <= 0:
        return float("nan")
    work = float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x)))
    return 100.0 * work / (fmax * stroke)
