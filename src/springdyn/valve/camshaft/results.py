"""Results of a camshaft: its torsional modes, one speed's periodic state, a sweep over speed.

Angles are cam angles over the shaft's nominal angle (the crankshaft's sprocket turns at the
nominal speed); timing errors are the shift of each valve's opening, closing and peak on the
twisting shaft against the same valve on a rigid shaft at the same speed (positive: later), in
cam degrees and in crank degrees (a four-stroke's, twice the cam's).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...core.results import Result, text_table

__all__ = ["TorsionalModes", "CamshaftRun", "CamshaftSweep", "EVENTS", "CRANK_PER_CAM"]

#: The valve events whose timing is reported.
EVENTS = ("opening", "closing", "peak")
#: Crank angle per cam angle of a four-stroke engine [-].
CRANK_PER_CAM = 2.0


def _labels(names) -> list[str]:
    """The lobes' names as column labels (no spaces: ``cylinder_1``)."""
    return [str(n).replace(" ", "_") for n in names]


@dataclass(repr=False)
class TorsionalModes(Result):
    """The camshaft's torsional natural frequencies and mode shapes (the crankshaft's sprocket held)."""

    frequency: np.ndarray  #: [Hz], ascending
    shapes: np.ndarray  #: (node, mode), largest node angle 1 [-]
    nodes: tuple  #: node names from the sprocket
    position: np.ndarray  #: [m]
    inertia: np.ndarray  #: [kg m^2]

    title = "camshaft torsional modes"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{len(self.nodes)} nodes"

    def _summary(self) -> dict:
        return dict(
            nodes=len(self.nodes),
            first_mode_Hz=float(self.frequency[0]),
            second_mode_Hz=float(self.frequency[1]) if self.frequency.size > 1 else None,
            total_inertia_kg_m2=float(self.inertia.sum()),
            notes=[] if self.frequency.size > 1 else ["second_mode_Hz: the chain has one node"],
        )

    def describe(self) -> str:
        rows = [(f"{i + 1}", f"{f:.1f}") for i, f in enumerate(self.frequency)]
        return "camshaft torsional modes (crank sprocket held)\n" + text_table(rows, headers=("mode", "frequency [Hz]"))

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        return xr.Dataset(
            {
                "frequency": (("mode",), self.frequency, {"units": "Hz"}),
                "shape": (("node", "mode"), self.shapes, {"units": "1", "csv": "no"}),
                "position": (("node",), self.position, {"units": "m", "csv": "no"}),
                "inertia": (("node",), self.inertia, {"units": "kg*m^2", "csv": "no"}),
            },
            coords={"mode": ("mode", np.arange(1, self.frequency.size + 1)), "node": ("node", list(self.nodes))},
        )

    def _plot(self, ax=None):
        """Each mode's shape along the shaft."""
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(7, 4.5))
        x = self.position * 1e3
        for m in range(self.frequency.size):
            ax.plot(x, self.shapes[:, m], "-o", ms=3, label=f"{self.frequency[m]:.0f} Hz")
        ax.set_xlabel("position along the shaft [mm]")
        ax.set_ylabel("mode shape [-]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return fig


@dataclass(repr=False)
class CamshaftRun(Result):
    """The periodic steady state of a camshaft and its valves at one speed (SI; angles in rad)."""

    cam_rpm: float
    cam_angle: np.ndarray  #: nominal cam angle (n,) [rad]
    lobe_names: tuple
    lobe_phase: np.ndarray  #: [rad]
    drive_torque: np.ndarray  #: the timing drive's torque on the camshaft (n,) [N m]
    lobe_torque: np.ndarray  #: each follower's load torque on its lobe (lobe, n) [N m]
    twist: np.ndarray  #: each lobe's angle ahead of the nominal (lobe, n) [rad]
    sprocket_twist: np.ndarray  #: the sprocket's (n,) [rad]
    valve_lift: np.ndarray  #: (lobe, n) [m]
    cam_contact_force: np.ndarray  #: (lobe, n) [N]
    events: np.ndarray  #: opening, closing, peak of each valve on its lobe's own angle (lobe, 3) [rad]
    timing_error: np.ndarray  #: the same against the rigid shaft (lobe, 3) [rad], positive: later
    iterations: int
    residual: float  #: the twist's last change [rad]
    converged: bool
    rigid: bool
    tolerance: float  #: [rad]
    residual_history: np.ndarray  #: [rad]
    modes_Hz: np.ndarray
    bearing_drag: float  #: the bearings' mean drag [N m]
    simulations: tuple = field(default=(), repr=False)  #: each valve's Simulation, on its lobe's own angle
    rigid_simulations: tuple = field(default=(), repr=False)  #: each valve alone (the rigid shaft)
    timing_lift: float = 1e-3  #: [m]

    title = "camshaft with torsion"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.cam_rpm:g} cam rpm, {len(self.lobe_names)} lobes"

    @property
    def timing_error_crank(self) -> np.ndarray:
        """The timing errors in crank angle (a four-stroke's) [rad]."""
        return CRANK_PER_CAM * self.timing_error

    def _summary(self) -> dict:
        notes = []
        err = np.where(np.isfinite(self.timing_error), self.timing_error, 0.0)
        if not np.isfinite(self.timing_error).all():
            notes.append(
                f"a valve does not reach the timing lift {self.timing_lift * 1e3:g} mm: no timing error for it"
            )
        if not self.converged:
            notes.append(
                f"the twist did not converge: its last change {math.degrees(self.residual):.3g} deg is above the "
                f"tolerance {math.degrees(self.tolerance):.3g} deg after {self.iterations} iterations"
            )
        if self.rigid:
            notes.append("rigid shaft: every valve runs as alone (no twist, no timing error)")
        i = int(np.argmax(np.abs(err)))
        worst_lobe, worst_event = divmod(i, len(EVENTS))
        valves = [s.summary for s in self.simulations]
        return dict(
            cam_rpm=self.cam_rpm,
            lobe_count=len(self.lobe_names),
            mean_drive_torque_N_m=float(np.mean(self.drive_torque)),
            max_drive_torque_N_m=float(np.max(self.drive_torque)),
            min_drive_torque_N_m=float(np.min(self.drive_torque)),
            max_twist_deg=float(np.degrees(np.max(np.abs(self.twist)))),
            max_twist_range_deg=float(np.degrees(np.max(np.ptp(self.twist, axis=1)))),
            max_timing_error_deg=float(np.degrees(abs(err.flat[i]))),
            max_timing_error_crank_deg=float(np.degrees(abs(err.flat[i])) * CRANK_PER_CAM),
            worst_timing_which=f"{self.lobe_names[worst_lobe]} {EVENTS[worst_event]}",
            first_mode_Hz=float(self.modes_Hz[0]),
            iteration_count=int(self.iterations),
            residual_deg=float(np.degrees(self.residual)),
            converged=bool(self.converged),
            max_cam_contact_force_N=max(float(v["max_cam_contact_force_N"]) for v in valves),
            min_cam_contact_force_N=min(float(v["min_cam_contact_force_N"]) for v in valves),
            liftoff_count=sum(1 for v in valves if v.get("liftoff")),
            notes=notes,
        )

    def lobe_table(self) -> list[tuple]:
        """Per lobe: phase, twist range and mean, the timing errors in cam and crank degrees,
        its cam contact force's extremes (rows of text)."""
        rows = []
        for i, name in enumerate(self.lobe_names):
            e = self.timing_error[i]
            s = self.simulations[i].summary
            rows.append(
                (
                    name,
                    f"{math.degrees(self.lobe_phase[i]):.0f}",
                    f"{math.degrees(float(np.mean(self.twist[i]))):+.4f}",
                    f"{math.degrees(float(np.ptp(self.twist[i]))):.4f}",
                    " / ".join("-" if not math.isfinite(x) else f"{math.degrees(x):+.3f}" for x in e),
                    " / ".join("-" if not math.isfinite(x) else f"{CRANK_PER_CAM * math.degrees(x):+.3f}" for x in e),
                    f"{s['min_cam_contact_force_N']:.0f} / {s['max_cam_contact_force_N']:.0f}",
                )
            )
        return rows

    def describe(self) -> str:
        m = self.summary
        head = (
            f"camshaft at {self.cam_rpm:g} cam rpm ({CRANK_PER_CAM * self.cam_rpm:g} engine rpm), "
            f"{len(self.lobe_names)} lobes, "
            + (
                "rigid shaft"
                if self.rigid
                else f"{self.iterations} iterations, twist change {m['residual_deg']:.2g} deg"
                + ("" if self.converged else " (NOT converged)")
            )
        )
        lines = [
            head,
            f"drive torque: mean {m['mean_drive_torque_N_m']:.3f} N m, min {m['min_drive_torque_N_m']:.2f} N m, "
            f"max {m['max_drive_torque_N_m']:.2f} N m",
            f"twist: largest {m['max_twist_deg']:.4f} deg; timing error: largest {m['max_timing_error_deg']:.4f} cam deg "
            f"({m['max_timing_error_crank_deg']:.4f} crank deg, {m['worst_timing_which']}, at "
            f"{self.timing_lift * 1e3:g} mm valve lift)",
            "torsional modes [Hz]: " + ", ".join(f"{f:.0f}" for f in self.modes_Hz),
            text_table(
                self.lobe_table(),
                headers=(
                    "lobe",
                    "phase [deg]",
                    "mean twist [deg]",
                    "twist range [deg]",
                    "timing error open/close/peak [cam deg]",
                    "[crank deg]",
                    "cam force min/max [N]",
                ),
            ),
        ]
        return "\n".join(lines + [f"note: {n}" for n in m["notes"]])

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        names = _labels(self.lobe_names)
        err = np.where(np.isfinite(self.timing_error), self.timing_error, 0.0)
        dims = ("cam_angle", "lobe")
        ds = xr.Dataset(
            {
                "drive_torque": (("cam_angle",), self.drive_torque, {"units": "N*m"}),
                "sprocket_twist": (("cam_angle",), self.sprocket_twist, {"units": "rad"}),
                "lobe_torque": (dims, self.lobe_torque.T, {"units": "N*m"}),
                "twist": (dims, self.twist.T, {"units": "rad"}),
                "valve_lift": (dims, self.valve_lift.T, {"units": "m"}),
                "cam_contact_force": (dims, self.cam_contact_force.T, {"units": "N"}),
                "timing_error": (("lobe", "event"), err, {"units": "rad", "csv": "no"}),
                "lobe_phase": (("lobe",), self.lobe_phase, {"units": "rad", "csv": "no"}),
            },
            coords={
                "cam_angle": ("cam_angle", self.cam_angle, {"units": "rad"}),
                "lobe": ("lobe", names),
                "event": ("event", list(EVENTS)),
            },
        )
        ds.attrs.update(cam_rpm=self.cam_rpm, iterations=int(self.iterations), residual_rad=float(self.residual))
        return ds

    def _plot(self, ax=None):
        """Drive torque, twist at each lobe and the valve lifts over the nominal cam angle."""
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        deg = np.degrees(self.cam_angle)
        if ax is None:
            fig, (ax, mid, low) = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
            for i, name in enumerate(self.lobe_names):
                mid.plot(deg, np.degrees(self.twist[i]), lw=0.9, label=name)
                low.plot(deg, self.valve_lift[i] * 1e3, lw=0.9, label=name)
            mid.set_ylabel("twist at the lobe [deg]")
            low.set_ylabel("valve lift [mm]")
            low.set_xlabel("cam angle [deg]")
            for a in (mid, low):
                a.grid(True, alpha=0.3)
                a.legend(fontsize=7, ncol=2)
        else:
            fig = ax.figure
        ax.plot(deg, self.drive_torque, "k-", lw=1.0, label="drive torque")
        ax.plot(deg, self.lobe_torque.sum(axis=0), "C3--", lw=0.8, label="sum of the lobes' torques")
        ax.set_ylabel("torque [N m]")
        ax.set_title(f"camshaft at {self.cam_rpm:g} cam rpm")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return fig


