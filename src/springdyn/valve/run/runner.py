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

from ...core.errors import SolverError
from ..engine import STATUS, integrate_speeds
from .periodicity import BAND_REVOLUTIONS
from .settings import BS3_MIN_ELEMENTS, MAX_STEP_FRACTION, PAIR, VELOCITY_TOLERANCE_DIVISOR, RunSettings
from .setup import SimulationSetup

__all__ = ["run_speeds", "engine_args", "velocity_tolerance", "runge_kutta_pair", "solver_error"]


def engine_args(setup: SimulationSetup, omega: float) -> tuple:
    """The engine's argument tuple of a set-up at a speed (:func:`springdyn.valve.engine.model_of` reads it).

    Parameters
    ----------
    setup : SimulationSetup
        The spring's chain, the cam table and the train's parameters.
    omega : float
        Cam speed [rad/s].
    """
    ch = setup.spring.spring_model.chain
    t = setup.table
    return (ch.masses, ch.laws, ch.setup_compressions, ch.c0_array, t.h, t.dh, t.ddh, t.dth, omega, setup.vt)


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


def run_speeds(
    setup: SimulationSetup, omegas, settings: RunSettings, points: int, *, warm_start: bool = False, y0=None
) -> dict:
    """Integrate the speeds ``omegas`` [rad/s] with the compiled engine to their periodic
    steady state (``settings.revolutions`` None) or for ``settings.revolutions``,
    monitoring the last revolution (true extremes and events on the dense output, see
    :func:`springdyn.valve.engine.integrate_speeds`).

    Parameters
    ----------
    setup : SimulationSetup
        The prepared spring, cam and train.
    omegas : array_like
        Cam speeds [rad/s].
    settings : RunSettings
        Revolutions, periodicity, tolerances and pair.
    points : int
        Output samples per revolution [-].
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


def solver_error(cam_rpm: float, omega: float, info: dict) -> SolverError:
    """The message of a failed integration: the speed, the time and cam angle, the cause.

    Parameters
    ----------
    cam_rpm : float
        Cam speed [rev/min].
    omega : float
        Cam speed [rad/s].
    info : dict
        The engine's ``status``, ``t`` [s] and ``steps`` (and ``message`` from SciPy).
    """
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
