"""The valve-spring section of the springdyn report (and of ``springdyn demo``).

The section loads a definition into :class:`springdyn.valve.ValveModel` (the spring alone, driven
by the valve lift, and with its train), runs its studies and writes what they give: files,
figures, findings in sentences, and the criteria judged by the one criteria set
(:mod:`springdyn.valve.design.criteria`) through the model that judges.  No numbers are made here.
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from pathlib import Path

import numpy as np

import springdyn.valve as valve
import springdyn.valve.design as design
from springdyn.app.report.html import Criterion, Section, parameter_rows
from springdyn.core.errors import InputError
from springdyn.core.io import write_json
from springdyn.core.params import Parameters, param, param_like
from springdyn.core.plotting import plt
from springdyn.core.units import format_quantity, omega_to_rpm, rpm_to_omega

__all__ = ["load", "section", "engines", "ValveDefinition", "ReportSettings", "DEFAULT_CAM"]

#: The tables that make a definition a spring pack (:class:`springdyn.valve.SpringPack`).
PACK_TABLES = ("inner_spring", "third_spring", "pack", "damper")

#: Cam used when a definition has a [spring] but no [cam] table.
DEFAULT_CAM = dict(law="3-4-5", lift="9 mm", duration="120 deg")

_RPM = dict(display="rpm", bare_unit="rpm", positive=True)


@dataclass(frozen=True)
class ReportSettings(Parameters):
    """The ``[report]`` table of a valve definition: the engine's speeds and the criteria's limits.

    Speeds are the engine's (four-stroke: the camshaft turns at half of it).
    """

    min_engine_rpm: float = param("rad/s", "lowest engine speed of the sweep", default=rpm_to_omega(1000.0), **_RPM)
    max_engine_rpm: float = param(
        "rad/s", "highest engine speed: the top of the sweep and of the criteria", default=rpm_to_omega(8000.0), **_RPM
    )
    engine_rpm_step: float = param("rad/s", "step of the sweep", default=rpm_to_omega(100.0), **_RPM)
    models: str = param(
        None,
        "spring models to run: 'both' (the criteria from the distributed one, Type C beside it), 'type-c' or "
        "'distributed'",
        kind="str",
        choices=("both", "type-c", "distributed"),
        default="both",
    )
    min_surge_margin: float = param_like(design.Criteria, "min_surge_margin", "the [criteria] key")
    float_margin: float = param_like(design.Criteria, "float_margin", "the [criteria] key")
    min_goodman_safety: float = param_like(design.Criteria, "min_goodman_safety", "the [criteria] key")
    max_seating_velocity: float = param_like(design.Criteria, "max_seating_velocity", "the [criteria] key")
    max_clash_severity: float = param_like(design.Criteria, "max_clash_severity", "the [criteria] key")
    min_valve_piston_clearance: float = param_like(
        design.Criteria, "min_valve_piston_clearance", "the [criteria] key; with [piston]"
    )

    run_up_rate: float = param(
        "1/s^2",
        "engine acceleration of the run-up through the float speed (a run-up in a low gear: some 3000-10000 "
        "engine rpm per second)",
        display="rpm/s",
        bare_unit="rpm/s",
        default=rpm_to_omega(5000.0),
        positive=True,
    )

    cylinder_pressure: str = param(
        None,
        "cylinder pressure against crank angle (a CSV beside the definition: crank_angle_deg and pressure_bar, _Pa, "
        "_kPa or _MPa): "
        "the gas force on the valve at the top speed (needs [timing] and [valve_train] seat_diameter)",
        kind="str",
        default=None,
    )
    port_pressure: float = param(
        "Pa",
        "pressure behind the valve head, absolute (with cylinder_pressure)",
        display="bar",
        default=101325.0,
        positive=True,
    )
    requirements: str = param(
        None,
        "requirements of a new spring (a file beside the definition with a [requirements] table): the report "
        "synthesises it (springdyn valve synthesize) and, with tolerances, proves the best candidate across them",
        kind="str",
        default=None,
    )
    tolerances: str = param(
        None,
        "manufacturing tolerances (a file beside the definition with [tolerances] and [criteria]): the spring, or "
        "the one synthesised for requirements, across them (springdyn valve tolerance)",
        kind="str",
        default=None,
    )
    camshaft: str = param(
        None,
        "a camshaft beside the definition (a file with [camshaft] and its [[camshaft.lobes]]): the report runs its "
        "valves on the twisting shaft at the low, middle and top speed (springdyn valve camshaft)",
        kind="str",
        default=None,
    )
    tolerance_samples: int = param(
        "", "variants of the tolerance study (Sobol points: a power of 2)", kind="int", default=64, positive=True
    )

    table = "report"

    def _validate(self) -> None:
        if self.tolerance_samples > 100_000:
            raise InputError(f"[report] tolerance_samples = {self.tolerance_samples} must be at most 100000")
        if not self.min_engine_rpm < self.max_engine_rpm:
            raise InputError("[report] min_engine_rpm must be below max_engine_rpm")
        if (self.max_engine_rpm - self.min_engine_rpm) / self.engine_rpm_step > 2000:
            raise InputError("[report] engine_rpm_step gives more than 2000 speeds: take a larger step")

    @property
    def criteria(self):
        """The report's limits as the one criteria set (:class:`springdyn.valve.design.Criteria`)."""
        return design.Criteria(
            min_goodman_safety=self.min_goodman_safety,
            min_surge_margin=self.min_surge_margin,
            float_margin=self.float_margin,
            max_seating_velocity=self.max_seating_velocity,
            max_clash_severity=self.max_clash_severity,
            min_valve_piston_clearance=self.min_valve_piston_clearance,
        )

    def cam_rpm(self, engine_rad_s: float) -> float:
        """Cam speed [rev/min] of an engine speed [rad/s] (four-stroke)."""
        return valve.cam_rpm_from_engine_rpm(omega_to_rpm(float(engine_rad_s)))

    @property
    def sweep_speeds(self) -> np.ndarray:
        """Cam speeds of the sweep [rev/min]."""
        lo, hi, step = (self.cam_rpm(v) for v in (self.min_engine_rpm, self.max_engine_rpm, self.engine_rpm_step))
        return np.arange(lo, hi + 1e-9 * hi, step)

    @property
    def report_speeds(self) -> tuple:
        """Cam speeds of the detailed runs [rev/min]: low, middle and top of the range."""
        lo, hi = self.cam_rpm(self.min_engine_rpm), self.cam_rpm(self.max_engine_rpm)
        return (lo, round(0.5 * (lo + hi), 6), hi)


@dataclass
class ValveDefinition:
    """A report definition: its model (spring, cam, train, timing, follower, friction, gas force),
    the ``[report]`` settings and the design studies it asks for."""

    model: valve.ValveModel
    cam_given: bool
    settings: ReportSettings = dataclasses.field(default_factory=ReportSettings)
    #: ``[report] requirements``: (Requirements, the file's folder), or None.
    requirements: object = None
    #: ``[report] tolerances``: (tolerances, Criteria), or None.
    tolerances: object = None
    #: ``[report] camshaft``: (CamshaftModel, its file), or None.
    camshaft: object = None

    @property
    def spring(self):
        return self.model.spring

    @property
    def cam(self):
        return self.model.cam

    @property
    def valve_train(self):
        return self.model.valve_train


def _beside(path: Path, name: str, key: str) -> Path:
    """The file ``name`` of ``[report] key``, relative to the definition's folder."""
    f = Path(name)
    f = f if f.is_absolute() else Path(path).parent / f
    if not f.is_file():
        raise InputError(f"{path}: [report] {key} = {name!r}: no such file")
    return f


