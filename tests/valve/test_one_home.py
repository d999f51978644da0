"""One home per law and per rule, checked by behaviour: change a law, a rule or a limit where
it lives and every consumer changes with it (issue 38, "One home per law and per rule").

The consumers: a simulation's summary (:func:`springdyn.valve.simulate`), a sweep's table
(:func:`springdyn.valve.sweep`), the synthesis' margins (:func:`springdyn.valve.design.synthesis.evaluate`),
the tolerance study's failing shares (:meth:`ToleranceStudy.failures`) and the report's rows
(:func:`springdyn.valve.design.criteria.spring_verdicts` and the others, and the report section
itself, slow).  Each law is changed by a known factor at its home (``monkeypatch`` on the
module that defines it); the consumers must show that factor, or the flipped verdict.  A
consumer with a copy of its own (as the synthesis had, ``8 F D / (pi d^3)`` inline) would not.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
import xarray as xr

import springdyn.valve as valve
from springdyn.valve.design import criteria
from springdyn.valve.design import synthesis as syn
from springdyn.valve.design.tolerances import ToleranceStudy
from springdyn.valve.run import studies, verdicts
from springdyn.valve.spring import formulas, solid_length, stress
from tests.paths import example

SPRING = valve.ValveSpring.from_toml(example("valve/one_step_spring.toml"))
CAM = valve.Cam.from_toml(example("valve/cam_polydyne_ramps.toml"))
TRAIN = valve.ValveTrain.from_toml(example("valve/valve_train.toml"))
SPEEDS = [1500.0, 2500.0]
REQ = syn.Requirements.from_dict(
    dict(
        installed_length="38 mm",
        installed_force="325 N",
        lift="9 mm",
        open_force="610 N",
        max_outer_diameter="31 mm",
        min_inner_diameter="16 mm",
        min_surge_frequency="400 Hz",
    )
)


def _fresh():
    """A new spring object (its model and cached parameters computed anew under a patch)."""
    return dataclasses.replace(SPRING)


def _candidates():
    return syn.evaluate(REQ, 3.8e-3, 24e-3, 0.0, 7.5, 48e-3)


def _consumers():
    """The figures every consumer gives for the example spring (spring alone and with its train)."""
    sp = _fresh()
    sim = valve.simulate(sp, CAM, 2500.0, valve_train=TRAIN)
    table = valve.sweep(sp, CAM, SPEEDS, valve_train=TRAIN).summary_table()
    fig = sp.spring_model.design_figures(lift=CAM.lift, cam_rpm=2500.0)
    return dict(sim=sim.summary, table=table, design=fig, synthesis=_candidates())


def test_the_corrected_stress_has_one_home(monkeypatch):
    """stress.bergstraesser_factor doubled: every corrected stress doubles (simulation, sweep,
    design figures), the synthesis' Goodman safety falls."""
    a = _consumers()
    k = stress.bergstraesser_factor
    monkeypatch.setattr(stress, "bergstraesser_factor", lambda w: 2.0 * k(w))
    b = _consumers()
    assert b["sim"]["peak_shear_stress_Pa"] == pytest.approx(2 * a["sim"]["peak_shear_stress_Pa"], rel=1e-12)
    np.testing.assert_allclose(b["table"]["peak_shear_stress_Pa"], 2 * a["table"]["peak_shear_stress_Pa"], rtol=1e-12)
    assert b["design"]["installed"]["shear_stress_Pa"] == pytest.approx(
        2 * a["design"]["installed"]["shear_stress_Pa"], rel=1e-12
    )
    assert b["synthesis"]["goodman"][0] < 0.6 * a["synthesis"]["goodman"][0]
    assert b["sim"]["fatigue_safety_factor"] < 0.6 * a["sim"]["fatigue_safety_factor"]


