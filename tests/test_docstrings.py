"""Docstrings of the physics: every public function of the family packages has a
numpydoc ``Parameters`` section whose numeric entries give their unit in brackets
(``Mean coil diameter [m].``; ``[-]`` for dimensionless), and no docstring cites a file
outside the repository (the reading notes and source documents are cited through
docs/references.md)."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import re

import pytest

FAMILIES = ("valve", "cfcs", "lsd")
#: Types whose entries need a unit in brackets.
NUMERIC = re.compile(r"\b(float|int|array|ndarray|array_like|array-like|number|scalar)\b")
ENTRY = re.compile(r"^(\w[\w, *]*?)\s*:\s*(.*)$")
OUTSIDE = re.compile(r"READING-NOTES|[Rr]eading notes|shared/seeds|seeds/|\.txt\b|\bnotes \d")


def _modules(family):
    pkg = importlib.import_module(f"springdyn.{family}")
    names = [f"springdyn.{family}"] + [m.name for m in pkgutil.walk_packages(pkg.__path__, f"springdyn.{family}.")]
    return [importlib.import_module(n) for n in sorted(names)]


def _public_functions(family):
    seen = {}
    for module in _modules(family):
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name, None)
            if inspect.isfunction(obj) and obj.__module__.startswith(f"springdyn.{family}"):
                seen[f"{obj.__module__}.{obj.__name__}"] = obj
    return sorted(seen.items())


def _parameters_section(doc: str) -> list[tuple[str, str, str]]:
    lines = inspect.cleandoc(doc).splitlines()
    try:
        start = next(
            i
            for i, l in enumerate(lines)
            if l.strip() == "Parameters" and i + 1 < len(lines) and set(lines[i + 1].strip()) == {"-"}
        )
    except StopIteration:
        return []
    entries, i = [], start + 2
    while i < len(lines):
        line = lines[i]
        if line.strip() and i + 1 < len(lines) and set(lines[i + 1].strip() or "x") == {"-"}:
            break  # next section
        m = ENTRY.match(line) if line and not line[0].isspace() else None
        if m:
            desc = []
            j = i + 1
            while j < len(lines) and (not lines[j] or lines[j][0].isspace()):
                desc.append(lines[j].strip())
                j += 1
            entries.append((m.group(1), m.group(2), " ".join(desc)))
            i = j
        else:
            i += 1
    return entries


@pytest.mark.parametrize("family", FAMILIES)
def test_public_physics_functions_document_parameters_with_units(family):
    problems = []
    for qualname, func in _public_functions(family):
        params = [
            p for p in inspect.signature(func).parameters.values() if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
        ]
        if not params:
            continue
        entries = _parameters_section(func.__doc__ or "")
        if not entries:
            problems.append(f"{qualname}: no numpydoc Parameters section")
            continue
        documented = {n.strip() for names, _, _ in entries for n in names.split(",")}
        missing = [p.name for p in params if p.name not in documented]
        if missing:
            problems.append(f"{qualname}: parameters not documented: {', '.join(missing)}")
        for names, typ, desc in entries:
            if NUMERIC.search(typ) and not re.search(r"\[[^\]]*\]", desc):
                problems.append(f"{qualname}: parameter {names!r} ({typ}) gives no [unit] in its description")
    assert not problems, f"{len(problems)} docstring problems:\n" + "\n".join(problems)


@pytest.mark.parametrize("family", FAMILIES)
def test_docstrings_cite_nothing_outside_the_repository(family):
    bad = []
    for module in _modules(family):
        for name, obj in [(module.__name__, module), *inspect.getmembers(module)]:
            doc = getattr(obj, "__doc__", None) or ""
            if (obj is module or getattr(obj, "__module__", "") == module.__name__) and OUTSIDE.search(doc):
                bad.append(f"{module.__name__}.{name}")
    assert not bad, "docstrings citing files outside the repository: " + ", ".join(sorted(set(bad)))


def test_the_parameters_parser_reads_numpydoc():
    """The check can fail: a docstring without units is caught."""

    def f(x, name):
        """Do.

        Parameters
        ----------
        x : float
            Length.
        name : str
            A name.
        """

    entries = _parameters_section(f.__doc__)
    assert [(n, t) for n, t, _ in entries] == [("x", "float"), ("name", "str")]
    assert not re.search(r"\[[^\]]*\]", entries[0][2])


def _public_methods(family):
    seen = {}
    for module in _modules(family):
        for name in getattr(module, "__all__", []):
            cls = getattr(module, name, None)
            if not (inspect.isclass(cls) and cls.__module__ == module.__name__):
                continue
            for mname, member in vars(cls).items():
                if mname.startswith("_"):
                    continue
                if isinstance(member, (staticmethod, classmethod)):
                    member = member.__func__
                if inspect.isfunction(member):
                    seen[f"{cls.__module__}.{cls.__name__}.{mname}"] = member
    return sorted(seen.items())


@pytest.mark.parametrize("family", FAMILIES)
def test_public_methods_document_their_parameters(family):
    """Every public method of a public class documents each parameter (numpydoc), with a unit
    in brackets for numbers, and documents no parameter it does not have."""
    problems = []
    for qualname, func in _public_methods(family):
        params = [
            p.name
            for p in inspect.signature(func).parameters.values()
            if p.name not in ("self", "cls") and p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD)
        ]
        entries = _parameters_section(func.__doc__ or "")
        documented = {n.strip() for names, _, _ in entries for n in names.split(",")}
        documented.discard("**extra")
        if params and not entries:
            problems.append(f"{qualname}: no numpydoc Parameters section")
            continue
        missing = [p for p in params if p not in documented]
        extra = sorted(documented - set(params) - {"**options", "**kwargs", "*args"})
        if missing:
            problems.append(f"{qualname}: parameters not documented: {', '.join(missing)}")
        if extra:
            problems.append(f"{qualname}: documents parameters it does not have: {', '.join(extra)}")
        for names, typ, desc in entries:
            if NUMERIC.search(typ) and not re.search(r"\[[^\]]*\]", desc):
                problems.append(f"{qualname}: parameter {names!r} ({typ}) gives no [unit] in its description")
    assert not problems, f"{len(problems)} docstring problems:\n" + "\n".join(problems)
