"""springdyn.valve.design.criteria: the one set of pass/fail rules and the [criteria] table.

The margins are checked against their definitions written out by hand (value / limit - 1 for
an "at least" rule, 1 - value / limit for an "at most" rule); the table against the units it
must take at the edge ("10 %", "3000 rpm") and the errors it must give.  That every consumer
follows a limit changed here is tests/valve/test_one_home.py's.
"""

import dataclasses
import math

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve.design.criteria import (
    FLOAT_MARGIN,
    JUDGING_MODEL,
    MIN_GOODMAN_SAFETY,
    RULES,
    Criteria,
    margin,
    passes,
    verdict,
)


def test_the_margin_of_each_sense_is_its_definition():
    # ">=": value / limit - 1; "<=": 1 - value / limit; ">0": value / scale; "within": the nearer
    # edge over the lower one; "none": -1 where it happens
    assert margin("goodman", 1.32, 1.1) == pytest.approx(1.32 / 1.1 - 1.0, rel=1e-15)
    assert margin("seating_velocity", 0.3, 0.5) == pytest.approx(1.0 - 0.3 / 0.5, rel=1e-15)
    assert margin("min_retainer_force", 50.0, 200.0) == pytest.approx(0.25, rel=1e-15)
    assert margin("spring_index", 6.0, (4.0, 16.0)) == pytest.approx((6.0 - 4.0) / 4.0, rel=1e-15)
    assert margin("spring_index", 15.0, (4.0, 16.0)) == pytest.approx((16.0 - 15.0) / 4.0, rel=1e-15)
    # coil clash: its severity [fraction of Fset] at most the limit
    assert margin("coil_clash", 0.05, 0.1) == pytest.approx(0.5, rel=1e-15)


def test_a_limit_met_exactly_passes_and_one_missed_by_a_hair_fails():
    assert passes("goodman", MIN_GOODMAN_SAFETY, MIN_GOODMAN_SAFETY)
    assert not passes("goodman", np.nextafter(MIN_GOODMAN_SAFETY, 0.0), MIN_GOODMAN_SAFETY)
    assert passes("seating_velocity", 0.5, 0.5)
    assert not passes("seating_velocity", np.nextafter(0.5, 1.0), 0.5)
    # "above zero": a retainer force of exactly 0 N is the spring leaving its retainer
    assert not passes("min_retainer_force", 0.0, 200.0)
    assert passes("min_retainer_force", 1e-9, 200.0)
    assert passes("coil_clash", 0.1, 0.1)
    assert not passes("coil_clash", np.nextafter(0.1, 1.0), 0.1)


def test_margins_and_verdicts_work_on_arrays_element_by_element():
    values = np.array([1.0, 1.1, 1.5])
    np.testing.assert_allclose(margin("goodman", values, 1.1), values / 1.1 - 1.0, rtol=1e-15)
    np.testing.assert_array_equal(passes("goodman", values, 1.1), [False, True, True])


def test_every_rule_with_a_limit_field_names_a_field_of_the_table():
    fields = {f.name for f in dataclasses.fields(Criteria)}
    for rule in RULES.values():
        assert rule.sense in (">=", "<=", ">0", "within", "none"), rule.name
        assert rule.limit_field is None or rule.limit_field in fields, rule.name


def test_the_table_takes_units_at_the_edge_and_holds_si():
    c = Criteria.from_dict({"float_margin": "15 %", "min_float_cam_rpm": "3000 rpm", "max_seating_velocity": "0.4 m/s"})
    assert c.float_margin == pytest.approx(0.15, rel=1e-12)
    assert c.min_float_cam_rpm == pytest.approx(3000.0 * 2.0 * math.pi / 60.0, rel=1e-12)  # rad/s inside
    assert c.float_speed_needed(rated_cam_rpm=4000.0) == pytest.approx(3000.0, rel=1e-12)  # the given one wins
    assert Criteria().float_speed_needed(4000.0) == pytest.approx(4000.0 * (1.0 + FLOAT_MARGIN), rel=1e-15)
    assert Criteria().float_speed_needed(None) is None


def test_limit_is_the_tables_field_or_the_values_own():
    c = Criteria(min_goodman_safety=1.3)
    assert c.limit("goodman") == 1.3
    assert c.limit("wire_stress", default=900e6) == 900e6  # the wire's own strength
    assert c.limit("max_retainer_force", default=None) is None  # optional and not given


@pytest.mark.parametrize(
    "table, words",
    [
        ({"min_goodman_safty": 1.2}, "min_goodman_safty"),
        ({"min_goodman_safety": -1.0}, "min_goodman_safety"),
        ({"float_margin": "fast"}, "float_margin"),
    ],
)
def test_a_wrong_key_or_value_is_one_clear_error(table, words):
    with pytest.raises(InputError, match=words):
        Criteria.from_dict(table)


def test_a_verdict_of_an_unknown_criterion_is_refused_and_no_value_is_not_applicable():
    with pytest.raises(InputError, match="goodmann"):
        verdict("goodmann", 1.2, 1.1, label="x", value_text="1.2", limit_text="1.1")
    v = verdict("goodman", None, 1.1, label="Goodman", value_text="-", limit_text=">= 1.1", model=JUDGING_MODEL)
    assert v.passed is None and v.model == "distributed"
