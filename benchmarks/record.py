"""Run the benchmarks and record what they print, per springdyn version.

Each benchmark runs as its own command (as a user would run it); its output, exit code and
wall time go to ``benchmarks/history/<version>/<date>-<commit>.md``, a plain record to
compare versions by (``git diff`` of two records, or reading them side by side). The
goals each benchmark checks are its own (it prints MET or NOT MET and exits non-zero on a
miss); this script exits non-zero when any benchmark did.

Run:  python benchmarks/record.py [--only cold_start valve_speed ...] [--quick]
``--quick`` skips the benchmarks that take minutes (the SciPy references, the demo).
"""

from __future__ import annotations

import argparse
import datetime
import platform
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
#: name -> (arguments, takes minutes)
BENCHMARKS = {
    "cold_start": (["--repeat", "2"], True),
    "startup": ([], False),
    "valve_speed": ([], True),
    "valve_distributed": ([], True),
    "valve_stepping": ([], True),
    "valve_tolerances": ([], True),
    "cfcs_beam": ([], False),
}


def _git(*args) -> str:
    done = subprocess.run(["git", *args], cwd=HERE, capture_output=True, text=True)
    return done.stdout.strip() if done.returncode == 0 else "unknown"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="+", choices=sorted(BENCHMARKS), help="these benchmarks only")
    parser.add_argument("--quick", action="store_true", help="skip the benchmarks that take minutes")
    args = parser.parse_args(argv)
    import springdyn

    names = args.only or [n for n, (_, slow) in BENCHMARKS.items() if not (args.quick and slow)]
    commit = _git("rev-parse", "--short", "HEAD")
    dirty = " (uncommitted changes)" if _git("status", "--porcelain", "--untracked-files=no") else ""
    stamp = datetime.datetime.now().strftime("%Y-%m-%d-%H%M")
    out = HERE / "history" / springdyn.__version__ / f"{stamp}-{commit}.md"
    lines = [
        f"# springdyn {springdyn.__version__}, commit {commit}{dirty}, {stamp}",
        "",
        f"Machine: {platform.machine()}, {platform.processor() or 'unknown CPU'}, Python {platform.python_version()}",
        "",
    ]
    failed = []
    for name in names:
        extra, _ = BENCHMARKS[name]
        print(f"running {name} ...", flush=True)
        t0 = time.perf_counter()
        done = subprocess.run([sys.executable, str(HERE / f"{name}.py"), *extra], capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if done.returncode != 0:
            failed.append(name)
        lines += [f"## {name} (exit {done.returncode}, {wall:.0f} s)", "", "```", done.stdout.rstrip()]
        if done.returncode != 0 and done.stderr.strip():
            lines += ["--- stderr ---", done.stderr.rstrip()[-4000:]]
        lines += ["```", ""]
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines), encoding="utf-8")
    print(f"recorded {out.relative_to(HERE.parent)}" + (f"; missed: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
