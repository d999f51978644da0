"""The constant-force-spring section of the springdyn report (and of ``springdyn demo``).

For a mechanism: the static curve (Figs. 2-3 of the CFCS paper), the drive force at the
four frequencies of Figs. 8-11 with and without tau_CF and tau_AF (from the preload offset),
what the toggle would do to them, the frequency sweep (Figs. 5-7), the pivot stress, the
flexure as a pin (PRBM) and as its elastica side by side, a forward-dynamics run (slider on
a spring from a moving base) and a design for the same force and stroke that holds.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from springdyn.app.report.html import Criterion, Section, add_result, fmt, parameter_rows
from springdyn.cfcs.design import design_flattest
from springdyn.cfcs.model import CFCS
from springdyn.cfcs.motion import SinusoidMotion
from springdyn.cfcs.params import CFCSParams
from springdyn.core.io import write_json
from springdyn.core.plotting import new_figure, save_figure

__all__ = ["load", "section", "PAPER_OMEGAS"]

#: Percent constant force a constant-force spring should reach over its stroke to be
#: called one (a common target of the constant-force mechanism literature; the paper's
#: own example reaches 87.2 %).
PCF_MIN = 90.0
#: The input frequencies of Figs. 8-11 of the CFCS paper [rad/s].
PAPER_OMEGAS = (2.09, 4.19, 14.7, 41.89)


def load(doc: dict, path: Path) -> CFCS:
    """Validate the [cfcs] table of a definition."""
    return CFCS(CFCSParams.from_dict(doc["cfcs"], source=str(path)))


def section(model: CFCS, *, source: str, out_dir: Path, quiet: bool = True) -> Section:
    """Static curve, dynamic force at the paper's four frequencies, sweep and pivot stress."""
    ideal = CFCS(model.params.without_dissipation())
    files, figures = [], []
    st = model.static()
    add_result(
        files,
        figures,
        st,
        out_dir / "static.png",
        "Force-deflection by virtual work (CFCS paper Figs. 2-3), with the "
        "compression and extension branches of the dissipative terms",
    )
    figures.append(
        (
            _stress_plot(model, st, out_dir / "pivot_stress.png"),
            "Flexural-pivot bending stress along the stroke against the allowable stress",
        )
    )
    dyn = {}
    for w in PAPER_OMEGAS:
        full, bare = model.dynamic(w), ideal.dynamic(w)
        tag = f"omega_{w:g}".replace(".", "p")
        files.append(full.to_csv(out_dir / f"dynamic_{tag}.csv"))
        figures.append(
            (
                _compare_plot(full, bare, out_dir / f"dynamic_{tag}.png"),
                f"Slider force at omega = {w:g} rad/s with and without tau_CF, tau_AF (paper Figs. 8-11)",
            )
        )
        dyn[w] = (full.summary, bare.summary)
    sw = model.sweep(np.arange(1.0, 50.0 + 1e-9, 0.5), quiet=quiet)
    add_result(
        files,
        figures,
        sw,
        out_dir / "sweep.png",
        "Mean, median, peak-to-peak force and PCF against omega (paper Figs. 5-7)",
    )
    s = st.summary
    p = model.params
    # the flexure: pseudo-rigid-body pin against the elastica of the strip (same modulus), side by side
    comparison = None
    if p.has_flexure:
        beam = CFCS(p.replace(flexure_model="beam", plate_bending=p.uses_plate_bending("prbm")))
        bs = beam.static(s["stroke_m"], n=289)
        files.append(bs.to_csv(out_dir / "flexure_models.csv"))
        figures.append(
            (
                _flexure_plot(bs, out_dir / "flexure_models.png"),
                "The flexure as a pin (PRBM) and as "
                "its large-deflection elastica (beam), same modulus: force, running PCF and peak bending "
                "stress against the deflection",
            )
        )
        comparison = bs.summary
        plate_factor = 1.0 / (1.0 - p.poisson_ratio**2)
    # the toggle: what the statistics would be if the motion started at the toggle (offset 0)
    through = model.dynamic(max(PAPER_OMEGAS[:3]), offset=0.0).summary
    # forward dynamics: the frictionless slider pushed through a spring by a moving base
    base = SinusoidMotion(10.0, 0.072, 0.0)  # x = 36 mm (1 - cos 10 t), the library's sinusoid
    fw = ideal.forward(1.0, base_motion=lambda t: base(t)[:2], base_stiffness=2000.0, x0=1e-3)
    add_result(
        files,
        figures,
        fw,
        out_dir / "forward_base_spring.png",
        "Forward dynamics: the slider driven through a 2 N/mm "
        "spring by a base moving 36 mm at 10 rad/s (frictionless model)",
    )
    # design for this mechanism's force and stroke, in its material, within its stress limit
    allowable = p.allowable_stress or 1.5e9
    limited = s["safety_factor"] is not None and s["safety_factor"] < 1
    target_stroke = s["max_stroke_for_stress_m"] if limited else s["stroke_m"]
    dz = design_flattest(s["force_at_zero_N"], target_stroke, p.youngs_modulus, allowable, stroke_fraction=0.1)
    files.append(dz.to_toml(out_dir / "design.toml"))
    files.append(
        write_json(
            out_dir / "summary.json",
            {
                "static": s,
                "dynamic": {f"{w:g}": v for w, v in dyn.items()},
                "dynamic_through_toggle": through,
                "flexure_models": comparison,
                "forward_base_spring": fw.summary,
                "design": dz.summary,
            },
        )
    )
    findings = [
        f"Over a {s['stroke_m'] * 1e3:.1f} mm stroke the static force stays between {s['force_min_N']:.3f} N and "
        f"{s['force_max_N']:.3f} N (maximum at {s['deflection_at_force_max_m'] * 1e3:.1f} mm): "
        f"{s['pcf_percent']:.1f} % constant force (Fmin/Fmax; energy-based {s['pcf_energy_percent']:.1f} %).",
        f"With pin friction and the axial-force term ({p.friction_model} friction model), the quasi-static "
        f"compression branch over the working range {s['working_start_m'] * 1e3:.1f}-{s['working_end_m'] * 1e3:.1f} mm "
        f"(from the preload offset) is {s['pcf_compression_percent']:.1f} % constant"
        + (
            " (toggle-dominated: depends on the cut-off)."
            if s["toggle_dominated"]
            else "; no statistic depends on the toggle cut-off."
        ),
        f"The flexural pivot (K3 = {s['k3_N_m_per_rad']:.4g} N m/rad) reaches {s['max_stress_Pa'] / 1e9:.2f} GPa over the "
        f"stroke: safety factor {s['safety_factor']:.2f} against {p.allowable_stress / 1e9:.2f} GPa"
        + (
            ": the pivot YIELDS (its stress exceeds the allowable, the mechanism takes a set)"
            if s["safety_factor"] < 1
            else ""
        )
        + f"; the pivot allows only {s['max_stroke_for_stress_m'] * 1e3:.1f} mm of stroke."
        if p.allowable_stress and s["max_stress_Pa"] is not None
        else f"The flexural pivot reaches {s['max_stress_Pa'] / 1e9:.2f} GPa over the stroke (no allowable stress given)."
        if s["max_stress_Pa"] is not None
        else f"The pivot is given by its stiffness K3 = {s['k3_N_m_per_rad']:.4g} N m/rad only: its stress is not known "
        "(give pivot_width, pivot_thickness and pivot_length for a stress check).",
    ]
    for w in (min(PAPER_OMEGAS), max(PAPER_OMEGAS)):
        full, bare = dyn[w]
        findings.append(
            f"At omega = {w:g} rad/s ({full['motion']}) the drive force averages {full['mean_force_N']:.2f} N with a "
            f"peak-to-peak of {full['peak_to_peak_N']:.2f} N (without tau_CF and tau_AF: {bare['peak_to_peak_N']:.2f} N); "
            f"hysteresis {full['hysteresis_energy_per_cycle_J'] * 1e3:.1f} mJ per cycle"
            + (" (toggle-dominated)." if full["toggle_dominated"] else ".")
        )
    chk = through.get("statistics_at_doubled_cutoff", {})
    findings.append(
        f"Started at the toggle instead (offset 0, omega = {through['omega_rad_per_s']:g} rad/s) the peak-to-peak force is "
        f"{through['peak_to_peak_N']:.1f} N with the {np.degrees(p.toggle_cutoff):.3g} deg cut-off and "
        f"{chk.get('peak_to_peak_N', through['peak_to_peak_N']):.1f} N with twice it: "
        + (
            "toggle-dominated, a property of the numerical cut-off and not of the mechanism (the axial-force term "
            "turned into a slider force grows as alpha/theta2 there); springdyn flags such results."
            if through["toggle_dominated"]
            else "not toggle-dominated for this mechanism."
        )
    )
    if p.drive_stiffness is not None:  # the same start through the toggle, forward, with the drive's compliance
        dr = model.driven(max(PAPER_OMEGAS[:3]), offset=0.0).summary
        findings.append(
            f"Through the toggle with the drive's compliance ([cfcs] drive_stiffness {p.drive_stiffness / 1e3:g} kN/m, "
            f"drive_damping {p.drive_damping:g} N s/m; forward dynamics, no cut-off): peak-to-peak "
            f"{dr['peak_to_peak_N']:.1f} N"
            + (
                f"; the crank sticks inside the shear angle for {dr['toggle_sticking_share']:.1%} of the period, held by "
                "tau_AF (22) taken with the static force, which is not a model of the mechanism there: without tau_AF "
                f"{dr['peak_to_peak_without_axial_friction_N']:.1f} N (docs/cfcs.md)."
                if dr.get("toggle_sticking")
                else "."
            )
        )
    else:
        findings.append(
            "Through the toggle the force is finite only with the compliance of what drives the slider: give "
            "[cfcs] drive_stiffness (and drive_damping) for the forward dynamics without a cut-off "
            "(springdyn cfcs dynamic --drive-stiffness; docs/cfcs.md)."
        )
    if comparison is not None:
        c = comparison
        f0 = c["force_at_zero_N"]
        findings.append(
            f"The flexure as its large-deflection elastica (l/r3 = {p.pivot_length / p.r3:.3g}, same modulus) against "
            f"the PRBM pin over 0-{c['stroke_m'] * 1e3:.0f} mm: the force differs by at most "
            f"{c['max_force_difference_to_prbm_N']:.3f} N ({100 * c['max_force_difference_to_prbm_N'] / f0:.2f} % of "
            f"F0), the maximum moves from {c['prbm_deflection_at_force_max_m'] * 1e3:.1f} to "
            f"{c['deflection_at_force_max_m'] * 1e3:.1f} mm, the band Fmax - Fmin is {c['force_max_N'] - c['force_min_N']:.3f} N "
            f"instead of {c['prbm_force_max_N'] - (c['prbm_force_max_N'] * c['prbm_pcf_percent'] / 100):.3f} N (PCF "
            f"{c['pcf_percent']:.1f} % vs {c['prbm_pcf_percent']:.1f} %), and the peak bending stress is "
            f"{100 * (c['max_stress_Pa'] / c['prbm_max_stress_Pa'] - 1):.0f} % above the PRBM's mean-curvature value. "
            f"As a plate (b/l = {p.pivot_width / p.pivot_length:.2g}, E/(1 - nu^2)) the strip is "
            f"{100 * (plate_factor - 1):.1f} % stiffer still."
        )
    d = dz.summary
    findings.append(
        f"Design for {d['target_force_N']:.2f} N over {d['stroke_m'] * 1e3:.1f} mm within {allowable / 1e9:.2f} GPa "
        f"over a safety factor {d['safety_factor_target']:g} ({d['flexure_model']} model, PCF >= "
        f"{d['min_pcf_percent']:g} %): "
        + (
            f"r2 + r3 = {d['total_length_m'] * 1e3:.1f} mm: r2 = {d['crank_length_m'] * 1e3:.1f} mm, r3 = {d['coupler_length_m'] * 1e3:.1f} mm, flexure "
            f"{d['pivot_width_m'] * 1e3:.2f} x {d['pivot_thickness_m'] * 1e3:.3f} x {d['pivot_length_m'] * 1e3:.2f} mm "
            f"(b x h x l), PCF {d['pcf_percent']:.1f} %, safety factor {d['safety_factor']:.2f}, force "
            f"{d['force_min_at_thickness_tolerance_N']:.2f}-{d['force_max_at_thickness_tolerance_N']:.2f} N for "
            f"+-{100 * d['thickness_tolerance']:.0f} % strip thickness (design.toml)."
            if d["feasible"]
            else f"no design meets the stress limit: {d['message']}"
        )
    )
    findings.append(
        f"The dynamic results start from a preload offset ({s['working_start_m'] * 1e3:.1f} mm, inside the "
        f"constant-force band), above the toggle zone (theta2 < {np.degrees(p.toggle_cutoff):.3g} deg) where "
        "the dissipative terms turned into a slider force diverge; a result that enters the zone is "
        "computed at the cut-off and at twice it and flagged when it moves by more than 1 %."
    )
    derived = [
        ("K3", fmt(s["k3_N_m_per_rad"], "N*m/rad"), "pivot torsional stiffness E I / l"),
        ("force at toggle", fmt(s["force_at_zero_N"], "N"), "static force as theta2 -> 0"),
        ("maximum force", fmt(s["force_max_N"], "N"), f"at {s['deflection_at_force_max_m'] * 1e3:.2f} mm"),
        ("PCF", fmt(s["pcf_percent"], "%", 4), "Fmin/Fmax over the stroke"),
        ("kinematic limit", fmt(s["kinematic_limit_m"] * 1e3, "mm"), "theta2 = 90 deg"),
        (
            "max pivot stress",
            fmt(s["max_stress_Pa"] / 1e9, "GPa") if s["max_stress_Pa"] is not None else "n/a",
            "E (h/2) theta_K3 / l",
        ),
        (
            "safety factor",
            fmt(s["safety_factor"], "", 3) if s["safety_factor"] is not None else "n/a",
            "allowable / max stress",
        ),
    ]
    criteria = [
        Criterion(
            "percent constant force (PCF)",
            f"{s['pcf_percent']:.1f} %",
            f">= {PCF_MIN:g} %",
            bool(s["pcf_percent"] >= PCF_MIN),
            "Fmin/Fmax of the static force over the stroke",
        ),
        Criterion(
            "pivot stress safety factor",
            f"{s['safety_factor']:.2f}" if s["safety_factor"] is not None else "n/a",
            ">= 1",
            None if s["safety_factor"] is None else bool(s["safety_factor"] >= 1.0),
            (
                f"allowable {p.allowable_stress / 1e9:.2f} GPa over {s['stroke_m'] * 1e3:.1f} mm"
                if s["safety_factor"] is not None
                else "needs allowable_stress and the pivot dimensions"
            ),
        ),
        Criterion(
            "results independent of the toggle cut-off",
            "yes"
            if not (s["toggle_dominated"] or any(v[0]["toggle_dominated"] for v in dyn.values()))
            else "no (toggle-dominated)",
            "no statistic moves > 1 % when the cut-off doubles",
            not (s["toggle_dominated"] or any(v[0]["toggle_dominated"] for v in dyn.values())),
            f"motion from the preload offset {s['working_start_m'] * 1e3:.1f} mm",
        ),
        Criterion(
            "design for this force and stroke",
            "feasible" if d["feasible"] else "not feasible",
            "feasible",
            bool(d["feasible"]),
            d.get("message", "") or "see the design finding",
        ),
    ]
    return Section(
        family="cfcs",
        title="Constant-force compression spring",
        source=source,
        criteria=criteria,
        commands=[
            f"springdyn cfcs static {source} --plot static.png --json",
            f"springdyn cfcs dynamic {source} --omega 14.7 --plot dynamic.png --json",
            f"springdyn cfcs sweep {source} --omega 1:50:0.5 --plot sweep.png",
            f"springdyn cfcs design --force {d['target_force_N']:.4g}N --stroke {d['stroke_m'] * 1e3:.4g}mm "
            f"--material-modulus {p.youngs_modulus / 1e9:.4g}GPa --allowable-stress {allowable / 1e9:.4g}GPa",
        ],
        inputs=parameter_rows(p),
        derived=derived,
        findings=findings,
        figures=figures,
        files=files,
    )


