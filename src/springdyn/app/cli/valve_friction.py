"""``springdyn valve friction``: the valve train's friction over speed (thin layer over
:func:`springdyn.valve.simulate` and :mod:`springdyn.valve.train.friction`)."""

from __future__ import annotations

from springdyn.app.cli.common import add_output_options, as_options, emit, print_notes, print_table
from springdyn.core.errors import InputError

__all__ = ["register", "cmd_friction"]


def register(vsub, add_speed_options, add_model_option, cam_speeds) -> None:
    """Add ``friction`` to the ``springdyn valve`` sub-commands ``vsub`` (with the valve commands'
    speed and model options and their reader of the speeds, ``cam_speeds(args, ranged=True)``)."""
    p = vsub.add_parser(
        "friction",
        help="valve-train friction over speed: cam-follower (lubrication regime, roller slip), stem guide and "
        "pivot; the camshaft drive torque over the cam angle and the friction power over speed",
    )
    p.add_argument("spring", metavar="SPRING.toml", help="file with a [spring] table")
    p.add_argument("--cam", required=True, metavar="CAM.toml", help="file with a [cam] table")
    p.add_argument(
        "--valve-train",
        required=True,
        metavar="VT.toml",
        help="file with [valve_train] and [follower] (the contact at the cam), and optionally [friction] "
        "(oil, roughness, coefficients, guide, pivot; defaults otherwise)",
    )
    add_speed_options(p, ranged=True)
    add_model_option(p)
    add_output_options(p)
    p.set_defaults(func=cmd_friction, cam_speeds=cam_speeds)


def cmd_friction(args) -> int:
    """``springdyn valve friction``: simulate each speed to its periodic state, then its friction."""
    from springdyn.core.params import load_toml
    from springdyn.core.progress import progress
    from springdyn.valve import simulate
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.cam.follower import Follower
    from springdyn.valve.run.friction import friction_over_speed, simulation_friction
    from springdyn.valve.spring.definition import ValveSpring
    from springdyn.valve.train.definition import ValveTrain
    from springdyn.valve.train.friction import Friction

    spring = ValveSpring.from_toml(args.spring).with_model(args.model)
    cam = Cam.from_toml(args.cam)
    vt = ValveTrain.from_toml(args.valve_train)
    follower = Follower.in_file(args.valve_train)
    if follower is None:
        raise InputError(
            f"{args.valve_train}: no [follower] table: friction at the cam needs the follower beside [valve_train] "
            "(see examples/valve/valve_train_with_follower.toml)"
        )
    doc = load_toml(args.valve_train)
    given = "friction" in doc
    friction = Friction.from_dict(doc["friction"], source=str(args.valve_train)) if given else Friction()
    speeds = args.cam_speeds(args, ranged=True)
    analyses = []
    with as_options(cam_rpm="--cam-rpm"):
        for rpm in progress(speeds, desc="friction", quiet=args.quiet):
            sim = simulate(spring, cam, float(rpm), valve_train=vt)
            analyses.append(simulation_friction(sim, follower, friction))
    sweep = friction_over_speed(analyses)
    s = sweep.summary
    data = dict(s, per_speed=[a.summary for a in analyses], friction_defaults=not given)
    if emit(sweep, args, json_data=data):
        return 0
    print(
        f"valve-train friction, {follower.kind} follower, {vt.layout} train"
        + ("" if given else " ([friction] not given: its defaults)")
    )
    rows = []
    for a in analyses:
        m = a.summary
        rows.append(
            (
                f"{m['cam_rpm']:.0f}",
                f"{m['mean_drive_torque_N_m']:.3f}",
                f"{m['min_drive_torque_N_m']:.2f} / {m['max_drive_torque_N_m']:.2f}",
                f"{m['friction_power_W']:.2f}",
                f"{m['friction_power_cam_W']:.2f}",
                f"{m['friction_power_roller_bearing_W']:.2f}",
                f"{m['friction_power_guide_W']:.2f}",
                f"{m['friction_power_pivot_W']:.2f}",
                f"{m.get('min_film_parameter', float('nan')):.3g}",
                "-"
                if "slip_share_loaded" not in m or m["slip_share_loaded"] is None
                else f"{m['slip_share_loaded']:.1%}",
            )
        )
    print_table(
        rows,
        headers=(
            "cam rpm",
            "mean torque [N m]",
            "min / max [N m]",
            "friction [W]",
            "cam",
            "roller bearing",
            "guide",
            "pivot",
            "min lambda",
            "roller slip",
        ),
    )
    last = analyses[-1].summary
    friction_j = sum(last[f"dissipated_{k}_J"] for k in ("cam", "roller_bearing", "guide", "pivot"))
    print(
        f"energy of a revolution at {last['cam_rpm']:.0f} rpm: cam work {last['cam_work_J']:.4g} J = friction "
        f"{friction_j:.4g} J + the train's dampers and elastic change {last['load_work_J']:.4g} J "
        f"(residual {last['energy_residual_J']:.2g} J)"
    )
    print_notes(s)
    return 0
