"""Valve-train parameters: direct-acting, rocker (finger follower) and pushrod layouts.

Beyond the MMS document (issue 3, section 3, and issue 13).  The spring sits between the
cylinder head and the retainer; the valve body (valve + retainer) lands on its seat
through a unilateral contact; the cam drives it through one of three layouts:

``"direct-acting"``
    bucket tappet: valve + retainer + follower are one rigid body, the cam contact (with
    the stem) is the only link.  One degree of freedom.
``"rocker"``
    rocker arm or finger follower: a rigid lever of ratio ``r`` (valve lift / follower
    lift) and inertia ``J`` about its pivot carries the follower (roller or pad) at the
    cam; its valve-side tip pushes the valve through the tip contact (rocker bending,
    stem and lash in series).  Two degrees of freedom: the lever, measured by the
    displacement of its valve-side tip, and the valve.
``"pushrod"``
    OHV: lifter (follower) at the cam, pushrod, rocker, valve.  Three degrees of freedom:
    lifter, rocker tip, valve.

Every link is a unilateral contact (compression only): cam-follower, pushrod ends,
rocker tip on the valve, valve on its seat.  The lever is rigid in its kinematics (the
lift at the valve is exactly ``r`` times the lift at the follower for a rigid train: the
small-rotation lever with contact points on the lever's line; a lever drawn in a
``[geometry]`` table has its real arcs, :mod:`springdyn.valve.train.lever`), flexible through
``rocker_stiffness`` at the tip.  Masses are referred to
the coordinate they move with by kinetic energy (``m_f / r^2`` and ``J / arm^2`` at the
valve side of the lever), stiffnesses by strain energy (``k / r^2``).

The clearance ``lash`` is at the valve side: between the rocker tip and the valve for the
lever layouts, between cam and bucket for the direct-acting one.  A hydraulic lash
adjuster (``lash_adjuster = "hydraulic"``) takes it up: on the base circle the train rests
on the cam with the plunger-spring force ``hla_preload`` and the seat carries the rest of
the spring preload; during the event the adjuster is a stiffness ``hla_stiffness`` in
series.  Its leak-down and pump-up are not modelled (see :data:`HLA_NOT_MODELLED`); an
``[hla]`` table gives the adjuster's dynamics at a finger follower's pivot or inside a
hydraulic bucket (:mod:`springdyn.valve.train.hla`).

Defaults and their sources are listed in :data:`DEFAULT_SOURCES` (and in docs/valve-train.md).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, load_toml, param
from ...core.units import format_quantity
from ..cam.follower import Follower
from ..engine import layout as L
from .hla import HLA, P_ATM
from .lever import LeverGeometry
from .oil import oil_of

__all__ = ["ValveTrain", "LAYOUTS", "DEFAULT_SOURCES", "HLA_NOT_MODELLED", "series_stiffness", "KERNEL_SIZE"]

LAYOUTS = ("direct-acting", "rocker", "pushrod")

#: Length of the engine's valve-train parameter vector (see :meth:`ValveTrain.kernel_parameters`).
KERNEL_SIZE = L.VT_SIZE

#: The adjuster's slots of the engine's parameter vector (:meth:`ValveTrain.kernel_parameters`).
_HLA_SLOTS = (
    L.VT_HLA,
    L.VT_HLA_AREA,
    L.VT_HLA_V0,
    L.VT_HLA_Y0,
    L.VT_HLA_MP,
    L.VT_HLA_MA,
    L.VT_HLA_FS,
    L.VT_HLA_KS,
    L.VT_HLA_CS,
    L.VT_HLA_G,
    L.VT_HLA_DRAG,
    L.VT_HLA_PS,
    L.VT_HLA_PCRACK,
    L.VT_HLA_KCV,
    L.VT_HLA_BETA,
    L.VT_HLA_AIR,
    L.VT_HLA_N,
    L.VT_HLA_YMAX,
    L.VT_HLA_YMIN,
    L.VT_HLA_KSTOP,
    L.VT_HLA_CSTOP,
)

#: Damping ratio of the plunger on its oil column (and at its travel stops) [-]: the oil's
#: viscous losses in the clearance, the check valve and the aerated oil, which the lumped
#: model does not resolve (an assumption; it damps the 10-20 kHz oil-spring ringing and
#: carries no volume).
HLA_PLUNGER_DAMPING_RATIO = 0.2

#: Where each default comes from (stated in messages, docs and the generated TOML reference).
DEFAULT_SOURCES = {
    "cam_contact_stiffness": (
        "direct-acting: 50 N/um for the bucket tappet including the valve stem (a 5.5 mm steel stem of 100 mm "
        "is E A / L = 49 N/um; the flat-face Hertz contact of a 14 mm wide cam is several times stiffer, so the "
        "stem governs); rocker and pushrod: 150 N/um for the cam-roller line contact alone (Hertz line contact "
        "of a 14 mm wide steel roller under 500-1500 N, secant stiffness 120-200 N/um), the stem being the "
        "separate key stem_stiffness"
    ),
    "stem_stiffness": "50 N/um: E A / L of a 5.5 mm steel valve stem of 100 mm (206 GPa)",
    "rocker_stiffness": (
        "15 N/um at the valve tip: bending of a stamped-steel finger follower or cast rocker "
        "arm; with the stem and the cam contact in series the train stiffness at the valve "
        "falls in the 3.5-10.5 N/um that handbooks give for follower trains (Norton, Cam Design "
        "and Manufacturing Handbook, 2nd ed., ch. 15)"
    ),
    "pushrod_stiffness": (
        "no default (required for the pushrod layout): E A / L of the pushrod, e.g. 21 N/um "
        "for an 8 x 1.2 mm steel tube of 250 mm"
    ),
    "seat_stiffness": "50 N/um: valve head and seat insert in axial contact (same order as the stem)",
    "damping": (
        "200 N s/m for each contact: a damping ratio of 0.05-0.1 of a contact of 10-50 N/um on "
        "50-100 g, the range valve-train models use to reproduce measured seat bounce"
    ),
    "hla_stiffness": (
        "20 N/um referred to the valve: the oil column of a hydraulic lash adjuster under "
        "load (bulk modulus of aerated oil 1-1.5 GPa over a 10 mm plunger chamber of 2 mm)"
    ),
    "hla_preload": "15 N referred to the valve: the plunger spring of an adjuster (10-30 N)",
}

HLA_NOT_MODELLED = (
    "the adjuster's leak-down (the plunger sinking under load: about 1-5 um per event at "
    "typical leak-down times of 5-20 s per mm under the valve load), its pump-up after a "
    "separation (it would take up any float gap between events: 'pump-up'), check-ball dynamics "
    "and oil aeration; within one event the adjuster is a stiffness with a fixed length"
)


def series_stiffness(*stiffnesses: float) -> float:
    """Stiffness of springs in series [N/m] (``inf`` entries are rigid and drop out).

    Parameters
    ----------
    *stiffnesses : float
        Stiffnesses [N/m], all referred to the same coordinate.

    Examples
    --------
    >>> series_stiffness(2.0, 2.0)
    1.0
    """
    compliance = sum(1.0 / k for k in stiffnesses if math.isfinite(k))
    return math.inf if compliance == 0.0 else 1.0 / compliance


@dataclass(frozen=True)
class ValveTrain(Parameters):
    """The valve train between cam and spring: layout, masses, stiffnesses, lash.

    See the module docstring for the three layouts and :data:`DEFAULT_SOURCES` for the
    defaults.  Values given for another layout are an error, so that nothing is silently
    ignored.
    """

    valve_mass: float = param("kg", "valve mass", display="g", positive=True)
    retainer_mass: float = param("kg", "retainer and keepers mass", display="g", nonnegative=True, default=0.0)
    follower_mass: float = param(
        "kg",
        "follower at the cam: bucket tappet, roller/pad on the lever, or lifter",
        display="g",
        nonnegative=True,
        default=0.0,
    )
    cam_contact_stiffness: float = param(
        "N/m",
        "cam-follower contact stiffness (direct-acting: including the valve stem; default 50 N/um, rocker "
        "and pushrod: the cam-roller contact alone, default 150 N/um)",
        display="N/um",
        positive=True,
        default=None,
    )
    cam_contact_damping: float = param("N*s/m", "cam-follower contact damping", nonnegative=True, default=200.0)
    seat_stiffness: float = param("N/m", "valve-seat contact stiffness", display="N/um", positive=True, default=5.0e7)
    seat_damping: float = param("N*s/m", "valve-seat contact damping", nonnegative=True, default=200.0)
    lash: float = param(
        "m", "valve lash: clearance at the valve side on the base circle", display="mm", nonnegative=True, default=0.0
    )
    layout: str = param(None, "valve-train layout", kind="str", choices=LAYOUTS, default="direct-acting")
    rocker_ratio: float = param(
        "", "rocker ratio: valve lift / follower (lobe) lift (rocker, pushrod)", default=None, minimum=0.2, maximum=5.0
    )
    rocker_inertia: float = param(
        "kg*m^2",
        "rocker or finger-follower inertia about its pivot (rocker, pushrod)",
        display="kg*mm^2",
        nonnegative=True,
        default=None,
    )
    rocker_valve_arm: float = param(
        "m", "rocker pivot to valve tip (rocker, pushrod)", display="mm", positive=True, default=None
    )
    rocker_stiffness: float = param(
        "N/m",
        "rocker bending stiffness at the valve tip (rocker, pushrod; default 15 N/um)",
        display="N/um",
        positive=True,
        default=None,
    )
    stem_stiffness: float = param(
        "N/m",
        "valve stem stiffness (rocker, pushrod: default 50 N/um; direct-acting: "
        "in series with the cam contact if given)",
        display="N/um",
        positive=True,
        default=None,
    )
    pushrod_mass: float = param(
        "kg", "pushrod mass (pushrod), half at each end", display="g", nonnegative=True, default=None
    )
    pushrod_stiffness: float = param(
        "N/m", "pushrod axial stiffness (pushrod)", display="N/um", positive=True, default=None
    )
    link_damping: float = param(
        "N*s/m", "damping of the rocker-tip and pushrod contacts", nonnegative=True, default=200.0
    )
    seat_diameter: float = param(
        "m",
        "valve seat diameter: the area the cylinder pressure acts on (a gas force, springdyn.valve.train.gas_force)",
        display="mm",
        positive=True,
        default=None,
    )
    lash_adjuster: str = param(
        None,
        "lash adjuster: none (mechanical lash) or hydraulic",
        kind="str",
        choices=("none", "hydraulic"),
        default="none",
    )
    hla_stiffness: float = param(
        "N/m",
        "hydraulic lash adjuster stiffness referred to the valve (default 20 N/um)",
        display="N/um",
        positive=True,
        default=None,
    )
    hla_preload: float = param(
        "N",
        "hydraulic lash adjuster plunger-spring force referred to the valve (default 15 N)",
        nonnegative=True,
        default=None,
    )

    #: The adjuster's dynamics, from the ``[hla]`` table beside ``[valve_train]``
    #: (:class:`springdyn.valve.train.hla.HLA`; :meth:`from_toml` reads it); None: the preloaded
    #: plunger of ``lash_adjuster = "hydraulic"``, or no adjuster.
    hla: object = field(default=None, repr=False, compare=False)
    #: The lever's kinematics from its drawing, the ``[geometry]`` table beside
    #: ``[valve_train]`` and ``[follower]`` (:class:`springdyn.valve.train.lever.LeverKinematics`;
    #: :meth:`from_toml` reads it; it sets ``rocker_ratio`` and ``rocker_valve_arm``); None:
    #: the constant-ratio lever.
    geometry: object = field(default=None, repr=False, compare=False)

    table = "valve_train"
    examples = {
        "direct-acting": "valve_train_direct_acting.toml",
        "finger-follower": "valve_train_finger.toml",
        "pushrod": "valve_train_pushrod.toml",
    }
    default_example = "direct-acting"

    def _validate(self) -> None:
        lever = self.layout in ("rocker", "pushrod")
        lever_keys = ("rocker_ratio", "rocker_inertia", "rocker_valve_arm", "rocker_stiffness")
        if lever:
            missing = [k for k in ("rocker_ratio", "rocker_inertia", "rocker_valve_arm") if getattr(self, k) is None]
            if self.layout == "pushrod":
                missing += [k for k in ("pushrod_mass", "pushrod_stiffness") if getattr(self, k) is None]
            if missing:
                raise InputError(f"[valve_train] layout = {self.layout!r} needs {', '.join(missing)}")
        else:
            given = [k for k in lever_keys if getattr(self, k) is not None]
            if given:
                raise InputError(
                    f"[valve_train] {', '.join(given)} apply to layout = 'rocker' or 'pushrod', not "
                    f"{self.layout!r}: remove them or set the layout"
                )
        if self.layout != "pushrod":
            given = [k for k in ("pushrod_mass", "pushrod_stiffness") if getattr(self, k) is not None]
            if given:
                raise InputError(
                    f"[valve_train] {', '.join(given)} apply to layout = 'pushrod' only, not {self.layout!r}"
                )
        if lever and self.rocker_mass <= 0.0:
            raise InputError(
                "[valve_train] rocker_inertia and follower_mass (and pushrod_mass) are all zero: the "
                "lever needs a mass; give rocker_inertia > 0"
            )
        if self.layout == "pushrod" and self.lifter_mass <= 0.0:
            raise InputError("[valve_train] follower_mass and pushrod_mass are zero: the lifter needs a mass")
        if self.geometry is not None and self.layout != "rocker":
            raise InputError(
                f"[geometry]: the lever's drawing applies to layout = 'rocker' (a rocker arm or a finger follower "
                f"with a roller on the cam), not to {self.layout!r}"
            )
        if self.hla is not None:
            if self.layout == "pushrod":
                raise InputError(
                    "[hla]: the adjuster's dynamics are modelled at the pivot of a finger follower (layout = "
                    "'rocker') and inside a hydraulic bucket (layout = 'direct-acting'), not for layout = 'pushrod': "
                    "remove [hla] and use lash_adjuster = 'hydraulic' (a preloaded plunger)"
                )
            if self.layout == "direct-acting" and not self.follower_mass > 0.0:
                raise InputError(
                    "[valve_train] follower_mass = 0 with [hla] under a bucket: the bucket body (on the cam, over the "
                    "adjuster's chamber) needs its mass (25-40 g for a 30-35 mm bucket)"
                )
            if self.lash_adjuster != "hydraulic":
                raise InputError(
                    "[hla] describes a hydraulic lash adjuster: set lash_adjuster = 'hydraulic' in [valve_train]"
                )
            given = [k for k in ("hla_stiffness", "hla_preload") if getattr(self, k) is not None]
            if given:
                raise InputError(
                    f"[valve_train] {', '.join(given)} describe the preloaded plunger; with an [hla] table the "
                    "adjuster's own plunger, chamber and oil carry the load: remove them"
                )
            if self.layout == "rocker" and not self.ratio > 1.0:
                raise InputError(
                    f"[hla] at a finger follower's pivot needs rocker_ratio > 1 (the pivot carries 1 - 1/r of "
                    f"the cam force), not {self.ratio:g}"
                )
        if self.lash_adjuster == "hydraulic":
            if self.lash != 0.0:
                raise InputError(
                    f"[valve_train] lash = {self.lash * 1e3:g} mm with lash_adjuster = 'hydraulic': "
                    "the adjuster takes the lash up; remove lash or set lash_adjuster = 'none'"
                )
        else:
            given = [k for k in ("hla_stiffness", "hla_preload") if getattr(self, k) is not None]
            if given:
                raise InputError(f"[valve_train] {', '.join(given)} apply to lash_adjuster = 'hydraulic' only")

    # -- resolved values ---------------------------------------------------------------
    @property
    def ratio(self) -> float:
        """Valve lift per follower (lobe) lift of the rigid train [-] (1 for direct-acting)."""
        return 1.0 if self.layout == "direct-acting" else float(self.rocker_ratio)

    @property
    def cam_stiffness(self) -> float:
        """Cam contact stiffness in use [N/m] (layout default if not given)."""
        if self.cam_contact_stiffness is not None:
            return self.cam_contact_stiffness
        return 5.0e7 if self.layout == "direct-acting" else 1.5e8

    @property
    def hydraulic(self) -> bool:
        """A hydraulic lash adjuster takes up the lash."""
        return self.lash_adjuster == "hydraulic"

    @property
    def hla_k(self) -> float:
        """Adjuster stiffness referred to the valve [N/m] (``inf`` without an adjuster, and
        with the ``[hla]`` dynamics, whose oil column is a degree of freedom of its own)."""
        if not self.hydraulic or self.hla is not None:
            return math.inf
        return 2.0e7 if self.hla_stiffness is None else self.hla_stiffness

    @property
    def hla_force(self) -> float:
        """Adjuster plunger-spring force referred to the valve [N] (0 without an adjuster)."""
        if not self.hydraulic:
            return 0.0
        if self.hla is not None and self.bucket_hla:  # the plunger spring on the stem
            return self.hla.plunger_spring_force
        if self.hla is not None:  # the plunger spring on the pivot: F_s = F_valve (r - 1)
            return self.hla.plunger_spring_force / (self.ratio - 1.0)
        return 15.0 if self.hla_preload is None else self.hla_preload

    @property
    def adjuster_placement(self) -> str | None:
        """Where a simple hydraulic adjuster's compliance sits in the model, and what that does
        to the float speed, in words; None where the model has the adjuster where it is (a
        bucket's, or an ``[hla]`` table's) or there is none.

        The simple adjuster (``lash_adjuster = "hydraulic"``, ``hla_stiffness``, no ``[hla]``) of
        a lever train is a stiffness in series at the valve side of the lever (:attr:`tip_stiffness`,
        with the rocker and the stem); a finger follower's adjuster carries its pivot and a
        pushrod train's sits in its lifter, at the lever's other end.  The placement moves the
        float speed: the finger example's 3364 cam rpm (the compliance at the valve side) to 3000
        (at the pivot), 11 %, measured in issue 40.
        """
        if not self.hydraulic or self.hla is not None or self.layout == "direct-acting":
            return None
        where = "carries the finger's pivot" if self.layout == "rocker" else "sits in the pushrod's lifter"
        return (
            f"the simple hydraulic adjuster (hla_stiffness = {self.hla_k / 1e6:.3g} N/um, no [hla] table) is a "
            "compliance in series at the valve side of the lever, with the rocker and the stem; a real adjuster "
            f"{where}, at the lever's other end: placed there, the same compliance moves the float speed (the "
            "finger example's 3364 cam rpm to 3000, 11 %, measured in issue 40); an [hla] table puts the "
            "adjuster at the pivot with its oil column"
        )

    @property
    def bucket_hla(self) -> bool:
        """A hydraulic bucket: ``[hla]`` dynamics inside a direct-acting train's bucket."""
        return self.hla is not None and self.layout == "direct-acting"

    @property
    def tip_stiffness(self) -> float:
        """Stiffness of the link at the valve side of the lever [N/m]: rocker, stem and
        adjuster in series (lever layouts); ``inf`` for direct-acting."""
        if self.layout == "direct-acting":
            return math.inf
        k_r = 1.5e7 if self.rocker_stiffness is None else self.rocker_stiffness
        k_s = 5.0e7 if self.stem_stiffness is None else self.stem_stiffness
        return series_stiffness(k_r, k_s, self.hla_k)

    @property
    def cam_link_stiffness(self) -> float:
        """Stiffness of the cam-side link in the engine [N/m]: direct-acting: the cam
        contact with the stem (if given separately) and the adjuster in series; lever
        layouts: the cam contact alone."""
        if self.layout == "direct-acting":
            return series_stiffness(
                self.cam_stiffness, math.inf if self.stem_stiffness is None else self.stem_stiffness, self.hla_k
            )
        return self.cam_stiffness

    @property
    def valve_side_mass(self) -> float:
        """Mass moving with the valve [kg]: valve + retainer (+ follower for direct-acting)."""
        m = self.valve_mass + self.retainer_mass
        return m + self.follower_mass if self.layout == "direct-acting" and not self.bucket_hla else m

    @property
    def rocker_mass(self) -> float:
        """Lever mass referred to its valve-side tip by kinetic energy [kg]:
        ``J / arm^2`` (+ ``m_f / r^2`` for the follower riding on a finger follower, +
        half the pushrod ``m_p / (2 r^2)``)."""
        if self.layout == "direct-acting":
            return 0.0
        if self.geometry is not None:  # the roller turns with the lever about its pivot
            return self.lever_inertia / self.geometry.valve_arm_at_rest**2
        r = self.ratio
        m = self.rocker_inertia / self.rocker_valve_arm**2
        if self.layout == "rocker":
            return m + self.follower_mass / r**2
        return m + 0.5 * self.pushrod_mass / r**2

    @property
    def lever_inertia(self) -> float:
        """The lever's moment of inertia about its pivot with its roller [kg m^2] (a drawn
        lever, ``[geometry]``: ``J + m_f |C_0 - O|^2``; the constant-ratio lever:
        :attr:`rocker_mass` times the valve arm squared)."""
        if self.geometry is not None:
            return self.geometry.inertia(self.rocker_inertia, self.follower_mass)
        return self.rocker_mass * self.rocker_valve_arm**2 if self.layout != "direct-acting" else 0.0

    @property
    def lifter_mass(self) -> float:
        """Lifter + half the pushrod [kg] (pushrod layout; 0 otherwise)."""
        return self.follower_mass + 0.5 * self.pushrod_mass if self.layout == "pushrod" else 0.0

    @property
    def moving_mass(self) -> float:
        """All moving masses referred to the valve by kinetic energy [kg]."""
        r = self.ratio
        return self.valve_side_mass + self.rocker_mass + self.lifter_mass / r**2

    @property
    def stiffness_at_valve(self) -> float:
        """Series stiffness of the train from cam to valve, referred to the valve [N/m]."""
        r = self.ratio
        parts = [self.tip_stiffness, self.cam_link_stiffness / r**2]
        if self.layout == "pushrod":
            parts.append(self.pushrod_stiffness / r**2)
        return series_stiffness(*parts)

    @property
    def lobe_lash(self) -> float:
        """Lobe lift at which a rigid train takes up the lash [m] (0 with an adjuster)."""
        return 0.0 if self.hydraulic else self.lash / self.ratio

    @property
    def degrees_of_freedom(self) -> int:
        """Degrees of freedom of the train: 1 direct-acting, 2 rocker, 3 pushrod; 7 for a
        finger follower on an ``[hla]`` (pivot end, plunger, and the chamber pressure and
        the oil volumes in and out as first-order states); 6 for a hydraulic bucket (bucket
        body, plunger, chamber pressure, oil in and out): :data:`springdyn.valve.engine.layout.TRAIN_DOF`
        of :attr:`kernel_kind`, whose :data:`~springdyn.valve.engine.layout.TRAIN_STATES` names them."""
        return L.TRAIN_DOF[self.kernel_kind]

    def equivalent_direct_acting(self) -> ValveTrain:
        """The direct-acting train of the same referred mass, series stiffness and lash.

        Masses referred to the valve by kinetic energy (``m / r^2``, ``J / arm^2``),
        stiffnesses in series referred by strain energy (``k / r^2``): the reduction a
        rigid lever allows.  The cam lift must be multiplied by :attr:`ratio` to drive it.
        """
        return ValveTrain(
            valve_mass=self.moving_mass,
            cam_contact_stiffness=self.stiffness_at_valve,
            cam_contact_damping=self.cam_contact_damping / self.ratio**2,
            seat_stiffness=self.seat_stiffness,
            seat_damping=self.seat_damping,
            lash=self.lash,
        )

    def kernel_parameters(self, lash: float | None = None) -> np.ndarray:
        """The engine's parameter vector (:func:`springdyn.valve.engine.chain_rhs`, ``vt``): its
        46 slots (``VT_SIZE``), each written here once by its name ``VT_*`` of
        :mod:`springdyn.valve.engine.layout`, where each is described.

        The train's kind (``VT_KIND``, :attr:`kernel_kind`) and degrees of freedom
        (``VT_DOF``), masses [kg], stiffnesses [N/m], dampings [N s/m], the lash at the valve
        side [m] (``lash`` overrides it: the effective lash of an adjuster), the lobe lift that
        starts the event [m], the adjuster's dynamics (``VT_HLA*``, zeros without ``[hla]``)
        and the drawn lever's (``VT_GEOM*``, zeros for the constant ratio).  The slots a train
        does not use are zero.  Set elsewhere: the gas force's samples
        (:meth:`springdyn.valve.run.setup.SimulationSetup.with_gas_force`, ``VT_GAS_N``), the
        lever's ratio table (:func:`springdyn.valve.run.setup.prepare`, ``VT_GEOM_N``), a speed
        ramp's acceleration (:mod:`springdyn.valve.run.run_up`, ``VT_ALPHA``).

        Parameters
        ----------
        lash : float, optional
            Lash at the valve side [m] (default: the train's).

        Returns
        -------
        ndarray (L.VT_SIZE,)
            The parameters [mixed units, layout ``VT_*``].
        """
        lash = self.lash if lash is None else lash
        lever = self.layout != "direct-acting"
        pushrod = self.layout == "pushrod"
        vt = np.zeros(L.VT_SIZE)
        vt[L.VT_ENABLED] = 1.0
        vt[L.VT_KIND] = float(self.kernel_kind)
        vt[L.VT_DOF] = float(self.degrees_of_freedom)
        vt[L.VT_MASS] = self.valve_side_mass
        vt[L.VT_K_CAM] = self.cam_link_stiffness
        vt[L.VT_C_CAM] = self.cam_contact_damping
        vt[L.VT_K_SEAT] = self.seat_stiffness
        vt[L.VT_C_SEAT] = self.seat_damping
        vt[L.VT_LASH] = lash
        vt[L.VT_RATIO] = self.ratio
        vt[L.VT_M_LEVER] = self.rocker_mass if lever else 0.0
        vt[L.VT_K_TIP] = self.tip_stiffness if lever else 0.0
        vt[L.VT_C_TIP] = self.link_damping if lever else 0.0
        vt[L.VT_M_LIFTER] = self.lifter_mass
        vt[L.VT_K_PUSH] = self.pushrod_stiffness if pushrod else 0.0
        vt[L.VT_C_PUSH] = self.link_damping if pushrod else 0.0
        vt[L.VT_LOBE_LASH] = self.lobe_lash
        self._write_hla_parameters(vt)
        vt[L.VT_GAS_N] = 0.0  # no gas force (SimulationSetup.with_gas_force adds its samples)
        vt[L.VT_ALPHA] = 0.0  # constant speed (springdyn.valve.run.run_up sets a ramp's acceleration)
        self._write_lever_parameters(vt)
        vt[L.VT_HLA_KCHK] = self.hla_check_stiffness
        return vt

    @property
    def kernel_kind(self) -> int:
        """The engine's kind of this train (``VT_KIND``, ``TRAIN_*`` of
        :mod:`springdyn.valve.engine.layout`): it chooses the train's equations [-]."""
        if self.hla is not None:
            return L.TRAIN_BUCKET_HLA if self.bucket_hla else L.TRAIN_LEVER_HLA
        return {"direct-acting": L.TRAIN_DIRECT, "rocker": L.TRAIN_LEVER, "pushrod": L.TRAIN_PUSHROD}[self.layout]

    @property
    def hla_check_stiffness(self) -> float:
        """The force per metre of an adjuster's collapse that judges periodicity [N/m]
        (``VT_HLA_KCHK``, :data:`springdyn.valve.engine.layout.CHK_HLA`): a collapse ``y``
        at the finger's pivot moves the valve's closed position by ``(r - 1) y``, which the
        train's stiffness at the valve turns into a force; 0 without ``[hla]`` dynamics."""
        if self.hla is None:
            return 0.0
        if self.bucket_hla:  # the collapse moves the valve's closed position one to one
            return self.stiffness_at_valve
        return (self.ratio - 1.0) * self.stiffness_at_valve

    def _write_lever_parameters(self, vt: np.ndarray) -> None:
        """Write the ``VT_GEOM*`` slots of :meth:`kernel_parameters`: the drawn lever's pad and
        inertia (zeros for the constant ratio; :func:`springdyn.valve.run.setup.prepare` appends
        the ratio table and sets ``VT_GEOM_N``).

        Parameters
        ----------
        vt : ndarray (L.VT_SIZE,)
            The parameter vector [mixed units].
        """
        if self.geometry is None:
            a = r2 = inertia = 0.0
        else:
            a, b, _ = self.geometry.geometry.pad_arms()
            r2, inertia = a * a + b * b, self.lever_inertia
        vt[L.VT_GEOM] = 0.0 if self.geometry is None else 1.0
        vt[L.VT_PAD_A] = a
        vt[L.VT_PAD_R2] = r2
        vt[L.VT_LEVER_J] = inertia
        vt[L.VT_GEOM_N] = 0.0

    def _write_hla_parameters(self, vt: np.ndarray) -> None:
        """Write the ``VT_HLA*`` slots of :meth:`kernel_parameters` (zeros without ``[hla]``).

        Parameters
        ----------
        vt : ndarray (L.VT_SIZE,)
            The parameter vector [mixed units].
        """
        for slot, value in self._hla_slots().items():
            vt[slot] = value

    def _hla_slots(self) -> dict:
        """The ``VT_HLA*`` slots of :meth:`kernel_parameters` by name (zeros without ``[hla]``)."""
        h = self.hla
        if h is None:
            return dict.fromkeys(_HLA_SLOTS, 0.0)

        if self.bucket_hla:  # the collapse's origin: the body less the plunger on the base circle
            origin, carried = self.bucket_hla_state()["collapse"], self.follower_mass
        else:  # the plunger's position in its fixed body
            origin, carried = self.hla_pivot_state()["plunger"], h.pivot_mass
        mass = h.plunger_mass
        k_oil = h.oil.bulk_modulus * h.area**2 / h.chamber_volume
        return {
            L.VT_HLA: 1.0,
            L.VT_HLA_AREA: h.area,
            L.VT_HLA_V0: h.chamber_volume,
            L.VT_HLA_Y0: origin,
            L.VT_HLA_MP: mass,
            L.VT_HLA_MA: carried,
            L.VT_HLA_FS: h.plunger_spring_force,
            L.VT_HLA_KS: h.socket_stiffness,
            L.VT_HLA_CS: self.link_damping,
            L.VT_HLA_G: h.conductance(),
            L.VT_HLA_DRAG: 0.5 * math.pi * h.plunger_diameter * h.radial_clearance,
            L.VT_HLA_PS: P_ATM + h.supply_pressure,
            L.VT_HLA_PCRACK: h.cracking_pressure,
            L.VT_HLA_KCV: h.discharge_coefficient * h.check_valve_area * math.sqrt(2.0 / h.oil.density()),
            L.VT_HLA_BETA: h.oil.bulk_modulus,
            L.VT_HLA_AIR: h.oil.air_fraction,
            L.VT_HLA_N: h.oil.polytropic_index,
            L.VT_HLA_YMAX: h.collapse_travel,
            L.VT_HLA_YMIN: -h.extension_travel,
            L.VT_HLA_KSTOP: 10.0 * k_oil,
            L.VT_HLA_CSTOP: HLA_PLUNGER_DAMPING_RATIO * 2.0 * math.sqrt(k_oil * mass),
        }

    def hla_pivot_state(
        self, valve_force: float | None = None, lobe_lift: float = 0.0, valve_lift: float = 0.0
    ) -> dict:
        """Positions of the finger's pivot end and of the plunger [m] in static equilibrium
        with the valve-side force ``valve_force`` [N] (default: the base circle's,
        :attr:`hla_force`), at the chamber's supply pressure.

        The finger is a rigid bar: with the roller at ``y_b`` and the tip at ``y_c``, the
        pivot end is at ``(r y_b - y_c) / (r - 1)``; the socket carries ``F_s = r F_v (1 - 1/r)``.

        Parameters
        ----------
        valve_force : float, optional
            Force of the tip on the valve [N].
        lobe_lift : float
            Cam lift at the roller [m].
        valve_lift : float
            Valve position [m].
        """
        r = self.ratio
        f_v = self.hla_force if valve_force is None else valve_force
        f_cam = r * f_v
        tip = valve_lift + f_v / self.tip_stiffness
        roller = lobe_lift - f_cam / self.cam_stiffness
        pivot = (r * roller - tip) / (r - 1.0)
        socket = f_cam * (1.0 - 1.0 / r)
        return dict(tip=tip, pivot=pivot, plunger=pivot - socket / self.hla.socket_stiffness)

    def bucket_hla_state(
        self, valve_force: float | None = None, lobe_lift: float = 0.0, valve_lift: float = 0.0
    ) -> dict:
        """Positions of a hydraulic bucket's body and plunger [m] in static equilibrium with the
        force ``valve_force`` [N] on the valve (default: the plunger spring's,
        :attr:`hla_force`) at the chamber's supply pressure, and its collapse ``body - plunger``.

        Parameters
        ----------
        valve_force : float, optional
            Force of the plunger on the stem [N].
        lobe_lift : float
            Cam lift [m].
        valve_lift : float
            Valve position [m].
        """
        f = self.hla_force if valve_force is None else valve_force
        body = lobe_lift - f / self.cam_link_stiffness
        plunger = valve_lift + f / self.hla.socket_stiffness
        return dict(body=body, plunger=plunger, collapse=body - plunger)

    def highest_frequency(self) -> float:
        """An upper bound of the train's contact frequencies [Hz] (bounds the work of a run)."""
        parts = [
            math.sqrt(
                (
                    self.cam_link_stiffness / self.ratio**2
                    + self.seat_stiffness
                    + (self.tip_stiffness if math.isfinite(self.tip_stiffness) else 0.0)
                )
                / self.valve_side_mass
            )
        ]
        if self.layout != "direct-acting" and self.rocker_mass > 0:
            parts.append(
                math.sqrt(
                    (
                        self.tip_stiffness
                        + self.cam_stiffness / self.ratio**2
                        + (self.pushrod_stiffness / self.ratio**2 if self.layout == "pushrod" else 0.0)
                    )
                    / self.rocker_mass
                )
            )
        if self.layout == "pushrod" and self.lifter_mass > 0:
            parts.append(math.sqrt((self.cam_stiffness + self.pushrod_stiffness) / self.lifter_mass))
        if self.hla is not None:
            h = self.hla
            k_oil = h.oil.bulk_modulus * h.area**2 / h.chamber_volume
            parts.append(math.sqrt((h.socket_stiffness + k_oil) / h.plunger_mass))
            if self.bucket_hla:  # the bucket body between the cam and the oil
                parts.append(math.sqrt((self.cam_link_stiffness + k_oil) / self.follower_mass))
            else:
                parts.append(math.sqrt((h.socket_stiffness + self.cam_stiffness) / h.pivot_mass))
        return max(parts) / (2 * math.pi)

    @classmethod
    def from_toml(cls, path):
        """Read ``[valve_train]`` of a TOML file, and its ``[hla]`` table when it has one.

        Parameters
        ----------
        path : str or path-like
            The definition file.
        """

        doc = load_toml(path)
        vt = cls.with_lever_drawing(doc, source=str(path)) if "geometry" in doc else super().from_toml(path)
        return vt.with_document_hla(doc, source=str(path))

    def with_document_hla(self, doc: dict, source: str | None = None) -> ValveTrain:
        """The same train with the ``[hla]`` table of a definition and the train's one oil
        (``[oil]`` with the oil keys of ``[hla]`` and ``[friction]``, :func:`springdyn.valve.train.oil.oil_of`);
        the train itself where the definition has no ``[hla]``.

        Parameters
        ----------
        doc : dict
            The definition's tables (``load_toml``).
        source : str, optional
            The file, for messages.
        """
        if "hla" not in doc:
            return self
        oil, rest = oil_of(doc, source)
        return self.with_hla(HLA.from_dict(rest["hla"], source=source, oil=oil), source=source)

    @classmethod
    def with_lever_drawing(cls, doc: dict, source: str | None = None) -> ValveTrain:
        """The train of a definition holding ``[valve_train]``, ``[follower]`` and ``[geometry]``:
        its lever's ratio and valve arm come from the drawing (:mod:`springdyn.valve.train.lever`).

        Parameters
        ----------
        doc : dict
            The definition's tables (``load_toml``).
        source : str, optional
            The file, for messages.
        """

        where = f"{source}: " if source else ""
        table = dict(doc.get("valve_train", {}))
        given = [k for k in ("rocker_ratio", "rocker_valve_arm") if k in table]
        if given:
            raise InputError(
                f"{where}[valve_train] {', '.join(given)}: with a [geometry] table the lever's ratio and valve arm "
                "come from the drawing; remove them (or remove [geometry] for the constant-ratio lever)"
            )
        geom = LeverGeometry.from_dict(doc["geometry"], source=source)
        follower = Follower.from_dict(doc["follower"], source=source) if "follower" in doc else None
        try:
            kin = geom.kinematics(follower)
        except InputError as exc:
            raise InputError(f"{where}{exc}") from None
        _check_drawn_ratio(kin, where)
        table["rocker_ratio"] = kin.ratio_at_rest
        table["rocker_valve_arm"] = kin.valve_arm_at_rest
        vt = cls.from_dict(table, source=source)
        try:
            return dataclasses.replace(vt, geometry=kin)
        except InputError as exc:
            raise InputError(f"{where}{exc}") from None

    def without_geometry(self) -> ValveTrain:
        """The constant-ratio lever of the same ratio, valve arm and inertia at rest (no ``[geometry]``)."""

        if self.geometry is None:
            return self
        j = self.lever_inertia
        r = self.ratio
        # the constant-ratio lever's mass J / arm^2 + m_f / r^2 must equal J_total / B^2
        return dataclasses.replace(
            self, geometry=None, rocker_inertia=j - self.follower_mass * (self.rocker_valve_arm / r) ** 2
        )

    def without_hla_dynamics(self, valve_force: float = 0.0) -> ValveTrain:
        """The preloaded-plunger train of the same base-circle force and oil-column stiffness.

        For analyses that linearise the train (natural frequencies): ``hla_preload`` the
        plunger spring's force at the valve, ``F_s / (r - 1)``, and ``hla_stiffness`` the oil
        column ``beta_e A_p^2 / V`` referred to the valve, ``/ (r - 1)^2``, in series with the
        socket.  The aerated oil's bulk modulus ``beta_e`` is taken at the chamber pressure
        that carries ``valve_force``: the pivot's load ``F_p = F_v (r - 1)`` (a bucket's: ``F_v``)
        less the plunger spring's, over the plunger area, and at least the supply pressure
        (the check valve is open below it).  Without ``[hla]``: the train itself.

        Parameters
        ----------
        valve_force : float
            The force on the valve the adjuster carries [N] (0: the base circle, the supply
            pressure; the full-lift spring force for the modes at full lift: issue 40).
        """

        if self.hla is None:
            return self

        h, r = self.hla, self.ratio
        beta = h.oil.bulk_modulus_at(P_ATM + self.hla_chamber_pressure(valve_force))
        k_pivot = series_stiffness(beta * h.area**2 / h.chamber_volume, h.socket_stiffness)
        if self.bucket_hla:  # the oil column under the bucket, in series with the stem contact
            return dataclasses.replace(self, hla=None, hla_stiffness=k_pivot, hla_preload=h.plunger_spring_force)
        return dataclasses.replace(
            self, hla=None, hla_stiffness=k_pivot / (r - 1.0) ** 2, hla_preload=h.plunger_spring_force / (r - 1.0)
        )

    def hla_chamber_pressure(self, valve_force: float) -> float:
        """The adjuster's chamber pressure above the atmosphere [Pa] that carries ``valve_force``
        [N] at the valve: ``max((F_p - F_s) / A_p, p_supply)`` with the pivot's load ``F_p = F_v (r -
        1)`` (a bucket adjuster's ``F_v``) and the plunger spring's force ``F_s``.

        Parameters
        ----------
        valve_force : float
            The force at the valve [N].
        """
        h = self.hla
        if h is None:
            raise InputError("hla_chamber_pressure needs an adjuster ([hla])")
        pivot = valve_force if self.bucket_hla else valve_force * (self.ratio - 1.0)
        return max((pivot - h.plunger_spring_force) / h.area, h.supply_pressure)

    def with_hla(self, table, source: str | None = None) -> ValveTrain:
        """The same train with the adjuster's dynamics of an ``[hla]`` table (or an :class:`~springdyn.valve.train.hla.HLA`).

        Parameters
        ----------
        table : dict or HLA
            The ``[hla]`` table's keys, or the adjuster.
        source : str, optional
            The file, for messages.
        """

        h = table if isinstance(table, HLA) else HLA.from_dict(table, source=source)
        try:
            return dataclasses.replace(self, hla=h)
        except InputError as exc:
            raise InputError(f"{source}: {exc}" if source else str(exc)) from None

    def static_state(self, lobe_lift: float, valve_lift: float, valve_force: float) -> np.ndarray:
        """Positions of the train's degrees of freedom in static equilibrium [m].

        Parameters
        ----------
        lobe_lift : float
            Cam lift at the follower [m].
        valve_lift : float
            Valve position [m] (negative: pressed into its seat).
        valve_force : float
            Force the train delivers to the valve [N] (0: the lash is open and the lever
            and lifter rest on the cam without load).

        Returns
        -------
        ndarray (dof,)
            Valve, then lever tip [m] and lifter [m] as the layout has them.
        """
        r = self.ratio
        if self.bucket_hla:
            st = self.bucket_hla_state(valve_force, lobe_lift, valve_lift)
            return np.array([valve_lift, st["body"], st["plunger"], P_ATM + self.hla.supply_pressure, 0.0, 0.0])
        if self.layout == "direct-acting":
            return np.array([valve_lift])
        f_cam = r * valve_force
        if self.hla is not None:
            st = self.hla_pivot_state(valve_force, lobe_lift, valve_lift)
            return np.array(
                [valve_lift, st["tip"], st["pivot"], st["plunger"], P_ATM + self.hla.supply_pressure, 0.0, 0.0]
            )
        if self.layout == "rocker":
            tip = r * (lobe_lift - f_cam / self.cam_stiffness)
            return np.array([valve_lift, tip])
        lifter = lobe_lift - f_cam / self.cam_stiffness
        tip = r * (lifter - f_cam / self.pushrod_stiffness)
        return np.array([valve_lift, tip, lifter])


