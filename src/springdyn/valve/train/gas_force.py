"""Gas force on the valve head: the cylinder pressure against the valve's seat area.

The valve opens into the cylinder; the cylinder pressure acts on its head, the port's on
its back, so the net gas force pushes the valve towards its seat,

    ``F_gas = (p_cyl - p_port) pi d_seat^2 / 4``,

on the seat's diameter while the valve is closed or barely open (the exhaust valve opens
against the blow-down pressure: the case that matters; once open, the pressure across the
head falls quickly, and taking the seat area throughout is the usual conservative
reading).  A cylinder-pressure trace is given against crank angle from the gas-exchange
TDC, as engine measurements are; the cam's ``[timing]`` table
(:mod:`springdyn.valve.cam.timing`) phases it onto the cam: :class:`GasForce` holds the force
over one camshaft revolution for the engine, which adds it to the valve's equation of
motion (:func:`springdyn.valve.engine.equations.train_rhs`).

Sources: docs/references.md, [Heywood] (cylinder pressure, blow-down), [Norton] (gas
loads on the valve train).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...core.errors import FactWarning, InputError
from ...core.io import read_csv_columns

__all__ = [
    "gas_force",
    "read_crank_table",
    "GasForce",
    "read_pressure_trace",
    "PRESSURE_COLUMNS",
    "GAS_SAMPLES",
    "MAX_CYLINDER_PRESSURE",
    "GAP_NOTE_DEG",
    "MAX_GAP_DEG",
]

#: Columns a pressure trace may give the (absolute) cylinder pressure in, with their factor to Pa.
PRESSURE_COLUMNS = {"pressure_Pa": 1.0, "pressure_kPa": 1e3, "pressure_bar": 1e5, "pressure_MPa": 1e6}
#: Samples of the gas force over one camshaft revolution (0.1 cam deg).
GAS_SAMPLES = 3600
#: The highest cylinder pressure a trace may hold [Pa]: peak firing pressures of engines reach
#: 200-300 bar (heavy-duty diesels); 500 bar is beyond any, a trace above it is in another unit.
MAX_CYLINDER_PRESSURE = 500e5
#: A gap between a trace's rows [crank deg] above which the linear interpolation across it is
#: stated (a warning naming the gap) ...
GAP_NOTE_DEG = 10.0
#: ... and above which the trace is refused: the pressure over such a gap is not known.
MAX_GAP_DEG = 90.0


def gas_force(cylinder_pressure, port_pressure, seat_diameter):
    """Net gas force [N] on the valve towards its seat.

    ``(p_cyl - p_port) pi d^2 / 4``: positive pushes the valve closed.

    Parameters
    ----------
    cylinder_pressure : float or ndarray
        Cylinder pressure [Pa] (absolute).
    port_pressure : float
        Port (manifold) pressure behind the valve [Pa] (absolute).
    seat_diameter : float
        Valve seat diameter [m].

    Examples
    --------
    >>> round(float(gas_force(6e5, 1e5, 0.03)), 3)
    353.429
    """
    return (np.asarray(cylinder_pressure, dtype=float) - port_pressure) * (0.25 * math.pi * seat_diameter**2)


def read_crank_table(path, columns: dict, what: str, min_rows: int):
    """A CSV of a quantity against crank angle: ``crank_angle_deg`` (increasing, at least
    ``min_rows`` rows) and the quantity in one of ``columns`` (name -> factor to SI).

    Returns the crank angles [deg], the values [SI], the column given and every column.

    Parameters
    ----------
    path : str or path-like
        The CSV file.
    columns : dict
        The columns the quantity may be given in, with their factors to SI [-].
    what : str
        The quantity, for messages [-].
    min_rows : int
        The fewest rows [-].
    """
    cols = read_csv_columns(path)
    if "crank_angle_deg" not in cols:
        raise InputError(f"{path}: no column 'crank_angle_deg' (found: {', '.join(cols)})")
    given = [c for c in columns if c in cols]
    if len(given) != 1:
        raise InputError(f"{path}: give {what} in one column of {', '.join(columns)} (found: {', '.join(cols)})")
    angle = np.asarray(cols["crank_angle_deg"], dtype=float)
    if angle.size < min_rows or np.any(np.diff(angle) <= 0):
        raise InputError(f"{path}: crank_angle_deg must increase, over at least {min_rows} rows")
    return angle, np.asarray(cols[given[0]], dtype=float) * columns[given[0]], given[0], cols


def read_pressure_trace(path) -> tuple[np.ndarray, np.ndarray]:
    """A cylinder-pressure trace: crank angle [deg from the gas-exchange TDC] and pressure [Pa].

    A CSV with ``crank_angle_deg`` and one of :data:`PRESSURE_COLUMNS` (absolute pressure),
    one engine cycle (720 deg for a four-stroke), angles increasing.

    Parameters
    ----------
    path : str or path-like
        The CSV file.
    """
    angle, pressure, given, cols = read_crank_table(path, PRESSURE_COLUMNS, "the cylinder pressure", 8)
    if np.any(pressure < 0):
        raise InputError(f"{path}: an absolute pressure cannot be negative (row {int(np.argmin(pressure)) + 2})")
    if np.max(pressure) > MAX_CYLINDER_PRESSURE:
        i = int(np.argmax(pressure))
        raise InputError(
            f"{path}: row {i + 2}, column {given!r}: {cols[given][i]:.6g} is {pressure[i] / 1e5:.6g} bar, beyond "
            f"any cylinder pressure (at most {MAX_CYLINDER_PRESSURE / 1e5:g} bar; engines fire at up to 300 bar): "
            "check the column's unit (" + ", ".join(PRESSURE_COLUMNS) + ")"
        )
    return angle, pressure


def _check_gaps(crank: np.ndarray, cycle_deg: float, source: str) -> None:
    """The trace's largest gap between rows (the cycle's wrap from the last row to the first
    included): refused above :data:`MAX_GAP_DEG`, stated in a warning above :data:`GAP_NOTE_DEG`
    (the pressure is interpolated linearly across it)."""
    ends = np.append(crank, crank[0] + cycle_deg)
    steps = np.diff(ends)
    i = int(np.argmax(steps))
    gap = float(steps[i])
    if gap <= GAP_NOTE_DEG:
        return
    start, stop = float(ends[i]), float(ends[i + 1])
    stop_text = f"{stop:g} deg" + (f" ({stop - cycle_deg:g} deg, the first row)" if i + 1 == crank.size else "")
    where = f"{source}: no rows from {start:g} deg to {stop_text}, a gap of {gap:g} crank deg"
    if gap > MAX_GAP_DEG:
        raise InputError(
            f"{where}: the cylinder pressure over it is not known (a trace may leave gaps of up to "
            f"{MAX_GAP_DEG:g} crank deg, interpolated linearly); give the whole {cycle_deg:g}-deg cycle"
        )
    more = int(np.count_nonzero(steps > GAP_NOTE_DEG)) - 1
    warnings.warn(
        FactWarning(
            f"{where}{f' (and {more} more gaps above {GAP_NOTE_DEG:g} deg)' if more else ''}: the pressure is "
            "interpolated linearly across it",
            key=f"pressure gap|{source}",
        ),
        stacklevel=3,
    )


@dataclass(frozen=True)
class GasForce:
    """The gas force on the valve over one camshaft revolution (for the engine) [N].

    ``force[k]`` acts at cam angle ``2 pi k / n``; the engine interpolates linearly and
    periodically.
    """

    force: np.ndarray  #: (n,) [N], positive towards the seat
    source: str = ""

    @classmethod
    def from_trace(cls, crank_deg, pressure, *, axis, seat_diameter: float, port_pressure: float = 101325.0, source=""):
        """Phase a cylinder-pressure trace onto the cam and turn it into the force on the valve.

        Parameters
        ----------
        crank_deg, pressure : array_like
            The trace: crank angle from the gas-exchange TDC [deg], absolute pressure [Pa].
        axis : CrankAxis
            The cam's crank axis, referenced to TDC by its ``[timing]`` table
            (:func:`springdyn.valve.cam.timing.crank_axis`).
        seat_diameter : float
            Valve seat diameter [m].
        port_pressure : float
            Port pressure behind the valve [Pa] (absolute).
        source : str
            Where the trace came from, for messages.
        """
        if axis is None or not axis.referenced:
            raise InputError(
                "a cylinder-pressure trace is against crank angle: give the cam's [timing] table (lobe_centre, "
                "valve, strokes) to phase it onto the cam"
            )
        if not (seat_diameter > 0 and math.isfinite(seat_diameter)):
            raise InputError(f"seat_diameter = {seat_diameter!r} must be a positive diameter [m]")
        crank = np.asarray(crank_deg, dtype=float)
        span = crank[-1] - crank[0]
        if span > axis.cycle_deg + 1e-9 or span < 0.9 * axis.cycle_deg:
            raise InputError(
                f"{source or 'the pressure trace'}: its crank angles span {span:g} deg; a {axis.cycle_deg:g}-deg "
                "engine cycle is needed (one trace row per crank angle of the cycle)"
            )
        _check_gaps(crank, axis.cycle_deg, source or "the pressure trace")
        cam_deg = np.arange(GAS_SAMPLES) * (360.0 / GAS_SAMPLES)
        phi = axis.crank_deg(cam_deg)
        p = np.interp(phi, crank, pressure, period=axis.cycle_deg)
        return cls(np.ascontiguousarray(gas_force(p, port_pressure, seat_diameter)), source)

    @classmethod
    def from_file(cls, path, *, axis, seat_diameter: float, port_pressure: float = 101325.0):
        """:meth:`from_trace` of a CSV trace (:func:`read_pressure_trace`).

        Parameters
        ----------
        path : str or path-like
            The CSV file.
        axis : CrankAxis
            The cam's referenced crank axis.
        seat_diameter : float
            Valve seat diameter [m].
        port_pressure : float
            Port pressure behind the valve [Pa] (absolute).
        """
        crank, p = read_pressure_trace(path)
        return cls.from_trace(
            crank, p, axis=axis, seat_diameter=seat_diameter, port_pressure=port_pressure, source=str(Path(path))
        )

    def at(self, cam_angle):
        """The force [N] at cam angles [rad] (linear, periodic), as the engine reads it.

        Parameters
        ----------
        cam_angle : float or ndarray
            Cam angle [rad].
        """
        n = self.force.size
        x = np.mod(np.asarray(cam_angle, dtype=float), 2.0 * math.pi) * (n / (2.0 * math.pi))
        i0 = np.floor(x).astype(int) % n
        frac = x - np.floor(x)
        return self.force[i0] * (1.0 - frac) + self.force[(i0 + 1) % n] * frac
