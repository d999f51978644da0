"""``springdyn valve simulate`` and ``springdyn valve float``: contracts and bad input."""

import csv
import json

import pytest

from springdyn.app.cli.main import main
from tests.paths import EXAMPLES

EX = EXAMPLES / "valve"
SPRING, CAM, VT = str(EX / "one_step_spring.toml"), str(EX / "cam_345.toml"), str(EX / "valve_train.toml")
CAMR = str(EX / "cam_polydyne_ramps.toml")  # the valve train's lash is taken up by these ramps


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_simulate_csv_json_plot(capsys, tmp_path):
    c, p = tmp_path / "s.csv", tmp_path / "s.png"
    code, out, _ = run(
        capsys,
        "valve",
        "simulate",
        SPRING,
        "--cam",
        CAM,
        "--cam-rpm",
        "3000",
        "--revolutions",
        "2",
        "--points-per-revolution",
        "360",
        "--csv",
        str(c),
        "--plot",
        str(p),
        "--json",
    )
    assert code == 0
    s = json.loads(out)
    for key in ("max_retainer_force_N", "min_retainer_force_N", "max_seat_force_N", "min_seat_force_N", "coil_contact"):
        assert key in s
    assert "liftoff" not in s
    header = next(csv.reader(open(c)))
    assert header[:6] == ["time_s", "cam_angle_deg", "lift_m", "retainer_force_N", "seat_force_N", "static_force_N"]
    assert sum(1 for _ in open(c)) == 361
    assert p.read_bytes()[:4] == b"\x89PNG"


def test_engine_rpm_is_twice_cam_rpm(capsys):
    _, a, _ = run(
        capsys, "valve", "simulate", SPRING, "--cam", CAM, "--cam-rpm", "2000", "--revolutions", "1", "--json"
    )
    _, b, _ = run(
        capsys, "valve", "simulate", SPRING, "--cam", CAM, "--engine-rpm", "4000", "--revolutions", "1", "--json"
    )
    b = json.loads(b)
    assert b.pop("crank_angle_origin") == "cam angle 0 (no [timing] table)"  # an engine speed: crank angles
    for key in ("coil_contact", "end_separation"):
        for ev in b[key]:
            assert ev.pop("start_crank_deg") == pytest.approx(2 * ev["start_deg"])
            ev.pop("end_crank_deg")
    assert json.loads(a) == b


def test_design_and_train_modes_take_the_engine_speed(capsys):
    """Issue 39 (engine rpm everywhere): ``design`` and ``train-modes`` take ``--engine-rpm``
    as every speed-taking command does; a four-stroke engine speed is twice the cam speed."""
    _, a, _ = run(capsys, "valve", "design", SPRING, "--cam-rpm", "3500", "--json")
    _, b, _ = run(capsys, "valve", "design", SPRING, "--engine-rpm", "7000 rpm", "--json")
    assert json.loads(a) == json.loads(b) and "surge_margin" in json.loads(a)["installed"]
    common = ("valve", "train-modes", SPRING, "--cam", CAM, "--valve-train", VT, "--json")
    _, a, _ = run(capsys, *common, "--cam-rpm", "1000:5000:500")
    _, b, _ = run(capsys, *common, "--engine-rpm", "2000:10000:1000")
    assert json.loads(a) == json.loads(b)


def test_an_absurd_engine_speed_is_named_as_given(capsys):
    """Issue 39: ``--engine-rpm 1e9`` was refused as ``--cam-rpm = 5e+08 ... did you mean 5e+07?``:
    the message names the option the user gave, its value, the cam speed it means, and a guess in
    the user's unit."""
    code, _, err = run(capsys, "valve", "simulate", SPRING, "--cam", CAM, "--engine-rpm", "1e9")
    assert code == 2
    assert err.startswith("springdyn: error: --engine-rpm = 1e+09 (a cam speed of 5e+08 rpm): ")
    assert "beyond any engine" in err and "--cam-rpm" not in err  # (issue 40: every command's speed options)
    code, _, err = run(capsys, "valve", "simulate", SPRING, "--cam", CAM, "--engine-rpm", "60000")
    assert err.startswith("springdyn: error: --engine-rpm = 60000 (a cam speed of 30000 rpm): ")
    assert "did you mean 6000?" in err and "--cam-rpm" not in err
    code, _, err = run(capsys, "valve", "simulate", SPRING, "--cam", CAM, "--cam-rpm", "1e9")
    assert code == 2 and err.startswith("springdyn: error: --cam-rpm = 1e+09: ")


