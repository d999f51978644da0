"""``springdyn valve ...`` commands (thin layer over :mod:`springdyn.valve`)."""

from __future__ import annotations

import numpy as np

from springdyn.app.cli import valve_cam_design, valve_friction, valve_synthesis
from springdyn.app.cli.common import (
    add_output_options,
    announce_written,
    as_options,
    close_figure,
    emit,
    existing_file,
    parse_range,
    print_json,
    print_notes,
    print_table,
    quantity,
)
from springdyn.core.errors import InputError
from springdyn.core.units import format_quantity
from springdyn.valve.run.periodicity import MAX_REVOLUTIONS, PERIODICITY_TOL
from springdyn.valve.spring.definition import MODEL_NAMES, ValveSpring

#: Default integration tolerances (the values of :mod:`springdyn.valve.run.setup`, kept here
#: so that building the parser does not load the compiled engine; a test checks they agree).
DEFAULT_RTOL = 1e-6
DEFAULT_ATOL = 1e-9
TRAIN_RTOL = 1e-8
TRAIN_ATOL = 1e-11

__all__ = ["register"]


#: The API arguments of a dynamic run and the options that set them (for error messages).
RUN_OPTIONS = dict(
    cam_rpm="--cam-rpm",
    revolutions="--revolutions",
    periodicity_tol="--periodicity-tol",
    max_revolutions="--max-revolutions",
    allow_extreme_speeds="--allow-extreme-speeds",
    rtol="--rtol",
    atol="--atol",
    points_per_revolution="--points-per-revolution",
    resolution="--resolution",
    lift="--lift",
    backend="--backend",
)


def register(sub) -> None:
    valve = sub.add_parser("valve", help="valve springs: MMS Type C multi-mass or distributed coil-by-coil model")
    vsub = valve.add_subparsers(dest="valve_command", metavar="COMMAND", required=True)

    p = vsub.add_parser("params", help="internal parameters and model variables")
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_params)

    p = vsub.add_parser(
        "cam", help="the cam first: lift, velocity, acceleration, jerk, timing at 0.050 in and 1 mm, lobe centre, ramps"
    )
    p.add_argument("cam", metavar="CAM.toml", help="file with a [cam] table")
    p.add_argument("--valve-train", metavar="VT.toml", help="at the valve: the train's rocker ratio and lash")
    p.add_argument(
        "--engine-rpm",
        metavar="RPM",
        help="engine speed (four-stroke): crank-angle axes and the derivatives in time (bare number: rpm)",
    )
    add_output_options(p)
    p.set_defaults(func=cmd_cam)

    p = vsub.add_parser(
        "calibrate", help="fit the shear modulus or the active coils to the drawing's load points (load_points)"
    )
    p.add_argument("spring", metavar="SPRING.toml")
    p.add_argument(
        "--fit", choices=("shear_modulus", "active_coils"), default="shear_modulus", help="what to fit (default G)"
    )
    p.add_argument("--out", metavar="FILE.toml", help="write the calibrated definition there")
    p.add_argument(
        "--trace",
        metavar="TRACE.csv",
        help="instead: fit damping_ratio and contact_stiffness to a measured retainer-force trace "
        "(columns cam_angle_deg, retainer_force_N; needs --cam and --cam-rpm)",
    )
    p.add_argument(
        "--trace-fit",
        default="damping_ratio,contact_stiffness",
        metavar="KEYS",
        help="with --trace: what to fit, of damping_ratio and contact_stiffness (default both; the contact "
        "stiffness shows only at a clash speed)",
    )
    p.add_argument("--cam", metavar="CAM.toml", help="with --trace: the cam of the measurement")
    p.add_argument("--cam-rpm", metavar="RPM", help="with --trace: the cam speed of the measurement")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_calibrate)

    p = vsub.add_parser("curve", help="static force and tangent stiffness vs spring length")
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument("--from", dest="start", metavar="L1", help="first length (default: free length)")
    p.add_argument("--to", dest="stop", metavar="L2", help="last length (default: where the force is 3 Fcon)")
    p.add_argument("--points", type=int, default=400, metavar="N", help="number of lengths (default 400)")
    add_output_options(p, json=False)
    p.set_defaults(func=cmd_curve)

    p = vsub.add_parser("modes", help="natural frequencies of the chain linearised at a length")
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument("--length", required=True, metavar="L", help="spring length, e.g. 38mm")
    p.add_argument("--count", type=int, default=5, metavar="N", help="how many modes (1-5, default 5)")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_modes)

    p = vsub.add_parser(
        "train-modes",
        help="natural frequencies of spring + valve train (base circle, full lift) and the cam-order resonance speeds",
    )
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument("--cam", required=True, metavar="CAM.toml", help="file with a [cam] table")
    p.add_argument(
        "--valve-train", metavar="VT.toml", help="file with a [valve_train] table (without: the spring alone)"
    )
    p.add_argument(
        "--cam-rpm",
        default="500:8000:500",
        metavar="RANGE",
        help="speed range for the resonance table, START:STOP:STEP in cam rpm (default 500:8000:500)",
    )
    p.add_argument("--count", type=int, default=6, metavar="N", help="frequencies per state (1-20, default 6)")
    p.add_argument(
        "--cam-contact",
        choices=("closed", "open"),
        default="closed",
        help="closed (default): the train on the cam; open: the separated train (follower off the cam, valve "
        "off its seat) held at --valve-lift, its first mode the jump frequency (no resonance table)",
    )
    p.add_argument(
        "--valve-lift",
        metavar="L",
        help="valve lift of the separated train (with --cam-contact open; default: full lift), e.g. 6mm",
    )
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_train_modes)

    p = vsub.add_parser("frf", help="linearised dynamic stiffness against frequency (seat fixed, retainer driven)")
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument(
        "--frequency", required=True, metavar="START:STOP:STEP", help="frequencies, e.g. 10:3000:5 (bare numbers: Hz)"
    )
    p.add_argument("--length", metavar="L", help="spring length of the static state (default: installed length)")
    add_output_options(p)
    p.set_defaults(func=cmd_frf)

    p = vsub.add_parser("design", help="index, corrected stress, surge frequency at installed/open/coil-contact length")
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument("--lift", metavar="LIFT", help="maximum valve lift, e.g. 9mm")
    p.add_argument("--cam-rpm", metavar="RPM", help="camshaft speed for the surge margin (bare number: rpm)")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_design)

    p = vsub.add_parser("simulate", help="dynamic response under cam drive (spring alone or valve train)")
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument("--cam", required=True, metavar="CAM.toml", help="file with a [cam] table")
    _add_speed_options(p, ranged=False, ramp=True)
    _add_revolution_options(p)
    p.add_argument("--valve-train", metavar="VT.toml", help="file with a [valve_train] table: adds lift-off")
    _add_gas_options(p)
    p.add_argument("--points-per-revolution", type=int, default=1440, metavar="N", help="output points (default 1440)")
    p.add_argument(
        "--rtol",
        type=float,
        help=f"relative tolerance (default {DEFAULT_RTOL:g}, {TRAIN_RTOL:g} with a valve train)",
    )
    p.add_argument(
        "--atol",
        type=float,
        help="absolute tolerance on displacements in m, velocities get it x 2 pi f1/30 "
        f"(default {DEFAULT_ATOL:g}, {TRAIN_ATOL:g} with a valve train)",
    )
    p.add_argument(
        "--backend",
        choices=("compiled", "scipy"),
        default="compiled",
        help="compiled engine (default) or the SciPy reference",
    )
    p.add_argument(
        "--closure-map",
        metavar="PNG",
        help="distributed model: write the coil-closure map (cam angle x position along the wire)",
    )
    add_output_options(p)
    p.set_defaults(func=cmd_simulate)

    p = vsub.add_parser(
        "float",
        help="float speed: lowest speed from which the valve leaves the cam over the nose; bounce and seating velocity",
    )
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument("--cam", required=True, metavar="CAM.toml", help="file with a [cam] table")
    p.add_argument("--valve-train", required=True, metavar="VT.toml", help="file with a [valve_train] table")
    _add_speed_options(p, ranged=True)
    _add_revolution_options(p)
    p.add_argument("--resolution", default="1", metavar="RPM", help="bisection resolution in cam rpm (default 1)")
    p.add_argument("--csv", metavar="FILE.csv", help="write the minimum cam contact force against speed")
    p.add_argument(
        "--plot", metavar="FILE.png", help="plot the minimum contact force against speed, float speed marked"
    )
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_float)

    p = vsub.add_parser("sweep", help="speed sweep (optionally over a design variable), locally or on Dask")
    p.add_argument("spring", metavar="SPRING.toml")
    _add_model_option(p)
    p.add_argument("--cam", required=True, metavar="CAM.toml", help="file with a [cam] table")
    _add_speed_options(p, ranged=True)
    p.add_argument("--valve-train", metavar="VT.toml", help="file with a [valve_train] table: adds lift-off")
    _add_gas_options(p)
    _add_revolution_options(p)
    p.add_argument("--points-per-revolution", type=int, default=720, metavar="N", help="output points (default 720)")
    p.add_argument(
        "--vary",
        metavar="FIELD=START:STOP:STEP",
        help="also sweep a numeric spring field, e.g. installed_length=36mm:40mm:0.5mm",
    )
    p.add_argument(
        "--on-invalid",
        choices=("stop", "skip"),
        default="stop",
        help="a --vary value that makes the spring invalid: stop (default) or skip it",
    )
    p.add_argument("--out", default="valve-sweep", metavar="DIR", help="output folder (default valve-sweep)")
    p.add_argument("--workers", type=int, metavar="N", help="local threads (default: 2, both cores)")
    p.add_argument(
        "--scheduler", metavar="ADDRESS", help="run on a Dask distributed scheduler, e.g. tcp://127.0.0.1:8786"
    )
    p.add_argument(
        "--rtol",
        type=float,
        help=f"relative tolerance (default {DEFAULT_RTOL:g}, {TRAIN_RTOL:g} with a valve train)",
    )
    p.add_argument(
        "--atol",
        type=float,
        help="absolute tolerance on displacements in m, velocities get it x 2 pi f1/30 "
        f"(default {DEFAULT_ATOL:g}, {TRAIN_ATOL:g} with a valve train)",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_sweep)

    valve_cam_design.register(vsub)  # cam-from-lift, cam-check, kinematics
    valve_friction.register(vsub, _add_speed_options, _add_model_option, cam_rpm_from_args)
    valve_synthesis.register(vsub)
    valve_synthesis.register_tolerance(vsub, _add_model_option, cam_rpm_from_args)
    valve_synthesis.register_life(vsub, _add_model_option)