def load(doc: dict, path: Path) -> ValveDefinition:
    """Validate the [spring] (or a spring pack's tables), [cam], [valve_train] and [report] tables of a definition."""
    if any(t in doc for t in PACK_TABLES):  # a spring pack: [inner_spring] ([third_spring], [pack], [damper])
        spring = valve.SpringPack.from_document(doc, source=str(path), base_dir=Path(path).parent)
    else:
        spring = valve.ValveSpring.from_dict(doc["spring"], source=str(path))
    cam_given = "cam" in doc
    cam = valve.Cam.from_dict(doc["cam"] if cam_given else DEFAULT_CAM, source=str(path), base_dir=Path(path).parent)
    for table in ("follower", "geometry"):
        if table in doc and "valve_train" not in doc:
            raise InputError(f"{path}: [{table}] needs a [valve_train] table in the same file")
    if "geometry" in doc:  # a drawn lever (springdyn.valve.train.lever): its ratio comes from the drawing
        vt = valve.ValveTrain.with_lever_drawing(doc, source=str(path))
    else:
        vt = valve.ValveTrain.from_dict(doc["valve_train"], source=str(path)) if "valve_train" in doc else None
    if "hla" in doc:
        if vt is None:
            raise InputError(f"{path}: [hla] needs a [valve_train] table in the same file")
        vt = vt.with_document_hla(doc, source=str(path))
    timing = valve.Timing.from_dict(doc["timing"], source=str(path)) if "timing" in doc else None
    # [report] speeds in engine rpm, or in cam rpm through [timing]'s strokes (four-stroke without it)
    per_crank = 2.0 / timing.strokes if timing is not None else 0.5
    settings = ReportSettings.from_dict(doc.get("report", {}), source=str(path), cam_per_crank=per_crank)
    follower = valve.Follower.from_dict(doc["follower"], source=str(path)) if "follower" in doc else None
    if "friction" in doc and follower is None:
        raise InputError(f"{path}: [friction] needs a [follower] table in the same file (the contact at the cam)")
    friction = valve.Friction.in_document(doc, source=str(path))
    oil = valve.oil_of(doc, source=str(path))[0] if vt is not None else None
    piston = None
    if "piston" in doc:  # the valve-to-piston clearance: the train's valve over the piston, placed by [timing]
        need = [t for t, ok in (("[valve_train]", vt is not None), ("[timing]", timing is not None)) if not ok]
        if need:
            raise InputError(f"{path}: [piston] needs {' and '.join(need)} (the valve's lift against crank angle)")
        piston = valve.Piston.from_dict(doc["piston"], source=str(path), base_dir=Path(path).parent)
    model = valve.ValveModel(
        spring, cam, vt, timing=timing, crank_angles=True, follower=follower, friction=friction, oil=oil, piston=piston
    )
    if settings.cylinder_pressure is not None:
        need = [t for t, ok in (("[valve_train]", vt is not None), ("[timing]", timing is not None)) if not ok]
        if vt is not None and vt.seat_diameter is None:
            need.append("[valve_train] seat_diameter")
        if need:
            raise InputError(
                f"{path}: [report] cylinder_pressure needs {', '.join(need)} (the force on the valve head)"
            )
        trace = Path(settings.cylinder_pressure)
        trace = trace if trace.is_absolute() else Path(path).parent / trace
        if not trace.is_file():
            raise InputError(f"{path}: [report] cylinder_pressure = {settings.cylinder_pressure!r}: no such file")
        model = model.with_gas_pressure(trace, settings.port_pressure)
    requirements = tolerances = None
    for key in ("requirements", "tolerances"):
        if getattr(settings, key) is not None and isinstance(spring, valve.SpringPack):
            raise InputError(
                f"{path}: [report] {key} studies one spring, and this definition is a spring pack: give it in a "
                "definition of one spring (the pack's report covers the pack's own analyses)"
            )
    if settings.requirements is not None:
        requirements = design.read_requirements(_beside(path, settings.requirements, "requirements"))
    if settings.tolerances is not None:
        tolerances = design.read_tolerances(_beside(path, settings.tolerances, "tolerances"))
        if "lash" in tolerances[0] and vt is None:
            raise InputError(f"{path}: [report] tolerances: lash is the valve train's: give a [valve_train] table")
    camshaft = None
    if settings.camshaft is not None:
        f = _beside(path, settings.camshaft, "camshaft")
        camshaft = (valve.CamshaftModel.from_toml(f), f)
    return ValveDefinition(model, cam_given, settings, requirements, tolerances, camshaft)


def _criterion(v) -> Criterion:
    """A judged criterion (:class:`springdyn.valve.design.Verdict`) as a row of the report."""
    return Criterion(v.label, v.value, v.limit, v.passed, v.note, v.model)


def _write_result(result, stem: Path, caption: str, files: list, figures: list) -> None:
    """A result's CSV and figure beside the section (``stem.csv``, ``stem.png``), the figure with
    its caption."""
    files.append(result.to_csv(stem.with_suffix(".csv")))
    plt.close(result.plot(stem.with_suffix(".png")))
    figures.append((stem.with_suffix(".png"), caption))


def _run_up_finding(model, f, rs, out_dir, files, figures) -> str:
    """The run-up through the float speed f [cam rpm] at [report] run_up_rate: where the valve
    first floats against the momentary speed (:meth:`ValveModel.run_up_through_float`)."""
    axis = model.crank_axis
    rate = rs.cam_rpm(rs.run_up_rate)  # cam rpm per second
    ramp = model.run_up_through_float(f, rate)
    r = ramp.summary
    _write_result(
        ramp,
        out_dir / "run_up",
        f"Run-up from {ramp.start_rpm:.0f} to {ramp.end_rpm:.0f} cam rpm at {rate:.0f} cam rpm/s "
        f"({_describe_model(model.spring).split(',')[0]}): lift-off and float against the momentary speed",
        files,
        figures,
    )
    onset = r["float_onset_cam_rpm"]
    where = (
        f"the valve first floats at {onset:.0f} cam rpm ({axis.per_cam * onset:.0f} engine rpm), "
        f"{abs(onset - f):.0f} cam rpm {'above' if onset >= f else 'below'} the steady-state float speed {f:.0f} cam rpm"
        if onset is not None
        else "the valve does not float over the nose within the ramp"
    )
    return (
        f"Run-up through the float speed at {axis.per_cam * rate:.0f} engine rpm/s ([report] run_up_rate, "
        f"{_describe_model(model.spring).split(',')[0]}): {where}"
        + (f"; the first lift-off at {r['first_liftoff_cam_rpm']:.0f} cam rpm" if r["first_liftoff_cam_rpm"] else "")
        + f"; up to {r['max_seat_landings']} seat landings per revolution."
    )


def _gas_finding(model, top) -> str:
    """The gas force on the valve at the top speed, against the run without it."""
    with_gas = model.simulate(top).summary
    without = model.replace(gas_force=None).simulate(top).summary
    return (
        f"Gas force on the valve head ([report] cylinder_pressure, seat {model.valve_train.seat_diameter * 1e3:.1f} "
        f"mm) at {model.crank_axis.per_cam * top:.0f} engine rpm: up to {with_gas['max_gas_force_N']:.0f} N, "
        f"{with_gas['gas_force_at_opening_N']:.0f} N as the valve leaves its seat; the largest cam contact force is "
        f"{with_gas['max_cam_contact_force_N']:.0f} N against {without['max_cam_contact_force_N']:.0f} N without it"
        + ("; the valve lifts off the cam" if with_gas["nose_separation"] else "")
        + "."
    )


def _friction_finding(model, report_speeds, out_dir, files, figures) -> str:
    """The train's friction over speed up to the top speed (:meth:`ValveModel.friction_over_speed`)."""
    axis = model.crank_axis
    speeds = np.linspace(report_speeds[0], report_speeds[-1], 5)
    sweep = model.friction_over_speed(speeds)
    analyses = sweep.analyses
    plt.close(sweep.plot(out_dir / "friction.png"))
    files.append(sweep.to_csv(out_dir / "friction.csv"))
    figures.append(
        (out_dir / "friction.png", "Camshaft drive torque over the cam angle and friction power over speed (one valve)")
    )
    top = analyses[-1].summary
    parts = ", ".join(
        f"{k.replace('_', ' ')} {top[f'friction_power_{k}_W']:.1f} W"
        for k in ("cam", "roller_bearing", "guide", "pivot")
        if top[f"friction_power_{k}_W"] >= 0.05
    )
    return (
        f"Friction of one valve's train ([follower]{'' if model.friction_table is not None else ', [friction] defaults'}): "
        f"{analyses[0].summary['friction_power_W']:.1f} W at {axis.per_cam * speeds[0]:.0f} engine rpm to "
        f"{top['friction_power_W']:.1f} W at {axis.per_cam * speeds[-1]:.0f} engine rpm ({parts}); mean camshaft "
        f"drive torque {top['mean_drive_torque_N_m']:.2f} N m, peaks {top['min_drive_torque_N_m']:.1f} / "
        f"{top['max_drive_torque_N_m']:.1f} N m; smallest film parameter {top.get('min_film_parameter', float('nan')):.2g}."
    )


