"""Valve springs designed from requirements: the ``[requirements]`` table and :func:`synthesize`.

A spring engineer starts from two load points and the space, not from a spring.  The search:

1. **Candidates.**  Every wire diameter of the grid (standard sizes, 0.05 mm apart), every
   mean coil diameter that fits the space (``D + d <= max_outer_diameter``,
   ``D - d >= min_inner_diameter``, 0.1 mm apart) and the kinds: one-step (constant pitch)
   and two-step springs with 1, 1.5 or 2 low-pitch coils that are closed at the installed
   length (the MMS Type C two-step spring: its rate in service is that of the ``N2 - Nb``
   high-pitch coils; the low-pitch coils lower its surge frequency's sensitivity and add
   the low rate from free to installed length).
2. **Load points.**  The working rate ``k = (F_open - F_installed) / lift`` fixes the active
   coils (``k = G d^4 / (8 D^3 n)``, :func:`springdyn.valve.spring.formulas.free_length_stiffness`),
   the installed force the free length (``F_set = K1 (Lf - L_inst)``,
   :func:`springdyn.valve.spring.formulas.setup_force`): the standard's linear rates meet both load
   points exactly.  Each candidate that is kept is built as a
   :class:`~springdyn.valve.spring.definition.ValveSpring` with the transition coils
   (``transition_turns``) at which the distributed model, coil by coil, meets the load points within
   half their tolerance (:func:`choose_transition`); its forces by the standard, the distributed
   model and Type C are stated (:func:`load_point_forces`), and where Type C's stiffening starts
   inside the working stroke while the coils are open, so is that (:func:`type_c_stiffening_note`).
3. **Requirements as margins** (:data:`MARGINS`, each a fraction, >= 0 where met): the
   space, the coil-bind clearance at the open length (EN 13906-1's dynamic clearance, 1.5 Sa
   cold coiled or 2 Sa hot coiled, by default), the Goodman safety between the two load points (:mod:`springdyn.valve.spring.stress`,
   the material's strengths), the stress at solid length against EN 13906-1's permissible
   ``0.5 Rm`` (cold-coiled springs), the spring index ``4 <= D/d <= 16``, and the surge
   frequency when asked.
4. **Ranking.**  Among the candidates that meet every requirement, the lightest first (the
   spring's mass is moving mass of the valve train: a third of it at the retainer).
5. **Dynamics.**  With a cam (and a valve train), the best candidates of each kind are run
   with the distributed model over the speed range: float speed, peak retainer force, coil
   clash (:func:`springdyn.valve.float_speed`, :func:`springdyn.valve.simulate`).  They are
   run lightest first and the runs screen (issue 42): once a candidate meets every
   requirement no heavier one is run (it cannot rank above it), one that misses a
   requirement already gets no float search, and one whose Goodman safety at a round's worst
   speeds already misses and lies below the round's best goes no further (:class:`_Probe`);
   ``judge_all`` runs everything.  The first candidate is the same either way.

Infeasible requirements get a message that names the binding requirements and how far the
best candidate misses each (:func:`infeasibility`).
"""

from __future__ import annotations

import dataclasses
import warnings
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...core.errors import InputError
from ...core.io import atomic_open, dumps_toml, output_set
from ...core.params import Parameters, load_toml, param
from ...core.results import Result, notes_lines, text_table
from ...core.units import format_mm, omega_to_rpm
from ..cam.definition import Cam
from ..run.float_search import float_speed
from ..run.periodicity import PeriodicStates
from ..run.sweeps import sweep
from ..spring import formulas, solid_length, stress
from ..spring.definition import END_TYPES, ValveSpring
from ..spring.materials import material
from ..train.definition import ValveTrain
from . import criteria

__all__ = [
    "Requirements",
    "MARGINS",
    "TWO_STEP_LOW_PITCH_COILS",
    "candidate_table",
    "infeasibility",
    "synthesize",
    "Synthesis",
    "evaluate",
    "read_requirements",
    "spring_table",
    "write_candidates",
    "choose_transition",
    "load_point_forces",
    "load_point_lines",
    "type_c_stiffening_note",
]

#: Low-pitch coils of the two-step candidates beyond the seat's dead coils [-] (the low-pitch
#: coils include the seat's dead coil).
TWO_STEP_LOW_PITCH_COILS = (0.5, 1.0, 1.5)
#: Spring index range of cold-coiled compression springs (EN 13906-1: ``4 <= w <= 20``;
#: valve springs keep it below 16, where the coils stay stable in coiling) [-].
INDEX_RANGE = (4.0, 16.0)
#: EN 13906-1's permissible (uncorrected) shear stress at solid length of cold-coiled
#: springs, a fraction of the tensile strength [-].
SOLID_STRESS_FRACTION = 0.5
#: The requirements judged for every candidate, as margins (a fraction; >= 0 where met; each
#: the rule of :data:`springdyn.valve.design.criteria.RULES` named beside it).
MARGINS = {
    "outer_diameter": "outer_diameter: 1 - (D + d) / max_outer_diameter",
    "inner_diameter": "inner_diameter: (D - d) / min_inner_diameter - 1",
    "coil_bind": "coil_bind: (open length - solid length) / clearance - 1",
    "goodman": "goodman: Goodman safety / min_goodman_safety - 1",
    "solid_stress": "solid_stress: 1 - stress at solid length / (0.5 Rm)",
    "spring_index": "spring_index: distance of D/d inside 4-16, over 4",
    "surge": "surge_margin: f1 / min_surge_frequency - 1 (with min_surge_frequency)",
}