def test_the_goodman_line_has_one_home(monkeypatch):
    """stress.goodman_safety_factor halved: every Goodman safety halves."""
    a = _consumers()
    n = stress.goodman_safety_factor
    monkeypatch.setattr(stress, "goodman_safety_factor", lambda *args: 0.5 * n(*args))
    b = _consumers()
    assert b["sim"]["fatigue_safety_factor"] == pytest.approx(0.5 * a["sim"]["fatigue_safety_factor"], rel=1e-12)
    np.testing.assert_allclose(b["table"]["fatigue_safety_factor"], 0.5 * a["table"]["fatigue_safety_factor"])
    assert b["synthesis"]["goodman"][0] == pytest.approx(0.5 * a["synthesis"]["goodman"][0], rel=1e-12)
    assert b["design"]["fatigue"]["static_fatigue_safety_factor"] == pytest.approx(
        0.5 * a["design"]["fatigue"]["static_fatigue_safety_factor"], rel=1e-12
    )


def test_the_rate_has_one_home(monkeypatch):
    """formulas.free_length_stiffness 10 % stiffer: the Type C chain's rates and the synthesis'
    active coils (the rate solved for n) follow."""
    k1 = _fresh().spring_model.internal_parameters()["K1"]
    n_before = formulas.active_coils_for_rate(78.5e9, 3.8e-3, 24e-3, 30e3)
    f = formulas.free_length_stiffness
    monkeypatch.setattr(formulas, "free_length_stiffness", lambda *args: 1.1 * f(*args))
    assert _fresh().spring_model.internal_parameters()["K1"] == pytest.approx(1.1 * k1, rel=1e-12)
    assert formulas.active_coils_for_rate(78.5e9, 3.8e-3, 24e-3, 30e3) == pytest.approx(1.1 * n_before, rel=1e-12)


def test_solid_length_and_the_coil_bind_clearance_have_one_home(monkeypatch):
    """solid_length.min_sum_of_gaps tripled: the clearance of the design figures, of a
    simulation and of the synthesis' coil-bind margin follow."""
    a = _consumers()
    sa = solid_length.min_sum_of_gaps
    monkeypatch.setattr(solid_length, "min_sum_of_gaps", lambda *args: 3.0 * sa(*args))
    b = _consumers()
    assert b["design"]["coil_bind"]["coil_bind_clearance_m"] == pytest.approx(
        3 * a["design"]["coil_bind"]["coil_bind_clearance_m"], rel=1e-12
    )
    assert b["sim"]["coil_bind_clearance_m"] == pytest.approx(3 * a["sim"]["coil_bind_clearance_m"], rel=1e-12)
    assert b["synthesis"]["margin_coil_bind"][0] < a["synthesis"]["margin_coil_bind"][0]


def test_the_wire_fatigue_rule_is_one_function_for_a_simulation_and_a_sweep(monkeypatch):
    """verdicts.wire_fatigue changed: a Simulation's summary and a SpeedSweep's table both show it."""
    rule = verdicts.wire_fatigue

    def marked(*args, **kw):
        out = dict(rule(*args, **kw))
        out["fatigue_safety_factor"] = 12.5
        return out

    monkeypatch.setattr(verdicts, "wire_fatigue", marked)
    assert valve.simulate(_fresh(), CAM, 2500.0).summary["fatigue_safety_factor"] == 12.5
    assert np.all(valve.sweep(_fresh(), CAM, SPEEDS).summary_table()["fatigue_safety_factor"] == 12.5)


