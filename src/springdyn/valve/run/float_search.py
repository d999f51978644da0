"""The float speed of a valve train, as valve-train engineers define it.

Float is the valve leaving the cam over the nose (:mod:`springdyn.valve.run.separation`): the
float speed is the lowest speed from which the valve separates over the nose at every
higher speed of the scan.  The scan is a speed sweep to the periodic steady state
(:func:`springdyn.valve.run.sweeps.sweep`); a bisection then narrows the step below the float
speed down to the resolution.  Beside it: the first speed with any lift-off and its phase
(opening-side bounce at lash take-up comes much earlier), seat bounce and the seating
velocity band per scanned speed.

Across many variants of one design (a tolerance study) the scan is not needed for each:
:func:`float_speed_near` finds a variant's float speed from the nominal's by a bracketed
search on the valve's smallest cam-contact gap over the nose (:func:`nose_gap`, positive
while the cam holds the valve, negative once it leaves it: continuous through the float
speed), each speed to its periodic steady state; four to five speeds per variant against a
scan's twenty.
"""

import math

import numpy as np

from ...core.errors import InputError, SolverError
from ...core.units import rpm_to_omega
from ..cam.definition import Cam
from ..engine import STATUS
from ..spring.definition import ValveSpring
from ..train.definition import ValveTrain
from .periodicity import PeriodicStates
from .results import FloatSpeedResult
from .runner import run_speeds, run_speeds_from
from .separation import cam_phases, phase_mask
from .settings import POINTS_PER_REVOLUTION, SWEEP_POINTS_PER_REVOLUTION, RunSettings
from .setup import output_angles
from .sweeps import sweep

__all__ = ["float_speed", "float_speed_near", "nose_gap", "FLOAT_RESOLUTION"]

