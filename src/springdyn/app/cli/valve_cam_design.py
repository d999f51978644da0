"""``springdyn valve cam-from-lift``, ``springdyn valve cam-check`` and ``springdyn valve
kinematics``: the cam and lever designer's commands (thin layer over
:mod:`springdyn.valve.cam.from_lift`, :mod:`springdyn.valve.cam.checks` and
:mod:`springdyn.valve.train.lever`)."""

from __future__ import annotations

from pathlib import Path

import springdyn.valve as valve
import springdyn.valve.cam as cam
from springdyn.app.cli.common import (
    add_output_options,
    announce_written,
    as_options,
    close_figure,
    emit,
    print_json,
    print_notes,
    quantity,
)
from springdyn.app.cli.valve_options import add_speed_options, cam_rpm_from_args, run_options
from springdyn.core.errors import InputError

__all__ = ["register", "cmd_cam_from_lift", "cmd_cam_check", "cmd_kinematics"]


def register(vsub) -> None:
    """Add ``cam-from-lift`` and ``cam-check`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "cam-from-lift",
        help="the lobe a wanted valve lift (LIFT.csv) or a cam card (--card) needs through the valve train "
        "(the backward solution), with lash ramps",
    )
    p.add_argument(
        "lift",
        nargs="?",
        metavar="LIFT.csv",
        help="wanted valve lift over one revolution: columns cam_angle_deg, valve_lift_m (or valve_lift_mm)",
    )
    p.add_argument(
        "--card",
        metavar="CARD.toml",
        help="instead of LIFT.csv: a [cam_card] table (lift, duration at a check height, ramps); a [timing] table "
        "beside it goes with the cam",
    )
    p.add_argument(
        "--valve-train",
        required=True,
        metavar="VT.toml",
        help="[valve_train] table (rocker ratio, lash); a [follower] table beside it adds the profile checks",
    )
    p.add_argument(
        "--out",
        dest="cam_out",
        required=True,
        metavar="CAM.toml",
        help="write the [cam] table there (a table's lobe lift beside it, CAM_lobe_lift.csv)",
    )
    p.add_argument(
        "--ramp-angle",
        metavar="DEG",
        help="with LIFT.csv: cam angle of each lash ramp (default: 2 x lash at the lobe / the valve lift's opening "
        "velocity; needed when the table opens at zero velocity; bare number: deg)",
    )
    add_output_options(p)
    p.set_defaults(func=cmd_cam_from_lift)

    p = vsub.add_parser(
        "cam-check",
        help="the cam designer's checks: radius of curvature and undercut, flat-tappet contact excursion, "
        "pressure angle, Hertz stress along the cam against the allowable",
    )
    p.add_argument("cam", metavar="CAM.toml", help="file with a [cam] table")
    p.add_argument(
        "--valve-train", required=True, metavar="VT.toml", help="file with the [valve_train] and [follower] tables"
    )
    p.add_argument(
        "--spring",
        metavar="SPRING.toml",
        help="the valve spring or a spring pack's file: the kinematic load (spring force + inertia) and the Hertz "
        "stress",
    )
    p.add_argument(
        "--model",
        choices=valve.MODEL_NAMES,
        help="spring model of the static force (default: the [spring] model key, else 'type-c')",
    )
    add_speed_options(p, ranged=False, required=False, what="the speed of the load (needs --spring; default 0: static)")
    add_output_options(p)
    p.set_defaults(func=cmd_cam_check)

    p = vsub.add_parser(
        "kinematics",
        help="a drawn lever's kinematics over the cam: ratio, moment arms, valve lift, pad travel on the stem, "
        "mass at the valve (the [geometry] table)",
    )
    p.add_argument("cam", metavar="CAM.toml", help="file with a [cam] table (the lobe)")
    p.add_argument(
        "--valve-train",
        required=True,
        metavar="VT.toml",
        help="file with [valve_train], [follower] (a roller) and [geometry] (the lever drawn at rest)",
    )
    add_output_options(p)
    p.set_defaults(func=cmd_kinematics)


# ----------------------------------------------------------------------------- helpers
def _follower(path, *, required: bool):
    follower = valve.Follower.in_file(path)
    if follower is None and required:
        raise InputError(
            f"{path}: no [follower] table: the cam checks need the follower's geometry beside [valve_train] "
            "(see examples/valve/valve_train_with_follower.toml)"
        )
    return follower


# ----------------------------------------------------------------------------- commands
def cmd_cam_from_lift(args) -> int:
    """``springdyn valve cam-from-lift``: the lobe of a valve-lift table or a cam card."""
    from springdyn.core.io import check_output_file

    if (args.lift is None) == (args.card is None):
        raise InputError("give the wanted valve lift LIFT.csv or --card CARD.toml (one of them)")
    if args.card is not None and args.ramp_angle is not None:
        raise InputError("--ramp-angle applies to LIFT.csv; a card gives its ramps in its [cam_card] table")
    out = check_output_file(args.cam_out, "--out")
    for given, what in ((args.lift, "LIFT.csv"), (args.card, "--card"), (args.valve_train, "--valve-train")):
        if given is not None and Path(given).exists() and Path(given).resolve() == out.resolve():
            raise InputError(f"--out = {str(args.cam_out)!r} is the input {what}: writing the lobe would overwrite it")
    vt = valve.ValveTrain.from_toml(args.valve_train)
    follower = _follower(args.valve_train, required=False)
    if args.lift is not None:
        ramp = quantity(args.ramp_angle, "rad", "--ramp-angle", bare_unit="deg") if args.ramp_angle else None
        angle, lift = cam.read_valve_lift_table(args.lift)
        with as_options(ramp_angle="--ramp-angle"):
            res = cam.cam_from_valve_lift(angle, lift, vt, ramp_angle=ramp, name=str(args.lift))
        header = f"lobe for the valve lift {args.lift} through {args.valve_train}, by springdyn valve cam-from-lift"
    else:
        res = cam.cam_from_card(cam.CamCard.from_toml(args.card), vt, valve.Timing.in_file(args.card))
        header = f"lobe of the cam card {args.card} through {args.valve_train}, by springdyn valve cam-from-lift"
    s = res.summary
    header += (
        f"\nmax valve lift {s['max_valve_lift_m'] * 1e3:.4f} mm; duration at 1 mm valve lift "
        f"{s['duration_at_1mm_deg']:.4f} cam deg"
    )
    written = cam.write_cam(res, out, header)
    check = cam.check_cam(res.cam, vt, follower) if follower is not None else None
    if args.csv:
        written.append(res.to_csv(args.csv))
    if args.plot:
        close_figure(res.plot(args.plot))
        written.append(args.plot)
    announce_written(written, args)
    if args.json:
        print_json(dict(s, written=[str(p) for p in written], **({"check": dict(check.summary)} if check else {})))
        return 0
    print(res.describe())
    if check is not None:
        cs = check.summary
        print(f"profile checks ([follower] {cs['follower']}, base circle {cs['base_circle_radius_m'] * 1e3:g} mm):")
        print(check.checks_text())
        print_notes(cs, skip=("no load given",))
    print(f"next: springdyn valve cam-check {out} --valve-train {args.valve_train} --spring SPRING.toml --cam-rpm RPM")
    return 0


def cmd_cam_check(args) -> int:
    """``springdyn valve cam-check``: curvature, excursion, pressure angle and Hertz stress."""
    lobe = valve.Cam.from_toml(args.cam)
    vt = valve.ValveTrain.from_toml(args.valve_train)
    follower = _follower(args.valve_train, required=True)
    timing = valve.Timing.in_file(args.cam)
    rpm = cam_rpm_from_args(args, ranged=False, timing=timing)
    if rpm is not None and args.spring is None:
        raise InputError("--cam-rpm and --engine-rpm set the speed of the load: give the spring with --spring")
    if args.model is not None and args.spring is None:
        raise InputError("--model applies to the spring: give it with --spring")
    # the spring file's spring, or its pack (the kinematic load: the pack's static force, a third of its springs' mass)
    spring = valve.ValveModel.from_files(args.spring, model=args.model).spring if args.spring else None
    with as_options(cam_rpm=run_options(args, timing=timing)["cam_rpm"]):
        res = cam.check_cam(lobe, vt, follower, spring=spring, cam_rpm=rpm)
    if not emit(res, args, json_data=dict(res.summary)):
        print(res.describe())
    return 0


def cmd_kinematics(args) -> int:
    """``springdyn valve kinematics``: the drawn lever over the cam."""
    lobe = valve.Cam.from_toml(args.cam)
    vt = valve.ValveTrain.from_toml(args.valve_train)
    if vt.geometry is None:
        raise InputError(
            f"{args.valve_train}: no [geometry] table: the lever's kinematics need its drawing beside [valve_train] "
            "and [follower] (see examples/valve/finger_follower_geometry.toml); without it the ratio is the constant "
            f"{vt.ratio:g}"
        )
    res = vt.geometry.over_cam(lobe, lash=0.0 if vt.hydraulic else vt.lash, inertia=vt.lever_inertia)
    if not emit(res, args, json_data=dict(res.summary)):
        print(res.describe(str(args.valve_train)))
    return 0
