"""Results objects (xarray, CSV, plot) and the lsd part of ``springdyn demo``."""

import numpy as np
import pytest

from springdyn.io import read_csv_columns
from springdyn.lsd import LSDModel, LSDParameters, circular_orbit, simulate_rig


def test_coefficients_results(tmp_path):
    res = LSDModel(LSDParameters.example("B")).coefficients([500, 1000], 50e-6)
    ds = res.to_xarray()
    assert ds["K"].shape == (2, 2, 2) and ds["K"].attrs["units"] == "N/m"
    np.testing.assert_allclose(ds["C"].values, ds["C_oring"] + ds["C_hysteresis"] + ds["C_viscous"])
    fig = res.plot(tmp_path / "b.png")
    assert (tmp_path / "b.png").stat().st_size > 10_000 and len(fig.axes) == 2


def test_rig_record_results(tmp_path):
    m = LSDModel(LSDParameters.example("C"))
    rec = simulate_rig(m, circular_orbit(1000, 50e-6, 3, 5e3))
    ds = rec.to_xarray()
    # the parts add up to the measured force (no noise)
    total = sum(ds[f"fx_{k}"] for k in rec.parts)
    np.testing.assert_allclose(total.values, ds["fx"].values)
    rec.to_csv(tmp_path / "r.csv")
    assert read_csv_columns(tmp_path / "r.csv")["fx_N"] == pytest.approx(rec.fx)
    rec.plot(tmp_path / "r.png")
    assert (tmp_path / "r.png").is_file()


def test_energy_balance_of_the_rig():
    # work done on the ring per cycle = oil dissipation (C_visc) + friction work; inertia and
    # springs do no net work over whole cycles.  Independent of the identification code.
    m = LSDModel(LSDParameters.example("C"))
    tr = circular_orbit(1000, 50e-6, 4, 20e3)
    rec = simulate_rig(m, tr)
    dt = tr.time[1] - tr.time[0]
    work = np.sum(rec.fx * tr.vx + rec.fy * tr.vy) * dt
    w = 2 * np.pi * 1000 / 60
    cycles = 4
    oil = cycles * 2 * np.pi * m.viscous_damping[0, 0] * w * 50e-6**2
    leaf = cycles * 6 * (1.5 * 0.1 * m.slip_factor * m.pack_stiffness * m.params.preload * 4 * 50e-6)
    # tolerance 0.1 %: rectangle-rule integration of a discontinuous friction force
    assert work == pytest.approx(oil + leaf, rel=1e-3)


@pytest.mark.slow
def test_demo_writes_types_a_b_c(tmp_path):
    from springdyn.lsd import demo

    files = demo.run(tmp_path, quiet=True)
    names = {p.name for p in files}
    for t in ("a", "b", "c"):
        assert f"type_{t}_coefficients.png" in names and f"type_{t}_identified.csv" in names
    assert all(p.is_file() for p in files)
    import json

    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["Type C"]["pack_stiffness_N_per_m"] == pytest.approx(106.9e3, abs=50)
    # identified (simulated x and y shakes, 2 N noise) Kxx within 1 % of the model
    for v in summary.values():
        assert v["kxx_identified_N_per_m_at_500rpm"] == pytest.approx(v["kxx_model_N_per_m"], rel=0.01)
