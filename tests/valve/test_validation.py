"""Bad input for valve springs: one clear message each."""

import re

import pytest

from springdyn.core.errors import InputError
from springdyn.valve import ValveSpring

BASE = {
    "type": "one-step",
    "mean_diameter": "22 mm",
    "wire_diameter": "3.5 mm",
    "free_length": "48 mm",
    "installed_length": "38 mm",
    "dead_coils": 1.0,
    "low_pitch_coils": 0.0,
    "high_pitch_coils": 7.5,
    "youngs_modulus": "206 GPa",
    "shear_modulus": "78.5 GPa",
    "density": "7850 kg/m^3",
    "damping_ratio": 0.05,
}


def build(**changes):
    d = dict(BASE)
    for k, v in changes.items():
        if v is None:
            d.pop(k)
        else:
            d[k] = v
    return ValveSpring.from_dict(d)


def test_base_is_valid_and_bare_numbers_are_si():
    assert build().mean_diameter == pytest.approx(0.022)
    assert build(mean_diameter=0.022).mean_diameter == 0.022


@pytest.mark.parametrize(
    "changes,pattern",
    [
        ({"mean_diameter": "0 mm"}, r"mean_diameter = 0 mm must be positive"),
        ({"wire_diameter": "-3.5 mm"}, r"wire_diameter = -3\.5 mm must be positive"),
        ({"youngs_modulus": "0 GPa"}, r"youngs_modulus = 0 GPa must be positive"),
        ({"shear_modulus": -1}, r"shear_modulus = -1e-09 GPa must be positive"),
        ({"density": None}, r"missing key 'density'"),
        ({"free_length": None}, r"missing key 'free_length'"),
        ({"free_lenght": "48 mm"}, r"unknown key 'free_lenght' \(did you mean 'free_length'\?\)"),
        ({"installed_length": "50 mm"}, r"installed_length = 50 mm must be shorter than free_length = 48 mm"),
        ({"installed_length": "48 mm"}, r"installed_length = 48 mm must be shorter than free_length = 48 mm"),
        ({"high_pitch_coils": 2.0}, r"active coils N1 \+ N2 - 2 Nb = 0 \+ 2 - 2\*1 = 0 must be positive"),
        ({"type": "two-step", "low_pitch_coils": 3.0, "high_pitch_coils": 1.0}, r"N2 - Nb = 1 - 1 must be positive"),
        ({"low_pitch_coils": 2.0}, r"low_pitch_coils = 2 must be 0 for a one-step spring"),
        ({"youngs_modulus": "0.004 GPa"}, r"contact stiffness K = .* must exceed 2 K1"),
        (
            {"type": "two-step", "low_pitch_coils": 2.0, "high_pitch_coils": 6.0, "youngs_modulus": "0.007 GPa"},
            r"must exceed 3 K2",
        ),
        ({"free_length": "500 mm"}, r"end mass me = -.* kg must be positive"),
        ({"installed_length": "28 mm"}, r"installed_length = 28 mm is at or below coil contact"),
        ({"installed_length": "27 mm"}, r"installed_length = 27 mm is at or below coil contact"),
        ({"damping_ratio": -0.1}, r"damping_ratio = -0\.1 must be zero or positive"),
        (
            {"mean_diameter": "22 kg"},
            r"mean_diameter = '22 kg' has the wrong dimension: expected a quantity convertible to m",
        ),
        ({"mean_diameter": "22 parsecs per fortnight x"}, r"mean_diameter = .* is not a quantity"),
        ({"type": "three-step"}, r"type = 'three-step' is not allowed; choose one of 'one-step', 'two-step'"),
        ({"dead_coils": "one"}, r"dead_coils = 'one' is not a quantity"),
    ],
)
def test_bad_input_one_clear_message(changes, pattern):
    with pytest.raises(InputError, match=pattern) as exc:
        build(**changes)
    assert isinstance(exc.value, ValueError)
    assert "\n" not in str(exc.value)


def test_length_outside_curve_range():
    s = build()
    with pytest.raises(
        InputError, match=r"length = 10 mm is outside the range of the spring: it must lie between 20\.08\d mm"
    ):
        s.spring_model.static_force(0.010)
    with pytest.raises(InputError, match=r"length = 50 mm is outside the range.*free length Lf = 48 mm"):
        s.spring_model.modes(0.050)
    with pytest.raises(InputError, match=r"stop = 5 mm"):
        s.spring_model.static_curve(stop=0.005)


def test_python_api_validates_too():
    with pytest.raises(InputError, match="installed_length = 50 mm must be shorter than free_length = 48 mm"):
        ValveSpring.example("one-step").replace(installed_length=0.050)


