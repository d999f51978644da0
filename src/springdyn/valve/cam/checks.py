"""The cam designer's checks: radius of curvature, contact excursion, pressure angle and
Hertz stress along the cam, and the cam's profile.

The follower (:class:`~springdyn.valve.cam.follower.Follower`, ``[follower]``) rides on the lobe
lift ``h(theta)`` (per radian of cam angle: ``h' = dh/dtheta``, ``h'' = d2h/dtheta2``) as a
follower translating along its axis.  Frame: the follower moves along +y above the cam
centre, its axis at ``x = offset``; the cam turns counter-clockwise; cam-frame coordinates
turn with the cam (``theta = 0``: the follower on the cam-frame +y axis).  Sources: [Norton]
(cam size and profile determination: radius of curvature, pressure angle, flat-follower
eccentricity), [Johnson] 4.2 (Hertz line and point contact), [Hamrock-Brewe] (elliptical
contact in closed form), all in docs/references.md.

**Flat-faced follower** (bucket tappet): the face is the line ``y = R_b + h``, the cam its
envelope.  The contact point sits ``h'`` from the cam centre's line along the face
(:func:`flat_contact_offset`; ``h' - offset`` from the follower axis), and the cam's radius
of curvature there is ``rho = R_b + h + h''`` (:func:`flat_follower_radius`).  ``rho <= 0``
is a cusp: no flat follower can follow that lift on that base circle (raise the base circle
or soften the nose).

**Roller follower**: the roller centre (pitch point) is at ``(offset, d0 + h)``,
``d0 = sqrt((R_b + r)^2 - offset^2)``.  In the cam frame that point traces the pitch curve;
its curvature :func:`pitch_curve_curvature` and the pressure angle
``tan(phi) = (h' - offset)/(d0 + h)`` (:func:`pressure_angle`) follow from the lift and its
derivatives.  The cam surface is the pitch curve offset inwards by ``r``: radius
``rho = rho_p - r`` (:func:`roller_cam_curvature`), convex where ``rho_p > r``; where the
pitch curve is convex with ``rho_p < r`` the offset curve folds over itself: **undercut**.
Concave parts (``rho_p < 0``) are allowed for a roller (not for a flat face).

**Hertz stress** (:func:`line_contact`, :func:`elliptical_contact`): cylinder on cylinder
(the cam's local radius against the roller, or against the flat face of infinite radius) over
the contact width; with a crown the elliptical (point) contact of the Hamrock-Brewe
formulas.  The force is the contact's normal force: the follower's axial force over
``cos(phi)``.

**Load** (:func:`kinematic_cam_force`): the quasi-static ("kinematic") cam force of a rigid
train, ``F_cam = r (F_s(L_inst - z) + M z'')`` while the valve is open, with the valve lift
``z = r h - lash``, its acceleration ``z'' = r h'' omega^2``, the spring's static force
``F_s`` at its length, and ``M`` the train's mass referred to the valve plus a third of the
spring's mass (the retainer end of a uniformly moving spring); the lever multiplies the
valve-side force by its ratio ``r`` (virtual work: ``F_cam dh = F_valve dz``, ``dz = r dh``).
On the base circle the cam carries only an adjuster's plunger force.  It ignores the train's
elasticity and surge: a dynamic check passes the simulation's cam contact force
(``Simulation.cam_contact_force``) as ``contact_force``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...core.docstrings import ParameterDocs
from ...core.errors import InputError
from ...core.results import Result, notes_lines
from ...core.units import rpm_to_omega
from .definition import OPEN_LIFT
from .follower import Follower

__all__ = [
    "flat_follower_radius",
    "flat_contact_offset",
    "flat_face_reach",
    "pressure_angle",
    "pitch_curve_curvature",
    "roller_cam_curvature",
    "cam_profile",
    "line_contact",
    "elliptical_contact",
    "kinematic_cam_force",
    "check_cam",
    "CamCheck",
    "PRESSURE_ANGLE_GUIDE",
    "PITCH_RADIUS_GUIDE",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    offset : float
        Follower axis offset along +x [m].
    velocity : float or array_like
        dh/dtheta [m/rad].
    lift : float or array_like
        Lobe lift h [m].
    reduced_modulus : float
        Contact modulus E* [Pa].
    follower : Follower
        The ``[follower]`` table.
    pitch_radius : float
        d0 = sqrt((R_b + r)^2 - offset^2) [m].
    acceleration : float or array_like
        d2h/dtheta2 [m/rad^2].
    force : float or array_like
        Normal force F [N] (negative counts as 0).
    """
)

#: Largest pressure angle of a translating roller follower of common guidance [rad] (30 deg,
#: [Norton]); beyond it the side thrust on the follower's guide grows quickly.
PRESSURE_ANGLE_GUIDE = math.radians(30.0)
#: Smallest ratio of the pitch curve's convex radius to the roller radius of common guidance
#: [-] ([Norton]: 2-3; below it the cam's convex radius is small and its stress high).
PITCH_RADIUS_GUIDE = 2.0
#: Samples per revolution of the checks (0.05 deg, as the cam analysis).
SAMPLES = 7200
_TWO_PI = 2.0 * math.pi


