"""``to_dataframe()``: every valve result as a pandas DataFrame with the CSV's columns.

The whole interface (the frame has exactly the CSV's columns, in order, with its values) is
checked for every result class in ``tests/test_result_interface.py``; here the names a user
reaches for are there, in SI with their unit, for each kind of valve result.
"""

from __future__ import annotations

import numpy as np
import pytest

import springdyn.valve as valve
from springdyn.core.io import read_csv_columns
from springdyn.valve import Cam, ValveSpring, ValveTrain
from springdyn.valve.run.run_up import speed_ramp

pytestmark = pytest.mark.filterwarnings("ignore:coil bind:UserWarning")


@pytest.fixture(scope="module")
def spring():
    return ValveSpring.example("one-step")


@pytest.fixture(scope="module")
def cam():
    return Cam.from_dict({"law": "3-4-5", "lift": "9 mm", "duration": "120 deg"})


def _same_as_csv(result, tmp_path):
    frame = result.to_dataframe()
    cols = read_csv_columns(result.to_csv(tmp_path / "result.csv"))
    assert list(frame.columns) == list(cols)
    for name, values in cols.items():
        np.testing.assert_allclose(frame[name].to_numpy(float), values, rtol=1e-12)
    return frame


def test_static_curve(spring, tmp_path):
    frame = _same_as_csv(spring.spring_model.static_curve(points=50), tmp_path)
    assert {"length_m", "force_N", "stiffness_N_per_m"} <= set(frame.columns)
    assert len(frame) == 50
    assert frame.attrs["spring_type"] == "one-step"


def test_simulation(spring, cam, tmp_path):
    sim = valve.simulate(spring, cam, 2500, 2, points_per_revolution=360)
    frame = _same_as_csv(sim, tmp_path)
    assert {"time_s", "cam_angle_deg", "lift_m", "retainer_force_N", "seat_force_N"} <= set(frame.columns)
    np.testing.assert_array_equal(frame["retainer_force_N"], sim.retainer_force)
    assert frame.attrs["cam_rpm"] == 2500  # the run's speed goes with the table


def test_speed_sweep(spring, cam, tmp_path):
    res = valve.sweep(spring, cam, np.array([1000.0, 2000.0]), revolutions=2, points_per_revolution=180, quiet=True)
    frame = _same_as_csv(res, tmp_path)
    assert list(frame["cam_rpm"]) == [1000.0, 2000.0]
    assert {"max_retainer_force_N", "min_retainer_force_N"} <= set(frame.columns)


def test_float_search_result(tmp_path):
    res = valve.run.results.FloatSpeedResult([1000.0, 2000.0], [120.0, -5.0], 1800.0, [1500.0, 1800.0], 1.0)
    frame = _same_as_csv(res, tmp_path)
    assert list(frame.columns) == ["cam_rpm", "engine_rpm", "min_cam_contact_force_N"]
    assert list(frame["engine_rpm"]) == [2000.0, 4000.0]  # four-stroke without a crank axis
    assert frame.attrs["float_cam_rpm"] == 1800.0


def test_run_up(spring, cam, tmp_path):
    res = speed_ramp(
        spring, cam, ValveTrain.example(), 3000.0, 3300.0, 3000.0, points_per_revolution=360, float_scan=False
    )
    frame = _same_as_csv(res, tmp_path)
    assert {"time_s", "cam_rpm", "cam_contact_force_N", "retainer_force_N"} <= set(frame.columns)
    assert frame["cam_rpm"].iloc[0] == pytest.approx(3000.0, rel=1e-3)
