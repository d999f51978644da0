"""Valve-train friction: the cam-follower contact (lubrication regime, roller slip), the stem
guide and the lever's pivot; the camshaft drive torque and the friction power (``[friction]``).

Frame and signs are those of :mod:`springdyn.valve.cam.checks`: the follower moves along +y
above the cam centre, its axis at ``x = offset``; the cam turns counter-clockwise at
``omega > 0``; the lobe lift ``h(theta)`` with ``h' = dh/dtheta`` and ``h'' = d2h/dtheta2``
per radian.  At the contact point ``P`` the contact normal ``n = (-sin(phi), cos(phi))``
points from the cam to the follower (``phi`` the pressure angle, 0 for a flat face) and the
tangent is ``t = (cos(phi), sin(phi))``; tangential velocities and forces are signed along
``t``.

**Contact kinematics** (:func:`flat_contact_velocities`, :func:`roller_contact_velocities`).
The surface velocities that carry oil into the contact are those relative to the moving
contact point.  The cam's material at ``P`` moves at ``omega x P``: along ``t`` that is
``omega a_t``, ``a_t = P_x sin(phi) - P_y cos(phi)`` (:func:`drive_torque_arms`).

- Flat face: ``P = (h', R_b + h)``, ``phi = 0``; the contact point slides along the face at
  ``omega h''``.  Relative to it the cam surface moves at ``u_1 = -omega (R_b + h + h'') =
  -omega rho`` and the face at ``u_2 = -omega h''``: entrainment
  ``u_e = (u_1 + u_2)/2 = -omega (R_b + h + 2 h'')/2`` (zero, and the film collapses, where
  ``rho = -h''`` near the nose of a flat-tappet cam), sliding
  ``u_s = u_1 - u_2 = -omega (R_b + h)`` ([Dyson], [Taylor]).
- Roller (radius ``r``, centre ``C = (e, d0 + h)``): ``P = C - r n``; with
  ``D = sqrt((d0 + h)^2 + (h' - e)^2)`` the cam surface moves at
  ``u_1 = omega (r - D) - r phi_dot`` and the roller's at ``u_2 = r (Omega - phi_dot)``,
  ``phi_dot = omega ((d0 + h) h'' - (h' - e) h') / D^2``; pure rolling is
  ``Omega = -omega (D - r)/r`` (:func:`roller_rolling_speed`; on the base circle
  ``-omega R_b / r``).

**Lubrication** (:func:`line_contact_film_thickness`, :func:`friction_coefficient`).  The
film of the line contact from the entrainment speed ``|u_e|``, the load per width, the
reduced radius (flat: the cam's radius of curvature ``rho``, :func:`~springdyn.valve.cam.checks.flat_follower_radius`;
roller: ``1/R = 1/rho + 1/r``, :func:`~springdyn.valve.cam.checks.roller_cam_curvature`) and
``E' = 2 E*`` by the isothermal EHL line-contact fit of [Pan-Hamrock]; the film parameter
``lambda = h_min / sigma`` sets the regime.  The friction coefficient blends boundary and
full-film friction by the share of the contact where the roughness spans the film
(:func:`boundary_share`): ``mu = f_b mu_b + (1 - f_b) mu_f``, ``f_b = erfc(lambda/sqrt(2))``,
the probability that a Gaussian composite roughness of rms ``sigma`` exceeds the film
``h_min`` in magnitude (the load-sharing idea of [Johnson-Greenwood-Poon]; 1 at ``lambda = 0``,
0.32 at 1, 0.05 at 2, 0.003 at 3: the boundary, mixed and full-film regimes of [Hamrock]).

**Roller slip** (:func:`roller_spin`).  The roller (inertia ``J``) is spun by the traction
``F_t`` at the cam and braked by its needle bearing, ``T_b = mu_b r_pin N_0`` (the pin
carries the frictionless normal force ``N_0 = F / cos(phi)``):
``J dOmega/dt = r F_t - T_b sign(Omega)``.  It rolls while the traction rolling needs stays
within ``mu N`` (``mu`` the regime's coefficient); beyond, it slides with
``F_t = mu N sign(u_s)``.  Integrated over the revolution (backward Euler on the uniform
cam-angle grid, the stick-slip switch solved in each step) until it repeats.  In the limit
``J -> 0``, ``T_b -> 0`` the roller rolls purely.

**Guide and pivot** (:func:`petroff_force`, :func:`guide_friction_force`,
:func:`pivot_friction_torque`).  The stem shears the oil in its guide clearance (Petroff:
``F = eta pi d L v / c``, [Hamrock]) and rubs under the side load (Coulomb, ``mu_g |S|``); a
lever's pivot (rocker shaft, HLA ball) carries ``T_p = mu_p r_p |F_p|`` against the lever's
rotation.

**Drive torque and energy** (:func:`friction_along_cam`).  The follower's axial force ``F``
(the cam contact force of a simulation or of the kinematic load) plus the guide and pivot
friction referred to the follower axis (rigid lever: ``r F_g sign(v)`` and
``T_p sign(h')/a``) is balanced by the contact forces: ``N cos(phi) + F_t sin(phi) = F``.
The camshaft's drive torque is ``T = N a_n + F_t a_t`` with the arms ``a_n = P_x cos(phi) +
P_y sin(phi)``, ``a_t = P_x sin(phi) - P_y cos(phi)`` of the contact geometry.  Power:
``T omega = F dh/dt + F_t u_s + F_t r Omega``; over a revolution the cam work equals the
work of the load on the follower (the spring's elastic change and the inertia: zero over a
periodic revolution of a conservative train) plus the energy each contact dissipates
(``F_t u_s`` at the cam, ``T_b |Omega|`` in the roller's bearing, ``F_g |v|`` in the guide,
``T_p |omega_lever|`` at the pivot); the roller's kinetic energy returns to its start.

**Decoupled.**  Friction is computed from the simulated (or kinematic) motion: the friction
forces do not feed back into the valve motion, and the camshaft turns at a constant speed.
The error this implies is the ratio of the friction forces along the motion to the forces
that set it: at 3000 cam rpm the guide's Petroff force (5.5 mm stem, 35 mm guide, 15 um
clearance, 8 mPa s, 4 m/s) is about 1.3 N against a spring force of 200-600 N (0.2-0.7 %),
plus ``mu_g`` times the side load; a pivot's friction referred to the cam is
``mu_p r_p / a`` of the pivot force (0.1 x 4 mm / 35 mm: about 1 %); the flat face's
friction ``mu N`` acts across the follower's axis, not along it (a roller's traction has the
axial share ``F_t sin(phi)``, which the force balance above includes).  The roller's slip and
the guide's side load are likewise taken from the given motion.

Not modelled: the bucket's rotation in its bore (a ``lateral_offset`` spins it and lowers
the sliding speed), the bucket's bore friction, squeeze films where the entrainment
vanishes, thermal and non-Newtonian (limiting-shear) effects in the EHL film, the EHL
rolling resistance of a roller, and the valve stem seal.  Sources: docs/references.md.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from scipy.special import erfc

from ...core.docstrings import ParameterDocs
from ...core.errors import InputError
from ...core.params import Parameters, param
from ...core.results import Result
from ..cam.checks import flat_follower_radius, pitch_curve_curvature, pressure_angle, roller_cam_curvature
from ..cam.follower import Follower
from .oil import HoldsOil, Oil, oil_of

__all__ = [
    "Friction",
    "DEFAULT_SOURCES",
    "contact_point",
    "drive_torque_arms",
    "flat_contact_velocities",
    "roller_rolling_speed",
    "roller_contact_velocities",
    "entrainment_velocity",
    "sliding_velocity",
    "line_contact_film_thickness",
    "boundary_share",
    "friction_coefficient",
    "roller_spin",
    "RollerSpin",
    "petroff_force",
    "guide_friction_force",
    "pivot_friction_torque",
    "friction_along_cam",
    "FrictionAnalysis",
    "CONTACTS",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    lift : array_like
        Lobe lift h [m].
    omega : float
        Cam speed [rad/s].
    velocity : array_like
        dh/dtheta [m/rad].
    roller_radius : float
        Roller radius r [m].
    film_parameter : array_like
        lambda = h_min / sigma [-].
    acceleration : array_like
        d2h/dtheta2 [m/rad^2].
    offset : float
        Follower axis offset e along +x [m].
    pitch_radius : float
        d0 = sqrt((R_b + r)^2 - offset^2) [m].
    follower : Follower
        The ``[follower]`` table.
    """,
    omega_positive="omega : float\n    Cam speed [rad/s], positive.",
)

