"""Design a constant-force compression spring for a target force and stroke.

``springdyn.cfcs.design`` picks the crank/coupler ratio r2/r3 with the flattest force over
the stroke, then the pivot stiffness K3 and the flexure (width b, thickness h, length l)
so that the force is the target and the peak bending stress of the strip (its
large-deflection elastica, the default ``flexure_model = "beam"``) stays below the allowable
stress over the safety factor (default 1.5).  The design is then checked independently: it
is turned into a ``[cfcs]`` parameter set and its static force curve is computed with the
``CFCS`` model, beam and PRBM side by side.  The script also shows what happens when the stroke is too long for the
material (no feasible design, with the length that would work).

Run:  python examples/cfcs/design_for_force.py [--out DIR] [--force 20N] [--stroke 30mm]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from springdyn.cfcs import CFCS, design
from springdyn.core.units import to_si


def design_and_check(force: float, stroke: float, modulus: float, allowable: float, stroke_fraction: float = 0.1):
    """The design for ``force`` [N] over ``stroke`` [m] and the model's static result of it."""
    result = design(force, stroke, modulus, allowable, stroke_fraction=stroke_fraction)
    params = result.to_params(
        crank_mass=0.02, coupler_mass=0.02, slider_mass=0.05, friction_model="none", axial_force=False
    )
    static = CFCS(params).static(stroke, offset=0.0)
    return result, static


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="output folder (default: a new temporary folder)")
    parser.add_argument("--force", default="20 N", help="target constant force (default 20 N)")
    parser.add_argument("--stroke", default="30 mm", help="working stroke from the toggle (default 30 mm)")
    parser.add_argument("--stroke-fraction", type=float, default=0.1, help="stroke / (r2 + r3) (default 0.1)")
    args = parser.parse_args(argv)
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="springdyn-cfcs-design-"))
    out.mkdir(parents=True, exist_ok=True)
    force, stroke = to_si(args.force, "N", "--force"), to_si(args.stroke, "m", "--stroke")
    modulus, allowable = 207e9, 1.5e9  # spring steel

    result, static = design_and_check(force, stroke, modulus, allowable, args.stroke_fraction)
    s = result.summary
    print(
        f"target {force:g} N over {stroke * 1e3:g} mm, spring steel (E 207 GPa, allowable 1.5 GPa, "
        f"safety {result.summary['safety_factor_target']:g})"
    )
    print(
        f"  r2 + r3 = {s['total_length_m'] * 1e3:.1f} mm, r2/r3 = {s['ratio']:.4f}: "
        f"r2 = {s['crank_length_m'] * 1e3:.2f} mm, r3 = {s['coupler_length_m'] * 1e3:.2f} mm"
    )
    print(
        f"  K3 = {s['torsional_stiffness_N_m_per_rad']:.4g} N*m/rad; flexure b x h x l = "
        f"{s['pivot_width_m'] * 1e3:.3g} x {s['pivot_thickness_m'] * 1e3:.3g} x {s['pivot_length_m'] * 1e3:.3g} mm"
    )
    print(
        f"  design force {s['force_min_N']:.3f} .. {s['force_max_N']:.3f} N, PCF {s['pcf_percent']:.2f} %, "
        f"max pivot stress {s['max_stress_Pa'] / 1e9:.3f} GPa (safety factor {s['safety_factor']:.2f})"
    )
    c = static.summary
    print(
        f"  check with the CFCS model: force {c['force_min_N']:.3f} .. {c['force_max_N']:.3f} N, "
        f"PCF {c['pcf_percent']:.2f} %, peak stress {c['max_stress_Pa'] / 1e9:.3f} GPa ({c['flexure_model']} model; "
        f"PRBM mean-curvature value {c['prbm_max_stress_Pa'] / 1e9:.3f} GPa)"
    )
    print(("FEASIBLE: " if result.feasible else "NOT FEASIBLE: ") + s["message"])
    result.to_toml(out / "designed_cfcs.toml")
    result.to_csv(out / "design_curve.csv")
    result.plot(out / "design_curve.png")

    long_stroke = design(force, stroke, modulus, allowable, stroke_fraction=0.4)
    print(
        f"same target at stroke fraction 0.4 (the paper's 40 %): "
        f"{'feasible' if long_stroke.feasible else 'not feasible'}: {long_stroke.summary['message']}"
    )
    print(f"wrote {out / 'designed_cfcs.toml'}, design_curve.csv, design_curve.png")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
