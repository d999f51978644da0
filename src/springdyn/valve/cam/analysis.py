"""The cam as a valve-train engineer checks it first: lift, velocity, acceleration and jerk,
the timing at check heights, the lobe centre, the ramps.

:func:`cam_derivatives` samples the lift law and its derivatives per radian of cam angle
(optionally at the valve: rocker ratio and lash); :func:`check_height_timing` finds where the
lift crosses a check height on the opening and the closing side; :func:`analyse_cam` gathers
everything into a :class:`CamAnalysis` (the Result interface: summary, xarray, CSV, plot),
with crank-angle axes (:mod:`springdyn.valve.cam.timing`) when an engine speed or a ``[timing]``
table is given, and derivatives in time with an engine speed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core.errors import InputError
from ...core.results import Result, notes_lines, text_table
from ...core.units import rpm_to_omega
from .timing import cam_rpm_from_engine_rpm, crank_axis

__all__ = ["CHECK_HEIGHTS", "cam_derivatives", "check_height_timing", "analyse_cam", "CamAnalysis"]

#: The check heights of valve timing [m]: 0.050 in (SAE practice) and 1 mm, by the name
#: their summary keys carry (``duration_at_0050in_deg``, ``duration_at_1mm_deg``).
CHECK_HEIGHTS = {"0050in": 0.050 * 0.0254, "1mm": 1.0e-3}
#: Samples per revolution of the analysis (0.05 deg, the engine's cam table).
SAMPLES = 7200

_TWO_PI = 2.0 * math.pi


def cam_derivatives(cam, samples: int = SAMPLES, ratio: float = 1.0, lash: float = 0.0) -> dict:
    """Lift and its derivatives per radian of cam angle over one revolution.

    The lift, velocity and acceleration are the cam law's own (:meth:`Cam.evaluate`); the jerk
    is the central difference of the acceleration (periodic).  At the valve: ``ratio`` times
    the lobe lift less the ``lash``, zero while the lash is open.

    Parameters
    ----------
    cam : Cam
    samples : int
        Samples per revolution [-].
    ratio : float
        Valve lift per lobe lift (rocker ratio) [-].
    lash : float
        Lash at the valve [m].

    Returns
    -------
    dict
        ``cam_angle`` [rad], ``lift`` [m], ``velocity`` [m/rad], ``acceleration`` [m/rad^2],
        ``jerk`` [m/rad^3].
    """
    theta = np.arange(samples) * (_TWO_PI / samples)
    h, dh, ddh = cam.evaluate(theta)
    step = _TWO_PI / samples
    jerk = (np.roll(ddh, -1) - np.roll(ddh, 1)) / (2.0 * step)
    lift = ratio * h - lash
    open_ = lift > 0.0
    return dict(
        cam_angle=theta,
        lift=np.where(open_, lift, 0.0),
        velocity=np.where(open_, ratio * dh, 0.0),
        acceleration=np.where(open_, ratio * ddh, 0.0),
        jerk=np.where(open_, ratio * jerk, 0.0),
    )


def check_height_timing(cam_angle, lift, height: float) -> dict | None:
    """Opening and closing cam angles where the lift crosses ``height`` around its peak.

    Walks from the largest lift to the first samples below ``height`` on either side and
    interpolates linearly between the two samples there.

    Parameters
    ----------
    cam_angle : ndarray
        Cam angles of one revolution [rad], equally spaced from 0.
    lift : ndarray
        Lift there [m].
    height : float
        Check height [m].

    Returns
    -------
    dict or None
        ``opening_deg``, ``closing_deg`` (in [0, 360)), ``duration_deg``, ``centre_deg``;
        None when the lift never reaches the height.

    Examples
    --------
    >>> th = np.radians(np.arange(0.0, 360.0, 1.0))
    >>> lift = np.maximum(0.0, 1e-2 * np.cos(th - np.pi))  # a peak of 10 mm at 180 deg
    >>> t = check_height_timing(th, lift, 5e-3)
    >>> round(t["opening_deg"], 1), round(t["closing_deg"], 1), round(t["duration_deg"], 1)
    (120.0, 240.0, 120.0)
    """
    n = lift.size
    peak = int(np.argmax(lift))
    if lift[peak] < height:
        return None
    step = _TWO_PI / n

    def cross(direction):
        i = peak
        for _ in range(n):
            j = (i + direction) % n
            if lift[j] < height:
                frac = (lift[i] - height) / (lift[i] - lift[j])
                return cam_angle[i] + direction * frac * step
            i = j
        return math.nan

    opening, closing = cross(-1), cross(1)
    duration = (closing - opening) % _TWO_PI
    return dict(
        opening_deg=math.degrees(opening % _TWO_PI),
        closing_deg=math.degrees(closing % _TWO_PI),
        duration_deg=math.degrees(duration),
        centre_deg=math.degrees((opening + duration / 2.0) % _TWO_PI),
    )


def analyse_cam(
    cam, valve_train=None, engine_rpm: float | None = None, samples: int = SAMPLES, timing=None
) -> CamAnalysis:
    """The cam's lift, derivatives and timing, at the valve when a valve train is given.

    Parameters
    ----------
    cam : Cam
    valve_train : ValveTrain, optional
        Gives the rocker ratio and the lash at the valve.
    engine_rpm : float, optional
        Engine speed [rev/min] (four-stroke: the cam turns at half of it): adds crank angles
        and the derivatives in time (velocity [m/s], acceleration [m/s^2], jerk [m/s^3]).
    samples : int
        Samples per revolution [-].
    timing : Timing, optional
        The ``[timing]`` table (:mod:`springdyn.valve.cam.timing`): crank angles from the
        gas-exchange TDC and the timing in words ("10.0 deg BTDC").
    """

    if engine_rpm is not None and not (isinstance(engine_rpm, (int, float)) and 0 < engine_rpm < 1e5):
        raise InputError(f"engine_rpm = {engine_rpm!r} must be an engine speed between 0 and 100000 rev/min")
    ratio = 1.0 if valve_train is None else valve_train.ratio
    lash = 0.0 if valve_train is None else valve_train.lash
    d = cam_derivatives(cam, samples, ratio, lash)
    axis = crank_axis(cam, timing) if (timing is not None or engine_rpm is not None) else None
    return CamAnalysis(
        cam=cam,
        at_valve=valve_train is not None,
        ratio=ratio,
        lash=lash,
        engine_rpm=engine_rpm,
        axis=axis,
        **d,
        valve=None if timing is None else timing.valve,
    )


@dataclass(repr=False)
class CamAnalysis(Result):
    """Lift, velocity, acceleration and jerk of a cam over one revolution, with its timing
    (:func:`analyse_cam`)."""

    cam: object
    at_valve: bool
    ratio: float
    lash: float
    engine_rpm: float | None
    axis: object  # CrankAxis (crank angles) or None
    cam_angle: np.ndarray  # [rad]
    lift: np.ndarray  # [m]
    velocity: np.ndarray  # [m/rad]
    acceleration: np.ndarray  # [m/rad^2]
    jerk: np.ndarray  # [m/rad^3]
    #: The valve of the ``[timing]`` table ("intake" or "exhaust"), None without one.
    valve: str | None = None

    title = "cam analysis"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.cam.law} cam, {self.lift.max() * 1e3:.3g} mm {'at the valve' if self.at_valve else 'lobe lift'}"

    def describe(self) -> str:
        """The cam in words and tables (what ``springdyn valve cam`` prints): the lift, the event
        and the timing at the check heights (in crank angles with an engine speed or a
        ``[timing]`` table), the lobe centre, the derivatives and the ramps."""
        s = self.summary
        crank = self.axis is not None
        ang = self.axis.unit if crank else "cam deg"

        def a(key):  # an angle in the axis asked for
            v = s.get(key.replace("_deg", "_crank_deg") if crank else key)
            return "-" if v is None else f"{v:.2f}"

        out = [
            f"{self.cam.law} cam at the {'valve' if self.at_valve else 'lobe'}: max lift {s['max_lift_m'] * 1e3:.3f} mm "
            f"at {s['max_lift_cam_angle_deg']:.2f} cam deg"
            + (f" (rocker ratio {s['rocker_ratio']:g}, lash {s['lash_m'] * 1e3:.3g} mm)" if self.at_valve else "")
        ]
        rows = [
            (
                "event (lift > 0)",
                a("event_opening_deg"),
                a("event_closing_deg"),
                f"{s.get('event_duration_deg', 0):.2f}",
            )
        ]
        for key, label in (("0050in", "0.050 in"), ("1mm", "1 mm")):
            if s.get(f"duration_at_{key}_deg") is not None:
                rows.append(
                    (
                        f"at {label}",
                        a(f"opening_at_{key}_deg"),
                        a(f"closing_at_{key}_deg"),
                        f"{s[f'duration_at_{key}_deg']:.2f}",
                    )
                )
            else:
                rows.append((f"at {label}", "-", "-", "lift below the check height"))
        out.append(text_table(rows, headers=("timing", f"opens [{ang}]", f"closes [{ang}]", "duration [cam deg]")))
        out.append(f"lobe centre (mid-way between the 1 mm points): {a('lobe_centre_deg')} {ang}")
        if "timing" in s:
            t = s["timing"]
            out.append(
                f"{self.valve or 'intake'} valve timing ([timing] lobe centre {t['max_lift']} at the maximum lift): "
                + "; ".join(
                    f"at {label} opens {t[f'opening_at_{key}']}, closes {t[f'closing_at_{key}']}"
                    for key, label in (("0050in", "0.050 in"), ("1mm", "1 mm"))
                    if f"opening_at_{key}" in t
                )
            )
        elif crank:
            out.append(
                "crank angles count from the start of the cam's event: give a [timing] table to count them from TDC"
            )
        out.append(
            f"velocity {s['min_velocity_m_per_rad'] * 1e3:.3f} to {s['max_velocity_m_per_rad'] * 1e3:.3f} mm/rad, "
            f"acceleration {s['min_acceleration_m_per_rad2'] * 1e3:.3f} to "
            f"{s['max_acceleration_m_per_rad2'] * 1e3:.3f} mm/rad^2, jerk up to "
            f"{s['max_abs_jerk_m_per_rad3'] * 1e3:.2f} mm/rad^3"
        )
        if self.engine_rpm is not None:
            out.append(
                f"at {self.engine_rpm:g} engine rpm: velocity up to {s['max_velocity_m_per_s']:.3f} m/s, acceleration "
                f"{s['min_acceleration_m_per_s2']:.0f} to {s['max_acceleration_m_per_s2']:.0f} m/s^2"
            )
        if "ramp_height_m" in s:
            out.append(
                f"ramps: {s['ramp_height_m'] * 1e3:.3f} mm over {s['ramp_duration_deg']:.2f} cam deg, "
                f"{s['ramp_velocity_m_per_rad'] * 1e3:.4f} mm/rad"
            )
        return "\n".join(out + notes_lines(s))

    @property
    def cam_omega(self) -> float | None:
        """Cam speed [rad/s] at the engine speed (four-stroke), None without one."""
        return None if self.engine_rpm is None else rpm_to_omega(cam_rpm_from_engine_rpm(self.engine_rpm))

    def _summary(self) -> dict:
        peak = int(np.argmax(self.lift))
        s = dict(
            law=self.cam.law,
            where="valve (rocker ratio and lash of the valve train)" if self.at_valve else "lobe",
            max_lift_m=float(self.lift[peak]),
            max_lift_cam_angle_deg=math.degrees(self.cam_angle[peak]),
            max_velocity_m_per_rad=float(self.velocity.max()),
            min_velocity_m_per_rad=float(self.velocity.min()),
            max_acceleration_m_per_rad2=float(self.acceleration.max()),
            min_acceleration_m_per_rad2=float(self.acceleration.min()),
            max_abs_jerk_m_per_rad3=float(np.abs(self.jerk).max()),
            rocker_ratio=self.ratio,
            lash_m=self.lash,
        )
        open_ = check_height_timing(self.cam_angle, self.lift, 1e-9 * max(self.lift.max(), 1e-12))
        if open_ is not None:
            s["event_opening_deg"], s["event_closing_deg"] = open_["opening_deg"], open_["closing_deg"]
            s["event_duration_deg"] = open_["duration_deg"]
        for name, h in CHECK_HEIGHTS.items():
            t = check_height_timing(self.cam_angle, self.lift, h)
            key = name
            if t is None:
                s[f"duration_at_{key}_deg"] = None
                continue
            s[f"opening_at_{key}_deg"] = t["opening_deg"]
            s[f"closing_at_{key}_deg"] = t["closing_deg"]
            s[f"duration_at_{key}_deg"] = t["duration_deg"]
            if name == "1mm":
                s["lobe_centre_deg"] = t["centre_deg"]  # mid-way between the 1 mm points
        ramp_h = getattr(self.cam, "ramp_height", 0.0) or 0.0
        ramp_phi = getattr(self.cam, "ramp_duration", 0.0) or 0.0
        if ramp_phi > 0:
            s["ramp_height_m"] = self.ratio * ramp_h
            s["ramp_duration_deg"] = math.degrees(ramp_phi)
            s["ramp_velocity_m_per_rad"] = self.ratio * ramp_h / ramp_phi
            if self.at_valve and self.lash >= self.ratio * ramp_h:
                s.setdefault("notes", []).append(
                    f"the lash {self.lash * 1e3:.3g} mm is not taken up on the ramps ({self.ratio * ramp_h * 1e3:.3g} mm "
                    "at the valve): the valve opens on the flank"
                )
        if self.engine_rpm is not None:
            w = self.cam_omega
            s["engine_rpm"] = self.engine_rpm
            s["max_velocity_m_per_s"] = s["max_velocity_m_per_rad"] * w
            s["max_acceleration_m_per_s2"] = s["max_acceleration_m_per_rad2"] * w**2
            s["min_acceleration_m_per_s2"] = s["min_acceleration_m_per_rad2"] * w**2
        if self.axis is not None:
            ax = self.axis
            s["crank_angle_per_cam_angle"] = ax.per_cam
            s["crank_angle_origin"] = "gas-exchange TDC" if ax.referenced else "cam angle 0 (no [timing] table)"
            keys = [k for k in s if k.endswith("_deg") and ("opening" in k or "closing" in k or "centre" in k)]
            keys.append("max_lift_cam_angle_deg")
            for key in keys:
                if s[key] is not None:
                    s[key.replace("_cam_angle_deg", "_deg").replace("_deg", "_crank_deg")] = ax.crank_deg(s[key])
            if ax.referenced:
                s["timing"] = {
                    k.replace("_cam_angle_deg", "").replace("_deg", ""): ax.words(
                        s[k], from_tdc=k.startswith("max_lift")
                    )
                    for k in keys
                    if s[k] is not None and ("opening_at" in k or "closing_at" in k or k == "max_lift_cam_angle_deg")
                }
        return s

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        data = {
            "lift": ("cam_angle", self.lift, {"units": "m"}),
            "velocity": ("cam_angle", self.velocity, {"units": "m/rad"}),
            "acceleration": ("cam_angle", self.acceleration, {"units": "m/rad^2"}),
            "jerk": ("cam_angle", self.jerk, {"units": "m/rad^3"}),
        }
        coords = {"cam_angle": ("cam_angle", np.degrees(self.cam_angle), {"units": "deg"})}
        if self.axis is not None:
            coords["crank_angle"] = ("cam_angle", self.axis.crank_deg(np.degrees(self.cam_angle)), {"units": "deg"})
        if self.engine_rpm is not None:
            w = self.cam_omega
            data["velocity_time"] = ("cam_angle", self.velocity * w, {"units": "m/s"})
            data["acceleration_time"] = ("cam_angle", self.acceleration * w**2, {"units": "m/s^2"})
            data["jerk_time"] = ("cam_angle", self.jerk * w**3, {"units": "m/s^3"})
        return xr.Dataset(data, coords=coords, attrs={"law": self.cam.law, "at_valve": int(self.at_valve)})

    def _plot(self, ax=None):
        """Lift, velocity, acceleration and jerk against cam (or crank) angle; into ``ax``: the lift."""
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        if ax is not None:  # one axes: the lift alone
            fig, axes = ax.figure, [ax]
        else:
            fig, axes = plt.subplots(4, 1, figsize=(8, 9), sharex=True)
        crank = self.engine_rpm is not None  # derivatives in time
        deg = np.degrees(self.cam_angle)
        order = np.arange(deg.size) if self.axis is None else self.axis.plot_order(deg)
        x = (deg if self.axis is None else self.axis.crank_deg(deg))[order]
        w = self.cam_omega if crank else 1.0
        rows = (
            (self.lift * 1e3, "lift [mm]"),
            (self.velocity * w * (1.0 if crank else 1e3), "velocity [m/s]" if crank else "velocity [mm/rad]"),
            (
                self.acceleration * w**2 * (1.0 if crank else 1e3),
                "acceleration [m/s^2]" if crank else "acceleration [mm/rad^2]",
            ),
            (self.jerk * w**3 * (1.0 if crank else 1e3), "jerk [m/s^3]" if crank else "jerk [mm/rad^3]"),
        )
        for a, (y, label) in zip(axes, rows[: len(axes)]):
            a.plot(x, y[order], "C0")
            a.axhline(0.0, color="k", lw=0.6)
            a.set_ylabel(label)
            a.grid(True, alpha=0.3)
        for name, h in CHECK_HEIGHTS.items():
            axes[0].axhline(h * 1e3, color="0.5", ls=":", lw=0.8)
            axes[0].text(
                x[-1], h * 1e3, {"0050in": "0.050 in", "1mm": "1 mm"}[name], fontsize=7, va="bottom", ha="right"
            )
        axes[-1].set_xlabel("cam angle [deg]" if self.axis is None else self.axis.label)
        axes[0].set_title(
            f"{self.cam.law} cam at the {'valve' if self.at_valve else 'lobe'}"
            + (f", {self.engine_rpm:g} engine rpm" if crank else "")
        )
        return fig
