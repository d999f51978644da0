"""Calibration against rig records: lsd/calibrate.py and ``springdyn lsd calibrate``."""

import json
import tomllib

import numpy as np
import pytest

from springdyn.app.cli.main import main
from springdyn.core.errors import InputError
from springdyn.lsd import LSDModel, LSDParameters, RigData, linear_shake, simulate_rig
from springdyn.lsd.calibrate import calibrate, update_toml_text
from tests.paths import ROOT

SPEEDS = (500.0, 1000.0, 2000.0, 3000.0)
TRUE = dict(leakage_factor=3.0, leaf_friction=0.15)


def _records(params, noise, seed=0, revolutions=10, rate=10e3):
    m = LSDModel(params)
    firsts, seconds = [], []
    for k, rpm in enumerate(SPEEDS):
        for axis, out in (("x", firsts), ("y", seconds)):
            r = simulate_rig(
                m,
                linear_shake(rpm, 50e-6, axis, revolutions, rate),
                force_noise=noise,
                seed=seed + 10 * k + (axis == "y"),
            )
            out.append(RigData(r.time, r.x, r.y, r.fx, r.fy, source=f"{axis}{rpm:g}.csv"))
    return firsts, seconds


@pytest.fixture(scope="module")
def noisy():
    return _records(LSDParameters.example("C").replace(**TRUE), noise=2.0)


def test_round_trip_recovers_leakage_and_friction_with_noise(noisy):
    # records simulated with a known leakage factor and friction (2 N force noise on ~25 N
    # forces, 10 periods) are calibrated back within 1 %, starting from the
    # uncalibrated Type C (leakage 1, friction 0.1)
    firsts, seconds = noisy
    cal = calibrate(LSDParameters.example("C"), firsts, seconds, fit=["leakage_factor", "leaf_friction"])
    for name, true in TRUE.items():
        assert cal.values[name] == pytest.approx(true, rel=0.01)
        low, high = cal.intervals[name]
        assert low < cal.values[name] < high
        assert low <= true <= high  # the 95 % interval holds the truth (here: one draw)
        assert high - low < 0.05 * true
    assert cal.params.leakage_factor == cal.values["leakage_factor"]
    assert cal.coefficients == ["cxx", "cyy"]  # the fitted keys do not change K
    assert cal.dof == 2 * len(SPEEDS) - 2
    d = cal.to_dict()
    assert set(d) >= {"leakage_factor", "leakage_factor_ci", "leaf_friction", "leaf_friction_ci", "residuals"}
    assert len(d["residuals"]) == len(SPEEDS)
    assert [r["rpm"] for r in d["residuals"]] == pytest.approx(SPEEDS, rel=1e-6)
    # residuals are noise-sized: the forward model is the identification of the rig's own laws
    assert max(abs(r["cxx_relative"]) for r in d["residuals"]) < 0.02
    assert len(repr(cal).splitlines()) <= 15


def test_a_single_orbit_carries_the_caveat(noisy, tmp_path, capsys):
    # issue 40, item 8: one orbit gave an interval (-119 to +300 %) and no word.  Reference: the truth of the
    # simulated records (leakage 3, friction 0.15).  Calibrating the leakage alone from the uncalibrated
    # friction (0.1) on one 40 um orbit at 1500 rpm (5 N noise, seed 1): 2.79 with a 95 % interval of
    # 2.74-2.84 that misses the truth, since at one frequency the leakage absorbs the friction's error; the
    # caveat says so, in the result, the JSON and the CLI
    from springdyn.core.io import write_csv
    from springdyn.lsd import circular_orbit

    p = LSDParameters.example("C").replace(**TRUE)
    r = simulate_rig(LSDModel(p), circular_orbit(1500, 40e-6, 5, 10e3), force_noise=5.0, seed=1)
    rec = RigData(r.time, r.x, r.y, r.fx, r.fy, source="o.csv")
    cal = calibrate(LSDParameters.example("C"), [rec])
    low, high = cal.intervals["leakage_factor"]
    assert not low <= TRUE["leakage_factor"] <= high
    assert cal.caveat.startswith("CAVEAT: calibrated on a single orbit (1500 rpm, one excitation)")
    assert "t = 12.7" in cal.caveat and "3 or more speeds" in cal.caveat and cal.notes[0] == cal.caveat
    d = cal.to_dict()
    assert d["caveat"] == cal.caveat and d["speeds"] == 1
    # four speeds with two excitations each: no caveat
    firsts, seconds = noisy
    assert calibrate(LSDParameters.example("C"), firsts, seconds).caveat is None
    # the CLI prints it as its own line
    path = tmp_path / "o.csv"
    write_csv(path, {"time_s": rec.time, "x_m": rec.x, "y_m": rec.y, "fx_N": rec.fx, "fy_N": rec.fy})
    assert main(["lsd", "calibrate", "C", str(path)]) == 0
    out = capsys.readouterr().out
    assert any(line.startswith("CAVEAT: calibrated on a single orbit") for line in out.splitlines())


