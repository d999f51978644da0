"""The compiled valve engine: time integration of the spring's chain (and valve train).

Module map (one reason to change each):

- :mod:`.layout`: the named indices of every array the engine reads or writes.
- :mod:`.equations`: the equations of motion, the cam the engine sees, the contact laws of
  the ends and of the valve train's links (plain Python, with their compiled twins).
- :mod:`.hydraulics`: the oil's scalar laws the compiled adjuster and the Python one share.
- :mod:`.cam_table`: :class:`CamTable`, the cam's sampled table, its interpolant on arrays
  and the angles a step lands on.
- :mod:`.stepping`: one Runge-Kutta step of each pair on the chain.
- :mod:`.loop`: the integration loops (adaptive steps, breakpoints, outputs, many speeds).
- :mod:`.monitor`: true extremes and events on the dense output.
- :mod:`.reference`: the NumPy / SciPy twins the tests and benchmarks compare with.
- :mod:`.static_force`: the compiled static force of the series chain.
- :mod:`.api`: the Python face below (argument tuples to model arrays, allocation, notices).

This module is the engine's Python face: :func:`integrate`, :func:`integrate_speeds` (compiled,
an adaptive embedded Runge-Kutta pair with dense output, :mod:`springdyn.numerics.erk`:
Dormand-Prince 5(4), Bogacki-Shampine 3(2) or Tsitouras 5(4)) and :func:`integrate_scipy`
(the reference).  Every kernel is a :func:`springdyn.numerics.jit.kernel`: cached on disk
under a stamp of all the engine's sources, compiled only for the pair and the model a call
uses, announced on stderr when it compiles.
"""

from __future__ import annotations

from ..._lazy import lazy_package

_EXPORTS = {
    "integrate": "api",
    "integrate_speeds": "api",
    "model_of": "equations",
    "train_of": "equations",
    "COMPILE_SECONDS": "api",
    "integrate_scipy": "reference",
    "CamTable": "cam_table",
    "atol_vector": "reference",
    "hermite5": "equations",
    "chain_rhs": "equations",
    "train_response": "equations",
    "damper_friction": "equations",
    "rhs_call": "equations",
    "rhs_kernel": "equations",
    "NO_EXTRA": "equations",
    "EngineModel": "equations",
    "series_force_compiled": "static_force",
    "extra_layout": "layout",
    "STATUS": "layout",
    "EXTRA": "layout",
    "EXT": "layout",
    "N_EXT": "layout",
    "EVENT_KINDS": "layout",
    "MAX_EVENTS": "layout",
    "VT_SIZE": "layout",
}
__all__ = sorted(_EXPORTS)

lazy_package(__name__, _EXPORTS)
