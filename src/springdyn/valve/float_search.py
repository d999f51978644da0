"""The float speed of a valve train: the lowest cam speed at which the follower leaves the cam.

A scan of the given speeds (the minimum cam contact force during the event at each), then
a bisection between the last speed that holds and the first that lifts off.
"""

import math

import numpy as np

from ..core.errors import InputError
from .cam import Cam
from .dynamics import simulate
from .results import FloatSpeedResult
from .setup import prepare
from .spring import ValveSpring
from .valvetrain import ValveTrain

__all__ = ["float_speed"]


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