def _check_drawn_ratio(kin, where: str = "") -> None:
    """A drawn lever's ratio at rest within the bounds of ``[valve_train] rocker_ratio``, refused
    naming the ``[geometry]`` keys that set it (the user set them, not ``rocker_ratio``).

    Parameters
    ----------
    kin : LeverKinematics
        The drawing's kinematics on the base circle.
    where : str
        The file, for messages (``"vt.toml: "``).
    """
    meta = next(f.metadata for f in dataclasses.fields(ValveTrain) if f.name == "rocker_ratio")
    lo, hi = meta["minimum"], meta["maximum"]
    r = kin.ratio_at_rest
    if lo <= r <= hi:
        return
    valve_arm = format_quantity(kin.valve_arm_at_rest, "m", "mm")
    cam_arm = format_quantity(kin.cam_arm_at_rest, "m", "mm")
    raise InputError(
        f"{where}[geometry] the lever drawn has a ratio of {r:.4g} at rest: its valve arm (the pad, pad_x and "
        f"pad_y, about the pivot, pivot_x and pivot_y) is {valve_arm} against the cam's arm (the roller, roller_x "
        f"and roller_y) {cam_arm}; a valve-train lever's ratio is {lo:g} to {hi:g}: check these points of the "
        "drawing (its units too)"
    )
