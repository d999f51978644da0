"""Coil geometry of a valve spring along its wire: pitch and mean diameter against turns.

The wire position ``s`` counts turns from the seat end (0) to the retainer end
(``N1 + N2``).  Pitch ``p(s)`` (axial advance per turn of the unloaded spring) and mean coil
diameter ``D(s)`` are piecewise linear in ``s``.  The free length is
``Lf = a + int_0^N p(s) ds`` and the solid length the wire stack ``Lc = a + N Dw``, where
the end allowance ``a`` (:func:`end_allowance`) makes ``Lc`` the spring's one solid length
(:func:`springdyn.valve.spring.solid_length.solid_length`): ``a = Dw/2`` gives the
document's ``Lc = Dw (N1 + N2 + 0.5)``, ``a = 0`` EN 13906-1's closed and ground ends.

Default profiles (:func:`default_pitch_knots`) follow from the ``[spring]`` keys:

- dead coils ``Nb`` at each end are closed (pitch ``Dw``);
- a transition of :data:`TRANSITION_TURNS` turns at each end of the active coils, where the
  pitch rises linearly from ``Dw`` (these coils close one by one under load);
- one-step: a constant active pitch between the transitions, from the free length;
- two-step: the ``N1 - Nb`` low-pitch active coils next to the seat's dead coil, their pitch
  rising linearly from ``Dw`` to ``Dw + delta`` so that the last of them closes exactly at
  the set-up length (the Type C reading: the low-pitch section is closed at set-up), then a
  transition to the high-pitch coils, whose pitch follows from the free length.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.docstrings import ParameterDocs
from ...core.errors import InputError
from ...core.io import read_csv_columns
from ...core.units import format_mm

__all__ = [
    "TRANSITION_TURNS",
    "CoilGeometry",
    "default_pitch_knots",
    "drawing_pitch_knots",
    "parse_profile",
    "turn_compliance",
    "wire_length_per_turn",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    s : float or array_like
        Turns from the seat end [-].
    """
)

#: Turns over which the pitch rises from the closed dead coil to the active pitch (an
#: assumption typical of coiled valve springs; give a ``pitch_profile`` for a measured one).
TRANSITION_TURNS = 0.5


def turn_compliance(
    mean_diameter, wire_diameter, pitch, shear_modulus, youngs_modulus, torsion_constant=None, bending_inertia=None
):
    """Axial compliance of one turn of an open-coiled helix [m/N], torsion and bending.

    ``c = 8 D^3 / (G d^4 cos a) (cos^2 a + (2 G/E) sin^2 a)``, ``tan a = p/(pi D)``: the
    energy method for an axially loaded open-coiled helix (Wahl, *Mechanical Springs*,
    2nd ed., 1963, ch. 3; Timoshenko, *Strength of Materials* II).  For ``a -> 0`` it is the
    closed-coil ``8 D^3/(G d^4)``.  Any section: ``c = pi D^3/(4 cos a) (cos^2 a/(G J) +
    sin^2 a/(E I))`` with its torsion constant ``J`` and the second moment ``I`` of the bending
    across the coil's radius (:mod:`springdyn.valve.spring.wire`; round wire ``J = 2 I = pi d^4/32``
    gives the line above).

    Parameters
    ----------
    mean_diameter : float or ndarray
        Mean coil diameter D [m].
    wire_diameter : float or ndarray
        Wire diameter d [m] (round wire; unused with ``torsion_constant``).
    pitch : float or ndarray
        Pitch p [m].
    shear_modulus, youngs_modulus : float
        G and E [Pa].
    torsion_constant, bending_inertia : float or ndarray, optional
        ``J`` and ``I`` of a section that is not round [m^4].
    """
    a = np.arctan2(pitch, np.pi * mean_diameter)
    ca, sa = np.cos(a), np.sin(a)
    if torsion_constant is not None:
        return (
            np.pi
            * mean_diameter**3
            / (4.0 * ca)
            * (ca * ca / (shear_modulus * torsion_constant) + sa * sa / (youngs_modulus * bending_inertia))
        )
    return (
        8.0
        * mean_diameter**3
        / (shear_modulus * wire_diameter**4 * ca)
        * (ca * ca + 2.0 * shear_modulus / youngs_modulus * sa * sa)
    )


