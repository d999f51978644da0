"""The valve-spring definition: the ``[spring]`` keys and their validation.

The definition holds geometry, material and damping; the ``model`` key chooses the
equations (:mod:`springdyn.valve.spring.chains`), built once as :attr:`ValveSpring.spring_model`.
The analyses (statics, modes, design figures, dynamics) are those of
:class:`springdyn.valve.ValveModel` and of the spring model.
"""

from __future__ import annotations

import dataclasses
import math
import sys
import warnings
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, describe_value, load_toml, param
from ...core.units import format_mm, format_quantity, to_si
from . import formulas
from .chains import make_model
from .geometry import TRANSITION_TURNS, drawing_pitch_knots, end_allowance
from .materials import MATERIALS, material
from .solid_length import COILINGS, en13906_solid_length, solid_length, solid_length_source
from .stress import spring_strengths
from .wire import WIRE_SHAPES, wire_section

__all__ = ["ValveSpring", "EXAMPLES", "MODEL_NAMES", "END_TYPES", "DRAWING_KEYS"]

#: Built-in example springs (the reference springs of docs/valve-spring.md), shipped in ``springdyn/data``.
EXAMPLES = {"one-step": "valve_one_step.toml", "two-step": "valve_two_step.toml"}

#: Coil end types of a drawing: dead coils per end (EN 13906-1, cold-coiled compression
#: springs: ``n_t = n + 2`` for closed ends; open ends have no dead coil).  Their solid lengths:
#: :func:`springdyn.valve.spring.solid_length.solid_length`.
#: Dead coils per end of each end type [-] (:func:`springdyn.valve.spring.solid_length.en13906_solid_length`
#: gives their solid lengths): closed ends one (EN 13906-1, cold coiled: ``n_t = n + 2``), plain
#: (open) ends none, plain ground ends half a coil (Shigley, Table 10-1: ``N_t = N_a + 1``), the
#: tapered ends of a hot-coiled bar three quarters (EN 13906-1, hot coiled: ``n_t = n + 1.5``).
END_TYPES = {"closed-ground": 1.0, "closed": 1.0, "open": 0.0, "plain": 0.0, "plain-ground": 0.5, "tapered": 0.75}

#: Keys of a drawing that the ``[spring]`` table reads into the model's own keys
#: (:meth:`ValveSpring._prepare`): they are not fields of the definition.
DRAWING_KEYS = ("total_coils", "active_coils", "outer_diameter", "inner_diameter", "pitch", "low_pitch", "high_pitch")
#: The drawing's pitches of the active coils [m]: ``pitch`` (one-step), ``low_pitch`` and
#: ``high_pitch`` (two-step); they become the ``pitch_profile`` (:func:`_pitches`).
PITCH_KEYS = ("pitch", "low_pitch", "high_pitch")
#: Longest transition from a dead coil to the active pitch a ``[spring]`` may give [turns].
MAX_TRANSITION_TURNS = 1.0

#: How the pitches are joined (for messages): :data:`springdyn.valve.spring.geometry.TRANSITION_TURNS`.
TRANSITION_TURNS_TEXT = "a transition of half a turn between sections"

#: Names of the spring models (:data:`springdyn.valve.spring.chains.MODELS`).
MODEL_NAMES = ("type-c", "distributed")

#: The tables that make a file a spring pack (:class:`springdyn.valve.spring.pack.SpringPack`):
#: :meth:`ValveSpring.from_toml` refuses such a file rather than read its outer spring alone.
PACK_FILE_TABLES = ("inner_spring", "third_spring", "pack", "damper")