@dataclass(frozen=True)
class Requirements(Parameters):
    """The ``[requirements]`` table: load points, space, material and the dynamic asks."""

    installed_length: float = param("m", "installed length (valve closed)", display="mm", positive=True)
    installed_force: float = param("N", "force at the installed length", positive=True)
    lift: float = param(
        "m", "valve lift: the spring's compression from the installed length", display="mm", positive=True
    )
    open_force: float = param("N", "force at the installed length less the lift (valve open)", positive=True)
    max_outer_diameter: float = param(
        "m", "largest outer coil diameter (the spring pocket)", display="mm", positive=True
    )
    min_inner_diameter: float = param(
        "m", "smallest inner coil diameter (the valve guide and stem seal inside)", display="mm", positive=True
    )
    min_coil_bind_clearance: float = param(
        "m",
        "smallest margin from the open length to the solid length (default: EN 13906-1's dynamic clearance, "
        "1.5 Sa cold coiled, 2 Sa hot coiled)",
        display="mm",
        nonnegative=True,
        default=None,
    )
    material: str = param(
        None,
        "wire: a name of springdyn.valve.spring.materials (SiCr, SiCrV, CrV, music-wire), or 'custom' with the values below",
        kind="str",
        default="SiCr",
    )
    shear_modulus: float = param(
        "Pa", "shear modulus (overrides the material's)", display="GPa", positive=True, default=None
    )
    youngs_modulus: float = param(
        "Pa", "Young's modulus (overrides the material's)", display="GPa", positive=True, default=None
    )
    density: float = param("kg/m^3", "density (overrides the material's)", positive=True, default=None)
    tensile_strength: float = param(
        "Pa",
        "tensile strength (overrides the material's, which depends on the wire diameter)",
        display="MPa",
        positive=True,
        default=None,
    )
    end_type: str = param(
        None,
        "coil ends (sets dead coils and solid length, EN 13906-1)",
        kind="str",
        choices=tuple(END_TYPES),
        default="closed-ground",
    )
    coiling: str = param(
        None,
        "how the springs are wound: 'cold' or 'hot' (EN 13906-1's Sa and its dynamic factor; default: hot for "
        "tapered ends, else cold)",
        kind="str",
        choices=("", *solid_length.COILINGS),
        default="",
    )
    load_point_tolerance: float = param(
        "",
        "tolerance of both load points, a fraction or '3 %' (springdyn's default; give the drawing's): each "
        "candidate meets the load points by the standard's linear rate exactly and in the distributed model "
        "within half of it",
        positive=True,
        default=0.03,
    )
    min_goodman_safety: float = param(
        "",
        "smallest Goodman safety between the two load points (1.1-1.3 in spring practice)",
        positive=True,
        default=criteria.MIN_GOODMAN_SAFETY,
    )
    min_surge_frequency: float = param(
        "Hz", "smallest first surge frequency at the installed length", positive=True, default=None
    )
    min_float_cam_rpm: float = param(
        "rad/s",
        "smallest float speed (needs cam and valve_train)",
        display="rpm",
        bare_unit="rpm",
        positive=True,
        default=None,
    )
    cam: str = param(None, "cam file (a [cam] table) for the dynamic checks", kind="str", default="")
    valve_train: str = param(
        None, "valve-train file (a [valve_train] table) for the float speed", kind="str", default=""
    )
    min_cam_rpm: float = param(
        "rad/s", "lowest cam speed of the dynamic checks", display="rpm", bare_unit="rpm", positive=True, default=None
    )
    max_cam_rpm: float = param(
        "rad/s", "highest cam speed of the dynamic checks", display="rpm", bare_unit="rpm", positive=True, default=None
    )
    damping_ratio: float = param("", "damping ratio written into the candidates", nonnegative=True, default=0.05)
    min_wire_diameter: float = param("m", "smallest wire of the search", display="mm", positive=True, default=2.0e-3)
    max_wire_diameter: float = param("m", "largest wire of the search", display="mm", positive=True, default=6.0e-3)

    table = "requirements"

    def _validate(self) -> None:
        where = "[requirements] "
        if not self.open_force > self.installed_force:
            raise InputError(
                f"{where}open_force = {self.open_force:g} N must exceed installed_force = {self.installed_force:g} N "
                "(a compression spring's force rises as the valve opens)"
            )
        if not self.lift < self.installed_length:
            raise InputError(
                f"{where}lift = {format_mm(self.lift)} must be below installed_length = {format_mm(self.installed_length)}"
            )
        if not self.min_inner_diameter < self.max_outer_diameter:
            raise InputError(
                f"{where}min_inner_diameter = {format_mm(self.min_inner_diameter)} must be below max_outer_diameter = "
                f"{format_mm(self.max_outer_diameter)}"
            )
        if not self.load_point_tolerance <= 0.5:
            raise InputError(
                f"{where}load_point_tolerance = {self.load_point_tolerance:g} must be at most 0.5 (50 %): a fraction "
                "of the load points' forces, e.g. '3 %'"
            )
        if self.coiling == "cold" and self.end_type == "tapered":
            raise InputError(f"{where}coiling = 'cold' with end_type = 'tapered': tapered bar ends are hot coiled")
        if not self.min_wire_diameter < self.max_wire_diameter:
            raise InputError(f"{where}min_wire_diameter must be below max_wire_diameter")
        if self.min_float_cam_rpm is not None and not (self.cam and self.valve_train):
            raise InputError(
                f"{where}min_float_cam_rpm needs cam and valve_train (files): the float speed is the train's"
            )
        if (self.min_cam_rpm is None) != (self.max_cam_rpm is None):
            raise InputError(f"{where}min_cam_rpm and max_cam_rpm go together (the speed range of the dynamic checks)")
        if self.min_cam_rpm is not None and not self.min_cam_rpm < self.max_cam_rpm:
            raise InputError(f"{where}min_cam_rpm must be below max_cam_rpm")
        if self.cam and self.min_cam_rpm is None:
            raise InputError(f"{where}cam needs the speed range min_cam_rpm and max_cam_rpm")
        if self.material.lower() == "custom":
            missing = [
                k
                for k in ("shear_modulus", "youngs_modulus", "density", "tensile_strength")
                if getattr(self, k) is None
            ]
            if missing:
                raise InputError(f"{where}material = 'custom' needs {', '.join(missing)}")
        else:
            material(self.material)  # an unknown name: its message lists the names

    @property
    def open_length(self) -> float:
        """Spring length with the valve open [m]."""
        return self.installed_length - self.lift

    @property
    def rate(self) -> float:
        """Working rate between the load points [N/m]."""
        return (self.open_force - self.installed_force) / self.lift

    @property
    def coiling_process(self) -> str:
        """How the springs are wound, ``coiling`` or by the end type
        (:func:`springdyn.valve.spring.solid_length.coiling_of`)."""
        return solid_length.coiling_of(self)

    @property
    def dead_coils(self) -> float:
        """Dead coils per end of the end type [-] (EN 13906-1)."""

        return END_TYPES[self.end_type]

    def wire(self, wire_diameter) -> dict:
        """The wire's values at a diameter: ``shear_modulus`` [Pa], ``youngs_modulus`` [Pa],
        ``density`` [kg/m^3], ``tensile_strength`` [Pa] (the table's keys override the material's).

        Parameters
        ----------
        wire_diameter : float or ndarray
            Wire diameter [m].
        """
        keys = ("shear_modulus", "youngs_modulus", "density", "tensile_strength")
        if self.material.lower() == "custom":
            out = {}
        else:
            m = material(self.material)
            d = np.asarray(wire_diameter, dtype=float)
            out = dict(
                shear_modulus=m.shear_modulus,
                youngs_modulus=m.youngs_modulus,
                density=m.density,
                tensile_strength=m.tensile_strength(d),
            )
        for k in keys:
            if getattr(self, k) is not None:
                out[k] = getattr(self, k)
        return out

    def speeds(self, count: int = 25) -> np.ndarray | None:
        """Cam speeds of the dynamic checks [rev/min] (None without a range).

        Parameters
        ----------
        count : int
            Speeds over the range [-].
        """
        if self.min_cam_rpm is None:
            return None
        return np.linspace(omega_to_rpm(self.min_cam_rpm), omega_to_rpm(self.max_cam_rpm), count)


def candidate_table(req: Requirements) -> dict:
    """Every candidate of the search with its geometry and its margins (vectorised).

    Parameters
    ----------
    req : Requirements
        The requirements.

    Returns
    -------
    dict
        Arrays over the candidates: ``kind`` (0 one-step, 1 two-step), ``wire_diameter``,
        ``mean_diameter`` [m], ``low_pitch_coils``, ``high_pitch_coils`` [-],
        ``free_length`` [m], ``mass`` [kg], ``surge_frequency`` [Hz], ``goodman`` [-], the
        margins of :data:`MARGINS` (``margin_<name>``) and ``worst`` (the smallest margin).
    """
    step_d, step_dm = 0.05e-3, 0.1e-3
    wires = np.round(np.arange(req.min_wire_diameter, req.max_wire_diameter + 0.5 * step_d, step_d), 7)
    rows = []
    for d in wires:
        lo = req.min_inner_diameter + d
        hi = req.max_outer_diameter - d
        # a little outside the space too: the margins then say how far a design misses it
        means = np.round(np.arange(max(lo - 1.0e-3, 2.0 * d), hi + 1.0e-3 + 0.5 * step_dm, step_dm), 7)
        for dm in means:
            for n1 in (0.0, *(req.dead_coils + x for x in TWO_STEP_LOW_PITCH_COILS)):
                rows.append((d, dm, n1))
    if not rows:
        raise InputError("[requirements]: no wire and coil diameter to search (check the diameters)")
    a = np.array(rows)
    d, dm, n1 = a[:, 0], a[:, 1], a[:, 2]
    two = n1 > 0
    g = req.wire(d)["shear_modulus"]
    nb = req.dead_coils
    # the working rate: one-step N1 + N2 - 2 Nb active coils, two-step N2 - Nb ([MMS] K2)
    n_work = formulas.active_coils_for_rate(g, d, dm, req.rate)
    n2 = np.where(two, n_work + nb, n_work + 2.0 * nb)
    k1 = formulas.free_length_stiffness(g, d, dm, np.maximum(n1 + n2 - 2.0 * nb, 1e-9))
    lf = req.installed_length + req.installed_force / k1  # F_set = K1 (Lf - Ls), formulas.setup_force
    return evaluate(req, d, dm, n1, n2, lf)


