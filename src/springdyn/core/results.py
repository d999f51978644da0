"""The base of every analysis result of every model family.

A :class:`Result` offers one interface:

- ``.summary``: a dict of SI figures under keys ``<quantity>_<unit>`` (``peak_force_N``);
- ``.to_xarray()``: the data as an :class:`xarray.Dataset`, the single source of the
  variable names and units (``attrs["units"]``);
- ``.to_csv(path)``: a table derived from :meth:`Result.to_xarray` (column
  ``<name>_<unit>``), written atomically;
- ``.to_dataframe()``: the same table as a :class:`pandas.DataFrame` (the CSV's columns);
- ``.plot(path=None, ax=None)``: returns the figure; with a path it writes that PNG file
  (never a folder);
- a ``repr`` of at most 15 lines and ``_repr_html_`` (the summary as a table, plus a small
  figure where it is cheap) for notebooks.

A subclass implements :meth:`Result._summary`, :meth:`Result.to_xarray` and
:meth:`Result._plot`.  Nothing here imports xarray or matplotlib until it is needed.
"""

from __future__ import annotations

import base64
import html
import io as _io
import math
import numbers
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any, ClassVar

import numpy as np

from .errors import InputError

__all__ = [
    "Result",
    "Summary",
    "unit_suffix",
    "units_from_name",
    "column_name",
    "dataset_columns",
    "format_value",
    "text_table",
    "notes_lines",
]

#: Lines of a result's ``repr`` at most (header and footer included).
REPR_LINES = 15


class Summary(dict):
    """A result's summary: SI figures under keys ``<quantity>_<unit>``.

    It is a plain :class:`dict`; calling it (the older ``result.summary()`` API) returns
    itself with a :class:`DeprecationWarning`.
    """

    def __call__(self) -> Summary:
        warnings.warn(
            "summary() is deprecated: summary is now an attribute (result.summary)", DeprecationWarning, stacklevel=2
        )
        return self


_UNIT_SUFFIX = {"": "", "1": "", "-": "", "%": "percent", "percent": "percent"}


def unit_suffix(units: str | None) -> str:
    """The suffix a unit gives a column or key name.

    Examples
    --------
    >>> unit_suffix("N/m"), unit_suffix("N*s/m"), unit_suffix("m^3"), unit_suffix("1")
    ('N_per_m', 'N_s_per_m', 'm3', '')
    """
    units = (units or "").strip()
    if units in _UNIT_SUFFIX:
        return _UNIT_SUFFIX[units]
    num, _, den = units.partition("/")
    clean = [p.replace("^", "").replace("**", "").strip() for p in num.replace(" ", "*").split("*") if p.strip()]
    out = "_".join(clean)
    if den:
        out += "_per_" + "_".join(p.replace("^", "").strip() for p in den.replace(" ", "*").split("*") if p.strip())
    return out


_SUFFIX_UNITS = {
    "N": "N",
    "m": "m",
    "s": "s",
    "Pa": "Pa",
    "Hz": "Hz",
    "kg": "kg",
    "deg": "deg",
    "rad": "rad",
    "rpm": "rpm",
    "percent": "%",
    "N_per_m": "N/m",
    "N_s_per_m": "N*s/m",
    "m_per_s": "m/s",
    "rad_per_s": "rad/s",
    "J": "J",
    "W": "W",
}


def units_from_name(name: str) -> str:
    """The unit a ``<quantity>_<unit>`` name carries (``"1"`` when it names none).

    >>> units_from_name("max_retainer_force_N"), units_from_name("rate_N_per_m"), units_from_name("periodic")
    ('N', 'N/m', '1')
    """
    for suffix in sorted(_SUFFIX_UNITS, key=len, reverse=True):
        if name.endswith("_" + suffix):
            return _SUFFIX_UNITS[suffix]
    return "1"


def column_name(name: str, units: str | None) -> str:
    """``name_<unit>`` unless the name already ends with the unit's suffix.

    >>> column_name("force", "N"), column_name("force_N", "N"), column_name("pcf", "%")
    ('force_N', 'force_N', 'pcf_percent')
    """
    suffix = unit_suffix(units)
    if not suffix or name.endswith("_" + suffix) or name == suffix:
        return name
    return f"{name}_{suffix}"


