"""Speed ramps (run-ups): the valve train through a changing cam speed.

Float under a fast engine acceleration can occur below the steady-state float speed: the
train enters each speed with the vibration of the slower ones.  A ramp starts from the
periodic steady state at ``start`` and turns the cam at the speed
``omega(t) = omega_0 + alpha t``, the cam angle ``omega_0 t + alpha t^2 / 2``
(:func:`springdyn.valve.engine.equations.train_rhs`), to ``end``.  Every revolution of the
ramp is judged like a steady speed (:mod:`springdyn.valve.run.separation`): lift-off, lift-off
over the nose (float), seat landings, against its momentary (mean) speed, beside the
steady-state float speed of the same range.

:func:`speed_ramp` runs it; :class:`RunUp` holds the revolutions (the Result interface).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ...core.errors import InputError, SolverError
from ...core.results import Result, notes_lines, text_table
from ...core.units import omega_to_rpm, rpm_to_omega
from ..engine import integrate, rhs_kernel
from ..engine.equations import model_of, train_of
from ..engine.layout import VT_ALPHA
from ..spring.results import coil_line
from . import verdicts
from .float_search import float_speed
from .runner import engine_args, run_speeds, runge_kutta_pair, velocity_tolerance
from .separation import cam_phases, phase_mask
from .settings import MAX_STEP_FRACTION, SWEEP_POINTS_PER_REVOLUTION, RunSettings
from .setup import prepare

__all__ = ["speed_ramp", "RunUp", "ramp_time", "ramp_angle", "MAX_RAMP_REVOLUTIONS"]

#: Most cam revolutions a ramp may span (a bound on the work: about 1 s per 100 revolutions).
MAX_RAMP_REVOLUTIONS = 2000


def ramp_angle(t, omega0: float, alpha: float):
    """Cam angle [rad] at time ``t`` [s] of a ramp from ``omega0`` [rad/s] at ``alpha`` [rad/s^2].

    Parameters
    ----------
    t : float or ndarray
        Time from the ramp's start [s].
    omega0 : float
        Cam speed at the start [rad/s].
    alpha : float
        Cam angular acceleration [rad/s^2].
    """
    return omega0 * np.asarray(t) + 0.5 * alpha * np.asarray(t) ** 2


def ramp_time(theta, omega0: float, alpha: float):
    """Time [s] at which a ramp reaches the cam angle ``theta`` [rad] (the inverse of :func:`ramp_angle`).

    ``t = 2 theta / (omega0 + sqrt(omega0^2 + 2 alpha theta))`` (the root that stays
    accurate as ``alpha`` goes to zero).

    Parameters
    ----------
    theta : float or ndarray
        Cam angle from the ramp's start [rad].
    omega0 : float
        Cam speed at the start [rad/s].
    alpha : float
        Cam angular acceleration [rad/s^2].
    """
    theta = np.asarray(theta, dtype=float)
    return 2.0 * theta / (omega0 + np.sqrt(omega0**2 + 2.0 * alpha * theta))


def speed_ramp(
    spring,
    cam,
    valve_train,
    start_rpm: float,
    end_rpm: float,
    rate_rpm_per_s: float,
    *,
    settings: RunSettings | None = None,
    float_scan: bool = True,
    **run,
) -> RunUp:
    """The valve train through a cam-speed ramp (see the module docstring).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain
    start_rpm, end_rpm : float
        Cam speeds at the ramp's start and end [rev/min].
    rate_rpm_per_s : float
        Rate of the cam speed [rev/min per s] (a deceleration when ``end < start``).
    settings : RunSettings, optional
        The tolerances (default: the valve train's) and output samples per revolution
        (default 720) of the ramp, and the periodic steady state it starts from.
    float_scan : bool
        Also find the steady-state float speed of the range (a sweep of its speeds), to
        report beside the ramp's.
    **run
        Fields of :class:`~springdyn.valve.run.settings.RunSettings` given one by one.
    """
    settings = RunSettings.of(settings, **run)
    if valve_train is None:
        raise InputError("a speed ramp judges lift-off and float: it needs a valve train (--valve-train)")
    for name, v in (("start", start_rpm), ("end", end_rpm)):
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise InputError(f"speed ramp {name} = {v!r} must be a positive cam speed [rev/min]")
    if not (isinstance(rate_rpm_per_s, (int, float)) and math.isfinite(rate_rpm_per_s) and rate_rpm_per_s > 0):
        raise InputError(f"speed ramp rate = {rate_rpm_per_s!r} must be a positive rate [rev/min per s]")
    if start_rpm == end_rpm:
        raise InputError("a speed ramp needs different start and end speeds (a constant speed is valve simulate)")
    n = settings.points(SWEEP_POINTS_PER_REVOLUTION)
    rtol, atol = settings.tolerances(valve_train)
    w0, w1 = rpm_to_omega(start_rpm), rpm_to_omega(end_rpm)
    alpha = math.copysign(rpm_to_omega(rate_rpm_per_s), w1 - w0)
    duration = (w1 - w0) / alpha
    total = ramp_angle(duration, w0, alpha)
    revs = int(math.floor(total / (2.0 * math.pi)))
    if revs < 2:
        raise InputError(
            f"the ramp from {start_rpm:g} to {end_rpm:g} cam rpm at {rate_rpm_per_s:g} rpm/s lasts {duration:.3g} s, "
            "less than two cam revolutions: take a slower rate or a wider range"
        )
    if revs > MAX_RAMP_REVOLUTIONS:
        raise InputError(
            f"the ramp from {start_rpm:g} to {end_rpm:g} cam rpm at {rate_rpm_per_s:g} rpm/s spans {revs} cam "
            f"revolutions, more than {MAX_RAMP_REVOLUTIONS}: take a faster rate or a narrower range"
        )

    setup = prepare(spring, cam, valve_train)
    start = run_speeds(
        setup, [w0], dataclasses.replace(settings, revolutions=None), n
    )  # the periodic state at the start
    if int(start["status"][0]) != 0:
        raise SolverError(f"the ramp's start at {start_rpm:g} cam rpm did not integrate ({start['status'][0]})")
    vt = setup.vt.copy()
    vt[VT_ALPHA] = alpha
    args = (*engine_args(setup, w0)[:9], vt)
    theta = np.arange(revs * n + 1) * (2.0 * math.pi / n)
    t_out = ramp_time(theta, w0, alpha)
    states, info = integrate(
        np.array(start["state"][0], dtype=float),
        t_out,
        args,
        rtol=rtol,
        atol=atol,
        h_max=MAX_STEP_FRACTION * 2.0 * math.pi / max(w0, w1),
        atol_velocity=velocity_tolerance(setup, atol),
        method=runge_kutta_pair(setup, settings),
    )
    if info["status"] != 0 or not np.isfinite(states).all():
        raise SolverError(
            f"the speed ramp from {start_rpm:g} to {end_rpm:g} cam rpm stopped at t = {info['t']:.4g} s "
            f"(status {info['status']}): {info}"
        )
    lay = setup.layout
    m = model_of(args)
    tr = train_of(vt)
    extra = np.empty((t_out.size, lay["size"]))
    d = np.empty(states.shape[1])
    rhs = rhs_kernel(m)
    for k in range(t_out.size):
        rhs(t_out[k], states[k], m, w0, tr, d, extra[k])
    phases = cam_phases(cam, valve_train.lobe_lash)
    angle = np.mod(theta, 2.0 * math.pi)
    nose = phase_mask(angle[:n], phases, "nose")
    return RunUp(
        spring=spring,
        cam=cam,
        valve_train=valve_train,
        start_rpm=float(start_rpm),
        end_rpm=float(end_rpm),
        rate_rpm_per_s=float(rate_rpm_per_s),
        time=t_out,
        cam_angle=theta,
        cam_rpm=omega_to_rpm(w0 + alpha * t_out),
        lift=extra[:, lay["lift"]],
        valve_lift=extra[:, lay["top_displacement"]],
        cam_contact_force=extra[:, lay["cam_contact_force"]],
        valve_seat_force=extra[:, lay["valve_seat_force"]],
        retainer_force=extra[:, lay["force"]][:, -1],
        points_per_revolution=n,
        nose=nose,
        lobe_lash=valve_train.lobe_lash,
        steady_float_cam_rpm=_steady_float(spring, cam, valve_train, start_rpm, end_rpm) if float_scan else None,
        info=info,
    )


def _steady_float(spring, cam, valve_train, a: float, b: float):
    """The steady-state float speed over the ramp's range (None: none within it)."""
    lo, hi = min(a, b), max(a, b)
    res = float_speed(spring, cam, valve_train, np.linspace(lo, hi, 16), progress_quiet=True)
    return res.float_cam_rpm


@dataclass(repr=False)
class RunUp(Result):
    """A valve train through a speed ramp (:func:`speed_ramp`), judged revolution by revolution."""

    spring: object
    cam: object
    valve_train: object
    start_rpm: float
    end_rpm: float
    rate_rpm_per_s: float
    time: np.ndarray  # [s]
    cam_angle: np.ndarray  # [rad] from the ramp's start
    cam_rpm: np.ndarray  # momentary cam speed [rev/min]
    lift: np.ndarray  # [m]
    valve_lift: np.ndarray  # [m]
    cam_contact_force: np.ndarray  # [N]
    valve_seat_force: np.ndarray  # [N]
    retainer_force: np.ndarray  # [N]
    points_per_revolution: int
    nose: np.ndarray  # (points,) the nose's samples of a revolution
    lobe_lash: float  # [m]
    steady_float_cam_rpm: float | None
    info: dict

    title = "valve train speed ramp"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.start_rpm:g} -> {self.end_rpm:g} cam rpm at {self.rate_rpm_per_s:g} rpm/s"

    def describe(self) -> str:
        """The ramp revolution by revolution (what ``springdyn valve simulate --speed-ramp`` prints)."""
        s = self.summary
        out = [
            coil_line(self.spring.coil_facts),
            f"speed ramp {self.start_rpm:g} -> {self.end_rpm:g} cam rpm at {self.rate_rpm_per_s:g} rpm/s: "
            f"{s['duration_s']:.3f} s, {s['revolutions']} revolutions, each judged at its mean speed",
        ]
        t = self.revolutions()
        out.append(
            text_table(
                [
                    (
                        f"{t['cam_rpm'][i]:.0f}",
                        "FLOAT" if t["nose_separation"][i] else ("lift-off" if t["liftoff"][i] else "-"),
                        str(t["seat_landings"][i]),
                        f"{t['min_cam_contact_force_N'][i]:.1f}",
                        f"{t['max_retainer_force_N'][i]:.1f}",
                    )
                    for i in range(t["cam_rpm"].size)
                ],
                headers=("cam rpm", "separation", "seat landings", "min cam force [N]", "max retainer force [N]"),
            )
        )
        onset, steady = s["float_onset_cam_rpm"], s["steady_float_cam_rpm"]
        out.append(
            (
                f"float (lift-off over the nose) from {onset:.0f} cam rpm of the ramp"
                if onset
                else "no float in the ramp"
            )
            + (f"; steady-state float speed {steady:.0f} cam rpm" if steady else "; no steady-state float in the range")
        )
        return "\n".join(out + notes_lines(s))

    def revolutions(self) -> dict:
        """One row per cam revolution: its mean speed and what the valve did in it.

        Returns
        -------
        dict
            ``cam_rpm`` (the revolution's mean speed), ``liftoff``, ``nose_separation``,
            ``seat_landings``, ``min_cam_contact_force_N`` (while the valve is open),
            ``min_nose_contact_force_N`` (over the nose, where float is judged),
            ``max_retainer_force_N``, ``min_retainer_force_N``.
        """
        n = self.points_per_revolution
        revs = (self.time.size - 1) // n
        rows = {k: [] for k in ("cam_rpm", "liftoff", "nose_separation", "seat_landings")}
        for k in (
            "min_cam_contact_force_N",
            "min_nose_contact_force_N",
            "max_retainer_force_N",
            "min_retainer_force_N",
        ):
            rows[k] = []
        for r in range(revs):
            sl = slice(r * n, (r + 1) * n)
            z, fc, lift = self.valve_lift[sl], self.cam_contact_force[sl], self.lift[sl]
            in_event = verdicts.valve_open(lift, z, self.lobe_lash)
            off = in_event & (fc <= 0.0)
            rows["cam_rpm"].append(omega_to_rpm(2.0 * math.pi / (self.time[(r + 1) * n] - self.time[r * n])))
            rows["liftoff"].append(bool(off.any()))
            rows["nose_separation"].append(
                verdicts.floats_over_nose(False, self.nose, np.where(in_event, fc, np.inf), z)
            )
            rows["seat_landings"].append(int(np.sum((z[:-1] > 0) & (z[1:] <= 0))))
            rows["min_cam_contact_force_N"].append(float(fc[in_event].min()) if in_event.any() else 0.0)
            nose = self.nose & in_event
            rows["min_nose_contact_force_N"].append(float(fc[nose].min()) if nose.any() else 0.0)
            rows["max_retainer_force_N"].append(float(self.retainer_force[sl].max()))
            rows["min_retainer_force_N"].append(float(self.retainer_force[sl].min()))
        return {k: np.asarray(v) for k, v in rows.items()}

    def _summary(self) -> dict:
        t = self.revolutions()
        first = np.flatnonzero(t["nose_separation"])
        lift = np.flatnonzero(t["liftoff"])
        s = dict(
            start_cam_rpm=self.start_rpm,
            end_cam_rpm=self.end_rpm,
            rate_rpm_per_s=self.rate_rpm_per_s,
            duration_s=float(self.time[-1]),
            revolutions=int(t["cam_rpm"].size),
            first_liftoff_cam_rpm=float(t["cam_rpm"][lift[0]]) if lift.size else None,
            float_onset_cam_rpm=float(t["cam_rpm"][first[0]]) if first.size else None,
            steady_float_cam_rpm=self.steady_float_cam_rpm,
            max_seat_landings=int(t["seat_landings"].max()),
            max_retainer_force_N=float(t["max_retainer_force_N"].max()),
        )
        notes = [
            "each revolution of the ramp is judged at its mean speed; the ramp starts from the periodic steady "
            "state at its start speed"
        ]
        if s["float_onset_cam_rpm"] is not None and self.steady_float_cam_rpm is not None:
            s["float_onset_below_steady_cam_rpm"] = self.steady_float_cam_rpm - s["float_onset_cam_rpm"]
        if self.steady_float_cam_rpm is None:
            notes.append("no steady-state float within the ramp's range (or not scanned)")
        s["notes"] = notes
        return s

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        dims = ("time",)
        return xr.Dataset(
            {
                "cam_rpm": (dims, self.cam_rpm, {"units": "rpm", "long_name": "momentary cam speed"}),
                "cam_angle": (dims, np.degrees(self.cam_angle), {"units": "deg", "long_name": "from the ramp's start"}),
                "lift": (dims, self.lift, {"units": "m"}),
                "valve_lift": (dims, self.valve_lift, {"units": "m"}),
                "cam_contact_force": (dims, self.cam_contact_force, {"units": "N"}),
                "valve_seat_force": (dims, self.valve_seat_force, {"units": "N"}),
                "retainer_force": (dims, self.retainer_force, {"units": "N"}),
            },
            coords={"time": (dims, self.time, {"units": "s"})},
        )

    def _plot(self, ax=None):
        """Per revolution against the momentary speed: the cam contact force at its least (over
        the event and over the nose) and the retainer force's range, the ramp's float onset, its
        first lift-off and the steady-state float speed marked; the seat landings below."""
        from ...core.plotting import new_figure  # (here: matplotlib costs 0.3 s of start-up)

        t, s = self.revolutions(), self.summary
        rpm = t["cam_rpm"]
        if ax is None:
            fig, axes = new_figure(2, 1, figsize=(11, 8), sharex=True)
        else:
            fig, axes = ax.figure, [ax]
        a = axes[0]
        a.plot(rpm, t["min_cam_contact_force_N"], "C0.-", lw=1.2, ms=4, label="cam contact force, least while open")
        a.plot(rpm, t["min_nose_contact_force_N"], "C2.-", lw=1.2, ms=4, label="cam contact force, least over the nose")
        a.fill_between(rpm, t["min_retainer_force_N"], t["max_retainer_force_N"], color="C1", alpha=0.15, lw=0)
        a.plot(rpm, t["max_retainer_force_N"], "C1-", lw=1, label="retainer force, most and least")
        a.plot(rpm, t["min_retainer_force_N"], "C1-", lw=1)
        nose = t["nose_separation"]
        a.plot(rpm[nose], np.zeros(nose.sum()), "C3x", ms=7, label="revolution floats over the nose")
        a.axhline(0.0, color="k", lw=0.6)
        for a_ in axes:
            self._mark_speeds(a_, s, label=a_ is a)
        a.set_ylabel("force [N]")
        a.set_title(f"speed ramp {self.start_rpm:.0f} -> {self.end_rpm:.0f} cam rpm at {self.rate_rpm_per_s:.0f} rpm/s")
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # beside: never over a curve
        if len(axes) > 1:
            b = axes[1]
            b.step(rpm, t["seat_landings"], where="mid", color="C4")
            b.set_ylabel("seat landings per revolution")
            b.yaxis.get_major_locator().set_params(integer=True)
            b.grid(True, alpha=0.3)
        axes[-1].set_xlabel("cam speed [rpm] (each revolution at its mean speed)")
        return fig

    def _mark_speeds(self, ax, s, label: bool):
        """The ramp's first lift-off and float onset, and the steady-state float speed, as lines."""
        for value, style, text in (
            (s["first_liftoff_cam_rpm"], dict(color="C3", ls=":", lw=1.2), "first lift-off"),
            (s["float_onset_cam_rpm"], dict(color="C3", ls="-", lw=1.2), "float onset in the ramp"),
            (self.steady_float_cam_rpm, dict(color="k", ls="--", lw=1.0), "steady-state float speed"),
        ):
            if value is not None:
                ax.axvline(value, **style, label=f"{text} {value:.0f} rpm" if label else None)