def evaluate(req: Requirements, d, dm, n1, n2, lf) -> dict:
    """Mass, surge frequency, Goodman safety and the margins of :data:`MARGINS` of springs
    (vectorised; :func:`candidate_table` for its outputs).

    Parameters
    ----------
    req : Requirements
        The requirements.
    d, dm : array_like
        Wire and mean coil diameters [m].
    n1, n2 : array_like
        Low- and high-pitch coils [-].
    lf : array_like
        Free lengths [m].
    """
    d, dm, n1, n2, lf = (np.atleast_1d(np.asarray(x, dtype=float)) for x in (d, dm, n1, n2, lf))
    two = n1 > 0
    w = req.wire(d)
    g, rho, rm = w["shear_modulus"], w["density"], np.broadcast_to(w["tensile_strength"], d.shape)
    nb = req.dead_coils
    n_work = np.where(two, n2 - nb, n1 + n2 - 2.0 * nb)
    total = n1 + n2
    mass = formulas.total_mass(rho, dm, d, n1, n2)
    solid = solid_length.en13906_solid_length(d, total, req.end_type)
    clearance = (
        req.min_coil_bind_clearance
        if req.min_coil_bind_clearance is not None
        else solid_length.dynamic_sum_of_gaps(dm, d, n_work, req.coiling_process)
    )
    index = dm / d
    tau_lo = stress.corrected_shear_stress(req.installed_force, dm, d)
    tau_hi = stress.corrected_shear_stress(req.open_force, dm, d)
    tau_u = stress.ultimate_shear_strength(rm)
    tau_e = stress.zimmerli_endurance_shear_strength(tau_u, peened=True)
    goodman = stress.goodman_safety_factor(tau_lo, tau_hi, tau_e, tau_u)
    f_solid = req.installed_force + req.rate * (req.installed_length - solid)  # the working rate to solid
    tau_solid = stress.nominal_shear_stress(f_solid, dm, d)  # uncorrected (EN 13906-1 at solid length)
    surge = formulas.surge_frequency(g, rho, d, dm, n_work)
    margins = dict(
        outer_diameter=criteria.margin("outer_diameter", dm + d, req.max_outer_diameter),
        inner_diameter=criteria.margin("inner_diameter", dm - d, req.min_inner_diameter),
        coil_bind=criteria.margin("coil_bind", req.open_length - solid, np.maximum(clearance, 1e-4)),
        goodman=criteria.margin("goodman", goodman, req.min_goodman_safety),
        solid_stress=criteria.margin("solid_stress", tau_solid, SOLID_STRESS_FRACTION * rm),
        spring_index=criteria.margin("spring_index", index, INDEX_RANGE),
    )
    if req.min_surge_frequency is not None:
        margins["surge"] = criteria.margin("surge_margin", surge, req.min_surge_frequency)
    worst = np.min(np.stack(list(margins.values())), axis=0)
    physical = (n_work >= 2.0) & (lf > req.installed_length)
    out = dict(
        kind=two.astype(int),
        wire_diameter=d,
        mean_diameter=dm,
        low_pitch_coils=n1,
        high_pitch_coils=n2,
        active_coils=n_work,
        free_length=lf,
        solid_length=solid,
        mass=mass,
        surge_frequency=surge,
        goodman=goodman,
        tensile_strength=rm,
        physical=physical,
    )
    out.update({f"margin_{k}": v for k, v in margins.items()})
    out["worst"] = np.where(physical, worst, -np.inf)
    return out


def infeasibility(table: dict, req: Requirements) -> str:
    """The message of requirements no candidate meets: the binding ones and how far apart.

    Parameters
    ----------
    table : dict
        :func:`candidate_table`.
    req : Requirements
    """
    ok = table["physical"]
    names = [k[len("margin_") :] for k in table if k.startswith("margin_")]
    binding = []
    for k in names:
        best = float(np.max(np.where(ok, table[f"margin_{k}"], -np.inf)))
        if best < 0:
            binding.append(f"{k} (its best candidate misses it by {-best:.1%}: {MARGINS[k]})")
    i = int(np.argmax(table["worst"]))
    failing = [f"{k} {table[f'margin_{k}'][i]:+.1%}" for k in names if table[f"margin_{k}"][i] < 0]
    closest = (
        f"the closest candidate ({'two' if table['kind'][i] else 'one'}-step, wire {table['wire_diameter'][i] * 1e3:.2f} mm, "
        f"mean diameter {table['mean_diameter'][i] * 1e3:.1f} mm) misses " + ", ".join(failing)
    )
    what = (
        "no single requirement is out of reach, but none of the candidates meets them all together: "
        if not binding
        else "binding requirements: " + "; ".join(binding) + ". "
    )
    return (
        f"[requirements]: no spring meets the requirements ({int(ok.sum())} candidates of wire "
        f"{req.min_wire_diameter * 1e3:g}-{req.max_wire_diameter * 1e3:g} mm searched). {what}{closest}. Relax those "
        "requirements (space, load points, lift, clearance, safety) or widen the wire range"
    )


