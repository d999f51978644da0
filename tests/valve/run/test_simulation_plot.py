"""Figures a user can read (issue 39): the distributed model's 51 masses get a
colour bar of their position along the wire and a legend naming the two end masses only;
Type C's 5 masses keep their legend."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest

import springdyn.valve as valve
from springdyn.valve import Cam, ValveSpring

pytestmark = pytest.mark.filterwarnings("ignore:coil bind:UserWarning")


@pytest.fixture(scope="module")
def cam():
    return Cam.from_dict({"law": "3-4-5", "lift": "9 mm", "duration": "120 deg"})


def _mass_panel(fig):
    return next(a for a in fig.axes if a.get_ylabel() == "displacement from set-up [mm]")


def test_distributed_masses_are_coloured_by_position(cam, tmp_path):
    spring = ValveSpring.example("one-step").replace(model="distributed")
    sim = valve.simulate(spring, cam, 3000, 2, points_per_revolution=360)
    fig = sim.plot(tmp_path / "sim.png")
    try:
        assert (tmp_path / "sim.png").stat().st_size > 1000
        panel = _mass_panel(fig)
        n = sim.mass_displacement.shape[0]
        assert n > 8 and len(panel.get_lines()) == n  # every mass drawn
        labels = [t.get_text() for t in panel.get_legend().get_texts()]
        assert len(labels) == 2, labels
        assert labels[0].startswith("seat-end mass (n0") and labels[1].startswith(f"retainer-end mass (n{n - 1}")
        bars = [a for a in fig.axes if a.get_ylabel() == "position along the wire [turns from the seat]"]
        assert len(bars) == 1  # the colour bar
    finally:
        plt.close(fig)


def test_type_c_masses_keep_their_legend(cam):
    sim = valve.simulate(ValveSpring.example("one-step"), cam, 3000, 2, points_per_revolution=360)
    fig = sim.plot()
    try:
        labels = [t.get_text() for t in _mass_panel(fig).get_legend().get_texts()]
        assert labels == [f"mass {i + 1} ({n})" for i, n in enumerate(sim.spring.spring_model.chain.mass_names)]
        assert len(labels) == 5
    finally:
        plt.close(fig)


def test_run_up_figure_shows_what_changes_through_the_ramp(cam, tmp_path):
    """The run-up figure (the report's run-up panel): the least cam contact force falls with
    speed, the retainer force's range beside it, and the ramp's float onset marked."""
    from springdyn.valve import ValveModel, ValveTrain

    model = ValveModel(ValveSpring.example("one-step"), cam, ValveTrain.example())
    ramp = model.run_up_through_float(2114.0, 3000.0)  # this train floats from 2114 cam rpm on
    assert ramp.steady_float_cam_rpm == 2114.0  # known to the study: its figure marks it
    t = ramp.revolutions()
    assert t["min_nose_contact_force_N"].max() > 10.0 and np.ptp(t["max_retainer_force_N"]) > 0.0
    fig = ramp.plot(tmp_path / "run_up.png")
    try:
        labels = [x.get_text() for x in fig.axes[0].get_legend().get_texts()]
        assert any(x.startswith("cam contact force") for x in labels)
        assert any(x.startswith("retainer force") for x in labels)
        assert any(x.startswith("steady-state float speed 2114 rpm") for x in labels)
        if ramp.summary["float_onset_cam_rpm"] is not None:
            assert any(x.startswith("float onset in the ramp") for x in labels)
    finally:
        plt.close(fig)
