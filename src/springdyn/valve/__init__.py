"""Valve springs: multi-mass models of helical valve springs driven by a cam through a valve train.

Start here: :class:`ValveModel` (:mod:`~springdyn.valve.model`), a spring with its cam and
valve train and every analysis of them, built from the definitions :class:`ValveSpring`
(``[spring]``), :class:`Cam` (``[cam]``) and :class:`ValveTrain` (``[valve_train]``), and run
with one :class:`RunSettings`.

The family is built in wings, each importing only the wings below it (``tests/valve/test_wings.py``
keeps the order):

- :mod:`~springdyn.valve.engine` -- the ground floor: the compiled equations of motion and
  their integrator;
- :mod:`~springdyn.valve.spring` -- the spring alone: its definition and material, the laws of
  its wire and coils, statics, modes, solid length, stress, the chain models;
- :mod:`~springdyn.valve.cam` -- the cam: lift laws and tables, its analysis and checks, the
  lobe from a wanted valve lift, the engine's timing, the follower;
- :mod:`~springdyn.valve.train` -- the valve train: layouts, a drawn lever, the hydraulic lash
  adjuster, the gas force, the friction laws, the oil;
- :mod:`~springdyn.valve.run` -- the spring and train driven by the cam: the run settings and
  set-up, one speed, sweeps, the float speed, run-ups, modes under the cam, the friction of a
  run, the rules that judge a run, results and figures;
- :mod:`~springdyn.valve.design` -- springs from requirements, across tolerances, over their
  life, calibrated to their drawing, and the one set of pass/fail criteria;
- :mod:`~springdyn.valve.camshaft` -- several valves on one camshaft with its torsion and timing
  drive (:class:`CamshaftModel`): each valve's run on its twisting lobe, the drive torque, the
  twist and the timing errors, the shaft's torsional modes;
- :mod:`~springdyn.valve.model` -- :class:`ValveModel` on top, the front door the CLI and the
  report call.

The names below load their modules on first use, so that ``import springdyn.valve`` stays
quick (the compiled engine, numba, loads only when a simulation needs it).
"""

from __future__ import annotations

from .._lazy import lazy_package

_EXPORTS = {
    # the front door
    "ValveModel": "model",
    "RunSettings": "run.settings",
    # the definitions
    "ValveSpring": "spring.definition",
    "SpringPack": "spring.pack",
    "MODEL_NAMES": "spring.definition",
    "Cam": "cam.definition",
    "Timing": "cam.timing",
    "Follower": "cam.follower",
    "ValveTrain": "train.definition",
    "GasForce": "train.gas_force",
    "Friction": "train.friction",
    "Oil": "train.oil",
    "oil_of": "train.oil",
    "Piston": "train.piston",
    # the spring models
    "Chain": "spring.chains",
    "SpringModel": "spring.chains",
    "TypeCModel": "spring.chains",
    "MODELS": "spring.chains",
    "PARAMETER_UNITS": "spring.formulas",
    # results
    "StaticCurve": "spring.results",
    "Simulation": "run.results",
    "FloatSpeedResult": "run.results",
    "NaturalFrequencies": "run.results",
    "SpeedSweep": "run.sweeps",
    "ValveClearance": "train.piston",
    # several valves on one camshaft with its torsion (issue 41)
    "CamshaftModel": "camshaft.coupled",
    "Camshaft": "camshaft.definition",
    "CamshaftRun": "camshaft.results",
    "CamshaftSweep": "camshaft.results",
    "TorsionalModes": "camshaft.results",
    # the analyses as functions (ValveModel's methods call them)
    "simulate": "run.simulation",
    "float_speed": "run.float_search",
    "sweep": "run.sweeps",
    "analyse_cam": "cam.analysis",
    "connect": "run.sweeps",
    # speeds and run defaults, for the application layer's options
    "cam_rpm_from_engine_rpm": "cam.timing",
    "engine_rpm_from_cam_rpm": "cam.timing",
    "DEFAULT_RTOL": "run.settings",
    "DEFAULT_ATOL": "run.settings",
    "TRAIN_RTOL": "run.settings",
    "TRAIN_ATOL": "run.settings",
    "BACKENDS": "run.settings",
    "PERIODICITY_TOL": "run.periodicity",
    "MAX_REVOLUTIONS": "run.periodicity",
    # what results say in words
    "coil_line": "spring.results",
    "load_points_text": "spring.results",
    "separated_train_text": "run.train_modes",
    "crank_words": "cam.timing",
    "calibrated_keys": "design.calibrate",
    "read_force_trace": "design.calibrate",
    "load_point_lines": "design.calibrate",
}

__all__ = list(_EXPORTS)


lazy_package(__name__, _EXPORTS)