_TWO_PI = 2.0 * math.pi
#: The contacts whose friction is reported, in this order.
CONTACTS = ("cam", "roller_bearing", "guide", "pivot")
#: Share of the cam work above which an energy residual is noted [-] (the rigid referral of the
#: guide's friction against a simulated, elastic train's valve velocity: below 1 % in the examples).
ENERGY_NOTE_TOL = 0.01
#: Density of a steel roller [kg/m^3] (a roller without inertia or mass given is solid steel).
STEEL_DENSITY = 7850.0
#: Smallest load per width of the film formula [N/m] (an unloaded contact carries no friction).
_MIN_LOAD_PER_WIDTH = 1.0
#: Revolutions the roller's spin may take to repeat (it repeats after the first stick).
_SPIN_REVOLUTIONS = 40

#: The ``[friction]`` keys of a roller follower's roller: a flat follower refuses them.
ROLLER_KEYS = ("roller_mass", "roller_inertia", "roller_bearing_friction", "roller_pin_radius")
#: Where each default comes from (stated in the docs and the generated TOML reference).
DEFAULT_SOURCES = {
    "surface_roughness": (
        "0.3 um: composite rms sqrt(sigma_1^2 + sigma_2^2) of a ground cam (0.2-0.3 um) and a ground or polished "
        "follower (0.1-0.2 um) ([Taylor])"
    ),
    "boundary_friction": "0.12: cam and flat tappet in boundary lubrication, 0.1-0.13 ([Staron-Willermet], [Taylor])",
    "fluid_friction": "0.02: EHL traction of a mineral oil at moderate sliding, 0.01-0.03 ([Taylor], [Hamrock])",
    "roller_inertia": (
        "none: from roller_mass as a solid disc m r^2/2, or else a solid steel roller of the contact width "
        "(7850 kg/m^3)"
    ),
    "roller_bearing_friction": (
        "0.003: needle bearing referred to its bore (the pin) radius, M = mu F r_pin; rolling-bearing catalogues "
        "give about 0.002-0.0025 for caged needle bearings, full-complement valve-train rollers run higher ([SKF])"
    ),
    "roller_pin_radius": "4 mm: the pin of a 17-18 mm roller on a full-complement needle bearing",
    "stem_diameter": "5.5 mm: a passenger-car valve stem (as the [valve_train] defaults)",
    "guide_length": "35 mm: the oil-wetted length of a passenger-car valve guide",
    "guide_clearance": (
        "15 um radial: passenger-car service specifications give diametral stem-guide clearances of about "
        "20-50 um (engineering judgement)"
    ),
    "guide_friction": (
        "0.1: steel stem in a sintered or bronze guide, boundary lubricated (typical boundary values 0.08-0.15, "
        "e.g. the friction tables of [Neale])"
    ),
    "pivot_radius": "4 mm: the ball end of a 12 mm hydraulic lash adjuster (a rocker shaft: about 9 mm)",
    "pivot_friction": "0.1: oil-wetted steel ball or shaft pivot in boundary lubrication (as guide_friction)",
}


