"""``springdyn valve ...`` commands: parse the options, call the valve family's front door
(:class:`springdyn.valve.ValveModel` and the design studies), emit what comes back.

Every command builds its :class:`~springdyn.valve.ValveModel` from the definition files and a
:class:`~springdyn.valve.RunSettings` from the run options (:func:`model_of`), calls one of its
studies, and prints the result's own account of itself (``describe()``), its JSON, CSV or
figure.  No numbers are made here.
"""

from __future__ import annotations

import dataclasses

import springdyn.valve as valve
from springdyn.app.cli import valve_cam_design, valve_camshaft, valve_clearance, valve_friction, valve_synthesis
from springdyn.app.cli.common import (
    add_output_options,
    announce_written,
    as_options,
    close_figure,
    emit,
    parse_range,
    print_json,
    quantity,
    whole_number,
)
from springdyn.app.cli.valve_options import (
    TRAIN_HELP,
    add_backend_option,
    add_gas_options,
    add_inputs,
    add_revolution_options,
    add_speed_options,
    add_tolerance_options,
    cam_rpm_from_args,
    model_of,
    run_options,
)
from springdyn.core.errors import InputError

__all__ = ["register"]


def register(sub) -> None:
    valve_p = sub.add_parser("valve", help="valve springs: MMS Type C multi-mass or distributed coil-by-coil model")
    vsub = valve_p.add_subparsers(dest="valve_command", metavar="COMMAND", required=True)

    p = vsub.add_parser("params", help="internal parameters and model variables")
    add_inputs(p, cam=False)
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
    p.add_argument(
        "--out", dest="calibrated_out", metavar="FILE.toml", help="write the calibrated definition there (a file)"
    )
    p.add_argument(
        "--trace",
        metavar="TRACE.csv",
        help="instead: fit damping_ratio and contact_stiffness to a measured retainer-force trace "
        "(columns cam_angle_deg, retainer_force_N; needs --cam and --cam-rpm or --engine-rpm)",
    )
    p.add_argument(
        "--trace-fit",
        default="damping_ratio,contact_stiffness",
        metavar="KEYS",
        help="with --trace: what to fit, of damping_ratio and contact_stiffness (default both; the contact "
        "stiffness shows only at a clash speed)",
    )
    p.add_argument("--cam", metavar="CAM.toml", help="with --trace: the cam of the measurement")
    add_speed_options(p, ranged=False, required=False, what="with --trace: the speed of the measurement")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_calibrate)

    p = vsub.add_parser("curve", help="static force and tangent stiffness vs spring length")
    add_inputs(p, cam=False)
    p.add_argument("--from", dest="start", metavar="L1", help="first length (default: free length)")
    p.add_argument("--to", dest="stop", metavar="L2", help="last length (default: where the force is 3 Fcon)")
    p.add_argument("--points", type=int, default=400, metavar="N", help="number of lengths (default 400)")
    add_output_options(p, json=False)
    p.set_defaults(func=cmd_curve)

    p = vsub.add_parser("modes", help="natural frequencies of the chain linearised at a length")
    add_inputs(p, cam=False)
    p.add_argument("--length", required=True, metavar="L", help="spring length, e.g. 38mm")
    p.add_argument("--count", type=int, default=5, metavar="N", help="how many modes (1-5, default 5)")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_modes)

    p = vsub.add_parser(
        "train-modes",
        help="natural frequencies of spring + valve train (base circle, full lift) and the cam-order resonance speeds",
    )
    add_inputs(p, train="file with a [valve_train] table (without: the spring alone)")
    add_speed_options(
        p,
        ranged=True,
        required=False,
        what="the range of the resonance table, START:STOP:STEP (default 500:8000:500 cam rpm)",
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
    p.set_defaults(func=cmd_train_modes, engine_rpm=None)

    p = vsub.add_parser("frf", help="linearised dynamic stiffness against frequency (seat fixed, retainer driven)")
    add_inputs(p, cam=False)
    p.add_argument(
        "--frequency", required=True, metavar="START:STOP:STEP", help="frequencies, e.g. 10:3000:5 (bare numbers: Hz)"
    )
    p.add_argument("--length", metavar="L", help="spring length of the static state (default: installed length)")
    add_output_options(p)
    p.set_defaults(func=cmd_frf)

    p = vsub.add_parser("design", help="index, corrected stress, surge frequency at installed/open/coil-contact length")
    add_inputs(p, cam=False)
    p.add_argument("--lift", metavar="LIFT", help="maximum valve lift, e.g. 9mm")
    add_speed_options(p, ranged=False, required=False, what="the speed of the surge margin")
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_design)

    p = vsub.add_parser("simulate", help="dynamic response under cam drive (spring alone or valve train)")
    add_inputs(p, train=TRAIN_HELP)
    add_speed_options(p, ranged=False, ramp=True)
    add_revolution_options(p)
    add_gas_options(p)
    p.add_argument("--points-per-revolution", type=int, default=1440, metavar="N", help="output points (default 1440)")
    add_tolerance_options(p)
    add_backend_option(p)
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
    add_inputs(p, train="file with a [valve_train] table", train_required=True)
    add_speed_options(p, ranged=True)
    add_revolution_options(p)
    p.add_argument("--resolution", default="1", metavar="RPM", help="bisection resolution in cam rpm (default 1)")
    p.add_argument("--csv", metavar="FILE.csv", help="write the minimum cam contact force against speed")
    p.add_argument(
        "--plot", metavar="FILE.png", help="plot the minimum contact force against speed, float speed marked"
    )
    p.add_argument("--json", action="store_true", help="print JSON")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_float)

    p = vsub.add_parser("sweep", help="speed sweep (optionally over a design variable), locally or on Dask")
    add_inputs(p, train=TRAIN_HELP)
    add_speed_options(p, ranged=True)
    add_gas_options(p)
    add_revolution_options(p)
    p.add_argument("--points-per-revolution", type=int, default=720, metavar="N", help="output points (default 720)")
    p.add_argument(
        "--vary",
        metavar="FIELD=START:STOP:STEP",
        help="also sweep a numeric spring field, e.g. installed_length=36mm:40mm:0.5mm; of a spring pack, one "
        "spring's, named by its table: inner_spring.wire_diameter=2.5mm:2.7mm:0.1mm (spring.<field>: the outer)",
    )
    p.add_argument(
        "--on-invalid",
        choices=("stop", "skip"),
        default="stop",
        help="a --vary value that makes the spring invalid: stop (default) or skip it",
    )
    p.add_argument("--out", default="valve-sweep", metavar="DIR", help="output folder (default valve-sweep)")
    p.add_argument("--workers", metavar="N", help="local threads (default: 2, both cores)")
    p.add_argument(
        "--scheduler", metavar="ADDRESS", help="run on a Dask distributed scheduler, e.g. tcp://127.0.0.1:8786"
    )
    add_tolerance_options(p)
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_sweep)

    valve_cam_design.register(vsub)  # cam-from-lift, cam-check, kinematics
    valve_friction.register(vsub)
    valve_clearance.register(vsub)
    valve_camshaft.register(vsub)
    valve_synthesis.register(vsub)
    valve_synthesis.register_inner(vsub)
    valve_synthesis.register_tolerance(vsub)
    valve_synthesis.register_life(vsub)


