"""Bad files and outputs at the core: files that cannot be read give one message; outputs are checked
before any work and written as one set (temporaries renamed together, removed on error)."""

from __future__ import annotations

import os

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.core.io import (
    check_output_file,
    check_output_folder,
    output_set,
    read_csv_columns,
    write_csv,
    write_json,
)
from springdyn.core.params import load_toml
from springdyn.core.units import to_si


@pytest.mark.parametrize(
    "content, message",
    [
        (b'[spring]\ntype = "one-\xff"\n', "line 2 is not UTF-8"),
        ("[spring]\nx = 1\n".encode("utf-16"), "UTF-16"),
        (bytes(range(256)), "NUL bytes"),
        (b"a = " + b"[" * 5000 + b"]" * 5000, "nested too deeply"),
        (b"[spring]\nx = " + b"9" * 5000 + b"\n", "too long to read"),  # fuzz: Python's 4300-digit limit
        (b"", "empty"),
        (b"[spring]\nx = 1\n[extra]\ny = 2\n", "unknown table [extra]"),
        (b"[sprnig]\nx = 1\n", "did you mean [spring]"),
        (b"[spring\n", "not valid TOML"),
    ],
)
def test_toml_files_that_cannot_be_read(tmp_path, content, message):
    f = tmp_path / "d.toml"
    f.write_bytes(content)
    with pytest.raises(InputError, match=message.replace("[", r"\[").replace("]", r"\]")):
        load_toml(f, "spring")


def test_a_folder_or_missing_file_is_named(tmp_path):
    with pytest.raises(InputError, match="is a folder"):
        load_toml(tmp_path, "spring")
    with pytest.raises(InputError, match="no such file"):
        load_toml(tmp_path / "nope.toml", "spring")


@pytest.mark.parametrize(
    "content, message",
    [
        (b"a,b\n1,nan\n", "row 2, column 'b': 'nan' is not a finite number"),
        (b"a,b\n1,inf\n", "not a finite number"),
        (b"a,b\n1\n", "row 2 has 1 cells"),
        (b"a,a\n1,2\n", "names column 'a' twice"),
        (b"a,b\n", "no data rows"),
        (b"a,b\n\xff,1\n", "not UTF-8"),
        (b"a,b\n1,x\n", "'x' is not a number"),
    ],
)
def test_csv_files_that_cannot_be_read(tmp_path, content, message):
    f = tmp_path / "d.csv"
    f.write_bytes(content)
    with pytest.raises(InputError, match=message):
        read_csv_columns(f)


def test_output_checks_before_any_work(tmp_path):
    (tmp_path / "file").write_text("x")
    with pytest.raises(InputError, match="is a file, not a folder"):
        check_output_file(tmp_path / "file" / "out.csv", "--csv")
    with pytest.raises(InputError, match="is a folder"):
        check_output_file(tmp_path, "--csv")
    with pytest.raises(InputError, match="does not exist"):
        check_output_file(tmp_path / "no" / "out.csv", "--csv")
    with pytest.raises(InputError, match="longer than 255 bytes"):
        check_output_file(tmp_path / ("x" * 300 + ".csv"), "--csv")
    with pytest.raises(InputError, match="empty file name"):
        check_output_file("", "--csv")
    with pytest.raises(InputError, match="existing file"):
        check_output_folder(tmp_path / "file", "--out")
    assert check_output_folder(tmp_path / "new", "--out") == tmp_path / "new"


def test_an_output_set_appears_together_or_not_at_all(tmp_path):
    (tmp_path / "sim.png").write_text("old")
    with pytest.raises(RuntimeError):
        with output_set():
            write_csv(tmp_path / "sim.csv", {"a": [1.0]})
            assert not (tmp_path / "sim.csv").exists()  # not yet under its final name
            raise RuntimeError("killed half way")
    assert sorted(os.listdir(tmp_path)) == ["sim.png"]  # no new csv beside the old png, no temporary
    with output_set():
        write_csv(tmp_path / "sim.csv", {"a": [1.0]})
        write_json(tmp_path / "sim.json", {"a": 1.0})
    assert sorted(os.listdir(tmp_path)) == ["sim.csv", "sim.json", "sim.png"]


@pytest.mark.parametrize(
    "text, unit, expected",
    [("5 %", "", 0.05), ("40%", "", 0.4), ("0.05", "", 0.05), ("50Hz", "rpm", 3000.0), ("3000", "rpm", 3000.0)],
)
def test_percent_and_speeds(text, unit, expected):
    assert to_si(text, unit, "x") == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize(
    "text, message",
    [
        ("3000,5", "comma"),
        ("3,8mm", "comma"),
        ("4000:1000:250", "range"),
        ("5e-324 m", "subnormal"),
        ("1e400 m", "finite"),
    ],
)
def test_quantities_never_misread(text, message):
    with pytest.raises(InputError, match=message):
        to_si(text, "m", "x")
    assert np.isfinite(to_si("1e300 m", "m", "x"))


def test_csv_cells_are_plain_numbers(tmp_path):
    """Issue 27: Python's float() reads '4_2e-5' as 4.2e-4; measured data takes plain numbers only."""
    from springdyn.core.errors import InputError
    from springdyn.core.io import read_csv_columns

    f = tmp_path / "u.csv"
    f.write_text("time_s,x_m\n0,4_2e-5\n")
    with pytest.raises(InputError, match="'4_2e-5' is not a plain number"):
        read_csv_columns(f)
    f.write_text("time_s,x_m\n0,-4.2e-5\n1,.5\n2,3.\n3,+1E3\n")
    assert list(read_csv_columns(f)["x_m"]) == [-4.2e-5, 0.5, 3.0, 1000.0]


def test_stale_temporaries_of_a_killed_run_are_removed(tmp_path):
    """Issue 27: a run killed while writing leaves '.<name>.XXXX<suffix>' beside the file; the
    next write of the same file removes it once it is older than an hour (a younger one may
    belong to a run still going)."""
    import os
    import time

    from springdyn.core.io import atomic_path

    target = tmp_path / "out.csv"
    old = tmp_path / ".out.csv.abc123.csv"
    young = tmp_path / ".out.csv.def456.csv"
    for f in (old, young):
        f.write_text("partial")
    os.utime(old, (time.time() - 7200, time.time() - 7200))
    with atomic_path(target) as tmp:
        tmp.write_text("a\n1\n")
    assert target.read_text() == "a\n1\n" and not old.exists() and young.exists()