# ----------------------------------------------------------------------------- geometry
@_DOCS.fill
def flat_follower_radius(base_circle_radius, lift, acceleration):
    """Radius of curvature of the cam under a flat-faced translating follower [m].

    ``rho = R_b + h + d2h/dtheta2`` ([Norton]); positive convex.  ``rho <= 0`` is a cusp (the
    face cannot follow the lift there).

    Parameters
    ----------
    base_circle_radius : float
        Base-circle radius R_b [m].
    {lift acceleration}

    Examples
    --------
    >>> float(flat_follower_radius(0.015, 0.0, 0.0))
    0.015
    """
    return base_circle_radius + np.asarray(lift, dtype=float) + np.asarray(acceleration, dtype=float)


@_DOCS.fill
def flat_contact_offset(velocity, offset=0.0):
    """Distance of the contact point from a flat follower's axis along its face [m].

    The contact sits ``dh/dtheta`` from the line through the cam centre along the motion
    ([Norton]: the eccentricity of the flat follower equals the velocity per radian), so
    ``h' - offset`` from the axis; positive towards +x (the cam turning counter-clockwise,
    the follower above it), positive on the opening flank without offset.

    Parameters
    ----------
    {velocity offset}
    """
    return np.asarray(velocity, dtype=float) - offset


def flat_face_reach(contact_offset, width, lateral_offset=0.0):
    """Largest distance of the contact line from the axis of a round flat face [m].

    The contact is a line of length ``width`` across the face (along the camshaft), centred
    ``lateral_offset`` from the axis and ``contact_offset`` from it along the motion; its ends
    are farthest: ``sqrt(e^2 + (|lateral_offset| + width/2)^2)``.  It must stay inside the
    face radius less the edge margin.

    Parameters
    ----------
    contact_offset : float or array_like
        Contact offset e along the motion [m] (:func:`flat_contact_offset`).
    width : float
        Contact width [m].
    lateral_offset : float
        Tappet axis offset along the camshaft [m].
    """
    e = np.asarray(contact_offset, dtype=float)
    return np.hypot(e, abs(lateral_offset) + 0.5 * width)


@_DOCS.fill
def pressure_angle(lift, velocity, pitch_radius, offset=0.0):
    """Pressure angle of a translating roller follower [rad]: between the contact normal and
    the follower's axis.

    ``tan(phi) = (h' - offset)/(d0 + h)``, ``d0`` the roller centre's height on the base
    circle ([Norton]).

    Parameters
    ----------
    {lift velocity pitch_radius offset}
    """
    return np.arctan2(np.asarray(velocity, dtype=float) - offset, pitch_radius + np.asarray(lift, dtype=float))


@_DOCS.fill
def pitch_curve_curvature(lift, velocity, acceleration, pitch_radius, offset=0.0):
    """Curvature of a roller follower's pitch curve in the cam frame [1/m], positive convex.

    The roller centre ``C = (offset, d0 + h)`` seen from the cam turned by ``theta`` is
    ``P = Rot(-theta) C``; with ``A = C' - J C`` and ``B = C'' - 2 J C' - C`` (``J`` the
    quarter turn) the convex curvature is ``-(A x B)/|A|^3``:

    ``kappa = ((d0+h)^2 + (h'-e)(2h'-e) - (d0+h) h'') / ((d0+h)^2 + (h'-e)^2)^(3/2)``,

    for ``e = 0`` the polar-curve formula ``(r^2 + 2r'^2 - r r'')/(r^2 + r'^2)^(3/2)``.

    Parameters
    ----------
    {lift velocity acceleration pitch_radius offset}
    """
    h, dh, ddh = (np.asarray(a, dtype=float) for a in (lift, velocity, acceleration))
    y = pitch_radius + h
    v = dh - offset
    return (y * y + v * (2.0 * dh - offset) - y * ddh) / (y * y + v * v) ** 1.5


def roller_cam_curvature(pitch_curvature, roller_radius):
    """Curvature of the cam surface under a roller [1/m], positive convex, and where it is
    undercut.

    The cam is the pitch curve offset inwards by the roller radius ``r``: ``rho = rho_p - r``,
    i.e. ``kappa = kappa_p / (1 - r kappa_p)``.  Where ``r kappa_p >= 1`` (a convex pitch
    radius at most ``r``) the offset folds over: undercut, the returned curvature is
    meaningless there.

    Parameters
    ----------
    pitch_curvature : float or array_like
        Pitch-curve curvature [1/m] (:func:`pitch_curve_curvature`).
    roller_radius : float
        Roller radius r [m].

    Returns
    -------
    curvature : ndarray
        Cam-surface curvature [1/m] (clipped to +-1e9 1/m at an undercut's fold).
    undercut : ndarray of bool
        True where the cam is undercut.
    """
    k = np.asarray(pitch_curvature, dtype=float)
    undercut = roller_radius * k >= 1.0
    denom = 1.0 - roller_radius * k
    safe = np.where(np.abs(denom) < 1e-12, 1e-12, denom)
    return np.clip(k / safe, -1e9, 1e9), undercut


