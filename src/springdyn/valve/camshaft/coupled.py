"""The valves on a twisting camshaft: their periodic steady state by waveform relaxation.

Lobe ``i`` turns at ``theta_i(t) = Omega t + phi_i(t)``, ``phi_i`` the shaft's twist there.  At a
steady cam speed every state is periodic in the nominal angle ``psi = Omega t``, and each valve
train sees the lift ``s_i(theta_i)`` as an equivalent cam table over ``psi`` (in the lobe's own
angle ``u = psi - phase_i``):

    L_i(u) = s(u + phi(u)),  L' = s'(theta) (1 + phi'),  L'' = s''(theta) (1 + phi')^2 + s'(theta) phi''

exactly (:func:`distorted_table`); the existing single-valve engine runs each valve on its
table, unchanged.  The lobe's load torque follows by virtual work, ``Q_i = F_i s'(theta_i)``
(the follower's force on the cam along its axis times the lobe's lift per cam angle;
frictionless, :func:`lobe_torque`), or with the train's ``[follower]`` the drive torque with the
contact's, guide's and pivot's friction (:func:`~springdyn.valve.train.friction.friction_along_cam`,
at the lobe's actual angle and the nominal speed); the shaft's periodic twist under the torques is linear
and solved per harmonic of the cam speed (:func:`~springdyn.valve.camshaft.shaft.periodic_twist`).
The loop (:func:`camshaft_run`): twist -> tables -> valves -> torques -> twist, under-relaxed,
until the twist changes by less than the tolerance.  Its first pass is the rigid shaft (no
twist): each valve then runs on its own cam's table, exactly as alone; ``rigid = true``
stops there.

"The cam angle of every lobe becomes a state" (issue 41) is realised this way for a steady
speed: each lobe's angle is a periodic state found by harmonic balance of the linear shaft,
each valve's by time integration; not integrated together in one system (run-ups on a
twisting shaft are not covered).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ...core.errors import InputError
from ...core.progress import progress
from ...core.units import rpm_to_omega
from ..engine.cam_table import CamTable
from ..run.friction import train_friction_loads
from ..run.settings import CAM_SAMPLES, POINTS_PER_REVOLUTION, SWEEP_POINTS_PER_REVOLUTION, RunSettings
from ..run.setup import prepare
from ..run.simulation import simulate
from ..train.friction import friction_along_cam
from .definition import Camshaft, check_lobes, read_camshaft, shaft_chain
from .results import CamshaftRun, CamshaftSweep, TorsionalModes
from .shaft import harmonics_on_grid, periodic_twist, torsional_modes

__all__ = ["CamshaftModel", "distorted_table", "lobe_torque", "valve_events", "camshaft_run"]

TWO_PI = 2.0 * math.pi


def distorted_table(cam, twist, dtwist, ddtwist) -> CamTable:
    """The lift a lobe gives over its nominal angle on a twisting shaft, as the engine's table.

    ``L(u) = s(u + phi)``, ``L' = s' (1 + phi')``, ``L'' = s'' (1 + phi')^2 + s' phi''`` (the
    chain rule, exact), at the table's nodes ``u_k = 2 pi k / M``.

    Parameters
    ----------
    cam : Cam
        The lobe's cam, ``s(theta)`` (:meth:`~springdyn.valve.cam.definition.Cam.evaluate`).
    twist, dtwist, ddtwist : ndarray (M,)
        The twist at the lobe [rad] and its derivatives per nominal cam angle [-, 1/rad] at the nodes.
    """
    m = np.asarray(twist).size
    u = np.arange(m) * (TWO_PI / m)
    h, dh, ddh = cam.evaluate(u + twist)
    g = 1.0 + dtwist
    return CamTable(
        np.ascontiguousarray(h),
        np.ascontiguousarray(dh * g),
        np.ascontiguousarray(ddh * g * g + dh * ddtwist),
        TWO_PI / m,
    )


def lobe_torque(cam_force, slope):
    """The load torque of a follower on its lobe [N m] by virtual work: ``Q = F ds/dtheta``.

    Parameters
    ----------
    cam_force : ndarray
        The follower's force on the cam along its axis [N] (the simulation's cam contact force).
    slope : ndarray
        The lobe's lift per cam angle at the lobe's actual angle [m/rad].
    """
    return np.asarray(cam_force) * np.asarray(slope)


def valve_events(valve_lift, height: float):
    """Opening, closing and peak angles of a valve over one revolution [rad].

    Opening and closing: where the valve lift crosses ``height`` at the ends of its longest
    stretch above it (linear between samples); peak: the largest lift (a parabola through
    the three samples around it).  None where the valve never reaches ``height``.

    Parameters
    ----------
    valve_lift : ndarray (n,)
        Valve lift at the angles ``2 pi j / n`` [m].
    height : float
        The timing height [m].

    Returns
    -------
    tuple of (float or None)
        Opening, closing, peak [rad], within [0, 2 pi).
    """
    z = np.asarray(valve_lift, dtype=float)
    n = z.size
    step = TWO_PI / n
    up = z > height
    if not up.any() or up.all():
        return None, None, None
    start = np.flatnonzero(up & ~np.roll(up, 1))  # first sample of each stretch above
    lengths = []
    for s in start:
        k = 0
        while up[(s + k) % n]:
            k += 1
        lengths.append(k)
    s = int(start[int(np.argmax(lengths))])
    e = (s + max(lengths) - 1) % n  # its last sample
    a, b = z[s - 1], z[s]
    opening = (s - 1 + (height - a) / (b - a)) * step
    a, b = z[e], z[(e + 1) % n]
    closing = (e + (a - height) / (a - b)) * step
    i = int(np.argmax(z))
    y0, y1, y2 = z[i - 1], z[i], z[(i + 1) % n]
    den = y0 - 2.0 * y1 + y2
    peak = (i + (0.5 * (y0 - y2) / den if den < 0 else 0.0)) * step
    return tuple(float(x % TWO_PI) for x in (opening, closing, peak))


def _moved_breakpoints(breakpoints, twist) -> np.ndarray:
    """Nominal angles where the lobe's actual angle meets its breakpoints: ``u + phi(u) = b``."""
    b = np.asarray(breakpoints, dtype=float)
    if b.size == 0:
        return b
    m = twist.size
    grid = np.arange(m + 1) * (TWO_PI / m)
    per = np.append(twist, twist[0])
    u = b.copy()
    for _ in range(4):  # a contraction: |phi'| << 1
        u = b - np.interp(np.mod(u, TWO_PI), grid, per)
    return np.unique(np.mod(u, TWO_PI))


