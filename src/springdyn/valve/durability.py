"""Fatigue of the spring wire: corrected shear stress and the Goodman safety factor.

The wire of a helical spring is loaded in torsion. Its shear stress, corrected for the
curvature of the coil and the direct shear (EN 13906-1, Eq. (22); identical to
Bergstraesser's factor), is

    tau = k 8 F D / (pi d^3),   k = (w + 0.5) / (w - 0.75),   w = D / d.

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
``tau_e = S_sa / (1 - S_sm / S_su)``.  (These are the building blocks of the fatigue
assessment of the valve spring; the assessment over a simulated cycle is future work.)
"""

from __future__ import annotations

import math

import numpy as np

from ..core.errors import InputError

__all__ = [
    "stress_correction_factor",
    "corrected_shear_stress",
    "ultimate_shear_strength",
    "zimmerli_endurance_shear_strength",
    "goodman_safety_factor",
    "ULTIMATE_SHEAR_FRACTION",
    "ZIMMERLI_PEENED",
]

#: Ultimate shear strength / tensile strength of spring wire (Shigley Sec. 10-4).
ULTIMATE_SHEAR_FRACTION = 0.67
#: Zimmerli's fatigue data for peened springs: (alternating, mean) shear strengths [Pa]
#: at 10^7 cycles (Shigley Sec. 10-9), valid for wire up to 10 mm of any spring steel.
ZIMMERLI_PEENED = (398e6, 534e6)
#: Zimmerli's data for unpeened springs [Pa] (Shigley Sec. 10-9).
ZIMMERLI_UNPEENED = (241e6, 379e6)


def stress_correction_factor(spring_index):
    """Stress correction factor ``k = (w + 0.5)/(w - 0.75)`` of EN 13906-1.

    It equals Bergstraesser's ``(4w + 2)/(4w - 3)``.

    Parameters
    ----------
    spring_index : float or array_like
        Spring index ``w = D/d`` [-], larger than 0.75.

    Examples
    --------
    >>> round(stress_correction_factor(22 / 3.5), 4)
    1.2258
    """
    w = np.asarray(spring_index, dtype=float)
    if np.any(~(w > 0.75)):
        raise InputError(f"spring_index = {spring_index!r} must be larger than 0.75")
    k = (w + 0.5) / (w - 0.75)
    return float(k) if k.ndim == 0 else k


def corrected_shear_stress(force, mean_diameter: float, wire_diameter: float):
    """Corrected torsional shear stress of the wire ``k 8 F D / (pi d^3)``.

    Parameters
    ----------
    force : float or array_like
        Axial spring force [N] (compression positive).
    mean_diameter : float
        Mean coil diameter ``D`` [m].
    wire_diameter : float
        Wire diameter ``d`` [m].

    Returns
    -------
    float or ndarray
        Shear stress [Pa].
    """
    k = stress_correction_factor(mean_diameter / wire_diameter)
    return k * 8.0 * np.asarray(force, dtype=float) * mean_diameter / (math.pi * wire_diameter ** 3)


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


def zimmerli_endurance_shear_strength(ultimate_shear: float, peened: bool = True) -> float:
    """Fully reversed torsional endurance strength from Zimmerli's data via the Goodman line.

    ``tau_e = S_sa / (1 - S_sm / S_su)`` (Shigley Sec. 10-9, Eq. (10-30) solved for the
    fully reversed intercept).

    Parameters
    ----------
    ultimate_shear : float
        Torsional ultimate strength of the wire [Pa]; larger than Zimmerli's mean stress.
    peened : bool
        Shot-peened wire (valve springs are) or not.
    """
    s_sa, s_sm = ZIMMERLI_PEENED if peened else ZIMMERLI_UNPEENED
    if not ultimate_shear > s_sm:
        raise InputError(f"ultimate shear strength {ultimate_shear / 1e6:.4g} MPa must exceed Zimmerli's mean "
                         f"stress {s_sm / 1e6:.4g} MPa")
    return s_sa / (1.0 - s_sm / ultimate_shear)


def goodman_safety_factor(tau_min, tau_max, endurance_shear: float, ultimate_shear: float):
    """Fatigue safety factor of a shear-stress cycle on the modified Goodman line.

    ``n = 1 / (tau_a / tau_e + tau_m / tau_u)`` with ``tau_m = (tau_max + tau_min)/2`` and
    ``tau_a = (tau_max - tau_min)/2``.

    Parameters
    ----------
    tau_min, tau_max : float or array_like
        Smallest and largest shear stress of the cycle [Pa].
    endurance_shear : float
        Fully reversed torsional endurance strength [Pa].
    ultimate_shear : float
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
    if not (endurance_shear > 0 and ultimate_shear > 0):
        raise InputError("endurance_shear and ultimate_shear must be positive")
    mean, amp = 0.5 * (hi + lo), 0.5 * (hi - lo)
    demand = amp / endurance_shear + np.maximum(mean, 0.0) / ultimate_shear
    n = np.where(demand > 0, 1.0 / np.where(demand > 0, demand, 1.0), np.inf)
    if np.any(~np.isfinite(n)):
        raise InputError("a stress cycle with no stress has no fatigue safety factor")
    return float(n) if n.ndim == 0 else n
