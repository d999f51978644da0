"""An independent fine-grid "continuum" reference for the distributed valve-spring model.

Written from the constitutive definition only, without the code under test
(``springdyn.valve.spring.chains``, ``.statics``, ``.elements``, ``.modes``): from springdyn it
reads only the spring's input drawing (the :class:`~springdyn.valve.ValveSpring` keys and,
for a spring without an inline ``pitch_profile``, the pitch and diameter profile of
``spring.with_model("distributed").spring_model.geometry``).

Definition
----------
The wire position ``sigma`` counts turns from the seat end.  The active wire runs from
``Nb`` to ``N - Nb``; the closed dead coils do not deform and their wire mass moves with the
nearest end of the active wire.  Per turn of active wire, at the axial force ``F``:

- open-coil compliance (Wahl, energy method)
  ``c = 8 D^3 / (G d^4 cos a) (cos^2 a + (2 G/E) sin^2 a)``, ``tan a = p / (pi D)``,
  rate ``k_t = 1/c``;
- coil gap ``gamma = max(p - Dw, 0)``, contact stiffness of a closed turn
  ``K = pi D E / 1000`` (or the spring's ``contact_stiffness`` if it has one), contact
  onset ``w = 0.05 Dw``;
- law of the compression ``e`` per turn: ``F = k_t e`` below ``gamma``,
  ``F = k_t e + K (e - gamma)^2 / (2 w)`` up to ``gamma + w``,
  ``F = k_t e + K (e - gamma - w/2)`` beyond;
- total compression ``x(F) = int e(sigma; F) dsigma + F/K_seat + F/K_ret`` with the end
  contacts ``K_seat = pi D(0) E/1000`` and ``K_ret = pi D(N) E/1000`` in series.

The integral is a midpoint sum over ``slices`` equal slices of the active wire; the first
mode at set-up is that of the chain of slices linearised about the set-up state, with
the slice masses lumped half to each end and both ends held by the end contacts.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import eigvalsh_tridiagonal
from scipy.optimize import brentq

from springdyn.valve import ValveSpring

__all__ = [
    "CONTACT_ONSET",
    "DEFAULT_SLICES",
    "DEFAULT_SUB",
    "LOW_PITCH",
    "comparison_lift",
    "continuum_compression",
    "continuum_f1_setup",
    "continuum_force",
    "continuum_frequency",
    "contact_per_turn",
    "free_length_of",
    "graded_spring",
    "lowest_frequency",
    "open_coil_compliance",
    "profiles",
    "setup_state",
    "surge_frequency",
    "turn_compression",
    "turn_tangent",
    "uniform_spring",
]

#: Contact onset per turn as a fraction of the wire diameter [-].
CONTACT_ONSET = 0.05
#: Default number of slices of the active wire [-].
DEFAULT_SLICES = 4000
#: Sub-slices per slice for the tangent compliance at set-up [-].
DEFAULT_SUB = 16
#: Pitch of the low-pitch coils of the graded two-step springs [m]: Dw + 0.25 mm, so
#: that they close at about 35 N, well before the set-up length.
LOW_PITCH = 3.75e-3


# ---------------------------------------------------------------------- the drawing
def _parse_table(text: str) -> tuple[np.ndarray, np.ndarray]:
    rows = [r.split() for r in text[len("table:") :].split(";") if r.strip()]
    return np.array([float(r[0]) for r in rows]), np.array([float(r[1]) for r in rows])


def profiles(spring: ValveSpring) -> dict:
    """The spring's drawing: pitch and diameter against turns, coil counts, wire.

    Inline ``"table: s p; ..."`` profiles are read here; otherwise the profiles come from
    the distributed model's geometry (the drawing the model is given).

    Parameters
    ----------
    spring : ValveSpring
        The spring.

    Returns
    -------
    dict
        ``pitch(s)`` [m] and ``diameter(s)`` [m] (callables of turns from the seat end),
        ``N`` total turns [-], ``Nb`` dead coils per end [-], ``Dw`` wire diameter [m].
    """
    n_total = spring.low_pitch_coils + spring.high_pitch_coils
    nb = spring.dead_coils
    own_pitch = spring.pitch_profile.startswith("table:")
    own_diameter = not spring.diameter_profile or spring.diameter_profile.startswith("table:")
    if own_pitch and own_diameter:
        ps, pv = _parse_table(spring.pitch_profile)
        if spring.diameter_profile:
            ds, dv = _parse_table(spring.diameter_profile)
        else:
            ds, dv = np.array([0.0, n_total]), np.full(2, spring.mean_diameter)
        return dict(
            pitch=lambda s: np.interp(s, ps, pv),
            diameter=lambda s: np.interp(s, ds, dv),
            N=float(n_total),
            Nb=float(nb),
            Dw=float(spring.wire_diameter),
        )
    g = spring.with_model("distributed").spring_model.geometry
    return dict(pitch=g.pitch, diameter=g.diameter, N=float(g.turns), Nb=float(g.dead_coils), Dw=float(g.wire_diameter))


def contact_per_turn(spring: ValveSpring, diameter):
    """Contact stiffness of one closed turn [N/m]: ``pi D E / 1000``, or the spring's
    ``contact_stiffness`` when it has one that is not ``None``.

    Parameters
    ----------
    spring : ValveSpring
        The spring.
    diameter : float or ndarray
        Mean coil diameter D [m].
    """
    given = getattr(spring, "contact_stiffness", None)
    if given is not None:
        return np.full_like(np.asarray(diameter, dtype=float), float(given))
    return np.pi * np.asarray(diameter, dtype=float) * spring.youngs_modulus / 1000.0


def open_coil_compliance(diameter, wire_diameter, pitch, shear_modulus, youngs_modulus):
    """Axial compliance of one open turn [m/N] (Wahl, energy method).

    ``c = 8 D^3 / (G d^4 cos a) (cos^2 a + (2 G/E) sin^2 a)``, ``tan a = p / (pi D)``.

    Parameters
    ----------
    diameter : float or ndarray
        Mean coil diameter D [m].
    wire_diameter : float
        Wire diameter d [m].
    pitch : float or ndarray
        Pitch p [m].
    shear_modulus, youngs_modulus : float
        G and E [Pa].
    """
    a = np.arctan(np.asarray(pitch, dtype=float) / (np.pi * np.asarray(diameter, dtype=float)))
    ca, sa = np.cos(a), np.sin(a)
    return (
        8.0
        * diameter**3
        / (shear_modulus * wire_diameter**4 * ca)
        * (ca**2 + 2.0 * shear_modulus / youngs_modulus * sa**2)
    )


def _wire_per_turn(diameter, pitch):
    return np.sqrt((np.pi * diameter) ** 2 + pitch**2)


def _slices(spring: ValveSpring, slices: int) -> dict:
    """Midpoint slices of the active wire: positions [turns], width [turns], per-turn
    rate k_t [N/m], gap [m], contact K [N/m], onset [m], slice masses and dead masses [kg]."""
    pr = profiles(spring)
    n_total, nb, dw = pr["N"], pr["Nb"], pr["Dw"]
    ds = (n_total - 2 * nb) / slices
    s = nb + (np.arange(slices) + 0.5) * ds
    d, p = pr["diameter"](s), pr["pitch"](s)
    area = np.pi * dw**2 / 4
    kt = 1.0 / open_coil_compliance(d, dw, p, spring.shear_modulus, spring.youngs_modulus)

    def dead_mass(a, b):
        m = max(int(np.ceil((b - a) / ds)), 200)
        x = a + (np.arange(m) + 0.5) * (b - a) / m
        return spring.density * area * float(np.sum(_wire_per_turn(pr["diameter"](x), pr["pitch"](x)))) * (b - a) / m

    return dict(
        s=s,
        ds=ds,
        kt=kt,
        gap=np.maximum(p - dw, 0.0),
        K=contact_per_turn(spring, d),
        w=np.full(slices, CONTACT_ONSET * dw),
        mass=spring.density * area * _wire_per_turn(d, p) * ds,
        dead=(dead_mass(0.0, nb) if nb > 0 else 0.0, dead_mass(n_total - nb, n_total) if nb > 0 else 0.0),
        k_seat=float(contact_per_turn(spring, pr["diameter"](0.0))),
        k_ret=float(contact_per_turn(spring, pr["diameter"](n_total))),
    )


# ---------------------------------------------------------------------- the per-turn law
def turn_compression(force, kt, gap, K, w):
    """Compression per turn [m] at the axial force ``force`` [N]: the per-turn law inverted
    in closed form.

    Parameters
    ----------
    force : float
        Axial force F [N], ``>= 0``.
    kt, gap, K, w : ndarray
        Per-turn rate [N/m], gap [m], contact stiffness [N/m] and onset [m].
    """
    f_gap = kt * gap
    f_full = kt * (gap + w) + 0.5 * K * w
    a = K / (2.0 * w)
    rest = np.maximum(force - f_gap, 0.0)
    u = 2.0 * rest / (kt + np.sqrt(kt * kt + 4.0 * a * rest))  # root of a u^2 + kt u = F - kt gap
    return np.where(
        force < f_gap,
        force / kt,
        np.where(force < f_full, gap + u, (force + K * (gap + 0.5 * w)) / (kt + K)),
    )


def turn_tangent(e, kt, gap, K, w):
    """Tangent rate ``dF/de`` of one turn [N/m] at the compression per turn ``e`` [m].

    Parameters
    ----------
    e : ndarray
        Compression per turn [m].
    kt, gap, K, w : ndarray
        Per-turn rate [N/m], gap [m], contact stiffness [N/m] and onset [m].
    """
    return kt + K * np.clip((e - gap) / w, 0.0, 1.0)


# ---------------------------------------------------------------------- statics
def continuum_compression(spring: ValveSpring, force: float, slices: int = DEFAULT_SLICES) -> float:
    """Total compression ``x(F)`` [m] of the spring at the axial force ``force`` [N].

    Parameters
    ----------
    spring : ValveSpring
        The spring.
    force : float
        Axial force [N].
    slices : int
        Midpoint slices of the active wire [-].
    """
    sl = _slices(spring, slices)
    return _compression(sl, force)


def _compression(sl: dict, force: float) -> float:
    e = turn_compression(force, sl["kt"], sl["gap"], sl["K"], sl["w"])
    return float(np.sum(e) * sl["ds"] + force / sl["k_seat"] + force / sl["k_ret"])


def _force(sl: dict, compression: float) -> float:
    if compression <= 0:
        return 0.0
    hi = compression / (np.sum(1.0 / sl["kt"]) * sl["ds"])  # open-coil force: an upper bound
    while _compression(sl, hi) < compression:  # pragma: no cover - open-coil is already above
        hi *= 2.0
    return float(brentq(lambda f: _compression(sl, f) - compression, 0.0, hi, xtol=1e-12, rtol=1e-14, maxiter=500))


def continuum_force(spring: ValveSpring, length: float, slices: int = DEFAULT_SLICES) -> float:
    """Static force [N] at the spring length ``length`` [m]: ``x(F) = Lf - length``.

    Parameters
    ----------
    spring : ValveSpring
        The spring.
    length : float
        Spring length [m].
    slices : int
        Midpoint slices of the active wire [-].
    """
    return _force(_slices(spring, slices), spring.free_length - length)


def setup_state(
    spring: ValveSpring, slices: int = DEFAULT_SLICES, length: float | None = None, sub: int = DEFAULT_SUB
) -> dict:
    """The linearised chain at a length (default the installed length).

    Parameters
    ----------
    spring : ValveSpring
        The spring.
    slices : int
        Midpoint slices of the active wire [-].
    length : float, optional
        Spring length [m] (default ``installed_length``).
    sub : int
        Midpoint sub-slices per slice for the slice's tangent compliance [-] (1: the
        tangent at the slice's midpoint).

    Returns
    -------
    dict
        ``force`` [N]; ``s`` slice midpoints [turns], ``e`` and ``gap`` per turn [m];
        ``masses`` (``slices + 1`` nodes, dead coils on the end nodes) [kg] and
        ``stiffness`` (seat contact, ``slices`` slices, retainer contact) [N/m];
        ``dead_masses`` (seat end, retainer end) [kg], included in ``masses``.
    """
    length = spring.installed_length if length is None else float(length)
    sl = _slices(spring, slices)
    force = _force(sl, spring.free_length - length)
    e = turn_compression(force, sl["kt"], sl["gap"], sl["K"], sl["w"])
    # tangent compliance of each slice: int dsigma / (dF/de) over the slice, by the midpoint
    # rule on ``sub`` sub-slices (a slice in the contact onset of a transition closes over
    # a small part of its width: the tangent there varies a hundredfold within a slice)
    fine = _slices(spring, slices * sub)
    e_fine = turn_compression(force, fine["kt"], fine["gap"], fine["K"], fine["w"])
    c_fine = 1.0 / turn_tangent(e_fine, fine["kt"], fine["gap"], fine["K"], fine["w"])
    k = 1.0 / (c_fine.reshape(slices, sub).sum(axis=1) * fine["ds"])
    masses = np.zeros(slices + 1)
    masses[:-1] += sl["mass"] / 2
    masses[1:] += sl["mass"] / 2
    masses[0] += sl["dead"][0]
    masses[-1] += sl["dead"][1]
    return dict(
        force=force,
        s=sl["s"],
        e=e,
        gap=sl["gap"],
        masses=masses,
        stiffness=np.concatenate([[sl["k_seat"]], k, [sl["k_ret"]]]),
        dead_masses=sl["dead"],
    )


# ---------------------------------------------------------------------- modes
def lowest_frequency(masses, stiffness) -> float:
    """Lowest natural frequency [Hz] of a chain ``ground -k0- m0 -k1- ... m_n -k_{n+1}- ground``.

    Parameters
    ----------
    masses : ndarray
        Node masses [kg], n values.
    stiffness : ndarray
        Element stiffnesses [N/m], n + 1 values (the first and last to ground).
    """
    m = np.asarray(masses, dtype=float)
    k = np.asarray(stiffness, dtype=float)
    diag = (k[:-1] + k[1:]) / m
    off = -k[1:-1] / np.sqrt(m[:-1] * m[1:])
    lam = eigvalsh_tridiagonal(diag, off, select="i", select_range=(0, 0))[0]
    return float(np.sqrt(lam) / (2 * np.pi))


def continuum_frequency(spring: ValveSpring, length: float, slices: int = DEFAULT_SLICES) -> float:
    """First natural frequency [Hz] linearised about the static state at ``length`` [m].

    Parameters
    ----------
    spring : ValveSpring
        The spring.
    length : float
        Spring length [m].
    slices : int
        Midpoint slices of the active wire [-].
    """
    st = setup_state(spring, slices, length)
    return lowest_frequency(st["masses"], st["stiffness"])


def continuum_f1_setup(spring: ValveSpring, slices: int = DEFAULT_SLICES) -> float:
    """First natural frequency [Hz] at the installed length (seat and retainer fixed).

    Parameters
    ----------
    spring : ValveSpring
        The spring.
    slices : int
        Midpoint slices of the active wire [-].
    """
    return continuum_frequency(spring, spring.installed_length, slices)


def surge_frequency(shear_modulus, density, wire_diameter, mean_diameter, active_coils) -> float:
    """Continuum surge frequency of a fixed-fixed closed-coil spring [Hz]:
    ``f = d / (2 pi n D^2) sqrt(G / (2 rho))``.

    Parameters
    ----------
    shear_modulus : float
        G [Pa].
    density : float
        rho [kg/m^3].
    wire_diameter, mean_diameter : float
        d and D [m].
    active_coils : float
        n [-].
    """
    return wire_diameter / (2 * np.pi * active_coils * mean_diameter**2) * np.sqrt(shear_modulus / (2 * density))


# ---------------------------------------------------------------------- test springs
def free_length_of(turns, pitch, wire_diameter) -> float:
    """``Dw/2 + int p ds`` [m] of a piecewise-linear pitch profile (exact trapezoids).

    Parameters
    ----------
    turns : array_like
        Knots [turns from the seat end].
    pitch : array_like
        Pitch at the knots [m].
    wire_diameter : float
        Dw [m].
    """
    s, p = np.asarray(turns, dtype=float), np.asarray(pitch, dtype=float)
    return 0.5 * wire_diameter + float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(s)))


def _table(turns, pitch) -> str:
    return "table: " + "; ".join(f"{s!r} {p!r}" for s, p in zip(turns, pitch))


def graded_spring(transition_turns: float, pitch_ratio: float | None = None, kind: str = "one-step") -> ValveSpring:
    """A test spring with an explicit graded ``pitch_profile`` (distributed model).

    ``kind="one-step"``: the one-step example (Nb = 1, N = 7.5) with the pitch rising
    linearly from Dw to the active pitch over ``transition_turns`` at both ends of the
    active wire; the active pitch keeps the example's free length, 48 mm.

    ``kind="two-step"``: the two-step example (Nb = 1, N1 = 2, N2 = 6): dead coil, a
    transition of ``transition_turns`` to the low pitch :data:`LOW_PITCH` (up to turn N1),
    a transition of ``transition_turns`` to the high pitch ``pitch_ratio * LOW_PITCH``, a
    transition of ``transition_turns`` back to Dw at ``N - Nb``, dead coil.  The free length
    follows from the profile (48.0 mm for ratio 2, 64.9 mm for ratio 3: a pitch ratio of
    3 with pitches >= Dw cannot fit 48 mm).  The installed length stays 38 mm.

    Parameters
    ----------
    transition_turns : float
        Turns over which the pitch changes at each transition [-].
    pitch_ratio : float, optional
        High-to-low pitch ratio of a two-step spring [-].
    kind : str
        ``"one-step"`` or ``"two-step"``.
    """
    base = ValveSpring.example(kind)
    dw, nb = base.wire_diameter, base.dead_coils
    n = base.low_pitch_coils + base.high_pitch_coils
    t = float(transition_turns)
    if kind == "one-step":
        # Lf = Dw/2 + 2 Nb Dw + t (Dw + pa) + (N - 2 Nb - 2 t) pa
        pa = (base.free_length - 0.5 * dw - 2 * nb * dw - t * dw) / (n - 2 * nb - t)
        s = [0.0, nb, nb + t, n - nb - t, n - nb, n]
        p = [dw, dw, pa, pa, dw, dw]
    elif kind == "two-step":
        n1 = base.low_pitch_coils
        pl, ph = LOW_PITCH, float(pitch_ratio) * LOW_PITCH
        s = [0.0, nb, nb + t, n1, n1 + t, n - nb - t, n - nb, n]
        p = [dw, dw, pl, pl, ph, ph, dw, dw]
    else:
        raise ValueError(f"kind = {kind!r}")
    if np.any(np.diff(s) <= 0):
        raise ValueError(f"transition_turns = {t:g} does not fit the coils: knots {s}")
    if min(p) < dw:
        raise ValueError(f"pitch {min(p)} below the wire diameter {dw}")
    return base.replace(model="distributed", pitch_profile=_table(s, p), free_length=free_length_of(s, p, dw))


def uniform_spring(dead_coils: float = 0.0) -> ValveSpring:
    """The one-step example with one constant pitch over its active wire (no transitions;
    the dead coils, if any, closed at Dw with a step of 1e-7 turns to the active pitch).

    Parameters
    ----------
    dead_coils : float
        Dead coils per end Nb [-].
    """
    base = ValveSpring.example("one-step")
    dw, n, nb = base.wire_diameter, base.high_pitch_coils, float(dead_coils)
    pa = (base.free_length - 0.5 * dw - 2 * nb * dw) / (n - 2 * nb)
    if nb == 0:
        s, p = [0.0, n], [pa, pa]
    else:
        eps = 1e-7
        s = [0.0, nb, nb + eps, n - nb - eps, n - nb, n]
        p = [dw, dw, pa, pa, dw, dw]
    return base.replace(
        model="distributed", dead_coils=nb, pitch_profile=_table(s, p), free_length=free_length_of(s, p, dw)
    )


def comparison_lift(spring: ValveSpring) -> float:
    """Valve lift [m] of the static-force comparison: 9 mm, or less so as to stay 0.5 mm
    above the solid length ``Dw (N + 1/2)``.

    Parameters
    ----------
    spring : ValveSpring
        The spring.
    """
    n = spring.low_pitch_coils + spring.high_pitch_coils
    return min(9e-3, spring.installed_length - spring.wire_diameter * (n + 0.5) - 0.5e-3)
