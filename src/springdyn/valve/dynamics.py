"""Valve-spring simulation under cam drive (document, "Initial condition & position").

:func:`simulate` runs the spring alone (retainer end prescribed by the cam) or, with a
:class:`~springdyn.valve.valvetrain.ValveTrain`, the valve train with lift-off; it
returns a :class:`Simulation` holding the last revolution and its summary.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass

import numpy as np

from ..core.errors import InputError, SolverError
from ..core.units import rpm_to_omega
from ..numerics.erk import PAIRS
from .cam import Cam
from .elements import damping_coefficient, law_force
from .engine import (
    STATUS,
    extra_layout,
    hermite_eval,
    integrate_scipy,
    run_speeds,
    series_force_compiled,
    stop_angles,
    train_response,
)
from .engine.layout import VT_LASH, VT_M_LEVER, VT_M_LIFTER, VT_MASS
from .results import FloatSpeedResult, Simulation
from .spring import ValveSpring
from .statics import series_force
from .valvetrain import KERNEL_SIZE, ValveTrain

__all__ = [
    "simulate",
    "check_run_settings",
    "Simulation",
    "SimulationSetup",
    "prepare",
    "float_speed",
    "chain_response",
    "DEFAULT_RTOL",
    "DEFAULT_ATOL",
]

#: Default integration tolerances (relative; absolute on displacements [m] and velocities
#: [m/s]).  Chosen by the refinement study of the tests: halving them changes peak forces
#: by far less than 0.05 %.
DEFAULT_RTOL = 1e-6
DEFAULT_ATOL = 1e-9
#: Cam table resolution for the engine (samples per revolution, 0.05 deg).
CAM_SAMPLES = 7200
#: Maximum step [fraction of a revolution] so that no step can jump over a short event.
MAX_STEP_FRACTION = 1.0 / 720.0
#: The spring's velocities get the absolute tolerance ``atol 2 pi f1 / VELOCITY_TOLERANCE_DIVISOR``
#: [m/s] (:meth:`SimulationSetup.atol_velocity`; the study in docs/valve.md).
VELOCITY_TOLERANCE_DIVISOR = 30.0
#: The embedded Runge-Kutta pair of the compiled engine per spring model, chosen by
#: measurement (docs/valve.md, "Stepping"): Type C's step is set by accuracy, where the
#: 5th-order Dormand-Prince pair takes the fewest right-hand sides; the distributed chain's
#: by the stability of its stiffness-proportionally damped top modes (real eigenvalues to
#: -3.3e5 1/s for 50 elements), where the Bogacki-Shampine 3(2) pair takes 1.3x more steps
#: for half the right-hand sides each, and still holds the end forces within 0.05 % of Fset.
PAIR = {"type-c": "dopri5", "distributed": "bs3"}


def output_angles(points: int) -> np.ndarray:
    """The cam angles [rad] of the output samples of a revolution, ``2 pi j / points``."""
    return np.arange(int(points)) * (2.0 * math.pi / int(points))


@dataclass
class SimulationSetup:
    """Everything the engine needs for one spring, cam and valve train (speed-independent)."""

    spring: ValveSpring
    cam: Cam
    valve_train: ValveTrain | None
    cam_h: np.ndarray
    cam_dh: np.ndarray
    cam_ddh: np.ndarray
    dth: float
    vt: np.ndarray
    y0: np.ndarray

    def static_force(self, lift) -> np.ndarray:
        """Static (massless) spring force [N] at cam or valve lift(s) [m]."""
        sp = self.spring
        lift = np.asarray(lift, dtype=float)
        dl = np.ascontiguousarray((sp.free_length - sp.installed_length) + lift.ravel())
        force = np.empty_like(dl)
        series_force_compiled(dl, sp.chain.laws, force, *sp.spring_model.force_table)
        return force.reshape(lift.shape)

    def static_force_along_cam(self, points: int) -> np.ndarray:
        """Static (massless) force [N] of the spring alone at the cam angles ``2 pi j / points``,
        ``j = 0 .. points - 1``: at the lift of the engine's cam table there.

        It depends on the spring, the cam and ``points`` only, not on the speed, so the
        spring keeps it for its last :attr:`STATIC_CACHE_SIZE` cams (a Newton solve per
        angle costs about 5 % of a Type C simulation).  Read-only: results share it.
        """
        store = self.spring.spring_model.static_force_cache
        key = (id(self.cam), int(points))  # the entry holds the cam: its id is not reused meanwhile
        hit = store.get(key)
        if hit is None:
            lift = hermite_eval(output_angles(points), self.cam_h, self.cam_dh, self.cam_ddh, self.dth)[0]
            force = self.static_force(lift)
            force.flags.writeable = False
            hit = store[key] = (self.cam, force)
            while len(store) > self.STATIC_CACHE_SIZE:
                store.pop(next(iter(store)), None)  # the oldest
        return hit[1]

    #: Cams per spring whose static force along the output grid is kept.
    STATIC_CACHE_SIZE = 8

    def args(self, omega: float) -> tuple:
        ch = self.spring.chain
        return (
            ch.masses,
            ch.laws,
            ch.setup_compressions,
            ch.c0_array,
            self.cam_h,
            self.cam_dh,
            self.cam_ddh,
            self.dth,
            omega,
            self.vt,
        )

    @property
    def n_masses(self) -> int:
        """Masses of the spring's chain."""
        return len(self.spring.chain.masses)

    @property
    def nfree(self) -> int:
        """Degrees of freedom: the chain's masses, plus the valve train's (valve, lever, lifter)."""
        return self.n_masses + (self.valve_train.degrees_of_freedom if self.valve_train is not None else 0)

    def run(self, omegas, revolutions: int, points: int, *, rtol: float, atol: float, method: str | None = None):
        """Integrate the speeds ``omegas`` [rad/s] with the compiled engine, monitoring the
        last revolution (true extremes and events on the dense output, see
        :func:`springdyn.valve.engine.run_speeds`)."""
        return run_speeds(
            self.y0,
            omegas,
            revolutions,
            points,
            self.args(0.0),
            rtol=rtol,
            atol=atol,
            max_step_fraction=MAX_STEP_FRACTION,
            gaps=self.spring.spring_model.contact_gaps,
            monitor=True,
            atol_velocity=self.atol_velocity(atol),
            method=self.method if method is None else method,
            stop_angles=stop_angles(self.cam.breakpoints, self.dth),
        )

    @property
    def method(self) -> str:
        """The engine's Runge-Kutta pair for this spring model (:data:`PAIR`)."""
        return PAIR[self.spring.model]

    def atol_velocity(self, atol: float) -> np.ndarray:
        """Absolute tolerances of the velocities [m/s] for ``atol`` [m] on the displacements.

        The spring's masses: ``atol 2 pi f1 / VELOCITY_TOLERANCE_DIVISOR`` (the velocity of
        a displacement ``atol`` oscillating at a thirtieth of the first surge frequency);
        the valve train's bodies keep ``atol`` (their stiff contacts make the contact forces
        sensitive to velocity errors).

        Measured (benchmarks/valve_tolerances.py, docs/valve.md): over 112 runs per model
        (two springs, four cams, 14 speeds) the worst end-force extreme against a tight
        reference is 0.014 % of Fset for Type C (0.0087 % with ``atol`` for every
        component, which takes 1.4 times more steps) and 0.0035 % for the distributed
        chain; ``/ 10`` reaches 0.028 %, a factor 1.8 to the 0.05 % target only (and 0.27 %
        on a ramp cam before the engine landed its steps on the ramps' ends).
        """
        out = np.full(self.nfree, float(atol))
        out[: self.n_masses] = (
            atol * 2.0 * math.pi * float(self.spring.internal_parameters()["f1"]) / VELOCITY_TOLERANCE_DIVISOR
        )
        return out