class CamshaftModel:
    """Several valves on one camshaft with its torsion and its timing drive.

    Parameters
    ----------
    shaft : Camshaft
        The ``[camshaft]`` table.
    lobes : tuple of Lobe
        The lobes with their valve trains and springs (:func:`~springdyn.valve.camshaft.definition.read_camshaft`).
    settings : RunSettings, optional
        How each valve's run is integrated.
    """

    def __init__(self, shaft: Camshaft, lobes, settings: RunSettings | None = None):
        if not isinstance(shaft, Camshaft):
            raise InputError(f"shaft = {shaft!r} must be a Camshaft (the [camshaft] table)")
        self.shaft = shaft
        self.lobes = check_lobes(shaft, tuple(lobes))
        self.settings = RunSettings.of(settings)
        self.chain = shaft_chain(shaft, self.lobes)
        self._setups: dict = {}

    @classmethod
    def from_toml(cls, path, settings: RunSettings | None = None) -> CamshaftModel:
        """A camshaft of its file (``[camshaft]`` and its ``[[camshaft.lobes]]``).

        Parameters
        ----------
        path : str or path-like
            The camshaft file.
        settings : RunSettings, optional
            How each valve's run is integrated.
        """
        shaft, lobes = read_camshaft(path)
        return cls(shaft, lobes, settings)

    def __repr__(self) -> str:
        kind = "rigid" if self.shaft.rigid else "torsional"
        return f"<CamshaftModel: {len(self.lobes)} lobes, {kind} shaft, first mode {self.modes().frequency[0]:.0f} Hz>"

    def replace(self, **changes) -> CamshaftModel:
        """The same lobes on a shaft with other ``[camshaft]`` keys (SI values).

        Parameters
        ----------
        **changes
            Fields of :class:`~springdyn.valve.camshaft.definition.Camshaft`.
        """
        return CamshaftModel(self.shaft.replace(**changes), self.lobes, self.settings)

    def with_settings(self, **changes) -> CamshaftModel:
        """The same camshaft, its valves run with these fields of :class:`RunSettings` changed
        (``points_per_revolution=720``, ``rtol=1e-9``, ...).

        Parameters
        ----------
        **changes
            Fields of :class:`RunSettings` and their values.
        """
        return CamshaftModel(self.shaft, self.lobes, RunSettings.of(self.settings, **changes))

    def setup(self, i: int):
        """The engine's set-up of lobe ``i``'s valve on its own cam (shared by lobes of the same files).

        Parameters
        ----------
        i : int
            The lobe, in the file's order [-].
        """
        lb = self.lobes[i]
        key = (id(lb.spring), id(lb.cam), id(lb.valve_train))
        if key not in self._setups:
            self._setups[key] = prepare(lb.spring, lb.cam, lb.valve_train)
        return self._setups[key]

    def modes(self) -> TorsionalModes:
        """The shaft's torsional modes with the crankshaft's sprocket held (:class:`TorsionalModes`)."""
        c = self.chain
        j, k, _ = c.matrices
        f, shapes = torsional_modes(j, k)
        return TorsionalModes(frequency=f, shapes=shapes, nodes=c.names, position=c.position, inertia=c.inertia)

    def simulate(self, cam_rpm: float, *, quiet: bool = True, points: int | None = None) -> CamshaftRun:
        """The periodic steady state of the shaft and its valves at one cam speed (:class:`CamshaftRun`).

        Parameters
        ----------
        cam_rpm : float
            Cam speed [rev/min].
        quiet : bool
            No progress line.
        points : int, optional
            Output samples per revolution [-] (default: the settings', else 1440).
        """
        return camshaft_run(self, cam_rpm, quiet=quiet, points=points)

    def sweep(self, cam_rpm, *, quiet: bool = True) -> CamshaftSweep:
        """The camshaft at every cam speed of ``cam_rpm`` (:class:`CamshaftSweep`).

        Parameters
        ----------
        cam_rpm : array_like
            Cam speeds [rev/min].
        quiet : bool
            No progress line.
        """
        rpm = np.atleast_1d(np.asarray(cam_rpm, dtype=float))
        points = self.settings.points(SWEEP_POINTS_PER_REVOLUTION)
        runs = [self.simulate(float(r), points=points) for r in progress(rpm, desc="camshaft sweep", quiet=quiet)]
        return CamshaftSweep.of(runs)


