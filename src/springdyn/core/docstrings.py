"""Shared parameter descriptions for numpydoc docstrings: one place for each symbol's meaning.

A module whose functions take the same symbols (the cam speed ``omega``, the lift ``h``, a
spring's ``Do``, ``Dw``, ``N1``, ``N2``) writes each description once in a
:class:`ParameterDocs` table and marks its docstrings with ``{name}`` lines where the entry
belongs; the decorator fills them at import, so ``help()``, the API reference and doctests see
the full numpydoc text.  Only a line that holds nothing but ``{name}`` (or several names,
``{theta2 r2 r3}``, for their entries in that order) is replaced (braces in equations and
examples stay as written), and an unknown name is an error at import, not a hole in the
documentation.  The pattern is MNE-Python's ``fill_doc``/``docdict`` and matplotlib's
``_docstring.interpd``.

Examples
--------
>>> DOCS = ParameterDocs('''
... omega : float
...     Cam speed [rad/s].
... ''')
>>> @DOCS.fill
... def spin(omega):
...     '''Spin [rad/s].
...
...     Parameters
...     ----------
...     {omega}
...     '''
...     return omega
>>> print(spin.__doc__.splitlines()[4])
    omega : float
"""

from __future__ import annotations

import re
import textwrap
from collections.abc import Callable
from typing import TypeVar

__all__ = ["ParameterDocs"]

F = TypeVar("F", bound=Callable)

_PLACEHOLDER = re.compile(
    r"^(?P<indent>[ \t]*)\{(?P<names>[A-Za-z_][A-Za-z0-9_]*(?: [A-Za-z_][A-Za-z0-9_]*)*)\}[ \t]*$", re.MULTILINE
)


def _parse(text: str) -> dict[str, str]:
    """The entries of a numpydoc ``Parameters`` block, by the name of their parameters."""
    lines = textwrap.dedent(text).strip("\n").splitlines()
    entries: dict[str, list[str]] = {}
    for line in lines:
        if line and not line[0].isspace():
            names = line.split(" : ")[0].replace("*", "")
            entries["_".join(n.strip() for n in names.split(","))] = [line]
        elif entries and line.strip():
            entries[next(reversed(entries))].append(line)
    return {name: "\n".join(body) for name, body in entries.items()}


class ParameterDocs:
    """A table of numpydoc parameter entries, ``name -> "name : type\\n    description"``.

    Parameters
    ----------
    text : str
        Entries as they stand under ``Parameters`` (their description lines indented by four
        spaces more); each is named by its parameters joined by ``_`` (``n1, n2 : float`` is
        ``{n1_n2}``) [-].
    **entries : str
        More entries by name, each as it stands under ``Parameters`` at indentation 0 [-].
    """

    def __init__(self, text: str = "", **entries: str) -> None:
        self.entries = {**_parse(text), **{name: entry.strip("\n") for name, entry in entries.items()}}

    def __or__(self, other: ParameterDocs) -> ParameterDocs:
        return ParameterDocs(**self.entries, **other.entries)

    def entry(self, name: str, indent: str = "") -> str:
        """The entry ``name`` with every line indented by ``indent``."""
        try:
            text = self.entries[name]
        except KeyError:
            raise KeyError(f"no shared parameter description {name!r}; have {sorted(self.entries)}") from None
        return "\n".join(indent + line if line else line for line in text.splitlines())

    def fill(self, obj: F) -> F:
        """Decorator: replace each ``{name}`` line of ``obj.__doc__`` by the entry ``name`` (a line
        ``{a b c}`` by the entries ``a``, ``b`` and ``c``)."""
        doc = obj.__doc__
        if doc:
            obj.__doc__ = _PLACEHOLDER.sub(
                lambda m: "\n".join(self.entry(name, m["indent"]) for name in m["names"].split()), doc
            )
        return obj
