"""The compiled kernels' cache and notices (springdyn.numerics.jit).

Requirements checked here:
- an edit to any file an engine is compiled from invalidates that engine's cache: an edited
  copy of the package runs its new code (numba alone keys a kernel on its own file only);
- every kernel calls compiled code only from its source group (so the stamp covers it);
- a cache folder that cannot be written, or cache files that cannot be read, never stop a
  run: the kernels compile again and one line says so;
- a compilation is announced by one line on stderr, none when nothing compiles or under
  ``notices(False)``;
- a Type C spring-alone run compiles no integration pair and no valve-train variant it does
  not run.
"""

from __future__ import annotations

import inspect
import os
import shutil
import subprocess
import sys
import types
from pathlib import Path

import pytest

import springdyn
from springdyn.numerics import jit

PACKAGE = Path(springdyn.__file__).resolve().parent

#: The compiled right-hand side (equations.py) against its plain-Python source, at a time
#: the cam lifts; prints whether they agree, then the kernel's cache hits and misses.
RHS_PROBE = """
import math
import numpy as np
from springdyn.valve import Cam, ValveSpring
from springdyn.valve.run.setup import prepare
from springdyn.valve.run.runner import engine_args
from springdyn.valve.engine.equations import chain_rhs, model_of, rhs_call, train_of
from springdyn.valve.engine.layout import extra_layout
setup = prepare(ValveSpring.example("one-step"), Cam(law="3-4-5", lift=9e-3, duration=math.radians(120)))
omega = 314.0
args = engine_args(setup, omega)
m, vt = model_of(args), train_of(args[9])
got, want = np.zeros(extra_layout(m.masses.shape[0])["size"]), np.zeros(extra_layout(m.masses.shape[0])["size"])
t = 0.1 * 2 * math.pi / omega
rhs_call(t, setup.y0.copy(), m, omega, vt, np.zeros(setup.y0.size), got)
chain_rhs(t, setup.y0.copy(), m, omega, vt, np.zeros(setup.y0.size), want)
s = rhs_call.stats
print(bool(np.allclose(got, want, rtol=1e-12, atol=0.0)), sum(s.cache_hits.values()), sum(s.cache_misses.values()))
"""


def _copy_package(tmp_path: Path) -> Path:
    root = tmp_path / "site"
    shutil.copytree(PACKAGE, root / "springdyn", ignore=shutil.ignore_patterns("__pycache__", "*.nbi", "*.nbc"))
    return root


def _run(root: Path, code: str, env_extra: dict) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env.update(PYTHONPATH=str(root), PYTHONDONTWRITEBYTECODE="1", **env_extra)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=root, timeout=300)
    assert done.returncode == 0, done.stderr
    return done


def test_an_edit_of_any_source_file_invalidates_the_cached_kernels(tmp_path):
    """The right-hand side (equations.py) writes its outputs at the offsets of layout.py:
    after layout.py swaps two of them, the cached kernel must not run (numba's own stamp
    covers equations.py only): the compiled code agrees with its plain-Python source
    again, after a compilation.  An edit of numerics/erk.py, which the engines call,
    invalidates it too."""
    root = _copy_package(tmp_path)
    env = {"NUMBA_CACHE_DIR": str(tmp_path / "cache")}
    first = _run(root, RHS_PROBE, env).stdout.split()
    assert first == ["True", "0", "1"]  # compiled
    again = _run(root, RHS_PROBE, env).stdout.split()
    assert again == ["True", "1", "0"]  # loaded from the cache
    layout = root / "springdyn" / "valve" / "engine" / "layout.py"
    text = layout.read_text()
    assert "X_LIFT = 0 " in text and "X_DLIFT = 1 " in text
    layout.write_text(text.replace("X_LIFT = 0 ", "X_LIFT = 1 ").replace("X_DLIFT = 1 ", "X_DLIFT = 0 "))
    edited = _run(root, RHS_PROBE, env).stdout.split()
    assert edited == ["True", "0", "1"]  # the new code runs (a stale kernel would disagree)
    erk = root / "springdyn" / "numerics" / "erk.py"
    erk.write_text(erk.read_text() + "\n# an edit\n")
    assert _run(root, RHS_PROBE, env).stdout.split() == ["True", "0", "1"]
    assert _run(root, RHS_PROBE, env).stdout.split() == ["True", "1", "0"]


def _kernel_modules():
    import springdyn.cfcs.beam  # noqa: F401
    import springdyn.valve.engine.api  # noqa: F401  (loads every engine module)
    import springdyn.valve.engine.stepping  # noqa: F401

    return jit.KERNELS


def _referenced_files(fn) -> set:
    """Files of the springdyn functions, kernels, classes and modules ``fn`` names as globals."""
    out = set()
    code_objects = [fn.__code__]
    while code_objects:
        code = code_objects.pop()
        code_objects += [c for c in code.co_consts if isinstance(c, types.CodeType)]
        for name in code.co_names:
            value = fn.__globals__.get(name)
            value = getattr(value, "py_func", value)
            if isinstance(value, types.ModuleType):
                f = getattr(value, "__file__", None)
            elif inspect.isfunction(value) or inspect.isclass(value):
                f = inspect.getfile(value) if value.__module__.startswith("springdyn") else None
            else:
                f = None
            if f and Path(f).resolve().is_relative_to(PACKAGE):
                out.add(Path(f).resolve())
    return out


def test_every_kernel_calls_code_from_its_source_group_only():
    kernels = _kernel_modules()
    assert len(kernels) > 20
    for k in kernels:
        own = Path(inspect.getfile(k.py_func)).resolve()
        group = set(jit.source_group(own))
        stray = _referenced_files(k.py_func) - group
        assert not stray, f"{k.py_func.__qualname__} ({own.name}) calls code outside its cache stamp: {stray}"


