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
    next write of the same file removes such a temporary of an earlier version once it is older
    than an hour (a younger one may belong to a run still going)."""
    import os
    import time

    from springdyn.core.io import atomic_path

    target = tmp_path / "out.csv"
    old = tmp_path / ".out.csv.abc12345.csv"
    young = tmp_path / ".out.csv.def45678.csv"
    for f in (old, young):
        f.write_text("partial")
    os.utime(old, (time.time() - 7200, time.time() - 7200))
    with atomic_path(target) as tmp:
        tmp.write_text("a\n1\n")
    assert target.read_text() == "a\n1\n" and not old.exists() and young.exists()


def test_a_killed_runs_temporaries_are_swept_by_the_next_write_in_the_folder(tmp_path):
    """Issue 40: a SIGKILLed sweep's temporaries were left for ever (only the same file's,
    after an hour, were removed).  Temporaries are named '.<name>.<pid>-XXXXXXXX.tmp<suffix>';
    the first write of a process in a folder removes those of any file whose process is gone,
    keeps a live process's (this one's) and leaves other files alone."""
    import subprocess
    import sys

    from springdyn.core import io

    gone = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    dead = int(gone.stdout)  # a process that has ended
    stale = tmp_path / f".sweep.nc.{dead}-abcd1234.tmp.nc"
    live = tmp_path / f".other.csv.{os.getpid()}-efgh5678.tmp.csv"
    mine = tmp_path / ".notes.txt"  # a hidden file of the user's, not a temporary
    for f in (stale, live, mine):
        f.write_text("partial")
    io._SWEPT.discard(os.path.abspath(tmp_path))
    with io.atomic_path(tmp_path / "out.csv") as tmp:
        assert io.TEMPORARY_NAME.match(tmp.name) and f".out.csv.{os.getpid()}-" in tmp.name
        tmp.write_text("a\n1\n")
    assert not stale.exists() and live.exists() and mine.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([live.name, mine.name, "out.csv"])


def test_a_write_error_names_the_output_not_its_temporary(tmp_path, monkeypatch, capsys):
    """Issue 40: exit-74 messages named the hidden temporary ('cannot write
    /dir/.sweep_summary.csv.k2j3x9.csv: No space left on device').  An OS error while writing,
    renaming or creating the temporary names the output file the user asked for."""
    import errno

    from springdyn.app.cli.main import main
    from springdyn.core import io

    target = tmp_path / "out.csv"
    with pytest.raises(OSError) as caught:
        with io.atomic_path(target) as tmp:
            raise OSError(errno.ENOSPC, f"No space left on device writing {tmp}", str(tmp))
    assert caught.value.filename == str(target) and ".tmp" not in str(caught.value)
    assert caught.value.errno == errno.ENOSPC and list(tmp_path.iterdir()) == []

    def refuse(src, dst, **kw):
        raise PermissionError(errno.EACCES, "Permission denied", str(src), None, str(dst))

    monkeypatch.setattr(io.os, "replace", refuse)
    out = tmp_path / "curve.csv"
    from tests.paths import example

    spring = example("valve/one_step_spring.toml")
    assert main(["valve", "curve", spring, "--csv", str(out)]) == 74
    err = capsys.readouterr().err
    assert f"springdyn: cannot write {out}: Permission denied" in err and ".tmp" not in err

    monkeypatch.undo()

    def no_temporary(*args, **kw):
        raise PermissionError(errno.EACCES, "Permission denied", str(tmp_path / f".out.csv.{os.getpid()}-x.tmp.csv"))

    monkeypatch.setattr(io.tempfile, "mkstemp", no_temporary)
    with pytest.raises(PermissionError, match="Permission denied") as caught:
        with io.atomic_path(target):
            pass
    assert caught.value.filename == str(target)


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into any folder")
def test_an_unwritable_folder_names_the_output_file(tmp_path):
    """A folder made read-only after the command's checks: the message names the output file."""
    from springdyn.core import io

    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o500)
    try:
        with pytest.raises(PermissionError) as caught:
            io.write_csv(folder / "out.csv", {"a": [1.0]})
        assert caught.value.filename == str(folder / "out.csv")
    finally:
        folder.chmod(0o700)
