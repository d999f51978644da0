"""The wire's cross-section: one home for the section laws of round, ovate and rectangular wire.

A helical spring's wire is twisted by the torque ``T = F D/2`` of the axial force ``F`` on the
mean coil diameter ``D``.  Its section enters the spring through four figures:

- the **torsion constant** ``J`` (Saint-Venant): the rate of ``n`` active coils is
  ``R = 4 G J / (pi D^3 n)`` (the wire of length ``pi D n`` twisted by ``F D/2``, small pitch
  angle; Wahl, *Mechanical Springs*, 1963, ch. 2 and ch. 12).  Round wire, ``J = pi d^4/32``,
  gives EN 13906-1's ``G d^4/(8 D^3 n)``;
- the **area** ``A``: the mass ``rho A`` per length of wire; with ``J`` the first surge
  frequency of a uniform spring, ends fixed, ``f = sqrt(G J/(rho A)) / (pi n D^2)`` (the wave
  equation of the wire; round wire gives Wahl's ``d/(2 pi n D^2) sqrt(G/(2 rho))``);
- the **axial height** ``h``: the wire stack of the solid length and the coil gaps
  ``p - h``;
- the **largest shear stress**, the straight bar's maximum corrected for the coil's curvature
  and the direct shear by the published factor of each shape (:meth:`WireSection.shear_stress`).

The shapes (``wire_shape`` of ``[spring]``):

``round``
    ``d``: ``J = pi d^4/32``, ``A = pi d^2/4``, ``h = d``; ``tau = k 8 F D/(pi d^3)`` with
    Bergstraesser's ``k = (w + 0.5)/(w - 0.75)``, ``w = D/d`` (EN 13906-1, Eq. (22);
    :func:`springdyn.valve.spring.stress.corrected_shear_stress`): unchanged.
``rectangular``
    ``b`` radial (``wire_width``) by ``h`` axial (``wire_height``), long side ``l``, short side
    ``t``: Saint-Venant's series (Timoshenko & Goodier, *Theory of Elasticity*, 3rd ed., 1970,
    sec. 109, Eqs. (166)-(170); the coefficients of their Table 7 and of Roark's)
    ``J = l t^3 / 3 [1 - 192 t/(pi^5 l) sum tanh(m pi l/(2t))/m^5]``,
    ``tau_max = G theta t [1 - 8/pi^2 sum 1/(m^2 cosh(m pi l/(2t)))]`` (``m`` odd) at the middle
    of the long sides (:func:`rectangle_torsion`); the coil's curvature and direct shear by
    Goehner's factor as Roark gives it for rectangular wire,
    ``K = 1 + 1.2/w + 0.56/w^2 + 0.5/w^3`` with ``w = D/b`` (the dimension in the coil's radial
    direction; Young & Budynas, *Roark's Formulas for Stress and Strain*, 7th ed., 2002, the
    torsion chapter's helical springs, after Goehner 1932 and Liesecke 1933, whose factors Wahl
    1963, ch. 12, plots): :func:`rectangular_curvature_factor`.
``ovate``
    an oval (elliptical) section, ``b`` radial by ``h`` axial: ``J = pi a^3 c^3/(a^2 + c^2)``
    and ``tau_max = 2 T/(pi a_max a_min^2)`` at the ends of the shorter axis, ``a = b/2``,
    ``c = h/2`` (Timoshenko & Goodier, sec. 105, Eqs. (h), (i)); corrected by Bergstraesser's
    factor at ``w = D/b``, so that equal axes give round wire exactly (EN 13906-1 gives no
    factor for oval wire; no published one was found for this release: docs/valve-spring.md).

A wire diameter that varies along the coil (``wire_diameter_profile``, round wire) is a
section at each turn: :func:`section_profile`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core.docstrings import ParameterDocs
from ...core.errors import InputError
from . import stress  # (the module: the stress factor stays at its one home)
from .geometry import parse_profile

__all__ = [
    "WIRE_SHAPES",
    "WireSection",
    "rectangle_torsion",
    "ellipse_torsion",
    "rectangular_curvature_factor",
    "wire_section",
    "section_profile",
    "stress_per_force",
    "wire_stack",
    "end_height",
    "section_along",
    "equivalent_diameters",
]

#: The wire shapes of ``[spring]`` ``wire_shape``.
WIRE_SHAPES = ("round", "ovate", "rectangular")

#: Odd terms of Saint-Venant's series for the rectangle: the rest of the ``1/m^5`` sum after
#: ``M`` terms is about ``1/(128 M^4)``, 1e-13 with 500 (and ``1/cosh`` falls faster).
SERIES_TERMS = 500

_DOCS = ParameterDocs(
    """
    width : float or array_like
        Dimension of the section in the coil's radial direction b [m].
    height : float or array_like
        Dimension of the section along the spring's axis h [m].
    torsion_constant : float or ndarray
        Saint-Venant's torsion constant ``J`` [m^4].
    stress_modulus : float or ndarray
        ``T / tau_max`` [m^3]: the largest shear stress is the torque over it.
    """
)


@_DOCS.fill
def rectangle_torsion(width, height):
    r"""Saint-Venant torsion of a rectangular bar: ``J = beta l t^3`` and ``tau_max = T/(alpha l t^2)``.

    .. math::

        \beta = \frac13\Bigl[1 - \frac{192\,t}{\pi^5 l}\sum_{m\ \mathrm{odd}}
        \frac{\tanh(m\pi l/2t)}{m^5}\Bigr],\qquad
        \alpha = \beta \Big/ \Bigl[1 - \frac{8}{\pi^2}\sum_{m\ \mathrm{odd}}
        \frac{1}{m^2\cosh(m\pi l/2t)}\Bigr]

    with ``l`` the long and ``t`` the short side.

    Parameters
    ----------
    {width height}

    Returns
    -------
    {torsion_constant stress_modulus}

    Notes
    -----
    Timoshenko & Goodier, *Theory of Elasticity*, 3rd ed., 1970, sec. 109, Eqs. (166)-(170)
    (their Table 7 lists ``alpha`` and ``beta``: 0.208 and 0.141 for a square, 0.333 for a thin
    strip).

    Examples
    --------
    >>> j, z = rectangle_torsion(1.0, 1.0)
    >>> round(j, 4), round(z, 4)
    (0.1406, 0.2082)
    """
    b, h = np.asarray(width, dtype=float), np.asarray(height, dtype=float)
    long, short = np.maximum(b, h), np.minimum(b, h)
    m = np.arange(1, 2 * SERIES_TERMS, 2, dtype=float)
    x = (m * np.pi / 2.0) * (long / short)[..., None]
    beta = (1.0 - 192.0 / np.pi**5 * (short / long) * np.sum(np.tanh(x) / m**5, axis=-1)) / 3.0
    # 1/cosh of a large argument: exp(-x) without overflow
    sech = 2.0 * np.exp(-x) / (1.0 + np.exp(-2.0 * x))
    peak = 1.0 - 8.0 / np.pi**2 * np.sum(sech / m**2, axis=-1)
    j = beta * long * short**3
    z = j / (short * peak)
    return (float(j), float(z)) if j.ndim == 0 else (j, z)


@_DOCS.fill
def ellipse_torsion(width, height):
    r"""Saint-Venant torsion of an elliptical bar: ``J`` and the stress modulus ``T / tau_max``.

    .. math::

        J = \frac{\pi a^3 c^3}{a^2 + c^2},\qquad \tau_{max} = \frac{2T}{\pi\,a_{max}\,a_{min}^2}

    ``a = b/2``, ``c = h/2`` (semi-axes); the largest stress at the ends of the shorter axis.

    Parameters
    ----------
    width, height : float or array_like
        The oval's axes across the coil (radial, ``b``) and along the spring's axis (``h``) [m].

    Returns
    -------
    torsion_constant : float or ndarray
        ``pi a^3 c^3/(a^2 + c^2)`` [m^4].
    stress_modulus : float or ndarray
        ``pi a_max a_min^2 / 2`` [m^3]: the torque over the largest stress.

    Notes
    -----
    Timoshenko & Goodier, *Theory of Elasticity*, 3rd ed., 1970, sec. 105, Eqs. (h), (i).

    Examples
    --------
    A circle of diameter 2: ``J = pi/2``, ``T/tau = pi/2``.

    >>> [round(v, 6) for v in ellipse_torsion(2.0, 2.0)]
    [1.570796, 1.570796]
    """
    a, c = 0.5 * np.asarray(width, dtype=float), 0.5 * np.asarray(height, dtype=float)
    j = np.pi * a**3 * c**3 / (a * a + c * c)
    z = 0.5 * np.pi * np.maximum(a, c) * np.minimum(a, c) ** 2
    return (float(j), float(z)) if j.ndim == 0 else (j, z)


def rectangular_curvature_factor(spring_index):
    """Stress factor of rectangular wire ``K = 1 + 1.2/w + 0.56/w^2 + 0.5/w^3`` [-].

    The coil's curvature and the direct shear raise the straight bar's largest stress by ``K``;
    ``w = D/b`` with ``b`` the wire's dimension in the coil's radial direction.

    Parameters
    ----------
    spring_index : float or array_like
        ``w = D/b`` [-], larger than 1.

    Notes
    -----
    Young & Budynas, *Roark's Formulas for Stress and Strain*, 7th ed., 2002, helical springs of
    rectangular wire (``1 + 1.2 (c/R) + 0.56 (c/R)^2 + 0.5 (c/R)^3`` with ``c/R = b/D``), after
    Goehner (1932) and Liesecke (1933) whose factors Wahl, *Mechanical Springs*, 1963, ch. 12
    gives.  The constants are as this project knows the book, not read from a copy for this
    release (a search of public sources found none, 2026-11-28; docs/references.md [Roark]):
    plausible (at ``w = 6`` it is 1.218, beside Bergstraesser's 1.238 for round wire), not
    verified.  Springdyn multiplies it by the exact Saint-Venant stress of the straight bar
    (:func:`rectangle_torsion`), where Roark's rectangular-wire formula multiplies it by the
    approximation ``P R (3b + 1.8t)/(8 b^2 t^2)``: the two differ by up to 4 % (+0.1 % square,
    +3 % at 1.5:1, +4 % at 2:1), springdyn's the higher.  For wire wound flatwise (the long side
    radial) the straight bar's largest stress is on the axial faces; that the factor applies
    there too is an assumption ([Wahl-1952] treats flatwise springs separately).

    Examples
    --------
    >>> round(rectangular_curvature_factor(6.0), 4)
    1.2179
    """
    w = np.asarray(spring_index, dtype=float)
    if np.any(~(w > 1.0)):
        raise InputError(f"spring index D/b = {spring_index!r} must be larger than 1")
    k = 1.0 + 1.2 / w + 0.56 / w**2 + 0.5 / w**3
    return float(k) if k.ndim == 0 else k


@dataclass(frozen=True)
class WireSection:
    """A wire's cross-section: its shape and its radial and axial dimensions [m].

    Examples
    --------
    >>> s = WireSection("ovate", 4.0e-3, 3.2e-3)
    >>> round(s.area * 1e6, 3), round(s.height * 1e3, 2)
    (10.053, 3.2)
    """

    shape: str
    width: float  # b, radial [m] (round: d)
    height: float  # h, axial [m] (round: d)

    def __post_init__(self):
        if self.shape not in WIRE_SHAPES:
            raise InputError(f"wire_shape = {self.shape!r} is not allowed; choose one of {', '.join(WIRE_SHAPES)}")

    @property
    def area(self) -> float:
        """Area of the section ``A`` [m^2]: ``pi d^2/4``, ``pi b h/4``, ``b h``."""
        b, h = self.width, self.height
        return b * h if self.shape == "rectangular" else math.pi * b * h / 4.0

    @property
    def torsion_constant(self) -> float:
        """Saint-Venant torsion constant ``J`` [m^4] (:func:`rectangle_torsion`, :func:`ellipse_torsion`;
        round ``pi d^4/32``)."""
        if self.shape == "round":
            return math.pi * self.width**4 / 32.0
        law = rectangle_torsion if self.shape == "rectangular" else ellipse_torsion
        return law(self.width, self.height)[0]

    @property
    def bending_inertia(self) -> float:
        """Second moment of area ``I`` [m^4] for bending that strains the section across the coil's
        radius (the open coil's bending, :func:`springdyn.valve.spring.geometry.turn_compliance`):
        ``pi d^4/64``, ``pi b^3 h/64``, ``b^3 h/12``."""
        b, h = self.width, self.height
        return b**3 * h / 12.0 if self.shape == "rectangular" else math.pi * b**3 * h / 64.0

    @property
    def rate_diameter(self) -> float:
        """The round wire of the same torsion constant, ``(32 J/pi)^(1/4)`` [m]: in the round wire's
        rate ``G d^4/(8 D^3 n)`` it gives ``4 G J/(pi D^3 n)``."""
        return self.width if self.shape == "round" else (32.0 * self.torsion_constant / math.pi) ** 0.25

    @property
    def mass_diameter(self) -> float:
        """The round wire of the same area, ``sqrt(4 A/pi)`` [m] (the spring's mass)."""
        return self.width if self.shape == "round" else math.sqrt(4.0 * self.area / math.pi)

    @property
    def surge_diameter(self) -> float:
        """The round wire of the same surge frequency, ``sqrt(8 J/A)`` [m]: in Wahl's
        ``d/(2 pi n D^2) sqrt(G/(2 rho))`` it gives ``sqrt(G J/(rho A))/(pi n D^2)``."""
        return self.width if self.shape == "round" else math.sqrt(8.0 * self.torsion_constant / self.area)

    def spring_index(self, mean_diameter):
        """Spring index ``w = D/b`` [-] (``b`` radial; round ``D/d``, EN 13906-1).

        Parameters
        ----------
        mean_diameter : float or array_like
            Mean coil diameter D [m].
        """
        return mean_diameter / self.width

    def stress_factor(self, mean_diameter):
        """The factor on the straight bar's largest stress for the coil's curvature and the direct
        shear [-]: Bergstraesser's (round and ovate, EN 13906-1 Eq. (22)) or Goehner's
        (rectangular, :func:`rectangular_curvature_factor`), at ``w = D/b``.

        Parameters
        ----------
        mean_diameter : float or array_like
            Mean coil diameter D [m].
        """
        w = self.spring_index(mean_diameter)
        return rectangular_curvature_factor(w) if self.shape == "rectangular" else stress.bergstraesser_factor(w)

    @property
    def stress_factor_name(self) -> str:
        """What :meth:`stress_factor` is for this section, in words (the reports name the factor by it)."""
        if self.shape == "rectangular":
            return "Goehner's curvature factor of rectangular wire (Roark), at D/b"
        if self.shape == "ovate":
            return "Bergstraesser's k (EN 13906-1 Eq. (22)) at D/b, on the ellipse's largest stress"
        return "Bergstraesser's k (EN 13906-1 Eq. (22))"

    @property
    def stress_modulus(self) -> float:
        """The straight bar's ``T / tau_max`` [m^3]: ``pi d^3/16`` (round) and the Saint-Venant
        forms of :func:`rectangle_torsion` and :func:`ellipse_torsion`."""
        if self.shape == "round":
            return math.pi * self.width**3 / 16.0
        law = rectangle_torsion if self.shape == "rectangular" else ellipse_torsion
        return law(self.width, self.height)[1]

    def shear_stress(self, force, mean_diameter):
        """Corrected largest shear stress of the wire ``K (F D/2) / Z`` [Pa] (``Z``: :attr:`stress_modulus`,
        ``K``: :meth:`stress_factor`); round wire gives EN 13906-1's ``k 8 F D/(pi d^3)``.

        Parameters
        ----------
        force : float or array_like
            Axial force [N].
        mean_diameter : float or array_like
            Mean coil diameter D [m].
        """
        return (
            self.stress_factor(mean_diameter)
            * 0.5
            * np.asarray(force, dtype=float)
            * mean_diameter
            / self.stress_modulus
        )

    @property
    def label(self) -> str:
        """The section in words, e.g. ``"ovate 4 x 3.2 mm"``."""
        if self.shape == "round":
            return f"round {self.width * 1e3:.4g} mm"
        return f"{self.shape} {self.width * 1e3:.4g} x {self.height * 1e3:.4g} mm (radial x axial)"


def wire_section(spring) -> WireSection:
    """The nominal section of ``spring``'s wire (its ``wire_shape`` with ``wire_width`` and
    ``wire_height``; round: ``wire_diameter``).

    Parameters
    ----------
    spring : ValveSpring
    """
    shape = getattr(spring, "wire_shape", "round") or "round"
    if shape == "round":
        return WireSection("round", spring.wire_diameter, spring.wire_diameter)
    return WireSection(shape, spring.wire_width, spring.wire_height)


def section_profile(spring):
    """The wire diameter against turns from the seat end, or None for one wire throughout.

    Parameters
    ----------
    spring : ValveSpring
        Reads ``wire_diameter_profile`` (``"table: s d; ..."`` SI, or a CSV file with columns
        ``turns`` and ``wire_diameter_mm`` or ``wire_diameter_m``).

    Returns
    -------
    tuple of ndarray or None
        Knots [turns] and wire diameters [m], piecewise linear between.
    """
    value = getattr(spring, "wire_diameter_profile", "")
    if not value:
        return None
    return parse_profile(value, "wire_diameter_profile", {"wire_diameter_mm": 1e-3, "wire_diameter_m": 1.0})


def stress_per_force(spring, mean_diameters=None, turns=None) -> float:
    """The largest corrected shear stress per newton of axial force over the coils [Pa/N].

    The stress is linear in the force; with a diameter profile or a wire diameter that varies the
    largest ratio over the given coils judges the spring (the conservative reading of one
    force through every coil).

    Parameters
    ----------
    spring : ValveSpring
    mean_diameters : array_like, optional
        Mean coil diameters [m] at ``turns`` (default the spring's ``mean_diameter``).
    turns : array_like, optional
        Turns from the seat end [-] where they are (for a wire diameter profile).
    """
    dm = np.atleast_1d(np.asarray(spring.mean_diameter if mean_diameters is None else mean_diameters, dtype=float))
    prof = section_profile(spring)
    if prof is None or turns is None:
        ratio = wire_section(spring).shear_stress(1.0, dm)
        if prof is not None:  # no positions: the thinnest wire on the largest diameter
            thin = WireSection("round", float(prof[1].min()), float(prof[1].min()))
            ratio = np.maximum(ratio, thin.shear_stress(1.0, dm.max()))
        return float(np.max(ratio))
    d = np.interp(np.asarray(turns, dtype=float), *prof)
    k = stress.bergstraesser_factor(dm / d)
    return float(np.max(k * 8.0 * dm / (math.pi * d**3)))


def wire_stack(spring) -> float:
    """The wire stacked along the axis over all the turns, ``int h ds`` [m]: ``N h`` for one wire,
    the integral of a ``wire_diameter_profile`` otherwise (the solid length less what the ends
    add, :func:`springdyn.valve.spring.solid_length.solid_length`).

    Parameters
    ----------
    spring : ValveSpring
    """
    total = spring.low_pitch_coils + spring.high_pitch_coils
    prof = section_profile(spring)
    if prof is None:
        return wire_section(spring).height * total
    return float(np.trapezoid(prof[1], prof[0]))


def end_height(spring) -> float:
    """The wire's axial height at the spring's ends [m] (their mean, for a profile): what an end
    type adds to the wire stack is counted in it (EN 13906-1's ``(n_t + x) d``).

    Parameters
    ----------
    spring : ValveSpring
    """
    prof = section_profile(spring)
    if prof is None:
        return wire_section(spring).height
    return 0.5 * float(prof[1][0] + prof[1][-1])


def section_along(spring, turns) -> dict:
    """The wire's section at ``turns`` from the seat end (arrays of the shape of ``turns``).

    Parameters
    ----------
    spring : ValveSpring
    turns : array_like
        Turns from the seat end [-].

    Returns
    -------
    dict
        ``height`` [m], ``area`` [m^2]; ``wire_diameter`` [m] for round wire (the round-wire
        compliance of :func:`springdyn.valve.spring.geometry.turn_compliance`), else
        ``torsion_constant`` and ``bending_inertia`` [m^4].
    """
    s = np.asarray(turns, dtype=float)
    prof = section_profile(spring)
    sec = wire_section(spring)
    if prof is not None:
        d = np.interp(s, *prof)
        return dict(height=d, area=np.pi * d * d / 4.0, wire_diameter=d)
    out = dict(height=np.full(s.shape, sec.height), area=np.full(s.shape, sec.area))
    if sec.shape == "round":
        out["wire_diameter"] = sec.width
    else:
        out["torsion_constant"] = sec.torsion_constant
        out["bending_inertia"] = sec.bending_inertia
    return out


def equivalent_diameters(spring) -> dict:
    """The round wires a closed form of one wire takes for this spring's (Type C, the linear rate).

    Parameters
    ----------
    spring : ValveSpring
        Its wire: ``wire_shape`` with its dimensions, or a ``wire_diameter_profile``.

    Returns
    -------
    dict
        ``rate`` (the same rate: :attr:`WireSection.rate_diameter`; for a ``wire_diameter_profile``
        ``(mean d^-4)^(-1/4)`` over the active turns, the coils in series), ``mass`` (the same mass:
        :attr:`WireSection.mass_diameter`; for a profile the root mean square over all turns),
        ``surge`` (``rate^2/mass``: the same ``sqrt(J/A)``, :attr:`WireSection.surge_diameter`) [m].
    """
    prof = section_profile(spring)
    if prof is None:
        sec = wire_section(spring)
        return dict(rate=sec.rate_diameter, mass=sec.mass_diameter, surge=sec.surge_diameter)
    total = spring.low_pitch_coils + spring.high_pitch_coils
    active = np.linspace(spring.dead_coils, total - spring.dead_coils, 2001)
    every = np.linspace(0.0, total, 2001)
    rate = float((np.trapezoid(np.interp(active, *prof) ** -4.0, active) / (active[-1] - active[0])) ** -0.25)
    mass = float(np.sqrt(np.trapezoid(np.interp(every, *prof) ** 2, every) / total))
    return dict(rate=rate, mass=mass, surge=rate * rate / mass)
