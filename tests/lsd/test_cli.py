"""``springdyn lsd ...`` commands: outputs, JSON keys, bad input (exit 2, one line)."""

import json
import re

import numpy as np
import pytest

from springdyn.app.cli.main import main
from springdyn.core.io import read_csv_columns
from springdyn.lsd import LSDModel, LSDParameters
from tests.paths import EXAMPLES

COEFF_KEYS = [
    "rpm",
    "kxx_N_per_m",
    "kxy_N_per_m",
    "kyx_N_per_m",
    "kyy_N_per_m",
    "cxx_Ns_per_m",
    "cxy_Ns_per_m",
    "cyx_Ns_per_m",
    "cyy_Ns_per_m",
    "mxx_kg",
    "mxy_kg",
    "myx_kg",
    "myy_kg",
]
FILM_KEYS = ["squeeze_reynolds", "inertia_ratio", "pressure_amplitude_Pa", "cavitation_margin_Pa", "notes"]


def _json(capsys):
    out = capsys.readouterr().out
    return json.loads(out)


def test_coefficients_json_csv_plot(tmp_path, capsys):
    from importlib import resources

    cfg = resources.files("springdyn.data") / "lsd_type_c.toml"
    rc = main(
        [
            "lsd",
            "coefficients",
            str(cfg),
            "--rpm",
            "500:3000:500",
            "--amplitude",
            "50um",
            "--json",
            "--csv",
            str(tmp_path / "c.csv"),
            "--plot",
            str(tmp_path / "c.png"),
        ]
    )
    assert rc == 0
    d = _json(capsys)
    for k in COEFF_KEYS + FILM_KEYS + ["pack_stiffness_N_per_m", "load_ratios"]:
        assert k in d
    assert d["rpm"] == [500.0, 1000.0, 1500.0, 2000.0, 2500.0, 3000.0]
    # k_s of Type C (READING-NOTES 3.1, 106.9 N/mm) and Kxx = 3 k_s (3.4)
    assert d["pack_stiffness_N_per_m"] == pytest.approx(106.9e3, abs=50)
    assert d["kxx_N_per_m"][0] == pytest.approx(3 * d["pack_stiffness_N_per_m"], rel=1e-12)
    np.testing.assert_allclose(d["load_ratios"], [1, 0.7696, 0.5926], atol=5e-5)
    cols = read_csv_columns(tmp_path / "c.csv")
    assert list(cols) == COEFF_KEYS
    np.testing.assert_allclose(cols["cxx_Ns_per_m"], d["cxx_Ns_per_m"])
    assert (tmp_path / "c.png").stat().st_size > 10_000


def test_coefficients_table_and_warning(capsys):
    assert main(["lsd", "coefficients", "A", "--rpm", "1000", "--amplitude", "150um"]) == 0
    cap = capsys.readouterr()
    assert "Type A" in cap.out and "Kxx N/mm" in cap.out
    assert "exceeds the pack preload" in cap.err


def test_rig_then_identify(tmp_path, capsys):
    x, y = tmp_path / "x.csv", tmp_path / "y.csv"
    for exc, path, seed in (("x", x, "1"), ("y", y, "2")):
        assert (
            main(
                [
                    "lsd",
                    "rig",
                    "C",
                    "--rpm",
                    "1000",
                    "--eccentricity",
                    "50um",
                    "--excitation",
                    exc,
                    "--revolutions",
                    "10",
                    "--sample-rate",
                    "10kHz",
                    "--noise",
                    "2N",
                    "--seed",
                    seed,
                    "--csv",
                    str(path),
                ]
            )
            == 0
        )
    capsys.readouterr()
    cols = read_csv_columns(x)
    assert list(cols) == ["time_s", "x_m", "y_m", "fx_N", "fy_N"] and cols["time_s"].size == 6000
    rc = main(
        [
            "lsd",
            "identify",
            str(x),
            "--second",
            str(y),
            "--mass",
            "0.5kg",
            "--json",
            "--plot",
            str(tmp_path / "id.png"),
            "--model",
            "C",
        ]
    )
    assert rc == 0
    d = _json(capsys)
    model = LSDModel(LSDParameters.example("C"))
    for name in ("kxx", "kxy", "kyx", "kyy"):
        assert f"{name}_N_per_m" in d and f"{name}_N_per_m_uncertainty" in d
    for name in ("cxx", "cxy", "cyx", "cyy"):
        assert f"{name}_Ns_per_m" in d and f"{name}_Ns_per_m_uncertainty" in d
    # the simulated rig is the model within the preload: K within 1 % (2 N noise on ~30 N)
    assert d["kxx_N_per_m"] == pytest.approx(model.stiffness_matrix[0, 0], rel=0.01)
    assert d["rpm"] == pytest.approx(1000, rel=1e-6)
    assert (tmp_path / "id.png").is_file()


