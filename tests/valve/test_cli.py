"""``springdyn valve ...`` commands: output contracts and bad input (exit code 2)."""

import csv
import json
import math
from importlib import resources

import pytest

from springdyn.app.cli.main import main

ONE = str(resources.files("springdyn.data") / "valve_one_step.toml")
TWO = str(resources.files("springdyn.data") / "valve_two_step.toml")

PARAM_KEYS = "K K1 K2 K3 Kh1 Kh2 m1 m2 me M f1 f2 n1p n2p Pc Lc Fset F1 F2 Fcon C0".split()


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_params_json_keys(capsys):
    code, out, _ = run(capsys, "valve", "params", ONE, "--json")
    assert code == 0
    data = json.loads(out)
    assert sorted(data) == sorted(PARAM_KEYS)
    assert data["Fset"] == pytest.approx(251.43, rel=1e-4)
    code, out, _ = run(capsys, "valve", "params", TWO, "--json")
    assert sorted(json.loads(out)) == sorted(PARAM_KEYS + ["Ks"])


def test_params_table(capsys):
    code, out, _ = run(capsys, "valve", "params", ONE)
    assert code == 0 and "Kh1" in out and "80.744 N/mm" in out


def test_curve_csv_and_plot(capsys, tmp_path):
    csv_path, png = tmp_path / "c.csv", tmp_path / "c.png"
    code, _, _ = run(
        capsys,
        "valve",
        "curve",
        ONE,
        "--from",
        "48mm",
        "--to",
        "30mm",
        "--points",
        "50",
        "--csv",
        str(csv_path),
        "--plot",
        str(png),
    )
    assert code == 0
    rows = list(csv.reader(open(csv_path)))
    assert rows[0] == [
        "length_m",
        "force_N",
        "stiffness_N_per_m",
        "first_mode_frequency_Hz",
    ]  # the first mode beside the force (distributed model)
    assert len(rows) == 51
    assert float(rows[1][0]) == pytest.approx(0.048) and float(rows[-1][0]) == pytest.approx(0.030)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_modes_json(capsys):
    code, out, _ = run(capsys, "valve", "modes", ONE, "--length", "38 mm", "--count", "3", "--json")
    data = json.loads(out)
    assert set(data) == {"length_m", "force_N", "frequencies_Hz", "modes"}
    assert data["modes"] == ["surge 1", "surge 2", "surge 3"]
    assert data["frequencies_Hz"] == sorted(data["frequencies_Hz"])
    assert data["frequencies_Hz"][0] == pytest.approx(449.61, abs=0.005)


def test_design(capsys):
    code, out, _ = run(capsys, "valve", "design", ONE, "--lift", "9mm", "--cam-rpm", "3000", "--json")
    assert code == 0
    assert json.loads(out)["installed"]["surge_margin"] == pytest.approx(449.61 / 50, rel=1e-4)


