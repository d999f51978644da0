"""Amplitude-consistent unbalance response of a simple rotor on two leaf spring dampers.

The damper's friction terms depend on the vibration amplitude, which the rotor's response
sets: a rotor calculation with coefficients taken at an assumed amplitude (50 um) is not
consistent when the damper actually moves 5-20 um.  Here the describing function of the
damper (:func:`springdyn.lsd.equivalent.forward_whirl_coefficient`, the nonlinear force laws
of the rig on a forward circular orbit) is iterated with the response until the amplitude
at the damper and the coefficients agree.

The rotor (a Jeffcott rotor on flexible, damped supports; e.g. Vance, Zeidan and Murphy,
*Machinery Vibration and Rotordynamics*, 2010, Ch. 3): a disk of mass ``M`` at midspan of a
massless shaft of midspan stiffness ``k``, on two identical dampers, each carrying a
bearing mass ``m_b``; unbalance ``U = M e``.  Symmetric, isotropic, so the synchronous
response is a forward circle; with ``z = x + j y``::

    M z_d'' + c_d z_d' + k (z_d - z_b)          = U w^2 e^(jwt)
    2 m_b z_b''       + k (z_b - z_d) + 2 F(z_b) = 0,   F = H(|z_b|, w) z_b

:func:`simulate_time_response` integrates the same rotor with the nonlinear damper forces
in the time domain (no describing function), to check it.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..core.errors import InputError, SolverError
from ..core.results import Result
from .equivalent import forward_whirl_coefficient
from .model import LSDModel, rpm_to_omega

__all__ = ["JeffcottRotor", "UnbalanceResponse", "unbalance_response", "simulate_time_response"]


@dataclasses.dataclass(frozen=True)
class JeffcottRotor:
    """A symmetric Jeffcott rotor on two identical dampers (SI).

    Parameters
    ----------
    disk_mass : float
        Disk mass ``M`` [kg].
    shaft_stiffness : float
        Midspan stiffness of the shaft relative to its supports ``k`` [N/m].
    bearing_mass : float
        Mass moving with each damper's inner ring (ring, bearing, journal) ``m_b`` [kg].
    unbalance : float
        Unbalance ``U = M e`` [kg m].
    disk_damping : float
        Viscous damping at the disk ``c_d`` [N s/m] (external/material).
    """

    disk_mass: float
    shaft_stiffness: float
    bearing_mass: float
    unbalance: float
    disk_damping: float = 0.0

    def __post_init__(self):
        for name in ("disk_mass", "shaft_stiffness", "unbalance"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and np.isfinite(v) and v > 0):
                raise InputError(f"{name} = {v!r} must be a positive number (SI)")
        for name in ("bearing_mass", "disk_damping"):
            v = getattr(self, name)
            if not (isinstance(v, (int, float)) and np.isfinite(v) and v >= 0):
                raise InputError(f"{name} = {v!r} must be zero or positive (SI)")

    def response(self, omega, H):
        """Complex disk and bearing amplitudes ``(D, B)`` [m] for a damper coefficient ``H`` [N/m].

        Parameters
        ----------
        omega : float
            Spin speed = whirl frequency [rad/s].
        H : complex
            Forward-whirl coefficient of one damper, ``K + j omega C`` [N/m].
        """
        k, M, mb = self.shaft_stiffness, self.disk_mass, self.bearing_mass
        A = np.array([[k - M * omega**2 + 1j * omega * self.disk_damping, -k], [-k, k - 2.0 * mb * omega**2 + 2.0 * H]])
        D, B = np.linalg.solve(A, np.array([self.unbalance * omega**2, 0.0]))
        return D, B


@dataclasses.dataclass(repr=False)
class UnbalanceResponse(Result):
    """Amplitude-consistent unbalance response vs speed.

    Attributes
    ----------
    rpm : numpy.ndarray
        Speeds [rev/min].
    disk_amplitude, bearing_amplitude : numpy.ndarray
        Orbit radii at the disk and at the dampers [m].
    stiffness, damping : numpy.ndarray
        Equivalent coefficients of one damper at the consistent amplitude [N/m], [N s/m];
        NaN where friction holds the ring (``None`` in :meth:`to_dict`, and a note).
    iterations : numpy.ndarray
        Root-finder evaluations per speed [-].
    notes : list of str
        Speeds with several consistent amplitudes (jump phenomenon) and what was reported.
    """

    rpm: np.ndarray
    disk_amplitude: np.ndarray
    bearing_amplitude: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray
    iterations: np.ndarray
    notes: list

    def to_dict(self) -> dict:
        """JSON-ready columns (SI, unit in the name) and the notes."""

        def clean(a):
            return [float(v) if np.isfinite(v) else None for v in a]

        return {
            "rpm": self.rpm.tolist(),
            "disk_amplitude_m": self.disk_amplitude.tolist(),
            "bearing_amplitude_m": self.bearing_amplitude.tolist(),
            "damper_stiffness_N_per_m": clean(self.stiffness),
            "damper_damping_Ns_per_m": clean(self.damping),
            "notes": list(self.notes),
        }

    @property
    def peak(self) -> tuple:
        """``(rpm, disk amplitude [m])`` at the largest disk amplitude of the sweep."""
        k = int(np.argmax(self.disk_amplitude))
        return float(self.rpm[k]), float(self.disk_amplitude[k])

    title = "amplitude-consistent unbalance response"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.rpm.min():g}-{self.rpm.max():g} rpm, {self.rpm.size} speeds"

    def _summary(self) -> dict:
        rpm, amp = self.peak
        locked = ~np.isfinite(self.stiffness)
        return dict(
            peak_rpm=rpm,
            peak_disk_amplitude_m=amp,
            peak_bearing_amplitude_m=float(self.bearing_amplitude[int(np.argmax(self.disk_amplitude))]),
            speeds=int(self.rpm.size),
            speeds_locked=int(locked.sum()),
            notes=list(self.notes),
        )

    def to_xarray(self):
        """Amplitudes and the damper's equivalent coefficients per speed (NaN where it is locked)."""
        import xarray as xr

        return xr.Dataset(
            {
                "disk_amplitude": ("rpm", self.disk_amplitude, {"units": "m", "long_name": "disk orbit radius"}),
                "bearing_amplitude": (
                    "rpm",
                    self.bearing_amplitude,
                    {"units": "m", "long_name": "damper orbit radius"},
                ),
                "damper_stiffness": ("rpm", self.stiffness, {"units": "N/m", "long_name": "equivalent stiffness"}),
                "damper_damping": ("rpm", self.damping, {"units": "N*s/m", "long_name": "equivalent damping"}),
                "locked": (
                    "rpm",
                    (~np.isfinite(self.stiffness)).astype(int),
                    {"units": "", "long_name": "1 where friction holds the ring"},
                ),
            },
            coords={"rpm": ("rpm", np.asarray(self.rpm, dtype=float), {"units": "rpm"})},
        )

    def _csv_dataset(self):
        """The CSV never holds NaN: where friction locks the ring the coefficients are left
        out (the ``locked`` column says where), and so are they when any speed is locked."""
        ds = self.to_xarray()
        if not np.all(np.isfinite(self.stiffness)) or not np.all(np.isfinite(self.damping)):
            ds = ds.drop_vars(["damper_stiffness", "damper_damping"])
        return ds

    def _plot(self, ax=None):
        """Disk and damper amplitudes vs speed [um]."""
        from ..core.plotting import new_figure

        if ax is None:
            fig, ax = new_figure(1, 1, figsize=(7, 4.5))
        ax.plot(self.rpm, self.disk_amplitude * 1e6, label="disk")
        ax.plot(self.rpm, self.bearing_amplitude * 1e6, "--", label="damper")
        ax.set_xlabel("speed [rpm]")
        ax.set_ylabel("orbit radius [um]")
        ax.grid(True, alpha=0.3)
        ax.legend()
        return ax.figure


