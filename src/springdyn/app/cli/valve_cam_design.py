"""``springdyn valve cam-from-lift``, ``springdyn valve cam-check`` and ``springdyn valve
kinematics``: the cam and lever designer's commands (thin layer over
:mod:`springdyn.valve.cam.from_lift`, :mod:`springdyn.valve.cam.checks` and
:mod:`springdyn.valve.train.lever`)."""

from __future__ import annotations

from springdyn.app.cli.common import (
    add_output_options,
    announce_written,
    as_options,
    close_figure,
    emit,
    print_json,
    print_notes,
    print_table,
    quantity,
)
from springdyn.core.errors import InputError
from springdyn.valve.spring.definition import MODEL_NAMES

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
        help="the valve spring: the kinematic load (spring force + inertia) and the Hertz stress",
    )
    p.add_argument(
        "--model",
        choices=MODEL_NAMES,
        help="spring model of the static force (default: the [spring] model key, else 'type-c')",
    )
    g = p.add_mutually_exclusive_group()
    g.add_argument("--cam-rpm", metavar="RPM", help="camshaft speed of the load (needs --spring; default 0: static)")
    g.add_argument(
        "--engine-rpm", metavar="RPM", help="engine speed instead (four-stroke: cam speed = engine speed / 2)"
    )
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
    from springdyn.valve.cam.follower import Follower

    follower = Follower.in_file(path)
    if follower is None and required:
        raise InputError(
            f"{path}: no [follower] table: the cam checks need the follower's geometry beside [valve_train] "
            "(see examples/valve/valve_train_with_follower.toml)"
        )
    return follower


def _cam_rpm(args, timing) -> float | None:
    """Cam speed [rev/min] from --cam-rpm or --engine-rpm (the [timing] strokes, else a four-stroke)."""
    from springdyn.valve.cam.definition import cam_rpm_from_engine_rpm

    if args.cam_rpm is None and args.engine_rpm is None:
        return None
    option = "--cam-rpm" if args.cam_rpm is not None else "--engine-rpm"
    value = quantity(args.cam_rpm if args.cam_rpm is not None else args.engine_rpm, "rpm", option, bare_unit="rpm")
    if not 0 < value < 1e5:
        raise InputError(f"{option} = {value:g} rpm must be a speed between 0 and 100000 rpm")
    if args.engine_rpm is not None:
        value = float(cam_rpm_from_engine_rpm(value, timing.strokes if timing is not None else 4))
    return value


def _mm(value) -> str:
    return "-" if value is None else f"{value * 1e3:.3f}"


def _print_checks(s) -> None:
    """The geometric and stress checks of a :class:`~springdyn.valve.cam.checks.CamCheck` summary."""
    kind = s["follower"]
    where = f" at {s['min_radius_of_curvature_cam_angle_deg']:.2f} deg" if s["min_radius_of_curvature_m"] else ""
    if kind == "flat":
        verdict = "CUSP: the face cannot follow the lift" if s["concave"] else "ok (convex everywhere)"
    else:
        verdict = "UNDERCUT" if s["undercut"] else "ok (no undercut)"
    print(
        f"radius of curvature: min {_mm(s['min_radius_of_curvature_m'])} mm{where}, at the nose "
        f"{_mm(s['nose_radius_of_curvature_m'])} mm: {verdict}"
    )
    if kind == "flat":
        face = (
            f"; with the {s['edge_margin_m'] * 1e3:g} mm edge margin it needs a face radius of "
            f"{_mm(s['required_face_radius_m'])} mm"
        )
        if s.get("face_radius_m") is not None:
            face += f" of the {_mm(s['face_radius_m'])} mm: " + ("ok" if s["excursion_ok"] else "BEYOND THE FACE")
        print(
            f"contact excursion: up to {_mm(s['max_excursion_m'])} mm from the tappet axis at "
            f"{s['max_excursion_cam_angle_deg']:.2f} deg; the contact line reaches {_mm(s['max_face_reach_m'])} mm"
            + face
        )
    else:
        concave = (
            f", concave down to {_mm(s['min_concave_radius_m'])} mm"
            if s.get("min_concave_radius_m") is not None
            else ""
        )
        print(
            f"pitch curve: smallest convex radius {_mm(s['min_pitch_radius_m'])} mm ({s['roller_radius_m'] * 1e3:g} mm "
            f"roller){concave}; pressure angle up to {s['max_pressure_angle_deg']:.2f} deg at "
            f"{s['max_pressure_angle_cam_angle_deg']:.2f} deg"
        )


