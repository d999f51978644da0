"""Issue 40, item 7: nonsense refused and unclear messages made clear, each case kept.

Each CLI case builds its bad input, runs the command and checks exit code 2, one line on
stderr naming the field, the value and what is allowed, and no traceback.  The library cases
check the same rules where they live (lift tables, pressure traces, force traces, the likely
cause of a solver failure, the simple adjuster's placement).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from springdyn.app.cli.main import main
from springdyn.core.errors import FactWarning, InputError, plain_numbers
from tests.paths import example

SPRING = example("valve/one_step_spring.toml")
CAM = example("valve/cam_345.toml")
EXHAUST = example("valve/exhaust_valve.toml")
PRESSURE = example("valve/cylinder_pressure.csv")
FOLLOWER = example("valve/valve_train_with_follower.toml")


def _text(path) -> str:
    with open(path, encoding="utf-8") as fh:
        return fh.read()


def _write(tmp_path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def _csv(tmp_path, name: str, header: str, rows) -> str:
    return _write(tmp_path, name, header + "\n" + "".join(",".join(f"{v:g}" for v in r) + "\n" for r in rows))


def _valve_lift_in_mm_as_metres(tmp_path):
    rows = [line.split(",") for line in _text(example("valve/valve_lift.csv")).split()[1:]]
    path = _csv(tmp_path, "lift.csv", "cam_angle_deg,valve_lift_m", [(float(a), 1e3 * float(z)) for a, z in rows])
    return ["valve", "cam-from-lift", path, "--valve-train", FOLLOWER, "--out", str(tmp_path / "cam.toml")]


def _both_lift_columns(tmp_path):
    rows = [line.split(",") for line in _text(example("valve/valve_lift.csv")).split()[1:]]
    path = _csv(
        tmp_path,
        "lift.csv",
        "cam_angle_deg,valve_lift_m,valve_lift_mm",
        [(float(a), float(z), 1e3 * float(z)) for a, z in rows],
    )
    return ["valve", "cam-from-lift", path, "--valve-train", FOLLOWER, "--out", str(tmp_path / "cam.toml")]


def _cam_table_in_mm_as_metres(tmp_path):
    _write(tmp_path, "lift.csv", _text(example("valve/lift_table.csv")).replace("lift_mm", "lift_m"))
    return ["valve", "cam", _write(tmp_path, "cam.toml", '[cam]\nlaw = "table"\nfile = "lift.csv"\n')]


def _trace(tmp_path, change):
    rows = [[a, 250.0 + 100.0 * math.sin(math.radians(a)) ** 2] for a in range(0, 360, 10)]
    change(rows)
    path = _csv(tmp_path, "trace.csv", "cam_angle_deg,retainer_force_N", rows)
    return ["valve", "calibrate", SPRING, "--trace", path, "--cam", CAM, "--cam-rpm", "2000"]


def _repeat(rows):
    rows[5][0] = rows[4][0]


def _backwards(rows):
    rows[7][0] -= 30.0


def _zero(rows):
    for r in rows:
        r[1] = 0.0


def _negative(rows):
    rows[9][1] = -12.5


def _gas(tmp_path, keep, scale=1.0):
    lines = _text(PRESSURE).split()
    rows = [(float(a), scale * float(p)) for a, p in (line.split(",") for line in lines[1:]) if keep(float(a))]
    path = _csv(tmp_path, "p.csv", lines[0], rows)
    return _gas_argv(path)


def _gas_argv(path):
    return ["valve", "simulate", SPRING, "--cam", EXHAUST, "--valve-train", EXHAUST, "--cam-rpm", "2000",
            "--gas-pressure", path]  # fmt: skip


def _train_file(tmp_path, name, source, old, new):
    text = _text(source)
    assert old in text
    return _write(tmp_path, name, text.replace(old, new))


def _geometry_pad(tmp_path):
    vt = _train_file(tmp_path, "vt.toml", example("valve/finger_follower_geometry.toml"), 'pad_x = "14 mm"',
                     'pad_x = "-21 mm"')  # fmt: skip
    return ["valve", "kinematics", example("valve/cam_finger.toml"), "--valve-train", vt]


def _spring_drawing(tmp_path, spring_type, pitches):
    text = (
        f'[spring]\ntype = "{spring_type}"\nmean_diameter = "22 mm"\nwire_diameter = "3.5 mm"\n'
        'installed_length = "38 mm"\nend_type = "closed-ground"\nactive_coils = 6\nlow_pitch_coils = 2.0\n'
        f'{pitches}material = "SiCr"\ndamping_ratio = 0.05\n'
    )
    return ["valve", "params", _write(tmp_path, "spring.toml", text)]


CASES = {
    # nonsense accepted before
    "a valve_lift_m column holding millimetres": (
        _valve_lift_in_mm_as_metres,
        ["column 'valve_lift_m': 8 is a lift of 8000 mm", "at most 50 mm", "name it valve_lift_mm"],
    ),
    "a [cam] table's lift_m column holding millimetres": (
        _cam_table_in_mm_as_metres,
        ["column 'lift_m': 9 is a lift of 9000 mm", "name it lift_mm"],
    ),
    "both lift columns": (_both_lift_columns, ["the columns valve_lift_m and valve_lift_mm both give the lift"]),
    "a trace's repeated angle": (
        lambda t: _trace(t, _repeat),
        ["trace.csv: row 7, column cam_angle_deg: 40 deg repeats the row before"],
    ),
    "a trace's backward angle": (
        lambda t: _trace(t, _backwards),
        ["trace.csv: row 9, column cam_angle_deg: 40 deg goes back from the row before (60 deg)"],
    ),
    "a trace of zeros": (lambda t: _trace(t, _zero), ["trace.csv: every retainer_force_N is zero"]),
    "a trace's negative force": (
        lambda t: _trace(t, _negative),
        ["trace.csv: row 11, column retainer_force_N: -12.5 N is negative"],
    ),
    "180 crank degrees missing from a pressure trace": (
        lambda t: _gas(t, lambda a: a < 0 or a >= 180),
        ["no rows from -1 deg to 180 deg, a gap of 181 crank deg", "gaps of up to 90 crank deg"],
    ),
    "a pressure trace of 1e6 bar": (
        lambda t: _gas(t, lambda a: True, scale=1e4),
        ["column 'pressure_bar'", "beyond any cylinder pressure (at most 500 bar"],
    ),
    "--cam-rpm with an open cam contact": (
        lambda t: [
            "valve",
            "train-modes",
            SPRING,
            "--cam",
            CAM,
            "--valve-train",
            example("valve/valve_train.toml"),
            "--cam-contact",
            "open",
            "--cam-rpm",
            "3000",
        ],  # fmt: skip
        ["--cam-rpm applies to --cam-contact closed"],
    ),
    "a roller's mass on a flat follower": (
        lambda t: [
            "valve",
            "friction",
            SPRING,
            "--cam",
            CAM,
            "--cam-rpm",
            "1000,2000",
            "--valve-train",
            _train_file(t, "vt.toml", FOLLOWER, "[friction]\n", '[friction]\nroller_mass = "12 g"\n'),
        ],  # fmt: skip
        ["[friction] roller_mass: [follower] kind = 'flat' has no roller"],
    ),
    # messages made clear
    "--engine-rpm 1e9 named as given (design)": (
        lambda t: ["valve", "design", SPRING, "--engine-rpm", "1e9"],
        ["--engine-rpm = 1e+09 (a cam speed of 5e+08 rpm): beyond any engine"],
    ),
    "--engine-rpm 1e9 named as given (calibrate --trace)": (
        lambda t: [*_trace(t, lambda rows: None)[:-2], "--engine-rpm", "1e9"],
        ["--engine-rpm = 1e+09 (a cam speed of 5e+08 rpm)"],
    ),
    "--engine-rpm named as given (tolerance)": (
        lambda t: [
            "valve",
            "tolerance",
            SPRING,
            "--cam",
            CAM,
            "--valve-train",
            example("valve/valve_train.toml"),
            "--tolerances",
            example("valve/tolerances.toml"),
            "--samples",
            "4",
            "--out",
            str(t / "tol"),
            "--engine-rpm",
            "60000",
        ],  # fmt: skip
        ["--engine-rpm = 60000 (a cam speed of 30000 rpm): the cam event"],
    ),
    "[geometry] pad_x named, not rocker_ratio": (
        _geometry_pad,
        ["[geometry] the lever drawn has a ratio of 0.04545 at rest", "pad_x and pad_y"],
    ),
    "a bad [spring] type named before the pitches": (
        lambda t: _spring_drawing(t, "twostep", 'low_pitch = "4 mm"\nhigh_pitch = "7 mm"\n'),
        ["spring.toml: [spring] type = 'twostep' is not allowed; choose one of 'one-step', 'two-step'"],
    ),
    "a missing key named, not the present one": (
        lambda t: _spring_drawing(t, "two-step", 'low_pitch = "4 mm"\n'),
        ["spring.toml: [spring] missing key 'high_pitch'"],
    ),
    "a missing ramp key named": (
        lambda t: [
            "valve",
            "cam",
            _train_file(t, "cam.toml", example("valve/cam_timing.toml"), 'ramp_height = "0.25 mm"\n', ""),
        ],  # fmt: skip
        ["ramp_duration is given without ramp_height"],
    ),
    "a folder for --gas-pressure": (lambda t: _gas_argv(str(t)), ["--gas-pressure", "is a folder, not a CSV file"]),
    "a folder for the spring": (lambda t: ["valve", "params", str(t)], ["is a folder, not a TOML file"]),
    "a folder for --trace": (
        lambda t: ["valve", "calibrate", SPRING, "--trace", str(t), "--cam", CAM, "--cam-rpm", "2000"],
        ["is a folder, not a CSV file"],
    ),
    "a unit pint does not know, in words": (
        lambda t: ["valve", "modes", SPRING, "--length", "22 mmm"],
        ["--length = '22 mmm' is not a quantity springdyn can read", "'mmm' is not a unit springdyn knows"],
    ),
    "echoed values without float noise": (
        lambda t: [
            "valve",
            "train-modes",
            SPRING,
            "--cam",
            CAM,
            "--valve-train",
            _train_file(
                t,
                "vt.toml",
                example("valve/finger_follower.toml"),
                "rocker_ratio = 1.64",
                "rocker_ratio = 0.15000000000000002",
            ),
        ],  # fmt: skip
        ["rocker_ratio = 0.15 must be from 0.2 to 5"],
    ),
    "the table tag once ([friction])": (
        lambda t: [
            "valve",
            "friction",
            SPRING,
            "--cam",
            CAM,
            "--cam-rpm",
            "1000,2000",
            "--valve-train",
            _train_file(t, "vt.toml", FOLLOWER, "fluid_friction = 0.02", "fluid_friction = 0.2"),
        ],  # fmt: skip
        ["vt.toml: [friction] fluid_friction = 0.2 must not exceed boundary_friction = 0.12"],
    ),
    "the table tag once ([valve_train])": (
        lambda t: [
            "valve",
            "train-modes",
            SPRING,
            "--cam",
            CAM,
            "--valve-train",
            _train_file(t, "vt.toml", example("valve/finger_follower.toml"), "rocker_ratio = 1.64\n", ""),
        ],  # fmt: skip
        ["vt.toml: [valve_train] layout = 'rocker' needs rocker_ratio"],
    ),
    "the table tag once ([follower])": (
        lambda t: [
            "valve",
            "kinematics",
            example("valve/cam_finger.toml"),
            "--valve-train",
            _train_file(t, "vt.toml", example("valve/finger_follower_geometry.toml"), 'roller_radius = "9 mm"\n', ""),
        ],  # fmt: skip
        ['vt.toml: [follower] kind = "roller" needs roller_radius'],
    ),
    "the program named once on a usage error": (
        lambda t: ["valve", "params", SPRING, "--bogus"],
        ["springdyn: error: unrecognized arguments: --bogus"],
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_bad_input_is_one_clear_line_and_exit_2(capsys, tmp_path, case):
    build, fragments = CASES[case]
    argv = [str(a) for a in build(tmp_path)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the examples' coil-bind clearance
        code = main(argv)
    _, err = capsys.readouterr()
    assert code == 2, err
    for fragment in fragments:
        assert fragment in err, (fragment, err)
    assert err.count("\n") == 1
    assert "Traceback" not in err
    assert "[friction] [friction]" not in err and "[valve_train] [valve_train]" not in err
    assert "[follower] [follower]" not in err and "springdyn: error: springdyn:" not in err
    if case.startswith("[geometry]"):
        assert "rocker_ratio" not in err  # the drawing's keys, not the key the drawing sets
    assert "unit registry" not in err


def test_echoed_values_have_six_significant_digits():
    """The one helper every message passes through: float noise removed, words and paths kept."""
    text = "x = 0.30000000000000004 m, ratio 5.545454545454547, 1000000000.0 rpm, 0.25 mm, run-0.1234567891/a"
    assert plain_numbers(text) == "x = 0.3 m, ratio 5.54545, 1e+09 rpm, 0.25 mm, run-0.1234567891/a"
    assert str(InputError("length = 0.30000000000000004 m")) == "length = 0.3 m"


def test_a_lift_table_in_python_beyond_50_mm_is_refused():
    from springdyn.valve import Cam

    angle = np.radians(np.arange(0.0, 360.0, 1.0))
    lift = 8.0 * np.sin(np.minimum(angle, math.pi)) ** 2  # 8 "m": millimetres given as metres
    with pytest.raises(InputError, match=r"a lift of 8000 mm is beyond any valve lift \(at most 50 mm\)"):
        Cam.from_table(angle, lift)


def test_a_pressure_gap_below_90_deg_is_stated(tmp_path):
    from springdyn.valve import Cam
    from springdyn.valve.cam.timing import Timing, crank_axis
    from springdyn.valve.train.gas_force import GasForce, read_pressure_trace

    crank, p = read_pressure_trace(PRESSURE)
    keep = (crank < 0) | (crank >= 60)
    axis = crank_axis(Cam.from_toml(EXHAUST), Timing.in_file(EXHAUST))
    with pytest.warns(FactWarning, match=r"no rows from -1 deg to 60 deg, a gap of 61 crank deg: the pressure is "):
        GasForce.from_trace(crank[keep], p[keep], axis=axis, seat_diameter=0.027)


def test_a_force_trace_is_checked_in_python_too():
    from springdyn.valve.design.calibrate import check_force_trace

    angle = np.arange(0.0, 360.0, 10.0)
    with pytest.raises(InputError, match=r"the trace: row 4, column cam_angle_deg: 10 deg repeats"):
        check_force_trace(np.r_[angle[:2], angle[1:]], np.full(angle.size + 1, 200.0))
    with pytest.raises(InputError, match="one revolution or more"):
        check_force_trace(np.r_[angle, 360.0, 370.0], np.full(angle.size + 2, 200.0))


@pytest.fixture(scope="module")
def setups():
    from springdyn.valve import Cam, ValveSpring, ValveTrain
    from springdyn.valve.run.setup import prepare

    spring, cam = ValveSpring.from_toml(SPRING), Cam.from_toml(CAM)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the 9 mm cam's coil-bind clearance
        return prepare(spring, cam, None), prepare(spring, cam, ValveTrain.from_toml(example("valve/valve_train.toml")))


def test_likely_cause_reads_the_speed_not_coil_contact(setups):
    """A failure at 4000 cam rpm of the direct-acting example (kinematic float near 2955 cam
    rpm, 6.7 surge orders) is put down to the speed; the 9 mm cam stays above the length of
    the coil-contact force statically, so coil contact is not named."""
    from springdyn.valve.run.runner import kinematic_float_rpm, likely_causes, solver_error

    alone, train = setups
    assert kinematic_float_rpm(train) == pytest.approx(2955, abs=5)
    causes = likely_causes(train, 4000.0)
    assert causes[0].startswith("the speed: 4000 cam rpm is above the train's kinematic float speed, about 2955")
    assert "6.7 cam orders" in causes[1]
    assert not any("coil contact" in c for c in causes)
    assert likely_causes(alone, 1000.0) == []
    message = str(solver_error(1000.0, 1000.0 * math.pi / 30, dict(status=2, t=0.01, steps=9), alone))
    assert "likely cause: the contact parameters" in message and "coil contact" not in message


def test_likely_cause_names_the_gas_pressure_and_static_coil_contact(setups):
    import dataclasses

    from springdyn.valve.run.runner import likely_causes
    from springdyn.valve.train.gas_force import GasForce

    alone, train = setups
    gas = dataclasses.replace(train, gas_force=GasForce(np.full(3600, 2000.0)))
    assert any(c.startswith("the gas pressure: up to 2000 N on the valve head") for c in likely_causes(gas, 1000.0))
    deep = dataclasses.replace(alone, table=dataclasses.replace(alone.table, h=alone.table.h * 1.5))
    assert any(c.startswith("coil contact: the cam drives the spring") for c in likely_causes(deep, 1000.0))


def test_the_simple_adjusters_placement_is_stated():
    """The simple adjuster of a finger follower is stated where it sits (the valve side) with
    what its placement does to the float speed; a bucket's and an [hla] table's are not."""
    from springdyn.valve import ValveTrain

    note = ValveTrain.from_toml(example("valve/finger_follower.toml")).adjuster_placement
    assert "at the valve side of the lever" in note and "3364 cam rpm to 3000, 11 %" in note
    assert ValveTrain.from_toml(example("valve/finger_follower_hla.toml")).adjuster_placement is None
    assert ValveTrain.from_toml(example("valve/bucket_hla.toml")).adjuster_placement is None


def test_train_modes_state_the_simple_adjusters_placement(capsys):
    argv = ["valve", "train-modes", SPRING, "--cam", example("valve/cam_finger.toml"), "--valve-train",
            example("valve/finger_follower.toml"), "--cam-rpm", "1000:2000:500"]  # fmt: skip
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert main(argv) == 0
    assert "note: adjuster: the simple hydraulic adjuster (hla_stiffness = 20 N/um" in capsys.readouterr().out
