"""Result objects of the valve-spring analyses, on the shared :class:`~springdyn.core.results.Result`.

:class:`Simulation` (one simulated revolution under cam drive, with its summary),
:class:`FloatSpeedResult`, :class:`NaturalFrequencies` (the spring and train under the cam);
the spring's own :class:`~springdyn.valve.spring.results.StaticCurve` is in the spring wing.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ...core.errors import InputError
from ...core.results import Result, dataset_columns, notes_lines, text_table, units_from_name
from ...core.units import rpm_to_hz
from ..cam.timing import CrankAngles
from ..spring.elements import law_force
from ..spring.results import coil_line
from . import verdicts
from .periodicity import PERIODICITY_TOL, is_periodic
from .separation import cam_phases, liftoffs, phase_mask
from .train_modes import resonance_speeds

__all__ = ["Simulation", "FloatSpeedResult", "NaturalFrequencies"]


@dataclass(repr=False)
class Simulation(CrankAngles, Result):
    """The last simulated revolution and its summary (SI; angles in rad, ``*_deg`` in degrees)."""

    spring: object  # ValveSpring
    cam: object  # Cam
    valve_train: object  # ValveTrain or None
    cam_rpm: float
    revolutions: int
    time: np.ndarray  # [s]
    cam_angle: np.ndarray  # [rad], within the revolution
    lift: np.ndarray  # [m]
    retainer_force: np.ndarray  # [N]
    seat_force: np.ndarray  # [N]
    static_force: np.ndarray  # [N]
    element_compression: np.ndarray  # (6, n) [m]
    element_force: np.ndarray  # (6, n) [N]
    element_contact: np.ndarray  # (6, n) bool
    mass_displacement: np.ndarray  # (5, n) [m]
    #: Largest change of the seat, retainer, cam-contact and valve-seat forces from the
    #: revolution before, on the output grid [fraction of Fset] (nan after one revolution).
    periodicity_error: float
    info: dict
    valve_lift: np.ndarray | None = None  # [m]
    cam_contact_force: np.ndarray | None = None  # [N]
    valve_seat_force: np.ndarray | None = None  # [N]
    #: Monitor outputs of the compiled engine (true extremes and located events of the
    #: last revolution from the dense output); ``None`` for the SciPy reference.
    monitor: dict | None = None
    #: Distributed model with coil clash: the peak forces of the same run with half the
    #: elements (``elements``, ``max_retainer_force_N``, ``max_seat_force_N``), see
    #: :func:`springdyn.valve.simulate`.
    element_check: dict | None = None
    #: Coil-bind figures of the cam's largest lift (:func:`springdyn.valve.spring.solid_length.check_coil_bind`).
    coil_bind: dict | None = None
    #: The tolerance [fraction of Fset] on ``periodicity_error`` under which the last
    #: revolution is the periodic steady state (None: :data:`springdyn.valve.run.periodicity.PERIODICITY_TOL`).
    periodicity_tol: float | None = None
    #: The signed cam-contact gap on the output grid [m] (positive in contact; valve train).
    cam_gap: np.ndarray | None = None
    #: A train on a hydraulic lash adjuster (``[hla]``): ``collapse`` [m, from the base-circle
    #: position], ``pressure`` [Pa above the supply], ``socket_force`` [N], ``inflow`` and
    #: ``leak`` (oil volumes through the check valve and the clearance since the run's start,
    #: m^3) on the output grid.
    hla: dict | None = None
    #: The cylinder's gas force on the valve on the output grid [N] (towards the seat;
    #: :mod:`springdyn.valve.train.gas_force`), None without one.
    gas_force: np.ndarray | None = None
    #: A run that did not settle (``periodic`` False after the most revolutions): each
    #: extreme's smallest and largest value over the last revolutions, name -> (lo, hi)
    #: (names of :data:`springdyn.valve.engine.EXT`); None when periodic.
    band: dict | None = None
    #: Notes on how the run was asked for (a speed beyond reason computed on request).
    flags: list = dataclasses.field(default_factory=list)
    #: Crank angles beside the cam angles in the outputs and plots: a
    #: :class:`~springdyn.valve.cam.timing.CrankAxis` (:func:`~springdyn.valve.cam.timing.crank_axis`),
    #: None for cam angles only (the CLI sets it for an engine speed or a ``[timing]`` table).
    crank_axis: object = None
    #: A spring pack's outputs (:class:`~springdyn.valve.spring.pack.SpringPack`): each spring's
    #: ``retainer_force`` and ``seat_force`` (springs, samples) [N], the first friction
    #: damper's ``damper_force`` [N] and ``damper_slip`` [m/s], the chains' ``dissipation`` [W]
    #: (their elements' damping and every damper); None for one spring.
    pack: dict | None = None

    #: Change of the peak end forces with twice the elements [fraction of Fset] above which
    #: the clash forces are flagged as not converged.
    ELEMENT_TOL = 0.01
    title = "valve spring simulation"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.spring.type} spring, {self.cam.law} cam, {self.cam_rpm:g} cam rpm"

    @property
    def cam_angle_deg(self) -> np.ndarray:
        return np.degrees(self.cam_angle)

    @cached_property
    def contact_share(self) -> np.ndarray:
        """The force [N] each element's closed coils pass through their contact over the
        revolution (:meth:`SpringModel.contact_share`; NaN for an element that is no wire)."""
        model = self.spring.spring_model
        x = self.element_compression
        return model.contact_share(np.stack([law_force(x[j], law) for j, law in enumerate(model.chain.laws)]))

    @property
    def periodic(self) -> bool | None:
        """Whether the last revolution repeats the one before within ``periodicity_tol``
        (``None`` after a single revolution: there is nothing to compare with)."""
        return is_periodic(self.periodicity_error, self.periodicity_tol)

    # ------------------------------------------------------------------ summary
    def _summary(self) -> dict:
        """Peak forces, ratios to static, surge, coil-contact and lift-off events, spectrum;
        with a :attr:`crank_axis`, every event's crank angles beside its cam angles."""
        s = _summarise(self)
        if self.crank_axis is not None:
            _add_crank_angles(s, self.crank_axis)
        return s

    def describe(self) -> str:
        """The run in words and a table (what ``springdyn valve simulate`` prints): periodicity,
        forces against static, surge, coil contact and clash, end separation, lift-off and
        float, the adjuster, seat impact, fatigue and wire stress, and every note."""
        s = self.summary
        vt = self.valve_train

        def angles(ev):  # an event's cam angles, and its crank angles when the run has them
            text = f"{ev['start_deg']:.2f}-{ev['end_deg']:.2f} cam deg"
            if "start_timing" in ev:
                return f"{text} ({ev['start_timing']} to {ev['end_timing']})"
            if "start_crank_deg" in ev:
                return f"{text} ({ev['start_crank_deg']:.1f}-{ev['end_crank_deg']:.1f} crank deg)"
            return text

        if s["periodicity_error"] is None:
            period = "periodicity n/a (1 revolution)"
        else:
            period = (
                f"{'periodic' if s['periodic'] else 'NOT periodic'}: {100 * s['periodicity_error']:.2f} % of Fset "
                "change from the revolution before"
            )
        out = [
            f"{self.spring.type} spring, {self.cam.law} cam at {self.cam_rpm:g} cam rpm, last of {s['revolutions']} "
            f"revolutions ({period})",
            coil_line(s["spring"]),
        ]
        rows = [
            (
                "retainer force",
                *(f"{v:.1f}" for v in (s["max_retainer_force_N"], s["min_retainer_force_N"])),
                f"{s['max_retainer_force_ratio']:.3f}",
                f"{s['retainer_surge_amplitude_N']:.1f}",
            ),
            (
                "seat force",
                *(f"{v:.1f}" for v in (s["max_seat_force_N"], s["min_seat_force_N"])),
                f"{s['max_seat_force_ratio']:.3f}",
                f"{s['seat_surge_amplitude_N']:.1f}",
            ),
            ("static force", f"{s['max_static_force_N']:.1f}", f"{s['min_static_force_N']:.1f}", "1", "0"),
        ]
        out.append(text_table(rows, headers=("", "max [N]", "min [N]", "max/static", "surge [N]")))
        if "band" in s:
            b = s["band"]
            out.append(
                "did not settle: over the last revolutions the extremes scatter: max retainer "
                f"{b['max_retainer_force_N'][0]:.1f}-{b['max_retainer_force_N'][1]:.1f} N, min retainer "
                f"{b['min_retainer_force_N'][0]:.1f}-{b['min_retainer_force_N'][1]:.1f} N, max seat "
                f"{b['max_seat_force_N'][0]:.1f}-{b['max_seat_force_N'][1]:.1f} N"
                + (
                    f", seat impact velocity {b['seat_impact_velocity_m_per_s'][0]:.2f}-"
                    f"{b['seat_impact_velocity_m_per_s'][1]:.2f} m/s"
                    if vt is not None
                    else ""
                )
            )
        out.append(
            f"f1 = {s['f1_Hz']:.1f} Hz = cam order {s['f1_cam_order']:.2f}; strongest harmonics: "
            + ", ".join(
                f"{h['order']}: {h['amplitude_N']:.1f} N"
                for h in sorted(s["spectrum"], key=lambda h: -h["amplitude_N"])[:4]
            )
        )
        for ev in s["coil_contact"]:
            els = ev["elements"]
            where = ", ".join(els) if len(els) <= 4 else f"{len(els)} elements, from {els[0]} to {els[-1]}"
            out.append(
                f"coil contact {angles(ev)} in {where} (element number:name from the "
                f"seat), peak element force {ev['peak_contact_force_N']:.1f} N"
                + (
                    f", closing where the static spring is open (severity {100 * ev['clash_severity']:.1f} % of Fset)"
                    if ev.get("dynamic_closing")
                    else ""
                )
            )
        if not s["coil_contact"]:
            out.append("no coil contact")
        if "clashing_coils" in s:
            out.append(
                "coils closing where the static spring is open (from the seat): "
                + (", ".join(map(str, s["clashing_coils"])) or "none")
            )
        out.append(_clash_text(s["coil_clash"]))
        for ev in s["end_separation"]:
            out.append(f"END SEPARATION at the {ev['end']} {angles(ev)} ({ev['duration_s'] * 1e3:.3f} ms)")
        if vt is not None:
            out += _train_lines(s, angles)
        if self.pack is not None:
            out += _pack_lines(s)
            return "\n".join(out + notes_lines(s))
        fs, fd = s["static_fatigue_safety_factor"], s["fatigue_safety_factor"]
        out.append(
            "fatigue safety factor (Goodman): static "
            + (f"{fs:.2f}" if fs is not None else "-")
            + ", dynamic "
            + (f"{fd:.2f}" if fd is not None else "-")
            + f" (element {s['fatigue_critical_element']}, {s['min_shear_stress_Pa'] / 1e6:.0f}-"
            f"{s['max_shear_stress_Pa'] / 1e6:.0f} MPa)"
            + (f"; smallest coil gap {s['min_coil_gap_m'] * 1e3:.3f} mm" if s.get("min_coil_gap_m") is not None else "")
        )
        out.append(
            f"wire stress (torsion only; {s['max_force_through_coil_contact_N']:.1f} N passed through coil contact at "
            f"most): peak {s['peak_shear_stress_Pa'] / 1e6:.0f} MPa in element {s['peak_shear_stress_element']}, limit "
            f"{s['shear_stress_limit_Pa'] / 1e6:.0f} MPa: " + ("ok" if s["wire_stress_ok"] else "OVERSTRESS")
        )
        return "\n".join(out + notes_lines(s))

    def spectrum(self, max_order: int = 40):
        """Cam-order harmonics of the retainer force: orders and amplitudes [N] (order 0: mean).

        Parameters
        ----------
        max_order : int
            Highest cam order [-].
        """
        n = self.retainer_force.size
        coef = np.fft.rfft(self.retainer_force) / n
        amp = np.abs(coef) * 2.0
        amp[0] /= 2.0
        k = np.arange(amp.size)
        keep = k <= max_order
        return k[keep], amp[keep]

    # ------------------------------------------------------------------ outputs
    def columns(self) -> dict:
        """The CSV columns (derived from :meth:`to_xarray`)."""

        return dataset_columns(self.to_xarray())

    def to_xarray(self):
        """The time series as an :class:`xarray.Dataset` over ``cam_angle`` [deg]."""
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        dims = ("cam_angle",)
        enames = list(self.spring.spring_model.chain.element_names)
        mnames = list(self.spring.spring_model.chain.mass_names)

        def per_element(what):
            return ",".join(f"element{j + 1}_{n}_{what}" for j, n in enumerate(enames))

        data = {
            "lift": (dims, self.lift, {"units": "m", "long_name": "cam lift"}),
            "retainer_force": (dims, self.retainer_force, {"units": "N"}),
            "seat_force": (dims, self.seat_force, {"units": "N"}),
            "static_force": (dims, self.static_force, {"units": "N", "long_name": "static (massless) spring force"}),
        }
        if self.valve_train is not None:
            data.update(
                valve_lift=(dims, self.valve_lift, {"units": "m"}),
                cam_contact_force=(dims, self.cam_contact_force, {"units": "N"}),
                valve_seat_force=(dims, self.valve_seat_force, {"units": "N"}),
            )
        if self.gas_force is not None:
            data.update(gas_force=(dims, self.gas_force, {"units": "N", "long_name": "gas force on the valve"}))
        if self.pack is not None:
            for k, name in enumerate(self.spring.names):
                data[f"{name}_retainer_force"] = (dims, self.pack["retainer_force"][k], {"units": "N"})
                data[f"{name}_seat_force"] = (dims, self.pack["seat_force"][k], {"units": "N"})
            data.update(
                damper_force=(dims, self.pack["damper_force"], {"units": "N", "long_name": "friction damper force"}),
                damper_slip=(dims, self.pack["damper_slip"], {"units": "m/s", "long_name": "friction damper slip"}),
                dissipation=(dims, self.pack["dissipation"], {"units": "W", "long_name": "power dissipated"}),
            )
        if self.hla is not None:
            data.update(
                hla_collapse=(dims, self.hla["collapse"], {"units": "m"}),
                hla_pressure=(
                    dims,
                    self.hla["pressure"],
                    {"units": "Pa", "long_name": "chamber pressure above the supply"},
                ),
                socket_force=(dims, self.hla["socket_force"], {"units": "N"}),
            )
        data.update(
            {
                "element_compression": (
                    ("element",) + dims,
                    self.element_compression,
                    {"units": "m", "csv_columns": per_element("compression_m")},
                ),
                "element_force": (
                    ("element",) + dims,
                    self.element_force,
                    {"units": "N", "csv_columns": per_element("force_N")},
                ),
                "element_contact": (
                    ("element",) + dims,
                    self.element_contact.astype(np.int8),
                    {"units": "1", "long_name": "element in coil contact", "csv_columns": per_element("contact")},
                ),
                "mass_displacement": (
                    ("mass",) + dims,
                    self.mass_displacement,
                    {
                        "units": "m",
                        "long_name": "displacement from set-up, towards the seat",
                        "csv_columns": ",".join(f"mass{i + 1}_{n}_displacement_m" for i, n in enumerate(mnames)),
                    },
                ),
            }
        )
        return xr.Dataset(
            data,
            coords={
                "time": (dims, self.time, {"units": "s"}),
                "cam_angle": (dims, self.cam_angle_deg, {"units": "deg"}),
                **(
                    {"crank_angle": (dims, self.crank_axis.crank_deg(self.cam_angle_deg), {"units": "deg"})}
                    if self.crank_axis is not None
                    else {}
                ),
                "element": enames,
                "mass": mnames,
            },
            attrs={
                "cam_rpm": self.cam_rpm,
                "revolutions": self.revolutions,
                "spring_type": self.spring.type,
                "model": getattr(self.spring, "model", "type-c"),
                "cam_law": self.cam.law,
                "periodicity_error": (
                    self.periodicity_error if np.isfinite(self.periodicity_error) else "n/a (1 revolution)"
                ),
            },
        )

    def _plot(self, ax=None):
        """Forces vs cam angle (dynamic against static), mass displacements, spectrum."""
        from .plots import plot_simulation  # (here: matplotlib costs 0.3 s of start-up)

        return plot_simulation(self, ax=ax)

    def plot_closure_map(self, path=None, ax=None):
        """Coil-closure map of the distributed model (cam angle x position along the wire).

        Parameters
        ----------
        path : path-like, optional
            PNG file to write.
        ax : matplotlib.axes.Axes, optional
            Axes to draw into.
        """
        from .plots import plot_closure_map  # (here: matplotlib costs 0.3 s of start-up)

        if not hasattr(self.spring.spring_model, "element_positions"):
            raise InputError(
                'the coil-closure map needs the distributed model (model = "distributed"): Type C has no coil geometry'
            )
        return plot_closure_map(self, path, ax)


