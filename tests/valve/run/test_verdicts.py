"""Coil clash classed and graded (:func:`springdyn.valve.run.verdicts.coil_clash`, issue 39 item 3):
the seating of a closed-end spring's transition coils is no clash; surge-driven impacts of the
active coils are; Type C and the distributed model grade on one scale; ``[criteria]
max_clash_severity`` judges it."""

from __future__ import annotations

import numpy as np
import pytest

import springdyn.valve as valve
from springdyn.core.errors import InputError
from springdyn.valve.design import criteria
from springdyn.valve.run import verdicts
from tests.paths import example

ONE_STEP = valve.ValveSpring.from_toml(example("valve/one_step_spring.toml"))
CAM = valve.Cam.from_toml(example("valve/cam_polydyne_ramps.toml"))
TRAIN = valve.ValveTrain.from_toml(example("valve/valve_train.toml"))

#: The tutorial's spring, cam and train (docs/tutorial-valve.md): closed and ground ends.
TUTORIAL = """
[spring]
type = "one-step"
wire_diameter = "3.5 mm"
outer_diameter = "25.5 mm"
end_type = "closed-ground"
active_coils = 5.5
free_length = "48 mm"
installed_length = "38 mm"
youngs_modulus = "206 GPa"
shear_modulus = "78.5 GPa"
density = "7850 kg/m^3"
damping_ratio = 0.05

[cam]
law = "polydyne"
lift = "8 mm"
duration = "110 deg"
ramp_height = "0.25 mm"
ramp_duration = "20 deg"

[valve_train]
layout = "direct-acting"
valve_mass = "45 g"
retainer_mass = "10 g"
follower_mass = "35 g"
lash = "0.15 mm"
"""


@pytest.fixture(scope="module")
def tutorial(tmp_path_factory):
    path = tmp_path_factory.mktemp("tutorial") / "my_engine.toml"
    path.write_text(TUTORIAL)
    return (
        valve.ValveSpring.from_toml(path).with_model("distributed"),
        valve.Cam.from_toml(path),
        valve.ValveTrain.from_toml(path),
    )


def test_the_transition_coils_are_the_ones_that_close_before_the_active_coils():
    """The distributed chain's transition elements lie at the ends (closed ends' pitch
    transition); Type C has none (its K elements stand for the closed end coils)."""
    dist = ONE_STEP.with_model("distributed").spring_model
    trans = verdicts.transition_elements(dist)
    n = trans.size
    assert trans[:5].any() and trans[-5:].any() and not trans[n // 2 - 5 : n // 2 + 5].any()
    assert not trans[[0, -1]].any()  # the end contacts never count as contact
    assert not verdicts.transition_elements(ONE_STEP.spring_model).any()


def test_a_closed_end_spring_at_low_speed_seats_its_transition_coils_without_clash(tutorial):
    """The tutorial's spring at 1900 cam rpm (where the old rule said "coil clash"): its
    transition coils close before the static spring closes them, passing no force to speak of
    through their contact: transition seating, no clash."""
    spring, cam, train = tutorial
    cc = valve.simulate(spring, cam, 1900.0, valve_train=train).summary["coil_clash"]
    assert cc["clash_class"] == "transition"
    assert cc["impacts"] >= 1  # the closing is there ...
    assert not cc["clash"] and cc["clash_severity"] < 0.02  # ... and it is seating
    sim = valve.simulate(spring, cam, 1900.0, valve_train=train)
    assert "transition coils seat" in sim.describe() and "FAIL" not in sim.describe().split("transition coils")[1]


def test_active_coils_clash_at_high_speed_in_both_models_on_one_scale():
    """The one-step spring at 4000 cam rpm (9 mm polydyne, the valve floating): the surge slams
    the active coils shut in both models; the severity, each model's force through contact over
    Fset, is well above the limit in both and of one order."""
    out = {}
    for model in ("type-c", "distributed"):
        out[model] = valve.simulate(ONE_STEP.with_model(model), CAM, 4000.0, valve_train=TRAIN).summary["coil_clash"]
    for cc in out.values():
        assert cc["clash_class"] == "active" and cc["clash"]
        assert cc["clash_severity"] > 5 * verdicts.MAX_CLASH_SEVERITY
        assert cc["closing_velocity_m_per_s"] > 0.5 and 0.0 < cc["contact_share"] < 1.0
    ratio = out["type-c"]["clash_severity"] / out["distributed"]["clash_severity"]
    assert 0.5 < ratio < 2.0


def test_both_models_agree_where_no_coil_closes():
    """At 1000 cam rpm neither model closes a coil beyond the static spring: class none, severity 0."""
    for model in ("type-c", "distributed"):
        t = valve.sweep(ONE_STEP.with_model(model), CAM, [1000.0], valve_train=TRAIN).summary_table()
        assert t["clash_severity"][0] == 0.0 and not t["coil_clash"][0]
        assert not t["transition_seating"][0] and not t["active_coil_closing"][0]


@pytest.fixture(scope="module")
def seating_table():
    """The distributed one-step spring at 2000 and 2500 cam rpm: transition seating, a few per
    cent of Fset through the contact."""
    sw = valve.sweep(ONE_STEP.with_model("distributed"), CAM, [2000.0, 2500.0], valve_train=TRAIN)
    return sw


def test_the_sweep_names_class_and_severity(seating_table):
    t = seating_table.summary_table()
    assert np.all(t["transition_seating"]) and not np.any(t["active_coil_closing"])
    assert 0.01 < t["clash_severity"][1] < verdicts.MAX_CLASH_SEVERITY and not np.any(t["coil_clash"])
    assert t["clash_severity"][1] > t["clash_severity"][0]  # harder with speed
    s = seating_table.summary
    assert s["speeds_with_transition_seating"] == 2 and s["speeds_with_coil_clash"] == 0
    assert s["max_clash_severity"] == pytest.approx(float(t["clash_severity"][1]))
    line = next(x for x in seating_table.describe().splitlines() if "static spring is open" in x)
    assert "transition coils seat at 2 of 2 runs" in line and "no coil clash" in line


def test_the_limit_key_changes_the_verdict(seating_table):
    """[criteria] max_clash_severity below the seating's severity fails the criterion; the
    default passes it; no_coil_clash = false does not judge it."""
    t = seating_table.summary_table()
    design = ONE_STEP.with_model("distributed").spring_model.design_figures(lift=CAM.lift, cam_rpm=2500.0)

    def row(c):
        rows = criteria.spring_verdicts(
            c, design, t, [2000.0, 2500.0], model="distributed", rated_cam_rpm=2500.0, wire_limit=2e9
        )
        return next(r for r in rows if r.name == "coil_clash")

    assert row(criteria.Criteria()).passed is True
    tight = criteria.Criteria.from_dict(dict(max_clash_severity="1 %"))
    assert tight.max_clash_severity == pytest.approx(0.01)
    assert row(tight).passed is False and "1 % of Fset" in row(tight).limit
    assert row(criteria.Criteria(max_clash_severity=0.01, no_coil_clash=False)).passed is True


def test_the_severity_limit_is_checked():
    with pytest.raises(InputError, match="max_clash_severity"):
        criteria.Criteria.from_dict(dict(max_clash_severity=-0.1))
