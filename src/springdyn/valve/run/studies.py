"""Speed studies of one design: a sweep refined where its figures are decided.

A tolerance study (:mod:`springdyn.valve.design.tolerances`) asks of each variant what a
designer asks of a spring: its float speed to a resolution, its largest retainer force and
smallest Goodman safety in service (a resonance's, which can lie between two swept speeds),
and where its coils start to clash.  :func:`speed_study` answers by a sweep of the speeds, the
float speed narrowed by a bracketed search (:func:`springdyn.valve.run.float_search.float_speed_near`)
and the worst speeds' neighbourhoods refined by halving the step :data:`REFINEMENTS` times;
:func:`variant_float_speed` searches a variant's float speed near a guess (four to five speeds,
not a sweep).
"""

from __future__ import annotations

import warnings

import numpy as np

from . import verdicts
from .float_search import FLOAT_RESOLUTION, float_speed_near
from .periodicity import PeriodicStates
from .separation import float_speed_of_scan
from .setup import prepare
from .sweeps import sweep

__all__ = ["speed_study", "variant_float_speed", "REFINEMENTS"]

#: Halvings of the speed step around the swept speeds with the smallest Goodman safety and the
#: largest retainer force (:func:`speed_study`): both are a resonance's, which can lie between
#: two swept speeds.
REFINEMENTS = 2


