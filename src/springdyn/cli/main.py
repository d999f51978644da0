"""Entry point of the ``springdyn`` command.

Each model family contributes ``springdyn.<family>.cli.register(subparsers)`` and
``springdyn.<family>.demo.run(out_dir, quiet=...)``; this module only wires them and
turns springdyn's errors into one line on stderr with exit code 2 (bad input) or 3
(solver failure), never a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import warnings
from pathlib import Path

from .. import __version__
from ..errors import InputError, SolverError

#: Model families, in the order the CLI lists them and the demo runs them.
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

    demo = sub.add_parser("demo", help="run every analysis on the built-in examples and write a report folder")
    demo.add_argument("--out", default="springdyn-demo", help="output folder (default: springdyn-demo)")
    demo.add_argument("--quiet", action="store_true", help="no progress bar, only the final line")
    demo.set_defaults(func=_run_demo)

    for family in FAMILIES:
        importlib.import_module(f"springdyn.{family}.cli").register(sub)
    return parser


def _run_demo(args) -> int:
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for family in FAMILIES:
        mod = importlib.import_module(f"springdyn.{family}.demo")
        fam_dir = out / family
        fam_dir.mkdir(parents=True, exist_ok=True)
        if not args.quiet:
            print(f"springdyn demo: {family} ...", file=sys.stderr)
        written += mod.run(fam_dir, quiet=args.quiet)
    print(f"springdyn demo: wrote {len(written)} files to {out.resolve()}")
    if not args.quiet:
        for p in written:
            print(f"  {p}")
    return 0


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
