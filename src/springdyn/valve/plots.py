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


