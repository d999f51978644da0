"""Spring packs: two or three concentric valve springs between one seat and one retainer.

High-speed engines run nested springs of opposite hand, often with a flat-wound friction
damper between them.  A pack file holds ``[spring]`` (the outer spring), ``[inner_spring]``
and optionally ``[third_spring]`` (each the keys of ``[spring]``: own geometry, material
and model), an optional ``[pack]`` table (hands, how to treat interfering diameters) and an
optional ``[damper]`` table (the friction damper).

Each spring becomes its own chain of masses (its model's, :mod:`.chains`); the engine runs
them side by side between the seat and the one retainer (:func:`springdyn.valve.engine.chain_forces`):
the retainer force is the sum of every chain's last element, the seat force of every first.
The lift is common; each spring keeps its own installed length (a seat step or a retainer
step gives the inner spring another one).

The friction damper is Coulomb friction, regularised (:func:`springdyn.valve.engine.damper_friction`):
a stated friction force, or a normal load times a friction coefficient, between a point of
one spring (its mass nearest the ``height`` fraction from the seat) and the seat or a
point of another spring.  Where the outer spring's inside diameter is smaller than the
inner spring's outside diameter (:func:`radial_clearance`, the coils' diameter growth
under compression included, [Wahl]), the springs touch: the pack refuses them, or,
with ``[pack] interference = "rub"`` and a ``radial_stiffness``, they rub with the normal
load of the interference (:class:`PackOptions`).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, load_toml, param
from ..engine.layout import DAMPER_SIZE
from .definition import ValveSpring
from .elements import law_stiffness
from .modes import chain_frequencies
from .solid_length import check_coil_bind
from .statics import series_force
from .stress import fatigue_assessment

__all__ = ["SpringPack", "PackOptions", "FrictionDamper", "PackModel", "PackChain", "SPRING_TABLES", "POSITIONS"]
__all__ += ["diameter_growth", "radial_clearance"]

#: The tables of a pack's springs, outer first.
SPRING_TABLES = ("spring", "inner_spring", "third_spring")
#: The springs' names in a pack, outer first.
POSITIONS = ("outer", "inner", "third")
#: The tables a pack file may hold besides the springs' (with a cam or a train in one file).
PACK_TABLES = ("pack", "damper")


@dataclass(frozen=True)
class PackOptions(Parameters):
    """The ``[pack]`` table: the springs' hands and how the pack treats interfering diameters."""

    outer_hand: str = param(
        None, "coiling hand of the outer spring", kind="str", choices=("right", "left"), default="right"
    )
    inner_hand: str = param(
        None, "coiling hand of the inner spring", kind="str", choices=("right", "left"), default="left"
    )
    third_hand: str = param(
        None, "coiling hand of the third (innermost) spring", kind="str", choices=("right", "left"), default="right"
    )
    interference: str = param(
        None,
        "springs whose diameters interfere (the outer's inside below the inner's outside): 'refuse' them, let "
        "them 'rub' (friction with the normal load of the interference times radial_stiffness), or 'ignore' the "
        "contact (a check of the equations only: no real pack)",
        kind="str",
        choices=("refuse", "rub", "ignore"),
        default="refuse",
    )
    radial_stiffness: float = param(
        "N/m",
        "radial stiffness of two interfering springs pressed together (normal load per metre of radial interference)",
        display="N/mm",
        positive=True,
        default=None,
    )
    rubbing_friction: float = param(
        "", "friction coefficient of interfering springs rubbing (steel on steel, oiled)", nonnegative=True, default=0.1
    )
    friction_velocity: float = param(
        "m/s",
        "regularising velocity of the friction laws: below it the friction force grows linearly with the sliding "
        "speed ([Andersson]; valve springs slide at metres per second)",
        display="mm/s",
        positive=True,
        default=0.01,
    )

    table = "pack"

    def hand(self, position: str) -> str:
        """The coiling hand (``right`` or ``left``) of a spring of the pack.

        Parameters
        ----------
        position : {"outer", "inner", "third"}
            The spring [-].
        """
        return getattr(self, f"{position}_hand")