def dataset_columns(ds) -> dict[str, np.ndarray]:
    """Columns of a table derived from a one-dimensional-in-rows :class:`xarray.Dataset`.

    The dataset's first dimension gives the rows.  Its coordinates come first, then the
    data variables in order.  A variable with a second dimension becomes one column per
    index: named from its ``csv_columns`` attribute (comma-separated) when present, else
    ``<name>_<label>``.  Each name takes its unit suffix (:func:`column_name`); a
    variable whose attribute ``csv`` is ``"no"`` is left out.
    """
    if not ds.dims:
        return {column_name(k, v.attrs.get("units")): np.atleast_1d(v.values) for k, v in ds.data_vars.items()}
    row_dim = next(iter(ds.dims))
    cols: dict[str, np.ndarray] = {}
    for name, var in [*ds.coords.items(), *ds.data_vars.items()]:
        if var.attrs.get("csv") == "no" or row_dim not in var.dims:
            continue
        units = var.attrs.get("units")
        if var.ndim == 1:
            cols[column_name(str(name), units)] = np.asarray(var.values)
            continue
        other = [d for d in var.dims if d != row_dim]
        flat = var.transpose(*other, row_dim).values.reshape(-1, ds.sizes[row_dim])
        names = var.attrs.get("csv_columns")
        if names:
            labels = [n.strip() for n in str(names).split(",")]
        else:
            index = var.coords[other[0]].values if len(other) == 1 and other[0] in var.coords else range(flat.shape[0])
            labels = [column_name(f"{name}_{lab}", units) for lab in index]
        for label, values in zip(labels, flat):
            cols[label] = values
    return cols


def format_value(value: Any, digits: int = 5) -> str:
    """A summary value for people: numbers to ``digits`` significant digits.

    >>> format_value(499.64271), format_value(True), format_value(None)
    ('499.64', 'yes', 'n/a')
    """
    if value is None:
        return "n/a"
    if isinstance(value, (bool, np.bool_)):
        return "yes" if value else "no"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        v = float(value)
        return f"{v:.{digits}g}" if math.isfinite(v) else "n/a"
    if isinstance(value, (list, tuple)):
        text = ", ".join(format_value(v, digits) for v in value[:4])
        return f"[{text}{', ...' if len(value) > 4 else ''}] ({len(value)})"
    if isinstance(value, Mapping):
        return f"{{{len(value)} entries}}"
    text = str(value)
    return text if len(text) <= 60 else text[:57] + "..."


class _SummaryAttribute:
    """``result.summary``: built once from ``_summary()`` and cached on the instance.

    A non-data descriptor, so that a result class that stores its summary itself (a
    dataclass field named ``summary``) keeps working: the instance's own value wins.  It
    is invisible on the class (``getattr(cls, "summary")`` raises), so that such a field
    gets no default.
    """

    def __get__(self, obj, objtype=None):
        if obj is None:
            raise AttributeError("summary is an attribute of a result, not of its class")
        cached = obj.__dict__.get("_summary_cache")
        if cached is None:
            cached = Summary(obj._summary())
            object.__setattr__(obj, "_summary_cache", cached)
        return cached


def text_table(rows, headers=("quantity", "value", "unit")) -> str:
    """Rows of values as an aligned plain-text table (headers, a rule, the rows).

    Parameters
    ----------
    rows : iterable of sequence
        The rows; each cell is shown with ``str``.
    headers : sequence of str
        The column headers.

    Examples
    --------
    >>> print(text_table([("a", 1), ("bb", 22)], headers=("name", "n")))
    name  n
    ----  --
    a     1
    bb    22
    """
    rows = [tuple(str(c) for c in r) for r in rows]
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(headers)]
    lines = ["  ".join(h.ljust(w) for h, w in zip(headers, widths)).rstrip(), "  ".join("-" * w for w in widths)]
    lines += ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
    return "\n".join(lines)


def notes_lines(summary, skip=()) -> list[str]:
    """Every caveat of a result's summary (its ``notes``), one ``note: ...`` line each: the text
    a result describes itself with carries what its JSON carries.

    Parameters
    ----------
    summary : Mapping
        The result's summary (its ``notes`` list, if any).
    skip : tuple of str
        Notes said in another form already (by their first words).
    """
    return ["note: " + n for n in summary.get("notes") or [] if not any(n.startswith(p) for p in skip)]


