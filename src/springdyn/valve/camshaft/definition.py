"""The ``[camshaft]`` table: a shaft with several lobes, each driving its own valve train and spring.

.. code-block:: toml

    [camshaft]
    shaft_diameter = "25 mm"          # or segment_stiffness = [...] between the nodes
    sprocket_inertia = "1.2e-3 kg*m^2"
    drive_stiffness = "10000 N*m/rad" # the timing drive, at the camshaft
    drive_damping = "0.5 N*m*s/rad"
    bearing_positions = ["20 mm", "85 mm"]

    [[camshaft.lobes]]
    name = "cylinder 1"
    position = "40 mm"                # along the shaft, from its datum
    phase = "0 deg"                   # cam angle by which this lobe's event follows the cam file's
    spring = "one_step_spring.toml"   # each lobe's own definition files (the same files may repeat)
    cam = "cam_polydyne_ramps.toml"
    valve_train = "valve_train.toml"

The shaft's nodes are the sprocket and the lobes, ordered from the sprocket (which must be at one
end: the drive is at one end); the shaft between two nodes is a torsional spring ``G I_p / L`` of
the given diameter (or the ``segment_stiffness`` given), its inertia ``rho I_p L`` shared half and
half by the two nodes (or ``segment_inertia``).  Each bearing damps the node nearest to it.
(:mod:`springdyn.valve.camshaft.shaft` holds the chain's laws.)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, load_toml, param
from ..cam.definition import Cam
from ..cam.follower import Follower
from ..spring.definition import ValveSpring
from ..train.definition import ValveTrain
from ..train.friction import Friction
from ..train.oil import oil_of
from .shaft import chain_matrices, polar_moment, segment_inertia, segment_stiffness

__all__ = ["Camshaft", "LobeDefinition", "Lobe", "read_camshaft", "ShaftChain", "shaft_chain"]

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class Camshaft(Parameters):
    """The shaft, its drive and how its periodic state is found (the ``[camshaft]`` keys; the
    lobes are the ``[[camshaft.lobes]]`` tables, :class:`LobeDefinition`)."""

    sprocket_inertia: float = param("kg*m^2", "inertia of the cam sprocket (with a phaser, if any)", positive=True)
    drive_stiffness: float = param(
        "N*m/rad", "torsional stiffness of the timing drive at the camshaft (chain or belt, tensioner)", positive=True
    )
    drive_damping: float = param("N*m*s/rad", "torsional damping of the timing drive", default=0.0, nonnegative=True)
    sprocket_position: float = param("m", "position of the sprocket along the shaft", display="mm", default=0.0)
    shaft_diameter: float = param(
        "m", "outer diameter of the shaft between the lobes (or segment_stiffness)", display="mm", default=None
    )
    shaft_bore: float = param("m", "inner diameter of a hollow shaft", display="mm", default=0.0, nonnegative=True)
    shear_modulus: float = param("Pa", "shear modulus of the shaft", display="GPa", default=80e9, positive=True)
    density: float = param("kg/m^3", "density of the shaft", default=7850.0, positive=True)
    segment_stiffness: list = param(
        "N*m/rad",
        "torsional stiffness of the shaft between consecutive nodes from the sprocket (instead of shaft_diameter)",
        kind="quantity_list",
        default=[],
        positive=True,
    )
    segment_inertia: list = param(
        "kg*m^2",
        "inertia of the shaft between consecutive nodes, shared half and half (with segment_stiffness)",
        kind="quantity_list",
        default=[],
        nonnegative=True,
    )
    lobe_inertia: float = param(
        "kg*m^2", "inertia of each lobe (a lobe's own inertia key overrides it)", default=0.0, nonnegative=True
    )
    bearing_positions: list = param("m", "positions of the bearings", display="mm", kind="quantity_list", default=[])
    bearing_damping: float = param(
        "N*m*s/rad", "viscous damping of each bearing against the head", default=0.0, nonnegative=True
    )
    rigid: bool = param(None, "a rigid shaft and drive: every valve runs as alone", kind="bool", default=False)
    timing_lift: float = param(
        "m", "valve lift at which opening and closing are read", display="mm", default=1e-3, positive=True
    )
    tolerance: float = param(
        "rad",
        "largest change of the twist between iterations at convergence",
        display="deg",
        default=math.radians(1e-3),
        positive=True,
    )
    relaxation: float = param(
        "", "under-relaxation of the twist update (1: none)", default=1.0, positive=True, maximum=1.0
    )
    feedback_frequency: float = param(
        "Hz",
        "the twist's harmonics up to this frequency act back on the valves' lift (above it the valves drive the "
        "shaft only)",
        default=1000.0,
        positive=True,
    )
    anderson_memory: int = param(
        "",
        "iterates the Anderson acceleration keeps (0: plain relaxation)",
        kind="int",
        default=6,
        minimum=0,
        maximum=50,
    )
    max_iterations: int = param("", "iterations at most", kind="int", default=30, minimum=1, maximum=500)

    table = "camshaft"
    extra_keys = ("lobes",)

    def _validate(self) -> None:
        if self.shaft_diameter is None and not self.segment_stiffness:
            raise InputError(
                'the shaft needs its stiffness: shaft_diameter (e.g. "25 mm", with shear_modulus) or segment_stiffness '
                "(one per shaft segment between the nodes, from the sprocket)"
            )
        if self.shaft_diameter is not None and self.segment_stiffness:
            raise InputError("give shaft_diameter or segment_stiffness, not both")
        if self.shaft_diameter is not None and not 0.0 <= self.shaft_bore < self.shaft_diameter:
            raise InputError(
                f"shaft_bore = {self.shaft_bore * 1e3:g} mm must be below shaft_diameter = {self.shaft_diameter * 1e3:g} mm"
            )
        if self.segment_inertia and not self.segment_stiffness:
            raise InputError("segment_inertia goes with segment_stiffness (shaft_diameter gives the shaft's inertia)")


@dataclass(frozen=True)
class LobeDefinition(Parameters):
    """One ``[[camshaft.lobes]]`` table: where the lobe sits, its phase and its valve's files."""

    position: float = param("m", "position of the lobe along the shaft", display="mm")
    spring: str = param(None, "the lobe's spring file ([spring])", kind="str")
    cam: str = param(None, "the lobe's cam file ([cam])", kind="str")
    valve_train: str = param(None, "the lobe's valve-train file ([valve_train])", kind="str")
    name: str = param(None, "what the lobe is called", kind="str", default="")
    phase: float = param(
        "rad", "cam angle by which the lobe's event follows the cam file's", display="deg", default=0.0
    )
    inertia: float = param("kg*m^2", "inertia of the lobe (default: [camshaft] lobe_inertia)", default=None)

    table = "camshaft.lobes"

    @classmethod
    def _prepare(cls, mapping: dict, *, base_dir=None, **context) -> dict:
        """Relative file names are taken from the camshaft file's folder."""
        for key in ("spring", "cam", "valve_train"):
            value = mapping.get(key)
            if isinstance(value, str) and value and base_dir is not None and not Path(value).is_absolute():
                mapping[key] = str(Path(base_dir) / value)
        return mapping


