"""Start-up time of the ``springdyn`` command against Python's own imports (issue 10).

Targets, measured in the same run on the same machine:

- ``springdyn --help`` and every ``springdyn <family> [<command>] --help`` within 3x
  ``python -c "import numpy"``;
- ``springdyn valve params FILE --json`` within 2x ``python -c "import numpy, scipy.optimize"``.

Each command runs in a fresh interpreter (``--repeat`` times, the best time counts: start-up
is what a user waits for on a warm machine).  Run it: ``python benchmarks/startup.py``.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPRING = ROOT / "examples" / "valve" / "one_step_spring.toml"
CLI = [sys.executable, "-c", "import sys; from springdyn.app.cli.main import main; sys.exit(main())"]


def best_time(argv, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        done = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        times.append(time.perf_counter() - t0)
        if done.returncode != 0:
            raise SystemExit(f"{' '.join(argv)} failed: {done.stderr.strip()}")
    return min(times)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="runs per command (best counts; default 7)")
    args = parser.parse_args()
    subprocess.run([*CLI, "valve", "params", str(SPRING), "--json"], stdout=subprocess.DEVNULL)  # pint cache, pyc
    numpy = best_time([sys.executable, "-c", "import numpy"], args.repeat)
    scipy = best_time([sys.executable, "-c", "import numpy, scipy.optimize"], args.repeat)
    print(
        f"references: python -c 'import numpy' {numpy * 1e3:.0f} ms; "
        f"python -c 'import numpy, scipy.optimize' {scipy * 1e3:.0f} ms"
    )
    helps = [["--help"], ["valve", "--help"], ["cfcs", "--help"], ["lsd", "--help"]]
    for family, commands in (
        ("valve", ["params", "curve", "modes", "design", "simulate", "float", "sweep"]),
        ("cfcs", ["static", "dynamic", "sweep", "forward", "design"]),
        ("lsd", ["coefficients", "rig", "identify"]),
    ):
        helps += [[family, c, "--help"] for c in commands]
    worst = 0.0
    failed = []
    for argv in helps:
        t = best_time([*CLI, *argv], args.repeat)
        ratio = t / numpy
        worst = max(worst, ratio)
        if ratio > 3.0:
            failed.append(" ".join(argv))
        print(f"  springdyn {' '.join(argv):<28} {t * 1e3:6.0f} ms  {ratio:4.2f}x import numpy")
    print(
        f"--help: worst {worst:.2f}x import numpy (target <= 3x): {'MET' if not failed else 'NOT MET: ' + ', '.join(failed)}"
    )
    t = best_time([*CLI, "valve", "params", str(SPRING), "--json"], args.repeat)
    ratio = t / scipy
    print(
        f"springdyn valve params FILE --json: {t * 1e3:.0f} ms, {ratio:.2f}x import numpy+scipy.optimize "
        f"(target <= 2x): {'MET' if ratio <= 2.0 else 'NOT MET'}"
    )
    return 0 if not failed and ratio <= 2.0 else 1


if __name__ == "__main__":
    sys.exit(main())
