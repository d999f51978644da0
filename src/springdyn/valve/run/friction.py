"""The friction of a run: a simulated valve train's friction over its revolution, and over speed.

The friction laws and the kinematic computation along the cam are the train wing's
(:mod:`springdyn.valve.train.friction`, :func:`~springdyn.valve.train.friction.friction_along_cam`);
here they are fed with a simulation's motion and contact forces (:func:`simulation_friction`,
with the loads of :func:`train_friction_loads`), and the analyses of several speeds are
gathered into a :class:`FrictionSweep` (:func:`friction_over_speed`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core.errors import InputError
from ...core.results import Result, notes_lines, text_table
from ...core.units import rpm_to_omega
from ..train.friction import CONTACTS, Friction, FrictionAnalysis, friction_along_cam

__all__ = ["train_friction_loads", "simulation_friction", "friction_over_speed", "FrictionSweep"]

_TWO_PI = 2.0 * math.pi


def train_friction_loads(sim, friction: Friction) -> dict:
    """The loads of a simulated valve train that :func:`friction_along_cam` needs.

    - valve velocity: the periodic central difference of the simulated valve lift;
    - the stem's side load: the lever's pad sliding on the stem tip pushes the stem sideways
      with its friction, ``mu_b F_tip`` (``F_tip = F_cam / r`` by virtual work; a bucket
      tappet carries its cam friction in its bore: no side load);
    - the pivot's load: an adjuster's socket force when it has ``[hla]`` dynamics; else the
      end-pivot finger's ``F_cam (1 - 1/r)`` (``layout = "rocker"``, the pivot on one side of
      the roller) or the pushrod rocker's centre pivot ``F_cam (1 + 1/r)``; the lever arm
      from the pivot to the cam side (a drawn lever's roller arm, else the valve arm over the
      ratio).

    Parameters
    ----------
    sim : Simulation
        A valve-train simulation (:func:`springdyn.valve.simulate`).
    friction : Friction
        The ``[friction]`` table.

    Returns
    -------
    dict
        Keyword arguments of :func:`friction_along_cam` (``valve_velocity``, ``ratio``,
        ``side_load``, ``pivot_force``, ``lever_arm``).
    """
    vt = sim.valve_train
    if vt is None or sim.cam_contact_force is None:
        raise InputError("friction needs a valve train: simulate the spring with its [valve_train]")
    n = sim.cam_angle.size
    dt = _TWO_PI / (n * rpm_to_omega(sim.cam_rpm))
    z = sim.valve_lift
    velocity = (np.roll(z, -1) - np.roll(z, 1)) / (2.0 * dt)
    force = np.maximum(sim.cam_contact_force, 0.0)
    r = vt.ratio
    out = dict(valve_velocity=velocity, ratio=r)
    if vt.layout == "direct-acting":
        return out
    out["side_load"] = friction.boundary_friction * force / r
    if vt.hla is not None and sim.hla is not None:
        out["pivot_force"] = np.maximum(sim.hla["socket_force"], 0.0)
    elif vt.layout == "rocker":
        out["pivot_force"] = force * abs(1.0 - 1.0 / r)
    else:
        out["pivot_force"] = force * (1.0 + 1.0 / r)
    out["lever_arm"] = vt.geometry.geometry.roller_arm() if vt.geometry is not None else vt.rocker_valve_arm / r
    return out


def simulation_friction(sim, follower, friction: Friction | None = None) -> FrictionAnalysis:
    """Friction of a simulated valve train over its last (periodic) revolution: the lobe, the
    simulated cam contact force and the loads of :func:`train_friction_loads` through
    :func:`friction_along_cam`.

    The contact kinematics are those of the lobe's translating follower (a lever's roller
    meets the lobe a few degrees off; its rolling speed differs by the lever's rotation).

    Parameters
    ----------
    sim : Simulation
        A valve-train simulation.
    follower : Follower
        The ``[follower]`` table (the bucket, the lever's roller or pad, the lifter).
    friction : Friction, optional
        The ``[friction]`` table (default: its defaults).
    """
    friction = Friction() if friction is None else friction
    theta = sim.cam_angle
    h, dh, ddh = sim.cam.evaluate(theta)
    omega = rpm_to_omega(sim.cam_rpm)
    res = friction_along_cam(
        theta,
        float(omega),
        h,
        dh,
        ddh,
        np.maximum(sim.cam_contact_force, 0.0),
        follower,
        friction,
        **train_friction_loads(sim, friction),
    )
    if sim.periodic is False:
        res.notes.append(
            f"the simulation at {sim.cam_rpm:g} cam rpm did not settle: its friction is one revolution of a transient"
        )
    return res


def friction_over_speed(analyses) -> FrictionSweep:
    """Friction power and mean drive torque over speed from per-speed analyses.

    Parameters
    ----------
    analyses : sequence of FrictionAnalysis
        One per cam speed (:func:`friction_along_cam`).
    """
    items = sorted(analyses, key=lambda a: a.omega)
    if not items or not all(isinstance(a, FrictionAnalysis) for a in items):
        raise InputError("friction_over_speed needs one or more FrictionAnalysis results (friction_along_cam)")
    rpm = np.array([a.cam_rpm for a in items])
    if np.any(np.diff(rpm) <= 0):
        raise InputError("friction_over_speed needs one analysis per cam speed (two share a speed)")
    power = {k: np.array([a.summary[f"friction_power_{k}_W"] for a in items]) for k in CONTACTS}
    torque = np.array([a.summary["mean_drive_torque_N_m"] for a in items])
    return FrictionSweep(
        cam_rpm=rpm, power=power, mean_drive_torque=torque, follower=items[0].follower.kind, analyses=tuple(items)
    )


@dataclass(repr=False)
class FrictionSweep(Result):
    """Friction power per contact and mean drive torque over cam speed (:func:`friction_over_speed`)."""

    cam_rpm: np.ndarray
    power: dict  # contact -> mean friction power [W]
    mean_drive_torque: np.ndarray  # [N m]
    follower: str = ""
    #: The per-speed analyses (their drive torque over the cam angle goes into the outputs).
    analyses: tuple = ()

    title = "valve-train friction over speed"
    cheap_plot = True

    def describe(self, train: str = "", friction_given: bool = True) -> str:
        """Per speed the drive torque and each contact's friction power, the energy balance of
        the top speed's revolution (what ``springdyn valve friction`` prints).

        Parameters
        ----------
        train : str
            The valve train's layout, for the first line [-].
        friction_given : bool
            Whether a ``[friction]`` table was given (else its defaults were used) [-].
        """
        out = [
            f"valve-train friction, {self.follower} follower"
            + (f", {train} train" if train else "")
            + ("" if friction_given else " ([friction] not given: its defaults)")
        ]
        rows = []
        for a in self.analyses:
            m = a.summary
            rows.append(
                (
                    f"{m['cam_rpm']:.0f}",
                    f"{m['mean_drive_torque_N_m']:.3f}",
                    f"{m['min_drive_torque_N_m']:.2f} / {m['max_drive_torque_N_m']:.2f}",
                    f"{m['friction_power_W']:.2f}",
                    f"{m['friction_power_cam_W']:.2f}",
                    f"{m['friction_power_roller_bearing_W']:.2f}",
                    f"{m['friction_power_guide_W']:.2f}",
                    f"{m['friction_power_pivot_W']:.2f}",
                    f"{m.get('min_film_parameter', float('nan')):.3g}",
                    "-"
                    if "slip_share_loaded" not in m or m["slip_share_loaded"] is None
                    else f"{m['slip_share_loaded']:.1%}",
                )
            )
        out.append(
            text_table(
                rows,
                headers=(
                    "cam rpm",
                    "mean torque [N m]",
                    "min / max [N m]",
                    "friction [W]",
                    "cam",
                    "roller bearing",
                    "guide",
                    "pivot",
                    "min lambda",
                    "roller slip",
                ),
            )
        )
        last = self.analyses[-1].summary
        friction_j = sum(last[f"dissipated_{k}_J"] for k in CONTACTS)
        out.append(
            f"energy of a revolution at {last['cam_rpm']:.0f} rpm: cam work {last['cam_work_J']:.4g} J = friction "
            f"{friction_j:.4g} J + the train's dampers and elastic change {last['load_work_J']:.4g} J "
            f"(residual {last['energy_residual_J']:.2g} J)"
        )
        return "\n".join(out + notes_lines(self.summary))

    @property
    def total_power(self) -> np.ndarray:
        """Total friction power over speed [W]."""
        return sum(self.power.values())

    def _summary(self) -> dict:
        total = self.total_power
        i = int(np.argmax(total))
        return dict(
            follower=self.follower,
            speeds=int(self.cam_rpm.size),
            min_cam_rpm=float(self.cam_rpm[0]),
            max_cam_rpm=float(self.cam_rpm[-1]),
            max_friction_power_W=float(total[i]),
            max_friction_power_cam_rpm=float(self.cam_rpm[i]),
            mean_drive_torque_at_min_speed_N_m=float(self.mean_drive_torque[0]),
            mean_drive_torque_at_max_speed_N_m=float(self.mean_drive_torque[-1]),
            notes=list(dict.fromkeys(n for a in self.analyses for n in a.summary.get("notes", []))),
        )

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        dims = ("cam_rpm",)
        data = {f"friction_power_{k}": (dims, self.power[k], {"units": "W"}) for k in CONTACTS}
        data["friction_power"] = (dims, self.total_power, {"units": "W"})
        data["mean_drive_torque"] = (dims, self.mean_drive_torque, {"units": "N*m"})
        coords = {"cam_rpm": (dims, self.cam_rpm, {"units": "rpm"})}
        if self.analyses and len({a.cam_angle.size for a in self.analyses}) == 1:
            torque = np.stack([a.drive_torque for a in self.analyses])
            data["drive_torque"] = (("cam_rpm", "cam_angle"), torque, {"units": "N*m"})
            coords["cam_angle"] = ("cam_angle", np.degrees(self.analyses[0].cam_angle), {"units": "deg"})
        return xr.Dataset(data, coords=coords)

    def _plot(self, ax=None):
        """Friction power per contact and in total over cam speed."""
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        if ax is None and self.analyses:
            fig, (top, ax) = plt.subplots(2, 1, figsize=(8, 8))
            for i, a in enumerate(self.analyses):
                top.plot(
                    np.degrees(a.cam_angle),
                    a.drive_torque,
                    color=plt.cm.viridis(i / max(len(self.analyses) - 1, 1)),
                    lw=0.9,
                    label=f"{a.cam_rpm:.0f} rpm",
                )
            top.set_xlabel("cam angle [deg]")
            top.set_ylabel("camshaft drive torque [N m]")
            top.grid(True, alpha=0.3)
            top.legend(fontsize=6, ncol=2)
        else:
            fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(7, 4.5))
        ax.plot(self.cam_rpm, self.total_power, "k-o", ms=3, label="total")
        for i, k in enumerate(CONTACTS):
            if np.any(self.power[k]):
                ax.plot(self.cam_rpm, self.power[k], f"C{i}-", label=k.replace("_", " "))
        ax.set_xlabel("cam speed [rpm]")
        ax.set_ylabel("friction power [W]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
        return fig
