"""Valve-spring synthesis end to end (issue 42, row 2).  Run:  python benchmarks/valve_synthesis.py

Runs ``springdyn valve synthesize examples/valve/requirements.toml`` as the library call it
makes (the engine loaded from its cache first), twice in one process:

1. as shipped: the dynamic checks screen (the lightest candidate that meets every requirement
   ends the distributed runs, no float search for a candidate that misses one already);
2. the reference measured in the same run: ``judge_all=True``, every candidate run and its
   float speed searched, the method before issue 42's screen.

Prints both wall times, their ratio, the distributed runs of each, and whether the first
candidate and its figures are the same; exits 1 if they differ or the screened synthesis takes
longer than the goal (issue 42: 15 s on a quiet 2-core machine; ``--goal`` to change it).
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--goal", type=float, default=15.0, help="seconds the screened synthesis may take (default 15)")
    args = ap.parse_args(argv)
    warnings.simplefilter("ignore")  # the candidates' own notes; the figures are what is measured

    from springdyn.valve import Cam, ValveSpring, simulate
    from springdyn.valve.design import synthesis

    simulate(
        ValveSpring.example("one-step").with_model("distributed"), Cam(law="3-4-5", lift=9e-3, duration=2.1), 3000.0
    )  # engine from the cache
    runs = []
    sweep = synthesis.sweep

    def counted(*a, **k):
        runs.append(1)
        return sweep(*a, **k)

    synthesis.sweep = counted
    req, base = synthesis.read_requirements(ROOT / "examples" / "valve" / "requirements.toml")
    times, results, counts = [], [], []
    for judge_all in (False, True):
        runs.clear()
        t = time.perf_counter()
        results.append(synthesis.synthesize(req, base_dir=base, judge_all=judge_all))
        times.append(time.perf_counter() - t)
        counts.append(len(runs))
    screened, every = results
    a = {k: v for k, v in screened.rows[0].items() if k != "dynamics"}
    b = {k: v for k, v in every.rows[0].items() if k != "dynamics"}
    same = a == b and screened.springs[0] == every.springs[0]
    print(f"screened synthesis   {times[0]:7.1f} s  ({counts[0]} distributed sweeps)")
    print(f"every candidate run  {times[1]:7.1f} s  ({counts[1]} distributed sweeps)")
    print(
        f"ratio                {times[1] / times[0]:7.2f}x faster; goal {args.goal:g} s: "
        f"{'met' if times[0] <= args.goal else 'MISSED'}"
    )
    print(
        f"first candidate the same: {'yes' if same else 'NO'} "
        f"({screened.rows[0]['wire_diameter_m'] * 1e3:.2f} mm wire, {screened.rows[0]['mass_kg'] * 1e3:.1f} g, "
        f"float {screened.rows[0].get('float_cam_rpm') or 0:.0f} cam rpm)"
    )
    return 0 if same and times[0] <= args.goal else 1


if __name__ == "__main__":
    sys.exit(main())
