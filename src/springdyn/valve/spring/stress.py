"""The stress in the spring wire and its fatigue: one home for the stress laws.

The wire of a helical spring is loaded in torsion. Its nominal shear stress is
``8 F D / (pi d^3)`` (:func:`nominal_shear_stress`); corrected for the curvature of the coil
and the direct shear (EN 13906-1, Eq. (22); Bergstraesser's factor) it is

    tau = k 8 F D / (pi d^3),   k = (w + 0.5) / (w - 0.75) = (4w + 2) / (4w - 3),   w = D / d

(:func:`corrected_shear_stress`, :func:`bergstraesser_factor`); ovate and rectangular wire
have their own sections and factors (:mod:`springdyn.valve.spring.wire`).  Wahl's factor
(:func:`wahl_factor`) is given beside it for comparison; every stress springdyn judges is
Bergstraesser's.

A stress cycle between ``tau_min`` and ``tau_max`` has the mean ``tau_m`` and the
amplitude ``tau_a``; the modified Goodman line between the fully reversed torsional
endurance strength ``tau_e`` and the torsional ultimate strength ``tau_u`` gives the
safety factor

    n = 1 / (tau_a / tau_e + tau_m / tau_u)

(Shigley's Mechanical Engineering Design, 10th ed., Sec. 10-9 and 6-12).

Strengths from the wire's tensile strength: the ultimate shear strength is 0.67 of it
(Shigley Sec. 10-4, after Joerres: ``S_su = 0.67 S_ut``), and the fully reversed torsional
endurance strength follows from Zimmerli's data for peened springs (``S_sa = 398 MPa`` at
``S_sm = 534 MPa``, Shigley Sec. 10-9) through the Goodman line
``tau_e = S_sa / (1 - S_sm / S_su)``.

:func:`spring_strengths` reads the wire's strengths from the spring definition
(``tensile_strength``, ``endurance_shear_strength``) or uses the documented defaults for
oil-tempered, shot-peened Cr-Si valve-spring wire (:data:`DEFAULT_TENSILE_STRENGTH`), and
says which defaults it used; :func:`fatigue_assessment` gives the factor of a force cycle.
The simulation results use it per element (Type C: its six elements; distributed: every
element, the coils' share) between the smallest and largest force of the cycle.
"""

from __future__ import annotations

import math

import numpy as np

from ...core.docstrings import ParameterDocs
from ...core.errors import InputError