@dataclass(frozen=True, repr=False)
class Synthesis(Result):
    """The best springs for the requirements (:func:`synthesize`), ranked, with their margins."""

    requirements: Requirements
    springs: list  #: ValveSpring per candidate, best first
    rows: list  #: dicts: kind, geometry, mass, margins, load-point check, dynamics
    searched: int = 0
    notes: list = field(default_factory=list)

    title = "valve spring synthesis"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{len(self.springs)} candidates"

    def describe(self, source: str = "", out_dir: str = "") -> str:
        """The ranked candidates as a table (what ``springdyn valve synthesize`` prints).

        Parameters
        ----------
        source : str
            The requirements file, for the first line [-].
        out_dir : str
            The folder the candidates' files went to [-].
        """
        req = self.requirements
        out = [
            f"{len(self.rows)} candidates of {self.searched} searched for {source or 'the requirements'}: "
            f"{req.installed_force:g} N at {req.installed_length * 1e3:g} mm, {req.open_force:g} N at "
            f"{req.open_length * 1e3:g} mm (lift {req.lift * 1e3:g} mm), material {req.material}"
        ]
        rows = []
        for r in self.rows:
            names = [k for k in r if k.startswith("margin_")]
            rows.append(
                (
                    r["rank"],
                    r["kind"] + ("" if r["low_pitch_coils"] == 0 else f" ({r['low_pitch_coils']:g} low)"),
                    f"{r['wire_diameter_m'] * 1e3:.2f}",
                    f"{r['mean_diameter_m'] * 1e3:.2f}",
                    f"{r['high_pitch_coils']:.2f}",
                    f"{r['free_length_m'] * 1e3:.2f}",
                    f"{r['mass_kg'] * 1e3:.1f}",
                    f"{r['surge_frequency_Hz']:.0f}",
                    f"{r['goodman_safety']:.2f}",
                    "-" if r.get("float_cam_rpm", "-") in ("-", None) else f"{r['float_cam_rpm']:.0f}",
                    f"{r['smallest_margin']:+.1%} ({min(names, key=lambda k: r[k])[len('margin_') :]})",
                    "not run" if r["meets_all"] is None else ("yes" if r["meets_all"] else "NO"),
                )
            )
        out.append(
            text_table(
                rows,
                headers=(
                    "rank",
                    "kind",
                    "wire [mm]",
                    "mean D [mm]",
                    "N2",
                    "free L [mm]",
                    "mass [g]",
                    "f1 [Hz]",
                    "Goodman",
                    "float [rpm]",
                    "smallest margin",
                    "meets all",
                ),
            )
        )
        for r in self.rows:
            d = r["distributed_installed_force_N"], r["distributed_open_force_N"]
            tc = r["type_c_installed_force_N"], r["type_c_open_force_N"]
            out.append(
                f"load points of {r['rank']}: {r['standard_installed_force_N']:.1f} / {r['standard_open_force_N']:.1f} N "
                f"by EN 13906-1's linear rate; distributed {d[0]:.1f} / {d[1]:.1f} N (transition "
                f"{r['transition_turns']:g} turn, judges the dynamics)"
                + ("" if tc[0] is None else f"; Type C {tc[0]:.1f} / {tc[1]:.1f} N")
                + (" (Type C stiffens inside the stroke: see the spring file)" if r.get("type_c_note") else "")
            )
        unrun = [str(r["rank"]) for r in self.rows if r["meets_all"] is None]
        if unrun:
            out.append(
                f"not run in the distributed model: {', '.join(unrun)}, heavier than candidate 1, which meets every "
                "requirement (they cannot rank above it; --judge-all runs them)"
            )
        probed = [str(r["rank"]) for r in self.rows if "probed_goodman_safety" in r]
        if probed:
            out.append(
                f"run at the probe speeds only: {', '.join(probed)}; their Goodman safety there already misses the "
                "requirement (their goodman_dynamic margin is an upper bound; --judge-all runs every speed)"
            )
        if out_dir:
            out.append(f"the candidates' spring files and candidates.csv are in {out_dir}")
        return "\n".join(out + notes_lines(self.summary))

    def _summary(self) -> dict:
        best = self.rows[0]
        s = dict(
            candidates=len(self.rows),
            searched=self.searched,
            best_kind=best["kind"],
            best_wire_diameter_m=best["wire_diameter_m"],
            best_mean_diameter_m=best["mean_diameter_m"],
            best_mass_kg=best["mass_kg"],
            best_smallest_margin=best["smallest_margin"],
        )
        if "float_cam_rpm" in best:
            s["best_float_cam_rpm"] = best["float_cam_rpm"]
        if self.notes:
            s["notes"] = list(self.notes)
        return s

    def columns(self) -> dict:
        # numbers only, never NaN: a figure some candidates lack (no clash onset, Type C's forces
        # where its equations do not hold) stays in the rows and the table, not in the columns
        keys = [k for k in self.rows[0] if not isinstance(self.rows[0][k], (list, dict, str))]
        keys = [k for k in keys if all(r.get(k) is not None for r in self.rows)]
        out = {k: np.array([float(r[k]) for r in self.rows]) for k in keys}
        if any("clash_onset_cam_rpm" in r for r in self.rows):
            out["coil_clash"] = np.array([float(r.get("clash_onset_cam_rpm") is not None) for r in self.rows])
        if any(r["meets_all"] is None for r in self.rows):  # the screen left some out: 0/1 and run 0/1
            out["meets_all"] = np.array([float(bool(r["meets_all"])) for r in self.rows])
            out["dynamics_run"] = np.array([float(r["meets_all"] is not None) for r in self.rows])
        return out

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        data = {}
        for k, v in self.columns().items():
            unit = next((u for suf, u in _UNITS.items() if k.endswith(suf)), "1")
            name = k[: -len(next(s for s in _UNITS if k.endswith(s)))] if unit != "1" else k
            data[name] = ("candidate", np.asarray(v, dtype=float), {"units": unit})
        # the kinds as numbers (a CSV of numbers): two-step 1 / one-step 0, distributed 1 / Type C 0
        data["two_step"] = ("candidate", np.array([float(r["kind"] == "two-step") for r in self.rows]), {"units": "1"})
        data["distributed_model"] = (
            "candidate",
            np.array([float(r["model"] == "distributed") for r in self.rows]),
            {"units": "1"},
        )
        return xr.Dataset(data, coords={"candidate": ("candidate", np.arange(1, len(self.rows) + 1))})

    def _plot(self, ax=None):
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(7, 4.5))
        req = self.requirements
        lengths = np.linspace(req.open_length, req.installed_length + 2e-3, 60)
        for i, sp in enumerate(self.springs):
            f = sp.spring_model.static_force(lengths)
            ax.plot(
                lengths * 1e3, f, f"C{i}", label=f"{i + 1}: {self.rows[i]['kind']}, d {sp.wire_diameter * 1e3:.2f} mm"
            )
        ax.plot(
            [req.installed_length * 1e3, req.open_length * 1e3],
            [req.installed_force, req.open_force],
            "ko",
            label="load points",
        )
        ax.invert_xaxis()
        ax.set_xlabel("spring length [mm]")
        ax.set_ylabel("static force [N]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return fig


_UNITS = {"_m": "m", "_kg": "kg", "_N": "N", "_Hz": "Hz", "_rpm": "rpm", "_Pa": "Pa"}


#: Searches with a raised static Goodman safety (the surge allowance) when no candidate keeps
#: the Goodman safety at speed [-].
SURGE_ITERATIONS = 3
#: Resolution of the candidates' float speeds [rev/min] (a bisection after the scan).
FLOAT_RESOLUTION = 5.0


#: Share of the load-point tolerance the distributed model's static forces may take when the
#: synthesis chooses a candidate's transition coils (the rest is left to manufacture) [-].
TRANSITION_SHARE = 0.5
#: Shortest transition from a dead coil to the active pitch the synthesis writes [turns].
MIN_TRANSITION_TURNS = 0.05
#: Bisection steps on the transition turns [-] (0.45 turn / 2^8: to 0.002 turn).
TRANSITION_STEPS = 8


def _spring(req: Requirements, table: dict, i: int):
    """The candidate ``i`` of the table as a ValveSpring: the closed-form coils and free length
    (the standard's linear rates meet both load points exactly, :func:`load_point_forces`), its
    transition coils chosen so that the distributed model meets them too
    (:func:`choose_transition`)."""

    n2 = float(table["high_pitch_coils"][i])
    try:
        sp = _valve_spring(req, table, i, n2, float(table["free_length"][i]))
    except InputError:
        # the Type C closed forms do not hold for it (e.g. a negative end mass of a two-step
        # spring): the distributed model, coil by coil from the geometry, describes it
        sp = _valve_spring(req, table, i, n2, float(table["free_length"][i]), model="distributed")
    return choose_transition(sp, req)


#: Secant steps on a two-step candidate's free length (its installed force in the distributed model).
FREE_LENGTH_STEPS = 8
#: Relative error of the installed force at which the free-length secant stops [-].
FREE_LENGTH_RTOL = 1e-6


def _two_step_free_length(sp, req: Requirements, start=None):
    """A two-step candidate with the free length at which the distributed model carries the
    installed force: its low-pitch coils close one by one before the installed length, which the
    standard's linear rate K1 up to it does not know (the working rate K2 between the load
    points is the standard's).

    A secant on the free length: its first slope the free rate K1 (or a neighbour's slope), then
    the slope through the last two steps, to :data:`FREE_LENGTH_RTOL` of the installed force.

    Parameters
    ----------
    sp : ValveSpring
        The candidate (its free length the first guess) [-].
    req : Requirements
        The installed length and force.
    start : tuple, optional
        ``(free length [m], slope dF/dLf [N/m])`` where a neighbouring transition's search ended
        (:func:`choose_transition`'s steps differ little): the secant starts there.

    Returns
    -------
    spring : ValveSpring
        The candidate with its free length (unchanged where the geometry refuses a length).
    twin : ValveSpring or None
        The same spring with the distributed model, whose forces the search evaluated (None when
        it did not converge).
    end : tuple or None
        ``(free length [m], slope [N/m])`` to start a neighbour's search from.
    """

    def twin_at(lf):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return dataclasses.replace(sp, model="distributed", free_length=float(lf))

    if start is None:
        lf = sp.free_length
        slope = formulas.free_length_stiffness(
            sp.shear_modulus,
            sp.wire_diameter,
            sp.mean_diameter,
            sp.low_pitch_coils + sp.high_pitch_coils - 2 * sp.dead_coils,
        )
    else:
        lf, slope = start
    last = None  # the step before: (free length, force)
    try:
        for _ in range(FREE_LENGTH_STEPS):
            twin = twin_at(lf)
            f = float(twin.spring_model.static_force(req.installed_length))
            if abs(f / req.installed_force - 1.0) < FREE_LENGTH_RTOL:
                return dataclasses.replace(sp, free_length=float(lf)), twin, (lf, slope)
            if last is not None and lf != last[0] and (f - last[1]) / (lf - last[0]) > 0.0:
                slope = (f - last[1]) / (lf - last[0])  # the force rises with the free length
            last = (lf, f)
            lf = lf + (req.installed_force - f) / slope
        return dataclasses.replace(sp, free_length=float(lf)), None, None
    except InputError:
        if start is not None:  # the neighbour's length is refused: from the candidate's own
            return _two_step_free_length(sp, req)
        return sp, None, None  # the geometry refuses the length: the row's check refuses the candidate


def load_point_forces(sp, req: Requirements) -> dict:
    """The spring's static forces at the installed and the open length by each description:
    ``"standard"`` (EN 13906-1's linear rates, :func:`springdyn.valve.spring.formulas.linear_rate_force`),
    ``"distributed"`` (coil by coil from the geometry, its transition coils closing one by one)
    and ``"type-c"`` (the MMS law, stiffening above F1; None where its equations do not hold).

    Parameters
    ----------
    sp : ValveSpring
        The spring.
    req : Requirements
        The load points' lengths.

    Returns
    -------
    dict
        model name -> ndarray (installed, open) [N] or None.
    """
    lengths = np.array([req.installed_length, req.open_length])
    out = {}
    for model in ("distributed", "type-c"):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                m = sp.with_model(model).spring_model
                out.setdefault("standard", np.asarray(m.linear_rate_force(lengths), dtype=float))
                out[model] = np.asarray(m.static_force(lengths), dtype=float)
        except InputError:
            out[model] = None
    return {"standard": out["standard"], "distributed": out["distributed"], "type-c": out["type-c"]}


def _load_point_error(forces, req: Requirements) -> float:
    """Largest relative difference of two forces from the load points [-] (inf: none)."""
    if forces is None:
        return float("inf")
    return float(max(abs(forces[0] / req.installed_force - 1.0), abs(forces[1] / req.open_force - 1.0)))


def _meets_load_points(sp, forces: dict, req: Requirements) -> bool:
    """Both load points within their tolerance in the distributed model (the judging one) and by
    the standard's linear rate: a one-step spring's forces, a two-step spring's working rate
    between the load points (its installed force is set by the free length of a spring whose
    low-pitch coils close before it, :func:`_two_step_free_length`)."""
    tol = req.load_point_tolerance
    if _load_point_error(forces["distributed"], req) > tol:
        return False
    std = forces["standard"]
    if sp.low_pitch_coils > 0:
        return abs((std[1] - std[0]) / (req.open_force - req.installed_force) - 1.0) <= tol
    return _load_point_error(std, req) <= tol


def choose_transition(sp, req: Requirements):
    """The spring with the longest transition coils (up to the usual
    :data:`~springdyn.valve.spring.geometry.TRANSITION_TURNS`) at which the distributed model's
    static forces stay within :data:`TRANSITION_SHARE` of the load-point tolerance.

    A transition's coils start closed against the dead coil and close one by one as the spring
    is compressed: a long one stiffens the spring inside the working stroke (candidate 1 of the
    example: +7.6 % at the open length with half a turn), which the standard's linear rate does
    not know. The chosen ``transition_turns`` goes into the spring file, so the drawing, the
    model and the standard describe one spring.

    Parameters
    ----------
    sp : ValveSpring
        The candidate (its coils and free length from the standard's rates).
    req : Requirements
        The load points and their tolerance.
    """
    from ..spring.geometry import TRANSITION_TURNS  # (here: the geometry's default, one home)

    limit = TRANSITION_SHARE * req.load_point_tolerance
    built = {}  # turns -> (spring, its distributed twin or None): each transition built once
    near = None  # where the last two-step free-length search ended: the next one starts there

    def build(turns):
        nonlocal near
        if turns not in built:
            d = dataclasses.replace(sp, transition_turns=float(turns))
            if d.low_pitch_coils > 0:
                d, twin, end = _two_step_free_length(d, req, near)
                near = end or near
            else:
                twin = None
            built[turns] = (d, twin)
        return built[turns]

    def error(turns):
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                d, twin = build(turns)
                d = twin if twin is not None else d.with_model("distributed")
                f = d.spring_model.static_force(np.array([req.installed_length, req.open_length]))
        except InputError:
            return float("inf")
        return _load_point_error(f, req)

    if error(TRANSITION_TURNS) <= limit:
        return build(TRANSITION_TURNS)[0]
    lo, hi = MIN_TRANSITION_TURNS, TRANSITION_TURNS
    if error(lo) > limit:
        return build(lo)[0]  # the row's check refuses it
    for _ in range(TRANSITION_STEPS):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if error(mid) <= limit else (lo, mid)
    return build(float(np.floor(lo * 1e3) / 1e3))[0]


def _valve_spring(req: Requirements, table: dict, i: int, n2: float, lf: float, model: str = "type-c"):

    d = float(table["wire_diameter"][i])
    w = req.wire(d)
    return ValveSpring(
        type="two-step" if table["kind"][i] else "one-step",
        mean_diameter=float(table["mean_diameter"][i]),
        wire_diameter=d,
        free_length=lf,
        installed_length=req.installed_length,
        dead_coils=req.dead_coils,
        low_pitch_coils=float(table["low_pitch_coils"][i]),
        high_pitch_coils=n2,
        youngs_modulus=float(w["youngs_modulus"]),
        shear_modulus=float(w["shear_modulus"]),
        density=float(w["density"]),
        damping_ratio=req.damping_ratio,
        tensile_strength=float(w["tensile_strength"]),
        end_type=req.end_type,
        coiling=req.coiling,
        min_coil_bind_clearance=req.min_coil_bind_clearance,
        model=model,
    )


def synthesize(
    req: Requirements,
    *,
    per_kind: int = 3,
    base_dir=None,
    dynamics: bool = True,
    judge_all: bool = False,
    progress=None,
    warm_starts: bool = True,
) -> Synthesis:
    """The best springs for the requirements (see the module docstring).

    Parameters
    ----------
    req : Requirements
        The ``[requirements]`` table.
    per_kind : int
        Candidates kept of each kind (one-step, two-step) [-].
    base_dir : path-like, optional
        Folder of the requirements file (its ``cam`` and ``valve_train`` paths are relative to it).
    dynamics : bool
        Run the dynamic checks when the requirements name a cam.
    judge_all : bool
        Run the dynamic checks on every candidate.  By default they screen (module docstring,
        5): a candidate heavier than one that meets every requirement cannot rank first and is
        not run, nor is the float search of one that misses a requirement already; the first
        candidate and its figures are the same (``tests/valve/design/test_synthesis.py``).
    progress : callable, optional
        ``progress(iterable, desc=...)`` wrapper for the dynamic runs.
    warm_starts : bool
        Each candidate's speeds start from the periodic states of the first candidate run (the
        lightest; of the round before, for a round's first) at the same speeds, its float search
        from its own (:func:`_candidate_starts`),
        not from rest: the figures within the periodicity tolerance of cold starts' (float
        speeds within their resolution), the same whether the screen runs or ``judge_all``.

    Returns
    -------
    Synthesis

    Raises
    ------
    InputError
        When no candidate meets the requirements (:func:`infeasibility`).
    """

    allowance, kept = 1.0, None
    first = []  # warm starts: the sweep states of the first candidate run (_candidate_starts)
    before = []  # the rounds before: what each found, for the note
    for _ in range(SURGE_ITERATIONS):
        screen = (
            req if allowance == 1.0 else dataclasses.replace(req, min_goodman_safety=req.min_goodman_safety * allowance)
        )
        table = candidate_table(screen)
        if not np.any(table["worst"] >= 0.0):
            if kept is None:
                raise InputError(infeasibility(table, req))
            kept[2].append(
                f"with the static Goodman safety raised to {screen.min_goodman_safety:.3g} for the surge no spring meets "
                "the requirements: the candidates above are those of the allowance before"
            )
            break
        try:
            springs, rows, notes = _select(req, screen, table, per_kind)
        except InputError:
            if kept is None:
                raise
            kept[2].append(
                f"with the static Goodman safety raised to {screen.min_goodman_safety:.3g} for the surge the spring "
                "model refuses every candidate: the candidates above are those of the allowance before"
            )
            break
        if allowance != 1.0:
            notes.append(
                f"the static Goodman safety between the load points was raised to {screen.min_goodman_safety:.3g} "
                f"(a surge allowance of {allowance:.3g}: the distributed model's dynamic wire stress at speed); "
                + "; ".join(before)
            )
        kept = (springs, rows, notes, table)
        if not (dynamics and req.cam):
            break
        _dynamics(req, springs, rows, base_dir, progress, notes, judge_all, first if warm_starts else None)
        if any(r["meets_all"] for r in rows) or min(r["margin_goodman_dynamic"] for r in rows) >= 0.0:
            break
        # no candidate meets everything: every one was run or probed (a screen stops only at one
        # that does); the best candidate's Goodman safety at speed (a probed one is below it: _Probe)
        dyn = [r["dynamic_goodman_safety"] for r in rows if r.get("dynamic_goodman_safety") is not None]
        allowance *= min(req.min_goodman_safety / max(g, 1e-6) for g in dyn) * 1.02
        probed = sum("probed_goodman_safety" in r for r in rows)
        before.append(
            f"with {screen.min_goodman_safety:.3g} the best of {len(rows)} candidates kept {max(dyn):.4g} at speed "
            f"({len(dyn)} run at every speed, {probed} at the probe speeds only)"
        )
    springs, rows, notes, table = kept
    order = sorted(range(len(rows)), key=lambda k: (_standing(rows[k]), rows[k]["mass_kg"]))
    rows = [rows[k] for k in order]
    springs = [springs[k] for k in order]
    for rank, r in enumerate(rows, 1):
        r["rank"] = rank
    return Synthesis(requirements=req, springs=springs, rows=rows, searched=int(table["physical"].sum()), notes=notes)


def _standing(row: dict) -> int:
    """A candidate's place in the ranking before its mass: 0 meets every requirement, 1 not
    judged (the screen did not run it), 2 misses one."""
    return 0 if row["meets_all"] else (1 if row["meets_all"] is None else 2)


def _select(req: Requirements, screen: Requirements, table: dict, per_kind: int):
    """The lightest candidates of each kind that meet the screen's margins, built and checked
    against the load points; their rows judged against the requirements ``req``."""

    feasible = np.flatnonzero(table["worst"] >= 0.0)
    springs, rows, notes = [], [], []
    for kind in (0, 1):
        mine = feasible[table["kind"][feasible] == kind]
        if mine.size == 0:
            notes.append(_kind_note(table, kind))
        order = mine[np.argsort(table["mass"][mine], kind="stable")]
        taken = 0
        wires = set()
        for i in order:
            if round(float(table["wire_diameter"][i]) * 1e5) in wires:
                continue  # one candidate per wire: the lightest coil diameter of each
            wires.add(round(float(table["wire_diameter"][i]) * 1e5))
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    sp = _spring(screen, table, int(i))
            except InputError:
                continue  # the model refuses it (its equations do not hold): the next
            forces = load_point_forces(sp, req)
            if not _meets_load_points(sp, forces, req):
                continue  # the distributed model misses a load point (its coils close before open)
            row = _row(req, sp, forces, kind)
            if row["smallest_margin"] < 0.0:  # the model's coils (e.g. the distributed fallback) miss a margin
                continue
            springs.append(sp)
            rows.append(row)
            taken += 1
            if taken == per_kind:
                break
        if mine.size and not taken:
            notes.append(
                f"the {'two' if kind else 'one'}-step candidates that meet the margins are refused by the spring "
                "model (their coils touch before the open length, or its equations do not hold)"
            )
    if not springs:
        raise InputError(
            "[requirements]: the candidates that meet the margins are refused by the spring model (its coils touch "
            "before the open length or its equations do not hold): relax the lift or the space"
        )
    return springs, rows, notes


def _kind_note(table: dict, kind: int) -> str:
    """Why no spring of a kind meets the requirements: its best margin on each that it misses."""
    mine = table["physical"] & (table["kind"] == kind)
    names = [k[len("margin_") :] for k in table if k.startswith("margin_")]
    i = int(np.argmax(np.where(mine, table["worst"], -np.inf)))
    failing = ", ".join(f"{k} {table[f'margin_{k}'][i]:+.1%}" for k in names if table[f"margin_{k}"][i] < 0)
    return (
        f"no {'two' if kind else 'one'}-step spring meets the requirements: the closest (wire "
        f"{table['wire_diameter'][i] * 1e3:.2f} mm, mean diameter {table['mean_diameter'][i] * 1e3:.2f} mm) misses "
        f"{failing}"
    )


def _row(req, sp, forces, kind) -> dict:
    # the final spring (its coils and free length from the standard's rates) judged again
    e = evaluate(req, sp.wire_diameter, sp.mean_diameter, sp.low_pitch_coils, sp.high_pitch_coils, sp.free_length)
    r = dict(
        kind="two-step" if kind else "one-step",
        model=sp.model,
        wire_diameter_m=sp.wire_diameter,
        mean_diameter_m=sp.mean_diameter,
        outer_diameter_m=sp.mean_diameter + sp.wire_diameter,
        low_pitch_coils=float(sp.low_pitch_coils),
        high_pitch_coils=float(sp.high_pitch_coils),
        free_length_m=float(sp.free_length),
        solid_length_m=float(e["solid_length"][0]),
        mass_kg=float(e["mass"][0]),
        surge_frequency_Hz=float(sp.spring_model.first_mode_installed),
        goodman_safety=float(e["goodman"][0]),
        tensile_strength_Pa=float(e["tensile_strength"][0]),
        transition_turns=float(sp.transition_turns),
        required_installed_force_N=req.installed_force,
        required_open_force_N=req.open_force,
    )
    # the load points by the standard's linear rates, the distributed model and Type C
    for name, key in (("standard", "standard"), ("distributed", "distributed"), ("type-c", "type_c")):
        f = forces[name]
        r[f"{key}_installed_force_N"] = None if f is None else float(f[0])
        r[f"{key}_open_force_N"] = None if f is None else float(f[1])
    r["installed_force_N"], r["open_force_N"] = r["standard_installed_force_N"], r["standard_open_force_N"]
    note = type_c_stiffening_note(sp, req)
    if note:
        r["type_c_note"] = note
    for k in e:
        if k.startswith("margin_"):
            r[k] = float(e[k][0])
    r["smallest_margin"] = float(e["worst"][0])
    r["meets_all"] = r["smallest_margin"] >= 0.0
    return r


#: Type C's open force departs from the linear rate by at least this before its stiffening is
#: noted (the table's last digit of a per-cent figure) [-].
TYPE_C_NOTE_FRACTION = 1e-3


def type_c_stiffening_note(sp, req: Requirements) -> str:
    """Where Type C's stiffening starts inside the working stroke while the drawing's coils are
    still open ("" where it does not, or the Type C equations do not hold for the spring).

    Type C stiffens its elements above ``F1 = Fset + (Ls - Lc - Pc) K2`` ([MMS],
    :func:`springdyn.valve.spring.formulas.first_nonlinear_force`), a rule of the document, not a
    coil that touches: a drawing whose active coils are open at the open length keeps its linear
    rate there.

    Parameters
    ----------
    sp : ValveSpring
    req : Requirements
    """
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            model = sp.with_model("type-c").spring_model
            p = model.internal_parameters()
    except InputError:
        return ""
    f_tc = float(model.static_force(req.open_length))
    f_lin = float(model.linear_rate_force(req.open_length))
    if not (p["F1"] < req.open_force and abs(f_tc / f_lin - 1.0) >= TYPE_C_NOTE_FRACTION):
        return ""
    two = sp.low_pitch_coils > 0
    n_open = formulas.active_coils_setup(sp.low_pitch_coils, sp.high_pitch_coils, sp.dead_coils, two)
    gap = (req.open_length - solid_length.solid_length(sp)) / max(n_open, 1e-9)
    start = model.stiffening_start_length()
    return (
        f"Type C stiffens from F1 = {p['F1']:.1f} N at {start * 1e3:.2f} mm, inside the working stroke, while the "
        f"drawing's active coils are still open (about {gap * 1e3:.2f} mm apart at the open length): its open force "
        f"{f_tc:.1f} N ({f_tc / f_lin - 1.0:+.1%} against the linear rate) is its law's, not the "
        "spring's; the standard's rate and the distributed model judge the load points"
    )


def _candidate_starts(first: list | None):
    """A candidate's warm starts (:class:`springdyn.valve.run.periodicity.PeriodicStates`): a
    copy of the sweep states of the first candidate run (``first``: empty until one ran), or
    None (``first`` None: cold starts).  Each round of the surge allowance's search starts its
    first candidate from the round before's and its others from it.  Only a round's first
    candidate's sweep is a neighbour: every candidate starts from the same states whichever
    others ran (the screen and ``judge_all`` agree to the bit; a round before the last runs
    every candidate in both)."""
    if first is None:
        return None
    return first[0].copy() if first else PeriodicStates()


def _judge(row: dict) -> None:
    """A row's smallest margin and whether it meets every requirement, from its margins."""
    row["smallest_margin"] = min(v for key, v in row.items() if key.startswith("margin_"))
    row["meets_all"] = row["smallest_margin"] >= 0.0


class _Probe:
    """The screen of a round's candidates at their likely worst speeds (issue 42, item 4).

    A candidate's Goodman safety at speed is the lowest over the speed range, so its value at a
    few of the speeds is an upper bound of it.  After each candidate run at every speed, the speed
    of its lowest Goodman safety joins the probe speeds; a later candidate is first run at those
    speeds alone (:meth:`bound`).  When its bound there already misses the required safety it
    cannot meet every requirement, whatever its other speeds; it then runs at every speed only
    while it may still be the round's best (its bound above the best safety of a candidate run at
    every speed), whose safety sets the next surge allowance (:func:`synthesize`): such candidates
    run after those that may meet every requirement, the highest bound first, so that the best
    is found early and the others' bounds fall below it.

    The others' remaining speeds and float speeds cannot change the ranking, the surge allowance
    or the notes, so the screened synthesis gives the ranking of ``judge_all`` and its first
    candidate with the same figures (a probed row keeps its bound, labelled, not its figures).
    The bound is exact only where each probed speed starts from the same state as in a full sweep:
    the warm starts' (each speed from the first candidate's periodic state at that speed,
    :func:`_candidate_starts`), so cold starts (``warm_starts=False``) run every speed.
    """

    def __init__(self, req: Requirements, speeds: np.ndarray, pool=None):
        self.req, self.speeds, self.pool = req, speeds, pool
        self.at = []  # indices of the probe speeds in ``speeds``
        self.best = None  # the highest Goodman safety of a candidate run at every speed [-]
        self.started = {}  # k -> (probe speeds, future): probes started ahead (:meth:`ahead`)

    def record(self, table: dict) -> None:
        """Take a candidate run at every speed (its sweep's summary table)."""
        g = np.asarray(table["fatigue_safety_factor"], dtype=float)
        j = int(np.argmin(g))
        if j not in self.at:
            self.at.append(j)
        self.best = float(g[j]) if self.best is None else max(self.best, float(g[j]))

    def ahead(self, ks, candidate, cam, vt) -> None:
        """Start the probes of the candidates ``ks`` (those still to come; ``candidate(k)`` gives
        its model and starts, asked only for a probe it starts) at the present probe speeds, in
        the pool's threads: a probe runs one speed, on one core, so two run at a time.
        :meth:`bound` takes a probe started at the same speeds; one started at others is not
        used (a candidate run at every speed since added a speed)."""
        if self.pool is None or self.best is None:
            return
        at = tuple(sorted(self.at))
        for k in ks:
            if k not in self.started or self.started[k][0] != at:
                model, starts = candidate(k)
                if starts is not None:
                    self.started[k] = (at, self.pool.submit(self._probe, model, cam, vt, starts, at))

    def bound(self, k, model, cam, vt, starts):
        """Candidate ``k``'s (``model``'s) lowest Goodman safety at the probe speeds and those
        speeds [rev/min], or None where it is not probed (no candidate run at every speed yet,
        or cold starts)."""
        if starts is None or self.best is None:
            return None
        at = tuple(sorted(self.at))
        early = self.started.pop(k, None)
        if early is not None and early[0] == at:
            return early[1].result()
        return self._probe(model, cam, vt, starts, at)

    def _probe(self, model, cam, vt, starts, at):
        # a copy: the probed speeds' states must not start the same speeds of a full sweep
        t = sweep(model, cam, self.speeds[list(at)], valve_train=vt, starts=starts.copy()).summary_table()
        return float(np.min(np.asarray(t["fatigue_safety_factor"], dtype=float))), self.speeds[list(at)]

    def fill(self, row: dict, probed) -> None:
        """The row of a candidate that goes no further than its probe (``probed``, :meth:`bound`)."""
        bound, rpm = probed
        need = self.req.min_goodman_safety
        row["probed_goodman_safety"] = bound
        row["margin_goodman_dynamic"] = criteria.margin("goodman", bound, need)
        row["dynamics"] = (
            f"run at {rpm.size} of {self.speeds.size} speeds ({', '.join(f'{r:.0f}' for r in rpm)} cam rpm): its "
            f"Goodman safety there, {bound:.4g}, already misses {need:g} and lies below {self.best:.4g}, the best of "
            "a candidate run at every speed; its other speeds can only lower it (its margin on goodman_dynamic is an "
            "upper bound; --judge-all runs them)"
        )
        _judge(row)


def _full_run(req, model, cam, vt, speeds, row, starts, first, probe, judge_all) -> None:
    """One candidate at every speed (module docstring, 5): its row's figures at speed and, unless
    it misses a requirement already (or ``judge_all``), its float speed; its sweep states start
    the round's other candidates when it is the round's first run (``first``, :func:`_candidate_starts`).
    Its caller, :func:`_dynamics`, keeps the candidates' warnings quiet."""
    t = sweep(model, cam, speeds, valve_train=vt, starts=starts).summary_table()
    if starts is not None and probe.best is None:  # the round's first run
        first[:] = [starts.copy()]
    probe.record(t)
    row["max_retainer_force_N"] = float(np.max(t["max_retainer_force_N"]))
    row["dynamic_goodman_safety"] = float(np.min(t["fatigue_safety_factor"]))
    row["margin_goodman_dynamic"] = criteria.margin("goodman", row["dynamic_goodman_safety"], req.min_goodman_safety)
    # coil clash: a severity above the default limit (verdicts.coil_clash, the sweep's column)
    clash = np.flatnonzero(np.asarray(t["coil_clash"], dtype=bool))
    row["clash_onset_cam_rpm"] = float(speeds[clash[0]]) if clash.size else None
    row["max_clash_severity"] = float(np.max(t["clash_severity"]))
    missed = [key[len("margin_") :] for key, v in row.items() if key.startswith("margin_") and v < 0.0]
    row["dynamics"] = "run"
    if vt is not None and missed and not judge_all:
        row["dynamics"] = f"run; float speed not searched: misses {', '.join(missed)} already"
    elif vt is not None:
        need = None if req.min_float_cam_rpm is None else omega_to_rpm(req.min_float_cam_rpm)
        scan = speeds if need is None else np.linspace(speeds[0], max(speeds[-1], 1.15 * need), speeds.size)
        res = float_speed(model, cam, vt, scan, resolution=FLOAT_RESOLUTION, starts=starts)
        row["float_cam_rpm"] = res["float_cam_rpm"]
        if need is not None:
            fl = res["float_cam_rpm"]
            # no float up to the scan's top: at least that (a lower bound of the margin)
            row["margin_float"] = criteria.margin("float_speed", scan[-1] if fl is None else fl, need)
    _judge(row)


def _dynamics(req, springs, rows, base_dir, progress, notes, judge_all: bool = False, first=None) -> None:
    """The distributed model of each candidate over the speed range (module docstring, 5).

    The candidates are run lightest first, the ranking's order among those that meet every
    requirement.  Unless ``judge_all``, the runs stop at the first candidate that meets every
    requirement (no heavier one can rank above it; their rows say they were not run and their
    ``meets_all`` is ``None``), a candidate that misses a requirement at speed (Goodman,
    clash) or statically gets no float search (it cannot meet all, whatever its float speed),
    and one whose Goodman safety at the probe speeds misses the requirement runs at every speed
    only while it may be the round's best (:class:`_Probe`).
    """

    base = Path(base_dir) if base_dir is not None else Path(".")

    def path(p):
        q = Path(p)
        return q if q.is_absolute() else base / q

    cam = Cam.from_toml(path(req.cam))
    vt = ValveTrain.from_toml(path(req.valve_train)) if req.valve_train else None
    speeds = req.speeds()
    order = sorted(range(len(rows)), key=lambda k: rows[k]["mass_kg"])
    it = progress(order, desc="dynamics") if progress is not None else order
    winner = None
    deferred = []  # (probed, k, model, starts): cannot meet all, may be the round's best (_Probe)
    models = {}  # k -> the candidate as designed (the standard's rates, its transition coils written),

    def model_of(k):  # run coil by coil: its static forces are the row's distributed ones
        if k not in models:
            models[k] = springs[k].with_model("distributed")
        return models[k]

    pool = ThreadPoolExecutor(max_workers=2)  # the probes of one speed, two at a time
    try:
        with warnings.catch_warnings():  # (here, not in the probes' threads: the filters are global)
            warnings.simplefilter("ignore")
            probe = _Probe(req, speeds, pool)
            for i, k in enumerate(it):
                row = rows[k]
                if winner is not None and not judge_all:
                    row["meets_all"] = None
                    row["dynamics"] = (
                        f"not run: heavier than the {rows[winner]['mass_kg'] * 1e3:.1f} g candidate that meets all"
                    )
                    continue
                model, starts = model_of(k), _candidate_starts(first)
                probed = None
                if not judge_all and probe.best is not None:
                    probe.ahead(order[i:], lambda j: (model_of(j), _candidate_starts(first)), cam, vt)
                    probed = probe.bound(k, model, cam, vt, starts)
                if probed is not None and probed[0] < req.min_goodman_safety:
                    if probed[0] < probe.best:
                        probe.fill(row, probed)
                    else:  # it may set the surge allowance: run once the candidates that may meet all have
                        deferred.append((probed, k, model, starts))
                    continue
                _full_run(req, model, cam, vt, speeds, row, starts, first, probe, judge_all)
                if row["meets_all"] and winner is None:
                    winner = k
            later = sorted(deferred, key=lambda d: -d[0][0])  # the highest bound first
            if later and progress is not None:
                later = progress(later, desc="dynamics: the round's best")
            for probed, k, model, starts in later:
                if winner is not None or probed[0] < probe.best:
                    probe.fill(rows[k], probed)
                else:
                    _full_run(req, model, cam, vt, speeds, rows[k], starts, first, probe, judge_all)
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
    if not any(r.get("margin_goodman_dynamic", 0.0) >= 0 for r in rows):
        best = max(r["dynamic_goodman_safety"] for r in rows if r.get("dynamic_goodman_safety") is not None)
        notes.append(
            f"no candidate keeps the Goodman safety {req.min_goodman_safety:g} over the speed range with its surge "
            f"(the distributed model's wire stress): the best reaches {best:.3g}; the static margin between the load "
            "points is not enough at speed (a lower stress: a larger wire or a lower open force)"
        )
    if req.min_float_cam_rpm is not None and not any(r.get("margin_float", -1.0) >= 0.0 for r in rows):
        notes.append(
            f"no candidate reaches the float speed {omega_to_rpm(req.min_float_cam_rpm):.0f} cam rpm: the best "
            f"reaches {max((r.get('float_cam_rpm') or 0.0) for r in rows):.0f} cam rpm (a stiffer spring: raise the "
            "installed force, or lighten the train)"
        )


def read_requirements(path) -> tuple[Requirements, Path]:
    """The ``[requirements]`` table of a file and its folder.

    Parameters
    ----------
    path : str or path-like
        The requirements file.
    """
    doc = load_toml(path, "requirements")
    return Requirements.from_dict(doc, source=str(path)), Path(path).parent


def spring_table(sp) -> dict:
    """The ``[spring]`` table of a synthesised spring, with units (a drawing's values).

    Parameters
    ----------
    sp : ValveSpring
        The spring.
    """
    mm = lambda v: f"{v * 1e3:.6g} mm"  # noqa: E731 - a local formatter
    table = {
        "type": sp.type,
        "mean_diameter": mm(sp.mean_diameter),
        "wire_diameter": mm(sp.wire_diameter),
        "free_length": mm(sp.free_length),
        "installed_length": mm(sp.installed_length),
        "dead_coils": float(sp.dead_coils),
        "low_pitch_coils": float(sp.low_pitch_coils),
        "high_pitch_coils": round(float(sp.high_pitch_coils), 4),
        "end_type": sp.end_type,
        **({"coiling": sp.coiling} if sp.coiling else {}),
        **({"transition_turns": float(sp.transition_turns)} if sp.transition_turns is not None else {}),
        "youngs_modulus": f"{sp.youngs_modulus / 1e9:.6g} GPa",
        "shear_modulus": f"{sp.shear_modulus / 1e9:.6g} GPa",
        "density": f"{sp.density:.6g} kg/m^3",
        # (None: the spring's default strengths)
        **({"tensile_strength": f"{sp.tensile_strength / 1e6:.6g} MPa"} if sp.tensile_strength is not None else {}),
        "damping_ratio": float(sp.damping_ratio),
    }
    if sp.min_coil_bind_clearance is not None:
        table["min_coil_bind_clearance"] = mm(sp.min_coil_bind_clearance)
    if sp.model != "type-c":  # the Type C closed forms do not hold for it
        table["model"] = sp.model
    return table


def load_point_lines(row: dict) -> str:
    """The load points of a candidate by the three descriptions (the spring file's header, the
    synthesis table's notes).

    Parameters
    ----------
    row : dict
        A row of :attr:`Synthesis.rows`.
    """

    ref = (row["required_installed_force_N"], row["required_open_force_N"])

    def pair(key):
        fi, fo = row[f"{key}_installed_force_N"], row[f"{key}_open_force_N"]
        if fi is None:
            return "its equations do not hold for this spring"
        return f"{fi:.1f} N installed ({fi / ref[0] - 1.0:+.1%}), {fo:.1f} N open ({fo / ref[1] - 1.0:+.1%})"

    lines = [
        f"load points {ref[0]:g} N installed, {ref[1]:g} N open; by EN 13906-1's linear rate: {pair('standard')}"
        + (
            " (a two-step spring's low-pitch coils close before the installed length: its free length is set for "
            "the distributed model's installed force, the linear rate holds for the working stroke)"
            if row["kind"] == "two-step"
            else ""
        ),
        f"by the distributed model (transition {row['transition_turns']:g} turn at each end, written below; it "
        f"judges the dynamics): {pair('distributed')}",
        f"by Type C: {pair('type_c')}",
    ]
    if row.get("type_c_note"):
        lines.append(f"note: {row['type_c_note']}")
    return "\n".join(lines)


def write_candidates(result: Synthesis, out_dir, source: str = "") -> list[Path]:
    """Each candidate as a ready spring file ``candidate_<rank>_<kind>.toml`` in ``out_dir``,
    with its margins in the header, together (:func:`springdyn.core.io.output_set`).

    Parameters
    ----------
    result : Synthesis
        The synthesis.
    out_dir : path-like
        Folder (created).
    source : str
        The requirements file, for the header.
    """

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    # an earlier run's candidates that this one does not write are removed once its own are in
    # place (issue 40: they stayed beside the new ones and read as part of this run)
    earlier = set(out.glob("candidate_*_*.toml"))
    with output_set():
        for row, sp in zip(result.rows, result.springs):
            path = out / f"candidate_{row['rank']:02d}_{row['kind']}.toml"
            margins = ", ".join(f"{k[len('margin_') :]} {v:+.1%}" for k, v in row.items() if k.startswith("margin_"))
            header = (
                f"candidate {row['rank']} of springdyn valve synthesize{' for ' + source if source else ''}: "
                f"{row['kind']}, {row['mass_kg'] * 1e3:.1f} g, f1 {row['surge_frequency_Hz']:.0f} Hz, Goodman "
                f"{row['goodman_safety']:.3g}\n"
                + load_point_lines(row)
                + f"\nmargins: {margins}"
                + (f"\nfloat speed {row['float_cam_rpm']:.0f} cam rpm" if row.get("float_cam_rpm") else "")
            )
            with atomic_open(path, "w", encoding="utf-8") as fh:
                fh.write(dumps_toml({"spring": spring_table(sp)}, header))
            written.append(path)
    for stale in sorted(earlier - set(written)):
        stale.unlink(missing_ok=True)
    return written
