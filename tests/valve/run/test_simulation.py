"""Valve spring under cam drive: limits, energy, periodicity, modes, lift-off."""

import math
import warnings

import numpy as np
import pytest

from springdyn.core.errors import InputError, SolverError
from springdyn.core.units import rpm_to_omega
from springdyn.valve import ValveSpring, engine
from springdyn.valve.cam.definition import Cam
from springdyn.valve.run import runner as runnermod
from springdyn.valve.run import settings as settingsmod
from springdyn.valve.run import setup as setupmod
from springdyn.valve.run import simulation as simmod
from springdyn.valve.run.float_search import float_speed
from springdyn.valve.run.runner import engine_args
from springdyn.valve.run.setup import prepare
from springdyn.valve.run.simulation import simulate
from springdyn.valve.spring.elements import law_energy, law_force
from springdyn.valve.train.definition import ValveTrain
from tests.paths import example

CAM = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
VT = ValveTrain(valve_mass=0.045, retainer_mass=0.010, follower_mass=0.035)


@pytest.fixture(scope="module")
def one_step():
    return ValveSpring.example("one-step")


def test_quasi_static_limit(one_step):
    """A 10 cam rpm drive reproduces the static force within 0.1 % of Fset."""
    sim = simulate(one_step, CAM, 10.0, revolutions=1, points_per_revolution=720)
    fset = one_step.spring_model.internal_parameters()["Fset"]
    assert np.max(np.abs(sim.retainer_force - sim.static_force)) < 1e-3 * fset
    assert np.max(np.abs(sim.seat_force - sim.static_force)) < 1e-3 * fset
    # and the static force itself is the static curve at the same lift
    np.testing.assert_allclose(
        sim.static_force, one_step.spring_model.static_force(one_step.installed_length - sim.lift), rtol=1e-12
    )


def test_static_force_along_the_cam_is_kept_per_cam(one_step):
    """The static force of a simulation of the spring alone is kept per spring, cam and output
    grid (it depends on no speed): each cam gets its own, equal to the static curve at that
    cam's lift (the static curve of test_statics_modes); the store is bounded, and the shared
    array is read-only."""
    spring = one_step.replace(free_length=one_step.free_length)  # a fresh store
    cams = [Cam(law="3-4-5", lift=lift, duration=math.radians(120)) for lift in (7e-3, 8e-3, 9e-3)]
    for cam in cams:
        sim = simulate(spring, cam, 2000.0, revolutions=1, points_per_revolution=720)
        again = simulate(spring, cam, 3500.0, revolutions=1, points_per_revolution=720)
        assert again.static_force is sim.static_force  # kept across speeds
        assert not sim.static_force.flags.writeable
        np.testing.assert_allclose(
            sim.static_force, spring.spring_model.static_force(spring.installed_length - sim.lift), rtol=1e-12
        )
        np.testing.assert_allclose(
            sim.static_force.max(),
            float(spring.spring_model.static_force(spring.installed_length - cam.lift)),
            rtol=1e-12,
        )
    coarse = simulate(spring, cams[0], 2000.0, revolutions=1, points_per_revolution=360)
    assert coarse.static_force.shape == (360,)
    for k in range(3 * setupmod.STATIC_CACHE_SIZE):
        setupmod.static_force_along_grid(
            prepare(spring, Cam(law="3-4-5", lift=5e-3 + 1e-5 * k, duration=math.radians(120))), 90
        )
    assert len(setupmod._STATIC) == setupmod.STATIC_CACHE_SIZE


@pytest.mark.parametrize("name", ["one-step", "two-step"])
def test_refinement_study(name):
    """Halving the tolerances changes the peak forces by less than 0.05 % of Fset."""
    s = ValveSpring.example(name)
    cam = CAM if name == "one-step" else CAM.scaled(7.5 / 9.0)  # 9 mm drives the two-step spring past solid
    fset = s.spring_model.internal_parameters()["Fset"]
    a = simulate(s, cam, 3000, 2).summary
    b = simulate(s, cam, 3000, 2, rtol=settingsmod.DEFAULT_RTOL / 2, atol=settingsmod.DEFAULT_ATOL / 2).summary
    for key in ("max_retainer_force_N", "min_retainer_force_N", "max_seat_force_N", "min_seat_force_N"):
        assert abs(a[key] - b[key]) < 5e-4 * fset, key