@dataclass(frozen=True)
class Friction(HoldsOil, Parameters):
    """The ``[friction]`` table: roughness, friction coefficients, the roller's inertia and
    bearing, the stem guide and the pivot; and the oil (:class:`~springdyn.valve.train.oil.Oil`).

    It sits in the valve-train file beside ``[valve_train]`` and ``[follower]``.  The oil is the
    train's one ``[oil]`` table; its keys may still be given here by their older names
    (``oil_viscosity``, ``oil_temperature``, ``oil_viscosity_40``, ``oil_viscosity_100``,
    ``oil_density_15``, ``pressure_viscosity``: :data:`springdyn.valve.train.oil.OLDER_KEYS`),
    with one meaning.  Defaults and their sources: :data:`DEFAULT_SOURCES`.

    Examples
    --------
    >>> f = Friction.from_dict({"boundary_friction": 0.11, "oil_viscosity": "8 mPa*s"})
    >>> f.viscosity
    0.008
    >>> round(Friction().viscosity * 1e3, 2)
    10.6
    """

    #: The oil at the contacts (not a key: ``[oil]``, or the older keys of this table).
    oil: Oil = field(default_factory=Oil)

    surface_roughness: float = param(
        "m",
        "composite rms roughness of cam and follower, sqrt(sigma_1^2 + sigma_2^2)",
        display="um",
        positive=True,
        default=0.3e-6,
        maximum=1e-5,
    )
    boundary_friction: float = param(
        "", "friction coefficient of the cam contact in boundary lubrication", default=0.12, minimum=0.0, maximum=0.5
    )
    fluid_friction: float = param(
        "", "friction coefficient of the cam contact under a full EHL film", default=0.02, minimum=0.0, maximum=0.5
    )
    roller_inertia: float = param(
        "kg*m^2",
        "roller's moment of inertia about its pin (default: from roller_mass, else a solid steel roller)",
        display="g*mm^2",
        nonnegative=True,
        default=None,
        maximum=1.0,
    )
    roller_mass: float = param(
        "kg",
        "roller mass, a solid disc (default: a solid steel roller of the contact width)",
        display="g",
        positive=True,
        default=None,
        maximum=10.0,
    )
    roller_bearing_friction: float = param(
        "",
        "friction coefficient of the roller's needle bearing, referred to the pin radius",
        default=0.003,
        minimum=0.0,
        maximum=0.5,
    )
    roller_pin_radius: float = param(
        "m", "radius of the roller's pin (the bearing's bore)", display="mm", positive=True, default=4e-3
    )
    stem_diameter: float = param("m", "valve stem diameter", display="mm", positive=True, default=5.5e-3)
    guide_length: float = param("m", "oil-wetted length of the valve guide", display="mm", positive=True, default=35e-3)
    guide_clearance: float = param(
        "m", "radial clearance between stem and guide", display="um", positive=True, default=15e-6
    )
    guide_friction: float = param(
        "",
        "Coulomb friction coefficient of the stem in its guide under side load",
        default=0.1,
        minimum=0.0,
        maximum=0.5,
    )
    pivot_radius: float = param(
        "m",
        "friction radius of the lever's pivot (HLA ball or rocker shaft)",
        display="mm",
        positive=True,
        default=4e-3,
    )
    pivot_friction: float = param(
        "", "friction coefficient of the lever's pivot", default=0.1, minimum=0.0, maximum=0.5
    )

    table = "friction"

    def _validate(self) -> None:
        where = "[friction] "
        if self.fluid_friction > self.boundary_friction:
            raise InputError(
                f"{where}fluid_friction = {self.fluid_friction:g} must not exceed boundary_friction = "
                f"{self.boundary_friction:g} (a full film carries less friction than boundary contact): "
                f"allowed 0 to {self.boundary_friction:g}"
            )
        if self.roller_inertia is not None and self.roller_mass is not None:
            raise InputError(f"{where}give roller_inertia or roller_mass (the inertia of a solid disc), not both")
        if not self.guide_clearance < 0.05 * self.stem_diameter:
            raise InputError(
                f"{where}guide_clearance = {self.guide_clearance * 1e6:g} um is not a narrow clearance of a "
                f"{self.stem_diameter * 1e3:g} mm stem: allowed up to 5 % of the diameter "
                f"({0.05 * self.stem_diameter * 1e6:g} um)"
            )

    @classmethod
    def in_document(cls, doc: Mapping, source: str | None = None) -> Friction | None:
        """The ``[friction]`` table of a definition with the train's one oil (``[oil]`` with the oil
        keys of ``[hla]`` and ``[friction]``); None where the definition has no ``[friction]``.

        Parameters
        ----------
        doc, source : mapping, str
            The definition's tables and its file, as :func:`~springdyn.valve.train.oil.oil_of` takes them.
        """
        if "friction" not in doc:
            return None
        oil, rest = oil_of(doc, source)
        follower = doc.get("follower")
        if isinstance(follower, Mapping) and follower.get("kind") == "flat" and isinstance(rest["friction"], Mapping):
            given = [k for k in ROLLER_KEYS if k in rest["friction"]]
            if given:
                raise InputError(
                    f"{source + ': ' if source else ''}[friction] {', '.join(given)}: [follower] kind = 'flat' has no "
                    "roller (a bucket or flat tappet slides on the cam): remove "
                    + ("it" if len(given) == 1 else "them")
                    + ", or describe the roller follower (kind = 'roller', roller_radius)"
                )
        return cls.from_dict(rest["friction"], source=source, oil=oil)

    # -- resolved values ---------------------------------------------------------------
    @property
    def viscosity(self) -> float:
        """Dynamic viscosity of the oil at the contacts [Pa s] (:meth:`Oil.dynamic_viscosity
        <springdyn.valve.train.oil.Oil.dynamic_viscosity>` at the oil's temperature)."""
        return self.oil.dynamic_viscosity()

    @property
    def pressure_viscosity(self) -> float:
        """Pressure-viscosity coefficient of the oil's films [1/Pa]."""
        return self.oil.pressure_viscosity

    def roller_moment_of_inertia(self, follower) -> float:
        """The roller's moment of inertia about its pin [kg m^2].

        ``roller_inertia``; else a solid disc of ``roller_mass``, ``m r^2 / 2``; else a solid
        steel disc of the follower's contact width, ``rho pi r^4 w / 2``.

        Parameters
        ----------
        follower : Follower
            The ``[follower]`` table (a roller: its radius and width).
        """
        if self.roller_inertia is not None:
            return self.roller_inertia
        r = follower.roller_radius
        if self.roller_mass is not None:
            return 0.5 * self.roller_mass * r * r
        return 0.5 * STEEL_DENSITY * math.pi * r**4 * follower.width


# ----------------------------------------------------------------------------- kinematics
@_DOCS.fill
def contact_point(lift, velocity, follower):
    """Contact point of cam and follower in the fixed frame [m] and the pressure angle [rad].

    Flat face: ``P = (h', R_b + h)``, ``phi = 0`` (:func:`~springdyn.valve.cam.checks.flat_contact_offset`);
    roller: ``P = C - r n``, ``C = (e, d0 + h)``, ``n = (-sin(phi), cos(phi))``, ``phi`` from
    :func:`~springdyn.valve.cam.checks.pressure_angle` ([Norton]).

    Parameters
    ----------
    {lift velocity follower}

    Returns
    -------
    px, py, phi : ndarray
        Contact point [m], [m]; pressure angle [rad].
    """
    h, dh = np.asarray(lift, dtype=float), np.asarray(velocity, dtype=float)
    if follower.kind == "flat":
        return dh.copy(), follower.base_circle_radius + h, np.zeros_like(h)
    r, e = follower.roller_radius, follower.offset
    phi = pressure_angle(h, dh, follower.pitch_radius, e)
    return e + r * np.sin(phi), follower.pitch_radius + h - r * np.cos(phi), phi


