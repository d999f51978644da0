"""Tolerance-study throughput (issue 29, part 3).  Run:  python benchmarks/valve_variants.py

Measures in one run, on this machine, with the one-step example spring (Type C) on the
bucket train of examples/valve (polydyne cam with ramps, lash), speeds 1500-3300 cam rpm:

1. the single-call figure: warm ``simulate`` calls at speeds across the range, each to its
   periodic steady state (simulations per second on one core);
2. a float-speed study of ``--variants`` variants (``tolerance_study(float_only=True)``: each
   variant's float speed searched from the nominal's to 5 rpm, its chunks on the local
   threads), timed end to end from the call (the nominal's scan included): variants per
   second, simulations (trial speeds, each to its periodic state) per second per core
   against the single-call figure, and the time a 10,000-variant study takes on this
   machine by the measured rate (goal: <= 5 minutes on 2 cores);
3. with ``--full``: the same for the full study (a sweep of 19 speeds per variant);
4. with ``--dask``: the float-speed study on a Dask LocalCluster of 1, 2 and 4 worker
   processes (one thread each), the speed-up against one worker, and the time 100,000
   variants take on the best of them by the measured rate.

Exits 1 when the 10,000-variant float-speed study's projection misses the goal.  The
compile (or cache load) of the engine is measured apart and printed: it happens once per
machine (benchmarks/cold_start.py).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
import warnings

GOAL_SECONDS = 300.0
STUDY = 10_000
CLUSTER_STUDY = 100_000


def _load_engine(spring, cam, vt) -> None:
    """One simulation on a worker: the engine loaded from the cache (not timed)."""
    warnings.simplefilter("ignore")
    from springdyn.valve import simulate

    simulate(spring, cam, 3000.0, valve_train=vt)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--variants", type=int, default=512, help="variants of the measured study (default 512)")
    ap.add_argument("--full", action="store_true", help="also measure the full study (19-speed sweep a variant)")
    ap.add_argument("--dask", action="store_true", help="also measure LocalCluster scaling over 1, 2, 4 workers")
    args = ap.parse_args(argv)
    warnings.simplefilter("ignore")

    import numpy as np

    from springdyn.valve import Cam, ValveSpring, ValveTrain, simulate
    from springdyn.valve.design.tolerances import parse_tolerance, tolerance_study

    root = os.path.join(os.path.dirname(__file__), "..", "examples", "valve")
    spring = ValveSpring.from_toml(os.path.join(root, "one_step_spring.toml"))
    cam = Cam.from_toml(os.path.join(root, "cam_polydyne_ramps.toml"))
    vt = ValveTrain.from_toml(os.path.join(root, "valve_train.toml"))
    speeds = np.arange(1500.0, 3301.0, 100.0)
    tols = {
        k: parse_tolerance(k, v)
        for k, v in (
            ("wire_diameter", "+-0.015 mm"),
            ("mean_diameter", "+-0.1 mm"),
            ("free_length", "+-0.3 mm"),
            ("lift", "+-0.03 mm"),
            ("lash", "+-0.03 mm"),
        )
    }

    t = time.perf_counter()
    simulate(spring, cam, 3000.0, valve_train=vt)
    print(f"engine compile or cache load and first call: {time.perf_counter() - t:.1f} s (once per machine/process)")
    t = time.perf_counter()
    n = 20
    for rpm in np.linspace(1500.0, 3300.0, n):
        simulate(spring, cam, float(rpm), valve_train=vt, check_elements=False)
    single = n / (time.perf_counter() - t)
    print(f"single calls: {single:.1f} simulations per second (one core, each to its periodic state)")

    cores = os.cpu_count() or 1

    def study(label, count, seed, **kw):
        t = time.perf_counter()
        res = tolerance_study(spring, cam, tols, count=count, seed=seed, speeds=speeds, valve_train=vt, **kw)
        wall = time.perf_counter() - t
        sims = float(res.dataset["simulations"].values.sum())
        print(
            f"{label}: {count} variants in {wall:.1f} s: {count / wall:.1f} variants/s, {sims / count:.2f} simulations "
            f"a variant, {sims / wall / cores:.1f} simulations/s per core ({sims / wall / cores / single:.2f}x the "
            "single-call figure)"
        )
        return wall, res

    wall, res = study("float-speed study", args.variants, 0, float_only=True)
    projected = STUDY * wall / args.variants
    ok = projected <= GOAL_SECONDS
    f = res.dataset["float_cam_rpm"].values
    print(f"  float speeds {np.percentile(f, 2.5):.0f}-{np.percentile(f, 97.5):.0f} cam rpm (2.5-97.5 %)")
    print(
        f"projected {STUDY} variants: {projected / 60:.1f} min on {cores} cores (goal <= {GOAL_SECONDS / 60:.0f} min): "
        + ("MET" if ok else f"MISSED by {projected / GOAL_SECONDS:.1f}x")
    )
    if args.full:
        count = max(32, args.variants // 8)
        wall_full, _ = study("full study (sweep)", count, 0)
        print(f"  projected {STUDY} variants of the full study: {STUDY * wall_full / count / 60:.1f} min")
    if args.dask:
        import distributed

        base = None
        count = max(args.variants, 256)
        for workers in (1, 2, 4):
            with (
                distributed.LocalCluster(
                    n_workers=workers, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
                ) as cluster,
                distributed.Client(cluster) as client,
            ):
                client.run(_load_engine, spring, cam, vt)  # load the engine on every worker, not timed
                t = time.perf_counter()
                tolerance_study(
                    spring,
                    cam,
                    tols,
                    count=count,
                    seed=1,
                    speeds=speeds,
                    valve_train=vt,
                    client=client,
                    float_only=True,
                )
                w = time.perf_counter() - t
            base = w if base is None else base
            print(
                f"LocalCluster {workers} worker(s): {count} variants in {w:.1f} s, speed-up {base / w:.2f}x against "
                f"1 worker; {CLUSTER_STUDY} variants: {CLUSTER_STUDY * w / count / 60:.0f} min at this rate"
            )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
