"""``springdyn cfcs ...`` through springdyn.app.cli.main.main (exit codes, stderr, files)."""

import json

import numpy as np
import pytest

from springdyn.app.cli.main import main
from springdyn.core.io import read_csv_columns, write_csv

#: The repository (the example files), wherever pytest runs from.
from tests.paths import ROOT, example


def run(capsys, *argv):
    code = main(list(argv))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_static_json_and_files(capsys, tmp_path):
    code, out, err = run(
        capsys,
        "cfcs",
        "static",
        "table1",
        "--stroke",
        "72mm",
        "--json",
        "--csv",
        str(tmp_path / "s.csv"),
        "--plot",
        str(tmp_path / "s.png"),
    )
    assert code == 0, err
    s = json.loads(out)
    for key in (
        "force_at_zero_N",
        "force_max_N",
        "deflection_at_force_max_m",
        "force_min_N",
        "pcf_percent",
        "stroke_m",
        "max_stress_Pa",
        "toggle_cutoff_rad",
    ):
        assert key in s
    # reading notes 2.3 with K3 from the flexure (2.53075 vs 2.5308: 2e-5 relative)
    assert s["force_max_N"] == pytest.approx(12.970, abs=1e-3)
    assert s["pcf_percent"] == pytest.approx(97.0, abs=0.05)
    cols = read_csv_columns(tmp_path / "s.csv")
    assert list(cols)[:3] == ["deflection_m", "theta2_rad", "force_N"]
    assert (tmp_path / "s.png").stat().st_size > 0


def test_static_table(capsys):
    code, out, _ = run(capsys, "cfcs", "static", "table1")
    assert code == 0
    assert "12.97 N" in out and "toggle cut-off" in out and "5 deg" in out


def test_a_safety_factor_below_one_says_the_pivot_yields(capsys):
    """Issue 40: a pivot safety factor of 0.42 was printed without the word that the mechanism
    yields (Table 1's spring over 72 mm: 3.54 GPa against its allowable)."""
    code, out, _ = run(capsys, "cfcs", "static", "table1", "--stroke", "72mm")
    line = next(x for x in out.splitlines() if x.startswith("safety factor"))
    assert code == 0 and "0.424" in line and "YIELDS" in line
    code, out, _ = run(capsys, "cfcs", "static", "table1", "--stroke", "10mm")
    line = next(x for x in out.splitlines() if x.startswith("safety factor"))
    assert code == 0 and "YIELDS" not in line


def test_dynamic(capsys, tmp_path):
    code, out, err = run(
        capsys,
        "cfcs",
        "dynamic",
        str(ROOT / example("cfcs/table1.toml")),
        "--omega",
        "14.7",
        "--amplitude",
        "0.4",
        "--cycles",
        "2",
        "--json",
        "--csv",
        str(tmp_path / "d.csv"),
    )
    assert code == 0, err
    s = json.loads(out)
    for key in ("mean_force_N", "median_force_N", "peak_to_peak_N", "pcf_percent", "toggle_cutoff_rad"):
        assert key in s
    cols = read_csv_columns(tmp_path / "d.csv")
    assert list(cols)[:4] == ["time_s", "deflection_m", "force_N", "force_static_N"]
    assert cols["time_s"].size == 801
    assert cols["deflection_m"].max() == pytest.approx(0.0045 + 0.072)  # default preload 2.5 % of r2 + r3


def test_dynamic_from_csv_motion(capsys, tmp_path):
    t = np.linspace(0, 1, 101)
    write_csv(tmp_path / "x.csv", {"time_s": t, "deflection_m": 0.01 + 0.02 * np.sin(np.pi * t) ** 2})
    code, out, err = run(capsys, "cfcs", "dynamic", "table1", "--motion", str(tmp_path / "x.csv"), "--json")
    assert code == 0, err
    assert json.loads(out)["omega_rad_per_s"] == pytest.approx(2 * np.pi)


def test_sweep(capsys, tmp_path):
    code, out, err = run(
        capsys,
        "cfcs",
        "sweep",
        "table1",
        "--omega",
        "1:50:7",
        "--csv",
        str(tmp_path / "w.csv"),
        "--plot",
        str(tmp_path / "w.png"),
    )
    assert code == 0, err
    cols = read_csv_columns(tmp_path / "w.csv")
    np.testing.assert_allclose(cols["omega_rad_per_s"], [1, 8, 15, 22, 29, 36, 43, 50])
    assert "toggle cut-off" in out


