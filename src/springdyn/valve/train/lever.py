"""Lever kinematics from the 2-D geometry: a rocker arm or a roller finger follower (``[geometry]``).

The constant-ratio lever of :mod:`springdyn.valve.train.definition` moves its contact points on
straight lines.  A real lever turns about its pivot: the roller centre and the pad centre
describe arcs, the roller meets the lobe at a cam angle that shifts with the lever's
rotation, the pad rolls and slides across the valve's stem tip, and the ratio (valve lift
per lobe lift) changes over the lift: by a few per cent for rocker arms and by over 10 % for
roller finger followers.  This module computes that kinematics from a drawing of the lever at
rest (the roller on the base circle).

**Frame** (the drawing's): the cam centre at the origin, ``x`` and ``y`` in the plane of the
lever, the cam turning counter-clockwise (mirror a drawing of a clockwise cam).  Keys of
``[geometry]`` (:class:`LeverGeometry`): the pivot, the roller centre at rest, the pad centre
at rest and its radius, the direction in which the valve opens.  The roller radius and the
base circle come from the ``[follower]`` table (``kind = "roller"``).

**The lobe.**  The ``[cam]`` table's lift ``h(theta)`` is the lift it gives a translating
roller of the same radius on the line through the cam centre and the roller's rest position
(the usual definition of a lobe's lift table).  The roller centre then lies on the pitch
curve, in polar coordinates about the cam centre ``rho(alpha) = R_b + r + h(theta + alpha_0
- alpha)`` at cam angle ``theta`` (:func:`lobe_angle`): a roller at the polar angle ``alpha``
meets the lobe where the reference roller at ``alpha_0`` met it ``alpha_0 - alpha`` earlier.

**Lever angle** ``phi`` (positive opening the valve): the roller centre ``C(phi)`` and the pad
centre ``P(phi)`` turn about the pivot.  The rigid train's ``phi_k(theta)`` is the root of the
contact condition ``g = |C(phi)| - R_b - r - h(theta + alpha_0 - alpha(phi)) = 0``
(:func:`contact_residual`, solved by Newton's method).

**Valve side.**  The pad (a circle of radius ``R_pad`` about ``P``) pushes the flat stem tip
along the valve axis ``d``: the valve lift is ``s(phi) = (P(phi) - P_0) . d = A (cos phi - 1) + B
sin phi`` (:func:`valve_side_lift`) with ``A = (P_0 - O) . d`` and ``B`` the valve-side moment
arm at rest, whatever the pad radius (the contact point slides across the tip by
``(P(phi) - P_0) . t``, :meth:`LeverKinematics.pad_travel`).  Its inverse and moment arm are closed
forms: ``L_v = ds/dphi = sqrt(A^2 + B^2 - (s + A)^2)`` (:func:`valve_moment_arm`).

**Cam side.**  The normal force's moment arm about the pivot is ``L_c = kappa dg/dphi`` with
``kappa = rho / sqrt(rho^2 + h'^2)``, the cosine between the pitch curve's normal and its
radius (:func:`cam_moment_arm`).  The instantaneous ratio is ``r = L_v / L_c`` (virtual work,
:func:`instantaneous_ratio`).

**In the engine** the lever's coordinate stays the displacement of its valve-side tip,
``x = s(phi)``: the tip contact is unchanged, the lever's kinetic energy ``J phi'^2 / 2`` gives
the effective mass ``M(x) = J / L_v(x)^2`` at the valve and the force ``-M'(x) x'^2 / 2``
(:func:`lever_mass_at_valve`), and the cam contact's penetration is ``delta = c(theta) (h_e -
x / r_0)`` with the equivalent lobe lift ``h_e = s(phi_k) / r_0``, the ratio at rest ``r_0``
and ``c = r_0 / r(theta)``: exact in the contact to first order in the contact's deflection
(micrometres against a radius of millimetres).  With an adjuster under the pivot
(:mod:`springdyn.valve.train.hla`), the pivot's collapse ``y_a`` along the valve axis moves the
roller by ``y_a (n . d)`` along the contact normal ``n`` (:attr:`LeverKinematics.pivot_factor`).

The constant-ratio model (no ``[geometry]``) remains the simple option: ``c = 1``, ``A = 0``.
Sources: plane kinematics of a cam and an oscillating roller follower ([Norton] ch. 8 and 15,
docs/references.md).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, param
from ...core.results import Result, notes_lines
from ...core.units import format_mm

__all__ = [
    "LeverGeometry",
    "LeverKinematics",
    "valve_side_lift",
    "valve_moment_arm",
    "lever_angle_of_lift",
    "lever_mass_at_valve",
    "lobe_angle",
    "contact_residual",
    "cam_moment_arm",
    "instantaneous_ratio",
    "GEOMETRY_TABLE_SAMPLES",
    "ROLLER_POSITION_TOL",
]

#: Samples per revolution of the engine's table of the ratio correction ``c(theta)`` and the
#: pivot factor (cubic Hermite; 0.25 deg: ``c`` changes by a few per cent over an event of
#: 100 deg and more, the interpolation error is below 1e-9).
GEOMETRY_TABLE_SAMPLES = 1440
#: The roller centre at rest must lie on the base circle's pitch circle ``R_b + r`` within this
#: fraction of its radius (a drawing's rounding); it is then moved onto it along its radius.
ROLLER_POSITION_TOL = 1e-3
#: Newton iterations of the contact condition (converges to round-off in 4-6).
_NEWTON_ITERATIONS = 30


def _rot90(x, y):
    """The vector turned by +90 deg."""
    return -y, x


def valve_side_lift(phi, a, b):
    """Valve lift of the rigid lever at the lever angle ``phi`` [m]: ``A (cos phi - 1) + B sin phi``.

    The pad centre ``P`` turns about the pivot ``O``; the flat stem tip moves with the pad
    along the valve axis ``d``, so the lift is ``(P(phi) - P_0) . d``.

    Parameters
    ----------
    phi : float or array_like
        Lever angle from rest, positive opening the valve [rad].
    a : float
        ``A = (P_0 - O) . d``: the pad centre's distance from the pivot along the valve axis [m].
    b : float
        ``B``: the valve-side moment arm at rest [m], positive.
    """
    phi = np.asarray(phi, dtype=float)
    return a * (np.cos(phi) - 1.0) + b * np.sin(phi)


def valve_moment_arm(lift, a, b):
    """Valve-side moment arm ``L_v = ds/dphi = sqrt(A^2 + B^2 - (s + A)^2)`` [m] at the valve lift ``s``.

    Parameters
    ----------
    lift : float or array_like
        Valve-side lift ``s`` of the lever [m].
    a, b : float
        The pad's ``A`` and ``B`` of :func:`valve_side_lift` [m].
    """
    s = np.asarray(lift, dtype=float)
    return np.sqrt(np.maximum(a * a + b * b - (s + a) ** 2, 0.0))


def lever_angle_of_lift(lift, a, b):
    """Lever angle [rad] at the valve-side lift ``s`` (the inverse of :func:`valve_side_lift`).

    ``A cos phi + B sin phi = s + A``, i.e. ``phi = asin((s + A) / R) - atan2(A, B)`` with
    ``R = sqrt(A^2 + B^2)``, the branch through ``phi = 0``.

    Parameters
    ----------
    lift : float or array_like
        Valve-side lift ``s`` [m].
    a, b : float
        The pad's ``A`` and ``B`` [m].
    """
    s = np.asarray(lift, dtype=float)
    r = math.hypot(a, b)
    return np.arcsin(np.clip((s + a) / r, -1.0, 1.0)) - math.atan2(a, b)


def lever_mass_at_valve(lift, inertia, a, b):
    """The lever's mass referred to its valve-side tip [kg] and its derivative [kg/m].

    Kinetic energy ``J phi'^2 / 2 = M(x) x'^2 / 2`` with ``x = s(phi)``: ``M = J / L_v^2``,
    ``dM/dx = 2 J (x + A) / L_v^4`` (:func:`valve_moment_arm`).  The equation of motion of
    the tip coordinate is ``M x'' + M'(x) x'^2 / 2 = Q`` (Lagrange).

    Parameters
    ----------
    lift : float or array_like
        Valve-side lift ``x`` [m].
    inertia : float
        The lever's moment of inertia about its pivot, roller included [kg m^2].
    a, b : float
        The pad's ``A`` and ``B`` [m].
    """
    s = np.asarray(lift, dtype=float)
    lv2 = a * a + b * b - (s + a) ** 2
    return inertia / lv2, 2.0 * inertia * (s + a) / (lv2 * lv2)


def lobe_angle(cam_angle, alpha, alpha0):
    """The reference follower's cam angle at which it met the lobe point a roller at the
    polar angle ``alpha`` meets at ``cam_angle`` [rad]: ``theta + alpha_0 - alpha`` (a
    counter-clockwise cam).

    Parameters
    ----------
    cam_angle : float or array_like
        Cam angle ``theta`` [rad].
    alpha : float or array_like
        Polar angle of the roller centre about the cam centre [rad].
    alpha0 : float
        Its angle at rest, the reference follower's line [rad].
    """
    return np.asarray(cam_angle, dtype=float) + alpha0 - np.asarray(alpha, dtype=float)


def contact_residual(radius, lift, pitch_radius):
    """The contact condition of the roller on the lobe [m]: ``g = |C| - (R_b + r) - h``; zero in contact.

    Parameters
    ----------
    radius : float or array_like
        Distance of the roller centre from the cam centre ``|C|`` [m].
    lift : float or array_like
        Lobe lift at the lobe angle of :func:`lobe_angle` [m].
    pitch_radius : float
        Base circle plus roller radius ``R_b + r`` [m].
    """
    return np.asarray(radius, dtype=float) - pitch_radius - np.asarray(lift, dtype=float)


def cam_moment_arm(radius, slope, dg_dphi):
    """Moment arm of the cam's normal force about the pivot [m]: ``L_c = kappa dg/dphi``.

    ``kappa = rho / sqrt(rho^2 + h'^2)`` is the cosine between the pitch curve's normal and
    its radius (the pitch curve ``rho(alpha)`` has ``drho/dalpha = -h'``): the normal
    distance of the roller centre from the pitch curve is ``kappa g``.

    Parameters
    ----------
    radius : float or array_like
        ``rho = |C|`` on the pitch curve [m].
    slope : float or array_like
        ``h' = dh/dtheta`` at the lobe angle [m/rad].
    dg_dphi : float or array_like
        Derivative of the contact residual by the lever angle [m/rad].
    """
    rho = np.asarray(radius, dtype=float)
    return rho / np.hypot(rho, slope) * np.asarray(dg_dphi, dtype=float)


def instantaneous_ratio(valve_arm, cam_arm):
    """The lever's instantaneous ratio, valve lift per normal lift at the cam [-]: ``L_v / L_c`` (virtual work).

    Parameters
    ----------
    valve_arm : float or array_like
        Valve-side moment arm [m].
    cam_arm : float or array_like
        Cam-side moment arm of the normal force [m].
    """
    return np.asarray(valve_arm, dtype=float) / np.asarray(cam_arm, dtype=float)


@dataclass(frozen=True)
class LeverGeometry(Parameters):
    """The lever drawn at rest: pivot, roller centre, pad centre and radius, valve axis.

    The frame has the cam centre at the origin and the cam turning counter-clockwise (see
    the module docstring); the roller radius and the base circle come from ``[follower]``.

    Examples
    --------
    >>> g = LeverGeometry.from_dict({"pivot_x": "-30 mm", "pivot_y": "-24 mm", "roller_x": "0 mm",
    ...     "roller_y": "-24 mm", "pad_x": "15 mm", "pad_y": "-27 mm", "pad_radius": "8 mm",
    ...     "valve_angle": "-90 deg"})
    >>> round(g.pad_arms()[1] * 1e3, 3)
    45.0
    """

    pivot_x: float = param("m", "pivot centre, x (the cam centre at the origin)", display="mm")
    pivot_y: float = param("m", "pivot centre, y", display="mm")
    roller_x: float = param("m", "roller centre at rest (the roller on the base circle), x", display="mm")
    roller_y: float = param("m", "roller centre at rest, y", display="mm")
    pad_x: float = param("m", "centre of the pad's arc on the valve tip at rest, x", display="mm")
    pad_y: float = param("m", "centre of the pad's arc at rest, y", display="mm")
    pad_radius: float = param("m", "radius of the pad's arc on the valve tip", display="mm", positive=True)
    valve_angle: float = param(
        "rad", "direction in which the valve opens, from the +x axis (e.g. -90 deg: downwards)", display="deg"
    )
    stem_diameter: float = param(
        "m",
        "valve stem tip diameter (optional: the pad's contact must stay on the tip)",
        display="mm",
        positive=True,
        default=None,
    )
    valve_axis_offset: float = param(
        "m",
        "distance of the pad's contact at rest from the valve axis, along the axis turned by +90 deg",
        display="mm",
        default=0.0,
    )

    table = "geometry"

    # -- the drawing's vectors ------------------------------------------------------------
    @property
    def axis(self) -> tuple[float, float]:
        """Unit vector of the valve's opening direction ``d`` [-]."""
        return math.cos(self.valve_angle), math.sin(self.valve_angle)

    @property
    def across(self) -> tuple[float, float]:
        """Unit vector across the stem tip ``t`` (``d`` turned by +90 deg) [-]."""
        dx, dy = self.axis
        return _rot90(dx, dy)

    @property
    def sense(self) -> float:
        """``sigma``: +1 when the lever opens the valve turning counter-clockwise, -1 clockwise [-]."""
        wx, wy = self.pad_x - self.pivot_x, self.pad_y - self.pivot_y
        dx, dy = self.axis
        rx, ry = _rot90(wx, wy)
        return 1.0 if rx * dx + ry * dy >= 0.0 else -1.0

    def pad_arms(self) -> tuple[float, float, float]:
        """``A``, ``B`` of :func:`valve_side_lift` and ``(P_0 - O) . t`` [m]."""
        wx, wy = self.pad_x - self.pivot_x, self.pad_y - self.pivot_y
        dx, dy = self.axis
        tx, ty = self.across
        rx, ry = _rot90(wx, wy)
        return wx * dx + wy * dy, self.sense * (rx * dx + ry * dy), wx * tx + wy * ty

    def roller_arm(self) -> float:
        """Distance of the roller centre from the pivot [m]."""
        return math.hypot(self.roller_x - self.pivot_x, self.roller_y - self.pivot_y)

    def _validate(self) -> None:
        w = math.hypot(self.pad_x - self.pivot_x, self.pad_y - self.pivot_y)
        if w == 0.0:
            raise InputError("[geometry] the pad centre is on the pivot: it would not move")
        a, b, _ = self.pad_arms()
        if b < 0.1 * w:
            raise InputError(
                f"[geometry] the pad moves across the valve axis, not along it: its moment arm about the pivot is "
                f"{format_mm(b if abs(b) > 1e-9 * w else 0.0)} of a distance {format_mm(w)} (the pivot-pad line "
                "must cross the valve axis clearly; check pad_x, pad_y against pivot_x, pivot_y, and valve_angle)"
            )
        if self.roller_arm() == 0.0:
            raise InputError("[geometry] the roller centre is on the pivot")
        if self.stem_diameter is not None and abs(self.valve_axis_offset) >= 0.5 * self.stem_diameter:
            raise InputError(
                f"[geometry] valve_axis_offset = {format_mm(self.valve_axis_offset)} puts the pad's contact at rest "
                f"off the stem tip (stem_diameter = {format_mm(self.stem_diameter)})"
            )

    def kinematics(self, follower) -> LeverKinematics:
        """The lever on a roller follower's base circle (:class:`LeverKinematics`).

        Parameters
        ----------
        follower : Follower
            The ``[follower]`` table, ``kind = "roller"`` (base circle and roller radius).
        """
        return LeverKinematics.of(self, follower)


@dataclass(frozen=True)
class LeverKinematics:
    """A drawn lever on its cam's base circle: positions over the lever angle, the rigid
    train's solution over the cam angle (:meth:`solve`), the engine's tables.

    Build it with :meth:`LeverGeometry.kinematics`.
    """

    geometry: LeverGeometry
    base_circle_radius: float  #: [m]
    roller_radius: float  #: [m]
    roller_x: float  #: roller centre at rest on the pitch circle [m]
    roller_y: float  #: [m]

    @classmethod
    def of(cls, geometry: LeverGeometry, follower) -> LeverKinematics:
        """See :meth:`LeverGeometry.kinematics`.

        Parameters
        ----------
        geometry : LeverGeometry
            The drawing.
        follower : Follower
            Its roller follower.
        """
        if follower is None or follower.kind != "roller":
            raise InputError(
                "[geometry] needs a [follower] table with kind = 'roller' in the valve-train file (its "
                "base_circle_radius and roller_radius): the lever's roller rides on the lobe"
            )
        if follower.offset != 0.0:
            raise InputError(
                "[follower] offset: with a [geometry] table the roller's position comes from the drawing "
                "(roller_x, roller_y); remove offset"
            )
        rp = follower.base_circle_radius + follower.roller_radius
        dist = math.hypot(geometry.roller_x, geometry.roller_y)
        if abs(dist - rp) > ROLLER_POSITION_TOL * rp:
            raise InputError(
                f"[geometry] roller centre ({format_mm(geometry.roller_x)}, {format_mm(geometry.roller_y)}) is "
                f"{format_mm(dist)} from the cam centre; on the base circle it is base_circle_radius + "
                f"roller_radius = {format_mm(rp)} from it (within {ROLLER_POSITION_TOL:.1%})"
            )
        scale = rp / dist
        kin = cls(
            geometry,
            follower.base_circle_radius,
            follower.roller_radius,
            geometry.roller_x * scale,
            geometry.roller_y * scale,
        )
        if not kin.cam_arm_at_rest > 0.05 * geometry.roller_arm():
            raise InputError(
                "[geometry] the lobe's lift would not open the valve: as the valve opens the roller must move away "
                f"from the cam centre, but its moment arm is {format_mm(kin.cam_arm_at_rest)} (check the pivot, the "
                "roller and valve_angle: the valve opens along valve_angle)"
            )
        return kin

    # -- positions over the lever angle ---------------------------------------------------
    @property
    def pitch_radius(self) -> float:
        """``R_b + r`` [m]."""
        return self.base_circle_radius + self.roller_radius

    @property
    def rest_angle(self) -> float:
        """Polar angle of the roller centre at rest ``alpha_0`` [rad]: the lobe table's reference line."""
        return math.atan2(self.roller_y, self.roller_x)

    def roller_centre(self, phi):
        """Roller centre ``C(phi)`` and its derivative by the lever angle [m, m/rad].

        Parameters
        ----------
        phi : float or array_like
            Lever angle [rad].

        Returns
        -------
        x, y, dx, dy : ndarray
        """
        g = self.geometry
        phi = np.asarray(phi, dtype=float) * g.sense
        wx, wy = self.roller_x - g.pivot_x, self.roller_y - g.pivot_y
        c, s = np.cos(phi), np.sin(phi)
        px, py = wx * c - wy * s, wx * s + wy * c
        dx, dy = _rot90(px, py)
        return g.pivot_x + px, g.pivot_y + py, g.sense * dx, g.sense * dy

    def pad_centre(self, phi):
        """Pad centre ``P(phi)`` [m].

        Parameters
        ----------
        phi : float or array_like
            Lever angle [rad].
        """
        g = self.geometry
        phi = np.asarray(phi, dtype=float) * g.sense
        wx, wy = g.pad_x - g.pivot_x, g.pad_y - g.pivot_y
        c, s = np.cos(phi), np.sin(phi)
        return g.pivot_x + wx * c - wy * s, g.pivot_y + wx * s + wy * c

    @property
    def cam_arm_at_rest(self) -> float:
        """Moment arm of the cam's normal force at rest ``L_c0`` [m] (the normal is radial there)."""
        x, y, dx, dy = self.roller_centre(0.0)
        return float((x * dx + y * dy) / math.hypot(x, y))

    @property
    def ratio_at_rest(self) -> float:
        """The ratio on the base circle ``r_0 = B / L_c0`` [-]: the constant-ratio model's."""
        return self.geometry.pad_arms()[1] / self.cam_arm_at_rest

    @property
    def valve_arm_at_rest(self) -> float:
        """The valve-side moment arm on the base circle ``B`` [m]."""
        return self.geometry.pad_arms()[1]

    def inertia(self, lever_inertia: float, roller_mass: float) -> float:
        """The lever's moment of inertia about its pivot with the roller [kg m^2]: ``J + m_r |C_0 - O|^2``.

        Parameters
        ----------
        lever_inertia : float
            The lever's own inertia about its pivot [kg m^2].
        roller_mass : float
            Roller mass at its centre [kg].
        """
        return lever_inertia + roller_mass * self.geometry.roller_arm() ** 2

    # -- the rigid train over the cam angle -------------------------------------------------
    def _residual(self, phi, theta, lift_at):
        x, y, dx, dy = self.roller_centre(phi)
        rho = np.hypot(x, y)
        alpha = np.arctan2(y, x)
        h, dh = lift_at(lobe_angle(theta, alpha, self.rest_angle))
        dalpha = (x * dy - y * dx) / (rho * rho)
        g = contact_residual(rho, h, self.pitch_radius)
        dg = (x * dx + y * dy) / rho + dh * dalpha
        return g, dg, rho, dh

    def lever_angle(self, theta, lift_at):
        """The rigid train's lever angle ``phi_k`` at the cam angles ``theta`` [rad] (Newton).

        Parameters
        ----------
        theta : array_like
            Cam angles [rad].
        lift_at : callable
            ``lift_at(angle) -> (h, dh/dtheta)``: the lobe lift [m] and slope [m/rad]
            (:meth:`springdyn.valve.engine.cam_table.CamTable.at`).
        """
        theta = np.asarray(theta, dtype=float)
        h0, _ = lift_at(theta)
        phi = np.asarray(h0, dtype=float) / self.cam_arm_at_rest  # the small-rotation guess
        for _ in range(_NEWTON_ITERATIONS):
            g, dg, _, _ = self._residual(phi, theta, lift_at)
            step = g / dg
            phi = phi - step
            if np.max(np.abs(step)) < 1e-15:
                break
        else:  # pragma: no cover - a smooth lobe converges in a few steps
            raise InputError("[geometry] the lever's contact with the lobe did not converge: check the drawing")
        return phi

    def solve(self, theta, lift_at) -> dict:
        """The rigid train over the cam angles ``theta``.

        Parameters
        ----------
        theta : array_like
            Cam angles [rad].
        lift_at : callable
            The lobe lift and slope (:meth:`lever_angle`).

        Returns
        -------
        dict
            ``phi`` [rad], ``dphi`` [rad/rad], ``valve_lift`` [m] (before the lash),
            ``valve_velocity`` [m/rad], ``ratio`` [-], ``cam_arm``, ``valve_arm`` [m],
            ``pivot_factor`` [-] (``n . d``), ``lobe_angle`` [rad], ``contact_x``,
            ``contact_y`` [m] (the roller's contact on the lobe), ``pad_travel`` [m].
        """
        theta = np.asarray(theta, dtype=float)
        phi = self.lever_angle(theta, lift_at)
        g, dg, rho, dh = self._residual(phi, theta, lift_at)
        a, b, wt = self.geometry.pad_arms()
        lift = valve_side_lift(phi, a, b)
        lv = valve_moment_arm(lift, a, b)
        lc = cam_moment_arm(rho, dh, dg)
        dphi = dh / dg  # g_theta = -h': d phi/d theta = -g_theta / g_phi
        x, y, _, _ = self.roller_centre(phi)
        # the pitch curve's outward normal: rho e_r + h' e_alpha (drho/dalpha = -h')
        er_x, er_y = x / rho, y / rho
        ea_x, ea_y = _rot90(er_x, er_y)
        nx, ny = rho * er_x + dh * ea_x, rho * er_y + dh * ea_y
        norm = np.hypot(nx, ny)
        nx, ny = nx / norm, ny / norm
        d = self.geometry.axis
        return dict(
            phi=phi,
            dphi=dphi,
            valve_lift=lift,
            valve_velocity=lv * dphi,
            ratio=instantaneous_ratio(lv, lc),
            cam_arm=lc,
            valve_arm=lv,
            pivot_factor=nx * d[0] + ny * d[1],
            lobe_angle=lobe_angle(theta, np.arctan2(y, x), self.rest_angle),
            contact_x=x - self.roller_radius * nx,
            contact_y=y - self.roller_radius * ny,
            pad_travel=self.pad_travel(phi),
        )

    def pad_travel(self, phi):
        """Travel of the pad's contact across the stem tip from rest [m]: ``(P(phi) - P_0) . t``.

        Parameters
        ----------
        phi : float or array_like
            Lever angle [rad].
        """
        px, py = self.pad_centre(phi)
        tx, ty = self.geometry.across
        g = self.geometry
        return (np.asarray(px) - g.pad_x) * tx + (np.asarray(py) - g.pad_y) * ty

    # -- lift heights: the same lever angle on both sides ------------------------------------
    def lobe_lift_at_valve_lift(self, gross_lift):
        """The lobe lift [m] at which the rigid lever lifts its valve side by ``gross_lift``.

        The roller centre's distance from the cam centre depends on the lever angle alone,
        ``h = |C(phi)| - R_b - r``, whatever the lobe's slope there; only the cam angle at
        which the lobe reaches it shifts (:func:`lobe_angle`).

        Parameters
        ----------
        gross_lift : float or array_like
            Valve-side lift of the lever, the lash not taken off [m].
        """
        a, b, _ = self.geometry.pad_arms()
        x, y, _, _ = self.roller_centre(lever_angle_of_lift(gross_lift, a, b))
        return np.hypot(x, y) - self.pitch_radius

    def valve_lift_at_lobe_lift(self, lobe_lift):
        """The valve-side lift of the rigid lever [m] (gross: before the lash) at the lobe lift ``h``
        (the inverse of :meth:`lobe_lift_at_valve_lift`, by Newton's method).

        Parameters
        ----------
        lobe_lift : float or array_like
            Lobe lift [m].
        """
        h = np.asarray(lobe_lift, dtype=float)
        phi = h / self.cam_arm_at_rest
        for _ in range(_NEWTON_ITERATIONS):
            x, y, dx, dy = self.roller_centre(phi)
            rho = np.hypot(x, y)
            step = (rho - self.pitch_radius - h) / ((x * dx + y * dy) / rho)
            phi = phi - step
            if np.max(np.abs(step)) < 1e-15:
                break
        a, b, _ = self.geometry.pad_arms()
        return valve_side_lift(phi, a, b)

    def lobe_of_valve_lift(self, cam_angle, gross_lift):
        """The lobe's points that give the valve-side lifts ``gross_lift`` at ``cam_angle``
        (the backward solution): the lobe lift and the reference follower's cam angle there
        (:func:`lobe_angle`).

        Parameters
        ----------
        cam_angle : array_like
            Cam angles [rad].
        gross_lift : array_like
            Valve-side lift of the lever there [m] (the lash not taken off).

        Returns
        -------
        lobe_angle, lobe_lift : ndarray
            [rad], [m].
        """
        a, b, _ = self.geometry.pad_arms()
        x, y, _, _ = self.roller_centre(lever_angle_of_lift(gross_lift, a, b))
        return lobe_angle(cam_angle, np.arctan2(y, x), self.rest_angle), np.hypot(x, y) - self.pitch_radius

    def breakpoint_angles(self, breakpoints, lift_at) -> np.ndarray:
        """Cam angles [rad] at which the lever's roller meets the lobe's breakpoints (given
        as the reference follower's cam angles): ``theta + alpha_0 - alpha(phi_k(theta)) = b``.

        Parameters
        ----------
        breakpoints : array_like
            The lift law's breakpoints [rad] (:attr:`springdyn.valve.cam.definition.Cam.breakpoints`).
        lift_at : callable
            The lobe lift and slope (:meth:`lever_angle`).
        """
        b = np.asarray(breakpoints, dtype=float)
        if b.size == 0:
            return b
        theta = b.copy()
        for _ in range(6):  # a contraction: the lobe angle moves by a few per cent of the cam angle
            x, y, _, _ = self.roller_centre(self.lever_angle(theta, lift_at))
            theta = b - self.rest_angle + np.arctan2(y, x)
        return np.mod(theta, 2.0 * math.pi)

    def engine_tables(self, table, samples: int = GEOMETRY_TABLE_SAMPLES) -> dict:
        """The engine's inputs for this lever on the lobe of the cam table ``table``.

        Parameters
        ----------
        table : CamTable
            The lobe's table (lift at the reference follower) [m, m/rad, m/rad^2].
        samples : int
            Nodes per revolution of the ratio table [-].

        Returns
        -------
        dict
            ``h``, ``dh``, ``ddh``: the equivalent lobe lift ``s(phi_k) / r_0`` on the lobe
            table's nodes [m, m/rad, m/rad^2]; ``geometry``: the flattened ratio table
            ``c, dc/dtheta, n . d, d(n . d)/dtheta`` per node (``samples`` nodes) [-, 1/rad];
            ``ratio0`` [-].
        """
        r0 = self.ratio_at_rest
        theta = np.arange(table.samples) * table.dth
        eps = 1e-5  # the second derivative by central differences of the exact first one

        def velocity(th):
            return self.solve(th, table.at)["valve_velocity"]

        sol = self.solve(theta, table.at)
        ddh = (velocity(theta + eps) - velocity(theta - eps)) / (2.0 * eps)
        th_g = np.arange(samples) * (2.0 * math.pi / samples)
        c, kap, dc, dkap = self._ratio_tables(th_g, table.at, r0, eps)
        flat = np.empty(4 * samples)
        flat[0::4], flat[1::4], flat[2::4], flat[3::4] = c, dc, kap, dkap
        return dict(h=sol["valve_lift"] / r0, dh=sol["valve_velocity"] / r0, ddh=ddh / r0, geometry=flat, ratio0=r0)

    def _ratio_tables(self, theta, lift_at, r0, eps):
        mid = self.solve(theta, lift_at)
        hi = self.solve(theta + eps, lift_at)
        lo = self.solve(theta - eps, lift_at)
        c = r0 / mid["ratio"]
        dc = (r0 / hi["ratio"] - r0 / lo["ratio"]) / (2.0 * eps)
        dk = (hi["pivot_factor"] - lo["pivot_factor"]) / (2.0 * eps)
        return c, mid["pivot_factor"], dc, dk

    def over_cam(self, cam, lash: float = 0.0, points: int = 3600, inertia: float | None = None) -> LeverTable:
        """The lever's kinematics over one revolution of ``cam`` (:class:`LeverTable`).

        Parameters
        ----------
        cam : Cam
            The lobe.
        lash : float
            Valve lash [m] (the valve lift is the lever's less the lash).
        points : int
            Samples [-].
        inertia : float, optional
            The lever's inertia about its pivot with the roller [kg m^2]: adds the effective
            mass at the valve.
        """
        from ..engine.cam_table import CamTable  # (here: the compiled engine (numba) loads only when a run needs it)

        table = CamTable.of(cam, 7200)
        theta = np.arange(points) * (2.0 * math.pi / points)
        sol = self.solve(theta, table.at)
        h, _ = table.at(theta)
        a, b, _ = self.geometry.pad_arms()
        mass = None if inertia is None else lever_mass_at_valve(sol["valve_lift"], inertia, a, b)[0]
        return LeverTable(self, cam, theta, h, sol, lash, mass)


@dataclass(frozen=True, repr=False)
class LeverTable(Result):
    """A lever's kinematics over a revolution: ratio, moment arms, contact points, effective mass."""

    kinematics: LeverKinematics
    cam: object
    cam_angle: np.ndarray  #: [rad]
    lobe_lift: np.ndarray  #: lobe lift at the cam angle (the reference follower's) [m]
    solution: dict  #: :meth:`LeverKinematics.solve`
    lash: float = 0.0  #: [m]
    mass_at_valve: np.ndarray | None = None  #: [kg]
    info: dict = field(default_factory=dict)

    title = "lever kinematics"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"lever on the {self.cam.law} cam, ratio {self.kinematics.ratio_at_rest:.4g} at rest"

    @property
    def valve_lift(self) -> np.ndarray:
        """The rigid train's valve lift [m] (less the lash, not below 0)."""
        return np.maximum(self.solution["valve_lift"] - self.lash, 0.0)

    def describe(self, source: str = "") -> str:
        """The lever over the cam in words (what ``springdyn valve kinematics`` prints): its ratio
        over the event, the valve lift against the constant ratio's, the pad's travel on the
        stem tip, its mass at the valve and the notes.

        Parameters
        ----------
        source : str
            The file the lever is drawn in, for the first line [-].
        """
        s = self.summary
        out = [
            f"lever drawn{' in ' + source if source else ''} on the {self.cam.law} lobe: ratio "
            f"{s['ratio_at_rest']:.4f} at rest, {s['ratio_min']:.4f} to {s['ratio_max']:.4f} over the event "
            f"({s['ratio_change']:.1%} of the ratio at rest), {s['ratio_at_max_lift']:.4f} at the largest lift",
            f"max valve lift {s['max_valve_lift_m'] * 1e3:.4f} mm at {s['max_lift_cam_angle_deg']:.2f} cam deg (constant "
            f"ratio: {s['constant_ratio_valve_lift_m'] * 1e3:.4f} mm); the lever turns {s['max_lever_angle_deg']:.2f} deg",
        ]
        lo, hi = s["pad_travel_m"]
        line = f"pad contact on the stem tip travels {lo * 1e3:+.3f} to {hi * 1e3:+.3f} mm from its place at rest"
        if "pad_on_stem_margin_m" in s:
            line += f" (margin to the tip's edge {s['pad_on_stem_margin_m'] * 1e3:.3f} mm)"
        out.append(line)
        if "mass_at_valve_kg" in s:
            m0, m1 = s["mass_at_valve_kg"]
            out.append(f"lever mass at the valve (J / L_v^2, roller included): {m0 * 1e3:.2f} to {m1 * 1e3:.2f} g")
        return "\n".join(out + notes_lines(s))

    def _summary(self) -> dict:
        sol = self.solution
        lift = sol["valve_lift"]
        event = lift > 1e-6 * max(float(lift.max()), 1e-12)
        ratio = sol["ratio"][event] if event.any() else sol["ratio"]
        i_max = int(np.argmax(lift))
        k = self.kinematics
        s = dict(
            ratio_at_rest=k.ratio_at_rest,
            ratio_at_max_lift=float(sol["ratio"][i_max]),
            ratio_min=float(ratio.min()),
            ratio_max=float(ratio.max()),
            ratio_change=float((ratio.max() - ratio.min()) / k.ratio_at_rest),
            max_valve_lift_m=float(self.valve_lift.max()),
            max_lift_cam_angle_deg=float(np.degrees(self.cam_angle[i_max])),
            constant_ratio_valve_lift_m=float(max(k.ratio_at_rest * float(self.lobe_lift.max()) - self.lash, 0.0)),
            max_lever_angle_deg=float(np.degrees(sol["phi"].max())),
            pad_travel_m=(float(sol["pad_travel"][event].min()), float(sol["pad_travel"][event].max()))
            if event.any()
            else (0.0, 0.0),
        )
        if self.mass_at_valve is not None:
            s["mass_at_valve_kg"] = (float(self.mass_at_valve.min()), float(self.mass_at_valve.max()))
        g = k.geometry
        notes = []
        if g.stem_diameter is not None:
            reach = max(abs(g.valve_axis_offset + t) for t in s["pad_travel_m"])
            s["pad_on_stem_margin_m"] = 0.5 * g.stem_diameter - reach
            if reach >= 0.5 * g.stem_diameter:
                notes.append(
                    f"PAD OFF THE STEM: the pad's contact reaches {reach * 1e3:.3g} mm from the valve axis, beyond "
                    f"the stem tip's radius {0.5 * g.stem_diameter * 1e3:.3g} mm"
                )
        s["notes"] = notes
        return s

    def columns(self) -> dict:
        sol = self.solution
        out = {
            "cam_angle_deg": np.degrees(self.cam_angle),
            "lobe_lift_m": self.lobe_lift,
            "valve_lift_m": self.valve_lift,
            "lever_angle_rad": sol["phi"],
            "ratio": sol["ratio"],
            "cam_arm_m": sol["cam_arm"],
            "valve_arm_m": sol["valve_arm"],
            "contact_x_m": sol["contact_x"],
            "contact_y_m": sol["contact_y"],
            "pad_travel_m": sol["pad_travel"],
        }
        if self.mass_at_valve is not None:
            out["mass_at_valve_kg"] = self.mass_at_valve
        return out

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        units = {"_m": "m", "_rad": "rad", "_kg": "kg"}
        data = {}
        for key, values in self.columns().items():
            if key == "cam_angle_deg":
                continue
            unit = next((u for suffix, u in units.items() if key.endswith(suffix)), "1")
            name = key[: -len(next(s for s in units if key.endswith(s)))] if unit != "1" else key
            data[name] = ("cam_angle", values, {"units": unit})
        return xr.Dataset(
            data,
            coords={"cam_angle": ("cam_angle", np.degrees(self.cam_angle), {"units": "deg"})},
            attrs={"title": self.title},
        )

    def _plot(self, ax=None):
        import matplotlib.pyplot as plt  # (here: matplotlib costs 0.3 s of start-up)

        if ax is None:
            fig, axes = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
        else:
            fig, axes = ax.figure, [ax, ax.twinx()]
        deg = np.degrees(self.cam_angle)
        k = self.kinematics
        axes[0].plot(deg, self.valve_lift * 1e3, "C0", label="valve lift, lever geometry")
        axes[0].plot(
            deg,
            np.maximum(k.ratio_at_rest * self.lobe_lift - self.lash, 0.0) * 1e3,
            "C1--",
            label=f"constant ratio {k.ratio_at_rest:.4g}",
        )
        axes[0].set_ylabel("valve lift [mm]")
        axes[0].legend(loc="upper right")
        lift = self.solution["valve_lift"]
        event = lift > 1e-6 * max(float(lift.max()), 1e-12)
        axes[1].plot(deg[event], self.solution["ratio"][event], "C2.", ms=1.5, label="instantaneous ratio")
        axes[1].axhline(k.ratio_at_rest, color="0.5", lw=0.8)
        axes[1].set_ylabel("ratio [-]")
        axes[-1].set_xlabel("cam angle [deg]")
        return fig