def test_periodicity(one_step):
    sim = simulate(one_step, CAM, 3000, 3)
    assert sim.periodic and sim.periodicity_error < 0.01
    np.testing.assert_allclose(sim.lift, CAM.lift_at(sim.cam_angle), atol=1e-12)
    assert sim.cam_angle_deg[0] == pytest.approx(0.0, abs=1e-9)
    # a transient that has not decayed is reported as not periodic
    assert not simulate(one_step.replace(damping_ratio=0.0), CAM, 3000, 2).periodic


def test_compiled_engine_matches_scipy_reference(one_step):
    """Both backends integrate the same right-hand side; at these tolerances they agree to
    far better than 0.05 % of Fset over the whole revolution."""
    a = simulate(one_step, CAM, 3000, 1, rtol=1e-9, atol=1e-12)
    b = simulate(one_step, CAM, 3000, 1, rtol=1e-9, atol=1e-12, backend="scipy")
    fset = one_step.spring_model.internal_parameters()["Fset"]
    assert np.max(np.abs(a.retainer_force - b.retainer_force)) < 1e-5 * fset


def test_compiled_rhs_equals_numpy_element_laws(one_step):
    """The scalar kernel's forces equal elements.law_force at random states (the end
    elements carry compression only, correction MMS-7)."""
    setup = prepare(one_step, CAM)
    args = engine_args(setup, rpm_to_omega(3000))
    rng = np.random.default_rng(0)
    ch = one_step.spring_model.chain
    for _ in range(20):
        s = np.concatenate([rng.normal(0, 2e-3, 5), np.zeros(5)])
        d = np.empty(10)
        engine.rhs_call(0.0, s, engine.model_of(args), args[8], engine.train_of(args[9]), d, engine.NO_EXTRA)
        u = np.concatenate([[0.0], s[:5], [0.0]])  # cam angle 0: lift 0
        x = ch.setup_compressions + np.diff(u)
        f = np.array([law_force(x[j], ch.laws[j]) for j in range(6)])
        f[[0, -1]] = np.where(x[[0, -1]] > 0, np.maximum(f[[0, -1]], 0.0), 0.0)  # unilateral ends (MMS-7)
        np.testing.assert_allclose(d[5:], (f[1:] - f[:-1]) / ch.masses, rtol=1e-10)


def test_energy_balance_undamped_chain(one_step):
    """Undamped chain: work done by the retainer = kinetic + elastic energy change
    (to integration and trapezoid-quadrature tolerance, 1e-5 of the peak energy)."""
    s = one_step.replace(damping_ratio=0.0)
    setup = prepare(s, CAM)
    omega = rpm_to_omega(3000)
    t = np.linspace(0, 2 * math.pi / omega, 40001)
    states, info = engine.integrate(setup.y0, t, engine_args(setup, omega), rtol=1e-10, atol=1e-13, h_max=1e-5)
    assert info["status"] == 0
    lift, dlift = setup.table.at(omega * t)
    dlift *= omega
    ch = s.spring_model.chain
    u = np.vstack([np.zeros_like(t), states[:, :5].T, lift])
    x = ch.setup_compressions[:, None] + np.diff(u, axis=0)
    pe = sum(law_energy(x[j], ch.laws[j]) - law_energy(ch.setup_compressions[j], ch.laws[j]) for j in range(6))
    ke = 0.5 * np.sum(ch.masses[:, None] * states[:, 5:].T ** 2, axis=0)
    power = law_force(x[5], ch.laws[5]) * dlift
    work = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))])
    assert np.max(np.abs(work - (ke + pe))) < 1e-5 * np.max(pe)


def test_law_energy_is_integral_of_force(one_step):
    for law in one_step.spring_model.chain.laws:
        xs = np.linspace(-1e-3, 9e-3, 200001)
        f = law_force(xs, law)
        num = np.concatenate([[0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(xs))])
        num -= np.interp(0.0, xs, num)
        np.testing.assert_allclose(law_energy(xs, law), num, atol=1e-7 * np.abs(num).max())