@dataclass(frozen=True)
class ValveSpring(Parameters):
    """A helical valve spring for the MMS Type C model (one-step or two-step).

    All values SI.  Build from TOML with :meth:`from_toml` (keys as the attribute names,
    values with units such as ``"22 mm"``), from a dict with :meth:`from_dict`, or take a
    built-in example with :meth:`example`.

    Examples
    --------
    >>> s = ValveSpring.example("one-step")
    >>> s.mean_diameter, s.wire_diameter
    (0.022, 0.0035)
    >>> round(s.spring_model.internal_parameters()["Fset"], 2)
    251.43
    """

    type: str = param(None, "spring kind", kind="str", choices=("one-step", "two-step"))
    mean_diameter: float = param("m", "mean coil diameter", symbol="Do", display="mm", positive=True)
    wire_diameter: float = param("m", "wire diameter", symbol="Dw", display="mm", positive=True)
    free_length: float = param("m", "free length", symbol="Lf", display="mm", positive=True)
    installed_length: float = param(
        "m", "set-up (installed) length, valve closed", symbol="Ls", display="mm", positive=True
    )
    dead_coils: float = param("", "dead coils per end", symbol="Nb", nonnegative=True)
    low_pitch_coils: float = param("", "low-pitch coils (0 for one-step)", symbol="N1", nonnegative=True)
    high_pitch_coils: float = param("", "high-pitch coils", symbol="N2", positive=True)
    youngs_modulus: float = param("Pa", "Young's modulus", symbol="E", display="GPa", positive=True)
    shear_modulus: float = param("Pa", "shear modulus", symbol="G'", display="GPa", positive=True)
    density: float = param("kg/m^3", "density", symbol="rho'", positive=True)
    damping_ratio: float = param("", "damping ratio", symbol="Cps", nonnegative=True)
    tensile_strength: float = param(
        "Pa",
        "tensile strength of the wire (default 2000 MPa: oil-tempered Cr-Si valve-spring wire, EN 10270-2 VDSiCr)",
        display="MPa",
        positive=True,
        default=None,
    )
    endurance_shear_strength: float = param(
        "Pa",
        "fully reversed torsional endurance strength of the wire (default: Zimmerli's peened data on the Goodman line)",
        display="MPa",
        positive=True,
        default=None,
    )
    shear_yield_strength: float = param(
        "Pa",
        "torsional stress the wire may not exceed in service (yield or relaxation limit; default the ultimate "
        "shear strength, 0.67 of the tensile)",
        display="MPa",
        positive=True,
        default=None,
    )
    contact_stiffness: float = param(
        "N/m",
        "stiffness of one closed turn in coil contact and of the end contacts (default pi Do E / 1e3, "
        "the MMS document's 'stiffness for fully contact'; docs/valve-spring.md shows its effect)",
        display="N/mm",
        positive=True,
        default=None,
    )
    end_type: str = param(
        None,
        "coil ends as drawn: 'closed-ground', 'closed' (not ground), 'plain' (or 'open'), 'plain-ground' or "
        "'tapered' (hot coiled, closed and ground); sets the dead coils and the solid length per EN 13906-1 "
        "and Shigley's Table 10-1 (default: the MMS document's solid length Dw (N1 + N2 + 0.5))",
        kind="str",
        choices=("", *END_TYPES),
        default="",
    )
    coiling: str = param(
        None,
        "how the spring is wound: 'cold' (valve springs, oil-tempered wire) or 'hot' (bar stock); sets EN "
        "13906-1's minimum sum of gaps Sa and its dynamic factor (1.5 Sa cold, 2 Sa hot) that judges the "
        "coil-bind clearance (default: hot for tapered ends, else cold)",
        kind="str",
        choices=("", *COILINGS),
        default="",
    )
    material: str = param(
        None,
        "named wire (SiCr, SiCrV, CrV, music-wire; springdyn.valve.spring.materials): its shear and Young's "
        "moduli, density and the tensile strength at this wire diameter, each overridable by its own key",
        kind="str",
        choices=("", *MATERIALS),
        default="",
    )
    load_points: str = param(
        None,
        "load points of the drawing to check the model against: a TOML array of tables "
        '[{ length = "38 mm", force = "250 N", tolerance = "5 %" }, ...] (tolerance in % of the force or in N)',
        kind="str",
        default="",
    )
    min_coil_bind_clearance: float = param(
        "m",
        "smallest allowed margin between the shortest working length and the solid length "
        "(default: EN 13906-1's dynamic clearance, 1.5 Sa cold coiled or 2 Sa hot coiled, Sa the minimum sum of "
        "gaps (0.0015 D^2/d + 0.1 d) n cold, 0.02 (D + d) n hot)",
        display="mm",
        nonnegative=True,
        default=None,
    )
    through_solid: bool = param(
        None,
        "simulate a spring that the cam drives past its solid length (experts: every result says so)",
        kind="bool",
        default=False,
    )
    model: str = param(
        None,
        "spring model: 'type-c' (the document's MMS Type C, 5 masses) or 'distributed' "
        "(coil by coil from the geometry)",
        kind="str",
        choices=MODEL_NAMES,
        default="type-c",
    )
    elements: int = param("", "wire elements of the distributed model", kind="int", default=50, positive=True)
    transition_turns: float = param(
        "",
        "distributed model: turns over which the pitch rises from a closed dead coil to the active pitch at each "
        "end (these coils close one by one under load; default 0.5, typical of coiled valve springs; a "
        "synthesised spring states its own)",
        positive=True,
        default=None,
    )
    pitch_profile: str = param(
        None,
        "distributed model: pitch against turns from the seat end, a CSV file (columns "
        "turns, pitch_mm) or an array of [turns, pitch] pairs (default: from the keys above)",
        kind="str",
        default="",
    )
    diameter_profile: str = param(
        None,
        "distributed model: mean coil diameter against turns from the seat end, a "
        "CSV file (columns turns, diameter_mm) or an array of [turns, diameter] pairs "
        "(default: mean_diameter throughout)",
        kind="str",
        default="",
    )
    wire_shape: str = param(
        None,
        "the wire's cross-section: 'round' (wire_diameter), 'ovate' (an oval of wire_width radial by wire_height "
        "axial, the beehive springs' wire) or 'rectangular' (wire_width by wire_height); sets the rate, stress, "
        "mass, solid length and surge of both models (springdyn.valve.spring.wire)",
        kind="str",
        choices=WIRE_SHAPES,
        default="round",
    )
    wire_width: float = param(
        "m",
        "ovate or rectangular wire: its dimension across the coil (radial)",
        display="mm",
        positive=True,
        default=None,
    )
    wire_height: float = param(
        "m",
        "ovate or rectangular wire: its dimension along the spring's axis (it stacks to the solid length)",
        display="mm",
        positive=True,
        default=None,
    )
    wire_diameter_profile: str = param(
        None,
        "distributed model, round wire: the wire diameter against turns from the seat end, a CSV file (columns "
        "turns, wire_diameter_mm) or an array of [turns, diameter] pairs (default: wire_diameter throughout; "
        "wire_diameter, when not given, is its largest)",
        kind="str",
        default="",
    )

    table = "spring"
    plausible_ranges = False  # _check_geometry's ranges say more (the likely unit slip)
    examples = EXAMPLES
    default_example = "one-step"
    extra_keys = DRAWING_KEYS

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_toml(cls, path) -> ValveSpring:
        """The ``[spring]`` table of a TOML file; a spring pack's file (with ``[inner_spring]``,
        ``[third_spring]``, ``[pack]`` or ``[damper]``) is refused: its ``[spring]`` is only the
        outer spring (:class:`springdyn.valve.spring.pack.SpringPack` reads the pack).

        Parameters
        ----------
        path : str or path-like
            The file.
        """
        doc = load_toml(path)
        pack = [t for t in PACK_FILE_TABLES if t in doc]
        if pack:
            raise InputError(
                f"{path}: [{pack[0]}] makes this file a spring pack, and a ValveSpring is one spring: read it with "
                "SpringPack.from_toml or ValveModel.from_files, run it through springdyn valve simulate, sweep, "
                "float, train-modes, clearance, cam-check or springdyn report, or give one spring's own file"
            )
        if cls.table not in doc:
            return super().from_toml(path)  # the missing table's own message
        return cls.from_dict(doc[cls.table], source=str(path), base_dir=Path(path).parent)

    @classmethod
    def outer_from_toml(cls, path) -> ValveSpring:
        """The ``[spring]`` of a file: one spring's, or a spring pack's outer spring (its other
        tables not read), for what designs against one given spring (``valve synthesize-inner``).

        Parameters
        ----------
        path : str or path-like
            The file.
        """
        doc = load_toml(path)
        if cls.table not in doc:
            return super().from_toml(path)  # the missing table's own message
        return cls.from_dict(doc[cls.table], source=str(path), base_dir=Path(path).parent)

    @classmethod
    def _prepare(cls, mapping: dict, base_dir=None, **context) -> dict:
        """The drawing's keys become the model's (:meth:`_from_drawing`); load points and
        profiles: a TOML array becomes an inline table (SI); a relative CSV path is taken from
        the TOML file's folder."""

        mapping = _from_drawing(_wire_keys(mapping))

        for key in ("pitch_profile", "diameter_profile", "wire_diameter_profile"):
            value = mapping.get(key)
            if isinstance(value, list):
                rows = []
                for i, row in enumerate(value):
                    if (
                        not isinstance(row, list)
                        or len(row) != 2
                        or isinstance(row[0], (bool, str))
                        or not isinstance(row[0], (int, float))
                    ):
                        raise InputError(f'{key}[{i}] = {row!r} must be a pair [turns, value], e.g. [1.5, "7 mm"]')
                    rows.append(f"{float(row[0])!r} {to_si(row[1], 'm', f'{key}[{i}][1]')!r}")
                mapping[key] = "table: " + "; ".join(rows)
            elif isinstance(value, str) and value and base_dir is not None and not value.startswith("table:"):
                p = Path(value)
                mapping[key] = str(p if p.is_absolute() else Path(base_dir) / p)
        return mapping

    def _validate(self) -> None:
        self._check_wire()

        if self.transition_turns is not None and self.transition_turns > MAX_TRANSITION_TURNS:
            raise InputError(
                f"transition_turns = {self.transition_turns:g} is more than {MAX_TRANSITION_TURNS:g} turn: the pitch of a "
                "coiled spring reaches the active pitch within a turn of the dead coil"
            )
        if self.load_points and not self.load_points.startswith("table:"):
            object.__setattr__(self, "load_points", _load_points(self.load_points))  # the API's TOML text, read once
        if self.coiling == "cold" and self.end_type == "tapered":
            raise InputError(
                "coiling = 'cold' with end_type = 'tapered': tapered bar ends are hot coiled (EN 13906-1); "
                "give coiling = 'hot' or another end_type"
            )
        unlikely = self._check_geometry()
        try:
            _ = self.spring_model  # the model checks that its equations hold for this spring
        except InputError as exc:
            if not unlikely:
                raise
            raise InputError(f"{exc} (note: {'; '.join(unlikely)})") from None
        if unlikely:
            # attribute the warning to the caller's line, outside springdyn
            package, level, frame = str(Path(__file__).parents[2]), 1, sys._getframe(0)  # springdyn/
            while frame is not None and (
                frame.f_code.co_filename.startswith(package)
                or frame.f_code.co_filename.endswith("dataclasses.py")
                or frame.f_locals.get("self") is self
            ):
                frame, level = frame.f_back, level + 1
        for message in unlikely:
            warnings.warn(message, UserWarning, stacklevel=level)

    def _check_wire(self) -> None:
        """The wire's keys agree with its shape (:mod:`springdyn.valve.spring.wire`)."""
        given = [k for k in ("wire_width", "wire_height") if getattr(self, k) is not None]
        if self.wire_shape == "round":
            if given:
                raise InputError(
                    f"{given[0]} applies to ovate and rectangular wire: give wire_shape = 'ovate' or 'rectangular', "
                    "or wire_diameter alone for round wire"
                )
            return
        if len(given) < 2:
            missing = "wire_height" if "wire_width" in given else "wire_width"
            raise InputError(
                f"wire_shape = {self.wire_shape!r} needs wire_width (radial) and wire_height (axial): missing {missing}"
            )
        if self.wire_diameter_profile:
            raise InputError(
                f"wire_diameter_profile is a round wire's: wire_shape = {self.wire_shape!r} takes one section "
                "(wire_width, wire_height)"
            )
        if abs(self.wire_diameter - self.wire_height) > 1e-9 * self.wire_height:
            raise InputError(
                f"{self._field('wire_diameter')} and {self._field('wire_height')} disagree: the wire_diameter of "
                f"{self.wire_shape} wire is its axial height (it stacks to the solid length); give wire_height alone"
            )
        ratio = self.wire_width / self.wire_height
        if not 0.2 <= ratio <= 5.0:
            raise InputError(
                f"{self._field('wire_width')} / {self._field('wire_height')} = {ratio:.3g} must lie between 0.2 and 5 "
                "(profiled spring wire; are the two swapped or a unit slipped?)"
            )

    @property
    def wire(self):
        """The wire's nominal cross-section (:class:`springdyn.valve.spring.wire.WireSection`)."""
        return wire_section(self)

    @property
    def total_coils(self) -> float:
        """Total coils ``N1 + N2`` [-] (dead coils included)."""
        return self.low_pitch_coils + self.high_pitch_coils

    @property
    def active_coils(self) -> float:
        """Active coils at free length ``N1 + N2 - 2 Nb`` [-]."""
        return formulas.active_coils_free(self.low_pitch_coils, self.high_pitch_coils, self.dead_coils)

    @property
    def solid_length(self) -> float:
        """Solid length [m] (:func:`springdyn.valve.spring.solid_length.solid_length`: by the end type)."""

        return solid_length(self)

    @property
    def coil_facts(self) -> dict:
        """The coils and the solid length every output states: ``total_coils``,
        ``active_coils``, ``dead_coils_per_end`` [-], ``solid_length_m`` [m] and its
        ``solid_length_source``, ``free_length_m`` [m]."""
        return dict(
            total_coils=self.total_coils,
            active_coils=self.active_coils,
            dead_coils_per_end=self.dead_coils,
            solid_length_m=self.solid_length,
            solid_length_source=solid_length_source(self),
            free_length_m=self.free_length,
        )

    @property
    def strengths(self) -> dict:
        """The wire's torsional strengths and stress limit, and which are defaults
        (:func:`springdyn.valve.spring.stress.spring_strengths`)."""
        return spring_strengths(self)

    @property
    def load_point_table(self) -> list[dict]:
        """The drawing's load points: ``length`` [m], ``force`` [N], ``tolerance`` [N] (None: not given)."""
        out = []
        if self.load_points:
            for row in self.load_points.removeprefix("table:").split(";"):
                length, force, tol = (float(v) for v in row.split())
                out.append(dict(length=length, force=force, tolerance=None if tol < 0 else tol))
        return out

    def with_model(self, model: str | None) -> ValveSpring:
        """The same spring with another model (``None``: unchanged).

        Parameters
        ----------
        model : str or None
            A spring model name (:data:`MODEL_NAMES`) [-].
        """
        return self if model is None or model == self.model else self.replace(model=model)

    @cached_property
    def spring_model(self):
        """The model of this definition (:class:`~springdyn.valve.spring.chains.SpringModel`)."""

        return make_model(self)

    @property
    def two_step(self) -> bool:
        return self.type == "two-step"

    def _field(self, name: str) -> str:
        meta = {f.name: f.metadata for f in dataclasses.fields(self)}[name]
        return f"{name} = {describe_value(getattr(self, name), meta)}"

    def _check_geometry(self) -> list[str]:
        """Cross-key and plausibility checks; returns warnings for values unlike a valve spring.

        Errors (:class:`InputError`) for values no helical spring can have, which would
        otherwise overflow, underflow or divide by zero in the closed forms of [MMS],
        "Internal Parameter"; warnings for values far outside the range of valve springs,
        naming the likely unit slip (``22 m`` for ``22 mm``).
        """

        # key: (error range, valve-spring range) in SI
        ranges = {
            "mean_diameter": ((1e-6, 1e3), (5e-3, 0.1), "any helical spring", "any valve spring"),
            "wire_diameter": ((1e-6, 1e3), (0.5e-3, 15e-3), "any helical spring", "any valve spring"),
            "free_length": ((1e-6, 1e4), (8e-3, 0.3), "any helical spring", "any valve spring"),
            "installed_length": ((1e-6, 1e4), (5e-3, 0.3), "any helical spring", "any valve spring"),
            "youngs_modulus": ((1e5, 1e16), (50e9, 400e9), "any spring material", "spring steel or titanium"),
            "shear_modulus": ((1e5, 1e16), (20e9, 150e9), "any spring material", "spring steel or titanium"),
            "density": ((1.0, 1e6), (1000.0, 25000.0), "any solid", "spring steel or titanium"),
        }

        def show(value, unit, display):
            # in the display unit unless that needs many digits: 22 m, not 22000 mm
            in_display = value * {"mm": 1e3, "GPa": 1e-9}.get(display, 1.0)
            return format_quantity(value, unit, display if 1e-2 <= in_display < 1e3 else None)

        unlikely = []
        for key, ((lo, hi), (wlo, whi), what, typical) in ranges.items():
            value = getattr(self, key)
            meta = {f.name: f.metadata for f in dataclasses.fields(self)}[key]
            display = meta.get("display") or meta["unit"]
            shown = show(value, meta["unit"], display)
            hint = ""
            for factor in (1e-3, 1e3, 1e-6, 1e6, 1e-9, 1e9, 1e-12, 1e12):
                if wlo <= value * factor <= whi:
                    hint = f": did you mean {format_quantity(value * factor, meta['unit'], display)}?"
                    break
            side = "larger" if value > whi else "smaller"
            if not lo <= value <= hi:
                raise InputError(
                    f"{key} = {shown} is far {side} than {what}: it must lie between "
                    f"{show(lo, meta['unit'], display)} and {show(hi, meta['unit'], display)}"
                    f"{hint}"
                )
            if not wlo <= value <= whi:
                unlikely.append(
                    f"{key} = {shown} is far {side} than {typical} "
                    f"({show(wlo, meta['unit'], display)} to {show(whi, meta['unit'], display)})"
                    + (hint or "; check its unit")
                )
        if self.contact_stiffness is not None and not 1e3 <= self.contact_stiffness <= 1e12:
            # the default pi Do E / 1e3 is some 1e7 N/m; beyond these the closed coils are a unit slip
            raise InputError(
                f"{self._field('contact_stiffness')} is outside any coil contact: it must lie between 1 N/mm and 1e9 N/mm (the default pi Do E / 1e3 is "
                f"{format_quantity(formulas.contact_stiffness(self.mean_diameter, self.youngs_modulus), 'N/m', 'N/mm')})"
            )
        for strength in ("shear_yield_strength", "endurance_shear_strength"):
            value = getattr(self, strength)
            if value is not None and self.tensile_strength is not None and value >= self.tensile_strength:
                raise InputError(
                    f"{self._field(strength)} is not below {self._field('tensile_strength')}: a "
                    "wire's torsional strengths lie below its tensile strength (the ultimate shear is some 0.67 of it)"
                )
        for key in ("dead_coils", "low_pitch_coils", "high_pitch_coils"):
            if getattr(self, key) > 1000:
                raise InputError(f"{self._field(key)} is more coils than any spring has: it must be at most 1000")
        if self.damping_ratio >= 1.0:  # (the distributed chain's damping is set from an underdamped first mode)
            raise InputError(
                f"damping_ratio = {self.damping_ratio:g} is "
                f"{'at' if self.damping_ratio == 1.0 else 'above'} critical damping (1), which no spring wire has"
                + (
                    f": did you mean {self.damping_ratio:g} % ({self.damping_ratio / 100:g})?"
                    if self.damping_ratio <= 100
                    else ""
                )
            )
        if self.damping_ratio > 0.2:
            unlikely.append(
                f"damping_ratio = {self.damping_ratio:g} is far above the damping of valve springs (a few %, e.g. 0.05)"
            )
        if self.shear_modulus > self.youngs_modulus:
            unlikely.append(
                f"{self._field('shear_modulus')} exceeds {self._field('youngs_modulus')}: for a metal "
                "G is about 0.4 E (are the two swapped?)"
            )
        radial = "wire_diameter" if self.wire_shape == "round" else "wire_width"
        index = self.mean_diameter / getattr(self, radial)
        if not 3.0 <= index <= 20.0:
            raise InputError(
                f"spring index C = mean_diameter / {radial} = {show(self.mean_diameter, 'm', 'mm')} / "
                f"{show(getattr(self, radial), 'm', 'mm')} = {index:.4g} must lie between 3 and 20 (EN 13906-1 recommends 4 to "
                "20; below 3 the wire cannot be coiled, above 20 the coils are unstable)"
                + (": is the wire diameter given as the mean diameter?" if index < 1 else "")
            )
        if not math.isfinite(index):  # pragma: no cover - excluded by the ranges above
            raise InputError(f"spring index C = {index!r} is not finite")
        if self.installed_length >= self.free_length:
            raise InputError(f"{self._field('installed_length')} must be shorter than {self._field('free_length')}")
        if not self.two_step and self.low_pitch_coils != 0:
            raise InputError(
                f"{self._field('low_pitch_coils')} must be 0 for a one-step spring "
                '(set type = "two-step" for a spring with low-pitch coils)'
            )
        n1, n2, nb = self.low_pitch_coils, self.high_pitch_coils, self.dead_coils
        if formulas.active_coils_free(n1, n2, nb) <= 0:
            raise InputError(
                f"active coils N1 + N2 - 2 Nb = {n1:g} + {n2:g} - 2*{nb:g} = "
                f"{formulas.active_coils_free(n1, n2, nb):g} must be positive "
                "(low_pitch_coils + high_pitch_coils - 2 dead_coils)"
            )
        if n2 - nb <= 0:
            raise InputError(
                f"active coils at set-up N2 - Nb = {n2:g} - {nb:g} must be positive (high_pitch_coils > dead_coils)"
            )
        lc = self.solid_length
        if self.installed_length <= lc:
            raise InputError(
                f"{self._field('installed_length')} is at or below coil contact: it must be longer than the "
                f"solid length Lc = {format_mm(lc)} ({self.coil_facts['solid_length_source']})"
            )
        return unlikely