def test_without_noise_the_fit_is_exact():
    firsts, seconds = _records(LSDParameters.example("C").replace(**TRUE), noise=0.0, revolutions=3, rate=5e3)
    cal = calibrate(LSDParameters.example("C"), firsts, seconds, fit="leakage_factor,leaf_friction")
    # the model's quadrature (1024 points a period) against the records' sampling: 1e-3
    assert cal.values["leakage_factor"] == pytest.approx(3.0, rel=1e-3)
    assert cal.values["leaf_friction"] == pytest.approx(0.15, rel=1e-3)


def test_a_stiffness_parameter_fits_the_stiffness(noisy):
    firsts, seconds = noisy
    start = LSDParameters.example("C").replace(leaf_friction=0.15, leakage_factor=3.0, youngs_modulus=190e9)
    cal = calibrate(start, firsts, seconds, fit=["youngs_modulus"])
    assert "kxx" in cal.coefficients and "cxx" in cal.coefficients
    # 2 N noise on the stiffness (~16 N in phase of 25 N): within 1 %
    assert cal.values["youngs_modulus"] == pytest.approx(206e9, rel=0.01)


def test_bad_fit_requests(noisy):
    firsts, seconds = noisy
    with pytest.raises(InputError, match="not a parameter calibrate can fit"):
        calibrate(LSDParameters.example("C"), firsts, fit=["packs"])
    with pytest.raises(InputError, match="nothing to fit"):
        calibrate(LSDParameters.example("C"), firsts, fit=["oil_density"])
    with pytest.raises(InputError, match="one to one"):
        calibrate(LSDParameters.example("C"), firsts, seconds[:1])


def test_update_toml_text_keeps_comments_and_adds_keys():
    text = "# head\n[lsd]\nname = 'x'  # label\nleakage_factor = 1.0  # old\n[other]\nleakage_factor = 5\n"
    out = update_toml_text(text, {"leakage_factor": 12.5, "leaf_friction": 0.2}, {"leakage_factor": "fitted"})
    doc = tomllib.loads(out)
    assert doc["lsd"]["leakage_factor"] == 12.5 and doc["lsd"]["leaf_friction"] == 0.2
    assert doc["other"]["leakage_factor"] == 5 and out.startswith("# head") and "# fitted" in out
    with pytest.raises(InputError, match="no \\[lsd\\] table"):
        update_toml_text("[cfcs]\n", {"leakage_factor": 1.0})


def test_cli_calibrate_json_and_toml(tmp_path, capsys):
    from springdyn.core.io import write_csv

    firsts, seconds = _records(LSDParameters.example("C").replace(**TRUE), noise=1.0, revolutions=5, rate=5e3)
    paths = []
    for group in (firsts, seconds):
        ps = []
        for r in group:
            p = tmp_path / r.source
            write_csv(p, {"time_s": r.time, "x_m": r.x, "y_m": r.y, "fx_N": r.fx, "fy_N": r.fy})
            ps.append(str(p))
        paths.append(ps)
    out = tmp_path / "calibrated.toml"
    rc = main(
        [
            "lsd",
            "calibrate",
            "C",
            *paths[0],
            "--second",
            *paths[1],
            "--fit",
            "leakage_factor,leaf_friction",
            "--toml",
            str(out),
            "--json",
            "--csv",
            str(tmp_path / "res.csv"),
        ]
    )
    assert rc == 0
    d = json.loads(capsys.readouterr().out)
    assert d["leakage_factor"] == pytest.approx(3.0, rel=0.01)
    assert d["leakage_factor_ci"][0] < d["leakage_factor"] < d["leakage_factor_ci"][1]
    assert len(d["residuals"]) == len(SPEEDS)
    cal = LSDParameters.from_toml(out)
    assert cal.leakage_factor == pytest.approx(d["leakage_factor"], rel=1e-7)
    assert cal.leaf_friction == pytest.approx(d["leaf_friction"], rel=1e-7)
    assert "Calibrated by springdyn lsd calibrate" in out.read_text()
    # the table output and a bad --fit (one line, the option named)
    assert main(["lsd", "calibrate", "C", *paths[0], "--second", *paths[1]]) == 0
    assert "leakage_factor" in capsys.readouterr().out
    assert main(["lsd", "calibrate", "C", *paths[0], "--fit", "nope"]) == 2
    err = capsys.readouterr().err
    assert "--fit" in err and "nope" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("kind, force", [("a", 200.0), ("b", 300.0)])
def test_calibrated_examples_reproduce_the_thesis_forces(kind, force):
    # examples/lsd/type_{a,b}_calibrated.toml: leakage_factor solved so that the first
    # harmonic of the damper force on the rig's 50 um orbit at 500 rpm is the force the
    # thesis reports (docs/lsd.md); 1 %: the factor is written with 3 digits

    from springdyn.lsd import forward_whirl_coefficient

    root = ROOT
    p = LSDParameters.from_toml(root / "examples" / "lsd" / f"type_{kind}_calibrated.toml")
    raw = LSDParameters.from_toml(root / "examples" / "lsd" / f"type_{kind}.toml")
    assert p.replace(leakage_factor=1.0, name=raw.name) == raw  # only the calibration differs
    w = 2 * np.pi * 500 / 60
    assert abs(forward_whirl_coefficient(LSDModel(p), w, 50e-6)) * 50e-6 == pytest.approx(force, rel=0.01)
    assert abs(forward_whirl_coefficient(LSDModel(raw), w, 50e-6)) * 50e-6 > 7 * force
