"""The package's architecture: the physics never imports the application layer,
and no two springdyn modules import each other, directly or through others.

The import graph is read from the source (every ``import`` statement, also inside
functions, except under ``if TYPE_CHECKING:``), so a cycle hidden behind a lazy import
counts as a cycle too.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import springdyn

PACKAGE = Path(springdyn.__file__).resolve().parent


def _module_name(path: Path) -> str:
    rel = path.relative_to(PACKAGE.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _is_type_checking(node: ast.If) -> bool:
    return isinstance(node.test, (ast.Name, ast.Attribute)) and "TYPE_CHECKING" in ast.unparse(node.test)


def _imports(path: Path, name: str, modules: set[str]) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    is_pkg = path.name == "__init__.py"
    base = name if is_pkg else name.rsplit(".", 1)[0]
    found: set[str] = set()

    def visit(node):
        if isinstance(node, ast.If) and _is_type_checking(node):
            for child in node.orelse:
                visit(child)
            return
        if isinstance(node, ast.Import):
            for alias in node.names:
                found.add(alias.name)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                parts = base.split(".")
                parts = parts[: len(parts) - (node.level - 1)]
                target = ".".join(parts + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            found.add(target)
            for alias in node.names:  # ``from . import design`` imports a submodule
                if f"{target}.{alias.name}" in modules:
                    found.add(f"{target}.{alias.name}")
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(tree)
    out = set()
    for target in found:
        while target and target not in modules:  # springdyn.valve.cam.Cam -> springdyn.valve.cam
            target = target.rsplit(".", 1)[0] if "." in target else ""
        if target and target != name:
            out.add(target)
    return out


def import_graph() -> dict[str, set[str]]:
    files = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    modules = set(files)
    return {name: _imports(files[name], name, modules) - {"springdyn"} for name in sorted(modules)}


def _cycle(graph):
    state: dict[str, int] = {}
    stack: list[str] = []

    def dfs(node):
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            # importing a package runs its __init__, but a module importing its own parent
            # package's siblings through the package is the usual layout, not a cycle
            if node.startswith(nxt + "."):
                continue
            if state.get(nxt) == 1:
                return stack[stack.index(nxt) :] + [nxt]
            if state.get(nxt) is None:
                found = dfs(nxt)
                if found:
                    return found
        stack.pop()
        state[node] = 2
        return None

    for node in graph:
        if node not in state:
            found = dfs(node)
            if found:
                return found
    return None


def test_no_import_cycle_inside_springdyn():
    cycle = _cycle(import_graph())
    assert cycle is None, "import cycle: " + " -> ".join(cycle)


def test_physics_never_imports_the_application_layer_statically():
    graph = import_graph()
    offenders = {
        m: sorted(d for d in deps if d.startswith("springdyn.app"))
        for m, deps in graph.items()
        if not m.startswith("springdyn.app")
    }
    offenders = {m: d for m, d in offenders.items() if d}
    assert not offenders, f"physics modules import the app layer: {offenders}"


def test_importing_the_families_loads_no_app_module():
    code = (
        "import sys, springdyn.valve, springdyn.cfcs, springdyn.lsd\n"
        "bad = sorted(m for m in sys.modules if m.startswith('springdyn.') and (m.startswith('springdyn.app') or m.endswith(('.cli', '.report'))))\n"
        "print(','.join(bad))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.strip()
    assert out == "", f"importing the physics loaded app modules: {out}"


def test_the_cycle_finder_finds_a_cycle():
    """The check above can fail: a made-up graph with a cycle is caught."""
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None
