"""A spring pack across its tolerances (springdyn.valve.design.tolerances, issue 41 Deliver 1).

References, written here independently of the code they check:

- the nominal pack's own results: its springs' installed forces and first modes
  (``SpringPack.setup_forces``, ``SpringPack.modes``), its static forces at full valve lift
  (the cam's 9 mm less the bucket train's 0.15 mm lash, ratio 1: by hand), its sweep at the
  study's one speed (``ValveModel.sweep``): the largest retainer force, the Goodman safety and the
  clash severity of that run;
- one spring toleranced alone: the single spring's study of that spring with the same bands,
  seed and count draws the same values (one Sobol dimension each, in the same order), so its
  figures are the pack's figures of that spring variant by variant; the other spring stays nominal;
- a varied static force by hand from the drawing: the rate ``k = G d^4 / (8 D^3 n)``
  (EN 13906-1, ``n`` the active coils, the total less a dead coil at each end) times the
  compression ``Lf - Ls`` (at full lift ``Lf - Ls + h``, where the Type C law may have begun to
  stiffen towards coil contact: the tolerance says by how much).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve import ValveModel
from springdyn.valve.design.tolerances import (
    definition_fingerprint,
    nominal_values,
    pack_figures,
    parse_tolerance,
    read_tolerances,
    run_variant,
    tolerances_for,
    variant,
)
from springdyn.valve.spring.pack import SpringPack
from tests.paths import example

PACK = example("valve/dual_spring_damper.toml")
CAM = example("valve/cam_polydyne_ramps.toml")
TRAIN = example("valve/valve_train.toml")
#: One speed of the bucket train, below the pack's float speed (about 3970 cam rpm): a study of one
#: speed runs each variant once (no refinement between speeds), so its figures are that run's.
SPEEDS = [3000.0]


@pytest.fixture(scope="module")
def model():
    return ValveModel.from_files(PACK, CAM, TRAIN)


def _tols(**kw):
    return {k.replace("__", "."): parse_tolerance(k.replace("__", "."), v) for k, v in kw.items()}


def test_a_packs_tolerances_name_each_springs_own(model):
    """The example file: a bare drawing key is every spring's (drawn independently), a key under
    a spring's table that spring's, the bare installed length the head's (one value), the
    damper's force; what cannot be meant is refused naming the key."""
    tols, _ = read_tolerances(example("valve/tolerances_pack.toml"))
    assert "inner_spring.installed_length" in tols and "damper.friction_force" in tols
    names = list(tolerances_for(model.spring, tols))
    for key in ("wire_diameter", "free_length", "shear_modulus"):
        assert f"spring.{key}" in names and f"inner_spring.{key}" in names and key not in names
    assert "installed_length" in names and "spring.installed_length" not in names
    nominal = nominal_values(model.spring, model.cam, model.valve_train)
    assert nominal["installed_length"] == pytest.approx(0.043, rel=1e-14)  # the outer's (its unit conversion)
    assert nominal["inner_spring.installed_length"] == pytest.approx(0.041, rel=1e-14)
    assert nominal["damper.friction_force"] == pytest.approx(60.0 * 0.15)
    bad = (
        (_tols(wire_diameter="+-0.01 mm", inner_spring__wire_diameter="+-0.02 mm"), "both vary inner_spring"),
        (_tols(third_spring__free_length="+-0.1 mm"), "no \\[third_spring\\]"),
        (_tols(inner_spring__outer_diameter="+-0.1 mm", mean_diameter="+-0.1 mm"), "both vary the coil diameter"),
    )
    for tols, match in bad:
        with pytest.raises(InputError, match=match):
            tolerances_for(model.spring, tols)
    with pytest.raises(InputError, match="names a spring of a pack"):
        tolerances_for(model.spring.outer, _tols(inner_spring__free_length="+-0.1 mm"))
    with pytest.raises(InputError, match="not a toleranced parameter"):
        parse_tolerance("inner_spring.lift", "+-0.01 mm")
    with pytest.raises(InputError, match="no \\[damper\\]"):
        tolerances_for(SpringPack(model.spring.springs), _tols(damper__friction_force="+-1 N"))
    # chunks on disk belong to the pack's every digit, not to its rounded repr
    other = model.spring.with_field("inner_spring.wire_diameter", 2.6e-3 + 1e-12)
    assert repr(other) == repr(model.spring)
    assert definition_fingerprint(other) != definition_fingerprint(model.spring)


