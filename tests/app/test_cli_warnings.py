"""Each warning once per command (issue 39): the coil-bind clearance is checked on two paths
(the spring's design figures for a lift, and every run's set-up for the cam), and a report
takes both; the command says the fact once, and not on stderr when its printed result states
it as a note already."""

from __future__ import annotations

import json
import re
import warnings

import pytest

from springdyn.app.cli import main as cli
from springdyn.app.cli.main import main
from springdyn.core.errors import FactWarning
from tests.paths import ROOT, example

ONE = str(ROOT / "src/springdyn/data/valve_one_step.toml")  # 9 mm of lift leaves 1 mm above solid: inside Sa
CAM = example("valve/cam_345.toml")


@pytest.fixture
def short_spring(tmp_path):
    """The one-step spring at a smaller installed length: 0.3 mm above solid at full lift."""
    text = (ROOT / "src/springdyn/data/valve_one_step.toml").read_text()
    src = tmp_path / "short.toml"
    src.write_text(text.replace('installed_length = "38 mm"', 'installed_length = "37.3 mm"'))
    assert src.read_text() != text
    return str(src)


def _run(argv) -> int:
    """``main(argv)`` as a fresh process would see warnings (none shown yet in this process)."""
    with warnings.catch_warnings():
        warnings.simplefilter("default")  # a changed filter forgets the warnings already shown
        return main(argv)


def _coil_bind_lines(text: str) -> list[str]:
    return [ln for ln in text.splitlines() if "coil bind:" in ln]


def test_one_fact_is_kept_once_whatever_its_words(monkeypatch):
    monkeypatch.setattr(cli, "_PENDING_WARNINGS", [])
    with warnings.catch_warnings():
        warnings.simplefilter("always")
        monkeypatch.setattr(warnings, "showwarning", cli._show_warning)
        warnings.warn(FactWarning("coil bind: lift = 9 mm leaves 1 mm", key="coil bind"), stacklevel=1)
        warnings.warn(FactWarning("coil bind: the cam (valve lift 9 mm) leaves 1 mm", key="coil bind"), stacklevel=1)
        warnings.warn("something else", stacklevel=1)
        warnings.warn("something else", stacklevel=1)
    assert [t for _, t in cli._PENDING_WARNINGS] == [
        "springdyn: warning: coil bind: lift = 9 mm leaves 1 mm",
        "springdyn: warning: something else",
    ]


def test_design_warns_once(short_spring, capsys):
    assert _run(["valve", "design", short_spring, "--lift", "9mm", "--cam-rpm", "3000"]) == 0
    err = capsys.readouterr().err
    assert len(_coil_bind_lines(err)) == 1, err


def test_simulate_says_coil_bind_once(short_spring, capsys):
    """The text states it as a note: stderr does not repeat it; with --json, stderr says it once."""
    argv = ["valve", "simulate", short_spring, "--cam", CAM, "--cam-rpm", "3000", "--revolutions", "2", "--quiet"]
    assert _run(argv) == 0
    out, err = capsys.readouterr()
    assert len(_coil_bind_lines(out)) == 1 and not _coil_bind_lines(err), (out, err)
    assert _run([*argv, "--json"]) == 0
    out, err = capsys.readouterr()
    assert len(_coil_bind_lines(err)) == 1, err
    assert any(n.startswith("coil bind:") for n in json.loads(out)["notes"])


@pytest.mark.slow  # a whole valve report (~30 s)
def test_report_warns_once(tmp_path, capsys):
    """The report takes both paths (design figures at the lift, runs on the cam): one line."""
    src = (ROOT / "examples" / "report" / "report_valve_one_step.toml").read_text()
    f = tmp_path / "one.toml"
    f.write_text(
        src + '\n[report]\nmin_engine_rpm = "2000 rpm"\nmax_engine_rpm = "5000 rpm"\nengine_rpm_step = "500 rpm"\n'
        'models = "type-c"\n'
    )
    assert _run(["report", str(f), "--out", str(tmp_path / "rep")]) == 0
    err = capsys.readouterr().err
    assert len(_coil_bind_lines(err)) == 1, err


@pytest.mark.slow  # two valve reports side by side (~40 s)
def test_reports_side_by_side_warn_once_per_spring_in_order(tmp_path, capsys):
    """Two definitions in two processes (``--workers 2``): each spring's coil bind once, in the
    order of the definitions (the warnings come back from the processes to this one)."""
    src = (ROOT / "examples" / "report" / "report_valve_one_step.toml").read_text()
    f = tmp_path / "one.toml"
    f.write_text(
        src + '\n[report]\nmin_engine_rpm = "2000 rpm"\nmax_engine_rpm = "5000 rpm"\nengine_rpm_step = "500 rpm"\n'
        'models = "type-c"\n'
    )
    two = str(ROOT / "examples" / "report" / "report_valve_two_step.toml")
    assert _run(["report", two, str(f), "--out", str(tmp_path / "rep"), "--workers", "2", "--quiet"]) == 0
    lines = _coil_bind_lines(capsys.readouterr().err)
    assert len(lines) == 2, lines
    assert re.search(r"lift (= )?7\.5 mm", lines[0]) and re.search(r"lift (= )?9 mm", lines[1]), lines