def _wire_keys(mapping: dict) -> dict:
    """The wire's keys in the model's: ``wire_diameter`` of ovate and rectangular wire is its axial
    height (given or not, it must be ``wire_height``); of a ``wire_diameter_profile`` its largest
    diameter (the closed dead coils' pitch and the nominal wire)."""
    m = dict(mapping)
    shape = m.get("wire_shape", "round")
    if shape not in WIRE_SHAPES:
        raise InputError(f"wire_shape = {shape!r} is not allowed; choose one of {', '.join(map(repr, WIRE_SHAPES))}")
    if shape != "round":
        if "wire_diameter" in m and "wire_height" not in m:
            raise InputError(
                f"wire_shape = {shape!r} takes wire_width (radial) and wire_height (axial), not wire_diameter"
            )
        missing = [k for k in ("wire_width", "wire_height") if k not in m]
        if missing:
            raise InputError(
                f"wire_shape = {shape!r} needs wire_width (radial) and wire_height (axial): missing {missing[0]}"
            )
        h = _quantity(m, "wire_height", "m")
        if "wire_diameter" in m and abs(_quantity(m, "wire_diameter", "m") - h) > 1e-9 * h:
            raise InputError(
                f"wire_diameter = {m['wire_diameter']!r} and wire_height = {m['wire_height']!r} disagree: the "
                f"wire_diameter of {shape} wire is its axial height; give wire_width and wire_height alone"
            )
        m["wire_diameter"] = h
    profile = m.get("wire_diameter_profile")
    if isinstance(profile, list) and "wire_diameter" not in m:
        values = []
        for i, row in enumerate(profile):
            if isinstance(row, list) and len(row) == 2:
                values.append(to_si(row[1], "m", f"wire_diameter_profile[{i}][1]"))
        if values:
            m["wire_diameter"] = max(values)
    return m