@dataclass(frozen=True)
class FrictionDamper(Parameters):
    """The ``[damper]`` table: a flat-wound friction damper between the springs (or a spring and the seat).

    The friction force is stated (``friction_force``) or the product of a normal load and a
    friction coefficient (``normal_load``, ``friction_coefficient``).  It acts on the mass of
    the ``acts_on`` spring nearest the ``height`` fraction of its length from the seat,
    against the seat (the damper seated on the spring seat, pressed against the outer
    spring's inside) or the same point of another spring.
    """

    acts_on: str = param(None, "the spring the damper rubs", kind="str", choices=POSITIONS, default="outer")
    against: str = param(
        None,
        "what the damper holds: the seat, or another spring",
        kind="str",
        choices=("seat", *POSITIONS),
        default="seat",
    )
    height: float = param(
        "", "where it rubs: a fraction of the spring's length from the seat", minimum=0.0, maximum=1.0, default=0.25
    )
    friction_force: float = param("N", "the Coulomb friction force", positive=True, default=None)
    normal_load: float = param("N", "normal load of the damper on the spring", positive=True, default=None)
    friction_coefficient: float = param(
        "", "friction coefficient of the damper on the spring", positive=True, default=None
    )

    table = "damper"

    def _validate(self) -> None:
        given = self.friction_force is not None
        pair = (self.normal_load is not None, self.friction_coefficient is not None)
        if given == any(pair) or (any(pair) and not all(pair)):
            raise InputError(
                "[damper] needs friction_force, or normal_load with friction_coefficient (not both ways): "
                f"friction_force = {self.friction_force}, normal_load = {self.normal_load}, "
                f"friction_coefficient = {self.friction_coefficient}"
            )
        if self.acts_on == self.against:
            raise InputError(f"[damper] acts_on = against = {self.acts_on!r}: a damper acts between two parts")

    @property
    def force(self) -> float:
        """The Coulomb friction force [N]."""
        return self.friction_force if self.friction_force is not None else self.normal_load * self.friction_coefficient


def diameter_growth(mean_diameter, wire_diameter, active_coils, free_length, solid_length, length):
    """Growth of a helical spring's coil diameter [m] compressed from its free length to ``length``.

    The wire's length in a turn is kept: a turn of pitch ``m`` and mean diameter ``D`` has the
    length ``sqrt((pi D)^2 + m^2)``, so ``D(L)^2 = D0^2 + (m0^2 - m^2) / pi^2`` ([Wahl], the change
    of the coil diameter under deflection), with the active pitch
    ``m = (L - Lc) / n + d`` (the coils touch, ``m = d``, at the solid length ``Lc``).

    Parameters
    ----------
    mean_diameter, wire_diameter : float
        Mean coil and wire diameters [m].
    active_coils : float
        Active coils [-].
    free_length, solid_length : float
        Free and solid lengths [m].
    length : float or ndarray
        The length reached [m].
    """
    n = float(active_coils)
    m0 = (float(free_length) - solid_length) / n + wire_diameter
    m = (np.maximum(np.asarray(length, dtype=float), solid_length) - solid_length) / n + wire_diameter
    return np.sqrt(mean_diameter**2 + (m0**2 - m**2) / math.pi**2) - mean_diameter


def radial_clearance(outer: ValveSpring, inner: ValveSpring, lift: float = 0.0) -> float:
    """Radial clearance [m] between a pack's outer and inner spring at a lift; negative: they interfere.

    ``((Do - bo + growth_o) - (Di + bi + growth_i)) / 2``: the outer spring's inside
    diameter less the inner spring's outside diameter (``b`` the wire's radial width, the
    diameter of round wire), each grown by its compression from free length
    (:func:`diameter_growth`, the pitch at solid the wire's axial height).

    Parameters
    ----------
    outer, inner : ValveSpring
        The two springs (their largest mean diameter counts).
    lift : float
        Lift from the installed lengths [m].
    """

    def grown(s, dm):
        return dm + float(
            diameter_growth(dm, s.wire.height, s.active_coils, s.free_length, s.solid_length, s.installed_length - lift)
        )

    return 0.5 * (
        (grown(outer, _smallest_diameter(outer)) - outer.wire.width)
        - (grown(inner, _largest_diameter(inner)) + inner.wire.width)
    )


def _largest_diameter(spring: ValveSpring) -> float:
    big = getattr(spring.spring_model, "largest_mean_diameter", None)
    return float(big()) if callable(big) else spring.mean_diameter


def _smallest_diameter(spring: ValveSpring) -> float:
    small = getattr(spring.spring_model, "smallest_mean_diameter", None)
    return float(small()) if callable(small) else spring.mean_diameter