def _camshaft_finding(camshaft, report_speeds, out_dir, files, figures) -> str:
    """The valves on the twisting camshaft of ``[report] camshaft`` at the report's speeds
    (:meth:`springdyn.valve.CamshaftModel.sweep`): drive torque, twist, timing errors, modes."""
    sweep = camshaft.sweep(np.asarray(report_speeds, dtype=float))
    top = sweep.runs[-1]
    plt.close(sweep.plot(out_dir / "camshaft_sweep.png"))
    plt.close(top.plot(out_dir / "camshaft.png"))
    files += [sweep.to_csv(out_dir / "camshaft_sweep.csv"), top.to_csv(out_dir / "camshaft.csv")]
    figures += [
        (out_dir / "camshaft.png", f"The camshaft at {top.cam_rpm:g} cam rpm: drive torque, twist and valve lifts"),
        (out_dir / "camshaft_sweep.png", "The camshaft over speed: drive torque and each valve's timing error"),
    ]
    m, t = sweep.summary, top.summary
    return (
        f"Camshaft ([report] camshaft, {len(camshaft.lobes)} lobes, torsional modes "
        + ", ".join(f"{f:.0f}" for f in sweep.modes_Hz[:3])
        + f" Hz): at {top.cam_rpm:g} cam rpm the drive torque swings {t['min_drive_torque_N_m']:.1f} / "
        f"{t['max_drive_torque_N_m']:.1f} N m about {t['mean_drive_torque_N_m']:.2f} N m, the lobes twist by up to "
        f"{t['max_twist_deg']:.3f} deg; the largest timing error over the speeds is {m['max_timing_error_deg']:.3f} cam "
        f"deg ({m['max_timing_error_crank_deg']:.3f} crank deg) at {m['max_timing_error_cam_rpm']:g} cam rpm"
        + ("" if m["converged"] else "; NOT converged at every speed (the valves float?)")
        + "."
    )


def engines(d: ValveDefinition) -> list:
    """The engine variants the section of ``d`` runs, each with a short run that makes it.

    Every model the section runs (``[report] models``), with its train and the spring alone
    (:attr:`springdyn.valve.ValveModel.engine_variant`: its Runge-Kutta pair, spring alone or
    valve train, one spring or a pack).  The report makes each variant once before its
    sections run side by side (:func:`springdyn.app.report.build.build_report`), so that two
    sections never compile the same engine at once.

    Returns
    -------
    list of (key, callable)
        Each variant once: its key and a run of one revolution that compiles it (or loads it
        from the cache); a model the definition cannot run is left out (its section says why).
    """
    names = ("type-c", "distributed") if d.settings.models == "both" else (d.settings.models,)
    made = {}
    for name in names:
        try:
            train = d.model.with_model(name)
            for m in (train, train.spring_alone()):  # (the same model twice without a train: kept once)
                made.setdefault(
                    m.engine_variant, functools.partial(_one_revolution, m, float(d.settings.report_speeds[0]))
                )
        except InputError:  # the section says it (e.g. the distributed model refuses the spring)
            continue
    return list(made.items())


def _one_revolution(model, cam_rpm: float) -> None:
    model.simulate(cam_rpm, revolutions=1)


def section(d: ValveDefinition, *, source: str, out_dir: Path, quiet: bool = True) -> Section:
    """Run the valve analyses of one definition into ``out_dir`` and describe them (a spring
    pack's: each spring's figures beside the pack's, :func:`_pack_part`)."""
    rs = d.settings
    train = d.model.with_model("distributed") if rs.models == "distributed" else d.model
    sp, lobe, vt = train.spring, train.cam, train.valve_train
    pack = isinstance(sp, valve.SpringPack)
    report_speeds, sweep_speeds = rs.report_speeds, rs.sweep_speeds
    top = report_speeds[-1]
    files, figures, findings, tables = [], [], [], []
    # the report is set for an engine: crank angles and engine speeds beside the cam's
    axis = train.crank_axis
    # the spring alone is driven by the valve lift: the lobe lift times the rocker ratio, or the
    # drawn lever's valve lift
    alone = train.spring_alone()
    cam = alone.cam
    if vt is not None and vt.geometry is not None:
        ls = train.lever_kinematics(lash=0.0).summary
        findings.append(
            f"The lever is drawn ([geometry]): its ratio runs from {ls['ratio_min']:.3f} to {ls['ratio_max']:.3f} over "
            f"the event ({ls['ratio_change']:.1%} of {ls['ratio_at_rest']:.3f} at rest), the valve lifts "
            f"{ls['max_valve_lift_m'] * 1e3:.3f} mm (constant ratio: {ls['constant_ratio_valve_lift_m'] * 1e3:.3f} mm); "
            "the spring-alone analyses are driven by this valve lift."
        )
    elif cam is not lobe:
        findings.append(
            f"The spring-alone analyses drive the spring with the valve lift of the rigid train: the "
            f"lobe lift ({lobe.max_lift * 1e3:.3g} mm) times the rocker ratio {vt.ratio:g}."
        )
    lift = cam.max_lift
    if pack:  # each spring's internal parameters and design figures, and the pack's (SpringPack.design_figures)
        p = {name: s.spring_model.internal_parameters() for name, s in zip(sp.names, sp.springs)}
        figs = sp.design_figures(lift, cam_rpm=top)
    else:
        p = sp.spring_model.internal_parameters()
        curve = alone.static_curve()
        files.append(curve.to_csv(out_dir / "static_curve.csv"))
        plt.close(curve.plot(out_dir / "static_curve.png"))
        figures.append(
            (
                out_dir / "static_curve.png",
                "Static force and tangent stiffness vs length, with the set-up "
                "length and the breakpoint forces F1, F2, Fcon (document Figs. 40.34-40.36)",
            )
        )
        figs = alone.design_figures(lift=lift, cam_rpm=top).figures
    files.append(write_json(out_dir / "params.json", p))
    files.append(write_json(out_dir / "design.json", figs))

    sims = {}
    for rpm in report_speeds:
        sim = alone.simulate(rpm)
        sims[rpm] = sim
        stem = out_dir / f"simulate_{rpm:.0f}rpm"
        files.append(sim.to_csv(stem.with_suffix(".csv")))
        files.append(write_json(stem.with_name(stem.name + "_summary.json"), sim.summary))
        plt.close(sim.plot(stem.with_suffix(".png")))
        figures.append(
            (
                stem.with_suffix(".png"),
                f"Spring{' pack' if pack else ''} alone at {axis.per_cam * rpm:.0f} engine rpm ({rpm:.0f} cam rpm, "
                f"{_describe_model(sp)}): retainer and seat force against the static (massless) force over the crank "
                + ("angle, each spring's force at the retainer, " if pack else "angle, ")
                + "mass displacements, cam-order spectrum",
            )
        )
    sw = alone.sweep(sweep_speeds, quiet=quiet)
    written = sw.write(out_dir, "sweep")
    files += written[:2]
    figures.append(
        (
            out_dir / "sweep_forces.png",
            f"Peak and minimum forces over the speed range against the static values ({_describe_model(sp)})",
        )
    )
    if pack:
        figures.append(
            (
                out_dir / "sweep_springs.png",
                f"Each spring of the pack over the speed range: its retainer force against its static force, its "
                f"Goodman safety ({_describe_model(sp)})",
            )
        )
    figures.append(
        (
            out_dir / "sweep_campbell.png",
            "Campbell diagram: cam-order harmonics of the retainer force against f1 at installed and open length "
            f"({_describe_model(sp)})",
        )
    )
    figures.append(
        (out_dir / "sweep_map.png", f"Retainer force over engine speed and crank angle ({_describe_model(sp)})")
    )

    other_model = "distributed" if sp.model == "type-c" else "type-c"
    sw_other = None
    if rs.models == "both":
        try:
            sw_other = alone.with_model(other_model).replace(crank_angles=False).sweep(sweep_speeds, quiet=quiet)
        except InputError as exc:  # the other model may not accept this spring
            findings.append(f"The {other_model} model cannot run this spring ({exc}); no model comparison.")
    if sw_other is not None:
        png, sentences, _ = _compare_models(sp, sw, sw_other, out_dir)
        files.append(sw_other.to_csv(out_dir / f"sweep_{other_model}_summary.csv"))
        figures.append(
            (
                png,
                "The same spring with both models over the speed range: peak and minimum retainer "
                "and seat forces, and the surge at the resonance orders",
            )
        )
        findings += sentences
    # the criteria come from the model that judges (design.JUDGING_MODEL, the distributed chain:
    # converged in its elements, every surge mode, coil closure turn by turn) whenever it runs
    # this spring
    by_model = {sp.model: sw} | ({sw_other.spring.model: sw_other} if sw_other is not None else {})
    crit_sweep = by_model.get(design.JUDGING_MODEL, sw)
    beside = by_model.get("type-c") if crit_sweep is not by_model.get("type-c") else None
    findings.insert(0, _model_choice(crit_sweep, beside, alone, top))

    for rpm, sim in sims.items():
        s = sim.summary
        contact = (
            f"coil contact from {axis.words(s['coil_contact'][0]['start_deg'])} to "
            f"{axis.words(s['coil_contact'][-1]['end_deg'])} "
            f"(peak element force {max(e['peak_contact_force_N'] for e in s['coil_contact']):.0f} N)"
            if s["coil_contact"]
            else "no coil contact"
        )
        findings.append(
            f"At {axis.per_cam * rpm:.0f} engine rpm ({rpm:.0f} cam rpm, {_describe_model(sw).split(',')[0]}) the peak "
            f"retainer force is {s['max_retainer_force_N']:.1f} N, "
            f"{s['max_retainer_force_ratio']:.3f} times the static peak of {s['max_static_force_N']:.1f} N; the seat "
            f"force swings from {s['min_seat_force_N']:.1f} to {s['max_seat_force_N']:.1f} N (surge amplitude "
            f"{s['seat_surge_amplitude_N']:.1f} N); {contact}." + (_energy_words(sp, s) if pack else "")
        )
    table = sw.summary_table()
    k = int(np.argmax(table["max_retainer_force_N"]))
    clash = sweep_speeds[np.asarray(table["coil_clash"], bool)]
    findings.append(
        f"Over {axis.per_cam * sweep_speeds[0]:.0f}-{axis.per_cam * sweep_speeds[-1]:.0f} engine rpm "
        f"({sweep_speeds[0]:.0f}-{sweep_speeds[-1]:.0f} cam rpm, {_describe_model(sw).split(',')[0]}) the retainer "
        "force peaks at "
        f"{table['max_retainer_force_N'][k]:.1f} N at {axis.per_cam * sweep_speeds[k]:.0f} engine rpm; "
        + (
            f"coil clash occurs from {axis.per_cam * clash[0]:.0f} engine rpm on ({clash.size} of {sweep_speeds.size} "
            "speeds)"
            if clash.size
            else "no coil clash occurs in that range"
        )
        + (" (in any spring of the pack, each over its own Fset)." if pack else ".")
    )
    # the surge frequency and margin of the model that judges, the other's beside
    judge_spring = crit_sweep.spring
    if judge_spring.model == sp.model:
        figs_judge = figs
    elif pack:
        figs_judge = judge_spring.design_figures(lift, cam_rpm=top)
    else:
        figs_judge = alone.replace(spring=judge_spring).design_figures(lift=lift, cam_rpm=top).figures
    if pack:
        criteria = [_criterion(v) for v in _pack_part(figs, figs_judge, crit_sweep, beside, rs, top)]
        findings += _pack_findings(sp, figs_judge, crit_sweep.spring.model)
        tables += _pack_tables(sp, figs, sims, lift)
    else:
        criteria = [_criterion(v) for v in _one_spring_part(figs, figs_judge, crit_sweep, beside, rs, top)]
        findings += _one_spring_findings(sp, p, figs, figs_judge, judge_spring, lift, top)
    if not d.cam_given:
        findings.append("The definition has no [cam] table: the built-in 3-4-5 cam (9 mm over 120 deg) was used.")
    speeds = f"{sweep_speeds[0]:g}:{sweep_speeds[-1]:g}:{sweep_speeds[1] - sweep_speeds[0]:g}"
    commands = [
        f"springdyn valve simulate {source} --cam {source} --cam-rpm {top:g} --plot sim.png --json",
        f"springdyn valve sweep {source} --cam {source} --cam-rpm {speeds} --model {judge_spring.model} --out sweep",
    ]
    if not pack:  # the spring's own commands (a pack's refuse it: docs/valve-spring.md, "Spring packs")
        commands[:0] = [
            f"springdyn valve params {source}",
            f"springdyn valve design {source} --lift {lift * 1e3:g}mm --cam-rpm {top:g} --model {judge_spring.model}",
            f"springdyn valve curve {source} --plot curve.png",
        ]
    if beside is not None:
        commands.append(
            f"springdyn valve sweep {source} --cam {source} --cam-rpm {speeds} --model {beside.spring.model} "
            "--out sweep_beside"
        )
    if vt is not None:
        _train_section(train, d, rs, top, report_speeds, out_dir, files, figures, findings, criteria, commands, source)
    if d.camshaft is not None:
        shaft, shaft_file = d.camshaft
        findings.append(_camshaft_finding(shaft, report_speeds, out_dir, files, figures))
        commands.append(f"springdyn valve camshaft {shaft_file} --cam-rpm {top:g}")
    if d.requirements is not None or d.tolerances is not None:
        _new_spring_and_tolerances(d, lobe, top, out_dir, files, figures, findings, criteria, commands, source, quiet)
    inputs = _spring_inputs(sp) + [(f"cam.{k}", v, m) for k, v, m in parameter_rows(cam) if k != "file" or v]
    if vt is not None:
        inputs += [(f"valve_train.{k}", v, m) for k, v, m in parameter_rows(vt)]
        if vt.hla is not None:
            inputs += [(f"hla.{k}", v, m) for k, v, m in parameter_rows(vt.hla)]
    derived = _derived_rows(sp, p, figs, alone) if not pack else _pack_derived_rows(sp, p)
    if vt is None:
        criteria.append(
            Criterion(
                "float speed",
                "n/a",
                "above the top speed",
                None,
                "the definition has no [valve_train]: the spring alone cannot float",
            )
        )
    return Section(
        family="valve",
        criteria=criteria,
        title=f"Valve spring: {sp.type}" + (" with valve train" if vt is not None else ""),
        source=source,
        commands=commands,
        inputs=inputs,
        derived=derived,
        findings=findings,
        figures=figures,
        tables=tables,
        files=files,
    )


