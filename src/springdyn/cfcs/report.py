"""The constant-force-spring section of the springdyn report (and of ``springdyn demo``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..io import write_json
from ..plotting import plt
from ..report.html import Section, fmt, parameter_rows
from .demo import PAPER_OMEGAS, _compare_plot, _stress_plot
from .model import CFCS
from .params import CFCSParams

__all__ = ["load", "section"]


def load(doc: dict, path: Path) -> CFCS:
    """Validate the [cfcs] table of a definition."""
    return CFCS(CFCSParams.from_dict(doc["cfcs"], source=str(path)))


def section(model: CFCS, *, source: str, out_dir: Path, quiet: bool = True) -> Section:
    """Static curve, dynamic force at the paper's four frequencies, sweep and pivot stress."""
    ideal = CFCS(model.params.without_dissipation())
    files, figures = [], []
    st = model.static()
    files.append(st.to_csv(out_dir / "static.csv"))
    plt.close(st.plot(out_dir / "static.png"))
    figures.append((out_dir / "static.png", "Force-deflection by virtual work (CFCS paper Figs. 2-3), with the "
                    "compression and extension branches of the dissipative terms"))
    figures.append((_stress_plot(model, st, out_dir / "pivot_stress.png"), "Flexural-pivot bending stress along "
                    "the stroke against the allowable stress"))
    dyn = {}
    for w in PAPER_OMEGAS:
        full, bare = model.dynamic(w), ideal.dynamic(w)
        tag = f"omega_{w:g}".replace(".", "p")
        files.append(full.to_csv(out_dir / f"dynamic_{tag}.csv"))
        figures.append((_compare_plot(full, bare, out_dir / f"dynamic_{tag}.png"),
                        f"Slider force at omega = {w:g} rad/s with and without tau_CF, tau_AF (paper Figs. 8-11)"))
        dyn[w] = (full.summary, bare.summary)
    sw = model.sweep(np.arange(1.0, 50.0 + 1e-9, 0.5), quiet=quiet)
    files.append(sw.to_csv(out_dir / "sweep.csv"))
    plt.close(sw.plot(out_dir / "sweep.png"))
    figures.append((out_dir / "sweep.png", "Mean, median, peak-to-peak force and PCF against omega (paper Figs. 5-7)"))
    s = st.summary
    files.append(write_json(out_dir / "summary.json", {"static": s, "dynamic": {f"{w:g}": v for w, v in dyn.items()}}))
    p = model.params
    findings = [
        f"Over a {s['stroke_m'] * 1e3:.1f} mm stroke the static force stays between {s['force_min_N']:.3f} N and "
        f"{s['force_max_N']:.3f} N (maximum at {s['deflection_at_force_max_m'] * 1e3:.1f} mm): "
        f"{s['pcf_percent']:.1f} % constant force (Fmin/Fmax; energy-based {s['pcf_energy_percent']:.1f} %).",
        f"With pin friction and the axial-force term ({p.friction_model} friction model), the quasi-static "
        f"compression branch alone is {s['pcf_compression_percent']:.1f} % constant.",
        f"The flexural pivot (K3 = {s['k3_N_m_per_rad']:.4g} N m/rad) reaches {s['max_stress_Pa'] / 1e9:.2f} GPa over the "
        f"stroke: safety factor {s['safety_factor']:.2f} against {p.allowable_stress / 1e9:.2f} GPa; the pivot allows "
        f"only {s['max_stroke_for_stress_m'] * 1e3:.1f} mm of stroke."
        if p.allowable_stress else
        f"The flexural pivot reaches {s['max_stress_Pa'] / 1e9:.2f} GPa over the stroke (no allowable stress given).",
    ]
    for w in (min(PAPER_OMEGAS), max(PAPER_OMEGAS)):
        full, bare = dyn[w]
        findings.append(
            f"At omega = {w:g} rad/s the drive force averages {full['mean_force_N']:.2f} N with a peak-to-peak of "
            f"{full['peak_to_peak_N']:.2f} N (without tau_CF and tau_AF: {bare['peak_to_peak_N']:.2f} N); "
            f"hysteresis {full['hysteresis_energy_per_cycle_J'] * 1e3:.1f} mJ per cycle."
        )
    findings.append(f"Near the toggle (theta2 < {np.degrees(p.toggle_cutoff):.3g} deg) the axial-force term and the "
                    "Jacobian diverge; springdyn holds them at the cut-off, stated in every output.")
    derived = [
        ("K3", fmt(s["k3_N_m_per_rad"], "N*m/rad"), "pivot torsional stiffness E I / l"),
        ("force at toggle", fmt(s["force_at_zero_N"], "N"), "static force as theta2 -> 0"),
        ("maximum force", fmt(s["force_max_N"], "N"), f"at {s['deflection_at_force_max_m'] * 1e3:.2f} mm"),
        ("PCF", fmt(s["pcf_percent"], "%", 4), "Fmin/Fmax over the stroke"),
        ("kinematic limit", fmt(s["kinematic_limit_m"] * 1e3, "mm"), "theta2 = 90 deg"),
        ("max pivot stress", fmt(s["max_stress_Pa"] / 1e9, "GPa"), "E (h/2) theta_K3 / l"),
        ("safety factor", fmt(s["safety_factor"], "", 3), "allowable / max stress"),
    ]
    return Section(
        family="cfcs", title="Constant-force compression spring", source=source,
        commands=[f"springdyn cfcs static {source} --plot static.png --json",
                  f"springdyn cfcs dynamic {source} --omega 14.7 --plot dynamic.png --json",
                  f"springdyn cfcs sweep {source} --omega 1:50:100 --plot sweep.png"],
        inputs=parameter_rows(p), derived=derived, findings=findings, figures=figures, files=files,
    )
