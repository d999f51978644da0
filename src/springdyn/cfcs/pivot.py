"""The small-length flexural pivot: stiffness, bending stress, allowable stroke.

In the pseudo-rigid-body model the flexure joining coupler and slider becomes a pin
with a torsional spring ``K3 = E I / l`` (Eq. (1) of the CFCS paper) centred on the
flexure.  A rectangular strip of width b and thickness h has ``I = b h^3 / 12``.  Its
surface bending stress at a pivot deflection ``theta_K3`` is
``sigma = E (h/2) theta_K3 / l`` (reference values of docs/references.md: 4.14 GPa per radian for Table 1,
so the stress check belongs to every honest result).
"""

from __future__ import annotations

import numpy as np

from .kinematics import deflection_from_theta2, kinematic_limit_deflection

__all__ = [
    "second_moment_rectangle",
    "flexure_stiffness",
    "bending_stress",
    "safety_factor",
    "allowable_spring_angle",
    "max_stroke_for_stress",
]


def second_moment_rectangle(width, thickness):
    """``I = b h^3 / 12`` [m^4] of a rectangular strip bent about its thin axis.

    Parameters
    ----------
    width : float
        Flexure width b [m].
    thickness : float
        Flexure thickness h [m].
    """
    return width * thickness**3 / 12.0


def flexure_stiffness(youngs_modulus, width, thickness, length):
    """Torsional stiffness ``K3 = E b h^3 / (12 l)`` [N*m/rad], Eq. (1) of the CFCS paper.

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E [Pa].
    width, thickness, length : float
        Flexure width b, thickness h and length l [m].
    """
    return youngs_modulus * second_moment_rectangle(width, thickness) / length


def bending_stress(spring_angle, youngs_modulus, thickness, length):
    """Surface bending stress ``sigma = E (h/2) |theta_K3| / l`` [Pa] (reference values of docs/references.md).

    Parameters
    ----------
    spring_angle : float or array
        Pivot deflection theta_K3 [rad].
    youngs_modulus : float
        E [Pa].
    thickness, length : float
        Flexure thickness h and length l [m].
    """
    return youngs_modulus * 0.5 * thickness * np.abs(spring_angle) / length


def safety_factor(allowable_stress, max_stress):
    """``n = sigma_allow / sigma_max`` [-]; infinite when the pivot is unstressed.

    Parameters
    ----------
    allowable_stress : float
        Allowable bending stress of the flexure [Pa].
    max_stress : float
        Largest bending stress [Pa].
    """
    max_stress = np.asarray(max_stress, dtype=float)
    with np.errstate(divide="ignore"):
        out = np.where(max_stress > 0, allowable_stress / np.where(max_stress > 0, max_stress, 1.0), np.inf)
    return out if out.ndim else float(out)


def allowable_spring_angle(allowable_stress, youngs_modulus, thickness, length):
    """Largest pivot deflection ``theta_K3 = 2 sigma_allow l / (E h)`` [rad] the stress allows.

    Parameters
    ----------
    allowable_stress : float
        Allowable bending stress of the flexure [Pa].
    youngs_modulus : float
        Young's modulus of the flexure [Pa].
    thickness : float
        Flexure thickness h [m].
    length : float
        Flexure length l [m].
    """
    return 2.0 * allowable_stress * length / (youngs_modulus * thickness)


def max_stroke_for_stress(allowable_stress, youngs_modulus, thickness, length, r2, r3):
    """Largest slider deflection [m] at which the pivot stress stays at the allowable value.

    The pivot angle ``theta_K3 = asin(r2 sin theta2 / r3)`` grows monotonically with
    the stroke up to ``asin(r2/r3)`` at the kinematic limit; if the allowable angle is
    larger, the kinematic limit governs.

    Parameters
    ----------
    allowable_stress : float
        Allowable bending stress of the flexure [Pa].
    youngs_modulus : float
        Young's modulus of the flexure [Pa].
    thickness : float
        Flexure thickness h [m].
    length : float
        Flexure length l [m].
    r2 : float
        Crank length r2 [m].
    r3 : float
        Coupler length r3 [m], longer than r2.
    """
    th_allow = allowable_spring_angle(allowable_stress, youngs_modulus, thickness, length)
    if th_allow >= np.arcsin(r2 / r3):
        return float(kinematic_limit_deflection(r2, r3))
    theta2 = np.arcsin(r3 * np.sin(th_allow) / r2)
    return float(deflection_from_theta2(theta2, r2, r3))
