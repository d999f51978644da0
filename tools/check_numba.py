"""Does springdyn's compiled engine work with the newest numba?  (Or with a numba you name.)

``springdyn/numerics/jit.py`` subclasses numba's private caching classes
(``numba.core.caching``: the cache locators, ``CompileResultCacheImpl``, ``FunctionCache``),
which numba may change in any release, so ``pyproject.toml`` pins numba to the releases that
were tested, with an upper bound.  This tool checks a release outside the pin:

1. it finds the newest numba on PyPI (``pip index versions numba``), or takes ``--numba``;
2. it makes a temporary virtual environment and installs that numba (pip picks its llvmlite
   and a NumPy it supports), springdyn's other dependencies and pytest, then springdyn from
   this checkout without its dependencies (the pin overridden);
3. it runs the engine's and the compiled kernels' tests there (``tests/numerics``,
   ``tests/valve/engine``, not the slow ones) with an empty numba cache;
4. it prints whether that numba works and what to change in the pin.

Run from anywhere:  python tools/check_numba.py [--numba 0.69.0] [--keep]
Exits 0 when the numba works, 1 when it does not, 2 when it could not be installed.
It takes some minutes (the install, then the engines compile with an empty cache).
"""

from __future__ import annotations

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: The tests that exercise the compiled engine and springdyn's numba cache classes.
TESTS = ("tests/numerics", "tests/valve/engine")
#: A test that holds the installed numba to the pin: deselected here, where the pin is overridden.
PIN_TEST = "tests/numerics/test_jit.py::test_the_installed_numba_is_within_the_pin"
#: What a checkout's src/ holds beside the sources (caches, an editable install's metadata).
_BUILD_LITTER = shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc", "*.egg-info")


def project() -> dict:
    """The ``[project]`` table of pyproject.toml."""
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def numba_pin(deps) -> tuple:
    """The numba requirement of ``deps`` and its bounds ``(lower, upper)`` as version tuples."""
    spec = next(d for d in deps if re.match(r"numba\b", d))
    lower = re.search(r">=\s*([\d.]+)", spec)
    upper = re.search(r"<\s*([\d.]+)", spec)
    return spec, _version(lower.group(1)) if lower else None, _version(upper.group(1)) if upper else None


def _version(text: str) -> tuple:
    return tuple(int(x) for x in re.findall(r"\d+", text)[:3])


def _show(v: tuple) -> str:
    return ".".join(str(x) for x in v)


def newest_numba(python: str) -> str:
    """The newest numba release on the package index pip uses."""
    done = subprocess.run(
        [python, "-m", "pip", "index", "versions", "numba"], capture_output=True, text=True, timeout=300
    )
    found = re.search(r"^numba \(([^)]+)\)", done.stdout, re.M)
    if not found:
        raise SystemExit(f"could not ask the package index for numba's releases: {done.stderr.strip()[-500:]}")
    return found.group(1)


def run(argv, **kw) -> subprocess.CompletedProcess:
    print("  $", " ".join(str(a) for a in argv), flush=True)
    return subprocess.run([str(a) for a in argv], capture_output=True, text=True, **kw)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--numba", help="the numba release to check (default: the newest on PyPI)")
    parser.add_argument("--python", default=sys.executable, help="the interpreter of the temporary venv")
    parser.add_argument("--keep", action="store_true", help="keep the temporary venv (its folder is printed)")
    args = parser.parse_args(argv)

    deps = project()["dependencies"]
    spec, lower, upper = numba_pin(deps)
    version = args.numba or newest_numba(args.python)
    v = _version(version)
    inside = (lower is None or v >= lower) and (upper is None or v < upper)
    print(f"numba {version} {'(the newest on PyPI) ' if not args.numba else ''}against the pin {spec!r}")

    work = Path(tempfile.mkdtemp(prefix="springdyn-numba-"))
    (work / "springdyn").mkdir()
    try:
        venv = work / "venv"
        py = venv / "bin" / "python"
        if run([args.python, "-m", "venv", venv]).returncode != 0:
            print("could not make a virtual environment")
            return 2
        others = [d for d in deps if not re.match(r"numba\b", d)]
        source = work / "springdyn"  # a copy to build from: the build leaves the checkout as it is
        for part in ("pyproject.toml", "README.md", "src"):
            copy = shutil.copytree if (ROOT / part).is_dir() else shutil.copy2
            copy(ROOT / part, source / part, **({"ignore": _BUILD_LITTER} if part == "src" else {}))
        steps = [
            [py, "-m", "pip", "install", "-q", f"numba=={version}", *others, "pytest"],
            [py, "-m", "pip", "install", "-q", "--no-deps", source],  # springdyn, the pin overridden
        ]
        for step in steps:
            done = run(step, timeout=1800)
            if done.returncode != 0:
                print(f"numba {version} could not be installed:\n{(done.stdout + done.stderr).strip()[-2000:]}")
                return 2
        got = run(
            [
                py,
                "-c",
                "import numba, llvmlite, numpy; print(numba.__version__, llvmlite.__version__, numpy.__version__)",
            ]
        ).stdout.split()
        print(f"installed: numba {got[0]}, llvmlite {got[1]}, numpy {got[2]}")
        env = {k: val for k, val in os.environ.items() if not k.startswith("NUMBA_") and k != "PYTHONPATH"}
        env["NUMBA_CACHE_DIR"] = str(work / "numba-cache")
        t0 = time.perf_counter()
        tests = [py, "-m", "pytest", "-q", "-m", "not slow", "-p", "no:cacheprovider", "--deselect", PIN_TEST]
        done = run([*tests, *TESTS], cwd=ROOT, env=env, timeout=3600)
        seconds = time.perf_counter() - t0
        lines = (done.stdout + done.stderr).strip().splitlines()
        summary = lines[-1] if lines else "(no output)"
        works = done.returncode == 0
        print(f"tests ({', '.join(TESTS)}): {summary} [{seconds:.0f} s]")
        if not works:
            print("\n".join(lines[-60:]))
        print()
        if works and inside:
            print(f"numba {version} works and lies within the pin {spec!r}: nothing to change.")
        elif works:
            bound = f"<{v[0]}.{v[1] + 1}"
            print(
                f"numba {version} WORKS but lies outside the pin {spec!r}: to allow it, write the upper bound "
                f"{bound} in pyproject.toml (numba>={_show(lower) if lower else '?'},{bound}), and the release "
                "checked in docs/performance.md."
            )
        else:
            print(
                f"numba {version} does NOT work: keep the pin {spec!r}. The failures above say what changed; "
                "springdyn/numerics/jit.py (numba's private caching classes) is the likely place to follow it."
            )
        return 0 if works else 1
    finally:
        if args.keep:
            print(f"kept: {work}")
        else:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
