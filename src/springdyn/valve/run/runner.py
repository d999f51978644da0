"""The one way the run wing calls the compiled engine: :func:`run_speeds`.

A prepared set-up (:func:`springdyn.valve.run.setup.prepare`) and a
:class:`~springdyn.valve.run.settings.RunSettings` go in; the engine integrates each speed to
its periodic steady state (or for the set revolutions) and returns the last revolution's
outputs (:func:`springdyn.valve.engine.integrate_speeds`).  One speed
(:func:`~springdyn.valve.run.simulation.simulate`), the chunks of a sweep, the float search and
the start of a run-up all run through it.  Beside it: the engine's argument tuple, the
velocity tolerances and the Runge-Kutta pair of a set-up, and the message of a failed run.
"""

from __future__ import annotations

import math

import numpy as np

from ...core.docstrings import ParameterDocs
from ...core.errors import SolverError
from ...core.units import omega_to_rpm
from ..engine import STATUS, integrate_speeds
from .periodicity import BAND_REVOLUTIONS, PeriodicStates
from .settings import BS3_MIN_ELEMENTS, MAX_STEP_FRACTION, PAIR, VELOCITY_TOLERANCE_DIVISOR, RunSettings
from .setup import SimulationSetup, static_force_at_lift

__all__ = ["run_speeds", "run_speeds_from", "engine_args", "velocity_tolerance", "runge_kutta_pair", "solver_error"]


def engine_args(setup: SimulationSetup, omega: float) -> tuple:
    """The engine's argument tuple of a set-up at a speed (:func:`springdyn.valve.engine.model_of` reads it).

    Parameters
    ----------
    setup : SimulationSetup
        The spring's chain, the cam table and the train's parameters.
    omega : float
        Cam speed [rad/s].
    """
    model = setup.spring.spring_model
    ch = model.chain
    t = setup.table
    args = (ch.masses, ch.laws, ch.setup_compressions, ch.c0_array, t.h, t.dh, t.ddh, t.dth, omega, setup.vt)
    if setup.n_chains > 1:  # a spring pack: its chains' first masses and its friction rows
        return (*args, ch.chains, model.damper)
    return args


def runge_kutta_pair(setup: SimulationSetup, settings: RunSettings | None = None) -> str:
    """The engine's Runge-Kutta pair for a set-up: the settings' ``method``, else the spring
    model's (:data:`~springdyn.valve.run.settings.PAIR`); a distributed chain of fewer than
    :data:`~springdyn.valve.run.settings.BS3_MIN_ELEMENTS` elements steps with Dormand-Prince.

    Parameters
    ----------
    setup : SimulationSetup
        The spring (its model and element count).
    settings : RunSettings, optional
        The run settings (their ``method``).
    """
    if settings is not None and settings.method is not None:
        return settings.method
    sp = setup.spring
    if sp.model == "distributed" and sp.elements < BS3_MIN_ELEMENTS:
        return "dopri5"
    return PAIR[sp.model]


def velocity_tolerance(setup: SimulationSetup, atol: float) -> np.ndarray:
    """Absolute tolerances of the velocities [m/s] for ``atol`` [m] on the displacements.

    The spring's masses: ``atol 2 pi f1 / VELOCITY_TOLERANCE_DIVISOR`` (the velocity of
    a displacement ``atol`` oscillating at a thirtieth of the first surge frequency);
    the valve train's bodies keep ``atol`` (their stiff contacts make the contact forces
    sensitive to velocity errors).

    Measured (benchmarks/valve_tolerances.py, docs/valve-dynamics.md, "Tolerances"): over 112 runs per model
    (two springs, four cams, 14 speeds) the worst end-force extreme against a tight
    reference is 0.014 % of Fset for Type C (0.0087 % with ``atol`` for every
    component, which takes 1.4 times more steps) and 0.0035 % for the distributed
    chain; ``/ 10`` reaches 0.028 %, a factor 1.8 to the 0.05 % target only (and 0.27 %
    on a ramp cam before the engine landed its steps on the ramps' ends).

    Parameters
    ----------
    setup : SimulationSetup
        The spring (its first surge frequency f1) and the degrees of freedom.
    atol : float
        Absolute tolerance of the displacements [m].
    """
    out = np.full(setup.nfree, float(atol))
    out[: setup.n_masses] = (
        atol * 2.0 * math.pi * float(setup.spring.spring_model.internal_parameters()["f1"]) / VELOCITY_TOLERANCE_DIVISOR
    )
    return out


