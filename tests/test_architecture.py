"""The package's architecture: the physics never imports the application layer,
and no two springdyn modules import each other, directly or through others.

The import graph is read from the source: every ``import`` statement, also inside
functions and under ``if TYPE_CHECKING:``, so a cycle hidden behind a lazy import or a
type-only import counts as a cycle too.
"""

from __future__ import annotations

import ast
import re
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


def _imports(path: Path, name: str, modules: set[str]) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    is_pkg = path.name == "__init__.py"
    base = name if is_pkg else name.rsplit(".", 1)[0]
    found: set[str] = set()

    def visit(node):
        # no branch is skipped: an import under ``if TYPE_CHECKING:`` is a dependency too
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
        while target and target not in modules:  # springdyn.valve.cam.definition.Cam -> springdyn.valve.cam.definition
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
        if not m.startswith("springdyn.app") and m != "springdyn.__main__"  # (python -m springdyn: the CLI's door)
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


def test_type_only_and_lazy_imports_count(tmp_path):
    """An import under ``if TYPE_CHECKING:`` or inside a function is an edge of the graph."""
    module = tmp_path / "rig.py"
    module.write_text(
        "from typing import TYPE_CHECKING\n"
        "if TYPE_CHECKING:\n"
        "    from .model import LSDModel\n"
        "else:\n"
        "    from . import forces\n"
        "def f():\n"
        "    from .film import film_network\n",
        encoding="utf-8",
    )
    modules = {f"pkg.{m}" for m in ("rig", "model", "forces", "film")}
    assert _imports(module, "pkg.rig", modules) == {"pkg.model", "pkg.forces", "pkg.film"}


# --------------------------------------------------------------------------- maps that stay true
DOCS = PACKAGE.parents[1] / "docs"


def _where_is_rows():
    text = (DOCS / "architecture.md").read_text(encoding="utf-8")
    section = text.split("## Where is X?", 1)[1].split("\n## ", 1)[0]
    rows = []
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 3 and cells[1].startswith("`") and cells[1].endswith(".py`"):
            rows.append((cells[0], cells[1].strip("`"), re.findall(r"`([\w.]+)`", cells[2])))
    return rows


def _top_level_functions(path: Path) -> set:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}


def test_where_is_x_names_one_file_per_law():
    """docs/architecture.md, "Where is X?": each law's file exists and defines its names, and
    no other module defines a function or class of the same name (one place per equation)."""
    rows = _where_is_rows()
    assert len(rows) >= 20
    defined = {p: _top_level_functions(p) for p in PACKAGE.rglob("*.py")}
    for law, rel, names in rows:
        path = PACKAGE / rel
        assert path.is_file(), f"{law}: {rel} does not exist"
        for name in names:
            top = name.split(".")[0]
            assert top in defined[path], f"{law}: {rel} defines no {top}"
            if "." in name:
                tree = ast.parse(path.read_text(encoding="utf-8"))
                cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == top)
                members = {n.name for n in cls.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}
                assert name.split(".")[1] in members, f"{law}: {name} is not in {rel}"
            elsewhere = [str(p.relative_to(PACKAGE)) for p, names_ in defined.items() if p != path and top in names_]
            assert not elsewhere, f"{law}: {top} is defined in {rel} and again in {elsewhere}"


def test_every_valve_module_is_on_the_map():
    """docs/architecture.md covers every module of the valve family: a "Where is X?" row names
    its file, or the family map names it (definitions, results, figures, the engine's loop)."""
    text = (DOCS / "architecture.md").read_text(encoding="utf-8")
    family_map = text.split("## One shape for the three families", 1)[1].split("\n## ", 1)[0]
    valve_map = family_map.split("  valve/", 1)[1].split("  cfcs/", 1)[0]
    rows = {rel for _, rel, _ in _where_is_rows()}
    missing = []
    for path in sorted((PACKAGE / "valve").rglob("*.py")):
        rel = str(path.relative_to(PACKAGE))
        if path.name == "__init__.py" or rel in rows:
            continue
        if not re.search(rf"\b{re.escape(path.stem)}\b", valve_map):
            missing.append(rel)
    assert not missing, f"on neither the family map nor the Where-is-X table of docs/architecture.md: {missing}"


