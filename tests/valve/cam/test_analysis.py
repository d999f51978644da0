"""The cam analysis (springdyn.valve.cam.analysis) against the 3-4-5 law's closed form."""

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq

from springdyn.app.cli.main import main
from springdyn.valve import Cam, ValveTrain
from springdyn.valve.cam.analysis import CHECK_HEIGHTS, analyse_cam, cam_derivatives, check_height_timing
from tests.paths import example

L, HALF = 9e-3, math.radians(60.0)  # 9 mm over 120 deg: rise over 60 deg
CAM = Cam(law="3-4-5", lift=L, duration=2 * HALF)


def p345(u):
    return 10 * u**3 - 15 * u**4 + 6 * u**5


def test_timing_at_the_check_heights_is_the_closed_form():
    """Opening where L P(u) = h: u from the polynomial (brentq), angle u * 60 deg; closing
    its mirror; sampled at 0.05 deg and interpolated linearly: within 0.005 deg."""
    s = analyse_cam(CAM).summary
    for key, h in CHECK_HEIGHTS.items():
        u = brentq(lambda x, h=h: L * p345(x) - h, 0.0, 0.5)
        assert s[f"opening_at_{key}_deg"] == pytest.approx(math.degrees(u * HALF), abs=5e-3)
        assert s[f"closing_at_{key}_deg"] == pytest.approx(120.0 - math.degrees(u * HALF), abs=5e-3)
    assert s["lobe_centre_deg"] == pytest.approx(60.0, abs=1e-9)
    assert s["max_lift_m"] == pytest.approx(L) and s["event_duration_deg"] == pytest.approx(120.0, abs=0.06)


def test_derivatives_are_the_laws():
    """v = L P'(u)/T, a = L P''(u)/T^2 (the cam law's own), jerk = L P'''(u)/T^3 from the
    central difference of a: within 1e-4 of its peak inside the rise."""
    d = cam_derivatives(CAM)
    u = d["cam_angle"] / HALF
    inside = (u > 0.05) & (u < 0.95)
    jerk = L * (60 - 360 * u + 360 * u**2) / HALF**3
    assert np.max(np.abs(d["jerk"][inside] - jerk[inside])) <= 1e-4 * np.max(np.abs(jerk))
    assert d["velocity"].max() == pytest.approx(L * 1.875 / HALF, rel=1e-9)  # P'(1/2) = 30/16
    # P''(u) = 60u - 180u^2 + 120u^3 peaks at u = (3 - sqrt 3)/6 with 10/sqrt 3; sampled at 0.05 deg
    assert d["acceleration"].max() == pytest.approx(L * 10 / math.sqrt(3) / HALF**2, rel=1e-5)


def test_at_the_valve_the_ratio_and_the_lash_apply():
    vt = ValveTrain.example("pushrod")
    a, b = analyse_cam(CAM), analyse_cam(CAM, vt)
    open_ = b.lift > 0
    np.testing.assert_allclose(b.lift[open_], vt.ratio * a.lift[open_] - vt.lash, rtol=1e-12)
    assert b.summary["event_opening_deg"] > a.summary["event_opening_deg"]  # the lash opens later


def test_engine_speed_gives_crank_angles_and_time_derivatives():
    s = analyse_cam(CAM, engine_rpm=6000.0).summary
    w = 3000.0 * 2 * math.pi / 60  # the cam at half the engine speed
    assert s["opening_at_1mm_crank_deg"] == pytest.approx(2 * s["opening_at_1mm_deg"])
    assert s["max_velocity_m_per_s"] == pytest.approx(s["max_velocity_m_per_rad"] * w)
    assert s["max_acceleration_m_per_s2"] == pytest.approx(s["max_acceleration_m_per_rad2"] * w**2)


def test_check_height_above_the_lift_has_no_timing():
    d = cam_derivatives(Cam(law="3-4-5", lift=0.8e-3, duration=2 * HALF))
    assert check_height_timing(d["cam_angle"], d["lift"], 1e-3) is None


def test_cli_cam(tmp_path, capsys):
    csv = tmp_path / "cam.csv"
    assert main(["valve", "cam", example("valve/cam_345.toml"), "--csv", str(csv), "--engine-rpm", "6000"]) == 0
    out = capsys.readouterr().out
    assert "at 1 mm" in out and "crank deg" in out and f"wrote {csv}" in out
    assert csv.read_text().splitlines()[0].startswith("cam_angle_deg,crank_angle_deg,lift_m,velocity_m_per_rad")
    assert main(["valve", "cam", example("valve/cam_345.toml"), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["duration_at_1mm_deg"] == pytest.approx(89.15, abs=0.01)
    assert main(["valve", "cam", example("valve/cam_345.toml"), "--engine-rpm", "-5"]) == 2


def test_asymmetric_lobe_has_its_flanks_own_durations_and_laws():
    """Opening flank 50 deg of 3-4-5, closing flank 70 deg of cycloidal: the nose at 50 deg,
    lift and velocity continuous there (both laws end at rest, the acceleration at zero),
    and the closing flank's 1 mm point where the cycloidal law's closed form puts it."""
    cam = Cam(
        law="3-4-5",
        lift=L,
        duration=math.radians(120),
        closing_duration=math.radians(70),
        closing_law="cycloidal",
    )
    assert cam.flank_durations == pytest.approx((math.radians(50), math.radians(70)))
    th = np.radians([49.999, 50.0, 50.001])
    h, dh, ddh = cam.evaluate(th)
    assert h[1] == pytest.approx(L) and np.max(np.abs(dh)) < 1e-7 and np.max(np.abs(ddh)) < 1e-3
    s = analyse_cam(cam).summary
    u = brentq(lambda x: L * (x - math.sin(2 * math.pi * x) / (2 * math.pi)) - 1e-3, 0.0, 0.5)
    assert s["closing_at_1mm_deg"] == pytest.approx(120.0 - math.degrees(u * math.radians(70)), abs=5e-3)
    u = brentq(lambda x: L * p345(x) - 1e-3, 0.0, 0.5)
    assert s["opening_at_1mm_deg"] == pytest.approx(math.degrees(u * math.radians(50)), abs=5e-3)
    # symmetric by default: half the duration each, bit for bit
    sym = Cam(law="3-4-5", lift=L, duration=2 * HALF, closing_duration=HALF)
    np.testing.assert_array_equal(sym.evaluate(th)[0], CAM.evaluate(th)[0])


def test_closing_flank_settings_are_checked():
    from springdyn.core.errors import InputError

    with pytest.raises(InputError, match="closing_duration = 130 deg must lie between 0 and the duration 120 deg"):
        Cam(law="3-4-5", lift=L, duration=2 * HALF, closing_duration=math.radians(130))
    with pytest.raises(InputError, match='closing_law = "table" is not a flank law'):
        Cam(law="3-4-5", lift=L, duration=2 * HALF, closing_law="table")
