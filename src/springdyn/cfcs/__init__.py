"""Constant-force compression spring (CFCS): pseudo-rigid-body statics, dynamics, design.

The model of Ugwuoke, "A Simplified Dynamic Model for Constant-Force Compression
Spring" (the CFCS paper), with the corrections CFCS-1 to CFCS-4 of docs/references.md.
Where to find each equation:

- :mod:`.kinematics` -- loop closure, exact inverse x -> theta2, Jacobian (Eq. (25)), toggle.
- :mod:`.statics` -- spring energy (17), static force by virtual work, tau_CF (21), tau_AF (22), PCF.
- :mod:`.dynamics` -- generalized mass (19), velocity term, inverse and forward dynamics.
- :mod:`.drive` -- forward dynamics through a compliant drive (spring and damper), through the toggle.
- :mod:`.pivot` -- flexure stiffness (1), bending stress, allowable stroke.
- :mod:`.motion` -- sinusoidal and tabulated slider motions.
- :mod:`.beam` -- the flexure as an elastica (shooting on the beam equations) and as a Hencky chain.
- :mod:`.design` -- choose r2/r3, K3 and the flexure for a target force and stroke.
- :mod:`.params`, :mod:`.model`, :mod:`.results` -- the classes on top.

The names below load their modules on first use, so that ``import springdyn.cfcs`` stays quick.
"""

from __future__ import annotations

from .._lazy import lazy_package

_EXPORTS = {
    "DesignResult": "design",
    "design": "design",
    "CFCS": "model",
    "DEFAULT_AMPLITUDE": "model",
    "SinusoidMotion": "motion",
    "TabulatedMotion": "motion",
    "CFCSParams": "params",
    "DrivenResult": "results",
    "DynamicResult": "results",
    "ForwardResult": "results",
    "FrequencySweep": "results",
    "StaticResult": "results",
    "running_pcf": "results",
}

__all__ = [
    "CFCS",
    "CFCSParams",
    "DEFAULT_AMPLITUDE",
    "DesignResult",
    "DrivenResult",
    "DynamicResult",
    "ForwardResult",
    "SinusoidMotion",
    "StaticResult",
    "FrequencySweep",
    "TabulatedMotion",
    "design",
    "running_pcf",
]


lazy_package(__name__, _EXPORTS)
