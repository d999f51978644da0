"""Build the report from TOML definition files (any mix of model families)."""

from __future__ import annotations

import importlib
import multiprocessing
import os
import shutil
import signal
import sys
import tempfile
import warnings
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


#: Most processes the definitions run in, side by side (a 2-core machine's cores).
REPORT_WORKERS = 2

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
    paths,
    out_dir,
    *,
    quiet: bool = False,
    title: str = "springdyn report",
    subtitle: str = "",
    labels=None,
    workers: int = 1,
) -> Path:
    """Run every definition's analyses into ``out_dir`` and write ``out_dir/index.html``.

    Every definition is read and validated first, so a bad file fails before any work.
    ``labels`` name the definitions in the page and its commands (default: their paths).

    The definitions are independent: with ``workers`` above 1 (the CLI's default:
    :data:`REPORT_WORKERS`, at most the machine's cores) they run side by side in that many
    processes, started afresh (a script that calls this with ``workers`` above 1 needs the
    ``if __name__ == "__main__":`` guard of :mod:`multiprocessing`); the default 1 runs them one
    after the other in this process.  Before they start, the engine variants their valve sections run
    are made once each, side by side (:func:`springdyn.app.report.valve.engines`): on a new
    machine they compile there, once, instead of in two sections at the same time.  The page
    and its files are the same either way; the warnings of the sections are given here, in the
    order of the definitions.
    """
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise InputError(f"workers = {workers!r} must be a whole number of at least 1")
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
            page = _build(prepared, modules, work, label_of, quiet, title, subtitle, workers)
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


def _build(prepared, modules, out_dir, label_of, quiet, title, subtitle, workers) -> Path:
    jobs = []
    used = set()
    for family, path, model in prepared:
        name = f"{family}-{path.stem}"
        k = 2
        while name in used:
            name, k = f"{family}-{path.stem}-{k}", k + 1
        used.add(name)
        sub = out_dir / name
        sub.mkdir(parents=True, exist_ok=True)
        jobs.append((family, model, label_of.get(path, str(path)), sub))
    workers = min(workers, len(jobs))
    if workers > 1:
        sections = _side_by_side(jobs, modules, workers, quiet)
    else:
        sections = [
            modules[family].section(model, source=source, out_dir=sub, quiet=quiet)
            for family, model, source, sub in progress(jobs, total=len(jobs), desc="report", quiet=quiet)
        ]
    return render_html(
        sections,
        out_dir / "index.html",
        title=title,
        subtitle=(subtitle + " " if subtitle else "")
        + f"{len(sections)} model definitions: "
        + ", ".join(s.title for s in sections),
    )


def _side_by_side(jobs, modules, workers: int, quiet: bool) -> list[Section]:
    """The sections of ``jobs`` run in ``workers`` processes; their warnings given here, in order.

    First the engine variants the sections run, each once (``engines`` of a family's module),
    so that no two processes compile the same one; then the sections, each in one process
    (quiet inside: the bars of two processes would mix; the report's bar counts the sections).
    """
    jit = sys.modules.get("springdyn.numerics.jit")  # the compile notices: as this process has them
    notices = jit.notices() if jit is not None else True
    pool = multiprocessing.get_context("spawn").Pool(workers, initializer=_worker_start, initargs=(notices,))
    try:
        variants = {}
        with warnings.catch_warnings():  # (a set-up's warnings: the section gives them)
            warnings.simplefilter("ignore")
            for family, model, _, _ in jobs:
                for key, make in getattr(modules[family], "engines", lambda _: [])(model):
                    variants.setdefault(key, make)
        # the valve train's engines first: the longest to compile
        order = sorted(variants, key=lambda key: key[1] != "train")
        made = _each(pool.imap_unordered(_make_engine, [variants[key] for key in order]))
        for _ in progress(made, total=len(order), desc="engines", quiet=quiet):
            pass
        tasks = [(i, family, model, source, sub) for i, (family, model, source, sub) in enumerate(jobs)]
        done = {}
        for i, section, caught in progress(
            _each(pool.imap_unordered(_section_task, tasks)), total=len(jobs), desc="report", quiet=quiet
        ):
            done[i] = (section, caught)
        pool.close()
    except BaseException:
        pool.terminate()
        raise
    finally:
        pool.join()
    for i in range(len(jobs)):
        for message, category, filename, lineno in done[i][1]:
            warnings.warn_explicit(message, category, filename, lineno)
    return [done[i][0] for i in range(len(jobs))]


def _each(results):
    """The results of a pool's ``imap_unordered`` as they come, waiting in short spells: a
    wait without end would not see Ctrl-C (the pool is then ended, the temporary folder removed)."""
    while True:
        try:
            yield results.next(timeout=0.25)
        except multiprocessing.TimeoutError:
            continue
        except StopIteration:
            return


def _worker_start(notices: bool) -> None:
    """A report process: Ctrl-C is its parent's to handle (which then ends it), the compile
    notices as its parent has them."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if not notices:
        from springdyn.numerics import jit  # (numba: imported only to switch them off)

        jit.notices(False)


def _make_engine(make) -> None:
    """Run ``make`` (a short run that compiles an engine variant); its failure is its section's to say."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            make()
        except Exception:  # noqa: BLE001 - the section runs the same model and says what failed
            pass


def _section_task(task):
    """One section in a report process: ``(index, section, warnings)``, each warning once."""
    i, family, model, source, sub = task
    module = importlib.import_module(f"springdyn.app.report.{family}")
    with warnings.catch_warnings(record=True) as caught, direct_outputs():
        warnings.simplefilter("always")
        section = module.section(model, source=source, out_dir=sub, quiet=True)
    seen, kept = set(), []
    for w in caught:
        if (w.category, str(w.message)) not in seen:
            seen.add((w.category, str(w.message)))
            kept.append((w.message, w.category, w.filename, w.lineno))
    return i, section, kept