__all__ = [
    "spring_index",
    "bergstraesser_factor",
    "wahl_factor",
    "nominal_shear_stress",
    "corrected_shear_stress",
    "ultimate_shear_strength",
    "zimmerli_endurance_shear_strength",
    "goodman_safety_factor",
    "ULTIMATE_SHEAR_FRACTION",
    "ZIMMERLI_PEENED",
    "DEFAULT_TENSILE_STRENGTH",
    "spring_strengths",
    "fatigue_assessment",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    wire_diameter : float or array_like
        Wire diameter ``d`` [m].
    mean_diameter : float or array_like
        Mean coil diameter ``D`` [m].
    force : float or array_like
        Axial spring force [N] (compression positive).
    """
)

#: Default tensile strength [Pa] of oil-tempered Cr-Si valve-spring wire of 3-4 mm
#: (EN 10270-2 grade VDSiCr: about 1960-2060 MPa at these diameters; the lower-middle value).
DEFAULT_TENSILE_STRENGTH = 2.0e9

#: Ultimate shear strength / tensile strength of spring wire (Shigley Sec. 10-4).
ULTIMATE_SHEAR_FRACTION = 0.67
#: Zimmerli's fatigue data for peened springs: (alternating, mean) shear strengths [Pa]
#: at 10^7 cycles (Shigley Sec. 10-9), valid for wire up to 10 mm of any spring steel.
ZIMMERLI_PEENED = (398e6, 534e6)
#: Zimmerli's data for unpeened springs [Pa] (Shigley Sec. 10-9).
ZIMMERLI_UNPEENED = (241e6, 379e6)


@_DOCS.fill
def spring_index(mean_diameter, wire_diameter):
    """Spring index ``w = D/d`` [-] (mean coil diameter over wire diameter).

    Parameters
    ----------
    {mean_diameter wire_diameter}

    Notes
    -----
    [EN 13906-1], spring index ``w = D/d``.
    """
    return mean_diameter / wire_diameter


def bergstraesser_factor(spring_index):
    r"""Stress correction factor ``k = (w + 0.5)/(w - 0.75)`` [-] of EN 13906-1 (Bergstraesser).

    .. math::

        k = \frac{w + 0.5}{w - 0.75} = \frac{4w + 2}{4w - 3}

    Parameters
    ----------
    spring_index : float or array_like
        Spring index ``w = D/d`` [-], larger than 0.75.

    Notes
    -----
    [EN 13906-1], Eq. (22), stress correction factor k.

    Examples
    --------
    >>> round(bergstraesser_factor(22 / 3.5), 4)
    1.2258
    """
    w = np.asarray(spring_index, dtype=float)
    if np.any(~(w > 0.75)):
        raise InputError(f"spring_index = {spring_index!r} must be larger than 0.75")
    k = (w + 0.5) / (w - 0.75)
    return float(k) if k.ndim == 0 else k


def wahl_factor(spring_index):
    """Wahl stress correction ``(4w - 1)/(4w - 4) + 0.615/w`` [-], for comparison with
    :func:`bergstraesser_factor` (springdyn judges Bergstraesser's).

    Parameters
    ----------
    spring_index : float or array_like
        Spring index ``w = D/d`` [-].

    Notes
    -----
    [Wahl], the curvature correction of torsional shear stress.
    """
    return (4.0 * spring_index - 1.0) / (4.0 * spring_index - 4.0) + 0.615 / spring_index


@_DOCS.fill
def nominal_shear_stress(force, mean_diameter, wire_diameter):
    r"""Nominal (uncorrected) torsional shear stress of the wire ``8 F D / (pi d^3)`` [Pa].

    .. math::

        \tau = \frac{8\,D\,F}{\pi\,d^3}

    EN 13906-1 states its relaxation charts and the permissible stress at solid length in it.

    Parameters
    ----------
    {force mean_diameter wire_diameter}

    Notes
    -----
    [EN 13906-1], shear stress ``tau = 8 D F / (pi d^3)``.
    """
    return 8.0 * np.asarray(force, dtype=float) * mean_diameter / (math.pi * wire_diameter**3)


@_DOCS.fill
def corrected_shear_stress(force, mean_diameter, wire_diameter):
    """Corrected torsional shear stress of the wire ``k 8 F D / (pi d^3)`` [Pa]
    (:func:`bergstraesser_factor` times :func:`nominal_shear_stress`).

    Parameters
    ----------
    {force mean_diameter wire_diameter}

    Returns
    -------
    float or ndarray
        Shear stress [Pa].

    Notes
    -----
    [EN 13906-1], Eq. (22), ``tau_k = k 8 D F / (pi d^3)``.

    Examples
    --------
    500 N on the one-step example's wire (D/d = 6.29, k = 1.226):

    >>> round(float(corrected_shear_stress(500.0, 22e-3, 3.5e-3)) / 1e6, 1)
    800.8
    """
    k = bergstraesser_factor(spring_index(mean_diameter, wire_diameter))
    return k * 8.0 * np.asarray(force, dtype=float) * mean_diameter / (math.pi * wire_diameter**3)


def ultimate_shear_strength(tensile_strength, fraction: float = ULTIMATE_SHEAR_FRACTION):
    """Torsional ultimate strength of spring wire from its tensile strength.

    Parameters
    ----------
    tensile_strength : float
        Tensile strength of the wire [Pa].
    fraction : float
        Ratio of ultimate shear to tensile strength [-] (Shigley Sec. 10-4: 0.67).
    """
    return fraction * tensile_strength


def zimmerli_endurance_shear_strength(ultimate_shear, peened: bool = True):
    """Fully reversed torsional endurance strength from Zimmerli's data via the Goodman line.

    ``tau_e = S_sa / (1 - S_sm / S_su)`` (Shigley Sec. 10-9, Eq. (10-30) solved for the
    fully reversed intercept).

    Parameters
    ----------
    ultimate_shear : float or array_like
        Torsional ultimate strength of the wire [Pa]; larger than Zimmerli's mean stress.
    peened : bool
        Shot-peened wire (valve springs are) or not.

    Returns
    -------
    float or ndarray
        Endurance strength [Pa].
    """
    s_sa, s_sm = ZIMMERLI_PEENED if peened else ZIMMERLI_UNPEENED
    u = np.asarray(ultimate_shear, dtype=float)
    bad = ~(u > s_sm)
    if np.any(bad):
        raise InputError(
            f"ultimate shear strength {float(u[bad].flat[0] if u.ndim else u) / 1e6:.4g} MPa must exceed Zimmerli's mean "
            f"stress {s_sm / 1e6:.4g} MPa"
        )
    tau_e = s_sa / (1.0 - s_sm / u)
    return float(tau_e) if tau_e.ndim == 0 else tau_e


def goodman_safety_factor(tau_min, tau_max, endurance_shear: float, ultimate_shear: float):
    """Fatigue safety factor of a shear-stress cycle on the modified Goodman line.

    ``n = 1 / (tau_a / tau_e + tau_m / tau_u)`` with ``tau_m = (tau_max + tau_min)/2`` and
    ``tau_a = (tau_max - tau_min)/2``.

    Parameters
    ----------
    tau_min, tau_max : float or array_like
        Smallest and largest shear stress of the cycle [Pa].
    endurance_shear : float or array_like
        Fully reversed torsional endurance strength [Pa].
    ultimate_shear : float or array_like
        Torsional ultimate strength [Pa].

    Examples
    --------
    A static stress of half the ultimate strength: n = 2.

    >>> goodman_safety_factor(500e6, 500e6, 400e6, 1000e6)
    2.0
    """
    lo, hi = np.asarray(tau_min, dtype=float), np.asarray(tau_max, dtype=float)
    if np.any(hi < lo):
        raise InputError("tau_max must not be below tau_min")
    if not (np.all(np.asarray(endurance_shear) > 0) and np.all(np.asarray(ultimate_shear) > 0)):
        raise InputError("endurance_shear and ultimate_shear must be positive")
    mean, amp = 0.5 * (hi + lo), 0.5 * (hi - lo)
    demand = amp / endurance_shear + np.maximum(mean, 0.0) / ultimate_shear
    n = np.where(demand > 0, 1.0 / np.where(demand > 0, demand, 1.0), np.inf)
    if np.any(~np.isfinite(n)):
        raise InputError("a stress cycle with no stress has no fatigue safety factor")
    return float(n) if n.ndim == 0 else n


def spring_strengths(spring) -> dict:
    """Torsional ultimate and endurance strengths of a spring's wire, and which are defaults.

    Parameters
    ----------
    spring : ValveSpring
        Reads ``tensile_strength`` [Pa] and ``endurance_shear_strength`` [Pa] (None: the
        defaults of this module: :data:`DEFAULT_TENSILE_STRENGTH`, and Zimmerli's peened
        data through the Goodman line).

    Returns
    -------
    dict
        ``tensile_strength_Pa``, ``ultimate_shear_strength_Pa`` (0.67 of the tensile),
        ``endurance_shear_strength_Pa``, ``shear_stress_limit_Pa`` (``shear_yield_strength``,
        else the ultimate shear strength), ``strength_defaults`` (the keys that took defaults).
    """
    defaults = []
    rm = getattr(spring, "tensile_strength", None)
    if rm is None:
        rm = DEFAULT_TENSILE_STRENGTH
        defaults.append("tensile_strength")
    tau_u = ultimate_shear_strength(rm)
    tau_e = getattr(spring, "endurance_shear_strength", None)
    if tau_e is None:
        tau_e = zimmerli_endurance_shear_strength(tau_u, peened=True)
        defaults.append("endurance_shear_strength")
    limit = getattr(spring, "shear_yield_strength", None)
    return dict(
        tensile_strength_Pa=float(rm),
        ultimate_shear_strength_Pa=float(tau_u),
        endurance_shear_strength_Pa=float(tau_e),
        shear_stress_limit_Pa=float(tau_u if limit is None else limit),
        shear_stress_limit_source="ultimate shear strength" if limit is None else "shear_yield_strength",
        strength_defaults=defaults,
    )


def fatigue_assessment(spring, force_min, force_max) -> dict:
    """Goodman fatigue safety factor of the wire for axial force cycles.

    Parameters
    ----------
    spring : ValveSpring
        Its model's corrected stress per newton (``spring_model.stress_per_force``: the wire's
        section and factor, the largest over the coils of a diameter or wire profile: the
        conservative choice) and strengths (:func:`spring_strengths`).
    force_min, force_max : float or array_like
        Smallest and largest force of the cycle [N] (per element for an array).

    Returns
    -------
    dict
        ``min_shear_stress_Pa``, ``max_shear_stress_Pa`` (the corrected stress of the wire's
        section, EN 13906-1's for round wire, at the critical element), ``fatigue_safety_factor`` (the smallest over the elements),
        ``critical_element`` (its index, 0 at the seat), and the strengths.
    """
    per_force = spring.spring_model.stress_per_force  # the section's corrected stress per newton (wire.py)
    lo = np.atleast_1d(np.asarray(force_min, dtype=float))
    hi = np.atleast_1d(np.asarray(force_max, dtype=float))
    tau_lo = per_force * np.maximum(lo, 0.0)
    tau_hi = per_force * np.maximum(hi, 0.0)
    st = spring_strengths(spring)
    demand = (
        0.5 * (tau_hi - tau_lo) / st["endurance_shear_strength_Pa"]
        + 0.5 * (tau_hi + tau_lo) / st["ultimate_shear_strength_Pa"]
    )
    j = int(np.argmax(demand))
    n = (
        goodman_safety_factor(tau_lo[j], tau_hi[j], st["endurance_shear_strength_Pa"], st["ultimate_shear_strength_Pa"])
        if demand[j] > 0
        else None
    )
    return dict(
        min_shear_stress_Pa=float(tau_lo[j]),
        max_shear_stress_Pa=float(tau_hi[j]),
        fatigue_safety_factor=n,
        critical_element=j,
        **st,
    )