@dataclass(frozen=True, eq=False)
class Lobe:
    """A lobe on the shaft with the valve it drives (SI)."""

    name: str
    position: float  #: along the shaft [m]
    phase: float  #: cam angle by which its event follows its cam's [rad]
    inertia: float  #: [kg m^2]
    spring: ValveSpring
    cam: Cam
    valve_train: ValveTrain
    #: The follower (``[follower]`` beside the train): with it the lobe's torque has its friction.
    follower: Follower | None = None
    #: The train's ``[friction]`` (its defaults with the train's oil where the file has none).
    friction: Friction | None = None


def read_camshaft(path) -> tuple[Camshaft, tuple[Lobe, ...]]:
    """The shaft and its lobes of a camshaft file (each lobe's definition files read once).

    Parameters
    ----------
    path : str or path-like
        The TOML file with ``[camshaft]`` and its ``[[camshaft.lobes]]``.
    """
    source = str(path)
    table = dict(load_toml(path, "camshaft", allowed=("camshaft",)))
    raw = table.pop("lobes", None)
    if not isinstance(raw, list) or not raw or not all(isinstance(t, dict) for t in raw):
        raise InputError(
            f"{source}: [camshaft] needs its lobes, one [[camshaft.lobes]] table each (position, phase, spring, cam, "
            "valve_train)"
        )
    shaft = Camshaft.from_dict(table, source=source)
    base = Path(path).parent
    loaded: dict = {}

    def once(kind, file):
        key = (kind, str(Path(file).resolve()) if Path(file).exists() else file)
        if key not in loaded:
            loaded[key] = kind.from_toml(file)
        return loaded[key]

    lobes = []
    for i, t in enumerate(raw):
        d = LobeDefinition.from_dict(t, source=f"{source}: lobe {i + 1}", base_dir=base)
        vt = once(ValveTrain, d.valve_train)
        if vt.geometry is not None:
            raise InputError(
                f"{source}: lobe {i + 1}: a drawn lever ([geometry]) is not taken on a camshaft yet; give its ratio"
            )
        follower, friction = once(_Contact, d.valve_train)
        lobes.append(
            Lobe(
                name=d.name or f"lobe {i + 1}",
                position=d.position,
                phase=d.phase % TWO_PI,
                inertia=shaft.lobe_inertia if d.inertia is None else d.inertia,
                spring=once(ValveSpring, d.spring),
                cam=once(Cam, d.cam),
                valve_train=vt,
                follower=follower,
                friction=friction,
            )
        )
    return shaft, check_lobes(shaft, tuple(lobes), source)