def _flexure_plot(bs, path) -> Path:
    """PRBM and beam side by side: force, running PCF and peak stress against the deflection."""
    from springdyn.cfcs.results import running_pcf

    fig, axes = new_figure(3, 1, figsize=(8.0, 9.0), sharex=True)
    mm = bs.deflection * 1e3
    beam_f, prbm_f = bs.force, bs.extra["force_prbm_N"]
    axes[0].plot(mm, beam_f, label="beam (elastica)")
    axes[0].plot(mm, prbm_f, "--", label="PRBM (pin, K3 = EI/l)")
    axes[0].set_ylabel("force [N]")
    axes[1].plot(mm, running_pcf(beam_f), label="beam")
    axes[1].plot(mm, running_pcf(prbm_f), "--", label="PRBM")
    axes[1].set_ylabel("PCF over 0..x [%]")
    axes[2].plot(mm, bs.stress / 1e9, label="beam: largest curvature")
    axes[2].plot(mm, bs.extra["stress_prbm_Pa"] / 1e9, "--", label="PRBM: mean curvature theta_K3/l")
    axes[2].set_ylabel("peak bending stress [GPa]")
    axes[2].set_xlabel("slider deflection [mm]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend()
    axes[0].set_title("Flexure as a pin (PRBM) and as its elastica (beam), same modulus")
    return save_figure(fig, path)


def _compare_plot(full, bare, path) -> Path:
    """Figs. 8-11: force with and without tau_CF and tau_AF at one frequency."""
    fig, ax = new_figure()
    ax.plot(full.time, full.force, label="with tau_CF, tau_AF")
    ax.plot(bare.time, bare.force, "--", label="without")
    ax.plot(full.time, full.force_static, ":", color="k", label="static force")
    s = full.summary
    ax.set_title(
        f"omega = {s['omega_rad_per_s']:g} rad/s, {s['motion']}\n"
        f"toggle cut-off {np.degrees(s['toggle_cutoff_rad']):.3g} deg",
        fontsize=10,
    )
    ax.set_xlabel("time [s]")
    ax.set_ylabel("slider force [N]")
    ax.grid(True, alpha=0.3)
    ax.legend()
    return save_figure(fig, path)


def _stress_plot(model, st, path) -> Path:
    """Pivot bending stress along the stroke against the allowable stress."""
    p = model.params
    fig, ax = new_figure()
    stress = st.stress if st.summary["max_stress_Pa"] is not None else np.zeros_like(st.deflection)
    ax.plot(st.deflection * 1e3, stress / 1e9, label="E (h/2) theta_K3 / l")
    if p.allowable_stress:
        ax.axhline(p.allowable_stress / 1e9, color="r", ls="--", label="allowable")
    if st.summary["max_stroke_for_stress_m"] is not None:
        ax.axvline(st.summary["max_stroke_for_stress_m"] * 1e3, color="r", ls=":", label="largest allowed stroke")
    ax.set_xlabel("slider deflection [mm]")
    ax.set_ylabel("pivot bending stress [GPa]")
    sf = st.summary["safety_factor"]
    ax.set_title(
        f"Safety factor {sf:.3g} over {st.summary['stroke_m'] * 1e3:.3g} mm"
        if sf is not None
        else "pivot stress (no allowable stress, or the pivot is given by its stiffness only: stress unknown)"
    )
    ax.grid(True, alpha=0.3)
    ax.legend()
    return save_figure(fig, path)
