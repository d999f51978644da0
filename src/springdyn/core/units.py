"""Quantities with units at the edges of springdyn (config files, CLI options).

Inside, every number is an SI float.  At the edges, values may be strings with units
(``"22 mm"``, ``"78.5 GPa"``, ``"3000 rpm"``) parsed with pint, or bare numbers, which
mean SI unless the caller names another default unit (a CLI option called ``--cam-rpm``
takes a bare number in rpm).
"""

from __future__ import annotations

import math
import re
import sys
from functools import cache
from numbers import Real

import numpy as np

from .errors import InputError, fmt_value

__all__ = [
    "ureg",  # noqa: F822 (made on first use by the module's __getattr__)
    "get_registry",
    "to_si",
    "format_quantity",
    "format_mm",
    "SI_UNITS",
    "rpm_to_omega",
    "omega_to_rpm",
    "rpm_to_hz",
]

#: Smallest magnitude springdyn accepts as a nonzero number: subnormal floats (5e-324)
#: are never a physical input and break the formulas.
TINY = sys.float_info.min


@cache
def get_registry():
    """springdyn's pint registry, built on first use (pint is imported only then).

    Its parsed definitions are cached on disk by pint (``cache_folder=":auto:"``), which
    makes a command's start about twice as fast; where no cache folder can be written the
    registry is built without one.
    """
    import pint

    try:
        reg = pint.UnitRegistry(cache_folder=":auto:")
    except Exception:  # pragma: no cover - an unwritable cache folder
        reg = pint.UnitRegistry()
    reg.define("cam_degree = degree")
    return reg


def __getattr__(name):
    if name == "ureg":
        return get_registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _number_or_array(value):
    """A real number as it is, anything else as a float array."""
    return value if isinstance(value, Real) else np.asarray(value, dtype=float)


def rpm_to_omega(rpm):
    """Angular speed [rad/s] from a speed [rev/min].

    Parameters
    ----------
    rpm : float or array_like
        Speed [rev/min].
    """
    rpm = _number_or_array(rpm)
    # (in this order: the valve and rig speeds were always computed so, and an adaptive
    # integration at another speed by one ulp takes other steps)
    return rpm * 2.0 * math.pi / 60.0


def omega_to_rpm(omega):
    """Speed [rev/min] from an angular speed [rad/s].

    Parameters
    ----------
    omega : float or array_like
        Angular speed [rad/s].
    """
    return _number_or_array(omega) * (60.0 / (2.0 * math.pi))


def rpm_to_hz(rpm):
    """Revolutions per second [Hz] from a speed [rev/min]: the frequency of a once-per-turn
    event (a cam's first order).

    Parameters
    ----------
    rpm : float or array_like
        Speed [rev/min].
    """
    return _number_or_array(rpm) / 60.0


def format_mm(value: float) -> str:
    """A length [m] for people, in millimetres (``"22 mm"``).

    Parameters
    ----------
    value : float
        Length [m].
    """
    return format_quantity(value, "m", "mm")


#: The SI unit springdyn uses inside for each dimension it names.
SI_UNITS = {
    "m": "m",
    "kg": "kg",
    "N": "N",
    "Pa": "Pa",
    "N/m": "N/m",
    "N*s/m": "N*s/m",
    "N*m": "N*m",
    "N*m/rad": "N*m/rad",
    "kg/m^3": "kg/m^3",
    "rad": "rad",
    "rad/s": "rad/s",
    "Hz": "Hz",
    "s": "s",
    "m^2/s": "m^2/s",
    "Pa*s": "Pa*s",
    "": "",
}


@cache
def _unit(unit: str):
    ureg = get_registry()
    return ureg.Unit(unit) if unit else ureg.dimensionless


