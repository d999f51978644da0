"""The valve family's model: a spring, optionally its cam and valve train, and every analysis.

:class:`ValveModel` is the valve counterpart of :class:`springdyn.cfcs.CFCS` and
:class:`springdyn.lsd.LSDModel`: built from the definitions (:class:`ValveSpring`, :class:`Cam`,
:class:`ValveTrain`), it runs the analyses and returns :class:`~springdyn.core.results.Result`
objects.  What it derives once and reuses is visible: the spring's chain model
(:attr:`chain_model`, :mod:`springdyn.valve.spring.chains`) and the speed-independent set-up of the
engine (:attr:`setup`), both cached properties of this (mutable) object.

Where each analysis lives: statics and modes of the chain, :mod:`springdyn.valve.spring.chains`; the
frequency response, :mod:`springdyn.valve.spring.frf`; simulation and natural frequencies under the
cam, :mod:`springdyn.valve.run.simulation`; speed sweeps, :mod:`springdyn.valve.run.sweeps`.

Examples
--------
>>> from springdyn.valve import Cam, ValveModel, ValveSpring
>>> model = ValveModel(ValveSpring.example("one-step"), Cam(law="3-4-5", lift=9e-3, duration=2.0944))
>>> round(model.internal_parameters()["Fset"], 2)
251.43
"""

from __future__ import annotations

from functools import cached_property

from ..core.errors import InputError
from .cam.definition import Cam
from .spring.definition import ValveSpring
from .train.definition import ValveTrain

__all__ = ["ValveModel"]