def _one_spring_part(figs, figs_judge, crit_sweep, beside, rs, top) -> list:
    """The criteria of one spring over the judging model's sweep (:func:`springdyn.valve.design.spring_verdicts`)."""
    return design.spring_verdicts(
        rs.criteria,
        figs_judge,
        crit_sweep.summary_table(),
        crit_sweep.cam_rpm,
        model=crit_sweep.spring.model,
        rated_cam_rpm=top,
        wire_limit=crit_sweep.spring.strengths["shear_stress_limit_Pa"],
        beside=beside.summary_table() if beside is not None else None,
        beside_design=figs if figs_judge is not figs else None,
    )


def _one_spring_findings(sp, p, figs, figs_judge, judge_spring, lift, top) -> list[str]:
    """One spring's surge frequency (the judging model's, Type C's beside) and corrected stress in words."""
    fi = figs_judge["installed"]
    surge = (
        f"First surge frequency f1 = {fi['surge_frequency_Hz']:.1f} Hz at installed length "
        f"({judge_spring.spring_model.surge_frequency_definition}; "
        f"{figs_judge['open']['surge_frequency_Hz']:.1f} Hz at full lift); at {top:.0f} cam rpm that is cam order "
        f"{fi['surge_frequency_Hz'] / (top / 60):.1f}, a surge margin of {fi['surge_margin']:.1f} "
        "(rule of thumb: 10-13 or more)"
        + (
            f"; Type C's chain: {figs['installed']['surge_frequency_Hz']:.1f} Hz, margin "
            f"{figs['installed']['surge_margin']:.1f}"
            if figs_judge is not figs
            else ""
        )
        + (
            f"; the document's closed form at free length (Wahl with n1', Type C's calibration) {p['f1']:.1f} Hz"
            if sp.model == "type-c"
            else ""
        )
        + "."
    )
    return [surge, "Corrected shear stress " + _stress_words(figs, lift) + "."]


def _stress_words(figs: dict, lift: float) -> str:
    """``(<the factor's name> = 1.226): 330 MPa installed, ...``: a spring's corrected stresses
    (:meth:`springdyn.valve.SpringModel.design_figures`), the factor named by what its wire uses."""
    return (
        f"({figs['stress_factor_name']} = {figs['stress_factor']:.3f}, wire {figs['wire_section']}): "
        f"{figs['installed']['shear_stress_Pa'] / 1e6:.0f} MPa installed, {figs['open']['shear_stress_Pa'] / 1e6:.0f} "
        f"MPa at {lift * 1e3:.3g} mm lift, {figs['coil_contact']['shear_stress_Pa'] / 1e6:.0f} MPa at coil contact"
    )


def _derived_rows(sp, p, figs, alone) -> list[tuple]:
    """One spring's internal parameters, its chain's modes at free length and its index."""
    units = valve.PARAMETER_UNITS
    derived = [(k, format_quantity(v, *units[k][:2]), sp.spring_model.parameter_meaning(k)) for k, v in p.items()]
    derived.append(
        (
            "chain modes",
            ", ".join(f"{f:.1f}" for f in alone.modes(sp.free_length, 3)) + " Hz",
            f"first three of the {sp.spring_model.name} chain, ends fixed, free length",
        )
    )
    derived.append(("spring index", f"{figs['spring_index']:.3f}", "D/d"))
    return derived


