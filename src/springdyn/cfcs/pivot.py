"""The small-length flexural pivot: stiffness, bending stress, allowable stroke.

In the pseudo-rigid-body model the flexure joining coupler and slider becomes a pin
with a torsional spring ``K3 = E I / l`` (Eq. (1) of the CFCS paper) centred on the
flexure.  A rectangular strip of width b and thickness h has ``I = b h^3 / 12``.  Its
surface bending stress at a pivot deflection ``theta_K3`` is
``sigma = E (h/2) theta_K3 / l`` (reference values of docs/references.md: 4.14 GPa per radian for Table 1,
so the stress check belongs to every honest result).

The strip's own properties live here too, for both flexure models (the pin and the
elastica of :mod:`springdyn.cfcs.beam`): plate or beam modulus, bending stiffness, the
Euler buckling load and the first bending frequency.
"""

from __future__ import annotations

import math

import numpy as np

from ..core.docstrings import ParameterDocs
from .kinematics import deflection_from_theta2, kinematic_limit_deflection

__all__ = [
    "second_moment_rectangle",
    "flexure_stiffness",
    "bending_stress",
    "safety_factor",
    "allowable_spring_angle",
    "max_stroke_for_stress",
    "FLEXURE_MODELS",
    "PLATE_WIDTH_RATIO",
    "plate_modulus",
    "default_plate_bending",
    "bending_stiffness",
    "strip_buckling_load",
    "strip_first_frequency",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    youngs_modulus : float
        Young's modulus E [Pa].
    allowable_stress : float
        Allowable bending stress of the flexure [Pa].
    thickness : float
        Flexure thickness h [m].
    ei : float
        Bending stiffness [N*m^2].
    length : float
        Strip length l [m].
    """,
)

#: Allowed values of ``flexure_model``.
FLEXURE_MODELS = ("prbm", "beam")

#: Width/length ratio b/l from which a strip bends as a plate (E / (1 - nu^2)) by default.
PLATE_WIDTH_RATIO = 1.0


@_DOCS.fill
def second_moment_rectangle(width, thickness):
    """``I = b h^3 / 12`` [m^4] of a rectangular strip bent about its thin axis.

    Parameters
    ----------
    width : float
        Flexure width b [m].
    {thickness}
    """
    return width * thickness**3 / 12.0


@_DOCS.fill
def flexure_stiffness(youngs_modulus, width, thickness, length):
    r"""Torsional stiffness ``K3 = E b h^3 / (12 l)`` [N*m/rad], Eq. (1) of the CFCS paper.

    .. math::

        K_3 = \frac{E\,b\,h^3}{12\,l}

    Parameters
    ----------
    {youngs_modulus}
    width, thickness, length : float
        Flexure width b, thickness h and length l [m].

    Examples
    --------
    >>> round(flexure_stiffness(207e9, 10e-3, 0.3e-3, 9.5e-3), 4)
    0.4903

    References
    ----------
    .. [1] [CFCS] of docs/references.md: the compliant slider-crank paper, Eq. (1).
    .. [2] L. L. Howell, *Compliant Mechanisms*, Wiley, 2001 (small-length flexural pivots).
    """
    return youngs_modulus * second_moment_rectangle(width, thickness) / length


def bending_stress(spring_angle, youngs_modulus, thickness, length):
    r"""Surface bending stress ``sigma = E (h/2) |theta_K3| / l`` [Pa] (reference values of docs/references.md).

    .. math::

        \sigma = \frac{E\,h}{2\,l}\,\lvert\theta_{K3}\rvert

    Parameters
    ----------
    spring_angle : float or array
        Pivot deflection theta_K3 [rad].
    youngs_modulus : float
        E [Pa].
    thickness, length : float
        Flexure thickness h and length l [m].

    Examples
    --------
    >>> round(float(bending_stress(0.1, 207e9, 0.3e-3, 9.5e-3)) / 1e6, 1)
    326.8

    References
    ----------
    .. [1] [CFCS] of docs/references.md: the compliant slider-crank paper, Eq. (1).
    .. [2] L. L. Howell, *Compliant Mechanisms*, Wiley, 2001 (small-length flexural pivots).
    """
    return youngs_modulus * 0.5 * thickness * np.abs(spring_angle) / length


@_DOCS.fill
def safety_factor(allowable_stress, max_stress):
    """``n = sigma_allow / sigma_max`` [-]; infinite when the pivot is unstressed.

    Parameters
    ----------
    {allowable_stress}
    max_stress : float
        Largest bending stress [Pa].
    """
    max_stress = np.asarray(max_stress, dtype=float)
    with np.errstate(divide="ignore"):
        out = np.where(max_stress > 0, allowable_stress / np.where(max_stress > 0, max_stress, 1.0), np.inf)
    return out if out.ndim else float(out)


@_DOCS.fill
def allowable_spring_angle(allowable_stress, youngs_modulus, thickness, length):
    """Largest pivot deflection ``theta_K3 = 2 sigma_allow l / (E h)`` [rad] the stress allows.

    Parameters
    ----------
    {allowable_stress youngs_modulus thickness length}
    """
    return 2.0 * allowable_stress * length / (youngs_modulus * thickness)


@_DOCS.fill
def max_stroke_for_stress(allowable_stress, youngs_modulus, thickness, length, r2, r3):
    """Largest slider deflection [m] at which the pivot stress stays at the allowable value.

    The pivot angle ``theta_K3 = asin(r2 sin theta2 / r3)`` grows monotonically with
    the stroke up to ``asin(r2/r3)`` at the kinematic limit; if the allowable angle is
    larger, the kinematic limit governs.

    Parameters
    ----------
    {allowable_stress youngs_modulus thickness length}
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


@_DOCS.fill
def plate_modulus(youngs_modulus, poisson_ratio):
    """Plate (cylindrical bending) modulus ``E / (1 - nu^2)`` [Pa].

    Parameters
    ----------
    {youngs_modulus}
    poisson_ratio : float
        Poisson's ratio nu [-].
    """
    return youngs_modulus / (1.0 - poisson_ratio * poisson_ratio)


@_DOCS.fill
def default_plate_bending(width, length) -> bool:
    """Whether a strip of width b and length l bends as a plate by default: ``b >= l``.

    A wide strip cannot take its anticlastic curvature except in edge zones of width about
    ``sqrt(R h)`` (R the bending radius), so most of its width is in cylindrical bending
    (E / (1 - nu^2)); a narrow one bends as a beam (E).  For ``b >= l`` the edge zones are a
    small part of the width at the curvatures a flexure reaches (R of the order of l), so the
    plate value is the closer one.

    Parameters
    ----------
    width : float
        Strip width b [m].
    {length}
    """
    return bool(width >= PLATE_WIDTH_RATIO * length)


@_DOCS.fill
def bending_stiffness(youngs_modulus, width, thickness, plate_bending=False, poisson_ratio=0.3):
    """Bending stiffness ``EI = E' b h^3 / 12`` [N*m^2], E' = E or E/(1 - nu^2).

    Parameters
    ----------
    {youngs_modulus}
    width, thickness : float
        Strip width b and thickness h [m].
    plate_bending : bool
        Use the plate modulus E / (1 - nu^2).
    poisson_ratio : float
        nu [-].
    """
    e = plate_modulus(youngs_modulus, poisson_ratio) if plate_bending else youngs_modulus
    return e * width * thickness**3 / 12.0


@_DOCS.fill
def strip_buckling_load(ei, effective_length):
    """Euler buckling load ``pi^2 EI / L_e^2`` [N] of the strip.

    The design check takes the strip as a cantilever (clamped at the slider, its other end
    free to sway and turn with the coupler): ``L_e = 2 l``, the lowest of the usual end
    conditions and so the safe one.

    Parameters
    ----------
    {ei}
    effective_length : float
        Effective column length L_e [m] (2 l for a cantilever).
    """
    return math.pi**2 * ei / (effective_length * effective_length)


@_DOCS.fill
def strip_first_frequency(ei, mass_per_length, length):
    """First bending frequency ``1.875^2 sqrt(EI / (rho A)) / l^2`` [rad/s] of the strip as a cantilever.

    The strip's own dynamics can be left out (its quasi-static force used with the PRBM's
    inertia) while the motion's frequencies stay far below this value and the strip's mass is
    small beside the link masses.

    Parameters
    ----------
    {ei}
    mass_per_length : float
        rho b h [kg/m].
    {length}
    """
    return 1.8751**2 * math.sqrt(ei / mass_per_length) / (length * length)
