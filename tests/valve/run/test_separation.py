"""Separation as valve-train engineers read it (springdyn.valve.run.separation, float_search):
phases from the cam's own lift law, float over the nose, bounce, the seating velocity band."""

import math

import numpy as np
import pytest

from springdyn.valve import Cam, ValveSpring, ValveTrain
from springdyn.valve.run.float_search import float_speed
from springdyn.valve.run.separation import (
    PHASES,
    cam_phases,
    first_separation,
    float_speed_of_scan,
    liftoffs,
    neighbour_band,
    phase_mask,
    phase_of,
)
from tests.paths import EXAMPLES

EX = EXAMPLES / "valve"


def test_345_cam_nose_is_the_middle_half_of_the_event():
    """The 3-4-5 rise's acceleration changes sign at half the rise (closed form: h'' of
    10u^3 - 15u^4 + 6u^5 is 60u - 180u^2 + 120u^3 = 60u(1 - u)(1 - 2u)); over 120 deg the nose
    runs from 30 to 90 deg, no ramps."""
    ph = cam_phases(Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))).as_degrees()
    assert ph["start"] == pytest.approx(0.0, abs=0.06) and ph["end"] == pytest.approx(120.0, abs=0.06)
    assert ph["nose_start"] == pytest.approx(30.0, abs=0.06) and ph["nose_end"] == pytest.approx(90.0, abs=0.06)
    assert ph["ramp_end"] == pytest.approx(ph["start"]) and ph["ramp_start"] == pytest.approx(ph["end"])


def test_ramps_are_the_cams_own_or_the_lash_take_up():
    """With 20-deg ramps the opening ramp ends at 20 deg; a lash above the ramp height moves
    the end of the lash take-up to where the lobe lift reaches the lash."""
    cam = Cam.from_toml(EX / "cam_polydyne_ramps.toml")
    ph = cam_phases(cam, 0.15e-3)
    assert math.degrees(ph.ramp_end) == pytest.approx(20.0, abs=0.06)
    assert math.degrees(ph.ramp_start) == pytest.approx(130.0, abs=0.06)
    deep = cam_phases(cam, 0.5e-3)  # above the 0.25 mm ramp: the lash is taken up on the flank
    theta = np.radians(np.arange(20.0, 40.0, 0.05))
    taken_up = theta[np.argmax(cam.lift_at(theta) >= 0.5e-3)]
    assert deep.ramp_end == pytest.approx(taken_up, abs=math.radians(0.06))


def test_phase_of_walks_the_event_in_order():
    ph = cam_phases(Cam(law="3-4-5", lift=9e-3, duration=math.radians(120)))
    names = [phase_of(math.radians(a), ph) for a in (10.0, 60.0, 100.0, 200.0)]
    assert names == ["opening flank", "nose", "closing flank", "base circle"]
    assert phase_of(math.radians(60.0) + 2 * math.pi, ph) == "nose"  # any real angle


def test_phase_mask_is_phase_of_on_every_angle():
    """The vectorised mask equals phase_of angle by angle (random reals, a revolution's grid
    and the bounds themselves) for four cams, with and without lash."""
    rng = np.random.default_rng(0)
    for name in ("cam_polydyne_ramps", "cam_345", "cam_finger", "cam_table"):
        cam = Cam.from_toml(EX / f"{name}.toml")
        for lash in (0.0, 2e-4):
            ph = cam_phases(cam, lash)
            angles = np.concatenate([rng.uniform(-10.0, 10.0, 2000), np.radians(np.arange(0.0, 360.0, 0.25))])
            angles = np.concatenate([angles, list(ph.__dict__.values())])
            for phase in (*PHASES, "base circle"):
                expected = np.array([phase_of(a, ph) == phase for a in angles])
                np.testing.assert_array_equal(phase_mask(angles, ph, phase), expected, err_msg=f"{name} {phase}")


def test_liftoffs_take_the_phase_of_their_start_and_the_largest_gap():
    ph = cam_phases(Cam(law="3-4-5", lift=9e-3, duration=math.radians(120)))
    theta = np.radians(np.arange(0.0, 360.0, 0.5))
    gap = np.where((theta > math.radians(40)) & (theta < math.radians(50)), 1e-4, -1e-6)
    rows = liftoffs([(40.0, 50.0, 10.0), (5.0, 6.0, 1.0)], ph, 3000.0, theta, gap)
    assert [r["phase"] for r in rows] == ["nose", "opening flank"]
    assert rows[0]["max_gap_m"] == pytest.approx(1e-4) and rows[1]["max_gap_m"] == 0.0
    assert rows[0]["duration_s"] == pytest.approx(10.0 / (6.0 * 3000.0))


def test_float_speed_of_a_scan_is_where_nose_separation_stays():
    rpm = [3000, 3100, 3200, 3300, 3400]
    assert float_speed_of_scan(rpm, [False, True, False, True, True]) == 3300.0  # 3100 switches off again
    assert float_speed_of_scan(rpm, [True] * 5) == 3000.0
    assert float_speed_of_scan(rpm, [False, False, True, True, False]) is None  # not at the highest
    assert first_separation(rpm, [[], [], [{"phase": "opening ramp", "start_deg": 17.0}], [], []]) == dict(
        cam_rpm=3200.0, phase="opening ramp", start_deg=17.0
    )


def test_neighbour_band_is_min_median_max_within_the_window():
    lo, med, hi = neighbour_band([3180, 3200, 3220, 3300], [2.1, 2.44, 2.3, 1.0], width=25.0)
    np.testing.assert_allclose(lo, [2.1, 2.1, 2.3, 1.0])
    np.testing.assert_allclose(hi, [2.44, 2.44, 2.44, 1.0])
    np.testing.assert_allclose(med, [2.27, 2.3, 2.37, 1.0])


def test_bucket_float_speed_is_nose_separation_not_the_first_bounce():
    """The bucket train on the ramp cam (examples): the first lift-off is opening-side bounce
    at the end of the opening ramp; the float speed is above it, and over the nose at every
    scanned speed from it on."""
    sp = ValveSpring.from_toml(EX / "one_step_spring.toml")
    cam = Cam.from_toml(EX / "cam_polydyne_ramps.toml")
    vt = ValveTrain.from_toml(EX / "valve_train.toml")
    with pytest.warns(UserWarning, match="coil bind"):
        res = float_speed(sp, cam, vt, np.arange(2900.0, 3601.0, 50.0), resolution=5.0)
    s = res.summary
    assert s["first_separation_phase"] == "opening ramp"
    assert s["first_separation_cam_rpm"] < res.float_cam_rpm
    scan = res.scan
    above = np.asarray(res.cam_rpm) >= res.bracket[1] - 1e-9
    assert all(np.asarray(scan["nose_separation"])[above])
    assert res.bracket[1] - res.bracket[0] <= 5.0
    assert set(scan["first_liftoff_phase"]) <= {"", *PHASES}
    # landings per revolution grow with speed past float (seat bounce)
    assert max(scan["seat_landings"]) > 1
    assert all(
        lo <= v + 1e-12 for lo, v in zip(scan["seat_impact_velocity_min_m_per_s"], scan["seat_impact_velocity_m_per_s"])
    )