def test_identify_single_orbit_prints_caveat(tmp_path, capsys):
    o = tmp_path / "o.csv"
    assert (
        main(
            [
                "lsd",
                "rig",
                "C",
                "--rpm",
                "1500",
                "--eccentricity",
                "40um",
                "--revolutions",
                "5",
                "--csv",
                str(o),
                "--plot",
                str(tmp_path / "loops.png"),
            ]
        )
        == 0
    )
    assert (tmp_path / "loops.png").is_file()
    capsys.readouterr()
    assert main(["lsd", "identify", str(o), "--rpm", "1500"]) == 0
    out = capsys.readouterr().out
    assert "cannot separate direct and cross-coupled terms" in out and "kxx" in out
    assert main(["lsd", "identify", str(o), "--json", "--csv", str(tmp_path / "id.csv")]) == 0
    d = _json(capsys)
    assert "kxy_N_per_m" not in d and "kxx_N_per_m_uncertainty" in d and "caveat" in d
    assert read_csv_columns(tmp_path / "id.csv")["rpm"][0] == pytest.approx(1500, rel=1e-6)


def _bad(capsys, argv, match):
    rc = main(argv)
    err = capsys.readouterr().err
    assert rc == 2
    assert match in err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    return err


def test_bad_inputs(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    from importlib import resources

    text = (resources.files("springdyn.data") / "lsd_type_c.toml").read_text()
    bad.write_text(text.replace('["38 mm", "34 mm", "25 mm"]', '["25 mm", "34 mm", "38 mm"]'))
    _bad(capsys, ["lsd", "coefficients", str(bad)], "non-increasing")
    _bad(capsys, ["lsd", "coefficients", str(tmp_path / "none.toml")], "no such file")
    _bad(capsys, ["lsd", "coefficients", "C", "--amplitude=-5um"], "amplitude")
    _bad(capsys, ["lsd", "coefficients", "C", "--rpm", "3000:500:500"], "STOP is below START")
    _bad(
        capsys,
        [
            "lsd",
            "rig",
            "C",
            "--rpm",
            "1000",
            "--eccentricity",
            "50um",
            "--sample-rate",
            "20Hz",
            "--csv",
            str(tmp_path / "r.csv"),
        ],
        "too low",
    )
    assert not (tmp_path / "r.csv").exists()  # nothing half-written
    nan = tmp_path / "nan.csv"
    nan.write_text("time_s,x_m,y_m,fx_N,fy_N\n0,0,0,0,0\n0.001,nan,0,0,0\n")
    _bad(capsys, ["lsd", "identify", str(nan)], "row 3, column 'x_m'")
    miss = tmp_path / "miss.csv"
    miss.write_text("time_s,x_m,y_m,fx_N\n0,0,0,0\n")
    _bad(capsys, ["lsd", "identify", str(miss)], "missing column 'fy_N'")


def test_rig_along_measured_path(tmp_path, capsys):
    # the ring follows a measured x(t), y(t) (here a sampled orbit); forces match the
    # analytic orbit within the finite-difference error (1e-3 of the peak force)
    from springdyn.core.io import write_csv
    from springdyn.lsd import circular_orbit, simulate_rig

    tr = circular_orbit(1000, 50e-6, 3, 10e3)
    write_csv(tmp_path / "path.csv", {"time_s": tr.time, "x_m": tr.x, "y_m": tr.y})
    assert (
        main(
            [
                "lsd",
                "rig",
                "C",
                "--path",
                str(tmp_path / "path.csv"),
                "--rpm",
                "1000",
                "--csv",
                str(tmp_path / "out.csv"),
                "--plot",
                str(tmp_path / "out.png"),
            ]
        )
        == 0
    )
    out = read_csv_columns(tmp_path / "out.csv")
    ref = simulate_rig(LSDModel(LSDParameters.example("C")), tr)
    inner = slice(5, -5)
    np.testing.assert_allclose(out["fx_N"][inner], ref.fx[inner], atol=1e-3 * np.abs(ref.fx).max())
    capsys.readouterr()
    _bad(capsys, ["lsd", "rig", "C", "--csv", str(tmp_path / "o.csv")], "needs --rpm and --eccentricity")


def test_issue11_reproducers(capsys, tmp_path):
    """A wrong --rpm, an all-zero record, an absurd rig request and a unit slip."""
    x = tmp_path / "x.csv"
    assert (
        main(
            [
                "lsd",
                "rig",
                "C",
                "--rpm",
                "1000",
                "--eccentricity",
                "50um",
                "--excitation",
                "x",
                "--revolutions",
                "5",
                "--csv",
                str(x),
            ]
        )
        == 0
    )
    capsys.readouterr()
    assert main(["lsd", "identify", str(x), "--rpm", "3000", "--json"]) == 2
    assert "does not match the record" in capsys.readouterr().err
    zeros = tmp_path / "z.csv"
    lines = x.read_text().splitlines()
    zeros.write_text("\n".join([lines[0]] + [r.split(",")[0] + ",0,0,0,0" for r in lines[1:]]) + "\n")
    assert main(["lsd", "identify", str(zeros), "--rpm", "1000", "--json"]) == 2
    assert "nothing to identify" in capsys.readouterr().err
    assert main(["lsd", "rig", "C", "--rpm", "2.5", "--eccentricity", "50um", "--csv", str(tmp_path / "r.csv")]) == 2
    assert "samples, more than" in capsys.readouterr().err
    assert (
        main(
            [
                "lsd",
                "rig",
                "C",
                "--rpm",
                "1000",
                "--eccentricity",
                "50um",
                "--revolutions",
                "inf",
                "--csv",
                str(tmp_path / "r.csv"),
            ]
        )
        == 2
    )
    assert "finite" in capsys.readouterr().err
    assert main(["lsd", "coefficients", "C", "--rpm", "1000", "--amplitude", "50", "--json"]) == 0
    assert "did you mean 50 um" in capsys.readouterr().err


def test_a_frequency_is_revolutions_per_second_in_every_lsd_command(tmp_path, capsys):
    # --rpm 50Hz is 3000 rpm (not 50 rad/s = 477.5 rpm) everywhere
    assert main(["lsd", "coefficients", "C", "--rpm", "50Hz,1000", "--json"]) == 0
    assert _json(capsys)["rpm"] == pytest.approx([3000.0, 1000.0])
    x = tmp_path / "x.csv"
    assert (
        main(
            [
                "lsd",
                "rig",
                "C",
                "--rpm",
                "50Hz",
                "--eccentricity",
                "20um",
                "--excitation",
                "x",
                "--revolutions",
                "3",
                "--csv",
                str(x),
            ]
        )
        == 0
    )
    assert "at 3000 rpm" in capsys.readouterr().out
    assert main(["lsd", "identify", str(x), "--rpm", "50 Hz", "--json"]) == 0
    assert _json(capsys)["rpm"] == pytest.approx(3000.0)
    assert main(["lsd", "calibrate", "C", str(x), "--rpm", "50Hz", "--json"]) == 0
    assert _json(capsys)["residuals"][0]["rpm"] == pytest.approx(3000.0)


def test_library_speeds_are_rpm_or_omega():
    model = LSDModel(LSDParameters.example("C"))
    a = model.coefficients([3000.0])
    b = model.coefficients(omega=[100 * np.pi])
    np.testing.assert_allclose(a.C, b.C, rtol=1e-12)
    assert b.rpm[0] == pytest.approx(3000.0)
    with pytest.raises(ValueError, match="exactly one"):
        model.coefficients([3000.0], omega=[1.0])


def test_amplitude_api_validates_like_the_cli():
    """Issue 27: amplitude=None raised a numpy TypeError and 5e-324 gave infinite damping; a
    length in mm read as m gets the um it likely meant."""
    import warnings

    from springdyn.core.errors import InputError
    from springdyn.lsd import LSDModel, LSDParameters

    m = LSDModel(LSDParameters.example("C"))
    for bad, message in ((None, "must be a vibration amplitude in m"), (5e-324, "must be at least 1e-09 m")):
        with pytest.raises(InputError, match=message):
            m.coefficients([1000.0], amplitude=bad)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        m.coefficients([1000.0], amplitude=0.05)  # "50 mm" for 50 um
    assert any("did you mean 50 um" in str(w.message) for w in seen)


def test_film_map_command(tmp_path, capsys):
    # a 2 x 2 map of Type C: inertia from ~1401 rpm (omega tau = 0.1), cavitation at 14100 rpm, 100 um
    args = ["lsd", "film", "C", "--rpm", "3000,14100", "--amplitude", "20um,100um", "--steps", "128", "--quiet"]
    assert main(args + ["--csv", str(tmp_path / "m.csv"), "--plot", str(tmp_path / "m.png")]) == 0
    out = capsys.readouterr().out
    assert "inertia changes the oil force by more than 10 % from 1401 rpm" in out
    assert re.search(
        r"at 100 um the film cavitates from 14100 rpm; cavitation changes the force by more than 10 % from 14100 rpm",
        out,
    )
    cols = read_csv_columns(tmp_path / "m.csv")
    assert len(cols["rpm"]) == 4 and "cavitation_change" in cols
    assert (tmp_path / "m.png").stat().st_size > 10_000
    assert main(args + ["--json"]) == 0
    d = _json(capsys)
    assert d["inertia_onset_rpm"] == pytest.approx(1401, abs=1)
    assert d["cavitation_change"][1][1] > 0.5 and d["cavitation_change_onset_rpm"][1] == 14100.0
    # issue 40, item 8: the figures for air-saturated oil (0.9 bar abs) beside the vapour limit's
    assert "19.5 um at the vapour limit" in out and "2.17 um with air-saturated oil" in out
    assert "with air-saturated oil, at 100 um the film cavitates from 3000 rpm" in out
    assert d["cavitation_sensitivity"]["aerated"]["cavitation_start_rpm"] == [3000.0, 3000.0]
    assert main(["lsd", "film", "C", "--steps", "8"]) == 2


def test_coefficients_with_the_film(capsys):
    # --film: describing function of the film network; at 14100 rpm, 100 um it has cavitated
    assert main(["lsd", "coefficients", "C", "--rpm", "3000,14100", "--amplitude", "100um", "--film", "--json"]) == 0
    d = _json(capsys)
    assert d["cavitated"] == [False, True]
    assert d["mxx_kg"][1] < 0.5 * d["mxx_kg"][0] and min(d["min_pressure_Pa"]) >= 0.0
    assert main(["lsd", "coefficients", "C", "--rpm", "14100", "--amplitude", "50um"]) == 0
    out = capsys.readouterr()
    assert "Mxx kg" in out.out and "cavitates" in out.out + out.err


def test_rig_with_the_film(tmp_path, capsys):
    # a 100 um orbit at 3000 rpm of Type C with air release at 0.9 bar: the pressures stop at 0.9 bar
    cfg = tmp_path / "c.toml"
    text = (EXAMPLES / "lsd/type_c.toml").read_text()
    cfg.write_text(text.replace("[lsd]", '[lsd]\ncavitation_pressure = "0.9 bar"'))
    args = ["lsd", "rig", str(cfg), "--rpm", "3000", "--eccentricity", "100um", "--revolutions", "4"]
    assert main(args + ["--film", "--csv", str(tmp_path / "r.csv")]) == 0
    out = capsys.readouterr().out
    m = re.search(r"lowest chamber pressure ([\d.]+) bar absolute", out)
    assert m and float(m.group(1)) == pytest.approx(0.9, abs=1e-6)