def to_si(value, unit: str, field: str, *, bare_unit: str | None = None) -> float:
    """Convert a value with or without units to a float in ``unit``.

    Parameters
    ----------
    value : str, int or float
        ``"22 mm"``, ``"3000 rpm"``, ``0.022`` ...  A bare number (or a string holding
        only a number) is taken in ``bare_unit`` (default: ``unit`` itself, i.e. SI).
    unit : str
        Unit of the returned float, e.g. ``"m"``; its dimension is the one required.
    field : str
        Name of the field or option, used in error messages.
    bare_unit : str, optional
        Unit assumed for bare numbers.

    Returns
    -------
    float
        The magnitude in ``unit``.

    Raises
    ------
    InputError
        Unparseable text, a unit of the wrong dimension, or a non-finite number.

    Examples
    --------
    >>> to_si("22 mm", "m", "mean_diameter")
    0.022
    >>> to_si("3000 rpm", "rad/s", "speed") == 3000 * 2 * math.pi / 60
    True
    >>> to_si(1500, "rad/s", "cam_rpm", bare_unit="rpm") == 50 * math.pi
    True
    """
    if isinstance(value, bool) or not isinstance(value, (Real, str)):
        raise InputError(f"{field} = {value!r} must be a number or a quantity with units such as '{_example(unit)}'")
    ureg = get_registry()
    target = _unit(unit)
    bare = _unit(bare_unit if bare_unit is not None else unit)
    if isinstance(value, Real):
        try:
            number = float(value)
        except OverflowError:
            raise InputError(f"{field} = {str(value)[:20]}... is too large to be a number springdyn can use") from None
        q = ureg.Quantity(number, bare)
    else:
        text = value.strip()
        if ":" in text:
            raise InputError(
                f"{field} = {value!r}: a range START:STOP:STEP is not taken here; give one value "
                f"such as '{_example(unit)}'"
            )
        if "," in text:
            raise InputError(
                f"{field} = {value!r}: a comma is neither a decimal point nor a thousands separator here; "
                f"give one value such as '{_example(unit)}' (lists a,b,c are only taken where an option says so)"
            )
        if len(text) > 200:
            raise InputError(f"{field} = {text[:40]!r}... is too long to be a quantity")
        text = re.sub(r"%", " percent", text)
        offset = re.fullmatch(r"([-+]?[\d.]+(?:[eE][-+]?\d+)?)\s*(degC|degF|°C|°F|celsius|fahrenheit)", text)
        try:
            # a temperature on an offset scale ("90 degC"): pint reads "90 * degC" as a product
            q = ureg.Quantity(float(offset[1]), offset[2].replace("°", "deg")) if offset else ureg.Quantity(text)
        except Exception as exc:  # pint raises several types for bad text: said in the user's words
            unknown = getattr(exc, "unit_names", None) or getattr(exc, "args", [None])[:1]
            why = (
                f": {unknown[0]!r} is not a unit springdyn knows"
                if type(exc).__name__ == "UndefinedUnitError" and unknown and isinstance(unknown[0], str)
                else ""
            )
            raise InputError(
                f"{field} = {value!r} is not a quantity springdyn can read "
                f"(expected a number and a unit, like '{_example(unit)}'){why}"
            ) from None
        if not isinstance(q, ureg.Quantity):  # a plain number
            q = ureg.Quantity(float(q), bare)
        elif str(q.units) == "dimensionless":  # a number in a string: the bare unit
            q = ureg.Quantity(float(q.magnitude), bare)
    if _is_angular_speed(target) and not _has_angle_unit(q):
        # "50 Hz" or "3000 1/min" for a rotation speed means revolutions per unit time
        # (pint alone would read 50 Hz as 50 rad/s, since rad is dimensionless).
        q = q * ureg.Quantity(1.0, "revolution")
    try:
        mag = q.to(target).magnitude
    except Exception as exc:
        if type(exc).__name__ != "DimensionalityError":
            raise InputError(
                f"{field} = {value!r} cannot be converted to {unit or 'a number'} (for example '{_example(unit)}')"
            ) from None
        want = "dimensionless" if not unit else f"a quantity convertible to {unit}"
        raise InputError(
            f"{field} = {value!r} has the wrong dimension: expected {want} (for example '{_example(unit)}')"
        ) from None
    try:
        mag = float(mag)
    except (OverflowError, TypeError, ValueError):
        raise InputError(f"{field} = {value!r} is not a number springdyn can use") from None
    if not math.isfinite(mag):
        raise InputError(f"{field} = {value!r} is not a finite number")
    if mag != 0.0 and abs(mag) < TINY:
        raise InputError(f"{field} = {value!r} is too small to be a physical value (a subnormal number)")
    return mag


_ANGLE_NAMES = (
    "radian",
    "degree",
    "revolution",
    "turn",
    "cycle",
    "revolutions_per_minute",
    "arcminute",
    "arcsecond",
    "cam_degree",
    "gradian",
)


def _is_angular_speed(unit) -> bool:
    ureg = get_registry()
    q = ureg.Quantity(1, unit)
    return q.dimensionality == ureg.Quantity(1, "1/s").dimensionality and _has_angle_unit(q)


def _has_angle_unit(q) -> bool:
    return any(name in str(q.units) for name in _ANGLE_NAMES)


def format_quantity(value: float, unit: str, display: str | None = None, digits: int = 5) -> str:
    """Format an SI value for people, optionally in a display unit.

    >>> format_quantity(0.022, "m", "mm")
    '22 mm'
    """
    if display and display != unit:
        scale, offset = _conversion(unit, display)
        value = value * scale + offset
        unit = display
    return fmt_value(float(f"{value:.{digits}g}"), unit)


@cache
def _conversion(unit: str, display: str) -> tuple[float, float]:
    """Scale and offset from ``unit`` to ``display`` (every pint conversion between units of
    one dimension is affine), found once: a pint conversion costs a third of a millisecond,
    which a run's set-up messages paid a dozen times."""
    ureg = get_registry()
    zero = ureg.Quantity(0.0, _unit(unit)).to(_unit(display)).magnitude
    return ureg.Quantity(1.0, _unit(unit)).to(_unit(display)).magnitude - zero, zero


_EXAMPLES = {
    "m": "22 mm",
    "kg": "0.5 kg",
    "N": "250 N",
    "Pa": "206 GPa",
    "N/m": "25 N/mm",
    "kg/m^3": "7850 kg/m^3",
    "rad": "120 deg",
    "rad/s": "3000 rpm",
    "Hz": "20 kHz",
    "s": "0.1 s",
    "N*m": "0.02 N*m",
    "N*m/rad": "2.5 N*m/rad",
}


def _example(unit: str) -> str:
    return _EXAMPLES.get(unit, f"1 {unit}" if unit else "0.5")