@_DOCS.fill
def cam_profile(cam_angle, lift, velocity, follower):
    """The cam surface (and a roller's pitch curve) in the cam frame [m].

    Flat face: the contact point ``(h', R_b + h)`` of the fixed frame; roller: the roller
    centre ``C = (offset, d0 + h)`` less ``r`` along the pitch curve's outward normal
    ``(-(h' - offset), d0 + h)/|.|``.  Both turned back by the cam angle:
    ``Rot(-theta)``.

    Parameters
    ----------
    cam_angle : array_like
        Cam angles [rad].
    lift : array_like
        Lobe lift h [m].
    velocity : array_like
        dh/dtheta [m/rad].
    {follower}

    Returns
    -------
    dict
        ``x``, ``y``: the cam surface [m]; for a roller also ``pitch_x``, ``pitch_y`` [m].
    """
    th, h, dh = (np.asarray(a, dtype=float) for a in (cam_angle, lift, velocity))
    c, s = np.cos(th), np.sin(th)

    def cam_frame(x, y):
        return x * c + y * s, -x * s + y * c

    if follower.kind == "flat":
        x, y = cam_frame(dh, follower.base_circle_radius + h)
        return dict(x=x, y=y)
    e = follower.offset
    cy = follower.pitch_radius + h
    norm = np.hypot(dh - e, cy)
    r = follower.roller_radius
    x, y = cam_frame(e + r * (dh - e) / norm, cy - r * cy / norm)
    px, py = cam_frame(np.full_like(h, e), cy)
    return dict(x=x, y=y, pitch_x=px, pitch_y=py)


# ----------------------------------------------------------------------------- contact
@_DOCS.fill
def line_contact(force, width, radius, reduced_modulus):
    """Hertz line contact of two cylinders: peak pressure [Pa] and half-width [m].

    ``p_max = sqrt(F E* / (pi L R))``, ``b = sqrt(4 F R / (pi L E*))`` ([Johnson] 4.2), with
    ``1/R = 1/R1 + 1/R2`` (a flat face: ``R = R1``) and ``1/E* = (1-nu1^2)/E1 + (1-nu2^2)/E2``.

    Parameters
    ----------
    {force}
    width : float
        Contact length L [m].
    radius : float or array_like
        Effective radius R [m], positive.
    {reduced_modulus}

    Returns
    -------
    p_max, half_width : ndarray
        [Pa], [m].

    Examples
    --------
    >>> p, b = line_contact(1000.0, 0.01, 0.005, 1e11)
    >>> round(float(p) / 1e6, 1), round(float(b) * 1e6, 2)
    (797.9, 79.79)
    """
    f = np.maximum(np.asarray(force, dtype=float), 0.0)
    r = np.asarray(radius, dtype=float)
    return np.sqrt(f * reduced_modulus / (math.pi * width * r)), np.sqrt(
        4.0 * f * r / (math.pi * width * reduced_modulus)
    )


@_DOCS.fill
def elliptical_contact(force, radius_x, radius_y, reduced_modulus):
    """Hertz point (elliptical) contact: peak pressure [Pa] and semi-axes [m], by the
    closed-form approximations of [Hamrock-Brewe].

    With ``R_x`` (rolling direction) and ``R_y`` (axial) the effective radii,
    ``alpha = R_y/R_x`` (taken >= 1 by swapping the axes), ``1/R = 1/R_x + 1/R_y``,
    ``E' = 2 E*``: ellipticity ``k = alpha^(2/pi)``, second elliptic integral
    ``Ecal = 1 + (pi/2 - 1)/alpha``; diameters ``D_y = 2 (6 k^2 Ecal F R / (pi E'))^(1/3)``,
    ``D_x = 2 (6 Ecal F R / (pi k E'))^(1/3)``; ``p_max = 6 F / (pi D_x D_y)``.  Exact for
    a sphere (``alpha = 1``); within a few per cent of the exact Hertz solution elsewhere
    (the tests compare them).

    Parameters
    ----------
    {force}
    radius_x : float or array_like
        Effective radius in the rolling direction [m], positive.
    radius_y : float or array_like
        Effective radius across it (the crown) [m], positive.
    {reduced_modulus}

    Returns
    -------
    p_max, semi_axis_x, semi_axis_y : ndarray
        [Pa], half-width along the rolling direction [m], half-length across it [m].
    """
    f = np.maximum(np.asarray(force, dtype=float), 0.0)
    rx, ry = np.broadcast_arrays(np.asarray(radius_x, dtype=float), np.asarray(radius_y, dtype=float))
    swap = ry < rx
    big, small = np.where(swap, rx, ry), np.where(swap, ry, rx)
    alpha = big / small
    k = alpha ** (2.0 / math.pi)
    ecal = 1.0 + (math.pi / 2.0 - 1.0) / alpha
    r = 1.0 / (1.0 / rx + 1.0 / ry)
    e_prime = 2.0 * reduced_modulus
    d_long = 2.0 * np.cbrt(6.0 * k * k * ecal * f * r / (math.pi * e_prime))  # along the larger radius
    d_short = 2.0 * np.cbrt(6.0 * ecal * f * r / (math.pi * k * e_prime))
    with np.errstate(divide="ignore", invalid="ignore"):
        p = np.where(f > 0, 6.0 * f / (math.pi * d_long * d_short), 0.0)
    a_x = np.where(swap, d_long, d_short) / 2.0
    a_y = np.where(swap, d_short, d_long) / 2.0
    return p, a_x, a_y


