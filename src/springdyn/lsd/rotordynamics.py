"""The leaf spring damper in a rotor model: ROSS bearing elements that never extrapolate.

ROSS (``ross-rotordynamics``, tested with 2.3) takes bearing and damper elements with
``kxx, kxy, kyx, kyy, cxx, cxy, cyx, cyy`` tabulated against ``frequency`` [rad/s] and
interpolates them with a spline that, left alone, extrapolates beyond the table
(polynomially: the damping of Type C comes out negative a little above 3000 rpm).
:func:`bearing_element` therefore

- tabulates the coefficients densely (40 log-spaced points by default) over a stated
  speed range, 0 to 20 000 rpm by default;
- replaces ROSS's smoothing spline by an interpolating one (``s = 0``) on that table;
- **refuses** (default ``outside="raise"``) any evaluation beyond the range with a
  :class:`~springdyn.core.errors.InputError` naming the frequency and the range, or, with
  ``outside="clamp"``, holds the coefficients at the nearest end of the table.

Which frequency.  The damper's coefficients depend on the **vibration frequency** (the
friction equivalents fall as ``1/omega``).  ROSS 2.3 evaluates bearing coefficients at
``frequency = speed``, the spin speed, in ``run_modal``, ``run_campbell``,
``run_freq_response`` and ``run_unbalance_response``.  For an unbalance (synchronous)
response the vibration frequency *is* the spin speed, so the table is right as it is.
For a modal analysis it is right only for a mode whose frequency equals the spin speed;
use :func:`bearing_at_frequency` (constant coefficients at one vibration frequency) and
:func:`whirl_consistent_mode` (iterate until the mode's frequency and the frequency of the
coefficients agree).  ROSS 3 renames/redefines ``frequency`` as the whirl frequency; the
tables built here are functions of the vibration (whirl) frequency, which for ROSS 2.3's
synchronous analyses equals the spin speed.
"""

from __future__ import annotations

import dataclasses
import warnings

import numpy as np

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError, SolverError
from ..core.units import omega_to_rpm, rpm_to_omega
from .damping import MIN_AMPLITUDE
from .forces import interleaf_friction_forces, oring_friction_force, pack_spring_forces

