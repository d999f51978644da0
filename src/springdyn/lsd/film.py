"""The oil network in the time domain: passage inertia and film rupture (cavitation).

The coefficient model treats the oil as incompressible and inertia-free:
``p = G^+ B v`` (:mod:`springdyn.lsd.damping`).  Here the network is integrated in time with

- **inertia of the oil in the passages**: the pressure drop across the passages between
  chambers ``k`` and ``k+1`` is ``R q_k + I dq_k/dt`` (``R = 1/C_D``, inertance
  ``I = kappa rho L_h / A`` of :func:`~springdyn.lsd.damping.passage_inertance`);
- **film rupture / gaseous cavitation**, a mass-conserving void model: a chamber holds an
  oil volume and a void (released gas or vapour) volume ``V_g >= 0``.  While ``V_g > 0`` its
  pressure is the cavitation pressure ``p_cav``; while ``V_g = 0`` the pressure is whatever
  continuity needs, but never below ``p_cav``.  A voided chamber must be refilled (its void
  driven back to zero by the flow balance) before its pressure can rise again.  This is the
  lumped form of the Jakobsson-Floberg-Olsson conditions used for squeeze-film dampers
  (e.g. Elrod, *A cavitation algorithm*, J. Lubr. Technol. 103, 1981): ``p >= p_cav``,
  ``V_g >= 0``, ``(p - p_cav) V_g = 0``, a linear complementarity problem at every step;
- **the supply**: a feed of conductance ``g_f`` from the supply (pressure ``p_s``) acts on
  the mean chamber pressure ``pbar``: each chamber receives ``g_f (p_s - pbar)``.  It holds
  ``pbar = p_s`` while no chamber is cavitated (so it changes neither the damping nor the
  added mass: ``B`` is orthogonal to the mean) and sets how fast the gas inventory
  ``sum V_g`` settles; at the periodic steady state the mean chamber pressure over a cycle
  equals the supply pressure whatever ``g_f``.

Time stepping: implicit (backward) Euler for the passage flows and the voids, with the
pressures of step ``n+1`` from the complementarity problem (Moreau's time stepping for
non-smooth systems); first order, convergence shown by halving the step in the tests.

Pressures here are **absolute** [Pa]; the force the shaft applies to the ring is
``F = B^T p`` (``B^T 1 = 0``, so the mean pressure exerts no force).
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.optimize import brentq, nnls

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError, SolverError
from ..core.results import Result
from ..core.units import omega_to_rpm, rpm_to_omega
from .damping import chamber_pressures

__all__ = [
    "AERATED_CAVITATION_PRESSURE",
    "FilmWarning",
    "FilmNetwork",
    "film_network",
    "solve_lcp",
    "simulate_film",
    "FilmHistory",
    "film_harmonic",
    "film_effect_map",
    "FilmMap",
    "DEFAULT_FEED_RATIO",
    "DEFAULT_STEPS_PER_CYCLE",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    model : LSDModel
        The damper.
    dt : float
        Time step [s].
    """
)

#: Default feed conductance of the time-domain network as a fraction of the passage
#: conductance ``C_D`` [-].  It acts on the mean pressure only (see the module docstring).
DEFAULT_FEED_RATIO = 0.05
#: Time steps per vibration period of :func:`film_harmonic` [-].
DEFAULT_STEPS_PER_CYCLE = 512

#: Cavitation pressure of air-saturated oil [Pa] (absolute), the figure beside the configured one (issue
#: 40): oil from a vented sump holds air dissolved at atmospheric pressure and releases it as the film's
#: pressure falls below that (gaseous cavitation, Zeidan and Vance 1990; Diaz and San Andres 2001,
#: docs/references.md), long before the vapour limit (0 bar).  0.9 bar, 0.11 bar below the atmosphere,
#: leaves an atmospheric supply a margin about nine times smaller than the vapour limit's.
AERATED_CAVITATION_PRESSURE = 0.9e5


class FilmWarning(UserWarning):
    """The film cavitates: the linear oil coefficients overstate its force."""