def kinematic_cam_force(valve_lift, valve_acceleration, spring_force, moving_mass, ratio, base_force=0.0):
    """Quasi-static ("kinematic") force of a rigid train on the cam along the follower's axis [N].

    ``F_cam = r (F_s + M z'')`` while the valve is open (``z > 0``), ``r F_0`` on the base
    circle (an adjuster's plunger force; 0 with mechanical lash).  Negative where the
    spring cannot hold the train on the cam at that acceleration.

    Parameters
    ----------
    valve_lift : array_like
        Valve lift z [m].
    valve_acceleration : array_like
        Valve acceleration z'' [m/s^2].
    spring_force : array_like
        Static spring force at the spring length of that lift [N].
    moving_mass : float
        Moving mass referred to the valve (train + a third of the spring) [kg].
    ratio : float
        Valve lift per lobe lift r [-].
    base_force : float
        Force referred to the valve while it is closed [N].
    """
    z = np.asarray(valve_lift, dtype=float)
    f = np.asarray(spring_force, dtype=float) + moving_mass * np.asarray(valve_acceleration, dtype=float)
    return ratio * np.where(z > 0.0, f, base_force)


# ----------------------------------------------------------------------------- the check
@_DOCS.fill
def check_cam(
    cam,
    valve_train,
    follower,
    spring=None,
    cam_rpm: float | None = None,
    contact_force=None,
    contact_angle=None,
    samples: int = SAMPLES,
) -> CamCheck:
    """Check a cam against its follower: curvature, undercut, excursion, pressure angle and
    Hertz stress along the cam (see the module docstring).

    Parameters
    ----------
    cam : Cam
        The lobe (its lift is the follower's lift).
    valve_train : ValveTrain or None
        Ratio, lash and masses of the load (None: the lobe is the valve, no train mass).
    {follower}
    spring : ValveSpring, optional
        The valve spring: with it the kinematic load and the Hertz stress.
    cam_rpm : float, optional
        Cam speed [rev/min] of the kinematic load (default: 0, the spring force alone).
    contact_force : array_like, optional
        A given force on the cam [N] along the follower's axis (e.g. a simulation's
        ``cam_contact_force``) instead of the kinematic one, at ``contact_angle``.
    contact_angle : array_like, optional
        Cam angles of ``contact_force`` [rad] (default: equal steps from 0 over one revolution).
    samples : int
        Samples per revolution without a given force [-].
    """

    if not isinstance(follower, Follower):
        raise InputError(f"follower = {follower!r} must be a Follower (the [follower] table)")
    if contact_force is not None and (spring is not None or cam_rpm is not None):
        raise InputError(
            "give either contact_force (a given load) or spring and cam_rpm (the kinematic load), not both"
        )
    if cam_rpm is not None:
        if spring is None:
            raise InputError("cam_rpm needs the spring: the kinematic load is the spring force plus the inertia")
        if isinstance(cam_rpm, bool) or not isinstance(cam_rpm, (int, float)) or not 0 <= cam_rpm < 1e5:
            raise InputError(f"cam_rpm = {cam_rpm!r} must be a cam speed from 0 to 100000 rev/min")
    if contact_force is not None:
        force_in = np.asarray(contact_force, dtype=float)
        if force_in.ndim != 1 or force_in.size < 8 or not np.all(np.isfinite(force_in)):
            raise InputError("contact_force must be a flat array of at least 8 finite forces [N] over one revolution")
        if contact_angle is None:
            theta = np.arange(force_in.size) * (_TWO_PI / force_in.size)
        else:
            theta = np.asarray(contact_angle, dtype=float)
            if theta.shape != force_in.shape or not np.all(np.isfinite(theta)):
                raise InputError("contact_angle must be finite cam angles [rad], one per contact_force")
    else:
        if isinstance(samples, bool) or not isinstance(samples, int) or not 360 <= samples <= 360_000:
            raise InputError(f"samples = {samples!r} must be a whole number from 360 to 360000")
        theta = np.arange(samples) * (_TWO_PI / samples)
    h, dh, ddh = (np.asarray(a, dtype=float) for a in cam.evaluate(theta))
    out = dict(cam=cam, valve_train=valve_train, follower=follower, cam_angle=theta, lift=h, velocity=dh)
    out["acceleration"] = ddh
    out.update(cam_profile(theta, h, dh, follower))
    if follower.kind == "flat":
        rho = flat_follower_radius(follower.base_circle_radius, h, ddh)
        out["radius"] = rho
        out["undercut"] = rho <= 0.0
        out["pressure_angle"] = np.zeros_like(h)
        out["excursion"] = flat_contact_offset(dh, follower.offset)
        out["face_reach"] = flat_face_reach(out["excursion"], follower.width, follower.lateral_offset)
        kappa = 1.0 / np.where(np.abs(rho) < 1e-9, 1e-9, rho)
    else:
        kp = pitch_curve_curvature(h, dh, ddh, follower.pitch_radius, follower.offset)
        kappa, undercut = roller_cam_curvature(kp, follower.roller_radius)
        out["pitch_curvature"] = kp
        out["undercut"] = undercut
        out["pressure_angle"] = pressure_angle(h, dh, follower.pitch_radius, follower.offset)
        with np.errstate(divide="ignore"):
            out["radius"] = np.where(kappa != 0.0, 1.0 / np.where(kappa == 0.0, 1.0, kappa), np.inf)
    out["curvature"] = np.clip(kappa, -1e9, 1e9)
    # the load
    ratio = 1.0 if valve_train is None else valve_train.ratio
    lash = 0.0 if valve_train is None else valve_train.lash
    if contact_force is not None:
        out["force"], out["load"] = force_in, "given"
    elif spring is not None:
        omega = rpm_to_omega(cam_rpm or 0.0)
        # open where the lobe is past the lash by OPEN_LIFT (the run's rule): a base circle's
        # round-off lift (+-1e-54 m) once counted as open and the load flickered
        z = np.where(ratio * h - lash > ratio * OPEN_LIFT, ratio * h - lash, 0.0)
        acc = np.where(z > 0.0, ratio * ddh * omega**2, 0.0)
        f_s = spring.spring_model.static_force(spring.installed_length - z)
        m_spring = float(spring.spring_model.internal_parameters()["M"])
        m_train = 0.0 if valve_train is None else valve_train.moving_mass
        base = 0.0 if valve_train is None else valve_train.hla_force
        out["force"] = kinematic_cam_force(z, acc, f_s, m_train + m_spring / 3.0, ratio, base)
        out["load"] = "kinematic"
        out["moving_mass"] = m_train + m_spring / 3.0
        out["cam_rpm"] = float(cam_rpm or 0.0)
    if "force" in out:
        normal = np.maximum(out["force"], 0.0) / np.cos(out["pressure_angle"])
        valid = ~out["undercut"]
        k_follower = 0.0 if follower.kind == "flat" else 1.0 / follower.roller_radius
        k_crown = 0.0 if follower.crown_radius is None else 1.0 / follower.crown_radius
        k_x = kappa + k_follower + (k_crown if follower.kind == "flat" else 0.0)
        valid &= k_x > 0.0
        r_x = 1.0 / np.where(valid, k_x, 1.0)
        p_line, b = line_contact(np.where(valid, normal, 0.0), follower.width, r_x, follower.reduced_modulus)
        out["normal_force"], out["half_width"] = normal, np.where(valid, b, 0.0)
        if follower.crown_radius is not None:
            p_ell, a_x, a_y = elliptical_contact(
                np.where(valid, normal, 0.0), r_x, follower.crown_radius, follower.reduced_modulus
            )
            truncated = valid & (a_y > 0.5 * follower.width)
            out["edge_loaded"] = truncated
            out["half_length"] = np.where(valid, a_y, 0.0)
            out["half_width"] = np.where(valid, a_x, 0.0)
            p = np.where(truncated, np.maximum(p_ell, p_line), p_ell)
        else:
            p = p_line
        out["stress"] = np.where(valid, p, 0.0)
    return CamCheck(**out)