def test_toml_errors_name_the_file(tmp_path):
    f = tmp_path / "s.toml"
    f.write_text('[spring]\ntype = "one-step"\nmean_diametre = "22 mm"\n')
    with pytest.raises(InputError, match=re.escape(f"{f}: [spring] unknown key 'mean_diametre'")):
        ValveSpring.from_toml(f)
    f.write_text("[spring\n")
    with pytest.raises(InputError, match="not valid TOML"):
        ValveSpring.from_toml(f)
    f.write_text("[cam]\nlaw='3-4-5'\n")
    with pytest.raises(InputError, match=r"no \[spring\] table"):
        ValveSpring.from_toml(f)
    with pytest.raises(InputError, match="no such file"):
        ValveSpring.from_toml(tmp_path / "missing.toml")


# --------------------------------------------------------------------------------------
# Reproducers of bad input on the library side: every bad input is an InputError naming the
# argument, the value and what is allowed; nothing hangs, overflows or returns NaN.

import math
import warnings

import numpy as np

from springdyn.valve import Cam, ValveTrain, float_speed, simulate, sweep
from springdyn.valve.spring.modes import surge_margin

CAM = Cam(law="3-4-5", lift=0.009, duration=math.radians(120))
VT = ValveTrain(valve_mass=0.05)


@pytest.fixture(scope="module")
def one_step():
    return ValveSpring.example("one-step")


@pytest.mark.parametrize("resolution", [0, -5.0, float("nan"), float("inf"), "5", True])
def test_float_speed_resolution_must_be_positive(one_step, resolution):
    """A hang: ``float --resolution 0`` (or negative) bisected forever."""
    with pytest.raises(InputError, match=r"resolution = .* must be a positive, finite speed \[rev/min\]"):
        float_speed(one_step, CAM, VT, [3000.0], resolution=resolution)


def test_float_speed_bisection_is_bounded(one_step):
    """A resolution finer than 40 halvings of the scanned range can reach is refused before
    any simulation (the bisection loop runs at most 40 times)."""
    with pytest.raises(
        InputError,
        match=r"resolution = 1e-12 rev/min is finer than the bisection reaches in 40 "
        r"halvings .* at least 3\.6\de-09 rev/min",
    ):
        float_speed(one_step, CAM, VT, [2000.0, 4000.0], resolution=1e-12)


@pytest.mark.parametrize("speeds", [[], [float("nan")], [3000.0, float("inf")], [-3000.0], "fast"])
def test_float_speed_speeds(one_step, speeds):
    with pytest.raises(InputError, match="cam_rpm = .* (must hold at least one speed|must be a speed)"):
        float_speed(one_step, CAM, VT, speeds)


@pytest.mark.parametrize("key", ["rtol", "atol"])
@pytest.mark.parametrize("value", [float("inf"), -1.0, float("nan"), 0.0, 1.0, "1e-6"])
def test_tolerances_are_inputs(one_step, key, value):
    """``--rtol inf`` or ``-1`` ran up to 52 s and was reported as a
    solver failure; now it is refused at once, naming the allowed range."""
    pattern = {
        "rtol": r"rtol = .* is outside the allowed range 1e-12 <= rtol <= 0\.01",
        "atol": r"atol = .* is outside the allowed range 1e-15 <= atol <= 1e-05",
    }[key]
    with pytest.raises(InputError, match=pattern):
        simulate(one_step, CAM, 3000, **{key: value})
    with pytest.raises(InputError, match=pattern):
        sweep(one_step, CAM, [3000.0], **{key: value})


@pytest.mark.parametrize(
    "key,value",
    [
        ("revolutions", 2.5),
        ("revolutions", 0),
        ("revolutions", float("inf")),
        ("revolutions", float("nan")),
        ("revolutions", 10_001),
        ("revolutions", True),
        ("revolutions", "3"),
        ("points_per_revolution", 720.5),
        ("points_per_revolution", 8),
        ("points_per_revolution", 10**7),
    ],
)
def test_whole_number_settings(one_step, key, value):
    """``revolutions`` and ``points_per_revolution`` are whole numbers in a stated range;
    the type is checked like the value (2.5 -> InputError, not a silent truncation)."""
    pattern = rf"{key} = .* must be a whole number of at least \d+ and at most \d+"
    with pytest.raises(InputError, match=pattern):
        simulate(one_step, CAM, 3000, **{key: value})
    with pytest.raises(InputError, match=pattern):
        sweep(one_step, CAM, [3000.0], **{key: value})