def solve_lcp(M, r):
    """Solve the linear complementarity problem ``u >= 0, w = M u + r >= 0, u.w = 0``.

    ``M`` symmetric positive definite: the problem is the quadratic programme
    ``min 1/2 u^T M u + r^T u, u >= 0``, written as the non-negative least-squares problem
    ``min |U u - b|``, ``M = U^T U`` (Cholesky), ``U^T b = -r`` (Lawson and Hanson,
    *Solving Least Squares Problems*, 1974; ``scipy.optimize.nnls``).

    Parameters
    ----------
    M : numpy.ndarray
        Symmetric positive definite matrix (n x n) [any consistent unit].
    r : numpy.ndarray
        Vector (n) [unit of ``M u``].

    Returns
    -------
    numpy.ndarray
        ``u``.
    """
    U = np.linalg.cholesky(M).T
    b = -np.linalg.solve(U.T, r)
    u, _ = nnls(U, b)
    return u


@dataclasses.dataclass
class FilmNetwork:
    """A ring of ``N`` chambers joined by inertial passages, with cavitation and a supply.

    Attributes
    ----------
    volume_matrix : numpy.ndarray
        ``B`` (N x 2) [m^2].
    conductance : float
        ``C_D`` of each boundary [m^3/(s Pa)].
    inertance : float
        ``I`` of each boundary [Pa s^2/m^3]; 0 is the inertia-free network.
    supply_pressure : float
        Supply pressure, absolute [Pa].
    cavitation_pressure : float
        Cavitation pressure, absolute [Pa].
    feed_conductance : float
        Supply feed acting on the mean pressure [m^3/(s Pa)].
    """

    volume_matrix: np.ndarray
    conductance: float
    inertance: float
    supply_pressure: float
    cavitation_pressure: float
    feed_conductance: float

    def __post_init__(self):
        B = np.asarray(self.volume_matrix, dtype=float)
        self.volume_matrix = B
        n = B.shape[0]
        if n < 2:
            raise InputError("the oil network needs at least 2 chambers")
        if not (self.conductance > 0 and self.inertance >= 0 and self.feed_conductance > 0):
            raise InputError(
                f"conductance = {self.conductance!r} m^3/(s Pa) and feed_conductance = {self.feed_conductance!r} "
                f"m^3/(s Pa) must be positive, inertance = {self.inertance!r} Pa s^2/m^3 zero or positive"
            )
        if not self.supply_pressure > self.cavitation_pressure:
            raise InputError(
                f"supply pressure {self.supply_pressure:g} Pa (absolute) must be above the cavitation pressure "
                f"{self.cavitation_pressure:g} Pa (absolute)"
            )
        # incidence: (D q)_i = q_i - q_(i-1) is the outflow of chamber i; passage k joins chambers k, k+1
        D = np.eye(n) - np.roll(np.eye(n), 1, axis=0)  # N = 2: two boundaries, as chamber_laplacian
        self._D = D
        self._L = D @ D.T
        self.reset()

    @property
    def chambers(self) -> int:
        """Number of chambers ``N`` [-]."""
        return self.volume_matrix.shape[0]

    def reset(self, void=0.0, flow=None):
        """Start from given voids [m^3] (scalar: that total spread evenly) and passage flows [m^3/s].

        Parameters
        ----------
        void : float or array_like
            Void volume per chamber, or a total spread over the chambers [m^3].
        flow : array_like, optional
            Passage flows [m^3/s] (default 0).
        """
        n = self.chambers
        v = np.asarray(void, dtype=float)
        self.void = np.full(n, float(v) / n) if v.ndim == 0 else v.copy()
        self.flow = np.zeros(n) if flow is None else np.asarray(flow, dtype=float).copy()
        self._cache = {}

    def _matrices(self, dt):
        key = float(dt)
        if key not in self._cache:
            n = self.chambers
            R = 1.0 / self.conductance
            beta = 1.0 / (self.inertance / dt + R)
            M = dt * (beta * self._L + self.feed_conductance / n * np.ones((n, n)))
            U = np.linalg.cholesky(M).T
            self._cache = {key: (beta, M, U)}
        return self._cache[key]

    def kinematic_flows(self, velocity):
        """Passage flows ``q`` [m^3/s] of the full, incompressible network for ring velocity ``v``.

        ``D q = B v`` with no circulation around the ring (``sum q = 0``).

        Parameters
        ----------
        velocity : array_like
            Ring velocity ``(vx, vy)`` [m/s].
        """
        return np.linalg.pinv(self._D) @ (self.volume_matrix @ np.asarray(velocity, dtype=float))

    @_DOCS.fill
    def step_terms(self, dt):
        """The step's linear complementarity data without the squeeze term.

        ``void_(n+1) = M (p - p_cav) + base - dt B v_(n+1)`` and ``q_(n+1) = beta D^T p + h``.

        Parameters
        ----------
        {dt}

        Returns
        -------
        tuple
            ``(M [m^3/Pa], base [m^3], beta [m^3/(s Pa)], h [m^3/s])``.
        """
        beta, M, _ = self._matrices(dt)
        h = beta * self.inertance / dt * self.flow  # flow carried over by inertia
        base = self.void + dt * (
            self._D @ h - self.feed_conductance * (self.supply_pressure - self.cavitation_pressure)
        )
        return M, base, beta, h

    def commit(self, pressures, void, beta, h):
        """Take the step's solution: pressures [Pa], voids [m^3] and the passage flows that follow.

        Parameters
        ----------
        pressures : numpy.ndarray
            Absolute chamber pressures [Pa].
        void : numpy.ndarray
            Void volumes [m^3].
        beta : float
            From :meth:`step_terms` [m^3/(s Pa)].
        h : numpy.ndarray
            From :meth:`step_terms` [m^3/s].
        """
        self.void = np.maximum(void, 0.0)
        self.flow = beta * (self._D.T @ pressures) + h

    @_DOCS.fill
    def step(self, velocity, dt):
        """Advance one step of ``dt`` [s] to ring velocity ``velocity`` [m/s]; return the pressures [Pa].

        Parameters
        ----------
        velocity : array_like
            Ring velocity ``(vx, vy)`` at the end of the step [m/s].
        {dt}

        Returns
        -------
        numpy.ndarray
            Absolute chamber pressures at the end of the step (``>= p_cav``) [Pa].
        """
        M, base, beta, h = self.step_terms(dt)
        U = self._matrices(dt)[2]
        r = base - dt * (self.volume_matrix @ np.asarray(velocity, dtype=float))
        b = -np.linalg.solve(U.T, r)
        u, _ = nnls(U, b)
        p = self.cavitation_pressure + u
        self.commit(p, M @ u + r, beta, h)
        return p

    def force(self, pressures):
        """Force the shaft applies to the ring ``B^T p`` [N].

        Parameters
        ----------
        pressures : array_like
            Chamber pressures [Pa] (absolute or gauge: the mean exerts no force).
        """
        return np.asarray(pressures, dtype=float) @ self.volume_matrix


