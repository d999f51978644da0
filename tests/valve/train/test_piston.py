"""The valve-to-piston clearance (``springdyn.valve.train.piston``, issue 41 item 3).

References checked:

- the crank-slider against a hand calculation at three crank angles (zero pin offset: the
  numbers below worked by hand from the triangle crank-rod-cylinder axis) and, with a pin
  offset, against the loop closure solved numerically here (the wrist pin found on the
  cylinder's line at rod length from the crank pin by bisection, the TDC by maximising that
  height): neither uses the closed form under test;
- the seated clearance at TDC against ``(gap + pocket) / cos(valve angle)`` worked by hand;
- the static clearance of the bucket example against the cam's lift placed on the crank by
  hand (``theta = theta_peak + (phi + lobe centre) / 2``, the exhaust lobe centred before TDC);
- the dynamic clearance above the float speed against one simulation of the same speed, its
  valve lift placed on the crank by hand.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

import springdyn.valve as valve
from springdyn.app.cli.main import main
from springdyn.core.errors import InputError
from springdyn.valve.cam.timing import crank_axis
from springdyn.valve.design import criteria
from springdyn.valve.train import piston as pis
from tests.paths import example

SPRING = example("valve/one_step_spring.toml")
ENGINE = example("valve/bucket_piston.toml")


# --------------------------------------------------------------------------- the crank-slider
def test_crank_slider_against_a_hand_calculation_at_three_crank_angles():
    """r = 40 mm, l = 140 mm, no offset, by hand: at 60 deg the pin stands
    20 + sqrt(140^2 - (40 sin 60)^2) = 20 + sqrt(18400) = 155.646600 mm above the crank axis, 180 mm at
    TDC: 24.353400 mm down; at 90 deg 180 - sqrt(140^2 - 40^2) = 180 - sqrt(18000) = 45.835921 mm;
    at 180 deg the stroke, 80 mm.  Tolerance 1e-9 m: the hand figures' six decimals in mm."""
    drop = pis.piston_drop(np.radians([60.0, 90.0, 180.0]), 0.080, 0.140, 0.0)
    np.testing.assert_allclose(drop, [24.353400e-3, 45.835921e-3, 80.0e-3], atol=1e-9)
    # symmetric about TDC without an offset
    np.testing.assert_allclose(pis.piston_drop(np.radians([-60.0, -90.0]), 0.080, 0.140), drop[:2], atol=1e-15)


def _loop_closure_height(theta, r, l, e):
    """The wrist pin's height [m] above the crank axis at the crank angle theta from the cylinder
    axis: the point on the line x = e at distance l from the crank pin (r sin, r cos), found by
    bisection (not the closed form)."""
    px, py = r * math.sin(theta), r * math.cos(theta)
    return brentq(lambda y: math.hypot(e - px, y - py) - l, py, py + l, xtol=1e-15, rtol=1e-15)


def test_offset_crank_slider_against_the_loop_closure_at_three_crank_angles():
    """86 mm stroke, 143.5 mm rod, 2 mm pin offset: the drop at 20 deg BTDC, 30 and 100 deg ATDC
    against the loop closure with its TDC found by maximising the pin's height.  Tolerance
    1e-8 m: the maximiser finds the flat top to about 1e-7 rad, times the crank radius."""
    r, l, e = 0.043, 0.1435, 0.002
    tdc = minimize_scalar(
        lambda t: -_loop_closure_height(t, r, l, e), bounds=(-0.2, 0.2), method="bounded", options={"xatol": 1e-12}
    ).x
    assert pis.tdc_crank_angle(r, l, e) == pytest.approx(tdc, abs=1e-6)
    top = _loop_closure_height(tdc, r, l, e)
    for phi_deg in (-20.0, 30.0, 100.0):
        expected = top - _loop_closure_height(tdc + math.radians(phi_deg), r, l, e)
        assert float(pis.piston_drop(math.radians(phi_deg), 2 * r, l, e)) == pytest.approx(expected, abs=1e-8)
    # the offset makes the stroke longer than twice the crank radius (the dead centres are not 180 deg apart)
    bdc = max(np.max(pis.piston_drop(np.radians(np.linspace(170, 190, 20001)), 2 * r, l, e)), 0.0)
    assert bdc > 2 * r


# --------------------------------------------------------------------------- the [piston] table
def _example_piston():
    return valve.Piston.in_file(ENGINE)