def prepare(spring: ValveSpring, cam: Cam, valve_train: ValveTrain | None = None) -> SimulationSetup:
    """Sample the cam, check the lift against coil contact, and find the initial state.

    Warns when the lift drives the spring into coil contact statically (force above
    Fcon), naming the cam angle and the force; raises :class:`InputError` when it would
    drive it beyond the model's range.

    Parameters
    ----------
    spring : ValveSpring
        The spring definition (its model gives the chain).
    cam : Cam
        The cam.
    valve_train : ValveTrain, optional
        Adds the valve body with cam and seat contacts.
    """
    h, dh, ddh = cam.sampled(CAM_SAMPLES)

    def deg(i):  # the cam angle of table sample i [deg]
        return 360.0 * int(i) / CAM_SAMPLES

    p = spring.internal_parameters()
    h_cam = h
    if valve_train is not None and valve_train.ratio != 1.0:
        h = h * valve_train.ratio  # the rigid valve lift checks the spring; the engine gets the lobe lift
    i_max = int(np.argmax(h))
    open_length = spring.installed_length - h[i_max]
    if open_length < spring.min_length:
        raise InputError(
            f"cam lift {h[i_max] * 1e3:.4g} mm at {deg(i_max):.1f} deg drives the spring solid: "
            f"installed_length - lift = {open_length * 1e3:.4g} mm is below {spring.min_length * 1e3:.4g} mm, where "
            f"the static force reaches {spring.LIMIT_FORCE_FACTOR:g} Fcon"
        )
    # static force above Fcon <=> lift beyond the lift at which the static force is Fcon
    lift_fcon = spring.spring_model.lift_at_coil_contact
    if h[i_max] > lift_fcon:
        over = np.flatnonzero(h > lift_fcon)
        peak = float(series_force(spring.free_length - spring.installed_length + h[i_max], spring.chain.laws))
        warnings.warn(
            f"the cam lift drives the spring into coil contact even statically: from cam angle "
            f"{deg(over[0]):.1f} deg to {deg(over[-1]):.1f} deg the static force "
            f"exceeds Fcon = {p['Fcon']:.1f} N, peaking at {peak:.1f} N at "
            f"{deg(i_max):.1f} deg (lift {h[i_max] * 1e3:.3g} mm)",
            stacklevel=3,
        )
    y0, lash = _initial_state(spring, h_cam[0], valve_train)
    vt = valve_train.kernel_parameters(lash=lash) if valve_train is not None else np.zeros(KERNEL_SIZE)
    return SimulationSetup(spring, cam, valve_train, h_cam, dh, ddh, 2 * math.pi / CAM_SAMPLES, vt, y0)