def film_network(model, *, inertia: bool = True, feed_ratio: float = DEFAULT_FEED_RATIO) -> FilmNetwork:
    """The :class:`FilmNetwork` of an :class:`~springdyn.lsd.LSDModel`.

    Parameters
    ----------
    model : LSDModel
        The damper (its ``supply_pressure``, ``cavitation_pressure``, passages and oil).
    inertia : bool
        Include the passage inertance (``False``: the inertia-free network of the
        coefficient model, with cavitation).
    feed_ratio : float
        Feed conductance over ``C_D`` [-] (acts on the mean pressure only).
    """
    if not (np.isfinite(feed_ratio) and feed_ratio > 0):
        raise InputError(f"feed_ratio = {feed_ratio!r} must be positive")
    p = model.params
    return FilmNetwork(
        model.volume_matrix,
        model.conductance,
        model.inertance if inertia else 0.0,
        p.supply_pressure_absolute,
        p.cavitation_pressure,
        feed_ratio * model.conductance,
    )


@dataclasses.dataclass
class FilmHistory:
    """Time histories of the network: pressures [Pa] (absolute), voids [m^3], force [N]."""

    time: np.ndarray
    pressures: np.ndarray
    voids: np.ndarray
    fx: np.ndarray
    fy: np.ndarray

    @property
    def min_pressure(self) -> float:
        """Lowest chamber pressure of the history, absolute [Pa]."""
        return float(self.pressures.min())


