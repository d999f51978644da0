"""Matplotlib helpers shared by every model: headless backend and atomic PNG saving."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg", force=False)

import matplotlib.pyplot as plt  # noqa: E402

from .io import atomic_path  # noqa: E402

__all__ = ["plt", "new_figure", "save_figure", "smallest_font_px"]


def new_figure(nrows: int = 1, ncols: int = 1, *, figsize=(8.0, 5.0), sharex=False, **kw):
    """Create a figure and its axes with springdyn's defaults."""
    fig, axes = plt.subplots(nrows, ncols, figsize=figsize, sharex=sharex, constrained_layout=True, **kw)
    return fig, axes


def smallest_font_px(fig, dpi: float) -> float:
    """Height [px] of the smallest visible text of ``fig`` when saved at ``dpi``.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    dpi : float
        Resolution of the saved image [pixels per inch].
    """
    sizes = [
        t.get_fontsize()
        for t in fig.findobj(lambda a: hasattr(a, "get_text") and hasattr(a, "get_fontsize"))
        if t.get_visible() and str(t.get_text()).strip()
    ]
    return min(sizes, default=10.0) * dpi / 72.0


def save_figure(fig, path: str | os.PathLike, *, dpi: int = 120, close: bool = True) -> Path:
    """Save ``fig`` as PNG atomically (temporary file, then rename) and close it.

    The PNG records the height of its smallest text in pixels (text chunk
    ``springdyn:min-font-px``), so that a page showing it can check the text stays legible.
    """
    path = Path(path)
    try:
        with atomic_path(path, suffix=".png") as tmp:
            fig.savefig(
                tmp, dpi=dpi, format="png", metadata={"springdyn:min-font-px": f"{smallest_font_px(fig, dpi):.2f}"}
            )
    finally:
        if close:
            plt.close(fig)
    return path
