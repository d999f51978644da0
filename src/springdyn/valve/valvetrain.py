"""Optional valve-train parameters: a rigid valve body on unilateral cam and seat contacts."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.params import Parameters, param

__all__ = ["ValveTrain"]


@dataclass(frozen=True)
class ValveTrain(Parameters):
    """Valve + retainer + follower as one rigid body, with cam and valve-seat contacts.

    Beyond the MMS document (issue 3, section 3): the spring sits between the cylinder
    head and the retainer; the cam pushes the follower through a unilateral contact
    (stiffness and damping, force never tensile); the valve head lands on its seat through
    a second unilateral contact.  The follower separates from the cam (valve float) when
    the spring cannot decelerate the valve body fast enough.

    Defaults are typical of a passenger-car direct-acting bucket valve train.
    """

    valve_mass: float = param("kg", "valve mass", display="g", positive=True)
    retainer_mass: float = param("kg", "retainer and keepers mass", display="g", nonnegative=True, default=0.0)
    follower_mass: float = param("kg", "follower (bucket tappet) mass", display="g", nonnegative=True, default=0.0)
    cam_contact_stiffness: float = param("N/m", "cam-follower contact stiffness (incl. valve stem)", display="N/um",
                                         positive=True, default=5.0e7)
    cam_contact_damping: float = param("N*s/m", "cam-follower contact damping", nonnegative=True, default=200.0)
    seat_stiffness: float = param("N/m", "valve-seat contact stiffness", display="N/um", positive=True, default=5.0e7)
    seat_damping: float = param("N*s/m", "valve-seat contact damping", nonnegative=True, default=200.0)
    lash: float = param("m", "valve lash (clearance on the base circle)", display="mm", nonnegative=True, default=0.0)

    table = "valve_train"

    @property
    def moving_mass(self) -> float:
        """Valve + retainer + follower [kg]."""
        return self.valve_mass + self.retainer_mass + self.follower_mass

    def kernel_parameters(self) -> np.ndarray:
        """``enabled, M_v, k_c, c_c, k_s, c_s, lash`` as the engine expects them."""
        return np.array([1.0, self.moving_mass, self.cam_contact_stiffness, self.cam_contact_damping,
                         self.seat_stiffness, self.seat_damping, self.lash])