def simulate_film(network: FilmNetwork, time, vx, vy, *, start_kinematic: bool = True) -> FilmHistory:
    """Integrate the network along ring velocities ``vx(t), vy(t)`` (uniform time steps).

    Parameters
    ----------
    network : FilmNetwork
        The network (its current voids are the initial state).
    time : array_like
        Uniform sample times [s].
    vx, vy : array_like
        Ring velocity [m/s].
    start_kinematic : bool
        Start the passage flows at the full network's flows for the first velocity
        (no start-up transient of the inertia).
    """
    t = np.asarray(time, dtype=float)
    vx, vy = np.asarray(vx, dtype=float), np.asarray(vy, dtype=float)
    if t.ndim != 1 or t.size < 2 or vx.shape != t.shape or vy.shape != t.shape:
        raise InputError("time, vx and vy must be 1-D arrays of equal length (at least 2 samples)")
    dt = np.diff(t)
    step = float(np.median(dt))
    if not (step > 0 and np.all(np.abs(dt - step) <= 1e-6 * step)):
        raise InputError("simulate_film needs uniform, increasing time steps")
    n = network.chambers
    if start_kinematic:
        network.flow = network.kinematic_flows((vx[0], vy[0]))
    P = np.empty((t.size, n))
    V = np.empty((t.size, n))
    P[0] = network.supply_pressure + np.linalg.pinv(network._L * network.conductance) @ (
        network.volume_matrix @ np.array([vx[0], vy[0]])
    )
    P[0] = np.maximum(P[0], network.cavitation_pressure)
    V[0] = network.void
    for k in range(1, t.size):
        P[k] = network.step((vx[k], vy[k]), step)
        V[k] = network.void
    F = P @ network.volume_matrix
    return FilmHistory(t, P, V, F[:, 0], F[:, 1])


def _cycle_run(network, X, Y, omega, void_total, steps, cycles):
    """Run ``cycles`` periods of ``x = Re(X e^(jwt))`` from a void inventory; last period's results."""
    T = 2.0 * np.pi / omega
    dt = T / steps
    t = np.arange(cycles * steps + 1) * dt
    e = np.exp(1j * omega * t)
    vx, vy = np.real(1j * omega * X * e), np.real(1j * omega * Y * e)
    network.reset(void=void_total)
    hist = simulate_film(network, t, vx, vy)
    last = slice(t.size - steps, t.size)
    return hist, last, e