@dataclass(frozen=True)
class PackChain:
    """The pack's chains one after the other, as the engine reads them (:class:`springdyn.valve.engine.EngineModel`)."""

    masses: np.ndarray  #: (N,) [kg]
    laws: np.ndarray  #: (N + C, S, 4): the springs' laws, padded to the most segments
    setup_compressions: np.ndarray  #: (N + C,) [m]
    c0_array: np.ndarray  #: (N + C,) [N s/m]
    chains: np.ndarray  #: (C + 1,): each chain's first mass, then N [-]
    setup_force: float  #: the pack's force at installed length, its springs' sum [N]
    element_names: tuple  #: ``<spring>:<element>``, every chain's [-]
    mass_names: tuple  #: ``<spring>:<mass>`` [-]

    def tangent_stiffness(self, compressions) -> np.ndarray:
        """Element tangent stiffnesses [N/m] at the given compressions (every chain's).

        Parameters
        ----------
        compressions : ndarray (N + C, ...)
            Element compressions [m].
        """
        x = np.asarray(compressions, dtype=float)
        return np.stack([law_stiffness(x[j], self.laws[j]) for j in range(self.laws.shape[0])])


class SpringPack:
    """Two or three concentric springs between one seat and one retainer.

    Parameters
    ----------
    springs : sequence of ValveSpring
        Outer first; two or three.
    options : PackOptions, optional
        Hands and interference (default: outer right, inner left, third right; refuse interference).
    damper : FrictionDamper, optional
        The friction damper.

    Examples
    --------
    >>> from springdyn.valve.spring import ValveSpring
    >>> outer = ValveSpring.example("one-step")
    >>> inner = outer.replace(mean_diameter=0.0145, wire_diameter=0.0025, high_pitch_coils=8.0)
    >>> pack = SpringPack((outer, inner))
    >>> [round(f) for f in pack.setup_forces]
    [251, 210]
    """

    def __init__(self, springs, options: PackOptions | None = None, damper: FrictionDamper | None = None):
        springs = tuple(springs)
        if not 2 <= len(springs) <= 3 or not all(isinstance(s, ValveSpring) for s in springs):
            raise InputError(f"a spring pack holds two or three ValveSprings, outer first; got {len(springs)}")
        self.springs = springs
        self.options = PackOptions() if options is None else options
        self.damper = damper
        self.names = POSITIONS[: len(springs)]
        if damper is not None:
            for what in (damper.acts_on, damper.against):
                if what != "seat" and what not in self.names:
                    raise InputError(f"[damper] names the {what} spring, but the pack has {', '.join(self.names)}")
        self.fit = self._check_fit()

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_toml(cls, path) -> SpringPack:
        """The pack of a TOML file: ``[spring]``, ``[inner_spring]``, ``[third_spring]``, ``[pack]``, ``[damper]``.

        Parameters
        ----------
        path : str or path-like
            The file.
        """
        doc = load_toml(path)
        return cls.from_document(doc, source=str(path), base_dir=Path(path).parent)

    @classmethod
    def in_document(cls, doc: dict) -> bool:
        """Whether a definition document holds a pack (an ``[inner_spring]`` table).

        Parameters
        ----------
        doc : dict
            The document (:func:`springdyn.core.params.load_toml`).
        """
        return "inner_spring" in doc

    @classmethod
    def from_document(cls, doc: dict, *, source: str | None = None, base_dir=None) -> SpringPack:
        """The pack of a definition document (its tables as :func:`springdyn.core.params.load_toml` returns them).

        Parameters
        ----------
        doc : dict
            The document.
        source : str, optional
            The file, for messages.
        base_dir : path-like, optional
            Its folder (relative profile files).
        """
        where = f"{source}: " if source else ""
        if "spring" not in doc or "inner_spring" not in doc:
            raise InputError(f"{where}a spring pack needs [spring] (the outer spring) and [inner_spring]")
        if "third_spring" in doc and "inner_spring" not in doc:
            raise InputError(f"{where}[third_spring] needs [inner_spring]")
        springs = []
        for table in SPRING_TABLES:
            if table not in doc:
                continue
            try:
                springs.append(ValveSpring.from_dict(doc[table], source=source, base_dir=base_dir))
            except InputError as exc:
                raise InputError(str(exc).replace("[spring]", f"[{table}]")) from None
        options = PackOptions.from_dict(doc["pack"], source=source) if "pack" in doc else None
        damper = FrictionDamper.from_dict(doc["damper"], source=source) if "damper" in doc else None
        return cls(springs, options, damper)

    def with_model(self, model: str | None) -> SpringPack:
        """The same pack with every spring in another model.

        Parameters
        ----------
        model : {"type-c", "distributed"} or None
            The spring model (None: unchanged) [-].
        """
        if model is None:
            return self
        return SpringPack([s.with_model(model) for s in self.springs], self.options, self.damper)

    def replace_spring(self, index: int, spring: ValveSpring) -> SpringPack:
        """The same pack with one spring replaced.

        Parameters
        ----------
        index : int
            Which (0: the outer) [-].
        spring : ValveSpring
            The new spring.
        """
        springs = list(self.springs)
        springs[index] = spring
        return SpringPack(springs, self.options, self.damper)

    def spring_field(self, name: str) -> tuple[int, str]:
        """The spring and the field a design value of the pack names: ``inner_spring.wire_diameter``
        is ``(1, "wire_diameter")`` (the tables of the pack file: ``spring`` the outer,
        ``inner_spring``, ``third_spring``).  A bare field is refused: it names no spring.

        Parameters
        ----------
        name : str
            ``<table>.<field>`` [-].
        """
        tables = SPRING_TABLES[: len(self.springs)]
        table, dot, key = str(name).rpartition(".")
        if not dot:
            raise InputError(
                f"{name}: a spring pack has {len(tables)} springs; name the spring's field: "
                + " or ".join(f"{t}.{name}" for t in tables)
                + " (spring: the outer)"
            )
        if table not in tables:
            raise InputError(f"{name}: the pack has no [{table}]; its springs: {', '.join(tables)}")
        return tables.index(table), key

    def with_field(self, name: str, value: float) -> SpringPack:
        """The same pack with one spring's field changed (:meth:`spring_field`, :meth:`replace_spring`).

        Parameters
        ----------
        name : str
            ``<table>.<field>`` [-].
        value : float
            The field's new value [SI].
        """
        index, key = self.spring_field(name)
        return self.replace_spring(index, self.springs[index].replace(**{key: value}))

    def __repr__(self) -> str:
        parts = [
            f"{name} {s.model} ({s.mean_diameter * 1e3:.4g} x {s.wire_diameter * 1e3:.3g} mm, {self.options.hand(name)})"
            for name, s in zip(self.names, self.springs)
        ]
        damper = f", damper {self.damper.force:.3g} N" if self.damper is not None else ""
        return f"SpringPack({'; '.join(parts)}{damper})"

    # ------------------------------------------------------------------ what the run wing reads
    @property
    def outer(self) -> ValveSpring:
        return self.springs[0]

    @property
    def installed_length(self) -> float:
        """The outer spring's installed length [m], the reference of the lift."""
        return self.outer.installed_length

    @property
    def free_length(self) -> float:
        """The outer spring's free length [m]."""
        return self.outer.free_length

    @property
    def model(self) -> str:
        """The springs' model: ``distributed`` if any is, else ``type-c`` (it chooses the Runge-Kutta pair)."""
        return "distributed" if any(s.model == "distributed" for s in self.springs) else "type-c"

    @property
    def elements(self) -> int:
        """The fewest elements of a distributed spring of the pack [-]."""
        return min(s.elements for s in self.springs if s.model == self.model)

    @property
    def coil_facts(self) -> dict:
        """The outer spring's coils; the pack's solid length (the longest spring's)."""
        out = dict(self.outer.coil_facts)
        out["solid_length_m"] = max(s.solid_length for s in self.springs)
        out["solid_length_source"] = "the longest solid length of the pack's springs"
        return out

    @property
    def type(self) -> str:
        return "pack of " + " + ".join(s.type for s in self.springs)

    @property
    def through_solid(self) -> bool:
        return all(s.through_solid for s in self.springs)

    @cached_property
    def spring_model(self) -> PackModel:
        """The pack's chains (:class:`PackModel`)."""
        return PackModel(self)

    @property
    def setup_forces(self) -> list[float]:
        """Each spring's force at its installed length [N], outer first."""
        return [float(s.spring_model.internal_parameters()["Fset"]) for s in self.springs]

    # ------------------------------------------------------------------ statics
    def static_forces(self, lift) -> np.ndarray:
        """Each spring's static force [N], shape (springs, ...).

        Parameters
        ----------
        lift : float or array_like
            Lift(s) from the installed lengths [m].
        """
        lift = np.asarray(lift, dtype=float)
        return np.stack(
            [
                np.asarray(series_force(s.free_length - s.installed_length + lift, s.spring_model.chain.laws))
                for s in self.springs
            ]
        )

    def static_force(self, lift) -> np.ndarray:
        """The pack's static force [N]: the sum of its springs'.

        Parameters
        ----------
        lift : float or array_like
            Lift(s) from the installed lengths [m].
        """
        return self.static_forces(lift).sum(axis=0)

    def initial_displacements(self, lift: float) -> np.ndarray:
        """The chains' static mass displacements [m] from their set-up, one chain after the other.

        Parameters
        ----------
        lift : float
            Lift from the installed lengths [m].
        """
        return np.concatenate(
            [
                s.spring_model.initial_condition(s.free_length - s.installed_length + lift)["displacements"]
                for s in self.springs
            ]
        )

    def modes(self, lift: float = 0.0, count: int | None = None) -> dict:
        """Natural frequencies [Hz] of the pack's springs, ends fixed, at ``lift`` [m]: each
        spring's (the chains share only their ends, so with the retainer held the pack's modes
        are its springs' together; the friction damper is left out, as a sliding contact
        carries no stiffness).

        Parameters
        ----------
        lift : float
            Lift from the installed lengths [m].
        count : int, optional
            Frequencies per spring [-] (default: every one).

        Returns
        -------
        dict
            ``pack`` (every frequency, ascending) and one array per spring name.
        """
        out = {}
        for name, s in zip(self.names, self.springs):
            ch = s.spring_model.chain
            _, x, _ = s.spring_model.static_state(s.installed_length - float(lift))
            out[name] = chain_frequencies(ch.masses, ch.tangent_stiffness(x), count)
        out["pack"] = np.sort(np.concatenate([out[n] for n in self.names]))
        return out

    # ------------------------------------------------------------------ fit, stress, solid
    def _check_fit(self) -> dict:
        """Radial clearances of neighbouring springs, their hands; refuse, rub or ignore interference."""
        opt = self.options
        fit = {}
        for k in range(len(self.springs) - 1):
            a, b = self.names[k], self.names[k + 1]
            sa, sb = self.springs[k], self.springs[k + 1]
            lift = max(0.0, min(sa.installed_length - sa.solid_length, sb.installed_length - sb.solid_length))
            free = radial_clearance(sa, sb, 0.0)
            solid = radial_clearance(sa, sb, lift)
            worst = min(free, solid)
            fit[f"{a}_{b}"] = dict(
                radial_clearance_installed_m=free, radial_clearance_at_bind_m=solid, interference_m=max(0.0, -worst)
            )
            if opt.hand(a) == opt.hand(b):
                warnings.warn(
                    f"the {a} and {b} springs are both {opt.hand(a)}-hand: nested springs of one hand can lock "
                    f"their coils into each other; valve-spring packs wind them opposite ([pack] {b}_hand)",
                    UserWarning,
                    stacklevel=3,
                )
            if worst < 0.0 and opt.interference == "refuse":
                raise InputError(
                    f"the {a} spring's inside diameter is {-worst * 2e3:.3g} mm below the {b} spring's outside "
                    f"diameter (radial clearance {free * 1e3:.3g} mm installed, {solid * 1e3:.3g} mm at coil bind, "
                    "with the diameters' growth under compression): the springs interfere. Change the diameters, or "
                    "set [pack] interference = 'rub' with a radial_stiffness to model them rubbing"
                )
            if worst < 0.0 and opt.interference == "rub" and opt.radial_stiffness is None:
                raise InputError(
                    f"[pack] interference = 'rub' needs radial_stiffness: the {a} and {b} springs interfere by "
                    f"{-worst * 1e3:.3g} mm (radial), and the normal load is the interference times that stiffness"
                )
        return fit

    def solid_and_bind(self, lift: float) -> dict:
        """Each spring's coil-bind figures (:func:`springdyn.valve.spring.solid_length.check_coil_bind`),
        and the pack's solid height (the longest spring's solid length, seat steps aside).

        Parameters
        ----------
        lift : float
            Lift from the installed lengths [m].
        """
        out = {
            name: check_coil_bind(s, lift, f"the lift {lift * 1e3:.4g} mm ({name} spring)")
            for name, s in zip(self.names, self.springs)
        }
        out["pack_solid_length_m"] = max(s.solid_length for s in self.springs)
        return out

    def stress(self, min_force, max_force) -> dict:
        """Each spring's corrected shear stress and Goodman safety over a force cycle.

        Parameters
        ----------
        min_force, max_force : array_like (springs,)
            Each spring's smallest and largest force [N].

        Returns
        -------
        dict
            Per spring name: :func:`springdyn.valve.spring.stress.fatigue_assessment`'s figures.
        """
        return {
            name: fatigue_assessment(s, float(lo), float(hi))
            for name, s, lo, hi in zip(self.names, self.springs, min_force, max_force)
        }

    def static_figures(self, lift: float) -> dict:
        """The pack's static design figures at installed length and at a lift: each spring's
        force, corrected shear stress and static Goodman safety, the total, the modes, the fit
        and the coil bind.  Flat keys ``<spring>_<quantity>_<unit>``.

        Parameters
        ----------
        lift : float
            Lift from the installed lengths [m].
        """
        f0 = self.static_forces(0.0)
        f1 = self.static_forces(lift)
        modes = self.modes(0.0)
        out = dict(
            installed_force_N=float(f0.sum()),
            open_force_N=float(f1.sum()),
            first_mode_Hz=float(modes["pack"][0]),
            pack_solid_length_m=max(s.solid_length for s in self.springs),
        )
        bind = self.solid_and_bind(lift)
        st = self.stress(f0, f1)
        for k, (name, s) in enumerate(zip(self.names, self.springs)):
            out[f"{name}_installed_force_N"] = float(f0[k])
            out[f"{name}_open_force_N"] = float(f1[k])
            out[f"{name}_force_share"] = float(f1[k] / f1.sum())
            out[f"{name}_max_shear_stress_Pa"] = float(f1[k] * s.spring_model.stress_per_force)  # the wire's section
            out[f"{name}_goodman_safety"] = st[name]["fatigue_safety_factor"]
            out[f"{name}_first_mode_Hz"] = float(modes[name][0])
            out[f"{name}_solid_length_m"] = float(s.solid_length)
            out[f"{name}_coil_bind_margin_m"] = float(bind[name]["coil_bind_margin_m"])
        for pair, fig in self.fit.items():
            out[f"{pair}_radial_clearance_m"] = float(fig["radial_clearance_installed_m"])
            out[f"{pair}_interference_m"] = float(fig["interference_m"])
        return out

    def design_figures(self, lift: float, cam_rpm: float | None = None) -> dict:
        """The pack's design figures at a lift: each spring's own (its model's
        :meth:`~springdyn.valve.spring.chains.SpringModel.design_figures` at its installed length
        and the same lift: forces, corrected stress by its wire's factor, surge frequency and
        margin, solid length and coil bind, static Goodman) under ``springs``, and the pack's:
        ``installed_force_N`` and ``open_force_N`` (its springs' sums), each spring's share of
        the open force (``force_share``), the modes with the ends held (``modes_Hz``, ascending,
        and the spring of each, ``mode_springs``), the solid height (``pack_solid_length_m``, the
        longest spring's solid length, seat steps aside) and the fit of neighbours (``fit``,
        :func:`radial_clearance`).

        Parameters
        ----------
        lift : float
            Lift from the installed lengths [m].
        cam_rpm : float, optional
            Cam speed of the surge margins [rev/min].
        """
        springs = {n: s.spring_model.design_figures(lift, cam_rpm) for n, s in zip(self.names, self.springs)}
        installed = sum(f["installed"]["force_N"] for f in springs.values())
        opened = sum(f["open"]["force_N"] for f in springs.values())
        modes = self.modes(0.0, 3)
        tagged = sorted((f, n) for n in self.names for f in modes[n])
        return dict(
            springs=springs,
            installed_force_N=float(installed),
            open_force_N=float(opened),
            force_share={n: f["open"]["force_N"] / opened for n, f in springs.items()},
            modes_Hz=[float(f) for f, _ in tagged],
            mode_springs=[n for _, n in tagged],
            pack_solid_length_m=max(s.solid_length for s in self.springs),
            fit=self.fit,
        )

    # ------------------------------------------------------------------ the friction rows
    def node(self, name: str, height: float) -> int:
        """The pack's mass index nearest a point of a spring.

        Parameters
        ----------
        name : {"outer", "inner", "third"}
            The spring [-].
        height : float
            The point, a fraction of the spring's length from the seat [-].
        """
        k = self.names.index(name)
        first, last = self.spring_model.chain.chains[k], self.spring_model.chain.chains[k + 1]
        n = last - first
        return int(first + min(n - 1, max(0, round(height * (n + 1)) - 1)))

    def friction_rows(self) -> np.ndarray:
        """The engine's friction rows (R, DAMPER_SIZE): the damper, then interfering springs that rub."""
        opt = self.options
        rows = []
        d = self.damper
        if d is not None:
            other = -1 if d.against == "seat" else self.node(d.against, d.height)
            rows.append([self.node(d.acts_on, d.height), other, d.force, opt.friction_velocity])
        if opt.interference == "rub":
            for k in range(len(self.springs) - 1):
                a, b = self.names[k], self.names[k + 1]
                interference = self.fit[f"{a}_{b}"]["interference_m"]
                if interference > 0.0:
                    force = opt.rubbing_friction * opt.radial_stiffness * interference
                    rows.append([self.node(a, 0.5), self.node(b, 0.5), force, opt.friction_velocity])
        if not rows:
            rows.append([0.0, -1.0, 0.0, 1.0])
        return np.array(rows, dtype=float).reshape(-1, DAMPER_SIZE)


