"""The valve family's floor plan (issue 38): wings that import only the wings below them, no
circle between or inside them (type-only imports counted), a top floor of ``__init__.py`` and
``model.py`` alone, function-level imports only where start-up needs them (each with its
reason), and an application layer that reaches the family through its front doors.

The import graph is the one of ``tests/test_architecture.py`` (every ``import`` statement of
the source, inside functions and under ``if TYPE_CHECKING:`` too).
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

from tests.test_architecture import PACKAGE, _cycle, import_graph

VALVE = PACKAGE / "valve"
#: The wings from the ground floor up: each may import only the wings before it.
WINGS = ("engine", "spring", "cam", "train", "run", "design", "camshaft", "model")
#: What the application layer may import of the valve family: the façade, the model, the wings' façades.
FRONT_DOORS = {
    "springdyn.valve",
    "springdyn.valve.model",
    "springdyn.valve.cam",
    "springdyn.valve.design",
}


def _wing(module: str) -> str | None:
    parts = module.split(".")
    return parts[2] if len(parts) > 2 and parts[:2] == ["springdyn", "valve"] else None


def wing_violations(graph) -> list[str]:
    """The imports of a graph (module -> imported modules) that go up a wing."""
    rank = {w: i for i, w in enumerate(WINGS)}
    bad = []
    for module, deps in graph.items():
        w = _wing(module)
        if w is None:
            continue
        for d in sorted(deps):
            wd = _wing(d)
            if wd is not None and rank[wd] > rank[w]:
                bad.append(f"{module} ({w}) imports {d} ({wd}), a wing above it")
    return bad


def test_each_wing_imports_only_the_wings_below_it():
    bad = wing_violations(import_graph())
    assert not bad, "\n".join(bad)


def test_the_wing_check_can_fail():
    graph = {"springdyn.valve.spring.stress": {"springdyn.valve.run.sweeps"}, "springdyn.valve.run.sweeps": set()}
    assert wing_violations(graph) == [
        "springdyn.valve.spring.stress (spring) imports springdyn.valve.run.sweeps (run), a wing above it"
    ]


def test_nothing_inside_the_family_imports_names_from_its_facade():
    """``from springdyn.valve import ValveSpring`` inside the family would make the façade a
    floor of its own: a module imports what it needs from the module that defines it."""
    bad = []
    for path in sorted(VALVE.rglob("*.py")):
        if path == VALVE / "__init__.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        depth = len(path.relative_to(VALVE).parts) - 1  # folders below valve/
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom):
                continue
            to_facade = node.module == "springdyn.valve" or (node.level == depth + 1 and node.module is None)
            names = [a.name for a in node.names]
            if to_facade and not all((VALVE / n).is_dir() or (VALVE / f"{n}.py").is_file() for n in names):
                bad.append(f"{path.relative_to(PACKAGE)}:{node.lineno} imports {names} from the façade")
    assert not bad, "\n".join(bad)


def test_no_circle_between_or_inside_the_wings():
    graph = {m: {d for d in deps if d.startswith("springdyn.valve")} for m, deps in import_graph().items()}
    graph = {m: d for m, d in graph.items() if m.startswith("springdyn.valve")}
    assert _cycle(graph) is None, " -> ".join(_cycle(graph))
    wings = {}
    for m, deps in graph.items():
        for d in deps:
            a, b = _wing(m), _wing(d)
            if a and b and a != b:
                wings.setdefault(a, set()).add(b)
    assert _cycle(wings) is None, "wings in a circle: " + " -> ".join(_cycle(wings))


def test_the_cycle_check_counts_type_only_imports(tmp_path):
    """A circle hidden behind ``if TYPE_CHECKING:`` is a circle: the graph reader sees it."""
    from tests.test_architecture import _imports

    f = tmp_path / "a.py"
    f.write_text(
        "from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from springdyn.valve.model import ValveModel\n"
    )
    assert "springdyn.valve.model" in _imports(f, "springdyn.valve.spring.a", {"springdyn.valve.model"})


def test_the_top_floor_holds_the_facade_and_the_model_only():
    files = sorted(p.name for p in VALVE.glob("*.py"))
    assert files == ["__init__.py", "model.py"], files
    folders = sorted(p.name for p in VALVE.iterdir() if p.is_dir() and (p / "__init__.py").is_file())
    assert folders == sorted(w for w in WINGS if w != "model"), folders


def test_no_wing_passes_fifteen_modules():
    for wing in WINGS[:-1]:
        modules = [p for p in (VALVE / wing).glob("*.py") if p.name != "__init__.py"]
        assert len(modules) <= 15, f"valve/{wing}/ holds {len(modules)} modules: grow a sub-package by topic"


def test_function_level_imports_say_why():
    """An import inside a function is there for start-up (xarray, matplotlib, dask, scipy in the
    wings every command loads, the engine's numba) and says so on its line, ``# (here: ...)``."""
    bad = []
    for path in sorted(VALVE.rglob("*.py")):
        src = path.read_text(encoding="utf-8")
        lines = src.splitlines()
        for fn in ast.walk(ast.parse(src)):
            if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            for node in ast.walk(fn):
                if isinstance(node, (ast.Import, ast.ImportFrom)) and "(here:" not in lines[node.lineno - 1]:
                    bad.append(f"{path.relative_to(PACKAGE)}:{node.lineno}: {lines[node.lineno - 1].strip()}")
    assert not bad, "function-level imports without their reason:\n" + "\n".join(bad)


def test_the_application_layer_uses_the_front_doors():
    """app/ imports the valve family through a handful of modules: its façade, the model and the
    wings' façades; never a wing's internals."""
    graph = import_graph()
    used = {
        d
        for m, deps in graph.items()
        if m.startswith("springdyn.app")
        for d in deps
        if _wing(d) or d == "springdyn.valve"
    }
    assert used <= FRONT_DOORS, f"app/ imports valve internals: {sorted(used - FRONT_DOORS)}"


def test_valve_commands_build_the_model_without_the_engine():
    """The front door is cheap: a command that needs no run (``valve params``) loads no numba."""
    code = (
        "import sys\n"
        "from springdyn.app.cli.main import main\n"
        "main(['valve', 'params', sys.argv[1], '--json'])\n"
        "print('numba' in sys.modules, 'xarray' in sys.modules, 'matplotlib' in sys.modules, file=sys.stderr)\n"
    )
    spring = str(Path(PACKAGE).parents[1] / "examples" / "valve" / "one_step_spring.toml")
    out = subprocess.run([sys.executable, "-c", code, spring], capture_output=True, text=True, check=True)
    assert out.stderr.strip().splitlines()[-1] == "False False False"


def test_a_run_loads_scipy_only_where_it_needs_it():
    """A run's modules (the engine's face, the set-up, the simulation and its results) load no
    ``scipy.integrate`` (the reference's), ``scipy.optimize`` or ``scipy.linalg`` (a train's
    equilibrium, the train modes): 0.4-0.9 s of every run's start-up on 2 cores, measured when
    imports at the tops of ``engine/reference.py``, ``run/setup.py`` and ``run/train_modes.py``
    made a warm ``valve simulate`` take 2.1 s of CPU instead of 1.7 s."""
    code = (
        "import sys\n"
        "import springdyn.valve.engine.api, springdyn.valve.run.simulation, springdyn.valve.run.results\n"
        "print(sorted(m for m in ('scipy.integrate', 'scipy.optimize', 'scipy.linalg') if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
