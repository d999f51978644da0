"""Spring packs under the cam (issue 41, Deliver 1 and 5): two identical springs nested give
twice one spring's forces, and the friction damper's energy balance over a periodic revolution.

References, written here independently of the code they check:

- on the bucket train, two identical springs side by side are one chain of twice the masses,
  element stiffnesses and damping (the one spring's arrays doubled here, run as one chain);
- two identical chains side by side between the seat and one retainer that follows the cam
  are the one chain twice: each carries the one spring's forces, the pack twice them (the
  equations of motion of each chain are the single spring's, :func:`springdyn.valve.engine.chain_forces`);
- each spring's coil clash is graded over its own set-up force: two identical springs nested, each
  is the one spring's clash, and so is the pack's (its worst spring's; over the pack's Fset, twice
  the one's, it would be half);
- each spring's static force is its rate times its compression (the rate ``G d^4/(8 D^3 n)`` by
  hand from the example's TOML values), and the springs' forces at the retainer sum to the pack's;
- the work-energy theorem over a periodic revolution: the elastic and kinetic energies of the
  chains return, so the work the retainer does on the springs, ``oint F_r dh``, equals the
  energy dissipated, ``oint sum_j c_j(x_j) x_j'^2 dt`` of the elements' dampers plus
  ``oint F_d v_slip dt`` of the friction damper (computed here from the recorded compressions,
  the element damping law of :mod:`springdyn.valve.spring.elements` and the damper's recorded
  force and slip, and, for springs that rub, the friction law ``F tanh(v / v_reg) v`` by hand
  on the slip of the two rubbing points; not from the engine's own dissipation output).
"""

import warnings
from pathlib import Path

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve import ValveModel, ValveTrain
from springdyn.valve.cam import Cam
from springdyn.valve.engine import extra_layout, integrate_speeds
from springdyn.valve.run.runner import engine_args
from springdyn.valve.run.setup import prepare
from springdyn.valve.run.simulation import simulate
from springdyn.valve.run.verdicts import coil_clash, spring_clashes
from springdyn.valve.spring import ValveSpring
from springdyn.valve.spring.elements import damping_coefficient
from springdyn.valve.spring.pack import FrictionDamper, PackOptions, SpringPack

CAM = Cam(law="3-4-5", lift=8e-3, duration=2.0944)


@pytest.fixture(scope="module")
def spring():
    return ValveSpring.example("one-step")


def test_two_identical_springs_nested_are_twice_one(spring):
    """Two identical springs side by side carry each the one spring's forces, the pack twice
    them; the end forces agree to 1e-6 N (the two runs take the same steps: the chains'
    states repeat, so the error norm does; what is left is round-off, some 1e-9 N measured)."""
    one = simulate(spring, CAM, 3000.0)
    pack = SpringPack((spring, spring), PackOptions(interference="ignore"))
    two = simulate(pack, CAM, 3000.0)
    assert np.max(np.abs(two.retainer_force - 2.0 * one.retainer_force)) < 1e-6
    assert np.max(np.abs(two.seat_force - 2.0 * one.seat_force)) < 1e-6
    for k in range(2):
        assert np.max(np.abs(two.pack["retainer_force"][k] - one.retainer_force)) < 1e-6
        assert np.max(np.abs(two.pack["seat_force"][k] - one.seat_force)) < 1e-6
    assert two.summary["max_retainer_force_N"] == pytest.approx(2.0 * one.summary["max_retainer_force_N"], rel=1e-9)
    assert np.allclose(two.static_force, 2.0 * one.static_force, rtol=1e-12)