def test_the_float_and_clash_verdicts_have_one_home(monkeypatch):
    """verdicts.floats_over_nose made always true and verdicts.coil_clash made to class every run
    an active-coil clash of severity 0.37: a simulation, a sweep, the speed study, the
    float-speed search and the criteria row all see float and that clash at every speed."""
    monkeypatch.setattr(verdicts, "floats_over_nose", lambda in_nose, nose, fc, z: np.ones(np.shape(fc)[:-1], bool))
    rule = verdicts.coil_clash

    def marked(model, compression, static, period, limit=None):
        out = dict(rule(model, compression, static, period, limit))
        shape = np.shape(out["severity"])
        out.update(
            severity=np.full(shape, 0.37)[()],
            active=np.ones(shape, bool)[()],
            transition=np.zeros(shape, bool)[()],
            class_index=np.full(shape, 2)[()],
            clash=np.ones(shape, bool)[()],
        )
        return out

    monkeypatch.setattr(verdicts, "coil_clash", marked)
    s = valve.simulate(_fresh(), CAM, 1500.0, valve_train=TRAIN).summary
    assert s["nose_separation"] and s["coil_clash"]["clash_class"] == "active" and s["coil_clash"]["clash"]
    assert s["coil_clash"]["clash_severity"] == 0.37
    t = valve.sweep(_fresh(), CAM, SPEEDS, valve_train=TRAIN).summary_table()
    assert np.all(t["nose_separation"]) and np.all(t["coil_clash"]) and np.all(t["clash_severity"] == 0.37)
    assert np.all(t["active_coil_closing"]) and not np.any(t["transition_seating"])
    study = studies.speed_study(_fresh(), CAM, TRAIN, SPEEDS, resolution=100.0)
    assert study["clash_onset_cam_rpm"] == SPEEDS[0] and study["max_clash_severity"] == 0.37
    row = _verdict_row("coil_clash", t, _fresh().spring_model.design_figures(lift=CAM.lift, cam_rpm=2500.0))
    assert row.passed is False and "37.0 %" in row.value
    res = valve.float_speed(_fresh(), CAM, TRAIN, SPEEDS, resolution=100.0)
    assert res.float_cam_rpm <= SPEEDS[0]


def test_the_clash_limit_has_one_home(monkeypatch):
    """verdicts.MAX_CLASH_SEVERITY at zero: a simulation and a sweep call the example's
    dynamic closings clash, while [criteria] max_clash_severity judges the same severities in
    the criteria row and the tolerance study."""
    spring = _fresh().with_model("distributed")  # its transition coils seat at 2500 cam rpm, within the limit
    a = valve.sweep(spring, CAM, [2500.0], valve_train=TRAIN).summary_table()
    assert a["clash_severity"][0] > 0.0 and a["transition_seating"][0] and not a["coil_clash"][0]
    monkeypatch.setattr(verdicts, "MAX_CLASH_SEVERITY", 0.0)
    b = valve.sweep(spring, CAM, [2500.0], valve_train=TRAIN).summary_table()
    assert b["coil_clash"][0] and b["clash_severity"][0] == a["clash_severity"][0]
    assert valve.simulate(spring, CAM, 2500.0, valve_train=TRAIN).summary["coil_clash"]["clash"]
    outputs = dict(max_clash_severity=[0.02, 0.2], goodman_safety=[2.0, 2.0], refused=[0, 0])
    ds = xr.Dataset({k: ("variant", np.array(v, float)) for k, v in outputs.items()})
    study = ToleranceStudy(
        dataset=ds, criteria=criteria.Criteria(), nominal={}, speeds=np.array(SPEEDS), floats=False, float_only=False
    )
    np.testing.assert_array_equal(study.failures()["coil_clash"], [False, True])


def test_the_pump_up_threshold_has_one_home(monkeypatch):
    """verdicts.PUMP_UP_THRESHOLD below the valve's seated lift: the simulation's adjuster, the
    sweep's column and the report's verdict call every run pumped up."""
    vt = valve.ValveTrain.from_toml(example("valve/finger_follower_hla.toml"))
    cam = valve.Cam.from_toml(example("valve/cam_finger.toml"))
    monkeypatch.setattr(verdicts, "PUMP_UP_THRESHOLD", -1.0)
    s = valve.simulate(_fresh(), cam, 1500.0, valve_train=vt).summary
    assert s["hla"]["pump_up"]
    assert np.all(valve.sweep(_fresh(), cam, [1500.0], valve_train=vt).summary_table()["pump_up"])
    assert criteria.pump_up_verdict(0.0, 3000.0).passed is False


