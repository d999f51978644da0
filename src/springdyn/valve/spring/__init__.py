"""The spring wing: a valve spring on its own, from the drawing to its chain of masses.

Everything here is about the spring alone, with no cam and no valve train: what the
spring is (its definition and material), the laws of its wire and coils, its statics and
natural frequencies, and the models that turn it into a chain of masses.

- :mod:`.definition` -- :class:`ValveSpring`, the ``[spring]`` table and the drawing's keys;
- :mod:`.materials` -- named spring wires: elastic constants, density, tensile strength
  against diameter, relaxation and load-spectrum life;
- :mod:`.formulas` -- the closed-form internal parameters of [MMS] (rates, masses, surge
  frequencies, coil-contact forces);
- :mod:`.geometry` -- pitch and diameter profiles, the open-coil compliance of a turn;
- :mod:`.elements` -- the element force laws (linear, hardening, coil contact) and the
  damping law;
- :mod:`.statics` -- series equilibrium of the chain (static force, stiffness, set-up state);
- :mod:`.modes` -- natural frequencies of the linearised chain, surge margin;
- :mod:`.solid_length` -- solid length by the end type (EN 13906-1), the coil-bind clearance;
- :mod:`.stress` -- the wire's corrected shear stress, strengths and Goodman safety;
- :mod:`.wire` -- the wire's cross-section (round, ovate, rectangular; a wire diameter along
  the coil): torsion constant, stress factor, area, axial height;
- :mod:`.frf` -- the linearised dynamic stiffness;
- :mod:`.chains` -- the spring models (:class:`TypeCModel`, the distributed chain) behind one
  interface, :class:`SpringModel`;
- :mod:`.pack` -- :class:`SpringPack`, two or three nested springs between one seat and one
  retainer (``[inner_spring]``, ``[third_spring]``, ``[pack]``, ``[damper]``): their forces,
  modes, fit, stress and coil bind, and the chains the engine runs side by side;
- :mod:`.results` -- :class:`StaticCurve`, and :mod:`.plots` its figure.

It imports only the engine below it (nothing here needs a cam).
"""

from __future__ import annotations

from ..._lazy import lazy_package

_EXPORTS = {
    "ValveSpring": "definition",
    "StaticCurve": "results",
    "SpringParameters": "results",
    "ChainModes": "results",
    "DesignFigures": "results",
    "dynamic_stiffness": "frf",
    "SpringModel": "chains",
    "TypeCModel": "chains",
    "Chain": "chains",
    "MODELS": "chains",
    "material": "materials",
    "Material": "materials",
    "WireSection": "wire",
    "SpringPack": "pack",
    "PackOptions": "pack",
    "FrictionDamper": "pack",
}
__all__ = sorted(_EXPORTS)

lazy_package(__name__, _EXPORTS)