def _add_revolution_options(p) -> None:
    p.add_argument(
        "--revolutions",
        type=int,
        metavar="N",
        help="run exactly N cam revolutions from rest (default: to the periodic steady state)",
    )
    p.add_argument(
        "--periodicity-tol",
        default=f"{100 * PERIODICITY_TOL:g} %",
        metavar="TOL",
        help="periodic steady state: the last two revolutions' seat, retainer, cam-contact and valve-seat forces "
        f"agree within TOL of Fset (default {100 * PERIODICITY_TOL:g} %%)",
    )
    p.add_argument(
        "--max-revolutions",
        type=int,
        default=MAX_REVOLUTIONS,
        metavar="N",
        help=f"periodic steady state: at most N revolutions per speed (default {MAX_REVOLUTIONS})",
    )
    p.add_argument(
        "--allow-extreme-speeds",
        action="store_true",
        help="compute speeds at which the cam event is shorter than one surge period (refused otherwise), flagged",
    )


def _run_length(args) -> dict:
    """The API's run-length arguments from the options."""
    if args.revolutions is not None and args.max_revolutions != MAX_REVOLUTIONS:
        raise InputError("--revolutions runs a fixed number of revolutions: --max-revolutions applies without it")
    return dict(
        revolutions=args.revolutions,
        periodicity_tol=quantity(args.periodicity_tol, "", "--periodicity-tol"),
        max_revolutions=args.max_revolutions,
        allow_extreme_speeds=args.allow_extreme_speeds,
    )


def _add_model_option(p) -> None:
    p.add_argument(
        "--model",
        choices=MODEL_NAMES,
        help="spring model (default: the [spring] model key, else 'type-c', the document's MMS Type C)",
    )


def _add_gas_options(p) -> None:
    p.add_argument(
        "--gas-pressure",
        metavar="P.csv",
        help="cylinder pressure against crank angle (columns crank_angle_deg, pressure_bar|_Pa|_kPa|_MPa, absolute): "
        "its force on the valve head over [valve_train] seat_diameter, phased by the cam's [timing]",
    )
    p.add_argument(
        "--port-pressure",
        default="1 atm",
        metavar="P",
        help="pressure behind the valve head, absolute (default 1 atm; bare number: Pa)",
    )


def _add_speed_options(p, *, ranged: bool, ramp: bool = False) -> None:
    g = p.add_mutually_exclusive_group(required=True)
    what = "START:STOP:STEP or a list" if ranged else "a speed"
    g.add_argument("--cam-rpm", metavar="RPM", help=f"camshaft speed, {what} (bare numbers: rpm)")
    g.add_argument(
        "--engine-rpm", metavar="RPM", help=f"engine speed, {what} (four-stroke: cam speed = engine speed / 2)"
    )
    if ramp:
        g.add_argument(
            "--speed-ramp",
            metavar="START:END:RATE",
            help="a cam-speed ramp (a run-up, or a run-down when END < START): cam speeds and the rate of the cam "
            "speed (bare numbers: rpm and rpm/s), from the periodic steady state at START; lift-off, float and "
            "seat landings per revolution against the momentary speed (needs --valve-train)",
        )