def test_design_infeasible_and_feasible(capsys, tmp_path):
    code, out, _ = run(
        capsys,
        "cfcs",
        "design",
        "--force",
        "12.8N",
        "--stroke",
        "40mm",
        "--material-modulus",
        "207GPa",
        "--allowable-stress",
        "1.5GPa",
    )
    assert code == 1
    assert "NO FEASIBLE DESIGN: no design meets the stress limit" in out
    code, out, _ = run(
        capsys,
        "cfcs",
        "design",
        "--force",
        "12.8N",
        "--stroke",
        "40mm",
        "--material-modulus",
        "207GPa",
        "--allowable-stress",
        "1.5GPa",
        "--length",
        "300mm",
        "--json",
        "--toml",
        str(tmp_path / "d.toml"),
    )
    assert code == 0
    assert json.loads(out)["feasible"] is True
    code, out, err = run(capsys, "cfcs", "static", str(tmp_path / "d.toml"), "--stroke", "40mm", "--json")
    assert code == 0, err
    s = json.loads(out)
    # the TOML keeps the design's bending model; 6 digits are written, hence 1e-4
    assert s["flexure_model"] == "beam"
    assert s["safety_factor"] == pytest.approx(1.5, rel=1e-4)


def test_design_stroke_fraction_message(capsys):
    code, out, err = run(
        capsys,
        "cfcs",
        "design",
        "--force",
        "12.8N",
        "--stroke",
        "40mm",
        "--material-modulus",
        "207GPa",
        "--allowable-stress",
        "1.5GPa",
        "--stroke-fraction",
        "0.95",
    )
    assert code == 2 and "--stroke-fraction = 0.95 must not exceed 0.9" in err and "Traceback" not in err


def test_forward(capsys, tmp_path):
    code, out, err = run(
        capsys,
        "cfcs",
        "forward",
        "table1",
        "--t-end",
        "0.3s",
        "--base-stiffness",
        "2000N/m",
        "--base-omega",
        "10",
        "--base-amplitude",
        "0.2",
        "--csv",
        str(tmp_path / "f.csv"),
    )
    assert code == 0, err
    assert read_csv_columns(tmp_path / "f.csv")["time_s"].size == 2001


@pytest.mark.parametrize(
    "argv, match",
    [
        (["cfcs", "static", "nope.toml"], "nope.toml: no such file"),
        (["cfcs", "static", "table1", "--stroke", "150mm"], "beyond the kinematic limit"),
        (["cfcs", "static", "table1", "--stroke", "7kg"], "wrong dimension"),
        (["cfcs", "dynamic", "table1", "--omega", "0"], "omega = 0 rad/s must be positive"),
        (["cfcs", "dynamic", "table1", "--omega", "-2"], "must be positive"),
        (["cfcs", "dynamic", "table1", "--omega", "5", "--amplitude", "0.9"], "kinematic limit"),
        (["cfcs", "dynamic", "table1", "--omega", "5", "--offset=-1mm"], "crosses the toggle"),
        (["cfcs", "dynamic", "table1"], "omega is required"),
        (["cfcs", "sweep", "table1", "--omega", "0:5:1"], "every omega must be positive"),
        (
            [
                "cfcs",
                "design",
                "--force=-1N",
                "--stroke",
                "40mm",
                "--material-modulus",
                "207GPa",
                "--allowable-stress",
                "1.5GPa",
            ],
            "force",
        ),
        (["cfcs", "forward", "table1", "--t-end", "1s"], "forward needs --force"),
        # issue 40, item 7: a zero was read as "not given" and the default (6 periods, 2000 or 400 samples) ran
        (
            ["cfcs", "dynamic", "table1", "--omega", "10", "--drive-stiffness", "20kN/m", "--periods", "0"],
            "--periods = 0",
        ),
        (
            ["cfcs", "dynamic", "table1", "--omega", "10", "--drive-stiffness", "20kN/m", "--samples", "0"],
            "--samples = 0",
        ),
        (["cfcs", "dynamic", "table1", "--omega", "10", "--samples", "0"], "--samples = 0"),
    ],
)
def test_bad_input_exit_2(capsys, argv, match):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert match in err
    assert "Traceback" not in err and err.count("\n") == 1


