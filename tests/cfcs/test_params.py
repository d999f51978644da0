"""Mechanism definition and bad input."""

import pytest

from springdyn.cfcs import CFCS, CFCSParams
from springdyn.core.errors import InputError
from tests.paths import EXAMPLES

BASE = {
    "crank_length": "85 mm",
    "coupler_length": "95 mm",
    "crank_mass": "0.025 kg",
    "coupler_mass": "0.028 kg",
    "slider_mass": "0.087 kg",
    "torsional_stiffness": "2.5308 N*m/rad",
}


def test_table1_example_loads_with_units(table1):
    assert table1.crank_length == pytest.approx(0.085)
    assert table1.pivot_thickness == pytest.approx(0.38e-3)
    assert table1.youngs_modulus == pytest.approx(207e9)
    assert table1.friction_model == "paper" and table1.axial_force is True
    assert table1.has_flexure


def test_examples_folder_matches_builtin(table1):

    path = EXAMPLES / "cfcs" / "table1.toml"
    assert CFCSParams.from_toml(path) == table1


def test_defaults():
    p = CFCSParams.from_dict(BASE)
    assert p.k3 == 2.5308 and not p.has_flexure
    assert p.pin_friction == 0.0 and p.friction_model == "paper"


@pytest.mark.parametrize(
    "changes, match",
    [
        ({"crank_length": "95 mm"}, "crank_length = 95 mm must be shorter than coupler_length"),
        ({"crank_length": "100 mm"}, "must be shorter"),
        ({"coupler_length": "-95 mm"}, "coupler_length = -95 mm must be positive"),
        ({"crank_mass": "0 kg"}, "crank_mass = 0 kg must be positive"),
        ({"slider_mass": "-1 kg"}, "slider_mass"),
        ({"friction_model": "viscous"}, "friction_model = 'viscous' is not allowed; choose one of 'paper'"),
        ({"pivot_width": "25.4 mm"}, "both torsional_stiffness and pivot dimensions"),
        ({"crank_length": "85 kg"}, "wrong dimension"),
        ({"colour": "red"}, "unknown key 'colour'"),
        ({"toggle_cutoff": "95 deg"}, "toggle_cutoff = 95 deg must be below 90 deg"),
        ({"pin_friction": "-0.1 N*m"}, "pin_friction"),
    ],
)
def test_bad_input(changes, match):
    with pytest.raises(InputError, match=match):
        CFCSParams.from_dict({**BASE, **changes})


def test_neither_or_partial_pivot():
    table = {k: v for k, v in BASE.items() if k != "torsional_stiffness"}
    with pytest.raises(InputError, match="neither torsional_stiffness nor the pivot dimensions"):
        CFCSParams.from_dict(table)
    with pytest.raises(InputError, match="needs pivot_length, youngs_modulus"):
        CFCSParams.from_dict({**table, "pivot_width": "25 mm", "pivot_thickness": "0.4 mm"})


def test_missing_key_names_it():
    table = {k: v for k, v in BASE.items() if k != "slider_mass"}
    with pytest.raises(InputError, match="missing key 'slider_mass'"):
        CFCSParams.from_dict(table)


def test_unknown_example():
    with pytest.raises(InputError, match="example = 'nope' is not a built-in cfcs; choose one of 'table1'"):
        CFCSParams.example("nope")


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(omega=0.0), "omega = 0 rad/s must be positive"),
        (dict(omega=-3.0), "must be positive"),
        (dict(omega=5.0, amplitude=0.9), "beyond the kinematic limit"),
        (dict(omega=5.0, amplitude="150 mm"), "beyond the kinematic limit"),
        (dict(omega=5.0, offset=-0.002), "crosses the toggle"),
        (dict(omega=5.0, amplitude=1.5), "1504.5 mm, beyond the kinematic limit"),  # bare numbers are metres
        (dict(omega=5.0, amplitude="150 %"), "percentage of r2 \\+ r3 must lie in"),
        (dict(), "omega is required"),
    ],
)
def test_bad_motion(model, kwargs, match):
    with pytest.raises(InputError, match=match):
        model.dynamic(**kwargs)


def test_bad_stroke(model):
    with pytest.raises(InputError, match="beyond the kinematic limit 137.57 mm"):
        model.static(0.15)
    with pytest.raises(InputError, match="must be positive"):
        model.static(-0.01)


def test_bad_forward(model):
    with pytest.raises(InputError, match="exactly one drive"):
        model.forward(1.0)
    with pytest.raises(InputError, match="toggle"):
        model.forward(1.0, force=1.0, x0=0.0, v0=0.1)
    with pytest.raises(InputError, match="base_stiffness"):
        model.forward(1.0, base_motion=lambda t: 0.01)


def test_model_needs_params():
    with pytest.raises(InputError):
        CFCS({"crank_length": 0.085})


def test_amplitude_bare_numbers_are_metres_and_percent_is_a_fraction(model):
    """Bare numbers are SI everywhere; a fraction of the mechanism needs '%'."""
    ext = model.params.extended_length
    a = model.dynamic(5.0, amplitude="40 %").summary
    b = model.dynamic(5.0, amplitude=0.4 * ext).summary
    assert a["peak_to_peak_N"] == pytest.approx(b["peak_to_peak_N"], rel=1e-12)
    with pytest.warns(DeprecationWarning, match="write '40 %'"):
        c = model.dynamic(5.0, amplitude=0.4).summary  # 0.4 m is beyond the mechanism: the old fraction
    assert c["peak_to_peak_N"] == pytest.approx(a["peak_to_peak_N"], rel=1e-12)


@pytest.mark.parametrize(
    "call, match",
    [
        (lambda m: m.dynamic(1e308), "beyond 100000 rad/s"),
        (lambda m: m.sweep([1.0, 1e306]), "beyond 100000 rad/s"),
        (lambda m: m.params.replace(shear_angle=1.5), "shear_angle = 1.5 rad must lie within"),
    ],
)
def test_issue11_reproducers_are_input_errors(model, call, match):
    """An omega of 1e308 and shear_angle = 1.5 rad gave NaN statistics; now one message each."""
    with pytest.raises(InputError, match=match):
        call(model)


def test_design_stroke_fraction_beyond_the_kinematic_range():
    """A stroke_fraction of 0.95 failed inside brentq; now the allowed range is named."""
    from springdyn.cfcs import design

    with pytest.raises(InputError, match=r"stroke_fraction = 0.95 must not exceed 0.9"):
        design(12.8, 0.04, 207e9, 1.5e9, stroke_fraction=0.95)


@pytest.mark.parametrize(
    "changes,match",
    [
        ({"pivot_thickness": "2**1000"}, "beyond any machine element"),  # the fuzz's OverflowError
        ({"pivot_thickness": "12 mm"}, "pivot_thickness = 12 mm must be smaller than pivot_length"),
        ({"pivot_width": "1e300 m"}, "beyond any machine element"),
        ({"pivot_width": "1e30 mm"}, r"pivot_width = 1e\+30 mm is beyond any machine element"),  # issue 27
    ],
)
def test_flexure_strip_is_checked(table1, changes, match):
    base = {k: v for k, v in table1.__dict__.items() if not k.startswith("_") and v is not None}
    with pytest.raises(InputError, match=match):
        CFCSParams.from_dict({**base, **changes})
