"""Parameters of a leaf spring damper (the ``[lsd]`` table of a TOML file)."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..core.errors import InputError
from ..core.params import Parameters, param
from ..core.units import to_si
from .damping import ATMOSPHERIC_PRESSURE

__all__ = ["LSDParameters", "EXAMPLES"]

#: Built-in examples: Types A, B and C of Table 4.1 of the thesis.
EXAMPLES = {"A": "lsd_type_a.toml", "B": "lsd_type_b.toml", "C": "lsd_type_c.toml"}


#: Most packs and leaves per pack springdyn models (the thesis' dampers have 4-8 packs of
#: 2-4 leaves; the limits keep the chamber network and the pack equations small).
MAX_PACKS = 64
MAX_LEAVES = 20


@dataclasses.dataclass(frozen=True)
class LSDParameters(Parameters):
    """Geometry, materials and oil of a leaf spring damper (SI floats).

    Symbols follow the leaf-spring-damper thesis (Table 4.1, Chapter 2).  Build it from
    a TOML file with :meth:`from_toml`, a mapping with :meth:`from_dict`, or take a
    built-in prototype with :meth:`example` (``"A"``, ``"B"``, ``"C"``).
    """

    packs: int = param("", "number of leaf spring packs", symbol="N", kind="int", minimum=2, maximum=MAX_PACKS)
    leaf_lengths: list = param(
        "m", "leaf lengths, longest first", symbol="L_i", kind="quantity_list", display="mm", positive=True
    )
    leaf_thicknesses: list = param(
        "m", "leaf thicknesses", symbol="t_i", kind="quantity_list", display="mm", positive=True
    )
    leaf_width: float = param("m", "leaf width", symbol="b_1", display="mm", positive=True)
    youngs_modulus: float = param("Pa", "Young's modulus of the leaves", symbol="E", display="GPa", positive=True)
    poisson_ratio: float = param("", "Poisson's ratio of the leaves", symbol="nu", nonnegative=True)
    preload: float = param("m", "pack preload deflection", symbol="delta_pre", display="mm", nonnegative=True)
    ring_outer_diameter: float = param("m", "inner ring outer diameter", symbol="d_o", display="mm", positive=True)
    ring_width: float = param("m", "inner ring width", symbol="b", display="mm", positive=True)
    passage_width: float = param("m", "oil passage width", symbol="b_o", display="mm", positive=True)
    passage_clearance: float = param("m", "oil passage clearance", symbol="h_o", display="mm", positive=True)
    passage_length: float = param("m", "oil passage length", symbol="L_h", display="mm", positive=True)
    oil_viscosity: float = param(
        "Pa*s",
        "dynamic oil viscosity (TOML may give kinematic, e.g. '100 cSt')",
        symbol="eta",
        display="Pa*s",
        positive=True,
    )
    oil_density: float = param("kg/m^3", "oil density", symbol="rho", positive=True)
    first_pack_angle: float = param(
        "rad", "angle of the first pack from the x axis", symbol="phi_1", display="deg", default=0.0
    )
    pack_angles: list = param(
        "rad", "explicit pack angles (empty: equally spaced)", kind="quantity_list", display="deg", default=[]
    )
    leaf_bending: str = param(
        None,
        "leaf rigidity in (2.8): 'plate' E/(1-nu^2) as printed, or 'beam' E (free anticlastic bending)",
        kind="str",
        choices=("plate", "beam"),
        default="plate",
    )
    clamp_overhang: float = param(
        "m", "clamp overhang a of Fig. 2.3", symbol="a", display="mm", default=0.0, nonnegative=True
    )
    ring_mass: float = param("kg", "mass of the inner ring", symbol="m", default=0.0, nonnegative=True)
    passages_per_boundary: int = param(
        "", "oil passages between two neighbouring chambers", kind="int", default=2, minimum=1, maximum=100
    )
    conductance_model: str = param(
        None, "passage conductance", kind="str", choices=("exact", "thesis"), default="exact"
    )
    leakage_factor: float = param("", "calibration factor on the passage conductance", default=1.0, positive=True)
    leaf_friction: float = param(
        "", "friction coefficient between leaves", symbol="mu_s", default=0.1, nonnegative=True
    )
    leaf_normal_load: str = param(
        None,
        "normal load in the inter-leaf friction of the coefficient model",
        kind="str",
        choices=("peak", "instantaneous"),
        default="peak",
    )
    supply_pressure: float = param(
        "Pa",
        "supply (mean chamber) pressure, gauge: above the atmosphere's 1.01325 bar",
        symbol="p_s",
        display="bar",
        default=0.0,
    )
    cavitation_pressure: float = param(
        "Pa",
        "absolute pressure at which the oil film ruptures or releases gas (0 bar: vapour limit)",
        symbol="p_cav",
        display="bar",
        default=0.0,
        nonnegative=True,
    )
    oring_friction: float = param("", "O-ring friction coefficient", symbol="mu_o", default=0.0, nonnegative=True)
    oring_normal_force: float = param("N", "O-ring normal force", symbol="F_N", default=0.0, nonnegative=True)
    name: str = param(None, "label used in plots", kind="str", default="LSD")

    def _validate(self) -> None:
        if len(self.leaf_lengths) > MAX_LEAVES:
            raise InputError(f"leaf_lengths has {len(self.leaf_lengths)} leaves; a pack has at most {MAX_LEAVES}")
        if self.packs < 2:
            raise InputError(f"packs = {self.packs} must be at least 2 (the oil chambers lie between packs)")
        if len(self.leaf_lengths) != len(self.leaf_thicknesses):
            raise InputError(
                f"leaf_lengths has {len(self.leaf_lengths)} entries and leaf_thicknesses "
                f"{len(self.leaf_thicknesses)}; give one thickness per leaf"
            )
        L = np.asarray(self.leaf_lengths)
        if np.any(np.diff(L) > 0):
            i = int(np.argmax(np.diff(L) > 0))
            raise InputError(
                f"leaf_lengths = {[f'{v * 1e3:g} mm' for v in L]} must be non-increasing "
                f"(L1 >= L2 >= ...): leaf {i + 2} is longer than leaf {i + 1}"
            )
        if not self.poisson_ratio < 0.5:
            raise InputError(f"poisson_ratio = {self.poisson_ratio} must be below 0.5")
        if not self.supply_pressure + ATMOSPHERIC_PRESSURE > self.cavitation_pressure:
            raise InputError(
                f"supply_pressure = {self.supply_pressure / 1e5:g} bar (gauge) is "
                f"{(self.supply_pressure + ATMOSPHERIC_PRESSURE) / 1e5:g} bar absolute, not above "
                f"cavitation_pressure = {self.cavitation_pressure / 1e5:g} bar (absolute): the chambers "
                "would be cavitated at rest; raise the supply pressure"
            )
        if self.passages_per_boundary < 1:
            raise InputError(f"passages_per_boundary = {self.passages_per_boundary} must be at least 1")
        if self.pack_angles:
            if len(self.pack_angles) != self.packs:
                raise InputError(f"pack_angles has {len(self.pack_angles)} entries but packs = {self.packs}")
            a = np.asarray(self.pack_angles)
            if np.any(np.diff(a) <= 0) or a[-1] - a[0] >= 2 * np.pi:
                raise InputError(
                    "pack_angles must increase around the ring and span less than 360 deg, got "
                    f"{[f'{np.degrees(v):g} deg' for v in a]}"
                )

    # ----------------------------------------------------------------- construction
    table = "lsd"
    examples = EXAMPLES
    default_example = "C"

    @classmethod
    def _prepare(cls, mapping: dict, *, source: str | None = None, **context) -> dict:
        """``oil_viscosity`` may be kinematic (``"100 cSt"``, converted with ``oil_density``)
        or dynamic (``"0.0965 Pa*s"``; a bare number is Pa s)."""
        table = mapping
        if isinstance(table.get("oil_viscosity"), str):
            where = f"{source}: [lsd] " if source else ""
            text = table["oil_viscosity"]
            try:
                nu = to_si(text, "m^2/s", f"{where}oil_viscosity")
            except InputError:
                table["oil_viscosity"] = to_si(
                    text, "Pa*s", f"{where}oil_viscosity (kinematic like '100 cSt' or dynamic like '0.1 Pa*s')"
                )
            else:
                if "oil_density" not in table:
                    raise InputError(f"{where}oil_viscosity = {text!r} is kinematic; give oil_density to convert it")
                rho = to_si(table["oil_density"], "kg/m^3", f"{where}oil_density")
                if not (isinstance(rho, float) and rho > 0):
                    raise InputError(f"{where}oil_density = {table['oil_density']!r} must be positive (oil density)")
                table["oil_viscosity"] = nu * rho
        return table

    @classmethod
    def _example_key(cls, name: str) -> str:
        """``"A"``, ``"type a"``, ``"Type_A"``: Types A, B, C of Table 4.1 of the thesis (values the
        thesis does not give are assumptions stated in the shipped TOML files)."""
        return str(name).upper().removeprefix("TYPE").strip(" _-")

    # ----------------------------------------------------------------- derived
    @property
    def supply_pressure_absolute(self) -> float:
        """Supply pressure, absolute [Pa]."""
        return self.supply_pressure + ATMOSPHERIC_PRESSURE

    @property
    def kinematic_viscosity(self) -> float:
        """``eta / rho`` [m^2/s]."""
        return self.oil_viscosity / self.oil_density