#: A pack's internal parameters its table shows already (installed force, mass, rate at free length).
PACK_TABLE_PARAMETERS = ("Fset", "M", "K1")


def _pack_derived_rows(pack, p) -> list[tuple]:
    """Each spring's internal parameters of its model, but those of the pack's table."""
    units = valve.PARAMETER_UNITS
    return [
        (f"{name}: {k}", format_quantity(v, *units[k][:2]), s.spring_model.parameter_meaning(k))
        for name, s in zip(pack.names, pack.springs)
        for k, v in p[name].items()
        if k not in PACK_TABLE_PARAMETERS
    ]


def _spring_inputs(sp) -> list[tuple]:
    """The spring's input rows; a pack's: each spring's under its table's name, then [pack] and [damper]."""
    if not isinstance(sp, valve.SpringPack):
        return parameter_rows(sp)
    rows = []
    for table, s in zip(("spring", "inner_spring", "third_spring"), sp.springs):
        rows += [(f"{table}.{k}", v, m) for k, v, m in parameter_rows(s)]
    rows += [(f"pack.{k}", v, m) for k, v, m in parameter_rows(sp.options)]
    if sp.damper is not None:
        rows += [(f"damper.{k}", v, m) for k, v, m in parameter_rows(sp.damper)]
    return rows


# ----------------------------------------------------------------------------- spring packs
def _pack_part(figs, figs_judge, crit_sweep, beside, rs, top) -> list:
    """A spring pack's criteria: each spring's (:func:`springdyn.valve.design.spring_verdicts` on
    its own design figures and its own columns of the judging model's sweep,
    :meth:`springdyn.valve.SpeedSweep.spring_table`), labelled by the spring."""
    out = []
    judge = crit_sweep.spring
    for name, s in zip(judge.names, judge.springs):
        verdicts = design.spring_verdicts(
            rs.criteria,
            figs_judge["springs"][name],
            crit_sweep.spring_table(name),
            crit_sweep.cam_rpm,
            model=judge.model,
            rated_cam_rpm=top,
            wire_limit=s.strengths["shear_stress_limit_Pa"],
            beside=beside.spring_table(name) if beside is not None else None,
            beside_design=figs["springs"][name] if figs_judge is not figs else None,
        )
        for v in verdicts:
            own = {
                "coil_clash": "; the severity over this spring's own Fset, against its share of the pack's static "
                "force (its share at installed length)",
                "min_retainer_force": "; this spring's end force at the retainer (the pack's springs leave it one "
                "by one)",
                "surge_margin": "; the pack's modes with its ends held are its springs' own (the chains share only "
                "their ends): each spring's first mode judges its surge",
            }.get(v.name, "")
            out.append(dataclasses.replace(v, label=f"{name} spring: {v.label}", note=v.note + own))
    return out


def _pack_findings(pack, figs, model: str) -> list[str]:
    """The pack's fit, modes and friction damper in words (:meth:`springdyn.valve.SpringPack.design_figures`)."""
    fit = "; ".join(
        f"the {a.replace('_', ' and ')} springs' radial clearance is {f['radial_clearance_installed_m'] * 1e3:.2f} mm "
        f"installed and {f['radial_clearance_at_bind_m'] * 1e3:.2f} mm at coil bind"
        + (f" (they interfere by {f['interference_m'] * 1e3:.2f} mm)" if f["interference_m"] > 0 else "")
        for a, f in figs["fit"].items()
    )
    modes = ", ".join(f"{f:.0f} Hz ({n})" for f, n in zip(figs["modes_Hz"], figs["mode_springs"]))
    d = pack.damper
    damper = (
        f"The friction damper ([damper]): Coulomb friction of {d.force:.3g} N "
        + (
            f"({d.normal_load:.3g} N normal load x {d.friction_coefficient:g})"
            if d.normal_load is not None
            else "(friction_force)"
        )
        + f" on the {d.acts_on} spring at {100 * d.height:.0f} % of its length from the seat, against the "
        + (d.against if d.against == "seat" else f"{d.against} spring")
        + "; its energy at each speed is in the sentences above."
        if d is not None
        else "The pack has no friction damper ([damper]): only the elements' damping dissipates."
    )
    return [
        f"The pack ({', '.join(f'{n} {pack.options.hand(n)}-hand' for n in pack.names)}; one seat, one retainer, one "
        f"lift; each spring at its own installed length): {fit}; solid height {figs['pack_solid_length_m'] * 1e3:.2f} "
        "mm (the longest spring's solid length, seat steps aside).",
        f"Natural frequencies of the pack with its ends held, installed ({_MODEL_NAMES[model]} chains): {modes}. The "
        "chains share only their ends, so these are each spring's own; each spring's first judges its surge margin "
        "(criteria). The pack on the valve train (the modes of springs, valve and train together) is the valve "
        "train's sentence below, not judged.",
        damper,
    ]


def _energy_words(pack, s: dict) -> str:
    """A spring pack's revolution in words: the energy balance (a simulation's summary,
    :func:`springdyn.valve.run.results.pack_energy`; each spring's forces are the pack's table)."""
    work, lost, damper = (
        s[f"{k}_per_revolution_J"] * 1e3 for k in ("retainer_work", "dissipated_energy", "damper_energy")
    )
    return (
        f" Over the revolution the retainer does {work:.2f} mJ of work on the pack and {lost:.2f} mJ are "
        f"dissipated (elements' damping and friction; a periodic revolution returns the rest)"
        + (f", {damper:.2f} mJ of it by the friction damper" if pack.damper is not None else "")
        + "."
    )


def _pack_tables(pack, figs, sims, lift) -> list[tuple]:
    """Each spring's static figures beside the pack's (:meth:`springdyn.valve.SpringPack.design_figures`)."""
    names = pack.names
    each = [figs["springs"][n] for n in names]
    mm = lift * 1e3

    def row(label, values, total="-"):
        return (label, *values, total)

    rows = [
        row(
            "model; wire; hand",
            [f"{f['model']}; {f['wire_section']}; {pack.options.hand(n)}" for f, n in zip(each, names)],
        ),
        row(
            "static force installed [N] (each spring at its own installed length)",
            [f"{f['installed']['force_N']:.1f}" for f in each],
            f"{figs['installed_force_N']:.1f}",
        ),
        row(
            f"static force at {mm:.3g} mm lift [N] (share of the pack's)",
            [f"{f['open']['force_N']:.1f} ({100 * figs['force_share'][n]:.1f} %)" for f, n in zip(each, names)],
            f"{figs['open_force_N']:.1f}",
        ),
        row(
            f"corrected shear stress installed / at {mm:.3g} mm lift [MPa] (the wire's factor)",
            [
                f"{f['installed']['shear_stress_Pa'] / 1e6:.0f} / {f['open']['shear_stress_Pa'] / 1e6:.0f} "
                f"({f['stress_factor_name']} = {f['stress_factor']:.3f})"
                for f in each
            ],
        ),
        row(
            "spring rate at free length [N/mm] (the model's)",
            [f"{f['rate_free_N_per_m'] / 1e3:.2f}" for f in each],
        ),
        row("spring mass [g]", [f"{f['spring_mass_kg'] * 1e3:.1f}" for f in each]),
    ]
    for rpm, sim in sims.items():
        s = sim.summary
        rows.append(
            row(
                f"retainer force at {rpm:.0f} cam rpm, least-most [N] (dynamic)",
                [f"{v['min_retainer_force_N']:.1f}-{v['max_retainer_force_N']:.1f}" for v in s["springs"].values()],
                f"{s['min_retainer_force_N']:.1f}-{s['max_retainer_force_N']:.1f}",
            )
        )
    return [
        (
            "Each spring of the pack and the pack (static: each spring's own model; dynamic: the pack's run of the "
            "spring alone driven by the valve lift). Solid length, coil bind, surge, clash, wire stress and Goodman "
            "of each spring are its criteria rows.",
            ("quantity", *names, "pack"),
            rows,
        )
    ]


