"""Design figures valve-train engineers expect (not in the MMS document; notes 1.7).

EN 13906-1 helical compression spring relations on SI floats.
"""

from __future__ import annotations

import math

__all__ = [
    "spring_index",
    "bergstraesser_factor",
    "wahl_factor",
    "shear_stress",
    "surge_margin",
]


def spring_index(do: float, dw: float) -> float:
    """Spring index ``C = D/d`` [-] (mean coil diameter over wire diameter)."""
    return do / dw


def bergstraesser_factor(c: float) -> float:
    """Stress correction ``k = (4C + 2)/(4C - 3)`` [-] (Bergstraesser, EN 13906-1)."""
    return (4.0 * c + 2.0) / (4.0 * c - 3.0)


def wahl_factor(c: float) -> float:
    """Wahl stress correction ``(4C - 1)/(4C - 4) + 0.615/C`` [-]."""
    return (4.0 * c - 1.0) / (4.0 * c - 4.0) + 0.615 / c


def shear_stress(force, do: float, dw: float, correction: float = 1.0):
    """Corrected torsional shear stress ``k 8 F D / (pi d^3)`` [Pa].

    Parameters
    ----------
    force : float or ndarray
        Spring force [N].
    do, dw : float
        Mean coil and wire diameters [m].
    correction : float
        Curvature correction (Bergstraesser or Wahl); 1 for the nominal stress.
    """
    return correction * 8.0 * force * do / (math.pi * dw**3)


def surge_margin(surge_frequency: float, cam_speed_rpm: float) -> float:
    """Ratio of the spring's surge frequency to the camshaft frequency [-].

    A common rule of thumb asks for 10-13 or more (notes 1.7): cam-order harmonics up to
    that order then stay below the first surge mode.
    """
    return surge_frequency / (cam_speed_rpm / 60.0)
