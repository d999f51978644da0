"""The damper's nonlinear force laws in time: pack springs with lift-off, inter-leaf and O-ring friction.

Pure functions of the ring's instantaneous displacement ``(x, y)`` [m] and velocity
``(vx, vy)`` [m/s] (floats or arrays of samples), giving the force the shaft applies to
the ring [N].  They are the physics the time-domain rig (:mod:`springdyn.lsd.rig`), the
describing-function coefficients (:mod:`springdyn.lsd.equivalent`) and the rotor time
responses (:mod:`springdyn.lsd.rotordynamics`, :mod:`springdyn.lsd.rotor_time`) share;
they take numbers, not a model, so that they sit below :mod:`springdyn.lsd.model`:

- each pack pushes with ``k_s max(delta_pre + delta_i, 0)``: it lifts off when the ring
  moves away from it by more than the preload (the nonlinearity the linear (3.4) misses);
- friction between the leaves of each pack is a Coulomb force
  ``1.5 mu_s S P_i sign(d delta_i/dt)`` along the pack, with the instantaneous pack load
  ``P_i`` (Eqs. (2.25)-(2.27) of the thesis, per unit tip deflection rate);
- the O-rings give a Coulomb force ``mu_o F_N`` opposing the ring velocity (2.21).

The pack deflection ``delta_i = x cos phi_i + y sin phi_i`` is
:func:`springdyn.lsd.stiffness.pack_deflections`.  Units: SI throughout.
"""

from __future__ import annotations

import numpy as np

from ..core.docstrings import ParameterDocs
from .stiffness import pack_deflections

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    angles : array_like
        Pack angles phi_i [rad].
    vy : float
        Ring velocity along y [m/s].
    friction_coefficient : float
        Coulomb friction coefficient [-].
    vx : float
        Ring velocity along x [m/s].
    """
)


__all__ = ["pack_spring_forces", "interleaf_friction_forces", "oring_friction_force"]


@_DOCS.fill
def pack_spring_forces(angles, pack_stiffness, preload, x, y):
    """Force of the packs on the shaft side, ``sum_i k_s [max(delta_pre + delta_i, 0) - delta_pre] e_i`` [N].

    The static preloads cancel at the centre; a pack that the ring leaves by more than
    the preload lifts off and stops pushing (the nonlinearity the linear (3.4) misses).
    Returns ``(fx, fy)`` and the pack loads ``P_i`` (shape ``(T, N)``).

    Parameters
    ----------
    {angles}
    pack_stiffness : float
        Stiffness k_s of one pack [N/m].
    preload : float
        Pack preload deflection delta_pre [m].
    x : array_like
        Ring displacement along x [m].
    y : array_like
        Ring displacement along y [m].

    Returns
    -------
    tuple of numpy.ndarray
        ``(fx, fy, loads)``: the force along x and y [N], shape of ``x``, and the pack loads
        ``P_i = k_s max(delta_pre + delta_i, 0)`` [N], shape ``x.shape + (N,)``.
    """
    phi = np.asarray(angles, dtype=float)
    delta = pack_deflections(phi, x, y)
    load = pack_stiffness * np.maximum(preload + delta, 0.0)
    net = load - pack_stiffness * preload
    return net @ np.cos(phi), net @ np.sin(phi), load


@_DOCS.fill
def interleaf_friction_forces(angles, pack_loads, friction_coefficient, slip_factor, vx, vy):
    """Coulomb friction between the leaves, ``1.5 mu_s S P_i sign(d delta_i/dt) e_i`` summed [N].

    The dissipation rate of Eq. (2.25) with the slips of (2.26) is
    ``1.5 mu_s S P_1 |d delta_1/dt|`` per pack; the force is that rate over the
    deflection rate, with the instantaneous pack load ``P_1``.

    Parameters
    ----------
    {angles}
    pack_loads : array_like
        Pack loads P_i [N].
    {friction_coefficient}
    slip_factor : float
        Inter-leaf slip factor S of Eqs. (2.27)-(2.28) [-].
    {vx vy}

    Returns
    -------
    tuple of numpy.ndarray
        ``(fx, fy)``: the friction force along x and y [N], one value per sample.
    """
    phi = np.asarray(angles, dtype=float)
    rate = pack_deflections(phi, vx, vy)
    # A pack the motion does not deflect (e.g. the pack at 0 deg in a y shake) has a
    # round-off rate; it sticks and carries no friction.
    scale = float(np.max(np.hypot(vx, vy), initial=0.0))
    moving = np.abs(rate) > 1e-9 * scale
    f = 1.5 * friction_coefficient * slip_factor * pack_loads * np.where(moving, np.sign(rate), 0.0)
    return f @ np.cos(phi), f @ np.sin(phi)


@_DOCS.fill
def oring_friction_force(friction_coefficient, normal_force, vx, vy):
    """O-ring Coulomb friction ``mu_o F_N v/|v|`` opposing the ring velocity [N] (Eq. (2.21)).

    Parameters
    ----------
    {friction_coefficient}
    normal_force : float
        O-ring normal force F_N [N].
    {vx vy}

    Returns
    -------
    tuple of numpy.ndarray
        ``(fx, fy)``: the friction force along x and y [N], shape of ``vx``; zero where the
        ring is at rest.
    """
    vx = np.asarray(vx, dtype=float)
    vy = np.asarray(vy, dtype=float)
    speed = np.hypot(vx, vy)
    scale = np.divide(friction_coefficient * normal_force, speed, out=np.zeros_like(speed), where=speed > 0)
    return scale * vx, scale * vy