class PackModel:
    """The pack as the run wing reads a spring's model: its chains, set-up force, first modes and limits.

    Parameters
    ----------
    pack : SpringPack
        The springs.
    """

    def __init__(self, pack: SpringPack):
        self.pack = pack
        self.models = [s.spring_model for s in pack.springs]
        self.name = " + ".join(m.name for m in self.models)
        self.LIMIT_FORCE_FACTOR = self.models[0].LIMIT_FORCE_FACTOR
        self.CLASH_MARGIN = self.models[0].CLASH_MARGIN

    @cached_property
    def chain(self) -> PackChain:
        chains = [m.chain for m in self.models]
        segments = max(c.laws.shape[1] for c in chains)
        laws = []
        for c in chains:
            pad = np.zeros((c.laws.shape[0], segments - c.laws.shape[1], 4))
            pad[:, :, 0] = np.inf  # never reached: the element law's segment search stops before
            laws.append(np.concatenate([c.laws, pad], axis=1))
        starts = np.concatenate([[0], np.cumsum([len(c.masses) for c in chains])]).astype(np.int64)
        return PackChain(
            masses=np.concatenate([c.masses for c in chains]),
            laws=np.ascontiguousarray(np.concatenate(laws, axis=0)),
            setup_compressions=np.concatenate([c.setup_compressions for c in chains]),
            c0_array=np.concatenate([c.c0_array for c in chains]),
            chains=starts,
            setup_force=float(sum(c.setup_force for c in chains)),
            element_names=tuple(f"{n}:{e}" for n, c in zip(self.pack.names, chains) for e in c.element_names),
            mass_names=tuple(f"{n}:{e}" for n, c in zip(self.pack.names, chains) for e in c.mass_names),
        )

    @cached_property
    def damper(self) -> np.ndarray:
        """The engine's friction rows (:meth:`SpringPack.friction_rows`)."""
        return self.pack.friction_rows()

    def engine_arrays(self) -> tuple:
        """``(masses, laws, xset, c0, chains, damper)`` of the engine (:func:`springdyn.valve.engine.model_of`)."""
        ch = self.chain
        return ch.masses, ch.laws, ch.setup_compressions, ch.c0_array, ch.chains, self.damper

    def static_force(self, length):
        """The pack's static force [N] (the same lift for every spring).

        Parameters
        ----------
        length : float or array_like
            The outer spring's length(s) [m].
        """
        return self.pack.static_force(self.pack.installed_length - np.asarray(length, dtype=float))

    def modes(self, length: float, count: int = 5) -> np.ndarray:
        """The pack's lowest natural frequencies [Hz], ends fixed (:meth:`SpringPack.modes`).

        Parameters
        ----------
        length : float
            The outer spring's length [m] (the lift from its installed length is every spring's).
        count : int
            How many [-].
        """
        return self.pack.modes(self.pack.installed_length - float(length))["pack"][: int(count)]

    def initial_condition(self, total_compression: float) -> dict:
        """The chains' static state at the outer spring's total compression: ``displacements`` of
        every chain's masses from their set-up [m] (:meth:`SpringPack.initial_displacements`) and
        the pack's ``force`` [N].

        Parameters
        ----------
        total_compression : float
            The outer spring's ``(Lf - Ls) + lift`` [m].
        """
        lift = float(total_compression) - (self.pack.free_length - self.pack.installed_length)
        return dict(displacements=self.pack.initial_displacements(lift), force=float(self.pack.static_force(lift)))

    def internal_parameters(self) -> dict:
        """The pack's ``Fset`` and ``M`` (sums), ``f1`` and ``Fcon`` (the smallest of its springs')."""
        ps = [m.internal_parameters() for m in self.models]
        return dict(
            Fset=sum(p["Fset"] for p in ps),
            M=sum(p["M"] for p in ps),
            f1=min(p["f1"] for p in ps),
            Fcon=min(p["Fcon"] for p in ps),
        )

    @cached_property
    def contact_forces(self) -> np.ndarray:
        """Each spring's element forces at coil contact [N] (``inf``: never), one after the other."""
        return np.concatenate([m.contact_forces for m in self.models])

    def contact_compressions(self) -> np.ndarray:
        """Each spring's element compressions at coil contact [m], one after the other."""
        return np.concatenate([m.contact_compressions() for m in self.models])

    @cached_property
    def contact_gaps(self) -> np.ndarray:
        return np.ascontiguousarray(np.concatenate([m.contact_gaps for m in self.models]))

    @property
    def first_mode_installed(self) -> float:
        return min(m.first_mode_installed for m in self.models)

    def element_ranges(self) -> list[slice]:
        """Each spring's elements in the pack's element arrays (outer first)."""
        st = self.chain.chains
        return [slice(int(st[k]) + k, int(st[k + 1]) + k + 1) for k in range(len(self.models))]

    def _per_spring(self, method: str, *arrays) -> np.ndarray:
        """Apply each spring model's per-element ``method`` to its part of ``arrays`` (elements first)."""
        parts = [
            getattr(m, method)(*(np.asarray(a)[r] for a in arrays)) for m, r in zip(self.models, self.element_ranges())
        ]
        return np.concatenate(parts, axis=0)

    def element_setup_forces(self) -> np.ndarray:
        """Each element's own spring's set-up force [N] (N + C,): a coil clash in a spring is graded
        over that spring's Fset, not the pack's."""
        return np.concatenate([m.element_setup_forces() for m in self.models])

    def contact_share(self, elastic_force) -> np.ndarray:
        """Each spring's :meth:`springdyn.valve.spring.chains.SpringModel.contact_share` [N].

        Parameters
        ----------
        elastic_force : ndarray (N + C, ...)
            Elastic (law) force of each element [N].
        """
        return self._per_spring("contact_share", elastic_force)

    def wire_forces(self, compression, force) -> np.ndarray:
        """Each spring's :meth:`springdyn.valve.spring.chains.SpringModel.wire_forces` [N].

        Parameters
        ----------
        compression : ndarray (N + C, ...)
            Element compressions [m].
        force : ndarray (N + C, ...)
            Element forces [N].
        """
        return self._per_spring("wire_forces", compression, force)

    def clash(self, contact, static_force) -> np.ndarray:
        """Coil clash of each spring against its own static force at the same lift
        (:meth:`springdyn.valve.spring.chains.SpringModel.clash`); ``static_force`` is the pack's
        and is split by the springs' static shares at installed length.

        Parameters
        ----------
        contact : ndarray of bool (N + C, ...)
            Each element past its contact compression [-].
        static_force : ndarray (...)
            The pack's static force at the same instants [N].
        """
        share = np.array(self.pack.setup_forces) / sum(self.pack.setup_forces)
        parts = [
            m.clash(np.asarray(contact)[r], share[k] * np.asarray(static_force))
            for k, (m, r) in enumerate(zip(self.models, self.element_ranges()))
        ]
        return np.concatenate(parts, axis=0)

    @property
    def fastest_mode(self) -> float:
        return max(m.fastest_mode for m in self.models)

    @property
    def lift_at_coil_contact(self) -> float:
        return min(m.lift_at_coil_contact for m in self.models)

    @property
    def min_length(self) -> float:
        """The outer spring's length at which the first spring reaches its model's limit [m]."""
        lift = min(s.installed_length - m.min_length for s, m in zip(self.pack.springs, self.models))
        return self.pack.installed_length - lift
