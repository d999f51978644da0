"""How a valve run is integrated: :class:`RunSettings`, checked once and passed as one object.

Every analysis of the run wing (:func:`~springdyn.valve.run.simulation.simulate`, the sweeps,
the float search, the run-ups, the tolerance study above them) takes one
:class:`RunSettings`: the revolutions (or the periodic steady state and its tolerance), the
output grid, the integration tolerances, the backend and Runge-Kutta pair, and whether speeds
beyond reason are computed.  The defaults below were chosen by the refinement studies of
docs/valve-dynamics.md ("Stepping and tolerances", "Periodic steady state"); the run-wide constants of the engine's
set-up (cam table resolution, largest step) live here too.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ...core.errors import InputError
from .periodicity import MAX_REVOLUTIONS, PERIODICITY_TOL

__all__ = [
    "RunSettings",
    "DEFAULT_RTOL",
    "DEFAULT_ATOL",
    "TRAIN_RTOL",
    "TRAIN_ATOL",
    "POINTS_PER_REVOLUTION",
    "SWEEP_POINTS_PER_REVOLUTION",
    "CAM_SAMPLES",
    "MAX_STEP_FRACTION",
    "VELOCITY_TOLERANCE_DIVISOR",
    "PAIR",
    "BS3_MIN_ELEMENTS",
    "MIN_EVENT_SURGE_PERIODS",
    "MAX_CAM_RPM",
    "BACKENDS",
]

#: Default integration tolerances (relative; absolute on displacements [m] and velocities
#: [m/s]).  Chosen by the refinement study of the tests: halving them changes peak forces
#: by far less than 0.05 %.
DEFAULT_RTOL = 1e-6
DEFAULT_ATOL = 1e-9
#: With a valve train the defaults are a hundred times tighter: its contacts open and close
#: with impacts (lash take-up, landings), and at 1e-6 those repeat from one revolution to the
#: next only to a few per cent of Fset (the pushrod example: 3.7 % at 1000 cam rpm, no speed
#: settles to the periodic steady state); at 1e-8 every speed below the first lift-off settles
#: within 0.2 % in 4-5 revolutions (docs/valve-dynamics.md, "Periodic steady state").
TRAIN_RTOL = 1e-8
TRAIN_ATOL = 1e-11
#: Output samples per revolution of one simulated speed (every 0.25 deg) and of each speed of
#: a sweep (every 0.5 deg) [-].
POINTS_PER_REVOLUTION = 1440
SWEEP_POINTS_PER_REVOLUTION = 720
#: The fewest periods of the spring's first surge mode a cam event may last for its speed to be
#: an operating point (:func:`springdyn.valve.run.setup.check_speeds`).
MIN_EVENT_SURGE_PERIODS = 1.0
#: Cam speed [rev/min] above any engine's (a racing engine's 20 000 rpm is 10 000 cam rpm): a
#: refused speed above it is likely a typing slip, and the message suggests a tenth of it.
MAX_CAM_RPM = 12000.0
#: Cam table resolution for the engine (samples per revolution, 0.05 deg).
CAM_SAMPLES = 7200
#: Maximum step [fraction of a revolution] so that no step can jump over a short event.
MAX_STEP_FRACTION = 1.0 / 720.0
#: The spring's velocities get the absolute tolerance ``atol 2 pi f1 / VELOCITY_TOLERANCE_DIVISOR``
#: [m/s] (:func:`springdyn.valve.run.runner.atol_velocity`; the study in docs/valve-dynamics.md, "Tolerances").
VELOCITY_TOLERANCE_DIVISOR = 30.0
#: The embedded Runge-Kutta pair of the compiled engine per spring model, chosen by
#: measurement (docs/valve-dynamics.md, "Which pair, measured"): Type C's step is set by accuracy, where the
#: 5th-order Dormand-Prince pair takes the fewest right-hand sides; the distributed chain's
#: by the stability of its stiffness-proportionally damped top modes (real eigenvalues to
#: -2.7e5 1/s for 50 elements), where the Bogacki-Shampine 3(2) pair takes 1.3x more steps
#: for half the right-hand sides each, and still holds the end forces within 0.05 % of Fset.
PAIR = {"type-c": "dopri5", "distributed": "bs3"}
#: Below this many elements the distributed chain's explicit step is set by accuracy, not by
#: stability, and Dormand-Prince is the faster pair (measured, one-step example at 1500 and
#: 3000 cam rpm: 25 elements 3.0 against 4.2 ms, 40 elements 6.2 against 6.7 ms, 50 elements
#: 10.4 against 9.6 ms; docs/valve-spring.md, "Stepping: explicit, from measurements").
BS3_MIN_ELEMENTS = 40
#: The integrators: the compiled engine, or SciPy's ``solve_ivp`` (DOP853) as the reference.
BACKENDS = ("compiled", "scipy")

_NUMBER = (int, float, np.integer, np.floating)


def _whole(name: str, value, lo: int, hi: int) -> int:
    if (
        isinstance(value, bool)
        or not isinstance(value, _NUMBER)
        or not math.isfinite(value)
        or value != int(value)
        or not lo <= value <= hi
    ):
        raise InputError(f"{name} = {value!r} must be a whole number of at least {lo} and at most {hi}")
    return int(value)


@dataclass(frozen=True)
class RunSettings:
    """How a run is integrated, checked when it is made (:class:`InputError` naming the field).

    Parameters
    ----------
    revolutions : int, optional
        Cam revolutions [-] from static equilibrium, 1 to 1000; the last is reported and
        compared with the one before.  None (default): to the periodic steady state, until
        the seat, retainer, cam-contact and valve-seat forces of the last two revolutions
        differ by at most ``periodicity_tol`` of Fset.
    points_per_revolution : int, optional
        Output samples per revolution [-], 16 to 100 000; None: the analysis's default
        (:data:`POINTS_PER_REVOLUTION` for one speed, :data:`SWEEP_POINTS_PER_REVOLUTION` for
        each speed of a sweep).
    rtol : float, optional
        Relative tolerance [-], 1e-12 to 1e-2; None: :data:`DEFAULT_RTOL`, with a valve train
        :data:`TRAIN_RTOL` (:meth:`tolerances`).
    atol : float, optional
        Absolute tolerance of the displacements [m], 1e-15 to 1e-5 (the velocities get it times
        ``2 pi f1 / 30``); None: :data:`DEFAULT_ATOL`, with a valve train :data:`TRAIN_ATOL`.
    periodicity_tol : float
        Periodic steady state: tolerance [fraction of Fset], 1e-7 to 0.5.
    max_revolutions : int
        Periodic steady state: the most revolutions per speed [-], 2 to 1000.
    backend : {"compiled", "scipy"}
        The compiled engine, or SciPy's ``solve_ivp`` (DOP853), the reference.
    method : {"dopri5", "tsit5", "bs3"}, optional
        The compiled engine's Runge-Kutta pair; None: the model's (:data:`PAIR`).
    allow_extreme_speeds : bool
        Compute speeds at which the cam event is shorter than one period of the spring's
        first surge mode (refused otherwise), flagged in the results' notes.
    check_elements : bool
        Distributed model with clashing coils: run again with twice the elements (at most
        400) and report how much the peak end forces change.

    Examples
    --------
    >>> RunSettings(revolutions=3).revolutions
    3
    >>> RunSettings(periodicity_tol=0.7)
    Traceback (most recent call last):
    ...
    springdyn.core.errors.InputError: periodicity_tol = 0.7 must be a fraction of Fset from 1e-07 to 0.5 (default 0.002, i.e. 0.2 %)
    """

    revolutions: int | None = None
    points_per_revolution: int | None = None
    rtol: float | None = None
    atol: float | None = None
    periodicity_tol: float = PERIODICITY_TOL
    max_revolutions: int = MAX_REVOLUTIONS
    backend: str = "compiled"
    method: str | None = None
    allow_extreme_speeds: bool = False
    check_elements: bool = True

    def __post_init__(self):
        if self.revolutions is None:
            tol = self.periodicity_tol
            if isinstance(tol, bool) or not isinstance(tol, _NUMBER) or not 1e-7 <= tol <= 0.5:
                raise InputError(
                    f"periodicity_tol = {tol!r} must be a fraction of Fset from 1e-07 to 0.5 "
                    f"(default {PERIODICITY_TOL:g}, i.e. {100 * PERIODICITY_TOL:g} %)"
                )
            most = self.max_revolutions
            if not isinstance(most, bool) and isinstance(most, _NUMBER) and most < 2:
                raise InputError(f"max_revolutions = {most!r} must be at least 2: two revolutions are compared")
            object.__setattr__(self, "max_revolutions", _whole("max_revolutions", most, 2, 1000))
            object.__setattr__(self, "periodicity_tol", float(tol))
        else:
            object.__setattr__(self, "revolutions", _whole("revolutions", self.revolutions, 1, 1000))
        if self.points_per_revolution is not None:
            object.__setattr__(
                self, "points_per_revolution", _whole("points_per_revolution", self.points_per_revolution, 16, 100_000)
            )
        for name, lo, hi in (("rtol", 1e-12, 1e-2), ("atol", 1e-15, 1e-5)):
            value = getattr(self, name)
            if value is None:
                continue
            if isinstance(value, bool) or not isinstance(value, _NUMBER) or not lo <= value <= hi:
                raise InputError(
                    f"{name} = {value!r} is outside the allowed range {lo:g} <= {name} <= {hi:g} "
                    "(integration tolerance"
                    + (
                        ": absolute, on displacements [m]; velocities get it times 2 pi f1/30)"
                        if name == "atol"
                        else ", relative)"
                    )
                )
        if self.backend not in BACKENDS:
            raise InputError(f"backend = {self.backend!r} must be 'compiled' or 'scipy'")
        if self.method is not None:
            self._check_method()

    def _check_method(self) -> None:
        # (imported here: the pairs live with the compiled kernels, numba; the CLI builds its
        # options from this module without loading it)
        from ...numerics.erk import PAIRS  # (here: the compiled engine (numba) loads only when a run needs it)

        if self.backend != "compiled" or self.method not in PAIRS:
            raise InputError(
                f"method = {self.method!r}: the compiled backend's pairs are {sorted(PAIRS)}"
                + ("" if self.backend == "compiled" else f"; backend = {self.backend!r} has its own (DOP853)")
            )

    @classmethod
    def of(cls, settings: RunSettings | None = None, **changes) -> RunSettings:
        """``settings`` (default: the defaults) with ``changes`` (fields of this class), checked.

        The one place where loose keyword arguments of the public functions become a
        :class:`RunSettings`: ``simulate(spring, cam, 3000, rtol=1e-7)`` and
        ``simulate(spring, cam, 3000, settings=RunSettings(rtol=1e-7))`` are one run.

        Parameters
        ----------
        settings : RunSettings, optional
            The settings to start from.
        **changes
            Fields to change; a value of None keeps the field's default where the field's
            default is not None (a CLI option left out).
        """
        base = cls() if settings is None else settings
        if not isinstance(base, cls):
            raise InputError(f"settings = {settings!r} must be a RunSettings")
        names = {f.name for f in dataclasses.fields(cls)}
        unknown = sorted(set(changes) - names)
        if unknown:
            raise InputError(f"{unknown[0]!r} is not a run setting; the settings are {', '.join(sorted(names))}")
        return dataclasses.replace(base, **changes) if changes else base

    @property
    def periodic(self) -> bool:
        """Whether each speed runs to its periodic steady state (``revolutions`` None)."""
        return self.revolutions is None

    @property
    def most_revolutions(self) -> int:
        """The most revolutions a speed runs [-]: ``max_revolutions`` to the periodic steady
        state, else ``revolutions``."""
        return self.max_revolutions if self.revolutions is None else self.revolutions

    def points(self, default: int) -> int:
        """Output samples per revolution [-]: the setting, or the analysis's ``default``.

        Parameters
        ----------
        default : int
            The analysis's own grid [-].
        """
        return int(default) if self.points_per_revolution is None else self.points_per_revolution

    def tolerances(self, valve_train) -> tuple[float, float]:
        """The integration tolerances ``(rtol [-], atol [m])``: those set, else the defaults of
        the spring alone (:data:`DEFAULT_RTOL`, :data:`DEFAULT_ATOL`) or of a valve train
        (:data:`TRAIN_RTOL`, :data:`TRAIN_ATOL`).

        Parameters
        ----------
        valve_train : ValveTrain or None
            The run's valve train.
        """
        train = valve_train is not None
        return (
            (TRAIN_RTOL if train else DEFAULT_RTOL) if self.rtol is None else self.rtol,
            (TRAIN_ATOL if train else DEFAULT_ATOL) if self.atol is None else self.atol,
        )
