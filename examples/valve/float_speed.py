"""Find the float speed of the example valve train (one-step spring, 3-4-5 cam).

The follower floats (leaves the cam) when the spring can no longer decelerate the valve,
retainer and follower over the nose of the cam.  ``float_speed`` scans the cam speeds,
then bisects between the last speed without lift-off and the first with it.  A
four-stroke camshaft turns at half the engine speed.

Run:  python examples/valve/float_speed.py [--out DIR] [--spring one-step|two-step]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from springdyn.core.io import write_csv, write_json
from springdyn.core.plotting import new_figure, save_figure
from springdyn.valve import Cam, ValveSpring, ValveTrain, float_speed, simulate

HERE = Path(__file__).resolve().parent


def find_float_speed(spring_name: str) -> tuple[dict, ValveSpring, Cam, ValveTrain]:
    """Float speed of the example valve train with the spring ``spring_name``."""
    spring = ValveSpring.example(spring_name)
    cam = Cam.from_toml(HERE / "cam_polydyne_ramps.toml")  # its ramps take up the train's lash
    train = ValveTrain.from_toml(HERE / "valve_train.toml")
    result = float_speed(
        spring, cam, train, np.arange(1000.0, 6001.0, 250.0), resolution=5.0, points_per_revolution=720
    )
    return result, spring, cam, train


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="output folder (default: a new temporary folder)")
    parser.add_argument("--spring", default="one-step", choices=("one-step", "two-step"), help="example spring")
    args = parser.parse_args(argv)
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="springdyn-float-"))
    out.mkdir(parents=True, exist_ok=True)

    result, spring, cam, train = find_float_speed(args.spring)
    print(
        f"valve train: moving mass {train.moving_mass * 1e3:.0f} g, {args.spring} spring "
        f"(Fset {spring.spring_model.internal_parameters()['Fset']:.1f} N), cam {cam.law} {cam.max_lift * 1e3:.1f} mm"
    )
    for rpm, f in zip(result["cam_rpm"], result["min_cam_contact_force_N"]):
        print(f"  {rpm:6.0f} cam rpm: minimum cam contact force {f:8.1f} N")
    write_json(out / "float_speed.json", result.to_dict())
    write_csv(
        out / "float_scan.csv",
        {"cam_rpm": result["cam_rpm"], "min_cam_contact_force_N": result["min_cam_contact_force_N"]},
    )
    if result["float_cam_rpm"] is None:
        print(f"no lift-off up to {result['cam_rpm'][-1]:.0f} cam rpm")
        return 0
    f = result["float_cam_rpm"]
    lo, hi = result["bracket"]
    print(f"float speed: {f:.0f} cam rpm = {2 * f:.0f} engine rpm (four-stroke); bracket {lo:.1f} - {hi:.1f} cam rpm")
    first = result.first_separation
    print(f"first lift-off: {first['cam_rpm']:.0f} cam rpm on the {first['phase']} (bounce below the float speed)")

    sim = simulate(spring, cam, f, valve_train=train, points_per_revolution=1440)
    fig, ax = new_figure()
    ax.plot(sim.cam_angle_deg, sim.cam_contact_force, label="cam contact force")
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xlim(0, 200)
    ax.set_xlabel("cam angle [deg]")
    ax.set_ylabel("force [N]")
    ax.set_title(f"cam-follower contact force at the float speed {f:.0f} cam rpm")
    ax.grid(True, alpha=0.3)
    ax.legend()
    print(f"wrote {save_figure(fig, out / 'float_speed.png')}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
