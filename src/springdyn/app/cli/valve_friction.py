"""``springdyn valve friction``: the valve train's friction over speed (thin layer over
:meth:`springdyn.valve.ValveModel.friction_over_speed`)."""

from __future__ import annotations

from springdyn.app.cli.common import add_output_options, as_options, emit
from springdyn.app.cli.valve_options import add_inputs, add_speed_options, cam_rpm_from_args, model_of, run_options
from springdyn.core.errors import InputError

__all__ = ["register", "cmd_friction"]


def register(vsub) -> None:
    """Add ``friction`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "friction",
        help="valve-train friction over speed: cam-follower (lubrication regime, roller slip), stem guide and "
        "pivot; the camshaft drive torque over the cam angle and the friction power over speed",
    )
    add_inputs(
        p,
        train="file with [valve_train] and [follower] (the contact at the cam), and optionally [friction] "
        "(oil, roughness, coefficients, guide, pivot; defaults otherwise)",
        train_required=True,
    )
    add_speed_options(p, ranged=True)
    add_output_options(p)
    p.set_defaults(func=cmd_friction)


def cmd_friction(args) -> int:
    """``springdyn valve friction``: simulate each speed to its periodic state, then its friction."""

    model = model_of(args)
    if model.follower is None:
        raise InputError(
            f"{args.valve_train}: no [follower] table: friction at the cam needs the follower beside [valve_train] "
            "(see examples/valve/valve_train_with_follower.toml)"
        )
    speeds = cam_rpm_from_args(args, ranged=True, model=model)
    with as_options(cam_rpm=run_options(args, model)["cam_rpm"]):
        sweep = model.friction_over_speed(speeds, quiet=args.quiet)
    given = model.friction_table is not None
    data = dict(sweep.summary, per_speed=[a.summary for a in sweep.analyses], friction_defaults=not given)
    if not emit(sweep, args, json_data=data):
        print(sweep.describe(model.valve_train.layout, friction_given=given))
    return 0
