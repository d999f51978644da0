"""Quantities with units at the edges of springdyn (config files, CLI options).

Inside, every number is an SI float.  At the edges, values may be strings with units
(``"22 mm"``, ``"78.5 GPa"``, ``"3000 rpm"``) parsed with pint, or bare numbers, which
mean SI unless the caller names another default unit (a CLI option called ``--cam-rpm``
takes a bare number in rpm).
"""

from __future__ import annotations

import math
from functools import lru_cache
from numbers import Real

import pint

from .errors import InputError, fmt_value

__all__ = ["ureg", "to_si", "format_quantity", "SI_UNITS"]

ureg = pint.UnitRegistry()
ureg.define("cam_degree = degree")

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


@lru_cache(maxsize=None)
def _unit(unit: str):
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
    target = _unit(unit)
    if isinstance(value, bool) or not isinstance(value, (Real, str)):
        raise InputError(
            f"{field} = {value!r} must be a number or a quantity with units such as "
            f"'{_example(unit)}'"
        )
    if isinstance(value, Real):
        q = ureg.Quantity(float(value), _unit(bare_unit if bare_unit is not None else unit))
    else:
        text = value.strip()
        try:
            q = ureg.Quantity(text)
        except Exception as exc:  # pint raises several types for bad text
            raise InputError(
                f"{field} = {value!r} is not a quantity springdyn can read "
                f"(expected something like '{_example(unit)}'): {exc}"
            ) from None
        if not isinstance(q, pint.Quantity) or q.unitless:  # a plain number in a string
            q = ureg.Quantity(float(getattr(q, "magnitude", q)), _unit(bare_unit if bare_unit is not None else unit))
    if _is_angular_speed(target) and not _has_angle_unit(q):
        # "50 Hz" or "3000 1/min" for a rotation speed means revolutions per unit time
        # (pint alone would read 50 Hz as 50 rad/s, since rad is dimensionless).
        q = q * ureg.Quantity(2.0 * math.pi, "rad")
    try:
        mag = q.to(target).magnitude
    except pint.DimensionalityError:
        want = "dimensionless" if not unit else f"a quantity convertible to {unit}"
        raise InputError(
            f"{field} = {value!r} has the wrong dimension: expected {want} "
            f"(for example '{_example(unit)}')"
        ) from None
    mag = float(mag)
    if not math.isfinite(mag):
        raise InputError(f"{field} = {value!r} is not a finite number")
    return mag


_ANGLE_NAMES = ("radian", "degree", "revolution", "turn", "cycle", "revolutions_per_minute", "arcminute", "arcsecond",
                "cam_degree", "gradian")


def _is_angular_speed(unit) -> bool:
    return "radian" in str(unit) and ureg.Quantity(1, unit).dimensionality == ureg.Quantity(1, "1/s").dimensionality


def _has_angle_unit(q) -> bool:
    return any(name in str(q.units) for name in _ANGLE_NAMES)


def format_quantity(value: float, unit: str, display: str | None = None, digits: int = 5) -> str:
    """Format an SI value for people, optionally in a display unit.

    >>> format_quantity(0.022, "m", "mm")
    '22 mm'
    """
    if display and display != unit:
        value = ureg.Quantity(value, _unit(unit)).to(_unit(display)).magnitude
        unit = display
    return fmt_value(float(f"{value:.{digits}g}"), unit)


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
