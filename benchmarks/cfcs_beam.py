"""Speed of the CFCS elastica (beam) model: shooting with continuation and the Hencky chain.

Run:  python benchmarks/cfcs_beam.py
Prints the time of a Table 1 force curve (0-72 mm) at 145 and 721 points, of one chain
solution with 100 and 200 links, and of a beam-model design.  The first call includes the
numba compilation (cached on disk afterwards).
"""

from __future__ import annotations

import time

import numpy as np

from springdyn.cfcs import beam, design

R2, R3, L = 0.085, 0.095, 0.0095
EI = 207e9 * 0.0254 * 0.00038**3 / 12


def timed(label, fn, repeat=3):
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    print(f"{label:45s} {best * 1e3:9.1f} ms (best of {repeat})")


def main() -> int:
    t = time.perf_counter()
    beam.beam_force_at_toggle(R2, R3, L, EI)
    print(f"{'first call (numba compile or cache load)':45s} {(time.perf_counter() - t) * 1e3:9.1f} ms")
    for n in (145, 721):
        x = np.linspace(0.0, 0.072, n)
        timed(f"shooting curve, {n} points", lambda x=x: beam.beam_force_curve(x, R2, R3, L, EI))
    for links in (100, 200):
        timed(
            f"chain, {links} links, x = 40 mm",
            lambda links=links: beam.chain_equilibrium(0.04, R2, R3, L, EI, links=links),
        )
    timed("design 12.8 N / 40 mm, beam model", lambda: design(12.8, 0.04, 207e9, 1.5e9, total_length=0.3), 1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
