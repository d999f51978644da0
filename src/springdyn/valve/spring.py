"""The valve-spring definition: the ``[spring]`` keys, their validation, and its model.

The definition holds geometry, material and damping; the ``model`` key chooses the
equations (:mod:`springdyn.valve.model`).  The methods of the model (statics, modes,
design figures, the chain) are available on the definition too.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import cached_property

from ..core.errors import InputError
from ..core.params import Parameters, describe_value, param
from ..core.units import format_quantity
from . import formulas

__all__ = ["ValveSpring", "EXAMPLES", "MODEL_NAMES"]

#: Built-in example springs (reading notes 1.6), shipped in ``springdyn/data``.
EXAMPLES = {"one-step": "valve_one_step.toml", "two-step": "valve_two_step.toml"}

#: Names of the spring models (:data:`springdyn.valve.model.MODELS`).
MODEL_NAMES = ("type-c", "distributed")


def _mm(value: float) -> str:
    return format_quantity(value, "m", "mm")


@dataclass(frozen=True)
class ValveSpring(Parameters):
    """A helical valve spring for the MMS Type C model (one-step or two-step).

    All values SI.  Build from TOML with :meth:`from_toml` (keys as the attribute names,
    values with units such as ``"22 mm"``), from a dict with :meth:`from_dict`, or take a
    built-in example with :meth:`example`.

    Examples
    --------
    >>> s = ValveSpring.example("one-step")
    >>> round(s.internal_parameters()["Fset"], 2)
    251.43
    >>> round(float(s.static_force(s.installed_length)), 2)
    251.43
    """

    type: str = param(None, "spring kind", kind="str", choices=("one-step", "two-step"))
    mean_diameter: float = param("m", "mean coil diameter", symbol="Do", display="mm", positive=True)
    wire_diameter: float = param("m", "wire diameter", symbol="Dw", display="mm", positive=True)
    free_length: float = param("m", "free length", symbol="Lf", display="mm", positive=True)
    installed_length: float = param("m", "set-up (installed) length, valve closed", symbol="Ls", display="mm", positive=True)
    dead_coils: float = param("", "dead coils per end", symbol="Nb", nonnegative=True)
    low_pitch_coils: float = param("", "low-pitch coils (0 for one-step)", symbol="N1", nonnegative=True)
    high_pitch_coils: float = param("", "high-pitch coils", symbol="N2", positive=True)
    youngs_modulus: float = param("Pa", "Young's modulus", symbol="E", display="GPa", positive=True)
    shear_modulus: float = param("Pa", "shear modulus", symbol="G'", display="GPa", positive=True)
    density: float = param("kg/m^3", "density", symbol="rho'", positive=True)
    damping_ratio: float = param("", "damping ratio", symbol="Cps", nonnegative=True)
    model: str = param(None, "spring model: 'type-c' (the document's MMS Type C, 5 masses) or 'distributed' "
                       "(coil by coil from the geometry)", kind="str", choices=MODEL_NAMES, default="type-c")
    elements: int = param("", "wire elements of the distributed model", kind="int", default=50, positive=True)
    pitch_profile: str = param(None, "distributed model: pitch against turns from the seat end, a CSV file (columns "
                               "turns, pitch_mm) or an array of [turns, pitch] pairs (default: from the keys above)",
                               kind="str", default="")
    diameter_profile: str = param(None, "distributed model: mean coil diameter against turns from the seat end, a "
                                  "CSV file (columns turns, diameter_mm) or an array of [turns, diameter] pairs "
                                  "(default: mean_diameter throughout)", kind="str", default="")

    table = "spring"
    examples = EXAMPLES
    default_example = "one-step"

    # ------------------------------------------------------------------ construction
    @classmethod
    def _prepare(cls, mapping: dict, base_dir=None, **context) -> dict:
        """Profiles: a TOML array of ``[turns, value]`` pairs becomes an inline table (SI); a
        relative CSV path is taken from the TOML file's folder."""
        from pathlib import Path

        from ..core.units import to_si

        for key in ("pitch_profile", "diameter_profile"):
            value = mapping.get(key)
            if isinstance(value, list):
                rows = []
                for i, row in enumerate(value):
                    if not isinstance(row, list) or len(row) != 2 or isinstance(row[0], (bool, str)) \
                            or not isinstance(row[0], (int, float)):
                        raise InputError(f"{key}[{i}] = {row!r} must be a pair [turns, value], e.g. [1.5, \"7 mm\"]")
                    rows.append(f"{float(row[0])!r} {to_si(row[1], 'm', f'{key}[{i}][1]')!r}")
                mapping[key] = "table: " + "; ".join(rows)
            elif isinstance(value, str) and value and base_dir is not None and not value.startswith("table:"):
                p = Path(value)
                mapping[key] = str(p if p.is_absolute() else Path(base_dir) / p)
        return mapping

    def _validate(self) -> None:
        self._check_geometry()
        self.spring_model  # the model checks that its equations hold for this spring

    def with_model(self, model: str | None) -> "ValveSpring":
        """The same spring with another model (``None``: unchanged)."""
        return self if model is None or model == self.model else self.replace(model=model)

    @cached_property
    def spring_model(self):
        """The model of this definition (:class:`~springdyn.valve.model.SpringModel`)."""
        from .model import make_model

        return make_model(self)

    @property
    def two_step(self) -> bool:
        return self.type == "two-step"

    def _field(self, name: str) -> str:
        meta = {f.name: f.metadata for f in dataclasses.fields(self)}[name]
        return f"{name} = {describe_value(getattr(self, name), meta)}"

    def _check_geometry(self) -> None:
        if self.installed_length >= self.free_length:
            raise InputError(
                f"{self._field('installed_length')} must be shorter than {self._field('free_length')}"
            )
        if not self.two_step and self.low_pitch_coils != 0:
            raise InputError(
                f"{self._field('low_pitch_coils')} must be 0 for a one-step spring "
                "(set type = \"two-step\" for a spring with low-pitch coils)"
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
        lc = formulas.coil_contact_length(self.wire_diameter, n1, n2)
        if self.installed_length <= lc:
            raise InputError(
                f"{self._field('installed_length')} is at or below coil contact: it must be longer than the "
                f"solid length Lc = Dw (N1 + N2 + 0.5) = {_mm(lc)}"
            )

    # ------------------------------------------------------------------ the model's methods
    def internal_parameters(self) -> dict:
        """Internal parameters and model variables (SI) under the CLI's JSON keys (see the model)."""
        return self.spring_model.internal_parameters()

    def breakpoints(self) -> dict:
        """Breakpoints of the model's nonlinear element laws (see the model)."""
        return self.spring_model.breakpoints()

    @property
    def chain(self):
        """The model's chain of masses and elements (:class:`~springdyn.valve.model.Chain`)."""
        return self.spring_model.chain

    @property
    def LIMIT_FORCE_FACTOR(self) -> float:  # noqa: N802 - kept name
        return self.spring_model.LIMIT_FORCE_FACTOR

    @property
    def min_length(self) -> float:
        """Shortest length [m] the model evaluates (where the static force is 10 Fcon)."""
        return self.spring_model.min_length

    def static_state(self, length):
        """Static force [N], element compressions [m] and tangent stiffness [N/m] at a length [m]."""
        return self.spring_model.static_state(length)

    def static_force(self, length):
        """Static (massless) spring force [N] at spring length ``length`` [m]."""
        return self.spring_model.static_force(length)

    def static_stiffness(self, length):
        """Static tangent stiffness ``-dF/dL`` [N/m] at spring length ``length`` [m]."""
        return self.spring_model.static_stiffness(length)

    def length_at_force(self, force: float) -> float:
        """Spring length [m] at which the static force is ``force`` [N]."""
        return self.spring_model.length_at_force(force)

    def initial_condition(self, total_compression: float):
        """Static state at a total compression [m] (see the model)."""
        return self.spring_model.initial_condition(total_compression)

    def static_curve(self, start: float | None = None, stop: float | None = None, points: int = 400):
        """Static force and stiffness against length (:class:`~springdyn.valve.results.StaticCurve`)."""
        return self.spring_model.static_curve(start, stop, points)

    def modes(self, length: float, count: int = 5):
        """Natural frequencies [Hz], ascending, of the model linearised at ``length`` [m], ends fixed."""
        return self.spring_model.modes(length, count)

    def design_figures(self, lift: float | None = None, cam_rpm: float | None = None) -> dict:
        """Design figures at installed length, at maximum lift and at coil contact (see the model)."""
        return self.spring_model.design_figures(lift, cam_rpm)