def _run_valves(model: CamshaftModel, cam_rpm: float, spectrum, n: int, settings: RunSettings):
    """Each valve on its lobe's distorted table (``spectrum`` None: the rigid shaft, each on its own cam).

    Returns the simulations, each lobe's twist on the output grid [rad] and its load torque [N m],
    in the lobe's own angle."""
    sims, twists, torques = [], [], []
    u = np.arange(n) * (TWO_PI / n)
    for i, lb in enumerate(model.lobes):
        setup = model.setup(i)
        if spectrum is None:
            phi = np.zeros(n)
        else:
            node = model.chain.order[i]
            t, dt, ddt = harmonics_on_grid(spectrum[node], n, CAM_SAMPLES, shift=lb.phase)
            table = distorted_table(lb.cam, t, dt, ddt)
            setup = dataclasses.replace(setup, table=table, breakpoints=_moved_breakpoints(setup.breakpoints, t))
            phi = harmonics_on_grid(spectrum[node], n, n, shift=lb.phase)[0]
        sim = simulate(lb.spring, lb.cam, cam_rpm, valve_train=lb.valve_train, settings=settings, setup=setup)
        sims.append(sim)
        twists.append(phi)
        torques.append(_load_torque(lb, sim, u, phi, rpm_to_omega(cam_rpm)))
    return sims, np.array(twists), np.array(torques)