def test_mode_frequencies_from_free_response(one_step):
    """Free vibration of the undamped chain (cam at rest): the spectrum peaks at the
    linearised chain modes (Hann window, 1 s record: 1 Hz bins, parabolic peak
    interpolation of the log spectrum good to ~0.1 Hz; we allow 0.5 Hz)."""
    s = one_step.replace(damping_ratio=0.0)
    flat = Cam(law="cycloidal", lift=1e-9, duration=math.radians(1))
    setup = prepare(s, flat)
    y0 = setup.y0.copy()
    y0[:5] = [2e-5, -1e-5, 3e-5, 1e-5, -2e-5]  # small: stays in the linear range
    fs, n = 20000.0, 20000
    t = np.arange(n) / fs
    states, info = engine.integrate(y0, t, engine_args(setup, 1e-6), rtol=1e-9, atol=1e-14, h_max=1e-4)
    sig = states[:, 1] + states[:, 2] - states[:, 3]
    spec = np.abs(np.fft.rfft((sig - sig.mean()) * np.hanning(n)))
    freqs = np.fft.rfftfreq(n, 1 / fs)
    expected = s.spring_model.modes(s.installed_length, 3)
    for f0 in expected:
        k = int(np.argmax(np.where(np.abs(freqs - f0) < 20, spec, 0)))
        a, b, c = np.log(spec[k - 1 : k + 2])
        peak = freqs[k] + 0.5 * (a - c) / (a - 2 * b + c) * (freqs[1] - freqs[0])
        assert peak == pytest.approx(f0, abs=0.5)


def test_coil_contact_events():
    """Type C's coil-contact flags, driven 2 mm past solid on purpose (through_solid)."""
    s = ValveSpring.example("one-step").replace(through_solid=True)
    high = Cam(law="3-4-5", lift=12e-3, duration=math.radians(120))
    sim = simulate(s, high, 4000, 2)
    ev = sim.summary["coil_contact"]
    assert ev, "12 mm lift at 4000 rpm must reach coil contact"
    fcon = s.spring_model.internal_parameters()["Fcon"]
    for e in ev:
        assert e["peak_contact_force_N"] >= fcon
        assert all(name.split(":")[1].startswith("Kh") for name in e["elements"])
    # flags are exactly the Fcon breakpoints of the Kh elements
    kh = [j for j, n in enumerate(s.spring_model.chain.element_names) if n.startswith("Kh")]
    for j in kh:
        flagged = sim.element_contact[j]
        np.testing.assert_array_equal(
            flagged, law_force(sim.element_compression[j], s.spring_model.chain.laws[j]) >= fcon * (1 - 1e-12)
        )


def test_spectrum_harmonics_reconstruct_force(one_step):
    sim = simulate(one_step, CAM, 3000, 2)
    orders, amp = sim.spectrum(max_order=10_000)
    assert amp[0] == pytest.approx(sim.retainer_force.mean(), rel=1e-12)
    # Parseval: mean square = mean^2 + sum amp^2 / 2
    ms = np.mean(sim.retainer_force**2)
    assert ms == pytest.approx(amp[0] ** 2 + np.sum(amp[1:] ** 2) / 2, rel=1e-3)


def test_liftoff_at_the_speed_where_contact_force_reaches_zero(one_step):
    """The float speed is bracketed by a speed whose minimum cam contact force is still
    positive and one with lift-off; far below it the contact force is large."""
    res = float_speed(one_step, CAM, VT, np.arange(2000, 4001, 250.0), resolution=2.0)
    lo, hi = res["bracket"]
    assert hi - lo <= 2.0
    a = simulate(one_step, CAM, lo, 3, valve_train=VT).summary
    b = simulate(one_step, CAM, hi, 3, valve_train=VT).summary
    assert not a["liftoff"] and a["min_cam_contact_force_N"] > 0
    assert b["liftoff"] and b["min_cam_contact_force_N"] == 0.0
    assert res["min_cam_contact_force_N"][0] > 50.0
    # Quasi-static estimate: contact is lost where F_static(h) < M_eff w^2 (-h''),
    # M_eff = valve body + 1/3 of the spring mass.  Surge forces move the dynamic float
    # speed, but not by more than 15 % for this spring (f1 is ~9x the cam frequency).
    th = np.linspace(0, CAM.duration, 4001)
    h, _, ddh = CAM.evaluate(th)
    m_eff = VT.moving_mass + one_step.spring_model.internal_parameters()["M"] / 3
    f_static = one_step.spring_model.static_force(one_step.installed_length - h)
    dec = ddh < 0
    w = math.sqrt(np.min(f_static[dec] / (m_eff * -ddh[dec])))
    rpm_qs = w * 60 / (2 * math.pi)
    assert 0.85 * rpm_qs < res["float_cam_rpm"] < 1.15 * rpm_qs


