"""The Result interface every analysis result must offer, as one reusable check.

Each family's tests call :func:`check_result_interface` on an instance of each of its
result classes; ``tests/test_result_interface.py`` walks the packages so that no result
class is forgotten.
"""

from __future__ import annotations

import math
import numbers
import re
from pathlib import Path

import numpy as np

from springdyn.core.io import read_csv_columns
from springdyn.core.results import REPR_LINES, Result, unit_suffix, units_from_name

#: A summary key ends with its unit, or is a count, flag, ratio or text; these words mark
#: dimensionless or non-numeric keys.
_UNITLESS = re.compile(
    r"(ratio|factor|margin|count|index|percent|order|flag|pcf|_n$|number|type|law|model|"
    r"name|periodic|liftoff|contact|feasible|dominated|notes|reason|status|error|bool|"
    r"which|kind|binding|warning|coverage|success|converged|orders|n_|revolutions|elements|"
    r"bounces|events|samples|points|records|speeds|leaves|packs|chambers)"
)


#: A name ending in a unit then ``_s`` reads as seconds, not as per second
#: (``velocity_m_s`` once got ``units: "s"``); the convention is ``velocity_m_per_s``.
_AMBIGUOUS = re.compile(r"_(m|rad|N|deg|rpm|Hz|Pa)_s$")


def check_result_interface(result, tmp_path: Path, *, plot: bool = True) -> None:
    """Assert that ``result`` offers the whole :class:`Result` interface and that it works."""
    assert isinstance(result, Result), f"{type(result).__name__} is not a springdyn.core.results.Result"
    summary = result.summary
    assert isinstance(summary, dict) and summary, "summary must be a non-empty dict"
    for key, value in summary.items():
        assert isinstance(key, str) and key == key.strip(), key
        assert not _AMBIGUOUS.search(key), f"summary key {key!r}: write a rate as <unit>_per_s"
        if isinstance(value, float):
            assert math.isfinite(value), f"summary[{key!r}] = {value} is not finite"
    ds = result.to_xarray()
    for name, var in [*ds.data_vars.items(), *ds.coords.items()]:
        if np.issubdtype(var.dtype, np.floating):
            assert "units" in var.attrs, f"to_xarray(): {name!r} has no attrs['units']"
        assert not _AMBIGUOUS.search(str(name)), f"to_xarray(): {name!r}: write a rate as <unit>_per_s"
        if "units" in var.attrs:
            # a name that ends with a unit (the <quantity>_<unit> convention) carries that unit:
            # velocity_m_per_s is in m/s (velocity_m_s was once read as seconds)
            implied = units_from_name(str(name))
            if implied != "1":
                assert unit_suffix(var.attrs["units"]) == unit_suffix(implied), (
                    f"to_xarray(): {name!r} has units {var.attrs['units']!r}, its name says {implied!r}"
                )
    csv = result.to_csv(tmp_path / "result.csv")
    cols = read_csv_columns(csv)
    assert cols, "to_csv wrote no column"
    frame = result.to_dataframe()
    assert list(frame.columns) == list(cols), "to_dataframe() must have the CSV's columns, in order"
    for name in cols:
        assert len(frame[name]) == len(cols[name]), f"to_dataframe(): column {name!r} has other rows than the CSV"
        if np.issubdtype(frame[name].dtype, np.number):
            np.testing.assert_allclose(frame[name].to_numpy(float), np.asarray(cols[name], float), rtol=1e-12)
    text = repr(result)
    assert 1 <= len(text.splitlines()) <= REPR_LINES, f"repr has {len(text.splitlines())} lines"
    assert "<" in text.splitlines()[0]
    html = result._repr_html_()
    assert "<table" in html
    if plot:
        import matplotlib.pyplot as plt

        png = tmp_path / "result.png"
        fig = result.plot(png)
        assert png.is_file() and png.stat().st_size > 1000, "plot(path) must write the PNG file"
        assert hasattr(fig, "savefig")
        plt.close(fig)
        fig, ax = plt.subplots()
        out = result.plot(ax=ax)
        assert out is fig, "plot(ax=ax) must draw into the given axes and return its figure"
        plt.close(fig)


def is_number(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)
