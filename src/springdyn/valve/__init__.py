"""Valve springs: multi-mass models of helical valve springs driven by a cam through a valve train.

Start here: :class:`ValveModel` (a spring, its cam and valve train, every analysis), built
from the definitions :class:`ValveSpring` (``[spring]``), :class:`Cam` (``[cam]``) and
:class:`ValveTrain` (``[valve_train]``).  Where each piece lives:

The definitions

- :mod:`~springdyn.valve.spring.definition` -- :class:`ValveSpring`, the ``[spring]`` table and its checks;
- :mod:`~springdyn.valve.cam.definition` -- cam lift laws and measured lift tables (``[cam]``);
- :mod:`~springdyn.valve.cam.analysis` -- the cam checked first: lift, velocity,
  acceleration, jerk, timing at check heights, lobe centre, ramps;
- :mod:`~springdyn.valve.cam.timing` -- the ``[timing]`` table: cam angles as crank angles from TDC
  ("12.0 deg BTDC") for every valve output;
- :mod:`~springdyn.valve.train.definition` -- layouts, masses, stiffnesses, lash (``[valve_train]``);
- :mod:`~springdyn.valve.train.hla` -- the hydraulic lash adjuster's plunger, chamber and oil (``[hla]``);
- :mod:`~springdyn.valve.train.gas_force` -- the cylinder's gas force on the valve head, phased by
  the cam's ``[timing]``;
- :mod:`~springdyn.valve.run.run_up` -- speed ramps: lift-off and float against the momentary speed;
- :mod:`~springdyn.valve.train.lever` -- a rocker arm or finger follower drawn in 2-D (``[geometry]``):
  the lift-dependent ratio, moment arms, contact points and mass at the valve;
- :mod:`~springdyn.valve.train.friction` -- friction at the cam, the roller, the stem guide and the
  pivot: the camshaft drive torque and the friction power (``[friction]``);
- :mod:`~springdyn.valve.cam.follower` -- the follower at the cam: flat face or roller, base
  circle, contact width, crown, materials, allowable contact stress (``[follower]``).

The spring designer's tools

- :mod:`~springdyn.valve.design.synthesis` -- valve springs from requirements (``[requirements]``):
  the lightest one-step and two-step springs that meet load points, space, Goodman, surge
  and float speed, ranked with their margins;
- :mod:`~springdyn.valve.design.tolerances` -- a spring across its manufacturing tolerances
  (``[tolerances]``, ``[criteria]``): Sobol or Monte Carlo variants, percentiles, failing shares;
- :mod:`~springdyn.valve.design.life` -- relaxation at the service temperature and the life against a
  load spectrum (``[spectrum]``);
- :mod:`~springdyn.valve.spring.materials` -- named spring wires (G, E, density, tensile strength
  against diameter), relaxation, load-spectrum life.

The cam designer's tools

- :mod:`~springdyn.valve.cam.from_lift` -- the lobe a wanted valve lift or a cam card
  (``[cam_card]``) needs through the train (the backward solution), with lash ramps;
- :mod:`~springdyn.valve.cam.checks` -- radius of curvature and undercut, flat-tappet contact
  excursion, pressure angle, Hertz stress along the cam, the cam's profile.

The physics, one place per equation

- :mod:`~springdyn.valve.spring.formulas` -- closed-form internal parameters and model variables ([MMS]);
- :mod:`~springdyn.valve.spring.elements` -- the element force laws (linear, quadratic, coil contact)
  and the damping law;
- :mod:`~springdyn.valve.spring.geometry` -- pitch and diameter profiles, open-coil compliance per turn;
- :mod:`~springdyn.valve.spring.statics` -- series equilibrium (static force, stiffness, set-up state);
- :mod:`~springdyn.valve.spring.modes` -- natural frequencies of the linearised chain;
- :mod:`~springdyn.valve.design` -- spring index, corrected shear stress, surge margin;
- :mod:`~springdyn.valve.durability` -- wire stress over a cycle, Goodman safety;
- :mod:`~springdyn.valve.spring.solid_length` -- solid length (by the end type) against the cam's lift,
  coil-bind clearance;
- :mod:`~springdyn.valve.design.calibrate` -- the drawing's load points against the model, and a fit
  of the shear modulus or the active coils to them;
- :mod:`~springdyn.valve.spring.chains` -- the spring models: :class:`Chain`, :class:`SpringModel`,
  :class:`TypeCModel` (the document's 5 masses), the distributed coil-by-coil chain;
- :mod:`~springdyn.valve.engine` -- the equations of motion and the compiled integrator.

The analyses and their results

- :mod:`~springdyn.valve.model` -- :class:`ValveModel`;
- :mod:`~springdyn.valve.run.setup` -- the engine's set-up for a spring, cam and train (cam
  table, initial state) and the run settings;
- :mod:`~springdyn.valve.run.simulation` -- :func:`simulate`;
- :mod:`~springdyn.valve.run.periodicity` -- the periodic steady state every result per speed is
  (tolerance, most revolutions, band);
- :mod:`~springdyn.valve.run.separation` -- lift-offs by cam phase, float over the nose, seat
  bounce, the seating velocity band;
- :mod:`~springdyn.valve.run.float_search` -- :func:`float_speed`;
- :mod:`~springdyn.valve.run.train_modes` -- natural frequencies under the cam, resonance speeds;
- :mod:`~springdyn.valve.spring.frf` -- the linearised dynamic stiffness;
- :mod:`~springdyn.valve.run.sweeps` -- :func:`sweep` over speeds and design values, local or Dask
  (:class:`SpeedSweep`);
- :mod:`~springdyn.valve.run.results` -- :class:`StaticCurve`, :class:`Simulation`,
  :class:`FloatSpeedResult`, :class:`NaturalFrequencies` (the shared Result interface);
- :mod:`~springdyn.valve.run.plots` -- their figures.

The names below load their modules on first use, so that ``import springdyn.valve`` stays
quick (the compiled engine, numba, loads only when a simulation needs it).
"""

from __future__ import annotations

from .._lazy import lazy_package

_EXPORTS = {
    "ValveModel": "model",
    "ValveSpring": "spring.definition",
    "Cam": "cam.definition",
    "ValveTrain": "train.definition",
    "Chain": "spring.chains",
    "SpringModel": "spring.chains",
    "TypeCModel": "spring.chains",
    "MODELS": "spring.chains",
    "StaticCurve": "spring.results",
    "Simulation": "run.results",
    "FloatSpeedResult": "run.results",
    "NaturalFrequencies": "run.results",
    "simulate": "run.simulation",
    "float_speed": "run.float_search",
    "sweep": "run.sweeps",
    "SpeedSweep": "run.sweeps",
}

__all__ = list(_EXPORTS)


lazy_package(__name__, _EXPORTS)