def test_valve_train_at_rest_is_static(one_step):
    """Far below float speed the valve follows the cam; at rest the spring preload is
    carried by the valve seat and, with zero lash, shared with the cam base circle
    (both contacts have the same stiffness here, so half each)."""
    fset = one_step.spring_model.internal_parameters()["Fset"]
    sim = simulate(one_step, CAM, 300, 2, valve_train=VT)
    closed = sim.lift == 0
    # the closing transient rings on the contacts for a few degrees: 1 % pointwise, 0.1 % mean
    total = (sim.valve_seat_force + sim.cam_contact_force)[closed]
    np.testing.assert_allclose(total, fset, rtol=1e-2)
    assert total.mean() == pytest.approx(fset, rel=1e-3)
    assert sim.valve_seat_force[closed].mean() == pytest.approx(fset / 2, rel=1e-3)
    np.testing.assert_allclose(sim.valve_lift[~closed], sim.lift[~closed], atol=2e-5)  # contact deflection only
    lashed = simulate(one_step, CAM, 300, 2, valve_train=VT.__class__(**{**VT.__dict__, "lash": 1e-4}))
    np.testing.assert_allclose(lashed.valve_seat_force[closed], fset, rtol=1e-2)
    assert np.all(lashed.cam_contact_force[closed] == 0)


@pytest.mark.parametrize("rpm", [0.0, -100.0, float("nan")])
def test_bad_speed(one_step, rpm):
    with pytest.raises(InputError, match="cam_rpm = .* must be a positive speed"):
        simulate(one_step, CAM, rpm)


def test_lift_that_drives_spring_solid(one_step):
    """Issue 25: a cam that drives the spring past its solid length Dw (N + 1/2) = 28 mm is
    refused (installed length, lift, solid length and shortfall named); below the coil-bind
    clearance (EN 13906-1's dynamic 1.5 Sa = 4.599 mm here, Sa 3.066 mm) it warns; ``through_solid`` lets an expert
    run it, and the model's own range (10 Fcon) still holds."""
    cam = lambda lift: Cam(law="3-4-5", lift=lift, duration=math.radians(120))  # noqa: E731
    with pytest.raises(
        InputError, match=r"38 mm - lift 10\.5 mm = 27\.5 mm is 0\.5 mm below the solid length 28 mm \(the MMS document"
    ):
        prepare(one_step, cam(10.5e-3))
    with pytest.warns(
        UserWarning,
        match=r"leaves 1 mm above the solid length 28 mm, less than the dynamic coil-bind clearance 4\.5988 mm",
    ):
        setup = prepare(one_step, cam(9e-3))
    assert setup.coil_bind["coil_bind_margin_m"] == pytest.approx(1e-3) and not setup.coil_bind["coil_bind_ok"]
    quiet = one_step.replace(min_coil_bind_clearance=0.5e-3)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert prepare(quiet, cam(9e-3)).coil_bind["coil_bind_ok"]
    expert = one_step.replace(through_solid=True)
    with pytest.warns(
        UserWarning,
        match=r"coil contact even statically: from cam angle [\d.]+ deg .* peaking at [\d.]+ N at 60\.0 deg",
    ):
        assert prepare(expert, cam(13e-3)).coil_bind["through_solid"]
    with pytest.raises(InputError, match=r"cam lift 25 mm at 60\.0 cam deg drives the spring solid"):
        prepare(expert, cam(25e-3))


def test_solver_failure_names_speed_time_and_cause(one_step, monkeypatch):
    def broken(y0, omegas, revolutions, points, args, **kw):
        n = len(omegas)
        return dict(
            extra=np.full((n, points, len(engine.EXTRA)), np.nan),
            status=np.full(n, 2),
            t_end=np.full(n, 0.0123),
            steps=np.full(n, 42),
            periodicity=np.full(n, np.nan),
        )

    monkeypatch.setattr(runnermod, "integrate_speeds", broken)
    with pytest.raises(
        SolverError,
        match=r"at 3000 cam rpm failed at t = 0\.0123 s \(cam angle 221\.40 deg.*step size "
        r"collapsed; likely cause: the speed: the spring's first surge mode \(450 Hz\) is only 9\.0 cam orders",
    ):
        simulate(one_step, CAM, 3000)


