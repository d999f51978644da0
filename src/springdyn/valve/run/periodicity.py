"""The periodic steady state a valve simulation reports (docs/valve-dynamics.md, "Periodic steady state").

A speed runs revolution by revolution until the seat, retainer, cam-contact and valve-seat
forces of the last two revolutions differ by at most :data:`PERIODICITY_TOL` of Fset on the
output grid (the engine's loop, :func:`springdyn.valve.engine.loop.run_speeds_loop`), for at
most :data:`MAX_REVOLUTIONS`.  One that does not settle by then (bounce that does not repeat)
is marked and reports the band of its extremes over its last :data:`BAND_REVOLUTIONS`.
"""

__all__ = ["PERIODICITY_TOL", "MAX_REVOLUTIONS", "BAND_REVOLUTIONS", "is_periodic"]

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
