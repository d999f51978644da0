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

import warnings

import numpy as np

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError, SolverError
from ..core.units import omega_to_rpm, rpm_to_omega
from .forces import interleaf_friction_forces, oring_friction_force, pack_spring_forces

__all__ = [
    "bearing_element",
    "bearing_at_frequency",
    "whirl_consistent_mode",
    "nonlinear_force",
    "small_orbit_element",
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
    K, C = coeffs.K, coeffs.C
    kwargs.setdefault("tag", f"LSD {model.params.name}")
    values = {name: (K if name[0] == "k" else C)[(slice(None),) + _INDEX["k" + name[1:]]] for name in _NAMES}
    if added_mass:
        kwargs.update(_mass_kwargs(model))
    elem = ross.BearingElement(n=n, frequency=w, **values, **kwargs)
    for name in _NAMES:
        setattr(
            elem,
            f"{name}_interpolated",
            TableInterpolant(w, values[name], w_low, w_high, outside, f"{name} of {kwargs['tag']}"),
        )
    elem.film_notes = coeffs.summary.get("notes", [])
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
