"""The inner spring of a pack for an outer spring and a force split (issue 41, Deliver 1).

References, written here independently of the code they check: the spring rate
``k = G d^4 / (8 D^3 n)`` and the corrected shear stress ``tau = k_B 8 F D / (pi d^3)`` with
Bergstraesser's ``k_B = (w + 0.5) / (w - 0.75)``, ``w = D / d`` (EN 13906-1), and the
diameters: the inner's outside ``D_i + d_i`` is the outer's inside ``D_o - d_o`` less twice the
clearance.
"""

import math
from pathlib import Path

import pytest

from springdyn.core.errors import InputError
from springdyn.valve.design.pack_synthesis import inner_spring_for
from springdyn.valve.spring import ValveSpring
from tests.paths import example

#: The outer spring of the dual-spring example: 24 x 3.8 mm, 7 coils, Lf 53 mm, Ls 43 mm, G 78.5 GPa.
EXAMPLE = Path(__file__).parents[3] / "examples" / "valve" / "dual_spring_damper.toml"


def _tau(force, d_mean, d_wire):
    w = d_mean / d_wire
    return (w + 0.5) / (w - 0.75) * 8.0 * force * d_mean / (math.pi * d_wire**3)


def test_the_inner_spring_carries_its_share_at_the_outers_stress():
    outer = ValveSpring.outer_from_toml(EXAMPLE)
    share, lift, clearance = 0.33, 9e-3, 1e-3
    r = inner_spring_for(outer, share, lift, clearance, installed_length=0.041)
    inner = r["spring"]
    # the outer spring's forces (its model, linear-rate range) and the inner's share of the pack
    f_set_o = float(outer.spring_model.static_force(0.043))
    f_open_o = float(outer.spring_model.static_force(0.043 - lift))
    for f_o, f_i in ((f_set_o, r["set_force_N"]), (f_open_o, r["open_force_N"])):
        assert f_i / (f_i + f_o) == pytest.approx(share, rel=1e-6)  # the Type C chain is linear below Fcon
    # the rate by hand, from the inner's own wire, diameter and active coils
    d, dm, n = inner.wire_diameter, inner.mean_diameter, inner.active_coils
    k = 78.5e9 * d**4 / (8.0 * dm**3 * n)
    assert k * lift == pytest.approx(r["open_force_N"] - r["set_force_N"], rel=1e-9)
    # equal corrected stress at full lift, and the space inside the outer
    assert _tau(r["open_force_N"], dm, d) == pytest.approx(_tau(f_open_o, 0.024, 0.0038), rel=1e-6)
    assert dm + d == pytest.approx(0.024 - 0.0038 - 2 * clearance, rel=1e-12)
    assert r["pack"].options.inner_hand != r["pack"].options.outer_hand
    assert r["coil_bind_margin_m"] > 0.0


def test_an_impossible_split_is_refused():
    outer = ValveSpring.outer_from_toml(EXAMPLE)
    with pytest.raises(InputError, match="share"):
        inner_spring_for(outer, 0.9, 9e-3)


def _mm(text):
    """A length of the written file, ``"15.5094 mm"``, in metres."""
    value, unit = text.split()
    assert unit == "mm"
    return float(value) * 1e-3


def test_cli_synthesize_inner_writes_a_pack_with_the_split(capsys, tmp_path):
    """``valve synthesize-inner`` on the example's outer spring: the written pack file reloads as
    a pack the other commands take, and its inner spring carries the requested share of the
    force at installed length and at full lift, by hand from the written drawings: each spring's
    rate ``G d^4 / (8 D^3 n)`` (``n`` the total coils less a dead coil at each end) times its
    compression (the file's values are written to 6 digits: the share within 1e-4)."""
    import json
    import tomllib

    from springdyn.app.cli.main import main
    from springdyn.valve import ValveModel

    out = tmp_path / "pack.toml"
    args = ["valve", "synthesize-inner", str(EXAMPLE), "--share", "35 %", "--lift", "9mm", "--clearance", "1mm"]
    assert main([*args, "--installed-length", "41mm", "--out", str(out), "--json"]) == 0
    figures = json.loads(capsys.readouterr().out)
    doc = tomllib.loads(out.read_text())
    assert set(doc) == {"spring", "inner_spring", "pack", "damper"}  # the example's damper kept
    rates, lengths = [], []
    for table in (doc["spring"], doc["inner_spring"]):
        d, dm = _mm(table["wire_diameter"]), _mm(table["mean_diameter"])
        n = table["high_pitch_coils"] + table["low_pitch_coils"] - 2.0 * table["dead_coils"]
        rates.append(78.5e9 * d**4 / (8.0 * dm**3 * n))
        lengths.append((_mm(table["free_length"]), _mm(table["installed_length"])))
    for lift in (0.0, 9e-3):
        (k_o, k_i), ((lf_o, ls_o), (lf_i, ls_i)) = rates, lengths
        f_o, f_i = k_o * (lf_o - ls_o + lift), k_i * (lf_i - ls_i + lift)
        assert f_i / (f_o + f_i) == pytest.approx(0.35, abs=1e-4)
    assert _mm(doc["inner_spring"]["installed_length"]) == pytest.approx(0.041)
    assert _mm(doc["inner_spring"]["mean_diameter"]) + _mm(doc["inner_spring"]["wire_diameter"]) == pytest.approx(
        0.024 - 0.0038 - 2e-3, rel=1e-5
    )
    model = ValveModel.from_files(str(out), example("valve/cam_polydyne_ramps.toml"), example("valve/valve_train.toml"))
    assert model.spring.setup_forces == pytest.approx(
        [figures["outer_installed_force_N"], figures["inner_installed_force_N"]], rel=1e-4
    )
    assert (doc["pack"]["outer_hand"], doc["pack"]["inner_hand"]) == ("right", "left")
    assert figures["radial_clearance_installed_m"] == pytest.approx(1e-3, abs=0.1e-3)  # 1 mm, grown a little
    assert len(figures["pack_modes_Hz"]) == 5 and figures["inner_goodman_safety"] > 1.0
    assert main([*args, "--share", "90 %", "--out", str(tmp_path / "bad.toml")]) == 2
    assert "--share = 0.9 must be from 0.05 to 0.7" in capsys.readouterr().err
    assert not (tmp_path / "bad.toml").exists()
