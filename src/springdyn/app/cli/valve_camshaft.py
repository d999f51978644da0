"""``springdyn valve camshaft``: several valves on one twisting camshaft (thin layer over
:class:`springdyn.valve.CamshaftModel`)."""

from __future__ import annotations

from pathlib import Path

import springdyn.valve as valve
from springdyn.app.cli.common import announce_written, as_options, close_figure, emit
from springdyn.app.cli.valve_options import add_speed_options, cam_rpm_from_args

__all__ = ["register", "cmd_camshaft"]


def register(vsub) -> None:
    """Add ``camshaft`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "camshaft",
        help="several valves on one camshaft with its torsion and timing drive: drive torque, twist, each "
        "valve's timing error, the shaft's torsional modes (one speed, or over a range)",
    )
    p.add_argument("camshaft", metavar="CAMSHAFT.toml", help="file with [camshaft] and its [[camshaft.lobes]]")
    add_speed_options(p, ranged=True, what="a speed, or START:STOP:STEP or a list (a sweep)")
    p.add_argument("--out", metavar="DIR", help="write the tables (CSV) and figures (PNG) into this folder")
    p.add_argument("--json", action="store_true", help="print machine-readable JSON (SI) instead of a table")
    p.add_argument("--quiet", action="store_true", help="no progress line")
    p.set_defaults(func=cmd_camshaft)


def cmd_camshaft(args) -> int:
    """``springdyn valve camshaft``: the periodic state at one speed, or a sweep over several."""
    model = valve.CamshaftModel.from_toml(args.camshaft)
    speeds = cam_rpm_from_args(args, ranged=True)
    modes = model.modes()
    with as_options(cam_rpm="--cam-rpm"):
        if speeds.size == 1:
            result = model.simulate(float(speeds[0]), quiet=args.quiet)
            name = "camshaft"
        else:
            result = model.sweep(speeds, quiet=args.quiet)
            name = "camshaft-sweep"
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        written = [result.to_csv(out / f"{name}.csv"), modes.to_csv(out / "torsional-modes.csv")]
        close_figure(result.plot(out / f"{name}.png"))
        written.append(out / f"{name}.png")
        announce_written(written, args)
    if not emit(result, args, json_data=dict(result.summary, modes_Hz=list(modes.frequency))):
        print(result.describe())
    return 0
