"""Build the report from TOML definition files (any mix of model families)."""

from __future__ import annotations

import importlib
from importlib import resources
from pathlib import Path

from springdyn.core.params import load_toml
from springdyn.core.errors import InputError
from springdyn.core.progress import progress
from .html import Section, render_html

__all__ = ["build_report", "demo_definitions", "DEMO_DEFINITIONS", "DEMO_LABEL", "MODEL_TABLES"]

#: Top-level table that makes a definition belong to a family, in report order.
MODEL_TABLES = {"spring": "valve", "cfcs": "cfcs", "lsd": "lsd"}
#: Tables that only complete another one.
SUPPORT_TABLES = {"cam": "spring", "valve_train": "spring"}
#: Built-in definitions of ``springdyn demo`` (shipped in springdyn/data, copies in examples/report).
DEMO_DEFINITIONS = (
    "report_valve_one_step.toml",
    "report_valve_two_step.toml",
    "cfcs_table1.toml",
    "lsd_type_a.toml",
    "lsd_type_b.toml",
    "lsd_type_c.toml",
)


#: Where the built-in definitions are for a user of the repository.
DEMO_LABEL = "examples/report/{}"


def demo_definitions() -> list[Path]:
    """Paths of the built-in example definitions."""
    base = resources.files("springdyn.data")
    return [Path(str(base / name)) for name in DEMO_DEFINITIONS]


def _jobs(paths):
    jobs = []
    for path in paths:
        path = Path(path)
        doc = load_toml(path)
        unknown = [k for k in doc if k not in MODEL_TABLES and k not in SUPPORT_TABLES]
        if unknown:
            allowed = ", ".join(f"[{k}]" for k in (*MODEL_TABLES, *SUPPORT_TABLES))
            raise InputError(f"{path}: unknown table [{unknown[0]}]; a definition holds {allowed}")
        for table, needs in SUPPORT_TABLES.items():
            if table in doc and needs not in doc:
                raise InputError(f"{path}: [{table}] needs a [{needs}] table in the same file")
        families = [(MODEL_TABLES[k], k) for k in MODEL_TABLES if k in doc]
        if not families:
            raise InputError(f"{path}: no model table: give [spring] (valve), [cfcs] or [lsd]")
        jobs += [(family, path, doc) for family, _ in families]
    return jobs


def build_report(paths, out_dir, *, quiet: bool = False, title: str = "springdyn report",
                 subtitle: str = "", labels=None) -> Path:
    """Run every definition's analyses into ``out_dir`` and write ``out_dir/index.html``.

    Every definition is read and validated first, so a bad file fails before any work.
    ``labels`` name the definitions in the page and its commands (default: their paths).
    """
    paths = [Path(p) for p in paths]
    label_of = dict(zip(paths, labels)) if labels is not None else {}
    if not paths:
        raise InputError("give at least one definition file (TOML with [spring], [cfcs] or [lsd])")
    jobs = _jobs(paths)
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    # validate every parameter table before running anything
    modules = {f: importlib.import_module(f"springdyn.app.report.{f}") for f in {j[0] for j in jobs}}
    prepared = [(family, path, modules[family].load(doc, path)) for family, path, doc in jobs]
    sections: list[Section] = []
    used = set()
    for family, path, model in progress(prepared, total=len(prepared), desc="report", quiet=quiet):
        name = f"{family}-{path.stem}"
        k = 2
        while name in used:
            name, k = f"{family}-{path.stem}-{k}", k + 1
        used.add(name)
        sub = out_dir / name
        sub.mkdir(parents=True, exist_ok=True)
        sections.append(modules[family].section(model, source=label_of.get(path, str(path)), out_dir=sub, quiet=quiet))
    return render_html(sections, out_dir / "index.html", title=title,
                       subtitle=subtitle or f"{len(sections)} model definitions: " + ", ".join(s.title for s in sections))
