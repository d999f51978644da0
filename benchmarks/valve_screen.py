"""The full tolerance study, screened (issue 42).  Run:  python benchmarks/valve_screen.py

Measures in one run, on this machine:

1. the yardstick: one Type C simulation, 2 revolutions at 3000 cam rpm, with SciPy's DOP853
   and the plain-Python right-hand side (as benchmarks/valve_speed.py), best of 3;
2. the README's full tolerance study (``examples/valve/tolerances.toml``: seven toleranced
   parameters and its criteria, the one-step spring on the bucket train and the polydyne cam,
   ``--cam-rpm`` 2000-3000 in steps of 100 as the README runs it (a sweep of 11 speeds a
   variant, the float speed narrowed to 5 rpm, the worst speeds refined; 1500:3300:100 is the
   range where the float limit, the range's top, cuts through the variants' float speeds and
   Goodman's limit through their safeties: the screen's worst case) screened
   (``tolerance_study(screen=True)``),
   ``--variants`` of them (default 10,000), end to end from the call: the statics of every
   variant, the fitted and held-out variants, the undecided ones;
3. the check (``--check`` variants, default 256): the same study screened and with every
   variant simulated: every criterion's verdict of every variant must be the same, and every
   figure the surface gave within its band and the simulation's own reproducibility (the
   periodicity tolerance in the figure's terms, ``figure_tolerance``: 0.2 % of Fset for a
   force, 0.2 % of a Goodman safety) of the simulation.  The unscreened study's time a
   variant projects the unscreened ``--variants`` study: the ratio is the screen's gain.

The goal (issue 42): 10,000 variants in 5 minutes on the 2-core machine of 2026-11-26, where
the yardstick took 0.65 s (docs/performance.md): 460 yardsticks.  Printed in both units;
exits 1 when a verdict differs, a figure leaves its band, or the screened study takes more
than 460 yardsticks.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings

#: The goal [s] on the machine of the yardstick's YARDSTICK_THEN (valve_variants.py).
GOAL_SECONDS = 300.0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--variants", type=int, default=10_000, help="variants of the screened study (default 10000)")
    ap.add_argument("--check", type=int, default=256, help="variants run both ways to check the screen (default 256)")
    ap.add_argument("--cam-rpm", default="2000:3000:100", help="START:STOP:STEP of the sweep (default 2000:3000:100)")
    args = ap.parse_args(argv)
    warnings.simplefilter("ignore")

    import numpy as np

    from springdyn.valve import simulate
    from springdyn.valve.design.tolerances import SEARCH_AGREEMENT, figure_tolerance, read_tolerances, tolerance_study

    sys.path.insert(0, os.path.dirname(__file__))
    from valve_variants import EXAMPLES, YARDSTICK_THEN, bucket_example, yardstick

    spring, cam, vt = bucket_example()
    tols, criteria = read_tolerances(os.path.join(EXAMPLES, "tolerances.toml"))
    lo, hi, step = (float(v) for v in args.cam_rpm.split(":"))
    speeds = np.arange(lo, hi + 0.5 * step, step)
    simulate(spring, cam, 3000.0, valve_train=vt)  # the engine loaded (compiled once per machine: cold_start.py)

    yard = yardstick()
    print(
        f"yardstick (SciPy DOP853, one Type C run of 2 revolutions): {yard:.3f} s (on 2026-11-26: {YARDSTICK_THEN} s)"
    )

    def study(count, screen):
        t = time.perf_counter()
        res = tolerance_study(
            spring, cam, tols, criteria, count=count, seed=0, speeds=speeds, valve_train=vt, screen=screen
        )
        return res, time.perf_counter() - t

    ok = True
    scr, t_scr = study(args.check, True)
    full, t_full = study(args.check, False)
    ds, ref = scr.dataset, full.dataset
    sim = ds["simulated"].values.astype(bool)
    print(
        f"check, {args.check} variants: screened {t_scr:.1f} s ({sim.sum()} simulated), every variant simulated "
        f"{t_full:.1f} s"
    )
    for name, fails in scr.failures().items():
        same = np.array_equal(fails, full.failures()[name])
        ok &= same
        print(f"  {name}: {fails.mean():.1%} failing, verdicts {'the same' if same else 'DIFFERENT'} for every variant")
    for k in ("float_cam_rpm", "max_retainer_force", "clash_onset_cam_rpm", "max_clash_severity", "goodman_safety"):
        how, band = ds.attrs.get(f"screen_{k}"), ds.attrs.get(f"screen_band_{k}")
        if how is None:
            continue
        # a simulation is itself reproducible to the periodicity tolerance (figure_tolerance)
        free = ~sim & ~(ds["float_searched"].values > 0) if k == "float_cam_rpm" else ~sim
        err = np.abs(ds[k].values - ref[k].values)[free]
        allowed = band + figure_tolerance(k, ref[k].values, ref["Fset"].values, 5.0, speeds)[free]
        worst = float(err.max()) if err.size else 0.0
        inside = bool(np.all(err <= allowed))
        ok &= inside
        print(
            f"  {k}: {how}, band {band:.4g}; largest error of a predicted variant {worst:.4g}, "
            + ("within" if inside else "OUTSIDE")
            + " its band and the simulation's own tolerance"
        )
    f = np.abs(ds["float_cam_rpm"].values - ref["float_cam_rpm"].values)[ds["float_searched"].values > 0]
    if f.size:
        inside = bool(np.all(f <= 5.0 + SEARCH_AGREEMENT))
        ok &= inside
        print(
            f"  float_cam_rpm of the {f.size} variants whose float speed alone was searched: largest difference "
            f"{f.max():.2f} rpm ({'within' if inside else 'OUTSIDE'} the resolution and the search's agreement, "
            f"{5.0 + SEARCH_AGREEMENT:g} rpm)"
        )

    big, t_big = study(args.variants, True)
    n_sim = int(big.dataset["simulated"].values.sum())
    projected = args.variants * t_full / args.check
    in_yards, goal_yards = t_big / yard, GOAL_SECONDS / YARDSTICK_THEN
    met = in_yards <= goal_yards
    ok &= met
    s = big.summary
    print(
        f"screened study, {args.variants} variants: {t_big:.1f} s ({t_big / 60:.1f} min), {n_sim} simulated "
        f"({n_sim / args.variants:.1%}); every variant simulated, projected from the check: {projected / 60:.1f} min; "
        f"gain {projected / t_big:.1f}x"
    )
    print(
        f"  {in_yards:.0f} yardsticks (goal <= {goal_yards:.0f}: 5 min on the machine of 2026-11-26): "
        + ("MET" if met else f"NOT MET ({in_yards / goal_yards:.2f}x)")
    )
    print(
        "  failing: "
        + ", ".join(f"{k[len('fail_share_') :]} {v:.1%}" for k, v in s.items() if k.startswith("fail_share_"))
    )
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