def test_every_package_docstring_lists_its_modules():
    """A package's docstring is its map: it names every public module in it."""
    for init in PACKAGE.rglob("__init__.py"):
        folder = init.parent
        doc = ast.get_docstring(ast.parse(init.read_text(encoding="utf-8"))) or ""
        modules = [p.stem for p in folder.glob("*.py") if not p.stem.startswith("_")]
        modules += [p.name for p in folder.iterdir() if p.is_dir() and (p / "__init__.py").is_file()]
        missing = [m for m in modules if not re.search(rf"\b{re.escape(m)}\b", doc)]
        assert not missing, f"{folder.relative_to(PACKAGE.parent)}/__init__.py does not list {missing}"


def _valve_tree() -> set[str]:
    """Every module and sub-package of springdyn/valve as a path below it: ``model.py``,
    ``spring/stress.py``, ``spring/chains/`` (a package), ``engine/loop.py``; the top
    ``__init__.py`` and private modules (``_name.py``) are not listed."""
    valve = PACKAGE / "valve"
    tree = set()
    for path in valve.rglob("*.py"):
        rel = path.relative_to(valve)
        if path.name == "__init__.py":
            if rel.parent.parts:  # a sub-package: its folder
                tree.add(rel.parent.as_posix() + "/")
        elif not path.stem.startswith("_"):
            tree.add(rel.as_posix())
    return tree


def test_the_valve_guide_lists_every_valve_module():
    """docs/valve.md, "Where each piece lives", lists every module and sub-package of
    springdyn/valve by its path below it (``spring/stress.py``, ``engine/``), once, and no others."""
    text = (DOCS / "valve.md").read_text(encoding="utf-8")
    section = text.split("## Where each piece lives", 1)[1].split("\n## ", 1)[0]
    rows = re.findall(r"^\| `([\w/]+(?:\.py|/))` \|", section, flags=re.M)
    assert len(rows) == len(set(rows)), f"listed twice: {sorted({r for r in rows if rows.count(r) > 1})}"
    listed, actual = set(rows), _valve_tree()
    assert {"model.py", "spring/", "spring/chains/", "engine/", "run/simulation.py"} <= actual
    assert listed == actual, (
        f"missing from the guide: {sorted(actual - listed)}; listed but absent: {sorted(listed - actual)}"
    )


# --------------------------------------------------------------------------- tests find the repository through tests/paths.py
TESTS = Path(__file__).resolve().parent
#: The repository's top folders: a string that starts with one of them and a slash is a path
#: relative to the working directory, which holds only when pytest runs from the repository.
REPO_FOLDERS = ("examples", "docs", "src", "tests", "benchmarks", "tools")
_CWD_PATH = re.compile(rf"^(?:\./)?(?:{'|'.join(REPO_FOLDERS)})/\S*$")
#: Calls that make a path of their first argument: a bare folder name there (``Path("docs")``) is one too.
_PATH_CALLS = {"Path", "PurePath", "PosixPath", "open", "join", "from_toml", "read_text"}
#: String methods: their receiver and arguments are text, not paths (``line.startswith("docs/")``).
_TEXT_METHODS = {
    "startswith",
    "endswith",
    "split",
    "rsplit",
    "partition",
    "rpartition",
    "replace",
    "find",
    "rfind",
    "index",
    "rindex",
    "count",
    "removeprefix",
    "removesuffix",
    "strip",
    "lstrip",
    "rstrip",
    "format",
}


def _docstring_nodes(tree: ast.AST) -> set[int]:
    """The ids of the docstrings' string nodes (module, class, function): prose, not paths."""
    ids = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, (ast.Constant, ast.JoinedStr)):
                ids.add(id(first.value))
    return ids


