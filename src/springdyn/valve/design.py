"""Design figures valve-train engineers expect (not in [MMS]).

EN 13906-1 helical compression spring relations on SI floats ([EN 13906-1], [Wahl];
see docs/references.md).
"""

from __future__ import annotations

import math

from ..core.errors import InputError

__all__ = [
    "spring_index",
    "bergstraesser_factor",
    "wahl_factor",
    "shear_stress",
    "surge_margin",
]


def spring_index(do: float, dw: float) -> float:
    """Spring index ``C = D/d`` [-] (mean coil diameter over wire diameter).

    Parameters
    ----------
    do : float
        Mean coil diameter [m].
    dw : float
        Wire diameter [m].

    Notes
    -----
    [EN 13906-1], spring index ``w = D/d``.
    """
    return do / dw


def bergstraesser_factor(c: float) -> float:
    r"""Stress correction ``k = (4C + 2)/(4C - 3)`` [-] (Bergstraesser).

    .. math::

        k = \frac{4C + 2}{4C - 3}

    Parameters
    ----------
    c : float
        Spring index ``D/d`` [-].

    Notes
    -----
    [EN 13906-1], stress correction factor k.

    Examples
    --------
    >>> round(bergstraesser_factor(22 / 3.5), 4)
    1.2258

    References
    ----------
    .. [1] EN 13906-1:2013, *Cylindrical helical springs made from round wire and bar:
       calculation and design*, compression springs ([EN 13906-1] of docs/references.md).
    """
    return (4.0 * c + 2.0) / (4.0 * c - 3.0)


def wahl_factor(c: float) -> float:
    """Wahl stress correction ``(4C - 1)/(4C - 4) + 0.615/C`` [-].

    Parameters
    ----------
    c : float
        Spring index ``D/d`` [-].

    Notes
    -----
    [Wahl], the curvature correction of torsional shear stress.
    """
    return (4.0 * c - 1.0) / (4.0 * c - 4.0) + 0.615 / c


def shear_stress(force, do: float, dw: float, correction: float = 1.0):
    r"""Corrected torsional shear stress ``k 8 F D / (pi d^3)`` [Pa].

    .. math::

        \tau_k = k\,\frac{8\,D\,F}{\pi\,d^3}

    Parameters
    ----------
    force : float or ndarray
        Spring force [N].
    do, dw : float
        Mean coil and wire diameters [m].
    correction : float
        Curvature correction (Bergstraesser or Wahl) [-]; 1 for the nominal stress.

    Notes
    -----
    [EN 13906-1], shear stress ``tau_k = k 8 D F / (pi d^3)``.

    Examples
    --------
    500 N on the one-step example's wire (D/d = 6.29, Bergstraesser k = 1.226):

    >>> round(shear_stress(500.0, 22e-3, 3.5e-3, bergstraesser_factor(22 / 3.5)) / 1e6, 1)
    800.8

    References
    ----------
    .. [1] EN 13906-1:2013, *Cylindrical helical springs made from round wire and bar:
       calculation and design*, compression springs ([EN 13906-1] of docs/references.md).
    """
    return correction * 8.0 * force * do / (math.pi * dw**3)


def surge_margin(surge_frequency: float, cam_speed_rpm: float) -> float:
    """Ratio of the spring's surge frequency to the camshaft frequency [-].

    A common rule of thumb of valve-train practice (not in [MMS]) asks for 10-13 or more:
    cam-order harmonics up to that order then stay below the first surge mode.

    Parameters
    ----------
    surge_frequency : float
        First surge frequency of the spring [Hz] ([Wahl]; [MMS], f1 and f2).
    cam_speed_rpm : float
        Camshaft speed [rev/min], positive.

    Raises
    ------
    InputError
        ``cam_speed_rpm`` is not a positive, finite speed (the margin needs a rotating cam).
    """
    if not (math.isfinite(cam_speed_rpm) and cam_speed_rpm > 0):
        raise InputError(f"cam_speed_rpm = {cam_speed_rpm!r} must be a positive, finite speed [rev/min]")
    return surge_frequency / (cam_speed_rpm / 60.0)
