"""LSDParameters: TOML reading, built-in Types A-C, bad input."""

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.lsd import LSDParameters
from tests.paths import EXAMPLES

C_TOML = """
[lsd]
packs = 6
first_pack_angle = "0 deg"
leaf_lengths = ["38 mm", "34 mm", "25 mm"]
leaf_thicknesses = ["1.35 mm", "1.35 mm", "1.35 mm"]
leaf_width = "14.8 mm"
youngs_modulus = "206 GPa"
poisson_ratio = 0.3
clamp_overhang = "0 mm"
preload = "0.25 mm"
ring_outer_diameter = "71 mm"
ring_width = "15 mm"
ring_mass = "0.5 kg"
passage_width = "2.4 mm"
passage_clearance = "0.9 mm"
passage_length = "10 mm"
passages_per_boundary = 2
conductance_model = "exact"
leakage_factor = 1.0
oil_viscosity = "100 cSt"
oil_density = "965 kg/m^3"
leaf_friction = 0.1
oring_friction = 0.0
oring_normal_force = "0 N"
"""


def _write(tmp_path, text, name="d.toml"):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_issue_toml_reads_and_matches_type_c(tmp_path):
    p = LSDParameters.from_toml(_write(tmp_path, C_TOML))
    c = LSDParameters.example("C")
    assert p.leaf_lengths == pytest.approx([0.038, 0.034, 0.025])
    assert p.oil_viscosity == pytest.approx(100e-6 * 965)  # kinematic x density [Pa s]
    assert p.oil_viscosity == pytest.approx(c.oil_viscosity)
    assert p.first_pack_angle == 0.0 and p.packs == 6


def test_examples_follow_table_4_1():
    a, b, c = (LSDParameters.example(k) for k in "ABC")
    assert a.leaf_lengths == pytest.approx([18.5e-3, 18.5e-3]) and a.leaf_width == pytest.approx(13.5e-3)
    assert b.leaf_width == pytest.approx(13.8e-3) and b.passage_clearance == pytest.approx(0.10e-3)
    assert a.passage_clearance == pytest.approx(0.25e-3) and a.ring_outer_diameter == pytest.approx(92e-3)
    assert c.preload == pytest.approx(0.25e-3) and a.preload == pytest.approx(0.1e-3)
    assert a.kinematic_viscosity == pytest.approx(1000e-6) and c.kinematic_viscosity == pytest.approx(100e-6)


def test_dynamic_viscosity_accepted(tmp_path):
    p = LSDParameters.from_toml(_write(tmp_path, C_TOML.replace('"100 cSt"', '"0.0965 Pa*s"')))
    assert p.oil_viscosity == pytest.approx(0.0965)


@pytest.mark.parametrize(
    "old, new, match",
    [
        ('["38 mm", "34 mm", "25 mm"]', '["34 mm", "38 mm", "25 mm"]', "non-increasing"),
        ('["1.35 mm", "1.35 mm", "1.35 mm"]', '["1.35 mm", "0 mm", "1.35 mm"]', r"leaf_thicknesses\[1\].*positive"),
        ('["1.35 mm", "1.35 mm", "1.35 mm"]', '["1.35 mm", "1.35 mm"]', "one thickness per leaf"),
        ('leaf_width = "14.8 mm"', 'leaf_width = "-14.8 mm"', "leaf_width.*positive"),
        ('"100 cSt"', '"0 cSt"', "oil_viscosity.*positive"),
        ('"100 cSt"', '"100 mm"', "oil_viscosity"),
        ('conductance_model = "exact"', 'conductance_model = "moody"', "choose one of"),
        ("packs = 6", "packs = 1", "from 2 to 64"),
        ("leaf_friction = 0.1", "leaf_fricton = 0.1", "did you mean 'leaf_friction'"),
        ('leaf_width = "14.8 mm"\n', "", "missing key 'leaf_width'"),
        ('oil_density = "965 kg/m^3"\n', "", "is kinematic; give oil_density"),
    ],
)
def test_bad_toml(tmp_path, old, new, match):
    assert old in C_TOML
    path = _write(tmp_path, C_TOML.replace(old, new))
    with pytest.raises(InputError, match=match) as err:
        LSDParameters.from_toml(path)
    assert str(path) in str(err.value)  # the message names the file


def test_pack_angles_checked():
    c = LSDParameters.example("C")
    with pytest.raises(InputError, match="pack_angles has 3 entries"):
        c.replace(pack_angles=[0.0, 1.0, 2.0])
    with pytest.raises(InputError, match="increase"):
        c.replace(pack_angles=list(np.radians([0, 60, 50, 180, 240, 300])))


def test_unknown_example():
    with pytest.raises(InputError, match="choose one of 'A', 'B', 'C'"):
        LSDParameters.example("D")


def test_example_files_load():
    # every TOML under examples/lsd/ reads; the Type files equal the built-in examples

    folder = EXAMPLES / "lsd"
    files = sorted(folder.glob("*.toml"))
    assert len(files) == 7  # Types A-C, C with two thicker oils, A and B calibrated
    for f in files:
        p = LSDParameters.from_toml(f)
        if f.stem == "type_c" or f.stem.endswith("_calibrated"):
            # the built-in A and B are the calibrated definitions: the demo shows them
            assert p == LSDParameters.example(f.stem.split("_")[1])
    for x in ("a", "b"):  # the raw closed form differs only in its leakage factor (and name)
        raw = LSDParameters.from_toml(folder / f"type_{x}.toml")
        cal = LSDParameters.example(x)
        assert raw.leakage_factor == 1.0 and cal.leakage_factor > 10
        assert raw.replace(leakage_factor=cal.leakage_factor, name=cal.name) == cal
    thick = LSDParameters.from_toml(folder / "type_c_3000cst.toml")
    assert thick.oil_viscosity == pytest.approx(3000e-6 * 970)
