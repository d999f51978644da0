"""Plots of the valve-spring analyses (PNG via :func:`springdyn.plotting.save_figure`)."""

from __future__ import annotations

import numpy as np

from ..plotting import new_figure, save_figure

__all__ = ["plot_static_curve"]


def plot_static_curve(curve, path=None):
    """Static force and tangent stiffness against spring length, breakpoints marked."""
    spring = curve.spring
    p = spring.internal_parameters()
    fig, (ax_f, ax_k) = new_figure(2, 1, figsize=(8, 7), sharex=True)
    mm = curve.length * 1e3
    ax_f.plot(mm, curve.force, color="C0", lw=2, label="static force")
    ax_k.plot(mm, curve.stiffness / 1e3, color="C1", lw=2, label="tangent stiffness")
    ls = spring.installed_length * 1e3
    for ax in (ax_f, ax_k):
        ax.axvline(ls, color="k", ls="--", lw=1)
        ax.grid(True, alpha=0.3)
    ax_f.text(ls, ax_f.get_ylim()[1], " set-up Ls", va="top", fontsize=8)
    for name, color in (("F1", "C2"), ("F2", "C3"), ("Fcon", "C4")):
        force = p[name]
        if force <= curve.force.max():
            length = spring.length_at_force(force) * 1e3
            ax_f.axhline(force, color=color, ls=":", lw=1)
            ax_f.plot([length], [force], "o", color=color, label=f"{name} = {force:.1f} N at {length:.2f} mm")
    ax_f.set_ylabel("force [N]")
    ax_k.set_ylabel("stiffness [N/mm]")
    ax_k.set_yscale("log")
    ax_k.set_xlabel("spring length [mm]")
    ax_f.invert_xaxis()
    ax_f.legend(fontsize=8, loc="upper left")
    ax_f.set_title(f"{spring.type} valve spring: static characteristic (MMS Type C chain)")
    if path is not None:
        save_figure(fig, path, close=False)
    return fig




def plot_simulation(sim, path=None):
    """Forces vs cam angle (dynamic against static), mass displacements and spectrum."""
    vt = sim.valve_train is not None
    fig, axes = new_figure(4 if vt else 3, 1, figsize=(9, 12 if vt else 10))
    deg = sim.cam_angle_deg
    order = np.argsort(deg)
    ax = axes[0]
    ax.plot(deg[order], sim.retainer_force[order], color="C0", lw=1.5, label="retainer force (dynamic)")
    ax.plot(deg[order], sim.seat_force[order], color="C1", lw=1.0, label="seat force (dynamic)")
    ax.plot(deg[order], sim.static_force[order], color="k", ls="--", lw=1.2, label="static (massless) force")
    for ev in sim.summary()["coil_contact"]:
        a, b = ev["start_deg"], ev["end_deg"]
        spans = [(a, b)] if a <= b else [(a, 360.0), (0.0, b)]
        for lo, hi in spans:
            ax.axvspan(lo, hi, color="C3", alpha=0.15)
    if sim.summary()["coil_contact"]:
        ax.plot([], [], color="C3", alpha=0.3, lw=6, label="coil contact")
    ax.set_ylabel("force [N]")
    ax.set_title(f"{sim.spring.type} spring, {sim.cam.law} cam, {sim.cam_rpm:.0f} cam rpm "
                 f"(revolution {sim.revolutions} of {sim.revolutions})")
    ax.legend(fontsize=8)
    ax2 = ax.twinx()
    ax2.plot(deg[order], sim.lift[order] * 1e3, color="0.6", lw=0.8)
    ax2.set_ylabel("cam lift [mm]", color="0.5")
    ax = axes[1]
    for i, name in enumerate(sim.spring.chain.mass_names):
        ax.plot(deg[order], sim.mass_displacement[i][order] * 1e3, lw=1, label=f"mass {i + 1} ({name})")
    ax.set_ylabel("displacement from set-up [mm]")
    ax.legend(fontsize=8, ncol=3)
    row = 2
    if vt:
        ax = axes[2]
        ax.plot(deg[order], sim.cam_contact_force[order], color="C2", label="cam-follower contact force")
        ax.plot(deg[order], sim.valve_seat_force[order], color="C4", label="valve-seat force")
        for ev in sim.summary()["liftoff"]:
            ax.axvspan(ev["start_deg"], ev["end_deg"], color="C3", alpha=0.2)
        if sim.summary()["liftoff"]:
            ax.plot([], [], color="C3", alpha=0.3, lw=6, label="lift-off")
        ax.set_ylabel("force [N]")
        ax.legend(fontsize=8)
        row = 3
    for a in axes[:row]:
        a.set_xlabel("cam angle [deg]")
        a.set_xlim(0, 360)
        a.grid(True, alpha=0.3)
    ax = axes[row]
    orders, amp = sim.spectrum(40)
    ax.bar(orders[1:], amp[1:], color="C0", width=0.7)
    f1_order = sim.summary()["f1_cam_order"]
    ax.axvline(f1_order, color="C3", ls="--", label=f"f1 = {sim.summary()['f1_Hz']:.0f} Hz (order {f1_order:.1f})")
    ax.set_xlabel("cam order")
    ax.set_ylabel("retainer force amplitude [N]")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    if path is not None:
        save_figure(fig, path, close=False)
    return fig