def _literal_text(node: ast.AST) -> str | None:
    """The text of a string literal; of an f-string with each replacement field as ``{}``."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.JoinedStr):
        return "".join(v.value if isinstance(v, ast.Constant) else "{}" for v in node.values)
    return None


def _not_a_path_here(node: ast.AST, parent: ast.AST | None, parents: dict) -> bool:
    """Where a path-like string is no working-directory path: joined onto a base
    (``ROOT / "docs/valve.md"``, ``.joinpath(...)``), compared or searched as text (also as an
    item of a list compared: expected values), a key."""
    if isinstance(parent, ast.BinOp) and isinstance(parent.op, ast.Div) and parent.right is node:
        return True
    outer = parent
    while isinstance(outer, (ast.Tuple, ast.List, ast.Set)):
        outer = parents.get(id(outer))
    if isinstance(outer, ast.Compare):
        return True
    if isinstance(parent, ast.Attribute):  # "docs/x".split(...): a method of the text
        return True
    if isinstance(parent, ast.Call) and isinstance(parent.func, ast.Attribute):
        if parent.func.attr in _TEXT_METHODS | {"joinpath"}:
            return True
    if isinstance(parent, ast.Subscript) and parent.slice is node:
        return True
    return isinstance(parent, ast.Dict) and any(k is node for k in parent.keys)


def _call_name(call: ast.Call) -> str:
    func = call.func
    return func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")


def cwd_relative_paths(source: str) -> list[tuple[int, str]]:
    """(line, text) of every string literal of ``source`` that is a path into the repository
    relative to the working directory: it starts with a top folder (``examples/``, ``docs/``,
    ``src/``, ``tests/``, ``benchmarks/``, ``tools/``) and stands where a path goes (an argument of
    ``open``, ``Path``, ``from_toml``, an argv list, an assignment, ...), or is a bare top folder
    given to a call that makes a path (``Path("docs")``).  Docstrings are prose and comments are
    not in the tree; strings joined onto a base (``ROOT / "docs/x.md"``), compared or searched as
    text, and dictionary keys are no such paths.
    """
    tree = ast.parse(source)
    docstrings = _docstring_nodes(tree)
    parents = {id(child): node for node in ast.walk(tree) for child in ast.iter_child_nodes(node)}
    found = []
    for node in ast.walk(tree):
        text = _literal_text(node)
        parent = parents.get(id(node))
        if text is None or id(node) in docstrings or isinstance(parent, (ast.JoinedStr, ast.FormattedValue)):
            continue  # an f-string's pieces are judged as the whole f-string
        if _CWD_PATH.match(text) and not _not_a_path_here(node, parent, parents):
            found.append((node.lineno, text))
        elif (
            text.rstrip("/") in REPO_FOLDERS
            and isinstance(parent, ast.Call)
            and parent.args[:1] == [node]
            and _call_name(parent) in _PATH_CALLS
        ):
            found.append((node.lineno, text))
    return sorted(found)


def test_tests_find_the_repository_through_tests_paths():
    """No test reads the repository's files by a path relative to the working directory:
    tests/paths.py (ROOT, EXAMPLES, DOCS, example(...)) finds them from any folder."""
    files = sorted(TESTS.rglob("*.py"))
    assert TESTS / "paths.py" in files and len(files) > 50
    offenders = [
        f"{path.relative_to(TESTS.parent).as_posix()}:{line}: {text!r}"
        for path in files
        for line, text in cwd_relative_paths(path.read_text(encoding="utf-8"))
    ]
    assert not offenders, (
        "paths relative to the working directory (use tests/paths.py: ROOT, EXAMPLES, DOCS, example(...)):\n"
        + "\n".join(offenders)
    )


def test_the_path_finder_finds_a_working_directory_path():
    """The check above can fail: it names the line of each such path and passes everything else."""
    source = '''"""A docstring that names docs/valve.md and examples/valve/x.toml: prose."""
from pathlib import Path

from tests.paths import DOCS, ROOT, example


def f(name, text, main, ValveSpring):
    """Nor is tests/paths.py here."""
    open("examples/valve/x.toml")
    main(["valve", "params", "examples/valve/one_step_spring.toml"])
    ValveSpring.from_toml(f"examples/valve/{name}.toml")
    Path("docs")
    SPRING = "./src/springdyn/data/valve_one_step.toml"
    open(ROOT / "examples/valve/x.toml")
    open(example("valve/x.toml"))
    (DOCS / "valve.md").read_text()
    assert "docs/valve.md" in text, f"docs/{name}.md lacks a part"
    text.split("## docs/"), text.startswith("tests/")
    return {"examples/valve/x.toml": 1}["examples/valve/x.toml"], SPRING
'''
    assert cwd_relative_paths(source) == [
        (9, "examples/valve/x.toml"),
        (10, "examples/valve/one_step_spring.toml"),
        (11, "examples/valve/{}.toml"),
        (12, "docs"),
        (13, "./src/springdyn/data/valve_one_step.toml"),
    ]