def _initial_state(spring: ValveSpring, lift0: float, valve_train: ValveTrain | None):
    """Static equilibrium at cam angle 0: displacements from set-up, zero velocities.

    Returns the state and the lash the engine uses [m]: the train's own, or, with a
    hydraulic adjuster, the one at which the train rests on the cam with the plunger
    force (the seat carries the rest of the spring force).
    """
    setup = spring.free_length - spring.installed_length
    nm = len(spring.chain.masses)
    if valve_train is None:
        if lift0 == 0.0:  # the set-up state itself: every displacement is zero by definition
            return np.zeros(2 * nm), 0.0
        u = spring.initial_condition(setup + lift0)["displacements"]
        return np.concatenate([u, np.zeros(nm)]), 0.0
    from scipy.optimize import brentq  # (imported here: scipy.optimize costs 0.2 s of start-up)

    laws = spring.chain.laws
    vt = valve_train
    r = vt.ratio
    k_train = vt.stiffness_at_valve
    fset = spring.internal_parameters()["Fset"]

    def seat(z):
        return -vt.seat_stiffness * z if z < 0 else 0.0

    def spring_force(z):
        return float(series_force(setup + z, laws))

    z_lo = -2.0 * (fset + 1.0) / vt.seat_stiffness
    if vt.hydraulic:
        f_h = vt.hla_force
        if not f_h < fset:
            raise InputError(
                f"[valve_train] hla_preload = {f_h:g} N must be below the spring's set-up force "
                f"Fset = {fset:.1f} N: the adjuster would open the valve"
            )
        z0 = brentq(lambda z: seat(z) + f_h - spring_force(z), z_lo, 1e-6, xtol=1e-16, rtol=1e-15)
        lash = r * lift0 - z0 - f_h / k_train
        force = f_h
    else:
        lash = vt.lash

        def train(z):
            pen = r * lift0 - z - lash
            return k_train * pen if pen > 0 else 0.0

        z_hi = max(r * lift0 - lash, 0.0) + 1e-6
        z0 = brentq(lambda z: train(z) + seat(z) - spring_force(z), z_lo, z_hi, xtol=1e-16, rtol=1e-15)
        force = train(z0)
    u = spring.initial_condition(setup + z0)["displacements"]
    pos = vt.static_state(lift0, z0, force)
    return np.concatenate([u, pos, np.zeros(nm + pos.size)]), float(lash)


def check_run_settings(revolutions, points_per_revolution, rtol, atol) -> None:
    """Check the run settings of :func:`simulate` and the sweeps (raise :class:`InputError`).

    Parameters
    ----------
    revolutions : int
        Cam revolutions [-], 1 to 1000.
    points_per_revolution : int
        Output samples per revolution [-], 16 to 100 000.
    rtol : float
        Relative tolerance [-], 1e-12 to 1e-2.
    atol : float
        Absolute tolerance [m, m/s], 1e-15 to 1e-5.
    """
    number = (int, float, np.integer, np.floating)
    for name, value, lo, hi in (
        ("revolutions", revolutions, 1, 1000),
        ("points_per_revolution", points_per_revolution, 16, 100_000),
    ):
        if (
            isinstance(value, bool)
            or not isinstance(value, number)
            or not math.isfinite(value)
            or value != int(value)
            or not lo <= value <= hi
        ):
            raise InputError(f"{name} = {value!r} must be a whole number of at least {lo} and at most {hi}")
    for name, value, lo, hi in (("rtol", rtol, 1e-12, 1e-2), ("atol", atol, 1e-15, 1e-5)):
        if isinstance(value, bool) or not isinstance(value, number) or not lo <= value <= hi:
            raise InputError(
                f"{name} = {value!r} is outside the allowed range {lo:g} <= {name} <= {hi:g} "
                "(integration tolerance"
                + (
                    ": absolute, on displacements [m]; velocities get it times 2 pi f1/30)"
                    if name == "atol"
                    else ", relative)"
                )
            )


