"""Result objects of the CFCS model: tables with ``to_xarray``, ``to_csv``, ``plot``.

Each result keeps SI arrays and a ``summary`` dict whose keys carry their unit
(``force_max_N``); every summary states the toggle cut-off it used.
"""

from __future__ import annotations

import dataclasses
from typing import ClassVar

import numpy as np
import xarray as xr

from ..core.plotting import new_figure
from ..core.results import Result, units_from_name

__all__ = ["StaticResult", "DynamicResult", "DrivenResult", "FrequencySweep", "ForwardResult", "running_pcf"]


def running_pcf(force):
    """PCF vs time [%]: ``100 min(F[0..i]) / max(F[0..i])`` over the record so far.

    springdyn's definition of the paper's Fig. 12 (the paper gives none, correction CFCS-4 of docs/references.md): it starts at 100 % and falls as the force explores its range; its
    value at the end of a whole cycle is the cycle's PCF.

    Parameters
    ----------
    force : array_like
        Force record [N].
    """
    f = np.asarray(force, dtype=float)
    lo = np.minimum.accumulate(f)
    hi = np.maximum.accumulate(f)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(hi > 0, 100.0 * lo / hi, np.nan)


class _Table(Result):
    """Shared plumbing of the CFCS results (and :class:`springdyn.cfcs.design.DesignResult`) on
    :class:`~springdyn.core.results.Result`.

    ``columns()`` gives ``{name_unit: array}``, the first column the coordinate along
    :attr:`dim`; :meth:`to_xarray` turns it into the dataset (each variable with the unit its
    name carries, the summary's scalars as attributes), from which the base derives the CSV.
    The summary is stored by the model that builds the result (a dataclass field).
    """

    title = "constant-force spring result"
    #: Name of the dataset's dimension (the rows of the CSV).
    dim: ClassVar[str]

    def columns(self) -> dict:  # pragma: no cover - overridden
        raise NotImplementedError

    def to_xarray(self) -> xr.Dataset:
        cols = self.columns()
        first = next(iter(cols))
        coord = cols.pop(first)
        ds = xr.Dataset(
            {k: (self.dim, np.asarray(v), {"units": units_from_name(k)}) for k, v in cols.items()},
            coords={first: (self.dim, coord, {"units": units_from_name(first)})},
        )
        ds.attrs.update(
            {k: v for k, v in self.summary.items() if isinstance(v, (int, float, str)) and not isinstance(v, bool)}
        )
        return ds

    @staticmethod
    def _panels(ax, height: float = 7.0):
        """The figure, its main axes and a second panel below them (``None`` when drawing into ``ax``)."""
        if ax is None:
            fig, (ax, ax2) = new_figure(2, 1, figsize=(8.0, height), sharex=True)
            return fig, ax, ax2
        return ax.figure, ax, None

    @staticmethod
    def _finish_main(ax, ax2) -> bool:
        """Grid and legend of the main axes; ``True`` when there is no second panel (the
        main axes then carry the time axis)."""
        ax.grid(True, alpha=0.3)
        ax.legend()
        if ax2 is None:
            ax.set_xlabel("time [s]")
        return ax2 is None


@dataclasses.dataclass(repr=False)
class StaticResult(_Table):
    """Quasi-static force-deflection curve over a stroke."""

    deflection: np.ndarray
    theta2: np.ndarray
    force: np.ndarray
    force_compression: np.ndarray
    force_extension: np.ndarray
    stress: np.ndarray
    summary: dict
    extra: dict = dataclasses.field(default_factory=dict)  # beam model: the PRBM beside it

    def columns(self) -> dict:
        cols = {
            "deflection_m": self.deflection,
            "theta2_rad": self.theta2,
            "force_N": self.force,
            "force_compression_N": self.force_compression,
            "force_extension_N": self.force_extension,
        }
        if np.all(np.isfinite(self.stress)):
            cols["stress_Pa"] = self.stress
        cols.update(self.extra)
        return cols

    dim = "sample"
    title = "constant-force spring: static force"

    def _plot(self, ax=None):
        fig, ax = new_figure() if ax is None else (ax.figure, ax)
        mm = self.deflection * 1e3
        beam = self.summary.get("flexure_model") == "beam"
        ax.plot(mm, self.force, label="static, beam (elastica)" if beam else "static (virtual work)", lw=2)
        if "force_prbm_N" in self.extra:
            ax.plot(mm, self.extra["force_prbm_N"], ":", label="static, PRBM (pin with K3)")
        if not np.allclose(self.force_compression, self.force):
            ax.plot(mm, self.force_compression, "--", label="with tau_CF, tau_AF: compression")
            ax.plot(mm, self.force_extension, "--", label="with tau_CF, tau_AF: extension")
        ax.set_xlabel("slider deflection [mm]")
        ax.set_ylabel("force [N]")
        s = self.summary
        ax.set_title(
            f"CFCS static force, PCF {s['pcf_percent']:.1f} % over {s['stroke_m'] * 1e3:.4g} mm "
            f"(toggle cut-off {np.degrees(s['toggle_cutoff_rad']):.3g} deg)"
        )
        ax.grid(True, alpha=0.3)
        ax.legend()
        return fig