def wire_length_per_turn(mean_diameter, pitch):
    """Length of wire in one turn [m]: ``sqrt((pi D)^2 + p^2)``.

    Parameters
    ----------
    mean_diameter : float or ndarray
        Mean coil diameter D [m].
    pitch : float or ndarray
        Pitch p [m].
    """
    return np.hypot(np.pi * mean_diameter, pitch)


def parse_profile(value: str, what: str, unit_columns: dict) -> tuple[np.ndarray, np.ndarray]:
    """Turns and values (SI) of a profile key: an inline ``"table: s v; s v; ..."`` (SI, as
    written by :meth:`ValveSpring._prepare` from a TOML array) or a CSV file.

    Parameters
    ----------
    value : str
        The key's value.
    what : str
        Key name for messages.
    unit_columns : dict
        Accepted CSV value columns and their factor to SI, e.g. ``{"pitch_mm": 1e-3, "pitch_m": 1}``.
    """
    if value.startswith("table:"):
        rows = [r.split() for r in value[6:].split(";") if r.strip()]
        s = np.array([float(r[0]) for r in rows])
        v = np.array([float(r[1]) for r in rows])
    else:
        cols = read_csv_columns(value)
        if "turns" not in cols:
            raise InputError(
                f"{what} = {value!r}: the CSV needs a column 'turns' (wire position in turns from the "
                f"seat end) and one of {', '.join(unit_columns)}"
            )
        found = [c for c in unit_columns if c in cols]
        if not found:
            raise InputError(f"{what} = {value!r}: the CSV needs one of the columns {', '.join(unit_columns)}")
        s = cols["turns"]
        v = cols[found[0]] * unit_columns[found[0]]
    if s.size < 2 or np.any(np.diff(s) <= 0):
        raise InputError(f"{what}: needs at least 2 rows with strictly increasing turns")
    if np.any(~np.isfinite(v)) or np.any(v <= 0):
        raise InputError(f"{what}: every value must be positive")
    return s, v


@dataclass(frozen=True)
class CoilGeometry:
    """Pitch and mean diameter of the unloaded spring against turns from the seat end (SI)."""

    turns: float  # total turns N1 + N2
    dead_coils: float  # closed coils at each end
    wire_diameter: float  # [m]
    pitch_s: np.ndarray  # knots [turns]
    pitch_v: np.ndarray  # pitch at the knots [m]
    diameter_s: np.ndarray  # knots [turns]
    diameter_v: np.ndarray  # mean diameter at the knots [m]
    end_allowance: float | None = None  # a [m]: solid length minus the wire stack (None: Dw/2)
    height_s: np.ndarray | None = None  # knots of a wire that varies along the coil [turns] (None: one wire)
    height_v: np.ndarray | None = None  # its axial height at the knots [m]

    @property
    def allowance(self) -> float:
        """End allowance ``a`` [m]: the solid length less the wire stack ``N Dw``."""
        return 0.5 * self.wire_diameter if self.end_allowance is None else self.end_allowance

    @_DOCS.fill
    def pitch(self, s):
        """Pitch [m] at turns ``s`` from the seat end.

        Parameters
        ----------
        {s}
        """
        return np.interp(s, self.pitch_s, self.pitch_v)

    @_DOCS.fill
    def diameter(self, s):
        """Mean coil diameter [m] at turns ``s`` from the seat end.

        Parameters
        ----------
        {s}
        """
        return np.interp(s, self.diameter_s, self.diameter_v)

    @_DOCS.fill
    def height(self, s):
        """Axial height of the wire [m] at turns ``s`` from the seat end (the wire diameter, or
        the ``wire_height`` of a profiled wire).

        Parameters
        ----------
        {s}
        """
        if self.height_s is None:
            return np.full(np.shape(s), self.wire_diameter)
        return np.interp(s, self.height_s, self.height_v)

    @property
    def free_length(self) -> float:
        """``a + int p ds`` [m] (``a``: :attr:`allowance`)."""
        return self.allowance + float(np.trapezoid(self.pitch_v, self.pitch_s))

    @property
    def solid_length(self) -> float:
        """Wire stack ``a + N Dw`` [m] (``a + int h ds`` for a wire that varies): the spring's solid length."""
        if self.height_s is not None:
            return self.allowance + float(np.trapezoid(self.height_v, self.height_s))
        return self.allowance + self.wire_diameter * self.turns


