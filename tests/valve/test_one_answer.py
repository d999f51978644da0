"""One spring, one answer (issue 39): one solid length and one first surge frequency per spring
and state, named with the model and definition; speeds in engine or cam rpm in every table;
every criterion named with the model that judged it; Type C's valid range said where a run
leaves it.

References: EN 13906-1:2013 (solid length by the end type); the report's own rule that the
criteria come from the distributed model (``design.JUDGING_MODEL``, docs/which-model.md).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import springdyn.valve as valve
from springdyn.app.report.valve import ReportSettings, _type_c_range
from springdyn.core.errors import InputError
from springdyn.core.units import omega_to_rpm
from springdyn.valve import design
from springdyn.valve.run.results import type_c_outside_range
from springdyn.valve.spring.results import SpringParameters
from tests.paths import example

SPRING = valve.ValveSpring.example("one-step")


@pytest.mark.parametrize("model", ["type-c", "distributed"])
def test_params_and_design_state_one_first_surge_frequency(model):
    """`valve params` states the one first surge frequency (the model's chain, ends fixed, at the
    installed length) and `valve design` shows the same figure at installed length; Type C's
    closed forms f1/f2 are labelled comparisons, not a second answer."""
    sp = SPRING.with_model(model)
    f = sp.spring_model.first_mode_installed
    text = SpringParameters.of(sp).describe()
    figs = sp.spring_model.design_figures(lift=9e-3, cam_rpm=3000.0)
    assert figs["installed"]["surge_frequency_Hz"] == pytest.approx(f, rel=1e-12)
    meaning = sp.spring_model.parameter_meaning("f1")
    if model == "type-c":
        assert "comparison" in meaning and "closed form" in meaning
    else:
        assert "chain's first mode" in meaning
    assert sp.spring_model.surge_frequency_definition == f"the {model} chain's first mode, ends fixed"
    assert f"first surge frequency {f:.1f} Hz at installed length" in text


def test_params_text_names_the_one_surge_frequency(capsys):
    """The CLI's `valve params` header names the figure every margin uses."""
    from springdyn.app.cli.main import main

    assert main(["valve", "params", str(example("valve/one_step_spring.toml"))]) == 0
    out = capsys.readouterr().out
    f = SPRING.spring_model.first_mode_installed
    assert f"first surge frequency {f:.1f} Hz at installed length (the type-c chain's first mode, ends fixed" in out
    assert "solid length 28.000 mm (the MMS document, Dw (N1 + N2 + 0.5))" in out


@pytest.mark.parametrize(
    ("cls", "cam_key", "engine_key", "value"),
    [
        (design.Criteria, "min_float_cam_rpm", "min_float_engine_rpm", "3500 rpm"),
        (ReportSettings, "max_cam_rpm", "max_engine_rpm", "4000 rpm"),
    ],
)
def test_a_speed_key_takes_its_twin_on_the_other_shaft(cls, cam_key, engine_key, value):
    """A four-stroke's camshaft turns once per two crankshaft turns: a speed given on one shaft
    is the same field as twice (half) the speed on the other; both at once is refused."""
    field = cam_key if hasattr(cls, "__dataclass_fields__") and cam_key in cls.__dataclass_fields__ else engine_key
    given_cam = cls.from_dict({cam_key: value})
    given_engine = cls.from_dict({engine_key: f"{2 * float(value.split()[0]):g} rpm"})
    assert getattr(given_cam, field) == pytest.approx(getattr(given_engine, field), rel=1e-12)
    with pytest.raises(InputError, match="give the same speed twice"):
        cls.from_dict({cam_key: value, engine_key: value})


def test_a_two_stroke_speed_twin_is_the_same_speed():
    """A two-stroke's camshaft turns with the crankshaft (``cam_per_crank = 1``)."""
    c = design.Criteria.from_dict({"min_float_engine_rpm": "3500 rpm"}, cam_per_crank=1.0)
    assert omega_to_rpm(c.min_float_cam_rpm) == pytest.approx(3500.0, rel=1e-12)


def test_the_load_spectrum_takes_engine_speeds():
    s = design.LoadSpectrum.from_dict({"engine_rpm": ["1500 rpm", "3000 rpm"], "share": [0.5, 0.5]})
    assert s.speeds_rpm == pytest.approx([750.0, 1500.0], rel=1e-12)


def test_an_unknown_speed_key_lists_the_twins():
    with pytest.raises(InputError, match="did you mean 'min_float_engine_rpm'"):
        design.Criteria.from_dict({"min_float_engin_rpm": "3000 rpm"})


