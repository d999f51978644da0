"""Valve-spring engine benchmark (issue 4).  Run:  python benchmarks/valve_speed.py

Measures in one run, on this machine, with the one-step example spring and a 3-4-5 cam of
9 mm over 120 cam degrees:

1. the first call of the compiled engine (compilation, or loading it from numba's disk
   cache), reported on its own line;
2. one simulation of 2 cam revolutions at 3000 cam rpm: springdyn's compiled engine
   against SciPy ``solve_ivp(method="DOP853", rtol=1e-8, atol=1e-12)`` with the plain
   Python right-hand side of the same model (target: >= 300x faster, peak retainer force
   within 0.05 % of Fset);
3. a sweep of 1000 speeds from 300 to 4000 cam rpm, each to its periodic steady state (the
   default: the last two revolutions within 0.2 % of Fset; target <= 3 s, issue 26), beside
   the same sweep of 2 revolutions from rest measured in the same process;
4. the peak resident memory of a process running that sweep (target < 1 GB);
5. that sweep in yardsticks (the best SciPy reference run of 2) against issue 42's goal (0.6 s
   on the machine of 2026-11-26, where the reference took 0.65 s).
"""

from __future__ import annotations

import argparse
import math
import subprocess
import sys
import time

from valve_variants import YARDSTICK_THEN

COMPILE_CHILD = """
import math, time
from springdyn.valve import ValveSpring, Cam, simulate, sweep
s = ValveSpring.example("one-step")
cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
t = time.perf_counter()
simulate(s, cam, 3000.0, 2)
sweep(s, cam, [3000.0])
print(time.perf_counter() - t)
"""

SWEEP_CHILD = """
import math, resource, sys, time
import numpy as np
from springdyn.valve import ValveSpring
from springdyn.valve.cam.definition import Cam
from springdyn.valve.run.sweeps import sweep
s = ValveSpring.example("one-step")
if "{model}" != "type-c":
    s = s.with_model("{model}")
cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
sweep(s, cam, [3000.0, 3100.0])                      # compile / load from cache first
rpm = np.linspace(300.0, 4000.0, {n})
t = time.perf_counter()
res = sweep(s, cam, rpm)
wall = time.perf_counter() - t
t = time.perf_counter()
sweep(s, cam, rpm, revolutions=2)
wall2 = time.perf_counter() - t
d = res.data
print(wall, wall2, int(d["steps"].sum()), float(d["revolutions"].mean()), float(np.max(d["periodicity"])),
      int(np.count_nonzero(~d["settled"])), resource.getrusage(resource.RUSAGE_SELF).ru_maxrss)
"""


#: Issue 42's goals for the 1000-speed sweeps to periodicity [s], on the 2-core machine of
#: 2026-11-26, whose yardstick (the SciPy reference run) took YARDSTICK_THEN [s].
SWEEP_GOALS_42 = {"type-c": 0.6, "distributed": 4.0}


