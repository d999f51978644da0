"""Valve timing: cam angles as the crank angles an engine builder reads.

A four-stroke engine turns its camshaft once per two crankshaft revolutions (a two-stroke's
cam, where it has one, once per revolution), so a cam angle ``theta`` is the crank angle

    ``phi = phi_c + k (theta - theta_c)``,  ``k = strokes / 2``

with ``theta_c`` the cam angle of the lobe's maximum lift and ``phi_c`` the crank angle the
``[timing]`` table gives it: the **lobe centreline**, counted from the gas-exchange
(overlap) TDC, *after* it for an intake valve and *before* it for an exhaust valve, as cam
cards give it (an intake centreline of 110 deg is 110 deg ATDC).  Crank angles are reported
in degrees from that TDC, within one cycle (-360 to +360 deg for a four-stroke), and in
words: "12.0 deg BTDC", "48.0 deg ABDC" from the nearest dead centre.

Given only an engine speed (``--engine-rpm``), the crank angle is ``k theta`` counted from
the start of the cam's event (no TDC is known): :func:`crank_axis` without a timing.

:class:`Timing` is the ``[timing]`` table (in the cam's TOML file); :class:`CrankAxis` maps
cam angles to crank angles for every valve output (simulation, sweep, cam analysis,
report).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, load_toml, param

__all__ = [
    "VALVES",
    "Timing",
    "CrankAxis",
    "CrankAngles",
    "crank_axis",
    "crank_words",
    "cam_rpm_from_engine_rpm",
    "engine_rpm_from_cam_rpm",
]

#: The valves a ``[timing]`` table can describe: the sign of the lobe centreline.
VALVES = ("intake", "exhaust")


def _cam_turns_per_crank_turn(strokes: int) -> float:
    """``2 / strokes`` [-]: the camshaft turns once per cycle, a cycle is ``strokes / 2`` crank turns."""
    if strokes not in (2, 4):
        raise InputError(f"strokes = {strokes!r} must be 2 or 4")
    return 2.0 / strokes


def _scaled(speed, factor: float):
    """``speed * factor``: a float for a scalar, an array for an array."""
    return np.asarray(speed, dtype=float) * factor if np.ndim(speed) else float(speed) * factor


def cam_rpm_from_engine_rpm(engine_rpm, strokes: int = 4):
    """Camshaft speed [rev/min] from the engine (crankshaft) speed [rev/min].

    A four-stroke engine turns its camshaft once per two crankshaft revolutions; a
    two-stroke engine once per revolution.

    Parameters
    ----------
    engine_rpm : float or array_like
        Engine speed [rev/min].
    strokes : int
        Strokes per cycle [-]: 4 (default) or 2.

    Examples
    --------
    >>> cam_rpm_from_engine_rpm(6000)
    3000.0
    """
    return _scaled(engine_rpm, _cam_turns_per_crank_turn(strokes))


def engine_rpm_from_cam_rpm(cam_rpm, strokes: int = 4):
    """Engine (crankshaft) speed [rev/min] from the camshaft speed [rev/min]: the inverse of
    :func:`cam_rpm_from_engine_rpm`.

    Parameters
    ----------
    cam_rpm : float or array_like
        Camshaft speed [rev/min].
    strokes : int
        Strokes per cycle [-]: 4 (default) or 2.

    Examples
    --------
    >>> engine_rpm_from_cam_rpm(3000)
    6000.0
    """
    return _scaled(cam_rpm, 1.0 / _cam_turns_per_crank_turn(strokes))


@dataclass(frozen=True)
class Timing(Parameters):
    """The ``[timing]`` table: where the lobe sits on the crank (see the module docstring).

    Examples
    --------
    >>> t = Timing.from_dict({"lobe_centre": "110 deg", "valve": "intake"})
    >>> round(math.degrees(t.lobe_centre), 6), t.strokes
    (110.0, 4)
    """

    lobe_centre: float = param(
        "rad",
        "crank angle of the lobe's maximum lift (the lobe centreline) from the gas-exchange TDC: "
        "after it for an intake valve, before it for an exhaust valve",
        display="deg",
    )
    valve: str = param(None, "which valve the cam drives", kind="str", choices=VALVES, default="intake")
    strokes: int = param(
        "", "strokes of the engine's cycle (4: the cam turns at half the crank speed)", kind="int", default=4
    )

    table = "timing"

    def _validate(self) -> None:
        if self.strokes not in (2, 4):
            raise InputError(f"strokes = {self.strokes!r} must be 4 (four-stroke) or 2 (two-stroke)")
        cycle = 180.0 * self.strokes
        deg = math.degrees(self.lobe_centre)
        if not 0.0 <= deg < cycle / 2:
            raise InputError(
                f"lobe_centre = {deg:.6g} deg must lie from 0 to {cycle / 2:g} deg (crank degrees "
                f"{'after' if self.valve == 'intake' else 'before'} the gas-exchange TDC; cam cards give about 100-120)"
            )

    @classmethod
    def in_file(cls, path) -> Timing | None:
        """The ``[timing]`` table of a TOML file, or None when it has none.

        Parameters
        ----------
        path : str or path-like
            A definition file (usually the cam's).
        """
        doc = load_toml(path)
        if "timing" not in doc:
            return None
        return cls.from_dict(doc["timing"], source=str(path), base_dir=Path(path).parent)


@dataclass(frozen=True)
class CrankAxis:
    """Crank angle [deg] of a cam angle: ``offset_deg + per_cam * cam_deg``.

    ``referenced``: counted from the gas-exchange TDC and wrapped into one cycle
    (``[-cycle/2, cycle/2)``); otherwise counted from cam angle 0 and not wrapped.
    """

    per_cam: float  # crank degrees per cam degree [-]
    offset_deg: float  # crank angle at cam angle 0 [deg]
    referenced: bool
    cycle_deg: float  # crank degrees of the engine's cycle [deg]
    kind: str = "crank"  # "cam": the identity axis of outputs without crank angles

    @classmethod
    def cam(cls) -> CrankAxis:
        """The identity axis: cam angles as they are (outputs without an engine)."""
        return cls(per_cam=1.0, offset_deg=0.0, referenced=False, cycle_deg=360.0, kind="cam")

    def crank_deg(self, cam_deg):
        """Crank angle(s) [deg] of cam angle(s) [deg].

        Parameters
        ----------
        cam_deg : float or array_like
            Cam angle [deg].
        """
        phi = self.offset_deg + self.per_cam * np.asarray(cam_deg, dtype=float)
        if self.referenced:
            half = 0.5 * self.cycle_deg
            phi = np.mod(phi + half, self.cycle_deg) - half
        return float(phi) if np.ndim(phi) == 0 else phi

    @property
    def label(self) -> str:
        """Axis label of plots."""
        if self.kind == "cam":
            return "cam angle [deg]"
        return "crank angle [deg ATDC]" if self.referenced else "crank angle [deg]"

    @property
    def unit(self) -> str:
        """The angle's unit in text: ``"deg ATDC"``, ``"crank deg"`` or ``"cam deg"``."""
        if self.kind == "cam":
            return "cam deg"
        return "deg ATDC" if self.referenced else "crank deg"

    @property
    def limits(self) -> tuple[float, float]:
        """The axis range of one camshaft revolution [deg]."""
        span = 360.0 * self.per_cam
        return (-0.5 * span, 0.5 * span) if self.referenced else (0.0, span)

    def spans(self, start_cam_deg: float, end_cam_deg: float) -> list[tuple[float, float]]:
        """An interval of cam angles [deg] (it may wrap through 0) as intervals of this axis.

        Parameters
        ----------
        start_cam_deg, end_cam_deg : float
            Start and end cam angle [deg].
        """
        lo, hi = self.limits
        a, b = self.crank_deg(start_cam_deg), self.crank_deg(end_cam_deg)
        return [(a, b)] if a <= b else [(a, hi), (lo, b)]

    def plot_order(self, cam_deg) -> np.ndarray:
        """Indices that sort the crank angles of ``cam_deg`` (a line drawn without the wrap jump).

        Parameters
        ----------
        cam_deg : array_like
            Cam angles [deg].
        """
        return np.argsort(self.crank_deg(cam_deg), kind="stable")

    def words(self, cam_deg: float, from_tdc: bool = False) -> str:
        """A cam angle as timing words: ``"12.0 deg BTDC"`` (or ``"24.0 crank deg"`` unreferenced).

        Parameters
        ----------
        cam_deg : float
            Cam angle [deg].
        from_tdc : bool
            Count from the gas-exchange TDC (a lobe centreline: "110.0 deg ATDC") instead of the
            nearest dead centre.
        """
        phi = self.crank_deg(cam_deg)
        return crank_words(phi, from_tdc) if self.referenced else f"{phi:.1f} crank deg"


def crank_words(phi: float, from_tdc: bool = False) -> str:
    """A crank angle [deg] from the gas-exchange TDC in the words of valve timing.

    Measured from the nearest dead centre: TDC at 0 and +-360 deg, BDC at +-180 deg.

    Parameters
    ----------
    phi : float
        Crank angle from the gas-exchange TDC [deg], in [-360, 360).
    from_tdc : bool
        Count from the gas-exchange TDC whatever the nearest dead centre (a centreline).

    Examples
    --------
    >>> crank_words(-12.0), crank_words(228.0), crank_words(-240.0), crank_words(8.0)
    ('12.0 deg BTDC', '48.0 deg ABDC', '60.0 deg BBDC', '8.0 deg ATDC')
    >>> crank_words(110.0, from_tdc=True), crank_words(-105.0, from_tdc=True)
    ('110.0 deg ATDC', '105.0 deg BTDC')
    """
    if from_tdc:
        return f"{abs(phi):.1f} deg {'A' if phi >= 0 else 'B'}TDC"
    centres = np.array([-360.0, -180.0, 0.0, 180.0, 360.0])
    c = float(centres[np.argmin(np.abs(phi - centres))])
    name = "TDC" if c in (-360.0, 0.0, 360.0) else "BDC"
    d = phi - c
    return f"{abs(d):.1f} deg {'A' if d >= 0 else 'B'}{name}"


def crank_axis(cam, timing: Timing | None = None) -> CrankAxis:
    """The crank axis of a cam: referenced to TDC by a :class:`Timing`, else from cam angle 0.

    Parameters
    ----------
    cam : Cam
        The cam (its maximum lift is the lobe centre of the timing).
    timing : Timing, optional
        The ``[timing]`` table; without it a four-stroke from the start of the event.
    """
    if timing is None:
        return CrankAxis(per_cam=2.0, offset_deg=0.0, referenced=False, cycle_deg=720.0)
    k = timing.strokes / 2.0
    centre = math.degrees(timing.lobe_centre) * (1.0 if timing.valve == "intake" else -1.0)
    offset = centre - k * math.degrees(cam.peak_angle)
    return CrankAxis(per_cam=k, offset_deg=offset, referenced=True, cycle_deg=180.0 * timing.strokes)


class CrankAngles:
    """Mixin of the valve results that show crank angles beside cam angles: their
    ``crank_axis`` field (a :class:`CrankAxis`, or None for cam angles only)."""

    crank_axis = None

    def set_crank_axis(self, axis) -> None:
        """Show crank angles in the outputs (``crank_axis``; the summary is rebuilt).

        Parameters
        ----------
        axis : CrankAxis or None
            :func:`crank_axis` of the cam (None: cam angles only).
        """
        self.crank_axis = axis
        self.__dict__.pop("_summary_cache", None)
