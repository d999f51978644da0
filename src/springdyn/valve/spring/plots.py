"""The spring wing's figure: the static characteristic (PNG via
:func:`springdyn.core.plotting.save_figure`)."""

from __future__ import annotations

from ...core.plotting import new_figure, save_figure

__all__ = ["plot_static_curve"]


def plot_static_curve(curve, path=None, ax=None):
    """Static force and tangent stiffness against spring length, breakpoints marked.

    With ``ax``, only the force panel is drawn into it.

    Parameters
    ----------
    curve : StaticCurve
        The curve.
    path : path-like, optional
        PNG file to write.
    ax : matplotlib.axes.Axes, optional
        Axes for the force panel.
    """
    spring = curve.spring
    p = spring.spring_model.internal_parameters()
    if ax is None:
        fig, (ax_f, ax_k) = new_figure(2, 1, figsize=(8, 7), sharex=True)
    else:
        fig, ax_f, ax_k = ax.figure, ax, None
    mm = curve.length * 1e3
    ax_f.plot(mm, curve.force, color="C0", lw=2, label="static force")
    if ax_k is not None:
        ax_k.plot(mm, curve.stiffness / 1e3, color="C1", lw=2, label="tangent stiffness")
        if getattr(curve, "frequency", None) is not None:
            ax_n = ax_k.twinx()
            ax_n.plot(mm, curve.frequency, color="C2", lw=1.5, label="first natural frequency")
            ax_n.set_ylabel("first natural frequency [Hz]", color="C2")
            ax_k.plot([], [], color="C2", lw=1.5, label="first natural frequency (right)")
            ax_k.legend(fontsize=8, loc="upper left")
    ls = spring.installed_length * 1e3
    for ax in (a for a in (ax_f, ax_k) if a is not None):
        ax.axvline(ls, color="k", ls="--", lw=1)
        ax.grid(True, alpha=0.3)
    ax_f.text(ls, ax_f.get_ylim()[1], " set-up Ls", va="top", fontsize=8)
    for name, color in (("F1", "C2"), ("F2", "C3"), ("Fcon", "C4")):
        if name not in p:
            continue
        force = p[name]
        if force <= curve.force.max():
            length = spring.spring_model.length_at_force(force) * 1e3
            ax_f.axhline(force, color=color, ls=":", lw=1)
            ax_f.plot([length], [force], "o", color=color, label=f"{name} = {force:.1f} N at {length:.2f} mm")
    ax_f.set_ylabel("force [N]")
    if ax_k is not None:
        ax_k.set_ylabel("stiffness [N/mm]")
        ax_k.set_yscale("log")
        ax_k.set_xlabel("spring length [mm]")
    else:
        ax_f.set_xlabel("spring length [mm]")
    ax_f.invert_xaxis()
    ax_f.legend(fontsize=8, loc="upper left")
    ax_f.set_title(f"{spring.type} valve spring: static characteristic ({curve.model} model)")
    if path is not None:
        save_figure(fig, path, close=False)
    return fig