def test_the_stamp_changes_with_every_file_of_the_group(tmp_path):
    files = jit.source_group(PACKAGE / "valve" / "engine" / "loop.py")
    names = {f.relative_to(PACKAGE).as_posix() for f in files}
    assert {"valve/engine/equations.py", "valve/engine/monitor.py", "numerics/erk.py", "numerics/jit.py"} <= names
    assert "valve/run/simulation.py" not in names  # the Python around the engine does not key it


def test_no_writable_cache_folder_compiles_in_memory_and_says_so_once(tmp_path):
    root = _copy_package(tmp_path)
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    for d in (root / "springdyn").rglob("*"):
        if d.is_dir():
            (d / "__pycache__").write_text("not a folder")  # numba's in-tree cache
    env = {
        "NUMBA_CACHE_DIR": str(blocker / "cache"),
        "XDG_CACHE_HOME": str(blocker / "xdg"),
        "HOME": str(blocker / "home"),
    }
    done = _run(root, RHS_PROBE, env)
    assert done.stdout.split()[0] == "True"
    lines = [ln for ln in done.stderr.splitlines() if ln.startswith("springdyn:")]
    assert len(lines) == 1 and "no writable compile cache folder" in lines[0], done.stderr


def test_unreadable_cache_files_are_dropped_and_compiled_again(tmp_path):
    root = _copy_package(tmp_path)
    cache = tmp_path / "cache"
    env = {"NUMBA_CACHE_DIR": str(cache)}
    _run(root, RHS_PROBE, env)
    files = list(cache.rglob("*.nb[ic]"))
    assert files
    for f in files:
        f.write_bytes(b"\x80\x04garbage, not a pickle")
    done = _run(root, RHS_PROBE, env)
    assert done.stdout.split() == ["True", "0", "1"]
    lines = [ln for ln in done.stderr.splitlines() if ln.startswith("springdyn:")]
    assert len(lines) == 1 and "could not be read" in lines[0], done.stderr
    healed = _run(root, RHS_PROBE, env)  # the cache was written anew
    assert healed.stdout.split() == ["True", "1", "0"] and "springdyn:" not in healed.stderr


def test_a_compilation_is_announced_once(capsys):
    import numba

    f = numba.njit(lambda x: x + 1.0)
    with jit.compiling("a test kernel", 3):
        assert f(1.0) == 2.0
        assert f(2.0) == 3.0
    err = capsys.readouterr().err
    assert err.count("springdyn: compiling a test kernel for this machine: about 3 s, once per machine") == 1
    with jit.compiling("a test kernel", 3):  # compiled already: silent
        f(3.0)
    assert capsys.readouterr().err == ""
    g = numba.njit(lambda x: x - 1.0)
    old = jit.notices(False)
    try:
        with jit.compiling("a quiet kernel", 3):
            g(1.0)
    finally:
        jit.notices(old)
    assert capsys.readouterr().err == ""


USED_PROBE = """
import math
from springdyn.valve import Cam, ValveSpring, simulate
from springdyn.numerics import erk
from springdyn.valve.engine import loop
simulate(ValveSpring.example("one-step"), Cam(law="3-4-5", lift=9e-3, duration=math.radians(120)), 3000.0, 2)
print("variants", sorted(k.py_func.__qualname__ for k in loop._COMPILED.values() if k.signatures))
print("trains", sorted({str(sig[6]) for k in loop._COMPILED.values() for sig in k.signatures}))
print("unused", [k.py_func.__name__ for k in (erk.stage_state, erk.error_norm, erk.tsit5_stage_state,
                                              erk.tsit5_error_norm, erk.dense_coefficients) if k.signatures])
from springdyn.valve.engine import equations
g = equations._TWINS["__globals__"]
print("models", sorted({str(sig[4]).count("none") for k in loop._COMPILED.values() for sig in k.signatures}))
print("pack", [name for name in ("_record_chains",) if g[name].signatures])
"""


@pytest.mark.slow
def test_a_type_c_run_compiles_only_its_pair_and_model(tmp_path):
    """With an empty cache (so that every kernel it calls compiles and shows its signatures)."""
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "cache")
    done = subprocess.run([sys.executable, "-c", USED_PROBE], capture_output=True, text=True, timeout=300, env=env)
    assert done.returncode == 0, done.stderr
    out = dict(line.split(" ", 1) for line in done.stdout.splitlines())
    assert out["variants"] == "['integrate_loop_dopri5_spring']"
    assert out["trains"] == "['none']"  # the spring alone: no valve-train variant
    assert out["unused"] == "[]"  # no Bogacki-Shampine or Tsitouras kernel
    # one spring's model (its damper None, equations.chain_forces): none of a spring pack's code
    assert out["models"] == "[1]"
    assert out["pack"] == "[]"


def test_the_installed_numba_is_within_the_pin():
    """jit subclasses numba's private caching classes, so pyproject.toml pins numba to the
    releases tested; an install outside the pin (pip --no-deps, a conda environment) fails
    here, and tools/check_numba.py says whether a newer numba works."""
    import re
    import tomllib

    import numba

    deps = tomllib.loads((Path(__file__).resolve().parents[2] / "pyproject.toml").read_text())["project"][
        "dependencies"
    ]
    spec = next(d for d in deps if re.match(r"numba\b", d))
    upper = re.search(r"<\s*([\d.]+)", spec)
    assert upper, f"the numba requirement {spec!r} has no upper bound"
    have = tuple(int(x) for x in re.findall(r"\d+", numba.__version__)[:2])
    assert have < tuple(int(x) for x in upper.group(1).split(".")[:2]), (numba.__version__, spec)