@dataclasses.dataclass(repr=False)
class DynamicResult(_Table):
    """Inverse dynamics: slider force along a prescribed periodic motion."""

    time: np.ndarray
    deflection: np.ndarray
    velocity: np.ndarray
    theta2: np.ndarray
    force: np.ndarray
    force_static: np.ndarray
    components: dict
    in_toggle_zone: np.ndarray
    summary: dict

    @property
    def pcf_vs_time(self) -> np.ndarray:
        """Running PCF [%] (see :func:`running_pcf`)."""
        return running_pcf(self.force)

    def columns(self) -> dict:
        cols = {
            "time_s": self.time,
            "deflection_m": self.deflection,
            "force_N": self.force,
            "force_static_N": self.force_static,
            "velocity_m_per_s": self.velocity,
            "theta2_rad": self.theta2,
        }
        for k, v in self.components.items():
            cols[f"{k}_N"] = v
        cols["pcf_running_percent"] = self.pcf_vs_time
        cols["in_toggle_zone"] = self.in_toggle_zone.astype(int)
        return cols

    dim = "time"
    title = "constant-force spring: dynamic force"

    def _plot(self, ax=None, *, label: str = "dynamic"):
        fig, ax, ax2 = self._panels(ax)
        ax.plot(self.time, self.force, label=label, lw=2)
        ax.plot(self.time, self.force_static, "--", label="static force at the same deflection")
        ax.set_ylabel("slider force [N]")
        s = self.summary
        ax.set_title(
            f"CFCS at omega = {s['omega_rad_per_s']:.4g} rad/s: mean {s['mean_force_N']:.4g} N, "
            f"p-p {s['peak_to_peak_N']:.3g} N, PCF {s['pcf_percent']:.1f} %\n"
            f"toggle cut-off {np.degrees(s['toggle_cutoff_rad']):.3g} deg "
            f"({s['toggle_zone_samples']} samples inside"
            + ("; TOGGLE-DOMINATED: the statistics depend on the cut-off)" if s.get("toggle_dominated") else ")"),
            fontsize=10,
        )
        if self._finish_main(ax, ax2):
            return fig
        ax2.plot(self.time, self.pcf_vs_time)
        ax2.set_xlabel("time [s]")
        ax2.set_ylabel("running PCF [%]")
        ax2.grid(True, alpha=0.3)
        return fig


@dataclasses.dataclass(repr=False)
class FrequencySweep(_Table):
    """Force statistics vs frequency (Figs. 5-7 of the CFCS paper), with and without
    the dissipative terms."""

    omega: np.ndarray
    stats: dict  # name -> array, e.g. mean_force_N, mean_force_no_dissipation_N
    summary: dict

    def columns(self) -> dict:
        return {"omega_rad_per_s": self.omega, **self.stats}

    dim = "omega"
    title = "constant-force spring: frequency sweep"

    def _plot(self, ax=None):
        names = [
            ("mean_force", "mean force [N]"),
            ("median_force", "median force [N]"),
            ("peak_to_peak", "peak-to-peak force [N]"),
            ("pcf", "PCF [%]"),
        ]
        if ax is None:
            fig, axes = new_figure(2, 2, figsize=(10.0, 7.0), sharex=True)
            pairs = list(zip(axes.flat, names))
        else:
            fig, axes, pairs = ax.figure, None, [(ax, names[2])]
        for ax, (name, label) in pairs:
            unit = "percent" if name == "pcf" else "N"
            ax.plot(self.omega, self.stats[f"{name}_{unit}"], label="with tau_CF, tau_AF")
            ax.plot(self.omega, self.stats[f"{name}_no_dissipation_{unit}"], "--", label="without")
            ax.set_ylabel(label)
            ax.grid(True, alpha=0.3)
        if axes is None:
            ax.set_xlabel("omega [rad/s]")
            ax.legend()
            return fig
        for ax in axes[1]:
            ax.set_xlabel("omega [rad/s]")
        axes[0, 0].legend()
        fig.suptitle(f"CFCS frequency sweep (toggle cut-off {np.degrees(self.summary['toggle_cutoff_rad']):.3g} deg)")
        return fig


