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
from ...core.results import text_table
from ..spring.definition import ValveSpring
from ..spring.formulas import active_coils_for_rate
from ..spring.pack import PackOptions, SpringPack, radial_clearance
from ..spring.stress import corrected_shear_stress
from .synthesis import spring_table

__all__ = ["inner_spring_for", "inner_spring_figures", "inner_spring_text", "pack_file_tables"]


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
        two, opposite hands), ``share`` (as asked), ``target_set_force_N``, ``target_open_force_N``,
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
        share=float(share),
        target_set_force_N=f_set,
        target_open_force_N=f_open,
        set_force_N=float(forces[0]),
        open_force_N=float(forces[1]),
        shear_stress_Pa=float(corrected_shear_stress(forces[1], dm, d)),
        outer_shear_stress_Pa=tau_o,
        radial_clearance_m=radial_clearance(outer, spring),
        coil_bind_margin_m=float(spring.installed_length - lift - spring.solid_length),
    )


def inner_spring_figures(design: dict, lift: float, count: int = 5) -> dict:
    """The figures of an inner spring of :func:`inner_spring_for` and its pack, flat in SI
    (keys ``<quantity>_<unit>``): the inner's drawing (mean, wire, outside and inside diameters,
    free and installed lengths, active and total coils, hand), each spring's forces at installed
    length and full lift and its share of the pack's, the corrected stress at full lift and the
    static Goodman safety (installed to full lift, :meth:`SpringPack.stress`), the radial
    clearance installed and at coil bind, the coil-bind margins, and the pack's lowest natural
    frequencies (its springs', ends held, :meth:`SpringPack.modes`); ``share`` as asked.

    Parameters
    ----------
    design : dict
        What :func:`inner_spring_for` returned.
    lift : float
        Valve lift [m] (the one it was designed for).
    count : int
        Natural frequencies of the pack [-].
    """
    pack, inner = design["pack"], design["spring"]
    out = dict(
        inner_mean_diameter_m=inner.mean_diameter,
        inner_wire_diameter_m=inner.wire_diameter,
        inner_outer_diameter_m=inner.mean_diameter + inner.wire_diameter,
        inner_inner_diameter_m=inner.mean_diameter - inner.wire_diameter,
        inner_free_length_m=inner.free_length,
        inner_installed_length_m=inner.installed_length,
        inner_active_coils=float(inner.active_coils),
        inner_total_coils=float(inner.high_pitch_coils),
        inner_hand=pack.options.hand("inner"),
        share=design["share"],
        lift_m=float(lift),
    )
    fig = pack.static_figures(float(lift))
    for name in pack.names:
        for key in ("installed_force_N", "open_force_N", "force_share", "max_shear_stress_Pa", "goodman_safety"):
            out[f"{name}_{key}"] = fig[f"{name}_{key}"]
        out[f"{name}_first_mode_Hz"] = fig[f"{name}_first_mode_Hz"]
        out[f"{name}_coil_bind_margin_m"] = fig[f"{name}_coil_bind_margin_m"]
    out["inner_target_installed_force_N"] = design["target_set_force_N"]
    out["inner_target_open_force_N"] = design["target_open_force_N"]
    fit = pack.fit["outer_inner"]
    out["radial_clearance_installed_m"] = fit["radial_clearance_installed_m"]
    out["radial_clearance_at_bind_m"] = fit["radial_clearance_at_bind_m"]
    out["pack_modes_Hz"] = [float(f) for f in pack.modes(0.0)["pack"][: int(count)]]
    return out


def inner_spring_text(figures: dict) -> str:
    """:func:`inner_spring_figures` in words: what ``springdyn valve synthesize-inner`` prints
    and its pack file's header.

    Parameters
    ----------
    figures : dict
        :func:`inner_spring_figures`' SI values [m, N, Pa, Hz, -].
    """
    f, mm = figures, 1e3
    lines = [
        f"inner spring for {f['share']:.1%} of the pack's force at {f['lift_m'] * mm:.3g} mm lift (one-step, "
        f"{f['inner_hand']}-hand, the outer's wire material):",
        f"  mean diameter {f['inner_mean_diameter_m'] * mm:.4g} mm, wire {f['inner_wire_diameter_m'] * mm:.4g} mm "
        f"(outside {f['inner_outer_diameter_m'] * mm:.4g} mm, inside {f['inner_inner_diameter_m'] * mm:.4g} mm)",
        f"  free length {f['inner_free_length_m'] * mm:.4g} mm, installed {f['inner_installed_length_m'] * mm:.4g} mm, "
        f"{f['inner_active_coils']:.4g} active coils of {f['inner_total_coils']:.4g}",
    ]
    rows = [
        (
            name,
            f"{f[f'{name}_installed_force_N']:.1f}",
            f"{f[f'{name}_open_force_N']:.1f}",
            f"{f[f'{name}_force_share']:.1%}",
            f"{f[f'{name}_max_shear_stress_Pa'] / 1e6:.0f}",
            f"{f[f'{name}_goodman_safety']:.3g}",
            f"{f[f'{name}_first_mode_Hz']:.0f}",
            f"{f[f'{name}_coil_bind_margin_m'] * mm:.2f}",
        )
        for name in ("outer", "inner")
    ]
    lines.append(
        text_table(
            rows,
            headers=(
                "spring",
                "installed N",
                "open N",
                "share open",
                "stress open MPa",
                "Goodman (static)",
                "f1 Hz",
                "to bind mm",
            ),
        )
    )
    lines.append(
        f"radial clearance to the outer spring: {f['radial_clearance_installed_m'] * mm:.3g} mm installed, "
        f"{f['radial_clearance_at_bind_m'] * mm:.3g} mm at coil bind (the coils' diameter growth included)"
    )
    lines.append("pack's first modes: " + ", ".join(f"{x:.0f}" for x in f["pack_modes_Hz"]) + " Hz (ends held)")
    return "\n".join(lines)


def pack_file_tables(outer_table: dict, design: dict, damper: dict | None = None) -> dict:
    """The tables of a pack file of the outer spring and the inner of :func:`inner_spring_for`:
    ``[spring]`` (the outer's table as it was given), ``[inner_spring]`` (the inner's drawing,
    :func:`springdyn.valve.design.synthesis.spring_table`), ``[pack]`` (the hands) and, when
    given, ``[damper]``.

    Parameters
    ----------
    outer_table : dict
        The outer spring's ``[spring]`` table, as read [-].
    design : dict
        What :func:`inner_spring_for` returned.
    damper : dict, optional
        A ``[damper]`` table to keep [-].
    """
    opt = design["pack"].options
    doc = {
        "spring": dict(outer_table),
        "inner_spring": spring_table(design["spring"]),
        "pack": {"outer_hand": opt.outer_hand, "inner_hand": opt.inner_hand},
    }
    if damper:
        doc["damper"] = dict(damper)
    return doc
