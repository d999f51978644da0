"""springdyn: dynamics of springs and spring dampers in machines.

Model families, one subpackage each:

- :mod:`springdyn.valve` -- multi-mass (MMS Type C) valve springs, one-step and two-step.
- :mod:`springdyn.cfcs` -- constant-force compression springs (pseudo-rigid-body model).
- :mod:`springdyn.lsd` -- leaf spring dampers for rotors.

Shared pieces: :mod:`springdyn.core` (units: pint at the edges, SI floats inside; params:
TOML parameters with validation; io: atomic CSV/JSON; results; plotting; progress;
errors) and :mod:`springdyn.numerics` (the compiled kernels and Runge-Kutta pairs).
The command line and the report live in :mod:`springdyn.app`; the built-in example
definitions (TOML) in ``springdyn.data``.
"""

from .core.errors import InputError, SolverError, SpringdynError

__version__ = "0.1.0"

__all__ = ["InputError", "SolverError", "SpringdynError", "__version__"]
