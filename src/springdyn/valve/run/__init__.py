"""The run wing: the spring (and its valve train) driven by the cam, at one speed or many.

- :mod:`.settings` -- :class:`RunSettings`: how every run is integrated, checked once;
- :mod:`.setup` -- :class:`SimulationSetup`, everything the engine needs for one spring, cam
  and train that does not depend on the speed (cam table, initial state, train parameters),
  data only, and its static force;
- :mod:`.runner` -- :func:`run_speeds`, the one call of the compiled engine;
- :mod:`.simulation` -- :func:`simulate`: one speed to its periodic state;
- :mod:`.periodicity` -- the periodic steady state every result per speed is;
- :mod:`.separation` -- lift-offs by cam phase, float over the nose, seat bounce;
- :mod:`.float_search` -- :func:`float_speed` and the search of a variant's float speed;
- :mod:`.sweeps` -- :func:`sweep` over speeds and design values, local or on Dask;
- :mod:`.run_up` -- speed ramps: lift-off and float against the momentary speed;
- :mod:`.studies` -- speed studies of one design: a sweep refined at the float speed and the
  worst speeds, a variant's float speed near a guess;
- :mod:`.train_modes` -- natural frequencies under the cam, resonance speeds;
- :mod:`.friction` -- the friction of a simulated revolution and over speed;
- :mod:`.verdicts` -- the rules that judge a revolution (valve open, float, clash, pump-up,
  wire fatigue), one home each for a simulation and a sweep;
- :mod:`.results` -- :class:`Simulation`, :class:`FloatSpeedResult`,
  :class:`NaturalFrequencies`, and :mod:`.plots` their figures.

It imports the spring, cam and train wings and the engine below them.
"""

from __future__ import annotations

from ..._lazy import lazy_package

_EXPORTS = {
    "RunSettings": "settings",
    "SimulationSetup": "setup",
    "prepare": "setup",
    "run_speeds": "runner",
    "runge_kutta_pair": "runner",
    "simulate": "simulation",
    "sweep": "sweeps",
    "SpeedSweep": "sweeps",
    "float_speed": "float_search",
    "float_speed_near": "float_search",
    "speed_ramp": "run_up",
    "speed_study": "studies",
    "variant_float_speed": "studies",
    "RunUp": "run_up",
    "PeriodicStates": "periodicity",
    "natural_frequencies": "train_modes",
    "separated_frequencies": "train_modes",
    "simulation_friction": "friction",
    "friction_over_speed": "friction",
    "FrictionSweep": "friction",
    "Simulation": "results",
    "FloatSpeedResult": "results",
    "NaturalFrequencies": "results",
}
__all__ = sorted(_EXPORTS)

lazy_package(__name__, _EXPORTS)