def _train_section(train, d, rs, top, report_speeds, out_dir, files, figures, findings, criteria, commands, source):
    """The valve train's part of the section: its modes, the float speed against the criteria, a
    run 5 % above it, the run-up through it, the adjuster, the seating velocity, the gas force
    and the friction."""
    model = train.replace(gas_force=None)  # every study but the gas force's own runs without it
    vt = model.valve_train
    axis = model.crank_axis
    crit = rs.criteria
    nat = model.natural_frequencies(count=6)
    files.append(write_json(out_dir / "train_modes.json", nat.to_dict()))
    findings.append(
        f"Valve train ({vt.layout}{', hydraulic lash adjuster' if vt.hydraulic else ''}, "
        f"{_describe_model(model.spring).split(',')[0]} spring): "
        f"{vt.moving_mass * 1e3:.1f} g referred to the valve, {vt.stiffness_at_valve / 1e6:.1f} N/um from cam to "
        f"valve; natural frequencies of spring and train on the base circle "
        + ", ".join(f"{f:.0f}" for f in nat.base_circle_Hz)
        + " Hz, at full lift "
        + (", ".join(f"{f:.0f}" for f in nat.full_lift_Hz) or "n/a")
        + " Hz."
    )
    res = model.float_speed_above(top, crit.float_margin)
    files.append(write_json(out_dir / "float_speed.json", res.to_dict()))
    f = res["float_cam_rpm"]
    # the float and seating verdicts from the model that judges, the definition's model beside
    judged, res_j = _judging_float(model, rs, top, crit, findings)
    if judged is not None:
        files.append(write_json(out_dir / f"float_speed_{judged}.json", res_j.to_dict()))
    ref = res_j if judged is not None else res
    beside = _float_words(model.spring.model, res) if judged is not None else ""
    criteria.append(
        _criterion(
            design.float_verdict(
                crit, ref, top, _first_lift_off(ref), model=judged or model.spring.model, beside=beside
            )
        )
    )
    s = None
    if f is None:
        findings.append(
            f"The valve stays on the cam over the nose up to {res['cam_rpm'][-1]:.0f} cam rpm (no valve float)"
            + _first_lift_off(res)
            + "."
        )
    else:
        above = model.simulate(1.05 * f)
        s = above.summary
        plt.close(above.plot(out_dir / "valve_train_above_float.png"))
        files.append(above.to_csv(out_dir / "valve_train_above_float.csv"))
        figures.append(
            (
                out_dir / "valve_train_above_float.png",
                f"Valve train 5 % above the float speed ({1.05 * f:.0f} cam rpm, "
                f"{_describe_model(model.spring).split(',')[0]}): contact forces, lift-off intervals",
            )
        )
        sc = res.scan
        hi = [i for i, r in enumerate(res.cam_rpm) if r >= f]
        v_lo = min(sc["seat_impact_velocity_min_m_per_s"][i] for i in hi)
        v_hi = max(sc["seat_impact_velocity_max_m_per_s"][i] for i in hi)
        landings = max(sc["seat_landings"][i] for i in hi)
        findings.append(
            f"Valve float ({_describe_model(model.spring).split(',')[0]}): the valve leaves the cam over the nose "
            f"from {f:.0f} cam rpm ({res.engine_per_cam * f:.0f} engine rpm) on{_first_lift_off(res)}"
            + (
                f"; the {design.JUDGING_MODEL} model, which judges, from "
                + (
                    f"{res_j.float_cam_rpm:.0f} cam rpm ({res_j.engine_per_cam * res_j.float_cam_rpm:.0f} engine rpm)"
                    if res_j.float_cam_rpm is not None
                    else f"above {res_j.cam_rpm[-1]:.0f} cam rpm"
                )
                if judged is not None
                else ""
            )
            + ". 5 % above it, contact is lost for "
            f"{sum(e['duration_deg'] for e in s['liftoff']):.1f} cam degrees and the valve lands on its seat at "
            f"{s['seat_impact_velocity_m_per_s']:.2f} m/s; over the scanned speeds from the float speed on the seating "
            f"velocity ranges {v_lo:.2f}-{v_hi:.2f} m/s (band over the speeds within 25 rpm and, where a speed does "
            f"not settle, over its last revolutions) with up to {landings} seat landings per cycle."
        )
        if isinstance(model.spring, valve.SpringPack):  # ValveModel.speed_ramp covers one spring
            findings.append("The run-up through the float speed covers one spring, not a spring pack: not run.")
        else:
            findings.append(_run_up_finding(model, f, rs, out_dir, files, figures))
    if vt.hla is not None:  # the adjuster at the top speed: leak-down, pump-up, socket hop
        h = model.simulate(top).summary["hla"]
        findings.append(
            f"Hydraulic lash adjuster at the top speed ({axis.per_cam * top:.0f} engine rpm): it collapses "
            f"{h['collapse_min_m'] * 1e6:.1f} to {h['collapse_max_m'] * 1e6:.1f} um over the cycle under up to "
            f"{h['peak_pressure_Pa'] / 1e5:.0f} bar above the supply; {h['leak_per_revolution_m3'] * 1e9:.3f} mm^3 "
            f"leaks out and {h['inflow_per_revolution_m3'] * 1e9:.3f} mm^3 refills per cycle"
            + (
                f"; {'the plunger leaves the stem' if vt.bucket_hla else 'the finger leaves its socket'} for "
                f"{h['socket_hop_deg']:.1f} cam degrees"
                if h["socket_hop"]
                else ""
            )
            + "."
        )
        criteria.append(_criterion(design.pump_up_verdict(h["valve_held_open_m"], top, model=model.spring.model)))
        if f is not None and "hla" in s:
            findings.append(
                f"5 % above the float speed the adjuster holds the valve {s['hla']['valve_held_open_m'] * 1e3:.3f} mm "
                "open on the base circle (pump-up)."
                if s["hla"]["pump_up"]
                else "5 % above the float speed the adjuster does not pump up: the valve still closes."
            )
    v = _max_seating_velocity(ref, top)
    if v is not None:
        v_other = _max_seating_velocity(res, top) if judged is not None else None
        criteria.append(
            _criterion(
                design.seating_verdict(
                    crit,
                    v,
                    top,
                    model=judged or model.spring.model,
                    beside=f"{_MODEL_NAMES[model.spring.model]}: {v_other:.2f} m/s" if v_other is not None else "",
                )
            )
        )
    if model.piston is not None:
        _clearance_part(model, rs, report_speeds, out_dir, files, figures, findings, criteria, commands, source)
    if train.gas_force is not None:
        findings.append(_gas_finding(train, top))
    if model.follower is not None and isinstance(model.spring, valve.SpringPack):  # ValveModel.friction: one spring
        findings.append("The train's friction ([follower]) covers one spring, not a spring pack: not computed.")
    elif model.follower is not None:
        findings.append(_friction_finding(model, report_speeds, out_dir, files, figures))
        commands.append(
            f"springdyn valve friction {source} --cam {source} --valve-train {source} "
            f"--cam-rpm {report_speeds[0]:.0f}:{top:.0f}:{(top - report_speeds[0]) / 4:.0f}"
        )
    commands.append(
        f"springdyn valve float {source} --cam {source} --valve-train {source} "
        f"--cam-rpm {ref.cam_rpm[0]:.0f}:{ref.cam_rpm[-1]:.0f}:{ref.cam_rpm[1] - ref.cam_rpm[0]:.0f}"
        + (f" --model {judged} --resolution {ref.resolution_rpm:g}" if judged is not None else "")
    )


_MODEL_NAMES = {"type-c": "Type C", "distributed": "distributed"}

#: Speeds of the valve-to-piston clearance's sweep in the report [-]: from the lowest report
#: speed to the over-speed the float criterion asks the valve to survive.
CLEARANCE_SPEEDS = 9


def _clearance_part(model, rs, report_speeds, out_dir, files, figures, findings, criteria, commands, source):
    """``[piston]``: the valve-to-piston clearance from the lowest speed up to the float margin
    above the top speed (:meth:`ValveModel.valve_clearance`), its speed map and its criterion."""
    crit = rs.criteria
    speeds = np.linspace(report_speeds[0], report_speeds[-1] * (1.0 + crit.float_margin), CLEARANCE_SPEEDS)
    res = model.valve_clearance(speeds, limit=crit.min_valve_piston_clearance)
    s = res.summary
    _write_result(
        res,
        out_dir / "valve_clearance",
        f"{s['valve'].capitalize()} valve-to-piston clearance ([piston]): the smallest against engine speed with the "
        "static (rigid train) one beside it, and the clearance over crank angle and speed "
        f"({_describe_model(model.spring).split(',')[0]})",
        files,
        figures,
    )
    axis = model.crank_axis
    findings.append(
        f"Valve-to-piston clearance ({s['valve']} valve, [piston]): the simulated valve comes within "
        f"{s['min_clearance_m'] * 1e3:.2f} mm of the piston at {axis.per_cam * s['min_clearance_cam_rpm']:.0f} engine "
        f"rpm, {valve.crank_words(s['min_clearance_crank_angle_deg'])} (along the valve's axis); the rigid train's "
        f"static clearance is {s['static_min_clearance_m'] * 1e3:.2f} mm at "
        f"{valve.crank_words(s['static_min_clearance_crank_angle_deg'])}"
        + ("; THE VALVE MEETS THE PISTON" if s["valve_meets_piston"] else "")
        + "."
    )
    criteria.append(_criterion(design.clearance_verdict(crit, res, model=model.spring.model)))
    commands.append(
        f"springdyn valve clearance {source} --cam {source} --valve-train {source} "
        f"--cam-rpm {','.join(f'{r:.0f}' for r in speeds)} --plot valve_clearance.png"
    )


