"""The follower at the cam: flat-faced (bucket tappet, flat lifter) or roller (``[follower]``).

The ``[follower]`` table sits in the valve-train file beside ``[valve_train]``: the
``[valve_train]`` table gives the train's kinematics and masses (ratio, lash), this one the
geometry and the materials of the cam contact that the cam checks need
(:mod:`springdyn.valve.cam.checks`): base circle, roller radius or tappet face radius, the
contact width, an optional crown, the elastic constants of cam and follower and the allowable
contact (Hertz) stress.

The follower rides on the **lobe lift** ``h`` (the ``[cam]`` table's lift), for every layout:
a bucket tappet directly, a finger follower's roller or pad and a pushrod train's lifter
through the small-rotation kinematics of :mod:`springdyn.valve.train.definition` (the follower is
taken as translating along its axis with the lobe lift; the arc a lever's contact point
describes is not modelled).

Frame and signs (:mod:`springdyn.valve.cam.checks`): the follower moves along +y above the
cam centre, the cam turns counter-clockwise; ``offset`` moves the follower axis along +x (in
the plane of motion), ``lateral_offset`` moves a flat tappet's axis along the camshaft
(the offset that makes a bucket spin).

Defaults and their sources are in :data:`DEFAULT_SOURCES` (and docs/valve-cam.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from ...core.errors import InputError
from ...core.params import Parameters, load_toml, param
from ...core.units import format_mm

__all__ = ["Follower", "FOLLOWER_KINDS", "DEFAULT_SOURCES", "STEEL_MODULUS", "STEEL_POISSON"]

#: The follower kinds: a flat face (bucket tappet, flat lifter) or a roller.
FOLLOWER_KINDS = ("flat", "roller")
#: Young's modulus of steel [Pa] (the value springdyn uses for steel throughout, as [MMS]).
STEEL_MODULUS = 206e9
#: Poisson's ratio of steel [-].
STEEL_POISSON = 0.3
#: Largest allowable contact stress the table accepts [Pa]: above the 4.0-4.6 GPa of the
#: static load ratings of rolling bearings (ISO 76), the hardest steel contacts designed for.
MAX_ALLOWABLE = 5.0e9

#: Where each default comes from (stated in the docs and the generated TOML reference).
DEFAULT_SOURCES = {
    "youngs_modulus": (
        "206 GPa, steel (the modulus springdyn uses for steel everywhere, as [MMS]); a cast-iron camshaft is softer "
        "(nodular iron about 170 GPa): give its value"
    ),
    "poisson_ratio": "0.3, steel",
    "edge_margin": (
        "1 mm: a bucket tappet's face ends in an edge chamfer or radius of about 0.5-1 mm, and the contact must "
        "stay on the flat (engineering judgement; Rothbart, Cam Design Handbook, ch. 16, names tappet diameter "
        "and offset among the factors of valve-gear design)"
    ),
}


@dataclass(frozen=True)
class Follower(Parameters):
    """The follower at the cam: flat face or roller, base circle, contact width, materials.

    See the module docstring for the frame and :data:`DEFAULT_SOURCES` for the defaults.
    Keys that belong to the other kind are an error, so that nothing is silently ignored.

    Examples
    --------
    >>> f = Follower.from_dict({"kind": "roller", "base_circle_radius": "15 mm",
    ...                         "roller_radius": "9 mm", "width": "12 mm"})
    >>> round(f.reduced_modulus / 1e9, 2)
    113.19
    """

    kind: str = param(
        None, "follower kind: flat face (bucket tappet, flat lifter) or roller", kind="str", choices=FOLLOWER_KINDS
    )
    base_circle_radius: float = param("m", "base-circle radius of the cam lobe", display="mm", positive=True)
    width: float = param(
        "m",
        "contact length of the line contact: the narrower of lobe and follower, less their edge chamfers",
        display="mm",
        positive=True,
    )
    roller_radius: float = param("m", "roller radius (roller)", display="mm", positive=True, default=None)
    face_radius: float = param(
        "m",
        "radius of the flat face (flat): the contact must stay inside it (a 33 mm bucket: 16.5 mm)",
        display="mm",
        positive=True,
        default=None,
    )
    edge_margin: float = param(
        "m",
        "flat: distance the contact must keep from the face's edge (chamfer or edge radius; default 1 mm)",
        display="mm",
        nonnegative=True,
        default=None,
    )
    crown_radius: float = param(
        "m",
        "crown radius of a crowned roller (in the axial plane) or a spherical tappet face: elliptical contact "
        "(default: none, line contact)",
        display="mm",
        positive=True,
        default=None,
    )
    offset: float = param(
        "m",
        "offset of the follower axis from the cam centre in the plane of motion (+x, the cam turning "
        "counter-clockwise with the follower above it)",
        display="mm",
        default=0.0,
    )
    lateral_offset: float = param(
        "m",
        "flat: offset of the tappet axis from the lobe's mid-plane along the camshaft (the offset that spins a bucket)",
        display="mm",
        default=0.0,
    )
    cam_youngs_modulus: float = param(
        "Pa", "Young's modulus of the cam (default 206 GPa, steel)", display="GPa", positive=True, default=STEEL_MODULUS
    )
    cam_poisson_ratio: float = param(
        "", "Poisson's ratio of the cam (default 0.3, steel)", default=STEEL_POISSON, minimum=0.0, maximum=0.5
    )
    follower_youngs_modulus: float = param(
        "Pa",
        "Young's modulus of the follower (default 206 GPa, steel)",
        display="GPa",
        positive=True,
        default=STEEL_MODULUS,
    )
    follower_poisson_ratio: float = param(
        "", "Poisson's ratio of the follower (default 0.3, steel)", default=STEEL_POISSON, minimum=0.0, maximum=0.5
    )
    allowable_contact_stress: float = param(
        "Pa",
        "allowable Hertz contact stress of the material pair (optional: the check then passes or fails)",
        display="MPa",
        positive=True,
        default=None,
        maximum=MAX_ALLOWABLE,
    )

    table = "follower"

    def _validate(self) -> None:
        where = "[follower] "
        if self.kind == "roller":
            if self.roller_radius is None:
                raise InputError(f'{where}kind = "roller" needs roller_radius (e.g. roller_radius = "9 mm")')
            given = [k for k in ("face_radius", "edge_margin") if getattr(self, k) is not None]
            if self.lateral_offset != 0.0:
                given.append("lateral_offset")
            if given:
                raise InputError(
                    f'{where}{", ".join(given)} apply to kind = "flat" (a flat face), not to a roller: remove them'
                )
            pitch = self.base_circle_radius + self.roller_radius
            if not abs(self.offset) < pitch:
                raise InputError(
                    f"{where}offset = {format_mm(self.offset)} must be smaller in magnitude than base_circle_radius "
                    f"+ roller_radius = {format_mm(pitch)} (the roller would miss the base circle)"
                )
        else:
            if self.roller_radius is not None:
                raise InputError(
                    f'{where}roller_radius applies to kind = "roller", not to a flat face: remove it or set kind'
                )
            if self.face_radius is not None and self.edge_margin is not None and self.edge_margin >= self.face_radius:
                raise InputError(
                    f"{where}edge_margin = {format_mm(self.edge_margin)} must be smaller than face_radius = "
                    f"{format_mm(self.face_radius)}"
                )
            reach = abs(self.lateral_offset) + 0.5 * self.width
            if self.face_radius is not None and reach >= self.face_radius:
                raise InputError(
                    f"{where}lateral_offset + width/2 = {format_mm(reach)} reaches beyond face_radius = "
                    f"{format_mm(self.face_radius)}: the contact line does not fit on the face"
                )
        for key in ("cam_poisson_ratio", "follower_poisson_ratio"):
            if not getattr(self, key) < 0.5:
                raise InputError(f"{where}{key} = {getattr(self, key):g} must be below 0.5 (0.5 is incompressible)")

    # -- resolved values ---------------------------------------------------------------
    @property
    def margin(self) -> float:
        """Edge margin of a flat face in use [m] (default 1 mm; 0 for a roller)."""
        if self.kind == "roller":
            return 0.0
        return 1e-3 if self.edge_margin is None else self.edge_margin

    @property
    def reduced_modulus(self) -> float:
        """Contact modulus ``E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)`` [Pa] ([Johnson] 4.2
        of docs/references.md; Hamrock's ``E'`` is ``2 E*``)."""
        return 1.0 / (
            (1.0 - self.cam_poisson_ratio**2) / self.cam_youngs_modulus
            + (1.0 - self.follower_poisson_ratio**2) / self.follower_youngs_modulus
        )

    @property
    def pitch_radius(self) -> float:
        """Distance of the roller centre from the cam centre on the base circle [m]
        (``sqrt((R_b + r)^2 - offset^2)``; a flat face: the base-circle radius)."""
        if self.kind == "flat":
            return self.base_circle_radius
        return math.sqrt((self.base_circle_radius + self.roller_radius) ** 2 - self.offset**2)

    @classmethod
    def in_file(cls, path) -> Follower | None:
        """The ``[follower]`` table of a TOML file (the valve train's), or None when it has none.

        Parameters
        ----------
        path : str or path-like
            A definition file (usually the valve train's).
        """
        doc = load_toml(path)
        if "follower" not in doc:
            return None
        return cls.from_dict(doc["follower"], source=str(path), base_dir=Path(path).parent)
