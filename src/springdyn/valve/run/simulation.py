"""Valve-spring simulation under cam drive (document, "Initial condition & position").

:func:`simulate` runs the spring alone (retainer end prescribed by the cam) or, with a
:class:`~springdyn.valve.train.definition.ValveTrain`, the valve train with lift-off; it
returns a :class:`Simulation` holding the last revolution and its summary.  The set-up it
runs from is :mod:`springdyn.valve.run.setup`; the float search, :mod:`springdyn.valve.run.float_search`;
natural frequencies under the cam, :mod:`springdyn.valve.run.train_modes`.
"""

import dataclasses
import functools
import math

import numpy as np

from ...core.errors import InputError
from ...core.units import rpm_to_omega
from ..cam.definition import Cam
from ..engine import EXT, integrate_scipy, train_response
from ..engine.layout import EXT_VALUES, VT_HLA_KCHK
from ..spring.definition import ValveSpring
from ..spring.elements import damping_coefficient, law_force
from ..train.definition import ValveTrain
from .results import Simulation
from .runner import engine_args, run_speeds, runge_kutta_pair, solver_error, velocity_tolerance
from .settings import MAX_STEP_FRACTION, POINTS_PER_REVOLUTION, RunSettings
from .setup import (
    SimulationSetup,
    check_speeds,
    output_angles,
    prepare,
    static_force_along_grid,
    static_force_at_lift,
    with_gas_force,
)

__all__ = ["simulate", "chain_response"]


