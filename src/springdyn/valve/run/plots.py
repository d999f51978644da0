"""Plots of the valve-spring analyses (PNG via :func:`springdyn.core.plotting.save_figure`)."""

from __future__ import annotations

import numpy as np
from matplotlib import colormaps
from matplotlib.cm import ScalarMappable
from matplotlib.colors import Normalize

from ...core.plotting import new_figure, save_figure
from ...core.units import rpm_to_hz
from ..cam.timing import CrankAxis

__all__ = ["plot_closure_map", "plot_simulation", "plot_sweep", "plot_sweep_forces"]


def plot_closure_map(sim, path=None, ax=None):
    """Coil-closure map: cam angle x position along the wire, closed (dark) or open.

    Parameters
    ----------
    sim : Simulation
        A simulation of the distributed model.
    path : path-like, optional
        PNG file to write.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.
    """
    model = sim.spring.spring_model
    contact = sim.element_contact[1:-1].astype(float)
    if ax is None:
        fig, ax = new_figure(figsize=(9, 4.5))
    else:
        fig = ax.figure
    deg = sim.cam_angle_deg
    order = np.argsort(deg)
    edges = model.element_turns
    step = 360.0 / deg.size
    ax.pcolormesh(
        np.append(deg[order], deg[order][-1] + step) - step / 2,
        edges,
        contact[:, order],
        shading="flat",
        cmap="Greys",
        vmin=0,
        vmax=1.3,
    )
    ax2 = ax.twinx()
    ax2.plot(deg[order], sim.lift[order] * 1e3, color="C0", lw=1)
    ax2.set_ylabel("cam lift [mm]", color="C0")
    clash = sim.summary.get("clashing_coils") or []
    ax.set_xlabel("cam angle [deg]")
    ax.set_ylabel("position along the wire [turns from the seat]")
    ax.set_ylim(edges[0], edges[-1])
    ax.set_title(
        f"coil closure (dark: closed), {sim.cam_rpm:.0f} cam rpm; clashing coils: "
        + (", ".join(map(str, clash)) if clash else "none")
    )
    if path is not None:
        save_figure(fig, path, close=False)
    return fig