def test_whole_float_settings_still_accepted(one_step):
    """A whole float (3.0, e.g. from a TOML number) is still a whole number."""
    sim = simulate(one_step, CAM, 3000, 2.0, points_per_revolution=360.0)
    assert sim.revolutions == 2


@pytest.mark.parametrize("rpm", [0, -3000, float("nan"), float("inf"), True, "3000", 5e-324])
def test_design_figures_need_a_positive_speed(one_step, rpm):
    """``valve design --cam-rpm 0`` crashed; ``-3000`` gave a negative surge margin; 5e-324 an
    infinite one."""
    with pytest.raises(
        InputError,
        match=r"cam_rpm = .* must be a finite camshaft speed of at least 0.1 rev/min: the surge margin",
    ):
        one_step.spring_model.design_figures(0.009, rpm)


def test_surge_margin_function_refuses_a_standing_cam():
    with pytest.raises(InputError, match=r"cam_speed_rpm = 0 must be a positive"):
        surge_margin(450.0, 0)
    assert surge_margin(450.0, 3000.0) == pytest.approx(9.0, rel=1e-15)


@pytest.mark.parametrize("points", [2.5, 1, "400", None])
def test_static_curve_points(one_step, points):
    """``static_curve(points=2.5)`` (checked: an InputError)."""
    with pytest.raises(InputError, match=r"points = .* must be a whole number of at least 2"):
        one_step.spring_model.static_curve(points=points)


@pytest.mark.parametrize("backend,rpm,limit", [("scipy", 1.0, r"59\.7"), ("compiled", 1e-3, r"0\.597")])
def test_low_speed_work_is_bounded(one_step, backend, rpm, limit):
    """A hang: ``simulate --cam-rpm 1 --backend scipy`` ran without a step cap.
    The number of periods of the chain's fastest mode (6633 Hz for the example) bounds the
    work: 2e4 for SciPy, 2e6 for the compiled engine (whose 1e7-step cap would otherwise
    end a long run in a misleading solver failure)."""
    with pytest.raises(
        InputError,
        match=rf"cam_rpm = {rpm:g} is too slow for backend = '{backend}'.*"
        rf"at least {limit} rev/min",
    ):
        simulate(one_step, CAM, rpm, 3, backend=backend)


# ---------------------------------------------------------------- extreme springs
@pytest.mark.parametrize(
    "changes,pattern",
    [
        (
            {"mean_diameter": 1e-300},
            r"mean_diameter = 1e-300 m is far smaller than any helical spring: it must "
            r"lie between 1e-06 m and 1000 m",
        ),
        ({"mean_diameter": 1e300}, r"mean_diameter = 1e\+300 m is far larger than any helical spring"),
        ({"wire_diameter": 1e-300}, r"wire_diameter = 1e-300 m is far smaller"),
        ({"free_length": 1e300}, r"free_length = 1e\+300 m is far larger"),
        ({"youngs_modulus": 1e300}, r"youngs_modulus = 1e\+300 Pa is far larger than any spring material"),
        ({"youngs_modulus": 206.0}, r"youngs_modulus = 206 Pa is far smaller .*: did you mean 206 GPa\?"),
        ({"shear_modulus": 1e-300}, r"shear_modulus = 1e-300 Pa is far smaller"),
        ({"density": 1e300}, r"density = 1e\+300 kg/m\^3 is far larger than any solid"),
        ({"high_pitch_coils": 1e300}, r"high_pitch_coils = 1e\+300 is more coils than any spring has"),
        ({"damping_ratio": 5.0}, r"damping_ratio = 5 is above critical damping \(1\).*did you mean 5 % \(0\.05\)\?"),
        ({"damping_ratio": 1.0}, r"damping_ratio = 1 is at critical damping \(1\).*did you mean 1 % \(0\.01\)\?"),
        (
            {"wire_diameter": 0.030},
            r"spring index C = mean_diameter / wire_diameter = 22 mm / 30 mm = 0\.7333 must "
            r"lie between 3 and 20 \(EN 13906-1 recommends 4 to 20",
        ),
        ({"wire_diameter": 0.001}, r"spring index C = .* = 22 must lie between 3 and 20"),
    ],
)
def test_extreme_springs_are_input_errors(changes, pattern):
    """An extreme ValveSpring raised ZeroDivisionError/OverflowError;
    now every value outside what a helical spring can be is an InputError naming the key,
    the value and the allowed range (the ranges keep the closed forms of [MMS] finite)."""
    with pytest.raises(InputError, match=pattern) as exc:
        ValveSpring.example("one-step").replace(**changes)
    assert "\n" not in str(exc.value)