#: The parameters of the engine calls, described once (springdyn.core.docstrings).
_DOCS = ParameterDocs(
    """
    setup : SimulationSetup
        The prepared spring, cam and train.
    omegas : array_like
        Cam speeds [rad/s].
    settings : RunSettings
        Revolutions, periodicity, tolerances and pair.
    points : int
        Output samples per revolution [-].
"""
)


@_DOCS.fill
def run_speeds(
    setup: SimulationSetup, omegas, settings: RunSettings, points: int, *, warm_start: bool = False, y0=None
) -> dict:
    """Integrate the speeds ``omegas`` [rad/s] with the compiled engine to their periodic
    steady state (``settings.revolutions`` None) or for ``settings.revolutions``,
    monitoring the last revolution (true extremes and events on the dense output, see
    :func:`springdyn.valve.engine.integrate_speeds`).

    Parameters
    ----------
    {setup omegas settings points}
    warm_start : bool
        Start each speed from the state the one before ended in (speeds ascending).
    y0 : ndarray, optional
        The state the first speed starts from [m, m/s] (default: the set-up's equilibrium).

    Returns
    -------
    dict
        :func:`springdyn.valve.engine.integrate_speeds`'s outputs, ``periodicity`` as a fraction
        of Fset.
    """
    fset = setup.spring.spring_model.internal_parameters()["Fset"]
    rtol, atol = settings.tolerances(setup.valve_train)
    periodic = settings.periodic
    res = integrate_speeds(
        setup.y0 if y0 is None else y0,
        omegas,
        settings.most_revolutions,
        points,
        engine_args(setup, 0.0),
        rtol=rtol,
        atol=atol,
        max_step_fraction=MAX_STEP_FRACTION,
        gaps=setup.spring.spring_model.contact_gaps,
        atol_velocity=velocity_tolerance(setup, atol),
        method=runge_kutta_pair(setup, settings),
        stop_angles=setup.table.stop_angles(setup.breakpoints),
        periodicity_tol=settings.periodicity_tol * fset if periodic else 0.0,
        warm_start=warm_start,
        band_revolutions=BAND_REVOLUTIONS if periodic else 0,
    )
    res["periodicity"] = res["periodicity"] / fset
    return res


@_DOCS.fill
def run_speeds_from(setup: SimulationSetup, omegas, settings: RunSettings, points: int, starts: PeriodicStates) -> dict:
    """:func:`run_speeds` with warm starts: each speed from the known periodic state nearest
    in speed (:meth:`PeriodicStates.start`; from rest where none is near), its own state then
    recorded into ``starts`` (a later speed, or the next design, starts from it).

    One engine call per speed (the engine takes one initial state per call); the outputs are
    those of :func:`run_speeds` with the speeds stacked.

    Parameters
    ----------
    {setup omegas settings points}
    starts : PeriodicStates
        The known periodic states (the set-up's own and a neighbouring design's); receives
        the states of these speeds.
    """
    omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
    if omegas.size == 0:
        return run_speeds(setup, omegas, settings, points)
    parts = []
    for omega in omegas:
        rpm = float(omega_to_rpm(omega))
        res = run_speeds(setup, omega[None], settings, points, y0=starts.start(setup, rpm))
        if res["status"][0] == 0:
            starts.add(rpm, res["state"][0], setup.y0)
        parts.append(res)
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


#: Cam orders the spring's first surge mode keeps above the cam speed in valve trains (fewer:
#: the spring surges hard, a likely cause of a failed run).
SURGE_ORDERS = 10.0