# ----------------------------------------------------------------------------- the spring alone
def cmd_params(args) -> int:
    table = model_of(args, cam=False, train=False).parameter_table()
    if args.json:
        print_json(table.to_dict())
        return 0
    print(f"{args.spring}: " + table.describe())
    return 0


def cmd_curve(args) -> int:
    model = model_of(args, cam=False, train=False)
    start = quantity(args.start, "m", "--from") if args.start is not None else None
    stop = quantity(args.stop, "m", "--to") if args.stop is not None else None
    with as_options(start="--from", stop="--to", points="--points"):
        curve = model.static_curve(start, stop, args.points)
    emit(curve, args)
    if not args.csv:
        print(curve.describe())
    return 0


def cmd_modes(args) -> int:
    model = model_of(args, cam=False, train=False)
    length = quantity(args.length, "m", "--length")
    with as_options(length="--length", count="--count"):
        modes = model.chain_modes(length, args.count)
    if args.json:
        print_json(modes.to_dict())
    else:
        print(modes.describe())
    return 0


def cmd_frf(args) -> int:
    model = model_of(args, cam=False, train=False)
    freq = parse_range(args.frequency, "Hz", "--frequency", bare_unit="Hz")
    length = quantity(args.length, "m", "--length") if args.length is not None else None
    with as_options(length="--length", frequency="--frequency"):
        res = model.dynamic_stiffness(freq, length)
    if not emit(res, args) and not args.csv:
        print(res.describe())
    return 0


def cmd_design(args) -> int:
    model = model_of(args, cam=False, train=False)
    lift = quantity(args.lift, "m", "--lift") if args.lift is not None else None
    rpm = cam_rpm_from_args(args, ranged=False, model=model)
    with as_options(**run_options(args, model)):
        fig = model.design_figures(lift=lift, cam_rpm=rpm)
    if args.json:
        print_json(fig.to_dict())
    else:
        print(fig.describe())
    return 0