def test_kernel_outputs_equal_numpy_postprocessing(one_step):
    """The compiled kernel's own force evaluation (used by simulate and sweep) equals the
    independent NumPy evaluation of the same states (chain_response)."""
    setup = prepare(one_step, CAM, VT)
    omega = rpm_to_omega(2000)  # below float speed: no impacts to amplify round-off
    period = 2 * math.pi / omega
    res = engine.integrate_speeds(
        setup.y0, [omega], 2, 360, engine_args(setup, omega), rtol=1e-6, atol=1e-9, max_step_fraction=1 / 720
    )
    extra = res["extra"]
    assert extra.shape == (1, 360, engine.extra_layout(5)["size"]) and res["revolutions"][0] == 2
    t = np.arange(720) * period / 360
    # integrate_speeds integrates revolution by revolution, landing a step on each revolution's
    # end: a stop there gives integrate the same step sequence
    states, info = engine.integrate(
        setup.y0, t, engine_args(setup, omega), rtol=1e-6, atol=1e-9, h_max=period / 720, stops=[period]
    )
    r = simmod.chain_response(setup, omega, omega * t, states)
    # the periodicity measure: the largest change of the seat, retainer, cam-contact and
    # valve-seat forces from the first revolution to the second
    chk = np.stack([r["force"][0], r["force"][-1], r["cam_contact_force"], r["valve_seat_force"]])
    assert res["periodicity"][0] == pytest.approx(np.max(np.abs(chk[:, 360:] - chk[:, :360])), rel=1e-5, abs=1e-6)
    r = {k: v[..., 360:] for k, v in r.items()}
    e = extra[0]
    # The right-hand side is inlined into each compiled caller, so the two runs round
    # differently and their adaptive step sequences part at round-off level; the outputs
    # then differ by far less than the integration tolerance (rtol 1e-6): we allow 1e-7.
    np.testing.assert_allclose(e[:, 0:6].T, r["force"], rtol=1e-7, atol=1e-6)
    np.testing.assert_allclose(e[:, 14], r["cam_contact_force"], rtol=1e-7, atol=1e-6)
    np.testing.assert_allclose(e[:, 17:22].T, r["displacement"], rtol=1e-7, atol=1e-12)


def test_speeds_beyond_reason_are_refused_or_flagged(capsys):
    """A cam event shorter than one period of the spring's first surge mode (450 Hz: 2.2 ms,
    a 120-deg event at 9000 cam rpm) is no valve-train operating point: refused with the
    figures and, far above any engine, a typing slip suggested; computed and flagged on request."""
    from springdyn.app.cli.main import main
    from springdyn.valve import sweep

    s = ValveSpring.example("one-step")
    with pytest.raises(
        InputError, match=r"cam_rpm = 60000: the cam event of 120 deg lasts 0.333 ms.*did you mean 6000\?"
    ):
        simulate(s, CAM, 60000.0)
    with pytest.raises(InputError, match=r"cam_rpm = 9500.*\(2 speeds of the range are beyond it\)"):
        sweep(s, CAM, [3000.0, 9500.0, 11000.0])
    with pytest.warns(UserWarning, match="coil bind"):
        sim = simulate(s, CAM, 20000.0, 2, allow_extreme_speeds=True)
    assert sim.summary["notes"][0].startswith("EXTREME SPEED, computed on request: cam_rpm = 20000")
    assert (
        main(
            [
                "valve",
                "simulate",
                example("valve/one_step_spring.toml"),
                "--cam",
                example("valve/cam_345.toml"),
                "--cam-rpm",
                "60000",
            ]
        )
        == 2
    )
    assert "did you mean 6000?" in capsys.readouterr().err


def test_a_lift_table_cam_simulates():
    """Regression: a ``law = "table"`` cam checks its resolution against the spring's first
    surge mode before the run (simulate once asked the spring itself for its modes)."""
    import warnings

    from springdyn.valve import Cam, ValveSpring, simulate

    cam = Cam.from_toml(example("valve/cam_table.toml"))
    assert cam.law == "table"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sim = simulate(ValveSpring.from_toml(example("valve/one_step_spring.toml")), cam, 2000.0)
    # at 2000 cam rpm the peak force is the static one less the nose's inertia, within 10 %
    assert sim.periodic and abs(sim.retainer_force.max() / sim.static_force.max() - 1.0) < 0.1
