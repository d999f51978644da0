"""The camshaft wing: several valves on one shaft with its torsion and its timing drive.

- :mod:`.definition` -- the ``[camshaft]`` table, its ``[[camshaft.lobes]]`` and the shaft as a chain;
- :mod:`.shaft` -- the torsional chain's laws: stiffness and inertia of a segment, the matrices,
  the modes and the periodic twist per harmonic;
- :mod:`.coupled` -- :class:`CamshaftModel`: each valve on its lobe's distorted table, the lobes'
  torques, the waveform relaxation to the periodic state, a sweep over speed;
- :mod:`.results` -- :class:`TorsionalModes`, :class:`CamshaftRun`, :class:`CamshaftSweep`.

It imports the wings below it (engine, spring, cam, train, run); the model wing above it and the
application layer reach it through :mod:`springdyn.valve`.
"""

from __future__ import annotations

from ..._lazy import lazy_package

_EXPORTS = {
    "Camshaft": "definition",
    "LobeDefinition": "definition",
    "Lobe": "definition",
    "read_camshaft": "definition",
    "CamshaftModel": "coupled",
    "TorsionalModes": "results",
    "CamshaftRun": "results",
    "CamshaftSweep": "results",
}
__all__ = sorted(_EXPORTS)

lazy_package(__name__, _EXPORTS)