def drive_torque_arms(px, py, phi):
    """Moment arms about the cam centre of the normal and the tangential contact force [m].

    The follower pushes the cam with ``-N n - F_t t`` at ``P``; the torque that drives the cam
    against it is ``N a_n + F_t a_t`` with ``a_n = P_x cos(phi) + P_y sin(phi)`` and
    ``a_t = P_x sin(phi) - P_y cos(phi)`` (``a_t omega`` is also the cam surface's velocity
    along ``t``).

    Parameters
    ----------
    px, py : array_like
        Contact point in the fixed frame [m] (:func:`contact_point`).
    phi : array_like
        Pressure angle [rad].

    Returns
    -------
    a_n, a_t : ndarray
        [m], [m].
    """
    px, py, phi = (np.asarray(a, dtype=float) for a in (px, py, phi))
    c, s = np.cos(phi), np.sin(phi)
    return px * c + py * s, px * s - py * c


@_DOCS.fill
def flat_contact_velocities(omega, lift, acceleration, base_circle_radius):
    """Surface velocities of cam and flat face relative to their moving contact point [m/s].

    ``u_1 = -omega (R_b + h + h'')`` (the cam, ``-omega rho``) and ``u_2 = -omega h''`` (the
    face), along +x: the contact point moves along the face at ``omega h''`` ([Dyson],
    [Taylor]).

    Parameters
    ----------
    {omega lift acceleration}
    base_circle_radius : float
        Base-circle radius R_b [m].

    Returns
    -------
    u_cam, u_follower : ndarray
        [m/s], [m/s].

    Examples
    --------
    >>> u1, u2 = flat_contact_velocities(100.0, 0.0, 0.0, 0.015)
    >>> float(u1), float(u2)
    (-1.5, -0.0)
    """
    ddh = np.asarray(acceleration, dtype=float)
    return -omega * flat_follower_radius(base_circle_radius, lift, ddh), -omega * ddh


@_DOCS.fill
def roller_rolling_speed(omega, lift, velocity, pitch_radius, roller_radius, offset=0.0):
    """Spin of a roller rolling without sliding on the cam [rad/s] (counter-clockwise positive).

    ``Omega = -omega (D - r) / r``, ``D = sqrt((d0 + h)^2 + (h' - e)^2)``: the cam surface's
    tangential velocity ``omega a_t`` less the roller centre's ``omega h' sin(phi)`` equals
    ``r Omega`` (``-omega R_b / r`` on the base circle).

    Parameters
    ----------
    {omega lift velocity pitch_radius roller_radius offset}
    """
    h, dh = np.asarray(lift, dtype=float), np.asarray(velocity, dtype=float)
    d = np.hypot(pitch_radius + h, dh - offset)
    return -omega * (d - roller_radius) / roller_radius


@_DOCS.fill
def roller_contact_velocities(
    omega, lift, velocity, acceleration, pitch_radius, roller_radius, offset=0.0, roller_speed=None
):
    """Surface velocities of cam and roller relative to their moving contact point [m/s].

    Along ``t``: ``u_1 = omega (r - D) - r phi_dot`` (the cam), ``u_2 = r (Omega - phi_dot)``
    (the roller), ``phi_dot = omega ((d0 + h) h'' - (h' - e) h') / D^2`` the turning rate of
    the contact normal, ``D = sqrt((d0 + h)^2 + (h' - e)^2)`` (module docstring).

    Parameters
    ----------
    {omega lift velocity acceleration pitch_radius roller_radius offset}
    roller_speed : array_like, optional
        The roller's spin Omega [rad/s] (default: pure rolling, :func:`roller_rolling_speed`).

    Returns
    -------
    u_cam, u_roller : ndarray
        [m/s], [m/s].
    """
    h, dh, ddh = (np.asarray(a, dtype=float) for a in (lift, velocity, acceleration))
    y, v = pitch_radius + h, dh - offset
    d2 = y * y + v * v
    phi_dot = omega * (y * ddh - v * dh) / d2
    r = roller_radius
    spin = roller_rolling_speed(omega, h, dh, pitch_radius, r, offset) if roller_speed is None else roller_speed
    return omega * (r - np.sqrt(d2)) - r * phi_dot, r * (np.asarray(spin, dtype=float) - phi_dot)


def entrainment_velocity(u_1, u_2):
    """Entrainment (rolling, mean) velocity ``u_e = (u_1 + u_2)/2`` [m/s] ([Hamrock]).

    Parameters
    ----------
    u_1, u_2 : array_like
        Surface velocities relative to the contact point [m/s].
    """
    return 0.5 * (np.asarray(u_1, dtype=float) + np.asarray(u_2, dtype=float))


def sliding_velocity(u_1, u_2):
    """Sliding velocity ``u_s = u_1 - u_2`` [m/s] (of the cam over the follower).

    Parameters
    ----------
    u_1, u_2 : array_like
        Surface velocities of cam and follower [m/s] (relative to the contact point or not:
        the difference is the same).
    """
    return np.asarray(u_1, dtype=float) - np.asarray(u_2, dtype=float)


# ----------------------------------------------------------------------------- lubrication
def line_contact_film_thickness(entrainment, load_per_width, radius, reduced_modulus, viscosity, pressure_viscosity):
    """Central and minimum EHL film thickness of a line contact [m] ([Pan-Hamrock]).

    ``H_c = 2.922 W^-0.166 U^0.692 G^0.470``, ``H_min = 1.714 W^-0.128 U^0.694 G^0.568``, with
    ``U = eta_0 |u_e| / (E' R)``, ``G = alpha E'``, ``W = w / (E' R)``, ``E' = 2 E*`` and
    ``h = H R``: isothermal, Newtonian, smooth surfaces, fully flooded.  No entrainment, no
    film (the squeeze film is not modelled).

    Parameters
    ----------
    entrainment : array_like
        Entrainment velocity u_e [m/s] (its magnitude is used).
    load_per_width : array_like
        Normal load per contact length w [N/m] (floored at 1 N/m).
    radius : array_like
        Reduced radius R in the rolling direction [m], positive.
    reduced_modulus : float
        Contact modulus E* [Pa] (Hamrock's E' = 2 E*).
    viscosity : float
        Dynamic viscosity at ambient pressure eta_0 [Pa s].
    pressure_viscosity : float
        Pressure-viscosity coefficient alpha [1/Pa].

    Returns
    -------
    h_central, h_min : ndarray
        [m], [m].
    """
    e_prime = 2.0 * reduced_modulus
    r = np.asarray(radius, dtype=float)
    u = viscosity * np.abs(np.asarray(entrainment, dtype=float)) / (e_prime * r)
    w = np.maximum(np.asarray(load_per_width, dtype=float), _MIN_LOAD_PER_WIDTH) / (e_prime * r)
    g = pressure_viscosity * e_prime
    h_c = 2.922 * w**-0.166 * u**0.692 * g**0.470 * r
    h_min = 1.714 * w**-0.128 * u**0.694 * g**0.568 * r
    return h_c, h_min


