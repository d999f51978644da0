"""The valve-spring part of ``springdyn demo``: every analysis on the built-in springs."""

from __future__ import annotations

from pathlib import Path

from importlib import resources

import numpy as np

from ..io import write_json
from ..progress import progress
from .cam import Cam
from .simulate import float_speed, simulate
from .spring import EXAMPLES, ValveSpring
from .valvetrain import ValveTrain

#: Camshaft speeds of the demo [rev/min]: slow, mid and near the top of the range.
DEMO_SPEEDS = (1000.0, 2500.0, 4000.0)


def _data(name: str) -> str:
    return str(resources.files("springdyn.data") / name)

__all__ = ["run"]


def run(out_dir: Path, quiet: bool = False) -> list[Path]:
    """Write parameters, static curves, modes and design figures of the example springs."""
    written = []
    for name in progress(list(EXAMPLES), desc="valve springs", quiet=quiet):
        spring = ValveSpring.example(name)
        tag = name.replace("-", "_")
        written.append(write_json(out_dir / f"{tag}_params.json", spring.internal_parameters()))
        curve = spring.static_curve()
        written.append(curve.to_csv(out_dir / f"{tag}_curve.csv"))
        curve.plot(out_dir / f"{tag}_curve.png")
        written.append(out_dir / f"{tag}_curve.png")
        modes = {
            "free_length": {"length_m": spring.free_length, "frequencies_Hz": list(spring.modes(spring.free_length))},
            "installed_length": {"length_m": spring.installed_length, "frequencies_Hz": list(spring.modes(spring.installed_length))},
            "closed_form_f1_Hz": spring.internal_parameters()["f1"],
            "closed_form_f2_Hz": spring.internal_parameters()["f2"],
        }
        written.append(write_json(out_dir / f"{tag}_modes.json", modes))
        written.append(write_json(out_dir / f"{tag}_design.json", spring.design_figures(lift=0.009, cam_rpm=3000.0)))
    written += _dynamics(out_dir, quiet)
    return written


def _dynamics(out_dir: Path, quiet: bool) -> list[Path]:
    """Spring alone at three speeds, and the valve train's float speed."""
    cam = Cam.from_toml(_data("valve_cam_345.toml"))
    vt = ValveTrain.from_toml(_data("valve_train.toml"))
    written = []
    runs = [(name, rpm) for name in EXAMPLES for rpm in DEMO_SPEEDS]
    for name, rpm in progress(runs, desc="valve dynamics", quiet=quiet):
        spring = ValveSpring.example(name)
        stem = out_dir / f"{name.replace('-', '_')}_{rpm:.0f}rpm"
        sim = simulate(spring, cam, rpm, revolutions=3)
        written.append(sim.to_csv(stem.with_suffix(".csv")))
        written.append(write_json(stem.with_name(stem.name + "_summary.json"), sim.summary()))
        sim.plot(stem.with_suffix(".png"))
        written.append(stem.with_suffix(".png"))
    spring = ValveSpring.example("one-step")
    res = float_speed(spring, cam, vt, np.arange(1000.0, 5001.0, 250.0), progress_quiet=quiet)
    written.append(write_json(out_dir / "one_step_valve_train_float.json", res))
    if res["float_cam_rpm"] is not None:
        sim = simulate(spring, cam, res["float_cam_rpm"] * 1.05, revolutions=3, valve_train=vt)
        stem = out_dir / "one_step_valve_train_above_float"
        written.append(sim.to_csv(stem.with_suffix(".csv")))
        written.append(write_json(stem.with_name(stem.name + "_summary.json"), sim.summary()))
        sim.plot(stem.with_suffix(".png"))
        written.append(stem.with_suffix(".png"))
    return written