def test_valve_train_reports_liftoff(capsys):
    code, out, _ = run(
        capsys, "valve", "simulate", SPRING, "--cam", CAMR, "--cam-rpm", "3500", "--valve-train", VT, "--json"
    )
    s = json.loads(out)
    assert code == 0 and s["liftoff"] and {"start_deg", "end_deg", "duration_s"} <= set(s["liftoff"][0])
    code, out, _ = run(
        capsys,
        "valve",
        "float",
        SPRING,
        "--cam",
        CAMR,
        "--valve-train",
        VT,
        "--cam-rpm",
        "2000:4000:500",
        "--resolution",
        "5",
        "--json",
    )
    res = json.loads(out)
    assert code == 0 and 3000 < res["float_cam_rpm"] < 3300


@pytest.mark.parametrize(
    "extra,message",
    [
        (["--cam-rpm", "0"], "--cam-rpm = '0' must be a positive speed"),
        (["--cam-rpm", "3000 mm"], "--cam-rpm = '3000 mm' has the wrong dimension"),
        (["--cam-rpm", "3000", "--revolutions", "0"], "revolutions = 0 must be a whole number of at least 1"),
    ],
)
def test_simulate_bad_input(capsys, extra, message):
    code, _, err = run(capsys, "valve", "simulate", SPRING, "--cam", CAM, *extra)
    assert code == 2 and message in err and "Traceback" not in err


def test_bad_cam_file(capsys, tmp_path):
    f = tmp_path / "cam.toml"
    f.write_text('[cam]\nlaw = "3-4-5"\nlift = "9 mm"\nduration = "400 deg"\n')
    code, _, err = run(capsys, "valve", "simulate", SPRING, "--cam", str(f), "--cam-rpm", "3000")
    assert code == 2 and "duration = 400 deg must lie in (0, 360] deg" in err


def test_float_empty_range(capsys):
    code, _, err = run(
        capsys, "valve", "float", SPRING, "--cam", CAM, "--valve-train", VT, "--cam-rpm", "4000:2000:500"
    )
    assert code == 2 and "is empty" in err


@pytest.mark.parametrize(
    "train,cam",
    [
        ("valve_train.toml", "cam_polydyne_ramps.toml"),
        ("finger_follower.toml", "cam_finger.toml"),
        ("pushrod.toml", "cam_pushrod.toml"),
    ],
)
def test_every_layout_runs_simulate_float_and_train_modes(capsys, tmp_path, train, cam):
    vt, cm = str(EX / train), str(EX / cam)
    code, out, _ = run(
        capsys,
        "valve",
        "simulate",
        SPRING,
        "--cam",
        cm,
        "--valve-train",
        vt,
        "--cam-rpm",
        "1500",
        "--revolutions",
        "2",
        "--json",
    )
    s = json.loads(out)
    assert code == 0 and isinstance(s["liftoff"], list)
    assert 0 < s["fatigue_safety_factor"] <= s["static_fatigue_safety_factor"] * 1.01
    c, p = tmp_path / "f.csv", tmp_path / "f.png"
    code, out, _ = run(
        capsys,
        "valve",
        "float",
        SPRING,
        "--cam",
        cm,
        "--valve-train",
        vt,
        "--cam-rpm",
        "1000:4000:1000",
        "--resolution",
        "50",
        "--csv",
        str(c),
        "--plot",
        str(p),
        "--quiet",
    )
    assert code == 0 and "float speed" in out
    header = next(csv.reader(open(c)))
    assert header[:3] == ["cam_rpm", "engine_rpm", "min_cam_contact_force_N"]
    assert {"nose_separation", "seat_landings"} <= set(header)
    assert p.read_bytes()[:4] == b"\x89PNG"
    code, out, _ = run(capsys, "valve", "train-modes", SPRING, "--cam", cm, "--valve-train", vt, "--json")
    res = json.loads(out)
    assert code == 0 and len(res["full_lift_Hz"]) == 6 and res["resonance_speeds"]


def test_engine_speed_gives_crank_angles(capsys, tmp_path):
    """Issue 27: with --engine-rpm the outputs carry crank angles (four-stroke: twice the cam's)."""
    c = tmp_path / "s.csv"
    code, out, _ = run(capsys, "valve", "simulate", SPRING, "--cam", CAM, "--engine-rpm", "6000", "--csv", str(c))
    assert code == 0 and "3000 cam rpm" in out and f"wrote {c}" in out
    rows = list(csv.reader(open(c)))
    assert rows[0][:3] == ["time_s", "cam_angle_deg", "crank_angle_deg"]
    assert float(rows[100][2]) == pytest.approx(2 * float(rows[100][1]))
