"""A spring pack's sweep against one spring's (issue 41).  Run:  python benchmarks/valve_packs.py

Measures in one run, on this machine, on the bucket train of examples/valve (polydyne cam with
ramps, lash): a sweep of 1000-4000 cam rpm in 250 rpm steps of

1. the outer spring of examples/valve/dual_spring_damper.toml alone,
2. the dual spring with its friction damper (two chains side by side and the damper, in the one
   compiled kernel),

each to its periodic steady state, on one thread; prints the wall time of each (the best of
three, alternating: the machine is shared), the revolutions to the steady state (the
damper's friction settles the pack sooner), and the ratios of the sweeps and of a revolution.  The
engine is loaded (or compiled) first and not timed.
"""

from __future__ import annotations

import os
import time
import warnings


def main() -> int:
    warnings.simplefilter("ignore")
    import numpy as np

    from springdyn.valve import Cam, ValveTrain, simulate, sweep
    from springdyn.valve.spring.pack import SpringPack

    root = os.path.join(os.path.dirname(__file__), "..", "examples", "valve")
    pack = SpringPack.from_toml(os.path.join(root, "dual_spring_damper.toml"))
    cam = Cam.from_toml(os.path.join(root, "cam_polydyne_ramps.toml"))
    vt = ValveTrain.from_toml(os.path.join(root, "valve_train.toml"))
    speeds = np.arange(1000.0, 4000.0 + 1.0, 250.0)
    cases = (("outer spring alone", pack.outer), ("dual spring with damper", pack))
    for _, spring in cases:
        simulate(spring, cam, 3000.0, valve_train=vt)  # the engine from the cache (or compiled): not timed
    times = {name: float("inf") for name, _ in cases}
    revs = {}
    for _ in range(3):
        for name, spring in cases:
            t0 = time.perf_counter()
            res = sweep(spring, cam, speeds, valve_train=vt, workers=1)
            times[name] = min(times[name], time.perf_counter() - t0)
            revs[name] = float(np.mean(res.summary_table()["revolutions"]))
    for name, _ in cases:
        print(
            f"{name:26s} {speeds.size} speeds: {times[name]:.2f} s ({times[name] / speeds.size * 1e3:.0f} ms a "
            f"speed, {revs[name]:.1f} revolutions a speed, {times[name] / speeds.size / revs[name] * 1e3:.1f} ms a "
            "revolution)"
        )
    per_rev = {name: times[name] / revs[name] for name, _ in cases}
    print(
        f"a revolution of the pack takes {per_rev['dual spring with damper'] / per_rev['outer spring alone']:.2f} times one spring's"
    )
    ratio = times["dual spring with damper"] / times["outer spring alone"]
    print(f"the pack's sweep takes {ratio:.2f} times the one spring's")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