def _train_lines(s: dict, angles) -> list[str]:
    """The valve train's lines of :meth:`Simulation.describe`: lift-off and float, the gas
    force, the adjuster, the seat impact."""
    out = []
    if s["liftoff"]:
        for ev in s["liftoff"]:
            gap = f", gap {ev['max_gap_m'] * 1e3:.3f} mm" if "max_gap_m" in ev else ""
            out.append(f"LIFT-OFF {angles(ev)} ({ev['duration_s'] * 1e3:.3f} ms{gap}) on the {ev['phase']}")
        out.append(
            "FLOAT: the valve leaves the cam over the nose"
            if s["nose_separation"]
            else "bounce only: the valve stays on the cam over the nose (no float)"
        )
    else:
        out.append(f"no lift-off: minimum cam contact force {s['min_cam_contact_force_N']:.1f} N")
    if "max_gas_force_N" in s:
        out.append(
            f"gas force on the valve: up to {s['max_gas_force_N']:.0f} N, {s['gas_force_at_opening_N']:.0f} N as it "
            "leaves its seat"
        )
    if "hla" in s:
        h = s["hla"]
        out.append(
            f"hydraulic lash adjuster: collapse {h['collapse_min_m'] * 1e6:.1f} to {h['collapse_max_m'] * 1e6:.1f} um, "
            f"length change {h['length_change_per_revolution_m'] * 1e6:+.3f} um per revolution, chamber up to "
            f"{h['peak_pressure_Pa'] / 1e5:.1f} bar above the supply; oil in {h['inflow_per_revolution_m3'] * 1e9:.4f}, "
            f"out {h['leak_per_revolution_m3'] * 1e9:.4f} mm^3 per revolution"
            + (f"; valve held open {h['valve_held_open_m'] * 1e3:.3f} mm" if h["pump_up"] else "")
            + (f"; socket hop {h['socket_hop_deg']:.1f} deg" if h["socket_hop"] else "")
        )
    out.append(
        f"seat impact velocity {s['seat_impact_velocity_m_per_s']:.3f} m/s, bounces {s['bounces']}, "
        f"max bounce {s['max_bounce_height_m'] * 1e3:.3f} mm"
    )
    return out