def cam_rpm_from_args(args, *, ranged: bool):
    """Camshaft speed(s) in rev/min from --cam-rpm or --engine-rpm (four-stroke: half)."""
    option = "--cam-rpm" if args.cam_rpm is not None else "--engine-rpm"
    text = args.cam_rpm if args.cam_rpm is not None else args.engine_rpm

    from springdyn.valve.cam.definition import cam_rpm_from_engine_rpm

    def cam(rpm):
        return rpm if args.cam_rpm is not None else cam_rpm_from_engine_rpm(rpm)

    if ranged:
        values = cam(parse_range(text, "rpm", option, bare_unit="rpm"))
        if (values <= 0).any():
            raise InputError(f"{option} = {text!r}: every speed must be positive")
        return values
    value = cam(quantity(text, "rpm", option, bare_unit="rpm"))
    if not value > 0:
        raise InputError(f"{option} = {text!r} must be a positive speed")
    return value


def _spring(args) -> ValveSpring:
    return ValveSpring.from_toml(args.spring).with_model(getattr(args, "model", None))


def cmd_params(args) -> int:
    spring = _spring(args)
    params = spring.spring_model.internal_parameters()
    if args.json:
        print_json(params)
        return 0
    from springdyn.valve.spring.chains import PARAMETER_UNITS

    rows = []
    for key, value in params.items():
        unit, display, doc = PARAMETER_UNITS[key]
        rows.append((key, format_quantity(value, unit, display), doc))
    print(f"{args.spring}: {spring.type} valve spring, {spring.spring_model.description}")
    print(
        f"coils: {spring.total_coils:g} total, {spring.active_coils:g} active ({spring.dead_coils:g} dead per end); "
        f"solid length {spring.solid_length * 1e3:.3f} mm"
        + (f" (EN 13906-1, ends {spring.end_type})" if spring.end_type else " (the MMS document's Dw (N1 + N2 + 0.5))")
        + f"; free length {spring.free_length * 1e3:.3f} mm"
        + (", pitch profile given" if spring.pitch_profile else "")
    )
    print_table(rows, headers=("parameter", "value", "meaning"))
    if spring.load_points:
        from springdyn.valve.design.calibrate import load_point_check

        _print_load_points(load_point_check(spring))
    return 0


def _print_coils(facts) -> None:
    """The coils and the solid length a run used (:attr:`ValveSpring.coil_facts`)."""
    print(
        f"spring: {facts['total_coils']:g} coils, {facts['active_coils']:g} active; solid length "
        f"{facts['solid_length_m'] * 1e3:.3f} mm ({facts['solid_length_source']}); free length "
        f"{facts['free_length_m'] * 1e3:.3f} mm"
    )


def _print_load_points(rows) -> None:
    """The drawing's load points against the model's static forces."""
    print("load points of the drawing against the model's static force:")
    print_table(
        [
            (
                f"{r['length_m'] * 1e3:.3f}",
                f"{r['force_N']:.1f}",
                f"{r['model_force_N']:.1f}",
                f"{r['deviation_N']:+.1f} ({r['deviation_percent']:+.2f} %)",
                "-" if r["tolerance_N"] is None else f"+-{r['tolerance_N']:.1f}",
                {None: "-", True: "ok", False: "OUTSIDE"}[r["within_tolerance"]],
            )
            for r in rows
        ],
        headers=("length [mm]", "drawing [N]", "model [N]", "deviation [N]", "tolerance [N]", ""),
    )


def cmd_cam(args) -> int:
    from springdyn.valve.cam.analysis import analyse_cam
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.train.definition import ValveTrain

    cam = Cam.from_toml(args.cam)
    timing = _timing(args.cam)
    vt = ValveTrain.from_toml(args.valve_train) if args.valve_train else None
    rpm = (
        quantity(args.engine_rpm, "rad/s", "--engine-rpm", bare_unit="rpm") * 60 / (2 * 3.141592653589793)
        if args.engine_rpm
        else None
    )
    with as_options(engine_rpm="--engine-rpm"):
        res = analyse_cam(cam, vt, rpm, timing=timing)
    if emit(res, args, json_data=dict(res.summary)):
        return 0
    s = res.summary
    crank = res.axis is not None
    ang = res.axis.unit if crank else "cam deg"

    def a(key):  # an angle in the axis the user asked for
        v = s.get(key.replace("_deg", "_crank_deg") if crank else key)
        return "-" if v is None else f"{v:.2f}"

    print(
        f"{cam.law} cam at the {'valve' if vt is not None else 'lobe'}: max lift {s['max_lift_m'] * 1e3:.3f} mm at "
        f"{s['max_lift_cam_angle_deg']:.2f} cam deg"
        + (f" (rocker ratio {s['rocker_ratio']:g}, lash {s['lash_m'] * 1e3:.3g} mm)" if vt is not None else "")
    )
    rows = [
        ("event (lift > 0)", a("event_opening_deg"), a("event_closing_deg"), f"{s.get('event_duration_deg', 0):.2f}")
    ]
    for key, label in (("0050in", "0.050 in"), ("1mm", "1 mm")):
        if s.get(f"duration_at_{key}_deg") is not None:
            rows.append(
                (
                    f"at {label}",
                    a(f"opening_at_{key}_deg"),
                    a(f"closing_at_{key}_deg"),
                    f"{s[f'duration_at_{key}_deg']:.2f}",
                )
            )
        else:
            rows.append((f"at {label}", "-", "-", "lift below the check height"))
    print_table(rows, headers=("timing", f"opens [{ang}]", f"closes [{ang}]", "duration [cam deg]"))
    print(f"lobe centre (mid-way between the 1 mm points): {a('lobe_centre_deg')} {ang}")
    if "timing" in s:
        t = s["timing"]
        v = "intake" if timing.valve == "intake" else "exhaust"
        print(
            f"{v} valve timing ([timing] lobe centre {t['max_lift']} at the maximum lift): "
            + "; ".join(
                f"at {label} opens {t[f'opening_at_{key}']}, closes {t[f'closing_at_{key}']}"
                for key, label in (("0050in", "0.050 in"), ("1mm", "1 mm"))
                if f"opening_at_{key}" in t
            )
        )
    elif crank:
        print("crank angles count from the start of the cam's event: give a [timing] table to count them from TDC")
    print(
        f"velocity {s['min_velocity_m_per_rad'] * 1e3:.3f} to {s['max_velocity_m_per_rad'] * 1e3:.3f} mm/rad, "
        f"acceleration {s['min_acceleration_m_per_rad2'] * 1e3:.3f} to {s['max_acceleration_m_per_rad2'] * 1e3:.3f} "
        f"mm/rad^2, jerk up to {s['max_abs_jerk_m_per_rad3'] * 1e3:.2f} mm/rad^3"
    )
    if rpm is not None:
        print(
            f"at {rpm:g} engine rpm: velocity up to {s['max_velocity_m_per_s']:.3f} m/s, acceleration "
            f"{s['min_acceleration_m_per_s2']:.0f} to {s['max_acceleration_m_per_s2']:.0f} m/s^2"
        )
    if "ramp_height_m" in s:
        print(
            f"ramps: {s['ramp_height_m'] * 1e3:.3f} mm over {s['ramp_duration_deg']:.2f} cam deg, "
            f"{s['ramp_velocity_m_per_rad'] * 1e3:.4f} mm/rad"
        )
    for note in s.get("notes", []):
        print("note: " + note)
    return 0