def simulate(
    spring: ValveSpring,
    cam: Cam,
    cam_rpm: float,
    revolutions: int = 3,
    *,
    valve_train: ValveTrain | None = None,
    points_per_revolution: int = 1440,
    rtol: float = DEFAULT_RTOL,
    atol: float = DEFAULT_ATOL,
    backend: str = "compiled",
    setup: SimulationSetup | None = None,
    check_elements: bool = True,
    method: str | None = None,
) -> Simulation:
    """Simulate the valve spring (or valve train) driven by the cam.

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    cam_rpm : float
        Camshaft speed [rev/min] (half the engine speed of a four-stroke engine).
    revolutions : int
        Cam revolutions [-] to integrate from static equilibrium; the last is reported and
        compared with the one before to judge periodicity.
    valve_train : ValveTrain, optional
        Adds the valve body with cam and seat contacts (lift-off, bounce).
    points_per_revolution : int
        Output resolution [-] (1440: every 0.25 deg).
    rtol, atol : float
        Integration tolerances: relative [-], and absolute on the displacements [m]; the
        velocities get ``atol 2 pi f1 / 30`` [m/s] (:meth:`SimulationSetup.atol_velocity`).
    backend : {"compiled", "scipy"}
        ``"compiled"``: the numba engine (embedded Runge-Kutta pair per model, :data:`PAIR`);
        ``"scipy"``: ``solve_ivp`` (DOP853) with the plain-Python right-hand side, the reference.
    setup : SimulationSetup, optional
        A prepared setup of the same spring, cam and valve train (:func:`prepare`), reused
        across speeds.
    check_elements : bool
        Distributed model: when coils clash, run again with half the elements and report
        how much the peak end forces change (``clash_force_element_sensitivity``,
        ``clash_forces_converged`` and a note in the summary): clash forces are a penalty
        contact on the element scale and may not be converged.
    method : {"dopri5", "tsit5", "bs3"}, optional
        The compiled engine's Runge-Kutta pair; default the model's (:data:`PAIR`: Type C
        Dormand-Prince 5(4), distributed Bogacki-Shampine 3(2)).

    Raises
    ------
    InputError
        Non-positive speed, fewer than one revolution, a lift that drives the spring solid.
    SolverError
        Integration failure, naming the speed, the time and the likely cause.
    """
    number = (int, float, np.integer, np.floating)
    if isinstance(cam_rpm, bool) or not isinstance(cam_rpm, number) or not (cam_rpm > 0 and math.isfinite(cam_rpm)):
        raise InputError(f"cam_rpm = {cam_rpm!r} must be a positive speed: a finite number [rev/min]")
    check_run_settings(revolutions, points_per_revolution, rtol, atol)
    if backend not in ("compiled", "scipy"):
        raise InputError(f"backend = {backend!r} must be 'compiled' or 'scipy'")
    if method is not None and (backend != "compiled" or method not in PAIRS):
        raise InputError(
            f"method = {method!r}: the compiled backend's pairs are {sorted(PAIRS)}"
            + ("" if backend == "compiled" else f"; backend = {backend!r} has its own (DOP853)")
        )
    revolutions, points_per_revolution = int(revolutions), int(points_per_revolution)
    # bound the work by the periods of the fastest mode: solve_ivp has no step cap (20 to
    # 70 right-hand-side calls per period: 2e4 periods take seconds to a minute); the
    # compiled engine stops at 1e7 steps (3 to 5 steps per period)
    max_cycles = 2.0e4 if backend == "scipy" else 2.0e6
    f_top = spring.spring_model.fastest_mode
    if valve_train is not None:
        f_top = max(f_top, valve_train.highest_frequency())
    cycles = revolutions * 60.0 / cam_rpm * f_top
    if cycles > max_cycles:
        raise InputError(
            f"cam_rpm = {cam_rpm:g} is too slow for backend = {backend!r}: {revolutions} revolutions last "
            f"{revolutions * 60.0 / cam_rpm:.4g} s, {cycles:.3g} periods of the fastest mode ({f_top:.0f} Hz), "
            f"more than the {max_cycles:g} this backend integrates in bounded time; "
            + ("use backend = 'compiled' or " if backend == "scipy" else "give fewer revolutions or ")
            + f"at least {revolutions * 60.0 * f_top / max_cycles:.3g} rev/min"
        )
    if setup is None:
        setup = prepare(spring, cam, valve_train)
        if cam.law == "table":
            cam.check_resolution(cam_rpm, float(spring.modes(spring.installed_length, 1)[0]))
    omega = rpm_to_omega(cam_rpm)
    period = 2 * math.pi / omega
    n = points_per_revolution
    if backend == "compiled":
        method = setup.method if method is None else method
        extra, prev, status, t_end, steps, mon = setup.run([omega], revolutions, n, rtol=rtol, atol=atol, method=method)
        info = dict(status=int(status[0]), t=float(t_end[0]), steps=int(steps[0]), method=method)
        if info["status"] != 0 or not (np.isfinite(extra).all() and np.isfinite(prev).all()):
            raise _solver_error(cam_rpm, omega, info)
        time = (revolutions - 1) * period + np.arange(n) * (period / n)
        sim = _from_extra(setup, cam_rpm, revolutions, time, extra[0], prev[0], info)
        sim.monitor = _monitor_record(mon, 0, omega, revolutions)
        if check_elements:
            _check_element_count(sim, cam, cam_rpm, revolutions, valve_train, points_per_revolution, rtol, atol)
        return sim
    keep = min(2, revolutions)
    t_keep = (revolutions - keep) * period + np.arange(keep * n) * (period / n)
    t_out = t_keep if t_keep[0] == 0.0 else np.concatenate([[0.0], t_keep])
    states, info = integrate_scipy(
        setup.y0,
        t_out,
        setup.args(omega),
        rtol=rtol,
        atol=atol,
        h_max=period * MAX_STEP_FRACTION,
        atol_velocity=setup.atol_velocity(atol),
    )
    if info["status"] != 0 or not np.all(np.isfinite(states)):
        raise _solver_error(cam_rpm, omega, info)
    return _postprocess(setup, cam_rpm, revolutions, t_keep, states[-keep * n :], info, n, keep)