def _load_torque(lobe, sim, u, phi, omega: float) -> np.ndarray:
    """A lobe's load torque [N m] over its own angle ``u``: ``F s'`` (:func:`lobe_torque`), or with
    the train's ``[follower]`` the drive torque with the contact's, the guide's and a pivot's
    friction (:func:`~springdyn.valve.train.friction.friction_along_cam`) at the lobe's actual angle."""
    h, dh, ddh = lobe.cam.evaluate(u + phi)
    if lobe.follower is None:
        return lobe_torque(sim.cam_contact_force, dh)
    force = np.maximum(sim.cam_contact_force, 0.0)
    loads = train_friction_loads(sim, lobe.friction)
    return friction_along_cam(u, float(omega), h, dh, ddh, force, lobe.follower, lobe.friction, **loads).drive_torque


def _shaft_frame(model: CamshaftModel, per_lobe: np.ndarray) -> np.ndarray:
    """Arrays over each lobe's own angle moved to the shaft's nominal angle (rows in the file's order)."""
    n = per_lobe.shape[-1]
    out = np.empty_like(per_lobe)
    for i, lb in enumerate(model.lobes):
        out[i] = np.roll(per_lobe[i], _grid_shift(lb.phase, n, lb.name))
    return out


def _grid_shift(phase: float, n: int, name: str) -> int:
    """The lobe's phase in output samples (it must fall on the grid)."""
    m = phase / (TWO_PI / n)
    if abs(m - round(m)) > 1e-6:
        raise InputError(
            f"{name}: phase = {math.degrees(phase):.6g} deg must be a multiple of the output step "
            f"{360.0 / n:g} deg (points_per_revolution = {n})"
        )
    return int(round(m)) % n