def _count(mapping: dict, key: str, default: float | None = None) -> float:
    """A coil count of a drawing's table as a number [-] (issue 40: a string such as
    ``"1 coil"`` beside pitch keys was a traceback): one message naming the key otherwise."""
    if key not in mapping and default is not None:
        return default
    value = mapping[key]
    if isinstance(value, bool):
        raise InputError(f"{key} = {value!r} must be a number of coils")
    try:
        return float(to_si(value, "", key))
    except InputError:
        raise InputError(f"{key} = {value!r} must be a number of coils (a bare number, e.g. {key} = 1)") from None


def _quantity(mapping: dict, key: str, unit: str) -> float:

    return to_si(mapping[key], unit, key)


def _from_drawing(mapping: dict) -> dict:
    """A ``[spring]`` table as a drawing or an EN 13906-1 calculator gives it, in the model's keys.

    - ``outer_diameter`` / ``inner_diameter`` give ``mean_diameter`` (``D = De - d = Di + d``);
    - ``end_type`` gives ``dead_coils`` (:data:`END_TYPES`);
    - ``total_coils`` (dead coils included) or ``active_coils`` give ``high_pitch_coils``
      (``N2 = n_t - N1``, ``n_t = n + 2 Nb``; a two-step spring needs ``low_pitch_coils``);
    - ``material`` (a named wire) gives ``shear_modulus``, ``youngs_modulus``, ``density`` and
      ``tensile_strength`` where the table gives none of its own;
    - ``load_points`` become an inline table (lengths [m], forces [N], tolerances [N]).

    Keys that say the same twice must agree (1 um, 1e-9 coils), else :class:`InputError`
    names both.
    """
    m = dict(mapping)
    if m.get("material"):
        wire = material(m["material"])  # (case-insensitive, grade names too; an unknown one says which are known)
        if "wire_diameter" not in m:
            raise InputError(f"material = {m['material']!r} needs wire_diameter (its tensile strength depends on it)")
        m["material"] = wire.name
        for key, value in wire.spring_keys(_quantity(m, "wire_diameter", "m")).items():
            m.setdefault(key, value)  # each of the wire's values unless the table gives its own
    given = [k for k in ("mean_diameter", "outer_diameter", "inner_diameter") if k in m]
    if any(k != "mean_diameter" for k in given):
        radial = "wire_width" if m.get("wire_shape", "round") != "round" else "wire_diameter"
        if radial not in m:
            raise InputError(f"{given[-1]} needs {radial} to give the mean coil diameter")
        d = _quantity(m, radial, "m")
        means = {
            k: _quantity(m, k, "m") + {"mean_diameter": 0.0, "outer_diameter": -d, "inner_diameter": d}[k]
            for k in given
        }
        first = given[0]
        for k in given[1:]:
            if abs(means[k] - means[first]) > 1e-6:
                raise InputError(
                    f"{first} and {k} disagree: they give mean coil diameters of {format_mm(means[first])} and "
                    f"{format_mm(means[k])} ({radial} {format_mm(d)}); give one of them"
                )
        for k in given:
            m.pop(k)
        m["mean_diameter"] = round(means[first], 12)  # 25.5 mm - 3.5 mm is 22 mm, not 22.000000000000002
    drawn_dead = _dead_coils_of_the_counts(m)  # both coil counts give the dead coils (None: not both)
    if m.get("end_type"):
        end = m["end_type"]
        if end not in END_TYPES:
            raise InputError(f"end_type = {end!r} is not allowed; choose one of {', '.join(map(repr, END_TYPES))}")
        nb = END_TYPES[end] if drawn_dead is None else drawn_dead
        if drawn_dead is not None and END_TYPES[end] == 0.0 and drawn_dead > 1e-9:
            raise InputError(
                f"total_coils and active_coils give {drawn_dead:g} dead coils per end, but end_type = {end!r} has "
                "none: give a closed end type, or equal counts"
            )
        if "dead_coils" in m and abs(_count(m, "dead_coils") - nb) > 1e-9:
            raise InputError(
                f"dead_coils = {m['dead_coils']!r} disagrees with "
                + (
                    f"end_type = {end!r}, which has {nb:g} dead coil per end (EN 13906-1)"
                    if drawn_dead is None
                    else f"total_coils and active_coils, which give {nb:g} per end"
                )
                + "; give one of them"
            )
        m["dead_coils"] = nb
    elif drawn_dead is not None and "dead_coils" not in m:
        m["dead_coils"] = drawn_dead
    coils = [k for k in ("total_coils", "active_coils") if k in m]
    if coils:
        if "dead_coils" not in m:
            raise InputError(f"{coils[0]} needs dead_coils or end_type to count the dead coils")
        nb = _count(m, "dead_coils")
        n1 = _count(m, "low_pitch_coils", 0.0)
        if m.get("type") == "two-step" and "low_pitch_coils" not in m:
            raise InputError(f"{coils[0]} of a two-step spring needs low_pitch_coils (the closely wound coils)")
        totals = {}
        for k in coils:
            v = m.pop(k)
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise InputError(f"{k} = {v!r} must be a number of coils")
            totals[k] = float(v) + (2 * nb if k == "active_coils" else 0.0)
        if len(totals) == 2 and abs(totals["total_coils"] - totals["active_coils"]) > 1e-9:
            raise InputError(
                f"total_coils = {totals['total_coils']:g} and active_coils = {totals['active_coils'] - 2 * nb:g} "
                f"disagree: with {nb:g} dead coil(s) per end the total is the active coils + {2 * nb:g}; give one of them"
            )
        n2 = next(iter(totals.values())) - n1
        if "high_pitch_coils" in m and abs(_count(m, "high_pitch_coils") - n2) > 1e-9:
            raise InputError(
                f"high_pitch_coils = {m['high_pitch_coils']!r} disagrees with {' and '.join(coils)} "
                f"(which give high_pitch_coils = {n2:g}); give one of them"
            )
        m["high_pitch_coils"] = n2
        m.setdefault("low_pitch_coils", 0.0)
    if any(k in m for k in PITCH_KEYS):
        _pitches(m)
    if "load_points" in m:
        m["load_points"] = _load_points(m["load_points"])
    return m