@_DOCS.fill
def film_harmonic(
    model,
    X,
    Y,
    omega,
    *,
    inertia: bool = True,
    steps: int = DEFAULT_STEPS_PER_CYCLE,
    cycles: int = 3,
    feed_ratio: float = 1e-6,
):
    """First-harmonic oil force on a harmonic ring motion at the periodic steady state.

    The ring moves along ``x = Re(X e^(jwt))``, ``y = Re(Y e^(jwt))``.  Without cavitation
    (the linear network's lowest pressure stays above ``p_cav``) the network is linear and the
    harmonic is ``(jw C_visc - w^2 M_a) X`` exactly.  Otherwise the gas inventory ``sum V_g`` is
    found (Brent's method) such that the mean chamber pressure over a period equals the supply
    pressure -- the periodic steady state of a slow supply feed (:mod:`springdyn.lsd.film`) --
    and the last of ``cycles`` simulated periods gives the harmonic.

    Parameters
    ----------
    {model}
    X, Y : complex
        Displacement phasors [m].
    omega : float
        Vibration frequency [rad/s].
    inertia : bool
        Include the passage inertance.
    steps : int
        Time steps per period [-].
    cycles : int
        Simulated periods per trial inventory (the last one is used) [-].
    feed_ratio : float
        Feed conductance over ``C_D`` during the simulated periods [-] (small: the inventory
        is held while its value is searched).

    Returns
    -------
    tuple
        ``(Fx, Fy, info)``: complex force phasors [N] and a dict with ``cavitated`` (bool),
        ``void_inventory_m3``, ``min_pressure_Pa`` (absolute), ``mean_pressure_residual_Pa``
        (the steady-state condition's residual) and ``history`` (the last period, or None).
    """
    if not (np.isfinite(omega) and omega > 0):
        raise InputError(f"omega = {omega!r} rad/s must be positive")
    steps, cycles = int(steps), int(cycles)
    if steps < 32 or cycles < 1:
        raise InputError(f"steps = {steps} must be at least 32 and cycles = {cycles} at least 1")
    p = model.params
    B = model.volume_matrix
    tau = model.film_time_constant if inertia else 0.0
    H_oil = 1j * omega * model.viscous_damping * (1.0 + 1j * omega * tau)
    F_lin = H_oil @ np.array([X, Y], dtype=complex)
    # linear pressure phasors (gauge): p = G^+ B (1 + j w tau) j w x
    p_phasor = chamber_pressures(B, model.conductance, np.array([X, Y], dtype=complex)) * (
        1j * omega * (1.0 + 1j * omega * tau)
    )
    margin = p.supply_pressure_absolute - p.cavitation_pressure
    info = dict(cavitated=False, void_inventory_m3=0.0, history=None, mean_pressure_residual_Pa=0.0)
    if np.max(np.abs(p_phasor)) <= margin:
        info["min_pressure_Pa"] = float(p.supply_pressure_absolute - np.max(np.abs(p_phasor)))
        return complex(F_lin[0]), complex(F_lin[1]), info
    net = film_network(model, inertia=inertia, feed_ratio=feed_ratio)

    def residual(void_total):
        hist, last, _ = _cycle_run(net, X, Y, omega, void_total, steps, cycles)
        return float(np.mean(hist.pressures[last])) - p.supply_pressure_absolute

    # bracket: no gas lifts the mean above p_s; enough gas to keep every chamber voided drops it to p_cav
    swept = float(np.max(np.abs(B @ np.array([X, Y], dtype=complex))))
    lo, hi = 0.0, 2.0 * B.shape[0] * swept
    r_lo = residual(lo)
    if r_lo <= 0:
        void = lo
    else:
        r_hi = residual(hi)
        tries = 0
        while r_hi > 0:
            lo, hi, tries = hi, hi * 4.0, tries + 1
            if tries > 20:
                raise SolverError("film_harmonic: no gas inventory brings the mean pressure down to the supply")
            r_hi = residual(hi)
        void = brentq(residual, lo, hi, xtol=1e-6 * swept, rtol=1e-10)
    hist, last, e = _cycle_run(net, X, Y, omega, void, steps, cycles)
    conj = np.conj(e[last]) * (2.0 / steps)
    # rectangle rule over one period: samples at the step ends of the last period
    Fx = complex(np.sum(hist.fx[last] * conj))
    Fy = complex(np.sum(hist.fy[last] * conj))
    info.update(
        cavitated=True,
        void_inventory_m3=float(void),
        min_pressure_Pa=float(hist.pressures[last].min()),
        mean_pressure_residual_Pa=float(np.mean(hist.pressures[last]) - p.supply_pressure_absolute),
        history=FilmHistory(hist.time[last], hist.pressures[last], hist.voids[last], hist.fx[last], hist.fy[last]),
    )
    return Fx, Fy, info


# ---------------------------------------------------------------- where the film effects matter


