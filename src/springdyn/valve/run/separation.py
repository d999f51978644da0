"""Valve separation as valve-train engineers read it: lift-offs by cam phase, float, seat bounce.

A lift-off (the follower off the cam while the valve is open) means different things by
where on the cam it starts:

- **opening ramp** (lash take-up): from the lobe's start to the end of the opening ramp or
  of the lash take-up, whichever is later: the impact that takes up the lash;
- **opening flank**: positive valve acceleration on the way up: opening-side bounce (noise,
  wear);
- **nose**: the negative valve acceleration around the peak, where only the spring holds the
  follower on the cam: **float**;
- **closing flank** and **closing ramp**: the mirror images on the way down.

:func:`cam_phases` finds the phase boundaries from the cam's own lift and acceleration;
:func:`phase_of` names the phase of a cam angle; :func:`liftoffs` classifies the located
lift-offs of a revolution (whether the valve leaves the cam over the nose in it is the rule
:func:`springdyn.valve.run.verdicts.floats_over_nose`).  Over a speed scan, :func:`float_speed_of_scan` is the float speed
as the field defines it (the lowest speed from which the valve separates over the nose at
every higher speed), :func:`first_separation` the first speed with any lift-off, and
:func:`neighbour_band` the band of a scattering quantity (seat impact velocity) over
neighbouring speeds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

__all__ = [
    "PHASES",
    "CamPhases",
    "cam_phases",
    "phase_of",
    "phase_mask",
    "liftoffs",
    "float_speed_of_scan",
    "first_separation",
    "neighbour_band",
    "SEATING_BAND_RPM",
]

#: The phases of the cam event, in order (then the base circle).
PHASES = ("opening ramp", "opening flank", "nose", "closing flank", "closing ramp")
#: Samples of the cam per revolution to find the phase boundaries (0.05 deg).
PHASE_SAMPLES = 7200
#: Half-width of the speed window [rev/min] of :func:`neighbour_band`.
SEATING_BAND_RPM = 25.0

_TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class CamPhases:
    """Cam angles [rad] that bound the phases of the event (each in [0, 2 pi)).

    The event runs from ``start`` through ``ramp_end`` (end of the opening ramp or lash
    take-up), ``nose_start`` and ``nose_end`` (the negative acceleration around the peak) and
    ``ramp_start`` (start of the closing ramp) to ``end``; angles wrap through 0.
    """

    start: float
    ramp_end: float
    nose_start: float
    nose_end: float
    ramp_start: float
    end: float

    def as_degrees(self) -> dict:
        """The boundaries in degrees, by name."""
        return {k: math.degrees(v) for k, v in self.__dict__.items()}


def cam_phases(cam, lobe_lash: float = 0.0) -> CamPhases:
    """The phase boundaries of the cam's event (see the module docstring).

    Parameters
    ----------
    cam : Cam
        The cam (any law or a table).
    lobe_lash : float
        Lash at the cam [m]: the lobe lift up to which the valve stays seated (the lash
        take-up belongs to the opening ramp).

    Returns
    -------
    CamPhases
        Boundaries [rad]: the ramps are the cam's own (``ramp_duration``) or, where later,
        the lash take-up; the nose is the contiguous region of negative lift acceleration
        ``d2h/dtheta2 < 0`` around the largest lift.
    """
    theta = np.arange(PHASE_SAMPLES) * (_TWO_PI / PHASE_SAMPLES)
    h, _, ddh = cam.evaluate(theta)
    n = PHASE_SAMPLES
    peak = int(np.argmax(h))
    base = float(h.min()) + 1e-9 * max(float(h.max()), 1e-12)

    def walk(i, step, keep):
        for _ in range(n):
            j = (i + step) % n
            if not keep(j):
                return i
            i = j
        return i

    start = (walk(peak, -1, lambda j: h[j] > base) - 1) % n  # the last samples on the base circle
    end = (walk(peak, 1, lambda j: h[j] > base) + 1) % n
    nose_start = walk(peak, -1, lambda j: ddh[j] < 0.0)
    nose_end = walk(peak, 1, lambda j: ddh[j] < 0.0)
    ramp = int(round(getattr(cam, "ramp_duration", 0.0) / (_TWO_PI / n)))
    lashed_up = walk(start, 1, lambda j: h[j] < lobe_lash and j != peak)
    lashed_down = walk(end, -1, lambda j: h[j] < lobe_lash and j != peak)

    def off(i):  # samples after the event's start
        return (i - start) % n

    ramp_end = start + max(ramp, off(lashed_up))
    ramp_start = end - max(ramp, (end - lashed_down) % n)
    # the ramps never reach into the nose
    ramp_end = start + min(off(ramp_end), off(nose_start))
    ramp_start = start + max(off(ramp_start), off(nose_end))
    step = _TWO_PI / n
    return CamPhases(*[float((i % n) * step) for i in (start, ramp_end, nose_start, nose_end, ramp_start, end)])


def phase_of(angle: float, phases: CamPhases) -> str:
    """The phase (one of :data:`PHASES`, or ``"base circle"``) of a cam angle.

    Parameters
    ----------
    angle : float
        Cam angle [rad], any real.
    phases : CamPhases
        The cam's phase boundaries (:func:`cam_phases`).
    """
    s = phases.start

    def off(a):
        return (a - s) % _TWO_PI

    a = off(angle)
    bounds = [off(phases.ramp_end), off(phases.nose_start), off(phases.nose_end), off(phases.ramp_start)]
    end = off(phases.end) or _TWO_PI
    if a > end:
        return "base circle"
    for name, b in zip(PHASES, bounds):
        if a < b:
            return name
    return PHASES[-1]


def phase_mask(cam_angle, phases: CamPhases, name: str) -> np.ndarray:
    """Whether each cam angle lies in the phase ``name``.

    Parameters
    ----------
    cam_angle : array_like
        Cam angles [rad].
    phases : CamPhases
        The cam's phase boundaries.
    name : str
        One of :data:`PHASES` or ``"base circle"``.
    """
    s = phases.start
    a = (np.ravel(np.asarray(cam_angle, dtype=float)) - s) % _TWO_PI
    end = (phases.end - s) % _TWO_PI or _TWO_PI
    base = a > end
    if name == "base circle":
        return base
    # phase_of's walk through the bounds, on every angle at once
    bounds = [(b - s) % _TWO_PI for b in (phases.ramp_end, phases.nose_start, phases.nose_end, phases.ramp_start)]
    index = np.full(a.shape, len(PHASES) - 1)
    open_ = np.ones(a.shape, dtype=bool)
    for k, b in enumerate(bounds):
        hit = open_ & (a < b)
        index[hit] = k
        open_ &= ~hit
    return ~base & (index == PHASES.index(name))


def liftoffs(intervals, phases: CamPhases, cam_rpm: float, cam_angle=None, gap=None) -> list:
    """The lift-offs of a revolution, each with its phase.

    Parameters
    ----------
    intervals : sequence of (start_deg, end_deg, duration_deg)
        The located lift-offs [deg] (an interval through 0 deg has ``end < start``).
    phases : CamPhases
        The cam's phase boundaries.
    cam_rpm : float
        Cam speed [rev/min].
    cam_angle, gap : ndarray, optional
        The output grid [rad] and the cam gap on it [m] (the follower's distance from the
        cam): gives each lift-off's largest gap.

    Returns
    -------
    list of dict
        ``phase``, ``start_deg``, ``end_deg``, ``duration_deg``, ``duration_s`` and, with
        the gap, ``max_gap_m``.
    """
    out = []
    for a, b, c in intervals:
        row = dict(
            phase=phase_of(math.radians(a), phases),
            start_deg=float(a),
            end_deg=float(b),
            duration_deg=float(c),
            duration_s=float(c) / (6.0 * cam_rpm),
        )
        if gap is not None:
            deg = np.degrees(cam_angle)
            inside = (deg >= a) & (deg <= b) if a <= b else (deg >= a) | (deg <= b)
            row["max_gap_m"] = float(max(np.max(gap[inside], initial=0.0), 0.0))
        out.append(row)
    return out


def float_speed_of_scan(cam_rpm, nose_separation) -> float | None:
    """The float speed of a scan: the lowest scanned speed from which the valve separates
    over the nose at every higher scanned speed [rev/min] (None: not at the highest).

    Parameters
    ----------
    cam_rpm : array_like
        Scanned speeds [rev/min], ascending.
    nose_separation : array_like of bool
        Whether the valve separates over the nose at each speed [-].

    Examples
    --------
    >>> float_speed_of_scan([3000, 3100, 3200, 3300, 3400], [False, True, False, True, True])
    3300.0
    """
    rpm = np.asarray(cam_rpm, dtype=float)
    nose = np.asarray(nose_separation, dtype=bool)
    if not nose.size or not nose[-1]:
        return None
    held = np.flatnonzero(~nose)
    return float(rpm[held[-1] + 1]) if held.size else float(rpm[0])


def first_separation(cam_rpm, rows) -> dict | None:
    """The lowest scanned speed with any lift-off, and the phase of its first lift-off.

    Parameters
    ----------
    cam_rpm : array_like
        Scanned speeds [rev/min], ascending.
    rows : sequence of list
        Per speed, its lift-offs (:func:`liftoffs`).
    """
    for rpm, lo in zip(cam_rpm, rows):
        if lo:
            return dict(cam_rpm=float(rpm), phase=lo[0]["phase"], start_deg=lo[0]["start_deg"])
    return None


def neighbour_band(cam_rpm, values, width: float = SEATING_BAND_RPM) -> tuple:
    """Minimum, median and maximum of ``values`` over the speeds within ``width`` of each speed.

    The rule for a quantity that scatters from speed to speed (the seat impact velocity
    after float: a chaotic landing): each speed's band is taken over the scanned speeds
    within +-``width`` [rev/min] of it, itself included.

    Parameters
    ----------
    cam_rpm : array_like
        Speeds [rev/min].
    values : array_like
        The quantity at each speed [its own unit].
    width : float
        Half-width of the window [rev/min].

    Returns
    -------
    lo, median, hi : ndarray
    """
    rpm = np.asarray(cam_rpm, dtype=float)
    v = np.asarray(values, dtype=float)
    lo, med, hi = (np.empty(v.size) for _ in range(3))
    for i, r in enumerate(rpm):
        w = v[np.abs(rpm - r) <= width]
        lo[i], med[i], hi[i] = w.min(), np.median(w), w.max()
    return lo, med, hi