def test_random_extreme_springs_never_crash():
    """Property (seeded): springs with every length, modulus and density drawn log-uniformly
    over 600 decades either build with finite internal parameters or raise InputError."""
    rng = np.random.default_rng(2024)
    base = ValveSpring.example("one-step")
    keys = [
        "mean_diameter",
        "wire_diameter",
        "free_length",
        "installed_length",
        "youngs_modulus",
        "shear_modulus",
        "density",
    ]
    built = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)
        for _ in range(300):
            key = keys[rng.integers(len(keys))]
            value = (
                float(10.0 ** rng.uniform(-300, 300))
                if rng.random() < 0.5
                else getattr(base, key) * float(10.0 ** rng.uniform(-4, 4))
            )
            try:
                s = base.replace(**{key: value})
            except InputError:
                continue
            built += 1
            assert all(np.isfinite(v) for v in s.spring_model.internal_parameters().values() if isinstance(v, float))
    assert built > 10  # the property is not vacuous


@pytest.mark.parametrize(
    "changes,pattern",
    [
        (
            {"mean_diameter": 22.0, "wire_diameter": 3.5, "free_length": 48.0, "installed_length": 38.0},
            r"mean_diameter = 22 m is far larger than any valve spring \(5 mm to 100 mm\): did you mean 22 mm\?",
        ),
        # the example scaled by 1/20 and by 8 (a uniform scale keeps the model valid)
        (
            {"wire_diameter": 0.175e-3, "mean_diameter": 1.1e-3, "free_length": 2.4e-3, "installed_length": 1.9e-3},
            r"wire_diameter = 0\.175 mm is far smaller than any valve spring \(0\.5 mm to 15 mm\)",
        ),
        (
            {"wire_diameter": 28e-3, "mean_diameter": 176e-3, "free_length": 384e-3, "installed_length": 304e-3},
            r"free_length = 384 mm is far larger than any valve spring \(8 mm to 300 mm\)",
        ),
        (
            {"density": 7.85},
            r"density = 7\.85 kg/m\^3 is far smaller than spring steel or titanium .*: did you mean "
            r"7850 kg/m\^3\?",
        ),
        (
            {"shear_modulus": 206e9, "youngs_modulus": 78.5e9},
            r"shear_modulus = 206 GPa exceeds youngs_modulus = "
            r"78\.5 GPa: .* swapped",
        ),
        ({"damping_ratio": 0.5}, r"damping_ratio = 0\.5 is far above the damping of valve springs"),
    ],
)
def test_unit_slips_warn(changes, pattern):
    """A bare ``mean_diameter = "22"`` is 22 m with no word; values far
    outside valve springs now warn (not an error: the model still holds) naming the slip."""
    with pytest.warns(UserWarning, match=pattern) as record:
        ValveSpring.example("one-step").replace(**changes)
    assert all(r.filename == __file__ for r in record)  # attributed to the caller's line


def test_the_examples_give_no_plausibility_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ValveSpring.example("one-step")
        ValveSpring.example("two-step")


def test_a_model_error_carries_the_unit_slip():
    """206 MPa for 206 GPa breaks the model's K > 2 K1: the error says why it likely happened."""
    with pytest.raises(
        InputError,
        match=r"must exceed 2 K1 .*note: youngs_modulus = 0\.206 GPa .* did you mean "
        r"206 GPa\?",
    ):
        ValveSpring.example("one-step").replace(youngs_modulus=206e6)


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        # issue 40: a traceback (exit 70): the TOML reference types load_points as a string
        ({"load_points": "38 mm"}, r"load_points = '38 mm' must be an array of tables"),
        (
            {"load_points": [{"length": "38 mm", "force": "250 N"}, {"length": "38 mm", "force": "260 N"}]},
            r"load_points\[0\] and load_points\[1\] give two forces \(250 N and 260 N\) at one length 38 mm",
        ),
        ({"shear_yield_strength": "2000 MPa", "tensile_strength": "1900 MPa"}, "is not below tensile_strength"),
        ({"contact_stiffness": "1e30 N/mm"}, "outside any coil contact"),
        # a traceback (exit 70): a unit on dead_coils beside pitch keys
        ({"dead_coils": "1 coil", "pitch": "7.5 mm", "free_length": None}, "dead_coils = '1 coil' must be a number"),
    ],
)
def test_nonsense_of_issue_40_is_refused(changes, message):
    """Accepted nonsense (issue 40): each now one message naming the key."""
    with pytest.raises(InputError, match=message):
        build(**changes)
