"""Distributed valve-spring model benchmark (issues 12 and 25).  Run:  python benchmarks/valve_distributed.py

Measures in one run, on this machine, with the one-step example spring and a 3-4-5 cam of
9 mm over 120 cam degrees:

1. one simulation of 2 cam revolutions at 3000 cam rpm with the distributed model (50
   elements) against Type C end to end, each with its largest end-force extreme error against
   a Dormand-Prince run of the same model at rtol 1e-10; and the distributed run with its
   clash check (as coils clash here: a second run at twice the elements, issue 40, item 5),
   against the run and the 100-element run timed alone (target: the check costs its own run,
   within the timing's noise, ``CHECK_OVERHEAD``). Issue 25's target, 8x Type C's time with the
   check on, was set when the check ran half the elements (7.4x then); issue 40 found that
   check blind to the default's own error, and the finer chain's run costs what it costs (6-8x
   the 50-element run: its steps grow as the square of the element count, its right-hand side
   as the count), so the ratio to Type C is printed, no longer judged;
2. the stiffness that limits the explicit step: the largest eigenvalue of the linearised
   chain at set-up times the mean step, against the stability limit of the pair each model
   steps with (Dormand-Prince ~3.3 for Type C, Bogacki-Shampine ~2.5 for the distributed
   chain; benchmarks/valve_stepping.py compares both pairs on both models);
3. a sweep of 1000 speeds from 300 to 4000 cam rpm, distributed model, both cores, each to its
   periodic steady state (target <= 20 s, issue 26; beside it the 2-revolution sweep from rest
   of the same process) and the peak resident memory of that process (target < 1 GB); and in
   yardsticks (one SciPy DOP853 Type C run, ``valve_variants.yardstick``) against issue 42's
   goal (4 s on the machine of 2026-11-26, where the yardstick took 0.65 s).
"""

from __future__ import annotations

import argparse
import math
import sys
import time

from valve_speed import periodic_sweep  # the sweep child both engine benchmarks share
from valve_variants import yardstick

#: The clash check's time may exceed the run's plus the finer chain's run alone by this factor
#: [-]: room for the timing's noise (the three runs interleaved, best of each; measured 1.01-1.02
#: on 2026-11-28 while the runs themselves moved by 1.5x; timed one block after another: 0.74-1.03).
CHECK_OVERHEAD = 1.15


def _best(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speeds", type=int, default=1000, help="speeds in the sweep (default 1000)")
    ap.add_argument("--repeat", type=int, default=10, help="repetitions of each single run (default 10)")
    args = ap.parse_args(argv)
    missed = []

    def met(ok: bool) -> str:
        """MET or NOT MET; a miss makes the benchmark exit non-zero."""
        if not ok:
            missed.append(1)
        return "MET" if ok else "NOT MET"

    import numpy as np

    from springdyn.valve import Cam, ValveSpring, simulate
    from springdyn.valve.spring.modes import chain_eigenvalues

    cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
    tc = ValveSpring.example("one-step")
    ds = tc.with_model("distributed")
    for s in (tc, ds):
        simulate(s, cam, 3000.0, 2)  # compile / load from cache
    print("one simulation, 2 revolutions at 3000 cam rpm (end to end), best of", args.repeat)
    print("  (the model's run: without the clash check, which runs the distributed model again with twice the")
    print("   elements when coils clash; its cost is printed below)")
    rows = {}
    for name, s in (("type-c", tc), ("distributed", ds)):
        t, sim = _best(lambda s=s: simulate(s, cam, 3000.0, 2, check_elements=False), args.repeat)
        ref = simulate(s, cam, 3000.0, 2, rtol=1e-10, atol=1e-13, method="dopri5")  # tight, 5th order
        fset = s.spring_model.internal_parameters()["Fset"]
        err = (
            max(
                abs(sim.summary[k] - ref.summary[k])
                for k in ("max_retainer_force_N", "min_retainer_force_N", "max_seat_force_N", "min_seat_force_N")
            )
            / fset
        )
        rows[name] = (t, sim.info["steps"])
        print(
            f"  {name:12s} {t * 1e3:8.2f} ms  {sim.info['steps']:6d} steps ({sim.info['method']})  "
            f"{len(s.spring_model.chain.masses):3d} masses  "
            f"error vs Dormand-Prince rtol 1e-10: {100 * err:.4f} % of Fset"
        )
    ratio = rows["distributed"][0] / rows["type-c"][0]
    print(f"  ratio distributed / Type C: {ratio:.1f}x")
    print(
        f"  of which steps {rows['distributed'][1] / rows['type-c'][1]:.2f}x and time per step "
        f"{ratio * rows['type-c'][1] / rows['distributed'][1]:.2f}x"
    )
    sim_chk = simulate(ds, cam, 3000.0, 2)
    fine = ds.replace(elements=sim_chk.element_check["elements"])
    simulate(fine, cam, 3000.0, 2, check_elements=False)  # its set-up, as the check's (kept per spring)
    # the three runs interleaved, best of each: a neighbour's load reaches them alike
    t_chk = t_run = t_fine = math.inf
    for _ in range(max(3, args.repeat // 2)):
        t_chk = min(t_chk, _best(lambda: simulate(ds, cam, 3000.0, 2), 1)[0])
        t_run = min(t_run, _best(lambda: simulate(ds, cam, 3000.0, 2, check_elements=False), 1)[0])
        t_fine = min(t_fine, _best(lambda: simulate(fine, cam, 3000.0, 2, check_elements=False), 1)[0])
    overhead = t_chk / (t_run + t_fine)
    print(
        f"  distributed with the clash check (coils {sim_chk.summary.get('clashing_coils')} clash here): "
        f"{t_chk * 1e3:.2f} ms, {t_chk / rows['type-c'][0]:.1f}x Type C; the check is a run at "
        f"{fine.elements} elements, {t_fine * 1e3:.2f} ms alone"
    )
    print(
        f"  with the check / (the run + the {fine.elements}-element run alone) = {overhead:.2f} "
        f"(target <= {CHECK_OVERHEAD}: the check costs its run): {met(overhead <= CHECK_OVERHEAD)}"
    )

    print()
    print("stiffness of the explicit step (linearised at set-up; stability limit on the negative real axis:")
    print("  Dormand-Prince ~3.3, Bogacki-Shampine ~2.5)")
    for name, s in (("type-c", tc), ("distributed", ds)):
        ch = s.spring_model.chain
        x = ch.setup_compressions
        lam = np.abs(chain_eigenvalues(ch.masses, ch.tangent_stiffness(x), ch.damping(x))).max()
        h = 2 * 0.02 / rows[name][1]
        print(f"  {name:12s} |lambda|max = {lam:.3g} 1/s, mean step {h * 1e6:.2f} us, |lambda| h = {lam * h:.2f}")

    periodic_sweep("distributed", args.speeds, 20.0, met, yard=yardstick())
    return 0 if not missed else 1


if __name__ == "__main__":
    sys.exit(main())