def _ranges(mask: np.ndarray) -> list[tuple[int, int]]:
    """Index ranges [start, end] of runs of True in a periodic boolean array."""
    if not mask.any():
        return []
    if mask.all():
        return [(0, mask.size - 1)]
    m = mask.astype(np.int8)
    d = np.diff(np.concatenate([[0], m, [0]]))
    starts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1) - 1
    runs = list(zip(starts.tolist(), ends.tolist()))
    if len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == mask.size - 1:  # wraps through 0 deg
        runs = [(runs[-1][0], runs[0][1])] + runs[1:-1]
    return runs


def _tol(sim) -> float:
    return PERIODICITY_TOL if sim.periodicity_tol is None else sim.periodicity_tol


def located_events(sim: Simulation) -> dict:
    """Events of the last revolution located on the dense output, as cam-angle intervals.

    Returns
    -------
    dict
        ``(kind, index) -> [(start_deg, end_deg, duration_deg), ...]`` for the interval
        events (0 end separation with index 0 seat / 1 retainer, 1 coil contact of element
        ``index``, 2 lift-off), and ``"landings"``: ``[(angle_deg, impact_velocity_m_per_s)]``.
        An interval that runs through the revolution's start is one wrapped interval
        (``end_deg < start_deg``); one that lasts the whole revolution is ``(0, 360, 360)``.
    """
    mon = sim.monitor
    if mon is None:
        return {"landings": []}
    return locate_intervals(mon["events"], mon["omega"], mon["t0"])


def locate_intervals(events: np.ndarray, omega: float, t0: float) -> dict:
    """The monitor's event rows of one revolution as cam-angle intervals (see :func:`located_events`).

    Parameters
    ----------
    events : ndarray (rows, 4)
        The located events ``kind, index, t_start, t_end`` (:data:`springdyn.valve.engine.EVENT_KINDS`).
    omega : float
        Cam speed [rad/s].
    t0 : float
        Start of the revolution [s].
    """
    out: dict = {"landings": []}
    period = 2 * np.pi / omega

    def deg(t):
        return float(np.degrees(omega * (t - t0)))

    chans: dict = {}
    for kind, index, ts, te in events:
        if kind == 3:
            out["landings"].append((deg(ts), float(te)))
            continue
        chans.setdefault((int(kind), int(index)), []).append((ts, te))
    for key, rows in chans.items():
        at_start = [r for r in rows if r[0] == t0]
        open_end = [r for r in rows if not np.isfinite(r[1])]
        ivals = []
        for ts, te in rows:
            if ts == t0 and not np.isfinite(te):
                ivals.append((0.0, 360.0, 360.0))
            elif ts == t0 and open_end:
                continue  # joined with the interval open at the end
            elif not np.isfinite(te):
                end = at_start[0][1] if at_start else t0 + period
                ivals.append(
                    (deg(ts), deg(end) % 360.0, (end + (period if at_start else 0.0) - ts) * omega * 180 / np.pi)
                )
            else:
                ivals.append((deg(ts), deg(te), (te - ts) * omega * 180 / np.pi))
        out[key] = sorted(ivals)
    return out


def _angle_mask(deg: np.ndarray, start: float, end: float) -> np.ndarray:
    if start <= end:
        return (deg >= start) & (deg <= end)
    return (deg >= start) | (deg <= end)


def _union(ivals: list) -> list:
    """Union of cam-angle intervals (wrapped ones unrolled past 360 deg)."""
    spans = sorted((s, e if e >= s else e + 360.0) for s, e, _ in ivals)
    merged: list = []
    for s, e in spans:
        if merged and s <= merged[-1][1]:
            merged[-1][1] = max(merged[-1][1], e)
        else:
            merged.append([s, e])
    return merged


#: Summary lists of events with ``start_deg``/``end_deg`` cam angles (crank angles added
#: beside them by :func:`_add_crank_angles`).
EVENT_LISTS = ("coil_contact", "end_separation", "liftoff")


def _add_crank_angles(s: dict, axis) -> None:
    """``start_crank_deg``/``end_crank_deg`` (and timing words from TDC) beside the cam angles."""
    s["crank_angle_origin"] = "gas-exchange TDC" if axis.referenced else "cam angle 0 (no [timing] table)"
    for key in EVENT_LISTS:
        for ev in s.get(key, []):
            ev["start_crank_deg"] = axis.crank_deg(ev["start_deg"])
            ev["end_crank_deg"] = axis.crank_deg(ev["end_deg"])
            if axis.referenced:
                ev["start_timing"], ev["end_timing"] = axis.words(ev["start_deg"]), axis.words(ev["end_deg"])


#: Length change of the adjuster per revolution [m] above which its figures are flagged as
#: not settled: a tenth of a micrometre (its leak-down per cycle is some 0.3 um at 1000 cam
#: rpm); the periodicity channel of the adjuster's length (``CHK_HLA``) judges it as well.
HLA_CREEP_TOL = 0.1e-6


def _hla_summary(sim: Simulation, notes: list) -> dict:
    """The adjuster over the last revolution: its collapse and length change, pressure, the
    oil volumes in and out (their balance), socket hop and pump-up (:mod:`springdyn.valve.train.hla`)."""
    h, vt = sim.hla, sim.valve_train
    hla = vt.hla
    n = sim.time.size
    per_rev = n / (n - 1.0)  # the grid's last sample is one step before the revolution's end
    inflow = float(h["inflow"][-1] - h["inflow"][0]) * per_rev
    leak = float(h["leak"][-1] - h["leak"][0]) * per_rev
    change = float(h["collapse"][-1] - h["collapse"][0]) * per_rev
    hop = sim.hla["socket_force"] <= 0.0
    out = dict(
        collapse_min_m=float(h["collapse"].min()),
        collapse_max_m=float(h["collapse"].max()),
        collapse_range_m=float(h["collapse"].max() - h["collapse"].min()),
        length_change_per_revolution_m=-change,
        peak_pressure_Pa=float(h["pressure"].max()),
        min_pressure_Pa=float(h["pressure"].min()),
        inflow_per_revolution_m3=inflow,
        leak_per_revolution_m3=leak,
        # a periodic revolution returns the chamber's oil: in = out (the leak-volume balance)
        volume_balance_m3=inflow - leak,
        socket_hop=bool(hop.any()),
        socket_hop_deg=float(hop.sum() * 360.0 / n),
        valve_held_open_m=verdicts.valve_held_open(sim.lift, sim.valve_lift),
    )
    out["pump_up"] = verdicts.pumps_up(out["valve_held_open_m"])
    if out["pump_up"]:
        notes.append(
            f"PUMP-UP: the adjuster holds the valve open by {out['valve_held_open_m'] * 1e3:.3f} mm on the base "
            "circle (it extends whenever the train unloads it, after a lift-off or a bounce; the valve fails to close)"
        )
    if abs(out["length_change_per_revolution_m"]) > HLA_CREEP_TOL:
        notes.append(
            f"the adjuster's length still changes by {out['length_change_per_revolution_m'] * 1e6:+.2f} um per "
            "revolution (oil in and out do not balance): its figures are those of this revolution, not of a "
            "steady state"
        )
    if out["socket_hop"]:
        who = "the plunger leaves the valve stem" if vt.bucket_hla else "the finger leaves the adjuster's plunger"
        notes.append(f"SOCKET HOP: {who} for {out['socket_hop_deg']:.1f} cam degrees")
    if hla is not None and out["collapse_max_m"] > hla.collapse_travel:
        notes.append("the plunger bottoms in the adjuster's body (collapse_travel)")
    return out


