"""The engine oil of a valve train: the ``[oil]`` table and the oil's laws.

One oil feeds the hydraulic lash adjuster and wets the cam, the stem guide and the pivot, so one
table holds it: its temperature, its datasheet (kinematic viscosities at 40 and 100 degC,
density at 15 degC), the pressure-viscosity coefficient of its films, and the bulk modulus and
free air of its columns.  The adjuster (:mod:`.hla`) and the friction laws (:mod:`.friction`)
both take their oil from here.  The keys may still be given under ``[hla]`` and ``[friction]``
by their older names (:data:`OLDER_KEYS`): they mean the same oil, and the same key given twice
with two values is an error (:func:`oil_of`).

One place per equation:

- :func:`kinematic_viscosity` -- the viscosity at a temperature from the datasheet's values at
  40 and 100 degC (the Walther equation, [ASTM D341]);
- :func:`oil_density` -- the density at a temperature (volumetric expansion);
- :func:`effective_bulk_modulus` -- aerated oil: the oil's bulk modulus in series with free air
  bubbles compressed polytropically ([Merritt] eq. 2-19; [Gholizadeh]); its home is
  :mod:`springdyn.valve.engine.hydraulics`, whose compiled twin the adjuster's chamber uses.

Sources: docs/references.md.
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, param
from ...core.units import to_si
from ..engine.hydraulics import effective_bulk_modulus

__all__ = [
    "Oil",
    "kinematic_viscosity",
    "oil_density",
    "effective_bulk_modulus",
    "OLDER_KEYS",
    "oil_of",
    "WALTHER_KEYS",
    "HoldsOil",
]

#: The datasheet keys of the Walther viscosity; with ``viscosity`` given they would go unused (the
#: density is the adjuster's check valve's too).
WALTHER_KEYS = ("viscosity_40", "viscosity_100")

#: The oil's keys as the ``[hla]`` and ``[friction]`` tables name them (older files), by table:
#: ``older name -> [oil] key``.  They mean the same oil.
OLDER_KEYS = {
    "hla": {
        "oil_temperature": "temperature",
        "oil_viscosity_40": "viscosity_40",
        "oil_viscosity_100": "viscosity_100",
        "oil_density_15": "density_15",
        "oil_bulk_modulus": "bulk_modulus",
        "air_fraction": "air_fraction",
        "polytropic_index": "polytropic_index",
    },
    "friction": {
        "oil_viscosity": "viscosity",
        "oil_temperature": "temperature",
        "oil_viscosity_40": "viscosity_40",
        "oil_viscosity_100": "viscosity_100",
        "oil_density_15": "density_15",
        "pressure_viscosity": "pressure_viscosity",
    },
}

#: Where each default comes from (stated in the docs and the generated TOML reference).
DEFAULT_SOURCES = {
    "temperature": (
        "90 degC: the oil of a warm engine as the gallery feeds it to the adjuster and the cam "
        "(90-110 degC at the cam, [Taylor])"
    ),
    "viscosity": (
        "none: from the Walther equation ([ASTM D341]) at the temperature, 10.6 mPa s for the defaults "
        "(a 5W-30: 60 and 10.5 mm^2/s at 40 and 100 degC, 850 kg/m^3 at 15 degC)"
    ),
    "viscosity_40": "60 mm^2/s: a 5W-30 engine oil's datasheet",
    "viscosity_100": "10.5 mm^2/s: a 5W-30 engine oil's datasheet",
    "density_15": "850 kg/m^3: a 5W-30 engine oil's datasheet",
    "pressure_viscosity": "2e-8 1/Pa: mineral engine oils about 1-3e-8 1/Pa ([Hamrock])",
    "bulk_modulus": "1.5 GPa: air-free mineral oil ([Merritt])",
    "air_fraction": "2 %: free air entrained in a running engine's oil ([Gholizadeh])",
    "polytropic_index": "1: the bubbles compressed isothermally, slowly against the oil's heat capacity ([Merritt])",
}


def kinematic_viscosity(temperature, nu_40, nu_100):
    """Kinematic viscosity [m^2/s] of an oil at a temperature, from its datasheet values.

    The Walther equation of ASTM D341: ``log10(log10(nu + 0.7)) = A - B log10(T)`` with
    ``nu`` in mm^2/s and ``T`` in K, through the values at 40 and 100 degC.

    Parameters
    ----------
    temperature : float or ndarray
        Oil temperature [K].
    nu_40, nu_100 : float
        Kinematic viscosity at 40 degC and at 100 degC [m^2/s].

    Examples
    --------
    >>> round(float(kinematic_viscosity(373.15, 60e-6, 10.5e-6)) * 1e6, 9)
    10.5
    """
    t1, t2 = 313.15, 373.15
    w1 = math.log10(math.log10(nu_40 * 1e6 + 0.7))
    w2 = math.log10(math.log10(nu_100 * 1e6 + 0.7))
    b = (w1 - w2) / (math.log10(t2) - math.log10(t1))
    a = w1 + b * math.log10(t1)
    w = a - b * np.log10(temperature)
    return (10.0 ** (10.0**w) - 0.7) * 1e-6


def oil_density(temperature, density_15, expansion=6.5e-4):
    """Oil density [kg/m^3] at a temperature: ``rho_15 / (1 + alpha (T - 288.15 K))``.

    Parameters
    ----------
    temperature : float
        Oil temperature [K].
    density_15 : float
        Density at 15 degC [kg/m^3].
    expansion : float
        Volumetric thermal expansion coefficient [1/K] (6.5e-4 for mineral engine oils).
    """
    return density_15 / (1.0 + expansion * (temperature - 288.15))


@dataclass(frozen=True)
class Oil(Parameters):
    """The ``[oil]`` table: the one engine oil of a valve train (the adjuster's and the friction's).

    Its viscosity is either given at its temperature (``viscosity``) or taken from its datasheet by
    the Walther equation (``viscosity_40``, ``viscosity_100``, and ``density_15`` for the dynamic
    viscosity), not both.  Defaults
    and their sources: :data:`DEFAULT_SOURCES`.

    Examples
    --------
    >>> round(Oil().dynamic_viscosity() * 1e3, 2)
    10.6
    >>> Oil.from_dict({"temperature": "100 degC"}).temperature
    373.15
    """

    temperature: float = param("K", "oil temperature (default 90 degC)", display="degC", positive=True, default=363.15)
    viscosity: float = param(
        "Pa*s",
        "dynamic viscosity at the temperature (default: from the datasheet by the Walther equation)",
        display="mPa*s",
        positive=True,
        default=None,
    )
    viscosity_40: float = param(
        "m^2/s", "kinematic viscosity at 40 degC (datasheet)", display="mm^2/s", positive=True, default=60e-6
    )
    viscosity_100: float = param(
        "m^2/s", "kinematic viscosity at 100 degC (datasheet)", display="mm^2/s", positive=True, default=10.5e-6
    )
    density_15: float = param("kg/m^3", "density at 15 degC (datasheet)", positive=True, default=850.0)
    pressure_viscosity: float = param(
        "1/Pa",
        "pressure-viscosity coefficient alpha of the oil's films (Barus)",
        display="1/GPa",
        default=2e-8,
        minimum=0.0,
        maximum=1e-7,
    )
    bulk_modulus: float = param("Pa", "bulk modulus of the air-free oil", display="GPa", positive=True, default=1.5e9)
    air_fraction: float = param(
        "", "free-air volume fraction of the oil at atmospheric pressure", nonnegative=True, default=0.02
    )
    polytropic_index: float = param(
        "", "polytropic index of the air bubbles (1 isothermal)", positive=True, default=1.0
    )

    table = "oil"

    def _validate(self) -> None:
        if not 233.15 <= self.temperature <= 443.15:
            raise InputError(f"temperature = {self.temperature - 273.15:.6g} degC must lie from -40 to 170 degC")
        if not self.viscosity_100 < self.viscosity_40:
            raise InputError(
                f"viscosity_100 = {self.viscosity_100 * 1e6:g} mm^2/s must be below viscosity_40 = "
                f"{self.viscosity_40 * 1e6:g} mm^2/s (oil thins as it warms)"
            )
        if not self.air_fraction < 0.5:
            raise InputError(f"air_fraction = {self.air_fraction:g} must be below 0.5: that is foam, not oil")
        if not 1.0 <= self.polytropic_index <= 1.4:
            raise InputError(
                f"polytropic_index = {self.polytropic_index:g} must lie from 1 (isothermal) to 1.4 (adiabatic)"
            )

    @classmethod
    def _prepare(cls, mapping: dict, **context) -> dict:
        source = context.get("source")
        _viscosity_once({k: f"[oil] {k}" for k in mapping}, f"{source}: " if source else "")
        return super()._prepare(mapping, **context)

    def density(self, temperature: float | None = None) -> float:
        """Density [kg/m^3] at a temperature (default: the oil's) (:func:`oil_density`).

        Parameters
        ----------
        temperature : float, optional
            Oil temperature [K].
        """
        return oil_density(self.temperature if temperature is None else temperature, self.density_15)

    def dynamic_viscosity(self, temperature: float | None = None) -> float:
        """Dynamic viscosity [Pa s] at a temperature (default: the oil's): ``viscosity`` where it
        is given, else the Walther viscosity (:func:`kinematic_viscosity`) times the density.

        Parameters
        ----------
        temperature : float, optional
            Oil temperature [K]; another than the oil's needs the datasheet, not ``viscosity``.
        """
        t = self.temperature if temperature is None else temperature
        if self.viscosity is not None:
            if t != self.temperature:
                raise InputError(
                    f"the oil's viscosity is given at {self.temperature - 273.15:g} degC only: for "
                    f"{t - 273.15:g} degC give the datasheet's viscosities (viscosity_40, viscosity_100) instead"
                )
            return self.viscosity
        return float(kinematic_viscosity(t, self.viscosity_40, self.viscosity_100)) * self.density(t)

    def bulk_modulus_at(self, p_abs: float) -> float:
        """Effective bulk modulus [Pa] at an absolute pressure (:func:`effective_bulk_modulus`).

        Parameters
        ----------
        p_abs : float
            Absolute pressure [Pa].
        """
        return effective_bulk_modulus(p_abs, self.bulk_modulus, self.air_fraction, self.polytropic_index)


def _viscosity_once(given: dict, where: str) -> None:
    """Refuse the viscosity given at the temperature beside the datasheet that would go unused
    (``given``: ``[oil] key -> where it was given``)."""
    datasheet = [given[k] for k in WALTHER_KEYS if k in given]
    if "viscosity" in given and datasheet:
        raise InputError(
            f"{where}{given['viscosity']} is given, so {', '.join(datasheet)} would be ignored: give either the "
            "viscosity at the temperature or the datasheet's viscosities (viscosity_40, viscosity_100), not both"
        )


def _si(table: str, key: str, name: str, value, source: str | None):
    """The value of the ``[oil]`` key ``name``, given as ``[table] key``, in SI (to compare two spellings)."""
    meta = Oil.__dataclass_fields__[name].metadata
    label = f"{source + ': ' if source else ''}[{table}] {key}"
    return to_si(value, meta["unit"], label, bare_unit=meta.get("bare_unit")) if meta["kind"] == "quantity" else value


def oil_of(doc: Mapping, source: str | None = None) -> tuple[Oil, dict]:
    """The one oil of a definition: ``[oil]`` with the oil keys of ``[hla]`` and ``[friction]``.

    A key given in two tables must have one value (compared in SI); the older names are mapped
    by :data:`OLDER_KEYS`.

    Parameters
    ----------
    doc : mapping
        The definition's tables (``load_toml``).
    source : str, optional
        The file, for messages.

    Returns
    -------
    oil : Oil
        The oil (its defaults where no table gives a key).
    rest : dict
        ``table -> its keys without the oil's`` for ``hla`` and ``friction`` (the tables given).
    """
    where = f"{source}: " if source else ""
    keys: dict[str, tuple] = {}  # [oil] key -> (where it was given, its value, the table, the key there)
    for key, value in dict(doc.get("oil", {})).items():
        keys[key] = ("[oil] " + key, value, "oil", key)
    rest = {}
    for table, names in OLDER_KEYS.items():
        if table not in doc:
            continue
        rest[table] = {}
        for key, value in dict(doc[table]).items():
            if key not in names:
                rest[table][key] = value
                continue
            name = names[key]
            if name in keys:
                first, before, table0, key0 = keys[name]
                if _si(table0, key0, name, before, source) != _si(table, key, name, value, source):
                    raise InputError(
                        f"{where}{first} = {before!r} and [{table}] {key} = {value!r}: one oil, one {name}; "
                        "give it once, in [oil]"
                    )
                continue
            keys[name] = (f"[{table}] {key}", value, table, key)
    _viscosity_once({name: entry[0] for name, entry in keys.items()}, where)
    mapping = {name: entry[1] for name, entry in keys.items()}
    try:
        return Oil.from_dict(mapping, source=source), rest
    except InputError as exc:
        given = {name: entry[0] for name, entry in keys.items() if not entry[0].startswith("[oil]")}
        if given:  # name the older spelling the user wrote
            text = str(exc)
            for name, first in given.items():
                text = re.sub(rf"(\[oil\] )?\b{name}\b(?= = )", lambda _m, first=first: first, text)
            raise InputError(text) from None
        raise


class HoldsOil:
    """Base of a table that holds the train's oil (``oil``, not a key) and may still give the oil's
    keys by their older names (:data:`OLDER_KEYS` of its ``table``): ``[hla]``, ``[friction]``."""

    @classmethod
    def from_dict(cls, mapping, *, source: str | None = None, oil: Oil | None = None, **context):
        """The table's keys (the oil's older keys among them, or the train's ``oil``).

        Parameters
        ----------
        mapping : mapping
            The table's keys.
        source : str, optional
            The file, for messages.
        oil : Oil, optional
            The train's oil (:func:`oil_of`): then the table holds no oil keys.
        """
        found, rest = oil_of({cls.table: mapping}, source) if isinstance(mapping, Mapping) else (None, {})
        table = rest.get(cls.table, mapping)
        if oil is not None and isinstance(mapping, Mapping) and len(table) != len(mapping):
            raise InputError(f"the oil is given twice: as the train's [oil] and in the [{cls.table}] table")
        made = super().from_dict(table, source=source, **context)
        return dataclasses.replace(made, oil=found if oil is None else oil)
