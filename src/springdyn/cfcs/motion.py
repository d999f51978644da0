"""Prescribed slider motions x(t) for the inverse dynamics.

Default: the sinusoid ``x(t) = offset + amplitude (1 - cos(w t)) / 2`` (Fig. 4 of the
CFCS paper), which starts at rest at ``offset`` and reaches ``offset + amplitude`` at
half period.  The paper's "amplitude equal to 40 % mechanism deflection" is read as
``amplitude = 0.4 (r2 + r3)`` (72 mm for Table 1); the motion starts from a preload
offset inside the constant-force band, by default ``2.5 %`` of ``r2 + r3`` (4.5 mm for
Table 1, crank angle 13.5 deg), not from the toggle (corrections CFCS-4 and CFCS-5 of
docs/references.md: both are explicit parameters here).  Any periodic x(t) can be read from a
CSV with columns ``time_s`` and ``deflection_m`` (one period, first and last
deflection equal); it is interpolated by a periodic cubic spline.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
from scipy.interpolate import CubicSpline

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError
from ..core.io import read_csv_columns
from ..core.units import format_quantity, to_si

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    field : str
        Name of the argument, for messages.
    extended_length : float
        r2 + r3, the slider position at the toggle [m].
    """
)


__all__ = ["sinusoid", "SinusoidMotion", "TabulatedMotion", "amplitude_to_si", "offset_to_si", "check_stroke"]


def sinusoid(t, offset, amplitude, omega):
    """``x = offset + amplitude (1 - cos w t)/2`` and its first two derivatives.

    Parameters
    ----------
    t : array
        Time [s].
    offset, amplitude : float
        Deflection at t = 0 [m] and peak-to-peak stroke [m].
    omega : float
        Circular frequency [rad/s].

    Returns
    -------
    x, xdot, xddot : arrays
        [m], [m/s], [m/s^2].
    """
    t = np.asarray(t, dtype=float)
    wt = omega * t
    return (
        offset + 0.5 * amplitude * (1.0 - np.cos(wt)),
        0.5 * amplitude * omega * np.sin(wt),
        0.5 * amplitude * omega * omega * np.cos(wt),
    )


#: Largest input frequency springdyn accepts [rad/s] (about 16 kHz).
MAX_OMEGA = 1e5


@_DOCS.fill
def amplitude_to_si(value, extended_length: float, field: str = "amplitude") -> float:
    """An amplitude [m]: a length (``"72 mm"``, or a bare number in metres, SI like every
    bare number), or a percentage of ``r2 + r3`` (``"40 %"``).

    Earlier versions read a bare number up to 1 as a fraction of ``r2 + r3``.  Where only
    that reading fits the mechanism (the number in metres would be beyond the kinematic
    range, the fraction within it) it is still taken as a fraction, with a
    :class:`DeprecationWarning`; write ``"40 %"`` instead.

    Parameters
    ----------
    value : str or float
        The amplitude: a length such as '72 mm' or a bare number [m], or a percentage
        of r2 + r3 such as '40 %' [-].
    {extended_length field}
    """
    import warnings

    frac = _percentage(value, field)
    if frac is not None:
        if not 0 < frac <= 1:
            raise InputError(f"{field} = {value!r}: a percentage of r2 + r3 must lie in (0 %, 100 %]")
        return frac * extended_length
    text = value.strip() if isinstance(value, str) else None
    length = to_si(value, "m", field)
    if not length > 0:
        raise InputError(
            f"{field} = {value!r} must be a positive length, e.g. '72 mm', or a percentage of r2 + r3, e.g. '40 %'"
        )
    bare = not isinstance(value, str) or _is_number(text)
    if bare and extended_length <= length <= 1.0:
        warnings.warn(
            f"{field} = {value!r} read as a fraction of r2 + r3 ({100 * length:g} %), as earlier versions "
            f"did: a bare number is metres ({length:g} m is beyond this mechanism); write "
            f"'{100 * length:g} %' instead",
            DeprecationWarning,
            stacklevel=3,
        )
        return length * extended_length
    return length


@_DOCS.fill
def offset_to_si(value, extended_length: float, field: str = "offset") -> float:
    """An offset (preload deflection) [m]: a length (``"5 mm"``, or a bare number in metres) or a
    percentage of ``r2 + r3`` (``"2.5 %"``).

    Parameters
    ----------
    value : str or float
        The offset: a length such as '5 mm' or a bare number [m], or a percentage of r2 + r3
        such as '2.5 %' [-].
    {extended_length field}
    """
    frac = _percentage(value, field)
    if frac is not None:
        if not 0 <= frac < 1:
            raise InputError(f"{field} = {value!r}: a percentage of r2 + r3 must lie in [0 %, 100 %)")
        return frac * extended_length
    return to_si(value, "m", field, bare_unit="m")


