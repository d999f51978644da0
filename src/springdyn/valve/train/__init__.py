"""The valve-train wing: the links between the cam and the valve.

- :mod:`.definition` -- :class:`ValveTrain`: layouts, masses, stiffnesses, lash (``[valve_train]``);
- :mod:`.lever` -- a rocker arm or finger follower drawn in 2-D (``[geometry]``): the
  lift-dependent ratio, moment arms, contact points and mass at the valve;
- :mod:`.hla` -- the hydraulic lash adjuster's plunger, chamber and check valve (``[hla]``);
- :mod:`.gas_force` -- the cylinder's gas force on the valve head;
- :mod:`.friction` -- the friction laws of the cam contact, the roller, the stem guide and
  the pivot, the camshaft drive torque along the cam (``[friction]``);
- :mod:`.piston` -- the piston's crank-slider under the valve and the valve-to-piston
  clearance (``[piston]``);
- :mod:`.oil` -- the engine oil (``[oil]``): viscosity by Walther's equation, density,
  bulk modulus with free air.

It imports the cam wing (the follower) and the engine below it.
"""

from __future__ import annotations

from ..._lazy import lazy_package

_EXPORTS = {
    "ValveTrain": "definition",
    "HLA": "hla",
    "GasForce": "gas_force",
    "Friction": "friction",
    "Oil": "oil",
    "oil_of": "oil",
    "Piston": "piston",
    "ValveClearance": "piston",
    "clearance_map": "piston",
    "static_valve_lift": "piston",
}
__all__ = sorted(_EXPORTS)

lazy_package(__name__, _EXPORTS)
