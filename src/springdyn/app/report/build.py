"""Build the report from TOML definition files (any mix of model families)."""

from __future__ import annotations

import importlib
import os
import shutil
import tempfile
from importlib import resources
from pathlib import Path

from springdyn.core.errors import InputError
from springdyn.core.io import direct_outputs
from springdyn.core.params import load_toml
from springdyn.core.progress import progress

from .html import Section, render_html

__all__ = ["build_report", "demo_definitions", "DEMO_DEFINITIONS", "DEMO_LABEL", "MODEL_TABLES"]

#: Top-level table that makes a definition belong to a family, in report order.
MODEL_TABLES = {"spring": "valve", "cfcs": "cfcs", "lsd": "lsd"}
#: Tables that only complete another one.
SUPPORT_TABLES = {
    "inner_spring": "spring",
    "third_spring": "spring",
    "pack": "spring",
    "damper": "spring",
    "cam": "spring",
    "timing": "spring",
    "valve_train": "spring",
    "hla": "spring",
    "follower": "spring",
    "geometry": "spring",
    "friction": "spring",
    "oil": "spring",
    "piston": "spring",
    "report": "spring",
}
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


def build_report(
    paths, out_dir, *, quiet: bool = False, title: str = "springdyn report", subtitle: str = "", labels=None
) -> Path:
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
    # validate every parameter table before running anything
    modules = {f: importlib.import_module(f"springdyn.app.report.{f}") for f in {j[0] for j in jobs}}
    prepared = [(family, path, modules[family].load(doc, path)) for family, path, doc in jobs]
    # build in a temporary folder beside out_dir and swap it in at the end: the report's files
    # appear together or not at all (an interrupted build leaves the previous report as it was)
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.", dir=out_dir.parent))
    try:
        with direct_outputs():
            page = _build(prepared, modules, work, label_of, quiet, title, subtitle)
        _swap_in(work, out_dir)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    return out_dir / page.name


def _swap_in(work: Path, out_dir: Path) -> None:
    """Put the finished folder ``work`` in place of ``out_dir`` (kept files of other programs stay)."""
    os.chmod(work, 0o777 & ~_umask())
    if out_dir.is_dir():
        old = Path(tempfile.mkdtemp(prefix=f".{out_dir.name}.old.", dir=out_dir.parent))
        # move what springdyn writes aside, then the new files in; a user's own files stay
        for item in work.iterdir():
            target = out_dir / item.name
            if target.exists():
                os.replace(target, old / item.name)
            os.replace(item, target)
        shutil.rmtree(old, ignore_errors=True)
        work.rmdir()
    else:
        os.replace(work, out_dir)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def _build(prepared, modules, out_dir, label_of, quiet, title, subtitle) -> Path:
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
    return render_html(
        sections,
        out_dir / "index.html",
        title=title,
        subtitle=(subtitle + " " if subtitle else "")
        + f"{len(sections)} model definitions: "
        + ", ".join(s.title for s in sections),
    )