def test_seated_clearance_at_tdc_by_hand():
    """(0.5 mm gap + 1.0 mm pocket) / cos 21 deg = 1.5 / 0.9335804 = 1.6067175 mm at TDC."""
    p = _example_piston()
    assert float(p.seated_at([0.0])[0]) == pytest.approx(1.6067175e-3, abs=1e-10)
    # a head wider than its pocket: the pocket is not counted, and the result says so
    wide = p.replace(valve_head_diameter=30e-3)
    assert float(wide.seated_at([0.0])[0]) == pytest.approx(0.5e-3 / math.cos(math.radians(21.0)), abs=1e-12)
    assert "does not fit the pocket" in wide.notes()[0]


@pytest.mark.parametrize(
    "keys, words",
    [
        (dict(bore="86 mm", stroke="86 mm", rod_length="143.5 mm"), "needs tdc_clearance"),
        (dict(bore="86 mm", stroke="86 mm", rod_length="40 mm", tdc_clearance="1 mm"), "cannot reach the pin"),
        (dict(bore="86 mm", stroke="86 mm", rod_length="143.5 mm", tdc_clearance="1 mm", pocket_depth="1 mm"), "needs"),
        (dict(bore="86 mm", stroke="86 mm", rod_length="143.5 mm", tdc_clearance="-1 mm"), "touch the piston at TDC"),
        (dict(bore="86 mm", stroke="86 mm", rod_length="143.5 mm", tdc_clearance="1 mm", valve_angle="70 deg"), "60"),
        (dict(bore="86 mm", clearance_table="x.csv"), "cannot be given beside it"),
    ],
)
def test_bad_piston_tables_are_refused_naming_the_key(keys, words):
    with pytest.raises(InputError, match=words):
        valve.Piston.from_dict(keys)


def test_a_measured_table_gives_the_seated_clearance_within_its_crank_angles(tmp_path):
    """The checking-spring readings interpolated linearly; outside them nothing is judged."""
    csv = tmp_path / "tc.csv"
    csv.write_text("crank_angle_deg,clearance_mm\n-30,6.0\n-10,2.5\n0,2.0\n10,2.4\n30,5.5\n")
    p = valve.Piston.from_dict({"clearance_table": str(csv), "valve_angle": "20 deg"})
    np.testing.assert_allclose(p.seated_at([-20.0, 5.0]), [4.25e-3, 2.2e-3], rtol=1e-12)
    assert np.isnan(p.seated_at([40.0])[0])
    axis = valve.Timing.from_dict({"lobe_centre": "100 deg", "valve": "intake"})
    cam = valve.Cam.from_dict({"law": "3-4-5", "lift": "9 mm", "duration": "120 deg"})
    theta = np.radians(np.arange(0.0, 360.0, 0.5))
    lift = cam.lift_at(theta)
    res = pis.clearance_map(p, crank_axis(cam, axis), theta, lift[None, :], lift, [3000.0], valve="intake")
    assert res.crank_angle_deg.min() >= -30.0 and res.crank_angle_deg.max() <= 30.0
    np.testing.assert_allclose(res.clearance[0], res.static_clearance)


# --------------------------------------------------------------------------- static and dynamic, on the example
@pytest.fixture(scope="module")
def clearance():
    """The bucket example below (2500) and above (4000 cam rpm) its float speed."""
    model = valve.ValveModel.from_files(SPRING, ENGINE, ENGINE)
    return model, model.valve_clearance([2500.0, 4000.0])


def _crank_of_cam(cam, cam_deg):
    """The crank angle [deg from the gas-exchange TDC] of cam angles, by hand: the exhaust lobe's
    peak 106 crank deg before TDC, two crank degrees per cam degree, wrapped into +-360."""
    phi = -106.0 + 2.0 * (np.asarray(cam_deg) - math.degrees(cam.peak_angle))
    return np.mod(phi + 360.0, 720.0) - 360.0


