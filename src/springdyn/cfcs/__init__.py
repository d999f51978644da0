"""Constant-force compression spring (CFCS): pseudo-rigid-body statics, dynamics, design.

The model of Ugwuoke, "A Simplified Dynamic Model for Constant-Force Compression
Spring" (the CFCS paper), with the corrections CFCS-1 to CFCS-4 of docs/references.md.
Where to find each equation:

- :mod:`.kinematics` -- loop closure, exact inverse x -> theta2, Jacobian (Eq. (25)), toggle.
- :mod:`.statics` -- spring energy (17), static force by virtual work, tau_CF (21), tau_AF (22), PCF.
- :mod:`.dynamics` -- generalized mass (19), velocity term, inverse and forward dynamics.
- :mod:`.pivot` -- flexure stiffness (1), bending stress, allowable stroke.
- :mod:`.motion` -- sinusoidal and tabulated slider motions.
- :mod:`.design` -- choose r2/r3, K3 and the flexure for a target force and stroke.
- :mod:`.params`, :mod:`.model`, :mod:`.results` -- the classes on top.
"""

from .design import DesignResult, design
from .model import CFCS, DEFAULT_AMPLITUDE
from .motion import SinusoidMotion, TabulatedMotion
from .params import CFCSParams
from .results import DynamicResult, ForwardResult, FrequencySweep, StaticResult, running_pcf

__all__ = [
    "CFCS",
    "CFCSParams",
    "DEFAULT_AMPLITUDE",
    "DesignResult",
    "DynamicResult",
    "ForwardResult",
    "SinusoidMotion",
    "StaticResult",
    "FrequencySweep",
    "TabulatedMotion",
    "design",
    "running_pcf",
]


def __getattr__(name):
    if name == "SweepResult":
        import warnings

        warnings.warn("springdyn.cfcs.SweepResult is now FrequencySweep", DeprecationWarning, stacklevel=2)
        return FrequencySweep
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