def _verdict_row(name, table, design):
    """The criteria row ``name`` of :func:`criteria.spring_verdicts` for a sweep table over SPEEDS."""
    return next(
        r
        for r in criteria.spring_verdicts(
            criteria.Criteria(),
            design,
            table,
            SPEEDS,
            model="type-c",
            rated_cam_rpm=2500.0,
            wire_limit=SPRING.strengths["shear_stress_limit_Pa"],
        )
        if r.name == name
    )


def test_a_criterion_has_one_rule_for_the_report_the_tolerance_study_and_the_synthesis(monkeypatch):
    """criteria.RULES["goodman"] turned round (at most, not at least): the report's Goodman row,
    the tolerance study's failing share and the synthesis' margin all flip."""
    a = _consumers()
    table = a["table"]

    def goodman_row():
        return next(
            r
            for r in criteria.spring_verdicts(
                criteria.Criteria(),
                a["design"],
                table,
                SPEEDS,
                model="type-c",
                rated_cam_rpm=2500.0,
                wire_limit=SPRING.strengths["shear_stress_limit_Pa"],
            )
            if r.name == "goodman"
        )

    goodman = goodman_row()
    ds = xr.Dataset(
        {
            k: ("variant", np.array(v, float))
            for k, v in dict(goodman_safety=[2.0, 2.5], refused=[0, 0], max_clash_severity=[0, 0]).items()
        }
    )
    study = ToleranceStudy(
        dataset=ds, criteria=criteria.Criteria(), nominal={}, speeds=np.array(SPEEDS), floats=False, float_only=False
    )
    share = study.failures()["goodman"].mean()
    margin = a["synthesis"]["margin_goodman"][0]
    rule = criteria.RULES["goodman"]
    monkeypatch.setitem(criteria.RULES, "goodman", dataclasses.replace(rule, sense="<="))
    assert goodman_row().passed is (not goodman.passed)
    assert study.failures()["goodman"].mean() == 1.0 - share
    assert math.copysign(1.0, _candidates()["margin_goodman"][0]) == -math.copysign(1.0, margin)


@pytest.mark.slow
def test_the_report_rows_follow_the_homes(monkeypatch, tmp_path):
    """The report's valve section takes its rows from the one criteria set: a rule turned round
    at its home flips the report's row; the stress law doubled at its home doubles its figure."""
    from springdyn.app.report.valve import load, section
    from springdyn.core.params import load_toml

    doc = load_toml(example("report/report_valve_one_step.toml"))
    doc["report"] = dict(
        min_engine_rpm="3000 rpm", max_engine_rpm="5000 rpm", engine_rpm_step="1000 rpm", models="type-c"
    )
    doc.pop("valve_train", None)

    def rows():
        out = tmp_path / f"r{len(list(tmp_path.iterdir()))}"
        out.mkdir()
        sec = section(load(doc, tmp_path / "def.toml"), source="def.toml", out_dir=out)
        return {c.name.split(",")[0]: c for c in sec.criteria}

    a = rows()
    rule = criteria.RULES["goodman"]
    with monkeypatch.context() as m:
        m.setitem(criteria.RULES, "goodman", dataclasses.replace(rule, sense="<="))
        b = rows()
    k = stress.bergstraesser_factor
    monkeypatch.setattr(stress, "bergstraesser_factor", lambda w: 2.0 * k(w))
    c = rows()
    name = "fatigue safety factor (Goodman)"
    assert b[name].passed is (not a[name].passed)
    mpa = [float(r["peak wire stress"].value.split()[0]) for r in (a, c)]
    assert mpa[1] == pytest.approx(2 * mpa[0], abs=1.0)