def test_bad_config_files(capsys, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(
        '[cfcs]\ncrank_length = "95 mm"\ncoupler_length = "85 mm"\ncrank_mass = 0.02\n'
        "coupler_mass = 0.02\nslider_mass = 0.05\ntorsional_stiffness = 2.5\n"
    )
    code, _, err = run(capsys, "cfcs", "static", str(bad))
    assert code == 2 and "must be shorter than coupler_length" in err
    bad.write_text(
        '[cfcs]\ncrank_length = "85 mm"\ncoupler_length = "95 mm"\ncrank_mass = 0.02\n'
        'coupler_mass = 0.02\nslider_mass = 0.05\ntorsional_stiffness = 2.5\npivot_width = "25 mm"\n'
        'friction_model = "stribeck"\n'
    )
    code, _, err = run(capsys, "cfcs", "static", str(bad))
    assert code == 2 and "friction_model = 'stribeck' is not allowed" in err
    bad.write_text(
        '[cfcs]\ncrank_length = "85 mm"\ncoupler_length = "95 mm"\ncrank_mass = 0.02\n'
        'coupler_mass = 0.02\nslider_mass = 0.05\ntorsional_stiffness = 2.5\npivot_width = "25 mm"\n'
    )
    code, _, err = run(capsys, "cfcs", "static", str(bad))
    assert code == 2 and "both torsional_stiffness and pivot dimensions" in err
    out_csv = tmp_path / "never.csv"
    code, _, _ = run(capsys, "cfcs", "static", str(bad), "--csv", str(out_csv))
    assert code == 2 and not out_csv.exists()  # nothing half-written on bad input


def test_cli_default_amplitude_is_the_library_default():
    """The parser keeps its own copy (so that --help does not load the model): they must agree."""
    from springdyn.app.cli import cfcs as cli
    from springdyn.cfcs.model import DEFAULT_AMPLITUDE

    assert cli.DEFAULT_AMPLITUDE == DEFAULT_AMPLITUDE


def test_cli_default_offset_is_the_library_default():
    from springdyn.app.cli import cfcs as cli
    from springdyn.cfcs.model import DEFAULT_OFFSET

    assert cli.DEFAULT_OFFSET == DEFAULT_OFFSET


def test_toggle_flag_in_the_table(capsys):
    code, out, err = run(capsys, "cfcs", "dynamic", "table1", "--omega", "14.7", "--offset", "0")
    assert code == 0, err
    row = next(line for line in out.splitlines() if line.startswith("toggle-dominated"))
    assert row.split()[1] == "YES" and "peak_to_peak_N" in row
    code, out, err = run(capsys, "cfcs", "dynamic", "table1", "--omega", "14.7")
    assert code == 0, err
    row = next(line for line in out.splitlines() if line.startswith("toggle-dominated"))
    assert row.split()[1] == "no"


def test_forward_force_range_and_unloaded_safety(capsys):
    """Issue 27: -13 MN ran for minutes (now refused, naming the mechanism's force scale); an
    unloaded flexure has an unbounded safety factor, a result (null, with a note), not exit 3."""
    import json

    assert main(["cfcs", "forward", "table1", "--t-end", "0.05", "--force", "-13000000N"]) == 2
    assert "beyond reason for this mechanism" in capsys.readouterr().err
    assert main(["cfcs", "forward", "table1", "--t-end", "0.05", "--force", "0N", "--x0", "0mm", "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["summary"]["safety_factor"] is None if "summary" in s else s["safety_factor"] is None


def test_kinematic_limit_hints_name_the_commands_own_options(capsys):
    """Issue 27: the static and forward commands were told to 'reduce the amplitude or the
    offset', options they lack."""
    assert main(["cfcs", "static", "table1", "--stroke", "500mm"]) == 2
    assert "give a shorter stroke" in capsys.readouterr().err
    assert main(["cfcs", "forward", "table1", "--t-end", "0.1", "--force", "5N", "--x0", "500mm"]) == 2
    assert "start at a smaller deflection x0" in capsys.readouterr().err


def test_static_carries_the_beam_check(capsys, tmp_path):
    """Issue 30 part 1: a PRBM result shows its error against the elastica in text, JSON and CSV."""
    code, out, err = run(capsys, "cfcs", "static", "table1", "--stroke", "72mm")
    assert code == 0, err
    row = next(line for line in out.splitlines() if line.startswith("PRBM band error"))
    assert "+18.6 %" in row
    assert any(line.startswith("PRBM force error") for line in out.splitlines())
    code, out, err = run(
        capsys, "cfcs", "static", "table1", "--stroke", "72mm", "--json", "--csv", str(tmp_path / "s.csv")
    )
    s = json.loads(out)
    assert s["beam_band_error_percent"] == pytest.approx(18.63, abs=0.05)
    assert s["beam_force_error_percent"] == pytest.approx(0.965, abs=0.005)
    assert "force_beam_N" in read_csv_columns(tmp_path / "s.csv")


def test_dynamic_with_a_compliant_drive(capsys, tmp_path):
    """Issue 30 part 2: --drive-stiffness integrates through the toggle; no cut-off, a finite peak."""
    code, out, err = run(
        capsys,
        "cfcs",
        "dynamic",
        "table1",
        "--omega",
        "14.7",
        "--offset",
        "0",
        "--drive-stiffness",
        "20 kN/m",
        "--drive-damping",
        "5 N*s/m",
        "--periods",
        "3",
        "--samples",
        "500",
        "--json",
        "--csv",
        str(tmp_path / "d.csv"),
        "--plot",
        str(tmp_path / "d.png"),
    )
    assert code == 0, err
    s = json.loads(out)
    assert s["drive_stiffness_N_per_m"] == 2e4 and s["drive_damping_N_s_per_m"] == 5.0
    assert s["toggle_cutoff_rad"] is None and s["periods"] == 3 and s["samples_per_period"] == 500
    assert 300 < s["peak_to_peak_N"] < 450  # 367 N at the default settings (docs/cfcs.md)
    # the crank sticks within the shear angle: flagged, and the run without tau_AF is given beside it
    assert s["toggle_sticking"] is True and abs(s["toggle_stop_angle_rad"]) < 0.045
    assert s["peak_to_peak_without_axial_friction_N"] < 0.2 * s["peak_to_peak_N"]
    cols = read_csv_columns(tmp_path / "d.csv")
    assert {"drive_position_m", "force_N", "energy_residual_J"} <= set(cols)
    assert (tmp_path / "d.png").is_file()
    code, out, err = run(capsys, "cfcs", "dynamic", "table1", "--omega", "14.7", "--periods", "3")
    assert code == 2 and "--drive-stiffness" in err


def test_a_rigid_drive_finishes(capsys):
    """Issue 40, item 7: --drive-stiffness 1e15N/m ran without end; it is the rigid drive (stated bound)."""
    code, out, err = run(capsys, "cfcs", "dynamic", "table1", "--omega", "10", "--drive-stiffness", "1e15N/m")
    assert code == 0, err
    assert "RIGID (from 1.91e+06 N/m)" in out and "note: RIGID DRIVE" in out
    row = next(line for line in out.splitlines() if line.startswith("peak-to-peak force"))
    assert "5.5828 N" in row  # the inverse dynamics' 5.58 N (rigid drive, 10 rad/s)
    code, out, err = run(
        capsys, "cfcs", "dynamic", "table1", "--omega", "10", "--offset", "0", "--drive-stiffness", "1e15N/m"
    )
    assert code == 2 and "--drive-stiffness = 1e+15 N/m is a rigid drive" in err and err.count("\n") == 1


def test_driven_text_output_says_the_crank_sticks(capsys):
    """The text table names the sticking and the figure without tau_AF; a note says what sets the peak."""
    code, out, err = run(
        capsys,
        "cfcs",
        "dynamic",
        "table1",
        "--omega",
        "14.7",
        "--offset",
        "0",
        "--drive-stiffness",
        "20 kN/m",
        "--drive-damping",
        "5 N*s/m",
        "--periods",
        "3",
        "--samples",
        "500",
    )
    assert code == 0, err
    row = next(line for line in out.splitlines() if line.startswith("toggle sticking"))
    assert "YES" in row and "alpha" in row
    assert any(line.startswith("p-p without tau_AF") and " N" in line for line in out.splitlines())
    assert "TOGGLE STICKING" in out and "F_static inside the shear angle" in out