def _dead_coils_of_the_counts(m: dict) -> float | None:
    """The dead coils per end a drawing gives by both its coil counts, ``(n_t - n) / 2`` [-]
    (real valve springs have 0.75-1.25: issue 40), or None when it gives fewer than both."""
    if "total_coils" not in m or "active_coils" not in m:
        return None
    for k in ("total_coils", "active_coils"):
        if isinstance(m[k], bool) or not isinstance(m[k], (int, float)):
            raise InputError(f"{k} = {m[k]!r} must be a number of coils")
    dead = (float(m["total_coils"]) - float(m["active_coils"])) / 2.0
    if dead < -1e-12:
        raise InputError(
            f"total_coils = {m['total_coils']!r} is below active_coils = {m['active_coils']!r}: the total counts the "
            "active coils and the dead ones"
        )
    return max(round(dead, 9), 0.0)  # (6.8 - 5.0) / 2 is 0.9, not 0.8999999999999999


def _pitches(m: dict) -> None:
    """The drawing's pitches -> ``pitch_profile`` (and ``free_length`` when not given).

    The profile is :func:`springdyn.valve.spring.geometry.drawing_pitch_knots`; a given free length
    must agree with the one the pitches give within 0.5 % (the distributed model's rule for a
    ``pitch_profile``).
    """

    given = [k for k in PITCH_KEYS if k in m]
    two = m.get("type") == "two-step"
    need = ("low_pitch", "high_pitch") if two else ("pitch",)
    if set(given) != set(need):
        kind = "a two-step" if two else "a one-step"
        missing = [k for k in need if k not in given]
        extra = [k for k in given if k not in need]
        said = (f"missing key {missing[0]!r}" if missing else "") + (
            f"{'; ' if missing else ''}{', '.join(extra)} {'does' if len(extra) == 1 else 'do'} not apply"
            if extra
            else ""
        )
        raise InputError(
            f"{said}: {kind} spring's drawing gives {' and '.join(need)} "
            + (
                "(the pitches of the low- and the high-pitch active coils)"
                if two
                else "(the pitch of the active coils)"
            )
        )
    if m.get("pitch_profile"):
        raise InputError(f"{given[0]} and pitch_profile both give the pitch: give one of them")
    missing = [k for k in ("wire_diameter", "dead_coils", "high_pitch_coils") if k not in m]
    if missing:
        raise InputError(
            f"{given[0]} needs {missing[0]}"
            + (" (or end_type)" if missing[0] == "dead_coils" else "")
            + (" (or total_coils / active_coils)" if missing[0] == "high_pitch_coils" else "")
            + " to give the free length"
        )
    dw = _quantity(m, "wire_diameter", "m")
    pitch = {k: _quantity(m, k, "m") for k in given}
    for k, v in pitch.items():
        if not v > dw:
            raise InputError(f"{k} = {format_mm(v)} must exceed the wire diameter {format_mm(dw)} (open coils)")
    if two and not pitch["high_pitch"] > pitch["low_pitch"]:
        raise InputError(
            f"high_pitch = {format_mm(pitch['high_pitch'])} must exceed low_pitch = {format_mm(pitch['low_pitch'])}"
        )
    nb, n1 = _count(m, "dead_coils"), _count(m, "low_pitch_coils", 0.0)
    n_total = n1 + _count(m, "high_pitch_coils")
    if two and not n1 > nb:
        raise InputError(
            f"low_pitch_coils = {n1:g} must exceed dead_coils = {nb:g}: the low-pitch coils include the seat's dead coil"
        )
    s, p = drawing_pitch_knots(
        n_total,
        nb,
        dw,
        n1,
        pitch["high_pitch" if two else "pitch"],
        pitch["low_pitch"] if two else None,
        transition=_count(m, "transition_turns", TRANSITION_TURNS) if "transition_turns" in m else None,
    )
    lc = en13906_solid_length(dw, n_total, m["end_type"]) if m.get("end_type") else dw * (n_total + 0.5)
    lf = end_allowance(lc, dw, n_total) + float(np.trapezoid(p, s))  # the geometry's a + int p ds
    if "free_length" in m:
        given_lf = _quantity(m, "free_length", "m")
        if abs(given_lf - lf) > 0.005 * given_lf:
            raise InputError(
                f"free_length = {format_mm(given_lf)} and the pitches ({', '.join(f'{k} = {format_mm(v)}' for k, v in pitch.items())}) "
                f"disagree: the pitches give a free length of {format_mm(lf)} (dead coils closed, {TRANSITION_TURNS_TEXT}); "
                "they must agree within 0.5 %: give one of them"
            )
    else:
        m["free_length"] = round(lf, 12)
    if two and "installed_length" in m:
        # open coils of equal diameter deflect alike: each by (Lf - Ls) / n at set-up, if none closed
        per_coil = (_quantity(m, "free_length", "m") - _quantity(m, "installed_length", "m")) / (n_total - 2 * nb)
        if per_coil < pitch["low_pitch"] - dw:
            warnings.warn(
                f"low_pitch = {format_mm(pitch['low_pitch'])}: the low-pitch coils are not closed at the installed "
                f"length (each open coil deflects about {format_mm(per_coil)} there, their gap is "
                f"{format_mm(pitch['low_pitch'] - dw)}); the Type C model reads a two-step spring with them closed: "
                'use model = "distributed", which follows the pitch coil by coil',
                UserWarning,
                stacklevel=4,
            )
    for k in given:
        m.pop(k)
    m["pitch_profile"] = "table: " + "; ".join(f"{a!r} {b!r}" for a, b in zip(s.tolist(), p.tolist()))


