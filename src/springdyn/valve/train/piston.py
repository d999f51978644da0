"""Valve-to-piston clearance: the piston's crank-slider motion against the valve's lift.

Near the gas-exchange TDC both valves are open while the piston passes its top: the exhaust
valve closing, the intake valve opening.  The **seated clearance** ``c0(phi)`` is how far the
seated valve could travel along its own axis before it touched the piston at the crank angle
``phi`` (what the checking-spring method measures with a dial indicator on the retainer, the
valve pushed down onto the piston at crank angles through the overlap [moparts]); the valve's
lift ``z(phi)`` takes it up:

    ``c(phi) = c0(phi) - z(phi)``,  judged along the valve's axis.

``c0`` comes from the ``[piston]`` table, either measured (``clearance_table``: a CSV of
``c0`` against crank angle) or from the geometry:

- **the piston** (crank radius ``r = stroke / 2``, rod ``l``, wrist-pin offset ``e``):
  the pin's height above the crank axis along the cylinder axis at the crank angle ``theta``
  from the cylinder axis is the exact closed form of the offset crank-slider,

      ``x(theta) = r cos(theta) + sqrt(l^2 - (r sin(theta) - e)^2)``

  ([Heywood] Eq. 2.3 for ``e = 0``; [Norton-DoM] sec. 4.6, the offset crank-slider).  Its TDC
  is where crank and rod line up, ``sin(theta_TDC) = e / (l + r)``, ``x_TDC = sqrt((l + r)^2 - e^2)``;
  crank angles are counted from that TDC (a degree wheel set with a piston stop finds it),
  so the piston stands ``s(phi) = x_TDC - x(theta_TDC + phi)`` below its TDC;
- **the valve**, inclined at ``alpha`` to the cylinder axis: a lift ``z`` along its axis
  brings its head ``z cos(alpha)`` nearer the piston along the cylinder axis, so a gap ``g``
  along the cylinder axis is ``g / cos(alpha)`` of valve travel;
- **the gap** along the cylinder axis between the seated valve's head (its lowest point) and
  the piston crown at TDC, ``tdc_clearance`` (the piston's depth below the deck, the compressed
  gasket and the valve's recess in the chamber together), deepened by the valve pocket
  ``pocket_depth`` where the valve head fits the pocket (``valve_head_diameter <=
  pocket_diameter``):

      ``c0(phi) = (tdc_clearance + pocket_depth + s(phi)) / cos(alpha)``.

Simplifications (docs/valve-train.md, "Valve-to-piston clearance"): the crank turns
uniformly (the crank angle is the cam's, doubled, through ``[timing]``); piston, rod and
crank are rigid and their bearing clearances closed (rod stretch at speed, thermal growth and
the piston's rock in its bore are not modelled: the criterion's margin is for them); the crown
under the valve is flat and the pocket a flat-bottomed recess cut along the valve's axis (the
head's sideways travel ``z sin(alpha)`` stays inside it); the clearance is measured along the
valve's axis at the head's lowest point, not as the shortest distance between the two
surfaces; the valve's own lift is the simulated one (float and bounce included) or the rigid
train's (:func:`static_valve_lift`, the "static" clearance beside it).

:class:`Piston` is the ``[piston]`` table; :class:`ValveClearance` the clearance over a
speed range (the speed map), built by :func:`clearance_map` from the valve lifts a speed sweep
records.

Sources: docs/references.md, [Heywood], [Norton-DoM], [moparts], [LC Engineering].
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, load_toml, param
from ...core.results import Result, text_table
from ..cam.from_lift import valve_lift_from_lobe_lift
from ..cam.timing import crank_words
from .gas_force import read_crank_table

__all__ = [
    "Piston",
    "ValveClearance",
    "tdc_crank_angle",
    "piston_position",
    "piston_drop",
    "seated_clearance",
    "static_valve_lift",
    "read_clearance_table",
    "clearance_map",
    "CLEARANCE_COLUMNS",
    "MAP_WINDOW_DEG",
]

#: Columns a measured clearance table may give the seated clearance in, with their factor to m.
CLEARANCE_COLUMNS = {"clearance_m": 1.0, "clearance_mm": 1e-3, "clearance_in": 0.0254}
#: The crank angles the speed map's figure shows around the gas-exchange TDC [deg]: the
#: overlap, where the valves and the piston meet.
MAP_WINDOW_DEG = 45.0
#: The largest valve angle to the cylinder axis the table takes [rad]: valves lean 0-30 deg
#: (pent-roof chambers 10-25 deg a side); past 60 deg the projection ``1 / cos`` runs away.
MAX_VALVE_ANGLE = math.radians(60.0)


def tdc_crank_angle(crank_radius: float, rod_length: float, pin_offset: float = 0.0) -> float:
    """Crank angle of the TDC from the cylinder axis [rad]: ``asin(e / (l + r))``.

    At TDC the crank and the rod lie on one line from the crank axis to the wrist pin, which
    runs ``e`` beside the crank axis ([Norton-DoM] sec. 4.6, the offset crank-slider's limit
    positions).

    Parameters
    ----------
    crank_radius : float
        Crank radius r, half the stroke [m].
    rod_length : float
        Connecting-rod length l, centre to centre [m].
    pin_offset : float
        Wrist-pin offset e from the crank axis, towards the side the crank pin moves to after
        TDC [m].

    Examples
    --------
    >>> round(math.degrees(tdc_crank_angle(0.043, 0.1435, 0.0)), 9)
    0.0
    """
    return math.asin(pin_offset / (rod_length + crank_radius))


def piston_position(theta, crank_radius: float, rod_length: float, pin_offset: float = 0.0):
    """Height of the wrist pin above the crank axis, along the cylinder axis [m].

    ``x = r cos(theta) + sqrt(l^2 - (r sin(theta) - e)^2)``: the exact closed form of the
    offset crank-slider ([Heywood] Eq. 2.3 with ``e = 0``; [Norton-DoM] sec. 4.6).

    Parameters
    ----------
    theta : float or array_like
        Crank angle from the cylinder axis [rad].
    crank_radius : float
        Crank radius r [m].
    rod_length : float
        Rod length l, centre to centre [m].
    pin_offset : float
        Wrist-pin offset e [m].

    Examples
    --------
    >>> round(float(piston_position(math.pi / 2, 0.04, 0.14)), 6)
    0.134164
    """
    theta = np.asarray(theta, dtype=float)
    side = crank_radius * np.sin(theta) - pin_offset
    return crank_radius * np.cos(theta) + np.sqrt(rod_length**2 - side**2)


def piston_drop(crank_angle, stroke: float, rod_length: float, pin_offset: float = 0.0):
    """How far the piston stands below its TDC [m] at crank angles from that TDC.

    ``s(phi) = x_TDC - x(theta_TDC + phi)`` (:func:`piston_position`, :func:`tdc_crank_angle`;
    ``x_TDC = sqrt((l + r)^2 - e^2)``); 0 at TDC, the stroke at BDC for ``e = 0``.

    Parameters
    ----------
    crank_angle : float or array_like
        Crank angle from the piston's TDC [rad].
    stroke : float
        Stroke, twice the crank radius [m].
    rod_length : float
        Rod length, centre to centre [m].
    pin_offset : float
        Wrist-pin offset [m].

    Examples
    --------
    >>> round(float(piston_drop(math.pi, 0.086, 0.1435)), 9)
    0.086
    """
    r = 0.5 * stroke
    top = math.sqrt((rod_length + r) ** 2 - pin_offset**2)
    theta = tdc_crank_angle(r, rod_length, pin_offset) + np.asarray(crank_angle, dtype=float)
    return top - piston_position(theta, r, rod_length, pin_offset)


def seated_clearance(drop, tdc_clearance: float, pocket_depth: float = 0.0, valve_angle: float = 0.0):
    """The seated valve's travel to the piston along its axis [m]:
    ``(tdc_clearance + pocket_depth + s) / cos(alpha)``.

    The gap along the cylinder axis (at TDC, the pocket's depth added, plus the piston's drop
    ``s``) closed by a valve inclined at ``alpha`` moving ``z cos(alpha)`` along it per lift ``z``.

    Parameters
    ----------
    drop : float or array_like
        The piston's drop below its TDC [m] (:func:`piston_drop`).
    tdc_clearance : float
        Gap between the seated valve's head and the crown at TDC, along the cylinder axis [m].
    pocket_depth : float
        Depth of the valve pocket the head fits [m] (0: none, or the head does not fit).
    valve_angle : float
        Valve axis to cylinder axis [rad].

    Examples
    --------
    >>> round(float(seated_clearance(0.0, 1e-3, 1e-3, math.radians(60.0))), 9)
    0.004
    """
    return (tdc_clearance + pocket_depth + np.asarray(drop, dtype=float)) / math.cos(valve_angle)


def static_valve_lift(cam, valve_train, cam_angle):
    """The valve lift of the rigid train [m] at cam angles [rad]: the lobe lift times the rocker
    ratio (or a drawn lever's valve-side lift) less the lash, never below 0; the cam lift for
    the spring alone.

    Parameters
    ----------
    cam : Cam
        The cam.
    valve_train : ValveTrain or None
        The train (None: the valve follows the cam).
    cam_angle : array_like
        Cam angles [rad].
    """
    h = cam.lift_at(np.asarray(cam_angle, dtype=float))
    if valve_train is None:
        return np.asarray(h, dtype=float)
    lash = 0.0 if valve_train.hydraulic else valve_train.lash
    if valve_train.geometry is not None:
        return np.maximum(valve_train.geometry.valve_lift_at_lobe_lift(h) - lash, 0.0)
    return valve_lift_from_lobe_lift(h, valve_train.ratio, lash)


def read_clearance_table(path) -> tuple[np.ndarray, np.ndarray]:
    """A measured seated clearance against crank angle: crank angle [deg from the
    gas-exchange TDC] and the seated valve's travel to the piston [m].

    A CSV with ``crank_angle_deg`` (increasing, within one cycle, -360 to 360) and one of
    :data:`CLEARANCE_COLUMNS` (the checking-spring method's readings [moparts]); at least 2 rows.

    Parameters
    ----------
    path : str or path-like
        The CSV file.
    """
    angle, clearance, given, _ = read_crank_table(
        path, CLEARANCE_COLUMNS, "the seated valve's clearance to the piston", 2
    )
    if angle[0] < -360.0 or angle[-1] > 360.0:
        raise InputError(f"{path}: crank_angle_deg must lie from -360 to 360 deg (from the gas-exchange TDC)")
    if np.any(clearance < 0):
        i = int(np.argmin(clearance))
        raise InputError(
            f"{path}: row {i + 2}, column {given!r}: a seated valve's clearance to the piston cannot be negative"
        )
    return angle, clearance


_GEOMETRY_KEYS = ("bore", "stroke", "rod_length", "tdc_clearance")


@dataclass(frozen=True)
class Piston(Parameters):
    """The ``[piston]`` table: the piston's crank-slider, the valve over it and its pocket, or a
    measured seated clearance against crank angle (see the module docstring).

    Examples
    --------
    >>> p = Piston.from_dict(dict(bore="86 mm", stroke="86 mm", rod_length="143.5 mm", tdc_clearance="1 mm"))
    >>> round(float(p.seated_at([0.0])[0]) * 1e3, 6)
    1.0
    """

    bore: float = param("m", "cylinder bore", display="mm", positive=True, default=None)
    stroke: float = param("m", "piston stroke (twice the crank radius)", display="mm", positive=True, default=None)
    rod_length: float = param("m", "connecting-rod length, centre to centre", display="mm", positive=True, default=None)
    pin_offset: float = param(
        "m",
        "wrist-pin offset from the crank axis (desaxe), towards the side the crank pin moves to after TDC "
        "(negative: the other side)",
        display="mm",
        default=0.0,
    )
    tdc_clearance: float = param(
        "m",
        "gap between the seated valve's head (its lowest point) and the piston crown at TDC, along the cylinder "
        "axis: the piston's depth below the deck, the compressed gasket and the valve's recess together",
        display="mm",
        default=None,
    )
    valve_angle: float = param(
        "rad", "angle of the valve's axis to the cylinder axis", display="deg", nonnegative=True, default=0.0
    )
    pocket_depth: float = param(
        "m",
        "depth of the valve pocket (relief) in the crown, along the cylinder axis",
        display="mm",
        nonnegative=True,
        default=0.0,
    )
    pocket_diameter: float = param(
        "m", "diameter of the valve pocket (with pocket_depth)", display="mm", positive=True, default=None
    )
    valve_head_diameter: float = param(
        "m",
        "valve head diameter: the pocket counts where the head fits it (with pocket_depth)",
        display="mm",
        positive=True,
        default=None,
    )
    clearance_table: str = param(
        None,
        "instead of the geometry: a CSV of the seated valve's travel to the piston against crank angle from the "
        "gas-exchange TDC (crank_angle_deg and clearance_mm, clearance_m or clearance_in), as the checking-spring "
        "method measures it",
        kind="str",
        default=None,
    )

    table = "piston"
    examples = {"exhaust": "valve_piston.toml"}
    default_example = "exhaust"

    @classmethod
    def _prepare(cls, mapping: dict, *, base_dir=None, **context) -> dict:
        """A relative ``clearance_table`` is taken from ``base_dir`` (the TOML file's folder)."""
        name = mapping.get("clearance_table")
        if isinstance(name, str) and name and base_dir is not None:
            p = Path(name)
            mapping["clearance_table"] = str(p if p.is_absolute() else Path(base_dir) / p)
        return mapping

    def _validate(self) -> None:
        if self.valve_angle > MAX_VALVE_ANGLE:
            raise InputError(
                f"[piston] valve_angle = {math.degrees(self.valve_angle):g} deg must be at most "
                f"{math.degrees(MAX_VALVE_ANGLE):g} deg (valves lean 0-30 deg to the cylinder axis)"
            )
        if self.clearance_table is not None:
            given = [k for k in (*_GEOMETRY_KEYS, "pocket_diameter", "valve_head_diameter") if getattr(self, k)]
            given += [k for k in ("pin_offset", "pocket_depth") if getattr(self, k) != 0.0]
            if given:
                raise InputError(
                    f"[piston] clearance_table gives the seated clearance measured: {', '.join(given)} (the "
                    "geometry) cannot be given beside it; give one or the other"
                )
            if not Path(self.clearance_table).is_file():
                raise InputError(f"[piston] clearance_table = {self.clearance_table!r}: no such file")
            read_clearance_table(self.clearance_table)  # checked whole before any work
            return
        missing = [k for k in _GEOMETRY_KEYS if getattr(self, k) is None]
        if missing:
            raise InputError(
                f"[piston] needs {', '.join(missing)} (the crank-slider and the gap at TDC), or a measured "
                "clearance_table"
            )
        reach = 0.5 * self.stroke + abs(self.pin_offset)
        if not self.rod_length > reach:
            raise InputError(
                f"[piston] rod_length = {self.rod_length * 1e3:g} mm must exceed half the stroke plus the pin offset "
                f"({reach * 1e3:g} mm): the rod cannot reach the pin (rods run 1.5-2 strokes)"
            )
        if abs(self.pin_offset) > 0.5 * self.bore:
            raise InputError(
                f"[piston] pin_offset = {self.pin_offset * 1e3:g} mm lies outside the bore (at most half of "
                f"{self.bore * 1e3:g} mm; offsets are 0.5-2 mm)"
            )
        if self.pocket_depth > 0.0:
            need = [k for k in ("pocket_diameter", "valve_head_diameter") if getattr(self, k) is None]
            if need:
                raise InputError(
                    f"[piston] pocket_depth = {self.pocket_depth * 1e3:g} mm needs {', '.join(need)} (whether the "
                    "valve head fits the pocket)"
                )
        if self.valve_head_diameter is not None and not self.valve_head_diameter < self.bore:
            raise InputError(
                f"[piston] valve_head_diameter = {self.valve_head_diameter * 1e3:g} mm must be below the bore "
                f"{self.bore * 1e3:g} mm"
            )
        if not self.tdc_clearance + self.pocket_counted > 0.0:
            raise InputError(
                f"[piston] tdc_clearance = {self.tdc_clearance * 1e3:g} mm"
                + (f" with the pocket's {self.pocket_counted * 1e3:g} mm" if self.pocket_counted else "")
                + ": the seated valve would touch the piston at TDC; the gap must be positive"
            )

    @classmethod
    def in_file(cls, path) -> Piston | None:
        """The ``[piston]`` table of a TOML file, or None when it has none.

        Parameters
        ----------
        path : str or path-like
            A definition file (the valve train's, the cam's or the spring's).
        """
        doc = load_toml(path)
        if "piston" not in doc:
            return None
        return cls.from_dict(doc["piston"], source=str(path), base_dir=Path(path).parent)

    @property
    def measured(self) -> bool:
        """Whether the seated clearance is a measured table (not the geometry)."""
        return self.clearance_table is not None

    @property
    def head_fits_pocket(self) -> bool:
        """Whether the valve head fits the pocket (its diameter at most the pocket's)."""
        return (
            self.pocket_depth > 0.0
            and self.valve_head_diameter is not None
            and self.pocket_diameter is not None
            and self.valve_head_diameter <= self.pocket_diameter
        )

    @property
    def pocket_counted(self) -> float:
        """The pocket depth the clearance counts [m]: the pocket's where the head fits it, else 0."""
        return self.pocket_depth if self.head_fits_pocket else 0.0

    def seated_at(self, crank_deg):
        """The seated valve's travel to the piston [m] at crank angles [deg from the
        gas-exchange TDC]: :func:`seated_clearance` of the geometry, or the measured table
        interpolated linearly (NaN outside its crank angles: not known there).

        Parameters
        ----------
        crank_deg : array_like
            Crank angles [deg].
        """
        phi = np.asarray(crank_deg, dtype=float)
        if self.measured:
            angle, clearance = read_clearance_table(self.clearance_table)
            return np.interp(phi, angle, clearance, left=np.nan, right=np.nan)
        drop = piston_drop(np.radians(phi), self.stroke, self.rod_length, self.pin_offset)
        return seated_clearance(drop, self.tdc_clearance, self.pocket_counted, self.valve_angle)

    def notes(self) -> list[str]:
        """What the clearance rests on, in words (the pocket, the measured table)."""
        if self.measured:
            return [
                f"seated clearance measured ({Path(self.clearance_table).name}), interpolated linearly; outside its "
                "crank angles the clearance is not judged"
            ]
        out = []
        if self.pocket_depth > 0.0 and not self.head_fits_pocket:
            out.append(
                f"the valve head ({self.valve_head_diameter * 1e3:g} mm) does not fit the pocket "
                f"({self.pocket_diameter * 1e3:g} mm): its edge meets the crown beside it, the pocket's depth is not "
                "counted"
            )
        return out


@dataclass(repr=False)
class ValveClearance(Result):
    """The valve-to-piston clearance over a speed range: the speed map (clearance against speed
    and crank angle), each speed's minimum and its crank angle, the rigid train's (static)
    clearance beside it.

    ``clearance = seated - valve lift`` along the valve's axis (module docstring), the valve lift
    the run's (float and bounce included).
    """

    cam_rpm: np.ndarray  #: (n,) [rev/min]
    crank_angle_deg: np.ndarray  #: (m,) from the gas-exchange TDC [deg], increasing
    seated: np.ndarray  #: (m,) the seated valve's travel to the piston [m]
    valve_lift: np.ndarray  #: (n, m) the simulated valve lift [m]
    static_lift: np.ndarray  #: (m,) the rigid train's valve lift [m]
    engine_per_cam: float = 2.0  #: engine revolutions per cam revolution [-]
    valve: str = "intake"
    limit: float | None = None  #: the criterion's smallest clearance [m] (None: not judged)
    valve_angle: float = 0.0  #: [rad], for the gap along the cylinder axis
    source_notes: tuple = ()

    title = "valve-to-piston clearance"

    @property
    def clearance(self) -> np.ndarray:
        """(n, m) clearance at each speed and crank angle [m]."""
        return self.seated[None, :] - self.valve_lift

    @property
    def static_clearance(self) -> np.ndarray:
        """(m,) clearance of the rigid train [m]."""
        return self.seated - self.static_lift

    @property
    def min_by_speed(self) -> tuple[np.ndarray, np.ndarray]:
        """Each speed's smallest clearance [m] and its crank angle [deg]."""
        c = self.clearance
        k = np.argmin(c, axis=1)
        return c[np.arange(c.shape[0]), k], self.crank_angle_deg[k]

    def _repr_caption(self) -> str:
        return f"{self.valve} valve, {self.cam_rpm.size} speeds {self.cam_rpm.min():g}-{self.cam_rpm.max():g} cam rpm"

    def _summary(self) -> dict:
        lows, where = self.min_by_speed
        i = int(np.argmin(lows))
        ks = int(np.argmin(self.static_clearance))
        static = float(self.static_clearance[ks])
        s = dict(
            valve=self.valve,
            speeds=int(self.cam_rpm.size),
            min_clearance_m=float(lows[i]),
            min_clearance_cam_rpm=float(self.cam_rpm[i]),
            min_clearance_engine_rpm=float(self.engine_per_cam * self.cam_rpm[i]),
            min_clearance_crank_angle_deg=float(where[i]),
            min_clearance_along_bore_m=float(lows[i] * math.cos(self.valve_angle)),
            static_min_clearance_m=static,
            static_min_clearance_crank_angle_deg=float(self.crank_angle_deg[ks]),
            clearance_lost_to_dynamics_m=float(static - lows[i]),
            valve_meets_piston=bool(lows[i] <= 0.0),
            min_clearance_limit_m=self.limit,
        )
        s["clearance_ok"] = None if self.limit is None else bool(lows[i] >= self.limit)
        notes = list(self.source_notes)
        if self.limit is None:
            notes.append("no limit given: the clearance is not judged")
        if s["valve_meets_piston"]:
            notes.append(
                f"VALVE MEETS PISTON at {self.cam_rpm[i]:.0f} cam rpm, {crank_words(float(where[i]))}: the simulated "
                f"valve reaches {-1e3 * lows[i]:.2f} mm past the piston (the run does not model the impact)"
            )
        s["notes"] = notes
        return s

    def describe(self) -> str:
        """Each speed's smallest clearance and its crank angle, the static one beside it, and the
        verdict against the limit."""
        s = self.summary
        lows, where = self.min_by_speed
        rows = [
            (
                f"{rpm:.0f}",
                f"{self.engine_per_cam * rpm:.0f}",
                f"{1e3 * c:.3f}",
                crank_words(float(w)),
                "" if self.limit is None else ("ok" if c >= self.limit else "BELOW LIMIT"),
            )
            for rpm, c, w in zip(self.cam_rpm, lows, where)
        ]
        lines = [
            f"{self.title}: {self._repr_caption()}",
            text_table(rows, headers=("cam rpm", "engine rpm", "min clearance [mm]", "at crank angle", "")),
            f"static (rigid train, cam lift): {1e3 * s['static_min_clearance_m']:.3f} mm at "
            f"{crank_words(s['static_min_clearance_crank_angle_deg'])}",
            f"smallest: {1e3 * s['min_clearance_m']:.3f} mm at {s['min_clearance_cam_rpm']:.0f} cam rpm "
            f"({s['min_clearance_engine_rpm']:.0f} engine rpm), {crank_words(s['min_clearance_crank_angle_deg'])}; "
            + (
                f"{1e3 * s['clearance_lost_to_dynamics_m']:.3f} mm below the static"
                if s["clearance_lost_to_dynamics_m"] >= 0.0
                else f"{-1e3 * s['clearance_lost_to_dynamics_m']:.3f} mm above the static (the train's deflection)"
            )
            + (
                f"; limit >= {1e3 * self.limit:g} mm: {'PASS' if s['clearance_ok'] else 'FAIL'}"
                if self.limit is not None
                else ""
            ),
        ]
        return "\n".join(lines + ["note: " + n for n in s["notes"]])

    def to_xarray(self):
        """Dataset over ``crank_angle`` (rows of the CSV) and ``cam_rpm``: the clearance map,
        the seated and static clearances, and each speed's minimum."""
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        lows, where = self.min_by_speed
        cols = ", ".join(f"clearance_at_{rpm:.0f}_cam_rpm_m" for rpm in self.cam_rpm)
        lift_cols = ", ".join(f"valve_lift_at_{rpm:.0f}_cam_rpm_m" for rpm in self.cam_rpm)
        return xr.Dataset(
            {
                "seated_clearance": ("crank_angle", self.seated, {"units": "m"}),
                "static_valve_lift": ("crank_angle", self.static_lift, {"units": "m"}),
                "static_clearance": ("crank_angle", self.static_clearance, {"units": "m"}),
                "clearance": (("cam_rpm", "crank_angle"), self.clearance, {"units": "m", "csv_columns": cols}),
                "valve_lift": (("cam_rpm", "crank_angle"), self.valve_lift, {"units": "m", "csv_columns": lift_cols}),
                "min_clearance": ("cam_rpm", lows, {"units": "m"}),
                "min_clearance_crank_angle": ("cam_rpm", where, {"units": "deg"}),
            },
            coords={
                "crank_angle": ("crank_angle", self.crank_angle_deg, {"units": "deg", "origin": "gas-exchange TDC"}),
                "cam_rpm": ("cam_rpm", self.cam_rpm, {"units": "rpm"}),
                "engine_rpm": ("cam_rpm", self.engine_per_cam * self.cam_rpm, {"units": "rpm"}),
            },
            attrs={"valve": self.valve, **({} if self.limit is None else {"limit_m": float(self.limit)})},
        )

    def _plot(self, ax=None):
        """The smallest clearance against engine speed (static and limit beside it), and the
        speed map over the crank angles around the gas-exchange TDC."""
        from ...core.plotting import new_figure  # (here: matplotlib costs 0.3 s of start-up)

        engine = self.engine_per_cam * self.cam_rpm
        lows, _ = self.min_by_speed
        if ax is None:
            fig, (ax, ax_map) = new_figure(1, 2, figsize=(12, 4.8))
        else:
            ax_map = None
        mm = 1e3
        ax.plot(engine, mm * lows, "o-", color="C0", label="simulated valve (float, bounce)")
        ax.axhline(mm * float(np.min(self.static_clearance)), color="C2", ls="--", label="static (rigid train)")
        if self.limit is not None:
            ax.axhline(mm * self.limit, color="C3", ls=":", label=f"limit {mm * self.limit:g} mm")
        ax.axhline(0.0, color="k", lw=0.8)
        ax.set_xlabel("engine speed [rpm]")
        ax.set_ylabel(f"smallest {self.valve} valve-to-piston clearance [mm]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        if ax_map is not None:
            window = np.abs(self.crank_angle_deg) <= MAP_WINDOW_DEG
            phi = self.crank_angle_deg[window]
            c = mm * self.clearance[:, window]
            if self.cam_rpm.size > 1 and phi.size > 1:
                # the colours span the clearances that matter: up to a few times the static minimum
                top = max(3.0 * mm * float(np.min(self.static_clearance)), 4.0 * mm * (self.limit or 0.0), 1.0)
                mesh = ax_map.pcolormesh(
                    phi, engine, c, shading="nearest", cmap="viridis_r", vmin=min(0.0, c.min()), vmax=top
                )
                fig.colorbar(mesh, ax=ax_map, label="clearance [mm]")
                if self.limit is not None and c.min() < mm * self.limit < c.max():
                    ax_map.contour(phi, engine, c, levels=[mm * self.limit], colors="C3", linewidths=1.2)
            else:
                ax_map.plot(phi, c[0], color="C0")
            ax_map.set_xlabel("crank angle [deg ATDC, gas exchange]")
            ax_map.set_ylabel("engine speed [rpm]")
            ax_map.set_title(
                "clearance map (red: the limit)" if self.limit is not None else "clearance map", fontsize=9
            )
        return ax.figure


def clearance_map(piston: Piston, axis, cam_angle, valve_lift, static_lift, cam_rpm, *, valve: str, limit=None):
    """The speed map of the valve-to-piston clearance (:class:`ValveClearance`) from the valve
    lifts of a sweep's last revolutions.

    Parameters
    ----------
    piston : Piston
        The ``[piston]`` table.
    axis : CrankAxis
        The cam's crank axis, referenced to the gas-exchange TDC by its ``[timing]``
        (:func:`springdyn.valve.cam.timing.crank_axis`).
    cam_angle : array_like
        (m,) cam angles of the lifts [rad].
    valve_lift : array_like
        (n, m) simulated valve lift at each speed [m].
    static_lift : array_like
        (m,) the rigid train's valve lift [m] (:func:`static_valve_lift`).
    cam_rpm : array_like
        (n,) cam speeds [rev/min].
    valve : str
        Which valve (the ``[timing]`` table's) [-].
    limit : float, optional
        Smallest clearance of the criterion [m].
    """
    if axis is None or not axis.referenced:
        raise InputError(
            "the valve-to-piston clearance is against crank angle: give the cam's [timing] table (lobe_centre, "
            "valve, strokes) to place the valve's lift on the piston's stroke"
        )
    phi = axis.crank_deg(np.degrees(np.asarray(cam_angle, dtype=float)))
    order = np.argsort(phi, kind="stable")
    phi = phi[order]
    seated = piston.seated_at(phi)
    known = np.isfinite(seated)
    if not known.any():
        raise InputError(
            f"[piston] clearance_table covers no crank angle of the cam's revolution ({phi[0]:.0f} to {phi[-1]:.0f} "
            "deg from the gas-exchange TDC)"
        )
    keep = order[known]
    lift = np.atleast_2d(np.asarray(valve_lift, dtype=float))[:, keep]
    return ValveClearance(
        cam_rpm=np.atleast_1d(np.asarray(cam_rpm, dtype=float)),
        crank_angle_deg=phi[known],
        seated=seated[known],
        valve_lift=lift,
        static_lift=np.asarray(static_lift, dtype=float)[keep],
        engine_per_cam=axis.per_cam,
        valve=valve,
        limit=limit,
        valve_angle=piston.valve_angle,
        source_notes=tuple(piston.notes()),
    )
