"""Speed ramps (springdyn.valve.run.run_up): the valve train through a changing cam speed.

References: the ramp's kinematics (cam angle omega_0 t + alpha t^2 / 2 and its inverse);
the engine's cam angle under a ramp (the lift it sees is the cam's at that angle); the
slow-ramp limit (the float onset of a slow ramp is the steady-state float speed).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from springdyn.app.cli.main import main
from springdyn.core.errors import InputError
from springdyn.valve import Cam, ValveSpring, ValveTrain
from springdyn.valve.run.run_up import ramp_angle, ramp_time, speed_ramp
from tests.paths import example

CAM = example("valve/cam_polydyne_ramps.toml")
TRAIN = example("valve/valve_train.toml")


def _inputs():
    return ValveSpring.example("one-step"), Cam.from_toml(CAM), ValveTrain.from_toml(TRAIN)


def test_ramp_time_inverts_ramp_angle():
    t = np.linspace(0.0, 2.0, 11)
    for alpha in (300.0, -30.0, 1e-12):
        assert np.allclose(ramp_time(ramp_angle(t, 314.0, alpha), 314.0, alpha), t, rtol=1e-12, atol=1e-15)


@pytest.fixture(scope="module")
def fast_ramp():
    spring, cam, vt = _inputs()
    return speed_ramp(spring, cam, vt, 3000.0, 3400.0, 2000.0, float_scan=False)


def test_the_engine_turns_the_cam_by_the_ramp(fast_ramp):
    """The lift the engine reports at each output time is the cam's lift at the ramp's cam
    angle (to the engine's table interpolation, 1e-9 m), and the speed grows at the rate."""
    r = fast_ramp
    cam = Cam.from_toml(CAM)
    assert np.max(np.abs(r.lift - cam.lift_at(np.mod(r.cam_angle, 2 * math.pi)))) < 1e-9
    # the outputs cover the ramp's whole revolutions: up to 3400 cam rpm
    assert np.allclose(r.cam_rpm, 3000.0 + 2000.0 * r.time, rtol=1e-12)
    assert 3400.0 - 2000.0 * 2 * math.pi / (3400 * 2 * math.pi / 60) <= r.cam_rpm[-1] <= 3400.0
    rows = r.revolutions()
    # a revolution's mean speed: 2 pi over its duration, between its start and end speeds
    assert np.all(np.diff(rows["cam_rpm"]) > 0) and 3000 < rows["cam_rpm"][0] < rows["cam_rpm"][-1] < 3400


def test_float_during_a_fast_ramp(fast_ramp):
    s = fast_ramp.summary
    assert s["revolutions"] == 10
    assert s["float_onset_cam_rpm"] is not None and s["first_liftoff_cam_rpm"] <= s["float_onset_cam_rpm"]


@pytest.mark.slow  # a slow ramp of 100 revolutions and the float scan (~15 s)
def test_a_slow_ramp_floats_at_the_steady_state_float_speed():
    """The quasi-static limit: at 100 rpm/s the train is at each speed's steady state; its
    float onset meets the steady float speed to the ramp's speed step per revolution (3 rpm)
    and the scan's resolution (the bisection's 5 rpm): within 25 rpm."""
    spring, cam, vt = _inputs()
    r = speed_ramp(spring, cam, vt, 3050.0, 3350.0, 100.0)
    s = r.summary
    assert s["float_onset_cam_rpm"] == pytest.approx(s["steady_float_cam_rpm"], abs=25.0)


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--speed-ramp", "3000:3000:100"], "different start and end speeds"),
        (["--speed-ramp", "3000:3400:-5"], "must be a positive rate"),
        (["--speed-ramp", "3000:3400"], "must be START:END:RATE"),
        (["--speed-ramp", "3000:3400:1e6"], "less than two cam revolutions"),
        (["--speed-ramp", "1000:9000:1"], "more than 2000"),
    ],
)
def test_bad_ramps(argv, message, capsys):
    base = ["valve", "simulate", example("valve/one_step_spring.toml"), "--cam", CAM, "--valve-train", TRAIN]
    assert main([*base, *argv]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_a_ramp_needs_a_valve_train():
    spring, cam, _ = _inputs()
    with pytest.raises(InputError, match="needs a valve train"):
        speed_ramp(spring, cam, None, 3000.0, 3400.0, 2000.0)


def test_cli_speed_ramp(capsys, tmp_path):
    csv = tmp_path / "ramp.csv"
    base = ["valve", "simulate", example("valve/one_step_spring.toml"), "--cam", CAM, "--valve-train", TRAIN]
    assert main([*base, "--speed-ramp", "3000:3400:2000", "--csv", str(csv)]) == 0
    out = capsys.readouterr().out
    assert "speed ramp 3000 -> 3400 cam rpm at 2000 rpm/s" in out and "FLOAT" in out
    assert "steady-state float speed" in out
    assert csv.read_text().splitlines()[0].startswith("time_s,")
