"""Valve-train layouts: reduction to the direct-acting train, quasi-static
deflection, the hydraulic lash adjuster, validation.  References: the kinetic- and
strain-energy reduction of a rigid lever (masses ``m / r^2``, ``J / arm^2``, stiffnesses
``k / r^2`` in series), and the static series-spring deflection."""

import math
from pathlib import Path

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


# --- the engine's parameter vector (issue 38 item 4): written by slot name, read by slot name ----
from springdyn.valve.engine import layout as engine_layout  # noqa: E402

#: One example train of each kind the engine knows (and the drawn lever, a lever of its own).
KIND_EXAMPLES = {
    "valve_train.toml": engine_layout.TRAIN_DIRECT,
    "finger_follower.toml": engine_layout.TRAIN_LEVER,
    "finger_follower_geometry.toml": engine_layout.TRAIN_LEVER,
    "pushrod.toml": engine_layout.TRAIN_PUSHROD,
    "bucket_hla.toml": engine_layout.TRAIN_BUCKET_HLA,
    "finger_follower_hla.toml": engine_layout.TRAIN_LEVER_HLA,
}


def _slot_names() -> dict:
    return {name: value for name, value in vars(engine_layout).items() if name.startswith("VT_") and name != "VT_SIZE"}


class _Recorder(np.ndarray):
    """An array that records the indices written into it."""

    def __array_finalize__(self, obj):
        self.writes = getattr(obj, "writes", None)

    def __setitem__(self, key, value):
        self.writes.append(key)
        super().__setitem__(key, value)


def _recorded_parameters(vt: ValveTrain, monkeypatch) -> tuple:
    """``vt.kernel_parameters()`` and the slots it wrote, in order."""
    real_zeros = np.zeros
    made = []

    def zeros(shape, *args, **kwargs):
        out = real_zeros(shape, *args, **kwargs)
        if shape == engine_layout.VT_SIZE:
            out = out.view(_Recorder)
            out.writes = []
            made.append(out)
        return out

    with monkeypatch.context() as mp:
        mp.setattr(np, "zeros", zeros)
        params = vt.kernel_parameters()
    assert len(made) == 1 and params is made[0]
    return np.asarray(params), list(made[0].writes)


def test_every_slot_has_one_name():
    """The layout names every slot of the vector, each slot once ("none left unnamed")."""
    names = _slot_names()
    assert sorted(names.values()) == list(range(engine_layout.VT_SIZE)), names


@pytest.mark.parametrize("name", sorted(KIND_EXAMPLES))
def test_kernel_parameters_write_every_slot_once_by_name(name, monkeypatch):
    vt = ValveTrain.from_toml(ROOT / example(f"valve/{name}"))
    params, writes = _recorded_parameters(vt, monkeypatch)
    assert params.shape == (engine_layout.VT_SIZE,)
    assert all(isinstance(k, int) for k in writes)  # one slot at a time, by its name
    assert sorted(writes) == list(range(engine_layout.VT_SIZE))  # every slot, each once
    kind = KIND_EXAMPLES[name]
    assert vt.kernel_kind == kind and params[engine_layout.VT_KIND] == kind
    assert params[engine_layout.VT_ENABLED] == 1.0
    dof = engine_layout.TRAIN_DOF[kind]
    assert params[engine_layout.VT_DOF] == dof == vt.degrees_of_freedom
    assert vt.static_state(0.0, 0.0, 0.0).shape == (dof,)
    assert (params[engine_layout.VT_HLA] == 1.0) == (vt.hla is not None)
    assert (params[engine_layout.VT_GEOM] == 1.0) == (vt.geometry is not None)


def test_the_docstrings_state_the_vectors_true_size():
    """The docstrings that give the vector's size give ``VT_SIZE`` (they once said 16 of 45)."""
    import re

    from springdyn.valve.engine import equations

    doc = " ".join(ValveTrain.kernel_parameters.__doc__.split())
    assert f"its {engine_layout.VT_SIZE} slots (``VT_SIZE``)" in doc
    for module in (equations, engine_layout):
        text = Path(module.__file__).read_text()
        sizes = re.findall(r"vt : ndarray \((\d+),\)", text)
        assert not sizes, f"{module.__name__} gives the vector {sizes} slots: write (VT_SIZE,)"


def test_state_offsets_name_the_states_of_each_kind():
    """``S_*`` and ``H_*`` are the positions of the states that TRAIN_STATES lists per kind, and
    a train's static state (its initial condition) has the pressure where the engine reads it."""
    L = engine_layout
    states = L.TRAIN_STATES
    assert states[L.TRAIN_DIRECT].index("valve") == L.S_VALVE
    assert states[L.TRAIN_LEVER].index("lever") == L.S_LEVER
    assert states[L.TRAIN_PUSHROD].index("lifter") == L.S_LIFTER
    assert states[L.TRAIN_LEVER_HLA].index("pivot") == L.S_PIVOT
    assert states[L.TRAIN_BUCKET_HLA].index("bucket") == L.S_BUCKET
    for kind, first in ((L.TRAIN_LEVER_HLA, L.S_LEVER_HLA), (L.TRAIN_BUCKET_HLA, L.S_BUCKET_HLA)):
        for h, name in (
            (L.H_PLUNGER, "plunger"),
            (L.H_PRESSURE, "pressure"),
            (L.H_INFLOW, "inflow"),
            (L.H_LEAK, "leak"),
        ):
            assert states[kind][first + h] == name
        assert len(states[kind]) == first + L.N_HLA_STATES
    for name, first in (("bucket_hla.toml", L.S_BUCKET_HLA), ("finger_follower_hla.toml", L.S_LEVER_HLA)):
        vt = ValveTrain.from_toml(ROOT / example(f"valve/{name}"))
        y = vt.static_state(0.0, 0.0, vt.hla_force)
        assert y[first + L.H_PRESSURE] == vt.kernel_parameters()[L.VT_HLA_PS]  # the supply, absolute