def simulate(
    spring: ValveSpring,
    cam: Cam,
    cam_rpm: float,
    revolutions: int | None = None,
    *,
    valve_train: ValveTrain | None = None,
    settings: RunSettings | None = None,
    setup: SimulationSetup | None = None,
    gas_force=None,
    **run,
) -> Simulation:
    """Simulate the valve spring (or valve train) driven by the cam.

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    cam_rpm : float
        Camshaft speed [rev/min] (half the engine speed of a four-stroke engine).
    revolutions : int, optional
        Cam revolutions [-] to integrate from static equilibrium; the last is reported and
        compared with the one before to judge periodicity.  Default: run to the periodic
        steady state, until the seat, retainer, cam-contact and valve-seat forces of the last
        two revolutions differ by at most ``periodicity_tol`` on the output grid, for at most
        ``max_revolutions`` (one that does not settle reports the band of its extremes over
        its last :data:`~springdyn.valve.run.periodicity.BAND_REVOLUTIONS`, ``Simulation.band``).
    valve_train : ValveTrain, optional
        Adds the valve body with cam and seat contacts (lift-off, bounce).
    settings : RunSettings, optional
        How the run is integrated (:class:`~springdyn.valve.run.settings.RunSettings`: output
        points, default 1440 a revolution; tolerances, default 1e-6 and 1e-9 m, with a valve
        train 1e-8 and 1e-11 m; periodicity; backend; pair; extreme speeds; the element check).
    setup : SimulationSetup, optional
        A prepared setup of the same spring, cam and valve train (:func:`prepare`), reused
        across speeds.
    gas_force : GasForce, optional
        The cylinder's gas force on the valve over the revolution [N]
        (:class:`springdyn.valve.train.gas_force.GasForce`; needs a valve train).
    **run
        Fields of :class:`~springdyn.valve.run.settings.RunSettings` given one by one
        (``rtol=1e-7``, ``points_per_revolution=720``, ...): they change ``settings``.

    Raises
    ------
    InputError
        Non-positive speed, bad settings, a lift that drives the spring solid.
    SolverError
        Integration failure, naming the speed, the time and the likely cause.
    """
    number = (int, float, np.integer, np.floating)
    if isinstance(cam_rpm, bool) or not isinstance(cam_rpm, number) or not (cam_rpm > 0 and math.isfinite(cam_rpm)):
        raise InputError(f"cam_rpm = {cam_rpm!r} must be a positive speed: a finite number [rev/min]")
    if revolutions is not None:
        run["revolutions"] = revolutions
    settings = RunSettings.of(settings, **run)
    most = settings.most_revolutions
    # bound the work by the periods of the fastest mode: solve_ivp has no step cap (20 to
    # 70 right-hand-side calls per period: 2e4 periods take seconds to a minute); the
    # compiled engine stops at 1e7 steps (3 to 5 steps per period)
    backend = settings.backend
    max_cycles = 2.0e4 if backend == "scipy" else 2.0e6
    f_top = spring.spring_model.fastest_mode
    if valve_train is not None:
        f_top = max(f_top, valve_train.highest_frequency())
    cycles = most * 60.0 / cam_rpm * f_top
    if cycles > max_cycles:
        raise InputError(
            f"cam_rpm = {cam_rpm:g} is too slow for backend = {backend!r}: {most} revolutions last "
            f"{most * 60.0 / cam_rpm:.4g} s, {cycles:.3g} periods of the fastest mode ({f_top:.0f} Hz), "
            f"more than the {max_cycles:g} this backend integrates in bounded time; "
            + ("use backend = 'compiled' or " if backend == "scipy" else "give fewer revolutions or ")
            + f"at least {most * 60.0 * f_top / max_cycles:.3g} rev/min"
        )
    if setup is None:
        setup = prepare(spring, cam, valve_train, gas_force)
        if cam.law == "table":
            cam.check_resolution(cam_rpm, float(spring.spring_model.first_mode_installed))
    elif gas_force is not None:
        setup = with_gas_force(setup, gas_force)
    extreme = check_speeds(setup, cam_rpm, settings.allow_extreme_speeds)
    omega = rpm_to_omega(cam_rpm)
    period = 2 * math.pi / omega
    n = settings.points(POINTS_PER_REVOLUTION)
    if backend == "compiled":
        res = run_speeds(setup, [omega], settings, n)
        info = dict(
            status=int(res["status"][0]),
            t=float(res["t_end"][0]),
            steps=int(res["steps"][0]),
            method=runge_kutta_pair(setup, settings),
        )
        if info["status"] != 0 or not np.isfinite(res["extra"]).all():
            raise solver_error(cam_rpm, omega, info, setup)
        done = int(res["revolutions"][0])
        time = (done - 1) * period + np.arange(n) * (period / n)
        sim = _from_extra(setup, cam_rpm, done, time, res["extra"][0], float(res["periodicity"][0]), info)
        sim.periodicity_tol = settings.periodicity_tol
        sim.monitor = _monitor_record(res, 0, omega, done)
        if settings.periodic and not res["settled"][0]:
            sim.band = _band(res, 0)
        sim.flags = extreme
        if settings.check_elements:
            _check_element_count(sim, setup, cam_rpm, settings)
        _add_gas_force(sim, setup.gas_force)
        return sim
    sim = _simulate_scipy(setup, cam_rpm, settings, n)
    sim.periodicity_tol = settings.periodicity_tol
    sim.flags = extreme
    _add_gas_force(sim, setup.gas_force)
    return sim


def _band(res: dict, i: int) -> dict:
    """The band of each extreme over the monitored revolutions of speed ``i``: name -> (lo, hi)."""
    return {EXT[k]: (float(res["band_lo"][i, k]), float(res["band_hi"][i, k])) for k in EXT_VALUES}