@dataclass(repr=False)
class CamCheck(Result):
    """The cam checks over one revolution (:func:`check_cam`): curvature, undercut, excursion,
    pressure angle, Hertz stress, and the profile."""

    cam: object
    valve_train: object
    follower: object
    cam_angle: np.ndarray  # [rad]
    lift: np.ndarray  # lobe lift [m]
    velocity: np.ndarray  # [m/rad]
    acceleration: np.ndarray  # [m/rad^2]
    x: np.ndarray  # cam surface, cam frame [m]
    y: np.ndarray
    radius: np.ndarray  # signed radius of curvature of the cam surface [m] (inf: flat)
    curvature: np.ndarray  # its inverse [1/m], clipped to +-1e9
    undercut: np.ndarray  # bool
    pressure_angle: np.ndarray  # [rad]
    pitch_x: np.ndarray | None = None  # roller centre, cam frame [m]
    pitch_y: np.ndarray | None = None
    pitch_curvature: np.ndarray | None = None  # [1/m]
    excursion: np.ndarray | None = None  # flat: contact offset from the axis [m]
    face_reach: np.ndarray | None = None  # flat: farthest contact point from the axis [m]
    force: np.ndarray | None = None  # along the follower axis [N]
    load: str | None = None  # "kinematic" or "given"
    moving_mass: float | None = None  # [kg]
    cam_rpm: float | None = None
    normal_force: np.ndarray | None = None  # [N]
    stress: np.ndarray | None = None  # Hertz peak pressure [Pa]
    half_width: np.ndarray | None = None  # [m]
    half_length: np.ndarray | None = None  # crowned: [m]
    edge_loaded: np.ndarray | None = None  # crowned: the ellipse is longer than the width
    notes: list = field(default_factory=list)

    title = "cam check"
    cheap_plot = True

    def _repr_caption(self) -> str:
        f = self.follower
        return f"{getattr(self.cam, 'law', 'cam')} lobe, {f.kind} follower, base circle {f.base_circle_radius * 1e3:.4g} mm"

    def _at(self, i) -> float:
        return math.degrees(float(self.cam_angle[i]))

    def checks_text(self) -> str:
        """The geometric checks in words: curvature and undercut (or cusp), the flat face's
        excursion or the roller's pitch curve and pressure angle."""
        s = self.summary
        kind = s["follower"]

        def mm(value):
            return "-" if value is None else f"{value * 1e3:.3f}"

        where = f" at {s['min_radius_of_curvature_cam_angle_deg']:.2f} deg" if s["min_radius_of_curvature_m"] else ""
        if kind == "flat":
            verdict = "CUSP: the face cannot follow the lift" if s["concave"] else "ok (convex everywhere)"
        else:
            verdict = "UNDERCUT" if s["undercut"] else "ok (no undercut)"
        out = [
            f"radius of curvature: min {mm(s['min_radius_of_curvature_m'])} mm{where}, at the nose "
            f"{mm(s['nose_radius_of_curvature_m'])} mm: {verdict}"
        ]
        if kind == "flat":
            face = (
                f"; with the {s['edge_margin_m'] * 1e3:g} mm edge margin it needs a face radius of "
                f"{mm(s['required_face_radius_m'])} mm"
            )
            if s.get("face_radius_m") is not None:
                face += f" of the {mm(s['face_radius_m'])} mm: " + ("ok" if s["excursion_ok"] else "BEYOND THE FACE")
            out.append(
                f"contact excursion: up to {mm(s['max_excursion_m'])} mm from the tappet axis at "
                f"{s['max_excursion_cam_angle_deg']:.2f} deg; the contact line reaches {mm(s['max_face_reach_m'])} mm"
                + face
            )
        else:
            concave = (
                f", concave down to {mm(s['min_concave_radius_m'])} mm"
                if s.get("min_concave_radius_m") is not None
                else ""
            )
            out.append(
                f"pitch curve: smallest convex radius {mm(s['min_pitch_radius_m'])} mm ({s['roller_radius_m'] * 1e3:g} "
                f"mm roller){concave}; pressure angle up to {s['max_pressure_angle_deg']:.2f} deg at "
                f"{s['max_pressure_angle_cam_angle_deg']:.2f} deg"
            )
        return "\n".join(out)

    def describe(self) -> str:
        """The checks in words (what ``springdyn valve cam-check`` prints): the follower, the
        geometric checks, the load and the Hertz stress, the verdict and the notes."""
        s = self.summary
        f = self.follower
        what = "flat face" if f.kind == "flat" else f"roller of {f.roller_radius * 1e3:g} mm"
        out = [
            f"{getattr(self.cam, 'law', 'cam')} lobe, {what}, base circle {f.base_circle_radius * 1e3:g} mm, contact "
            f"width {f.width * 1e3:g} mm"
            + (f", crown {f.crown_radius * 1e3:g} mm" if f.crown_radius is not None else ""),
            self.checks_text(),
        ]
        if "max_contact_stress_Pa" in s:
            out.append(
                f"load (kinematic: spring + {s['moving_mass_kg'] * 1e3:.1f} g at the valve, ratio "
                f"{self.valve_train.ratio:g}) at {s['cam_rpm']:g} cam rpm: {s['min_contact_force_N']:.1f} N (at "
                f"{s['min_contact_force_cam_angle_deg']:.2f} deg, valve open) to {s['max_contact_force_N']:.1f} N (at "
                f"{s['max_contact_force_cam_angle_deg']:.2f} deg)"
                + ("" if s["follower_stays_on_cam"] else ": the spring cannot hold the follower on the cam")
            )
            allow = (
                f"; allowable {s['allowable_contact_stress_Pa'] / 1e6:.0f} MPa: "
                + ("ok" if s["contact_stress_ok"] else "EXCEEDED")
                if s.get("allowable_contact_stress_Pa") is not None
                else " (no allowable_contact_stress in [follower]: not checked)"
            )
            out.append(
                f"Hertz stress ({s['contact_at_max_stress']} contact): max {s['max_contact_stress_Pa'] / 1e6:.0f} MPa at "
                f"{s['max_contact_stress_cam_angle_deg']:.2f} deg, contact half-width "
                f"{s['contact_half_width_at_max_stress_m'] * 1e3:.3f} mm" + allow
            )
        out.append("checks: " + ("all passed" if s["ok"] else "FAILED: " + ", ".join(s["checks_failed"])))
        return "\n".join(out + notes_lines(s))

    def _summary(self) -> dict:
        f = self.follower
        notes = list(self.notes)
        s = dict(
            follower=f.kind,
            base_circle_radius_m=f.base_circle_radius,
            max_lobe_lift_m=float(self.lift.max()),
        )
        failed = []
        if f.kind == "flat":  # signed: at or below 0 the face cannot follow (a cusp)
            i = int(np.argmin(self.radius))
            s["min_radius_of_curvature_m"] = float(self.radius[i])
            s["min_radius_of_curvature_cam_angle_deg"] = self._at(i)
        else:  # the smallest convex radius where the cam is not undercut
            convex = (self.radius > 0.0) & ~self.undercut
            i = int(np.argmin(np.where(convex, self.radius, np.inf)))
            s["min_radius_of_curvature_m"] = float(self.radius[i]) if convex[i] else None
            s["min_radius_of_curvature_cam_angle_deg"] = self._at(i) if convex[i] else None
        if self.valve_train is not None and self.valve_train.layout == "rocker":
            notes.append(
                "the follower is taken as translating with the lobe lift: a finger follower's or rocker's own "
                "contact path and pressure angle depend on its pivot, which is not modelled"
            )
        nose = int(np.argmax(self.lift))
        s["nose_radius_of_curvature_m"] = float(self.radius[nose]) if np.isfinite(self.radius[nose]) else None
        s["undercut"] = bool(self.undercut.any())
        if f.kind == "flat":
            j = int(np.argmin(self.radius))
            s["concave"] = bool((self.radius <= 0.0).any())
            if s["concave"]:
                failed.append("radius of curvature")
                notes.append(
                    f"the cam needs a negative radius of curvature ({self.radius[j] * 1e3:.3g} mm at "
                    f"{self._at(j):.2f} deg): no flat follower can follow this lift on a {f.base_circle_radius * 1e3:.4g} "
                    "mm base circle (a cusp); raise the base circle or soften the nose"
                )
            k = int(np.argmax(np.abs(self.excursion)))
            s["max_excursion_m"] = float(abs(self.excursion[k]))
            s["max_excursion_cam_angle_deg"] = self._at(k)
            s["excursion_range_m"] = [float(self.excursion.min()), float(self.excursion.max())]
            s["max_face_reach_m"] = float(self.face_reach.max())
            s["required_face_radius_m"] = float(self.face_reach.max() + f.margin)
            s["edge_margin_m"] = f.margin
            if f.face_radius is not None:
                s["face_radius_m"] = f.face_radius
                s["excursion_ok"] = bool(s["required_face_radius_m"] <= f.face_radius)
                if not s["excursion_ok"]:
                    failed.append("contact excursion")
                    notes.append(
                        f"the contact reaches {s['max_face_reach_m'] * 1e3:.3f} mm from the tappet axis (at "
                        f"{s['max_excursion_cam_angle_deg']:.2f} deg): with the {f.margin * 1e3:g} mm edge margin it "
                        f"needs a face radius of {s['required_face_radius_m'] * 1e3:.3f} mm, the face has "
                        f"{f.face_radius * 1e3:.3f} mm"
                    )
            else:
                s["excursion_ok"] = None
                notes.append("no face_radius in [follower]: the excursion is reported, not checked")
        else:
            s["roller_radius_m"] = f.roller_radius
            concave = self.radius < 0.0
            if concave.any():
                j = int(np.argmax(np.where(concave, self.radius, -np.inf)))  # smallest concave radius
                s["min_concave_radius_m"] = float(-self.radius[j])
                s["min_concave_radius_cam_angle_deg"] = self._at(j)
            else:
                s["min_concave_radius_m"] = None
            kp = self.pitch_curvature
            j = int(np.argmax(kp))
            s["min_pitch_radius_m"] = float(1.0 / kp[j]) if kp[j] > 0 else None
            if s["undercut"]:
                failed.append("radius of curvature")
                notes.append(
                    f"the cam is undercut: the pitch curve's convex radius falls to {1e3 / kp[j]:.3g} mm at "
                    f"{self._at(j):.2f} deg, below the roller radius {f.roller_radius * 1e3:.3g} mm; raise the base "
                    "circle or use a smaller roller"
                )
            elif s["min_pitch_radius_m"] is not None and s["min_pitch_radius_m"] < PITCH_RADIUS_GUIDE * f.roller_radius:
                notes.append(
                    f"the pitch curve's smallest convex radius {s['min_pitch_radius_m'] * 1e3:.3g} mm is less than "
                    f"{PITCH_RADIUS_GUIDE:g} roller radii (common guidance: 2-3)"
                )
            k = int(np.argmax(np.abs(self.pressure_angle)))
            s["max_pressure_angle_deg"] = math.degrees(abs(float(self.pressure_angle[k])))
            s["max_pressure_angle_cam_angle_deg"] = self._at(k)
            if abs(self.pressure_angle[k]) > PRESSURE_ANGLE_GUIDE:
                notes.append(
                    f"the pressure angle reaches {s['max_pressure_angle_deg']:.1f} deg, beyond the 30 deg of common "
                    "guidance for a translating roller follower"
                )
        if self.stress is not None:
            fmax = int(np.argmax(self.force))
            s["load"] = self.load
            if self.load == "kinematic":
                s["cam_rpm"] = self.cam_rpm
                s["moving_mass_kg"] = self.moving_mass
            s["max_contact_force_N"] = float(self.force[fmax])
            s["max_contact_force_cam_angle_deg"] = self._at(fmax)
            lifted = self.lift > 0.0
            if self.load == "kinematic":
                z = self._valve_open()
                fmin_mask = z if z.any() else lifted
            else:
                fmin_mask = lifted if lifted.any() else np.ones_like(lifted)
            fmin = np.where(fmin_mask, self.force, np.inf)
            m = int(np.argmin(fmin))
            s["min_contact_force_N"] = float(self.force[m])
            s["min_contact_force_cam_angle_deg"] = self._at(m)
            s["follower_stays_on_cam"] = bool(self.force[m] > 0.0)
            if not s["follower_stays_on_cam"]:
                failed.append("contact force")
                notes.append(
                    f"the contact force falls to {self.force[m]:.1f} N at {self._at(m):.2f} deg: the spring cannot hold "
                    "the follower on the cam there (a kinematic estimate: simulate to see the separation)"
                    if self.load == "kinematic"
                    else f"the given contact force falls to {self.force[m]:.1f} N at {self._at(m):.2f} deg (separation)"
                )
            p = int(np.argmax(self.stress))
            s["max_contact_stress_Pa"] = float(self.stress[p])
            s["max_contact_stress_cam_angle_deg"] = self._at(p)
            s["contact_at_max_stress"] = "crowned (elliptical)" if f.crown_radius is not None else "line"
            s["contact_half_width_at_max_stress_m"] = float(self.half_width[p])
            if self.edge_loaded is not None and self.edge_loaded.any():
                notes.append(
                    "the crowned contact's ellipse is longer than the width over part of the cam: the contact is "
                    "edge loaded there and the stress shown is the larger of the ellipse's and the line contact's"
                )
            if f.allowable_contact_stress is not None:
                s["allowable_contact_stress_Pa"] = f.allowable_contact_stress
                s["contact_stress_ok"] = bool(self.stress[p] <= f.allowable_contact_stress)
                if not s["contact_stress_ok"]:
                    failed.append("contact stress")
                    notes.append(
                        f"the Hertz stress {self.stress[p] / 1e6:.0f} MPa at {self._at(p):.2f} deg exceeds the "
                        f"allowable {f.allowable_contact_stress / 1e6:.0f} MPa"
                    )
            else:
                s["contact_stress_ok"] = None
            if f.crown_radius is None:
                notes.append(
                    "line contact: the stress excludes the edge concentration at the ends of an uncrowned contact"
                )
        else:
            notes.append("no load given (spring and speed, or a contact force): no Hertz stress")
        s["checks_failed"] = failed
        s["ok"] = not failed
        if notes:
            s["notes"] = notes
        return s

    def _valve_open(self) -> np.ndarray:
        vt = self.valve_train
        r = 1.0 if vt is None else vt.ratio
        lash = 0.0 if vt is None else vt.lash
        return r * self.lift - lash > r * OPEN_LIFT

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        dims = ("cam_angle",)
        data = {
            "lift": (dims, self.lift, {"units": "m"}),
            "velocity": (dims, self.velocity, {"units": "m/rad"}),
            "acceleration": (dims, self.acceleration, {"units": "m/rad^2"}),
            "profile_x": (dims, self.x, {"units": "m"}),
            "profile_y": (dims, self.y, {"units": "m"}),
            "curvature": (dims, self.curvature, {"units": "1/m"}),
            "undercut": (dims, self.undercut.astype(int), {"units": "1"}),
            "pressure_angle": (dims, np.degrees(self.pressure_angle), {"units": "deg"}),
        }
        optional = (
            ("pitch_x", self.pitch_x, "m"),
            ("pitch_y", self.pitch_y, "m"),
            ("pitch_curvature", self.pitch_curvature, "1/m"),
            ("excursion", self.excursion, "m"),
            ("face_reach", self.face_reach, "m"),
            ("contact_force", self.force, "N"),
            ("normal_force", self.normal_force, "N"),
            ("contact_stress", self.stress, "Pa"),
            ("contact_half_width", self.half_width, "m"),
            ("contact_half_length", self.half_length, "m"),
        )
        for name, values, unit in optional:
            if values is not None:
                data[name] = (dims, np.asarray(values, dtype=float), {"units": unit})
        coords = {"cam_angle": (dims, np.degrees(self.cam_angle), {"units": "deg"})}
        return xr.Dataset(data, coords=coords, attrs={"follower": self.follower.kind})

    def _plot(self, ax=None):
        """The profile, the radius of curvature, the excursion or pressure angle, and the
        contact stress; into ``ax``: the profile."""
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        f = self.follower
        if ax is not None:
            fig, axes = ax.figure, [ax]
        else:
            fig, grid = plt.subplots(2, 2, figsize=(10, 8))
            axes = list(grid.ravel())
        a = axes[0]
        t = np.linspace(0, _TWO_PI, 361)
        a.plot(f.base_circle_radius * 1e3 * np.cos(t), f.base_circle_radius * 1e3 * np.sin(t), color="0.7", lw=0.8)
        a.plot(self.x * 1e3, self.y * 1e3, "C0", label="cam")
        if self.pitch_x is not None:
            a.plot(self.pitch_x * 1e3, self.pitch_y * 1e3, "C1--", lw=0.8, label="pitch curve")
        if self.undercut.any():
            a.plot(self.x[self.undercut] * 1e3, self.y[self.undercut] * 1e3, "r.", ms=2, label="undercut")
        a.set_aspect("equal")
        a.set_xlabel("x [mm]")
        a.set_ylabel("y [mm]")
        a.set_title(f"{getattr(self.cam, 'law', 'cam')} lobe, {f.kind} follower")
        a.legend(fontsize=7)
        if len(axes) == 1:
            return fig
        deg = np.degrees(self.cam_angle)
        scale = 10.0 * (f.base_circle_radius + float(self.lift.max()))
        rho = np.clip(self.radius, -scale, scale)
        axes[1].plot(deg, rho * 1e3, "C0")
        axes[1].axhline(0.0, color="k", lw=0.6)
        if f.kind == "roller":
            axes[1].axhline(-f.roller_radius * 1e3, color="0.5", ls=":", lw=0.8)
        axes[1].set_ylabel("radius of curvature [mm]")
        if f.kind == "flat":
            axes[2].plot(deg, self.excursion * 1e3, "C0", label="contact offset")
            axes[2].plot(deg, self.face_reach * 1e3, "C2", lw=0.8, label="reach of the contact line")
            if f.face_radius is not None:
                axes[2].axhline((f.face_radius - f.margin) * 1e3, color="r", ls="--", lw=0.8, label="face - margin")
                axes[2].axhline(-(f.face_radius - f.margin) * 1e3, color="r", ls="--", lw=0.8)
            axes[2].set_ylabel("contact excursion [mm]")
            axes[2].legend(fontsize=7)
        else:
            axes[2].plot(deg, np.degrees(self.pressure_angle), "C0")
            axes[2].set_ylabel("pressure angle [deg]")
        if self.stress is not None:
            axes[3].plot(deg, self.stress / 1e6, "C3")
            if f.allowable_contact_stress is not None:
                axes[3].axhline(f.allowable_contact_stress / 1e6, color="k", ls="--", lw=0.8, label="allowable")
                axes[3].legend(fontsize=7)
            axes[3].set_ylabel("Hertz stress [MPa]")
        else:
            axes[3].text(0.5, 0.5, "no load given", ha="center", va="center", transform=axes[3].transAxes)
        for a in axes[1:]:
            a.set_xlabel("cam angle [deg]")
            a.grid(True, alpha=0.3)
        fig.tight_layout()
        return fig
