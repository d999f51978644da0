"""Results objects of the valve-spring analyses: arrays plus ``to_xarray``/``to_csv``/``plot``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.io import write_csv

__all__ = ["StaticCurve"]


@dataclass
class StaticCurve:
    """Static force and tangent stiffness of a spring against its length (SI)."""

    spring: object
    length: np.ndarray  # [m]
    force: np.ndarray  # [N]
    stiffness: np.ndarray  # [N/m]

    def columns(self) -> dict:
        return {"length_m": self.length, "force_N": self.force, "stiffness_N_per_m": self.stiffness}

    def to_csv(self, path):
        """Write ``length_m, force_N, stiffness_N_per_m`` (atomic)."""
        return write_csv(path, self.columns())

    def to_xarray(self):
        import xarray as xr

        return xr.Dataset(
            {
                "force": ("length", self.force, {"units": "N", "long_name": "static spring force"}),
                "stiffness": ("length", self.stiffness, {"units": "N/m", "long_name": "tangent stiffness -dF/dL"}),
            },
            coords={"length": ("length", self.length, {"units": "m", "long_name": "spring length"})},
            attrs={"model": "MMS Type C static series equilibrium", "spring_type": self.spring.type},
        )

    def plot(self, path=None):
        """Force and stiffness vs length with Ls, F1, F2 and Fcon marked (document Figs. 40.34-40.36)."""
        from .plots import plot_static_curve

        return plot_static_curve(self, path)
