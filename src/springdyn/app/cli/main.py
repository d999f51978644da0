"""Entry point of the ``springdyn`` command.

Each model family contributes ``springdyn.<family>.cli.register(subparsers)`` and a
report section (``springdyn.<family>.report``); this module only wires them and
turns springdyn's errors into one line on stderr with exit code 2 (bad input) or 3
(solver failure), never a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import warnings
from pathlib import Path

from springdyn import __version__
from springdyn.core.errors import InputError, SolverError
from . import docs_cmd

#: Model families, in the order the CLI lists them.
FAMILIES = ["valve", "cfcs", "lsd"]


class _Parser(argparse.ArgumentParser):
    """argparse with exit code 2 and a one-line message (argparse's own convention)."""


def _show_warning(message, category, filename, lineno, file=None, line=None):
    print(f"springdyn: warning: {message}", file=sys.stderr)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(
        prog="springdyn",
        description="Dynamics of springs and spring dampers in machines.",
    )
    parser.add_argument("--version", action="version", version=f"springdyn {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    demo = sub.add_parser("demo", help="run every analysis on the built-in examples and write the HTML report")
    demo.add_argument("--out", default="springdyn-demo", help="output folder (default: springdyn-demo)")
    demo.add_argument("--quiet", action="store_true", help="no progress bar, only the final line")
    demo.set_defaults(func=_run_demo)

    rep = sub.add_parser("report", help="the HTML report for your own definitions (any mix of [spring]+[cam], "
                                        "[cfcs], [lsd] TOML files)")
    rep.add_argument("definitions", nargs="+", metavar="FILE.toml")
    rep.add_argument("--out", default="springdyn-report", help="output folder (default: springdyn-report)")
    rep.add_argument("--quiet", action="store_true", help="no progress bar, only the final line")
    rep.set_defaults(func=_run_report)

    for family in FAMILIES:
        importlib.import_module(f"springdyn.app.cli.{family}").register(sub)
    docs_cmd.register(sub)
    return parser


def _report(definitions, out, quiet: bool, title: str, labels=None) -> int:
    from springdyn.app.report import build_report

    page = build_report(definitions, out, quiet=quiet, title=title, labels=labels)
    files = sum(1 for p in Path(out).rglob("*") if p.is_file())
    print(f"springdyn: wrote the report {page.resolve()} ({files} files in {Path(out).resolve()})")
    return 0


def _run_demo(args) -> int:
    from springdyn.app.report.build import DEMO_LABEL, demo_definitions

    paths = demo_definitions()
    return _report(paths, args.out, args.quiet, "springdyn demo: the built-in examples",
                   labels=[DEMO_LABEL.format(p.name) for p in paths])


def _run_report(args) -> int:
    return _report(args.definitions, args.out, args.quiet, "springdyn report")


def main(argv=None) -> int:
    warnings.showwarning = _show_warning
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except InputError as exc:
        print(f"springdyn: error: {exc}", file=sys.stderr)
        return 2
    except SolverError as exc:
        print(f"springdyn: solver failed: {exc}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        print("springdyn: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