def periodic_sweep(model: str, n: int, target: float, met, yard: float | None = None) -> None:
    """Run the sweep child for ``model`` and print its figures against ``target`` [s] and,
    given the yardstick ``yard`` [s] measured in the same run, against issue 42's goal in
    yardsticks (:data:`SWEEP_GOALS_42`, for 1000 speeds)."""
    out = subprocess.run(
        [sys.executable, "-c", SWEEP_CHILD.format(n=n, model=model)], capture_output=True, text=True, check=True
    )
    wall, wall2, steps, revs, per, unsettled, maxrss_kb = out.stdout.split()
    wall, wall2, rss_mb = float(wall), float(wall2), int(maxrss_kb) / 1024
    print()
    print(
        f"sweep of {n} speeds, 300-4000 cam rpm, {model}, both cores, each to its periodic steady state "
        "(after compilation)"
    )
    print(
        f"  wall time: {wall:.2f} s ({int(steps)} steps, {wall / n * 1e3:.2f} ms per speed, {float(revs):.2f} revolutions "
        f"per speed on average, largest periodicity error {100 * float(per):.3f} % of Fset, {unsettled} speeds "
        f"unsettled); target <= {target:g} s (issue 26): {met(wall <= target)}"
    )
    print(
        f"  the same speeds, 2 revolutions from rest each (a transient, the earlier default): {wall2:.2f} s; "
        f"periodic / 2 revolutions = {wall / wall2:.2f}"
    )
    print(f"  peak resident memory of the sweep process: {rss_mb:.0f} MB; target < 1024 MB: {met(rss_mb < 1024)}")
    if yard is not None and n == 1000:
        goal = SWEEP_GOALS_42[model] / YARDSTICK_THEN
        print(
            f"  in yardsticks (the SciPy reference run, {yard:.3f} s here, {YARDSTICK_THEN} s on 2026-11-26): "
            f"{wall / yard:.2f}; issue 42's goal {SWEEP_GOALS_42[model]:g} s there = {goal:.2f} yardsticks: "
            f"{met(wall / yard <= goal)}"
        )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speeds", type=int, default=1000, help="speeds in the sweep (default 1000)")
    ap.add_argument("--rounds", type=int, default=7, help="interleaved reference/engine rounds (default 7)")
    ap.add_argument("--repeat", type=int, default=40, help="runs of the compiled engine per round (default 40)")
    ap.add_argument(
        "--ref-repeat", type=int, default=3, help="repetitions of the SciPy reference per round (default 3)"
    )
    args = ap.parse_args(argv)
    missed = []

    def met(ok: bool) -> str:
        """MET or NOT MET; a miss makes the benchmark exit non-zero."""
        if not ok:
            missed.append(1)
        return "MET" if ok else "NOT MET"

    t0 = time.perf_counter()
    import numpy as np

    from springdyn.core.units import rpm_to_omega
    from springdyn.valve import ValveSpring, engine
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.run.runner import engine_args, velocity_tolerance
    from springdyn.valve.run.settings import MAX_STEP_FRACTION
    from springdyn.valve.run.setup import prepare
    from springdyn.valve.run.simulation import simulate

    spring = ValveSpring.example("one-step")
    cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
    fset = spring.spring_model.internal_parameters()["Fset"]
    t_import = time.perf_counter() - t0

    t = time.perf_counter()
    simulate(spring, cam, 3000.0, 2)
    first = time.perf_counter() - t
    from springdyn.numerics import erk
    from springdyn.valve.engine import loop

    cached = loop.integrate_kernel(erk.TABLEAUS["dopri5"], None).stats.cache_hits
    how = "loaded from numba's disk cache" if sum(cached.values()) else "compiled (now cached on disk)"
    import os
    import tempfile

    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        cold = float(
            subprocess.run(
                [sys.executable, "-c", COMPILE_CHILD], capture_output=True, text=True, check=True, env=env
            ).stdout.split()[-1]
        )
    print(f"import springdyn: {t_import:.2f} s")
    print(f"compile time of the engine with an empty numba cache: {cold:.2f} s (once; then cached on disk)")
    print(f"first call of the compiled engine: {first:.2f} s ({how}; paid once per process)")

    # --- one simulation -------------------------------------------------------------
    # Rounds interleave the reference and the engine so that both see the same load on this
    # shared machine: a round runs engine, reference, engine, ..., engine (the engine's runs
    # split into blocks around each reference run), and its ratio is the best reference run
    # against the best engine run of the same round (load only ever adds time).  The load
    # of a neighbour changes within seconds and slows the compiled engine more than the
    # interpreter (measured: engine 1.8-3.3 ms, reference 0.79-1.0 s); engine runs taken
    # only after the reference runs made single rounds range from 173x to 444x.
    def engine_block(n):
        best = math.inf
        for _ in range(n):
            t = time.perf_counter()
            simulate(spring, cam, 3000.0, 2)
            best = min(best, time.perf_counter() - t)
        return best

    block = max(1, args.repeat // (args.ref_repeat + 1))
    ratios, fast_times, ref_times = [], [], []
    for _ in range(args.rounds):
        t_r = math.inf
        t_f = engine_block(block)
        for _ in range(args.ref_repeat):
            t = time.perf_counter()
            ref = simulate(spring, cam, 3000.0, 2, backend="scipy", rtol=1e-8, atol=1e-12)
            t_r = min(t_r, time.perf_counter() - t)
            t_f = min(t_f, engine_block(block))
        ratios.append(t_r / t_f)
        fast_times.append(t_f)
        ref_times.append(t_r)
    fast = simulate(spring, cam, 3000.0, 2)
    t_fast = float(np.median(fast_times))
    setup = prepare(spring, cam)
    omega = rpm_to_omega(3000.0)
    eng = []
    for _ in range(args.repeat):
        t = time.perf_counter()
        engine.integrate_speeds(
            setup.y0,
            [omega],
            2,
            1440,
            engine_args(setup, omega),
            rtol=1e-6,
            atol=1e-9,
            max_step_fraction=MAX_STEP_FRACTION,
            atol_velocity=velocity_tolerance(setup, 1e-9),
        )
        eng.append(time.perf_counter() - t)
    t_eng = min(eng)
    t_ref = float(np.median(ref_times))
    peak_fast = fast.summary["max_retainer_force_N"]
    peak_ref = ref.summary["max_retainer_force_N"]
    diff = abs(peak_fast - peak_ref) / fset
    print()
    print("one simulation, 2 revolutions at 3000 cam rpm (end to end: setup, integration, outputs)")
    med = float(np.median(ratios))
    print(
        f"  SciPy DOP853 rtol=1e-8 atol=1e-12, pure-Python RHS (median of {args.rounds} rounds, best of "
        f"{args.ref_repeat} each): {t_ref:8.3f} s  "
        f"({ref.info['steps']} RHS calls)"
    )
    print(
        f"  springdyn compiled engine (median of {args.rounds} rounds, best of {block * (args.ref_repeat + 1)} "
        f"each, in {args.ref_repeat + 1} blocks around the reference runs): "
        f"{t_fast * 1e3:8.2f} ms  ({fast.info['steps']} steps)"
    )
    print(
        f"  ratio: median {med:.0f}x over {args.rounds} interleaved rounds (min {min(ratios):.0f}x, max "
        f"{max(ratios):.0f}x; target >= 300x): {met(med >= 300)}"
    )
    print(
        f"  of which the compiled integration (with its output evaluation): {t_eng * 1e3:.2f} ms, "
        f"{t_ref / t_eng:.0f}x the reference; the rest is setup (cam table, initial state) and outputs"
    )
    print(
        f"  peak retainer force: {peak_fast:.4f} N vs {peak_ref:.4f} N, difference {100 * diff:.5f} % of Fset "
        f"(target < 0.05 %): {met(diff < 5e-4)}"
    )
    loose = []
    for _ in range(args.repeat):
        t = time.perf_counter()
        lo = simulate(spring, cam, 3000.0, 2, rtol=1e-5, atol=1e-8)
        loose.append(time.perf_counter() - t)
    d_lo = abs(lo.summary["max_retainer_force_N"] - peak_ref) / fset
    print(
        f"  the trade-off: with rtol=1e-5, atol=1e-8 instead of the defaults (1e-6, 1e-9): {min(loose) * 1e3:.2f} ms, "
        f"{t_ref / min(loose):.0f}x, peak difference {100 * d_lo:.4f} % of Fset"
    )

    # --- sweep, in a fresh process so that its peak memory is its own -----------------
    periodic_sweep("type-c", args.speeds, 3.0, met, yard=min(ref_times))
    steps = fast.info["steps"]
    print(f"  (the SciPy reference takes {t_ref * 1e3:.0f} ms for the {steps} steps of one 2-revolution run)")
    return 0 if not missed else 1


if __name__ == "__main__":
    sys.exit(main())