#: Width of the final bracket of the judging model's float search [rev/min]: the distributed
#: chain costs some ten times Type C per speed, and the bracket is stated beside the figure.
JUDGING_FLOAT_RESOLUTION = 10.0


def _judging_float(model, rs, top, crit, findings):
    """The float search with the model that judges (``design.JUDGING_MODEL``) when the report
    runs both models and the definition's is the other one: ``(model name, result)``, else
    ``(None, None)``."""
    if rs.models != "both" or model.spring.model == design.JUDGING_MODEL:
        return None, None
    try:
        other = model.with_model(design.JUDGING_MODEL)
        return design.JUDGING_MODEL, other.float_speed_above(
            top, crit.float_margin, resolution=JUDGING_FLOAT_RESOLUTION
        )
    except InputError as exc:  # the distributed model may not accept this spring
        findings.append(f"The {design.JUDGING_MODEL} model cannot run this train ({exc}): its float is not judged.")
        return None, None


def _float_words(name: str, res) -> str:
    """``"Type C: 2683 cam rpm"``: a float search's figure for a note."""
    f = res.float_cam_rpm
    return f"{_MODEL_NAMES[name]}: " + (f"above {res.cam_rpm[-1]:.0f} cam rpm" if f is None else f"{f:.0f} cam rpm")


def _max_seating_velocity(res, top):
    """The largest seating velocity band's top of a float scan up to ``top`` [m/s] (None: not scanned)."""
    sc = res.scan or {}
    upto = [i for i, r in enumerate(res.cam_rpm) if r <= top + 1e-9]
    if not upto or "seat_impact_velocity_max_m_per_s" not in sc:
        return None
    return max(sc["seat_impact_velocity_max_m_per_s"][i] for i in upto)


def _new_spring_and_tolerances(d, lobe, top, out_dir, files, figures, findings, criteria, commands, source, quiet):
    """``[report] requirements``: a new spring synthesised for them (the best candidate);
    ``[report] tolerances``: that spring, else the definition's, across its tolerances."""
    from springdyn.core.progress import progress

    rs, vt = d.settings, d.valve_train
    spring = d.spring
    model = "type-c" if rs.models == "type-c" else "distributed"

    def bar(items, total=None, desc=""):
        return progress(items, total=total, desc=desc, quiet=quiet)

    if d.requirements is not None:
        req, base = d.requirements
        syn = design.synthesize(req, base_dir=base, progress=bar)  # infeasible: an InputError naming the binding ones
        folder = out_dir / "new_spring"
        files += design.write_candidates(syn, folder, source=rs.requirements)
        files.append(syn.to_csv(folder / "candidates.csv"))
        plot = folder / "candidates.png"
        plt.close(syn.plot(plot))
        figures.append((plot, "Force against length of the synthesised candidates, with the two load points"))
        best, spring = syn.rows[0], syn.springs[0]
        meets = best["meets_all"]
        binding = min((k for k in best if k.startswith("margin_")), key=lambda k: best[k])[len("margin_") :]
        float_text = f", floats at {best['float_cam_rpm']:.0f} cam rpm" if best.get("float_cam_rpm") else ""
        findings.append(
            f"A new spring for [report] requirements ({rs.requirements}): of {syn.searched} geometries searched, "
            f"{len(syn.rows)} candidates are ranked (new_spring/candidates.csv); the best is {best['kind']}, "
            f"{best['wire_diameter_m'] * 1e3:.2f} mm wire on {best['mean_diameter_m'] * 1e3:.2f} mm, "
            f"{best['mass_kg'] * 1e3:.1f} g{float_text}; its smallest margin is {best['smallest_margin']:+.1%} "
            f"({binding})." + (" " + " ".join(syn.notes) if syn.notes else "")
        )
        criteria.append(
            Criterion(
                "new spring meets its requirements",
                "yes" if meets else f"no: {binding} {best['smallest_margin']:+.1%}",
                "every margin of [report] requirements >= 0",
                bool(meets),
                "the best synthesised candidate (springdyn valve synthesize), with the distributed model's dynamic "
                "checks where the requirements name a cam",
            )
        )
        commands.append(f"springdyn valve synthesize {rs.requirements} --out new_spring")
    if d.tolerances is None:
        return
    tols, crit = d.tolerances
    # up to 10 % past the float speed the report asks for (the variants' float speeds inside
    # the range), in the step of the report's sweep: the smallest Goodman safety over the
    # speeds is a resonance's, which a coarser step misses (250 rpm instead of 100 passed 50 %
    # more of the worked example's variants)
    step = rs.cam_rpm(rs.engine_rpm_step)
    speeds = d.model.service_speeds(rs.report_speeds[0], top, step, rs.float_margin)
    which = "the synthesised spring" if d.requirements is not None else "the spring"
    st = design.tolerance_study(
        spring.with_model(model),
        lobe,
        tols,
        crit,
        count=int(rs.tolerance_samples),
        seed=0,
        speeds=speeds,
        valve_train=vt,
        out_dir=out_dir / "tolerances",
        progress=bar,
    )
    plot = out_dir / "tolerances" / "histograms.png"
    plt.close(st.plot(plot))
    files.append(out_dir / "tolerances" / "variants.nc")
    figures.append((plot, f"{which.capitalize()} across its tolerances: histograms of the variants' outputs"))
    s = st.summary

    def band(k, scale=1.0, fmt=".0f"):
        return f"{s[f'{k}_p2.5'] * scale:{fmt}}-{s[f'{k}_p97.5'] * scale:{fmt}}"

    fails = {k[len("fail_share_") :]: v for k, v in s.items() if k.startswith("fail_share_") and k != "fail_share_any"}
    findings.append(
        f"{which.capitalize()} across its tolerances ([report] tolerances, {s['variants']} Sobol variants, "
        f"{model} model, {speeds[0]:.0f}-{speeds[-1]:.0f} cam rpm; 2.5-97.5 %): Fset {band('Fset', fmt='.1f')} N, "
        f"f1 {band('f1')} Hz"
        + (f", float speed {band('float_cam_rpm')} cam rpm" if vt is not None else "")
        + f", Goodman safety {band('goodman_safety', fmt='.3f')}, peak retainer force {band('max_retainer_force')} N; "
        + "variants failing: "
        + ", ".join(f"{k.replace('_', ' ')} {v:.1%}" for k, v in fails.items())
        + "."
    )
    criteria.append(
        Criterion(
            "across tolerances",
            f"{s['fail_share_any']:.1%} of {s['variants']} variants fail",
            "no sampled variant fails [criteria]",
            bool(s["fail_share_any"] == 0.0),
            "; ".join(s["notes"]),
        )
    )
    commands.append(
        f"springdyn valve tolerance SPRING.toml --model {model} --cam {source}"
        + (f" --valve-train {source}" if vt is not None else "")
        + f" --tolerances {rs.tolerances} --samples {s['variants']} --seed 0 "
        f"--cam-rpm {speeds[0]:.0f}:{speeds[-1]:.0f}:{step:.0f} --out tolerances"
    )


