"""Shared pieces: unit parsing, parameter fields, atomic writers, README/CI contract."""

import dataclasses
import json
import math
import os
import re

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.core.io import atomic_open, read_csv_columns, write_csv, write_json
from springdyn.core.params import check_fields, from_mapping, param
from springdyn.core.units import to_si
from tests.paths import ROOT


@pytest.mark.parametrize(
    "value,unit,expected",
    [
        ("22 mm", "m", 0.022),
        ("78.5 GPa", "Pa", 78.5e9),
        ("3000 rpm", "rad/s", 100 * math.pi),
        ("120 deg", "rad", 2 * math.pi / 3),
        ("100 cSt", "m^2/s", 1e-4),
        ("50um", "m", 50e-6),
        ("7850 kg/m^3", "kg/m^3", 7850.0),
        (0.5, "m", 0.5),
        ("0.5", "m", 0.5),
    ],
)
def test_to_si(value, unit, expected):
    assert to_si(value, unit, "x") == pytest.approx(expected, rel=1e-12)


def test_hz_for_a_rotation_speed_means_revolutions_per_second():
    assert to_si("50 Hz", "rad/s", "--rpm") == pytest.approx(100 * math.pi)
    assert to_si("50 Hz", "rad/s", "--rpm", bare_unit="rpm") == pytest.approx(100 * math.pi)
    assert to_si("3000 rpm", "rad/s", "--rpm") == pytest.approx(100 * math.pi)
    assert to_si("100 rad/s", "rad/s", "--rpm") == pytest.approx(100)
    assert to_si("20 kHz", "Hz", "--sample-rate") == pytest.approx(20000)


def test_bare_unit_for_named_options():
    assert to_si(3000, "rad/s", "--cam-rpm", bare_unit="rpm") == pytest.approx(100 * math.pi)
    assert to_si("3000", "rad/s", "--cam-rpm", bare_unit="rpm") == pytest.approx(100 * math.pi)


@pytest.mark.parametrize("value", ["22 kg", "abc", float("nan"), True, [1]])
def test_to_si_errors(value):
    with pytest.raises(InputError, match="length"):
        to_si(value, "m", "length")


@dataclasses.dataclass
class Demo:
    width: float = param("m", "width", positive=True, display="mm")
    mode: str = param(None, "mode", kind="str", choices=("a", "b"), default="a")
    count: int = param(None, "count", kind="int", default=3)

    def __post_init__(self):
        check_fields(self)


def test_from_mapping():
    d = from_mapping(Demo, {"width": "5 mm", "mode": "b"}, section="demo")
    assert d == Demo(0.005, "b", 3)
    with pytest.raises(InputError, match=r"\[demo\] unknown key 'widht' \(did you mean 'width'\?\)"):
        from_mapping(Demo, {"widht": 1}, section="demo")
    with pytest.raises(InputError, match=r"width = -5 mm must be positive"):
        from_mapping(Demo, {"width": "-5 mm"})
    with pytest.raises(InputError, match=r"count = 2.5 must be a whole number"):
        from_mapping(Demo, {"width": 1, "count": 2.5})
    with pytest.raises(InputError, match=r"mode = 'c' is not allowed"):
        Demo(0.1, "c")
    # fuzz: an integer beyond any float (math.isfinite raised OverflowError)
    with pytest.raises(InputError, match=r"count is an integer of 1329 bits: too large"):
        from_mapping(Demo, {"width": 1, "count": 10**400})


def test_atomic_writers_leave_nothing_on_failure(tmp_path):
    target = tmp_path / "out.csv"
    write_csv(target, {"a_m": [1.0, 2.0]})
    before = target.read_text()
    with pytest.raises(RuntimeError):
        with atomic_open(target) as fh:
            fh.write("half")
            raise RuntimeError("boom")
    assert target.read_text() == before
    assert os.listdir(tmp_path) == ["out.csv"]
    write_json(tmp_path / "x.json", {"v": np.float64(1.5), "n": None, "arr": np.arange(2)})
    assert json.loads((tmp_path / "x.json").read_text()) == {"v": 1.5, "n": None, "arr": [0, 1]}
    # a NaN never reaches a file: the writer refuses, naming the key, and writes nothing
    from springdyn.core.io import NonFiniteOutputError

    with pytest.raises(NonFiniteOutputError, match="'n'"):
        write_json(tmp_path / "y.json", {"v": 1.0, "n": float("nan")})
    with pytest.raises(NonFiniteOutputError, match="column 'b', row 2"):
        write_csv(tmp_path / "y.csv", {"a": [1.0, 2.0], "b": [0.0, float("inf")]})
    assert not (tmp_path / "y.json").exists() and not (tmp_path / "y.csv").exists()
    assert sorted(os.listdir(tmp_path)) == ["out.csv", "x.json"]


def test_read_csv_columns_errors(tmp_path):
    f = tmp_path / "d.csv"
    f.write_text("a,b\n1,2\n3,x\n")
    with pytest.raises(InputError, match=r"row 3, column 'b': 'x' is not a number"):
        read_csv_columns(f)
    f.write_text("a,b\n1,2\n")
    assert read_csv_columns(f)["b"].tolist() == [2.0]


def test_ci_runs_the_readme_test_command():
    """.ci/run must execute the README's test command verbatim."""
    readme = (ROOT / "README.md").read_text()
    blocks = re.findall(r"```sh\n(.*?)\n```", readme, flags=re.S)
    test_cmd = [b for b in blocks if "pytest" in b]
    demo_cmd = [b for b in blocks if "springdyn demo" in b]
    assert len(test_cmd) >= 1 and len(demo_cmd) >= 1
    assert test_cmd[0].strip() in (ROOT / ".ci" / "run").read_text()


def test_a_name_with_a_unit_gives_that_unit():
    """The <quantity>_<unit> convention of every family: a rate is <unit>_per_s (the CFCS
    names velocity_m_s and omega_rad_s were read as seconds and written into NetCDF as such)."""
    from springdyn.core.results import column_name, units_from_name

    assert units_from_name("velocity_m_per_s") == "m/s"
    assert units_from_name("omega_rad_per_s") == "rad/s"
    assert units_from_name("time_s") == "s"
    assert column_name("velocity", "m/s") == "velocity_m_per_s"
    from springdyn.cfcs import CFCS

    ds = CFCS.example("table1").dynamic(14.7).to_xarray()
    assert ds["velocity_m_per_s"].attrs["units"] == "m/s"