@pytest.mark.parametrize(
    "argv,message",
    [
        (["valve", "modes", ONE, "--length", "10mm"], "length = 10 mm is outside the range of the spring"),
        (["valve", "modes", ONE, "--length", "38 kg"], "--length = '38 kg' has the wrong dimension"),
        (["valve", "curve", ONE, "--to", "5mm"], "--to = 5 mm is outside the range"),
        (["valve", "params", "nonexistent.toml"], "nonexistent.toml: no such file"),
        (["valve", "modes", ONE, "--length", "38mm", "--count", "9"], "--count = 9 must be a whole number from 1 to 5"),
        # a literal '--' is named, not reported as a missing value or an unknown argument (issue 27)
        (["valve", "modes", ONE, "--length", "--"], "a bare '--' after --length is not an argument"),
        (["valve", "params", ONE, "--"], "a bare '--' is not an argument springdyn takes"),
    ],
)
def test_bad_input_exit_2(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert message in err
    assert "Traceback" not in err and err.count("\n") == 1


def test_bad_toml_exit_2(capsys, tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text(open(ONE).read().replace('installed_length = "38 mm"', 'installed_length = "50 mm"'))
    code, _, err = run(capsys, "valve", "params", str(f))
    assert code == 2
    assert "installed_length = 50 mm must be shorter than free_length = 48 mm" in err


def test_argparse_errors_exit_2_in_one_line(capsys):
    code, out, err = run(capsys, "valve", "modes", ONE)  # --length missing
    assert code == 2
    assert err.count("\n") == 1 and "--length" in err and "usage:" not in err


def test_cli_help_states_the_library_defaults(capsys):
    """The options' help reads the run settings' own defaults (one home, numba-free)."""
    import subprocess
    import sys

    from springdyn.valve.run import settings

    out = subprocess.run(
        [sys.executable, "-m", "springdyn.app.cli.main", "valve", "simulate", "--help"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    assert f"default {settings.DEFAULT_RTOL:g}, {settings.TRAIN_RTOL:g} with a valve train" in " ".join(out.split())
    code = "import sys, springdyn.app.cli.main as m; m.build_parser('valve'); print('numba' in sys.modules)"
    assert subprocess.run([sys.executable, "-c", code], capture_output=True, text=True).stdout.strip() == "False"


def test_every_valve_command_takes_the_model_option(capsys):
    code, out, err = run(capsys, "valve", "params", ONE, "--model", "type-c", "--json")
    assert code == 0
    code, out, err = run(capsys, "valve", "params", ONE, "--model", "nonsense")
    assert code == 2 and "--model" in err


@pytest.mark.slow
@pytest.mark.parametrize("quiet", [False, True])
def test_a_compiling_command_says_so_in_one_line_unless_quiet(tmp_path, quiet):
    """With an empty compile cache the first `valve simulate` prints one line on
    stderr while its engine compiles (what, about how long, once per machine), none under
    --quiet; the result on stdout is the same."""
    import os
    import subprocess
    import sys

    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_")}
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "cache")
    cam = str(resources.files("springdyn.data") / "valve_cam_345.toml")
    argv = [
        sys.executable,
        "-c",
        "import sys; from springdyn.app.cli.main import main; sys.exit(main())",
        "valve",
        "simulate",
        ONE,
        "--cam",
        cam,
        "--cam-rpm",
        "3000",
    ] + (["--quiet"] if quiet else [])
    done = subprocess.run(argv, capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "retainer force" in done.stdout
    # compile notices only: warnings about the input (here the coil-bind clearance) stay under --quiet
    notices = [
        ln
        for ln in done.stderr.splitlines()
        if ln.startswith("springdyn:") and not ln.startswith("springdyn: warning:")
    ]
    if quiet:
        assert notices == []
    else:
        assert len(notices) == 1, done.stderr
        assert "compiling the valve engine (spring alone, Dormand-Prince 5(4))" in notices[0]
        assert "once per machine" in notices[0]


def test_train_modes_with_the_cam_contact_open_prints_the_jump_frequency(capsys):
    """``train-modes --cam-contact open``: the separated train's modes and jump frequency, the
    library's figures (separated_frequencies); a wrong use is one line and exit 2."""
    import warnings

    from springdyn.valve import Cam, ValveSpring, ValveTrain
    from springdyn.valve.run.train_modes import separated_frequencies

    cam = str(resources.files("springdyn.data") / "valve_cam_345.toml")
    vt = str(resources.files("springdyn.data") / "valve_train_direct_acting.toml")
    base = ["valve", "train-modes", ONE, "--cam", cam, "--valve-train", vt, "--cam-contact", "open"]
    code, out, _ = run(capsys, *base, "--valve-lift", "5mm", "--count", "3", "--json")
    data = json.loads(out)
    assert code == 0 and data["cam_contact"] == "open" and data["valve_lift_m"] == pytest.approx(5e-3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the 9 mm cam's coil-bind clearance warning
        ref = separated_frequencies(
            ValveSpring.from_toml(ONE), Cam.from_toml(cam), ValveTrain.from_toml(vt), count=3, valve_lift=5e-3
        )
    assert data["jump_frequency_Hz"] == pytest.approx(ref["jump_frequency_Hz"], rel=1e-12)
    assert data["frequencies_Hz"] == pytest.approx(ref["frequencies_Hz"], rel=1e-12)
    code, out, _ = run(capsys, *base)
    assert code == 0 and "jump frequency (first mode of the separated train):" in out
    code, _, err = run(capsys, "valve", "train-modes", ONE, "--cam", cam, "--cam-contact", "open")
    assert code == 2 and "need a valve train" in err and err.count("\n") == 1
    code, _, err = run(capsys, *base, "--valve-lift", "0mm")
    assert code == 2 and "--valve-lift = 0 mm must be above 0" in err


def test_options_of_issue_40_are_refused_not_ignored(capsys, tmp_path):
    """Issue 40: options silently ignored or nonsense accepted, each now one message, exit 2."""
    from tests.paths import example

    spring, cam = example("valve/one_step_spring.toml"), example("valve/cam_345.toml")
    exhaust, pressure = example("valve/exhaust_valve.toml"), example("valve/cylinder_pressure.csv")
    lift = tmp_path / "lift.csv"
    lift.write_bytes(open(example("valve/valve_lift.csv"), "rb").read())
    before = lift.read_bytes()
    cases = [
        (
            ["valve", "simulate", spring, "--cam", cam, "--cam-rpm", "2000", "--port-pressure", "2 bar"],
            "--port-pressure = '2 bar' needs --gas-pressure",
        ),
        (
            [
                "valve",
                "simulate",
                spring,
                "--cam",
                exhaust,
                "--valve-train",
                exhaust,
                "--cam-rpm",
                "2000",
                "--gas-pressure",
                pressure,
                "--port-pressure",
                "-2 bar",
            ],
            "is an absolute pressure: it must be 0 or more",
        ),
        (
            [
                "valve",
                "sweep",
                spring,
                "--cam",
                cam,
                "--cam-rpm",
                "1000,2000",
                "--scheduler",
                "",
                "--out",
                str(tmp_path / "s"),
            ],
            "--scheduler = '': give a Dask scheduler's address",
        ),
        (["valve", "synthesize", example("valve/requirements.toml"), "--out", ""], "--out: an empty folder name"),
        (
            [
                "valve",
                "cam-from-lift",
                str(lift),
                "--valve-train",
                example("valve/valve_train_with_follower.toml"),
                "--out",
                str(lift),
            ],
            "is the input LIFT.csv: writing the lobe would overwrite it",
        ),
    ]
    for argv, message in cases:
        code, _, err = run(capsys, *map(str, argv))
        assert code == 2 and message in err and "Traceback" not in err, (argv, err)
    assert lift.read_bytes() == before


def test_study_commands_answer_a_new_users_mistakes_in_the_options_words(capsys, tmp_path):
    """Issue 40, item 7: `valve tolerance --out FILE` (an existing file) failed at the end with
    exit 74 ('cannot write FILE/chunks: Not a directory'); `--samples abc` answered with the unit
    parser's words ("'abc' is not defined in the unit registry"); `valve sweep --workers x` with
    argparse's ('invalid int value'); a --vary value the spring refuses named itself twice and
    the API's `on_invalid='skip'`.  Each is one line naming the option, exit 2."""
    from tests.paths import example

    spring, cam = example("valve/one_step_spring.toml"), example("valve/cam_345.toml")
    tol = tmp_path / "tol.toml"
    tol.write_text('[tolerances]\nwire_diameter = "+-0.02 mm"\n')
    study = ["valve", "tolerance", spring, "--cam", cam, "--tolerances", str(tol), "--cam-rpm", "1500,2500"]
    sweep = ["valve", "sweep", spring, "--cam", cam, "--cam-rpm", "1000,2000", "--out", str(tmp_path / "s")]
    cases = [
        (study + ["--samples", "4", "--out", str(tol)], f"--out = {str(tol)!r} is an existing file: give a folder"),
        (study + ["--samples", "abc", "--out", str(tmp_path / "o")], "--samples = 'abc' must be a whole number from 1"),
        (study + ["--samples", "4", "--seed", "1.5", "--out", str(tmp_path / "o")], "--seed = '1.5' must be a whole"),
        (sweep + ["--workers", "x"], "--workers = 'x' must be a whole number of at least 1"),
        (
            sweep + ["--vary", "installed_length=0.1mm:0.3mm:0.1mm"],
            "--vary: installed_length = 0.1 mm is at or below coil contact",
        ),
    ]
    for argv, words in cases:
        assert main(argv) == 2, argv
        err = capsys.readouterr().err
        assert err.startswith(f"springdyn: error: {words}") and err.count("\n") == 1, err
        assert "on_invalid" not in err and "registry" not in err and "invalid int" not in err
    assert main(sweep + ["--vary", "installed_length=0.1mm:0.3mm:0.1mm"]) == 2
    assert "(--on-invalid skip leaves such values out)" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()  # refused before any work


def test_camshaft_one_speed_json_and_out(capsys, tmp_path):
    """``valve camshaft``: the summary as JSON with the modes, the tables and figure in --out."""
    from tests.paths import example

    out_dir = tmp_path / "cs"
    code, out, _ = run(
        capsys,
        "valve",
        "camshaft",
        example("valve/camshaft_4lobe.toml"),
        "--cam-rpm",
        "2000",
        "--json",
        "--quiet",
        "--out",
        str(out_dir),
    )
    assert code == 0
    data = json.loads(out)
    assert data["converged"] and data["lobe_count"] == 4
    assert data["modes_Hz"][0] == pytest.approx(423.2, abs=0.1)  # the example's first torsional mode
    assert sorted(p.name for p in out_dir.iterdir()) == ["camshaft.csv", "camshaft.png", "torsional-modes.csv"]
    with open(out_dir / "camshaft.csv", newline="") as fh:
        header = next(csv.reader(fh))
    assert "drive_torque_N_m" in header and "twist_cylinder_1_rad" in header


def test_camshaft_without_lobes_is_bad_input(capsys, tmp_path):
    f = tmp_path / "shaft.toml"
    f.write_text('[camshaft]\nsprocket_inertia = "1e-3 kg*m^2"\ndrive_stiffness = "1e4 N*m/rad"\n', encoding="utf-8")
    code, _, err = run(capsys, "valve", "camshaft", str(f), "--cam-rpm", "2000")
    assert code == 2 and "[[camshaft.lobes]]" in err and len(err.strip().splitlines()) == 1


def test_a_spring_pack_file_in_the_commands_of_one_spring_of_the_cam_and_of_a_camshaft(capsys, tmp_path):
    """A spring pack's file (issue 41): the commands of one spring refuse it in one line (exit 2)
    naming the commands that take a pack; cam-check takes it, its kinematic load with a third of the
    springs' mass ([MMS]'s spring mass ``rho (pi d^2/4) pi D (N - 0.7)`` of each, by hand here)
    beside the train's; a camshaft's lobe refuses it naming the pack's table."""
    import re

    from tests.paths import EXAMPLES

    pack = str(EXAMPLES / "valve" / "dual_spring_damper.toml")
    for argv in (("params", pack), ("design", pack, "--lift", "9mm"), ("curve", pack)):
        code, out, err = run(capsys, "valve", *argv)
        assert code == 2 and out == "" and len(err.strip().splitlines()) == 1, err
        assert "not a spring pack" in err and "springdyn report" in err
    train = str(EXAMPLES / "valve" / "valve_train_with_follower.toml")
    cam = str(EXAMPLES / "valve" / "cam_polydyne_ramps.toml")
    code, out, err = run(
        capsys, "valve", "cam-check", cam, "--valve-train", train, "--spring", pack, "--cam-rpm", "3000", "--json"
    )
    assert code == 0, err
    spring_mass = sum(
        7850 * (math.pi * d**2 / 4) * math.pi * dm * (n - 0.7)
        for d, dm, n in ((3.8e-3, 24e-3, 7), (2.6e-3, 15.5e-3, 9))
    )
    from springdyn.valve import ValveTrain

    moving = ValveTrain.from_toml(train).moving_mass + spring_mass / 3
    assert json.loads(out)["moving_mass_kg"] == pytest.approx(moving, rel=1e-9)
    shaft = (EXAMPLES / "valve" / "camshaft_4lobe.toml").read_text()
    shaft = re.sub(r'= "(\w+\.toml)"', lambda m: f'= "{EXAMPLES / "valve" / m.group(1)}"', shaft)
    f = tmp_path / "camshaft.toml"
    f.write_text(shaft.replace(str(EXAMPLES / "valve" / "one_step_spring.toml"), pack, 1))
    code, out, err = run(capsys, "valve", "camshaft", str(f), "--cam-rpm", "3000")
    assert code == 2 and len(err.strip().splitlines()) == 1 and "[inner_spring] makes this file a spring pack" in err