def _compare_models(sp, sw, sw_other, out_dir: Path):
    """Figure and sentence: the definition's model against the other one over the speeds."""
    a, b = sw.summary_table(), sw_other.summary_table()
    names = (sp.model, sw_other.spring.model)
    rpm = sw.cam_rpm
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(9, 8), sharex=True)
    for t, name, ls in ((a, names[0], "-"), (b, names[1], "--")):
        ax.plot(rpm, t["max_retainer_force_N"], "C0" + ls, label=f"max retainer, {name}")
        ax.plot(rpm, t["min_retainer_force_N"], "C1" + ls, label=f"min retainer, {name}")
        ax.plot(rpm, t["max_seat_force_N"], "C2" + ls, lw=1, label=f"max seat, {name}")
        ax.plot(rpm, t["min_seat_force_N"], "C3" + ls, lw=1, label=f"min seat, {name}")
        ax2.plot(rpm, t["retainer_surge_amplitude_N"], "C0" + ls, label=f"retainer surge, {name}")
        ax2.plot(rpm, t["seat_surge_amplitude_N"], "C2" + ls, label=f"seat surge, {name}")
    top = ax2.get_ylim()[1]
    for spring, name, ls in ((sw.spring, names[0], "-"), (sw_other.spring, names[1], "--")):
        f1 = spring.spring_model.modes(sp.installed_length, 1)[0]
        for order in (8, 10, 12):  # cam orders that meet f1 within the speed range
            r = 60 * f1 / order
            if rpm[0] <= r <= rpm[-1]:
                ax2.axvline(r, color="0.6", ls=ls, lw=0.8)
                ax2.text(r, top * 0.95, f" order {order} = f1 ({name})", fontsize=7, va="top", rotation=90)
    ax.set_ylabel("force [N]")
    ax.legend(fontsize=7, ncol=2)
    ax.grid(True, alpha=0.3)
    ax.set_title(f"{sp.type} spring: {names[0]} (solid) and {names[1]} (dashed) models")
    ax2.set_ylabel("surge amplitude |F - F_static| [N]")
    ax2.set_xlabel("cam speed [rpm]")
    ax2.legend(fontsize=7)
    ax2.grid(True, alpha=0.3)
    png = out_dir / "sweep_models.png"
    fig.savefig(png, dpi=110)
    plt.close(fig)
    ta, tb = (a, b) if names[0] == "type-c" else (b, a)
    fset = sp.with_model("type-c").spring_model.internal_parameters()["Fset"]
    fset_d = sp.with_model("distributed").spring_model.internal_parameters()["Fset"]
    parts = []
    for key, label in (
        ("max_retainer_force_N", "peak retainer"),
        ("min_retainer_force_N", "minimum retainer"),
        ("max_seat_force_N", "peak seat"),
        ("min_seat_force_N", "minimum seat"),
    ):
        diff = (tb[key] - ta[key]) / fset
        k = int(np.argmax(np.abs(diff)))
        parts.append(f"{label} force {100 * diff[k]:+.0f} % of Fset at {rpm[k]:.0f} cam rpm")
    # the dynamics alone: the surge amplitudes (|F - F_static|) and the minimum end forces (Fset
    # when static), each model's over its own Fset, so that the static curves' difference drops out
    worst = np.zeros(rpm.size)
    for key in ("retainer_surge_amplitude_N", "seat_surge_amplitude_N", "min_retainer_force_N", "min_seat_force_N"):
        worst = np.maximum(worst, np.abs(np.asarray(tb[key]) / fset_d - np.asarray(ta[key]) / fset))
    clash_a, clash_b = (rpm[np.asarray(t["coil_clash"], bool)] for t in (ta, tb))
    only_b = np.setdiff1d(clash_b, clash_a)
    sentences = [
        f"Distributed model against Type C over {rpm[0]:.0f}-{rpm[-1]:.0f} cam rpm, the largest differences "
        "(distributed minus Type C; both to the periodic steady state): " + "; ".join(parts) + ".",
        "Coil clash: "
        + (f"Type C from {clash_a[0]:.0f} cam rpm ({clash_a.size} speeds)" if clash_a.size else "none in Type C")
        + ", "
        + (
            f"distributed from {clash_b[0]:.0f} cam rpm ({clash_b.size} speeds)"
            if clash_b.size
            else "none in the distributed model"
        )
        + (
            f"; Type C misses it at {only_b.size} speeds ({only_b[0]:.0f}-{only_b[-1]:.0f} cam rpm)"
            if only_b.size
            else ""
        )
        + ". The distributed model carries every surge mode and stiffens as its end coils close one by one; Type C "
        "has three surge modes on a fixed chain whose coil contact comes only from its empirical element laws.",
    ]
    sentences.append(
        f"The static forces differ before any dynamics: Fset {fset:.1f} N in Type C, {fset_d:.1f} N in the distributed "
        f"model ({100 * (fset_d / fset - 1):+.1f} %), because Type C's rate is the closed form of the active coils, "
        "linear up to F1, while the distributed chain's stiffens as its end (and low-pitch) coils close "
        '(docs/which-model.md, "Static forces differ").'
    )
    sentences.append(_type_c_range(rpm, worst, ta, tb))
    return png, sentences, b


#: Type C is within its valid range for a spring while its end forces stay within this share
#: of Fset of the distributed model's (the tolerance of a drawing's installed force, some 5 %).
TYPE_C_AGREEMENT = 0.05


def _type_c_range(rpm, worst, ta, tb) -> str:
    """Where Type C leaves its valid range for this spring: the first speed where its dynamics
    (``worst``: the surge amplitudes and minimum end forces, each model's over its own Fset, so
    that the static curves' difference drops out) differ from the distributed model's by more
    than :data:`TYPE_C_AGREEMENT` of Fset, and the first speed where its end-separation or clash
    verdict differs."""
    out = np.flatnonzero(worst > TYPE_C_AGREEMENT)
    text = (
        f"Type C leaves its valid range for this spring at {rpm[out[0]]:.0f} cam rpm: from there its surge "
        f"amplitudes or minimum end forces differ from the distributed model's by more than "
        f"{100 * TYPE_C_AGREEMENT:g} % of Fset, each in its own Fset (up to {100 * worst.max():.0f} %)"
        if out.size
        else f"Type C's surge amplitudes and minimum end forces stay within {100 * TYPE_C_AGREEMENT:g} % of Fset of "
        f"the distributed model's over the whole range, each in its own Fset (largest {100 * worst.max():.1f} %)"
    )
    verdicts_differ = []
    for key, what in (("min_retainer_force_N", "end separation"), ("coil_clash", "coil clash")):
        va = np.asarray(ta[key]) <= 0 if key != "coil_clash" else np.asarray(ta[key], bool)
        vb = np.asarray(tb[key]) <= 0 if key != "coil_clash" else np.asarray(tb[key], bool)
        k = np.flatnonzero(va != vb)
        if k.size:
            verdicts_differ.append(
                f"its {what} verdict differs from {rpm[k[0]]:.0f} cam rpm ({k.size} speeds; Type C "
                f"{'yes' if va[k[0]] else 'no'}, distributed {'yes' if vb[k[0]] else 'no'} there)"
            )
    return (
        text
        + ("; " + "; ".join(verdicts_differ) if verdicts_differ else "; its end-separation and clash verdicts agree")
        + ". The criteria use the distributed model (docs/which-model.md)."
    )


def _model_choice(crit, beside, alone, top) -> str:
    """The paragraph up front: which model the criteria use, why, and its convergence evidence."""
    s = crit.spring
    if s.model != "distributed":
        return (
            f"The criteria below come from the {_describe_model(crit)}: the definition asks for it alone "
            "([report] models), or the distributed model cannot run this spring. Type C's three surge modes and "
            "empirical coil contact make its clash and float figures indicative (docs/valve.md)."
        )
    sm = {} if isinstance(s, valve.SpringPack) else alone.replace(spring=s).simulate(top).summary  # element check
    if isinstance(s, valve.SpringPack):  # a pack's runs carry no element check (docs/valve-spring.md)
        evidence = "the element-count check of the clash forces is not run for a spring pack"
    elif "clash_force_element_sensitivity" in sm:
        evidence = (
            f"at {top:.0f} cam rpm its coils clash and the peak end forces with twice the elements ({2 * s.elements}) "
            f"change by {100 * sm['clash_force_element_sensitivity']:.2f} % of Fset"
        )
    else:
        evidence = f"at {top:.0f} cam rpm no coils clash, where its forces converge fastest"
    return (
        f"The criteria below come from the {_describe_model(crit)}, because it converges in its element count "
        f"(clash forces at 50 elements within 0.9 % of Fset of 200, docs/valve.md; {evidence}), carries every surge "
        "mode and closes its coils turn by turn, where Type C has three surge modes and an empirical coil contact"
        + (f"; the Type C figure stands beside each ({_describe_model(beside)})." if beside is not None else ".")
    )


def _first_lift_off(res) -> str:
    fs = res.first_separation
    if not fs:
        return ""
    if res.float_cam_rpm is not None and fs["cam_rpm"] >= res.float_cam_rpm:
        return " (also the first lift-off)"
    return f" (first lift-off, bounce: {fs['cam_rpm']:.0f} cam rpm on the {fs['phase']})"


def _describe_model(run) -> str:
    """Which model and settings produced a figure: ``run`` a sweep, or a spring (its runs to
    the default periodic steady state)."""
    s = getattr(run, "spring", run)
    tol = getattr(run, "periodicity_tol", valve.PERIODICITY_TOL)
    name = f"distributed model ({s.elements} elements)" if s.model == "distributed" else "Type C model (5 masses)"
    return f"{name}, each speed to its periodic steady state (last two revolutions within {100 * tol:g} % of Fset)"
