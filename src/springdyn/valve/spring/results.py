"""The spring wing's result: :class:`StaticCurve`, the static force, stiffness and first
natural frequency of a spring against its length, on the shared
:class:`~springdyn.core.results.Result` (its figure: :mod:`.plots`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.results import Result, dataset_columns

__all__ = ["StaticCurve"]


@dataclass(repr=False)
class StaticCurve(Result):
    """Static force and tangent stiffness of a spring against its length (SI)."""

    spring: object
    length: np.ndarray  # [m]
    force: np.ndarray  # [N]
    stiffness: np.ndarray  # [N/m]
    model: str = "type-c"
    frequency: np.ndarray | None = None  # first natural frequency, ends fixed [Hz]

    title = "valve spring static curve"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.spring.type} spring, {self.model} model, {self.length.size} points"

    def _summary(self) -> dict:
        return dict(
            model=self.model,
            points=int(self.length.size),
            length_max_m=float(self.length.max()),
            length_min_m=float(self.length.min()),
            force_min_N=float(self.force.min()),
            force_max_N=float(self.force.max()),
            stiffness_min_N_per_m=float(self.stiffness.min()),
            stiffness_max_N_per_m=float(self.stiffness.max()),
            **(
                {}
                if self.frequency is None
                else dict(first_mode_min_Hz=float(self.frequency.min()), first_mode_max_Hz=float(self.frequency.max()))
            ),
        )

    def columns(self) -> dict:
        """``length_m, force_N, stiffness_N_per_m`` (the CSV columns)."""
        return dataset_columns(self.to_xarray())

    def to_xarray(self):
        import xarray as xr

        data = {
            "force": ("length", self.force, {"units": "N", "long_name": "static spring force"}),
            "stiffness": ("length", self.stiffness, {"units": "N/m", "long_name": "tangent stiffness -dF/dL"}),
        }
        if self.frequency is not None:
            data["first_mode_frequency"] = (
                "length",
                self.frequency,
                {"units": "Hz", "long_name": "first natural frequency, ends fixed"},
            )
        return xr.Dataset(
            data,
            coords={"length": ("length", self.length, {"units": "m", "long_name": "spring length"})},
            attrs={"model": self.model, "spring_type": self.spring.type},
        )

    def _plot(self, ax=None):
        """Force and stiffness vs length with Ls, F1, F2 and Fcon marked."""
        from .plots import plot_static_curve  # (here: matplotlib costs 0.3 s of start-up)

        return plot_static_curve(self, ax=ax)