def end_allowance(solid_length: float, wire_diameter: float, turns: float) -> float:
    """End allowance ``a = Lc - N Dw`` [m]: what the ends add to (or grind off) the wire stack.

    Parameters
    ----------
    solid_length : float
        The spring's solid length Lc [m] (by its end type).
    wire_diameter : float
        Wire diameter Dw [m].
    turns : float
        Total turns N [-].

    Examples
    --------
    >>> round(end_allowance(28e-3, 3.5e-3, 7.5) / 3.5e-3, 6)  # the document's Lc: half a wire
    0.5
    """
    return solid_length - wire_diameter * turns


def default_pitch_knots(
    n_total: float,
    dead: float,
    dw: float,
    free_length: float,
    installed_length: float,
    low_pitch: float,
    field,
    allowance: float | None = None,
    transition: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Knots (turns, pitch [m]) of the default pitch profile (see the module docstring).

    Parameters
    ----------
    n_total : float
        Total turns N1 + N2 [-].
    dead : float
        Dead coils per end Nb [-].
    dw : float
        Wire diameter [m].
    free_length, installed_length : float
        Lf and Ls [m].
    low_pitch : float
        N1 (0 for a one-step spring) [-].
    field : callable
        ``field(name)`` describes a ``[spring]`` key for messages.
    allowance : float, optional
        End allowance ``a`` [m] (:func:`end_allowance`; default ``Dw/2``, the document's).
    transition : float, optional
        Turns of each transition [-] (default :data:`TRANSITION_TURNS`).
    """
    transition = TRANSITION_TURNS if transition is None else transition
    active = n_total - 2 * dead
    tr = min(transition, active / 4.0) if dead > 0 else 0.0
    a = 0.5 * dw if allowance is None else allowance
    base = a + 2 * dead * dw  # free length of the closed dead coils and the ends
    if low_pitch <= 0:
        pa = (free_length - base - tr * dw) / (active - tr)
        if not pa > dw:
            raise InputError(
                f"{field('free_length')} is too short for the coils: the active pitch would be "
                f"{format_mm(pa)}, not more than the wire diameter {format_mm(dw)}"
            )
        if dead == 0:
            return np.array([0.0, n_total]), np.array([pa, pa])
        s = [0.0, dead, dead + tr, n_total - dead - tr, n_total - dead, n_total]
        p = [dw, dw, pa, pa, dw, dw]
        return _dedupe(s, p)
    nl = low_pitch - dead  # low-pitch active coils
    if nl <= 0:
        raise InputError(
            f"{field('low_pitch_coils')} must exceed {field('dead_coils')}: the low-pitch coils "
            "include the seat's dead coil"
        )
    rest = n_total - dead - low_pitch  # high-pitch active coils with their transitions
    trh = min(transition, rest / 4.0)
    tre = trh if dead > 0 else 0.0

    def knots(delta):
        p1 = dw + delta
        # free length: base + low section + transition + high section + end transition
        fixed = base + nl * (dw + p1) / 2 + trh * p1 / 2 + tre * dw / 2
        ph = (free_length - fixed) / (rest - trh / 2 - tre / 2)
        s = [0.0, dead, low_pitch, low_pitch + trh, n_total - dead - tre, n_total - dead, n_total]
        p = [dw, dw, p1, ph, ph, dw, dw]
        return np.array(s), np.array(p)

    def closed_at_setup(delta):
        s, p = knots(delta)
        grid = np.linspace(0.0, n_total, 20001)
        gap = np.interp(grid, s, p) - dw
        return float(np.trapezoid(np.minimum(gap, delta), grid)) - (free_length - installed_length)

    from scipy.optimize import brentq  # (here: scipy.optimize costs start-up of every valve command)

    hi = (free_length - base) / max(nl, 1e-9)
    try:
        delta = brentq(closed_at_setup, 1e-9, hi, xtol=1e-12)
    except ValueError:
        raise InputError(
            f"{field('installed_length')}: the low-pitch coils cannot be closed at the set-up length "
            "with the given free length and coil counts"
        ) from None
    s, p = knots(delta)
    if not p[3] > p[2]:
        raise InputError(
            f"two-step spring: the high-pitch coils' pitch {format_mm(p[3])} must exceed the low-pitch "
            f"coils' {format_mm(p[2])}; check {field('free_length')}, {field('installed_length')} and the "
            "coil counts"
        )
    return _dedupe(list(s), list(p))


def drawing_pitch_knots(
    n_total: float,
    dead: float,
    dw: float,
    low_coils: float,
    pitch: float,
    low_pitch: float | None = None,
    transition: float | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """Knots (turns, pitch [m]) of a spring whose drawing gives the pitch of its sections.

    The dead coils are closed (pitch ``Dw``); the pitch rises to the active pitch over
    :data:`TRANSITION_TURNS` turns at each end of the active coils (as in
    :func:`default_pitch_knots`); a two-step spring's ``N1 - Nb`` low-pitch active coils next
    to the seat's dead coil have the pitch ``low_pitch``, then a transition of the same length
    leads to the high-pitch coils' ``pitch``.  The free length is then
    ``a + int p ds`` (:attr:`CoilGeometry.free_length`).

    Parameters
    ----------
    n_total : float
        Total turns N1 + N2 [-].
    dead : float
        Dead coils per end Nb [-].
    dw : float
        Wire diameter [m].
    low_coils : float
        N1, the low-pitch coils with the seat's dead coil (0 for a one-step spring) [-].
    pitch : float
        Pitch of the (high-pitch) active coils [m].
    low_pitch : float, optional
        Pitch of the low-pitch active coils [m] (two-step).
    transition : float, optional
        Turns of each transition [-] (default :data:`TRANSITION_TURNS`).
    """
    transition = TRANSITION_TURNS if transition is None else transition
    active = n_total - 2 * dead
    if low_pitch is None:
        if dead == 0:  # open ends: the active pitch throughout
            return np.array([0.0, n_total]), np.array([pitch, pitch])
        tr = min(transition, active / 4.0)
        s = [0.0, dead, dead + tr, n_total - dead - tr, n_total - dead, n_total]
        p = [dw, dw, pitch, pitch, dw, dw]
        return _dedupe(s, p)
    nl = low_coils - dead  # low-pitch active coils
    rest = n_total - dead - low_coils  # high-pitch active coils
    trh = min(transition, rest / 4.0)
    if dead == 0:
        return _dedupe([0.0, low_coils, low_coils + trh, n_total], [low_pitch, low_pitch, pitch, pitch])
    tr = min(transition, nl / 2.0)
    s = [0.0, dead, dead + tr, low_coils, low_coils + trh, n_total - dead - trh, n_total - dead, n_total]
    p = [dw, dw, low_pitch, low_pitch, pitch, pitch, dw, dw]
    return _dedupe(s, p)


def _dedupe(s, p):
    s, p = np.asarray(s, float), np.asarray(p, float)
    keep = np.concatenate([[True], np.diff(s) > 1e-12])
    return s[keep], p[keep]


def check_profile_span(s: np.ndarray, n_total: float, what: str) -> None:
    """A profile must run from turn 0 to turn N1 + N2."""
    if abs(s[0]) > 1e-6 or abs(s[-1] - n_total) > 1e-6:
        raise InputError(
            f"{what}: the turns must run from 0 to low_pitch_coils + high_pitch_coils = {n_total:g} "
            f"(seat end to retainer end), not {s[0]:g} to {s[-1]:g}"
        )
