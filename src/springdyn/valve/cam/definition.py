"""Cam lift laws: built-in symmetric events and measured lift tables.

A cam is a periodic lift ``h(theta)`` over one camshaft revolution, ``theta`` in radians
of cam angle.  The built-in laws describe a symmetric event that starts at cam angle 0:
an optional constant-velocity opening ramp, the rise over the first half of the main
duration, the fall over the second half, an optional closing ramp, and zero lift for the
rest of the revolution.  Each exposes lift, velocity ``dh/dtheta`` and acceleration
``d2h/dtheta2`` (per radian of cam angle); multiply by ``omega`` and ``omega^2`` for time
derivatives.

Rise laws of valve-cam practice (not in [MMS], which drives the retainer end by a given
lift, "Initial condition & position"), with ``u`` in [0, 1] over the rise half and ``P(u)`` rising 0 -> 1:

- ``cycloidal``: ``P = u - sin(2 pi u)/(2 pi)``
- ``3-4-5``: ``P = 10u^3 - 15u^4 + 6u^5``
- ``4-5-6-7``: ``P = 35u^4 - 84u^5 + 70u^6 - 20u^7``
- ``polydyne``: the 2-10-14-18 polydyne of valve-cam practice (Stoddart, 1953):
  ``y(x) = 1 + C2 x^2 + C10 x^10 + C14 x^14 + C18 x^18`` over the whole event with
  ``x`` in [-1, 1] from the nose, ``C`` chosen so that lift, velocity, acceleration and
  jerk vanish at both ends.

With a ramp of height ``h_r`` over ``phi_r``, the ramp rises at constant velocity
``v_r = h_r/phi_r``; the main rise then goes from ``h_r`` to the full lift with its start
velocity matched to ``v_r`` by the term ``v_r T g(u)`` (``T`` the half duration),
``g(u) = u (1 - u)^4 (1 + 4u)`` (``g(0) = 0, g'(0) = 1, g''(0) = 0``, and ``g`` vanishes
to third order at the nose), so velocity and acceleration are continuous at the junction.
The ramp itself starts with a velocity step (its purpose: lash is taken up at a
controlled constant velocity).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from ...core.errors import FactWarning, InputError
from ...core.io import read_csv_columns
from ...core.params import Parameters, param
from ...core.units import format_mm, rpm_to_hz

__all__ = ["Cam", "rise_law", "polydyne_coefficients", "LAWS", "OPEN_LIFT", "BASE_CIRCLE_LIFT"]

#: Lobe lift past the lash [m] from which the lobe is in its event and drives the valve open
#: (a micrometre: far above the table's round-off, some 1e-54 m on the base circle, and below
#: any lash or ramp height); the run's verdicts and the cam checks use this one rule.
OPEN_LIFT = 1e-6
#: Lobe lift [m] at or below which the lobe is on its base circle.
BASE_CIRCLE_LIFT = 1e-9

LAWS = ("cycloidal", "3-4-5", "4-5-6-7", "polydyne", "table")
TWO_PI = 2.0 * math.pi


def polydyne_coefficients() -> np.ndarray:
    """Coefficients ``(C2, C10, C14, C18)`` of the 2-10-14-18 polydyne.

    Solves ``y(1) = y'(1) = y''(1) = y'''(1) = 0`` for
    ``y = 1 + C2 x^2 + C10 x^10 + C14 x^14 + C18 x^18``.
    """
    p = np.array([2, 10, 14, 18], dtype=float)
    rows = [np.ones(4), p, p * (p - 1), p * (p - 1) * (p - 2)]
    return np.linalg.solve(np.array(rows), np.array([-1.0, 0.0, 0.0, 0.0]))


_POLYDYNE = polydyne_coefficients()


def rise_law(name: str, u):
    """Normalised rise ``P(u)`` and its first two derivatives for ``u`` in [0, 1].

    Parameters
    ----------
    name : {"cycloidal", "3-4-5", "4-5-6-7", "polydyne"}
    u : ndarray
        Fraction of the rise half [-].

    Returns
    -------
    p, dp, ddp : ndarray
        ``P``, ``dP/du``, ``d2P/du2``.
    """
    u = np.asarray(u, dtype=float)
    if name == "cycloidal":
        s = np.sin(TWO_PI * u)
        c = np.cos(TWO_PI * u)
        return u - s / TWO_PI, 1.0 - c, TWO_PI * s
    if name == "3-4-5":
        return (
            u**3 * (10 - 15 * u + 6 * u**2),
            30 * u**2 * (1 - u) ** 2,
            60 * u * (1 - 3 * u + 2 * u**2),
        )
    if name == "4-5-6-7":
        return (
            u**4 * (35 - 84 * u + 70 * u**2 - 20 * u**3),
            140 * u**3 * (1 - u) ** 3,
            420 * u**2 * (1 - u) ** 2 * (1 - 2 * u),
        )
    if name == "polydyne":
        x = 1.0 - u  # distance from the nose, in half-events
        y, dy, ddy = np.ones_like(x), np.zeros_like(x), np.zeros_like(x)
        for c, k in zip(_POLYDYNE, (2, 10, 14, 18)):
            y = y + c * x**k
            dy = dy + c * k * x ** (k - 1)
            ddy = ddy + c * k * (k - 1) * x ** (k - 2)
        return y, -dy, ddy
    raise InputError(f"law = {name!r} is not a built-in cam law; choose one of {', '.join(LAWS)}")


def _g(u):
    """Ramp-velocity matching term and its first two derivatives.

    ``g(u) = u (1-u)^4 (1+4u) = u - 10u^3 + 20u^4 - 15u^5 + 4u^6``: ``g(0) = 0``,
    ``g'(0) = 1``, ``g''(0) = 0``, and ``g`` vanishes to third order at ``u = 1`` so that
    it never dominates the rise law's approach to the nose.
    """
    return (
        u - 10 * u**3 + 20 * u**4 - 15 * u**5 + 4 * u**6,
        1 - 30 * u**2 + 80 * u**3 - 75 * u**4 + 24 * u**5,
        -60 * u + 240 * u**2 - 300 * u**3 + 120 * u**4,
    )


@dataclass(frozen=True)
class Cam(Parameters):
    """A cam lift law over one camshaft revolution (SI: m and rad).

    Examples
    --------
    >>> cam = Cam(law="3-4-5", lift=0.009, duration=math.radians(120))
    >>> round(float(cam.lift_at(math.radians(60))) * 1e3, 6)
    9.0
    """

    law: str = param(None, "lift law", kind="str", choices=LAWS)
    lift: float = param("m", "maximum lift (including ramps)", display="mm", default=None)
    duration: float = param("rad", "main event duration in cam angle (excluding ramps)", display="deg", default=None)
    ramp_height: float = param(
        "m", "height of each constant-velocity ramp", display="mm", default=0.0, nonnegative=True
    )
    ramp_duration: float = param("rad", "cam angle of each ramp", display="deg", default=0.0, nonnegative=True)
    closing_duration: float = param(
        "rad",
        "cam angle of the closing flank, the fall from the nose (default: half the duration, a symmetric lobe); "
        "the opening flank takes the rest of the duration",
        display="deg",
        default=None,
    )
    closing_law: str = param(
        None, "lift law of the closing flank (default: law)", kind="str", choices=("", *LAWS), default=""
    )
    file: str = param(None, 'lift table CSV (law = "table")', kind="str", default="")
    table_angle: np.ndarray = field(default=None, repr=False, compare=False)
    table_lift: np.ndarray = field(default=None, repr=False, compare=False)

    table = "cam"

    def _validate(self) -> None:
        if self.law == "table":
            given = [k for k in ("lift", "duration") if getattr(self, k) is not None]
            if given or self.ramp_height or self.ramp_duration:
                raise InputError(
                    f'law = "table" takes its lift from the file; remove {", ".join(given) or "the ramp keys"}'
                )
            if self.table_angle is None:
                if not self.file:
                    raise InputError('law = "table" needs file = "lift.csv" (columns cam_angle_deg, lift_mm)')
                angle, lift = read_lift_table(self.file)
            else:
                angle, lift = self.table_angle, self.table_lift
            angle, lift = _normalise_table(angle, lift, self.file or "table")
            object.__setattr__(self, "table_angle", angle)
            object.__setattr__(self, "table_lift", lift)
            return
        for key, example in (("lift", '"9 mm"'), ("duration", '"120 deg"')):
            if getattr(self, key) is None:
                raise InputError(f"law = {self.law!r} needs {key} (e.g. {key} = {example})")
        if self.file:
            raise InputError(f'file = {self.file!r} is only used with law = "table"')
        if not self.lift > 0:
            raise InputError(f"lift = {format_mm(self.lift)} must be positive")
        deg = math.degrees(self.duration)
        if not 0 < self.duration <= TWO_PI + 1e-12:
            raise InputError(f"duration = {deg:.6g} deg must lie in (0, 360] deg")
        if self.duration + 2 * self.ramp_duration > TWO_PI + 1e-12:
            raise InputError(
                f"duration + 2 ramp_duration = {deg + 2 * math.degrees(self.ramp_duration):.6g} deg exceeds one revolution"
            )
        if (self.ramp_height > 0) != (self.ramp_duration > 0):
            given, missing = (
                ("ramp_height", "ramp_duration") if self.ramp_height > 0 else ("ramp_duration", "ramp_height")
            )
            raise InputError(
                f"{given} is given without {missing} (zero or missing): a ramp has both, its height and its "
                f'duration (e.g. ramp_height = "0.25 mm", ramp_duration = "20 deg"); give {missing}, or '
                f"remove {given} for no ramps"
            )
        if self.ramp_height >= self.lift:
            raise InputError(
                f"ramp_height = {format_mm(self.ramp_height)} must be smaller than lift = {format_mm(self.lift)}"
            )
        if self.closing_duration is not None and not 0 < self.closing_duration < self.duration:
            raise InputError(
                f"closing_duration = {math.degrees(self.closing_duration):.6g} deg must lie between 0 and the duration "
                f"{deg:.6g} deg (the opening flank takes the rest)"
            )
        if self.closing_law == "table":
            raise InputError('closing_law = "table" is not a flank law; a measured lift table is law = "table"')

    @classmethod
    def _prepare(cls, mapping: dict, *, base_dir: Path | str | None = None, **context) -> dict:
        """A relative lift-table ``file`` is taken from ``base_dir`` (the TOML file's folder)."""
        if "file" in mapping and base_dir is not None and isinstance(mapping["file"], str) and mapping["file"]:
            p = Path(mapping["file"])
            mapping["file"] = str(p if p.is_absolute() else Path(base_dir) / p)
        return mapping

    @classmethod
    def from_table(cls, angle, lift, name: str = "table") -> Cam:
        """A cam from arrays: cam angle [rad] over one revolution and lift [m].

        Parameters
        ----------
        angle : array_like
            Cam angles [rad] over one revolution, ascending.
        lift : array_like
            Lift at each angle [m].
        name : str
            What the cam is called (its source) [-].
        """
        return cls(law="table", file=name, table_angle=np.asarray(angle), table_lift=np.asarray(lift))

    def scaled(self, factor: float) -> Cam:
        """The same cam with every lift multiplied by ``factor`` (e.g. the valve lift of a
        rigid rocker train: lobe lift x rocker ratio).

        Parameters
        ----------
        factor : float
            Lift factor [-], positive.
        """
        if (
            isinstance(factor, bool)
            or not isinstance(factor, (int, float, np.number))
            or not (math.isfinite(factor) and factor > 0)
        ):
            raise InputError(f"factor = {factor!r} must be a positive, finite number")
        if self.law == "table":
            return Cam.from_table(self.table_angle, self.table_lift * factor, name=f"{self.file} x {factor:g}")
        return dataclasses.replace(self, lift=self.lift * factor, ramp_height=self.ramp_height * factor)

    # -------------------------------------------------------------- evaluation
    @property
    def max_lift(self) -> float:
        """Maximum lift [m]."""
        if self.law == "table":
            return float(self._spline(np.linspace(0, TWO_PI, 7201)).max())
        return self.lift

    @property
    def peak_angle(self) -> float:
        """Cam angle [rad] of the maximum lift, the lobe centre of the valve timing
        (:mod:`springdyn.valve.cam.timing`): after the opening ramp and flank; for a table, where
        the spline's slope vanishes at its largest lift."""
        if self.law != "table":
            return self.ramp_duration + self.flank_durations[0]
        grid = np.linspace(0.0, TWO_PI, 7201)
        i = int(np.argmax(self._spline(grid)))
        d = self._spline.derivative()
        lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, 7200)]
        if d(lo) > 0 > d(hi):
            from scipy.optimize import brentq  # (here: scipy.optimize costs start-up of every valve command)

            return float(brentq(d, lo, hi, xtol=1e-12)) % TWO_PI
        return float(grid[i]) % TWO_PI

    @property
    def event_duration(self) -> float:
        """Cam angle [rad] of the whole event including ramps (the table: 2 pi)."""
        if self.law == "table":
            return TWO_PI
        return self.duration + 2 * self.ramp_duration

    @property
    def breakpoints(self) -> np.ndarray:
        """Cam angles [rad] in [0, 2 pi) where the lift rate steps: the outer ends of the
        ramps (a ramp starts and ends at constant velocity); empty without ramps, where every
        join keeps lift, velocity and acceleration continuous, and for a table (a periodic
        spline).

        The engine's cam table smooths such a step over one table interval (0.05 deg), a
        feature an adaptive step can cross without one of its stages inside it; the engine
        therefore lands a step on the table nodes around each breakpoint
        (:func:`springdyn.valve.engine.stop_angles`).
        """
        if self.law == "table" or self.ramp_duration == 0.0:
            return np.empty(0)
        total = self.duration + 2 * self.ramp_duration
        return np.unique(np.mod(np.array([0.0, total]), TWO_PI))

    @cached_property
    def _spline(self):
        from scipy.interpolate import CubicSpline  # (here: scipy.interpolate costs start-up of every valve command)

        a = np.append(self.table_angle, self.table_angle[0] + TWO_PI)
        h = np.append(self.table_lift, self.table_lift[0])
        return CubicSpline(a, h, bc_type="periodic")

    def evaluate(self, theta):
        """Lift [m], ``dh/dtheta`` [m/rad] and ``d2h/dtheta2`` [m/rad^2] at cam angle(s) [rad].

        Parameters
        ----------
        theta : float or array_like
            Cam angles [rad], any real.
        """
        theta = np.asarray(theta, dtype=float)
        if self.law == "table":
            a0 = self.table_angle[0]
            th = a0 + np.mod(theta - a0, TWO_PI)
            sp = self._spline
            return sp(th), sp(th, 1), sp(th, 2)
        th = np.mod(theta, TWO_PI)
        phi_r, h_r = self.ramp_duration, self.ramp_height
        t_close = self.flank_durations[1]
        t_open = self.duration - t_close
        total = self.duration + 2 * phi_r
        # the fall is the mirror image of a rise over its own duration, from the event's end
        closing = th > phi_r + t_open
        s = np.where(closing, total - th, th)
        sign = np.where(closing, -1.0, 1.0)
        half = np.where(closing, t_close, t_open)
        h = np.zeros_like(s)
        dh = np.zeros_like(s)
        ddh = np.zeros_like(s)
        inside = th < total
        if phi_r > 0:
            v_r = h_r / phi_r
            on_ramp = inside & (s < phi_r)
            h = np.where(on_ramp, v_r * s, h)
            dh = np.where(on_ramp, v_r, dh)
        else:
            v_r = 0.0
        main = inside & (s >= phi_r)
        u = np.clip((s - phi_r) / half, 0.0, 1.0)
        p, dp, ddp = rise_law(self.law, u)
        if self.closing_law and self.closing_law != self.law:
            pc, dpc, ddpc = rise_law(self.closing_law, u)
            p, dp, ddp = np.where(closing, pc, p), np.where(closing, dpc, dp), np.where(closing, ddpc, ddp)
        span = self.lift - h_r
        if v_r > 0:
            g, dg, ddg = _g(u)
            p, dp, ddp = p + v_r * half / span * g, dp + v_r * half / span * dg, ddp + v_r * half / span * ddg
        h = np.where(main, h_r + span * p, h)
        dh = np.where(main, span * dp / half, dh)
        ddh = np.where(main, span * ddp / half**2, ddh)
        return h, sign * dh, ddh

    @property
    def flank_durations(self) -> tuple[float, float]:
        """Cam angles [rad] of the opening and the closing flank (without the ramps)."""
        close = self.duration / 2.0 if self.closing_duration is None else self.closing_duration
        return self.duration - close, close

    def sampled(self, samples: int) -> tuple:
        """Lift [m], ``dh/dtheta`` [m/rad], ``d2h/dtheta2`` [m/rad^2] at ``samples`` equal steps
        over one revolution (the engine keeps them: :meth:`springdyn.valve.engine.CamTable.of`).

        Parameters
        ----------
        samples : int
            Steps per revolution [-].
        """
        theta = np.arange(samples) * (2 * math.pi / samples)
        return tuple(np.ascontiguousarray(a) for a in self.evaluate(theta))

    def lift_at(self, theta):
        """Lift [m] at cam angle(s) [rad].

        Parameters
        ----------
        theta : float or array_like
            Cam angles [rad], any real.
        """
        return self.evaluate(theta)[0]

    def check_resolution(self, cam_rpm: float, frequency: float) -> None:
        """Warn when a lift table is too coarse for the speed.

        A table with step ``d theta`` resolves cam orders up to ``pi / d theta`` (its
        Nyquist order).  At ``cam_rpm`` the spring's first surge mode ``frequency`` [Hz]
        is excited by cam order ``frequency / (cam_rpm/60)``; when that order is beyond
        the table's Nyquist order, the acceleration that drives surge is not resolved and
        the response near the surge frequency comes from the spline, not from the cam.

        Parameters
        ----------
        cam_rpm : float
            Cam speed [rev/min].
        frequency : float
            The spring's first surge frequency [Hz].
        """
        if self.law != "table":
            return
        step = float(np.max(np.diff(np.append(self.table_angle, self.table_angle[0] + TWO_PI))))
        nyquist_order = math.pi / step
        needed = frequency / rpm_to_hz(cam_rpm)
        if nyquist_order < needed:
            warnings.warn(
                f"cam table {self.file}: its largest step of {math.degrees(step):.3g} deg resolves cam orders up "
                f"to {nyquist_order:.0f}, but at {cam_rpm:g} cam rpm the spring's modes up to {frequency:.0f} Hz "
                f"need order {needed:.0f}: the acceleration is not resolved (use a step below "
                f"{180.0 / needed:.3g} deg)",
                stacklevel=2,
            )