#: Width of the final bracket of a variant's float speed [rev/min] (:func:`float_speed_near`).
FLOAT_RESOLUTION = 5.0

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
    settings: RunSettings | None = None,
    resolution: float = 1.0,
    progress_quiet: bool = True,
    workers: int | None = None,
    starts: PeriodicStates | None = None,
    **run,
) -> FloatSpeedResult:
    """Float speed: the lowest cam speed from which the valve separates over the nose at
    every higher scanned speed.

    Scans the speeds ``cam_rpm`` (each to its periodic steady state, continued from the
    slower speed before it), then bisects between the scanned speed below the float speed
    and the float speed down to ``resolution`` [rev/min] (at most ``MAX_HALVINGS``
    halvings); each bisection speed runs from rest (with ``starts``: from the nearest known
    periodic state).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain
        The valve body whose contact with the cam may open.
    cam_rpm : array_like
        Camshaft speeds to scan [rev/min], positive.
    settings : RunSettings, optional
        How each speed is integrated (:class:`~springdyn.valve.run.settings.RunSettings`;
        default: to the periodic steady state, 1440 output points a revolution).
    resolution : float
        Width of the final bracket [rev/min], positive.
    progress_quiet : bool
        No progress bar.
    workers : int, optional
        Local threads of the scan [-].
    starts : PeriodicStates, optional
        Warm starts: every scanned and bisection speed from the nearest known periodic state
        (a neighbouring design's, the scan's), its own recorded there (results within the
        periodicity tolerance of cold starts').
    **run
        Fields of :class:`~springdyn.valve.run.settings.RunSettings` given one by one.

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
    settings = RunSettings.of(settings, **run)
    settings = RunSettings.of(settings, points_per_revolution=settings.points(POINTS_PER_REVOLUTION))
    scan = sweep(
        spring,
        cam,
        rpms,
        valve_train=valve_train,
        settings=settings,
        quiet=progress_quiet,
        workers=workers,
        starts=starts,
    )
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
            periodicity_tol=settings.periodicity_tol,
            model=spring.model,
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
        if bool(
            sweep(
                spring, cam, [mid], valve_train=valve_train, settings=settings, workers=1, starts=starts
            ).summary_table()["nose_separation"][0]
        ):
            hi = mid
        else:
            lo = mid
    if first_separation is None or hi < first_separation["cam_rpm"]:
        first_separation = dict(cam_rpm=hi, phase="nose")  # the bisection found it below the scanned speed
    return result(hi, [lo, hi])


def nose_gap(cam_gap, nose) -> float:
    """The valve's smallest cam-contact gap over the nose [m]: positive while the cam holds
    the valve (the contact's compression), negative once the valve leaves it.

    Parameters
    ----------
    cam_gap : array_like
        The signed cam-contact gap over a revolution's output grid [m], positive in contact
        (the engine's ``cam_gap`` output).
    nose : array_like of bool
        The grid points in the nose phase [-] (:func:`springdyn.valve.run.separation.phase_mask`).
    """
    g = np.asarray(cam_gap, dtype=float)
    nose = np.asarray(nose, dtype=bool)
    k = np.flatnonzero(nose)
    i = int(k[np.argmin(g[k])])
    if 0 < i < g.size - 1 and nose[i - 1] and nose[i + 1]:
        # the grid's smallest value refined by the parabola through it and its neighbours
        # (independent of the output grid: the test runs it on two grids)
        curvature = g[i + 1] - 2.0 * g[i] + g[i - 1]
        if curvature > 0.0:
            return float(g[i] - (g[i + 1] - g[i - 1]) ** 2 / (8.0 * curvature))
    return float(g[i])


def float_speed_near(
    setup,
    guess_rpm: float,
    lo_rpm: float,
    hi_rpm: float,
    *,
    resolution: float = FLOAT_RESOLUTION,
    settings: RunSettings | None = None,
    starts: PeriodicStates | None = None,
    **run,
) -> dict:
    """The float speed of a prepared valve train near ``guess_rpm`` [rev/min], within
    ``[lo_rpm, hi_rpm]``, to ``resolution``.

    Each trial speed runs from rest (with ``starts``: from the nearest known periodic state,
    a neighbouring design's or an earlier trial's) to its periodic steady state and gives the smallest
    cam-contact gap over the nose, ``g`` (:func:`nose_gap`): the valve separates over the
    nose where ``g <= 0``.  From just below the guess the search steps outwards (doubling its
    step) until ``g`` changes sign, then narrows the bracket by regula falsi with the
    Illinois modification (a bracket end kept twice has its ``g`` halved), each trial kept a
    quarter of the resolution inside the bracket, down to ``resolution``.  It assumes one
    sign change near the guess: a tolerance study takes the nominal's float speed, which a
    scan established (:func:`float_speed`), as the guess.

    Parameters
    ----------
    setup : SimulationSetup
        The prepared spring, cam and valve train (:func:`springdyn.valve.run.setup.prepare`).
    guess_rpm : float
        Where to start [rev/min] (e.g. the nominal design's float speed).
    lo_rpm, hi_rpm : float
        The speed range [rev/min].
    resolution : float
        Width of the final bracket [rev/min].
    settings : RunSettings, optional
        How each trial speed is integrated (default: to the periodic steady state with the
        valve train's tolerances, on 720 output points a revolution).
    starts : PeriodicStates, optional
        Warm starts: known periodic states (e.g. the nominal design's); each trial records its
        own there, so that the next starts from the nearest trial (results within the
        periodicity tolerance of cold starts'; :class:`~springdyn.valve.run.periodicity.PeriodicStates`).
    **run
        Fields of :class:`~springdyn.valve.run.settings.RunSettings` given one by one.

    Returns
    -------
    dict
        ``float_cam_rpm`` (the bracket's upper end, the lowest speed found separating over the
        nose; ``hi_rpm`` when the valve stays on the cam up to it, ``lo_rpm`` when it
        separates already there), ``bracket`` [rev/min], ``in_range`` (the float speed lies
        within the range), ``evaluations`` (trial speeds), ``revolutions`` (summed),
        ``periodicity`` (the largest periodicity measure of the trial speeds [fraction of
        Fset]: at most ``periodicity_tol`` when every one settled),.
    """
    if setup.valve_train is None:
        raise InputError("float_speed_near needs a valve train: the spring alone has no cam contact to lose")
    lo_rpm, hi_rpm = float(lo_rpm), float(hi_rpm)
    if not (0.0 < lo_rpm <= hi_rpm and math.isfinite(hi_rpm)):
        raise InputError(f"speed range [{lo_rpm:g}, {hi_rpm:g}] rev/min must be positive, finite and ascending")
    if not (math.isfinite(resolution) and resolution > 0.0):
        raise InputError(f"resolution = {resolution!r} must be a positive speed [rev/min]")
    settings = RunSettings.of(settings, **run)
    points = settings.points(SWEEP_POINTS_PER_REVOLUTION)
    nose = phase_mask(output_angles(points), cam_phases(setup.cam, setup.valve_train.lobe_lash), "nose")
    column = _gap_column(setup)
    stats = dict(evaluations=0, revolutions=0, periodicity=0.0)

    def gap(rpm: float) -> float:
        omega = np.array([rpm_to_omega(rpm)])
        if starts is None:
            r = run_speeds(setup, omega, settings, points)
        else:
            r = run_speeds_from(setup, omega, settings, points, starts)
        if r["status"][0] != 0:
            raise _search_failure(rpm, r)
        stats["evaluations"] += 1
        stats["revolutions"] += int(r["revolutions"][0])
        stats["periodicity"] = max(stats["periodicity"], float(r["periodicity"][0]))
        return nose_gap(r["extra"][0, :, column], nose)

    def found(f, bracket, in_range=True):
        return dict(float_cam_rpm=float(f), bracket=[float(b) for b in bracket], in_range=bool(in_range), **stats)

    def step_to_root(x0, g0, x1, g1, last):
        """The next step's length [rev/min]: to half a resolution past the root the last two
        trials extrapolate to, between half a resolution and four times the step before;
        twice the step before where they give no root ahead."""
        d = (g1 - g0) / (x1 - x0)
        if not d < 0.0:
            return 2.0 * last
        return min(max(abs(g1 / d) + 0.5 * resolution, 0.5 * resolution), 4.0 * last)

    step = max(4.0 * resolution, 0.01 * (hi_rpm - lo_rpm))
    a = min(max(float(guess_rpm) - resolution, lo_rpm), hi_rpm)
    ga = gap(a)
    if ga > 0.0:  # held at a: step up until the valve separates
        while True:
            if a >= hi_rpm:
                return found(hi_rpm, [hi_rpm, hi_rpm], in_range=False)
            b = min(a + step, hi_rpm)
            gb = gap(b)
            if gb <= 0.0:
                break
            step = step_to_root(a, ga, b, gb, step)
            a, ga = b, gb
    else:  # separated at a: step down until the valve is held
        b, gb = a, ga
        while True:
            if b <= lo_rpm:
                return found(lo_rpm, [lo_rpm, lo_rpm])
            a = max(b - step, lo_rpm)
            ga = gap(a)
            if ga > 0.0:
                break
            step = step_to_root(b, gb, a, ga, step)
            b, gb = a, ga
    kept = 0  # +1: a kept (b moved) last, -1: b kept
    while b - a > resolution:
        m = b - gb * (b - a) / (gb - ga)
        m = min(max(m, a + 0.25 * resolution), b - 0.25 * resolution)
        gm = gap(m)
        if gm > 0.0:
            a, ga = m, gm
            if kept == -1:
                gb *= 0.5
            kept = -1
        else:
            b, gb = m, gm
            if kept == 1:
                ga *= 0.5
            kept = 1
    return found(b, [a, b])


def _gap_column(setup) -> int:
    return setup.layout["cam_gap"]


def _search_failure(rpm, r):
    status = int(r["status"][0])
    return SolverError(
        f"float search: the integration failed at {rpm:.1f} cam rpm ({STATUS.get(status, status)}) "
        f"at t = {float(r['t_end'][0]):.4g} s after {int(r['steps'][0])} steps"
    )
