"""The PRBM band error's dependence on where the range ends (issue 40, item 8).

The band error compares two differences of extremes, so it moves with the range's end: Table 1's
+18.6 % over 0-72 mm is +23.6 % over 0-71.5 mm (the issue).  Every beam check gives its spread over
the ends in the last 10 % of the range; the reference is an independent static run over the shorter
range (its own grid of 721 samples).
"""

import numpy as np
import pytest

from springdyn.cfcs.beam import band_error_over_range_ends


def test_the_issue_ranges(model):
    full = model.static(0.072).summary
    short = model.static(0.0715).summary
    assert full["beam_band_error_percent"] == pytest.approx(18.6, abs=0.05)
    assert short["beam_band_error_percent"] == pytest.approx(23.6, abs=0.05)
    # the spread over ends from 64.8 to 72 mm holds both, and the note says the force error does not move
    lo, hi = full["beam_band_error_min_percent"], full["beam_band_error_max_percent"]
    assert full["beam_band_error_ends_m"] == pytest.approx([0.0648, 0.072], abs=1e-4)
    assert lo <= full["beam_band_error_percent"] <= hi and lo <= short["beam_band_error_percent"] <= hi
    assert lo == pytest.approx(18.6, abs=0.05) and hi == pytest.approx(31.3, abs=0.05)
    assert any("depends on where the range ends" in n and "only grows" in n for n in full["notes"])
    # the force error, a largest difference, only grows with the range: 0.940 % and 0.965 % of F0 (2.6 %,
    # against the band error's 27 %)
    assert short["beam_force_error_percent"] == pytest.approx(0.940, abs=5e-4)
    assert full["beam_force_error_percent"] == pytest.approx(0.965, abs=5e-4)


def test_band_error_over_range_ends_matches_the_band_error_of_each_range(model):
    # independent: prbm_error on the truncated samples, end by end
    from springdyn.cfcs.beam import prbm_error

    x = np.linspace(0.0, 0.072, 201)
    th = np.arccos(1 - x / 0.18)  # any two smooth curves will do: these are not the mechanism's
    fp, fb = 12.6 + 0.4 * np.sin(3 * th), 12.6 + 0.3 * np.sin(3.2 * th)
    ends = x[-5:]
    got = band_error_over_range_ends(x, fp, fb, ends)
    for e, g in zip(ends, got):
        k = x <= e
        assert g == prbm_error(x[k], fp[k], fb[k], 1.0)["band_error"]


def test_cli_row(capsys):
    from .test_cli import run

    code, out, err = run(capsys, "cfcs", "static", "table1")
    assert code == 0, err
    row = next(line for line in out.splitlines() if "with the range's end" in line)
    assert "+18.6 .. +31.3 %" in row and "64.8 mm .. 72 mm" in row