def plot_simulation(sim, path=None, ax=None):
    """Forces vs cam angle (dynamic against static), mass displacements and spectrum.

    With ``ax``, only the force panel is drawn into it.  A chain of more than
    :data:`MAX_LEGEND_MASSES` masses (the distributed model) has its masses coloured by their
    position along the wire (a colour bar) and only its two end masses in the legend.

    Parameters
    ----------
    sim : Simulation
        The simulated revolution.
    path : path-like, optional
        PNG file to write.
    ax : matplotlib.axes.Axes, optional
        Axes for the force panel.
    """
    vt = sim.valve_train is not None
    only_forces = ax is not None
    if only_forces:
        fig, axes = ax.figure, [ax]
    else:
        fig, axes = new_figure(5 if vt else 3, 1, figsize=(9, 15 if vt else 10))
    # crank angles (springdyn.valve.cam.timing) when the run asks for them
    axis = sim.crank_axis if sim.crank_axis is not None else CrankAxis.cam()
    deg = axis.crank_deg(sim.cam_angle_deg)
    order = np.argsort(deg, kind="stable")
    ax = axes[0]
    ax.plot(deg[order], sim.retainer_force[order], color="C0", lw=1.5, label="retainer force (dynamic)")
    ax.plot(deg[order], sim.seat_force[order], color="C1", lw=1.0, label="seat force (dynamic)")
    ax.plot(deg[order], sim.static_force[order], color="k", ls="--", lw=1.2, label="static (massless) force")
    if sim.pack is not None:  # a spring pack: each spring's force at the retainer
        for k, name in enumerate(sim.spring.names):
            force = sim.pack["retainer_force"][k][order]
            ax.plot(deg[order], force, color=f"C{k + 5}", lw=0.9, label=f"{name} spring at the retainer")
    for ev in sim.summary["coil_contact"]:
        for lo, hi in axis.spans(ev["start_deg"], ev["end_deg"]):
            ax.axvspan(lo, hi, color="C3", alpha=0.15)
    if sim.summary["coil_contact"]:
        ax.plot([], [], color="C3", alpha=0.3, lw=6, label="coil contact")
    ax.set_ylabel("force [N]")
    ax.set_title(
        f"{sim.spring.type} spring, {sim.cam.law} cam, {sim.cam_rpm:.0f} cam rpm"
        + (f" ({axis.per_cam * sim.cam_rpm:.0f} engine rpm)" if axis.kind == "crank" else "")
        + f" (revolution {sim.revolutions} of {sim.revolutions})"
    )
    ax.legend(fontsize=8)
    if only_forces:
        ax.set_xlabel(axis.label)
        ax.set_xlim(*axis.limits)
        ax.grid(True, alpha=0.3)
        return fig
    ax2 = ax.twinx()
    ax2.plot(deg[order], sim.lift[order] * 1e3, color="0.6", lw=0.8)
    ax2.set_ylabel("cam lift [mm]", color="0.5")
    _plot_masses(axes[1], sim, deg, order)
    row = 2
    if vt:
        ax = axes[2]
        ax.plot(deg[order], sim.cam_contact_force[order], color="C2", label="cam-follower contact force")
        ax.plot(deg[order], sim.valve_seat_force[order], color="C4", label="valve-seat force")
        for ev in sim.summary["liftoff"]:
            for lo, hi in axis.spans(ev["start_deg"], ev["end_deg"]):
                ax.axvspan(lo, hi, color="C3", alpha=0.2)
        if sim.summary["liftoff"]:
            ax.plot([], [], color="C3", alpha=0.3, lw=6, label="lift-off")
        sm = sim.summary
        ax.set_title(
            f"seat impact velocity {sm['seat_impact_velocity_m_per_s']:.3f} m/s, "
            f"{sm['seat_landings']} landing(s), {sm['bounces']} bounce(s)",
            fontsize=9,
        )
        ax.set_ylabel("force [N]")
        ax.legend(fontsize=8)
        row = 3
    for a in axes[:row]:
        a.set_xlabel(axis.label)
        a.set_xlim(*axis.limits)
        a.grid(True, alpha=0.3)
    if vt:  # valve lift against lobe lift: the train's ratio, lash and elastic deflection
        ax = axes[3]
        t = sim.valve_train
        ax.plot(sim.lift[order] * 1e3, sim.valve_lift[order] * 1e3, color="C0", lw=1, label="valve lift (dynamic)")
        lobe = np.linspace(0.0, float(sim.lift.max()), 50)
        ax.plot(
            lobe * 1e3,
            np.maximum(t.ratio * lobe - t.lash, 0.0) * 1e3,
            "k--",
            lw=1,
            label=f"rigid train: {t.ratio:g} x lobe lift - lash",
        )
        ax.set_xlabel("lobe lift at the follower [mm]")
        ax.set_ylabel("valve lift [mm]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        row = 4
    ax = axes[row]
    orders, amp = sim.spectrum(40)
    ax.bar(orders[1:], amp[1:], color="C0", width=0.7)
    f1_order = sim.summary["f1_cam_order"]
    ax.axvline(f1_order, color="C3", ls="--", label=f"f1 = {sim.summary['f1_Hz']:.0f} Hz (order {f1_order:.1f})")
    ax.set_xlabel("cam order")
    ax.set_ylabel("retainer force amplitude [N]")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    if path is not None:
        save_figure(fig, path, close=False)
    return fig


#: Most masses a chain's displacement panel names one by one in its legend (Type C has 5);
#: a longer chain (the distributed model's) is coloured by position with a colour bar.
MAX_LEGEND_MASSES = 8


def _plot_masses(ax, sim, deg, order):
    """The masses' displacements: a legend for a short chain; for a long one, the chain masses
    coloured by their position along the wire (a colour bar) and the two end masses named."""
    model = sim.spring.spring_model
    names = model.chain.mass_names
    disp = sim.mass_displacement[:, order] * 1e3
    x = deg[order]
    ax.set_ylabel("displacement from set-up [mm]")
    if len(names) <= MAX_LEGEND_MASSES:
        for i, name in enumerate(names):
            ax.plot(x, disp[i], lw=1, label=f"mass {i + 1} ({name})")
        ax.legend(fontsize=8, ncol=3)
        return
    turns = getattr(model, "element_turns", None)  # the distributed model: each mass at an element edge
    if turns is not None and len(turns) == len(names):
        where, label, unit = np.asarray(turns, float), "position along the wire [turns from the seat]", " turns"
    else:
        where, label, unit = np.arange(1.0, len(names) + 1), "mass number (from the seat)", ""
    cmap, norm = colormaps["viridis"], Normalize(float(where[0]), float(where[-1]))
    for i in range(1, len(names) - 1):
        ax.plot(x, disp[i], lw=0.7, color=cmap(norm(where[i])))
    for i, end, style in ((0, "seat-end", dict(color="k", ls="--")), (-1, "retainer-end", dict(color="C3"))):
        ax.plot(x, disp[i], lw=1.8, **style, label=f"{end} mass ({names[i]}, at {where[i]:.2f}{unit})")
    ax.figure.colorbar(ScalarMappable(norm=norm, cmap=cmap), ax=ax, label=label, pad=0.01)
    ax.legend(fontsize=8, loc="upper right", title=f"{len(names)} masses", title_fontsize=8)


def plot_sweep_forces(result, ax=None):
    """Peak and minimum retainer (and seat) forces against speed, with the static values.

    Parameters
    ----------
    result : SpeedSweep
        The sweep.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into.
    """
    table = result.summary_table()
    nv, nr = result.vary_values.size, result.cam_rpm.size
    rpm, speed_label = _speed_axis(result)
    if ax is None:
        fig, ax = new_figure(figsize=(9, 5.5))
    for k in range(nv):
        sl = slice(k * nr, (k + 1) * nr)
        tag = f" ({_vary_label(result, k)})" if result.vary_name else ""
        color = f"C{k % 10}"
        ax.plot(rpm, table["max_retainer_force_N"][sl], color=color, lw=1.6, label=f"max retainer force{tag}")
        ax.plot(rpm, table["min_retainer_force_N"][sl], color=color, lw=1.6, ls="-.", label=f"min retainer force{tag}")
        if nv == 1:
            ax.plot(rpm, table["max_seat_force_N"][sl], color="C1", lw=1, label="max seat force")
            ax.plot(rpm, table["min_seat_force_N"][sl], color="C1", lw=1, ls="-.", label="min seat force")
        ax.plot(
            rpm,
            table["max_static_force_N"][sl],
            color=color,
            ls="--",
            lw=0.8,
            alpha=0.7,
            label="static max / min" if k == 0 else None,
        )
        ax.plot(rpm, table["min_static_force_N"][sl], color=color, ls="--", lw=0.8, alpha=0.7)
    ax.set_xlabel(speed_label)
    ax.set_ylabel("force [N]")
    ax.set_title(f"{result.spring.type} spring, {result.cam.law} cam: forces over the speed range")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    return ax.figure


def plot_sweep(result, out_dir, prefix="sweep"):
    """Peak/min forces vs speed, speed x cam-angle map, Campbell diagram (and contact force).

    Parameters
    ----------
    result : SpeedSweep
        The sweep.
    out_dir : Path
        Folder of the PNG files.
    prefix : str
        File name prefix.
    """
    table = result.summary_table()
    nv, nr = result.vary_values.size, result.cam_rpm.size
    written = [save_figure(plot_sweep_forces(result), out_dir / f"{prefix}_forces.png")]
    if getattr(result.spring, "names", None) is not None:  # a spring pack: each spring's forces and Goodman
        written.append(save_figure(_pack_springs(result), out_dir / f"{prefix}_springs.png"))
    axis = result.crank_axis if result.crank_axis is not None else CrankAxis.cam()
    deg = axis.crank_deg(np.degrees(result.cam_angle))
    order = np.argsort(deg, kind="stable")
    speed, speed_label = _speed_axis(result)
    for k in range(nv):
        suffix = f"_{k}" if nv > 1 else ""
        tag = f", {_vary_label(result, k)}" if result.vary_name else ""
        force = result.data["retainer"][k]
        fig, ax = new_figure(figsize=(9, 5.5))
        mesh = ax.pcolormesh(deg[order], speed, force[:, order], shading="auto", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label="retainer force [N]")
        ax.set_xlabel(axis.label)
        ax.set_ylabel(speed_label)
        ax.set_title(f"retainer force over speed and {axis.kind} angle{tag}")
        written.append(save_figure(fig, out_dir / f"{prefix}_map{suffix}.png"))
        written.append(_campbell(result, k, out_dir / f"{prefix}_campbell{suffix}.png", tag))
    if result.valve_train is not None:
        per_cam = 1.0 if result.crank_axis is None else result.crank_axis.per_cam
        fig, ax = new_figure(figsize=(9, 5))
        for k in range(nv):
            sl = slice(k * nr, (k + 1) * nr)
            ax.plot(
                speed,
                table["min_cam_contact_force_N"][sl],
                color=f"C{k % 10}",
                label="min cam contact force" + (f" ({_vary_label(result, k)})" if result.vary_name else ""),
            )
        for k, f in enumerate(result.float_speeds()):
            if np.isfinite(f):
                ax.axvline(per_cam * f, color=f"C{k % 10}", ls="--", lw=1, label=f"float speed ~ {per_cam * f:.0f} rpm")
        ax.axhline(0, color="k", lw=0.8)
        ax.set_xlabel(speed_label)
        ax.set_ylabel("force [N]")
        ax.set_title("cam-follower contact during the event")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        written.append(save_figure(fig, out_dir / f"{prefix}_contact.png"))
    return written


def _pack_springs(result):
    """A spring pack's sweep, each spring: its retainer force's extremes against its static force's,
    and its Goodman safety (dynamic and static) over the speeds (:meth:`SpeedSweep.spring_table`)."""
    rpm, speed_label = _speed_axis(result)
    nr = len(rpm)
    fig, (ax, ax2) = new_figure(2, 1, figsize=(9, 8), sharex=True)
    for k, name in enumerate(result.spring.names):
        t, color = result.spring_table(name), f"C{k}"
        for j in range(len(t["max_retainer_force_N"]) // nr):  # each value of a design variable
            sl = slice(j * nr, (j + 1) * nr)
            who = name + (f" ({_vary_label(result, j)})" if result.vary_name else "")
            alpha = 1.0 / (1.0 + 0.6 * j)
            ax.plot(rpm, t["max_retainer_force_N"][sl], color=color, alpha=alpha, lw=1.5, label=f"{who}: max / min")
            ax.plot(rpm, t["min_retainer_force_N"][sl], color=color, alpha=alpha, lw=1.5, ls="-.")
            ax.plot(rpm, t["max_static_force_N"][sl], color=color, alpha=alpha, lw=0.8, ls="--", label=f"{who}: static")
            ax.plot(rpm, t["min_static_force_N"][sl], color=color, alpha=alpha, lw=0.8, ls="--")
            ax2.plot(rpm, t["fatigue_safety_factor"][sl], color=color, alpha=alpha, lw=1.5, label=f"{who}: dynamic")
            ax2.plot(
                rpm,
                t["static_fatigue_safety_factor"][sl],
                color=color,
                alpha=alpha,
                lw=0.8,
                ls="--",
                label=f"{who}: static",
            )
    ax.set_ylabel("force [N] at the retainer")
    ax.set_title(f"{result.spring.type}: each spring over the speed range")
    ax2.set_ylabel("Goodman safety [-]")
    ax2.set_xlabel(speed_label)
    for a in (ax, ax2):
        a.grid(True, alpha=0.3)
        a.legend(fontsize=7, ncol=2)
    return fig


def _speed_axis(result):
    """The sweep's speeds and their label: engine speeds when the sweep has crank angles."""
    if result.crank_axis is not None:
        return result.engine_rpm, "engine speed [rpm]"
    return result.cam_rpm, "cam speed [rpm]"


def _vary_label(result, k):
    return result.vary_label(k)


def _campbell(result, k, path, tag, max_order=30):
    spring = result.springs[k]
    rpm = result.cam_rpm
    force = result.data["retainer"][k]
    amp = np.abs(np.fft.rfft(force, axis=1)) * 2.0 / force.shape[1]
    orders = np.arange(1, min(max_order, amp.shape[1] - 1) + 1)
    fig, ax = new_figure(figsize=(9, 6))
    rr, oo = np.meshgrid(rpm, orders, indexing="ij")
    a = amp[:, orders]
    sc = ax.scatter(
        rr.ravel(),
        rpm_to_hz(oo * rr).ravel(),
        c=np.log10(np.maximum(a.ravel(), 1e-3)),
        s=4 + 40 * (a.ravel() / a.max()),
        cmap="magma_r",
    )
    fig.colorbar(sc, ax=ax, label="log10 retainer-force harmonic amplitude [N]")
    for o in orders[::5]:
        ax.annotate(f"{o}", (rpm[-1], rpm_to_hz(o * rpm[-1])), fontsize=7, color="0.4")
    f_inst = float(spring.spring_model.modes(spring.installed_length, 1)[0])
    ax.axhline(f_inst, color="C0", lw=1.5, label=f"f1 at installed length {f_inst:.0f} Hz")
    open_len = spring.installed_length - result.cam.max_lift
    if open_len >= spring.spring_model.min_length:
        f_open = float(spring.spring_model.modes(open_len, 1)[0])
        ax.axhline(f_open, color="C3", lw=1.5, ls="--", label=f"f1 at open length {f_open:.0f} Hz")
    ax.set_ylim(0, max(2.5 * f_inst, 1.0))
    ax.set_xlabel("cam speed [rpm]")
    ax.set_ylabel("frequency [Hz]")
    ax.set_title(f"Campbell diagram: cam-order harmonics of the retainer force{tag}")
    ax.legend(fontsize=8, loc="upper left")
    return save_figure(fig, path)