# ----------------------------------------------------------------------------- commands
def cmd_cam_from_lift(args) -> int:
    """``springdyn valve cam-from-lift``: the lobe of a valve-lift table or a cam card."""
    from springdyn.core.io import check_output_file
    from springdyn.valve.cam.checks import check_cam
    from springdyn.valve.cam.from_lift import (
        CamCard,
        cam_from_card,
        cam_from_valve_lift,
        read_valve_lift_table,
        write_cam,
    )
    from springdyn.valve.cam.timing import Timing
    from springdyn.valve.train.definition import ValveTrain

    if (args.lift is None) == (args.card is None):
        raise InputError("give the wanted valve lift LIFT.csv or --card CARD.toml (one of them)")
    if args.card is not None and args.ramp_angle is not None:
        raise InputError("--ramp-angle applies to LIFT.csv; a card gives its ramps in its [cam_card] table")
    out = check_output_file(args.cam_out, "--out")
    vt = ValveTrain.from_toml(args.valve_train)
    follower = _follower(args.valve_train, required=False)
    if args.lift is not None:
        ramp = quantity(args.ramp_angle, "rad", "--ramp-angle", bare_unit="deg") if args.ramp_angle else None
        angle, lift = read_valve_lift_table(args.lift)
        with as_options(ramp_angle="--ramp-angle"):
            res = cam_from_valve_lift(angle, lift, vt, ramp_angle=ramp, name=str(args.lift))
        header = f"lobe for the valve lift {args.lift} through {args.valve_train}, by springdyn valve cam-from-lift"
    else:
        card = CamCard.from_toml(args.card)
        res = cam_from_card(card, vt, Timing.in_file(args.card))
        header = f"lobe of the cam card {args.card} through {args.valve_train}, by springdyn valve cam-from-lift"
    s = res.summary
    header += (
        f"\nmax valve lift {s['max_valve_lift_m'] * 1e3:.4f} mm; duration at 1 mm valve lift "
        f"{s['duration_at_1mm_deg']:.4f} cam deg"
    )
    written = write_cam(res, out, header)
    check = check_cam(res.cam, vt, follower) if follower is not None else None
    if args.csv:
        written.append(res.to_csv(args.csv))
    if args.plot:
        close_figure(res.plot(args.plot))
        written.append(args.plot)
    announce_written(written, args)
    if args.json:
        data = dict(s, written=[str(p) for p in written])
        if check is not None:
            data["check"] = dict(check.summary)
        print_json(data)
        return 0
    print(
        f"{s['law']} lobe from {s['source']}: ratio {s['rocker_ratio']:g}, lash {s['lash_m'] * 1e3:.3g} mm at the "
        f"valve ({s['lobe_lash_m'] * 1e3:.4g} mm at the lobe)"
    )
    print(
        f"max valve lift {s['max_valve_lift_m'] * 1e3:.4f} mm, max lobe lift {s['max_lobe_lift_m'] * 1e3:.4f} mm at "
        f"{s['max_lift_cam_angle_deg']:.2f} cam deg"
    )
    if res.cam.law == "table":
        print(
            f"valve opens at {s['valve_opening_deg']:.3f}, closes at {s['valve_closing_deg']:.3f} cam deg; "
            f"round trip (the lobe's valve lift against the table, every row): {s['round_trip_error_m']:.3g} m"
        )
        if "opening_ramp_deg" in s:
            print_table(
                [
                    (side, f"{s[f'{side}_ramp_deg']:.3f}", f"{s[f'{side}_lash_velocity_m_per_rad'] * 1e3:.4f}")
                    for side in ("opening", "closing")
                ],
                headers=("lash ramp (from rest)", "cam angle [deg]", "lobe velocity at the lash [mm/rad]"),
            )
            print(
                f"the opening ramp starts at {s['opening_ramp_start_deg']:.3f} deg, the closing ramp ends at "
                f"{s['closing_ramp_end_deg']:.3f} deg"
            )
    else:
        unit = s["card_duration_angle"]
        print(
            f"main duration {s['main_duration_deg']:.6f} cam deg; ramps {s['ramp_height_m'] * 1e3:.4g} mm over "
            f"{s['ramp_duration_deg']:.4f} deg ({s['ramp_velocity_m_per_rad'] * 1e3:.4f} mm/rad)"
            + (f", height {s['ramp_height_default']}" if "ramp_height_default" in s else "")
        )
        print(
            f"card: {s['card_lift_m'] * 1e3:g} mm lift ({s['card_lift_at']}), {s['card_duration_deg']:g} {unit} deg at "
            f"{s['card_check_height_m'] * 1e3:.4g} mm ({s['card_check_at']}); the lobe misses them by "
            f"{s['lift_error_m']:.3g} m and {s['duration_error_deg']:.3g} {unit} deg"
        )
    rows = []
    for key, label in (("0050in", "0.050 in"), ("1mm", "1 mm")):
        if s.get(f"duration_at_{key}_deg") is None:
            rows.append((f"at {label}", "-", "-", "lift below the check height"))
        else:
            rows.append(
                (
                    f"at {label}",
                    f"{s[f'opening_at_{key}_deg']:.3f}",
                    f"{s[f'closing_at_{key}_deg']:.3f}",
                    f"{s[f'duration_at_{key}_deg']:.3f}",
                )
            )
    print_table(rows, headers=("valve timing", "opens [cam deg]", "closes [cam deg]", "duration [cam deg]"))
    if check is not None:
        cs = check.summary
        print(f"profile checks ([follower] {cs['follower']}, base circle {cs['base_circle_radius_m'] * 1e3:g} mm):")
        _print_checks(cs)
        print_notes(cs, skip=("no load given",))
    print_notes(s)
    print(f"next: springdyn valve cam-check {out} --valve-train {args.valve_train} --spring SPRING.toml --cam-rpm RPM")
    return 0


