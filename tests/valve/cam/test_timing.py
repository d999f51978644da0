"""Valve timing (springdyn.valve.cam.timing): cam angles as crank angles from TDC.

References: the four-stroke relation (the camshaft turns once per two crank revolutions),
the cam-card convention (intake centreline after, exhaust centreline before the gas-exchange
TDC), and the 3-4-5 rise's closed form for the check-height angles.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from springdyn.app.cli.main import main
from springdyn.core.errors import InputError
from springdyn.valve.cam.analysis import analyse_cam
from springdyn.valve.cam.definition import Cam
from springdyn.valve.cam.timing import CrankAxis, Timing, crank_axis, crank_words
from tests.paths import ROOT

CAM = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
TIMING_FILE = str(ROOT / "src/springdyn/data/valve_cam_timing.toml")


def _one_mm_cam_deg() -> float:
    """Cam angle [deg] where the 3-4-5 rise of 9 mm over 60 deg reaches 1 mm (closed form)."""
    u = brentq(lambda u: 10 * u**3 - 15 * u**4 + 6 * u**5 - 1.0 / 9.0, 0.0, 1.0, xtol=1e-14)
    return 60.0 * u


@pytest.mark.parametrize(
    ("valve", "strokes", "centre"),
    [("intake", 4, 110.0), ("exhaust", 4, -110.0), ("intake", 2, 110.0)],
)
def test_opening_at_1mm_by_hand(valve, strokes, centre):
    """phi = +-lobe_centre + k (theta - theta_max), k = strokes / 2, theta_max = 60 deg."""
    t = Timing.from_dict({"lobe_centre": "110 deg", "valve": valve, "strokes": strokes})
    s = analyse_cam(CAM, timing=t).summary
    k = strokes / 2
    expected = centre + k * (_one_mm_cam_deg() - 60.0)
    # the analysis interpolates linearly between samples 0.05 cam deg apart: 0.005 cam deg
    # (tests/valve/test_cam_analysis.py), k times that in crank degrees
    assert s["opening_at_1mm_crank_deg"] == pytest.approx(expected, abs=0.005 * k)
    assert s["max_lift_crank_deg"] == pytest.approx(centre, abs=1e-9)


def test_words_of_the_3_4_5_intake_lobe():
    """Opening at 1 mm 20.85 deg ATDC (the lobe is short: 240 crank deg), closing 19.15 ABDC."""
    s = analyse_cam(CAM, timing=Timing.from_dict({"lobe_centre": "110 deg"})).summary
    assert s["timing"]["opening_at_1mm"] == "20.8 deg ATDC"
    assert s["timing"]["closing_at_1mm"] == "19.2 deg ABDC"
    assert s["timing"]["max_lift"] == "110.0 deg ATDC"


def test_crank_angles_lie_in_one_cycle_and_keep_their_spacing():
    axis = crank_axis(CAM, Timing.from_dict({"lobe_centre": "110 deg", "valve": "exhaust"}))
    cam_deg = np.arange(0.0, 360.0, 0.5)
    phi = axis.crank_deg(cam_deg)
    assert phi.min() >= -360.0 and phi.max() < 360.0
    # one cam revolution covers the cycle once: sorted, the crank angles are 1 deg apart
    assert np.allclose(np.diff(np.sort(phi)), 1.0)
    assert axis.limits == (-360.0, 360.0)


def test_without_timing_the_crank_counts_from_the_event_start():
    axis = crank_axis(CAM)
    assert axis.crank_deg(60.0) == 120.0 and not axis.referenced
    assert axis.label == "crank angle [deg]" and CrankAxis.cam().label == "cam angle [deg]"


def test_spans_split_at_the_wrap():
    axis = crank_axis(CAM, Timing.from_dict({"lobe_centre": "110 deg"}))
    lo, hi = axis.limits
    # crank = -10 + 2 cam: cam 100-120 is 190-230; cam 170-190 is 330-370, wrapped at 360
    assert axis.spans(100.0, 120.0) == [(pytest.approx(190.0), pytest.approx(230.0))]
    assert axis.spans(170.0, 190.0) == [(pytest.approx(330.0), hi), (lo, pytest.approx(-350.0))]


def test_peak_angle_of_a_lift_table_is_its_maximum():
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    table = Cam.from_table(theta, CAM.lift_at(theta))
    assert math.degrees(table.peak_angle) == pytest.approx(60.0, abs=1e-6)
    asym = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120), closing_duration=math.radians(70))
    assert math.degrees(asym.peak_angle) == pytest.approx(50.0)


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ({"lobe_centre": "400 deg"}, "lobe_centre = 400 deg must lie from 0 to 360 deg"),
        ({"lobe_centre": "110 deg", "strokes": 3}, "strokes = 3 must be 4"),
        ({"lobe_centre": "110 deg", "valve": "inlet"}, "valve = 'inlet' is not allowed"),
        ({"lobe_centre": "110 deg", "centre": 1}, "centre"),
    ],
)
def test_bad_timing_tables(table, message):
    with pytest.raises(InputError, match=message):
        Timing.from_dict(table)


def test_crank_words_name_the_nearest_dead_centre():
    assert crank_words(-12.0) == "12.0 deg BTDC"
    assert crank_words(-181.0) == "1.0 deg BBDC"
    assert crank_words(-179.0) == "1.0 deg ABDC"
    assert crank_words(350.0) == "10.0 deg BTDC"  # the firing TDC at 360


def test_simulation_events_carry_crank_angles(tmp_path, capsys):
    """valve simulate with the cam file's [timing]: a crank_angle_deg column, and every
    event's crank angles equal the axis applied to its cam angles."""
    csv = tmp_path / "s.csv"
    code = main(
        [
            "valve",
            "simulate",
            str(ROOT / "src/springdyn/data/valve_one_step.toml"),
            "--cam",
            TIMING_FILE,
            "--valve-train",
            str(ROOT / "src/springdyn/data/valve_train_direct_acting.toml"),
            "--cam-rpm",
            "3300",
            "--revolutions",
            "2",
            "--json",
            "--csv",
            str(csv),
        ]
    )
    assert code == 0
    s = json.loads(capsys.readouterr().out)
    axis = crank_axis(Cam.from_toml(TIMING_FILE), Timing.in_file(TIMING_FILE))
    assert s["crank_angle_origin"] == "gas-exchange TDC"
    assert s["liftoff"]  # the run has events to check (the valve floats at 3300 cam rpm)
    for ev in s["coil_contact"] + s["end_separation"] + s["liftoff"]:
        assert ev["start_crank_deg"] == pytest.approx(axis.crank_deg(ev["start_deg"]))
        assert ev["start_timing"] == axis.words(ev["start_deg"])
    header = csv.read_text().splitlines()[0].split(",")
    assert header[:3] == ["time_s", "cam_angle_deg", "crank_angle_deg"]


def test_cli_cam_prints_the_timing(capsys):
    assert main(["valve", "cam", TIMING_FILE]) == 0
    out = capsys.readouterr().out
    # the example lobe: 86.6 cam deg at 0.050 in around the 108 deg centreline
    assert (
        "intake valve timing ([timing] lobe centre 108.0 deg ATDC" in out and "at 0.050 in opens 21.4 deg ATDC" in out
    )
    assert "opens [deg ATDC]" in out