class _Contact:
    """The follower and the friction of a valve-train file (read once per file, as the other tables)."""

    @staticmethod
    def from_toml(path):
        follower = Follower.in_file(path)
        if follower is None:
            return None, None
        doc = load_toml(path)
        friction = Friction.in_document(doc, source=str(path)) or Friction(oil=oil_of(doc, source=str(path))[0])
        return follower, friction


def check_lobes(shaft: Camshaft, lobes: tuple, source: str = "camshaft") -> tuple:
    """The lobes checked against the shaft: distinct positions, all on one side of the sprocket.

    Parameters
    ----------
    shaft : Camshaft
        The shaft.
    lobes : tuple of Lobe
        Its lobes.
    source : str
        The file, for messages.
    """
    if not lobes:
        raise InputError(f"{source}: a camshaft needs at least one lobe")
    x = np.array([lb.position for lb in lobes]) - shaft.sprocket_position
    if not (np.all(x > 0) or np.all(x < 0)):
        raise InputError(
            f"{source}: the sprocket (sprocket_position = {shaft.sprocket_position * 1e3:g} mm) drives the shaft at one "
            "end: every lobe's position must lie on one side of it"
        )
    if np.unique(np.round(x, 9)).size != x.size:
        raise InputError(f"{source}: two lobes share a position; each lobe sits at its own place along the shaft")
    n_seg = len(lobes)
    for key in ("segment_stiffness", "segment_inertia"):
        given = getattr(shaft, key)
        if given and len(given) != n_seg:
            raise InputError(
                f"{source}: [camshaft] {key} has {len(given)} values; the sprocket and {n_seg} lobes need {n_seg} "
                "(one per segment, from the sprocket)"
            )
    return lobes


@dataclass(frozen=True)
class ShaftChain:
    """The shaft as a chain: its nodes from the sprocket, their inertia, the springs between them."""

    names: tuple  #: the nodes: "sprocket", then the lobes' names from the sprocket
    position: np.ndarray  #: along the shaft [m]
    inertia: np.ndarray  #: [kg m^2]
    stiffness: np.ndarray  #: between consecutive nodes [N m/rad]
    ground_damping: np.ndarray  #: the bearings' damping at each node [N m s/rad]
    order: np.ndarray  #: node index of each lobe (in the file's order) [-]
    drive_stiffness: float
    drive_damping: float
    #: (J, K, C) of :func:`~springdyn.valve.camshaft.shaft.chain_matrices`.
    matrices: tuple = field(repr=False, default=())


def shaft_chain(shaft: Camshaft, lobes: tuple) -> ShaftChain:
    """The torsional chain of a shaft and its lobes (:func:`~springdyn.valve.camshaft.shaft.chain_matrices`).

    Parameters
    ----------
    shaft : Camshaft
        The ``[camshaft]`` table.
    lobes : tuple of Lobe
        The lobes.
    """
    x = np.array([lb.position for lb in lobes])
    dist = np.abs(x - shaft.sprocket_position)
    rank = np.argsort(dist)
    pos = np.concatenate([[shaft.sprocket_position], x[rank]])
    inertia = np.concatenate([[shaft.sprocket_inertia], [lobes[i].inertia for i in rank]])
    length = np.abs(np.diff(pos))
    if shaft.shaft_diameter is not None:
        ip = polar_moment(shaft.shaft_diameter, shaft.shaft_bore)
        k = segment_stiffness(shaft.shear_modulus, ip, length)
        js = segment_inertia(shaft.density, ip, length)
    else:
        k = np.asarray(shaft.segment_stiffness, dtype=float)
        js = np.asarray(shaft.segment_inertia or [0.0] * k.size, dtype=float)
    inertia = inertia.astype(float)
    inertia[:-1] += 0.5 * js
    inertia[1:] += 0.5 * js
    if np.any(inertia <= 0.0):
        raise InputError(
            "a node of the shaft has no inertia: give lobe_inertia (or each lobe's inertia), or the shaft's "
            "diameter or segment_inertia"
        )
    ground = np.zeros(pos.size)
    for b in shaft.bearing_positions:
        ground[int(np.argmin(np.abs(pos - b)))] += shaft.bearing_damping
    order = np.empty(len(lobes), dtype=int)
    order[rank] = np.arange(1, len(lobes) + 1)
    chain = ShaftChain(
        names=("sprocket", *(lobes[i].name for i in rank)),
        position=pos,
        inertia=inertia,
        stiffness=np.asarray(k, dtype=float),
        ground_damping=ground,
        order=order,
        drive_stiffness=shaft.drive_stiffness,
        drive_damping=shaft.drive_damping,
    )
    mats = chain_matrices(inertia, chain.stiffness, shaft.drive_stiffness, shaft.drive_damping, ground)
    object.__setattr__(chain, "matrices", mats)
    return chain
