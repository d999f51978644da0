"""``springdyn demo`` for the CFCS: the paper's Table 1 mechanism end to end.

Writes the static curve (Figs. 2-3 of the CFCS paper), the four frequencies of
Figs. 8-11 with and without tau_CF and tau_AF, the frequency sweep (Figs. 5-7), the
running PCF (Fig. 12, springdyn's definition), the pivot stress, a forward-dynamics
run and a design example, plus ``summary.json`` with the key figures.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..io import write_json
from ..plotting import new_figure, plt, save_figure
from .design import design
from .model import CFCS

__all__ = ["run", "PAPER_OMEGAS"]

#: The input frequencies of Figs. 8-11 of the CFCS paper [rad/s].
PAPER_OMEGAS = (2.09, 4.19, 14.7, 41.89)


def run(out_dir: Path, quiet: bool = False) -> list[Path]:
    """Run the CFCS demo into ``out_dir``; return the files written."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    model = CFCS.example("table1")
    ideal = CFCS(model.params.without_dissipation())
    written: list[Path] = []
    summary: dict = {"mechanism": "Table 1 of the CFCS paper", "toggle_cutoff_rad": model.params.toggle_cutoff}

    st = model.static()
    written.append(st.to_csv(out_dir / "static.csv"))
    fig = st.plot(out_dir / "static.png")
    plt.close(fig)
    written.append(out_dir / "static.png")
    summary["static"] = st.summary
    written.append(_stress_plot(model, st, out_dir / "pivot_stress.png"))

    summary["dynamic"] = {}
    for w in PAPER_OMEGAS:
        full = model.dynamic(w)
        bare = ideal.dynamic(w)
        tag = f"omega_{w:g}".replace(".", "p")
        written.append(full.to_csv(out_dir / f"dynamic_{tag}.csv"))
        written.append(_compare_plot(full, bare, out_dir / f"dynamic_{tag}.png"))
        summary["dynamic"][f"{w:g}"] = {"with_dissipation": full.summary, "without_dissipation": bare.summary}

    sw = model.sweep(np.arange(1.0, 50.0 + 1e-9, 0.5), quiet=quiet)
    written.append(sw.to_csv(out_dir / "sweep.csv"))
    plt.close(sw.plot(out_dir / "sweep.png"))
    written.append(out_dir / "sweep.png")

    fw = ideal.forward(1.0, base_motion=lambda t: (0.036 * (1 - np.cos(10.0 * t)), 0.36 * np.sin(10.0 * t)),
                       base_stiffness=2000.0, x0=1e-3)
    written.append(fw.to_csv(out_dir / "forward_base_spring.csv"))
    plt.close(fw.plot(out_dir / "forward_base_spring.png"))
    written.append(out_dir / "forward_base_spring.png")
    summary["forward_base_spring"] = fw.summary

    dz = design(12.8, 0.040, 207e9, 1.5e9)
    dz_ok = design(12.8, 0.040, 207e9, 1.5e9, stroke_fraction=0.2)
    summary["design_40mm_fraction_0.4"] = dz.summary
    summary["design_40mm_fraction_0.2"] = dz_ok.summary
    written.append(dz_ok.to_toml(out_dir / "design_12p8N_40mm.toml"))

    written.append(write_json(out_dir / "summary.json", summary))
    return written


def _compare_plot(full, bare, path) -> Path:
    """Figs. 8-11: force with and without tau_CF and tau_AF at one frequency."""
    fig, ax = new_figure()
    ax.plot(full.time, full.force, label="with tau_CF, tau_AF")
    ax.plot(bare.time, bare.force, "--", label="without")
    ax.plot(full.time, full.force_static, ":", color="k", label="static force")
    s = full.summary
    ax.set_title(f"omega = {s['omega_rad_s']:g} rad/s, {s['motion']}\n"
                 f"toggle cut-off {np.degrees(s['toggle_cutoff_rad']):.3g} deg", fontsize=10)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("slider force [N]")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return save_figure(fig, path)


def _stress_plot(model, st, path) -> Path:
    """Pivot bending stress along the stroke against the allowable stress."""
    p = model.params
    fig, ax = new_figure()
    ax.plot(st.deflection * 1e3, st.stress / 1e9, label="E (h/2) theta_K3 / l")
    ax.axhline(p.allowable_stress / 1e9, color="r", ls="--", label="allowable")
    ax.axvline(st.summary["max_stroke_for_stress_m"] * 1e3, color="r", ls=":", label="largest allowed stroke")
    ax.set_xlabel("slider deflection [mm]")
    ax.set_ylabel("pivot bending stress [GPa]")
    ax.set_title(f"Safety factor {st.summary['safety_factor']:.3g} over {st.summary['stroke_m'] * 1e3:.3g} mm")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return save_figure(fig, path)
