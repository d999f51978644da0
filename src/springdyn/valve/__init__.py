"""Valve springs: the MMS Type C multi-mass model (one-step and two-step).

Where to find each piece:

- :mod:`~springdyn.valve.formulas` -- closed-form internal parameters and model variables;
- :mod:`~springdyn.valve.elements` -- nonlinear element laws (linear / quadratic /
  coil-contact quadratic) and the damping law;
- :mod:`~springdyn.valve.statics` -- series equilibrium (static force, stiffness, set-up state);
- :mod:`~springdyn.valve.modes` -- natural frequencies of the linearised chain;
- :mod:`~springdyn.valve.design` -- spring index, corrected shear stress, surge margin;
- :mod:`~springdyn.valve.spring` -- :class:`ValveSpring` (the ``[spring]`` table) and its chain;
- :mod:`~springdyn.valve.cam` -- cam lift laws and measured lift tables (``[cam]``);
- :mod:`~springdyn.valve.valvetrain` -- valve body with cam and seat contacts (``[valve_train]``);
- :mod:`~springdyn.valve.engine` -- equations of motion and the compiled integrator;
- :mod:`~springdyn.valve.dynamics` -- :func:`simulate`, :class:`Simulation`, :func:`float_speed`;
- :mod:`~springdyn.valve.sweeps` -- :func:`sweep` over speeds and design values, local or Dask.
"""

from .cam import Cam
from .dynamics import Simulation, float_speed, simulate
from .results import StaticCurve
from .spring import Chain, ValveSpring
from .sweeps import SweepResult, sweep
from .valvetrain import ValveTrain

__all__ = ["ValveSpring", "Chain", "StaticCurve", "Cam", "ValveTrain", "simulate", "Simulation", "float_speed",
           "sweep", "SweepResult"]
