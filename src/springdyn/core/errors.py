"""Exceptions raised by springdyn.

Every input problem is an :class:`InputError` (a :class:`ValueError`), whose message
names the field, the value and what is allowed.  A numerical failure is a
:class:`SolverError` that says where (speed, time) and why.  The CLI turns both into
one line on stderr and exit code 2 (input) or 3 (solver), never a traceback.

A warning about one fact that several paths may reach (the coil-bind clearance is checked
by the spring's design figures and by every run's set-up) is a :class:`FactWarning` named
by its ``key``: a command shows it once.
"""

from __future__ import annotations

import re

#: A number written with float noise: more than 9 significant digits after the decimal point
#: (``0.30000000000000004``, ``5.545454545454547``) or a float's ``.0`` on a long integer
#: (``1000000000.0``), not inside a word, a path or a longer number.
_NOISY_NUMBER = re.compile(r"(?<![\w./-])[-+]?(?:\d+\.\d{9,}|\d{7,}\.0)(?:[eE][-+]?\d+)?(?![\w.])")


def plain_numbers(text: str) -> str:
    """A message's echoed values with 6 significant digits: float noise removed.

    The one home of how a message shows a value it echoes (every :class:`SpringdynError`
    passes its message through it).

    Parameters
    ----------
    text : str
        The message [-].

    Examples
    --------
    >>> plain_numbers("x = 0.30000000000000004 m, ratio 5.545454545454547, 1000000000.0 rpm, 0.25 mm")
    'x = 0.3 m, ratio 5.54545, 1e+09 rpm, 0.25 mm'
    """
    return _NOISY_NUMBER.sub(lambda m: fmt_value(float(m.group(0))), text)


class SpringdynError(Exception):
    """Base class of every error springdyn raises on purpose.

    Its message echoes values with 6 significant digits (:func:`plain_numbers`): a value read
    in SI and converted back is shown as the user wrote it, not as ``0.30000000000000004``.
    """

    def __init__(self, *args):
        if len(args) == 1 and isinstance(args[0], str):
            args = (plain_numbers(args[0]),)
        super().__init__(*args)


class InputError(SpringdynError, ValueError):
    """Bad input: a field, a file or an option that is missing, malformed or out of range."""


class SolverError(SpringdynError, RuntimeError):
    """A numerical solution failed (NaN, step-size collapse, no convergence)."""


class FactWarning(UserWarning):
    """A warning about one fact, named by ``key``, that several paths of one command may reach.

    The CLI prints the first warning of a command with a key and drops the others with the
    same key (the coil-bind check of the design figures and that of a run's set-up say the
    same thing in other words), and drops it too when the command's printed result already
    states the fact as a note (``note: <key>: ...``).

    Parameters
    ----------
    message : str
        The warning's text [-].
    key : str
        The fact it is about: its topic, as its text and its notes begin (``"coil bind"``),
        and after a ``|`` what it is about (``"coil bind|<the spring>"``: two springs are two
        facts) [-].
    """

    def __init__(self, message: str, key: str = ""):
        super().__init__(message)
        self.key = key


def fmt_value(value, unit: str = "") -> str:
    """Format a number (optionally with its SI unit) for an error message."""
    if isinstance(value, float):
        text = f"{value:.6g}"
    else:
        text = str(value)
    return f"{text} {unit}".strip()
