"""The valve family's front door: a spring with its cam and valve train, and every study of it.

:class:`ValveModel` is the valve counterpart of :class:`springdyn.cfcs.CFCS` and
:class:`springdyn.lsd.LSDModel`.  It holds the definitions (:class:`ValveSpring`,
:class:`Cam`, :class:`ValveTrain`, the engine's ``[timing]``, the follower and its friction,
the gas force) and the :class:`~springdyn.valve.run.settings.RunSettings` every run uses, and
offers every analysis of the family as a method returning a
:class:`~springdyn.core.results.Result`.  The CLI and the report call it, never the wings.

What it derives once and reuses is visible: the spring's chain model (:attr:`chain_model`),
the engine's speed-independent set-up (:attr:`setup`) and the crank-angle axis
(:attr:`crank_axis`), cached properties of this object.  Besides the single analyses it offers
the named studies a valve-train engineer runs: the friction over a speed range
(:meth:`friction_over_speed`), the resonance speeds in a range (:meth:`resonance_speeds`), the
float speed against a rated speed (:meth:`float_speed_above`) and the run-up through the float
speed (:meth:`run_up_through_float`).

Where each analysis lives: the spring alone, :mod:`springdyn.valve.spring`; the cam,
:mod:`springdyn.valve.cam`; the runs under the cam, :mod:`springdyn.valve.run`; the design
studies (tolerances, life, calibration), :mod:`springdyn.valve.design`.

Examples
--------
>>> from springdyn.valve import Cam, ValveModel, ValveSpring
>>> model = ValveModel(ValveSpring.example("one-step"), Cam(law="3-4-5", lift=9e-3, duration=2.0944))
>>> round(model.internal_parameters()["Fset"], 2)
251.43
"""

from __future__ import annotations

import dataclasses
from functools import cached_property
from pathlib import Path

import numpy as np

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError
from ..core.params import load_toml
from ..core.progress import progress
from . import cam as cam_wing
from . import design as design_wing
from . import run as run_wing
from . import spring as spring_wing
from . import train as train_wing
from .cam.definition import Cam
from .cam.follower import Follower
from .cam.timing import Timing, cam_rpm_from_engine_rpm, crank_axis
from .run.settings import RunSettings
from .spring.definition import ValveSpring
from .spring.pack import SpringPack
from .train.definition import ValveTrain

__all__ = ["ValveModel", "RUN_UP_WINDOW", "FLOAT_SCAN"]