def cmd_cam_check(args) -> int:
    """``springdyn valve cam-check``: curvature, excursion, pressure angle and Hertz stress."""
    from springdyn.valve.cam.checks import check_cam
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.cam.timing import Timing
    from springdyn.valve.spring.definition import ValveSpring
    from springdyn.valve.train.definition import ValveTrain

    cam = Cam.from_toml(args.cam)
    vt = ValveTrain.from_toml(args.valve_train)
    follower = _follower(args.valve_train, required=True)
    rpm = _cam_rpm(args, Timing.in_file(args.cam))
    if rpm is not None and args.spring is None:
        raise InputError("--cam-rpm and --engine-rpm set the speed of the load: give the spring with --spring")
    if args.model is not None and args.spring is None:
        raise InputError("--model applies to the spring: give it with --spring")
    spring = ValveSpring.from_toml(args.spring).with_model(args.model) if args.spring else None
    with as_options(cam_rpm="--cam-rpm"):
        res = check_cam(cam, vt, follower, spring=spring, cam_rpm=rpm)
    if emit(res, args, json_data=dict(res.summary)):
        return 0
    s = res.summary
    f = follower
    what = "flat face" if f.kind == "flat" else f"roller of {f.roller_radius * 1e3:g} mm"
    print(
        f"{cam.law} lobe, {what}, base circle {f.base_circle_radius * 1e3:g} mm, contact width {f.width * 1e3:g} mm"
        + (f", crown {f.crown_radius * 1e3:g} mm" if f.crown_radius is not None else "")
    )
    _print_checks(s)
    if "max_contact_stress_Pa" in s:
        print(
            f"load (kinematic: spring + {s['moving_mass_kg'] * 1e3:.1f} g at the valve, ratio {vt.ratio:g}) at "
            f"{s['cam_rpm']:g} cam rpm: {s['min_contact_force_N']:.1f} N (at {s['min_contact_force_cam_angle_deg']:.2f} "
            f"deg, valve open) to {s['max_contact_force_N']:.1f} N (at {s['max_contact_force_cam_angle_deg']:.2f} deg)"
            + ("" if s["follower_stays_on_cam"] else ": the spring cannot hold the follower on the cam")
        )
        allow = (
            f"; allowable {s['allowable_contact_stress_Pa'] / 1e6:.0f} MPa: "
            + ("ok" if s["contact_stress_ok"] else "EXCEEDED")
            if s.get("allowable_contact_stress_Pa") is not None
            else " (no allowable_contact_stress in [follower]: not checked)"
        )
        print(
            f"Hertz stress ({s['contact_at_max_stress']} contact): max {s['max_contact_stress_Pa'] / 1e6:.0f} MPa at "
            f"{s['max_contact_stress_cam_angle_deg']:.2f} deg, contact half-width "
            f"{s['contact_half_width_at_max_stress_m'] * 1e3:.3f} mm" + allow
        )
    print("checks: " + ("all passed" if s["ok"] else "FAILED: " + ", ".join(s["checks_failed"])))
    print_notes(s)
    return 0


