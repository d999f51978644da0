"""Gas force on the valve head (springdyn.valve.train.gas_force) in the valve train's dynamics.

References: the force by hand, (p_cyl - p_port) pi d^2 / 4; a constant pressure as an extra
preload on the seat (statics); the phasing of a pressure peak through the [timing] table
(the four-stroke relation); the cam force at the valve's opening carrying the gas force.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from springdyn.app.cli.main import main
from springdyn.core.errors import InputError
from springdyn.valve import Cam, ValveSpring, ValveTrain, simulate
from springdyn.valve.cam.timing import Timing, crank_axis
from springdyn.valve.train.gas_force import GasForce, gas_force
from tests.paths import example

EXHAUST = example("valve/exhaust_valve.toml")
TRACE = example("valve/cylinder_pressure.csv")


def _exhaust():
    cam = Cam.from_toml(EXHAUST)
    return ValveSpring.example("one-step"), cam, ValveTrain.from_toml(EXHAUST), crank_axis(cam, Timing.in_file(EXHAUST))


def test_force_by_hand():
    """5 bar against 1.1 bar on a 27 mm seat: 3.9e5 Pa x pi 0.027^2 / 4 = 223.3 N."""
    assert gas_force(5e5, 1.1e5, 0.027) == pytest.approx(3.9e5 * math.pi * 0.027**2 / 4, rel=1e-12)


def test_a_constant_pressure_is_a_seat_preload():
    """A constant 3 bar (2 bar above the port) presses the closed valve onto its seat with
    exactly that force more: the base-circle seat force grows by F (statics; to the
    periodic run's residual ringing, 0.1 %)."""
    spring, cam, vt, axis = _exhaust()
    crank = np.arange(-360.0, 360.0, 1.0)
    g = GasForce.from_trace(crank, np.full(crank.size, 3e5), axis=axis, seat_diameter=0.027, port_pressure=1e5)
    f = 2e5 * math.pi * 0.027**2 / 4
    a = simulate(spring, cam, 1000.0, valve_train=vt, gas_force=g)
    b = simulate(spring, cam, 1000.0, valve_train=vt)
    base = slice(300 * 4, 340 * 4)  # cam 300-340 deg: the lobe on its base circle
    assert np.mean(a.valve_seat_force[base] - b.valve_seat_force[base]) == pytest.approx(f, rel=1e-3)
    assert a.summary["max_gas_force_N"] == pytest.approx(f, rel=1e-12)


def test_a_pressure_peak_lands_where_the_timing_puts_it():
    """An exhaust lobe centred 110 deg before the gas-exchange TDC: the firing TDC (crank
    -360 = +360) is 250 crank deg before the centreline, 125 cam deg before the maximum lift
    at 75 deg: cam angle -50 = 310 deg."""
    spring, cam, vt, axis = _exhaust()
    crank = np.arange(-360.0, 360.0, 0.5)
    p = 1e5 + 40e5 * np.exp(-(np.minimum(np.abs(crank + 360.0), np.abs(crank - 360.0)) ** 2) / 50.0)
    g = GasForce.from_trace(crank, p, axis=axis, seat_diameter=0.027)
    k = int(np.argmax(g.force))
    assert k * 360.0 / g.force.size == pytest.approx(math.degrees(cam.peak_angle) - 125.0 + 360.0, abs=0.1)


def test_the_cam_carries_the_gas_force_as_the_valve_opens():
    """The synthetic full-load cycle: the exhaust valve leaves its seat against ~4 bar; over
    the first 2-10 cam degrees of the opening the cam contact force exceeds the run without
    gas by the gas force on average (the same spring force and inertia; within 5 %: the
    lash impact rings differently; measured 1.2 %)."""
    spring, cam, vt, axis = _exhaust()
    g = GasForce.from_file(TRACE, axis=axis, seat_diameter=vt.seat_diameter, port_pressure=1.1e5)
    a = simulate(spring, cam, 1000.0, valve_train=vt, gas_force=g)
    b = simulate(spring, cam, 1000.0, valve_train=vt)
    i = int(np.argmax(a.valve_lift > 0.0))  # the valve leaves its seat
    w = slice(i + 8, i + 40)  # 2 to 10 cam degrees later (0.25 deg per sample)
    f_gas = float(np.mean(g.at(a.cam_angle[w])))
    assert f_gas > 100.0
    assert np.mean(a.cam_contact_force[w] - b.cam_contact_force[w]) == pytest.approx(f_gas, rel=0.05)


def test_gas_force_needs_its_inputs(capsys, tmp_path):
    spring, cam, vt, axis = _exhaust()
    crank = np.arange(-360.0, 360.0, 1.0)
    with pytest.raises(InputError, match=r"\[timing\] table"):
        GasForce.from_trace(crank, np.full(crank.size, 2e5), axis=crank_axis(cam), seat_diameter=0.027)
    with pytest.raises(InputError, match="engine cycle is needed"):
        GasForce.from_trace(crank[:300], np.full(300, 2e5), axis=axis, seat_diameter=0.027)
    no_seat = tmp_path / "vt.toml"
    no_seat.write_text(open(EXHAUST).read().replace('seat_diameter = "27 mm"', ""))
    argv = ["valve", "simulate", example("valve/one_step_spring.toml"), "--cam", EXHAUST, "--cam-rpm", "2000"]
    assert main([*argv, "--valve-train", str(no_seat), "--gas-pressure", TRACE]) == 2
    assert "needs the valve's seat_diameter" in capsys.readouterr().err
    assert main([*argv, "--gas-pressure", TRACE]) == 2
    assert "give --valve-train" in capsys.readouterr().err
    assert main([*argv, "--valve-train", EXHAUST, "--gas-pressure", "missing.csv"]) == 2
    assert "missing.csv" in capsys.readouterr().err


def test_cli_prints_the_gas_force(capsys):
    argv = ["valve", "simulate", example("valve/one_step_spring.toml"), "--cam", EXHAUST, "--valve-train", EXHAUST]
    assert main([*argv, "--engine-rpm", "6000", "--gas-pressure", TRACE, "--port-pressure", "1.1 bar"]) == 0
    out = capsys.readouterr().out
    assert "gas force on the valve: up to 2314 N" in out


def test_a_sweep_carries_the_gas_force_like_simulate():
    """The sweep's speed and the simulation at that speed see the same gas force: their
    minimum cam contact forces agree to the periodicity tolerance (0.2 % of Fset), and the
    gas force changes them (the exhaust opening against the blow-down)."""
    from springdyn.valve.run.sweeps import sweep

    spring, cam, vt, axis = _exhaust()
    g = GasForce.from_file(TRACE, axis=axis, seat_diameter=vt.seat_diameter, port_pressure=1.1e5)
    sw = sweep(spring, cam, [2500.0], valve_train=vt, gas_force=g)
    sim = simulate(spring, cam, 2500.0, valve_train=vt, gas_force=g)
    plain = simulate(spring, cam, 2500.0, valve_train=vt)
    fset = spring.spring_model.internal_parameters()["Fset"]
    row = sw.summary_table()
    assert row["min_cam_contact_force_N"][0] == pytest.approx(sim.summary["min_cam_contact_force_N"], abs=0.004 * fset)
    assert row["max_retainer_force_N"][0] == pytest.approx(sim.summary["max_retainer_force_N"], abs=0.004 * fset)
    # the firing pressure presses the closed valve onto its seat: ~2300 N more
    assert sim.valve_seat_force.max() > plain.valve_seat_force.max() + 2000.0
    assert any("gas force" in n for n in sw.summary["notes"])
