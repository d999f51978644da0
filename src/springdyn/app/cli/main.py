"""Entry point of the ``springdyn`` command.

Each model family contributes ``springdyn.app.cli.<family>.register(subparsers)`` and a
report section (``springdyn.app.report.<family>``); this module only wires them (loading
only the family a command needs) and turns every outcome into one line on stderr and an
exit code: 2 bad input, 3 solver failure, 70 a bug (traceback in a log file), 74 the
output could not be written, never a traceback.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import os
import re
import signal
import sys
import warnings
from pathlib import Path

from springdyn import __version__
from springdyn.core.errors import InputError, SolverError, plain_numbers
from springdyn.core.io import NonFiniteOutputError, check_output_file, check_output_folder, output_set

from . import docs_cmd
from .common import whole_number

#: Model families, in the order the CLI lists them, with their help line (the family's
#: ``register`` uses the same line; a test checks it).
FAMILIES = {
    "valve": "valve springs: MMS Type C multi-mass model",
    "cfcs": "constant-force compression springs (pseudo-rigid-body model)",
    "lsd": "leaf spring dampers: coefficients, rig simulation, identification",
}


class UsageError(Exception):
    """A command line argparse cannot read (one line, exit code 2)."""


class _Parser(argparse.ArgumentParser):
    """argparse whose errors are one line (usage only with ``--help``) and exit code 2."""

    def error(self, message):
        where = "" if self.prog == "springdyn" else f"{self.prog}: "  # (the line starts 'springdyn: error:')
        raise UsageError(f"{where}{message} (see '{self.prog} --help')")


#: Warnings of the running command: printed when it succeeds; when it fails, its one-line
#: error is all that is printed (bad input gets one message).  Each entry is the warning's
#: key (a :class:`~springdyn.core.errors.FactWarning`'s fact, else ``""``) and its line.
_PENDING_WARNINGS: list[tuple[str, str]] = []


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """Keep a warning of the running command: once per text, and once per fact (its key)."""
    text = f"springdyn: warning: {plain_numbers(str(message))}"
    key = str(getattr(message, "key", "") or "")
    if any(t == text or (key and k == key) for k, t in _PENDING_WARNINGS):
        return  # said already: the same text, or the same fact reached by another path
    _PENDING_WARNINGS.append((key, text))


def _flush_warnings(stated=()) -> None:
    """Print the kept warnings on stderr, but not a fact the printed result states as a note.

    Parameters
    ----------
    stated : iterable of str
        The ``note: ...`` lines the command printed on standard output [-].
    """
    notes = [n.lower() for n in stated]
    for key, text in _PENDING_WARNINGS:
        if key and any(n.startswith(f"note: {key.split('|')[0].lower()}") for n in notes):
            continue  # the result said it (``note: coil bind: ...``): once per command
        print(text, file=sys.stderr)
    _PENDING_WARNINGS.clear()


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The ``springdyn`` parser.

    Parameters
    ----------
    only : str, optional
        Build the sub-commands of this family only (the others are listed with their help
        line): ``springdyn --help`` and a command of one family then load no other family.
        ``""`` builds no family's sub-commands; ``None`` (the default) builds them all.
    """
    parser = _Parser(
        prog="springdyn",
        description="Dynamics of springs and spring dampers in machines.",
        epilog="Quantities take units ('22 mm', '3000 rpm', '5 %'); bare numbers are SI unless an option says "
        "otherwise. Ranges are START:STOP:STEP, lists a,b,c. Exit codes: 0 done, 2 bad input, "
        "3 solver failure, 70 a bug in springdyn (the traceback in a log file named on stderr), 74 an output "
        "that cannot be written (disk full, closed pipe), 130 interrupted.",
    )
    parser.add_argument("--version", action="version", version=f"springdyn {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    demo = sub.add_parser("demo", help="run every analysis on the built-in examples and write the HTML report")
    demo.add_argument("--out", default="springdyn-demo", help="output folder (default: springdyn-demo)")
    demo.add_argument("--quiet", action="store_true", help="no progress bar, only the final line")
    demo.add_argument("--workers", metavar="N", help=WORKERS_HELP)
    demo.set_defaults(func=_run_demo)

    rep = sub.add_parser(
        "report", help="the HTML report for your own definitions (any mix of [spring]+[cam], [cfcs], [lsd] TOML files)"
    )
    rep.add_argument("definitions", nargs="+", metavar="FILE.toml")
    rep.add_argument("--out", default="springdyn-report", help="output folder (default: springdyn-report)")
    rep.add_argument("--quiet", action="store_true", help="no progress bar, only the final line")
    rep.add_argument("--workers", metavar="N", help=WORKERS_HELP)
    rep.set_defaults(func=_run_report)

    for family, help_line in FAMILIES.items():
        if only is None or only == family:
            importlib.import_module(f"springdyn.app.cli.{family}").register(sub)
        else:
            sub.add_parser(family, help=help_line, add_help=False)
    docs_cmd.register(sub)
    _add_quiet(parser)
    return parser


def _add_quiet(parser: argparse.ArgumentParser) -> None:
    """Give every command that has none a ``--quiet`` (no compile notice on stderr)."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for child in action.choices.values():
                if child.add_help:  # (not a placeholder of a family that is not loaded)
                    _add_quiet(child)
            return
    if "--quiet" not in parser._option_string_actions:
        parser.add_argument("--quiet", action="store_true", help="no notice on stderr while an engine compiles")


#: The help of the report's ``--workers``.
WORKERS_HELP = (
    "processes the definitions run in, side by side (default: 2, both cores of a 2-core machine; 1: one by one)"
)


def _report(args, definitions, title: str, labels=None, subtitle: str = "") -> int:
    from springdyn.app.report.build import REPORT_WORKERS, build_report

    if args.workers is None:
        workers = min(os.cpu_count() or 1, REPORT_WORKERS)
    else:
        workers = whole_number(args.workers, "--workers", 1, 64, "from 1 to 64")
    out, quiet = args.out, args.quiet
    page = build_report(definitions, out, quiet=quiet, title=title, labels=labels, subtitle=subtitle, workers=workers)
    files = sum(1 for p in Path(out).rglob("*") if p.is_file())
    print(f"springdyn: wrote the report {page.resolve()} ({files} files in {Path(out).resolve()})")
    return 0


#: What the demo's fails mean.
DEMO_NOTE = (
    "The built-in examples are the source documents' springs, not designs for an engine: they fail some "
    "criteria on purpose (the surge margin at 8000 engine rpm, coil clash, fatigue) to show what the report "
    "says when a spring does not hold. Give your own definition a [report] table for your engine."
)


def _run_demo(args) -> int:
    from springdyn.app.report.build import DEMO_LABEL, demo_definitions

    paths = demo_definitions()
    return _report(
        args,
        paths,
        "springdyn demo: the built-in examples",
        subtitle=DEMO_NOTE,
        labels=[DEMO_LABEL.format(p.name) for p in paths],
    )


def _run_report(args) -> int:
    return _report(args, args.definitions, "springdyn report")


def _join_negative_values(argv) -> list[str]:
    """``--lift -1mm`` -> ``--lift=-1mm``: a value starting with a minus sign and a digit (or
    ``-inf``, ``-nan``) reaches the option's validator instead of being taken for an option by
    argparse.  A bare ``--`` (argparse's end of options) is refused with its own message:
    no springdyn argument starts with a minus sign, and argparse would report it as a
    missing value or an unrecognized argument."""
    out: list[str] = []
    for token in argv:
        if token == "--":
            after = f" after {out[-1]}" if out and out[-1].startswith("-") and "=" not in out[-1] else ""
            raise UsageError(
                f"springdyn: a bare '--'{after} is not an argument springdyn takes: no file or value of it "
                "starts with '-'; remove it (a negative value is written --option=-1)"
            )
        if (
            out
            and re.match(r"^-(\.?\d|inf|nan|infinity)", token, re.IGNORECASE)
            and out[-1].startswith("--")
            and "=" not in out[-1]
        ):
            out[-1] = f"{out[-1]}={token}"
        else:
            out.append(token)
    return out


#: Options that name an output file, and options that name an output folder.
OUTPUT_FILE_OPTIONS = ("csv", "plot", "toml", "netcdf", "json_out")
OUTPUT_FOLDER_OPTIONS = ("out",)


def check_outputs(args) -> None:
    """Check every output file and folder option before any work is done."""
    for name in OUTPUT_FILE_OPTIONS:
        value = getattr(args, name, None)
        if isinstance(value, str):
            check_output_file(value, f"--{name.replace('_', '-')}")
    for name in OUTPUT_FOLDER_OPTIONS:
        value = getattr(args, name, None)
        if isinstance(value, str):
            check_output_folder(value, f"--{name}")


def _family_of(argv) -> str:
    """The family whose sub-commands a command line needs (``""``: none)."""
    for token in argv:
        if not token.startswith("-"):
            return token if token in FAMILIES else ""
    return ""


def _write_bug_log(exc: BaseException) -> Path | None:
    """Write the traceback of an unexpected exception to a log file; return its path."""
    import tempfile
    import time
    import traceback

    try:
        fd, name = tempfile.mkstemp(prefix=f"springdyn-bug-{time.strftime('%Y%m%d-%H%M%S')}-", suffix=".log")
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(f"springdyn {__version__}, Python {sys.version.split()[0]}\n")
            fh.write("command line: springdyn " + " ".join(sys.argv[1:]) + "\n\n")
            traceback.print_exception(type(exc), exc, exc.__traceback__, file=fh)
        return Path(name)
    except OSError:
        return None


def _silence_stdout() -> None:
    """After stdout broke, point it at /dev/null so that the interpreter's final flush is quiet."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError, AttributeError):
        pass


class StdoutError(OSError):
    """Standard output is closed, full or broken."""


class _GuardedStdout:
    """Standard output whose write failures become :class:`StdoutError` (exit 74)."""

    def __init__(self, stream):
        self._stream = stream
        self.failed = False
        self.notes: list[str] = []

    def _call(self, name, *args):
        if self._stream is None:
            self.failed = True
            raise StdoutError("standard output is closed")
        try:
            return getattr(self._stream, name)(*args)
        except (OSError, ValueError) as exc:
            self.failed = True
            raise StdoutError(getattr(exc, "strerror", None) or str(exc)) from exc

    def write(self, text):
        if "note: " in text:  # a fact the result states: its warning is not repeated on stderr
            self.notes.extend(line.strip() for line in text.splitlines() if line.strip().startswith("note: "))
        return self._call("write", text)

    def flush(self):
        return self._call("flush")

    def __getattr__(self, name):
        return getattr(self._stream, name)


class _Terminated(BaseException):
    """SIGTERM: unwind (so that temporary outputs are removed), then exit 143."""


def _on_sigterm(signum, frame):
    raise _Terminated()


#: Exit codes (sysexits.h where one fits).
EXIT_INPUT, EXIT_SOLVER, EXIT_BUG, EXIT_IO, EXIT_INTERRUPTED = 2, 3, 70, 74, 130


@contextlib.contextmanager
def _compile_notices(on: bool):
    """The one-line compile notices of the engines on stderr, off under ``--quiet``."""
    if on:
        yield
        return
    from springdyn.numerics import jit  # (numba: imported only when it is switched off)

    old = jit.notices(False)
    try:
        yield
    finally:
        jit.notices(old)


def main(argv=None) -> int:
    """Run ``springdyn`` with ``argv`` (default: the process's); return the exit code.

    0 done; 2 bad input (one line on stderr); 3 solver failure; 70 an unexpected error,
    i.e. a bug in springdyn (one line on stderr, the traceback in a log file); 74 the
    output could not be written (e.g. stdout is full or closed); 130 interrupted.
    """
    argv = sys.argv[1:] if argv is None else list(argv)
    warnings.showwarning = _show_warning
    real_stdout = sys.stdout
    sys.stdout = _GuardedStdout(real_stdout)
    try:
        previous = signal.signal(signal.SIGTERM, _on_sigterm)
    except ValueError:  # not the main thread
        previous = None
    try:
        argv = _join_negative_values(argv)
        parser = build_parser(_family_of(argv))
        args = parser.parse_args(argv)
        check_outputs(args)
        with output_set(), _compile_notices(not getattr(args, "quiet", False)):
            # every file of the command is renamed into place together, at the end
            code = int(args.func(args) or 0)
        sys.stdout.flush()
        _flush_warnings(getattr(sys.stdout, "notes", ()))
        return code
    except (UsageError, InputError) as exc:
        print(f"springdyn: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except SolverError as exc:
        print(f"springdyn: solver failed: {exc}", file=sys.stderr)
        return EXIT_SOLVER
    except NonFiniteOutputError as exc:
        print(
            f"springdyn: solver failed: the result holds a value that is not a finite number ({exc}); "
            "no output was written",
            file=sys.stderr,
        )
        return EXIT_SOLVER
    except (KeyboardInterrupt, _Terminated) as exc:
        print("springdyn: interrupted; no partial output was left", file=sys.stderr)
        return 143 if isinstance(exc, _Terminated) else EXIT_INTERRUPTED
    except (StdoutError, BrokenPipeError) as exc:
        _silence_stdout()
        if not isinstance(exc.__cause__, BrokenPipeError) and not isinstance(exc, BrokenPipeError):
            print(f"springdyn: cannot write to standard output: {exc.strerror or exc}", file=sys.stderr)
        return EXIT_IO
    except OSError as exc:  # the environment, not springdyn: e.g. a disk that is full
        print(f"springdyn: cannot write {exc.filename or 'an output'}: {exc.strerror or exc}", file=sys.stderr)
        return EXIT_IO
    except SystemExit as exc:  # --help and --version (argparse ignores write errors: the guard saw them)
        try:
            sys.stdout.flush()
        except OSError:
            pass
        if getattr(sys.stdout, "failed", False):
            _silence_stdout()
            return EXIT_IO
        return int(exc.code or 0) if not isinstance(exc.code, str) else EXIT_INPUT
    except Exception as exc:  # noqa: BLE001 - the safety net: a bug, said in one line
        return _bug(exc)
    finally:
        _PENDING_WARNINGS.clear()
        sys.stdout = real_stdout
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


def _bug(exc: BaseException) -> int:
    log = _write_bug_log(exc)
    where = f"the traceback is in {log}" if log else "no log file could be written"
    print(
        f"springdyn: internal error (a bug in springdyn, please report it): {type(exc).__name__}: "
        f"{str(exc).splitlines()[0] if str(exc) else ''}; {where}",
        file=sys.stderr,
    )
    return EXIT_BUG


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
