"""The tolerance study's histograms draw the criteria's limits (issue 39): each limit a labelled
line, on the figure it judges, as :meth:`ToleranceStudy.failures` judges it."""

from __future__ import annotations

import matplotlib.pyplot as plt
import pytest

from springdyn.valve import Cam, ValveSpring
from springdyn.valve.design import tolerances as tol
from springdyn.valve.design.criteria import Criteria

pytestmark = pytest.mark.filterwarnings("ignore:coil bind:UserWarning")


def test_histograms_draw_the_criteria_limits(tmp_path):
    crit = Criteria.from_dict({"max_retainer_force": "560 N", "installed_force_band": "5 %", "min_goodman_safety": 1.2})
    study = tol.tolerance_study(
        ValveSpring.example("one-step"),
        Cam.from_dict({"law": "3-4-5", "lift": "9 mm", "duration": "120 deg"}),
        {"wire_diameter": tol.parse_tolerance("wire_diameter", "+-0.02 mm")},
        count=8,
        seed=1,
        speeds=[1500.0, 2000.0],
        criteria=crit,
    )
    limits = study.limits()
    assert limits["goodman_safety"] == [(1.2, "min", "min_goodman_safety 1.2")]
    assert limits["max_retainer_force"][0][:2] == (560.0, "max")
    f0 = study.nominal["Fset"]
    assert [v for v, _, _ in limits["Fset"]] == pytest.approx([0.95 * f0, 1.05 * f0])
    assert limits["clash_onset_cam_rpm"][0][:2] == (2000.0, "min")  # no clash up to the top speed
    fig = study.plot(tmp_path / "tol.png")
    try:
        assert (tmp_path / "tol.png").stat().st_size > 1000
        by_name = {a.get_xlabel().split(" [")[0]: a for a in fig.axes if a.get_visible() and a.get_xlabel()}
        for name, rows in limits.items():
            if name not in by_name:
                continue
            labels = [t.get_text() for t in by_name[name].get_legend().get_texts()]
            assert all(label in labels for _, _, label in rows), (name, labels)
            lo, hi = by_name[name].get_xlim()
            assert all(lo < v < hi for v, _, _ in rows), (name, lo, hi)  # every limit in view
    finally:
        plt.close(fig)
