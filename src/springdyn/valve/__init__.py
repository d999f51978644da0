"""Valve springs: the MMS Type C multi-mass model (one-step and two-step).

Where to find each piece:

- :mod:`~springdyn.valve.formulas` -- closed-form internal parameters and model variables;
- :mod:`~springdyn.valve.elements` -- nonlinear element laws (linear / quadratic /
  coil-contact quadratic) and the damping law;
- :mod:`~springdyn.valve.statics` -- series equilibrium (static force, stiffness, set-up state);
- :mod:`~springdyn.valve.modes` -- natural frequencies of the linearised chain;
- :mod:`~springdyn.valve.design` -- spring index, corrected shear stress, surge margin;
- :mod:`~springdyn.valve.spring` -- :class:`ValveSpring`, the definition (the ``[spring]`` table);
- :mod:`~springdyn.valve.model` -- the spring models (:class:`TypeCModel`, the document's
  MMS Type C chain) behind one interface, chosen by the ``model`` key;
- :mod:`~springdyn.valve.results` -- :class:`StaticCurve`, :class:`Simulation`,
  :class:`FloatSpeedResult` (the shared Result interface);
- :mod:`~springdyn.valve.cam` -- cam lift laws and measured lift tables (``[cam]``);
- :mod:`~springdyn.valve.valvetrain` -- valve body with cam and seat contacts (``[valve_train]``);
- :mod:`~springdyn.valve.engine` -- equations of motion and the compiled integrator;
- :mod:`~springdyn.valve.dynamics` -- :func:`simulate`, :class:`Simulation`, :func:`float_speed`;
- :mod:`~springdyn.valve.sweeps` -- :func:`sweep` over speeds and design values, local or Dask
  (:class:`SpeedSweep`).

The names below load their modules on first use, so that ``import springdyn.valve`` stays
quick (the compiled engine, numba, loads only when a simulation needs it).
"""

from __future__ import annotations

from .._lazy import lazy_package

_EXPORTS = {
    "ValveSpring": "spring",
    "Chain": "model",
    "SpringModel": "model",
    "TypeCModel": "model",
    "MODELS": "model",
    "StaticCurve": "results",
    "Simulation": "results",
    "FloatSpeedResult": "results",
    "Cam": "cam",
    "ValveTrain": "valvetrain",
    "simulate": "dynamics",
    "float_speed": "dynamics",
    "sweep": "sweeps",
    "SpeedSweep": "sweeps",
}

__all__ = [
    "ValveSpring",
    "SpringModel",
    "TypeCModel",
    "MODELS",
    "Chain",
    "StaticCurve",
    "Cam",
    "ValveTrain",
    "simulate",
    "Simulation",
    "float_speed",
    "FloatSpeedResult",
    "sweep",
    "SpeedSweep",
]


lazy_package(__name__, _EXPORTS)