def _simulate_scipy(setup, cam_rpm, settings: RunSettings, n: int) -> Simulation:
    """The SciPy reference, revolution by revolution: ``settings.revolutions`` of them, or
    (None) until the periodicity channels of two revolutions agree within the periodicity
    tolerance of Fset (at most ``max_revolutions``), as the compiled engine judges them
    (:func:`_check_forces`)."""
    omega = rpm_to_omega(cam_rpm)
    period = 2 * math.pi / omega
    fset = setup.spring.spring_model.internal_parameters()["Fset"]
    rtol, atol = settings.tolerances(setup.valve_train)
    y = np.array(setup.y0, dtype=float)
    before = None
    err = math.nan
    steps = 0
    for r in range(settings.most_revolutions):
        t_rev = r * period + np.arange(n + 1) * (period / n)
        states, info = integrate_scipy(
            y,
            t_rev,
            engine_args(setup, omega),
            rtol=rtol,
            atol=atol,
            h_max=period * MAX_STEP_FRACTION,
            atol_velocity=velocity_tolerance(setup, atol),
        )
        steps += int(info["steps"])
        if info["status"] != 0 or not np.all(np.isfinite(states)):
            raise solver_error(cam_rpm, omega, info, setup)
        y = states[-1]
        forces = _check_forces(setup, omega, t_rev[:n], states[:n])
        if before is not None:
            err = float(np.max(np.abs(forces - before))) / fset
        before = forces
        if settings.periodic and r >= 1 and err <= settings.periodicity_tol:
            break
    return _postprocess(setup, cam_rpm, r + 1, t_rev[:n], states[:n], dict(info, steps=steps), err)


def _check_forces(setup: SimulationSetup, omega: float, t: np.ndarray, states: np.ndarray) -> np.ndarray:
    """The periodicity channels (seat, retainer, cam-contact, valve-seat forces [N]) of the
    reference's states, as :func:`springdyn.valve.engine.loop.check_channels` samples them."""
    r = chain_response(setup, omega, omega * t, states)
    zero = np.zeros(t.size)
    hla = r.get("hla_collapse", zero) * setup.vt[VT_HLA_KCHK] if setup.valve_train is not None else zero
    return np.stack(
        [r["force"][0], r["force"][-1], r.get("cam_contact_force", zero), r.get("valve_seat_force", zero), hla],
        axis=-1,
    )


def _add_gas_force(sim: Simulation, gas) -> None:
    """The gas force on the output grid and its peak in the summary's terms."""
    if gas is not None:
        sim.gas_force = gas.at(sim.cam_angle)


def _check_element_count(sim, setup: SimulationSetup, cam_rpm: float, settings: RunSettings) -> None:
    """Distributed model with clashing coils: the peak end forces with twice the elements
    (with the pair the caller chose, else the finer chain's own, :func:`runge_kutta_pair`).

    Twice, not half: the change from the default to a finer chain estimates the default's own
    error (issue 40: against half the elements the flag was false at every clash speed of two
    test springs whose true error against 200 elements was 0.03-1.6 % of Fset)."""
    sp = sim.spring
    if getattr(sp, "springs", None) is not None:  # a spring pack: no element check (docs/valve-packs.md)
        return
    if sp.model != "distributed" or not sp.spring_model.clashing_coils(sim):
        return
    finer = min(2 * sp.elements, MAX_CHECK_ELEMENTS)
    if finer <= sp.elements:
        return
    fine_spring = _with_elements(sp, finer)  # its set-up is kept
    fine = simulate(
        fine_spring,
        setup.cam,
        cam_rpm,
        valve_train=setup.valve_train,
        settings=dataclasses.replace(settings, check_elements=False),
        gas_force=setup.gas_force,
    )
    ext = fine.monitor["ext"]  # the true extremes of the dense output, as in the summary
    sim.element_check = dict(
        elements=finer,
        max_retainer_force_N=max(float(ext["max_retainer_force"]), float(fine.retainer_force.max())),
        max_seat_force_N=max(float(ext["max_seat_force"]), float(fine.seat_force.max())),
    )
    sim.__dict__.pop("_summary_cache", None)  # the summary now includes the check


#: The element count of the convergence check at most [-] (twice the default's, up to this).
MAX_CHECK_ELEMENTS = 400


@functools.lru_cache(maxsize=8)
def _with_elements(spring: ValveSpring, elements: int) -> ValveSpring:
    """``spring`` with ``elements`` elements: the finer spring of the clash check, kept for the
    last few springs (an explicit cache: its model and set-up are reused by every run that
    checks the same spring)."""
    return spring.replace(elements=elements)