def cmd_calibrate(args) -> int:
    from springdyn.core.io import atomic_open, check_output_file, dumps_toml
    from springdyn.core.params import load_toml
    from springdyn.core.units import format_quantity

    model = model_of(args, cam=False, train=False)
    out = check_output_file(args.calibrated_out, "--out") if args.calibrated_out else None
    doc = load_toml(args.spring)
    table = dict(doc["spring"])
    if args.trace:
        rpm = cam_rpm_from_args(args, ranged=False, model=model)
        if not (args.cam and rpm is not None):
            raise InputError(
                "--trace needs --cam (the cam of the measurement) and --cam-rpm or --engine-rpm (its speed)"
            )
        angle, force = valve.read_force_trace(args.trace)
        model = model.replace(cam=valve.Cam.from_toml(args.cam))
        with as_options(fit="--trace-fit", cam_rpm=run_options(args, model)["cam_rpm"]):
            res = model.calibrate_trace(rpm, angle, force, [k.strip() for k in args.trace_fit.split(",") if k.strip()])
        text = [f"{k}: {res['before'][k]:.6g} -> {v:.6g}" for k, v in res["values"].items()]
        text.append(f"rms deviation from the trace: {res['rms_before_N']:.3f} N -> {res['rms_N']:.3f} N")
        if "damping_ratio" in res["values"]:
            table["damping_ratio"] = round(res["values"]["damping_ratio"], 8)
        if "contact_stiffness" in res["values"]:
            table["contact_stiffness"] = f"{res['values']['contact_stiffness'] / 1e3:.6g} N/mm"
        header = f"{args.spring} calibrated by springdyn valve calibrate --trace {args.trace}: " + text[-1]
    else:
        with as_options(fit="--fit"):
            res = model.calibrate(args.fit)
        unit = ("Pa", "GPa") if args.fit == "shear_modulus" else ("", None)
        text = [
            f"{args.fit}: {format_quantity(res['before'], *unit)} -> {format_quantity(res['after'], *unit)} "
            f"(rms deviation over tolerance {res['rms_weighted_residual']:.3g})",
            "before:\n" + valve.load_points_text(res["load_points_before"]),
            "after:\n" + valve.load_points_text(res["load_points_after"]),
        ]
        table.update(valve.calibrated_keys(res, table))
        header = f"{args.spring} calibrated by springdyn valve calibrate --fit {args.fit}: " + "\n".join(
            valve.load_point_lines(res)
        )
    if args.json:
        print_json({k: v for k, v in res.items() if k != "spring"})
    else:
        print("\n".join(text))
    if out is not None:
        with atomic_open(out, "w", encoding="utf-8") as fh:
            fh.write(dumps_toml(dict(doc, spring=table), header))
        announce_written([out], args)
    return 0


# ----------------------------------------------------------------------------- the cam
def cmd_cam(args) -> int:
    cam = valve.Cam.from_toml(args.cam)
    vt = valve.ValveTrain.from_toml(args.valve_train) if args.valve_train else None
    rpm = quantity(args.engine_rpm, "rpm", "--engine-rpm", bare_unit="rpm") if args.engine_rpm else None
    with as_options(engine_rpm="--engine-rpm"):
        res = valve.analyse_cam(cam, vt, rpm, timing=valve.Timing.in_file(args.cam))
    if not emit(res, args, json_data=dict(res.summary)):
        print(res.describe())
    return 0


# ----------------------------------------------------------------------------- under the cam
def cmd_train_modes(args) -> int:
    model = model_of(args)
    if not 1 <= args.count <= 20:
        raise InputError(f"--count = {args.count} must be from 1 to 20")
    if args.cam_contact == "open":
        speed = next((o for o, v in (("--cam-rpm", args.cam_rpm), ("--engine-rpm", args.engine_rpm)) if v), None)
        if speed is not None:
            raise InputError(
                f"{speed} applies to --cam-contact closed (its cam-order resonance table): the separated train's "
                "frequencies do not depend on the speed; remove it"
            )
        lift = quantity(args.valve_lift, "m", "--valve-lift") if args.valve_lift is not None else None
        with as_options(count="--count", valve_lift="--valve-lift"):
            res = model.separated_frequencies(args.count, lift)
        if args.json:
            print_json({"cam_contact": "open", **res})
        else:
            print(valve.separated_train_text(res))
        return 0
    if args.valve_lift is not None:
        raise InputError("--valve-lift applies to --cam-contact open (the closed train is linearised at full lift)")
    if args.cam_rpm is None and args.engine_rpm is None:
        args.cam_rpm = "500:8000:500"
    rpms = cam_rpm_from_args(args, ranged=True, model=model)
    with as_options(count="--count"):
        res = model.resonance_speeds(float(rpms.min()), float(rpms.max()), args.count)
    if args.json:
        print_json(res.to_dict())
    else:
        print(res.describe())
    return 0