class Result:
    """Base of every analysis result (see the module docstring for the interface)."""

    summary = _SummaryAttribute()

    #: What the result is, for people: ``"valve spring simulation"``.
    title: ClassVar[str] = "result"
    #: Whether ``_repr_html_`` draws a small figure (only where plotting is cheap).
    cheap_plot: ClassVar[bool] = False

    # ------------------------------------------------------------------ to implement
    def _summary(self) -> Mapping[str, Any]:
        """The summary figures (SI, keys ``<quantity>_<unit>``)."""
        raise NotImplementedError

    def to_xarray(self):
        """The result as an :class:`xarray.Dataset` (every variable with ``attrs["units"]``)."""
        raise NotImplementedError

    def _plot(self, ax=None):
        """Draw the result; return the figure (into ``ax`` when given)."""
        raise NotImplementedError

    def _repr_caption(self) -> str:
        """One line naming what this result is about (e.g. the speed)."""
        return ""

    def describe(self) -> str:
        """The result in words and tables, as the CLI prints it (lines of plain text).

        The default: its title and caption, its scalar figures and its notes; a result with a
        richer account overrides it.
        """
        caption = self._repr_caption()
        lines = [f"{self.title}" + (f": {caption}" if caption else "")]
        items = [(k, format_value(v)) for k, v in self._scalar_items()]
        if items:
            lines.append(text_table(items, headers=("figure", "value (SI)")))
        return "\n".join(lines + notes_lines(self.summary))

    # ------------------------------------------------------------------ the interface
    def to_csv(self, path) -> Path:
        """Write the table derived from :meth:`to_xarray` (SI, unit in each column name), atomically."""
        from .io import write_csv

        return write_csv(path, dataset_columns(self._csv_dataset()))

    def _csv_dataset(self):
        """The dataset :meth:`to_csv` writes (default: :meth:`to_xarray`)."""
        return self.to_xarray()

    def to_dataframe(self):
        """The table :meth:`to_csv` writes, as a :class:`pandas.DataFrame`.

        The same columns in the same order, SI, each named with its unit (``cam_rpm``,
        ``retainer_force_N``, ``time_s``); a scalar column is repeated on every row.  The
        dataset's attributes (the run's speed, the spring type, ...) are the frame's
        ``attrs``.  Unlike a file, the frame may hold NaN where a figure does not apply.

        Returns
        -------
        pandas.DataFrame
            One row per row of the CSV table [-].
        """
        import pandas as pd  # (here: pandas costs 0.3 s of start-up, and only this method needs it)

        ds = self._csv_dataset()
        cols = {name: np.atleast_1d(np.asarray(v)) for name, v in dataset_columns(ds).items()}
        rows = max((a.shape[0] for a in cols.values()), default=0)
        frame = pd.DataFrame({name: np.broadcast_to(a, (rows,)) if a.shape[0] == 1 else a for name, a in cols.items()})
        frame.attrs.update({str(k): v for k, v in ds.attrs.items()})
        return frame

    def to_netcdf(self, path) -> Path:
        """Write :meth:`to_xarray` as NetCDF, atomically."""
        from .io import atomic_path

        with atomic_path(path, suffix=".nc") as tmp:
            self.to_xarray().to_netcdf(tmp)
        return Path(path)

    def plot(self, path=None, ax=None, **kwargs):
        """Plot the result; return the figure.

        Parameters
        ----------
        path : path-like, optional
            PNG file to write (atomically); never a folder.
        ax : matplotlib.axes.Axes, optional
            Axes to draw into (results with several panels draw their main panel).
        """
        if path is not None:
            path = Path(path)
            if path.is_dir():
                raise InputError(f"plot path {path} is a folder: give a file name such as {path / 'plot.png'}")
        fig = self._plot(ax=ax, **kwargs)
        if path is not None:
            from .plotting import save_figure

            save_figure(fig, path, close=False)
        return fig

    # ------------------------------------------------------------------ reprs
    def _scalar_items(self) -> list[tuple[str, Any]]:
        return [
            (k, v) for k, v in self.summary.items() if v is None or isinstance(v, (numbers.Number, bool, np.bool_, str))
        ]

    def __repr__(self) -> str:
        head = f"<{type(self).__name__}: {self.title}"
        caption = self._repr_caption()
        head += f", {caption}>" if caption else ">"
        items = self._scalar_items()
        room = REPR_LINES - 2
        shown = items if len(items) <= room + 1 else items[:room]
        width = max((len(k) for k, _ in shown), default=0)
        lines = [head] + [f"  {k.ljust(width)}  {format_value(v)}" for k, v in shown]
        rest = len(self.summary) - len(shown)
        if rest:
            lines.append(f"  ... {rest} more in .summary; data in .to_xarray()")
        return "\n".join(lines[:REPR_LINES])

    def _repr_html_(self) -> str:
        caption = self._repr_caption()
        rows = "".join(
            f"<tr><td style='text-align:left'><code>{html.escape(k)}</code></td>"
            f"<td style='text-align:right'>{html.escape(format_value(v))}</td></tr>"
            for k, v in self._scalar_items()
        )
        out = (
            f"<div><strong>{html.escape(type(self).__name__)}</strong>: {html.escape(self.title)}"
            f"{', ' + html.escape(caption) if caption else ''}"
            f"<table><thead><tr><th>summary</th><th>value (SI)</th></tr></thead><tbody>{rows}</tbody></table>"
        )
        if self.cheap_plot:
            out += self._figure_html()
        return out + "</div>"

    def _figure_html(self) -> str:
        try:
            from .plotting import plt

            fig = self._plot()
            fig.set_size_inches(6.0, 3.6)
            buf = _io.BytesIO()
            fig.savefig(buf, format="png", dpi=80)
            plt.close(fig)
        except Exception:  # a figure in a notebook repr is a convenience, never an error
            return ""
        data = base64.b64encode(buf.getvalue()).decode("ascii")
        return f"<img alt='{html.escape(self.title)}' src='data:image/png;base64,{data}'/>"