_ANGLE_UNITS = {"cam_angle_deg": math.pi / 180.0, "cam_angle_rad": 1.0}
#: Crank-angle columns a cam card gives: read as a four-stroke's, cam angle = crank angle / 2.
_CRANK_UNITS = {"crank_angle_deg": math.pi / 360.0, "crank_angle_rad": 0.5}
_LIFT_UNITS = {"lift_mm": 1e-3, "lift_m": 1.0, "lift_um": 1e-6}
#: The largest lift a lift table may hold [m]: valve lifts of engines with valve springs are
#: 5-20 mm; a table beyond 50 mm holds another unit than its column says (mm in a ``_m`` column).
MAX_LIFT = 0.05


def read_lift_table(path) -> tuple[np.ndarray, np.ndarray]:
    """Read a lift table CSV: ``cam_angle_deg`` (or ``cam_angle_rad``) and ``lift_mm``
    (or ``lift_m``, ``lift_um``).  Returns SI arrays (rad, m)."""
    return read_angle_table(path, _LIFT_UNITS, most=MAX_LIFT)


def check_lift_bound(lift, name: str, column: str | None = None, value_columns=None) -> None:
    """A lift table's lift within :data:`MAX_LIFT`, else the row, its value and the likely slip
    named (millimetres in a metre column): the one home of the lift's physical bound.

    Parameters
    ----------
    lift : ndarray
        The lift [m].
    name : str
        The table, for messages (its file).
    column : str, optional
        The column the lift came from (None: arrays given in Python, in metres).
    value_columns : dict, optional
        The table's accepted lift columns and their factor to SI, to name the right one.
    """
    lift = np.asarray(lift, dtype=float)
    if not lift.size or not np.nanmax(lift) > MAX_LIFT:
        return
    i = int(np.nanargmax(lift))
    if column is None:
        raise InputError(
            f"{name}: row {i + 2}: a lift of {lift[i] * 1e3:.6g} mm is beyond any valve lift (at most "
            f"{MAX_LIFT * 1e3:g} mm): the lift is taken in metres"
        )
    factor = (value_columns or {}).get(column, 1.0)
    mm = next((k for k, f in (value_columns or {}).items() if f == 1e-3), None)
    hint = (
        f": the column holds millimetres? name it {mm} (the column's name gives the unit)"
        if mm and factor > 1e-3
        else ": check the column's unit"
    )
    raise InputError(
        f"{name}: row {i + 2}, column {column!r}: {lift[i] / factor:.6g} is a lift of {lift[i] * 1e3:.6g} mm, "
        f"beyond any valve lift (at most {MAX_LIFT * 1e3:g} mm){hint}"
    )


