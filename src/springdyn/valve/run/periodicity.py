"""The periodic steady state a valve simulation reports (docs/valve-dynamics.md, "Periodic steady state").

A speed runs revolution by revolution until the seat, retainer, cam-contact and valve-seat
forces of the last two revolutions differ by at most :data:`PERIODICITY_TOL` of Fset on the
output grid (the engine's loop, :func:`springdyn.valve.engine.loop.run_speeds_loop`), for at
most :data:`MAX_REVOLUTIONS`.  One that does not settle by then (bounce that does not repeat)
is marked and reports the band of its extremes over its last :data:`BAND_REVOLUTIONS`.

**Warm starts** (issue 42): :class:`PeriodicStates` keeps the states a design's speeds ended
in (its periodic states at cam angle 0), each as its deviation from the design's static
equilibrium, so that a speed of the same or a neighbouring design (a tolerance variant, the
next candidate of a synthesis) starts from the nearest known one (:meth:`PeriodicStates.start`)
instead of from rest.  The start changes the path to the periodic state, not the acceptance
test (two revolutions within the tolerance), so the results agree with a cold start's within
that tolerance.
"""

import threading

import numpy as np

__all__ = ["PERIODICITY_TOL", "MAX_REVOLUTIONS", "BAND_REVOLUTIONS", "is_periodic", "PeriodicStates", "WARM_REACH"]

#: Largest change of the periodicity forces between the last two revolutions [fraction of Fset].
PERIODICITY_TOL = 0.002
#: The most revolutions a speed runs to its periodic steady state [-].
MAX_REVOLUTIONS = 40
#: Revolutions at the end of a speed that does not settle whose extremes give its band [-].
BAND_REVOLUTIONS = 8


def is_periodic(periodicity_error: float, tol: float | None = None) -> bool | None:
    """Whether a revolution repeats the one before within ``tol`` (None: :data:`PERIODICITY_TOL`).

    Parameters
    ----------
    periodicity_error : float
        The largest change of the periodicity forces from the revolution before [fraction
        of Fset]; nan after a single revolution (then None: nothing to compare with).
    tol : float, optional
        Tolerance [fraction of Fset].
    """
    if not periodicity_error == periodicity_error:
        return None
    return bool(periodicity_error <= (PERIODICITY_TOL if tol is None else tol))


#: The farthest speed a known periodic state starts another from, as a fraction of that speed
#: [-]: farther, the speed starts from rest (measured on the tolerance example, bucket train:
#: a state 100 rpm away, 3-7 % of the speed, saved no revolution against rest; the same speed's
#: state of the nominal saved a quarter of them).
WARM_REACH = 0.1


class PeriodicStates:
    """Known periodic states at cam angle 0, by cam speed, each as its deviation from the
    static equilibrium of its design's set-up (``state - setup.y0``), to start other speeds
    from: a warm start (module docstring).

    A design's own states come back exactly (its equilibrium added back); a neighbouring
    design's (a tolerance variant's nominal, the previous candidate of a synthesis) are its
    periodic motion about the new design's own equilibrium (which carries the change of the
    installed deflection, the lash and the masses' static positions), the first-order
    estimate of the new periodic state.  States of another size (a distributed chain of other
    elements) are not used.  Thread-safe (the chunks of a sweep record into one).
    """

    def __init__(self, cam_rpm=(), deviations=()):
        self._rpm = [float(r) for r in cam_rpm]
        self._dev = [np.array(d, dtype=float) for d in deviations]
        self._lock = threading.Lock()

    def __len__(self) -> int:
        return len(self._rpm)

    def __getstate__(self):  # the lock stays behind (a Dask worker gets its own)
        return dict(rpm=list(self._rpm), dev=list(self._dev))

    def __setstate__(self, state):
        self.__init__(state["rpm"], state["dev"])

    def copy(self) -> "PeriodicStates":
        """The same states in a new collection (a variant records its own into it)."""
        with self._lock:
            return PeriodicStates(self._rpm, self._dev)

    def add(self, cam_rpm: float, state, equilibrium) -> None:
        """Record the state a speed ended in.

        Parameters
        ----------
        cam_rpm : float
            Cam speed [rev/min].
        state : ndarray
            The state the speed ended in, at cam angle 0 [m, m/s].
        equilibrium : ndarray
            The static equilibrium of its set-up (``setup.y0``) [m, m/s].
        """
        dev = np.asarray(state, dtype=float) - np.asarray(equilibrium, dtype=float)
        if not np.all(np.isfinite(dev)):
            return
        with self._lock:
            self._rpm.append(float(cam_rpm))
            self._dev.append(dev)

    def start(self, setup, cam_rpm: float):
        """The state a speed of ``setup`` starts from [m, m/s]: the known state nearest in speed
        (the latest of equally near ones) about the set-up's own equilibrium, or None (start
        from rest) when none is within :data:`WARM_REACH` of the speed or of the state's size.

        Parameters
        ----------
        setup : SimulationSetup
            The design to start (its equilibrium ``y0``).
        cam_rpm : float
            Cam speed [rev/min].
        """
        y0 = setup.y0
        with self._lock:
            best, far = None, WARM_REACH * float(cam_rpm)
            for r, d in zip(self._rpm, self._dev):
                gap = abs(r - float(cam_rpm))
                if d.shape == y0.shape and gap <= far:
                    best, far = d, gap
        return None if best is None else y0 + best
