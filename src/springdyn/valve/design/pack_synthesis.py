"""The inner spring of a pack for a given outer spring and a force split (issue 41).

:func:`inner_spring_for` designs a one-step inner spring that sits inside the outer one with a
stated radial clearance, carries a stated share of the pack's force at installed length and
at full lift, and is stressed as the outer spring is at full lift (equal corrected stress, the
usual aim of a nested pair: neither wire is the weak one).  The closed forms:

- the inner spring's forces: ``F_i = s / (1 - s) F_o`` at installed length and at full lift
  (``s`` the inner's share of the pack), so its rate is ``k_i = (F_i,open - F_i,set) / lift``;
- its mean diameter from the space inside the outer spring: ``D_i = D_o - d_o - 2 c - d_i``
  (``c`` the radial clearance);
- its wire ``d_i`` from equal corrected stress at full lift, ``tau(F_i,open, D_i, d_i) =
  tau(F_o,open, D_o, d_o)`` (EN 13906-1's corrected stress, :func:`springdyn.valve.spring.stress.corrected_shear_stress`),
  solved by bisection;
- its active coils from the rate (:func:`springdyn.valve.spring.formulas.active_coils_for_rate`,
  EN 13906-1's ``n = G d^4 / (8 D^3 k)``) and its free length ``L_s + F_i,set / k_i``.

The spring keeps the outer's wire material, dead coils and model; its hand is the opposite.
"""

from __future__ import annotations

import numpy as np

from ...core.errors import InputError
from ..spring.definition import ValveSpring
from ..spring.formulas import active_coils_for_rate
from ..spring.pack import PackOptions, SpringPack, radial_clearance
from ..spring.stress import corrected_shear_stress

__all__ = ["inner_spring_for"]


def inner_spring_for(
    outer: ValveSpring,
    share: float,
    lift: float,
    clearance: float = 0.5e-3,
    installed_length: float | None = None,
) -> dict:
    """A one-step inner spring for ``outer`` that carries ``share`` of the pack's force.

    Parameters
    ----------
    outer : ValveSpring
        The outer spring.
    share : float
        The inner spring's share of the pack's force at installed length and at full lift [-],
        between 0.05 and 0.7.
    lift : float
        Valve lift [m].
    clearance : float
        Radial clearance between the outer spring's inside and the inner spring's outside [m].
    installed_length : float, optional
        The inner spring's installed length [m] (default: the outer's; a seat step shortens it).

    Returns
    -------
    dict
        ``spring`` (the inner :class:`ValveSpring`), ``pack`` (the :class:`SpringPack` of the
        two, opposite hands), ``target_set_force_N``, ``target_open_force_N``,
        ``set_force_N``, ``open_force_N`` (the inner's forces, its model's), ``shear_stress_Pa``
        (the inner's at full lift, the outer's beside it as ``outer_shear_stress_Pa``),
        ``radial_clearance_m``, ``coil_bind_margin_m``.

    Raises
    ------
    InputError
        A share outside its range, no wire that fits, or an inner spring driven solid.
    """
    if not 0.05 <= float(share) <= 0.7:
        raise InputError(f"share = {share!r} must be from 0.05 to 0.7 (the inner spring's share of the pack's force)")
    if not 0.0 < lift < outer.installed_length:
        raise InputError(f"lift = {lift!r} m must be positive and below the outer's installed length")
    if not 0.0 <= clearance < 0.1 * outer.mean_diameter:
        raise InputError(f"clearance = {clearance!r} m must be from 0 to a tenth of the outer's mean diameter")
    ls = outer.installed_length if installed_length is None else float(installed_length)
    model = outer.spring_model
    f_set_o = float(model.static_force(outer.installed_length))
    f_open_o = float(model.static_force(outer.installed_length - lift))
    ratio = share / (1.0 - share)
    f_set, f_open = ratio * f_set_o, ratio * f_open_o
    rate = (f_open - f_set) / lift
    tau_o = float(corrected_shear_stress(f_open_o, outer.mean_diameter, outer.wire_diameter))
    room = outer.mean_diameter - outer.wire_diameter - 2.0 * clearance  # the inner's outside diameter

    def excess(d):  # the inner's stress at full lift less the outer's
        return float(corrected_shear_stress(f_open, room - d, d)) - tau_o

    lo, hi = 0.05 * room, 0.3 * room  # spring index 19 to 2.3
    if not excess(lo) > 0.0 > excess(hi):
        raise InputError(
            f"no wire gives the inner spring the outer's stress {tau_o / 1e6:.0f} MPa at {share:g} of the force "
            f"inside {room * 1e3:.3g} mm: change the share or the clearance"
        )
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if excess(mid) > 0.0 else (lo, mid)
    d = 0.5 * (lo + hi)
    dm = room - d
    n = float(active_coils_for_rate(outer.shear_modulus, d, dm, rate))
    spring = outer.replace(
        type="one-step",
        mean_diameter=dm,
        wire_diameter=d,
        free_length=ls + f_set / rate,
        installed_length=ls,
        low_pitch_coils=0.0,
        high_pitch_coils=n + 2.0 * outer.dead_coils,
        load_points="",
        pitch_profile="",
        diameter_profile="",
    )
    pack = SpringPack((outer, spring), PackOptions(outer_hand="right", inner_hand="left"))
    forces = pack.static_forces(np.array([0.0, lift]))[1]
    return dict(
        spring=spring,
        pack=pack,
        target_set_force_N=f_set,
        target_open_force_N=f_open,
        set_force_N=float(forces[0]),
        open_force_N=float(forces[1]),
        shear_stress_Pa=float(corrected_shear_stress(forces[1], dm, d)),
        outer_shear_stress_Pa=tau_o,
        radial_clearance_m=radial_clearance(outer, spring),
        coil_bind_margin_m=float(spring.installed_length - lift - spring.solid_length),
    )