def test_static_clearance_of_the_example_by_hand(clearance):
    """At 10 deg BTDC: the seated clearance less the cam's lift minus the lash, the cam angle of
    that crank angle placed by hand."""
    model, res = clearance
    cam = model.cam
    k = int(np.argmin(np.abs(res.crank_angle_deg + 10.0)))
    phi = res.crank_angle_deg[k]
    cam_deg = math.degrees(cam.peak_angle) + (phi + 106.0) / 2.0
    lift = max(float(cam.lift_at(math.radians(cam_deg))) - 0.15e-3, 0.0)
    seated = (0.5e-3 + 1.0e-3 + float(pis.piston_drop(math.radians(phi), 0.086, 0.1435, 0.0005))) / math.cos(
        math.radians(21.0)
    )
    assert res.static_clearance[k] == pytest.approx(seated - lift, abs=1e-12)
    s = res.summary
    assert s["static_min_clearance_m"] == pytest.approx(float(np.min(res.static_clearance)))
    assert -10.0 <= s["static_min_clearance_crank_angle_deg"] <= 10.0  # near the overlap TDC


def test_dynamic_clearance_with_float_against_a_simulation(clearance):
    """Below the float speed the valve follows the cam (within 20 um of the static clearance: the
    train's deflection); above it the late-closing exhaust valve meets the rising piston before
    TDC.  The minimum at 4000 cam rpm agrees with one simulation's valve lift placed on the crank
    by hand, within 5 um (the sweep and the simulation settle separately, to 0.2 % of Fset)."""
    model, res = clearance
    lows, where = res.min_by_speed
    assert lows[0] == pytest.approx(float(np.min(res.static_clearance)), abs=20e-6)
    assert lows[1] < 0.0 < lows[0] and -30.0 < where[1] < 0.0
    sim = model.simulate(4000.0)
    phi = _crank_of_cam(model.cam, np.degrees(sim.cam_angle))
    seated = model.piston.seated_at(phi)
    assert float(np.min(seated - sim.valve_lift)) == pytest.approx(lows[1], abs=5e-6)
    s = res.summary
    assert s["valve_meets_piston"] and s["clearance_ok"] is False
    assert s["min_clearance_cam_rpm"] == 4000.0
    assert "VALVE MEETS PISTON" in res.describe()


def test_the_criterion_judges_the_smallest_clearance(clearance):
    _, res = clearance
    v = criteria.clearance_verdict(criteria.Criteria(), res)
    assert v.passed is False and "min_valve_piston_clearance" in v.limit
    loose = criteria.Criteria(min_valve_piston_clearance=1e-6)
    below = dataclasses.replace(res, valve_lift=res.valve_lift[:1], cam_rpm=res.cam_rpm[:1])
    assert criteria.clearance_verdict(loose, below).passed is True
    assert criteria.Criteria.from_dict({"min_valve_piston_clearance": "1.5 mm"}).min_valve_piston_clearance == 1.5e-3


# --------------------------------------------------------------------------- the command
def test_cli_clearance_json_and_without_a_piston(capsys, tmp_path):
    code = main(
        ["valve", "clearance", SPRING, "--cam", ENGINE, "--valve-train", ENGINE, "--cam-rpm", "2500", "--json"]
        + ["--csv", str(tmp_path / "c.csv")]
    )
    out = capsys.readouterr().out
    data = json.loads(out[out.index("{") :])
    assert code == 0 and data["valve"] == "exhaust" and data["clearance_ok"] is True
    assert data["min_clearance_m"] == pytest.approx(1.49e-3, abs=0.02e-3)
    assert "clearance_at_2500_cam_rpm_m" in (tmp_path / "c.csv").read_text().splitlines()[0]
    code = main(
        ["valve", "clearance", SPRING, "--cam", example("valve/cam_timing.toml")]
        + ["--valve-train", example("valve/valve_train.toml"), "--cam-rpm", "2500"]
    )
    assert code == 2 and "[piston]" in capsys.readouterr().err
    piston = str(tmp_path / "piston.toml")
    (tmp_path / "piston.toml").write_text(open(ENGINE).read().split("[piston]", 1)[0].split("[valve_train]")[0])
    code = main(
        ["valve", "clearance", SPRING, "--cam", example("valve/cam_timing.toml"), "--piston", piston]
        + ["--valve-train", example("valve/valve_train.toml"), "--cam-rpm", "2500"]
    )
    assert code == 2 and "no [piston] table" in capsys.readouterr().err
    code = main(
        ["valve", "clearance", SPRING, "--cam", example("valve/cam_timing.toml"), "--piston", ENGINE]
        + ["--valve-train", example("valve/valve_train.toml"), "--cam-rpm", "2500", "--limit", "2mm"]
    )
    out = capsys.readouterr().out
    assert code == 0 and "intake valve" in out and "limit >= 2 mm: FAIL" in out  # the intake's static 1.5 mm