def _work_and_dissipation(sim, pack):
    """``oint F_r dh`` and the dissipation of the elements' dampers and the friction damper [J],
    each by the periodic trapezoidal rule on the output grid (rates by central differences)."""
    n = sim.time.size
    dt = float(sim.time[1] - sim.time[0])
    dh = 0.5 * (np.roll(sim.lift, -1) - np.roll(sim.lift, 1))
    work = float(np.sum(sim.retainer_force * dh))
    x = sim.element_compression
    rate = (np.roll(x, -1, axis=1) - np.roll(x, 1, axis=1)) / (2.0 * dt)
    laws = pack.spring_model.chain.laws
    c0 = pack.spring_model.chain.c0_array
    damping = 0.0
    for j in range(x.shape[0]):
        c = damping_coefficient(x[j], laws[j], c0[j])
        carrying = sim.element_force[j] != 0.0  # an end contact lifted off carries (and dissipates) nothing
        damping += float(np.sum(np.where(carrying, c * rate[j] ** 2, 0.0))) * dt
    friction = float(-np.sum(sim.pack["damper_force"] * sim.pack["damper_slip"])) * dt
    for row in pack.friction_rows()[1:]:  # the springs rubbing: the slip of the two points, the law by hand
        node, other = int(row[0]), int(row[1])
        v = (np.roll(sim.mass_displacement, -1, axis=1) - np.roll(sim.mass_displacement, 1, axis=1)) / (2.0 * dt)
        slip = v[node] - v[other]
        friction += float(np.sum(row[2] * np.tanh(slip / row[3]) * slip)) * dt
    assert n > 1000
    return work, damping, friction