@_DOCS.fill
def boundary_share(film_parameter):
    """Share of the contact in boundary lubrication ``f_b = erfc(lambda / sqrt(2))`` [-].

    The probability that a Gaussian composite roughness of rms ``sigma`` exceeds the film
    ``lambda sigma`` in magnitude ([Johnson-Greenwood-Poon] load sharing; the regime limits of
    [Hamrock]: 1 at ``lambda = 0``, 0.32 at 1, 0.046 at 2, 0.0027 at 3).

    Parameters
    ----------
    {film_parameter}
    """
    lam = np.maximum(np.asarray(film_parameter, dtype=float), 0.0)
    return erfc(lam / math.sqrt(2.0))


@_DOCS.fill
def friction_coefficient(film_parameter, boundary, fluid):
    """Friction coefficient of a lubricated contact by its regime [-].

    ``mu = f_b mu_b + (1 - f_b) mu_f`` with ``f_b`` the boundary share (:func:`boundary_share`):
    ``mu_b`` for ``lambda -> 0``, ``mu_f`` for ``lambda >> 3``, monotone between.

    Parameters
    ----------
    {film_parameter}
    boundary : float
        Boundary friction coefficient mu_b [-].
    fluid : float
        Full-film friction coefficient mu_f [-].

    Examples
    --------
    >>> float(friction_coefficient(0.0, 0.12, 0.02)), round(float(friction_coefficient(10.0, 0.12, 0.02)), 6)
    (0.12, 0.02)
    """
    f = boundary_share(film_parameter)
    return f * boundary + (1.0 - f) * fluid


# ----------------------------------------------------------------------------- roller slip
@dataclass(frozen=True)
class RollerSpin:
    """The roller's spin over one periodic revolution (:func:`roller_spin`)."""

    speed: np.ndarray  #: spin Omega [rad/s]
    traction: np.ndarray  #: traction on the roller along t [N]
    normal_force: np.ndarray  #: contact normal force N [N]
    sliding: np.ndarray  #: sliding velocity u_s = r (Omega_roll - Omega) [m/s]
    slipping: np.ndarray  #: bool: the roller slides on the cam
    bearing_torque: np.ndarray  #: bearing torque acting against the spin [N m]
    periodic: bool  #: the spin repeated over the revolution
    revolutions: int  #: revolutions integrated


@_DOCS.fill
def roller_spin(omega, rolling_speed, axial_force, pressure_angle, friction, roller_radius, inertia, bearing_arm):
    """The roller's spin over a periodic revolution, with slip where traction runs short.

    ``J dOmega/dt = r F_t - T_b sign(Omega)``, ``T_b = mu_b r_pin N_0`` (the bearing carries
    the normal force ``N_0 = F / cos(phi)``).  A step rolls (``Omega = Omega_roll``) when the
    traction that needs, ``F_t = (J dOmega_roll/dt + T_b sign)/r``, is within ``mu N``; else
    the roller slides with ``F_t = mu N sign(F_t needed)`` (backward Euler on the uniform grid,
    the bearing's Coulomb torque never reversing the spin).  The normal force balances the
    axial force: ``N cos(phi) + F_t sin(phi) = F``.  Repeated from the rolling start until the
    spin repeats (at once after the first stick).  ``J = 0``: rolling where the traction holds
    the bearing torque, else the roller stands still and slides.

    Parameters
    ----------
    {omega_positive}
    rolling_speed : array_like
        Pure-rolling spin Omega_roll over the revolution [rad/s] (:func:`roller_rolling_speed`),
        on a uniform cam-angle grid over [0, 2 pi).
    axial_force : array_like
        Force along the follower axis F [N] (negative counts as 0).
    pressure_angle : array_like
        phi [rad].
    friction : array_like
        Traction limit mu of the cam contact [-] (:func:`friction_coefficient`).
    roller_radius : float
        r [m].
    inertia : float
        J [kg m^2], zero or positive.
    bearing_arm : float
        mu_b r_pin: bearing torque per normal force [m].

    Returns
    -------
    RollerSpin
    """
    w_roll = np.asarray(rolling_speed, dtype=float)
    n = w_roll.size
    f = np.maximum(np.asarray(axial_force, dtype=float), 0.0)
    phi = np.broadcast_to(np.asarray(pressure_angle, dtype=float), (n,))
    mu = np.broadcast_to(np.asarray(friction, dtype=float), (n,))
    c, s = np.cos(phi), np.sin(phi)
    t_b = bearing_arm * f / c
    r, j = roller_radius, inertia
    dt = _TWO_PI / (n * omega)
    speed, traction, normal = np.empty(n), np.empty(n), np.empty(n)
    slipping, torque = np.zeros(n, dtype=bool), np.empty(n)
    start = float(w_roll[0])
    periodic, revolutions = False, 0
    while not periodic and revolutions < _SPIN_REVOLUTIONS:
        revolutions += 1
        w = start
        for i in range(1, n + 1):
            k = i % n
            wr = float(w_roll[k])
            direction = math.copysign(1.0, wr) if wr != 0.0 else 0.0
            need = (j * (wr - w) / dt + t_b[k] * direction) / r
            n_roll = (f[k] - need * s[k]) / c[k]
            if n_roll >= 0.0 and abs(need) <= mu[k] * n_roll:
                w, ft, nn, tb, slip = wr, need, n_roll, t_b[k] * abs(direction), False
            else:
                sigma = math.copysign(1.0, need)
                nn = f[k] / (c[k] + mu[k] * sigma * s[k])
                ft = mu[k] * nn * sigma
                if j > 0.0:
                    trial = w + dt * r * ft / j
                    after = math.copysign(max(abs(trial) - dt * t_b[k] / j, 0.0), trial)
                    tb = abs(trial - after) * j / dt
                    w = after
                else:
                    w, tb = 0.0, 0.0
                slip = True
            speed[k], traction[k], normal[k], torque[k], slipping[k] = w, ft, nn, tb, slip
        scale = max(abs(start), float(np.max(np.abs(w_roll))), 1e-12)
        periodic = abs(w - start) <= 1e-10 * scale
        start = w
    return RollerSpin(
        speed=speed,
        traction=traction,
        normal_force=normal,
        sliding=r * (w_roll - speed),
        slipping=slipping,
        bearing_torque=torque,
        periodic=periodic,
        revolutions=revolutions,
    )


