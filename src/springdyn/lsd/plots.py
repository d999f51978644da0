"""Figure layouts shared by the leaf-spring-damper results (coefficients vs speed)."""

from __future__ import annotations

from ..core.plotting import new_figure, save_figure

__all__ = ["coefficients_figure"]


def coefficients_figure(title, draw, path=None, damping_linthresh=None):
    """Stiffness and damping vs shaft speed side by side (like Figs. 5.9/5.10, 5.27/5.28).

    Parameters
    ----------
    title : str
        Figure title.
    draw : callable
        ``draw(ax_k, ax_c)`` plots the curves/markers (stiffness in N/mm, damping in N s/m).
    path : path-like, optional
        Save a PNG there.
    damping_linthresh : float, optional
        Use a symmetric-log damping axis with this linear range [N s/m].
    """
    fig, (ax_k, ax_c) = new_figure(1, 2, figsize=(11, 4.5))
    draw(ax_k, ax_c)
    ax_k.set_xlabel("shaft speed [rpm]")
    ax_k.set_ylabel("stiffness [N/mm]")
    ax_c.set_xlabel("shaft speed [rpm]")
    ax_c.set_ylabel("damping [N s/m]")
    if damping_linthresh is not None:
        ax_c.set_yscale("symlog", linthresh=damping_linthresh)
    for ax in (ax_k, ax_c):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(title)
    if path is not None:
        save_figure(fig, path, close=False)
    return fig
