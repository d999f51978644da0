"""The engine oil (springdyn.valve.train.oil): its laws and the one [oil] of a valve train.

References: the Walther equation (ASTM D341) at its two datasheet points and written out by hand
between them; the density's linear expansion; Merritt's eq. 2-19 for aerated oil at its limits
and against the compiled twin; the one-oil rule (the adjuster and the friction read the same
oil, older keys mean the same, two values are an error).
"""

from __future__ import annotations

import math

import pytest

from springdyn.core.errors import InputError
from springdyn.core.params import load_toml
from springdyn.valve import ValveModel, ValveTrain
from springdyn.valve.engine import equations
from springdyn.valve.engine.layout import P_ATM
from springdyn.valve.train.friction import Friction
from springdyn.valve.train.hla import HLA
from springdyn.valve.train.oil import Oil, effective_bulk_modulus, kinematic_viscosity, oil_density, oil_of
from tests.paths import EXAMPLES, example

HLA_TRAIN = EXAMPLES / "valve" / "finger_follower_hla.toml"
SPRING = example("valve/one_step_spring.toml")


# ----------------------------------------------------------------------------- the laws
def test_walther_passes_its_datasheet_points_and_is_the_formula_between():
    assert kinematic_viscosity(313.15, 60e-6, 10.5e-6) == pytest.approx(60e-6, rel=1e-12)
    assert kinematic_viscosity(373.15, 60e-6, 10.5e-6) == pytest.approx(10.5e-6, rel=1e-12)
    # ASTM D341 written out: log log (nu + 0.7) = A - B log T through the two points (nu in cSt)
    b = (math.log10(math.log10(60.7)) - math.log10(math.log10(11.2))) / math.log10(373.15 / 313.15)
    a = math.log10(math.log10(60.7)) + b * math.log10(313.15)
    by_hand = (10 ** (10 ** (a - b * math.log10(363.15))) - 0.7) * 1e-6
    assert kinematic_viscosity(363.15, 60e-6, 10.5e-6) == pytest.approx(by_hand, rel=1e-12)
    assert 10.5e-6 < by_hand < 60e-6


def test_density_expands_linearly_from_15_degc():
    assert oil_density(288.15, 850.0) == 850.0
    assert oil_density(363.15, 850.0) == pytest.approx(850.0 / (1 + 6.5e-4 * 75), rel=1e-15)


def test_bulk_modulus_limits_and_the_compiled_twin():
    """Air-free: the oil's modulus; much air at low pressure: n p / x (the air alone); the
    compiled twin (the engine's) equals the documented function."""
    assert effective_bulk_modulus(5e6, 1.5e9, 0.0) == pytest.approx(1.5e9, rel=1e-12)
    assert effective_bulk_modulus(P_ATM, 1.5e9, 0.3, 1.0) == pytest.approx(P_ATM / 0.3, rel=0.01)
    for p in (3e3, 1e5, 3e5, 1e7):
        for n in (1.0, 1.4):
            assert equations._TWINS["effective_bulk_modulus"](p, 1.5e9, 0.02, n) == pytest.approx(
                effective_bulk_modulus(p, 1.5e9, 0.02, n), rel=1e-14
            )
    assert Oil().bulk_modulus_at(3e5) == effective_bulk_modulus(3e5, 1.5e9, 0.02, 1.0)


def test_the_check_valve_is_the_compiled_orifice():
    """hla.check_valve_flow and the chamber's compiled orifice are one law (engine.hydraulics):
    the same flow, continuous at the laminar transition (Merritt 1967, eq. 3-6)."""
    from springdyn.valve.engine.layout import CHECK_VALVE_TRANSITION
    from springdyn.valve.train.hla import check_valve_flow

    k = 0.7 * 1e-6 * math.sqrt(2.0 / 850.0)
    for dp in (-10.0, 0.0, 500.0, CHECK_VALVE_TRANSITION, 1e5):
        assert equations._TWINS["orifice_flow"](dp, k) == pytest.approx(
            check_valve_flow(dp, 1e-6, 0.7, 850.0), rel=1e-14
        )
    below = check_valve_flow(CHECK_VALVE_TRANSITION * (1 - 1e-12), 1e-6, 0.7, 850.0)
    assert below == pytest.approx(check_valve_flow(CHECK_VALVE_TRANSITION, 1e-6, 0.7, 850.0), rel=1e-9)