def cmd_simulate(args) -> int:
    model = model_of(args)
    if getattr(args, "speed_ramp", None):
        given = [o for o, v in (("--gas-pressure", args.gas_pressure), ("--revolutions", args.revolutions)) if v]
        if given:
            raise InputError(
                f"--speed-ramp runs from the periodic steady state at its start: {given[0]} does not apply"
            )
        return _speed_ramp(args, model)
    rpm = cam_rpm_from_args(args, ranged=False, model=model)
    with as_options(**run_options(args, model)):
        sim = model.simulate(rpm)
    written = []
    if args.csv:
        written.append(sim.to_csv(args.csv))
    if args.plot:
        close_figure(sim.plot(args.plot))
        written.append(args.plot)
    if args.closure_map:
        close_figure(sim.plot_closure_map(args.closure_map))
        written.append(args.closure_map)
    announce_written(written, args)
    if args.json:
        print_json(sim.summary)
    else:
        print(sim.describe())
    return 0


def _speed_ramp(args, model) -> int:
    """``valve simulate --speed-ramp START:END:RATE``: the run-up (:meth:`ValveModel.speed_ramp`)."""
    parts = args.speed_ramp.split(":")
    if len(parts) != 3:
        raise InputError(f"--speed-ramp = {args.speed_ramp!r} must be START:END:RATE, e.g. 2500:3500:2000")
    start, end = (quantity(x, "rpm", "--speed-ramp", bare_unit="rpm") for x in parts[:2])
    rate = quantity(parts[2], "rpm/s", "--speed-ramp", bare_unit="rpm/s")
    with as_options(start="--speed-ramp", end="--speed-ramp", rate_rpm_per_s="--speed-ramp"):
        res = model.speed_ramp(start, end, rate)
    if not emit(res, args, json_data=dict(res.summary)):
        print(res.describe())
    return 0


def cmd_float(args) -> int:
    model = model_of(args)
    rpms = cam_rpm_from_args(args, ranged=True, model=model)
    resolution = quantity(args.resolution, "rpm", "--resolution", bare_unit="rpm")
    with as_options(**run_options(args, model)):
        res = model.float_speed(rpms, resolution=resolution, quiet=args.quiet)
    if args.csv:
        res.to_csv(args.csv)
    if args.plot:
        close_figure(res.plot(args.plot))
    announce_written([args.csv, args.plot], args)
    if args.json:
        print_json(res.to_dict())
    else:
        print(valve.coil_line(model.spring.coil_facts))
        print(res.describe())
        if model.valve_train.adjuster_placement:
            print(f"note: adjuster: {model.valve_train.adjuster_placement}")
    return 0


def parse_vary(text: str):
    """``FIELD=START:STOP:STEP`` (values with units) -> (field, SI values)."""
    if "=" not in text:
        raise InputError(f"--vary {text!r} must read FIELD=START:STOP:STEP, e.g. installed_length=36mm:40mm:0.5mm")
    name, rng = (t.strip() for t in text.split("=", 1))
    field = name.rpartition(".")[2]  # a spring pack's: inner_spring.wire_diameter (the sweep checks the table)
    meta = {f.name: f.metadata for f in dataclasses.fields(valve.ValveSpring)}
    if field not in meta or meta[field].get("kind") != "quantity":
        numeric = [k for k, m in meta.items() if m.get("kind") == "quantity"]
        raise InputError(f"--vary {name}: not a numeric spring field; choose one of {', '.join(numeric)}")
    return name, parse_range(rng, meta[field]["unit"], f"--vary {name}")


def cmd_sweep(args) -> int:
    from pathlib import Path

    model = model_of(args)
    rpms = cam_rpm_from_args(args, ranged=True, model=model)
    vary = parse_vary(args.vary) if args.vary else None
    workers = None if args.workers is None else whole_number(args.workers, "--workers", 1, None, "of at least 1")
    with as_options(scheduler="--scheduler"):
        client = valve.connect(args.scheduler) if args.scheduler is not None else None
    try:
        with as_options(vary="--vary", workers="--workers", **run_options(args, model)):
            try:
                res = model.sweep(
                    rpms, vary=vary, on_invalid=args.on_invalid, workers=workers, client=client, quiet=args.quiet
                )
            except InputError as exc:  # the option's name, not the API's
                raise InputError(str(exc).replace("on_invalid='skip'", "--on-invalid skip")) from None
    finally:
        if client is not None:
            client.close()
    written = res.write(Path(args.out))
    print(res.describe("on " + args.scheduler if args.scheduler else "locally"))
    print(f"wrote {len(written)} files to {Path(args.out).resolve()}")
    return 0
