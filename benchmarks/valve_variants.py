"""Tolerance-study throughput (issue 29, part 3).  Run:  python benchmarks/valve_variants.py

Measures in one run, on this machine, with the one-step example spring on the bucket train
of examples/valve (polydyne cam with ramps, lash), over 19 cam speeds from 1500 to 3300 rpm:

1. the single-call figure: warm ``simulate`` calls of one speed to its periodic state
   (simulations per second on one core);
2. a tolerance study of ``--variants`` variants (springdyn.valve.tolerances, locally: each
   variant's sweep runs its speeds on the engine's threads): variants per second, simulations
   (variant x speed) per second per core against the single-call figure, and the time a
   10,000-variant study would take on this machine (goal: <= 5 minutes on 2 cores);
3. with ``--dask``: the same study on a Dask LocalCluster of 1, 2 and 4 worker processes,
   the speed-up against one worker.

Exits 1 when the 10,000-variant projection misses the goal (it does: the variant loop is a
Python call per variant and 94 % of a variant is the engine's own integration; docs/valve.md).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings

GOAL_SECONDS = 300.0
STUDY = 10_000


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--variants", type=int, default=64, help="variants of the measured study (default 64)")
    ap.add_argument("--dask", action="store_true", help="also measure LocalCluster scaling over 1, 2, 4 workers")
    args = ap.parse_args(argv)
    warnings.simplefilter("ignore")

    import numpy as np

    from springdyn.valve import Cam, ValveSpring, ValveTrain, simulate
    from springdyn.valve.tolerances import parse_tolerance, tolerance_study

    root = os.path.join(os.path.dirname(__file__), "..", "examples", "valve")
    spring = ValveSpring.from_toml(os.path.join(root, "one_step_spring.toml"))
    cam = Cam.from_toml(os.path.join(root, "cam_polydyne_ramps.toml"))
    vt = ValveTrain.from_toml(os.path.join(root, "valve_train.toml"))
    speeds = np.arange(1500.0, 3301.0, 100.0)
    tols = {k: parse_tolerance(k, v) for k, v in (("wire_diameter", "+-0.015 mm"), ("free_length", "+-0.3 mm"))}

    simulate(spring, cam, 3000.0, valve_train=vt)  # compile or load, not timed
    t = time.perf_counter()
    n = 20
    for rpm in np.linspace(1500.0, 3300.0, n):
        simulate(spring, cam, float(rpm), valve_train=vt, check_elements=False)
    single = n / (time.perf_counter() - t)
    print(f"single calls: {single:.1f} simulations per second (one core, each to its periodic state)")

    cores = os.cpu_count() or 1
    t = time.perf_counter()
    tolerance_study(spring, cam, tols, count=args.variants, seed=0, speeds=speeds, valve_train=vt)
    wall = time.perf_counter() - t
    per_core = args.variants * speeds.size / wall / cores
    projected = STUDY * wall / args.variants
    print(
        f"tolerance study: {args.variants} variants x {speeds.size} speeds in {wall:.1f} s: "
        f"{args.variants / wall:.2f} variants/s, {per_core:.1f} simulations/s per core "
        f"({per_core / single:.2f}x the single-call figure)"
    )
    print(
        f"projected {STUDY} variants: {projected / 60:.1f} min on {cores} cores (goal <= {GOAL_SECONDS / 60:.0f} min): "
        + ("MET" if projected <= GOAL_SECONDS else f"MISSED by {projected / GOAL_SECONDS:.1f}x")
    )
    if args.dask:
        import distributed

        base = None
        for workers in (1, 2, 4):
            with (
                distributed.LocalCluster(
                    n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
                ) as cluster,
                distributed.Client(cluster) as client,
            ):
                client.run(lambda: __import__("springdyn.valve.engine"))
                t = time.perf_counter()
                tolerance_study(
                    spring,
                    cam,
                    tols,
                    count=max(args.variants, 200),
                    seed=1,
                    speeds=speeds,
                    valve_train=vt,
                    client=client,
                )
                w = time.perf_counter() - t
            base = w if base is None else base
            print(f"LocalCluster {workers} worker(s): {w:.1f} s, speed-up {base / w:.2f}x against 1 worker")
    return 0 if projected <= GOAL_SECONDS else 1


if __name__ == "__main__":
    sys.exit(main())