def test_a_viscosity_given_holds_at_its_temperature_only():
    oil = Oil(viscosity=8e-3)
    assert oil.dynamic_viscosity() == 8e-3
    with pytest.raises(InputError, match="given at 90 degC only"):
        oil.dynamic_viscosity(313.15)


# ----------------------------------------------------------------------------- one oil
def test_the_adjuster_and_the_friction_read_one_oil():
    """The default oil is the adjuster's and the friction's (one temperature, 90 degC)."""
    assert HLA().oil == Friction().oil == Oil()
    assert Oil().temperature == pytest.approx(363.15)


def test_older_keys_mean_the_same_oil():
    by_oil = oil_of({"oil": {"temperature": "100 degC", "viscosity_40": "70 mm^2/s"}})[0]
    by_hla = HLA.from_dict({"oil_temperature": "100 degC", "oil_viscosity_40": "70 mm^2/s"}).oil
    by_friction = Friction.from_dict({"oil_temperature": "100 degC", "oil_viscosity_40": "70 mm^2/s"}).oil
    assert by_oil == by_hla == by_friction
    # the same value in two tables (in other units) is one oil, not a conflict
    same = oil_of({"oil": {"temperature": "100 degC"}, "hla": {"oil_temperature": "373.15 K"}})[0]
    assert same.temperature == pytest.approx(373.15)


def test_two_values_of_one_oil_key_are_one_clear_error():
    doc = {"oil": {"temperature": "100 degC"}, "friction": {"oil_temperature": "90 degC"}}
    with pytest.raises(InputError, match=r"vt.toml: \[oil\] temperature = '100 degC' and \[friction\] oil_temperature"):
        oil_of(doc, "vt.toml")
    doc = {"hla": {"oil_density_15": 850.0}, "friction": {"oil_density_15": 870.0}}
    with pytest.raises(InputError, match=r"\[hla\] oil_density_15 = 850.0 and \[friction\] oil_density_15 = 870.0"):
        oil_of(doc)


@pytest.mark.parametrize(
    "doc, message",
    [
        ({"oil": {"temperatur": "90 degC"}}, r"\[oil\] unknown key 'temperatur' \(did you mean 'temperature'\?\)"),
        ({"oil": {"air_fraction": 0.6}}, r"air_fraction = 0.6 must be below 0.5"),
        ({"hla": {"oil_temperature": "600 degC"}}, r"\[hla\] oil_temperature = 600 degC must lie from -40 to 170"),
        (
            {"oil": {"viscosity": "8 mPa*s"}, "friction": {"oil_viscosity_100": "9 mm^2/s"}},
            r"\[oil\] viscosity is given, so \[friction\] oil_viscosity_100 would be ignored",
        ),
        ({"oil": {"viscosity_100": "80 mm^2/s"}}, r"viscosity_100 = 80 mm\^2/s must be below viscosity_40"),
    ],
)
def test_bad_oil_tables(doc, message):
    with pytest.raises(InputError, match=message):
        oil_of(doc, "vt.toml")


def test_an_oil_table_in_a_train_file_sets_the_adjusters_and_the_frictions_oil(tmp_path):
    text = HLA_TRAIN.read_text(encoding="utf-8")
    assert 'temperature = "90 degC"' in text.split("[oil]")[1]  # the example's [oil]
    path = tmp_path / "vt.toml"
    path.write_text(text.replace('temperature = "90 degC"', 'temperature = "110 degC"'), encoding="utf-8")
    vt = ValveTrain.from_toml(path)
    assert vt.hla.oil.temperature == pytest.approx(383.15)
    model = ValveModel.from_files(SPRING, None, path)
    assert model.oil == vt.hla.oil
    assert "oil" in load_toml(path)
    # the same key under [hla] (its older name) with another value is refused, naming both
    path.write_text(text.replace("\n[hla]\n", '\n[hla]\noil_temperature = "80 degC"\n'), encoding="utf-8")
    with pytest.raises(InputError, match=r"\[oil\] temperature = '90 degC' and \[hla\] oil_temperature = '80 degC'"):
        ValveTrain.from_toml(path)