def _load_points(value) -> str:
    """``[{ length, force, tolerance }, ...]`` -> ``"table: L F tol; ..."`` in SI (tolerance in N, -1: none)."""

    if isinstance(value, str) and (value == "" or value.startswith("table:")):
        return value  # none, or already read (a definition's fields given back, ValveSpring.replace)
    if isinstance(value, str) and value.lstrip().startswith("["):
        import tomllib  # (here: only a TOML array given as text in the API needs it)

        try:
            value = tomllib.loads(f"load_points = {value}")["load_points"]
        except tomllib.TOMLDecodeError as exc:
            raise InputError(f"load_points = {value!r} is not a TOML array of tables ({exc})") from None
    if not isinstance(value, list) or not value:
        raise InputError(
            f'load_points = {value!r} must be an array of tables, e.g. [{{ length = "38 mm", force = "250 N", '
            'tolerance = "5 %" }]'
        )
    rows, seen = [], []
    for i, row in enumerate(value):
        if not isinstance(row, dict):
            raise InputError(f"load_points[{i}] = {row!r} must be a table with length, force and tolerance")
        unknown = sorted(set(row) - {"length", "force", "tolerance"})
        if unknown or "length" not in row or "force" not in row:
            raise InputError(
                f"load_points[{i}] has "
                + (f"unknown key(s) {', '.join(unknown)}" if unknown else "no length or no force")
                + ": its keys are length, force and (optionally) tolerance"
            )
        length = to_si(row["length"], "m", f"load_points[{i}].length")
        force = to_si(row["force"], "N", f"load_points[{i}].force")
        if not (length > 0 and force > 0):
            raise InputError(f"load_points[{i}]: length and force must be positive")
        tol = -1.0
        if "tolerance" in row:
            t = row["tolerance"]
            try:
                tol = to_si(t, "N", f"load_points[{i}].tolerance")
            except InputError:
                tol = to_si(t, "", f"load_points[{i}].tolerance") * force  # a fraction: "5 %"
            if not tol > 0:
                raise InputError(f"load_points[{i}].tolerance = {t!r} must be positive (in % of the force or in N)")
        for j, (other_length, other_force) in enumerate(seen):
            if abs(other_length - length) <= 1e-9 and abs(other_force - force) > 1e-9:
                raise InputError(
                    f"load_points[{j}] and load_points[{i}] give two forces ({other_force:g} N and {force:g} N) at one "
                    f"length {format_mm(length)}: a drawing gives one force per length"
                )
        seen.append((length, force))
        rows.append(f"{length!r} {force!r} {tol!r}")
    return "table: " + "; ".join(rows)