def _consistent(rotor, model, omega, samples, lo=1e-9, hi=1e-2, grid=40):
    """All consistent damper amplitudes at ``omega``: roots of ``|B(H(A))| - A`` on a log scale."""
    from scipy.optimize import brentq

    count = [0]

    def g(log_a):
        count[0] += 1
        a = float(np.exp(log_a))
        _, B = rotor.response(omega, forward_whirl_coefficient(model, omega, a, samples))
        return np.log(abs(B)) - log_a

    xs = np.linspace(np.log(lo), np.log(hi), grid)
    gs = np.array([g(x) for x in xs])
    roots = []
    for i in range(grid - 1):
        if gs[i] == 0.0:
            roots.append(xs[i])
        elif gs[i] * gs[i + 1] < 0:
            roots.append(brentq(g, xs[i], xs[i + 1], xtol=1e-10, rtol=1e-10, maxiter=100))
    if not roots:
        if gs[0] < 0:  # friction holds the ring: |B| < A down to 1 nm
            return [], count[0]
        raise SolverError(
            f"unbalance_response: no consistent damper amplitude between {lo:g} m and {hi:g} m at "
            f"omega = {omega:.6g} rad/s"
        )
    return [float(np.exp(r)) for r in roots], count[0]


def unbalance_response(model: LSDModel, rotor: JeffcottRotor, rpm, *, samples: int = 1024) -> UnbalanceResponse:
    """Synchronous unbalance response with the damper's coefficients at the response's own amplitude.

    At each speed the damper amplitude ``A`` solves ``A = |B(H(A, omega))|`` (the
    describing-function balance), found by bracketing on a log grid from 1 nm to 10 mm and
    Brent's method (bounded).  With several solutions (friction can give a jump), the
    smallest is reported and a note says so.

    Parameters
    ----------
    model : LSDModel
        The damper (each of the two supports).
    rotor : JeffcottRotor
        The rotor.
    rpm : array_like
        Speeds [rev/min] (the whirl is synchronous: one orbit per revolution).
    samples : int
        Quadrature points per period of the describing function [-].
    """
    if not isinstance(rotor, JeffcottRotor):
        raise InputError(f"rotor must be a JeffcottRotor, got {type(rotor).__name__}")
    rpm = np.atleast_1d(np.asarray(rpm, dtype=float))
    if rpm.ndim != 1 or np.any(~np.isfinite(rpm)) or np.any(rpm <= 0):
        raise InputError(f"rpm = {rpm.tolist()} must be positive speeds")
    out = {k: [] for k in ("disk", "bearing", "K", "C", "n")}
    notes = []
    for r in rpm:
        w = float(rpm_to_omega(r))
        amps, n = _consistent(rotor, model, w, samples)
        if not amps:
            notes.append(
                f"{r:g} rpm: the friction holds the damper ring (no amplitude above 1 nm is consistent): "
                "the supports act rigid; damper coefficients are not defined there"
            )
            D, _ = rotor.response(w, 1e30)
            out["disk"].append(abs(D))
            out["bearing"].append(0.0)
            out["K"].append(np.nan)
            out["C"].append(np.nan)
            out["n"].append(n)
            continue
        if len(amps) > 1:
            notes.append(
                f"{r:g} rpm: {len(amps)} consistent damper amplitudes "
                f"({', '.join(f'{a * 1e6:.3g} um' for a in amps)}); the smallest is reported"
            )
        a = amps[0]
        H = forward_whirl_coefficient(model, w, a, samples)
        D, B = rotor.response(w, H)
        out["disk"].append(abs(D))
        out["bearing"].append(abs(B))
        out["K"].append(H.real)
        out["C"].append(H.imag / w)
        out["n"].append(n)
    return UnbalanceResponse(
        rpm=rpm,
        disk_amplitude=np.array(out["disk"]),
        bearing_amplitude=np.array(out["bearing"]),
        stiffness=np.array(out["K"]),
        damping=np.array(out["C"]),
        iterations=np.array(out["n"]),
        notes=notes,
    )


