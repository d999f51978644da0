"""The readable output carries every caveat the JSON carries (issue 27, part 4): for each
command below, every ``notes`` entry of ``--json`` appears as a ``note:`` line (or, for the
ones a command states in its own line, in its words) of the text output."""

import json

import pytest

from springdyn.app.cli.main import main
from tests.paths import ROOT, example

ONE = str(ROOT / "src/springdyn/data/valve_one_step.toml")
CAM = example("valve/cam_345.toml")
TRAIN = str(ROOT / "src/springdyn/data/valve_train_direct_acting.toml")

CASES = [
    ["cfcs", "dynamic", "table1", "--omega", "14.7", "--offset", "0"],  # toggle-dominated
    ["cfcs", "forward", "table1", "--force", "0N", "--x0", "0mm", "--t-end", "0.05s"],  # unloaded part
    ["valve", "simulate", ONE, "--cam", CAM, "--cam-rpm", "3000", "--revolutions", "2"],  # default strengths
    ["valve", "simulate", ONE, "--cam", CAM, "--cam-rpm", "3300", "--valve-train", TRAIN, "--revolutions", "3"],
    ["lsd", "coefficients", str(ROOT / "src/springdyn/data/lsd_type_c.toml"), "--rpm", "3000"],
]


def _notes(data) -> list:
    items = data if isinstance(data, list) else [data]
    return [n for d in items for n in (d.get("notes") or [])]


@pytest.mark.parametrize("argv", CASES, ids=lambda a: " ".join(a[:3]).replace(f"{ROOT}/", ""))  # ids as from the root
def test_every_json_note_is_in_the_text(argv, capsys):
    assert main([*argv, "--json", "--quiet"]) == 0
    notes = _notes(json.loads(capsys.readouterr().out))
    assert main([*argv, "--quiet"]) == 0
    text = capsys.readouterr().out
    for note in notes:
        assert note in text, f"the text drops the note {note!r}"


def test_every_sweep_note_is_in_the_text(capsys, tmp_path):
    """valve sweep writes no JSON: its summary's notes, from the API, against its text."""
    from springdyn.valve import ValveSpring
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.run.sweeps import sweep

    res = sweep(ValveSpring.from_toml(ONE), Cam.from_toml(CAM), [3000.0, 3400.0], revolutions=2, quiet=True)
    notes = res.summary.get("notes", [])
    assert notes  # two revolutions from rest do not settle: at least that note
    argv = ["valve", "sweep", ONE, "--cam", CAM, "--cam-rpm", "3000,3400", "--revolutions", "2", "--quiet"]
    assert main([*argv, "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    for note in notes:
        if "did not settle within their revolutions" in note:  # said by the sweep's own periodicity line
            assert "did not settle in 2 revolutions" in text
            continue
        assert note in text, f"the text drops the note {note!r}"
