"""Valve-train layouts: reduction to the direct-acting train, quasi-static
deflection, the hydraulic lash adjuster, validation.  References: the kinetic- and
strain-energy reduction of a rigid lever (masses ``m / r^2``, ``J / arm^2``, stiffnesses
``k / r^2`` in series), and the static series-spring deflection."""

import math

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve import Cam, ValveSpring, float_speed, simulate
from springdyn.valve.run.runner import engine_args
from springdyn.valve.run.setup import prepare
from springdyn.valve.train.definition import ValveTrain, series_stiffness

#: The repository (the example files), wherever pytest runs from.
from tests.paths import ROOT, example

SPRING = ValveSpring.example("one-step")
FSET = SPRING.spring_model.internal_parameters()["Fset"]
LOBE = Cam(law="3-4-5", lift=6e-3, duration=math.radians(120))
RATIO = 1.5


def stiff_pushrod(**changes):
    """A pushrod train whose only compliance is the cam contact: every other link 1000x
    stiffer, so lifter, pushrod, rocker and valve move as one rigid lever.  The difference
    from the reduced train falls as 1/k of those links (largest cam-force difference at
    1500 cam rpm: 7.0, 1.8, 0.36 N for 5e9, 2e10, 1e11 N/m; 3.4 N at 2600 rpm for 2e10):
    5e10 puts it below 1 % of Fset at both speeds."""
    kw = dict(
        layout="pushrod",
        valve_mass=0.045,
        retainer_mass=0.010,
        follower_mass=0.040,
        pushrod_mass=0.050,
        pushrod_stiffness=5e10,
        rocker_ratio=RATIO,
        rocker_inertia=14e-6,
        rocker_valve_arm=0.035,
        rocker_stiffness=5e10,
        stem_stiffness=5e10,
        cam_contact_stiffness=50e6 * RATIO**2,
        cam_contact_damping=200.0 * RATIO**2,
        link_damping=2000.0,
    )
    kw.update(changes)
    return ValveTrain(**kw)


def valve_cam(cam, ratio):
    return Cam(law=cam.law, lift=cam.lift * ratio, duration=cam.duration)


def test_referred_mass_and_stiffness_by_hand():
    vt = ValveTrain.example("pushrod")
    r = 1.5
    m = 0.045 + 0.010 + 14e-6 / 0.035**2 + 0.025 / r**2 + (0.040 + 0.025) / r**2
    assert vt.moving_mass == pytest.approx(m, rel=1e-12)
    k = 1.0 / (1 / 15e6 + 1 / 50e6 + r**2 / 150e6 + r**2 / 21e6)
    assert vt.stiffness_at_valve == pytest.approx(k, rel=1e-12)
    # handbook range for follower trains, 3.5-10.5 N/um
    for name in ("pushrod", "finger-follower"):
        assert 3.5e6 <= ValveTrain.example(name).stiffness_at_valve <= 10.5e6
    assert series_stiffness(2.0, math.inf, 2.0) == 1.0


@pytest.mark.parametrize("rpm", [1500.0, 2600.0])
def test_stiff_pushrod_reduces_to_direct_acting(rpm):
    # reference: the rigid-lever reduction; tolerance 1 % of Fset
    lever = stiff_pushrod()
    eq = lever.equivalent_direct_acting()
    a = simulate(SPRING, LOBE, rpm, 2, valve_train=lever)
    b = simulate(SPRING, valve_cam(LOBE, RATIO), rpm, 2, valve_train=eq)
    assert np.max(np.abs(a.retainer_force - b.retainer_force)) < 0.01 * FSET
    assert np.max(np.abs(a.cam_contact_force / RATIO - b.cam_contact_force)) < 0.01 * FSET
    assert np.max(np.abs(a.valve_seat_force - b.valve_seat_force)) < 0.01 * FSET
    assert np.max(np.abs(a.valve_lift - b.valve_lift)) < 0.01 * 9e-3


def test_stiff_pushrod_float_speed_matches_reduced_train():
    lever = stiff_pushrod()
    eq = lever.equivalent_direct_acting()
    rpms = np.arange(1500.0, 4001.0, 250.0)
    fa = float_speed(SPRING, LOBE, lever, rpms, revolutions=2, resolution=5.0)["float_cam_rpm"]
    fb = float_speed(SPRING, valve_cam(LOBE, RATIO), eq, rpms, revolutions=2, resolution=5.0)["float_cam_rpm"]
    assert fa is not None and fb is not None
    assert abs(fa - fb) <= 0.01 * fb  # 1 %


