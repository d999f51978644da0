"""The valve-spring part of ``springdyn demo``: every analysis on the built-in springs."""

from __future__ import annotations

from pathlib import Path

from ..io import write_json
from ..progress import progress
from .spring import EXAMPLES, ValveSpring

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
    return written