#: Parameter descriptions shared by the model's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    length : float
        Spring length [m].
    count : int
        Frequencies [-].
    start, stop : float, optional
        Lengths [m] (default: the free length down to the model's limit).
    points : int
        Samples [-].
    """
)

#: The run-up through the float speed f (:meth:`ValveModel.run_up_through_float`): from this
#: fraction of f to this fraction [-] (the valve settles before, and floats well after).
RUN_UP_WINDOW = (0.85, 1.1)
#: The float-speed scan against a rated speed (:meth:`ValveModel.float_speed_above`): from this
#: fraction of the rated speed to this fraction of the float speed asked for, in this many
#: speeds [-, -, -].
FLOAT_SCAN = (0.25, 1.5, 21)
#: Cam speeds of the friction over speed (:meth:`ValveModel.friction_over_speed`) when a range
#: is given as its ends [-].
FRICTION_SPEEDS = 5


class ValveModel:
    """A valve spring with its cam and valve train, and the analyses of springdyn's valve family.

    Parameters
    ----------
    spring : ValveSpring or SpringPack
        The spring definition (its ``model`` key chooses Type C or the distributed chain), or
        a pack of two or three nested springs (:class:`~springdyn.valve.spring.pack.SpringPack`).
    cam : Cam, optional
        The cam; needed by every analysis under the cam.
    valve_train : ValveTrain, optional
        The valve train between cam and valve; without it the retainer follows the cam.
    settings : RunSettings, optional
        How every run of this model is integrated (default: :class:`RunSettings`' defaults).
    timing : Timing, optional
        The ``[timing]`` table: crank angles from TDC and the engine's strokes.
    crank_angles : bool, optional
        Give the results crank angles beside the cam's (default: when ``timing`` is given).
    follower : Follower, optional
        The ``[follower]`` table (cam checks, friction).
    friction : Friction, optional
        The ``[friction]`` table (default: its defaults, with ``oil``).
    oil : Oil, optional
        The train's one oil (``[oil]``; the friction table's and the adjuster's are the same):
        the friction's where no ``friction`` is given (default: the oil's defaults).
    gas_force : GasForce, optional
        The cylinder's gas force on the valve over a cam revolution [N] (needs a valve train).
    piston : Piston, optional
        The ``[piston]`` table under the valve: the valve-to-piston clearance
        (:meth:`valve_clearance`; with ``timing``).
    """

    def __init__(
        self,
        spring: ValveSpring,
        cam: Cam | None = None,
        valve_train: ValveTrain | None = None,
        *,
        settings: RunSettings | None = None,
        timing: Timing | None = None,
        crank_angles: bool | None = None,
        follower: Follower | None = None,
        friction=None,
        gas_force=None,
        oil=None,
        piston=None,
    ):
        if not isinstance(spring, (ValveSpring, SpringPack)):
            raise InputError(
                f"spring = {spring!r} must be a ValveSpring (ValveSpring.from_toml(...) or .example()) or a "
                "SpringPack (SpringPack.from_toml(...))"
            )
        if cam is not None and not isinstance(cam, Cam):
            raise InputError(f"cam = {cam!r} must be a Cam or None")
        if valve_train is not None and not isinstance(valve_train, ValveTrain):
            raise InputError(f"valve_train = {valve_train!r} must be a ValveTrain or None")
        if gas_force is not None and valve_train is None:
            raise InputError(
                "a gas force acts on the valve: it needs a valve train (--valve-train / [valve_train]); the spring "
                "alone has no valve"
            )
        self.spring = spring
        self.cam = cam
        self.valve_train = valve_train
        self.settings = RunSettings.of(settings)
        self.timing = timing
        self.crank_angles = timing is not None if crank_angles is None else bool(crank_angles)
        self.follower = follower
        self.friction_table = friction
        self.oil = oil if oil is not None or friction is None else friction.oil
        self.gas_force = gas_force
        if piston is not None and not isinstance(piston, train_wing.Piston):
            raise InputError(f"piston = {piston!r} must be a Piston ([piston] table) or None")
        self.piston = piston

    @classmethod
    def from_files(
        cls,
        spring,
        cam=None,
        valve_train=None,
        *,
        model: str | None = None,
        settings: RunSettings | None = None,
        crank_angles: bool | None = None,
    ) -> ValveModel:
        """A model of definition files: ``[spring]``, ``[cam]`` (with its ``[timing]``, or the
        spring file's), ``[valve_train]`` (with its ``[hla]``, ``[geometry]``, ``[follower]`` and
        ``[friction]``), and a ``[piston]`` table in any of them.  A spring file with
        ``[inner_spring]`` is a spring pack (:class:`~springdyn.valve.spring.pack.SpringPack`:
        ``[third_spring]``, ``[pack]``, ``[damper]``).

        Parameters
        ----------
        spring : str or path-like
            The spring file.
        cam, valve_train : str or path-like, optional
            The cam file and the valve-train file.
        model : str, optional
            The spring model, overriding the file's ``model`` key.
        settings : RunSettings, optional
            The run settings.
        crank_angles : bool, optional
            Crank angles in the results (default: when a ``[timing]`` table is given).
        """
        if SpringPack.in_document(load_toml(spring)):  # [inner_spring]: a spring pack
            sp = SpringPack.from_toml(spring).with_model(model)
        else:
            sp = ValveSpring.from_toml(spring).with_model(model)
        c = Cam.from_toml(cam) if cam is not None else None
        vt = ValveTrain.from_toml(valve_train) if valve_train is not None else None
        timing = (Timing.in_file(cam) if cam is not None else None) or Timing.in_file(spring)
        follower = Follower.in_file(valve_train) if valve_train is not None else None
        friction = oil = None
        if valve_train is not None:
            doc = load_toml(valve_train)
            friction = train_wing.Friction.in_document(doc, source=str(valve_train))
            oil = train_wing.oil_of(doc, source=str(valve_train))[0]
        return cls(
            sp,
            c,
            vt,
            settings=settings,
            timing=timing,
            crank_angles=crank_angles,
            follower=follower,
            friction=friction,
            oil=oil,
            piston=_piston_of(valve_train, cam, spring),
        )

    def __repr__(self) -> str:
        parts = [f"{self.spring.type} spring, {self.spring.model} model"]
        if self.cam is not None:
            parts.append(f"{self.cam.law} cam")
        if self.valve_train is not None:
            parts.append(f"{self.valve_train.layout} valve train")
        return f"<ValveModel: {', '.join(parts)}>"

    # ------------------------------------------------------------------ variants
    def replace(self, **changes) -> ValveModel:
        """The same model with other definitions or settings (``spring=``, ``cam=``,
        ``valve_train=``, ``settings=``, ``gas_force=``, ...): a new model, its derived
        state computed anew.

        Parameters
        ----------
        **changes
            Constructor arguments to change.
        """
        args = dict(
            spring=self.spring,
            cam=self.cam,
            valve_train=self.valve_train,
            settings=self.settings,
            timing=self.timing,
            crank_angles=self.crank_angles,
            follower=self.follower,
            friction=self.friction_table,
            gas_force=self.gas_force,
            oil=self.oil,
            piston=self.piston,
        )
        unknown = sorted(set(changes) - set(args))
        if unknown:
            raise InputError(f"{unknown[0]!r} is not a part of a ValveModel; its parts are {', '.join(args)}")
        args.update(changes)
        return ValveModel(**args)

    def with_model(self, name: str | None) -> ValveModel:
        """The same definitions with the spring model ``name`` (None: this model).

        Parameters
        ----------
        name : {"type-c", "distributed"} or None
            The spring model.
        """
        return self if name is None or name == self.spring.model else self.replace(spring=self.spring.with_model(name))

    def with_settings(self, settings: RunSettings | None = None, **changes) -> ValveModel:
        """The same model run with other settings.

        Parameters
        ----------
        settings : RunSettings, optional
            New settings (default: this model's).
        **changes
            Fields of :class:`RunSettings` to change.
        """
        return self.replace(settings=RunSettings.of(self.settings if settings is None else settings, **changes))

    def with_gas_pressure(self, path, port_pressure: float = 101325.0) -> ValveModel:
        """The same model with the gas force of a cylinder-pressure trace on its valve
        (:meth:`springdyn.valve.train.gas_force.GasForce.from_file`), phased by the ``[timing]``
        table, over the valve train's ``seat_diameter``.

        Parameters
        ----------
        path : str or path-like
            The trace: crank angle against absolute cylinder pressure (CSV).
        port_pressure : float
            Pressure behind the valve head, absolute [Pa].
        """
        if self.valve_train is None:
            raise InputError(
                "the gas force acts on the valve: give --valve-train / [valve_train] (the spring alone has no valve)"
            )
        vt = self.valve_train
        if vt.seat_diameter is None:
            raise InputError("the gas force needs the valve's seat_diameter in [valve_train]")
        if self.timing is None:
            raise InputError(
                "the cylinder pressure is against crank angle: the cam file needs a [timing] table (lobe_centre, "
                "valve) to phase it"
            )
        if not Path(path).is_file():
            what = "is a folder, not a CSV file" if Path(path).is_dir() else "no such file"
            raise InputError(f"path = {str(path)!r}: {what} (the cylinder pressure)")
        gas = train_wing.GasForce.from_file(
            path,
            axis=crank_axis(self._need_cam("the gas force"), self.timing),
            seat_diameter=vt.seat_diameter,
            port_pressure=port_pressure,
        )
        return self.replace(gas_force=gas)

    def spring_alone(self) -> ValveModel:
        """The spring alone driven by the valve lift of this model's train: the lobe lift times
        the rocker ratio, or a drawn lever's valve lift over the cam (:meth:`lever_kinematics`);
        this model itself without a train.  Its crank angles are this model's (the lobe's)."""
        vt = self.valve_train
        if vt is None or self.cam is None:
            return self
        if vt.geometry is not None:
            lever = self.lever_kinematics(lash=0.0)
            cam = Cam.from_table(
                lever.cam_angle, np.maximum(lever.solution["valve_lift"], 0.0), name="valve lift of the lever"
            )
        else:
            cam = self.cam if vt.ratio == 1.0 else self.cam.scaled(vt.ratio)
        alone = self.replace(cam=cam, valve_train=None, gas_force=None)
        alone.__dict__["crank_axis"] = self.crank_axis  # its crank angles stay the lobe's (the engine's)
        return alone

    def service_speeds(self, low_cam_rpm: float, rated_cam_rpm: float, step: float, float_margin: float = 0.0):
        """The named study's speed range "in service and past the float speed": from ``low`` up to
        10 % past the float speed the criteria ask for (the rated speed plus ``float_margin``;
        the rated speed itself for the spring alone), in ``step`` [rev/min].

        Parameters
        ----------
        low_cam_rpm, rated_cam_rpm : float
            The lowest and the highest cam speed in service [rev/min].
        step : float
            The step [rev/min] (the smallest Goodman safety is a resonance's, which a coarse step misses).
        float_margin : float
            How far above the rated speed the float speed is asked for [fraction].
        """
        hi = 1.1 * rated_cam_rpm * (1.0 + float_margin) if self.valve_train is not None else rated_cam_rpm
        return np.arange(low_cam_rpm, hi + step, step)

    # ------------------------------------------------------------------ derived once
    @cached_property
    def chain_model(self):
        """The spring's chain model (:class:`~springdyn.valve.spring.chains.SpringModel`)."""
        return self.spring.spring_model

    @cached_property
    def setup(self):
        """The engine's speed-independent set-up: cam table, initial state, the train's
        parameters with the gas force (:func:`springdyn.valve.run.setup.prepare`)."""
        return run_wing.prepare(self.spring, self._need_cam("the set-up"), self.valve_train, self.gas_force)

    @property
    def engine_variant(self) -> tuple:
        """The compiled engine this model's runs use: ``(pair, kind, pack)``, its Runge-Kutta
        pair (:func:`~springdyn.valve.run.runner.runge_kutta_pair`, e.g. ``"dopri5"``), ``"spring"``
        (alone) or ``"train"``, and True for a spring pack (one key of
        :data:`springdyn.valve.engine.loop.VARIANTS`, with the pack as a flag)."""
        kind = "spring" if self.valve_train is None else "train"
        return run_wing.runge_kutta_pair(self.setup, self.settings), kind, isinstance(self.spring, SpringPack)

    @cached_property
    def crank_axis(self):
        """Crank angles and engine speeds beside the cam's (:class:`~springdyn.valve.cam.timing.CrankAxis`),
        or None (:attr:`crank_angles` false or no cam)."""
        if not self.crank_angles or self.cam is None:
            return None
        return crank_axis(self.cam, self.timing)

    @property
    def strokes(self) -> int:
        """Strokes of the engine's cycle (the ``[timing]`` table's; a four-stroke by default) [-]."""
        return self.timing.strokes if self.timing is not None else 4

    def cam_rpm(self, engine_rpm):
        """The cam speed [rev/min] of an engine speed [rev/min] (:attr:`strokes`).

        Parameters
        ----------
        engine_rpm : float or array_like
            Engine speed [rev/min].
        """
        return cam_rpm_from_engine_rpm(engine_rpm, self.strokes)

    def _one_spring(self, what: str) -> None:
        """Refuse a spring pack where an analysis covers one spring only (docs/valve-spring.md, "Spring packs")."""
        if isinstance(self.spring, SpringPack):
            raise InputError(
                f"{what} covers one spring, not a spring pack ({self.spring!r}): run it on each spring's own "
                "file, or run the pack through valve simulate, sweep, float, train-modes, clearance, cam-check or "
                "springdyn report"
            )

    def _need_cam(self, what: str) -> Cam:
        if self.cam is None:
            raise InputError(f"{what} needs a cam: ValveModel(spring, cam=Cam(...))")
        return self.cam

    def _need_train(self, what: str) -> ValveTrain:
        if self.valve_train is None:
            raise InputError(f"{what} needs a valve train: ValveModel(spring, cam, valve_train=ValveTrain(...))")
        return self.valve_train

    def _with_axis(self, result):
        if self.crank_axis is not None:
            result.set_crank_axis(self.crank_axis)
        return result

    # ------------------------------------------------------------------ the spring alone
    def internal_parameters(self) -> dict:
        """The model's internal parameters (K, K1, Kh1, m1, f1, Fset, ... [SI])."""
        return self.chain_model.internal_parameters()

    def parameter_table(self):
        """The internal parameters with their units and meaning, the coils and the drawing's load
        points (:class:`~springdyn.valve.spring.results.SpringParameters`)."""
        self._one_spring("valve params")
        return spring_wing.SpringParameters.of(self.spring)

    def static_force(self, length):
        """Static force [N] at the spring length(s) [m].

        Parameters
        ----------
        length : float or array_like
            Spring length [m].
        """
        return self.chain_model.static_force(length)

    @_DOCS.fill
    def static_curve(self, start: float | None = None, stop: float | None = None, points: int = 400):
        """The static force and stiffness against length (:class:`~springdyn.valve.spring.results.StaticCurve`).

        Parameters
        ----------
        {start_stop points}
        """
        self._one_spring("valve curve")
        return self.chain_model.static_curve(start, stop, points)

    @_DOCS.fill
    def modes(self, length: float, count: int = 5):
        """Natural frequencies [Hz] of the chain at a length, both ends fixed.

        Parameters
        ----------
        {length count}
        """
        return self.chain_model.modes(length, count)

    @_DOCS.fill
    def chain_modes(self, length: float, count: int = 5):
        """The chain's natural frequencies at a length with what moves in each
        (:class:`~springdyn.valve.spring.results.ChainModes`).

        Parameters
        ----------
        {length count}
        """
        self._one_spring("valve modes")
        return spring_wing.ChainModes.of(self.spring, length, count)

    def design_figures(self, lift: float | None = None, cam_rpm: float | None = None):
        """Spring index, corrected stresses, surge margin, coil bind, static fatigue
        (:class:`~springdyn.valve.spring.results.DesignFigures`; its ``figures`` dict is
        :meth:`~springdyn.valve.spring.chains.SpringModel.design_figures`).

        Parameters
        ----------
        lift : float, optional
            Valve lift [m] (default: the cam's).
        cam_rpm : float, optional
            Cam speed [rev/min] for the surge margin.
        """
        self._one_spring("valve design")
        if lift is None and self.cam is not None:
            lift = self.cam.lift
        return spring_wing.DesignFigures(self.spring, self.chain_model.design_figures(lift, cam_rpm), cam_rpm)

    def dynamic_stiffness(self, frequency, length: float | None = None):
        """The linearised dynamic stiffness of the spring (:class:`~springdyn.valve.spring.frf.FrequencyResponse`).

        Parameters
        ----------
        frequency : array_like
            Frequencies [Hz].
        length : float, optional
            Spring length [m] (default: installed).
        """
        self._one_spring("valve frf")
        return spring_wing.dynamic_stiffness(self.spring, frequency, length)

    def calibrate(self, fit: str = "shear_modulus") -> dict:
        """The shear modulus or the active coils fitted to the drawing's load points
        (:func:`springdyn.valve.design.calibrate.calibrate`).

        Parameters
        ----------
        fit : {"shear_modulus", "active_coils"}
            What to fit.
        """
        self._one_spring("valve calibrate")
        return design_wing.calibrate(self.spring, fit)

    def calibrate_trace(self, cam_rpm: float, cam_angle, retainer_force, fit=("damping_ratio", "contact_stiffness")):
        """The damping and the coils' contact stiffness fitted to a measured retainer-force trace
        (:func:`springdyn.valve.design.calibrate.calibrate_trace`).

        Parameters
        ----------
        cam_rpm, cam_angle, retainer_force, fit : float, array_like, array_like, sequence of str
            The measurement's cam speed [rev/min], cam angles [rad] and retainer forces [N], and
            what to fit, as :func:`~springdyn.valve.design.calibrate.calibrate_trace` takes them.
        """
        self._one_spring("the trace calibration")
        return design_wing.calibrate_trace(
            self.spring, self._need_cam("calibrate_trace"), cam_rpm, cam_angle, retainer_force, fit
        )

    # ------------------------------------------------------------------ the cam
    def cam_analysis(self, engine_rpm: float | None = None):
        """The cam checked first: lift and its derivatives, timing at the check heights
        (:class:`~springdyn.valve.cam.analysis.CamAnalysis`; at the valve with a train).

        Parameters
        ----------
        engine_rpm : float, optional
            Engine speed [rev/min]: crank angles and the derivatives in time.
        """
        return cam_wing.analyse_cam(self._need_cam("cam_analysis"), self.valve_train, engine_rpm, timing=self.timing)

    def cam_check(self, cam_rpm: float | None = None):
        """Curvature, undercut, excursion, pressure angle and Hertz stress along the cam, with
        the spring's load at ``cam_rpm`` (:class:`~springdyn.valve.cam.checks.CamCheck`).

        Parameters
        ----------
        cam_rpm : float, optional
            Cam speed of the load [rev/min] (None: the geometric checks only).
        """
        if self.follower is None:
            raise InputError("the cam checks need the follower: a [follower] table beside [valve_train]")
        return cam_wing.check_cam(
            self._need_cam("cam_check"),
            self._need_train("cam_check"),
            self.follower,
            spring=self.spring,
            cam_rpm=cam_rpm,
        )

    def lever_kinematics(self, lash: float | None = None):
        """The drawn lever over the cam: its ratio, arms and mass over the lift
        (:class:`~springdyn.valve.train.lever.LeverTable`).

        Parameters
        ----------
        lash : float, optional
            Lash at the valve [m] (default: the train's; none with a hydraulic adjuster).
        """
        vt = self._need_train("lever_kinematics")
        if vt.geometry is None:
            raise InputError(
                "the lever's kinematics need its drawing: a [geometry] table beside [valve_train] and [follower]; "
                f"without it the ratio is the constant {vt.ratio:g}"
            )
        lash = (0.0 if vt.hydraulic else vt.lash) if lash is None else lash
        return vt.geometry.over_cam(self._need_cam("lever_kinematics"), lash=lash, inertia=vt.lever_inertia)

    # ------------------------------------------------------------------ under the cam
    def natural_frequencies(self, count: int = 8):
        """Natural frequencies of spring and valve train on the base circle and at full lift
        (:class:`~springdyn.valve.run.results.NaturalFrequencies`).

        Parameters
        ----------
        count : int
            Frequencies per state [-].
        """
        out = run_wing.natural_frequencies(self.spring, self._need_cam("natural_frequencies"), self.valve_train, count)
        return run_wing.NaturalFrequencies(
            out["base_circle_Hz"], out["full_lift_Hz"], out["full_lift_cam_angle_deg"], out["notes"]
        )

    def separated_frequencies(self, count: int = 8, valve_lift: float | None = None) -> dict:
        """Natural frequencies of the separated train, its first the jump frequency
        (:func:`springdyn.valve.run.train_modes.separated_frequencies`).

        Parameters
        ----------
        count : int
            Frequencies [-].
        valve_lift : float, optional
            Valve lift of the held state [m] (default: full lift).
        """
        return run_wing.separated_frequencies(
            self.spring, self._need_cam("separated_frequencies"), self.valve_train, count, valve_lift
        )

    def resonance_speeds(self, cam_rpm_min: float, cam_rpm_max: float, count: int = 6):
        """The named study "resonances in a range": the modes under the cam and the cam speeds
        where a cam order meets one (:class:`~springdyn.valve.run.results.NaturalFrequencies`
        with its ``resonances`` over the range).

        Parameters
        ----------
        cam_rpm_min, cam_rpm_max : float
            The speed range [rev/min].
        count : int
            Frequencies per state [-].
        """
        nat = self.natural_frequencies(count)
        return nat.with_resonances(cam_rpm_min, cam_rpm_max)

    def _run_inputs(self, changes: dict, setup: bool = True) -> dict:
        """The train, the settings with ``changes`` and (with ``setup``) the cached set-up of a run."""
        inputs = dict(valve_train=self.valve_train, settings=RunSettings.of(self.settings, **changes))
        return {**inputs, "setup": self.setup} if setup else inputs

    def simulate(self, cam_rpm: float, revolutions: int | None = None, **changes):
        """The dynamic response at one cam speed (:class:`~springdyn.valve.run.results.Simulation`).

        Parameters
        ----------
        cam_rpm : float
            Cam speed [rev/min].
        revolutions : int, optional
            Revolutions from rest; the last is reported [-].  Default: this model's settings
            (to the periodic steady state).
        **changes
            Fields of :class:`RunSettings` to change for this run.
        """
        if revolutions is not None:
            changes["revolutions"] = revolutions
        run = run_wing.simulate(self.spring, self._need_cam("simulate"), cam_rpm, **self._run_inputs(changes))
        return self._with_axis(run)

    def sweep(self, cam_rpm, *, vary=None, on_invalid: str = "stop", workers=None, client=None, quiet=True, **changes):
        """Every cam speed of ``cam_rpm`` (and every design value of ``vary``)
        (:class:`~springdyn.valve.run.sweeps.SpeedSweep`).

        Parameters
        ----------
        cam_rpm : array_like
            Cam speeds [rev/min].
        vary : (str, array_like), optional
            A numeric spring field and its values [SI].
        on_invalid : {"stop", "skip"}
            A design value that makes the spring invalid.
        workers : int, optional
            Local threads [-].
        client : dask.distributed.Client, optional
            Run on this cluster.
        quiet : bool
            No progress bar.
        **changes
            Fields of :class:`RunSettings` to change for this sweep.
        """
        return self._with_axis(
            run_wing.sweep(
                self.spring,
                self._need_cam("sweep"),
                cam_rpm,
                **self._run_inputs(changes, setup=False),
                vary=vary,
                on_invalid=on_invalid,
                workers=workers,
                client=client,
                quiet=quiet,
                gas_force=self.gas_force,
            )
        )

    def float_speed(self, cam_rpm, *, resolution: float = 1.0, quiet: bool = True, workers=None, **changes):
        """The float speed of the valve train (:class:`~springdyn.valve.run.results.FloatSpeedResult`).

        Parameters
        ----------
        cam_rpm : array_like
            Cam speeds to scan [rev/min].
        resolution : float
            Width of the final bracket [rev/min].
        quiet : bool
            No progress bar.
        workers : int, optional
            Local threads of the scan [-].
        **changes
            Fields of :class:`RunSettings` to change for this search.
        """
        return self._with_axis(
            run_wing.float_speed(
                self.spring,
                self._need_cam("float_speed"),
                self._need_train("float_speed"),
                cam_rpm,
                settings=RunSettings.of(self.settings, **changes),
                resolution=resolution,
                progress_quiet=quiet,
                workers=workers,
            )
        )

    def float_speed_above(self, rated_cam_rpm: float, margin: float = 0.0, *, resolution: float = 1.0):
        """The named study "float speed against a rated speed": the float speed searched over
        :data:`FLOAT_SCAN` of the rated speed up to past the float speed asked for, ``(1 +
        margin)`` times the rated speed (:meth:`float_speed`).

        Parameters
        ----------
        rated_cam_rpm : float
            The highest cam speed in service [rev/min].
        margin : float
            How far above it the float speed is asked for [fraction].
        resolution : float
            Width of the final bracket [rev/min].
        """
        lo, hi, n = FLOAT_SCAN
        need = rated_cam_rpm * (1.0 + margin)
        return self.float_speed(np.linspace(lo * rated_cam_rpm, hi * need, n), resolution=resolution)

    def speed_ramp(self, start_rpm: float, end_rpm: float, rate_rpm_per_s: float, *, float_scan: bool = True):
        """The valve train through a cam-speed ramp (:class:`~springdyn.valve.run.run_up.RunUp`).

        Parameters
        ----------
        start_rpm, end_rpm : float
            Cam speeds at the ramp's start and end [rev/min].
        rate_rpm_per_s : float
            Rate of the cam speed [rev/min per s].
        float_scan : bool
            Also find the steady-state float speed of the range.
        """
        self._one_spring("a speed ramp")
        return run_wing.speed_ramp(
            self.spring,
            self._need_cam("speed_ramp"),
            self.valve_train,
            start_rpm,
            end_rpm,
            rate_rpm_per_s,
            settings=self.settings,
            float_scan=float_scan,
        )

    def run_up_through_float(self, float_cam_rpm: float, rate_rpm_per_s: float):
        """The named study "run-up through the float speed": a ramp over :data:`RUN_UP_WINDOW` of
        the float speed ``f`` at the given rate (:meth:`speed_ramp`, no float scan: ``f`` is known,
        and the ramp carries it as its ``steady_float_cam_rpm``, which its figure marks).

        Parameters
        ----------
        float_cam_rpm : float
            The steady-state float speed [rev/min].
        rate_rpm_per_s : float
            Rate of the cam speed [rev/min per s].
        """
        a, b = RUN_UP_WINDOW
        ramp = self.speed_ramp(a * float_cam_rpm, b * float_cam_rpm, rate_rpm_per_s, float_scan=False)
        return dataclasses.replace(ramp, steady_float_cam_rpm=float(float_cam_rpm))  # known: its figure marks it

    def valve_clearance(self, cam_rpm, *, limit: float | None = None, quiet: bool = True, workers=None, **changes):
        """The valve-to-piston clearance over the speeds: the simulated valve (float and bounce
        included) against the piston's crank-slider of the ``[piston]`` table, its smallest value
        and crank angle at each speed, the rigid train's (static) clearance beside it
        (:class:`~springdyn.valve.train.piston.ValveClearance`, the speed map; needs a valve
        train and the ``[timing]`` table).

        Parameters
        ----------
        cam_rpm : array_like
            Cam speeds [rev/min] (a sweep, :meth:`sweep`).
        limit : float, optional
            Smallest clearance [m] (default: :class:`~springdyn.valve.design.criteria.Criteria`'s
            ``min_valve_piston_clearance``).
        quiet : bool
            No progress bar.
        workers : int, optional
            Local threads of the sweep [-].
        **changes
            Fields of :class:`RunSettings` to change for this sweep.
        """
        if self.piston is None:
            raise InputError(
                "the valve-to-piston clearance needs the piston: a [piston] table (bore, stroke, rod_length, "
                "tdc_clearance, ... or clearance_table) in the valve-train, cam or spring file"
            )
        vt = self._need_train("the valve-to-piston clearance")
        cam = self._need_cam("the valve-to-piston clearance")
        if self.timing is None:
            raise InputError(
                "the valve-to-piston clearance is against crank angle: the cam file needs a [timing] table "
                "(lobe_centre, valve) to place the valve's lift on the piston's stroke"
            )
        sw = self.sweep(cam_rpm, quiet=quiet, workers=workers, **changes)
        limit = design_wing.Criteria().min_valve_piston_clearance if limit is None else limit
        return train_wing.clearance_map(
            self.piston,
            crank_axis(cam, self.timing),
            sw.cam_angle,
            sw.data["valve_lift"][0],
            train_wing.static_valve_lift(cam, vt, sw.cam_angle),
            sw.cam_rpm,
            valve=self.timing.valve,
            limit=limit,
        )

    def friction(self, cam_rpm: float):
        """The train's friction over a simulated revolution at ``cam_rpm``
        (:class:`~springdyn.valve.train.friction.FrictionAnalysis`; needs the follower).

        Parameters
        ----------
        cam_rpm : float
            Cam speed [rev/min].
        """
        self._one_spring("valve friction")
        if self.follower is None:
            raise InputError(
                "friction at the cam needs the follower: a [follower] table beside [valve_train] (see "
                "examples/valve/valve_train_with_follower.toml)"
            )
        self._need_train("friction")
        friction = self.friction_table
        if friction is None and self.oil is not None:  # the friction's defaults with the train's oil
            friction = train_wing.Friction(oil=self.oil)
        return run_wing.simulation_friction(self.simulate(float(cam_rpm)), self.follower, friction)

    def friction_over_speed(self, cam_rpm, *, quiet: bool = True):
        """The named study "friction over a speed range": each speed simulated to its periodic
        state and its friction (:class:`~springdyn.valve.run.friction.FrictionSweep`).

        Parameters
        ----------
        cam_rpm : array_like
            Cam speeds [rev/min]; two values are a range's ends, filled to
            :data:`FRICTION_SPEEDS` speeds.
        quiet : bool
            No progress bar.
        """
        speeds = np.atleast_1d(np.asarray(cam_rpm, dtype=float))
        return run_wing.friction_over_speed(
            [self.friction(float(r)) for r in progress(speeds, desc="friction", quiet=quiet)]
        )

    def tolerance_study(self, tolerances: dict, criteria=None, **options):
        """The spring (or the spring pack, each spring's own tolerances) across its manufacturing
        tolerances (:class:`~springdyn.valve.design.tolerances.ToleranceStudy`).

        Parameters
        ----------
        tolerances : dict
            name -> (Tolerance, relative) (:func:`springdyn.valve.design.tolerances.read_tolerances`).
        criteria : Criteria, optional
            The limits each variant is judged against.
        **options
            Further options of :func:`springdyn.valve.design.tolerances.tolerance_study` (count,
            seed, speeds, method, out_dir, client, progress, float_only, resolution, workers,
            periodicity_tol, warm_starts, screen).
        """
        study = design_wing.tolerance_study(
            self.spring,
            self._need_cam("tolerance_study"),
            tolerances,
            criteria,
            valve_train=self.valve_train,
            **options,
        )
        return dataclasses.replace(study, engine_per_cam=self.strokes / 2.0)  # engine rpm beside the cam's

    def service_life(self, spectrum, float_speeds=None):
        """Relaxation and load-spectrum life (:class:`~springdyn.valve.design.life.ServiceLife`).

        Parameters
        ----------
        spectrum : LoadSpectrum
            The ``[spectrum]`` table.
        float_speeds : array_like, optional
            Cam speeds of the float-speed scans [rev/min].
        """
        self._one_spring("valve life")
        return design_wing.service_life(
            self.spring, self._need_cam("service_life"), spectrum, self.valve_train, float_speeds
        )


def _piston_of(*paths):
    """The one ``[piston]`` table of the definition files (None: none has one)."""
    found = {}
    for path in paths:
        if path is not None and Path(path).resolve() not in found:
            piston = train_wing.Piston.in_file(path)
            if piston is not None:
                found[Path(path).resolve()] = (path, piston)
    if len(found) > 1:
        names = ", ".join(str(p) for p, _ in found.values())
        raise InputError(f"[piston] is given in {names}: give the piston once (in the valve-train file)")
    return next(iter(found.values()))[1] if found else None