__all__ = [
    "bearing_element",
    "bearing_at_frequency",
    "whirl_consistent_mode",
    "nonlinear_force",
    "small_orbit_element",
    "amplitude_consistent_response",
    "orbit_dependent_element",
    "orbit_major_semi_axis",
    "example_rotor",
    "ConsistentResponse",
    "TableInterpolant",
    "DEFAULT_RPM_RANGE",
    "DEFAULT_POINTS",
    "LOWEST_TABLE_RPM",
    "DEFAULT_FREQUENCIES",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    model : LSDModel
        The damper.
    n : int
        Rotor node number [-].
    """
)

#: Default speed range of :func:`bearing_element` [rev/min].
DEFAULT_RPM_RANGE = (0.0, 20000.0)
#: Default number of table points (log-spaced) [-].
DEFAULT_POINTS = 40
#: Lowest tabulated speed [rev/min] (1 Hz): below it the friction equivalents
#: ``C ~ 1/omega`` grow without bound, so a range starting lower is held at this value.
LOWEST_TABLE_RPM = 60.0
#: Old default table [rad/s] (500-3000 rpm, 11 points); kept for code that imported it.
DEFAULT_FREQUENCIES = rpm_to_omega(np.linspace(500.0, 3000.0, 11))

_NAMES = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")
_INDEX = {"kxx": (0, 0), "kxy": (0, 1), "kyx": (1, 0), "kyy": (1, 1)}


def _import_ross():
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            import ross
    except ImportError:
        raise InputError(
            "to_ross() needs the optional package ross-rotordynamics (pip install 'springdyn[ross]')"
        ) from None
    return ross


class TableInterpolant:
    """Interpolating cubic spline of one coefficient over a table, never extrapolating.

    Called by ROSS with a frequency [rad/s] (scalar or array).  Inside
    ``[omega_low, omega_high]`` it interpolates (values between 0 and the first table
    point, when the stated range starts below it, are the first point's value); outside it
    raises :class:`InputError` (``outside="raise"``) or returns the value at the nearer end
    (``outside="clamp"``).

    Parameters
    ----------
    omega : array_like
        Table frequencies [rad/s], increasing.
    values : array_like
        Coefficient at those frequencies [N/m or N s/m].
    omega_low, omega_high : float
        The stated range [rad/s] (``omega_low`` may be below ``omega[0]``).
    outside : {"raise", "clamp"}
        What to do beyond the stated range.
    label : str
        Name used in messages, e.g. ``"cxx of LSD Type C"``.
    """

    def __init__(self, omega, values, omega_low, omega_high, outside="raise", label="coefficient"):
        from scipy.interpolate import UnivariateSpline

        self.omega = np.asarray(omega, dtype=float)
        self.values = np.asarray(values, dtype=float)
        self.omega_low, self.omega_high = float(omega_low), float(omega_high)
        self.outside, self.label = outside, label
        k = min(3, self.omega.size - 1)
        if self.omega.size == 1:
            self._spline = None
        else:
            self._spline = UnivariateSpline(self.omega, self.values, k=k, s=0, ext=3)

    def __call__(self, frequency):
        w = np.asarray(frequency, dtype=float)
        tol = 1e-9 * self.omega_high
        bad = (w < self.omega_low - tol) | (w > self.omega_high + tol) | ~np.isfinite(w)
        if np.any(bad):
            if self.outside == "raise" or np.any(~np.isfinite(w)):
                first = float(np.atleast_1d(w)[np.atleast_1d(bad)][0])
                raise InputError(
                    f"{self.label}: asked at frequency = {first:.6g} rad/s ({omega_to_rpm(first):.6g} rpm), outside "
                    f"the table {self.omega_low:.6g}-{self.omega_high:.6g} rad/s "
                    f"({omega_to_rpm(self.omega_low):.6g}-{omega_to_rpm(self.omega_high):.6g} rpm); springdyn does not "
                    "extrapolate: build the element over a wider rpm_range, or with outside='clamp'"
                )
        w = np.clip(w, self.omega[0], self.omega[-1])
        if self._spline is None:
            out = np.full(w.shape, self.values[0])
        else:
            out = self._spline(w)
        return out if np.ndim(frequency) else float(out)


def _table(rpm_range, points):
    """Log-spaced table speeds [rev/min] over ``rpm_range`` (from 60 rpm up if it starts lower)."""
    try:
        lo, hi = (float(v) for v in rpm_range)
    except (TypeError, ValueError):
        raise InputError(f"rpm_range = {rpm_range!r} must be two speeds (start, stop) in rpm") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and 0.0 <= lo < hi):
        raise InputError(f"rpm_range = ({lo:g}, {hi:g}) rpm must satisfy 0 <= start < stop")
    if int(points) != points or points < 30:
        raise InputError(f"points = {points!r} must be a whole number of at least 30 (the table must be dense)")
    first = max(lo, LOWEST_TABLE_RPM)
    if not hi > first:
        raise InputError(f"rpm_range = ({lo:g}, {hi:g}) rpm must reach above {LOWEST_TABLE_RPM:g} rpm")
    return lo, hi, np.geomspace(first, hi, int(points))


@_DOCS.fill
def bearing_element(
    model,
    n: int,
    frequencies=None,
    *,
    amplitude: float = 50e-6,
    motion: str = "linear",
    rpm_range=DEFAULT_RPM_RANGE,
    points: int = DEFAULT_POINTS,
    outside: str = "raise",
    omega=None,
    added_mass: bool = True,
    **kwargs,
):
    """``ross.BearingElement`` at node ``n`` from an :class:`~springdyn.lsd.LSDModel`, never extrapolating.

    Parameters
    ----------
    {model n}
    frequencies : array_like, optional
        Deprecated alias of ``omega`` (explicit table frequencies [rad/s]).
    amplitude : float
        Vibration amplitude [m] for the amplitude-dependent friction damping.
    motion : {"linear", "circular"}
        Motion assumed for the O-ring Coulomb equivalent.
    rpm_range : tuple of float
        ``(start, stop)`` [rev/min] of vibration frequencies the element answers for; default
        0 to 20 000 rpm.  The table is log-spaced from ``max(start, 60 rpm)`` to ``stop``
        (between 0 and 60 rpm the 60 rpm values are used: friction equivalents are unbounded
        at rest).
    points : int
        Table points, at least 30 [-].
    outside : {"raise", "clamp"}
        Beyond the range: raise an :class:`InputError` (default) or hold the end value.
    omega : array_like, optional
        Explicit table frequencies [rad/s] instead of ``rpm_range`` (the range is then the
        table's span).
    added_mass : bool
        Give ROSS the added mass of the oil in the passages, ``mxx ... myy`` =
        :attr:`~springdyn.lsd.LSDModel.added_mass` [kg] (constant in frequency).
    **kwargs
        Passed on (``tag``, ``n_link``, ``scale_factor``...).

    Returns
    -------
    ross.BearingElement
        Its ``frequency`` is the **vibration frequency** [rad/s] (equal to the spin speed in
        ROSS 2.3's synchronous analyses); ``kxx_interpolated`` ... are
        :class:`TableInterpolant` objects; ``film_notes`` says from which speed the film would
        cavitate at ``amplitude`` (the linear oil coefficients hold while it is whole: see
        ``springdyn lsd film`` for the orbits the rotor reaches).
    """
    if outside not in ("raise", "clamp"):
        raise InputError(f"outside = {outside!r} is not allowed; choose 'raise' or 'clamp'")
    if frequencies is not None:
        warnings.warn(
            "to_ross(frequencies=...) is deprecated: give rpm_range=(start, stop) for a dense table, "
            "or omega=[...] [rad/s] for an explicit one",
            DeprecationWarning,
            stacklevel=3,
        )
        if omega is None:
            omega = frequencies
    if omega is not None:
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        if w.ndim != 1 or w.size < 1 or np.any(~np.isfinite(w)) or np.any(w <= 0) or np.any(np.diff(w) <= 0):
            raise InputError(f"omega = {w.tolist()} rad/s must be positive and increasing")
        w_low, w_high = float(w[0]), float(w[-1])
    else:
        lo, hi, rpm = _table(rpm_range, points)
        w = rpm_to_omega(rpm)
        w_low, w_high = float(rpm_to_omega(lo)), float(rpm_to_omega(hi))
    ross = _import_ross()
    from .film import FilmWarning

    with warnings.catch_warnings():
        # a wide table reaches speeds where the film would rupture at this amplitude; that is
        # said in elem.film_notes, not warned at every export (the amplitude is the friction's)
        warnings.simplefilter("ignore", FilmWarning)
        coeffs = model.coefficients(omega=w, amplitude=amplitude, motion=motion)
    elem = _table_element(ross, model, n, w, coeffs.K, coeffs.C, (w_low, w_high, outside), added_mass, kwargs)
    elem.film_notes = coeffs.summary.get("notes", [])
    return elem


def _table_element(ross, model, n, w, K, C, bounds, added_mass, kwargs):
    """A ``ross.BearingElement`` at node ``n`` from the coefficient tables ``K``, ``C`` over the
    frequencies ``w`` [rad/s], each coefficient read between the table's points
    (:class:`TableInterpolant`, ``bounds = (w_low, w_high, outside)``)."""
    kwargs.setdefault("tag", f"LSD {model.params.name}")
    values = {name: (K if name[0] == "k" else C)[(slice(None),) + _INDEX["k" + name[1:]]] for name in _NAMES}
    if added_mass:
        kwargs.update(_mass_kwargs(model))
    elem = ross.BearingElement(n=n, frequency=w, **values, **kwargs)
    w_low, w_high, outside = bounds
    for name in _NAMES:
        setattr(
            elem,
            f"{name}_interpolated",
            TableInterpolant(w, values[name], w_low, w_high, outside, f"{name} of {kwargs['tag']}"),
        )
    return elem


def _matrix_kwargs(prefix: str, A) -> dict:
    """``ross.BearingElement``'s keywords of a 2 x 2 matrix: ``{prefix}xx`` ... ``{prefix}yy``."""
    return {f"{prefix}{a}{b}": A[i, j] for i, a in enumerate("xy") for j, b in enumerate("xy")}


def _mass_kwargs(model) -> dict:
    return _matrix_kwargs("m", model.added_mass)


@_DOCS.fill
def bearing_at_frequency(
    model, n: int, omega: float, *, amplitude: float = 50e-6, motion: str = "linear", added_mass: bool = True, **kwargs
):
    """``ross.BearingElement`` with the coefficients at one vibration frequency ``omega`` [rad/s].

    Constant coefficients (no table), so ROSS uses them at every spin speed: the element
    for a modal analysis of a mode vibrating at ``omega`` (see :func:`whirl_consistent_mode`),
    or for a forced response at a single frequency.

    Parameters
    ----------
    {model n}
    omega : float
        Vibration frequency [rad/s].
    amplitude : float
        Vibration amplitude [m].
    motion : {"linear", "circular"}
        Motion for the O-ring Coulomb equivalent.
    added_mass : bool
        Include the oil's added mass ``mxx ... myy`` [kg].
    **kwargs
        Passed on to ``ross.BearingElement``.
    """
    if not (np.isfinite(omega) and omega > 0):
        raise InputError(f"omega = {omega!r} rad/s must be a positive vibration frequency")
    ross = _import_ross()
    c = model.coefficients(omega=[float(omega)], amplitude=amplitude, motion=motion)
    kwargs.setdefault("tag", f"LSD {model.params.name}")
    K, C = c.K[0], c.C[0]
    if added_mass:
        kwargs.update(_mass_kwargs(model))
    return ross.BearingElement(n=n, **_matrix_kwargs("k", K), **_matrix_kwargs("c", C), **kwargs)


def whirl_consistent_mode(
    build_rotor,
    speed: float,
    omega_guess: float,
    *,
    mode: int = 0,
    num_modes: int = 12,
    rtol: float = 1e-4,
    max_iterations: int = 50,
):
    """Modal analysis with the damper's coefficients at the mode's own frequency.

    Repeats ``rotor = build_rotor(omega)`` (the rotor with every damper built by
    :func:`bearing_at_frequency` at ``omega``) and ``rotor.run_modal(speed)`` until the
    damped natural frequency ``wd`` of mode ``mode`` equals ``omega`` within ``rtol``.

    Parameters
    ----------
    build_rotor : callable
        ``build_rotor(omega) -> ross.Rotor`` [omega in rad/s].
    speed : float
        Spin speed [rad/s] of the modal analysis.
    omega_guess : float
        Starting vibration frequency [rad/s].
    mode : int
        Index of the mode in ROSS's (frequency-sorted) list [-].
    num_modes : int
        Modes ROSS computes [-].
    rtol : float
        Relative tolerance on ``wd - omega`` [-].
    max_iterations : int
        Bound on the iterations [-].

    Returns
    -------
    tuple
        ``(omega, modal)``: the consistent frequency [rad/s] and ROSS's modal results.

    Raises
    ------
    SolverError
        No consistent frequency within ``max_iterations`` (a mode that is overdamped at
        that frequency has no damped frequency to iterate on).
    """
    if not (np.isfinite(omega_guess) and omega_guess > 0):
        raise InputError(f"omega_guess = {omega_guess!r} rad/s must be positive")
    omega = float(omega_guess)
    for _ in range(int(max_iterations)):
        modal = build_rotor(omega).run_modal(speed=speed, num_modes=num_modes)
        wd = float(modal.wd[mode])
        if not (np.isfinite(wd) and wd > 0):
            raise SolverError(
                f"whirl_consistent_mode: mode {mode} has no damped frequency at omega = {omega:.6g} rad/s "
                "(overdamped); pick another mode"
            )
        if abs(wd - omega) <= rtol * wd:
            return wd, modal
        omega = wd
    raise SolverError(
        f"whirl_consistent_mode: mode {mode} did not settle in {max_iterations} iterations "
        f"(last omega {omega:.6g} rad/s, wd {wd:.6g} rad/s)"
    )


@_DOCS.fill
def small_orbit_element(model, n: int, **kwargs):
    """``ross.BearingElement`` with the damper's small-orbit linearisation, constant in frequency.

    Pack stiffness ``K`` (3.4), oil damping ``C_visc`` and the passages' added mass
    ``M_a = tau C_visc`` (:attr:`~springdyn.lsd.LSDModel.added_mass`): the exact linearisation
    of the packs and of the film network (with inertia) while no pack lifts off and the film
    does not cavitate.  Friction is left out (its equivalent grows without bound as the
    amplitude falls).  Pair it with :func:`nonlinear_force` ``(..., residual=True)``, which adds
    the rest of the nonlinear force.

    Parameters
    ----------
    {model n}
    **kwargs
        Passed on to ``ross.BearingElement`` (``tag`` ...).
    """
    ross = _import_ross()
    K, C, M = model.stiffness_matrix, model.viscous_damping, model.added_mass
    kwargs.setdefault("tag", f"LSD {model.params.name} (small orbit)")
    return ross.BearingElement(
        n=n, **_matrix_kwargs("k", K), **_matrix_kwargs("c", C), **_matrix_kwargs("m", M), **kwargs
    )


@_DOCS.fill
def nonlinear_force(
    model, rotor, n: int, *, count: int = 1, film: bool = False, residual: bool = False, inertia: bool = True
):
    """The damper's nonlinear force as an ``add_to_RHS`` callback of ROSS's time response.

    ROSS 2.3's ``rotor.run_time_response(speed, F, t, add_to_RHS=f)`` adds ``f(step,
    disp_resp=..., velc_resp=..., accl_resp=..., time_step=...)`` to the right-hand side at
    every step.  The callback evaluates the rig's force laws (pack springs with lift-off,
    inter-leaf and O-ring Coulomb friction: :mod:`springdyn.lsd.forces`; oil) at the x, y
    displacement and velocity of node ``n`` and returns minus that force (the damper pushes
    back) on the node's x and y degrees of freedom.

    - ``film=False``: the oil is the thesis' linear, inertia-free ``C_visc v``.
    - ``film=True``: the oil is the time-domain film network (:mod:`springdyn.lsd.film`:
      passage inertia, cavitation at ``cavitation_pressure``, supply at ``supply_pressure``),
      integrated along the node's velocity history, one network step per ROSS step (the
      callback keeps the network's state; call ``f.reset()`` before reusing it for a new run).
    - ``residual=False``: build the rotor **without** a linear element for this damper (or with
      zero coefficients at node ``n``), so it is not counted twice.
    - ``residual=True``: the rotor carries :func:`small_orbit_element` at node ``n`` (implicit in
      ROSS's Newmark scheme) and the callback adds only the rest,
      ``F_nonlinear - (K x + C_visc v + M_a a)``, small while the orbit is small.

    ROSS evaluates the callback with the state of the step before, so the callback's part of
    the force lags by one step (first order in the step): with ``residual=True`` that lag only
    touches the nonlinear remainder.

    Parameters
    ----------
    {model}
    rotor : ross.Rotor
        The rotor (for ``ndof`` and ``number_dof``).
    n : int
        Node of the damper [-].
    count : int
        Identical dampers acting on that node [-].
    film : bool
        Oil from the film network (inertia and cavitation).
    residual : bool
        Return only the part beyond :func:`small_orbit_element`.
    inertia : bool
        Passage inertia in the film network (with ``film``).

    Returns
    -------
    callable
        ``f(step, disp_resp=None, velc_resp=None, accl_resp=None, time_step=None, **kwargs) ->
        ndarray (rotor.ndof,)`` [N]; ``f.network`` is the film network (or None), ``f.history``
        the node's oil pressures per step (absolute, [Pa]) when ``film``.
    """
    from .film import film_network

    ndof, per_node = int(rotor.ndof), int(rotor.number_dof)
    ix, iy = per_node * int(n), per_node * int(n) + 1
    if not (0 <= iy < ndof):
        raise InputError(f"n = {n!r} is not a node of the rotor ({ndof // per_node} nodes)")
    p = model.params
    Cv = model.viscous_damping
    K_lin, M_lin = model.stiffness_matrix, model.added_mass
    network = film_network(model, inertia=inertia) if film else None
    state = {"step": None, "out": None, "started": False, "v": None}

    def oil(v, dt):
        if network is None:
            return Cv @ v
        if not state["started"]:
            network.reset()
            network.flow = network.kinematic_flows(v)
            state["started"] = True
        if not (dt and dt > 0):
            return Cv @ v
        pressures = network.step(v, dt)
        force.history.append(pressures)
        return network.force(pressures)

    def force(step, disp_resp=None, velc_resp=None, accl_resp=None, time_step=None, **kwargs):
        if step == state["step"]:
            return state["out"].copy()  # the same step asked twice: the network advances once
        out = np.zeros(ndof)
        if disp_resp is None or velc_resp is None:
            return out
        x, y = np.array([disp_resp[ix]]), np.array([disp_resp[iy]])
        vx, vy = np.array([velc_resp[ix]]), np.array([velc_resp[iy]])
        fx, fy, loads = pack_spring_forces(model.angles, model.pack_stiffness, p.preload, x, y)
        lx, ly = interleaf_friction_forces(model.angles, loads, p.leaf_friction, model.slip_factor, vx, vy)
        ox, oy = oring_friction_force(p.oring_friction, p.oring_normal_force, vx, vy)
        v = np.array([vx[0], vy[0]])
        f = np.array([fx[0] + lx[0] + ox[0], fy[0] + ly[0] + oy[0]]) + oil(v, time_step)
        if residual:
            # the acceleration as the film network sees it (its backward difference), so that the
            # remainder vanishes exactly while the film is linear; Newmark's own acceleration
            # oscillates step to step and would feed that oscillation back through M_a
            if film and time_step:
                a = (v - state["v"]) / time_step if state["v"] is not None else np.zeros(2)
            else:
                a = np.zeros(2) if accl_resp is None else np.array([accl_resp[ix], accl_resp[iy]])
            f = f - (K_lin @ np.array([x[0], y[0]]) + Cv @ v + M_lin @ a)
        state["v"] = v
        out[ix], out[iy] = -count * f[0], -count * f[1]
        state["step"], state["out"] = step, out
        return out.copy()

    def reset():
        state.update(step=None, out=None, started=False, v=None)
        force.history = []

    force.network = network
    force.history = []
    force.reset = reset
    return force


# ----------------------------------------------------------------- the amplitude the rotor reaches
#: Default relative tolerance of the amplitude iteration, ``|orbit - A| / A`` [-].
AMPLITUDE_RTOL = 0.01
#: Default relaxation of the amplitude iteration, ``A <- A + r (orbit - A)`` [-].
AMPLITUDE_RELAXATION = 0.5
#: Relative change of a damper's dynamic stiffness below which the coefficients are taken as
#: independent of the amplitude (then the first orbit is the fixed point) [-].
_SAME_COEFFICIENTS = 1e-12


def orbit_major_semi_axis(X, Y):
    """Largest displacement over a cycle of the synchronous orbit ``x = Re(X e^(jwt))``, ``y = Re(Y e^(jwt))``.

    With ``z = x + j y = F e^(jwt) + B e^(-jwt)``, ``F = (X + jY)/2``, ``B = conj(X - jY)/2``
    (forward and backward circles), the orbit is an ellipse of semi-axes ``|F| + |B|`` and
    ``||F| - |B||``; the first is returned (a circle's radius on a forward circular orbit).

    Parameters
    ----------
    X, Y : array_like of complex
        Complex amplitudes of the x and y displacements [m].

    Returns
    -------
    numpy.ndarray
        Major semi-axis [m].
    """
    X, Y = np.asarray(X, dtype=complex), np.asarray(Y, dtype=complex)
    return 0.5 * (np.abs(X + 1j * Y) + np.abs(X - 1j * Y))


def _per_speed_coefficients(model, omega, amplitudes, motion):
    """``K, C, M`` [N/m, N s/m, kg], shape ``(len(omega), 2, 2)``, each speed at its own amplitude [m]."""
    from .film import FilmWarning
    from .stiffness import PreloadExceededWarning

    K = np.empty((omega.size, 2, 2))
    C = np.empty((omega.size, 2, 2))
    with warnings.catch_warnings():
        # said once per run (ConsistentResponse.notes), not at every iterate
        warnings.simplefilter("ignore", FilmWarning)
        warnings.simplefilter("ignore", PreloadExceededWarning)
        for i, (w, a) in enumerate(zip(omega, amplitudes)):
            c = model.coefficients(omega=[float(w)], amplitude=float(a), motion=motion)
            K[i], C[i] = c.K[0], c.C[0]
    M = np.broadcast_to(model.added_mass, K.shape).copy()
    return K, C, M


@_DOCS.fill
def orbit_dependent_element(
    model, n: int, omega, amplitude, *, motion: str = "circular", added_mass: bool = True, **kwargs
):
    """``ross.BearingElement`` whose coefficients at each table frequency are taken at that speed's own amplitude.

    The export of :func:`amplitude_consistent_response`: at ``omega[i]`` the coefficients
    are the damper's at ``amplitude[i]``.  Exact at the table frequencies (an interpolating
    spline through them); between them interpolated; beyond them refused
    (:class:`TableInterpolant`, ``outside="raise"``).

    Parameters
    ----------
    {model n}
    omega : array_like
        Table frequencies [rad/s], positive and increasing.
    amplitude : array_like
        Vibration amplitude at each frequency [m].
    motion : {"linear", "circular"}
        Motion of the O-ring Coulomb equivalent (an unbalance orbit is circular).
    added_mass : bool
        Include the oil's added mass ``mxx ... myy`` [kg].
    **kwargs
        Passed on to ``ross.BearingElement`` (``tag`` ...).

    Returns
    -------
    ross.BearingElement
        ``amplitude`` holds the amplitude [m] of each table frequency.
    """
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    a = np.broadcast_to(np.asarray(amplitude, dtype=float), w.shape)
    if w.ndim != 1 or np.any(~np.isfinite(w)) or np.any(w <= 0) or np.any(np.diff(w) <= 0):
        raise InputError(f"omega = {w.tolist()} rad/s must be positive and increasing")
    ross = _import_ross()
    K, C, M = _per_speed_coefficients(model, w, a, motion)
    elem = _table_element(ross, model, n, w, K, C, (w[0], w[-1], "raise"), added_mass, kwargs)
    elem.amplitude = np.array(a)
    return elem


def _unbalance_list(unbalance):
    """``[(node, magnitude [kg m], phase [rad]), ...]`` from one triple or a list of them."""
    items = [unbalance] if np.ndim(unbalance) == 1 and not isinstance(unbalance[0], (tuple, list)) else unbalance
    out = []
    for u in items:
        try:
            node, mag, phase = u
            node, mag, phase = int(node), float(mag), float(phase)
        except (TypeError, ValueError):
            raise InputError(f"unbalance = {unbalance!r} must be (node, magnitude in kg m, phase in rad)") from None
        if not (np.isfinite(mag) and mag > 0 and np.isfinite(phase)):
            raise InputError(f"unbalance magnitude = {mag!r} kg m must be positive (phase {phase!r} rad finite)")
        out.append((node, mag, phase))
    return out


@dataclasses.dataclass
class ConsistentResponse:
    """Unbalance response of a ROSS rotor with each damper's coefficients at the orbit it reaches.

    Attributes
    ----------
    rpm : numpy.ndarray
        Speeds [rev/min] (vibration frequency = spin speed).
    nodes : list of int
        Damper nodes, in the order of the columns below.
    amplitude : numpy.ndarray
        ``(speeds, dampers)``: the amplitude each damper's coefficients were taken at [m].
    orbit : numpy.ndarray
        ``(speeds, dampers)``: the major semi-axis of the damper node's orbit in ROSS's
        response with those coefficients [m].
    residual : numpy.ndarray
        ``max |orbit - amplitude| / amplitude`` over the dampers, per speed [-].
    iterations : numpy.ndarray
        Rotor solves per speed until the residual fell below ``rtol`` (0: a fixed amplitude) [-].
    converged : numpy.ndarray of bool
        ``residual <= rtol`` and the ring moves.
    held : numpy.ndarray of bool
        The iterate fell to the model's smallest amplitude (1 nm) with the orbit still below
        it: the friction holds the ring, no equivalent-viscous coefficient applies.
    K, C, M : numpy.ndarray
        ``(dampers, speeds, 2, 2)``: the coefficients used [N/m], [N s/m], [kg].
    response : ross.ForcedResponseResults
        ROSS's unbalance response of the rotor with those coefficients (``forced_resp``:
        ``(ndof, speeds)`` complex amplitudes [m]).
    rotor : ross.Rotor
        The rotor with the :func:`orbit_dependent_element` bearings.
    mode : str
        ``"consistent"`` or ``"fixed"`` (one amplitude at every speed).
    rtol, relaxation : float
        The iteration's tolerance and relaxation [-].
    notes : list of str
    """

    rpm: np.ndarray
    nodes: list
    amplitude: np.ndarray
    orbit: np.ndarray
    residual: np.ndarray
    iterations: np.ndarray
    converged: np.ndarray
    held: np.ndarray
    K: np.ndarray
    C: np.ndarray
    M: np.ndarray
    response: object
    rotor: object
    mode: str
    rtol: float
    relaxation: float
    notes: list

    def orbit_at(self, node: int) -> np.ndarray:
        """Major semi-axis of node ``node``'s orbit per speed [m] (ROSS's response).

        Parameters
        ----------
        node : int
            A node of the rotor [-].
        """
        nd = int(self.rotor.number_dof)
        if not (0 <= nd * int(node) + 1 < self.rotor.ndof):
            raise InputError(f"node = {node!r} is not a node of the rotor ({self.rotor.ndof // nd} nodes)")
        q = self.response.forced_resp
        return orbit_major_semi_axis(q[nd * int(node)], q[nd * int(node) + 1])

    def peak(self, node: int) -> tuple:
        """``(rpm, orbit [m])`` of node ``node``'s largest orbit over the converged speeds.

        With a fixed amplitude (``mode == "fixed"``) every speed counts: the linear response is
        exact for the coefficients it was given, and ``residual`` says how far they are from
        the orbit.

        Parameters
        ----------
        node : int
            A node of the rotor [-].

        Raises
        ------
        SolverError
            No speed converged (a figure from unconverged speeds is not a result).
        """
        ok = self.converged if self.mode == "consistent" else np.ones(self.rpm.size, dtype=bool)
        if not np.any(ok):
            raise SolverError(
                f"no speed converged (largest residual {self.residual.max():.3g} against rtol {self.rtol:g})"
            )
        r = np.where(ok, self.orbit_at(node), -np.inf)
        k = int(np.argmax(r))
        return float(self.rpm[k]), float(r[k])

    def to_dict(self) -> dict:
        """JSON-ready columns (SI, unit in the name) and the notes."""
        out = {"mode": self.mode, "rtol": self.rtol, "rpm": self.rpm.tolist(), "nodes": list(self.nodes)}
        for j, n in enumerate(self.nodes):
            out[f"node{n}_amplitude_m"] = self.amplitude[:, j].tolist()
            out[f"node{n}_orbit_m"] = self.orbit[:, j].tolist()
            for name in _NAMES:
                A = self.K if name[0] == "k" else self.C
                unit = "N_per_m" if name[0] == "k" else "Ns_per_m"
                out[f"node{n}_{name}_{unit}"] = A[(j, slice(None)) + _INDEX["k" + name[1:]]].tolist()
        out.update(
            residual=self.residual.tolist(),
            iterations=self.iterations.tolist(),
            converged=self.converged.tolist(),
            held=self.held.tolist(),
            notes=list(self.notes),
        )
        return out


def _dynamic_stiffness(K, C, M, w):
    return K - (w**2)[:, None, None] * M + 1j * w[:, None, None] * C


def amplitude_consistent_response(
    build_rotor,
    dampers: dict,
    rpm,
    unbalance,
    *,
    amplitude="consistent",
    start_amplitude: float = 50e-6,
    rtol: float = AMPLITUDE_RTOL,
    relaxation: float = AMPLITUDE_RELAXATION,
    max_iterations: int = 100,
    motion: str = "circular",
    added_mass: bool = True,
) -> ConsistentResponse:
    """Unbalance response of a ROSS rotor with each damper's coefficients at the amplitude it reaches.

    ``to_ross`` takes the friction equivalents at one amplitude (50 um by default); a damper
    that orbits at 16 um has several times that friction damping.  Per speed this iterates

    1. the damper coefficients at amplitude ``A`` (:meth:`~springdyn.lsd.LSDModel.coefficients`,
       the closed forms: the friction equivalents fall as ``1/A``);
    2. the rotor's synchronous response at that speed with those coefficients (the ROSS
       rotor's ``M``, ``K(w)``, ``C(w)``, ``G`` with the dampers' ``K - w^2 M_a + j w C``
       added at their nodes: ROSS's own ``transfer_matrix`` algebra);
    3. the damper node's orbit ``A_new`` (major semi-axis, :func:`orbit_major_semi_axis`);

    with ``A <- A + relaxation (A_new - A)`` until ``max |A_new - A| / A <= rtol`` over the
    dampers, at most ``max_iterations`` rotor solves.  Where the coefficients at ``A_new``
    equal those at ``A`` (relative change of ``K - w^2 M + j w C`` below 1e-12: a damper
    without friction) ``A_new`` is taken at once: the response cannot change, one solve.
    The rotor is then built with :func:`orbit_dependent_element` bearings (each speed's
    coefficients at its own amplitude) and ROSS's ``run_unbalance_response`` gives the
    response; the residual reported is that response's ``|orbit - A| / A``.

    Parameters
    ----------
    build_rotor : callable
        ``build_rotor(bearings) -> ross.Rotor``; ``bearings`` is a list of
        ``ross.BearingElement``, one per damper in the order of ``dampers``.
    dampers : dict
        ``{node: LSDModel}``.
    rpm : array_like
        Speeds [rev/min], positive and increasing.
    unbalance : tuple or list of tuple
        ``(node, magnitude [kg m], phase [rad])``, or a list of them.
    amplitude : "consistent" or float
        ``"consistent"`` (iterate), or one amplitude [m] at every speed (the fixed export,
        its residual then says how far the orbit is from it).
    start_amplitude : float
        First iterate [m] (where several amplitudes are consistent, the iteration finds the
        one it reaches from here).
    rtol : float
        Tolerance on ``|A_new - A| / A`` [-] (default 1 %).
    relaxation : float
        ``0 < r <= 1`` [-] (default 0.5).
    max_iterations : int
        Bound on the rotor solves per speed [-].
    motion : {"linear", "circular"}
        Motion of the O-ring Coulomb equivalent; an unbalance orbit is a circle (default).
    added_mass : bool
        Include the oil's added mass [kg].

    Returns
    -------
    ConsistentResponse
        Per speed: the amplitude used, the iterations, the residual, the coefficients; the
        rotor and ROSS's response with them.
    """
    if not isinstance(dampers, dict) or not dampers:
        raise InputError(f"dampers = {dampers!r} must be a dict {{node: LSDModel}} with at least one damper")
    rpm = np.atleast_1d(np.asarray(rpm, dtype=float))
    if rpm.ndim != 1 or np.any(~np.isfinite(rpm)) or np.any(rpm <= 0) or np.any(np.diff(rpm) <= 0):
        raise InputError(f"rpm = {rpm.tolist()} must be positive and increasing")
    fixed = not (isinstance(amplitude, str) and amplitude == "consistent")
    if fixed:
        if isinstance(amplitude, str) or not (np.isfinite(amplitude) and amplitude >= MIN_AMPLITUDE):
            raise InputError(f"amplitude = {amplitude!r} must be 'consistent' or an amplitude of at least 1e-9 m")
    for name, value, low, high in (
        ("rtol", rtol, 0.0, 0.5),
        ("relaxation", relaxation, 0.0, 1.0),
        ("start_amplitude", start_amplitude, MIN_AMPLITUDE, 0.01),
    ):
        if not (np.isfinite(value) and low < value <= high):
            raise InputError(f"{name} = {value!r} must lie in ({low:g}, {high:g}]")
    if int(max_iterations) != max_iterations or max_iterations < 1:
        raise InputError(f"max_iterations = {max_iterations!r} must be a whole number of at least 1")
    if motion not in ("linear", "circular"):
        raise InputError(f"motion = {motion!r} is not allowed; choose 'linear' or 'circular'")
    ross = _import_ross()
    unb = _unbalance_list(unbalance)
    nodes = [int(n) for n in dampers]
    models = [dampers[n] for n in dampers]
    w = rpm_to_omega(rpm)
    ns, nd = w.size, len(nodes)

    # the rotor without the dampers (zero-coefficient elements at their nodes)
    bare = build_rotor([ross.BearingElement(n, kxx=0.0, cxx=0.0, tag=f"damper{j}") for j, n in enumerate(nodes)])
    per, ndof = int(bare.number_dof), int(bare.ndof)
    for n in nodes + [u[0] for u in unb]:
        if not (0 <= per * n + 1 < ndof):
            raise InputError(f"node = {n} is not a node of the rotor ({ndof // per} nodes)")
    D0 = np.array([-(wi**2) * bare.M(wi) + 1j * wi * (bare.C(wi) + wi * bare.G()) + bare.K(wi) for wi in w])
    F = np.zeros((ns, ndof), dtype=complex)
    for n, mag, phase in unb:  # ROSS's synchronous unbalance force
        F[:, per * n] += w**2 * mag * np.exp(1j * phase)
        F[:, per * n + 1] += -1j * w**2 * mag * np.exp(1j * phase)
    ix = [(per * n, per * n + 1) for n in nodes]

    def coefficients(A):
        mats = [_per_speed_coefficients(m, w, A[:, j], motion) for j, m in enumerate(models)]
        if not added_mass:
            mats = [(K, C, np.zeros_like(M)) for K, C, M in mats]
        return mats

    def orbits(mats, active):
        D = D0[active].copy()
        for j, (K, C, M) in enumerate(mats):
            H = _dynamic_stiffness(K[active], C[active], M[active], w[active])
            D[:, ix[j][0] : ix[j][1] + 1, ix[j][0] : ix[j][1] + 1] += H
        q = np.linalg.solve(D, F[active][..., None])[..., 0]
        return np.column_stack([orbit_major_semi_axis(q[:, a], q[:, b]) for a, b in ix])

    A = np.full((ns, nd), float(amplitude if fixed else start_amplitude))
    iterations = np.zeros(ns, dtype=int)
    held = np.zeros(ns, dtype=bool)
    if not fixed:
        active = np.ones(ns, dtype=bool)
        mats = coefficients(A)
        for _ in range(int(max_iterations)):
            new = orbits(mats, active)
            iterations[active] += 1
            idx = np.flatnonzero(active)
            res = np.max(np.abs(new - A[idx]) / A[idx], axis=1)
            done = res <= rtol
            # a damper whose coefficients do not depend on the amplitude: the orbit is the answer
            trial = A.copy()
            trial[idx] = np.maximum(new, MIN_AMPLITUDE)
            mats_new = coefficients(trial)
            same = np.ones(idx.size, dtype=bool)
            for (K0, C0, M0), (K1, C1, M1) in zip(mats, mats_new):
                H0 = _dynamic_stiffness(K0[idx], C0[idx], M0[idx], w[idx])
                H1 = _dynamic_stiffness(K1[idx], C1[idx], M1[idx], w[idx])
                scale = np.linalg.norm(H0, axis=(1, 2))
                same &= np.linalg.norm(H1 - H0, axis=(1, 2)) <= _SAME_COEFFICIENTS * scale
            step = A[idx] + relaxation * (new - A[idx])
            step = np.where(same[:, None], new, step)
            floor = (A[idx] <= MIN_AMPLITUDE * (1 + 1e-9)) & (new < A[idx])
            held[idx] = np.any(floor, axis=1) & ~done
            keep = done | held[idx]
            A[idx] = np.where(keep[:, None] & ~same[:, None], A[idx], np.maximum(step, MIN_AMPLITUDE))
            active[idx] = ~(keep | same)
            mats = coefficients(A)
            if not active.any():
                break

    tags = [f"LSD {m.params.name} node {n}" for n, m in zip(nodes, models)]
    bearings = [
        orbit_dependent_element(m, n, w, A[:, j], motion=motion, added_mass=added_mass, tag=t)
        for j, (n, m, t) in enumerate(zip(nodes, models, tags))
    ]
    rotor = build_rotor(bearings)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # ROSS's own deprecation chatter
        resp = rotor.run_unbalance_response([u[0] for u in unb], [u[1] for u in unb], [u[2] for u in unb], frequency=w)
    q = resp.forced_resp
    orbit = np.column_stack([orbit_major_semi_axis(q[a], q[b]) for a, b in ix])
    residual = np.max(np.abs(orbit - A) / A, axis=1)
    converged = (residual <= rtol) & ~held
    mats = coefficients(A)
    K = np.array([m[0] for m in mats])
    C = np.array([m[1] for m in mats])
    M = np.array([m[2] for m in mats])
    notes = []
    if np.any(held):
        notes.append(
            f"at {', '.join(f'{r:g}' for r in rpm[held])} rpm the friction holds the ring (the iterate fell to "
            f"{MIN_AMPLITUDE:g} m with the orbit still smaller): no equivalent-viscous coefficient applies there; "
            "those speeds are not results"
        )
    bad = ~converged & ~held
    if np.any(bad):
        what = "far from the fixed amplitude" if fixed else f"not converged in {max_iterations} solves"
        notes.append(
            f"at {', '.join(f'{r:g}' for r in rpm[bad])} rpm the orbit is {what} (residual up to "
            f"{residual[bad].max():.3g} against rtol {rtol:g})"
        )
    preload = [m.params.preload for m in models]
    over = np.any(A > np.array(preload)[None, :], axis=1)
    if np.any(over):
        notes.append(
            f"at {', '.join(f'{r:g}' for r in rpm[over])} rpm the amplitude exceeds the pack preload: the packs lift "
            "off and the coefficients are those of the first harmonic only"
        )
    return ConsistentResponse(
        rpm=rpm,
        nodes=nodes,
        amplitude=A,
        orbit=orbit,
        residual=residual,
        iterations=iterations,
        converged=converged,
        held=held,
        K=K,
        C=C,
        M=M,
        response=resp,
        rotor=rotor,
        mode="fixed" if fixed else "consistent",
        rtol=float(rtol),
        relaxation=float(relaxation),
        notes=notes,
    )


def example_rotor(bearings):
    """The rotor of ``examples/lsd/rotor_with_lsd.py``: dampers at nodes 0 and 2, a disk at node 1.

    Two steel shaft elements 0.1 m long, 80 mm diameter (Timoshenko, gyroscopic), a disk
    0.2 m in diameter and 50 mm wide on an 80 mm bore at node 1 (about 18 kg in all).

    Parameters
    ----------
    bearings : list
        Two ``ross.BearingElement``, at nodes 0 and 2.

    Returns
    -------
    ross.Rotor
    """
    ross = _import_ross()
    steel = ross.Material(name="steel_lsd_example_rotor", rho=7810, E=211e9, G_s=81.2e9)
    shaft = [
        ross.ShaftElement(0.1, 0.0, 0.08, material=steel, shear_effects=True, rotary_inertia=True, gyroscopic=True)
        for _ in range(2)
    ]
    disk = ross.DiskElement.from_geometry(n=1, material=steel, width=0.05, i_d=0.08, o_d=0.2)
    return ross.Rotor(shaft, [disk], list(bearings))