class ValveModel:
    """A valve spring with its cam and valve train, and the analyses of springdyn's valve family.

    Parameters
    ----------
    spring : ValveSpring
        The spring definition (its ``model`` key chooses Type C or the distributed chain).
    cam : Cam, optional
        The cam; needed by :meth:`simulate`, :meth:`sweep`, :meth:`float_speed` and
        :meth:`natural_frequencies`.
    valve_train : ValveTrain, optional
        The valve train between cam and valve; without it the retainer follows the cam.
    """

    def __init__(self, spring: ValveSpring, cam: Cam | None = None, valve_train: ValveTrain | None = None):
        if not isinstance(spring, ValveSpring):
            raise InputError(f"spring = {spring!r} must be a ValveSpring (ValveSpring.from_toml(...) or .example())")
        if cam is not None and not isinstance(cam, Cam):
            raise InputError(f"cam = {cam!r} must be a Cam or None")
        if valve_train is not None and not isinstance(valve_train, ValveTrain):
            raise InputError(f"valve_train = {valve_train!r} must be a ValveTrain or None")
        self.spring = spring
        self.cam = cam
        self.valve_train = valve_train

    def __repr__(self) -> str:
        parts = [f"{self.spring.type} spring, {self.spring.model} model"]
        if self.cam is not None:
            parts.append(f"{self.cam.law} cam")
        if self.valve_train is not None:
            parts.append(f"{self.valve_train.layout} valve train")
        return f"<ValveModel: {', '.join(parts)}>"

    # ------------------------------------------------------------------ derived once
    @cached_property
    def chain_model(self):
        """The spring's chain model (:class:`~springdyn.valve.spring.chains.SpringModel`)."""
        return self.spring.spring_model

    @cached_property
    def setup(self):
        """The engine's speed-independent set-up: cam table, initial state
        (:func:`springdyn.valve.run.setup.prepare`)."""
        from .run.setup import prepare

        return prepare(self.spring, self._need_cam("the set-up"), self.valve_train)

    def _need_cam(self, what: str) -> Cam:
        if self.cam is None:
            raise InputError(f"{what} needs a cam: ValveModel(spring, cam=Cam(...))")
        return self.cam

    # ------------------------------------------------------------------ the spring alone
    def internal_parameters(self) -> dict:
        """The model's internal parameters (K, K1, Kh1, m1, f1, Fset, ... [SI])."""
        return self.chain_model.internal_parameters()

    def static_force(self, length):
        """Static force [N] at the spring length(s) [m].

        Parameters
        ----------
        length : float or array_like
            Spring length [m].
        """
        return self.chain_model.static_force(length)

    def static_curve(self, start: float | None = None, stop: float | None = None, points: int = 400):
        """The static force and stiffness against length (:class:`~springdyn.valve.run.results.StaticCurve`).

        Parameters
        ----------
        start, stop : float, optional
            Lengths [m] (default: the free length down to the model's limit).
        points : int
            Samples [-].
        """
        return self.chain_model.static_curve(start, stop, points)

    def modes(self, length: float, count: int = 5):
        """Natural frequencies [Hz] of the chain at a length, both ends fixed.

        Parameters
        ----------
        length : float
            Spring length [m].
        count : int
            Frequencies [-].
        """
        return self.chain_model.modes(length, count)

    def design_figures(self, lift: float | None = None, cam_rpm: float | None = None) -> dict:
        """Spring index, corrected stresses, surge margin (:meth:`~springdyn.valve.spring.chains.SpringModel.design_figures`).

        Parameters
        ----------
        lift : float, optional
            Valve lift [m] (default: the cam's).
        cam_rpm : float, optional
            Cam speed [rev/min] for the surge margin.
        """
        if lift is None and self.cam is not None:
            lift = self.cam.lift
        return self.chain_model.design_figures(lift, cam_rpm)

    def dynamic_stiffness(self, frequency, length: float | None = None):
        """The linearised dynamic stiffness of the spring (:class:`~springdyn.valve.spring.frf.FrequencyResponse`).

        Parameters
        ----------
        frequency : array_like
            Frequencies [Hz].
        length : float, optional
            Spring length [m] (default: installed).
        """
        from .spring.frf import dynamic_stiffness

        return dynamic_stiffness(self.spring, frequency, length)

    # ------------------------------------------------------------------ under the cam
    def natural_frequencies(self, count: int = 8):
        """Natural frequencies of spring and valve train on the base circle and at full lift
        (:class:`~springdyn.valve.run.results.NaturalFrequencies`).

        Parameters
        ----------
        count : int
            Frequencies per state [-].
        """
        from .run.results import NaturalFrequencies
        from .run.train_modes import natural_frequencies

        out = natural_frequencies(self.spring, self._need_cam("natural_frequencies"), self.valve_train, count)
        return NaturalFrequencies(
            out["base_circle_Hz"], out["full_lift_Hz"], out["full_lift_cam_angle_deg"], out["notes"]
        )

    def simulate(self, cam_rpm: float, revolutions: int | None = None, **options):
        """The dynamic response at one cam speed (:class:`~springdyn.valve.run.results.Simulation`).

        Parameters
        ----------
        cam_rpm : float
            Cam speed [rev/min].
        revolutions : int, optional
            Revolutions from rest; the last is reported [-].  Default: to the periodic
            steady state.
        **options
            Further options of :func:`springdyn.valve.run.simulation.simulate` (periodicity
            tolerance, tolerances, outputs per revolution, backend, pair).
        """
        from .run.simulation import simulate

        self._need_cam("simulate")
        return simulate(
            self.spring, self.cam, cam_rpm, revolutions, valve_train=self.valve_train, setup=self.setup, **options
        )

    def sweep(self, cam_rpm, **options):
        """Every cam speed of ``cam_rpm`` (:class:`~springdyn.valve.run.sweeps.SpeedSweep`).

        Parameters
        ----------
        cam_rpm : array_like
            Cam speeds [rev/min].
        **options
            Further options of :func:`springdyn.valve.run.sweeps.sweep` (revolutions, a design
            variable, workers, a Dask client).
        """
        from .run.sweeps import sweep

        return sweep(self.spring, self._need_cam("sweep"), cam_rpm, valve_train=self.valve_train, **options)

    def float_speed(self, cam_rpm, **options):
        """The float speed of the valve train (:class:`~springdyn.valve.run.results.FloatSpeedResult`).

        Parameters
        ----------
        cam_rpm : array_like
            Cam speeds to scan [rev/min].
        **options
            Further options of :func:`springdyn.valve.run.float_search.float_speed`.
        """
        from .run.float_search import float_speed

        if self.valve_train is None:
            raise InputError("float_speed needs a valve train: ValveModel(spring, cam, valve_train=ValveTrain(...))")
        return float_speed(self.spring, self._need_cam("float_speed"), self.valve_train, cam_rpm, **options)
