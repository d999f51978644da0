"""Cam from valve lift: the lobe a wanted valve lift or a cam card needs (the "backward"
solution of the train's kinematics).

Engineers own a valve lift (a table from a breathing study) or a cam card (lift, duration at
a check height, lash, lobe centre), not a cam law.  Two ways back to the lobe:

**From a valve-lift table** (:func:`cam_from_valve_lift`): while the valve is open the rigid
train gives the lobe lift ``h = (z + lash)/r`` (:func:`lobe_lift_from_valve_lift`, the
inverse of ``z = r h - lash`` of :mod:`springdyn.valve.train.definition`).  While it is closed the
lobe must take up the lash at the lobe, ``lash/r``, before the opening and give it back after
the closing: a **lash ramp** (:func:`lash_ramp`) that leaves the base circle at rest (lift,
velocity and acceleration continuous there) and reaches the lash height with the valve
lift's own velocity ``v1`` and acceleration ``a1`` at the opening (a quintic in the ramp
angle: continuous in lift, velocity and acceleration at both ends).  The velocity at which
the lash closes is therefore the table's opening velocity (its ramp, if it has one): a table
states the valve's ramp, the lash ramp only reaches it.  Its cam angle is by default
``2 (lash/r)/v1`` (the quartic ``h = l (2x^3 - x^4)``, rising monotonically); a table that
opens at zero velocity (no ramp) needs the angle given (``ramp_angle``).  The lobe is a
``law = "table"`` cam on the table's own angles: the forward valve lift ``max(r h - lash, 0)``
equals the table at every row, and the lobe is C2 wherever the table is, so that its spline
has no spurious acceleration (a velocity step in a table makes a cubic spline ring).

**From a cam card** (:class:`CamCard`, ``[cam_card]``; :func:`cam_from_card`): the card's
lift gives the lobe's lift, its ramp height and velocity the constant-velocity ramps of a
``[cam]`` law (default polydyne), and the main duration is solved (``brentq``) so that the
duration at the card's check height -- on the valve, the gross valve lift or the lobe, in crank
or cam degrees -- is the card's.  The crossing angles are found on the law itself
(:func:`event_crossings`, to 1e-12 rad), not between samples.

:func:`write_cam` writes the result as a ``[cam]`` TOML file (with the lobe-lift CSV of a
table, and the card file's ``[timing]`` table), atomically and together.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...core.errors import InputError
from ...core.io import atomic_open, dumps_toml, output_set, write_csv
from ...core.params import Parameters, param
from ...core.results import Result, notes_lines, text_table
from ...core.units import format_mm
from .analysis import CHECK_HEIGHTS
from .definition import MAX_LIFT, Cam, _normalise_table, read_angle_table

__all__ = [
    "CamCard",
    "LIFT_MEASURES",
    "DEFAULT_RAMP_VELOCITY",
    "DEFAULT_RAMP_MARGIN",
    "lobe_lift_from_valve_lift",
    "valve_lift_from_lobe_lift",
    "lobe_height",
    "lash_ramp",
    "event_crossings",
    "read_valve_lift_table",
    "cam_from_valve_lift",
    "cam_from_card",
    "write_cam",
    "CamFromLift",
]

#: Where a lift or a check height is measured: ``"valve"`` the net valve lift ``r h - lash``
#: (what the valve travels), ``"gross"`` the gross valve lift ``r h`` (lash not taken off, as
#: US cam cards give the lift), ``"lobe"`` the lobe (tappet) lift ``h`` (US cards' duration
#: "at 0.050 in tappet lift").
LIFT_MEASURES = ("valve", "gross", "lobe")
#: Default ramp velocity at the lobe [m/rad]: 0.0125 mm per cam degree, the ramp of
#: ``examples/valve/cam_polydyne_ramps.toml`` (0.25 mm over 20 deg), which seats the valve of a
#: direct-acting train at 0.22 m/s at 3000 cam rpm (the seating velocity is ``r v omega``).
DEFAULT_RAMP_VELOCITY = 0.25e-3 / math.radians(20.0)
#: Default ramp height above the lash at the lobe [m]: 0.1 mm, for the lash's change from
#: cold to hot and the train's deflection under the spring preload (0.15 mm lash -> the
#: 0.25 mm ramps of the bucket example, ``examples/valve/valve_train.toml``).
DEFAULT_RAMP_MARGIN = 0.1e-3
_TWO_PI = 2.0 * math.pi
_SAMPLES = 7200


# ----------------------------------------------------------------------------- kinematics
def lobe_lift_from_valve_lift(valve_lift, ratio: float, lash: float):
    """Lobe lift [m] of a rigid train while the valve is open: ``h = (z + lash)/r``.

    Parameters
    ----------
    valve_lift : float or array_like
        Valve lift z [m], positive.
    ratio : float
        Valve lift per lobe lift r [-].
    lash : float
        Lash at the valve [m].
    """
    return (np.asarray(valve_lift, dtype=float) + lash) / ratio


def valve_lift_from_lobe_lift(lobe_lift, ratio: float, lash: float):
    """Valve lift [m] of a rigid train: ``z = max(r h - lash, 0)``.

    Parameters
    ----------
    lobe_lift : float or array_like
        Lobe lift h [m].
    ratio : float
        Valve lift per lobe lift r [-].
    lash : float
        Lash at the valve [m].
    """
    return np.maximum(ratio * np.asarray(lobe_lift, dtype=float) - lash, 0.0)


def lobe_height(height: float, measure: str, ratio: float, lash: float) -> float:
    """The lobe lift [m] at which a lift ``measure`` (:data:`LIFT_MEASURES`) reads ``height``.

    ``"valve"``: ``(height + lash)/r``; ``"gross"``: ``height/r``; ``"lobe"``: ``height``.

    Parameters
    ----------
    height : float
        The lift in that measure [m].
    measure : {"valve", "gross", "lobe"}
        Where it is measured.
    ratio : float
        Valve lift per lobe lift r [-].
    lash : float
        Lash at the valve [m].
    """
    if measure == "valve":
        return (height + lash) / ratio
    if measure == "gross":
        return height / ratio
    if measure == "lobe":
        return height
    raise InputError(f"measure = {measure!r} must be one of {', '.join(LIFT_MEASURES)}")


def lash_ramp(s, duration: float, height: float, start_velocity: float, end_velocity: float, end_acceleration=0.0):
    """The lash ramp: lobe lift rising from 0 to ``height`` over ``duration`` of cam angle.

    ``h = v0 T x + C3 x^3 + C4 x^4 + C5 x^5``, ``x = s/T``, with ``h(0) = 0``, ``h'(0) = v0``,
    ``h''(0) = 0`` and ``h(T) = height``, ``h'(T) = v1``, ``h''(T) = a1``: the quintic that
    meets the valve lift's velocity and acceleration at the opening.  With ``v0 = v1`` and
    ``a1 = 0`` it is the constant-velocity ramp ``v0 s``; with ``T = 2 height/(v0 + v1)`` and
    ``a1 = 0`` it is ``v0 T x + D (2x^3 - x^4)``, ``D = height - v0 T``, rising
    monotonically for any ``v0, v1 >= 0`` (the lash ramp of a table starts at rest, ``v0 = 0``).

    Parameters
    ----------
    s : float or array_like
        Cam angle from the ramp's start [rad], in [0, duration].
    duration : float
        Ramp angle T [rad].
    height : float
        Lobe lift at its end (the lash at the lobe) [m].
    start_velocity : float
        v0 [m/rad].
    end_velocity : float
        v1 [m/rad].
    end_acceleration : float
        a1 [m/rad^2].

    Returns
    -------
    h, dh, ddh : ndarray
        Lift [m], dh/dtheta [m/rad], d2h/dtheta2 [m/rad^2].

    Examples
    --------
    >>> h, dh, ddh = lash_ramp(0.1, 0.2, 1e-4, 5e-4, 5e-4)
    >>> round(float(h) * 1e6, 9), round(float(dh) * 1e4, 9), float(ddh)
    (50.0, 5.0, 0.0)
    """
    T = duration
    d = height - start_velocity * T
    v = (end_velocity - start_velocity) * T
    a = end_acceleration * T * T
    c3, c4, c5 = np.linalg.solve(np.array([[1.0, 1.0, 1.0], [3.0, 4.0, 5.0], [6.0, 12.0, 20.0]]), [d, v, a])
    x = np.asarray(s, dtype=float) / T
    h = start_velocity * T * x + c3 * x**3 + c4 * x**4 + c5 * x**5
    dh = start_velocity + (3 * c3 * x**2 + 4 * c4 * x**3 + 5 * c5 * x**4) / T
    ddh = (6 * c3 * x + 12 * c4 * x**2 + 20 * c5 * x**3) / (T * T)
    return h, dh, ddh


def event_crossings(cam, lobe_lift: float, samples: int = _SAMPLES):
    """Cam angles [rad] where the lobe lift crosses ``lobe_lift`` before and after its peak,
    found on the cam law (``brentq`` to 1e-12 rad between the bracketing samples).

    Parameters
    ----------
    cam : Cam
        The lobe.
    lobe_lift : float
        The height [m].
    samples : int
        Samples per revolution of the bracket search [-].

    Returns
    -------
    tuple or None
        ``(opening, closing, duration)`` [rad] (opening and closing in [0, 2 pi)); None when
        the lift never reaches the height.
    """
    from scipy.optimize import brentq  # (here: scipy.optimize costs start-up of every valve command)

    step = _TWO_PI / samples
    theta = np.arange(samples) * step
    h = np.asarray(cam.lift_at(theta), dtype=float)
    peak = int(np.argmax(h))
    if h[peak] <= lobe_lift:
        return None
    below = np.nonzero(h < lobe_lift)[0]
    if below.size == 0:
        return None
    after = (below - peak) % samples  # samples from the peak, forwards
    close_i = int(below[np.argmin(after)])
    before = (peak - below) % samples
    open_i = int(below[np.argmin(before)])

    def g(t):
        return float(cam.lift_at(t)) - lobe_lift

    opening = brentq(g, theta[open_i], theta[open_i] + step, xtol=1e-13, rtol=1e-15)
    closing = brentq(g, theta[close_i] - step, theta[close_i], xtol=1e-13, rtol=1e-15)
    return opening % _TWO_PI, closing % _TWO_PI, (closing - opening) % _TWO_PI


# ----------------------------------------------------------------------------- the card
@dataclass(frozen=True)
class CamCard(Parameters):
    """A cam card (``[cam_card]``): lift, duration at a check height, ramps, lash.

    The lobe centre is the ``[timing]`` table beside it (copied to the cam).  Cards give the
    duration in crank degrees (``duration_angle = "crank"``, the default; a four-stroke's cam
    turns half as far, or ``strokes / 2`` of the ``[timing]`` table).

    Examples
    --------
    >>> c = CamCard.from_dict({"lift": "9 mm", "duration": "230 deg", "check_height": "1 mm"})
    >>> c.law, round(math.degrees(c.duration), 6), c.check_at
    ('polydyne', 230.0, 'valve')
    """

    lift: float = param("m", "maximum lift, measured where lift_at says", display="mm", positive=True)
    duration: float = param(
        "rad", "duration at the check height, in the degrees duration_angle says", display="deg", positive=True
    )
    check_height: float = param(
        "m", 'check height of the duration (1 mm, or "0.050 in")', display="mm", positive=True, default=1e-3
    )
    lift_at: str = param(
        None,
        "where lift is measured: valve (net valve lift r h - lash), gross (r h, as US cards give it) or lobe",
        kind="str",
        choices=LIFT_MEASURES,
        default="valve",
    )
    check_at: str = param(
        None,
        "where the check height is measured: valve, gross or lobe (US cards: duration at 0.050 in of tappet "
        "lift, lobe)",
        kind="str",
        choices=LIFT_MEASURES,
        default="valve",
    )
    duration_angle: str = param(
        None,
        "degrees of the duration: crank (as cards give it) or cam",
        kind="str",
        choices=("crank", "cam"),
        default="crank",
    )
    law: str = param(
        None,
        "lift law of the flanks",
        kind="str",
        choices=("cycloidal", "3-4-5", "4-5-6-7", "polydyne"),
        default="polydyne",
    )
    ramp_height: float = param(
        "m",
        "height of each constant-velocity ramp at the lobe (default: the lash at the lobe + 0.1 mm; none without lash)",
        display="mm",
        nonnegative=True,
        default=None,
    )
    ramp_velocity: float = param(
        "m/rad",
        "ramp velocity at the lobe (default 0.0125 mm/deg: 0.25 mm over 20 deg)",
        display="mm/deg",
        positive=True,
        default=None,
    )
    lash: float = param(
        "m",
        "lash at the valve (optional: it must then agree with the valve train's)",
        display="mm",
        nonnegative=True,
        default=None,
    )

    table = "cam_card"

    def _validate(self) -> None:
        limit = 720.0 if self.duration_angle == "crank" else 360.0
        if not math.degrees(self.duration) < limit:
            raise InputError(
                f"[cam_card] duration = {math.degrees(self.duration):.6g} deg must be below {limit:g} "
                f"{self.duration_angle} degrees"
            )
        if self.check_at == self.lift_at and not self.check_height < self.lift:
            raise InputError(
                f"[cam_card] check_height = {format_mm(self.check_height)} must be below lift = {format_mm(self.lift)}"
            )
        if self.ramp_velocity is not None and self.ramp_height == 0.0:
            raise InputError("[cam_card] ramp_velocity is given but ramp_height = 0 mm (no ramps): remove one")


# ----------------------------------------------------------------------------- tables
_LIFT_COLUMNS = {"valve_lift_m": 1.0, "valve_lift_mm": 1e-3}


def read_valve_lift_table(path) -> tuple[np.ndarray, np.ndarray]:
    """Read a valve-lift CSV: ``cam_angle_deg`` (or ``cam_angle_rad``) and ``valve_lift_m``
    (or ``valve_lift_mm``) over one revolution.  Returns SI arrays (rad, m).

    Parameters
    ----------
    path : str or path-like
        The CSV file.
    """

    return read_angle_table(path, _LIFT_COLUMNS, most=MAX_LIFT)


def _lobe_height(height: float, measure: str, valve_train) -> float:
    """:func:`lobe_height` through the train: a constant ratio, or a drawn lever's kinematics
    (the same lever angle on both sides, :meth:`springdyn.valve.train.lever.LeverKinematics.lobe_lift_at_valve_lift`)."""
    ratio, lash = _train(valve_train)
    kin = None if valve_train is None else valve_train.geometry
    if kin is None or measure == "lobe":
        return lobe_height(height, measure, ratio, lash)
    if measure not in LIFT_MEASURES:
        raise InputError(f"measure = {measure!r} must be one of {', '.join(LIFT_MEASURES)}")
    return float(kin.lobe_lift_at_valve_lift(height + (lash if measure == "valve" else 0.0)))


def _train(valve_train):
    """Ratio and lash at the valve of a train (None: 1 and 0)."""
    if valve_train is None:
        return 1.0, 0.0
    return valve_train.ratio, (0.0 if valve_train.hydraulic else valve_train.lash)


def _edge(theta, z, i, direction):
    """Opening (direction +1) or closing (-1) of the valve-lift table at its first (last) open
    row ``i``: the angle where the quadratic through the three outermost open rows reaches 0
    (not before the closed row next to it), and the lift's velocity and acceleration there
    along the direction of travel into the event [m/rad, m/rad^2]."""
    n = z.size
    rows = [(i + direction * k) % n for k in range(3)]
    ds = np.array([direction * (((theta[j] - theta[i]) + math.pi) % _TWO_PI - math.pi) for j in rows])
    c2, c1, c0 = np.polyfit(ds, z[rows], 2)  # z(s) = c0 + c1 s + c2 s^2, s into the event from row i
    closed = (i - direction) % n
    s_closed = -abs(((theta[closed] - theta[i]) + math.pi) % _TWO_PI - math.pi)
    roots = np.roots([c2, c1, c0]) if abs(c2) > 0 else np.array([-c0 / c1]) if c1 else np.array([])
    roots = [float(r.real) for r in np.atleast_1d(roots) if abs(r.imag) < 1e-14 and s_closed <= r.real <= 0.0]
    s0 = max(roots) if roots else s_closed
    velocity = c1 + 2.0 * c2 * s0
    return float((theta[i] + direction * s0) % _TWO_PI), float(velocity), float(2.0 * c2)


def cam_from_valve_lift(cam_angle, valve_lift, valve_train=None, ramp_angle: float | None = None, name="valve lift"):
    """The lobe that gives a wanted valve lift through a rigid train (see the module docstring).

    Parameters
    ----------
    cam_angle : array_like
        Cam angles [rad] over one revolution, ascending.
    valve_lift : array_like
        Wanted valve lift there [m]: exactly zero while closed, one opening per revolution.
    valve_train : ValveTrain, optional
        Ratio and lash (None: the lobe is the valve).
    ramp_angle : float, optional
        Cam angle of each lash ramp [rad] (default: ``2 (lash/r)/v1``, ``v1`` the table's
        opening or closing velocity at the lobe; needed when the table opens at zero velocity).
    name : str
        What the table is called, for messages [-].

    Returns
    -------
    CamFromLift
    """

    theta, z = _normalise_table(cam_angle, valve_lift, name)
    ratio, lash = _train(valve_train)
    kin = None if valve_train is None else valve_train.geometry
    if kin is None:
        cam, out = _lobe_from_table(theta, z, ratio, lash, ramp_angle, name)
    else:
        # a drawn lever (springdyn.valve.train.lever): each open row's lever angle gives the lobe's lift
        # and the cam angle at which the lobe must hold it; the lash ramps are built at the lobe
        # (ratio 1, the lobe's lash height) on the lobe's own angles
        lt, lz = _lobe_space_table(kin, theta, z, lash)
        lobe_lash = float(kin.lobe_lift_at_valve_lift(lash)) if lash > 0 else 0.0
        cam, out = _lobe_from_table(lt, lz, 1.0, lobe_lash, ramp_angle, name)
        out.update(ratio=ratio, lash=lash, input_angle=theta, input_valve_lift=z)
    result = CamFromLift(cam=cam, valve_train=valve_train, **out)
    result.round_trip_error_m = float(np.abs(result.forward_valve_lift(theta) - z).max())
    return result


def _lobe_space_table(kin, theta, z, lash):
    """A drawn lever's wanted valve lift as a lobe-side table: the lobe lift above its lash
    height on the lobe's angles (open rows), zero on the closed rows outside them."""
    open_ = z > 0.0
    ang, h = kin.lobe_of_valve_lift(theta[open_], z[open_] + lash)
    h = h - (float(kin.lobe_lift_at_valve_lift(lash)) if lash > 0 else 0.0)
    ang = np.mod(ang, _TWO_PI)
    # closed rows that the shifted event now covers are dropped (angles relative to the event)
    mid = ang[len(ang) // 2]

    def rel(a):
        return (a - mid + math.pi) % _TWO_PI - math.pi

    lo, hi = rel(ang).min(), rel(ang).max()
    closed = ~open_
    keep = closed & ~((rel(theta) >= lo) & (rel(theta) <= hi))
    angles = np.concatenate([ang, theta[keep]])
    lifts = np.concatenate([np.maximum(h, 0.0), np.zeros(int(keep.sum()))])
    order = np.argsort(angles)
    return angles[order], lifts[order]


def _lobe_from_table(theta, z, ratio, lash, ramp_angle, name):
    """The lobe of a normalised valve-lift table through a constant ratio (the body of
    :func:`cam_from_valve_lift`): the ``table`` cam and the result's fields."""

    if ramp_angle is not None and not (math.isfinite(ramp_angle) and 0 < ramp_angle < math.pi):
        raise InputError(f"ramp_angle = {math.degrees(ramp_angle):.6g} deg must lie between 0 and 180 deg")
    open_ = z > 0.0
    n = z.size
    starts = np.nonzero(open_ & ~np.roll(open_, 1))[0]
    if not open_.any():
        raise InputError(f"{name}: the valve never opens (every valve lift is 0)")
    if open_.all():
        raise InputError(f"{name}: the valve never closes: a valve lift must be exactly 0 on the base circle")
    if starts.size > 1:
        raise InputError(
            f"{name}: the valve opens {starts.size} times per revolution (at "
            + ", ".join(f"{math.degrees(theta[i]):.6g}" for i in starts[:4])
            + " deg): one event per revolution (a valve lift must be exactly 0 while the valve is closed)"
        )
    i_open = int(starts[0])
    i_close = int(np.nonzero(open_ & ~np.roll(open_, -1))[0][0])
    if int(open_.sum()) < 4:
        raise InputError(f"{name}: the valve is open over {int(open_.sum())} rows: give at least 4 rows of the event")
    h = np.zeros(n)
    h[open_] = lobe_lift_from_valve_lift(z[open_], ratio, lash)
    lobe_lash = lash / ratio
    out = dict(
        source=f"valve-lift table {name}", ratio=ratio, lash=lash, input_angle=theta, input_valve_lift=z, figures={}
    )
    fig = out["figures"]
    edges = {"opening": (i_open, 1), "closing": (i_close, -1)}
    for side, (i, direction) in edges.items():
        fig[f"valve_{side}_deg"] = math.degrees(_edge(theta, z, i, direction)[0])
    if lobe_lash > 0.0:
        dz = np.diff(np.append(z, z[0])) / np.diff(np.append(theta, theta[0] + _TWO_PI))
        v_scale = float(np.abs(dz).max())
        ramps = {}
        for side, (i, direction) in edges.items():
            edge, v1, a1 = _edge(theta, z, i, direction)
            v1, a1 = max(v1, 0.0) / ratio, a1 / ratio
            duration = ramp_angle
            if duration is None:
                if v1 * ratio < 0.01 * v_scale:
                    raise InputError(
                        f"{name}: the valve lift {'starts' if direction > 0 else 'ends'} at zero velocity (no ramp in "
                        f"the table) at {math.degrees(edge):.3f} deg: give ramp_angle, the cam angle over which the "
                        f"lobe takes up the lash of {format_mm(lash)} (e.g. 20 deg)"
                    )
                duration = 2.0 * lobe_lash / v1
            ramps[side] = [edge, duration, v1, a1, direction]
        gap = (ramps["opening"][0] - ramps["closing"][0]) % _TWO_PI
        if ramps["opening"][1] + ramps["closing"][1] >= gap:
            raise InputError(
                f"{name}: the lash ramps need {math.degrees(ramps['opening'][1] + ramps['closing'][1]):.4g} deg but the "
                f"valve is closed over {math.degrees(gap):.4g} deg: give a shorter ramp_angle"
            )
        for side, (_, duration, v1, a1, _) in ramps.items():
            s = np.linspace(0.0, duration, 401)

            def falls(a, duration=duration, v1=v1, s=s):
                dh = lash_ramp(s, duration, lobe_lash, 0.0, v1, a)[1]
                return bool(np.any(dh < -1e-9 * max(v1, lobe_lash / duration)))

            if a1 != 0.0 and falls(a1):  # meet the velocity only: an acceleration step at the opening
                out.setdefault("notes", []).append(
                    f"the {side} lash ramp meets the valve lift's velocity but not its acceleration at the "
                    f"{side} ({a1 * ratio * 1e3:.4g} mm/rad^2 at the valve): no ramp rising from rest reaches both"
                )
                ramps[side][3] = a1 = 0.0
            if falls(a1):
                raise InputError(
                    f"{name}: a {side} lash ramp of {math.degrees(duration):.4g} deg cannot reach the valve's "
                    f"{v1 * 1e3:.4g} mm/rad at the lash height {format_mm(lobe_lash)} without falling back: give a "
                    + (
                        f"ramp_angle of at most {math.degrees(2.5 * lobe_lash / v1):.4g} deg (2.5 x lash at the lobe / velocity)"
                        if v1 > 0
                        else "ramp_angle"
                    )
                )
        for side, (edge, duration, v1, a1, direction) in ramps.items():
            # cam angle back from the opening (forward from the closing) into the closed rows
            back = np.maximum((direction * (edge - theta) + 1e-12) % _TWO_PI - 1e-12, 0.0)
            on = ~open_ & (back <= duration)
            h[on] = lash_ramp(duration - back[on], duration, lobe_lash, 0.0, v1, a1)[0]
            fig[f"{side}_ramp_deg"] = math.degrees(duration)
            fig[f"{side}_lash_velocity_m_per_rad"] = v1
        fig["opening_ramp_start_deg"] = math.degrees((ramps["opening"][0] - ramps["opening"][1]) % _TWO_PI)
        fig["closing_ramp_end_deg"] = math.degrees((ramps["closing"][0] + ramps["closing"][1]) % _TWO_PI)
    cam = Cam.from_table(theta, h, name=name)
    out["round_trip_error_m"] = math.nan  # the caller's forward check
    return cam, out


def cam_from_card(card: CamCard, valve_train=None, timing=None) -> CamFromLift:
    """The lobe of a cam card: the card's law with constant-velocity ramps, its main duration
    solved so that the duration at the card's check height is the card's.

    Parameters
    ----------
    card : CamCard
        The ``[cam_card]`` table.
    valve_train : ValveTrain, optional
        Ratio and lash (None: the lobe is the valve, the card's lash).
    timing : Timing, optional
        The ``[timing]`` table: its strokes turn crank degrees into cam degrees (default a
        four-stroke), and it goes with the cam.

    Returns
    -------
    CamFromLift
    """
    from scipy.optimize import brentq  # (here: scipy.optimize costs start-up of every valve command)

    if not isinstance(card, CamCard):
        raise InputError(f"card = {card!r} must be a CamCard (the [cam_card] table)")
    ratio, lash = _train(valve_train)
    if card.lash is not None:
        if valve_train is None:
            lash = card.lash
        elif abs(card.lash - lash) > 1e-9:
            raise InputError(
                f"[cam_card] lash = {format_mm(card.lash)} differs from the valve train's lash {format_mm(lash)}: "
                "remove one or make them agree"
            )
    per_cam = (timing.strokes if timing is not None else 4) / 2.0
    target = card.duration / per_cam if card.duration_angle == "crank" else card.duration
    kin = None if valve_train is None else valve_train.geometry

    def lobe_of(height, measure):  # through the constant ratio, or the drawn lever's kinematics
        if kin is None or measure == "lobe":
            return lobe_height(height, measure, ratio, lash)
        return float(kin.lobe_lift_at_valve_lift(height + (lash if measure == "valve" else 0.0)))

    lobe_lash = lobe_of(lash, "gross") if lash > 0 else 0.0
    h_max = lobe_of(card.lift, card.lift_at)
    h_check = lobe_of(card.check_height, card.check_at)
    if card.ramp_height is None:
        h_r = lobe_lash + DEFAULT_RAMP_MARGIN if lobe_lash > 0 else 0.0
    else:
        h_r = card.ramp_height
    v_r = DEFAULT_RAMP_VELOCITY if card.ramp_velocity is None else card.ramp_velocity
    if h_r == 0.0 and card.ramp_velocity is not None:
        raise InputError(
            "[cam_card] ramp_velocity is given but the lobe has no ramps (no lash: the default ramp_height is 0): "
            "give ramp_height too, or remove ramp_velocity"
        )
    if lobe_lash > 0 and not h_r > lobe_lash:
        raise InputError(
            f"[cam_card] ramp_height = {format_mm(h_r)} must exceed the lash at the lobe {format_mm(lobe_lash)} "
            f"({format_mm(lash)} / ratio {ratio:g}): the valve would open on the flank"
        )
    if not h_max > h_r:
        raise InputError(
            f"[cam_card] the lift at the lobe {format_mm(h_max)} must exceed the ramp height {format_mm(h_r)}"
        )
    if not 0 < h_check < h_max:
        raise InputError(
            f"[cam_card] check_height = {format_mm(card.check_height)} ({card.check_at}) is {format_mm(h_check)} at "
            f"the lobe: it must lie between 0 and the lobe lift {format_mm(h_max)}"
        )
    phi_r = h_r / v_r if h_r > 0 else 0.0
    if 2 * phi_r >= _TWO_PI * 0.9:
        raise InputError(
            f"[cam_card] the ramps of {format_mm(h_r)} at {v_r * 1e3:.4g} mm/rad take {math.degrees(2 * phi_r):.4g} deg: "
            "give a higher ramp_velocity"
        )

    def make(d):
        return Cam(law=card.law, lift=h_max, duration=d, ramp_height=h_r, ramp_duration=phi_r)

    def duration_at_check(d):
        return event_crossings(make(d), h_check)[2]

    lo, hi = math.radians(1.0), _TWO_PI - 2 * phi_r - 1e-9
    d_lo, d_hi = duration_at_check(lo), duration_at_check(hi)
    if not d_lo < target < d_hi:
        raise InputError(
            f"[cam_card] duration = {math.degrees(card.duration):.6g} {card.duration_angle} deg at "
            f"{format_mm(card.check_height)} ({card.check_at}) cannot be met: this law with these ramps gives "
            f"{math.degrees(d_lo) * (per_cam if card.duration_angle == 'crank' else 1):.4g} to "
            f"{math.degrees(d_hi) * (per_cam if card.duration_angle == 'crank' else 1):.4g} {card.duration_angle} deg"
        )
    main = brentq(lambda d: duration_at_check(d) - target, lo, hi, xtol=1e-14, rtol=4 * np.finfo(float).eps)
    cam = make(main)
    achieved = duration_at_check(main)
    gross = ratio * h_max if kin is None else float(kin.valve_lift_at_lobe_lift(h_max))
    lift_now = {"valve": gross - lash, "gross": gross, "lobe": h_max}[card.lift_at]
    figures = dict(
        law=card.law,
        main_duration_deg=math.degrees(main),
        ramp_height_m=h_r,
        ramp_duration_deg=math.degrees(phi_r),
        ramp_velocity_m_per_rad=v_r if h_r > 0 else 0.0,
        card_duration_deg=math.degrees(card.duration),
        card_duration_angle=card.duration_angle,
        card_check_height_m=card.check_height,
        card_check_at=card.check_at,
        card_lift_m=card.lift,
        card_lift_at=card.lift_at,
        duration_error_deg=math.degrees(achieved - target) * (per_cam if card.duration_angle == "crank" else 1.0),
        lift_error_m=lift_now - card.lift,
    )
    if card.ramp_height is None and h_r > 0:
        figures["ramp_height_default"] = "the lash at the lobe + 0.1 mm"
    return CamFromLift(
        cam=cam,
        valve_train=valve_train,
        source="cam card",
        ratio=ratio,
        lash=lash,
        figures=figures,
        timing=timing,
        round_trip_error_m=abs(lift_now - card.lift),
    )


# ----------------------------------------------------------------------------- output
def write_cam(result: CamFromLift, path, header: str = "") -> list[Path]:
    """Write the designed cam as a ``[cam]`` TOML file (with a table's lobe-lift CSV beside it,
    ``<name>_lobe_lift.csv``, and the card's ``[timing]``), all files or none.

    Parameters
    ----------
    result : CamFromLift
        The designed cam.
    path : str or path-like
        The TOML file.
    header : str
        Comment lines for the top of the file.

    Returns
    -------
    list of Path
        The files written.
    """

    path = Path(path)
    cam = result.cam
    written = [path]
    with output_set():
        if cam.law == "table":
            csv = path.with_name(f"{path.stem}_lobe_lift.csv")
            write_csv(csv, {"cam_angle_deg": np.degrees(cam.table_angle), "lift_m": cam.table_lift})
            table = {"law": "table", "file": csv.name}
            written.append(csv)
        else:
            table = {
                "law": cam.law,
                "lift": f"{cam.lift * 1e3:.15g} mm",
                "duration": f"{math.degrees(cam.duration):.15g} deg",
            }
            if cam.ramp_height > 0:
                table["ramp_height"] = f"{cam.ramp_height * 1e3:.15g} mm"
                table["ramp_duration"] = f"{math.degrees(cam.ramp_duration):.15g} deg"
        doc = {"cam": table}
        t = result.timing
        if t is not None:
            doc["timing"] = {
                "lobe_centre": f"{math.degrees(t.lobe_centre):.15g} deg",
                "valve": t.valve,
                "strokes": t.strokes,
            }
        with atomic_open(path, "w", encoding="utf-8") as fh:
            fh.write(dumps_toml(doc, header))
    return written


@dataclass(repr=False)
class CamFromLift(Result):
    """A lobe designed from a valve lift or a cam card (:func:`cam_from_valve_lift`,
    :func:`cam_from_card`), with the forward check of the train's kinematics."""

    cam: object
    valve_train: object
    source: str
    ratio: float
    lash: float
    figures: dict
    round_trip_error_m: float
    input_angle: np.ndarray | None = None  # [rad]
    input_valve_lift: np.ndarray | None = None  # [m]
    timing: object = None
    notes: list = field(default_factory=list)

    title = "cam from valve lift"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.cam.law} lobe from {self.source}"

    def forward_valve_lift(self, cam_angle) -> np.ndarray:
        """The rigid train's valve lift on this lobe [m] at the cam angles ``cam_angle`` [rad]:
        ``max(r h - lash, 0)``, or through a drawn lever's kinematics (:mod:`springdyn.valve.train.lever`).

        Parameters
        ----------
        cam_angle : array_like
            Cam angles [rad].
        """
        theta = np.asarray(cam_angle, dtype=float)
        kin = None if self.valve_train is None else self.valve_train.geometry
        if kin is None:
            return valve_lift_from_lobe_lift(self.cam.lift_at(theta), self.ratio, self.lash)
        from ..engine.cam_table import CamTable  # (here: the compiled engine (numba) loads only when a run needs it)

        gross = kin.solve(theta, CamTable.of(self.cam, _SAMPLES).at)["valve_lift"]
        return np.maximum(gross - self.lash, 0.0)

    def describe(self) -> str:
        """The lobe in words and tables (what ``springdyn valve cam-from-lift`` prints): the ratio
        and lash, the lifts, the valve timing or the card's figures, the lash ramps, the timing
        at the check heights and the notes."""
        s = self.summary
        out = [
            f"{s['law']} lobe from {s['source']}: ratio {s['rocker_ratio']:g}, lash {s['lash_m'] * 1e3:.3g} mm at the "
            f"valve ({s['lobe_lash_m'] * 1e3:.4g} mm at the lobe)",
            f"max valve lift {s['max_valve_lift_m'] * 1e3:.4f} mm, max lobe lift {s['max_lobe_lift_m'] * 1e3:.4f} mm "
            f"at {s['max_lift_cam_angle_deg']:.2f} cam deg",
        ]
        if self.cam.law == "table":
            out.append(
                f"valve opens at {s['valve_opening_deg']:.3f}, closes at {s['valve_closing_deg']:.3f} cam deg; "
                f"round trip (the lobe's valve lift against the table, every row): {s['round_trip_error_m']:.3g} m"
            )
            if "opening_ramp_deg" in s:
                out.append(
                    text_table(
                        [
                            (side, f"{s[f'{side}_ramp_deg']:.3f}", f"{s[f'{side}_lash_velocity_m_per_rad'] * 1e3:.4f}")
                            for side in ("opening", "closing")
                        ],
                        headers=("lash ramp (from rest)", "cam angle [deg]", "lobe velocity at the lash [mm/rad]"),
                    )
                )
                out.append(
                    f"the opening ramp starts at {s['opening_ramp_start_deg']:.3f} deg, the closing ramp ends at "
                    f"{s['closing_ramp_end_deg']:.3f} deg"
                )
        else:
            unit = s["card_duration_angle"]
            out.append(
                f"main duration {s['main_duration_deg']:.6f} cam deg; ramps {s['ramp_height_m'] * 1e3:.4g} mm over "
                f"{s['ramp_duration_deg']:.4f} deg ({s['ramp_velocity_m_per_rad'] * 1e3:.4f} mm/rad)"
                + (f", height {s['ramp_height_default']}" if "ramp_height_default" in s else "")
            )
            out.append(
                f"card: {s['card_lift_m'] * 1e3:g} mm lift ({s['card_lift_at']}), {s['card_duration_deg']:g} {unit} deg "
                f"at {s['card_check_height_m'] * 1e3:.4g} mm ({s['card_check_at']}); the lobe misses them by "
                f"{s['lift_error_m']:.3g} m and {s['duration_error_deg']:.3g} {unit} deg"
            )
        rows = []
        for key, label in (("0050in", "0.050 in"), ("1mm", "1 mm")):
            if s.get(f"duration_at_{key}_deg") is None:
                rows.append((f"at {label}", "-", "-", "lift below the check height"))
            else:
                rows.append(
                    (
                        f"at {label}",
                        f"{s[f'opening_at_{key}_deg']:.3f}",
                        f"{s[f'closing_at_{key}_deg']:.3f}",
                        f"{s[f'duration_at_{key}_deg']:.3f}",
                    )
                )
        out.append(
            text_table(rows, headers=("valve timing", "opens [cam deg]", "closes [cam deg]", "duration [cam deg]"))
        )
        return "\n".join(out + notes_lines(s))

    def _summary(self) -> dict:
        theta = np.arange(_SAMPLES) * (_TWO_PI / _SAMPLES)
        h = self.cam.lift_at(theta)
        z = self.forward_valve_lift(theta)
        s = dict(
            source=self.source,
            law=self.cam.law,
            rocker_ratio=self.ratio,
            lash_m=self.lash,
            lobe_lash_m=_lobe_height(self.lash, "gross", self.valve_train) if self.lash else 0.0,
            max_lobe_lift_m=float(h.max()),
            max_valve_lift_m=float(z.max()),
            max_lift_cam_angle_deg=math.degrees(self.cam.peak_angle),
            round_trip_error_m=self.round_trip_error_m,
        )
        s.update(self.figures)

        for key, height in CHECK_HEIGHTS.items():
            c = event_crossings(self.cam, _lobe_height(height, "valve", self.valve_train))
            s[f"duration_at_{key}_deg"] = None if c is None else math.degrees(c[2])
            if c is not None:
                s[f"opening_at_{key}_deg"], s[f"closing_at_{key}_deg"] = math.degrees(c[0]), math.degrees(c[1])
        if self.notes:
            s["notes"] = list(self.notes)
        return s

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        theta = np.arange(_SAMPLES) * (_TWO_PI / _SAMPLES)
        h, dh, ddh = self.cam.evaluate(theta)
        dims = ("cam_angle",)
        data = {
            "lobe_lift": (dims, np.asarray(h, dtype=float), {"units": "m"}),
            "lobe_velocity": (dims, np.asarray(dh, dtype=float), {"units": "m/rad"}),
            "lobe_acceleration": (dims, np.asarray(ddh, dtype=float), {"units": "m/rad^2"}),
            "valve_lift": (dims, self.forward_valve_lift(theta), {"units": "m"}),
        }
        coords = {"cam_angle": (dims, np.degrees(theta), {"units": "deg"})}
        return xr.Dataset(data, coords=coords, attrs={"source": self.source, "law": self.cam.law})

    def _plot(self, ax=None):
        """Valve lift (wanted and forward), lobe lift, lobe acceleration; into ``ax``: the lifts."""
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        if ax is not None:
            fig, axes = ax.figure, [ax]
        else:
            fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
        theta = np.arange(_SAMPLES) * (_TWO_PI / _SAMPLES)
        h, _, ddh = self.cam.evaluate(theta)
        deg = np.degrees(theta)
        a = axes[0]
        a.plot(deg, self.forward_valve_lift(theta) * 1e3, "C0", label="valve lift of the lobe")
        a.plot(deg, np.asarray(h) * 1e3, "C1", lw=0.8, label="lobe lift")
        if self.input_angle is not None:
            a.plot(np.degrees(self.input_angle), self.input_valve_lift * 1e3, "k.", ms=2, label="wanted valve lift")
        a.set_ylabel("lift [mm]")
        a.legend(fontsize=7)
        a.grid(True, alpha=0.3)
        a.set_title(f"{self.cam.law} lobe from {self.source}")
        if len(axes) > 1:
            axes[1].plot(deg, np.asarray(ddh) * 1e3, "C1")
            axes[1].set_ylabel("lobe acceleration [mm/rad^2]")
            axes[1].grid(True, alpha=0.3)
        axes[-1].set_xlabel("cam angle [deg]")
        return fig
