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
   variants take on the best of them by the measured rate;
5. warm starts (issue 42, item 3): each study of 2 and 3 is also run with
   ``warm_starts=False`` (every speed from rest or the slower speed, the method before) in the
   same run: the revolutions per speed and the wall time of both, their ratios, and whether
   every variant's figures agree (float speeds within the resolution, forces within the
   periodicity tolerance of 0.2 % Fset, Goodman safety within 0.2 %).

Exits 1 when the 10,000-variant float-speed study's projection misses the goal, or the warm
starts change a figure beyond its tolerance or save no revolution.  The
compile (or cache load) of the engine is measured apart and printed: it happens once per
machine (benchmarks/cold_start.py).
"""

from __future__ import annotations

import argparse
import os
import sys
import threading
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


#: The yardstick's time on the 2-core machine issue 42's goals were set on (2026-11-26) [s].
YARDSTICK_THEN = 0.65


def yardstick(rounds: int = 3) -> float:
    """The yardstick [s], best of ``rounds``: one Type C simulation of the one-step example, 2
    revolutions at 3000 cam rpm under a 3-4-5 cam, with SciPy's DOP853 and the plain-Python
    right-hand side (as benchmarks/valve_speed.py): a time in yardsticks compares machines."""
    import math

    from springdyn.valve import Cam, ValveSpring, simulate

    spring, cam = ValveSpring.example("one-step"), Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
    best = math.inf
    for _ in range(rounds):
        t = time.perf_counter()
        simulate(spring, cam, 3000.0, 2, backend="scipy", rtol=1e-8, atol=1e-12)
        best = min(best, time.perf_counter() - t)
    return best


#: The examples' folder of valve definitions.
EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "examples", "valve")


def bucket_example():
    """The README's tolerance example: the one-step spring, the polydyne cam, the bucket train."""
    from springdyn.valve import Cam, ValveSpring, ValveTrain

    return (
        ValveSpring.from_toml(os.path.join(EXAMPLES, "one_step_spring.toml")),
        Cam.from_toml(os.path.join(EXAMPLES, "cam_polydyne_ramps.toml")),
        ValveTrain.from_toml(os.path.join(EXAMPLES, "valve_train.toml")),
    )


class RevolutionCounter:
    """Counts the speeds and revolutions of every engine call (``runner.integrate_speeds``)
    while in its ``with`` block."""

    def __enter__(self):
        from springdyn.valve.run import runner

        self.speeds = self.revolutions = 0
        self._runner, self._engine = runner, runner.integrate_speeds
        lock = threading.Lock()  # the study's threads call the engine at once

        def counted(*args, **kwargs):
            out = self._engine(*args, **kwargs)
            with lock:
                self.speeds += len(out["revolutions"])
                self.revolutions += int(out["revolutions"].sum())
            return out

        runner.integrate_speeds = counted
        return self

    def __exit__(self, *exc):
        self._runner.integrate_speeds = self._engine

    def per_speed(self) -> float:
        return self.revolutions / max(self.speeds, 1)


def warm_against_cold(label, warm, cold, fset, resolution) -> bool:
    """Print the warm study against the cold one (wall time, revolutions per speed) and whether
    every variant's figures agree; returns whether they do and the warm one ran fewer revolutions.
    ``warm`` and ``cold``: (wall time [s], RevolutionCounter, ToleranceStudy)."""
    import numpy as np

    (tw, cw, rw), (tc, cc, rc) = warm, cold
    a, b = rc.dataset, rw.dataset
    worst = {"float_cam_rpm": float(np.max(np.abs(a["float_cam_rpm"].values - b["float_cam_rpm"].values)))}
    ok = worst["float_cam_rpm"] <= resolution
    if "max_retainer_force" in a:
        worst["max_retainer_force"] = float(
            np.max(np.abs(a["max_retainer_force"].values - b["max_retainer_force"].values))
        )
        worst["goodman_safety"] = float(np.max(np.abs(b["goodman_safety"].values / a["goodman_safety"].values - 1.0)))
        ok = ok and worst["max_retainer_force"] <= 0.002 * fset and worst["goodman_safety"] <= 0.002
    fewer = cw.revolutions < cc.revolutions
    print(
        f"{label}, warm starts: {tw:.1f} s, {cw.per_speed():.2f} revolutions a speed ({cw.revolutions} in "
        f"{cw.speeds} speeds); cold: {tc:.1f} s, {cc.per_speed():.2f} ({cc.revolutions} in {cc.speeds}); "
        f"{tc / tw:.2f}x faster, {cc.revolutions / max(cw.revolutions, 1):.2f}x fewer revolutions"
    )
    print(
        "  largest difference warm - cold: "
        + ", ".join(
            f"{k} {v:.3g} " + ("rpm" if k == "float_cam_rpm" else "N" if k.endswith("force") else "(relative)")
            for k, v in worst.items()
        )
        + f" (allowed: {resolution:g} rpm, {0.002 * fset:.2f} N = 0.2 % Fset, 0.2 %): "
        + ("SAME" if ok else "DIFFERENT")
        + ("" if fewer else "; NO revolutions saved")
    )
    return ok and fewer


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--variants", type=int, default=512, help="variants of the measured study (default 512)")
    ap.add_argument("--full", action="store_true", help="also measure the full study (19-speed sweep a variant)")
    ap.add_argument("--dask", action="store_true", help="also measure LocalCluster scaling over 1, 2, 4 workers")
    args = ap.parse_args(argv)
    warnings.simplefilter("ignore")

    import numpy as np

    from springdyn.valve import simulate
    from springdyn.valve.design.tolerances import parse_tolerance, tolerance_study

    spring, cam, vt = bucket_example()
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

    fset = float(spring.spring_model.internal_parameters()["Fset"])

    def study(label, count, seed, **kw):
        with RevolutionCounter() as counter:
            t = time.perf_counter()
            res = tolerance_study(spring, cam, tols, count=count, seed=seed, speeds=speeds, valve_train=vt, **kw)
            wall = time.perf_counter() - t
        sims = float(res.dataset["simulations"].values.sum())
        print(
            f"{label}: {count} variants in {wall:.1f} s: {count / wall:.1f} variants/s, {sims / count:.2f} simulations "
            f"a variant, {sims / wall / cores:.1f} simulations/s per core ({sims / wall / cores / single:.2f}x the "
            "single-call figure)"
        )
        return wall, counter, res

    wall, counter, res = study("float-speed study", args.variants, 0, float_only=True)
    cold = study("  the same, cold starts", args.variants, 0, float_only=True, warm_starts=False)
    same = warm_against_cold("float-speed study", (wall, counter, res), cold, fset, 5.0)
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
        full = study("full study (sweep)", count, 0)
        print(f"  projected {STUDY} variants of the full study: {STUDY * full[0] / count / 60:.1f} min")
        cold = study("  the same, cold starts", count, 0, warm_starts=False)
        same = warm_against_cold("full study", full, cold, fset, 5.0) and same
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
    return 0 if ok and same else 1


if __name__ == "__main__":
    sys.exit(main())
