"""``springdyn demo`` for leaf spring dampers: Types A, B, C of Table 4.1 of the thesis.

For each type: the model coefficients vs speed (CSV + plot), simulated rig records with
hysteresis loops at 500 and 3000 rpm (1000 and 2000 rpm for Type C, like Figs. 5.11-5.26),
and the identification of x and y shakes at every speed drawn against the model.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from ..io import write_json
from ..plotting import plt
from ..progress import progress
from .identify import RigData, identify_series
from .model import LSDModel
from .parameters import LSDParameters
from .rig import circular_orbit, linear_shake, simulate_rig
from .stiffness import PreloadExceededWarning

__all__ = ["run"]

AMPLITUDE = 50e-6  # [m] the thesis' 50 um orbit
SPEEDS = np.arange(500.0, 3001.0, 500.0)  # [rpm] the thesis' range
LOOP_SPEEDS = {"A": (500.0, 3000.0), "B": (500.0, 3000.0), "C": (1000.0, 2000.0)}


def _data(rec):
    return RigData(rec.time, rec.x, rec.y, rec.fx, rec.fy, source=f"{rec.name} {rec.excitation} {rec.rpm:g} rpm")


def run(out_dir: Path, quiet: bool = False) -> list[Path]:
    """Write the leaf-spring-damper demo files into ``out_dir``; return their paths."""
    out_dir = Path(out_dir)
    written: list[Path] = []
    summary = {}
    for key in progress(("A", "B", "C"), total=3, desc="lsd", quiet=quiet):
        model = LSDModel(LSDParameters.example(key))
        tag = f"type_{key.lower()}"
        coeffs = model.coefficients(SPEEDS, AMPLITUDE)
        written.append(coeffs.to_csv(out_dir / f"{tag}_coefficients.csv"))
        for rpm in LOOP_SPEEDS[key]:
            for exc in ("orbit", "x"):
                tr = circular_orbit(rpm, AMPLITUDE, 10, 5e3) if exc == "orbit" else linear_shake(rpm, AMPLITUDE, "x", 10, 5e3)
                rec = simulate_rig(model, tr, force_noise=2.0, seed=int(rpm))
                written.append(rec.to_csv(out_dir / f"{tag}_rig_{exc}_{rpm:.0f}rpm.csv"))
                fig = rec.plot(out_dir / f"{tag}_loops_{exc}_{rpm:.0f}rpm.png")
                plt.close(fig)
                written.append(out_dir / f"{tag}_loops_{exc}_{rpm:.0f}rpm.png")
        firsts, seconds = [], []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", PreloadExceededWarning)
            for k, rpm in enumerate(SPEEDS):
                firsts.append(_data(simulate_rig(model, linear_shake(rpm, AMPLITUDE, "x", 10, 5e3), force_noise=2.0, seed=10 * k)))
                seconds.append(_data(simulate_rig(model, linear_shake(rpm, AMPLITUDE, "y", 10, 5e3), force_noise=2.0, seed=10 * k + 1)))
        ident = identify_series(firsts, seconds, mass=model.params.ring_mass, name="identified (simulated rig)")
        written.append(ident.to_csv(out_dir / f"{tag}_identified.csv"))
        fig = coeffs.plot(out_dir / f"{tag}_coefficients.png", identified=ident)
        plt.close(fig)
        written.append(out_dir / f"{tag}_coefficients.png")
        summary[model.params.name] = {
            "pack_stiffness_N_per_m": model.pack_stiffness,
            "load_ratios": model.load_ratios,
            "stiffness_factor": model.stiffness_factor,
            "kxx_model_N_per_m": coeffs.K[0, 0, 0],
            "cxx_model_Ns_per_m_at_500rpm": coeffs.C[0, 0, 0],
            "kxx_identified_N_per_m_at_500rpm": ident.items[0].K[0, 0],
            "cxx_identified_Ns_per_m_at_500rpm": ident.items[0].C[0, 0],
            "note": "identified from simulated x and y shakes with 2 N force noise; the time-domain "
                    "leaf friction uses the instantaneous pack load and each pack's own amplitude, "
                    "the coefficient model Eq. (2.28) the peak load and the full amplitude",
        }
    written.append(write_json(out_dir / "summary.json", summary))
    return written