def speed_study(
    spring,
    cam,
    valve_train,
    speeds,
    rated_rpm: float | None = None,
    resolution: float = FLOAT_RESOLUTION,
    max_clash_severity: float | None = None,
    periodicity_tol: float | None = None,
    starts: PeriodicStates | None = None,
) -> dict:
    """A design over its speeds [rev/min]: the float speed to ``resolution``, the smallest
    Goodman safety and the largest retainer force up to ``rated_rpm`` (default: all), the lowest
    speed with coil clash (a severity above ``max_clash_severity``,
    :func:`springdyn.valve.run.verdicts.coil_clash`) and the largest severity.

    The speeds are swept (:func:`springdyn.valve.sweep`); the float speed, the lowest swept
    speed from which the valve leaves the cam over the nose at every higher one, is then
    narrowed to ``resolution`` between it and the swept speed below
    (:func:`springdyn.valve.run.float_search.float_speed_near`); the smallest Goodman safety and
    the largest retainer force come from the swept speeds up to ``rated_rpm``, ``rated_rpm``
    itself and, around the worst of each, the step halved :data:`REFINEMENTS` times (a
    resonance between two swept speeds).

    Parameters
    ----------
    spring : ValveSpring
        The design [-].
    cam : Cam
        The cam [-].
    valve_train : ValveTrain or None
        The train (float speed) [-].
    speeds : array_like
        Cam speeds [rev/min], ascending.
    rated_rpm : float, optional
        The highest speed in service [rev/min] (above it the valve may float and the spring is
        not loaded in service).
    resolution : float
        Width of the float speed's final bracket [rev/min].
    max_clash_severity : float, optional
        Largest clash severity that is no clash [fraction of Fset] (default
        :data:`springdyn.valve.run.verdicts.MAX_CLASH_SEVERITY`).
    periodicity_tol : float, optional
        The periodic steady state each speed runs to [fraction of Fset] (default the run's,
        :data:`springdyn.valve.run.periodicity.PERIODICITY_TOL`).
    starts : PeriodicStates, optional
        Warm starts: every speed (swept, searched, refined) from the nearest known periodic
        state (e.g. the nominal design's at the same speed), its own recorded there; the
        figures agree with cold starts' within the periodicity tolerance (float speed: within
        ``resolution``).

    Returns
    -------
    dict
        ``float_cam_rpm`` (None: no float within the speeds) [rev/min], ``max_retainer_force``
        [N], ``goodman_safety`` [-], ``clash_onset_cam_rpm`` (None: no clash) [rev/min],
        ``max_clash_severity`` (the largest over the swept speeds) [fraction of Fset],
        ``periodicity`` (the largest residual of any speed run [fraction of Fset]) and
        ``simulations`` (the speeds run).
    """
    tol = {} if periodicity_tol is None else dict(periodicity_tol=float(periodicity_tol))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sw = sweep(spring, cam, speeds, valve_train=valve_train, workers=1, starts=starts, **tol)
    t = sw.summary_table()
    rpm = np.asarray(t["cam_rpm"], dtype=float)
    severity = np.asarray(t["clash_severity"], dtype=float)
    clash = np.flatnonzero(verdicts.clashes(severity, max_clash_severity))
    f = float_speed_of_scan(rpm, t["nose_separation"]) if valve_train is not None else None
    periodicity = float(np.max(np.asarray(t["periodicity_error"], dtype=float)))
    k = -1 if f is None else int(np.flatnonzero(rpm == f)[0])
    runs = rpm.size
    if k > 0 and f - rpm[k - 1] > resolution:
        near = float_speed_near(
            prepare(spring, cam, valve_train),
            0.5 * (rpm[k - 1] + f),
            rpm[k - 1],
            f,
            resolution=resolution,
            starts=starts,
            **tol,
        )
        f = near["float_cam_rpm"]
        periodicity = max(periodicity, near["periodicity"])
        runs += near["evaluations"]
    service = rpm <= (rpm[-1] if rated_rpm is None else max(rated_rpm, rpm[0]))
    worst = {
        float(r): (float(g), float(x))
        for r, g, x in zip(
            rpm[service],
            np.asarray(t["fatigue_safety_factor"], dtype=float)[service],
            np.asarray(t["max_retainer_force_N"], dtype=float)[service],
        )
    }
    # a resonance between two swept speeds: the worst speeds' neighbourhoods halved twice; the
    # rated speed itself, the end of the service range (where the stress is often highest)
    rated = None if rated_rpm is None else float(rated_rpm)
    for level in range(REFINEMENTS):
        known = sorted(worst)
        new = (
            {rated} if (level == 0 and rated is not None and rpm[0] < rated < rpm[-1] and rated not in worst) else set()
        )
        for r in {min(worst, key=lambda r: worst[r][0]), max(worst, key=lambda r: worst[r][1])}:
            i = known.index(r)
            new |= {0.5 * (r + known[j]) for j in (i - 1, i + 1) if 0 <= j < len(known)}
        if not new:
            break
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            more = sweep(
                spring, cam, sorted(new), valve_train=valve_train, workers=1, starts=starts, **tol
            ).summary_table()
        worst |= {
            float(r): (float(g), float(x))
            for r, g, x in zip(more["cam_rpm"], more["fatigue_safety_factor"], more["max_retainer_force_N"])
        }
        periodicity = max(periodicity, float(np.max(np.asarray(more["periodicity_error"], dtype=float))))
        runs += len(new)
    return dict(
        float_cam_rpm=f,
        max_retainer_force=max(v[1] for v in worst.values()),
        goodman_safety=min(v[0] for v in worst.values()),
        clash_onset_cam_rpm=float(rpm[clash[0]]) if clash.size else None,
        max_clash_severity=float(np.max(severity)),
        periodicity=periodicity,
        simulations=runs,
    )


def variant_float_speed(
    spring,
    cam,
    valve_train,
    guess_rpm: float,
    lo_rpm: float,
    hi_rpm: float,
    resolution: float,
    periodicity_tol: float | None = None,
    starts: PeriodicStates | None = None,
):
    """The float speed of a design near ``guess_rpm`` within ``[lo_rpm, hi_rpm]``
    (:func:`springdyn.valve.run.float_search.float_speed_near` on its prepared set-up).

    Parameters
    ----------
    spring, cam, valve_train : ValveSpring, Cam, ValveTrain
        The design, its cam and its train [-].
    guess_rpm : float
        Where the search starts [rev/min].
    lo_rpm, hi_rpm : float
        The speed range [rev/min].
    resolution : float
        Width of the final bracket [rev/min].
    periodicity_tol : float, optional
        The periodic steady state each trial speed runs to [fraction of Fset] (default the run's).
    starts : PeriodicStates, optional
        Warm starts (:func:`~springdyn.valve.run.float_search.float_speed_near`).
    """
    tol = {} if periodicity_tol is None else dict(periodicity_tol=float(periodicity_tol))
    return float_speed_near(
        prepare(spring, cam, valve_train), guess_rpm, lo_rpm, hi_rpm, resolution=resolution, starts=starts, **tol
    )