def chain_response(setup: SimulationSetup, omega, theta: np.ndarray, states: np.ndarray) -> dict:
    """Forces and contacts of the chain from integrated states (vectorised NumPy).

    The reference backend's post-processing, independent of the compiled kernel's own
    output evaluation (``engine.chain_rhs`` with ``extra``); the tests compare the two.

    Parameters
    ----------
    setup : SimulationSetup
    omega : float or ndarray (...,)
        Cam speed(s) [rad/s], one per leading index of ``states``.
    theta : ndarray (n_t,)
        Cam angles of the samples [rad] (the same for every speed).
    states : ndarray (..., n_t, 2 nfree)
        Displacements [m] then velocities [m/s] at those angles.

    Returns
    -------
    dict
        ``lift`` (n_t,) [m]; ``compression``, ``force`` (..., 6, n_t) [m, N];
        ``contact`` (..., 6, n_t) bool; ``static`` (..., n_t) or (n_t,) [N];
        with a valve train also ``valve_lift``, ``cam_contact_force``,
        ``valve_seat_force`` (..., n_t).
    """
    chain = setup.spring.spring_model.chain
    nf = setup.nfree
    omega = np.asarray(omega, dtype=float)[..., None]
    lift, dlift_dth = setup.table.at(theta)
    dlift = dlift_dth * omega  # (..., n_t)
    u = np.swapaxes(states[..., :nf], -1, -2)  # (..., nf, n_t)
    v = np.swapaxes(states[..., nf:], -1, -2)
    lead = u.shape[:-2]
    n_t = theta.size
    nm = setup.n_masses
    if nf > nm:
        u_top, v_top = u[..., nm, :], v[..., nm, :]
    else:
        u_top = np.broadcast_to(lift, lead + (n_t,))
        v_top = np.broadcast_to(dlift, lead + (n_t,))
    zeros = np.zeros(lead + (1, n_t))
    x = chain.setup_compressions[:, None] + np.diff(
        np.concatenate([zeros, u[..., :nm, :], u_top[..., None, :]], axis=-2), axis=-2
    )
    xd = np.diff(np.concatenate([zeros, v[..., :nm, :], v_top[..., None, :]], axis=-2), axis=-2)
    c0 = chain.c0_array
    force = np.stack(
        [
            law_force(x[..., j, :], chain.laws[j])
            + damping_coefficient(x[..., j, :], chain.laws[j], c0[j]) * xd[..., j, :]
            for j in range(nm + 1)
        ],
        axis=-2,
    )
    for j in (0, nm):  # unilateral end contacts (correction MMS-7 of docs/references.md)
        force[..., j, :] = np.where(x[..., j, :] > 0.0, np.maximum(force[..., j, :], 0.0), 0.0)
    out = dict(lift=lift, compression=x, force=force, contact=x >= setup.spring.spring_model.contact_gaps[:, None])
    if nf > nm:
        out["static"] = static_force_at_lift(setup, u_top)
        out.update(train_response(setup.vt, lift, dlift, u[..., nm:, :], v[..., nm:, :], theta=theta, omega=omega))
    else:
        out["static"] = static_force_at_lift(setup, lift)
    out["displacement"] = u[..., :nm, :]
    return out


def _run_record(setup: SimulationSetup, cam_rpm, revolutions, prev_err, info) -> dict:
    """The fields of a :class:`Simulation` that say what was run and how well it settled."""
    return dict(
        spring=setup.spring,
        cam=setup.cam,
        valve_train=setup.valve_train,
        cam_rpm=cam_rpm,
        revolutions=revolutions,
        periodicity_error=prev_err,
        info=info,
        coil_bind=setup.coil_bind,
    )