# ----------------------------------------------------------------------------- guide, pivot
def petroff_force(viscosity, diameter, length, radial_clearance, velocity):
    """Viscous (Petroff) force of a shaft sliding concentrically in a bore [N], signed as the
    velocity: ``F = eta pi d L v / c`` (Couette shear of the clearance's oil, [Hamrock]).

    Parameters
    ----------
    viscosity : float
        Oil dynamic viscosity eta [Pa s].
    diameter : float
        Shaft (stem) diameter d [m].
    length : float
        Wetted length L [m].
    radial_clearance : float
        Radial clearance c [m].
    velocity : array_like
        Sliding velocity v [m/s].

    Examples
    --------
    >>> round(float(petroff_force(0.01, 0.005, 0.04, 20e-6, 1.0)), 4)
    0.3142
    """
    return viscosity * math.pi * diameter * length / radial_clearance * np.asarray(velocity, dtype=float)


def guide_friction_force(velocity, side_load, viscosity, stem_diameter, guide_length, radial_clearance, coefficient):
    """Friction force of the stem guide on the valve [N], against the valve's velocity.

    ``F_g = -(eta pi d L |v| / c + mu_g |S|) sign(v)``: Petroff's viscous force
    (:func:`petroff_force`) plus Coulomb friction under the side load ``S``.

    Parameters
    ----------
    velocity : array_like
        Valve velocity v [m/s].
    side_load : array_like
        Side (radial) load of the stem on its guide S [N] (the caller derives it, e.g. from a
        lever's tip force).
    viscosity : float
        Oil dynamic viscosity [Pa s].
    stem_diameter : float
        d [m].
    guide_length : float
        L [m].
    radial_clearance : float
        c [m].
    coefficient : float
        mu_g [-].
    """
    v = np.asarray(velocity, dtype=float)
    magnitude = np.abs(petroff_force(viscosity, stem_diameter, guide_length, radial_clearance, v))
    magnitude = magnitude + coefficient * np.abs(np.asarray(side_load, dtype=float))
    return -np.sign(v) * magnitude


def pivot_friction_torque(pivot_force, pivot_radius, coefficient):
    """Friction torque of a lever's pivot [N m], its magnitude: ``T_p = mu_p r_p |F_p|``.

    Parameters
    ----------
    pivot_force : array_like
        Force on the pivot F_p [N].
    pivot_radius : float
        Friction radius r_p [m] (ball or shaft radius).
    coefficient : float
        mu_p [-].
    """
    return coefficient * pivot_radius * np.abs(np.asarray(pivot_force, dtype=float))


# ----------------------------------------------------------------------------- the analysis
def _array(name, value, n):
    a = np.asarray(value, dtype=float)
    if a.ndim == 0:
        a = np.full(n, float(a))
    if a.shape != (n,) or not np.all(np.isfinite(a)):
        raise InputError(f"{name} must be a finite number or {n} finite values, one per cam angle")
    return a


