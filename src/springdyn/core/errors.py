"""Exceptions raised by springdyn.

Every input problem is an :class:`InputError` (a :class:`ValueError`), whose message
names the field, the value and what is allowed.  A numerical failure is a
:class:`SolverError` that says where (speed, time) and why.  The CLI turns both into
one line on stderr and exit code 2 (input) or 3 (solver), never a traceback.
"""

from __future__ import annotations


class SpringdynError(Exception):
    """Base class of every error springdyn raises on purpose."""


class InputError(SpringdynError, ValueError):
    """Bad input: a field, a file or an option that is missing, malformed or out of range."""


class SolverError(SpringdynError, RuntimeError):
    """A numerical solution failed (NaN, step-size collapse, no convergence)."""


def fmt_value(value, unit: str = "") -> str:
    """Format a number (optionally with its SI unit) for an error message."""
    if isinstance(value, float):
        text = f"{value:.6g}"
    else:
        text = str(value)
    return f"{text} {unit}".strip()
