"""Mechanism definition of a constant-force compression spring (TOML ``[cfcs]`` table)."""

from __future__ import annotations

import dataclasses

import numpy as np

from ..core.errors import InputError
from ..core.params import Parameters, param
from ..core.units import format_quantity
from .kinematics import kinematic_limit_deflection
from .pivot import FLEXURE_MODELS, bending_stiffness, default_plate_bending, flexure_stiffness, plate_modulus
from .statics import FRICTION_MODELS

__all__ = ["CFCSParams", "EXAMPLES"]

#: Built-in examples: name -> TOML file in ``springdyn/data``.
EXAMPLES = {"table1": "cfcs_table1.toml"}

_PIVOT_DIMENSIONS = ("pivot_width", "pivot_thickness", "pivot_length")


#: Largest shear angle alpha of Eq. (22) springdyn accepts [rad] (about 17 deg; the
#: expression needs r2 alpha < r3 and is a small-angle one).
MAX_SHEAR_ANGLE = 0.3


@dataclasses.dataclass(frozen=True)
class CFCSParams(Parameters):
    """Parameters of the pseudo-rigid-body model of a CFCS (Table 1 of the CFCS paper).

    The pivot stiffness is given either directly (``torsional_stiffness``) or by the
    flexure dimensions ``pivot_width``, ``pivot_thickness``, ``pivot_length`` with
    ``youngs_modulus`` (``K3 = E b h^3 / (12 l)``), never both.
    """

    crank_length: float = param("m", "crank length", symbol="r2", display="mm", positive=True)
    coupler_length: float = param("m", "coupler length", symbol="r3", display="mm", positive=True)
    crank_mass: float = param("kg", "crank mass", symbol="m2", positive=True)
    coupler_mass: float = param("kg", "coupler mass", symbol="m3", positive=True)
    slider_mass: float = param("kg", "slider mass", symbol="ms", positive=True)
    torsional_stiffness: float | None = param(
        "N*m/rad", "pivot torsional stiffness", default=None, symbol="K3", positive=True
    )
    pivot_width: float | None = param(
        "m", "flexural pivot width", default=None, symbol="b", display="mm", positive=True
    )
    pivot_thickness: float | None = param(
        "m", "flexural pivot thickness", default=None, symbol="h", display="mm", positive=True
    )
    pivot_length: float | None = param(
        "m", "flexural pivot length", default=None, symbol="l", display="mm", positive=True
    )
    youngs_modulus: float | None = param(
        "Pa", "Young's modulus of the pivot", default=None, symbol="E", display="GPa", positive=True
    )
    allowable_stress: float | None = param(
        "Pa", "allowable bending stress of the pivot", default=None, display="GPa", positive=True
    )
    pin_friction: float = param("N*m", "Coulomb torque of a pin", default=0.0, symbol="C", nonnegative=True)
    shear_angle: float = param(
        "rad", "shear angle of the axial-force term", default=0.0, symbol="alpha", nonnegative=True
    )
    friction_model: str = param(None, "pin friction model", default="paper", kind="str", choices=FRICTION_MODELS)
    axial_force: bool = param(None, "include tau_AF (Eq. 22)", default=True, kind="bool")
    slider_friction: float = param("N", "Coulomb friction force of the slider", default=0.0, nonnegative=True)
    flexure_model: str = param(
        None,
        "bending model of the flexure: 'prbm' (pin with K3 = EI/l, Eq. (1)) or 'beam' "
        "(large-deflection elastica of the strip)",
        default="prbm",
        kind="str",
        choices=FLEXURE_MODELS,
    )
    plate_bending: bool | None = param(
        None,
        "bend the strip as a plate, E/(1 - nu^2); default: true for the beam "
        "model when pivot_width >= pivot_length, false for the PRBM (Eq. (1))",
        default=None,
        kind="bool",
    )
    poisson_ratio: float = param(
        "", "Poisson's ratio of the flexure (plate bending)", default=0.3, symbol="nu", minimum=0.0, maximum=0.49
    )
    drive_stiffness: float | None = param(
        "N/m",
        "stiffness of what drives the slider (the compliant drive of the driven model, "
        "springdyn.cfcs.drive); unset: the slider follows x(t) rigidly (inverse dynamics)",
        default=None,
        symbol="k_d",
        positive=True,
    )
    drive_damping: float = param(
        "N*s/m", "damping of what drives the slider (with drive_stiffness)", default=0.0, symbol="c_d", nonnegative=True
    )
    toggle_cutoff: float = param(
        "rad",
        "toggle zone: below this crank angle tau_CF, tau_AF use dx/dtheta2 at the cut-off",
        default=float(np.radians(5.0)),
        display="deg",
        positive=True,
    )

    def _validate(self) -> None:
        r2, r3 = self.crank_length, self.coupler_length
        if not r2 < r3:
            raise InputError(
                f"crank_length = {format_quantity(r2, 'm', 'mm')} must be shorter than coupler_length = "
                f"{format_quantity(r3, 'm', 'mm')} (the slider-crank needs r2 < r3)"
            )
        if not abs(self.shear_angle) <= MAX_SHEAR_ANGLE:
            raise InputError(
                f"shear_angle = {self.shear_angle:g} rad must lie within +-{MAX_SHEAR_ANGLE:g} rad: Eq. (22) of "
                "[CFCS] is a small-angle expression (the shear angle of a flexure is a few degrees)"
            )
        dims = {k: getattr(self, k) for k in _PIVOT_DIMENSIONS}
        given = [k for k, v in dims.items() if v is not None]
        if self.torsional_stiffness is not None and given:
            raise InputError(
                f"both torsional_stiffness and pivot dimensions ({', '.join(given)}) are given; give either "
                "torsional_stiffness or pivot_width, pivot_thickness, pivot_length and youngs_modulus"
            )
        if self.torsional_stiffness is None:
            missing = [k for k, v in dims.items() if v is None]
            if self.youngs_modulus is None:
                missing.append("youngs_modulus")
            if len(missing) == len(_PIVOT_DIMENSIONS) + 1:
                raise InputError(
                    "neither torsional_stiffness nor the pivot dimensions are given; give either "
                    'torsional_stiffness = "2.5308 N*m/rad" or pivot_width, pivot_thickness, pivot_length '
                    "and youngs_modulus"
                )
            if missing:
                raise InputError(f"the flexural pivot needs {', '.join(missing)} (or give torsional_stiffness)")
        if self.flexure_model == "beam" and not self.has_flexure:
            raise InputError(
                "flexure_model = 'beam' needs the strip: give pivot_width, pivot_thickness, pivot_length and "
                "youngs_modulus instead of torsional_stiffness"
            )
        if self.plate_bending and not self.has_flexure:
            raise InputError(
                "plate_bending = true needs the flexure dimensions (pivot_width, pivot_thickness, "
                "pivot_length, youngs_modulus), not torsional_stiffness"
            )
        if self.has_flexure and not self.pivot_thickness < self.pivot_length:
            raise InputError(
                f"pivot_thickness = {format_quantity(self.pivot_thickness, 'm', 'mm')} must be smaller than "
                f"pivot_length = {format_quantity(self.pivot_length, 'm', 'mm')}: the flexure is a thin strip (bending "
                "theory needs a length of several thicknesses)"
            )
        if self.has_flexure:
            with np.errstate(over="ignore"):
                ei = (
                    np.float64(self.youngs_modulus)
                    * np.float64(self.pivot_width)
                    * np.float64(self.pivot_thickness) ** 3
                )
            if not np.isfinite(ei / 12.0 / self.pivot_length):
                raise InputError(
                    "youngs_modulus x pivot_width x pivot_thickness^3 overflows: the flexure's bending stiffness is "
                    f"not a finite number (pivot_thickness = {format_quantity(self.pivot_thickness, 'm', 'mm')}, "
                    f"pivot_width = {format_quantity(self.pivot_width, 'm', 'mm')}); check their units"
                )
        if self.has_flexure and not self.pivot_length < 2.0 * self.coupler_length:
            raise InputError(
                f"pivot_length = {format_quantity(self.pivot_length, 'm', 'mm')} must be shorter than twice "
                f"coupler_length = {format_quantity(self.coupler_length, 'm', 'mm')} (the PRBM pin sits at the middle "
                "of the strip)"
            )
        if self.drive_damping > 0 and self.drive_stiffness is None:
            raise InputError(
                f"drive_damping = {self.drive_damping:g} N*s/m needs drive_stiffness (the drive's spring, e.g. "
                '"20 kN/m"): a drive of damping alone does not hold the slider'
            )
        if not self.toggle_cutoff < np.pi / 2:
            raise InputError(
                f"toggle_cutoff = {format_quantity(self.toggle_cutoff, 'rad', 'deg')} must be below 90 deg "
                "(the kinematic limit)"
            )

    table = "cfcs"
    examples = EXAMPLES
    default_example = "table1"

    # -- derived values -----------------------------------------------------------------
    @property
    def r2(self) -> float:
        return self.crank_length

    @property
    def r3(self) -> float:
        return self.coupler_length

    @property
    def k3(self) -> float:
        """Pivot stiffness K3 [N*m/rad] of the PRBM, given or from the flexure (Eq. (1)).

        With the flexure dimensions, ``K3 = E b h^3 / (12 l)`` (Eq. (1), beam modulus) unless
        ``plate_bending = true`` is set explicitly (then E / (1 - nu^2)).
        """
        if self.torsional_stiffness is not None:
            return self.torsional_stiffness
        return float(
            flexure_stiffness(self.bending_modulus("prbm"), self.pivot_width, self.pivot_thickness, self.pivot_length)
        )

    def uses_plate_bending(self, model: str | None = None) -> bool:
        """Whether the strip bends as a plate in ``model`` (default: this mechanism's flexure model).

        An explicit ``plate_bending`` holds for both models; unset, the beam model chooses by
        the width/length ratio (:func:`springdyn.cfcs.pivot.default_plate_bending`) and the PRBM
        keeps Eq. (1) of [CFCS] (beam modulus).

        Parameters
        ----------
        model : str, optional
            ``prbm`` or ``beam`` (default: this mechanism's) [-].
        """
        model = model or self.flexure_model
        if self.plate_bending is not None:
            return bool(self.plate_bending)
        if model == "beam" and self.has_flexure:
            return default_plate_bending(self.pivot_width, self.pivot_length)
        return False

    def bending_modulus(self, model: str | None = None) -> float | None:
        """E or E / (1 - nu^2) [Pa] of the strip in ``model``; None without the flexure.

        Parameters
        ----------
        model : str, optional
            ``prbm`` or ``beam`` (default: this mechanism's) [-].
        """
        if self.youngs_modulus is None:
            return None
        if self.uses_plate_bending(model):
            return float(plate_modulus(self.youngs_modulus, self.poisson_ratio))
        return self.youngs_modulus

    def bending_stiffness(self, model: str | None = None) -> float:
        """EI [N*m^2] of the strip in ``model`` (``K3 l`` when only K3 is given).

        Parameters
        ----------
        model : str, optional
            ``prbm`` or ``beam`` (default: this mechanism's) [-].
        """
        if not self.has_flexure:
            raise InputError(
                "the strip's bending stiffness needs pivot_width, pivot_thickness, pivot_length and youngs_modulus"
            )
        return float(bending_stiffness(self.bending_modulus(model), self.pivot_width, self.pivot_thickness))

    @property
    def has_flexure(self) -> bool:
        """True when the flexure dimensions (and so the bending stress) are known."""
        return self.torsional_stiffness is None

    @property
    def extended_length(self) -> float:
        """``r2 + r3`` [m], the slider distance at the toggle (zero deflection)."""
        return self.crank_length + self.coupler_length

    @property
    def max_deflection(self) -> float:
        """Kinematic limit of the slider deflection [m]."""
        return float(kinematic_limit_deflection(self.r2, self.r3))

    def values(self) -> dict:
        """The SI values the physics functions take (see :mod:`springdyn.cfcs.dynamics`)."""
        return dict(
            r2=self.r2,
            r3=self.r3,
            m2=self.crank_mass,
            m3=self.coupler_mass,
            ms=self.slider_mass,
            k3=self.k3,
            pin_friction=self.pin_friction,
            friction_model=self.friction_model,
            shear_angle=self.shear_angle,
            axial_force=self.axial_force,
            slider_friction=self.slider_friction,
        )

    def without_dissipation(self) -> CFCSParams:
        """The same mechanism with tau_CF, tau_AF and slider friction switched off."""
        return self.replace(friction_model="none", axial_force=False, slider_friction=0.0)
