"""``springdyn valve clearance``: the valve-to-piston clearance over speed (thin layer over
:meth:`springdyn.valve.ValveModel.valve_clearance`)."""

from __future__ import annotations

import springdyn.valve as valve
import springdyn.valve.design as design
from springdyn.app.cli import valve_options as vo
from springdyn.app.cli.common import add_output_options, as_options, emit, quantity
from springdyn.core.errors import InputError

__all__ = ["register", "cmd_clearance"]


def register(vsub) -> None:
    """Add ``clearance`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "clearance",
        help="valve-to-piston clearance over speed: the simulated valve (float and bounce) against the piston's "
        "crank-slider ([piston] with the cam's [timing]), its minimum and crank angle at each speed, the static "
        "clearance beside it, the speed map",
    )
    vo.add_inputs(p, train="file with a [valve_train] table (and [piston], unless --piston)", train_required=True)
    vo.add_speed_options(p, ranged=True)
    p.add_argument(
        "--piston",
        metavar="PISTON.toml",
        help="file with the [piston] table (default: the one in the valve-train, cam or spring file)",
    )
    p.add_argument(
        "--limit",
        metavar="C",
        help=f"smallest clearance along the valve's axis (default "
        f"{design.MIN_VALVE_PISTON_CLEARANCE * 1e3:g} mm, [criteria] min_valve_piston_clearance)",
    )
    vo.add_gas_options(p)
    vo.add_revolution_options(p)
    p.add_argument("--points-per-revolution", type=int, default=720, metavar="N", help="output points (default 720)")
    vo.add_tolerance_options(p)
    add_output_options(p)
    p.set_defaults(func=cmd_clearance)


def cmd_clearance(args) -> int:
    """``springdyn valve clearance``: sweep the speeds, then the clearance of each."""
    model = vo.model_of(args)
    if args.piston:
        piston = valve.Piston.in_file(args.piston)
        if piston is None:
            raise InputError(f"--piston = {args.piston!r}: the file has no [piston] table")
        model = model.replace(piston=piston)
    speeds = vo.cam_rpm_from_args(args, ranged=True, model=model)
    limit = quantity(args.limit, "m", "--limit") if args.limit is not None else None
    if limit is not None and not limit > 0:
        raise InputError(f"--limit = {args.limit!r} must be a positive clearance, e.g. 1mm")
    with as_options(**vo.run_options(args, model)):
        res = model.valve_clearance(speeds, limit=limit, quiet=args.quiet)
    if not emit(res, args, json_data=dict(res.summary)):
        print(res.describe())
    return 0