@dataclass(repr=False)
class CamshaftSweep(Result):
    """A camshaft over cam speed: drive torque, twist and each valve's timing error (SI)."""

    cam_rpm: np.ndarray
    lobe_names: tuple
    mean_drive_torque: np.ndarray  #: [N m]
    max_drive_torque: np.ndarray  #: [N m]
    min_drive_torque: np.ndarray  #: [N m]
    max_twist: np.ndarray  #: [rad]
    timing_error: np.ndarray  #: (speed, lobe, event) [rad]
    iterations: np.ndarray
    converged: np.ndarray
    modes_Hz: np.ndarray
    runs: tuple = field(default=(), repr=False)

    title = "camshaft over speed"
    cheap_plot = True

    @classmethod
    def of(cls, runs) -> CamshaftSweep:
        """The sweep of the runs at each speed.

        Parameters
        ----------
        runs : sequence of CamshaftRun
            One per speed, ascending.
        """
        return cls(
            cam_rpm=np.array([r.cam_rpm for r in runs]),
            lobe_names=runs[0].lobe_names,
            mean_drive_torque=np.array([np.mean(r.drive_torque) for r in runs]),
            max_drive_torque=np.array([np.max(r.drive_torque) for r in runs]),
            min_drive_torque=np.array([np.min(r.drive_torque) for r in runs]),
            max_twist=np.array([np.max(np.abs(r.twist)) for r in runs]),
            timing_error=np.array([np.where(np.isfinite(r.timing_error), r.timing_error, 0.0) for r in runs]),
            iterations=np.array([r.iterations for r in runs]),
            converged=np.array([r.converged for r in runs]),
            modes_Hz=runs[0].modes_Hz,
            runs=tuple(runs),
        )

    def _repr_caption(self) -> str:
        return f"{self.cam_rpm.size} speeds, {len(self.lobe_names)} lobes"

    def _summary(self) -> dict:
        worst = np.max(np.abs(self.timing_error), axis=(1, 2))
        i = int(np.argmax(worst))
        return dict(
            speeds=int(self.cam_rpm.size),
            min_cam_rpm=float(self.cam_rpm[0]),
            max_cam_rpm=float(self.cam_rpm[-1]),
            max_drive_torque_N_m=float(self.max_drive_torque.max()),
            max_twist_deg=float(np.degrees(self.max_twist.max())),
            max_timing_error_deg=float(np.degrees(worst[i])),
            max_timing_error_crank_deg=float(np.degrees(worst[i]) * CRANK_PER_CAM),
            max_timing_error_cam_rpm=float(self.cam_rpm[i]),
            first_mode_Hz=float(self.modes_Hz[0]),
            converged=bool(self.converged.all()),
            notes=[]
            if self.converged.all()
            else ["the twist did not converge at every speed (see converged per speed)"],
        )

    def describe(self) -> str:
        rows = []
        for k, r in enumerate(self.cam_rpm):
            rows.append(
                (
                    f"{r:.0f}",
                    f"{self.mean_drive_torque[k]:.3f}",
                    f"{self.min_drive_torque[k]:.2f} / {self.max_drive_torque[k]:.2f}",
                    f"{math.degrees(self.max_twist[k]):.4f}",
                    f"{math.degrees(np.max(np.abs(self.timing_error[k]))):.4f}",
                    f"{self.iterations[k]}" + ("" if self.converged[k] else " (not converged)"),
                )
            )
        return "camshaft over speed\n" + text_table(
            rows,
            headers=(
                "cam rpm",
                "mean torque [N m]",
                "min / max [N m]",
                "max twist [deg]",
                "max timing error [cam deg]",
                "iterations",
            ),
        )

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        dims = ("cam_rpm",)
        data = {
            "mean_drive_torque": (dims, self.mean_drive_torque, {"units": "N*m"}),
            "max_drive_torque": (dims, self.max_drive_torque, {"units": "N*m"}),
            "min_drive_torque": (dims, self.min_drive_torque, {"units": "N*m"}),
            "max_twist": (dims, self.max_twist, {"units": "rad"}),
            "iteration_count": (dims, self.iterations),
        }
        for j, ev in enumerate(EVENTS):
            data[f"{ev}_error"] = (("cam_rpm", "lobe"), self.timing_error[:, :, j], {"units": "rad"})
        return xr.Dataset(
            data, coords={"cam_rpm": (dims, self.cam_rpm, {"units": "rpm"}), "lobe": ("lobe", _labels(self.lobe_names))}
        )

    def _plot(self, ax=None):
        """Each valve's timing errors over speed; above them the drive torque's band."""
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        if ax is None:
            fig, (top, ax) = plt.subplots(2, 1, figsize=(8, 8), sharex=True)
            top.fill_between(self.cam_rpm, self.min_drive_torque, self.max_drive_torque, alpha=0.3, label="min-max")
            top.plot(self.cam_rpm, self.mean_drive_torque, "k-o", ms=3, label="mean")
            top.set_ylabel("drive torque [N m]")
            top.grid(True, alpha=0.3)
            top.legend(fontsize=7)
        else:
            fig = ax.figure
        for i, name in enumerate(self.lobe_names):
            for j, (ev, style) in enumerate(zip(EVENTS, ("-", "--", ":"))):
                ax.plot(
                    self.cam_rpm, np.degrees(self.timing_error[:, i, j]), f"C{i}{style}", lw=1, label=f"{name} {ev}"
                )
        ax.set_xlabel("cam speed [rpm]")
        ax.set_ylabel("timing error [cam deg]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=6, ncol=2)
        return fig