def _summarise(sim: Simulation) -> dict:
    p = sim.spring.spring_model.internal_parameters()
    deg = sim.cam_angle_deg
    step_deg = 360.0 / sim.cam_angle.size
    names = sim.spring.spring_model.chain.element_names
    mon = sim.monitor
    s = dict(
        model=getattr(sim.spring, "model", "type-c"),
        spring=sim.spring.coil_facts,  # the coils and solid length the run used
        cam_rpm=sim.cam_rpm,
        revolutions=sim.revolutions,
        periodic=sim.periodic,
        periodicity_error=sim.periodicity_error if np.isfinite(sim.periodicity_error) else None,
        max_retainer_force_N=float(sim.retainer_force.max()),
        min_retainer_force_N=float(sim.retainer_force.min()),
        max_seat_force_N=float(sim.seat_force.max()),
        min_seat_force_N=float(sim.seat_force.min()),
        max_static_force_N=float(sim.static_force.max()),
        min_static_force_N=float(sim.static_force.min()),
    )
    notes = list(sim.flags)
    if sim.coil_bind is not None:
        cb = sim.coil_bind
        s.update(cb)
        if cb["through_solid"]:
            notes.append(
                f"THROUGH SOLID: the cam drives the spring {-cb['coil_bind_margin_m'] * 1e3:.3g} mm past its solid length "
                f"{cb['solid_length_m'] * 1e3:.4g} mm (through_solid = true); the forces there rest on the contact "
                "stiffness of closed coils"
            )
        elif not cb["coil_bind_ok"]:
            notes.append(
                f"coil bind: the cam leaves {cb['coil_bind_margin_m'] * 1e3:.3g} mm above the solid length "
                f"{cb['solid_length_m'] * 1e3:.4g} mm, less than the coil-bind clearance "
                f"{cb['coil_bind_clearance_m'] * 1e3:.3g} mm ({cb['coil_bind_clearance_source']})"
            )
    if mon is not None:
        ext = mon["ext"]
        to_deg = lambda t: float(np.degrees(mon["omega"] * (t - mon["t0"])) % 360.0)  # noqa: E731
        # true extremes from the dense output; never less extreme than the grid samples
        for key, ek, pick in (
            ("max_retainer_force", "max_retainer_force", max),
            ("min_retainer_force", "min_retainer_force", min),
            ("max_seat_force", "max_seat_force", max),
            ("min_seat_force", "min_seat_force", min),
        ):
            s[key + "_N"] = float(pick(ext[ek], s[key + "_N"]))
            s[key + "_cam_angle_deg"] = to_deg(ext["t_" + ek])
    else:
        notes.append(
            "extremes are samples of the output grid (the SciPy reference backend has no dense-output monitor)"
        )
    s["max_retainer_force_ratio"] = s["max_retainer_force_N"] / s["max_static_force_N"]
    s["min_retainer_force_ratio"] = s["min_retainer_force_N"] / s["min_static_force_N"]
    s["max_seat_force_ratio"] = s["max_seat_force_N"] / s["max_static_force_N"]
    s["min_seat_force_ratio"] = s["min_seat_force_N"] / s["min_static_force_N"]
    s["retainer_surge_amplitude_N"] = float(np.max(np.abs(sim.retainer_force - sim.static_force)))
    s["seat_surge_amplitude_N"] = float(np.max(np.abs(sim.seat_force - sim.static_force)))
    rpm = sim.cam_rpm
    located = located_events(sim)
    events = []
    if mon is not None:
        per_el = {k[1]: v for k, v in located.items() if isinstance(k, tuple) and k[0] == 1}
        allv = [(a, b, c, j) for j, v in per_el.items() for a, b, c in v]
        for lo, hi in _union([(a, b, c) for a, b, c, _ in allv]):
            end = hi % 360.0 if hi > 360.0 else hi
            elems = sorted(
                {j for a, b, c, j in allv if any(lo - 1e-9 <= x <= hi + 1e-9 for x in (a, b if b >= a else b + 360.0))}
            )
            mask = _angle_mask(deg, lo, end)
            grid = sim.element_force[np.ix_(elems, np.flatnonzero(mask))] if mask.any() else np.empty((0, 0))
            gaps = sim.spring.spring_model.contact_gaps
            at_touch = max(
                float(law_force(gaps[j], sim.spring.spring_model.chain.laws[j])) if np.isfinite(gaps[j]) else 0.0
                for j in elems
            )
            events.append(
                dict(
                    start_deg=float(lo),
                    end_deg=float(end),
                    duration_deg=float(hi - lo),
                    elements=[f"{j + 1}:{names[j]}" for j in elems],
                    peak_contact_force_N=float(max(grid.max(), at_touch)) if grid.size else at_touch,
                )
            )
    else:
        for a, b in _ranges(sim.element_contact.any(axis=0)):
            idx = np.arange(a, b + 1) if a <= b else np.concatenate([np.arange(a, deg.size), np.arange(0, b + 1)])
            elems = np.flatnonzero(sim.element_contact[:, idx].any(axis=1))
            events.append(
                dict(
                    start_deg=float(deg[a]),
                    end_deg=float(deg[b]),
                    duration_deg=float(idx.size * step_deg),
                    elements=[f"{j + 1}:{names[j]}" for j in elems],
                    peak_contact_force_N=float(sim.element_force[np.ix_(elems, idx)].max()),
                )
            )
    s["coil_contact"] = events
    s.update(_durability(sim, s, notes))
    s["coil_clash"] = _clash_impacts(sim, events)
    clash = sim.spring.spring_model.clashing_coils(sim) if hasattr(sim.spring.spring_model, "clashing_coils") else None
    if clash is not None:
        s["clashing_coils"] = clash
    if sim.element_check is not None:
        chk = sim.element_check
        fset = sim.spring.spring_model.internal_parameters()["Fset"]
        change = (
            max(
                abs(s["max_retainer_force_N"] - chk["max_retainer_force_N"]),
                abs(s["max_seat_force_N"] - chk["max_seat_force_N"]),
            )
            / fset
        )
        error = ELEMENT_RICHARDSON * change  # the default count's error, of the change to twice the elements
        s["clash_force_element_sensitivity"] = change
        s["clash_force_error_estimate"] = error
        s["clash_forces_converged"] = bool(error <= sim.ELEMENT_TOL)
        if error > sim.ELEMENT_TOL:
            notes.append(
                f"coil clash: the peak end forces depend on the element count ({chk['elements']} elements give "
                f"{chk['max_retainer_force_N']:.1f} / {chk['max_seat_force_N']:.1f} N at the retainer / seat against "
                f"{s['max_retainer_force_N']:.1f} / {s['max_seat_force_N']:.1f} N; the error estimate is "
                f"{100 * error:.1f} % of Fset): treat the clash forces as indicative and compare designs at one "
                "element count"
            )
    sep = []
    for end_index, end_name in ((0, "seat"), (1, "retainer")):
        for a, b, c in located.get((0, end_index), []):
            sep.append(dict(end=end_name, start_deg=a, end_deg=b, duration_deg=c, duration_s=c / (6.0 * rpm)))
    if mon is None:
        for j, end_name in ((0, "seat"), (-1, "retainer")):
            for a, b in _ranges(sim.element_compression[j] <= 0.0):
                count = (b - a + 1) if a <= b else (deg.size - a + b + 1)
                sep.append(
                    dict(
                        end=end_name,
                        start_deg=float(deg[a]),
                        end_deg=float(deg[b]),
                        duration_deg=float(count * step_deg),
                        duration_s=float(count * step_deg / (6.0 * rpm)),
                    )
                )
    s["end_separation"] = sep
    if s["periodicity_error"] is None:
        notes.append(
            "periodicity_error needs at least 2 revolutions (the last one is compared with the one "
            "before): run 2 or more"
        )
    elif not s["periodic"]:
        notes.append(
            f"NOT PERIODIC: the last two of {sim.revolutions} revolutions differ by {100 * s['periodicity_error']:.3g} % "
            f"of Fset (more than {100 * _tol(sim):g} %)"
            + (
                ": the run did not settle (bounce that does not repeat); its extremes scatter from revolution to "
                "revolution, see 'band' (over the last revolutions)"
                if sim.band is not None
                else "; the figures are a transient: run more revolutions or to the periodic steady state (the default)"
            )
        )
    if sim.band is not None:
        unit = {"force": "_N", "velocity": "_m_per_s"}
        s["band"] = {k + next((u for w, u in unit.items() if w in k), ""): [lo, hi] for k, (lo, hi) in sim.band.items()}
    f_cam = rpm_to_hz(sim.cam_rpm)
    orders, amp = sim.spectrum(40)
    top = np.argsort(amp[1:])[::-1][:8] + 1
    s["f1_Hz"] = p["f1"]
    s["f1_cam_order"] = p["f1"] / f_cam
    s["spectrum"] = [dict(order=int(k), frequency_Hz=float(k * f_cam), amplitude_N=float(amp[k])) for k in sorted(top)]
    if sim.valve_train is not None:
        vt = sim.valve_train
        # float: the valve open (off its seat, the lobe past the lash) and before its first
        # landing in the revolution (later separations are seat bounces)
        in_event = verdicts.valve_open(sim.lift, sim.valve_lift, vt.lobe_lash)
        phases = cam_phases(sim.cam, vt.lobe_lash)
        if mon is not None:
            intervals = located.get((2, 0), [])
        else:
            separated = in_event & (sim.cam_contact_force <= 0.0)
            intervals = []
            for a, b in _ranges(separated):
                count = (b - a + 1) if a <= b else (deg.size - a + b + 1)
                intervals.append((float(deg[a]), float(deg[b]), float(count * step_deg)))
        lo = liftoffs(intervals, phases, sim.cam_rpm, sim.cam_angle, None if sim.cam_gap is None else -sim.cam_gap)
        s["liftoff"] = lo
        # float as valve-train engineers read it: the valve leaves the cam over the nose
        s["nose_separation"] = verdicts.floats_over_nose(
            any(r["phase"] == "nose" for r in lo),
            phase_mask(sim.cam_angle, phases, "nose"),
            sim.cam_contact_force,
            sim.valve_lift,
        )
        s["first_liftoff_phase"] = lo[0]["phase"] if lo else None
        s["cam_phases_deg"] = phases.as_degrees()
        grid_min = float(sim.cam_contact_force[in_event].min()) if in_event.any() else 0.0
        if mon is not None and np.isfinite(mon["ext"]["min_cam_contact_force"]):
            s["min_cam_contact_force_N"] = max(min(mon["ext"]["min_cam_contact_force"], grid_min), 0.0)
        else:
            s["min_cam_contact_force_N"] = grid_min
        s["max_cam_contact_force_N"] = float(sim.cam_contact_force.max())
        z = sim.valve_lift
        dt = sim.time[1] - sim.time[0]
        landings = np.flatnonzero((z[:-1] > 0) & (z[1:] <= 0))
        if mon is not None:
            lands = located["landings"]
            s["seat_impact_velocity_m_per_s"] = float(lands[0][1]) if lands else 0.0
            s["seat_landings"] = len(lands)
        else:
            vz = np.gradient(z, dt)
            s["seat_impact_velocity_m_per_s"] = float(-vz[landings[0] + 1]) if landings.size else 0.0
            s["seat_landings"] = int(landings.size)
        s["bounces"] = max(s["seat_landings"] - 1, 0)
        if lo and s["seat_landings"]:
            # measured (tests/valve/test_distributed.py): the one-step spring's bucket train at
            # 3150-3250 cam rpm gives 0.2-0.9 % at rtol 1e-6 and 3e-7, 0.13 % at 1e-8, 0.007 % at 1e-9
            notes.append(
                "the valve floated: the landing after lift-off (seat impact velocity, bounces) depends on "
                "the tolerances, ~0.1 % at the valve train's default rtol = 1e-8; use rtol = 1e-9 for ~0.01 %"
            )
        s["max_bounce_height_m"] = verdicts.seat_rebound_height(sim.lift, z, vt.lobe_lash)
        if sim.hla is not None:
            s["hla"] = _hla_summary(sim, notes)
        if sim.gas_force is not None:
            k = int(np.argmax(sim.gas_force))
            opening = int(np.argmax(sim.valve_lift > 0.0))  # the first sample off the seat
            s["max_gas_force_N"] = float(sim.gas_force[k])
            s["max_gas_force_cam_angle_deg"] = float(deg[k])
            s["gas_force_at_opening_N"] = float(sim.gas_force[opening])
    if mon is not None and mon["ext"]["events_lost"] > 0:
        notes.append(f"{int(mon['ext']['events_lost'])} events beyond the first {len(mon['events'])} were not located")
    outside = type_c_outside_range(sim.spring.model, s)
    if outside:
        notes.append(outside)
    s["notes"] = notes
    return s


