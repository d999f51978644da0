"""Time-domain simulation of the thesis' test rig (Chapter 4).

The inner ring is moved along a prescribed path -- a circular orbit of the eccentric
shaft, an x-only or y-only shake, or any measured ``x(t), y(t)`` -- and the force the
shaft must apply to it (what the load cells measure) is computed with the nonlinear
model, not with the linearised coefficients (the force laws of :mod:`springdyn.lsd.forces`,
summed with the oil and the ring's inertia):

- each pack pushes with ``k_s max(delta_pre + delta_i, 0)`` (it lifts off when the ring
  moves away from it by more than the preload);
- friction between the leaves of each pack is a Coulomb force
  ``1.5 mu_s S P_i sign(d delta_i/dt)`` along the pack, with the instantaneous pack load
  ``P_i`` (Eqs. (2.25)-(2.27) of the thesis, per unit tip deflection rate);
- the O-rings give a Coulomb force ``mu_o F_N`` opposing the ring velocity (2.21);
- the oil network gives ``B^T G^+ B v`` (incompressible oil, docs/references.md), or with
  ``film=True`` the time-domain network with passage inertia and cavitation
  (:mod:`springdyn.lsd.film`);
- the ring's inertia adds ``m a``.

Optional Gaussian sensor noise is added to the measured forces and displacements.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..core.errors import InputError
from ..core.results import Result
from ..core.units import rpm_to_hz, rpm_to_omega
from .forces import interleaf_friction_forces, oring_friction_force, pack_spring_forces
from .model import LSDModel
from .stiffness import warn_if_unloading

__all__ = [
    "RIG_COLUMNS",
    "Trajectory",
    "circular_orbit",
    "linear_shake",
    "trajectory_from_samples",
    "simulate_rig",
    "RigRecord",
]


@dataclasses.dataclass
class Trajectory:
    """A prescribed path of the inner ring: time [s], position [m], velocity [m/s], acceleration [m/s^2]."""

    time: np.ndarray
    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    ax: np.ndarray
    ay: np.ndarray
    excitation: str = "measured"
    rpm: float = float("nan")


#: Most samples one simulated rig record may hold (a few tens of MB of signals).
MAX_SAMPLES = 2_000_000


def _time_base(rpm, revolutions, sample_rate):
    if not (np.isfinite(rpm) and rpm > 0):
        raise InputError(f"rpm = {rpm!r} must be a positive shaft speed")
    if not (np.isfinite(revolutions) and revolutions > 0):
        raise InputError(f"revolutions = {revolutions!r} must be a positive, finite number of revolutions")
    if not (np.isfinite(sample_rate) and sample_rate > 0):
        raise InputError(f"sample_rate = {sample_rate!r} Hz must be positive")
    f = rpm_to_hz(rpm)
    if not sample_rate > 4 * f:
        raise InputError(
            f"sample rate {sample_rate:g} Hz is too low for {rpm:g} rpm ({f:g} Hz); use at least {8 * f:g} Hz"
        )
    n = revolutions / f * sample_rate
    if n > MAX_SAMPLES:
        raise InputError(
            f"rpm = {rpm:g}, revolutions = {revolutions:g} at {sample_rate:g} Hz give {n:.3g} samples, more than "
            f"{MAX_SAMPLES:g}: fewer revolutions, a lower sample rate or a higher speed"
        )
    n = int(round(n))
    return np.arange(n) / sample_rate, rpm_to_omega(rpm)


def circular_orbit(rpm, eccentricity, revolutions=20, sample_rate=20e3, direction=1):
    """Circular orbit of the eccentric shaft: ``x = e cos wt``, ``y = +-e sin wt``.

    Parameters
    ----------
    rpm : float
        Shaft speed [rev/min]; one orbit per revolution.
    eccentricity : float
        Orbit radius [m].
    revolutions : float
        Number of revolutions [-].
    sample_rate : float
        Samples per second [Hz].
    direction : {1, -1}
        Forward (counter-clockwise) or backward orbit.
    """
    if not eccentricity > 0:
        raise InputError(f"eccentricity = {eccentricity!r} m must be positive")
    t, w = _time_base(rpm, revolutions, sample_rate)
    c, s = np.cos(w * t), np.sin(w * t)
    d = 1.0 if direction >= 0 else -1.0
    e = eccentricity
    return Trajectory(
        t,
        e * c,
        d * e * s,
        -e * w * s,
        d * e * w * c,
        -e * w * w * c,
        -d * e * w * w * s,
        excitation="orbit" if d > 0 else "backward-orbit",
        rpm=float(rpm),
    )


def linear_shake(rpm, amplitude, axis="x", revolutions=20, sample_rate=20e3):
    """Straight harmonic shake along ``axis`` ("x" or "y"): ``u = A cos wt`` [m].

    Parameters
    ----------
    rpm : float or array_like
        Shaft speed [rev/min].
    amplitude : float
        Shake amplitude [m].
    axis : str
        Axis of the shake, 'x' or 'y'.
    revolutions : float
        Shaft revolutions to record [-].
    sample_rate : float
        Samples per second [Hz].
    """
    if axis not in ("x", "y"):
        raise InputError(f"axis = {axis!r} must be 'x' or 'y'")
    if not amplitude > 0:
        raise InputError(f"amplitude = {amplitude!r} m must be positive")
    t, w = _time_base(rpm, revolutions, sample_rate)
    u, v, a = amplitude * np.cos(w * t), -amplitude * w * np.sin(w * t), -amplitude * w * w * np.cos(w * t)
    z = np.zeros_like(t)
    if axis == "x":
        return Trajectory(t, u, z, v, z, a, z, excitation="x", rpm=float(rpm))
    return Trajectory(t, z, u, z, v, z, a, excitation="y", rpm=float(rpm))


def trajectory_from_samples(time, x, y, rpm=float("nan")):
    """A measured path; velocity and acceleration by second-order finite differences.

    Parameters
    ----------
    time : array_like
        Sample times [s].
    x : array_like
        Ring displacement along x [m].
    y : array_like
        Ring displacement along y [m].
    rpm : float or array_like
        Shaft speed [rev/min].
    """
    t = np.asarray(time, dtype=float)
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if t.ndim != 1 or t.size < 3 or x.shape != t.shape or y.shape != t.shape:
        raise InputError("time, x and y must be 1-D arrays of the same length (at least 3 samples)")
    if np.any(np.diff(t) <= 0):
        raise InputError(f"time stamps must increase; row {int(np.argmax(np.diff(t) <= 0)) + 2} does not")
    vx, vy = np.gradient(x, t, edge_order=2), np.gradient(y, t, edge_order=2)
    ax, ay = np.gradient(vx, t, edge_order=2), np.gradient(vy, t, edge_order=2)
    return Trajectory(t, x, y, vx, vy, ax, ay, excitation="measured", rpm=float(rpm))


def simulate_rig(
    model: LSDModel, trajectory: Trajectory, *, force_noise=0.0, displacement_noise=0.0, seed=None, film=False
):
    """Reaction forces of the damper along a prescribed ring path.

    By default the oil is the thesis' incompressible, inertia-free network
    (``C_visc v``).  With ``film=True`` the oil network is integrated in time with the
    passage inertia and film rupture (:mod:`springdyn.lsd.film`; pressures absolute, never
    below ``cavitation_pressure``), starting full at the supply pressure; the chamber
    pressures and voids are in ``record.film``.

    Parameters
    ----------
    model : LSDModel
    trajectory : Trajectory
        From :func:`circular_orbit`, :func:`linear_shake` or :func:`trajectory_from_samples`.
    force_noise : float
        Standard deviation of Gaussian noise added to each force channel [N].
    displacement_noise : float
        Standard deviation of Gaussian noise added to each displacement channel [m].
    seed : int, optional
        Seed of the noise generator [-].
    film : bool
        Integrate the oil network with inertia and cavitation (needs uniform time steps).

    Returns
    -------
    RigRecord
    """
    if force_noise < 0 or displacement_noise < 0:
        raise InputError("noise levels must be zero or positive")
    p = model.params
    tr = trajectory
    parts = {}
    fx, fy, loads = pack_spring_forces(model.angles, model.pack_stiffness, p.preload, tr.x, tr.y)
    parts["spring"] = (fx, fy)
    parts["leaf_friction"] = interleaf_friction_forces(
        model.angles, loads, p.leaf_friction, model.slip_factor, tr.vx, tr.vy
    )
    parts["oring_friction"] = oring_friction_force(p.oring_friction, p.oring_normal_force, tr.vx, tr.vy)
    history = None
    if film:
        from .film import film_network, simulate_film

        history = simulate_film(film_network(model), tr.time, tr.vx, tr.vy)
        parts["oil"] = (history.fx, history.fy)
    else:
        Cv = model.viscous_damping
        parts["oil"] = (Cv[0, 0] * tr.vx + Cv[0, 1] * tr.vy, Cv[1, 0] * tr.vx + Cv[1, 1] * tr.vy)
    parts["inertia"] = (p.ring_mass * tr.ax, p.ring_mass * tr.ay)
    total_x = sum(v[0] for v in parts.values())
    total_y = sum(v[1] for v in parts.values())
    rng = np.random.default_rng(seed)
    x, y = tr.x, tr.y
    if displacement_noise > 0:
        x = x + rng.normal(0.0, displacement_noise, x.shape)
        y = y + rng.normal(0.0, displacement_noise, y.shape)
    if force_noise > 0:
        total_x = total_x + rng.normal(0.0, force_noise, total_x.shape)
        total_y = total_y + rng.normal(0.0, force_noise, total_y.shape)
    amplitude = float(np.max(np.hypot(tr.x - tr.x.mean(), tr.y - tr.y.mean())))
    warn_if_unloading(amplitude, p.preload)
    return RigRecord(
        name=p.name,
        excitation=tr.excitation,
        rpm=tr.rpm,
        time=tr.time,
        x=x,
        y=y,
        fx=total_x,
        fy=total_y,
        parts={k: (np.asarray(a), np.asarray(b)) for k, (a, b) in parts.items()},
        preload_exceeded=amplitude > p.preload,
        film=history,
    )


#: The columns of a rig CSV (SI, unit in the name).
RIG_COLUMNS = ("time_s", "x_m", "y_m", "fx_N", "fy_N")
_IRREGULAR_TOLERANCE = 0.01  # relative deviation of a time step from the median step


@dataclasses.dataclass(repr=False)
class RigRecord(Result):
    """Simulated (or measured) rig signals: displacements [m] and reaction forces [N] vs time [s]."""

    name: str
    excitation: str
    rpm: float
    time: np.ndarray
    x: np.ndarray
    y: np.ndarray
    fx: np.ndarray
    fy: np.ndarray
    parts: dict = dataclasses.field(default_factory=dict)
    preload_exceeded: bool = False
    source: str = ""
    row_offset: int = 2  # file row of sample 0 (CSV: header is row 1)
    film: object = None  # FilmHistory of a film=True simulation (pressures, voids)

    title = "leaf spring damper rig record"

    def __post_init__(self):
        self.source = self.source or f"{self.name} {self.excitation}"
        for name in ("time", "x", "y", "fx", "fy"):
            setattr(self, name, np.asarray(getattr(self, name), dtype=float).ravel())
        cols = dict(zip(RIG_COLUMNS, (self.time, self.x, self.y, self.fx, self.fy)))
        n = self.time.size
        for col, v in cols.items():
            if v.size != n:
                raise InputError(f"{self.source}: column {col!r} has {v.size} values, 'time_s' has {n}")
            bad = np.flatnonzero(~np.isfinite(v))
            if bad.size:
                raise InputError(
                    f"{self.source}: row {bad[0] + self.row_offset}, column {col!r}: "
                    f"{v[bad[0]]} is not a finite number ({bad.size} such rows); remove or fill them"
                )
        if n < 8:
            raise InputError(f"{self.source}: only {n} samples; a rig record needs at least 8")
        dt = np.diff(self.time)
        back = np.flatnonzero(dt <= 0)
        if back.size:
            r = back[0] + 1
            raise InputError(
                f"{self.source}: row {r + self.row_offset}, column 'time_s': time stamps must increase "
                f"({self.time[r]!r} s follows {self.time[r - 1]!r} s)"
            )
        step = float(np.median(dt))
        off = np.flatnonzero(np.abs(dt - step) > _IRREGULAR_TOLERANCE * step)
        if off.size:
            r = off[0] + 1
            raise InputError(
                f"{self.source}: row {r + self.row_offset}, column 'time_s': irregular time stamps "
                f"(step {dt[r - 1]:.6g} s against the usual {step:.6g} s); resample to a uniform rate"
            )

    @property
    def sample_rate(self) -> float:
        """Samples per second [Hz]."""
        return 1.0 / float(np.median(np.diff(self.time)))

    @property
    def duration(self) -> float:
        """Span of the record including the last sample interval [s]."""
        return float(self.time[-1] - self.time[0]) + 1.0 / self.sample_rate

    def _repr_caption(self) -> str:
        speed = f"{self.rpm:g} rpm" if np.isfinite(self.rpm) else "measured"
        return f"{self.name}, {self.excitation} excitation, {speed}, {self.time.size} samples"

    def _summary(self) -> dict:
        s = dict(
            name=self.name,
            excitation=self.excitation,
            samples=int(self.time.size),
            duration_s=float(self.time[-1] - self.time[0]) if self.time.size else 0.0,
            x_amplitude_m=float(np.ptp(self.x) / 2),
            y_amplitude_m=float(np.ptp(self.y) / 2),
            fx_amplitude_N=float(np.ptp(self.fx) / 2),
            fy_amplitude_N=float(np.ptp(self.fy) / 2),
            preload_exceeded=bool(self.preload_exceeded),
        )
        if self.film is not None:
            s["min_chamber_pressure_Pa"] = self.film.min_pressure
            s["max_void_volume_m3"] = float(self.film.voids.max())
        s["rpm"] = float(self.rpm) if np.isfinite(self.rpm) else None
        if s["rpm"] is None:
            s["notes"] = ["the shaft speed of a measured record is not known until it is identified"]
        return s

    def columns(self) -> dict:
        """The rig CSV columns ``time_s, x_m, y_m, fx_N, fy_N`` (read back by :mod:`.identify`)."""
        return {"time_s": self.time, "x_m": self.x, "y_m": self.y, "fx_N": self.fx, "fy_N": self.fy}

    def to_xarray(self):
        """``xarray.Dataset`` over ``time`` with the signals and the force parts (the CSV:
        ``time_s, x_m, y_m, fx_N, fy_N``)."""
        import xarray as xr

        data = {
            k: ("time", v, {"units": "m" if k in ("x", "y") else "N"})
            for k, v in (("x", self.x), ("y", self.y), ("fx", self.fx), ("fy", self.fy))
        }
        for k, (a, b) in self.parts.items():
            data[f"fx_{k}"] = ("time", a, {"units": "N", "csv": "no"})
            data[f"fy_{k}"] = ("time", b, {"units": "N", "csv": "no"})
        return xr.Dataset(
            data,
            coords={"time": ("time", self.time, {"units": "s"})},
            attrs={
                "name": self.name,
                "excitation": self.excitation,
                "rpm": self.rpm if np.isfinite(self.rpm) else "unknown",
            },
        )

    def _plot(self, ax=None, cycles=2):
        """Hysteresis loops ``F_x`` vs ``x`` and ``F_y`` vs ``y`` (like Figs. 5.3-5.26 of the thesis).

        Draws the last ``cycles`` periods when the speed is known, else the whole record.
        """
        from ..core.plotting import new_figure

        sel = slice(None)
        if np.isfinite(self.rpm) and self.rpm > 0:
            n = int(round(cycles * 60.0 / self.rpm / np.median(np.diff(self.time))))
            sel = slice(max(0, self.time.size - n), None)
        if ax is not None:
            ax.plot(self.x[sel] * 1e6, self.fx[sel], lw=0.8)
            ax.set_xlabel("x [um]")
            ax.set_ylabel("Fx [N]")
            ax.grid(True, alpha=0.3)
            return ax.figure
        fig, (ax1, ax2) = new_figure(1, 2, figsize=(10, 4.5))
        span_x, span_y = np.ptp(self.x[sel]), np.ptp(self.y[sel])
        # a single-axis shake: draw both forces against the moving axis
        ux, lx = (self.y, "y") if span_x < 1e-3 * span_y else (self.x, "x")
        uy, ly = (self.x, "x") if span_y < 1e-3 * span_x else (self.y, "y")
        ax1.plot(ux[sel] * 1e6, self.fx[sel], lw=0.8)
        ax2.plot(uy[sel] * 1e6, self.fy[sel], lw=0.8, color="C1")
        ax1.set_xlabel(f"{lx} [um]")
        ax1.set_ylabel("Fx [N]")
        ax2.set_xlabel(f"{ly} [um]")
        ax2.set_ylabel("Fy [N]")
        for ax in (ax1, ax2):
            ax.grid(True, alpha=0.3)
            ax.axhline(0, color="k", lw=0.5)
            ax.axvline(0, color="k", lw=0.5)
        speed = f"{self.rpm:g} rpm" if np.isfinite(self.rpm) else "measured"
        fig.suptitle(f"{self.name}: hysteresis loops ({self.excitation}, {speed})")
        return fig