@_DOCS.fill
def friction_along_cam(
    cam_angle,
    omega,
    lift,
    dlift,
    ddlift,
    cam_force,
    follower,
    friction,
    *,
    valve_velocity=None,
    ratio=1.0,
    side_load=0.0,
    pivot_force=None,
    lever_arm=None,
    reflect=True,
):
    """Friction of the valve train over one revolution, the camshaft's drive torque and the
    energy balance (module docstring).

    Parameters
    ----------
    cam_angle : array_like
        Cam angles [rad], uniform over one revolution [0, 2 pi) (at least 360).
    {omega_positive}
    lift, dlift, ddlift : array_like
        Lobe lift h [m], dh/dtheta [m/rad], d2h/dtheta2 [m/rad^2] at those angles.
    cam_force : array_like
        Force of the follower on the cam along its axis [N] (a simulation's cam contact force
        or the kinematic load; negative counts as 0, no contact).
    {follower}
    friction : Friction
        The ``[friction]`` table.
    valve_velocity : array_like, optional
        Valve velocity [m/s] (default: the rigid train's ``ratio h' omega``).
    ratio : float
        Valve lift per lobe lift r [-] (refers the guide friction to the cam).
    side_load : float or array_like
        Side load of the stem on its guide [N] (default 0: viscous guide friction only).
    pivot_force : array_like, optional
        Force on a lever's pivot [N] (default: no pivot, as a bucket tappet).
    lever_arm : float, optional
        Distance from the pivot to the cam contact along the lever [m] (with ``pivot_force``):
        the lever turns at ``h' omega / lever_arm``.
    reflect : bool
        Add the guide and pivot friction, referred to the follower axis, to the cam's load
        (the camshaft drives them); False: the cam carries ``cam_force`` alone.

    Returns
    -------
    FrictionAnalysis
    """

    if not isinstance(follower, Follower):
        raise InputError(f"follower = {follower!r} must be a Follower (the [follower] table)")
    if not isinstance(friction, Friction):
        raise InputError(f"friction = {friction!r} must be a Friction (the [friction] table)")
    theta = np.asarray(cam_angle, dtype=float)
    n = theta.size
    if theta.ndim != 1 or n < 360 or not np.all(np.isfinite(theta)):
        raise InputError("cam_angle must be a flat array of at least 360 finite cam angles [rad] over one revolution")
    step = _TWO_PI / n
    if not np.allclose(np.diff(theta), step, rtol=1e-6, atol=1e-12):
        raise InputError(
            f"cam_angle must be uniform over one revolution: {n} angles {math.degrees(step):.6g} deg apart"
        )
    if isinstance(omega, bool) or not isinstance(omega, (int, float)) or not 0 < omega < 1e5:
        raise InputError(f"omega = {omega!r} must be a cam speed from 0 to 1e5 rad/s (positive)")
    if not 0 < ratio < 100:
        raise InputError(f"ratio = {ratio!r} must be a positive lever ratio (valve lift per lobe lift)")
    h, dh, ddh, force = (
        _array(k, v, n) for k, v in (("lift", lift), ("dlift", dlift), ("ddlift", ddlift), ("cam_force", cam_force))
    )
    notes = []
    v_valve = ratio * dh * omega if valve_velocity is None else _array("valve_velocity", valve_velocity, n)
    side = _array("side_load", side_load, n)
    eta = friction.viscosity
    contact = force > 0.0

    # guide and pivot
    f_guide = guide_friction_force(
        v_valve,
        side,
        eta,
        friction.stem_diameter,
        friction.guide_length,
        friction.guide_clearance,
        friction.guide_friction,
    )
    p_guide = -f_guide * v_valve
    if pivot_force is not None:
        if lever_arm is None or not lever_arm > 0:
            raise InputError("pivot_force needs lever_arm: the distance from the pivot to the cam contact [m]")
        t_pivot = pivot_friction_torque(
            _array("pivot_force", pivot_force, n), friction.pivot_radius, friction.pivot_friction
        )
        lever_rate = dh * omega / lever_arm
        p_pivot = t_pivot * np.abs(lever_rate)
        reflected_pivot = t_pivot * np.sign(dh) / lever_arm
    else:
        t_pivot = np.zeros(n)
        p_pivot = np.zeros(n)
        reflected_pivot = np.zeros(n)
    axial = np.where(contact, force, 0.0)
    if reflect:
        axial = np.where(contact, np.maximum(axial - ratio * f_guide + reflected_pivot, 0.0), 0.0)

    # the contact geometry and the lubrication at the contact
    px, py, phi = contact_point(h, dh, follower)
    a_n, a_t = drive_torque_arms(px, py, phi)
    if follower.kind == "flat":
        rho = flat_follower_radius(follower.base_circle_radius, h, ddh)
        if np.any(rho <= 0.0):
            notes.append("the cam's radius of curvature is not positive somewhere (a cusp): the film is zero there")
        radius = np.maximum(rho, 1e-6)
        u1, u2 = flat_contact_velocities(omega, h, ddh, follower.base_circle_radius)
    else:
        kp = pitch_curve_curvature(h, dh, ddh, follower.pitch_radius, follower.offset)
        kappa, undercut = roller_cam_curvature(kp, follower.roller_radius)
        if np.any(undercut):
            notes.append("the cam is undercut somewhere: the film there is meaningless")
        k_x = kappa + 1.0 / follower.roller_radius
        radius = 1.0 / np.maximum(k_x, 1e-6)
        u1, u2 = roller_contact_velocities(
            omega, h, dh, ddh, follower.pitch_radius, follower.roller_radius, follower.offset
        )
    u_e_film = entrainment_velocity(u1, u2)  # a roller: the rolling entrainment
    normal0 = axial / np.cos(phi)
    _, h_min = line_contact_film_thickness(
        u_e_film, normal0 / follower.width, radius, follower.reduced_modulus, eta, friction.pressure_viscosity
    )
    lam = h_min / friction.surface_roughness
    mu = friction_coefficient(lam, friction.boundary_friction, friction.fluid_friction)

    spin = None
    if follower.kind == "flat":
        u_s = sliding_velocity(u1, u2)
        normal = axial
        traction = mu * normal * np.sign(u_s)
        p_bearing = np.zeros(n)
        u_e = u_e_film
    else:
        w_roll = roller_rolling_speed(omega, h, dh, follower.pitch_radius, follower.roller_radius, follower.offset)
        j = friction.roller_moment_of_inertia(follower)
        wedge = float(np.max(np.abs(np.tan(phi)))) * friction.boundary_friction
        if wedge >= 0.9:
            raise InputError(
                f"the pressure angle reaches {math.degrees(float(np.max(np.abs(phi)))):.1f} deg: with boundary_friction "
                f"= {friction.boundary_friction:g} the roller's traction nearly wedges it (mu tan(phi) = {wedge:.2f}, "
                "allowed below 0.9); check the cam against its follower (check_cam)"
            )
        if not friction.roller_pin_radius < follower.roller_radius:
            raise InputError(
                f"[friction] roller_pin_radius = {friction.roller_pin_radius * 1e3:g} mm must be smaller than the "
                f"roller radius {follower.roller_radius * 1e3:g} mm"
            )
        spin = roller_spin(
            omega,
            w_roll,
            axial,
            phi,
            mu,
            follower.roller_radius,
            j,
            friction.roller_bearing_friction * friction.roller_pin_radius,
        )
        if not spin.periodic:
            notes.append(f"the roller's spin did not repeat within {spin.revolutions} revolutions")
        u_s, normal, traction = spin.sliding, spin.normal_force, spin.traction
        p_bearing = spin.bearing_torque * np.abs(spin.speed)
        _, u_roller = roller_contact_velocities(
            omega, h, dh, ddh, follower.pitch_radius, follower.roller_radius, follower.offset, spin.speed
        )
        u_e = entrainment_velocity(u1, u_roller)
    p_cam = traction * u_s
    torque = normal * a_n + traction * a_t
    powers = dict(cam=p_cam, roller_bearing=p_bearing, guide=p_guide, pivot=p_pivot)
    return FrictionAnalysis(
        cam_angle=theta,
        omega=float(omega),
        follower=follower,
        friction=friction,
        lift=h,
        cam_force=force,
        axial_force=axial,
        normal_force=normal,
        tangential_force=traction,
        pressure_angle=phi,
        entrainment_velocity=u_e,
        sliding_velocity=u_s,
        film_thickness=h_min,
        film_parameter=lam,
        friction_coefficient=mu,
        drive_torque=torque,
        normal_torque=normal * a_n,
        friction_torque=traction * a_t,
        guide_force=f_guide,
        pivot_torque=t_pivot,
        powers=powers,
        roller_speed=None if spin is None else spin.speed,
        rolling_speed=None if spin is None else w_roll,
        slipping=None if spin is None else spin.slipping,
        notes=notes,
    )