def _from_extra(setup: SimulationSetup, cam_rpm, revolutions, time, e, prev_err, info) -> Simulation:
    """Build the results from the compiled kernel's own force evaluation (:data:`engine.EXTRA`)
    over the last revolution, ``e``; ``prev_err`` is its periodicity error [fraction of Fset]."""
    lay = setup.layout
    force, x = e[:, lay["force"]].T, e[:, lay["compression"]].T
    lift = e[:, lay["lift"]]
    if setup.valve_train is None:  # the lift of the cam table at the output angles: kept per cam
        static = static_force_along_grid(setup, time.size)
    else:
        static = static_force_at_lift(setup, e[:, lay["top_displacement"]])
    sim = Simulation(
        **_run_record(setup, cam_rpm, revolutions, prev_err, info),
        time=time,
        cam_angle=output_angles(time.size),
        lift=lift,
        retainer_force=e[:, lay["retainer_total"]],
        seat_force=e[:, lay["seat_total"]],
        static_force=static,
        element_compression=x,
        element_force=force,
        element_contact=x >= setup.spring.spring_model.contact_gaps[:, None],
        mass_displacement=e[:, lay["displacement"]].T,
    )
    if setup.n_chains > 1:  # a spring pack: each spring's end forces, the friction and the dissipation
        ranges = setup.spring.spring_model.element_ranges()
        sim.pack = dict(
            retainer_force=np.stack([force[r][-1] for r in ranges]),
            seat_force=np.stack([force[r][0] for r in ranges]),
            **{k: e[:, lay[k]] for k in ("damper_force", "damper_slip", "dissipation")},
        )
    if setup.valve_train is not None:
        sim.valve_lift = e[:, lay["top_displacement"]]
        sim.cam_contact_force = e[:, lay["cam_contact_force"]]
        sim.valve_seat_force = e[:, lay["valve_seat_force"]]
        sim.cam_gap = e[:, lay["cam_gap"]]
        if setup.valve_train.hla is not None:
            sim.hla = {k: e[:, lay[f"hla_{k}" if k != "socket_force" else k]] for k in HLA_OUTPUTS}
    return sim


def _monitor_record(mon: dict, i: int, omega: float, revolutions: int) -> dict:
    """The monitor outputs of speed ``i`` in the terms of the last revolution.

    Times become cam angles within the revolution [rad] (``t0`` the revolution's start);
    events open at the window's start or end are marked by ``None`` times there.
    """
    ext = dict(zip(EXT, mon["ext"][i].tolist()))
    t0 = (revolutions - 1) * (2.0 * np.pi / omega)  # as the engine's loop computes it
    rows = mon["events"][i, : int(mon["n_events"][i])]
    return dict(ext=ext, events=rows.copy(), omega=omega, t0=t0)


def _postprocess(setup: SimulationSetup, cam_rpm, revolutions, t_last, states, info, prev_err) -> Simulation:
    """The reference's results from the states ``states`` of the last revolution at the
    times ``t_last`` [s]."""
    omega = rpm_to_omega(cam_rpm)
    theta = omega * t_last
    r = chain_response(setup, omega, theta, states)
    last = slice(0, t_last.size)
    force = r["force"]
    sim = Simulation(
        **_run_record(setup, cam_rpm, revolutions, prev_err, info),
        time=t_last,
        cam_angle=np.mod(theta[last], 2 * math.pi),
        lift=r["lift"][last],
        retainer_force=force[-1, last],
        seat_force=force[0, last],
        static_force=r["static"][last],
        element_compression=r["compression"][:, last],
        element_force=force[:, last],
        element_contact=r["contact"][:, last],
        mass_displacement=r["displacement"][:, last],
    )
    if setup.valve_train is not None:
        sim.valve_lift = r["valve_lift"][last]
        sim.cam_contact_force = r["cam_contact_force"][last]
        sim.valve_seat_force = r["valve_seat_force"][last]
        if setup.valve_train.hla is not None:
            sim.hla = {k: r[f"hla_{k}" if k != "socket_force" else k][last] for k in HLA_OUTPUTS}
    return sim


#: The adjuster's outputs of a simulation (:attr:`Simulation.hla`).
HLA_OUTPUTS = ("collapse", "pressure", "socket_force", "inflow", "leak")