def test_the_nominal_variant_is_the_nominal_pack(model):
    """The study's nominal is the pack's own: its springs' installed forces and modes, static
    forces at full lift by hand, fit, and its sweep; a variant drawn at the nominal values is the
    pack itself and gives the nominal's outputs to the bit."""
    pack, cam, vt = model.spring, model.cam, model.valve_train
    tols = _tols(inner_spring__free_length="+-0.2 mm", wire_diameter="+-0.01 mm", damper__friction_force="+-20 %")
    study = model.tolerance_study(tols, count=2, seed=3, speeds=SPEEDS)
    nom = study.nominal
    assert [nom["outer_Fset"], nom["inner_Fset"]] == pack.setup_forces
    assert nom["Fset"] == pytest.approx(sum(pack.setup_forces), rel=1e-14)
    modes = pack.modes(0.0)
    assert nom["outer_f1"] == pytest.approx(modes["outer"][0], rel=1e-9)
    assert nom["inner_f1"] == pytest.approx(modes["inner"][0], rel=1e-9)
    assert nom["f1"] == pytest.approx(modes["pack"][0], rel=1e-9)
    lift = 9e-3 - 0.15e-3  # the cam's lift less the lash, ratio 1 (by hand)
    open_forces = pack.static_forces(lift)
    assert [nom["outer_open_force"], nom["inner_open_force"]] == pytest.approx(list(open_forces), rel=1e-6)
    fit = pack.fit["outer_inner"]
    assert nom["outer_inner_radial_clearance"] == min(
        fit["radial_clearance_installed_m"], fit["radial_clearance_at_bind_m"]
    )
    table = model.sweep(SPEEDS).summary_table()
    assert nom["max_retainer_force"] == float(table["max_retainer_force_N"][0])
    assert nom["goodman_safety"] == float(table["fatigue_safety_factor"][0])
    assert nom["max_clash_severity"] == float(table["clash_severity"][0])
    assert nom["float_in_range"] == 0.0  # the pack floats from about 3970 cam rpm
    # a variant at the nominal values is the nominal pack
    at_nominal = {k: v for k, v in nominal_values(pack, cam, vt).items() if k in tolerances_for(pack, tols)}
    again, c, t = variant(pack, cam, vt, at_nominal)
    assert again.springs == pack.springs and again.damper.force == pytest.approx(pack.damper.force, rel=1e-15)
    assert run_variant(again, c, t, SPEEDS) == nom
    assert set(study.pack_outputs) <= set(study.dataset) and study.dataset["inner_Fset"].attrs["units"] == "N"
    assert "inner_static_goodman_safety" in study.describe()


def test_one_springs_tolerances_alone_are_that_spring_varied_alone(model):
    """The inner spring toleranced alone (the outer's tolerances zero): variant by variant, the
    pack study's inner-spring figures are the single-spring study's of the inner spring with the
    same bands, seed and count; the outer's stay at the nominal."""
    pack = model.spring
    bands = dict(free_length="+-0.3 mm", wire_diameter="+-0.015 mm", shear_modulus="+-1 %")
    in_pack = model.tolerance_study(
        _tols(**{f"inner_spring__{k}": v for k, v in bands.items()}), count=2, seed=11, speeds=SPEEDS
    )
    alone = ValveModel(pack.springs[1], model.cam, model.valve_train).tolerance_study(
        _tols(**bands), count=2, seed=11, speeds=SPEEDS
    )
    p, a = in_pack.dataset, alone.dataset
    for key in bands:
        np.testing.assert_array_equal(p[f"inner_spring.{key}"].values, a[key].values)
    np.testing.assert_array_equal(p["inner_Fset"].values, a["Fset"].values)
    np.testing.assert_array_equal(p["inner_f1"].values, a["f1"].values)
    assert np.all(p["outer_Fset"].values == pack.setup_forces[0])
    np.testing.assert_allclose(p["Fset"].values, pack.setup_forces[0] + a["Fset"].values, rtol=1e-14)
    assert np.ptp(p["inner_Fset"].values) > 0.0


def test_a_varied_static_force_by_hand(model):
    """One variant's forces from its drawing by hand: the outer's wire 3.81 mm, the inner's
    free length 48.2 mm, the head 0.1 mm longer (both installed lengths), the cam's lift 9.03 mm."""
    pack, cam, vt = model.spring, model.cam, model.valve_train
    values = {
        "spring.wire_diameter": 3.81e-3,
        "inner_spring.free_length": 48.2e-3,
        "installed_length": 43.1e-3,
        "lift": 9.03e-3,
    }
    sp, c, t = variant(pack, cam, vt, values)
    fig = pack_figures(sp, c, t)
    g, h = 78.5e9, 9.03e-3 - 0.15e-3

    def rate(d, dm, total):
        return g * d**4 / (8.0 * dm**3 * (total - 2.0))

    k_o, k_i = rate(3.81e-3, 24e-3, 7.0), rate(2.6e-3, 15.5e-3, 9.0)
    assert fig["outer_Fset"] == pytest.approx(k_o * (53e-3 - 43.1e-3), rel=1e-9)
    assert fig["inner_Fset"] == pytest.approx(k_i * (48.2e-3 - 41.1e-3), rel=1e-9)
    # at full lift the Type C element law has begun to stiffen towards coil contact (past its first
    # knee, MMS Type C): the thicker wire's outer spring 2.6e-5 above the linear rate, the inner linear
    assert fig["outer_open_force"] == pytest.approx(k_o * (53e-3 - 43.1e-3 + h), rel=1e-4)
    assert fig["inner_open_force"] == pytest.approx(k_i * (48.2e-3 - 41.1e-3 + h), rel=1e-9)
    assert math.isclose(sp.springs[1].installed_length, 41.1e-3, rel_tol=1e-12)


def test_cli_tolerance_of_a_pack(capsys, tmp_path):
    from springdyn.app.cli.main import main

    args = ["valve", "tolerance", PACK, "--cam", CAM, "--valve-train", TRAIN]
    args += ["--tolerances", example("valve/tolerances_pack.toml"), "--samples", "2", "--cam-rpm", "3000"]
    assert main([*args, "--out", str(tmp_path / "o"), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["nominal_inner_Fset"] == pytest.approx(120.4, abs=0.05) and "inner_static_goodman_safety_p50" in s
    tol = tmp_path / "tol.toml"
    tol.write_text('[tolerances]\ninner_spring.wire_diameter = "+-0.01 mm"\n')
    single = ["valve", "tolerance", example("valve/one_step_spring.toml"), "--cam", CAM, "--tolerances", str(tol)]
    assert main([*single, "--samples", "2", "--cam-rpm", "2500", "--out", str(tmp_path / "p")]) == 2
    assert "names a spring of a pack" in capsys.readouterr().err