def kinematic_float_rpm(setup: SimulationSetup) -> float | None:
    """The cam speed [rev/min] above which the spring's static force no longer decelerates the
    valve train's moving mass over the nose (the rigid train's kinematic limit, ``F_s(z) = m r
    omega^2 |h''|`` at the worst cam angle; the valve floats near it).  None without a train.

    Parameters
    ----------
    setup : SimulationSetup
        The spring, cam table and valve train.
    """
    vt = setup.valve_train
    if vt is None:
        return None
    table = setup.table
    r = vt.ratio
    closing = table.ddh < 0.0  # where the lobe decelerates the train (over the nose)
    if not np.any(closing):
        return None
    lift = np.maximum(r * table.h[closing] - vt.lash, 0.0)
    force = static_force_at_lift(setup, lift)
    mass = vt.moving_mass + setup.spring.spring_model.internal_parameters()["M"] / 3.0
    omega2 = force / (mass * r * -table.ddh[closing])
    return float(math.sqrt(float(np.min(omega2))) * 60.0 / (2.0 * math.pi))


def likely_causes(setup: SimulationSetup | None, cam_rpm: float) -> list[str]:
    """What in the run's own state makes an integration fail, in words (first the likeliest):
    the speed (above the kinematic float speed, or the surge mode few cam orders above it), the
    gas pressure, the cam driving the spring into coil contact statically.  Empty when none
    applies.

    Parameters
    ----------
    setup : SimulationSetup or None
        The run's spring, cam, train and gas force.
    cam_rpm : float
        Cam speed [rev/min].
    """
    if setup is None:
        return []
    causes = []
    spring = setup.spring.spring_model
    floats = kinematic_float_rpm(setup)
    if floats is not None and cam_rpm > floats:
        causes.append(
            f"the speed: {cam_rpm:g} cam rpm is above the train's kinematic float speed, about {floats:.0f} cam rpm "
            "(the spring's force no longer holds the train on the nose): the valve leaves the cam and lands hard"
        )
    f1 = float(spring.first_mode_installed)
    orders = f1 * 60.0 / cam_rpm
    if orders < SURGE_ORDERS:
        causes.append(
            f"the speed: the spring's first surge mode ({f1:.0f} Hz) is only {orders:.1f} cam orders above "
            f"{cam_rpm:g} cam rpm (valve trains keep {SURGE_ORDERS:g} or more): the coils surge hard and clash"
        )
    if setup.gas_force is not None:
        fset = float(spring.internal_parameters()["Fset"])
        peak = float(np.max(setup.gas_force.force))
        if peak > fset:
            causes.append(
                f"the gas pressure: up to {peak:.0f} N on the valve head against the spring's {fset:.0f} N at "
                "installed length (the cam opens the valve against it)"
            )
    r = setup.valve_train.ratio if setup.valve_train is not None else 1.0
    depth = float(np.max(setup.table.h)) * r - float(spring.lift_at_coil_contact)
    if depth > 0.0:
        causes.append(
            f"coil contact: the cam drives the spring {depth * 1e3:.3g} mm past the length of its coil-contact "
            "force even statically"
        )
    return causes


def solver_error(cam_rpm: float, omega: float, info: dict, setup: SimulationSetup | None = None) -> SolverError:
    """The message of a failed integration: the speed, the time and cam angle, the cause.

    The likely cause is read from the run's state (:func:`likely_causes`); without a cause
    there, the tolerances or the contact parameters.

    Parameters
    ----------
    cam_rpm : float
        Cam speed [rev/min].
    omega : float
        Cam speed [rad/s].
    info : dict
        The engine's ``status``, ``t`` [s] and ``steps`` (and ``message`` from SciPy).
    setup : SimulationSetup, optional
        The run's spring, cam, train and gas force (the state the cause is read from).
    """
    t = info["t"]
    angle = math.degrees(omega * t) % 360.0
    why = STATUS.get(info["status"], info.get("message", "failed"))
    causes = likely_causes(setup, cam_rpm)
    cause = (
        "; or ".join(causes)
        if causes
        else {
            1: "the tolerances are too tight for the run (--rtol, --atol), or a contact is far stiffer than the "
            "rest of the train",
            2: "the contact parameters (contact stiffnesses, damping) are inconsistent with the masses, or the "
            "tolerances are too tight",
            3: "the response diverged: check masses, stiffnesses and contact parameters",
        }.get(info["status"], "see the message")
    )
    return SolverError(
        f"valve simulation at {cam_rpm:g} cam rpm failed at t = {t:.6g} s (cam angle {angle:.2f} deg, "
        f"after {info['steps']} steps): {why}; likely cause: {cause}"
    )
