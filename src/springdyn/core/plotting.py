"""Matplotlib helpers shared by every model: headless backend and atomic PNG saving."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib

matplotlib.use("Agg", force=False)

import matplotlib.pyplot as plt  # noqa: E402

from .io import atomic_path  # noqa: E402

__all__ = ["plt", "new_figure", "save_figure"]


def new_figure(nrows: int = 1, ncols: int = 1, *, figsize=(8.0, 5.0), sharex=False, **kw):
    """Create a figure and its axes with springdyn's defaults."""
    fig, axes = plt.subplots(nrows, ncols, figsize=figsize, sharex=sharex, constrained_layout=True, **kw)
    return fig, axes


def save_figure(fig, path: str | os.PathLike, *, dpi: int = 120, close: bool = True) -> Path:
    """Save ``fig`` as PNG atomically (temporary file, then rename) and close it."""
    path = Path(path)
    try:
        with atomic_path(path, suffix=".png") as tmp:
            fig.savefig(tmp, dpi=dpi, format="png")
    finally:
        if close:
            plt.close(fig)
    return path
