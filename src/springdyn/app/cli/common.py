"""Helpers shared by the CLI of every model family: quantity options, ranges, output."""

from __future__ import annotations

import argparse
import contextlib
import re
import json
import sys
from pathlib import Path

import numpy as np

from springdyn.core.errors import InputError
from springdyn.core.io import to_jsonable
from springdyn.core.units import to_si

__all__ = [
    "quantity",
    "parse_range",
    "print_json",
    "print_table",
    "add_output_options",
    "existing_file",
    "as_options",
    "close_figure",
]


def quantity(text, unit: str, option: str, *, bare_unit: str | None = None) -> float:
    """Parse a CLI option value with units into SI (``"22mm"`` -> 0.022)."""
    return to_si(text, unit, option, bare_unit=bare_unit)


def parse_range(text: str, unit: str, option: str, *, bare_unit: str | None = None) -> np.ndarray:
    """Parse ``START:STOP:STEP`` (inclusive of STOP when it falls on the grid), or a
    comma-separated list, or one value, into an SI array.

    Examples: ``300:4000:25`` (rpm), ``36mm:40mm:0.5mm``, ``1000,2000,3000``.
    """
    text = str(text).strip()
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise InputError(f"{option} = {text!r} must be START:STOP:STEP, e.g. 300:4000:25")
        start, stop, step = (to_si(p, unit, option, bare_unit=bare_unit) for p in parts)
        if step <= 0:
            raise InputError(f"{option} = {text!r}: the step must be positive")
        if stop < start:
            raise InputError(f"{option} = {text!r} is empty: STOP is below START")
        n = int(np.floor((stop - start) / step + 1e-9)) + 1
        return start + step * np.arange(n)
    values = [to_si(p, unit, option, bare_unit=bare_unit) for p in text.split(",") if p.strip()]
    if not values:
        raise InputError(f"{option} = {text!r} is empty")
    return np.asarray(values, dtype=float)


def existing_file(path: str, option: str) -> Path:
    p = Path(path)
    if not p.is_file():
        raise InputError(f"{option}: {path}: no such file")
    return p


def print_json(data) -> None:
    json.dump(to_jsonable(data), sys.stdout, indent=2)
    sys.stdout.write("\n")


def print_table(rows, headers=("quantity", "value", "unit")) -> None:
    """Print rows of strings as an aligned plain-text table."""
    rows = [tuple(str(c) for c in r) for r in rows]
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(headers)]
    line = "  ".join(h.ljust(w) for h, w in zip(headers, widths))
    print(line)
    print("  ".join("-" * w for w in widths))
    for r in rows:
        print("  ".join(c.ljust(w) for c, w in zip(r, widths)))


def add_output_options(p: argparse.ArgumentParser, *, csv=True, plot=True, json=True) -> None:
    if csv:
        p.add_argument("--csv", metavar="OUT.csv", help="write the table as CSV (SI, unit in column names)")
    if plot:
        p.add_argument("--plot", metavar="OUT.png", help="write the plot as PNG")
    if json:
        p.add_argument("--json", action="store_true", help="print machine-readable JSON (SI) instead of a table")


@contextlib.contextmanager
def as_options(**names):
    """Name CLI options in the library's errors: ``as_options(stop="--to")`` turns an
    :class:`InputError` starting ``stop = 5 mm ...`` into ``--to = 5 mm ...``."""
    try:
        yield
    except InputError as exc:
        text = str(exc)
        for arg, option in names.items():
            new = re.sub(rf"^{re.escape(arg)}(\[\d+\])? = ", rf"{option}\1 = ", text)
            if new != text:
                raise InputError(new) from None
        raise


def close_figure(fig) -> None:
    """Close a matplotlib figure (matplotlib is imported only when a command plots)."""
    from springdyn.core.plotting import plt

    plt.close(fig)