@dataclass(repr=False)
class FrictionAnalysis(Result):
    """Valve-train friction over one revolution (:func:`friction_along_cam`): the cam contact's
    kinematics, film and friction, the roller's slip, the drive torque and each contact's
    friction power."""

    cam_angle: np.ndarray  # [rad]
    omega: float  # [rad/s]
    follower: object
    friction: object
    lift: np.ndarray  # lobe lift [m]
    cam_force: np.ndarray  # given axial force [N]
    axial_force: np.ndarray  # axial force the cam carries (guide and pivot friction included) [N]
    normal_force: np.ndarray  # [N]
    tangential_force: np.ndarray  # traction on the follower along t [N]
    pressure_angle: np.ndarray  # [rad]
    entrainment_velocity: np.ndarray  # [m/s]
    sliding_velocity: np.ndarray  # cam over follower [m/s]
    film_thickness: np.ndarray  # h_min [m]
    film_parameter: np.ndarray  # lambda [-]
    friction_coefficient: np.ndarray  # [-]
    drive_torque: np.ndarray  # [N m]
    normal_torque: np.ndarray  # [N m]
    friction_torque: np.ndarray  # [N m]
    guide_force: np.ndarray  # on the valve [N]
    pivot_torque: np.ndarray  # magnitude [N m]
    powers: dict  # contact -> friction power [W]
    roller_speed: np.ndarray | None = None  # [rad/s]
    rolling_speed: np.ndarray | None = None  # [rad/s]
    slipping: np.ndarray | None = None  # bool
    notes: list = field(default_factory=list)

    title = "valve-train friction"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.follower.kind} follower at {self.cam_rpm:.6g} cam rpm"

    @property
    def cam_rpm(self) -> float:
        """Cam speed [rev/min]."""
        return self.omega * 60.0 / _TWO_PI

    @property
    def dt(self) -> float:
        """Time step of the cam-angle grid [s]."""
        return _TWO_PI / (self.cam_angle.size * self.omega)

    @property
    def friction_power(self) -> np.ndarray:
        """Total friction power over the cam angle [W]."""
        return sum(self.powers.values())

    @property
    def cam_work(self) -> float:
        """Work of the camshaft over the revolution, ``int T dtheta`` [J]."""
        return float(np.sum(self.drive_torque)) * _TWO_PI / self.cam_angle.size

    @property
    def dissipated(self) -> dict:
        """Energy each contact dissipates over the revolution [J]."""
        return {k: float(np.sum(p)) * self.dt for k, p in self.powers.items()}

    @property
    def load_work(self) -> float:
        """Work of the given axial force over the revolution, ``int F dh`` [J] (``F h' dtheta``;
        the spring's elastic change and the inertia: zero for a periodic conservative train)."""
        h = self.lift
        dh = np.gradient(np.concatenate([h[-1:], h, h[:1]]), _TWO_PI / h.size)[1:-1]
        return float(np.sum(np.where(self.cam_force > 0.0, self.cam_force, 0.0) * dh)) * _TWO_PI / h.size

    def _summary(self) -> dict:
        diss = self.dissipated
        rev_time = _TWO_PI / self.omega
        s = dict(
            follower=self.follower.kind,
            cam_rpm=self.cam_rpm,
            mean_drive_torque_N_m=float(np.mean(self.drive_torque)),
            max_drive_torque_N_m=float(np.max(self.drive_torque)),
            min_drive_torque_N_m=float(np.min(self.drive_torque)),
            friction_power_W=float(sum(diss.values()) / rev_time),
        )
        for k in CONTACTS:
            s[f"friction_power_{k}_W"] = diss[k] / rev_time
        s["cam_work_J"] = self.cam_work
        s["load_work_J"] = self.load_work
        for k in CONTACTS:
            s[f"dissipated_{k}_J"] = diss[k]
        s["energy_residual_J"] = self.cam_work - self.load_work - sum(diss.values())
        notes = list(self.notes)
        if abs(s["energy_residual_J"]) > ENERGY_NOTE_TOL * max(abs(self.cam_work), sum(diss.values()), 1e-12):
            notes.append(
                f"the energy balance leaves {s['energy_residual_J']:.3g} J of {self.cam_work:.3g} J: the guide and "
                "pivot friction are referred to the cam by the rigid lever (ratio), and the simulated valve velocity "
                "differs from the rigid train's by the train's elasticity"
            )
        loaded = self.normal_force > 0.0
        if loaded.any():
            lam = self.film_parameter[loaded]
            s["min_film_parameter"] = float(lam.min())
            s["boundary_share_of_contact"] = float(np.mean(lam < 1.0))
            s["full_film_share_of_contact"] = float(np.mean(lam > 3.0))
            s["max_friction_coefficient"] = float(self.friction_coefficient[loaded].max())
        if self.slipping is not None:
            s["slip_share"] = float(np.mean(self.slipping))
            s["slip_share_loaded"] = float(np.mean(self.slipping[loaded])) if loaded.any() else None
            s["max_slip_velocity_m_per_s"] = float(np.max(np.abs(self.sliding_velocity)))
        if notes:
            s["notes"] = notes
        return s

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        dims = ("cam_angle",)
        data = {
            "lift": (dims, self.lift, {"units": "m"}),
            "cam_force": (dims, self.cam_force, {"units": "N"}),
            "normal_force": (dims, self.normal_force, {"units": "N"}),
            "tangential_force": (dims, self.tangential_force, {"units": "N"}),
            "entrainment_velocity": (dims, self.entrainment_velocity, {"units": "m/s"}),
            "sliding_velocity": (dims, self.sliding_velocity, {"units": "m/s"}),
            "film_thickness": (dims, self.film_thickness, {"units": "m"}),
            "film_parameter": (dims, self.film_parameter, {"units": "1"}),
            "friction_coefficient": (dims, self.friction_coefficient, {"units": "1"}),
            "drive_torque": (dims, self.drive_torque, {"units": "N*m"}),
            "guide_force": (dims, self.guide_force, {"units": "N"}),
        }
        for k in CONTACTS:
            data[f"friction_power_{k}"] = (dims, self.powers[k], {"units": "W"})
        if self.roller_speed is not None:
            data["roller_speed"] = (dims, self.roller_speed, {"units": "rad/s"})
            data["rolling_speed"] = (dims, self.rolling_speed, {"units": "rad/s"})
            data["slipping"] = (dims, self.slipping.astype(int), {"units": "1"})
        coords = {"cam_angle": (dims, np.degrees(self.cam_angle), {"units": "deg"})}
        return xr.Dataset(data, coords=coords, attrs={"follower": self.follower.kind, "cam_rpm": self.cam_rpm})

    def _plot(self, ax=None):
        """Drive torque, friction power per contact, film parameter and friction coefficient
        over the cam angle; into ``ax``: the drive torque."""
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        deg = np.degrees(self.cam_angle)
        if ax is not None:
            fig, axes = ax.figure, [ax]
        else:
            fig, grid = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
            axes = list(grid)
        a = axes[0]
        a.plot(deg, self.drive_torque, "C0", label="drive torque")
        a.plot(deg, self.friction_torque, "C3", lw=0.8, label="of the cam contact's friction")
        a.axhline(float(np.mean(self.drive_torque)), color="k", ls="--", lw=0.8, label="mean")
        a.set_ylabel("torque [N m]")
        a.legend(fontsize=7)
        a.set_title(f"{self.follower.kind} follower, {self.cam_rpm:.0f} cam rpm")
        if len(axes) == 1:
            return fig
        for i, k in enumerate(CONTACTS):
            if np.any(self.powers[k]):
                axes[1].plot(deg, self.powers[k], f"C{i}", label=k.replace("_", " "))
        axes[1].set_ylabel("friction power [W]")
        axes[1].legend(fontsize=7)
        axes[2].semilogy(deg, np.clip(self.film_parameter, 1e-3, 1e3), "C0", label="film parameter lambda")
        axes[2].set_ylabel("lambda [-]")
        b = axes[2].twinx()
        b.plot(deg, self.friction_coefficient, "C3", lw=0.8)
        b.set_ylabel("friction coefficient [-]", color="C3")
        axes[2].set_xlabel("cam angle [deg]")
        for a in axes:
            a.grid(True, alpha=0.3)
        fig.tight_layout()
        return fig
