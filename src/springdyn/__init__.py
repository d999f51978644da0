"""springdyn: dynamics of springs and spring dampers in machines.

Model families, one subpackage each:

- :mod:`springdyn.valve` -- multi-mass (MMS Type C) valve springs, one-step and two-step.
- :mod:`springdyn.cfcs` -- constant-force compression springs (pseudo-rigid-body model).
- :mod:`springdyn.lsd` -- leaf spring dampers for rotors.

Shared pieces: :mod:`springdyn.units` (pint at the edges, SI floats inside),
:mod:`springdyn.config` (TOML parameters with validation), :mod:`springdyn.io`
(atomic CSV/JSON), :mod:`springdyn.plotting`, :mod:`springdyn.progress`.
"""

from .core.errors import InputError, SolverError, SpringdynError

__version__ = "0.1.0"

__all__ = ["InputError", "SolverError", "SpringdynError", "__version__"]