def _slider_columns(r) -> dict:
    """The slider's and the crank's motion and the forces of a forward or driven run, as columns."""
    return {
        "deflection_m": r.deflection,
        "velocity_m_per_s": r.velocity,
        "theta2_rad": r.theta2,
        "theta2dot_rad_per_s": r.theta2dot,
        "force_N": r.force,
        "force_static_N": r.force_static,
    }


@dataclasses.dataclass(repr=False)
class ForwardResult(_Table):
    """Forward dynamics: the slider's response to a force (or a spring from a moving base)."""

    time: np.ndarray
    deflection: np.ndarray
    velocity: np.ndarray
    theta2: np.ndarray
    theta2dot: np.ndarray
    force: np.ndarray
    force_static: np.ndarray
    energy: np.ndarray
    summary: dict

    def columns(self) -> dict:
        return {"time_s": self.time, **_slider_columns(self), "energy_J": self.energy}

    dim = "time"
    title = "constant-force spring: forward dynamics"

    def _plot(self, ax=None):
        fig, ax, ax2 = self._panels(ax, height=6.5)
        ax.plot(self.time, self.deflection * 1e3)
        ax.set_ylabel("slider deflection [mm]")
        ax.grid(True, alpha=0.3)
        if ax2 is None:
            ax.set_xlabel("time [s]")
            return fig
        ax.set_title(
            f"CFCS forward dynamics (smoothed Coulomb sign, v_s = {self.summary['sign_smoothing_rad_per_s']:.3g} rad/s)"
        )
        ax2.plot(self.time, self.force, label="drive force")
        ax2.plot(self.time, self.force_static, "--", label="static force at the deflection")
        ax2.set_xlabel("time [s]")
        ax2.set_ylabel("force [N]")
        ax2.grid(True, alpha=0.3)
        ax2.legend()
        return fig


@dataclasses.dataclass(repr=False)
class DrivenResult(_Table):
    """Forward dynamics through a compliant drive (:meth:`springdyn.cfcs.model.CFCS.driven`).

    The drive's far end follows ``drive_position`` (the prescribed motion); ``force`` is the
    drive's force on the slider; ``work``, ``heat_friction``, ``heat_damper`` the running
    integrals of the energy balance and ``energy_residual`` its residual.
    """

    time: np.ndarray
    drive_position: np.ndarray
    deflection: np.ndarray
    velocity: np.ndarray
    theta2: np.ndarray
    theta2dot: np.ndarray
    force: np.ndarray
    force_static: np.ndarray
    work: np.ndarray
    heat_friction: np.ndarray
    heat_damper: np.ndarray
    energy_residual: np.ndarray
    summary: dict

    def columns(self) -> dict:
        return {
            "time_s": self.time,
            "drive_position_m": self.drive_position,
            **_slider_columns(self),
            "actuator_work_J": self.work,
            "heat_friction_J": self.heat_friction,
            "heat_damper_J": self.heat_damper,
            "energy_residual_J": self.energy_residual,
        }

    dim = "time"
    title = "constant-force spring: driven through a compliant drive"

    def _plot(self, ax=None):
        s = self.summary
        fig, ax, ax2 = self._panels(ax)
        ax.plot(self.time, self.force, label="drive force", lw=1.5)
        ax.plot(self.time, self.force_static, "--", label="static force at the deflection")
        ax.set_ylabel("force [N]")
        ax.set_title(
            f"CFCS driven at omega = {s['omega_rad_per_s']:.4g} rad/s through k_d = "
            f"{s['drive_stiffness_N_per_m'] / 1e3:.4g} kN/m, c_d = {s['drive_damping_N_s_per_m']:.3g} N s/m\n"
            f"last period: p-p {s['peak_to_peak_N']:.4g} N, mean {s['mean_force_N']:.4g} N (no toggle cut-off)"
            + (
                f"\ncrank sticks at the toggle (tau_AF with F_static inside alpha); without tau_AF p-p "
                f"{s['peak_to_peak_without_axial_friction_N']:.4g} N"
                if s.get("toggle_sticking") and s.get("peak_to_peak_without_axial_friction_N") is not None
                else ""
            ),
            fontsize=10,
        )
        if self._finish_main(ax, ax2):
            return fig
        ax2.plot(self.time, self.drive_position * 1e3, "--", label="drive x_d")
        ax2.plot(self.time, self.deflection * 1e3, label="slider x")
        ax2.set_xlabel("time [s]")
        ax2.set_ylabel("position [mm]")
        ax2.grid(True, alpha=0.3)
        ax2.legend()
        return fig