def type_c_outside_range(model: str, summary: dict) -> str:
    """A note when a Type C run reaches what Type C does not model reliably: its coils touch (an
    empirical contact law on three surge modes), an end of the spring separates, or the valve
    leaves the cam; empty otherwise (and for the distributed model).

    Parameters
    ----------
    model : str
        The spring model of the run.
    summary : dict
        The run's summary (``coil_contact``, ``end_separation``, ``liftoff``).
    """
    if model != "type-c":
        return ""
    what = [
        name
        for key, name in (
            ("coil_contact", "coil contact"),
            ("end_separation", "end separation"),
            ("liftoff", "lift-off"),
        )
        if summary.get(key)
    ]
    if not what:
        return ""
    return (
        f"TYPE C RANGE: this run has {', '.join(what)}, where Type C's three surge modes and empirical coil "
        "contact differ most from the distributed model (which judges the report's criteria): check it with "
        "--model distributed (docs/which-model.md)"
    )


#: The error of the default element count from the change to twice the elements: Richardson's
#: ``2^p / (2^p - 1)`` with second order in the element length (``p = 2``).  Measured (issue 40)
#: at three clash speeds of the examples against 200 elements: changes 0.72, 0.33, 1.03 % of
#: Fset, errors 0.86, 0.43, 1.25 %; these estimates 0.96, 0.44, 1.37 % bound them.
ELEMENT_RICHARDSON = 4.0 / 3.0


