"""``springdyn valve friction``: the valve train's friction over speed (thin layer over
:meth:`springdyn.valve.ValveModel.friction_over_speed`)."""

from __future__ import annotations

from springdyn.app.cli.common import add_output_options, as_options, emit
from springdyn.app.cli.valve_options import model_of
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

    model = model_of(args)
    if model.follower is None:
        raise InputError(
            f"{args.valve_train}: no [follower] table: friction at the cam needs the follower beside [valve_train] "
            "(see examples/valve/valve_train_with_follower.toml)"
        )
    speeds = args.cam_speeds(args, ranged=True, model=model)
    with as_options(cam_rpm="--cam-rpm"):
        sweep = model.friction_over_speed(speeds, quiet=args.quiet)
    given = model.friction_table is not None
    data = dict(sweep.summary, per_speed=[a.summary for a in sweep.analyses], friction_defaults=not given)
    if not emit(sweep, args, json_data=data):
        print(sweep.describe(model.valve_train.layout, friction_given=given))
    return 0
