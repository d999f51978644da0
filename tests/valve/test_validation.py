"""Bad input for valve springs (issue 2, section 5): one clear message each."""

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
        ({"type": "two-step", "low_pitch_coils": 2.0, "high_pitch_coils": 6.0, "youngs_modulus": "0.007 GPa"},
         r"must exceed 3 K2"),
        ({"free_length": "500 mm"}, r"end mass me = -.* kg must be positive"),
        ({"installed_length": "28 mm"}, r"installed_length = 28 mm is at or below coil contact"),
        ({"installed_length": "27 mm"}, r"installed_length = 27 mm is at or below coil contact"),
        ({"damping_ratio": -0.1}, r"damping_ratio = -0\.1 must be zero or positive"),
        ({"mean_diameter": "22 kg"}, r"mean_diameter = '22 kg' has the wrong dimension: expected a quantity convertible to m"),
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
    with pytest.raises(InputError, match=r"length = 10 mm is outside the range of the spring: it must lie between 20\.08\d mm"):
        s.static_force(0.010)
    with pytest.raises(InputError, match=r"length = 50 mm is outside the range.*free length Lf = 48 mm"):
        s.modes(0.050)
    with pytest.raises(InputError, match=r"stop = 5 mm"):
        s.static_curve(stop=0.005)


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
