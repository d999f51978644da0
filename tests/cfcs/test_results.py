"""Result objects: xarray, CSV and PNG outputs."""

import numpy as np
import pytest

from springdyn.core.io import read_csv_columns


def test_static_outputs(model, tmp_path):
    r = model.static()
    cols = read_csv_columns(r.to_csv(tmp_path / "s.csv"))
    assert list(cols)[:3] == ["deflection_m", "theta2_rad", "force_N"]
    np.testing.assert_allclose(cols["force_N"], r.force, rtol=1e-15)
    ds = r.to_xarray()
    assert ds.attrs["toggle_cutoff_rad"] == pytest.approx(np.radians(5))
    fig = r.plot(tmp_path / "s.png")
    assert (tmp_path / "s.png").stat().st_size > 1000
    assert "toggle cut-off" in fig.axes[0].get_title()


def test_dynamic_outputs(model, tmp_path):
    r = model.dynamic(14.7, cycles=1)
    cols = read_csv_columns(r.to_csv(tmp_path / "d.csv"))
    assert list(cols)[:4] == ["time_s", "deflection_m", "force_N", "force_static_N"]
    assert r.to_xarray()["force_N"].dims == ("time",)
    r.plot(tmp_path / "d.png")
    assert (tmp_path / "d.png").exists()


def test_sweep_outputs(model, tmp_path):
    r = model.sweep([2.0, 10.0, 30.0], samples_per_cycle=100)
    cols = read_csv_columns(r.to_csv(tmp_path / "w.csv"))
    assert {
        "omega_rad_per_s",
        "mean_force_N",
        "median_force_N",
        "peak_to_peak_N",
        "pcf_percent",
        "pcf_no_dissipation_percent",
    } <= set(cols)
    # the inertia grows with omega^2: the ideal peak-to-peak force grows with omega (Fig. 7 trend)
    assert np.all(np.diff(r.stats["peak_to_peak_no_dissipation_N"]) > 0)
    r.plot(tmp_path / "w.png")
    assert (tmp_path / "w.png").exists()