def cmd_kinematics(args) -> int:
    """``springdyn valve kinematics``: the drawn lever over the cam."""
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.train.definition import ValveTrain

    cam = Cam.from_toml(args.cam)
    vt = ValveTrain.from_toml(args.valve_train)
    if vt.geometry is None:
        raise InputError(
            f"{args.valve_train}: no [geometry] table: the lever's kinematics need its drawing beside [valve_train] "
            "and [follower] (see examples/valve/finger_follower_geometry.toml); without it the ratio is the constant "
            f"{vt.ratio:g}"
        )
    lash = 0.0 if vt.hydraulic else vt.lash
    res = vt.geometry.over_cam(cam, lash=lash, inertia=vt.lever_inertia)
    if emit(res, args, json_data=dict(res.summary)):
        return 0
    s = res.summary
    print(
        f"lever drawn in {args.valve_train} on the {cam.law} lobe: ratio {s['ratio_at_rest']:.4f} at rest, "
        f"{s['ratio_min']:.4f} to {s['ratio_max']:.4f} over the event ({s['ratio_change']:.1%} of the ratio at rest), "
        f"{s['ratio_at_max_lift']:.4f} at the largest lift"
    )
    print(
        f"max valve lift {s['max_valve_lift_m'] * 1e3:.4f} mm at {s['max_lift_cam_angle_deg']:.2f} cam deg (constant "
        f"ratio: {s['constant_ratio_valve_lift_m'] * 1e3:.4f} mm); the lever turns {s['max_lever_angle_deg']:.2f} deg"
    )
    lo, hi = s["pad_travel_m"]
    line = f"pad contact on the stem tip travels {lo * 1e3:+.3f} to {hi * 1e3:+.3f} mm from its place at rest"
    if "pad_on_stem_margin_m" in s:
        line += f" (margin to the tip's edge {s['pad_on_stem_margin_m'] * 1e3:.3f} mm)"
    print(line)
    if "mass_at_valve_kg" in s:
        m0, m1 = s["mass_at_valve_kg"]
        print(f"lever mass at the valve (J / L_v^2, roller included): {m0 * 1e3:.2f} to {m1 * 1e3:.2f} g")
    print_notes(s)
    return 0