def read_angle_table(path, value_columns: dict, most: float | None = None) -> tuple[np.ndarray, np.ndarray]:
    """A CSV of a quantity against cam angle, each column named with its unit.

    Parameters
    ----------
    path : str or path-like
        The CSV file: ``cam_angle_deg`` or ``cam_angle_rad``, and one of ``value_columns``.
    value_columns : dict
        Accepted value columns and their factor to SI, e.g. ``{"lift_mm": 1e-3, "lift_m": 1.0}``.

    most : float, optional
        The largest value the table may hold [SI] (a lift table: :data:`MAX_LIFT`,
        :func:`check_lift_bound`).

    Returns
    -------
    angle, value : ndarray
        Cam angle [rad] and the value [SI].
    """
    cols = read_csv_columns(path)
    units = {**_ANGLE_UNITS, **_CRANK_UNITS}
    for kind, accepted in (("angle", units), ("lift" if most is not None else "value", value_columns)):
        both = [k for k in accepted if k in cols]
        if len(both) > 1:
            raise InputError(
                f"{path}: the columns {' and '.join(both)} both give the {kind}: keep one of them (the column's "
                "name gives the unit)"
            )
    a_key = next((k for k in units if k in cols), None)
    v_key = next((k for k in value_columns if k in cols), None)
    if a_key is None or v_key is None:
        first, *rest = value_columns
        raise InputError(
            f"{path}: needs columns cam_angle_deg (or cam_angle_rad, crank_angle_deg) and {first} (or "
            f"{', '.join(rest)}); found {', '.join(cols)}"
        )
    if a_key in _CRANK_UNITS:  # a cam card against crank degrees (issue 40): stated, not refused
        warnings.warn(
            FactWarning(
                f"{path}: {a_key} read as a four-stroke's crank angle (cam angle = crank angle / 2)",
                key=f"crank angles|{path}",
            ),
            stacklevel=2,
        )
    value = cols[v_key] * value_columns[v_key]
    if most is not None:
        check_lift_bound(value, str(path), v_key, value_columns)
    return cols[a_key] * units[a_key], value