def _calibrate_trace(args, spring, out) -> int:
    """``valve calibrate --trace``: damping and contact stiffness from a measured retainer force."""
    import math

    from springdyn.core.io import atomic_open, dumps_toml, read_csv_columns
    from springdyn.core.params import load_toml
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.design.calibrate import calibrate_trace

    if not (args.cam and args.cam_rpm):
        raise InputError("--trace needs --cam (the cam of the measurement) and --cam-rpm (its speed)")
    cols = read_csv_columns(args.trace)
    missing = [c for c in ("cam_angle_deg", "retainer_force_N") if c not in cols]
    if missing:
        raise InputError(f"{args.trace}: no column {missing[0]!r}; the trace has cam_angle_deg and retainer_force_N")
    cam = Cam.from_toml(args.cam)
    rpm = quantity(args.cam_rpm, "rad/s", "--cam-rpm", bare_unit="rpm") * 30 / math.pi
    fit = [k.strip() for k in args.trace_fit.split(",") if k.strip()]
    with as_options(fit="--trace-fit"):
        res = calibrate_trace(spring, cam, rpm, np.radians(cols["cam_angle_deg"]), cols["retainer_force_N"], fit=fit)
    if args.json:
        print_json({k: v for k, v in res.items() if k != "spring"})
    else:
        for name, value in res["values"].items():
            print(f"{name}: {res['before'][name]:.6g} -> {value:.6g}")
        print(f"rms deviation from the trace: {res['rms_before_N']:.3f} N -> {res['rms_N']:.3f} N")
    if out is not None:
        doc = load_toml(args.spring)
        table = dict(doc["spring"])
        if "damping_ratio" in res["values"]:
            table["damping_ratio"] = round(res["values"]["damping_ratio"], 8)
        if "contact_stiffness" in res["values"]:
            table["contact_stiffness"] = f"{res['values']['contact_stiffness'] / 1e3:.6g} N/mm"
        doc["spring"] = table
        header = (
            f"{args.spring} calibrated by springdyn valve calibrate --trace {args.trace}: rms deviation "
            f"{res['rms_before_N']:.3f} N -> {res['rms_N']:.3f} N"
        )
        with atomic_open(out, "w", encoding="utf-8") as fh:
            fh.write(dumps_toml(doc, header))
        announce_written([out], args)
    return 0


def cmd_calibrate(args) -> int:
    from springdyn.core.io import atomic_open, check_output_file, dumps_toml
    from springdyn.core.params import load_toml
    from springdyn.valve.design.calibrate import calibrate

    spring = _spring(args)
    out = check_output_file(args.out, "--out") if args.out else None
    if args.trace:
        return _calibrate_trace(args, spring, out)
    with as_options(fit="--fit"):
        res = calibrate(spring, args.fit)
    if args.json:
        print_json({k: v for k, v in res.items() if k != "spring"})
    else:
        unit = ("Pa", "GPa") if args.fit == "shear_modulus" else ("", None)
        print(
            f"{args.fit}: {format_quantity(res['before'], *unit)} -> {format_quantity(res['after'], *unit)} "
            f"(rms deviation over tolerance {res['rms_weighted_residual']:.3g})"
        )
        print("before:")
        _print_load_points(res["load_points_before"])
        print("after:")
        _print_load_points(res["load_points_after"])
    if out is not None:
        doc = load_toml(args.spring)
        table = dict(doc["spring"])
        if args.fit == "shear_modulus":
            table["shear_modulus"] = f"{res['after'] / 1e9:.6g} GPa"
        else:
            key = next((k for k in ("active_coils", "total_coils") if k in table), "high_pitch_coils")
            value = res["spring"].active_coils if key == "active_coils" else res["spring"].total_coils
            table[key] = round(value if key != "high_pitch_coils" else res["spring"].high_pitch_coils, 6)
        doc["spring"] = table
        header = (
            f"{args.spring} calibrated by springdyn valve calibrate --fit {args.fit}: "
            f"{res['before']:.6g} -> {res['after']:.6g}\n"
            + "\n".join(
                f"load point {r['length_m'] * 1e3:.4g} mm: drawing {r['force_N']:.2f} N, model {r['model_force_N']:.2f} N "
                f"({r['deviation_percent']:+.2f} %)"
                for r in res["load_points_after"]
            )
        )
        with atomic_open(out, "w", encoding="utf-8") as fh:
            fh.write(dumps_toml(doc, header))
        print(f"wrote {out}")
    return 0