@pytest.mark.parametrize("name", ["pushrod", "finger-follower"])
def test_quasi_static_valve_lift_is_kinematics_minus_train_deflection(name):
    # at 150 cam rpm the inertia forces are below 1 % of the spring force: valve lift =
    # ratio x lobe lift - lash - (spring force) / (series stiffness at the valve)
    vt = ValveTrain.example(name)
    cam = Cam(law="3-4-5", lift=9e-3 / vt.ratio, duration=math.radians(120))
    sim = simulate(SPRING, cam, 150.0, 1, valve_train=vt, points_per_revolution=720)
    lash = prepare(SPRING, cam, vt).vt[6]
    open_ = sim.valve_lift > 0.5e-3
    expected = vt.ratio * sim.lift - lash - sim.retainer_force / vt.stiffness_at_valve
    deflection = sim.retainer_force / vt.stiffness_at_valve
    err = np.abs(sim.valve_lift - expected)[open_]
    assert np.max(err / deflection[open_]) < 0.02  # 2 % of the elastic deflection (inertia < 1 %)


def test_hydraulic_adjuster_zero_lash_and_seat_preload():
    vt = ValveTrain.example("finger-follower")
    cam = Cam(law="3-4-5", lift=5.5e-3, duration=math.radians(120))
    sim = simulate(SPRING, cam, 1000.0, 1, valve_train=vt)  # from static equilibrium
    # cam angle 0, on the base circle: the seat carries the spring force less the plunger
    # force; the train rests on the cam with the plunger force (times the ratio at the cam):
    # no clearance anywhere.  The spring force is Fset less K times the seat deflection.
    assert sim.lift[0] == 0.0
    assert sim.valve_seat_force[0] == pytest.approx(sim.static_force[0] - vt.hla_force, rel=1e-9)
    assert sim.static_force[0] == pytest.approx(FSET, rel=1e-3)
    assert sim.cam_contact_force[0] == pytest.approx(vt.ratio * vt.hla_force, rel=1e-9)
    # the valve leaves its seat while the lobe lift is still within the elastic take-up
    first_open = np.flatnonzero(sim.valve_lift > 0)[0]
    assert vt.ratio * sim.lift[first_open] < 1.05 * FSET / vt.stiffness_at_valve + 2e-6


def test_lever_train_forces_never_pull():
    vt = ValveTrain.example("pushrod")
    cam = Cam.from_toml(ROOT / example("valve/cam_pushrod.toml"))
    sim = simulate(SPRING, cam, 3000.0, 2, valve_train=vt)
    assert sim.summary["liftoff"]  # a heavy OHV train floats at 3000 cam rpm with this spring
    assert np.all(sim.cam_contact_force >= 0) and np.all(sim.valve_seat_force >= 0)
    assert np.all(sim.seat_force >= 0) and np.all(sim.retainer_force >= 0)


def test_compiled_and_reference_backends_agree_for_a_finger_follower():
    # the finger follower: with a mechanical lash the free lifter rattles on the base circle and
    # its impacts make the two solvers' histories differ in detail
    vt = ValveTrain.example("finger-follower")
    cam = Cam.from_toml(ROOT / example("valve/cam_finger.toml"))
    a = simulate(SPRING, cam, 1200.0, 1, valve_train=vt, points_per_revolution=360)
    b = simulate(
        SPRING, cam, 1200.0, 1, valve_train=vt, points_per_revolution=360, backend="scipy", rtol=1e-9, atol=1e-12
    )
    assert np.max(np.abs(a.cam_contact_force - b.cam_contact_force)) < 0.01 * FSET
    assert np.max(np.abs(a.retainer_force - b.retainer_force)) < 0.01 * FSET


@pytest.mark.parametrize(
    "changes,message",
    [
        (dict(layout="rocker"), "needs rocker_ratio, rocker_inertia, rocker_valve_arm"),
        (dict(rocker_ratio=1.5), "apply to layout = 'rocker' or 'pushrod'"),
        (dict(pushrod_mass=0.05), "apply to layout = 'pushrod' only"),
        (dict(lash_adjuster="hydraulic", lash=1e-4), "the adjuster takes the lash up"),
        (dict(hla_preload=10.0), "apply to lash_adjuster = 'hydraulic' only"),
        (dict(layout="lever"), "choose one of 'direct-acting', 'rocker', 'pushrod'"),
    ],
)
def test_bad_layout_keys_are_one_clear_error(changes, message):
    with pytest.raises(InputError, match=message.replace("(", r"\(").replace(")", r"\)")):
        ValveTrain(valve_mass=0.05, **changes)


def test_examples_load_and_state_their_layouts():
    assert ValveTrain.example().layout == "direct-acting" and ValveTrain.example().lash > 0
    assert ValveTrain.example("finger-follower").hydraulic
    assert ValveTrain.example("pushrod").degrees_of_freedom == 3


def test_natural_frequencies_of_the_spring_alone_equal_its_modes():
    # the linearisation of the simulation's own laws against the model's modal analysis
    from springdyn.valve.run.train_modes import natural_frequencies

    res = natural_frequencies(SPRING, LOBE, None, count=5)
    assert res["base_circle_Hz"] == pytest.approx(list(SPRING.spring_model.modes(SPRING.installed_length)), rel=1e-6)