@pytest.mark.parametrize("against", ["seat", "inner", "rubbing"])
def test_the_friction_damper_balances_its_energy(spring, against):
    """Over a periodic revolution the retainer's work equals the energy the elements' dampers
    and the friction damper dissipate.  Tolerance 1e-3 of the work: the trapezoidal rule and the
    central differences on 2880 samples are second order; measured, the mismatch falls from
    8e-5 at 1440 samples to 2e-5 at 2880 (the engine's own dissipation output), the rates by
    central differences add their own O(h^2)."""
    inner = spring.replace(mean_diameter=0.0145, wire_diameter=0.0025, high_pitch_coils=8.0)
    options = None
    if against == "rubbing":  # and the springs rub: the inner's outside 19.5 mm, the outer's inside 18.5 mm
        inner = spring.replace(mean_diameter=0.0165, wire_diameter=0.003, high_pitch_coils=7.0)
        options = PackOptions(interference="rub", radial_stiffness=1e5, rubbing_friction=0.1)
        against = "seat"
    damper = FrictionDamper(friction_force=20.0, acts_on="outer", against=against, height=0.25)
    pack = SpringPack((spring, inner), options, damper)
    rows = pack.friction_rows()
    assert rows.shape[0] == (2 if options is not None else 1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the coil-bind clearance of the example spring at 8 mm
        sim = simulate(pack, CAM, 3000.0, points_per_revolution=2880)
    assert sim.periodic
    work, damping, friction = _work_and_dissipation(sim, pack)
    assert friction > 0.0 and damping > 0.0
    assert work == pytest.approx(damping + friction, rel=1e-3)
    s = sim.summary
    assert s["retainer_work_per_revolution_J"] == pytest.approx(work, rel=1e-9)
    if pack.friction_rows().shape[0] == 1:  # the damper's own share (the first row)
        assert s["damper_energy_per_revolution_J"] == pytest.approx(friction, rel=1e-9)
    assert s["dissipated_energy_per_revolution_J"] == pytest.approx(damping + friction, rel=1e-3)


def test_two_identical_springs_on_the_bucket_train_are_one_spring_of_twice_everything():
    """On the bucket train the valve sees the pack of two identical springs as one chain of
    twice the masses, element stiffnesses and damping: that chain, run by the engine as one
    spring (its own arrays doubled here), gives the pack's retainer force to 1e-5 of its peak
    (measured 2e-6: the two runs take different steps, their states differ in number, at
    rtol 1e-8)."""
    root = Path(__file__).parents[3] / "examples" / "valve"
    spring = SpringPack.from_toml(root / "dual_spring_damper.toml").outer  # the outer spring alone
    cam = Cam.from_toml(root / "cam_polydyne_ramps.toml")
    train = ValveTrain.from_toml(root / "valve_train.toml")
    pack = prepare(SpringPack((spring, spring), PackOptions(interference="ignore")), cam, train)
    one = prepare(spring, cam, train)
    masses, laws, xset, c0, *rest = engine_args(one, 0.0)
    doubled = laws.copy()
    doubled[:, :, 1:] *= 2.0  # the law's a, b, c; its segments' starts stay
    nm, nf = one.n_masses, pack.nfree
    y = pack.y0  # the pack's equilibrium: both chains alike, then the train
    y0 = np.concatenate([y[:nm], y[2 * nm : nf], y[nf : nf + nm], y[nf + 2 * nm :]])
    omega = np.array([2.0 * np.pi * 3000.0 / 60.0])
    run = dict(rtol=1e-8, atol=1e-11, max_step_fraction=0.002)
    f_pack = integrate_speeds(pack.y0, omega, 4, 720, engine_args(pack, 0.0), **run)["extra"][0]
    f_one = integrate_speeds(y0, omega, 4, 720, (2.0 * masses, doubled, xset, 2.0 * c0, *rest), **run)["extra"][0]
    f_pack = f_pack[:, extra_layout(2 * nm, 2)["retainer_total"]]
    f_one = f_one[:, extra_layout(nm, 1)["retainer_total"]]
    assert np.max(np.abs(f_pack - f_one)) < 1e-5 * f_pack.max()


def test_each_springs_coil_clash_is_graded_over_its_own_fset(spring):
    """A revolution of 8 samples at 4 mm lift with one active element pushed 0.5 mm past its coil
    contact in two samples: two identical springs nested each have the one spring's severity
    (spring_clashes), and the pack's severity is the same (its worst spring's, each element over its
    own spring's Fset: not the half the pack's Fset would give); exact."""
    model = spring.spring_model
    _, x0, _ = model.static_state(spring.installed_length - 4e-3)
    closes = model.contact_compressions()
    j = int(np.flatnonzero(np.isfinite(closes))[0])
    x = np.tile(x0[:, None], (1, 8))
    x[j, 3:5] = closes[j] + 0.5e-3
    static = np.full(8, float(model.static_force(spring.installed_length - 4e-3)))
    one = coil_clash(model, x, static, 0.02)
    assert one["severity"] > 0.1 and one["clash"]
    pack = SpringPack((spring, spring), PackOptions(interference="ignore"))
    both = np.concatenate([x, x])
    each = spring_clashes(pack.spring_model, both, 2.0 * static, 0.02)
    assert list(each) == ["outer", "inner"]
    for c in each.values():
        assert c["severity"] == pytest.approx(one["severity"], rel=1e-12) and c["clash"]
    assert coil_clash(pack.spring_model, both, 2.0 * static, 0.02)["severity"] == pytest.approx(
        one["severity"], rel=1e-12
    )
    assert spring_clashes(model, x, static, 0.02) == {}  # one spring: no springs of its own


def test_each_spring_over_a_sweep_on_the_bucket_train():
    """The example pack on the bucket train over two speeds: each spring's columns of the sweep
    (SpeedSweep.spring_table).  Its smallest static force is its rate times its set-up compression
    by hand (the valve seated, to 1e-9); its static Goodman safety is the simulation's (the same
    static range by another path, the sweep's grid against the run's: to 1e-3); the springs'
    forces at the retainer sum to the pack's (to 1e-9 of the peak)."""
    root = Path(__file__).parents[3] / "examples" / "valve"
    model = ValveModel.from_files(
        root / "dual_spring_damper.toml", root / "cam_polydyne_ramps.toml", root / "valve_train.toml"
    )
    sw = model.sweep([2500.0, 3500.0])
    g = 78.5e9
    rate = {"outer": g * 3.8e-3**4 / (8 * 24e-3**3 * 5), "inner": g * 2.6e-3**4 / (8 * 15.5e-3**3 * 7)}
    set_up = {"outer": 10e-3, "inner": 7e-3}
    sim = model.simulate(3500.0)
    for name in ("outer", "inner"):
        t = sw.spring_table(name)
        assert np.allclose(t["min_static_force_N"], rate[name] * set_up[name], rtol=1e-9)
        assert t["static_fatigue_safety_factor"][1] == pytest.approx(
            sim.summary["springs"][name]["static_fatigue_safety_factor"], rel=1e-3
        )
        assert t["fatigue_safety_factor"][1] == pytest.approx(
            sim.summary["springs"][name]["fatigue_safety_factor"], rel=1e-3
        )
        assert set(t) >= {"cam_rpm", "min_retainer_force_N", "clash_severity", "peak_shear_stress_Pa"}
    peak = float(np.max(sim.retainer_force))
    assert np.max(np.abs(sim.pack["retainer_force"].sum(axis=0) - sim.retainer_force)) < 1e-9 * peak
    table = sw.summary_table()
    both = np.minimum(
        sw.spring_table("outer")["fatigue_safety_factor"], sw.spring_table("inner")["fatigue_safety_factor"]
    )
    assert np.allclose(table["fatigue_safety_factor"], both, rtol=1e-12)  # the pack's: its critical spring's
    with pytest.raises(InputError, match="third"):
        sw.spring_table("third")


def test_a_sweep_varies_one_spring_of_a_pack(tmp_path):
    """A sweep's design variable on a pack names one spring's field (``inner_spring.wire_diameter``):
    each value is the pack built with that spring replaced (``SpringPack.replace_spring``, run
    here on its own), the spring's own value the pack's sweep to the bit; a bare field names no
    spring and is refused, as is a spring the pack does not hold.  Its figures draw each spring
    at each value (the per-spring figure once drew the speeds against every value's rows)."""
    root = Path(__file__).parents[3] / "examples" / "valve"
    model = ValveModel.from_files(
        root / "dual_spring_damper.toml", root / "cam_polydyne_ramps.toml", root / "valve_train.toml"
    )
    pack = model.spring
    own = pack.springs[1].wire_diameter
    varied = model.sweep([3000.0, 3100.0], vary=("inner_spring.wire_diameter", [own, 2.7e-3]))
    assert (tmp_path / "sweep_springs.png") in varied.plot_all(tmp_path)
    sw = {k: v[::2] for k, v in varied.summary_table().items()}  # 3000 rpm: each value's first row
    thick = model.replace(spring=pack.replace_spring(1, pack.springs[1].replace(wire_diameter=2.7e-3)))
    for k, m in enumerate((model, thick)):
        alone = m.sweep([3000.0]).summary_table()
        for key in ("max_retainer_force_N", "min_retainer_force_N", "fatigue_safety_factor"):
            assert sw[key][k] == alone[key][0]
    assert sw["inner_spring.wire_diameter_m"].tolist() == [own, 2.7e-3]
    for name, match in (
        ("wire_diameter", "name the spring's field: spring.wire_diameter or inner_spring.wire_diameter"),
        ("third_spring.free_length", "no \\[third_spring\\]"),
        ("inner_spring.type", "not a numeric spring field"),
    ):
        with pytest.raises(InputError, match=match):
            model.sweep([3000.0], vary=(name, [0.05]))


def test_cli_sweep_refuses_a_bare_field_of_a_pack(capsys, tmp_path):
    """``valve sweep --vary`` on a pack file: a bare field is refused with exit 2, naming the option
    and the fields of each spring (before any run)."""
    from springdyn.app.cli.main import main

    root = Path(__file__).parents[3] / "examples" / "valve"
    args = ["valve", "sweep", str(root / "dual_spring_damper.toml"), "--cam", str(root / "cam_polydyne_ramps.toml")]
    args += ["--cam-rpm", "3000", "--vary", "free_length=50mm:52mm:1mm", "--out", str(tmp_path / "o")]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert "--vary = free_length: a spring pack has 2 springs" in err and "inner_spring.free_length" in err
