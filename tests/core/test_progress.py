"""springdyn.core.progress: a bar on a terminal, a line now and then in a log, nothing when quiet
(issue 39: a five-minute synthesis said nothing when stderr was not a terminal)."""

from __future__ import annotations

from springdyn.core import progress as prog


def test_a_log_gets_a_line_per_interval_and_a_short_job_none(capsys, monkeypatch):
    assert list(prog.progress(range(3), total=3, desc="variants")) == [0, 1, 2]
    assert capsys.readouterr().err == ""  # shorter than LOG_INTERVAL: nothing
    monkeypatch.setattr(prog, "LOG_INTERVAL", 0.0)
    assert list(prog.progress(range(2), total=2, desc="variants")) == [0, 1]
    lines = capsys.readouterr().err.splitlines()
    assert [ln.split(" after ")[0] for ln in lines] == [
        "springdyn: variants: 1/2 (50 %)",
        "springdyn: variants: 2/2 (100 %)",
    ]
    assert list(prog.progress(iter("ab"), desc="")) == ["a", "b"]
    assert capsys.readouterr().err.splitlines()[0].startswith("springdyn: working: 1 after ")


def test_quiet_is_silent(capsys, monkeypatch):
    monkeypatch.setattr(prog, "LOG_INTERVAL", 0.0)
    assert list(prog.progress(range(3), total=3, quiet=True)) == [0, 1, 2]
    assert capsys.readouterr().err == ""