def _check_element_count(sim, cam, cam_rpm, revolutions, valve_train, points, rtol, atol) -> None:
    """Distributed model with clashing coils: the peak end forces with half the elements."""
    sp = sim.spring
    if sp.model != "distributed" or not sim.summary.get("clashing_coils"):
        return
    half = max(sp.elements // 2, 10)
    if half == sp.elements:
        return
    coarse_spring = _coarser(sp, half)  # its set-up is kept
    coarse = simulate(
        coarse_spring,
        cam,
        cam_rpm,
        revolutions,
        valve_train=valve_train,
        points_per_revolution=points,
        rtol=rtol,
        atol=atol,
        check_elements=False,
        method=sim.info.get("method"),
    ).summary
    sim.element_check = dict(
        elements=half, max_retainer_force_N=coarse["max_retainer_force_N"], max_seat_force_N=coarse["max_seat_force_N"]
    )
    sim.__dict__.pop("_summary_cache", None)  # the summary now includes the check


@functools.lru_cache(maxsize=8)
def _coarser(spring: ValveSpring, elements: int) -> ValveSpring:
    """``spring`` with ``elements`` elements, kept for the last few springs (an explicit cache:
    the coarse spring's model and set-up are reused by every run that checks it)."""
    return spring.replace(elements=elements)


def _solver_error(cam_rpm: float, omega: float, info: dict) -> SolverError:
    t = info["t"]
    angle = math.degrees(omega * t) % 360.0
    why = STATUS.get(info["status"], info.get("message", "failed"))
    cause = {
        1: "the step size became very small for very long: the spring is driven deep into coil contact, or the "
        "tolerances are too tight",
        2: "the element stiffness became extreme (deep coil contact) or the contact parameters are inconsistent",
        3: "the response diverged: check masses, stiffnesses and contact parameters",
    }.get(info["status"], "see the message")
    return SolverError(
        f"valve simulation at {cam_rpm:g} cam rpm failed at t = {t:.6g} s (cam angle {angle:.2f} deg, "
        f"after {info['steps']} steps): {why}; likely cause: {cause}"
    )


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
    chain = setup.spring.chain
    nf = setup.nfree
    omega = np.asarray(omega, dtype=float)[..., None]
    lift, dlift_dth = hermite_eval(theta, setup.cam_h, setup.cam_dh, setup.cam_ddh, setup.dth)
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
        out["static"] = setup.static_force(u_top)
        out.update(train_response(setup.vt, lift, dlift, u[..., nm:, :], v[..., nm:, :]))
    else:
        out["static"] = setup.static_force(lift)
    out["displacement"] = u[..., :nm, :]
    return out


def _from_extra(setup: SimulationSetup, cam_rpm, revolutions, time, e, previous, info) -> Simulation:
    """Build the results from the compiled kernel's own force evaluation (:data:`engine.EXTRA`)
    over the last revolution, ``e``; ``previous`` is the retainer force over the one before."""
    fset = setup.spring.internal_parameters()["Fset"]
    lay = extra_layout(setup.n_masses)
    ne = setup.n_masses + 1
    force, x = e[:, lay["force"]].T, e[:, lay["compression"]].T
    prev_err = float(np.max(np.abs(e[:, ne - 1] - previous)) / fset) if previous.size else math.nan
    lift = e[:, lay["lift"]]
    if setup.valve_train is None:  # the lift of the cam table at the output angles: kept per cam
        static = setup.static_force_along_cam(time.size)
    else:
        static = setup.static_force(e[:, lay["top_displacement"]])
    sim = Simulation(
        spring=setup.spring,
        cam=setup.cam,
        valve_train=setup.valve_train,
        cam_rpm=cam_rpm,
        revolutions=revolutions,
        time=time,
        cam_angle=output_angles(time.size),
        lift=lift,
        retainer_force=force[-1],
        seat_force=force[0],
        static_force=static,
        element_compression=x,
        element_force=force,
        element_contact=x >= setup.spring.spring_model.contact_gaps[:, None],
        mass_displacement=e[:, lay["displacement"]].T,
        periodicity_error=prev_err,
        info=info,
    )
    if setup.valve_train is not None:
        sim.valve_lift = e[:, lay["top_displacement"]]
        sim.cam_contact_force = e[:, lay["cam_contact_force"]]
        sim.valve_seat_force = e[:, lay["valve_seat_force"]]
    return sim


def _monitor_record(mon: dict, i: int, omega: float, revolutions: int) -> dict:
    """The monitor outputs of speed ``i`` in the terms of the last revolution.

    Times become cam angles within the revolution [rad] (``t0`` the revolution's start);
    events open at the window's start or end are marked by ``None`` times there.
    """
    from .engine import EXT

    ext = dict(zip(EXT, mon["ext"][i].tolist()))
    t0 = (revolutions - 1) * 2 * math.pi / omega
    rows = mon["events"][i, : int(mon["n_events"][i])]
    return dict(ext=ext, events=rows.copy(), omega=omega, t0=t0)


def _postprocess(setup: SimulationSetup, cam_rpm, revolutions, t_keep, states, info, n, keep) -> Simulation:
    omega = rpm_to_omega(cam_rpm)
    theta = omega * t_keep
    r = chain_response(setup, omega, theta, states)
    last = slice((keep - 1) * n, keep * n)
    fset = setup.spring.internal_parameters()["Fset"]
    force = r["force"]
    prev_err = float(np.max(np.abs(force[-1, last] - force[-1, :n])) / fset) if keep == 2 else math.nan
    sim = Simulation(
        spring=setup.spring,
        cam=setup.cam,
        valve_train=setup.valve_train,
        cam_rpm=cam_rpm,
        revolutions=revolutions,
        time=t_keep[last],
        cam_angle=np.mod(theta[last], 2 * math.pi),
        lift=r["lift"][last],
        retainer_force=force[-1, last],
        seat_force=force[0, last],
        static_force=r["static"][last],
        element_compression=r["compression"][:, last],
        element_force=force[:, last],
        element_contact=r["contact"][:, last],
        mass_displacement=r["displacement"][:, last],
        periodicity_error=prev_err,
        info=info,
    )
    if setup.valve_train is not None:
        sim.valve_lift = r["valve_lift"][last]
        sim.cam_contact_force = r["cam_contact_force"][last]
        sim.valve_seat_force = r["valve_seat_force"][last]
    return sim


def float_speed(
    spring: ValveSpring,
    cam: Cam,
    valve_train: ValveTrain,
    cam_rpm,
    *,
    revolutions: int = 3,
    resolution: float = 1.0,
    points_per_revolution: int = 1440,
    progress_quiet: bool = True,
) -> FloatSpeedResult:
    """Float speed: the lowest cam speed at which the follower separates from the cam.

    Scans the speeds ``cam_rpm`` (ascending), then bisects between the last speed without
    lift-off and the first with it down to ``resolution`` [rev/min] (at most
    ``MAX_HALVINGS`` halvings).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain
        The valve body whose contact with the cam may open.
    cam_rpm : array_like
        Camshaft speeds to scan [rev/min], positive.
    revolutions : int
        Cam revolutions per simulation [-] (see :func:`simulate`).
    resolution : float
        Width of the final bracket [rev/min], positive.
    points_per_revolution : int
        Output resolution of each simulation [-].
    progress_quiet : bool
        No progress bar.

    Returns
    -------
    FloatSpeedResult
        ``float_cam_rpm`` (None if no lift-off in the range), ``bracket`` (speeds either
        side), and per scanned speed ``cam_rpm`` and ``min_cam_contact_force_N``.
    """
    from ..core.progress import progress

    max_halvings = 40
    try:
        rpms = np.sort(np.atleast_1d(np.asarray(cam_rpm, dtype=float)))
    except (TypeError, ValueError):
        raise InputError(f"cam_rpm = {cam_rpm!r} must be a speed or a list of speeds [rev/min]") from None
    if rpms.ndim != 1 or rpms.size == 0 or not np.all(np.isfinite(rpms)) or rpms[0] <= 0:
        raise InputError(f"cam_rpm = {cam_rpm!r} must hold at least one speed, all positive and finite [rev/min]")
    if (
        isinstance(resolution, bool)
        or not isinstance(resolution, (int, float, np.integer, np.floating))
        or not (math.isfinite(resolution) and resolution > 0)
    ):
        raise InputError(f"resolution = {resolution!r} must be a positive, finite speed [rev/min]")
    finest = max(float(rpms[-1] - rpms[0]), float(rpms[-1])) / 2.0**max_halvings
    if resolution < finest:
        raise InputError(
            f"resolution = {resolution:g} rev/min is finer than the bisection reaches in {max_halvings} "
            f"halvings of the scanned range: it must be at least {finest:.3g} rev/min"
        )
    setup = prepare(spring, cam, valve_train)

    def min_force(rpm):
        sim = simulate(
            spring,
            cam,
            rpm,
            revolutions,
            valve_train=valve_train,
            setup=setup,
            points_per_revolution=points_per_revolution,
            check_elements=False,
        )
        sm = sim.summary
        return sm["min_cam_contact_force_N"], bool(sm["liftoff"])

    scanned, forces = [], []
    first = None
    for rpm in progress(rpms, total=rpms.size, desc="float speed scan", quiet=progress_quiet):
        f, lifted = min_force(rpm)
        scanned.append(float(rpm))
        forces.append(f)
        if lifted:
            first = len(scanned) - 1
            break

    def result(float_rpm, bracket):
        return FloatSpeedResult(scanned, forces, float_rpm, bracket, float(resolution))

    if first is None:
        return result(None, None)
    if first == 0:
        return result(scanned[0], [None, scanned[0]])
    lo, hi = scanned[first - 1], scanned[first]
    for _ in range(max_halvings):  # bounded: the check above makes this many enough
        if hi - lo <= resolution:
            break
        mid = 0.5 * (lo + hi)
        if min_force(mid)[1]:
            hi = mid
        else:
            lo = mid
    return result(hi, [lo, hi])


def _static_accelerations(setup: SimulationSetup, theta: float, u: np.ndarray) -> np.ndarray:
    """Accelerations [m/s^2] of the masses at rest at positions ``u`` [m], cam at ``theta`` [rad]."""
    from .engine import NO_EXTRA, chain_rhs, model_of, train_of

    nf = setup.nfree
    omega = 1e-9  # quasi-static: the cam's velocity terms vanish
    y = np.concatenate([u, np.zeros(nf)])
    out = np.empty(2 * nf)
    chain_rhs(theta / omega, y, model_of(setup.args(omega)), omega, train_of(setup.vt), out, NO_EXTRA)
    return out[nf:]


def _frequencies(setup: SimulationSetup, theta: float, u: np.ndarray, dofs: np.ndarray, count: int) -> list:
    """Natural frequencies [Hz] of the system linearised at rest at ``u`` (central differences
    of the accelerations over the degrees of freedom ``dofs``; the others held)."""
    from scipy.linalg import eigvals

    h = 1e-9
    jac = np.empty((dofs.size, dofs.size))
    for c, j in enumerate(dofs):
        up, dn = u.copy(), u.copy()
        up[j] += h
        dn[j] -= h
        jac[:, c] = (_static_accelerations(setup, theta, up)[dofs] - _static_accelerations(setup, theta, dn)[dofs]) / (
            2 * h
        )
    w2 = np.sort(np.real(eigvals(-jac)))
    w2 = w2[w2 > (2 * math.pi * 1.0) ** 2]  # rigid-body (unloaded) motions have none
    return [float(math.sqrt(v) / (2 * math.pi)) for v in w2[:count]]


def natural_frequencies(spring: ValveSpring, cam: Cam, valve_train: ValveTrain | None = None, count: int = 8) -> dict:
    """Natural frequencies of spring and valve train, linearised on the base circle and at full lift.

    The same element and contact laws as the simulation (:func:`springdyn.valve.engine.chain_rhs`),
    linearised by central differences of the accelerations at static equilibrium: on the
    base circle (the initial state of :func:`simulate`) and at the cam's largest lift (the
    static equilibrium found from the rigid-train guess).  With a mechanical lash the lever
    and lifter rest unloaded on the base circle: their modes are not defined there and
    only the spring and the seated valve are linearised (a note says so).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain, optional
        Without it, the spring alone between the seat and the cam-driven retainer.
    count : int
        Frequencies to return per state [-].

    Returns
    -------
    dict
        ``base_circle_Hz``, ``full_lift_Hz`` (ascending lists), ``full_lift_cam_angle_deg``,
        ``notes``.
    """
    from scipy.optimize import root

    setup = prepare(spring, cam, valve_train)
    nf = setup.nfree
    nm = setup.n_masses
    notes = []
    u0 = setup.y0[:nf]
    dofs = np.arange(nf)
    if valve_train is not None and not valve_train.hydraulic and valve_train.lash > 0 and nf > nm + 1:
        dofs = np.arange(nm + 1)
        notes.append(
            "base circle: the lash is open and the lever/lifter rest unloaded on the cam; only the spring "
            "and the seated valve are linearised there"
        )
    base = _frequencies(setup, 0.0, u0, dofs, count)
    i_max = int(np.argmax(setup.cam_h))
    theta = i_max * setup.dth
    h_max = float(setup.cam_h[i_max])
    # rigid-train guess, then the static equilibrium of every mass
    sp_setup = spring.free_length - spring.installed_length
    if valve_train is None:
        z = h_max
        guess = spring.initial_condition(sp_setup + z)["displacements"]
    else:
        f = float(setup.static_force(valve_train.ratio * h_max))
        z = valve_train.ratio * h_max - setup.vt[VT_LASH] - f / valve_train.stiffness_at_valve
        guess = np.concatenate(
            [spring.initial_condition(sp_setup + z)["displacements"], valve_train.static_state(h_max, z, f)]
        )
    scale = max(h_max, 1e-3)
    mass = np.asarray(spring.chain.masses, dtype=float)
    if valve_train is not None:
        mass = np.concatenate([mass, [setup.vt[VT_MASS], setup.vt[VT_M_LEVER], setup.vt[VT_M_LIFTER]][: nf - nm]])

    def residual(x):  # forces [N]: better scaled than accelerations across light and heavy masses
        return _static_accelerations(setup, theta, x * scale) * mass

    sol = root(residual, guess / scale, method="hybr", options=dict(xtol=1e-14, maxfev=200 * (nf + 1)))
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-6 * spring.internal_parameters()["Fset"]:
        sol = root(residual, guess / scale, method="lm", options=dict(xtol=1e-15, ftol=1e-15, maxiter=200 * (nf + 1)))
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-6 * spring.internal_parameters()["Fset"]:
        notes.append(f"full lift: the static equilibrium was not found ({sol.message}); its frequencies are omitted")
        full = []
    else:
        full = _frequencies(setup, theta, sol.x * scale, np.arange(nf), count)
    return dict(base_circle_Hz=base, full_lift_Hz=full, full_lift_cam_angle_deg=math.degrees(theta), notes=notes)


def resonance_speeds(frequencies, cam_rpm_min: float, cam_rpm_max: float, max_order: int = 20) -> list:
    """Cam speeds where a cam harmonic meets a natural frequency: ``60 f / N`` [rev/min].

    Parameters
    ----------
    frequencies : sequence of float
        Natural frequencies [Hz].
    cam_rpm_min, cam_rpm_max : float
        Speed range [rev/min].
    max_order : int
        Highest cam order ``N`` [-] (20: higher harmonics of a valve-train cam are weak).

    Returns
    -------
    list of dict
        ``mode`` (1-based), ``frequency_Hz``, ``order``, ``cam_rpm``, ascending in speed.

    Examples
    --------
    >>> [r["cam_rpm"] for r in resonance_speeds([450.0], 2000, 3000)]
    [2076.923076923077, 2250.0, 2454.5454545454545, 2700.0, 3000.0]
    """
    rows = []
    for m, f in enumerate(frequencies, start=1):
        for n in range(1, max_order + 1):
            rpm = 60.0 * f / n
            if cam_rpm_min <= rpm <= cam_rpm_max:
                rows.append(dict(mode=m, frequency_Hz=float(f), order=n, cam_rpm=rpm))
    return sorted(rows, key=lambda r: r["cam_rpm"])
