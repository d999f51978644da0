"""The float speed of a valve train, as valve-train engineers define it.

Float is the valve leaving the cam over the nose (:mod:`springdyn.valve.separation`): the
float speed is the lowest speed from which the valve separates over the nose at every
higher speed of the scan.  The scan is a speed sweep to the periodic steady state
(:func:`springdyn.valve.sweeps.sweep`); a bisection then narrows the step below the float
speed down to the resolution.  Beside it: the first speed with any lift-off and its phase
(opening-side bounce at lash take-up comes much earlier), seat bounce and the seating
velocity band per scanned speed.
"""

import math

import numpy as np

from ..core.errors import InputError
from .cam import Cam
from .periodicity import MAX_REVOLUTIONS, PERIODICITY_TOL
from .results import FloatSpeedResult
from .spring import ValveSpring
from .sweeps import sweep
from .valvetrain import ValveTrain

__all__ = ["float_speed"]

#: Columns of the sweep's summary table a float-speed result keeps per scanned speed.
SCAN_COLUMNS = (
    "min_cam_contact_force_N",
    "liftoff",
    "nose_separation",
    "first_liftoff_phase",
    "max_liftoff_gap_m",
    "seat_landings",
    "seat_rebound_height_m",
    "seat_impact_velocity_m_per_s",
    "seat_impact_velocity_min_m_per_s",
    "seat_impact_velocity_median_m_per_s",
    "seat_impact_velocity_max_m_per_s",
    "periodicity_error",
    "periodic",
    "revolutions",
)


def float_speed(
    spring: ValveSpring,
    cam: Cam,
    valve_train: ValveTrain,
    cam_rpm,
    *,
    revolutions: int | None = None,
    resolution: float = 1.0,
    points_per_revolution: int = 1440,
    progress_quiet: bool = True,
    periodicity_tol: float = PERIODICITY_TOL,
    max_revolutions: int = MAX_REVOLUTIONS,
    workers: int | None = None,
    allow_extreme_speeds: bool = False,
) -> FloatSpeedResult:
    """Float speed: the lowest cam speed from which the valve separates over the nose at
    every higher scanned speed.

    Scans the speeds ``cam_rpm`` (each to its periodic steady state, continued from the
    slower speed before it), then bisects between the scanned speed below the float speed
    and the float speed down to ``resolution`` [rev/min] (at most ``MAX_HALVINGS``
    halvings); each bisection speed runs from rest.

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain
        The valve body whose contact with the cam may open.
    cam_rpm : array_like
        Camshaft speeds to scan [rev/min], positive.
    revolutions : int, optional
        Cam revolutions per speed from rest [-]; default: to the periodic steady state.
    resolution : float
        Width of the final bracket [rev/min], positive.
    points_per_revolution : int
        Output resolution of each speed [-].
    progress_quiet : bool
        No progress bar.
    periodicity_tol : float
        Periodic steady state: tolerance [fraction of Fset].
    max_revolutions : int
        Periodic steady state: the most revolutions per speed [-].
    workers : int, optional
        Local threads of the scan [-].
    allow_extreme_speeds : bool
        Scan speeds at which the cam event is shorter than one period of the spring's first
        surge mode (refused otherwise).

    Returns
    -------
    FloatSpeedResult
        ``float_cam_rpm`` (None if the valve does not separate over the nose at the highest
        scanned speed), ``bracket`` (speeds either side), ``first_separation`` (the lowest
        scanned speed with any lift-off and its phase) and per scanned speed the columns
        :data:`SCAN_COLUMNS`.
    """
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
    run = dict(
        valve_train=valve_train,
        revolutions=revolutions,
        points_per_revolution=points_per_revolution,
        periodicity_tol=periodicity_tol,
        max_revolutions=max_revolutions,
        allow_extreme_speeds=allow_extreme_speeds,
    )
    scan = sweep(spring, cam, rpms, quiet=progress_quiet, workers=workers, **run)
    table = scan.summary_table()
    columns = {k: table[k].tolist() for k in SCAN_COLUMNS if k in table}
    first = scan.first_separation_speeds()[0]
    first_separation = None
    if np.isfinite(first):
        i = int(np.flatnonzero(rpms == first)[0])
        first_separation = dict(
            cam_rpm=float(first),
            phase=str(table["first_liftoff_phase"][i])
            or ("nose" if table["nose_separation"][i] else "event (not located)"),
        )

    def result(float_rpm, bracket):
        return FloatSpeedResult(
            list(map(float, rpms)),
            columns["min_cam_contact_force_N"],
            float_rpm,
            bracket,
            float(resolution),
            first_separation=first_separation,
            scan=columns,
            periodicity_tol=periodicity_tol,
        )

    f = scan.float_speeds()[0]
    if not np.isfinite(f):
        return result(None, None)
    k = int(np.flatnonzero(rpms == f)[0])
    if k == 0:
        return result(float(f), [None, float(f)])
    lo, hi = float(rpms[k - 1]), float(f)
    for _ in range(max_halvings):  # bounded: the check above makes this many enough
        if hi - lo <= resolution:
            break
        mid = 0.5 * (lo + hi)
        if bool(sweep(spring, cam, [mid], workers=1, **run).summary_table()["nose_separation"][0]):
            hi = mid
        else:
            lo = mid
    if first_separation is None or hi < first_separation["cam_rpm"]:
        first_separation = dict(cam_rpm=hi, phase="nose")  # the bisection found it below the scanned speed
    return result(hi, [lo, hi])