def simulate_time_response(
    model: LSDModel,
    rotor: JeffcottRotor,
    rpm: float,
    *,
    revolutions: float = 30.0,
    initial=None,
    steps_per_revolution: int = 2000,
):
    """Time-domain unbalance response of the rotor with the nonlinear damper forces.

    The damper force on each bearing is the rig's force law (pack springs with lift-off,
    inter-leaf Coulomb friction on the instantaneous pack load, O-ring Coulomb friction:
    the laws of :mod:`springdyn.lsd.forces`, written out here for scalars; oil), evaluated
    pack by pack; the rotor equations of the module docstring (two dampers) are
    integrated with the classical fixed-step Runge-Kutta method (a fixed step crosses the
    friction switches without the step-size collapse of adaptive solvers; the switches make
    it first order there, so check the step).

    Parameters
    ----------
    model : LSDModel
        The damper.
    rotor : JeffcottRotor
        The rotor (``bearing_mass > 0``).
    rpm : float
        Speed [rev/min].
    revolutions : float
        Revolutions to integrate [-], at most 10 000.
    initial : array_like, optional
        ``[xd, yd, xb, yb, vxd, vyd, vxb, vyb]`` [m, m/s]; default at rest.
    steps_per_revolution : int
        Time steps per revolution [-].

    Returns
    -------
    tuple
        ``(t, states)``: times [s] (one sample every step) and the states (8, T) [m, m/s].
    """
    import math

    if not (np.isfinite(revolutions) and 0 < revolutions <= 10_000):
        raise InputError(f"revolutions = {revolutions!r} must be in (0, 10000]")
    if int(steps_per_revolution) != steps_per_revolution or not 100 <= steps_per_revolution <= 100_000:
        raise InputError(f"steps_per_revolution = {steps_per_revolution!r} must be a whole number in [100, 100000]")
    w = float(rpm_to_omega(rpm))
    if not (np.isfinite(w) and w > 0):
        raise InputError(f"rpm = {rpm!r} must be a positive speed")
    p = model.params
    M, k, mb, cd, U = rotor.disk_mass, rotor.shaft_stiffness, rotor.bearing_mass, rotor.disk_damping, rotor.unbalance
    if mb <= 0:
        raise InputError("simulate_time_response needs bearing_mass > 0 (the damper node needs inertia)")
    cv = [[float(v) for v in row] for row in model.viscous_damping]
    packs = [(math.cos(a), math.sin(a)) for a in model.angles]
    ks, pre = float(model.pack_stiffness), float(p.preload)
    mu_leaf = 1.5 * p.leaf_friction * float(model.slip_factor)
    f_oring = p.oring_friction * p.oring_normal_force

    def damper(x, y, vx, vy):
        fx = cv[0][0] * vx + cv[0][1] * vy
        fy = cv[1][0] * vx + cv[1][1] * vy
        speed = math.hypot(vx, vy)
        for c, s in packs:
            load = ks * max(pre + x * c + y * s, 0.0)
            rate = vx * c + vy * s
            f = load - ks * pre
            if abs(rate) > 1e-9 * speed:
                f += mu_leaf * load * (1.0 if rate > 0 else -1.0)
            fx += f * c
            fy += f * s
        if speed > 0.0:
            fx += f_oring * vx / speed
            fy += f_oring * vy / speed
        return fx, fy

    uw2 = U * w * w

    def rhs(t, st):
        xd, yd, xb, yb, vxd, vyd, vxb, vyb = st
        fx, fy = damper(xb, yb, vxb, vyb)
        return (
            vxd,
            vyd,
            vxb,
            vyb,
            (uw2 * math.cos(w * t) - cd * vxd - k * (xd - xb)) / M,
            (uw2 * math.sin(w * t) - cd * vyd - k * (yd - yb)) / M,
            (-k * (xb - xd) - 2.0 * fx) / (2.0 * mb),
            (-k * (yb - yd) - 2.0 * fy) / (2.0 * mb),
        )

    n = int(round(revolutions * steps_per_revolution))
    h = 2.0 * math.pi / w / steps_per_revolution
    st = [0.0] * 8 if initial is None else [float(v) for v in initial]
    if len(st) != 8 or not all(math.isfinite(v) for v in st):
        raise InputError("initial must hold 8 finite numbers [xd, yd, xb, yb, vxd, vyd, vxb, vyb]")
    out = np.empty((8, n + 1))
    out[:, 0] = st
    t = 0.0
    for i in range(n):
        k1 = rhs(t, st)
        k2 = rhs(t + 0.5 * h, [a + 0.5 * h * b for a, b in zip(st, k1)])
        k3 = rhs(t + 0.5 * h, [a + 0.5 * h * b for a, b in zip(st, k2)])
        k4 = rhs(t + h, [a + h * b for a, b in zip(st, k3)])
        st = [a + h / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4) for a, b1, b2, b3, b4 in zip(st, k1, k2, k3, k4)]
        t += h
        out[:, i + 1] = st
    if not np.all(np.isfinite(out[:, -1])):
        raise SolverError(
            f"simulate_time_response at {rpm:g} rpm: the state diverged (step {h:.3g} s too large "
            "for the damper's oil time constant: raise steps_per_revolution)"
        )
    return np.arange(n + 1) * h, out