@_DOCS.fill
def film_effect_map(model, rpm, amplitudes, *, steps: int = DEFAULT_STEPS_PER_CYCLE, progress=None):
    """Where fluid inertia and where cavitation change the oil force, over speed and orbit.

    On forward circular orbits (the unbalance response of a rotor) of radius ``A`` at the
    vibration frequency ``omega = 2 pi rpm / 60``:

    - **inertia**: ``|H_inertial - H_visc| / |H_visc| = omega tau`` (the lumped passage; the
      same for every orbit while the film is whole), against the thesis' inertia-free
      ``H_visc = j omega C_visc``;
    - **cavitation**: ``|H_film - H_lin| / |H_lin|``, the film network's first harmonic at its
      periodic steady state (:func:`film_harmonic`) against the linear network with inertia
      ``H_lin = j omega C_visc (1 + j omega tau)``;
    - **both** against the thesis' network: ``|H_film - H_visc| / |H_visc|``.

    Parameters
    ----------
    {model}
    rpm : array_like
        Vibration frequencies as shaft speeds [rev/min].
    amplitudes : array_like
        Orbit radii [m].
    steps : int
        Time steps per period of the film simulations [-].
    progress : callable, optional
        Wraps the iterable of speed indices (e.g. :func:`springdyn.core.progress.progress`).

    Returns
    -------
    FilmMap
    """

    rpm = np.atleast_1d(np.asarray(rpm, dtype=float))
    amps = np.atleast_1d(np.asarray(amplitudes, dtype=float))
    if rpm.ndim != 1 or np.any(~np.isfinite(rpm)) or np.any(rpm <= 0):
        raise InputError(f"rpm = {rpm.tolist()} must be positive speeds")
    if amps.ndim != 1 or np.any(~np.isfinite(amps)) or np.any(amps <= 0):
        raise InputError(f"amplitudes = {amps.tolist()} m must be positive")
    w = rpm_to_omega(rpm)
    tau = model.film_time_constant
    cv = model.viscous_damping
    cav = np.zeros((rpm.size, amps.size))
    both = np.zeros_like(cav)
    residual = np.zeros_like(cav)
    p_amp = np.zeros_like(cav)
    min_p = np.zeros_like(cav)
    diag = model.film_diagnostics(w, 1.0)
    for i in (progress or iter)(range(w.size)):
        wi = w[i]
        # forward whirl z = A e^(jwt) of the linear network: (F_x + j F_y) / (2 A) for x = Re(A e^(jwt)), y = Re(-j A e^(jwt))
        h_visc = 1j * wi * (cv[0, 0] + cv[1, 1] + 1j * (cv[1, 0] - cv[0, 1])) / 2.0
        h_lin = h_visc * (1.0 + 1j * wi * tau)
        for j, a in enumerate(amps):
            fx, fy, info = film_harmonic(model, a, -1j * a, wi, steps=steps)
            h = (fx + 1j * fy) / (2.0 * a)
            cav[i, j] = abs(h - h_lin) / abs(h_lin)
            both[i, j] = abs(h - h_visc) / abs(h_visc)
            residual[i, j] = info["mean_pressure_residual_Pa"]
            min_p[i, j] = info["min_pressure_Pa"]
            p_amp[i, j] = diag["pressure_amplitude_Pa"][i] * a
    p = model.params
    return FilmMap(
        name=p.name,
        rpm=rpm,
        amplitude=amps,
        inertia_change=w * tau,
        cavitation_change=cav,
        total_change=both,
        squeeze_reynolds=diag["squeeze_reynolds"],
        pressure_amplitude=p_amp,
        min_pressure=min_p,
        mean_pressure_residual=residual,
        supply_pressure=p.supply_pressure_absolute,
        cavitation_pressure=p.cavitation_pressure,
        steps=int(steps),
        time_constant=float(tau),
    )