@dataclass(repr=False)
class FloatSpeedResult(CrankAngles, Result):
    """The float speed of a valve train: the lowest cam speed from which the valve
    separates over the nose at every higher scanned speed (:mod:`springdyn.valve.run.separation`).

    ``float_cam_rpm`` is ``None`` when the valve does not separate over the nose at the
    highest scanned speed; ``bracket`` gives the speeds either side of the bisection;
    ``first_separation`` the lowest scanned speed with any lift-off and its phase; ``scan``
    per scanned speed the minimum cam contact force during the event, lift-off, nose
    separation, the first lift-off's phase, seat landings and rebound height, the seat
    impact velocity and its band, and the periodicity.  ``result["float_cam_rpm"]`` works
    as for the dict earlier versions returned.
    """

    cam_rpm: list  # scanned speeds [rev/min]
    min_cam_contact_force_N: list  # per scanned speed [N]
    float_cam_rpm: float | None
    bracket: list | None
    resolution_rpm: float
    first_separation: dict | None = None
    scan: dict | None = None  # column -> list per scanned speed (float_search.SCAN_COLUMNS)
    periodicity_tol: float | None = None
    model: str = ""  # the spring model of the search

    title = "valve float speed"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return "no float in the range" if self.float_cam_rpm is None else f"{self.float_cam_rpm:.1f} cam rpm"

    def _summary(self) -> dict:
        s = dict(
            float_cam_rpm=self.float_cam_rpm,
            float_engine_rpm=None if self.float_cam_rpm is None else self.engine_per_cam * self.float_cam_rpm,
            float_definition="the lowest speed from which the valve separates over the nose (the negative "
            "acceleration around the peak) at every higher scanned speed",
            resolution_rpm=self.resolution_rpm,
            speeds_scanned=len(self.cam_rpm),
        )
        s["bracket_low_cam_rpm"], s["bracket_high_cam_rpm"] = self.bracket or [None, None]
        fs = self.first_separation
        s["first_separation_cam_rpm"] = fs["cam_rpm"] if fs else None
        s["first_separation_phase"] = fs["phase"] if fs else None
        notes = []
        sc = self.scan or {}
        if sc.get("periodic") is not None:
            bad = [r for r, p in zip(self.cam_rpm, sc["periodic"]) if not p]
            s["speeds_not_periodic"] = len(bad)
            if bad:
                notes.append(
                    f"{len(bad)} scanned speeds did not settle (bounce that does not repeat from one revolution to "
                    f"the next, from {min(bad):g} cam rpm): their seating velocity is a band over the last "
                    "revolutions and the speeds within +-25 rpm"
                )
        if self.float_cam_rpm is None:
            notes.append(
                "the valve does not separate over the nose at the highest scanned speed: no float in the range"
            )
        if fs and (self.float_cam_rpm is None or fs["cam_rpm"] < self.float_cam_rpm):
            notes.append(
                f"lift-off from {fs['cam_rpm']:g} cam rpm ({fs['phase']}) is bounce, not float: the valve does not "
                "leave the cam over the nose at every speed above it"
            )
        if self.model:
            s["model"] = self.model
        if self.model == "type-c" and fs:
            notes.append(
                "TYPE C RANGE: this float speed is Type C's; the distributed model, which judges the report's float "
                "criterion, separates at a somewhat different speed (its surge carries every mode): confirm it with "
                "--model distributed (docs/which-model.md)"
            )
        if notes:
            s["notes"] = notes
        return s

    @property
    def engine_per_cam(self) -> float:
        """Engine turns per cam turn [-]: the crank axis's, else a four-stroke's 2."""
        return 2.0 if self.crank_axis is None else float(self.crank_axis.per_cam)

    def table(self) -> str:
        """The scan as a table: per speed the minimum cam force, the first lift-off, float over
        the nose, seat landings, rebound, the seating-velocity band and the periodicity (the
        engine speed first when the result has a crank axis)."""
        sc = self.scan or {}
        engine = self.crank_axis is not None
        rows = []
        for i, rpm in enumerate(self.cam_rpm):
            phase = sc["first_liftoff_phase"][i] or ("off the cam" if sc["liftoff"][i] else "-")
            band = (
                f"{sc['seat_impact_velocity_min_m_per_s'][i]:.2f}/{sc['seat_impact_velocity_median_m_per_s'][i]:.2f}/"
                f"{sc['seat_impact_velocity_max_m_per_s'][i]:.2f}"
            )
            rows.append(
                (f"{self.engine_per_cam * rpm:g}",) * engine
                + (
                    f"{rpm:g}",
                    f"{sc['min_cam_contact_force_N'][i]:.1f}",
                    phase,
                    "yes" if sc["nose_separation"][i] else "no",
                    str(sc["seat_landings"][i]),
                    f"{1e3 * sc['seat_rebound_height_m'][i]:.3f}",
                    band,
                    "yes" if sc["periodic"][i] else f"no ({100 * sc['periodicity_error'][i]:.3g} %)",
                )
            )
        return text_table(
            rows,
            headers=("engine rpm",) * engine
            + (
                "cam rpm",
                "min cam force [N]",
                "first lift-off",
                "over the nose",
                "seat landings",
                "rebound [mm]",
                "seating v min/med/max [m/s]",
                "periodic",
            ),
        )

    def describe(self) -> str:
        """The scan's table (:meth:`table`), the first lift-off and the float speed in words."""
        s = self.summary
        top = max(self.cam_rpm)
        out = [
            self.table(),
            "seating velocity band: min/median/max over the scanned speeds within +-25 rpm and, where a speed does not",
            "settle, over its last revolutions",
        ]
        if s["first_separation_cam_rpm"] is not None:
            out.append(f"first lift-off: {s['first_separation_cam_rpm']:.0f} cam rpm ({s['first_separation_phase']})")
        else:
            out.append(f"no lift-off up to {top:g} cam rpm")
        if self.float_cam_rpm is None:
            out.append(f"float speed: above {top:g} cam rpm (no separation over the nose at the highest speed)")
        else:
            f = self.float_cam_rpm
            out.append(
                f"float speed: {self.engine_per_cam * f:.0f} engine rpm ({f:.0f} cam rpm"
                + (", four-stroke" if self.crank_axis is None else "")
                + "), the valve separating over the nose at every higher scanned speed"
            )
        return "\n".join(out + notes_lines(s))

    def to_dict(self) -> dict:
        """The JSON of ``springdyn valve float``: the scan and the float speed (SI, rpm)."""
        out = dict(
            cam_rpm=list(self.cam_rpm),
            min_cam_contact_force_N=list(self.min_cam_contact_force_N),
            float_cam_rpm=self.float_cam_rpm,
            bracket=self.bracket,
            first_separation=self.first_separation,
        )
        out.update({k: v for k, v in (self.scan or {}).items() if k not in out})
        return out

    def __getitem__(self, key):
        legacy = self.to_dict()
        return legacy[key] if key in legacy else self.summary[key]

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        data = {
            "min_cam_contact_force": (
                "cam_rpm",
                np.asarray(self.min_cam_contact_force_N, dtype=float),
                {"units": "N", "long_name": "minimum cam-follower contact force in the event"},
            )
        }
        for k, v in (self.scan or {}).items():
            if k == "min_cam_contact_force_N":
                continue
            a = np.asarray(v)
            data[k] = ("cam_rpm", a.astype(np.int8) if a.dtype == bool else a, {"units": units_from_name(k)})
        return xr.Dataset(
            data,
            coords={
                "cam_rpm": ("cam_rpm", np.asarray(self.cam_rpm, dtype=float), {"units": "rpm"}),
                "engine_rpm": (
                    "cam_rpm",
                    self.engine_per_cam * np.asarray(self.cam_rpm, dtype=float),
                    {"units": "rpm"},
                ),
            },
            attrs={"float_cam_rpm": "none" if self.float_cam_rpm is None else self.float_cam_rpm},
        )

    def _plot(self, ax=None):
        from ...core.plotting import new_figure  # (here: matplotlib costs 0.3 s of start-up)

        if ax is None:
            fig, ax = new_figure(figsize=(8, 4.5))
        ax.plot(self.cam_rpm, self.min_cam_contact_force_N, "o-", color="C0", label="minimum cam contact force")
        sc = self.scan or {}
        if "nose_separation" in sc:
            rpm = np.asarray(self.cam_rpm)
            nose = np.asarray(sc["nose_separation"], dtype=bool)
            other = np.asarray(sc["liftoff"], dtype=bool) & ~nose
            ax.plot(rpm[other], np.zeros(other.sum()), "^", color="C1", label="lift-off off the nose (bounce)")
            ax.plot(rpm[nose], np.zeros(nose.sum()), "v", color="C3", label="separation over the nose")
        ax.axhline(0.0, color="k", lw=0.8)
        if self.float_cam_rpm is not None:
            ax.axvline(self.float_cam_rpm, color="C3", ls="--", label=f"float speed {self.float_cam_rpm:.0f} cam rpm")
        ax.set_xlabel("cam speed [rpm]")
        ax.set_ylabel("force [N]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        return ax.figure


def _clash_impacts(sim, events: list) -> dict:
    """Coil clash, classed and graded (:func:`springdyn.valve.run.verdicts.coil_clash`), apart
    from the wire's stress: each coil-contact event gets the largest force its closed coils pass
    through their contact, whether coils close in it where the static spring is open
    (``dynamic_closing``) and with what severity; the summary gives the revolution's class,
    severity, closing velocity and contact share, the verdict against the limit, and counts the
    dynamic closings, their total duration and their peak force through contact."""
    model = sim.spring.spring_model
    share = np.nan_to_num(sim.contact_share)
    cc = verdicts.coil_clash(model, sim.element_compression, sim.static_force, 60.0 / sim.cam_rpm)
    closing = cc["closing"]
    fset = model.element_setup_forces()  # each element's own spring's Fset (verdicts.coil_clash)
    deg = sim.cam_angle_deg
    index = {f"{j + 1}:{n}": j for j, n in enumerate(model.chain.element_names)}
    count, duration, peak = 0, 0.0, 0.0
    for ev in events:
        rows = [index[e] for e in ev["elements"]]
        mask = _angle_mask(deg, ev["start_deg"], ev["end_deg"])
        ev["peak_force_through_contact_N"] = float(share[np.ix_(rows, mask)].max()) if mask.any() else 0.0
        block = np.ix_(rows, mask)
        ev["dynamic_closing"] = bool(closing[block].any()) if mask.any() else False
        through = np.where(closing[block], share[block], 0.0) if mask.any() else np.zeros((1, 1))
        ev["clash_severity"] = float((through / fset[rows][:, None]).max()) if mask.any() else 0.0
        ev["clash"] = ev["clash_severity"] > verdicts.MAX_CLASH_SEVERITY
        if ev["dynamic_closing"]:
            count += 1
            duration += ev["duration_deg"]
            peak = max(peak, float(through.max()))
    return dict(
        clash_class=verdicts.CLASH_CLASSES[int(cc["class_index"])],
        clash_severity=float(cc["severity"]),
        clash_severity_limit=verdicts.MAX_CLASH_SEVERITY,
        clash=bool(cc["clash"]),
        closing_velocity_m_per_s=float(cc["closing_velocity_m_per_s"]),
        contact_share=float(cc["contact_share"]),
        impacts=count,
        duration_deg=duration,
        peak_force_through_contact_N=peak,
    )


def _clash_text(cc: dict) -> str:
    """A revolution's coil clash in words (the ``coil_clash`` entry of a simulation's summary):
    its class and severity against the limit, ``FAIL`` above it.

    Parameters
    ----------
    cc : dict
        ``summary["coil_clash"]`` [-].
    """
    sev, limit = 100 * cc["clash_severity"], 100 * cc["clash_severity_limit"]
    if cc["clash_class"] == "none":
        return "coil clash: none (no coil closes where the static spring is open)"
    what = {
        "transition": ("transition coils seat", "transition coils clash"),
        "active": ("active coils touch", "active-coil clash"),
    }
    name = what[cc["clash_class"]][int(cc["clash"])]
    return (
        f"{name} (severity {sev:.1f} % of Fset through the contact, "
        + (f"above the {limit:g} % limit): FAIL" if cc["clash"] else f"within the {limit:g} % limit)")
        + f"; closing at {cc['closing_velocity_m_per_s']:.3f} m/s, {100 * cc['contact_share']:.1f} % of the "
        f"element's force through the contact; {cc['impacts']} closing event{'s' if cc['impacts'] != 1 else ''} over "
        f"{cc['duration_deg']:.1f} cam degrees"
    )


def _pack_lines(s: dict) -> list[str]:
    """The lines of a spring pack's summary: each spring's forces, fatigue, stress and room to
    solid, and the energy balance of the revolution."""
    out = []
    for name, v in s["springs"].items():
        fd, fs = v["fatigue_safety_factor"], v["static_fatigue_safety_factor"]
        out.append(
            f"{name} spring: retainer force {v['min_retainer_force_N']:.1f}-{v['max_retainer_force_N']:.1f} N; "
            "Goodman safety static "
            + (f"{fs:.2f}" if fs is not None else "-")
            + ", dynamic "
            + (f"{fd:.2f}" if fd is not None else "-")
            + f"; peak stress {v['peak_shear_stress_Pa'] / 1e6:.0f} MPa "
            + ("ok" if v["wire_stress_ok"] else "OVERSTRESS")
            + f"; {v['min_length_to_solid_m'] * 1e3:.2f} mm from solid at least"
        )
    out.append(
        f"energy per revolution: the retainer's work {s['retainer_work_per_revolution_J'] * 1e3:.2f} mJ, dissipated "
        f"{s['dissipated_energy_per_revolution_J'] * 1e3:.2f} mJ, of which the friction damper "
        f"{s['damper_energy_per_revolution_J'] * 1e3:.2f} mJ"
    )
    return out


def pack_energy(sim) -> dict:
    """The energy balance of a spring pack over the simulated revolution [J]: the work the
    retainer does on the springs, ``oint F_r dz`` (the retainer's displacement ``z`` by central
    differences over the periodic samples), the energy the chains dissipate (their elements'
    damping and the friction dampers, ``oint P dt``) and the first damper's share.  Over a
    periodic revolution the springs' elastic and kinetic energies return, so the work equals
    the dissipation (to the quadrature's error: the trapezoidal rule, exact to
    ``O(h^2)``, on the output grid).

    Parameters
    ----------
    sim : Simulation
        A simulation of a pack (its :attr:`Simulation.pack` outputs).
    """
    pk = sim.pack
    z = sim.valve_lift if sim.valve_lift is not None else sim.lift
    dz = 0.5 * (np.roll(z, -1) - np.roll(z, 1))
    dt = float(sim.time[1] - sim.time[0])
    return dict(
        retainer_work_per_revolution_J=float(np.sum(sim.retainer_force * dz)),
        dissipated_energy_per_revolution_J=float(np.sum(pk["dissipation"]) * dt),
        damper_energy_per_revolution_J=float(-np.sum(pk["damper_force"] * pk["damper_slip"]) * dt),
    )


def _pack_durability(sim, s: dict, notes: list) -> dict:
    """Each spring's wire fatigue, stress, length to solid and coil clash (over its own Fset,
    :func:`springdyn.valve.run.verdicts.spring_clashes`) over the simulated cycle (the
    figures of :func:`_durability` per spring, under ``springs``); the pack's own keys are the
    Goodman-critical spring's, and its energy balance (:func:`pack_energy`)."""
    pack = sim.spring
    model = pack.spring_model
    share = sim.contact_share
    wire_all = sim.element_force - share
    z = sim.valve_lift if sim.valve_lift is not None else sim.lift
    static = pack.static_forces(np.array([max(float(z.min()), 0.0), float(z.max())]))
    per = {}
    clash = verdicts.spring_clashes(model, sim.element_compression, sim.static_force, 60.0 / sim.cam_rpm)
    for k, (name, spring, r) in enumerate(zip(pack.names, pack.springs, model.element_ranges())):
        wire = wire_all[r]
        ends = sim.element_force[r]
        f = verdicts.wire_fatigue(
            spring,
            np.where(np.isfinite(wire).all(axis=1), wire.min(axis=1), np.nan),
            wire.max(axis=1),
            (float(ends[0].min()), float(ends[-1].min())),
            (float(ends[0].max()), float(ends[-1].max())),
            float(static[k, 0]),
            float(static[k, 1]),
        )
        length = spring.free_length - sim.element_compression[r].sum(axis=0)
        per[name] = dict(
            max_retainer_force_N=float(sim.pack["retainer_force"][k].max()),
            min_retainer_force_N=float(sim.pack["retainer_force"][k].min()),
            fatigue_safety_factor=f["fatigue_safety_factor"],
            static_fatigue_safety_factor=f["static_fatigue_safety_factor"],
            max_shear_stress_Pa=f["max_shear_stress_Pa"],
            peak_shear_stress_Pa=f["peak_shear_stress_Pa"],
            wire_stress_ok=f["wire_stress_ok"],
            min_length_to_solid_m=float(max(length.min() - spring.solid_length, 0.0)),
            clash_class=verdicts.CLASH_CLASSES[int(clash[name]["class_index"])],
            clash_severity=float(clash[name]["severity"]),
            coil_clash=bool(clash[name]["clash"]),
            fatigue=f,
        )
        if not f["wire_stress_ok"]:
            notes.append(
                f"WIRE OVERSTRESS: the {name} spring reaches {f['peak_shear_stress_Pa'] / 1e6:.0f} MPa at "
                f"{sim.cam_rpm:g} cam rpm, above the {f['shear_stress_limit_source']} "
                f"{f['shear_stress_limit_Pa'] / 1e6:.0f} MPa"
            )
    critical = min(per, key=lambda n: per[n]["fatigue_safety_factor"] or np.inf)
    f = per[critical]["fatigue"]
    keys = (
        "static_fatigue_safety_factor fatigue_safety_factor static_min_shear_stress_Pa static_max_shear_stress_Pa "
        "min_shear_stress_Pa max_shear_stress_Pa endurance_shear_strength_Pa ultimate_shear_strength_Pa "
        "shear_stress_limit_Pa max_wire_force_N peak_shear_stress_Pa wire_stress_ok"
    )
    out = {key: f[key] for key in keys.split()}
    out["fatigue_critical_spring"] = critical
    out["wire_stress_ok"] = all(v["wire_stress_ok"] for v in per.values())
    out["peak_shear_stress_Pa"] = max(v["peak_shear_stress_Pa"] for v in per.values())
    out["min_length_to_solid_m"] = min(v["min_length_to_solid_m"] for v in per.values())
    for v in per.values():
        v.pop("fatigue")
    out["springs"] = per
    out.update(pack_energy(sim))
    return out


def _durability(sim, s: dict, notes: list) -> dict:
    """Fatigue of the wire over the simulated cycle, beside the static one (issue 13).

    Dynamic: every element's wire torsion (its force less what closed coils pass through
    their contact, :meth:`SpringModel.wire_forces`) between its smallest and largest value
    of the last revolution (the end elements of the Type C chain from the true extremes);
    static: the static force's range over the cycle (installed to open).  A largest stress
    above the limit (``shear_yield_strength``, else the ultimate) is a failure naming the
    element.  Also the smallest length to solid, and for the distributed model the smallest
    coil gap.
    """
    if sim.pack is not None:
        return _pack_durability(sim, s, notes)
    model = sim.spring.spring_model
    share = sim.contact_share
    wire = sim.element_force - share  # SpringModel.wire_forces, with the share computed once
    f = verdicts.wire_fatigue(
        sim.spring,
        np.where(np.isfinite(wire).all(axis=1), wire.min(axis=1), np.nan),
        wire.max(axis=1),
        (s["min_seat_force_N"], s["min_retainer_force_N"]),
        (s["max_seat_force_N"], s["max_retainer_force_N"]),
        s["min_static_force_N"],
        s["max_static_force_N"],
    )
    peak_share = np.nanmax(np.where(np.isfinite(share), share, 0.0), axis=1)
    f = dict(  # elements counted from 1 for people; the force through the coils' contact
        f,
        fatigue_critical_element=f["fatigue_critical_element"] + 1,
        peak_shear_stress_element=f["peak_shear_stress_element"] + 1,
        max_force_through_coil_contact_N=float(np.max(peak_share)),
    )
    keys = (  # peak_shear_stress_*: the largest stress of any element (the Goodman-critical one need not be it)
        "static_fatigue_safety_factor fatigue_safety_factor static_min_shear_stress_Pa static_max_shear_stress_Pa "
        "min_shear_stress_Pa max_shear_stress_Pa fatigue_critical_element endurance_shear_strength_Pa "
        "ultimate_shear_strength_Pa shear_stress_limit_Pa max_wire_force_N max_force_through_coil_contact_N "
        "peak_shear_stress_Pa peak_shear_stress_element wire_stress_ok"
    )
    out = {key: f[key] for key in keys.split()}
    if not out["wire_stress_ok"]:
        j = f["peak_shear_stress_element"] - 1
        notes.append(
            f"WIRE OVERSTRESS: element {j + 1} ({model.chain.element_names[j]}) reaches "
            f"{out['peak_shear_stress_Pa'] / 1e6:.0f} MPa at {sim.cam_rpm:g} cam rpm, above the "
            f"{f['shear_stress_limit_source']} {out['shear_stress_limit_Pa'] / 1e6:.0f} MPa"
        )
    if f["strength_defaults"]:
        notes.append(
            "fatigue: default wire strengths used for "
            + " and ".join(f["strength_defaults"])
            + " (oil-tempered, shot-peened Cr-Si valve-spring wire; give them in [spring] for your wire)"
        )
    if out["fatigue_safety_factor"] is None:
        notes.append("fatigue: the wire carries no stress over the cycle")
    # length to solid: the spring's length against its solid length
    p = sim.spring.spring_model.internal_parameters()
    length = sim.spring.free_length - sim.element_compression.sum(axis=0)
    out["min_length_to_solid_m"] = float(max(length.min() - p["Lc"], 0.0))
    if sim.spring.model == "distributed":
        gaps = sim.spring.spring_model.contact_gaps
        # the coils open at set-up (dead coils and closed transitions excluded)
        active = np.isfinite(gaps) & (gaps > sim.spring.spring_model.chain.setup_compressions + 1e-12)
        gap = gaps[active, None] - sim.element_compression[active]
        out["min_coil_gap_m"] = float(max(gap.min(), 0.0)) if gap.size else None
    return out


@dataclass(repr=False)
class NaturalFrequencies(Result):
    """Natural frequencies of a spring (and its valve train) linearised on the base circle and
    at full lift (:func:`springdyn.valve.run.train_modes.natural_frequencies`)."""

    base_circle_Hz: list  # ascending [Hz]
    full_lift_Hz: list  # ascending [Hz]; empty when the full-lift equilibrium was not found
    full_lift_cam_angle_deg: float  # [deg]
    notes: list
    #: Cam speeds where a cam order meets a mode (:meth:`with_resonances`): ``mode``,
    #: ``frequency_Hz``, ``order``, ``cam_rpm`` per row; None when no range was asked for.
    resonances: list | None = None
    #: The speed range of :attr:`resonances` [rev/min].
    speed_range: tuple | None = None

    title = "valve natural frequencies"
    cheap_plot = True

    def with_resonances(self, cam_rpm_min: float, cam_rpm_max: float) -> NaturalFrequencies:
        """The same modes with the cam speeds in a range where a cam order meets one
        (:func:`springdyn.valve.run.train_modes.resonance_speeds`, the full-lift modes, else the
        base circle's).

        Parameters
        ----------
        cam_rpm_min, cam_rpm_max : float
            The speed range [rev/min].
        """

        rows = resonance_speeds(self.full_lift_Hz or self.base_circle_Hz, float(cam_rpm_min), float(cam_rpm_max))
        return dataclasses.replace(self, resonances=rows, speed_range=(float(cam_rpm_min), float(cam_rpm_max)))

    def to_dict(self) -> dict:
        """``base_circle_Hz``, ``full_lift_Hz``, ``full_lift_cam_angle_deg``, ``notes`` and, with a
        range, ``resonance_speeds`` (the JSON of ``springdyn valve train-modes``)."""
        out = dict(
            base_circle_Hz=list(self.base_circle_Hz),
            full_lift_Hz=list(self.full_lift_Hz),
            full_lift_cam_angle_deg=self.full_lift_cam_angle_deg,
            notes=list(self.notes),
        )
        if self.resonances is not None:
            out["resonance_speeds"] = list(self.resonances)
        return out

    def describe(self) -> str:
        """The modes on the base circle and at full lift, and the resonance speeds."""
        n = max(len(self.base_circle_Hz), len(self.full_lift_Hz))
        rows = [
            (
                str(i + 1),
                f"{self.base_circle_Hz[i]:.1f}" if i < len(self.base_circle_Hz) else "-",
                f"{self.full_lift_Hz[i]:.1f}" if i < len(self.full_lift_Hz) else "-",
            )
            for i in range(n)
        ]
        out = [
            text_table(
                rows, headers=("mode", "base circle [Hz]", f"full lift ({self.full_lift_cam_angle_deg:.0f} deg) [Hz]")
            )
        ]
        out += ["note: " + note for note in self.notes]
        if self.resonances is not None:
            lo, hi = self.speed_range
            out.append(
                f"cam-order resonances (cam rpm = 60 f / N, full-lift frequencies) from {lo:g} to {hi:g} cam rpm:"
            )
            out.append(
                text_table(
                    [
                        (str(r["mode"]), f"{r['frequency_Hz']:.1f}", str(r["order"]), f"{r['cam_rpm']:.0f}")
                        for r in self.resonances
                    ],
                    headers=("mode", "f [Hz]", "order N", "cam rpm"),
                )
            )
        return "\n".join(out)

    def _repr_caption(self) -> str:
        return f"first {self.base_circle_Hz[0]:.1f} Hz on the base circle" if self.base_circle_Hz else "none"

    def _summary(self) -> dict:
        s = dict(
            first_base_circle_Hz=self.base_circle_Hz[0] if self.base_circle_Hz else None,
            first_full_lift_Hz=self.full_lift_Hz[0] if self.full_lift_Hz else None,
            full_lift_cam_angle_deg=self.full_lift_cam_angle_deg,
            modes_count=len(self.base_circle_Hz),
        )
        if self.notes:
            s["notes"] = list(self.notes)
        return s

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        n = max(len(self.base_circle_Hz), len(self.full_lift_Hz))

        def padded(values):
            return np.array(list(values) + [np.nan] * (n - len(values)), dtype=float)

        return xr.Dataset(
            {
                "base_circle_frequency": ("mode", padded(self.base_circle_Hz), {"units": "Hz"}),
                "full_lift_frequency": ("mode", padded(self.full_lift_Hz), {"units": "Hz"}),
            },
            coords={"mode": ("mode", np.arange(1, n + 1), {"units": "1"})},
            attrs={"full_lift_cam_angle_deg": self.full_lift_cam_angle_deg},
        )

    def _csv_dataset(self):
        # a mode without a full-lift value is left out of the table (never NaN in a file)
        ds = self.to_xarray()
        keep = min(len(self.base_circle_Hz), len(self.full_lift_Hz)) or len(self.base_circle_Hz)
        ds = ds.isel(mode=slice(0, keep))
        return ds if self.full_lift_Hz else ds.drop_vars("full_lift_frequency")

    def _plot(self, ax=None):
        from ...core.plotting import new_figure  # (here: matplotlib costs 0.3 s of start-up)

        if ax is None:
            fig, ax = new_figure(figsize=(8, 4.5))
        for i, (values, label) in enumerate(((self.base_circle_Hz, "base circle"), (self.full_lift_Hz, "full lift"))):
            if values:
                ax.plot(np.arange(1, len(values) + 1), values, "o-", color=f"C{i}", label=label)
        ax.set_xlabel("mode")
        ax.set_ylabel("natural frequency [Hz]")
        ax.set_yscale("log")
        ax.grid(True, alpha=0.3)
        ax.legend()
        return ax.figure