def test_valve_on_its_seat_has_the_seat_frequency():
    # a valve far heavier than the spring on a soft seat: f -> sqrt((k_seat + K) / m) / 2 pi
    from springdyn.valve.run.train_modes import natural_frequencies

    vt = ValveTrain(valve_mass=5.0, seat_stiffness=1e6, lash=1e-3)  # lash beyond the 0.25 mm seat deflection
    res = natural_frequencies(SPRING, LOBE, vt, count=8)
    k_spring = SPRING.spring_model.internal_parameters()["K1"]
    f = math.sqrt((1e6 + k_spring) / 5.0) / (2 * math.pi)
    assert min(abs(x - f) for x in res["base_circle_Hz"]) < 0.02 * f  # spring mass 35 g vs 5 kg


def test_resonance_speeds_by_hand():
    from springdyn.valve.run.train_modes import resonance_speeds

    rows = resonance_speeds([500.0], 2900, 3100)
    assert rows == [dict(mode=1, frequency_Hz=500.0, order=10, cam_rpm=3000.0)]


def _train_energy_error(vt, cam, rpm):
    """Undamped spring and train: work of the cam = kinetic + elastic energy change of every
    mass and link (chain elements, cam contact, pushrod, rocker tip, seat) over a revolution.
    Returns the largest mismatch over the revolution relative to the peak elastic energy,
    and whether a link opened while the valve was open (lift-off)."""
    from springdyn.core.units import rpm_to_omega
    from springdyn.valve import engine
    from springdyn.valve.spring.elements import law_energy

    s = SPRING.replace(damping_ratio=0.0)
    setup = prepare(s, cam, vt)
    omega = rpm_to_omega(rpm)
    t = np.linspace(0, 2 * math.pi / omega, 40001)
    states, info = engine.integrate(setup.y0, t, engine_args(setup, omega), rtol=1e-10, atol=1e-13, h_max=2e-6)
    assert info["status"] == 0
    lift, dlift = setup.table.at(omega * t)
    dlift *= omega
    p = setup.vt
    ch = s.spring_model.chain
    nm, nf = setup.n_masses, setup.nfree
    u, v = states[:, :nf].T, states[:, nf:].T
    z = u[nm]
    x = ch.setup_compressions[:, None] + np.diff(np.vstack([np.zeros_like(t), u[:nm], z]), axis=0)
    x[[0, nm]] = np.maximum(x[[0, nm]], 0.0)  # the end elements are unilateral (MMS-7): no tensile energy
    pe = sum(law_energy(x[j], ch.laws[j]) for j in range(nm + 1))
    masses = np.concatenate([ch.masses, [p[1], p[9], p[12]][: nf - nm]])
    ke = 0.5 * np.sum(masses[:, None] * v**2, axis=0)

    def link(k, pen):
        return np.where(pen > 0, 0.5 * k * pen**2, 0.0), np.where(pen > 0, k * pen, 0.0)

    seat_e, _ = link(p[4], -z)
    if nf - nm == 1:
        cam_e, f_cam = link(p[2], lift - z - p[6])
        others = 0.0
    else:
        tip_e, _ = link(p[10], u[nm + 1] - z - p[6])
        if nf - nm == 2:
            cam_e, f_cam = link(p[2], lift - u[nm + 1] / p[8])
            others = tip_e
        else:
            cam_e, f_cam = link(p[2], lift - u[nm + 2])
            push_e, _ = link(p[13], u[nm + 2] - u[nm + 1] / p[8])
            others = tip_e + push_e
    energy = ke + pe + seat_e + cam_e + others
    power = f_cam * dlift
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))])
    err = np.max(np.abs(work - (energy - energy[0]))) / np.max(pe - pe.min())
    return err


@pytest.mark.parametrize(
    "name,camfile,rpm",
    [
        ("finger-follower", example("valve/cam_finger.toml"), 1500.0),  # no lift-off
        ("pushrod", example("valve/cam_pushrod.toml"), 3000.0),  # lift-off and lash impacts
        ("direct-acting", example("valve/cam_polydyne_ramps.toml"), 3500.0),  # floats
    ],
)
def test_train_energy_balance_over_a_revolution(name, camfile, rpm):
    # tolerance: integration at rtol 1e-10 and trapezoid quadrature of the cam's work on
    # 40 000 intervals through contact impacts: 1e-4 of the peak elastic energy
    vt = ValveTrain.example(name).replace(cam_contact_damping=0.0, seat_damping=0.0, link_damping=0.0)
    err = _train_energy_error(vt, Cam.from_toml(ROOT / camfile), rpm)
    assert err < 1e-4