def _normalise_table(angle: np.ndarray, lift: np.ndarray, name: str):
    """Check a lift table covers exactly one revolution; drop a closing row at +360 deg."""
    try:
        angle, lift = np.asarray(angle, dtype=float), np.asarray(lift, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"{name}: cam angle and lift must be arrays of numbers") from None
    if angle.ndim != 1 or lift.shape != angle.shape:
        raise InputError(
            f"{name}: cam angle and lift must be two flat arrays of the same length, "
            f"not of shapes {angle.shape} and {lift.shape}"
        )
    for column, values in (("cam angle", angle), ("lift", lift)):
        if not np.all(np.isfinite(values)):
            i = int(np.argmax(~np.isfinite(values)))
            raise InputError(f"{name}: row {i + 2}, column {column}: {values[i]:g} is not a finite number")
    if angle.size < 8:
        raise InputError(f"{name}: a lift table needs at least 8 rows, found {angle.size}")
    d = np.diff(angle)
    if np.any(d <= 0):
        i = int(np.argmax(d <= 0))
        raise InputError(
            f"{name}: cam angle must increase: row {i + 3} ({math.degrees(angle[i + 1]):.6g} deg) does not exceed "
            f"the row before ({math.degrees(angle[i]):.6g} deg)"
        )
    if np.any(lift < 0):
        i = int(np.argmax(lift < 0))
        raise InputError(f"{name}: lift must not be negative: row {i + 2} has {lift[i] * 1e3:.6g} mm")
    check_lift_bound(lift, name)
    span = angle[-1] - angle[0]
    if span > TWO_PI + 1e-9:
        raise InputError(f"{name}: the table spans {math.degrees(span):.6g} deg, more than one revolution (360 deg)")
    if math.isclose(span, TWO_PI, abs_tol=1e-9):
        if not math.isclose(lift[-1], lift[0], rel_tol=1e-9, abs_tol=1e-12):
            raise InputError(
                f"{name}: the row at {math.degrees(angle[-1]):.6g} deg closes the revolution but its lift "
                f"{lift[-1] * 1e3:.6g} mm differs from the first row's {lift[0] * 1e3:.6g} mm"
            )
        return angle[:-1].copy(), lift[:-1].copy()
    gap = angle[0] + TWO_PI - angle[-1]
    step = float(np.median(d))
    if gap > 2.0 * step + 1e-12 and lift[0] <= 1e-12 and lift[-1] <= 1e-12:
        # a table of the event only, closed at both ends (as cam cards give it, issue 40): the base
        # circle between its last and its first row is filled with zero lift at the table's step
        fill = angle[-1] + step * np.arange(1, int(math.floor((gap - 0.5 * step) / step)) + 1)
        warnings.warn(
            FactWarning(
                f"{name}: the table covers the event only ({math.degrees(span):.6g} deg): the base circle's "
                f"{math.degrees(gap):.6g} deg are filled with zero lift",
                key=f"event only|{name}",
            ),
            stacklevel=3,
        )
        return np.concatenate([angle, fill]), np.concatenate([lift, np.zeros(fill.size)])
    if gap > 2.0 * step + 1e-12:
        raise InputError(
            f"{name}: the table must cover one whole revolution: it spans {math.degrees(span):.6g} deg, leaving a "
            f"gap of {math.degrees(gap):.6g} deg before it repeats (give lift from 0 to 360 deg)"
        )
    return angle.copy(), lift.copy()
