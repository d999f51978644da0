"""The velocity tolerance of the valve-spring engine (issue 12).  Run:  python benchmarks/valve_tolerances.py

The displacements get the absolute tolerance ``atol`` [m]; the spring's velocities get
``atol 2 pi f1 / D`` [m/s] (``D`` = :data:`springdyn.valve.run.settings.VELOCITY_TOLERANCE_DIVISOR`).
For each ``D`` in 10, 30, 100 and "one tolerance for every component" (``D = 2 pi f1`` in
1/s units, the earliest versions), over the runs of benchmarks/valve_stepping.py (two
springs, four cams, 14 speeds), it prints the total steps and the worst error of the four
end-force extremes against a Dormand-Prince run at rtol 1e-10, in % of Fset (target < 0.05 %).
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--model", default="type-c", choices=("type-c", "distributed"))
    args = ap.parse_args(argv)
    # the study's ramp cam drives the two-step spring into coil contact statically: expected here
    warnings.filterwarnings("ignore", message="the cam lift drives the spring into coil contact")

    import numpy as np

    sys.path.insert(0, str(__import__("pathlib").Path(__file__).parent))
    from valve_stepping import SPEEDS, _cams

    from springdyn.valve import Cam, ValveSpring, simulate
    from springdyn.valve.run import runner  # its velocity_tolerance reads the divisor

    cams = _cams(Cam)
    keys = ("max_retainer_force_N", "min_retainer_force_N", "max_seat_force_N", "min_seat_force_N")
    cases = [
        (ValveSpring.example(n).with_model(args.model), c, r)
        for n in ("one-step", "two-step")
        for c in cams
        for r in SPEEDS
    ]
    refs = [
        simulate(s, cams[c], r, 2, rtol=1e-10, atol=1e-13, check_elements=False, method="dopri5").summary
        for s, c, r in cases
    ]
    default = runner.VELOCITY_TOLERANCE_DIVISOR
    f1 = float(cases[0][0].spring_model.internal_parameters()["f1"])
    print(f"{args.model}: {len(cases)} runs; velocity tolerance atol 2 pi f1 / D")
    print(f"{'D':>12s} {'steps':>9s} {'worst [% Fset]':>15s} {'2nd':>8s}  worst case")
    try:
        for d in (10.0, 30.0, 100.0, 2 * math.pi * f1):
            runner.VELOCITY_TOLERANCE_DIVISOR = d
            steps, errs = 0, []
            for (s, c, r), ref in zip(cases, refs):
                sim = simulate(s, cams[c], r, 2, check_elements=False)
                steps += sim.info["steps"]
                errs.append(
                    max(abs(sim.summary[k] - ref[k]) for k in keys) / s.spring_model.internal_parameters()["Fset"]
                )
            errs = 100 * np.array(errs)
            w = int(np.argmax(errs))
            name = f"{d:g}" if d < 1000 else "atol for all"
            mark = "  <- default" if d == default else ""
            print(
                f"{name:>12s} {steps:9d} {errs.max():15.4f} {np.sort(errs)[-2]:8.4f}  "
                f"{cases[w][0].type} {cases[w][1]} {cases[w][2]:g} rpm{mark}"
            )
    finally:
        runner.VELOCITY_TOLERANCE_DIVISOR = default
    return 0


if __name__ == "__main__":
    sys.exit(main())
