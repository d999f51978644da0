"""Which Runge-Kutta pair for which valve-spring model (issue 12).  Run:  python benchmarks/valve_stepping.py

For Type C and the distributed model (50 elements), the one- and two-step example springs,
four cams (3-4-5, cycloidal, 4-5-6-7, polydyne with ramps) and 14 speeds from 700 to 4300
cam rpm (:data:`SPEEDS`; 112 runs per model), it runs the compiled engine with each embedded
pair at the default tolerances and prints, per model and pair:

- the total steps and the total time of the runs (end to end; each run's best of ``--repeat``,
  the pairs interleaved run by run);
- the worst error of the four end-force extremes (peak and minimum of retainer and seat
  force, from the dense-output monitor) against a run with Dormand-Prince at rtol 1e-10,
  in % of Fset (target < 0.05 %).

It also prints the stability figure that explains the result: the largest eigenvalue of
the linearised chain at set-up times the mean step, against each pair's stability interval
on the negative real axis (computed from its tableau).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings

#: The study's speeds [cam rpm]: 700 to 4300 in steps of 400, and 800, 1700, 2600, 3500, 4200.
SPEEDS = tuple(float(v) for v in sorted({*range(700, 4700, 400), 800, 1700, 2600, 3500, 4200}))


def _cams(Cam) -> dict:
    """The study's cams: three laws without ramps (9 mm over 120 deg) and a polydyne with ramps."""
    out = {law: Cam(law=law, lift=9e-3, duration=math.radians(120)) for law in ("3-4-5", "cycloidal", "4-5-6-7")}
    out["polydyne+ramps"] = Cam(
        law="polydyne", lift=9.5e-3, duration=math.radians(110), ramp_height=3e-4, ramp_duration=math.radians(20)
    )
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3, help="repetitions of each timed set (default 3)")
    ap.add_argument("--quick", action="store_true", help="two speeds instead of 14")
    ap.add_argument("--models", nargs="+", default=["type-c", "distributed"], choices=("type-c", "distributed"))
    ap.add_argument("--pairs", nargs="+", default=["dopri5", "tsit5", "bs3"], choices=("dopri5", "tsit5", "bs3"))
    args = ap.parse_args(argv)
    # the study's ramp cam drives the two-step spring into coil contact statically: expected here
    warnings.filterwarnings("ignore", message="the cam lift drives the spring into coil contact")

    import numpy as np

    from springdyn.valve import Cam, ValveSpring, simulate
    from springdyn.valve.run import settings
    from springdyn.valve.spring.modes import chain_eigenvalues

    cams = _cams(Cam)
    speeds = (1700.0, 3500.0) if args.quick else SPEEDS
    keys = ("max_retainer_force_N", "min_retainer_force_N", "max_seat_force_N", "min_seat_force_N")
    print(f"{len(speeds) * 2 * len(cams)} runs per model")
    print(f"{'model':12s} {'pair':7s} {'steps':>8s} {'time [ms]':>10s} {'worst error [% Fset]':>21s}  worst case")
    for model in args.models:
        springs = [ValveSpring.example(n).with_model(model) for n in ("one-step", "two-step")]
        cases = [(s, c, rpm) for s in springs for c in cams for rpm in speeds]
        refs = {}
        for i, (s, c, rpm) in enumerate(cases):
            refs[i] = simulate(
                s, cams[c], rpm, 2, rtol=1e-10, atol=1e-13, check_elements=False, method="dopri5"
            ).summary
        for pair in args.pairs:
            for s, c, rpm in cases[:2]:
                simulate(s, cams[c], rpm, 2, check_elements=False, method=pair)  # compile / load from cache
        # interleaved: every run is timed with each pair in turn (the order alternating), so that
        # a neighbour's load on a shared machine reaches all pairs alike; a pair's time is the
        # sum over the runs of its best of --repeat (timing each pair's runs as one block
        # moved the pairs' times by up to 30 % against each other)
        best = {(i, pair): math.inf for i in range(len(cases)) for pair in args.pairs}
        sims = {}
        for rep in range(args.repeat):
            for i, (s, c, rpm) in enumerate(cases):
                for pair in args.pairs if rep % 2 == 0 else args.pairs[::-1]:
                    t = time.perf_counter()
                    sims[i, pair] = simulate(s, cams[c], rpm, 2, check_elements=False, method=pair)
                    best[i, pair] = min(best[i, pair], time.perf_counter() - t)
        for pair in args.pairs:
            total = sum(best[i, pair] for i in range(len(cases)))
            steps, worst, where = 0, 0.0, ""
            for i, (s, c, rpm) in enumerate(cases):
                sim = sims[i, pair]
                steps += sim.info["steps"]
                fset = s.spring_model.internal_parameters()["Fset"]
                err = max(abs(sim.summary[k] - refs[i][k]) for k in keys) / fset
                if err > worst:
                    worst, where = err, f"{s.type} {c} {rpm:g} rpm"
            mark = "  <- used" if settings.PAIR[model] == pair else ""
            print(f"{model:12s} {pair:7s} {steps:8d} {total * 1e3:10.1f} {100 * worst:21.4f}  {where}{mark}")
    print()
    from springdyn.numerics.erk import pair_arrays

    print(
        "stability interval on the negative real axis: "
        + ", ".join(f"{p} [{-_real_stability(*pair_arrays(p)[:2]):.2f}, 0]" for p in args.pairs)
    )
    print("stability: largest |eigenvalue| of the linearised chain at set-up x mean step (3000 cam rpm, 3-4-5)")
    for model in args.models:
        s = ValveSpring.example("one-step").with_model(model)
        ch = s.spring_model.chain
        x = ch.setup_compressions
        lam = chain_eigenvalues(ch.masses, ch.tangent_stiffness(x), ch.damping(x))
        top = lam[np.argmax(np.abs(lam))]
        sim = simulate(s, cams["3-4-5"], 3000.0, 2, check_elements=False)
        h = 2 * 0.02 / sim.info["steps"]
        print(
            f"  {model:12s} ({settings.PAIR[model]}) top eigenvalue {top.real:.3g}{top.imag:+.3g}j 1/s, "
            f"mean step {h * 1e6:.2f} us, |lambda| h = {abs(top) * h:.2f}"
        )
    return 0


def _real_stability(c, a) -> float:
    """The end of the stability interval on the negative real axis, -x where |R(-x)| first
    exceeds 1, for the FSAL tableau (its weights are the last row of ``a``)."""
    import numpy as np

    s = c.size - 1
    A = np.zeros((s, s))
    A[:, : a.shape[1]] = a[:s, :s] if a.shape[1] >= s else a[:s]
    b = a[s, :s]
    for x in np.arange(0.01, 10.0, 0.001):
        r = 1.0 - x * b @ np.linalg.solve(np.eye(s) + x * A, np.ones(s))
        if abs(r) > 1.0:
            return -x
    return -10.0


if __name__ == "__main__":
    sys.exit(main())
