"""``springdyn demo`` part of the CFCS (the paper's mechanism end to end)."""

import json

import pytest

from springdyn.cfcs import demo


@pytest.mark.slow
def test_demo_writes_every_file(tmp_path):
    files = demo.run(tmp_path, quiet=True)
    assert all(p.exists() and p.stat().st_size > 0 for p in files)
    names = {p.name for p in files}
    assert {"static.csv", "static.png", "sweep.csv", "sweep.png", "pivot_stress.png", "summary.json"} <= names
    assert sum(n.startswith("dynamic_omega_") and n.endswith(".png") for n in names) == len(demo.PAPER_OMEGAS)
    s = json.loads((tmp_path / "summary.json").read_text())
    assert s["static"]["pcf_percent"] == pytest.approx(97.0, abs=0.05)
    assert s["design_40mm_fraction_0.4"]["feasible"] is False
    assert s["design_40mm_fraction_0.2"]["feasible"] is True