def _percentage(value, field: str):
    """The fraction [-] that a percentage such as ``"40 %"`` or ``"40 percent"`` gives; None
    when ``value`` is not one (a length, or a bare number)."""
    text = value.strip() if isinstance(value, str) else None
    if text is not None and (text.endswith("%") or text.endswith("percent")):
        return to_si(text, "", field)
    return None


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def check_stroke(
    lowest: float, highest: float, max_deflection: float, what: str, remedy: str = "reduce the amplitude or the offset"
) -> None:
    """Raise InputError if the deflections leave ``[0, max_deflection]``.

    Parameters
    ----------
    lowest : float
        Smallest deflection of the motion [m].
    highest : float
        Largest deflection of the motion [m].
    max_deflection : float
        Kinematic limit deflection [m].
    what : str
        What the deflections belong to, for messages.
    remedy : str
        What to change, in the words of the caller's options.
    """
    if lowest < -1e-12:
        raise InputError(
            f"{what} reaches a deflection of {format_quantity(lowest, 'm', 'mm')}: it crosses the toggle "
            "(deflection 0, links in line); deflections must stay >= 0"
        )
    if highest > max_deflection * (1 + 1e-12):
        raise InputError(
            f"{what} reaches a deflection of {format_quantity(highest, 'm', 'mm')}, beyond the kinematic limit "
            f"{format_quantity(max_deflection, 'm', 'mm')} (theta2 = 90 deg): {remedy}"
        )


@dataclasses.dataclass(frozen=True)
class SinusoidMotion:
    """``x(t) = offset + amplitude (1 - cos w t)/2`` [m] (Fig. 4 of the CFCS paper)."""

    omega: float
    amplitude: float
    offset: float = 0.0

    def __post_init__(self):
        if not (np.isfinite(self.omega) and self.omega > 0):
            raise InputError(f"omega = {self.omega!r} rad/s must be positive")
        if self.omega > MAX_OMEGA:
            raise InputError(
                f"omega = {self.omega:g} rad/s is beyond {MAX_OMEGA:g} rad/s: far above any motion of a "
                "constant-force mechanism (its inertia forces would overflow)"
            )
        if not (np.isfinite(self.amplitude) and self.amplitude > 0):
            raise InputError(f"amplitude = {format_quantity(self.amplitude, 'm', 'mm')} must be positive")

    @property
    def period(self) -> float:
        return 2.0 * np.pi / self.omega

    @property
    def bounds(self) -> tuple[float, float]:
        return self.offset, self.offset + self.amplitude

    def __call__(self, t):
        return sinusoid(t, self.offset, self.amplitude, self.omega)

    def describe(self) -> str:
        return (
            f"x(t) = {format_quantity(self.offset, 'm', 'mm')} + {format_quantity(self.amplitude, 'm', 'mm')}"
            f" (1 - cos({self.omega:.6g} t))/2"
        )


@dataclasses.dataclass(frozen=True)
class TabulatedMotion:
    """A periodic x(t) from samples, interpolated by a periodic cubic spline.

    Parameters
    ----------
    time, deflection : arrays
        One period of samples [s], [m]; the first and last deflections must match.
    """

    time: np.ndarray
    deflection: np.ndarray
    source: str = "table"

    def __post_init__(self):
        t = np.asarray(self.time, dtype=float)
        x = np.asarray(self.deflection, dtype=float)
        if t.size < 4:
            raise InputError(f"{self.source}: a periodic motion needs at least 4 samples, got {t.size}")
        if np.any(np.diff(t) <= 0):
            raise InputError(f"{self.source}: time_s must increase strictly")
        scale = max(np.ptp(x), 1e-12)
        if abs(x[-1] - x[0]) > 1e-6 * scale:
            raise InputError(
                f"{self.source}: the motion is not periodic: the last deflection {x[-1]:.6g} m differs from "
                f"the first {x[0]:.6g} m (give exactly one period)"
            )
        x = x.copy()
        x[-1] = x[0]
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "deflection", x)
        object.__setattr__(self, "_spline", CubicSpline(t - t[0], x, bc_type="periodic"))

    @classmethod
    def from_csv(cls, path: str | Path, omega: float | None = None) -> TabulatedMotion:
        """Read ``time_s, deflection_m`` from a CSV; rescale time to period ``2 pi/omega`` if given.

        Parameters
        ----------
        path : str or Path
            The CSV file [-].
        omega : float, optional
            Angular frequency to rescale the period to [rad/s].
        """
        cols = read_csv_columns(path)
        for name in ("time_s", "deflection_m"):
            if name not in cols:
                raise InputError(f"{path}: no column {name!r} (columns found: {', '.join(cols)})")
        t = cols["time_s"]
        if omega is not None:
            if not omega > 0:
                raise InputError(f"omega = {omega!r} rad/s must be positive")
            t = (t - t[0]) * (2.0 * np.pi / omega) / max(t[-1] - t[0], 1e-300)
        return cls(t, cols["deflection_m"], source=str(path))

    @property
    def period(self) -> float:
        return float(self.time[-1] - self.time[0])

    @property
    def omega(self) -> float:
        return 2.0 * np.pi / self.period

    @property
    def bounds(self) -> tuple[float, float]:
        fine = self._spline(np.linspace(0.0, self.period, 20 * self.time.size))
        return float(fine.min()), float(fine.max())

    def __call__(self, t):
        tau = np.mod(np.asarray(t, dtype=float), self.period)
        return self._spline(tau), self._spline(tau, 1), self._spline(tau, 2)

    def describe(self) -> str:
        return f"periodic spline through {self.time.size} samples of {self.source} (period {self.period:.6g} s)"