def camshaft_run(model: CamshaftModel, cam_rpm: float, *, quiet: bool = True, points: int | None = None) -> CamshaftRun:
    """The periodic steady state of a camshaft at one speed by waveform relaxation (module docstring).

    Parameters
    ----------
    model : CamshaftModel
        The shaft and its lobes.
    cam_rpm : float
        Cam speed [rev/min].
    quiet : bool
        No progress line.
    points : int, optional
        Output samples per revolution [-].
    """
    number = (int, float, np.integer, np.floating)
    if isinstance(cam_rpm, bool) or not isinstance(cam_rpm, number) or not (cam_rpm > 0 and math.isfinite(cam_rpm)):
        raise InputError(f"cam_rpm = {cam_rpm!r} must be a positive speed: a finite number [rev/min]")
    shaft, chain = model.shaft, model.chain
    n = int(points or model.settings.points(POINTS_PER_REVOLUTION))
    settings = RunSettings.of(model.settings, points_per_revolution=n)
    shifts = [_grid_shift(lb.phase, n, lb.name) for lb in model.lobes]
    omega = rpm_to_omega(cam_rpm)
    j, k, c = chain.matrices
    drag = -chain.ground_damping * omega  # the bearings' mean drag on each node [N m]
    rigid_sims, _, torque = _run_valves(model, cam_rpm, None, n, settings)
    sims, twist_local = rigid_sims, np.zeros((len(model.lobes), n))
    spectrum = np.zeros((j.shape[0], n // 2 + 1), dtype=complex)
    iterations, residual, converged, history = 0, 0.0, True, []
    # the harmonics of the twist that act back on the valves (the rest: the valves drive the shaft only)
    fed = (np.arange(n // 2 + 1) * rpm_to_omega(cam_rpm) / TWO_PI <= shaft.feedback_frequency)[None, :]
    full = spectrum
    if not shaft.rigid:
        converged = False
        mixer = AndersonMixing(shaft.anderson_memory, shaft.relaxation)
        for _ in progress(range(shaft.max_iterations), desc=f"camshaft at {cam_rpm:g} cam rpm", quiet=quiet):
            node_torque = np.zeros((j.shape[0], n))
            for i, s in enumerate(shifts):
                node_torque[chain.order[i]] -= np.roll(torque[i], s)
            full = periodic_twist(j, k, c, node_torque, omega, mean_torque=drag)
            new = full * fed
            residual = float(np.max(np.abs(np.fft.irfft(new - spectrum, n=n, axis=-1))))
            history.append(residual)
            if residual <= shaft.tolerance:
                converged = True
                break
            spectrum = mixer.next(spectrum, new)
            iterations += 1
            sims, twist_local, torque = _run_valves(model, cam_rpm, spectrum, n, settings)
    phi0, dphi0, _ = harmonics_on_grid(full[0], n, n)
    lobe_q = _shaft_frame(model, torque)
    if shaft.rigid:
        drive = lobe_q.sum(axis=0) - drag.sum()
    else:
        drive = -(chain.drive_stiffness * phi0 + chain.drive_damping * omega * dphi0)
    twist_nodes = np.fft.irfft(full, n=n, axis=-1)
    events = np.array([[_or_nan(e) for e in valve_events(s.valve_lift, shaft.timing_lift)] for s in sims])
    rigid_events = np.array([[_or_nan(e) for e in valve_events(s.valve_lift, shaft.timing_lift)] for s in rigid_sims])
    error = np.mod(events - rigid_events + math.pi, TWO_PI) - math.pi
    return CamshaftRun(
        cam_rpm=float(cam_rpm),
        cam_angle=np.arange(n) * (TWO_PI / n),
        lobe_names=tuple(lb.name for lb in model.lobes),
        lobe_phase=np.array([lb.phase for lb in model.lobes]),
        drive_torque=drive,
        lobe_torque=lobe_q,
        twist=twist_nodes[chain.order],
        sprocket_twist=twist_nodes[0],
        valve_lift=_shaft_frame(model, np.array([s.valve_lift for s in sims])),
        cam_contact_force=_shaft_frame(model, np.array([s.cam_contact_force for s in sims])),
        events=events,
        timing_error=error,
        iterations=iterations,
        residual=residual,
        converged=converged,
        rigid=shaft.rigid,
        tolerance=shaft.tolerance,
        residual_history=np.array(history),
        modes_Hz=model.modes().frequency,
        bearing_drag=float(-drag.sum()),
        simulations=tuple(sims),
        rigid_simulations=tuple(rigid_sims),
        timing_lift=shaft.timing_lift,
    )


class AndersonMixing:
    """Anderson acceleration of the fixed-point iteration ``x = G(x)`` (type II, [Walker-Ni]).

    With the residuals ``f_k = G(x_k) - x_k`` of the last ``memory`` iterates, the next iterate is
    ``x_{k+1} = G(x_k) - dG gamma - (1 - beta) (f_k - dF gamma)``, ``gamma`` the least-squares
    solution of ``dF gamma = f_k`` (``dF``, ``dG`` the differences of consecutive residuals and
    images); memory 0 is plain relaxation ``x + beta f``.  It converges where plain iteration
    diverges on a few unstable directions (here the lightly damped shaft modes the valves'
    contacts couple to), as GMRES would on the linearised map.

    Parameters
    ----------
    memory : int
        Iterates kept [-].
    beta : float
        Relaxation [-], in (0, 1].
    """

    def __init__(self, memory: int, beta: float):
        self.memory, self.beta = int(memory), float(beta)
        self.f: list = []
        self.g: list = []

    def next(self, x, gx):
        """The next iterate from ``x`` and its image ``gx`` (arrays of any shape, complex allowed).

        Parameters
        ----------
        x, gx : ndarray
            The iterate and ``G(x)``.
        """
        shape = np.shape(x)
        xv = _real(x)
        gv = _real(gx)
        f = gv - xv
        self.f.append(f)
        self.g.append(gv)
        if self.memory == 0 or len(self.f) < 2:
            if self.memory == 0:
                self.f, self.g = [], []
            return _complex(xv + self.beta * f, shape)
        self.f, self.g = self.f[-(self.memory + 1) :], self.g[-(self.memory + 1) :]
        d_f = np.diff(np.array(self.f), axis=0).T
        d_g = np.diff(np.array(self.g), axis=0).T
        gamma = np.linalg.lstsq(d_f, f, rcond=None)[0]
        out = gv - d_g @ gamma - (1.0 - self.beta) * (f - d_f @ gamma)
        return _complex(out, shape)


def _real(z) -> np.ndarray:
    z = np.asarray(z, dtype=complex).ravel()
    return np.concatenate([z.real, z.imag])


def _complex(v, shape) -> np.ndarray:
    h = v.size // 2
    return (v[:h] + 1j * v[h:]).reshape(shape)


def _or_nan(x):
    return math.nan if x is None else x