def cmd_curve(args) -> int:
    spring = _spring(args)
    start = quantity(args.start, "m", "--from") if args.start is not None else None
    stop = quantity(args.stop, "m", "--to") if args.stop is not None else None
    with as_options(start="--from", stop="--to", points="--points"):
        curve = spring.spring_model.static_curve(start, stop, args.points)
    emit(curve, args)
    if not args.csv:
        step = max(1, len(curve.length) // 20)
        rows = [
            (f"{l * 1e3:.3f}", f"{f:.2f}", f"{k / 1e3:.2f}", f"{n:.1f}")
            for l, f, k, n in zip(
                curve.length[::step], curve.force[::step], curve.stiffness[::step], curve.frequency[::step]
            )
        ]
        print_table(rows, headers=("length [mm]", "force [N]", "stiffness [N/mm]", "first mode [Hz]"))
    return 0


def cmd_modes(args) -> int:
    spring = _spring(args)
    length = quantity(args.length, "m", "--length")
    with as_options(length="--length", count="--count"):
        freqs = spring.spring_model.modes(length, args.count)
        labels = spring.spring_model.mode_labels(length, args.count)
    force = float(spring.spring_model.static_force(length))
    if args.json:
        print_json({"length_m": length, "force_N": force, "frequencies_Hz": list(freqs), "modes": labels})
    else:
        print(f"length {length * 1e3:.3f} mm, static force {force:.2f} N")
        print_table(
            [(str(i + 1), f"{f:.2f}", label) for i, (f, label) in enumerate(zip(freqs, labels))],
            headers=("mode", "frequency [Hz]", "what moves"),
        )
        if "end mass" in labels:
            print(
                "end mass: the chain's end masses bouncing on their stiff end contacts (a lumped model's mode, "
                "not a surge of the coils)"
            )
    return 0


def cmd_train_modes(args) -> int:
    from springdyn.valve.run.train_modes import natural_frequencies, resonance_speeds

    spring = _spring(args)
    cam, vt = _load_cam_and_train(args)
    if not 1 <= args.count <= 20:
        raise InputError(f"--count = {args.count} must be from 1 to 20")
    if args.cam_contact == "open":
        return _train_modes_separated(args, spring, cam, vt)
    if args.valve_lift is not None:
        raise InputError("--valve-lift applies to --cam-contact open (the closed train is linearised at full lift)")
    rpms = cam_rpm_from_args(args, ranged=True)
    with as_options(count="--count"):
        res = natural_frequencies(spring, cam, vt, count=args.count)
    table = resonance_speeds(res["full_lift_Hz"] or res["base_circle_Hz"], float(rpms.min()), float(rpms.max()))
    if args.json:
        print_json({**res, "resonance_speeds": table})
        return 0
    rows = [
        (
            str(i + 1),
            f"{b:.1f}" if i < len(res["base_circle_Hz"]) else "-",
            f"{f:.1f}" if i < len(res["full_lift_Hz"]) else "-",
        )
        for i, (b, f) in enumerate(
            zip(res["base_circle_Hz"] + [0.0] * args.count, res["full_lift_Hz"] + [0.0] * args.count)
        )
        if i < max(len(res["base_circle_Hz"]), len(res["full_lift_Hz"]))
    ]
    print_table(
        rows, headers=("mode", "base circle [Hz]", f"full lift ({res['full_lift_cam_angle_deg']:.0f} deg) [Hz]")
    )
    for note in res["notes"]:
        print("note: " + note)
    print(
        f"cam-order resonances (cam rpm = 60 f / N, full-lift frequencies) from {rpms.min():g} to {rpms.max():g} "
        "cam rpm:"
    )
    print_table(
        [(str(r["mode"]), f"{r['frequency_Hz']:.1f}", str(r["order"]), f"{r['cam_rpm']:.0f}") for r in table],
        headers=("mode", "f [Hz]", "order N", "cam rpm"),
    )
    return 0


def _train_modes_separated(args, spring, cam, vt) -> int:
    """``train-modes --cam-contact open``: the separated train and its jump frequency."""
    from springdyn.valve.run.train_modes import separated_frequencies

    lift = quantity(args.valve_lift, "m", "--valve-lift") if args.valve_lift is not None else None
    with as_options(count="--count", valve_lift="--valve-lift"):
        res = separated_frequencies(spring, cam, vt, count=args.count, valve_lift=lift)
    if args.json:
        print_json({"cam_contact": "open", **res})
        return 0
    print(
        f"separated train (cam contact open, valve off its seat) at valve lift {res['valve_lift_m'] * 1e3:.3f} mm, "
        f"static spring force {res['spring_force_N']:.1f} N"
    )
    print_table(
        [(str(i + 1), f"{f:.1f}") for i, f in enumerate(res["frequencies_Hz"])], headers=("mode", "frequency [Hz]")
    )
    print(f"jump frequency (first mode of the separated train): {res['jump_frequency_Hz']:.1f} Hz")
    return 0


def cmd_frf(args) -> int:
    from springdyn.valve.spring.frf import dynamic_stiffness

    spring = _spring(args)
    freq = parse_range(args.frequency, "Hz", "--frequency", bare_unit="Hz")
    length = quantity(args.length, "m", "--length") if args.length is not None else None
    with as_options(length="--length", frequency="--frequency"):
        res = dynamic_stiffness(spring, freq, length)
    if emit(res, args):
        return 0
    if not args.csv:
        step = max(1, res.frequency.size // 25)
        rows = [
            (f"{f:.1f}", f"{abs(r) / 1e3:.3f}", f"{abs(st) / 1e3:.3f}")
            for f, r, st in zip(res.frequency[::step], res.retainer[::step], res.seat[::step])
        ]
        print(
            f"{spring.type} spring, {res.model} model, at {res.length * 1e3:.3f} mm: static rate "
            f"{res.static_stiffness / 1e3:.3f} N/mm, modes " + ", ".join(f"{f:.1f}" for f in res.modes) + " Hz"
        )
        print_table(rows, headers=("frequency [Hz]", "retainer [N/mm]", "seat [N/mm]"))
    return 0


def cmd_design(args) -> int:
    spring = _spring(args)
    lift = quantity(args.lift, "m", "--lift") if args.lift is not None else None
    rpm = (
        quantity(args.cam_rpm, "rad/s", "--cam-rpm", bare_unit="rpm") * 60 / (2 * 3.141592653589793)
        if args.cam_rpm
        else None
    )
    with as_options(**RUN_OPTIONS):
        fig = spring.spring_model.design_figures(lift=lift, cam_rpm=rpm)
    if args.json:
        print_json(fig)
        return 0
    print(
        f"spring index C = {fig['spring_index']:.3f}, Bergstraesser k = {fig['bergstraesser_factor']:.4f}, "
        f"Wahl k = {fig['wahl_factor']:.4f}"
    )
    print(
        f"coils: {fig['total_coils']:g} total, {fig['active_coils']:g} active ({fig['dead_coils_per_end']:g} dead per end); "
        f"solid length Lc = {fig['solid_length_m'] * 1e3:.3f} mm ({fig['solid_length_source']}); "
        f"spring mass M = {fig['spring_mass_kg'] * 1e3:.2f} g"
    )
    rows = []
    for state in ("installed", "open", "coil_contact"):
        if state in fig:
            s = fig[state]
            rows.append(
                (
                    state,
                    f"{s['length_m'] * 1e3:.3f}",
                    f"{s['force_N']:.1f}",
                    f"{s['shear_stress_Pa'] / 1e6:.0f}",
                    f"{s['surge_frequency_Hz']:.1f}",
                    f"{s['surge_margin']:.2f}" if "surge_margin" in s else "-",
                )
            )
    print_table(rows, headers=("state", "length [mm]", "force [N]", "stress [MPa]", "surge [Hz]", "surge margin"))
    if "coil_bind" in fig:
        cb = fig["coil_bind"]
        verdict = "ok" if cb["coil_bind_ok"] else ("THROUGH SOLID" if cb["through_solid"] else "BELOW CLEARANCE")
        print(
            f"coil bind: {cb['coil_bind_margin_m'] * 1e3:.3f} mm above solid at full lift "
            f"(clearance {cb['coil_bind_clearance_m'] * 1e3:.3f} mm): {verdict}"
        )
    if "coil_contact_note" in fig:
        print(f"note: {fig['coil_contact_note']}")
    if "load_points" in fig:
        _print_load_points(fig["load_points"])
    if "fatigue" in fig:
        f = fig["fatigue"]
        print(
            f"fatigue (Goodman, installed -> open): safety factor {f['static_fatigue_safety_factor']:.2f}; "
            f"endurance {f['endurance_shear_strength_Pa'] / 1e6:.0f} MPa, ultimate shear "
            f"{f['ultimate_shear_strength_Pa'] / 1e6:.0f} MPa"
            + (f" (defaults for {', '.join(f['strength_defaults'])})" if f["strength_defaults"] else "")
        )
    return 0


def _gas_force(args, cam, vt):
    """``--gas-pressure``: the trace's force on the valve, phased by the cam's ``[timing]``."""
    if not args.gas_pressure:
        return None
    from springdyn.valve.cam.timing import crank_axis
    from springdyn.valve.train.gas_force import GasForce

    if vt is None:
        raise InputError("--gas-pressure acts on the valve: give --valve-train (the spring alone has no valve)")
    if vt.seat_diameter is None:
        raise InputError(f"--gas-pressure needs the valve's seat_diameter in [valve_train] ({args.valve_train})")
    timing = _timing(args.cam) or _timing(args.spring)
    if timing is None:
        raise InputError(
            "--gas-pressure is against crank angle: the cam file needs a [timing] table (lobe_centre, valve) to phase it"
        )
    port = quantity(args.port_pressure, "Pa", "--port-pressure")
    with as_options(path="--gas-pressure"):
        return GasForce.from_file(
            existing_file(args.gas_pressure, "--gas-pressure"),
            axis=crank_axis(cam, timing),
            seat_diameter=vt.seat_diameter,
            port_pressure=port,
        )


def _crank_axis(args, cam):
    """Crank angles for the outputs: with an engine speed or the cam file's ``[timing]`` table."""
    from springdyn.valve.cam.timing import crank_axis

    timing = _timing(args.cam)
    if timing is None and getattr(args, "spring", None):  # one file may hold the whole definition
        timing = _timing(args.spring)
    if getattr(args, "engine_rpm", None) is None and timing is None:
        return None
    return crank_axis(cam, timing)


def _timing(cam_file):
    """The file's ``[timing]`` table (the cam's, or the definition's), or None."""
    from springdyn.valve.cam.timing import Timing

    return Timing.in_file(cam_file)


def _load_cam_and_train(args):
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.train.definition import ValveTrain

    cam = Cam.from_toml(args.cam)
    vt = ValveTrain.from_toml(args.valve_train) if getattr(args, "valve_train", None) else None
    return cam, vt


def cmd_speed_ramp(args, spring, cam, vt) -> int:
    """``valve simulate --speed-ramp START:END:RATE``: the run-up (:func:`springdyn.valve.run.run_up.speed_ramp`)."""
    from springdyn.valve.run.run_up import speed_ramp

    parts = args.speed_ramp.split(":")
    if len(parts) != 3:
        raise InputError(f"--speed-ramp = {args.speed_ramp!r} must be START:END:RATE, e.g. 2500:3500:2000")
    start, end = (quantity(x, "rpm", "--speed-ramp", bare_unit="rpm") for x in parts[:2])
    rate = quantity(parts[2], "rad/s**2", "--speed-ramp", bare_unit="rpm/s") * 60.0 / (2.0 * 3.141592653589793)
    with as_options(start="--speed-ramp", end="--speed-ramp", rate_rpm_per_s="--speed-ramp"):
        res = speed_ramp(spring, cam, vt, start, end, rate, rtol=args.rtol, atol=args.atol)
    if emit(res, args, json_data=dict(res.summary)):
        return 0
    s = res.summary
    _print_coils(spring.coil_facts)
    print(
        f"speed ramp {start:g} -> {end:g} cam rpm at {rate:g} rpm/s: {s['duration_s']:.3f} s, {s['revolutions']} "
        "revolutions, each judged at its mean speed"
    )
    t = res.revolutions()
    print_table(
        [
            (
                f"{t['cam_rpm'][i]:.0f}",
                "FLOAT" if t["nose_separation"][i] else ("lift-off" if t["liftoff"][i] else "-"),
                str(t["seat_landings"][i]),
                f"{t['min_cam_contact_force_N'][i]:.1f}",
                f"{t['max_retainer_force_N'][i]:.1f}",
            )
            for i in range(t["cam_rpm"].size)
        ],
        headers=("cam rpm", "separation", "seat landings", "min cam force [N]", "max retainer force [N]"),
    )
    onset, steady = s["float_onset_cam_rpm"], s["steady_float_cam_rpm"]
    print(
        (
            "float (lift-off over the nose) from " + f"{onset:.0f} cam rpm of the ramp"
            if onset
            else "no float in the ramp"
        )
        + (f"; steady-state float speed {steady:.0f} cam rpm" if steady else "; no steady-state float in the range")
    )
    print_notes(s)
    return 0


def cmd_simulate(args) -> int:
    from springdyn.valve.run.simulation import simulate

    spring = _spring(args)
    cam, vt = _load_cam_and_train(args)
    if getattr(args, "speed_ramp", None):
        given = [o for o, v in (("--gas-pressure", args.gas_pressure), ("--revolutions", args.revolutions)) if v]
        if given:
            raise InputError(
                f"--speed-ramp runs from the periodic steady state at its start: {given[0]} does not apply"
            )
        return cmd_speed_ramp(args, spring, cam, vt)
    rpm = cam_rpm_from_args(args, ranged=False)
    gas = _gas_force(args, cam, vt)
    with as_options(**RUN_OPTIONS):
        sim = simulate(
            spring,
            cam,
            rpm,
            valve_train=vt,
            **_run_length(args),
            rtol=args.rtol,
            atol=args.atol,
            points_per_revolution=args.points_per_revolution,
            backend=args.backend,
            gas_force=gas,
        )
    sim.set_crank_axis(_crank_axis(args, cam))  # crank angles beside the cam's

    def angles(ev):  # an event's cam angles, and its crank angles when the run has them
        text = f"{ev['start_deg']:.2f}-{ev['end_deg']:.2f} cam deg"
        if "start_timing" in ev:
            return f"{text} ({ev['start_timing']} to {ev['end_timing']})"
        if "start_crank_deg" in ev:
            return f"{text} ({ev['start_crank_deg']:.1f}-{ev['end_crank_deg']:.1f} crank deg)"
        return text

    if args.csv:
        sim.to_csv(args.csv)
    if args.plot:
        close_figure(sim.plot(args.plot))
    if args.closure_map:
        close_figure(sim.plot_closure_map(args.closure_map))
    announce_written([args.csv, args.plot, args.closure_map], args)
    s = sim.summary
    if args.json:
        print_json(s)
        return 0
    if s["periodicity_error"] is None:
        period = "periodicity n/a (1 revolution)"
    else:
        period = (
            f"{'periodic' if s['periodic'] else 'NOT periodic'}: {100 * s['periodicity_error']:.2f} % of Fset "
            "change from the revolution before"
        )
    print(f"{spring.type} spring, {cam.law} cam at {rpm:g} cam rpm, last of {s['revolutions']} revolutions ({period})")
    _print_coils(s["spring"])
    rows = [
        (
            "retainer force",
            f"{s['max_retainer_force_N']:.1f}",
            f"{s['min_retainer_force_N']:.1f}",
            f"{s['max_retainer_force_ratio']:.3f}",
            f"{s['retainer_surge_amplitude_N']:.1f}",
        ),
        (
            "seat force",
            f"{s['max_seat_force_N']:.1f}",
            f"{s['min_seat_force_N']:.1f}",
            f"{s['max_seat_force_ratio']:.3f}",
            f"{s['seat_surge_amplitude_N']:.1f}",
        ),
        ("static force", f"{s['max_static_force_N']:.1f}", f"{s['min_static_force_N']:.1f}", "1", "0"),
    ]
    print_table(rows, headers=("", "max [N]", "min [N]", "max/static", "surge [N]"))
    if "band" in s:
        b = s["band"]
        print(
            "did not settle: over the last revolutions the extremes scatter: max retainer "
            f"{b['max_retainer_force_N'][0]:.1f}-{b['max_retainer_force_N'][1]:.1f} N, min retainer "
            f"{b['min_retainer_force_N'][0]:.1f}-{b['min_retainer_force_N'][1]:.1f} N, max seat "
            f"{b['max_seat_force_N'][0]:.1f}-{b['max_seat_force_N'][1]:.1f} N"
            + (
                f", seat impact velocity {b['seat_impact_velocity_m_per_s'][0]:.2f}-"
                f"{b['seat_impact_velocity_m_per_s'][1]:.2f} m/s"
                if vt is not None
                else ""
            )
        )
    print(
        f"f1 = {s['f1_Hz']:.1f} Hz = cam order {s['f1_cam_order']:.2f}; strongest harmonics: "
        + ", ".join(
            f"{h['order']}: {h['amplitude_N']:.1f} N"
            for h in sorted(s["spectrum"], key=lambda h: -h["amplitude_N"])[:4]
        )
    )
    if s["coil_contact"]:
        for ev in s["coil_contact"]:
            els = ev["elements"]
            where = ", ".join(els) if len(els) <= 4 else f"{len(els)} elements, from {els[0]} to {els[-1]}"
            print(
                f"coil contact {angles(ev)} in {where} (element number:name from the "
                f"seat), peak element force {ev['peak_contact_force_N']:.1f} N"
                + (", a clash" if ev.get("clash") else "")
            )
    else:
        print("no coil contact")
    if "clashing_coils" in s:
        print("clashing coils (from the seat): " + (", ".join(map(str, s["clashing_coils"])) or "none"))
    cc = s["coil_clash"]
    if cc["impacts"]:
        print(
            f"coil clash: {cc['impacts']} impacts over {cc['duration_deg']:.1f} cam degrees, up to "
            f"{cc['peak_force_through_contact_N']:.1f} N through the closed coils' contact"
        )
    for ev in s["end_separation"]:
        print(f"END SEPARATION at the {ev['end']} {angles(ev)} ({ev['duration_s'] * 1e3:.3f} ms)")
    if vt is not None:
        if s["liftoff"]:
            for ev in s["liftoff"]:
                gap = f", gap {ev['max_gap_m'] * 1e3:.3f} mm" if "max_gap_m" in ev else ""
                print(f"LIFT-OFF {angles(ev)} ({ev['duration_s'] * 1e3:.3f} ms{gap}) on the {ev['phase']}")
            print(
                "FLOAT: the valve leaves the cam over the nose"
                if s["nose_separation"]
                else "bounce only: the valve stays on the cam over the nose (no float)"
            )
        else:
            print(f"no lift-off: minimum cam contact force {s['min_cam_contact_force_N']:.1f} N")
        if "max_gas_force_N" in s:
            print(
                f"gas force on the valve: up to {s['max_gas_force_N']:.0f} N, {s['gas_force_at_opening_N']:.0f} N as it "
                "leaves its seat"
            )
        if "hla" in s:
            h = s["hla"]
            print(
                f"hydraulic lash adjuster: collapse {h['collapse_min_m'] * 1e6:.1f} to {h['collapse_max_m'] * 1e6:.1f} um, "
                f"length change {h['length_change_per_revolution_m'] * 1e6:+.3f} um per revolution, chamber up to "
                f"{h['peak_pressure_Pa'] / 1e5:.1f} bar above the supply; oil in {h['inflow_per_revolution_m3'] * 1e9:.4f}, "
                f"out {h['leak_per_revolution_m3'] * 1e9:.4f} mm^3 per revolution"
                + (f"; valve held open {h['valve_held_open_m'] * 1e3:.3f} mm" if h["valve_held_open_m"] > 1e-6 else "")
                + (f"; socket hop {h['socket_hop_deg']:.1f} deg" if h["socket_hop"] else "")
            )
        print(
            f"seat impact velocity {s['seat_impact_velocity_m_per_s']:.3f} m/s, bounces {s['bounces']}, "
            f"max bounce {s['max_bounce_height_m'] * 1e3:.3f} mm"
        )
    fs, fd = s["static_fatigue_safety_factor"], s["fatigue_safety_factor"]
    print(
        "fatigue safety factor (Goodman): static "
        + (f"{fs:.2f}" if fs is not None else "-")
        + ", dynamic "
        + (f"{fd:.2f}" if fd is not None else "-")
        + f" (element {s['fatigue_critical_element']}, {s['min_shear_stress_Pa'] / 1e6:.0f}-"
        f"{s['max_shear_stress_Pa'] / 1e6:.0f} MPa)"
        + (f"; smallest coil gap {s['min_coil_gap_m'] * 1e3:.3f} mm" if s.get("min_coil_gap_m") is not None else "")
    )
    print(
        f"wire stress (torsion only; {s['max_force_through_coil_contact_N']:.1f} N passed through coil contact at most): "
        f"peak {s['peak_shear_stress_Pa'] / 1e6:.0f} MPa in element {s['peak_shear_stress_element']}, limit "
        f"{s['shear_stress_limit_Pa'] / 1e6:.0f} MPa: " + ("ok" if s["wire_stress_ok"] else "OVERSTRESS")
    )
    for note in s.get("notes", []):  # every caveat the JSON carries, in words
        print("note: " + note)
    return 0


def cmd_float(args) -> int:
    from springdyn.valve.run.float_search import float_speed

    spring = _spring(args)
    cam, vt = _load_cam_and_train(args)
    rpms = cam_rpm_from_args(args, ranged=True)
    with as_options(**RUN_OPTIONS):
        res = float_speed(
            spring,
            cam,
            vt,
            rpms,
            resolution=quantity(args.resolution, "rpm", "--resolution", bare_unit="rpm"),
            progress_quiet=args.quiet,
            **_run_length(args),
        )
    if args.csv:
        res.to_csv(args.csv)
    if args.plot:
        close_figure(res.plot(args.plot))
    announce_written([args.csv, args.plot], args)
    if args.json:
        print_json(res.to_dict())
        return 0
    s = res.summary
    sc = res.scan
    _print_coils(spring.coil_facts)
    rows = []
    for i, rpm in enumerate(res.cam_rpm):
        phase = sc["first_liftoff_phase"][i] or ("off the cam" if sc["liftoff"][i] else "-")
        band = (
            f"{sc['seat_impact_velocity_min_m_per_s'][i]:.2f}/{sc['seat_impact_velocity_median_m_per_s'][i]:.2f}/"
            f"{sc['seat_impact_velocity_max_m_per_s'][i]:.2f}"
        )
        rows.append(
            (
                f"{rpm:g}",
                f"{sc['min_cam_contact_force_N'][i]:.1f}",
                phase,
                "yes" if sc["nose_separation"][i] else "no",
                str(sc["seat_landings"][i]),
                f"{1e3 * sc['seat_rebound_height_m'][i]:.3f}",
                band,
                "yes" if sc["periodic"][i] else f"no ({100 * sc['periodicity_error'][i]:.3g} %)",
            )
        )
    print_table(
        rows,
        headers=(
            "cam rpm",
            "min cam force [N]",
            "first lift-off",
            "over the nose",
            "seat landings",
            "rebound [mm]",
            "seating v min/med/max [m/s]",
            "periodic",
        ),
    )
    print("seating velocity band: min/median/max over the scanned speeds within +-25 rpm and, where a speed does not")
    print("settle, over its last revolutions")
    if s["first_separation_cam_rpm"] is not None:
        print(f"first lift-off: {s['first_separation_cam_rpm']:.0f} cam rpm ({s['first_separation_phase']})")
    else:
        print(f"no lift-off up to {rpms.max():g} cam rpm")
    if res["float_cam_rpm"] is None:
        print(f"float speed: above {rpms.max():g} cam rpm (no separation over the nose at the highest speed)")
    else:
        f = res["float_cam_rpm"]
        print(
            f"float speed: {f:.0f} cam rpm ({2 * f:.0f} engine rpm, four-stroke), the valve separating over the nose "
            "at every higher scanned speed"
        )
    for note in s.get("notes", []):
        print("note: " + note)
    return 0


def parse_vary(text: str, spring: ValveSpring):
    """``FIELD=START:STOP:STEP`` (values with units) -> (field, SI values)."""
    import dataclasses

    if "=" not in text:
        raise InputError(f"--vary {text!r} must read FIELD=START:STOP:STEP, e.g. installed_length=36mm:40mm:0.5mm")
    name, rng = (t.strip() for t in text.split("=", 1))
    meta = {f.name: f.metadata for f in dataclasses.fields(ValveSpring)}
    if name not in meta or meta[name].get("kind") != "quantity":
        numeric = [k for k, m in meta.items() if m.get("kind") == "quantity"]
        raise InputError(f"--vary {name}: not a numeric spring field; choose one of {', '.join(numeric)}")
    return name, parse_range(rng, meta[name]["unit"], f"--vary {name}")


def cmd_sweep(args) -> int:
    from pathlib import Path

    from springdyn.valve.run.sweeps import connect, describe_design_value, sweep

    spring = _spring(args)
    cam, vt = _load_cam_and_train(args)
    rpms = cam_rpm_from_args(args, ranged=True)
    vary = parse_vary(args.vary, spring) if args.vary else None
    gas = _gas_force(args, cam, vt)
    if args.workers is not None and args.workers < 1:
        raise InputError(f"--workers = {args.workers} must be at least 1")
    with as_options(scheduler="--scheduler"):
        client = connect(args.scheduler) if args.scheduler else None
    try:
        with as_options(vary="--vary", workers="--workers", **RUN_OPTIONS):
            res = sweep(
                spring,
                cam,
                rpms,
                valve_train=vt,
                **_run_length(args),
                points_per_revolution=args.points_per_revolution,
                rtol=args.rtol,
                atol=args.atol,
                vary=vary,
                on_invalid=args.on_invalid,
                workers=args.workers,
                client=client,
                quiet=args.quiet,
                gas_force=gas,
            )
    finally:
        if client is not None:
            client.close()
    res.set_crank_axis(_crank_axis(args, cam))
    engine = res.crank_axis is not None

    def speed(rpm):  # a cam speed, with the engine's beside it when the sweep has crank angles
        return f"{rpm:g} cam rpm" + (f" ({res.crank_axis.per_cam * rpm:g} engine rpm)" if engine else "")

    written = res.write(Path(args.out))
    table = res.summary_table()
    where = "on " + args.scheduler if args.scheduler else "locally"
    _print_coils(spring.coil_facts)
    print(
        f"swept {rpms.size} speeds ({rpms.min():g}-{rpms.max():g} cam rpm"
        + (f", {res.engine_rpm.min():g}-{res.engine_rpm.max():g} engine rpm)" if engine else ")")
        + (f" x {res.vary_values.size} values of {res.vary_name}" if vary else "")
        + f" {where}"
    )
    k = int(np.argmax(table["max_retainer_force_N"]))
    print(
        f"peak retainer force {table['max_retainer_force_N'][k]:.1f} N at {speed(table['cam_rpm'][k])} "
        f"(static peak {table['max_static_force_N'][k]:.1f} N); coil contact at "
        f"{int(np.sum(table['coil_contact']))} of {table['cam_rpm'].size} runs, coil clash at "
        f"{int(np.sum(table['coil_clash']))}"
    )
    sm = res.summary
    print(
        f"periodic steady state: {table['cam_rpm'].size - sm['speeds_not_periodic']} of {table['cam_rpm'].size} runs "
        f"settled within {100 * res.periodicity_tol:g} % of Fset ({np.mean(table['revolutions']):.1f} revolutions on "
        "average)"
        + (
            f"; {sm['speeds_not_periodic']} did not settle in {int(np.max(table['revolutions']))} revolutions: their "
            "extremes are bands (*_lo_N, *_hi_N in sweep_summary.csv)"
            if sm["speeds_not_periodic"]
            else ""
        )
    )
    if vt is not None:
        for v, f, first in zip(res.vary_values, res.float_speeds(), res.first_separation_speeds()):
            tag = f"{describe_design_value(res.vary_name, v)}: " if vary else ""
            print(
                f"{tag}float speed "
                + (
                    f"~{speed(f)} (lowest swept speed from which the valve leaves the cam over the nose at every "
                    "higher one; refine with 'springdyn valve float')"
                    if np.isfinite(f)
                    else "above the swept range"
                )
                + (f"; first lift-off at {speed(first)}" if np.isfinite(first) else "")
            )
    if "valve_held_open_m" in table:
        pumped = np.flatnonzero(np.asarray(table["valve_held_open_m"]) > 1e-6)
        if pumped.size:
            i = int(pumped[0])
            print(
                f"PUMP-UP: the hydraulic lash adjuster holds the valve open on the base circle from "
                f"{speed(table['cam_rpm'][i])} (up to {np.max(table['valve_held_open_m']) * 1e3:.3f} mm; "
                "column valve_held_open_m)"
            )
    # every caveat (the periodicity one is the line above)
    print_notes(sm, skip=(f"{sm['speeds_not_periodic']} speeds did not settle",))
    for value, reason in res.skipped:
        print(f"skipped {describe_design_value(res.vary_name, value)}: {reason}")
    first = [r for r in res.resonance_table() if r["mode"] == 1]
    if first:
        print(
            f"cam-order resonances of the first mode ({first[0]['frequency_Hz']:.0f} Hz at full lift): "
            + ", ".join(f"N={r['order']} at {r['cam_rpm']:.0f}" for r in first)
            + " cam rpm (all modes: "
            "sweep_resonances.csv)"
        )
    print(f"wrote {len(written)} files to {Path(args.out).resolve()}")
    return 0