@dataclasses.dataclass(repr=False)
class FilmMap(Result):
    """Relative change of the oil force by fluid inertia and by cavitation over speed and orbit [-]."""

    name: str
    rpm: np.ndarray
    amplitude: np.ndarray
    inertia_change: np.ndarray
    cavitation_change: np.ndarray
    total_change: np.ndarray
    squeeze_reynolds: np.ndarray
    pressure_amplitude: np.ndarray
    min_pressure: np.ndarray
    mean_pressure_residual: np.ndarray
    supply_pressure: float
    cavitation_pressure: float
    steps: int = DEFAULT_STEPS_PER_CYCLE
    threshold: float = 0.10
    time_constant: float = 0.0

    title = "leaf spring damper film effects"

    def _repr_caption(self) -> str:
        return f"{self.name}, {self.rpm.size} speeds x {self.amplitude.size} orbits"

    def inertia_onset_rpm(self):
        """Speed where inertia changes the oil force by the threshold, ``omega tau = 0.1`` [rev/min].

        None when that is above the mapped speeds.
        """
        if not self.time_constant > 0:
            return None
        rpm = omega_to_rpm(self.threshold / self.time_constant)
        return float(rpm) if rpm <= self.rpm.max() else None

    def cavitation_change_onset_rpm(self):
        """Per orbit, the lowest mapped speed where cavitation changes the force by more than the threshold [rev/min].

        ``nan`` where it never does over the mapped speeds.  Not where cavitation starts
        (:meth:`cavitation_start_rpm`): the film cavitates some speeds before its force
        changes by the threshold (issue 40: at 100 um it starts at 4000 rpm, this says 6000).
        """
        over = self.cavitation_change > self.threshold
        return np.array([self.rpm[np.argmax(c)] if np.any(c) else np.nan for c in over.T])

    def cavitation_start_rpm(self):
        """Per orbit, the lowest mapped speed where the film's pressure reaches the cavitation
        pressure (where cavitation starts) [rev/min]; ``nan`` where it never does.
        """
        reached = self.min_pressure <= self.cavitation_pressure + 1e-9 * max(abs(self.cavitation_pressure), 1.0)
        return np.array([self.rpm[np.argmax(c)] if np.any(c) else np.nan for c in reached.T])

    def cavitation_start_rpm_at(self, cavitation_pressure: float):
        """Per orbit, the lowest mapped speed where the linear pressure amplitude reaches ``p_s - p_cav`` for
        another cavitation pressure [rev/min] (where the film would start to cavitate); ``nan`` where never.

        The film is linear until it cavitates, so this needs no film simulation; at the map's own
        ``cavitation_pressure`` it is :meth:`cavitation_start_rpm`.

        Parameters
        ----------
        cavitation_pressure : float
            Absolute cavitation pressure [Pa].
        """
        reached = self.pressure_amplitude >= (self.supply_pressure - cavitation_pressure) * (1.0 - 1e-9)
        return np.array([self.rpm[np.argmax(c)] if np.any(c) else np.nan for c in reached.T])

    def whole_film_orbit(self, cavitation_pressure: float | None = None):
        """Per speed, the largest forward orbit [m] on which the film stays whole: ``(p_s - p_cav)`` over the
        linear pressure amplitude per metre of orbit (the map's cavitation pressure by default).

        Parameters
        ----------
        cavitation_pressure : float, optional
            Absolute cavitation pressure [Pa].
        """
        p_cav = self.cavitation_pressure if cavitation_pressure is None else float(cavitation_pressure)
        per_metre = self.pressure_amplitude[:, 0] / self.amplitude[0]
        return (self.supply_pressure - p_cav) / per_metre

    def cavitation_sensitivity(self) -> dict:
        """The cavitation figures at the vapour limit (0 bar) and for air-saturated oil
        (:data:`AERATED_CAVITATION_PRESSURE`), beside the map's own (issue 40)."""
        out = {}
        for tag, p_cav in (("vapour_limit", 0.0), ("aerated", AERATED_CAVITATION_PRESSURE)):
            start = self.cavitation_start_rpm_at(p_cav)
            orbit = self.whole_film_orbit(p_cav)
            out[tag] = {
                "cavitation_pressure_abs_Pa": p_cav,
                "cavitation_start_rpm": [None if np.isnan(v) else float(v) for v in start],
                "whole_film_orbit_at_rpm_max_m": float(orbit[-1]),
            }
        out["whole_film_orbit_ratio"] = (
            out["vapour_limit"]["whole_film_orbit_at_rpm_max_m"] / out["aerated"]["whole_film_orbit_at_rpm_max_m"]
        )
        return out

    def _summary(self) -> dict:
        onset = self.cavitation_change_onset_rpm()
        start = self.cavitation_start_rpm()
        sens = self.cavitation_sensitivity()
        s = dict(
            name=self.name,
            rpm_min=float(self.rpm.min()),
            rpm_max=float(self.rpm.max()),
            amplitude_min_m=float(self.amplitude.min()),
            amplitude_max_m=float(self.amplitude.max()),
            supply_pressure_abs_Pa=float(self.supply_pressure),
            cavitation_pressure_abs_Pa=float(self.cavitation_pressure),
            threshold=float(self.threshold),
            inertia_onset_rpm=self.inertia_onset_rpm(),
            inertia_change_max=float(self.inertia_change.max()),
            squeeze_reynolds_max=float(self.squeeze_reynolds.max()),
            cavitation_change_max=float(self.cavitation_change.max()),
            cavitation_change_onset_rpm_smallest_orbit=None if np.isnan(onset[0]) else float(onset[0]),
            cavitation_change_onset_rpm_largest_orbit=None if np.isnan(onset[-1]) else float(onset[-1]),
            cavitation_start_rpm_smallest_orbit=None if np.isnan(start[0]) else float(start[0]),
            cavitation_start_rpm_largest_orbit=None if np.isnan(start[-1]) else float(start[-1]),
            mean_pressure_residual_max_Pa=float(np.abs(self.mean_pressure_residual).max()),
            steps_per_period=int(self.steps),
            whole_film_orbit_at_rpm_max_m=float(self.whole_film_orbit()[-1]),
            aerated_cavitation_pressure_abs_Pa=AERATED_CAVITATION_PRESSURE,
            cavitation_start_rpm_aerated_smallest_orbit=sens["aerated"]["cavitation_start_rpm"][0],
            cavitation_start_rpm_aerated_largest_orbit=sens["aerated"]["cavitation_start_rpm"][-1],
            whole_film_orbit_at_rpm_max_aerated_m=sens["aerated"]["whole_film_orbit_at_rpm_max_m"],
            whole_film_orbit_at_rpm_max_vapour_limit_m=sens["vapour_limit"]["whole_film_orbit_at_rpm_max_m"],
        )
        return s

    def to_xarray(self):
        """``xarray.Dataset`` over ``(rpm, amplitude)``; the CSV has one row per speed and orbit."""
        import xarray as xr

        return xr.Dataset(
            {
                "inertia_change": ("rpm", self.inertia_change, {"units": "1"}),
                "squeeze_reynolds": ("rpm", self.squeeze_reynolds, {"units": "1"}),
                "cavitation_change": (("rpm", "amplitude"), self.cavitation_change, {"units": "1"}),
                "total_change": (("rpm", "amplitude"), self.total_change, {"units": "1"}),
                "pressure_amplitude": (("rpm", "amplitude"), self.pressure_amplitude, {"units": "Pa"}),
                "min_pressure": (("rpm", "amplitude"), self.min_pressure, {"units": "Pa"}),
            },
            coords={
                "rpm": ("rpm", self.rpm, {"units": "rpm"}),
                "amplitude": ("amplitude", self.amplitude, {"units": "m"}),
            },
            attrs={
                "name": self.name,
                "supply_pressure_abs_Pa": self.supply_pressure,
                "cavitation_pressure_abs_Pa": self.cavitation_pressure,
            },
        )

    def _csv_dataset(self):
        ds = self.to_xarray()
        return ds.stack(point=("rpm", "amplitude")).reset_index("point")

    def _plot(self, ax=None):
        """Map: cavitation's change of the oil force (colour, 10 % contour), inertia's 10 % speed."""
        from ..core.plotting import new_figure

        if ax is None:
            fig, ax = new_figure(1, 1, figsize=(7.5, 5))
        else:
            fig = ax.figure
        R, A = np.meshgrid(self.rpm, self.amplitude * 1e6, indexing="ij")
        if self.rpm.size > 1 and self.amplitude.size > 1:
            cs = ax.contourf(
                R, A, 100 * self.cavitation_change, levels=[0, 1, 5, 10, 20, 40, 60, 80, 100], cmap="Blues"
            )
            fig.colorbar(cs, ax=ax, label="cavitation: change of the oil force [%]")
            ax.contour(R, A, self.cavitation_change, levels=[self.threshold], colors="C3", linewidths=1.5)
            margin = self.supply_pressure - self.cavitation_pressure
            ax.contour(R, A, self.pressure_amplitude / margin, levels=[1.0], colors="k", linestyles=":")
        else:
            ax.scatter(R.ravel(), A.ravel(), c=100 * self.cavitation_change.ravel(), cmap="Blues")
        onset = self.inertia_onset_rpm()
        if onset is not None:
            ax.axvline(onset, color="C1", ls="--", label=f"inertia > {self.threshold:.0%} from {onset:.0f} rpm")
        ax.plot([], [], color="C3", label=f"cavitation > {self.threshold:.0%}")
        ax.plot([], [], color="k", ls=":", label="linear pressure amplitude = p_s - p_cav")
        ax.set_xlabel("speed (whirl frequency) [rpm]")
        ax.set_ylabel("orbit radius [um]")
        ax.set_title(
            f"{self.name}: film effects (p_s {self.supply_pressure / 1e5:.3g} bar abs, "
            f"p_cav {self.cavitation_pressure / 1e5:.3g} bar abs)"
        )
        ax.legend(fontsize=8, loc="upper left")
        return fig
