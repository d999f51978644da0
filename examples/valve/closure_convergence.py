"""Coil clash in the distributed model: convergence in the element count and the effect of
the contact stiffness of closed turns (the tables of docs/valve-spring.md, issue 25).

Runs the one-step example on a 3-4-5 cam of 9 mm at 4000 cam rpm and the two-step example
on 7.5 mm at 4500 cam rpm (9 mm would drive it past solid), each to its periodic steady state (the last two revolutions within 1e-5 of Fset), and prints
the peak seat, peak retainer and minimum retainer force of the last (periodic) revolution
at 50, 100 and 200 elements; then the one-step case at 0.3, 1 and 3 times the default
contact stiffness.  Writes ``closure_convergence.csv`` into ``--out``.

Usage: python examples/valve/closure_convergence.py [--out DIR]
"""

from __future__ import annotations

import argparse
import csv
import math
import warnings
from pathlib import Path

from springdyn.valve import Cam, ValveSpring, simulate

CASES = (("one-step", 9e-3, 4000.0), ("two-step", 7.5e-3, 4500.0))


def extremes(spring, cam, rpm) -> dict:
    """Last-revolution extremes [N] and the periodicity error [fraction of Fset]."""
    sim = simulate(spring, cam, rpm, check_elements=False, periodicity_tol=1e-5)
    s = sim.summary
    return dict(
        seat_max_N=s["max_seat_force_N"],
        retainer_max_N=s["max_retainer_force_N"],
        retainer_min_N=s["min_retainer_force_N"],
        periodicity_error=sim.periodicity_error,
        steps=sim.info["steps"],
    )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=".", help="folder for closure_convergence.csv")
    args = ap.parse_args()
    warnings.simplefilter("ignore", UserWarning)  # the examples sit below EN 13906-1's clearance
    rows = []
    print("elements  spring    rpm   peak seat [N]  peak retainer [N]  min retainer [N]  periodicity [Fset]")
    for name, lift, rpm in CASES:
        cam = Cam(law="3-4-5", lift=lift, duration=math.radians(120))
        base = ValveSpring.example(name).with_model("distributed")
        fset = base.spring_model.internal_parameters()["Fset"]
        for n in (50, 100, 200):
            r = extremes(base.replace(elements=n), cam, rpm)
            rows.append(dict(case=name, elements=n, contact_factor=1.0, Fset_N=fset, **r))
            print(
                f"{n:8d}  {name:8s} {rpm:5.0f}   {r['seat_max_N']:13.1f}  {r['retainer_max_N']:17.1f}  "
                f"{r['retainer_min_N']:16.1f}  {r['periodicity_error']:.1e}"
            )
        fine = rows[-1]
        for coarse in rows[-3:-1]:
            diff = max(abs(coarse[k] - fine[k]) for k in ("seat_max_N", "retainer_max_N", "retainer_min_N"))
            print(f"  {name}: {coarse['elements']} elements within {100 * diff / fset:.2f} % of Fset of 200")
    print()
    print("contact stiffness  peak seat [N]  peak retainer [N]  min retainer [N]  steps   (one-step, 4000 cam rpm)")
    name, lift, rpm = CASES[0]
    cam = Cam(law="3-4-5", lift=lift, duration=math.radians(120))
    base = ValveSpring.example(name).with_model("distributed")
    k = base.spring_model.internal_parameters()["K"]
    for factor in (0.3, 1.0, 3.0):
        r = extremes(base.replace(contact_stiffness=factor * k), cam, rpm)
        rows.append(dict(case=name, elements=50, contact_factor=factor, Fset_N=float("nan"), **r))
        print(
            f"{factor:4.1f} x {factor * k / 1e3:6.0f} N/mm  {r['seat_max_N']:13.1f}  {r['retainer_max_N']:17.1f}  "
            f"{r['retainer_min_N']:16.1f}  {r['steps']:6d}"
        )
    out = Path(args.out) / "closure_convergence.csv"
    tmp = out.with_suffix(".csv.tmp")
    with open(tmp, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    tmp.replace(out)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