def test_the_float_scan_given_in_engine_rpm_gives_engine_rpm(tmp_path):
    """`valve float --engine-rpm` prints an engine-rpm column and writes engine_rpm to its CSV."""
    from springdyn.app.cli.main import main

    csv = tmp_path / "f.csv"
    args = ["valve", "float", str(example("valve/one_step_spring.toml")), "--cam", str(example("valve/cam_345.toml"))]
    args += ["--valve-train", str(example("valve/valve_train.toml")), "--engine-rpm", "5000,5500", "--quiet"]
    assert main(args + ["--csv", str(csv)]) == 0
    head = csv.read_text().splitlines()[0].split(",")
    assert head[:2] == ["cam_rpm", "engine_rpm"]
    rows = np.loadtxt(csv, delimiter=",", skiprows=1, usecols=(0, 1))
    np.testing.assert_allclose(rows[:, 1], 2.0 * rows[:, 0], rtol=1e-12)


def test_type_c_says_where_it_leaves_its_range():
    """A Type C run with coil contact, end separation or lift-off says so and points to the
    distributed model; the distributed model's run needs no such note."""
    assert type_c_outside_range("type-c", {"coil_contact": [{}], "end_separation": [], "liftoff": []}).startswith(
        "TYPE C RANGE: this run has coil contact"
    )
    assert type_c_outside_range("type-c", {"coil_contact": [], "end_separation": [], "liftoff": []}) == ""
    assert type_c_outside_range("distributed", {"coil_contact": [{}]}) == ""


def test_the_report_states_type_c_s_valid_range():
    """The speed where the two models' end forces first differ by more than 5 % of Fset, and the
    first speed where a verdict differs, from the two sweep tables."""
    rpm = np.array([1000.0, 2000.0, 3000.0, 4000.0])
    worst = np.array([0.01, 0.03, 0.07, 0.2])
    ta = dict(min_retainer_force_N=np.array([100.0, 90.0, 10.0, -1.0]), coil_clash=np.array([0, 0, 0, 0]))
    tb = dict(min_retainer_force_N=np.array([100.0, 90.0, 20.0, 5.0]), coil_clash=np.array([0, 0, 1, 1]))
    text = _type_c_range(rpm, worst, ta, tb)
    assert "leaves its valid range for this spring at 3000 cam rpm" in text
    assert "end separation verdict differs from 4000 cam rpm" in text
    assert "coil clash verdict differs from 3000 cam rpm (2 speeds" in text
    assert "stay within 5 % of Fset" in _type_c_range(rpm, worst * 0.1, ta, ta)


def test_every_train_verdict_names_its_model():
    """The float, seating and pump-up verdicts carry the model that judged them."""
    from springdyn.valve.run.results import FloatSpeedResult

    res = FloatSpeedResult([1000.0, 2000.0], [10.0, 0.0], 1500.0, [1000.0, 2000.0], 10.0, model="distributed")
    crit = design.Criteria()
    v = design.float_verdict(crit, res, 1200.0, model="distributed", beside="Type C: 1450 cam rpm")
    assert v.model == "distributed" and v.label == "float speed, distributed" and "Type C: 1450" in v.note
    assert design.seating_verdict(crit, 0.3, 1200.0, model="type-c").model == "Type C"
    assert design.pump_up_verdict(0.0, 1200.0, model="distributed").model == "distributed"


def _json(capsys, args):
    import json

    from springdyn.app.cli.main import main

    assert main(args + ["--json"]) == 0
    return json.loads(capsys.readouterr().out)


SPRING_FILE = str(example("valve/one_step_spring.toml"))
CAM_FILE = str(example("valve/cam_polydyne_ramps.toml"))
TRAIN_FILE = str(example("valve/valve_train.toml"))


@pytest.mark.parametrize(
    "command",
    [
        ["valve", "design", SPRING_FILE, "--lift", "9mm"],
        ["valve", "train-modes", SPRING_FILE, "--cam", CAM_FILE, "--valve-train", TRAIN_FILE],
    ],
)
def test_a_new_user_s_engine_speed_needs_no_conversion(command, capsys):
    """Issue 39: design and train-modes given 6000 engine rpm give what 3000 cam rpm gives."""
    engine = _json(capsys, command + ["--engine-rpm", "6000"])
    cam = _json(capsys, command + ["--cam-rpm", "3000"])
    assert engine == cam


def test_the_life_spectrum_in_engine_rpm(capsys, tmp_path):
    """The example spectrum is given in engine rpm: the life is that of the same cam speeds."""
    base = ["valve", "life", SPRING_FILE, "--cam", CAM_FILE, "--valve-train", TRAIN_FILE, "--quiet"]
    engine = _json(capsys, base + ["--spectrum", str(example("valve/spectrum.toml"))])
    text = Path(example("valve/spectrum.toml")).read_text()
    cam_file = tmp_path / "spectrum.toml"
    cam_file.write_text(
        text.replace(
            'engine_rpm = ["1500 rpm", "3000 rpm", "4500 rpm", "6000 rpm"]', "cam_rpm = [750, 1500, 2250, 3000]"
        )
    )
    cam = _json(capsys, base + ["--spectrum", str(cam_file)])
    assert engine == cam
