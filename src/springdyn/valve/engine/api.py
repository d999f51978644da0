"""The engine's Python face: argument checks, array allocation, the compile notice, and the
calls into the compiled loops (:mod:`.loop`)."""

from __future__ import annotations

import numpy as np

from ...numerics import erk as _ig
from ...numerics.jit import call, compiling
from .equations import model_of, train_of
from .layout import MAX_EVENTS, N_CHECK, N_EXT, extra_layout
from .loop import Revolutions, SpeedOutputs, Tolerances, integrate_kernel, run_speeds_loop, workspace
from .monitor import new_monitor
from .reference import INTEGRATION_DOCS, atol_vector

__all__ = ["integrate", "integrate_speeds", "COMPILE_SECONDS"]

#: About how long the engine takes to compile on a 2-core machine [s], per model and pair:
#: the figure the compile notice quotes.  Measured with an empty cache by
#: ``python benchmarks/cold_start.py --variants`` (2026-11-26: spring alone 6.8, 6.3, 6.3 s;
#: valve train 12.7, 12.8, 12.3 s for dopri5, bs3, tsit5, with the adjuster's dynamics (finger
#: and bucket), the drawn lever, the gas force and speed ramps).
COMPILE_SECONDS = {
    ("spring alone", "dopri5"): 6.0,
    ("spring alone", "bs3"): 6.0,
    ("spring alone", "tsit5"): 6.0,
    ("valve train", "dopri5"): 13.0,
    ("valve train", "bs3"): 13.0,
    ("valve train", "tsit5"): 13.0,
}
_PAIR_NAMES = {"dopri5": "Dormand-Prince 5(4)", "bs3": "Bogacki-Shampine 3(2)", "tsit5": "Tsitouras 5(4)"}


def _tableau(method: str):
    if method not in _ig.TABLEAUS:
        raise ValueError(f"method = {method!r} must be one of {sorted(_ig.TABLEAUS)}")
    return _ig.TABLEAUS[method]


#: The loop variants run in this process (their first call may compile).
_RUN = set()


def _run(loop, vt, method, *args):
    """Call the compiled ``loop`` with ``args``, announcing a compilation (first call of a
    variant in a process: then on a deep frame, :func:`springdyn.numerics.jit.call`)."""
    model = "spring alone" if vt is None else "valve train"
    key = (loop.__name__, model, method)
    if key in _RUN:
        return loop(*args)
    with compiling(f"the valve engine ({model}, {_PAIR_NAMES[method]})", COMPILE_SECONDS[(model, method)]):
        result = call(loop, *args)
    _RUN.add(key)
    return result


def _angles(a) -> np.ndarray:
    return np.empty(0) if a is None else np.ascontiguousarray(a, dtype=float)


def integrate_speeds(
    y0,
    omegas,
    revolutions,
    points,
    args,
    *,
    rtol,
    atol,
    max_step_fraction,
    max_steps=10_000_000,
    gaps=None,
    atol_velocity=None,
    method="dopri5",
    stop_angles=None,
    periodicity_tol=0.0,
    warm_start=False,
    band_revolutions=0,
):
    """Integrate several speeds in one compiled call (the GIL is released throughout).

    Each speed runs revolution by revolution (:func:`.loop.run_speeds_loop`): ``revolutions``
    of them, or with ``periodicity_tol`` until two revolutions repeat.  The last revolution
    is sampled at ``points`` per revolution, where the right-hand side evaluates its
    ``extra`` outputs, and monitored on the integrator's dense output (true extremes and
    events, :mod:`.monitor`).

    Parameters
    ----------
    y0 : ndarray
        Initial state: displacements [m] then velocities [m/s].
    omegas : array_like
        Cam speeds [rad/s].
    revolutions : int
        Revolutions to integrate per speed, or with ``periodicity_tol`` the most [-].
    points : int
        Output samples per revolution [-].
    args : tuple
        The set-up's argument tuple (:func:`model_of`); its speed is ignored.
    rtol, atol : float
        Relative [-] and absolute [m] tolerances.
    max_step_fraction : float
        Largest step as a fraction of a revolution [-].
    max_steps : int
        Step budget per speed [-].
    gaps : ndarray (N + 1,), optional
        Compression [m] of each element beyond which its coils touch (``inf``: never);
        crossings are located as coil-contact events.
    atol_velocity : float or ndarray, optional
        Absolute tolerance of the velocities [m/s], one for all or one per velocity
        (default ``atol``).
    method : {"dopri5", "tsit5", "bs3"}
        The embedded Runge-Kutta pair (:data:`springdyn.numerics.erk.TABLEAUS`).
    stop_angles : array_like, optional
        Cam angles [rad] in [0, 2 pi), ascending, on which a step lands in every revolution
        (:meth:`.cam_table.CamTable.stop_angles` of the cam's breakpoints).
    periodicity_tol : float
        Stop a speed once the seat, retainer, cam-contact and valve-seat forces of two
        revolutions differ by at most this much on the output grid [N]; 0: run
        ``revolutions``.
    warm_start : bool
        Start each speed from the state the speed before ended in (a continuation in speed).
    band_revolutions : int
        A speed that does not settle: revolutions monitored at its end for the band [-].

    Returns
    -------
    dict
        The fields of :class:`.loop.SpeedOutputs` with a leading speed dimension: ``extra``
        (n_speeds, points, extra size, layout :func:`extra_layout`), ``status``, ``t_end``,
        ``steps``, ``ext`` (n_speeds, :data:`N_EXT`, layout :data:`EXT`), ``events``
        (n_speeds, :data:`MAX_EVENTS`, 4; rows ``kind, index, t_start, t_end``, a landing
        has its impact velocity [m/s] in the last column), ``n_events``, ``periodicity``
        [N], ``revolutions``, ``settled`` (bool), ``band_lo``, ``band_hi`` (n_speeds,
        :data:`N_EXT`) and ``state`` (the state each speed ended in).
    """
    tab = _tableau(method)
    omegas = np.ascontiguousarray(omegas, dtype=float)
    m = model_of(args)
    vt = train_of(args[9])
    size = extra_layout(m.masses.shape[0], m.chains.shape[0] - 1)["size"]
    k = omegas.size
    out = SpeedOutputs(
        extra=np.empty((k, points, size)),  # every row written, NaN on a failed speed
        status=np.zeros(k, dtype=np.int64),
        t_end=np.zeros(k),
        steps=np.zeros(k, dtype=np.int64),
        ext=np.zeros((k, N_EXT)),
        events=np.full((max(k, 1), MAX_EVENTS, 4), np.nan),
        nev=np.zeros((max(k, 1), 1), dtype=np.int64),
        periodicity=np.full(k, np.nan),
        revolutions=np.zeros(k, dtype=np.int64),
        settled=np.zeros(k, dtype=bool),
        band_lo=np.zeros((k, N_EXT)),
        band_hi=np.zeros((k, N_EXT)),
        state=np.zeros((k, len(y0))),
    )
    gaps = np.full(m.laws.shape[0], np.inf) if gaps is None else np.ascontiguousarray(gaps, dtype=float)
    tol = Tolerances(float(rtol), atol_vector(len(y0), atol, atol_velocity), float(max_step_fraction), int(max_steps))
    revs = Revolutions(int(revolutions), float(periodicity_tol), bool(warm_start), int(band_revolutions))
    if k:
        _run(
            run_speeds_loop,
            vt,
            method,
            np.ascontiguousarray(y0, dtype=float),
            omegas,
            int(points),
            m,
            vt,
            tab,
            tol,
            revs,
            _angles(stop_angles),
            gaps,
            out,
        )
    res = out._asdict()
    res["n_events"] = res.pop("nev")[:k, 0].copy()
    res["events"] = res["events"][:k]
    return res


@INTEGRATION_DOCS.fill
def integrate(
    y0, t_out, args, *, rtol, atol, h_max, max_steps=10_000_000, atol_velocity=None, method="dopri5", stops=None
):
    """Integrate with the compiled engine; states at ``t_out`` (ascending, from ``t_out[0]``).

    Parameters
    ----------
    {y0 t_out}
    args : tuple
        The set-up's argument tuple (:func:`model_of`), with the speed [rad/s].
    {rtol_atol h_max}
    max_steps : int
        Most steps [-] (the loop is bounded).
    atol_velocity : float or ndarray, optional
        Velocity tolerance [m/s], as for :func:`integrate_speeds`.
    method : {"dopri5", "tsit5", "bs3"}
        Runge-Kutta pair, as for :func:`integrate_speeds`.
    stops : array_like, optional
        Times [s], ascending, on which a step lands.

    Returns
    -------
    states : ndarray (len(t_out), n)
    info : dict
        ``status`` (0 ok, see :data:`STATUS`), ``t`` (time reached [s]), ``steps``, ``rejected``.
    """
    tab = _tableau(method)
    m = model_of(args)
    vt = train_of(args[9])
    out = np.full((t_out.size, y0.size), np.nan)
    t_out = np.ascontiguousarray(t_out, dtype=float)
    size = extra_layout(m.masses.shape[0], m.chains.shape[0] - 1)["size"]
    gaps = np.full(m.laws.shape[0], np.inf)
    tol = Tolerances(float(rtol), atol_vector(len(y0), atol, atol_velocity), float(h_max), int(max_steps))
    off = new_monitor(np.empty(0), np.empty((0, 4)), np.zeros(1, dtype=np.int64), gaps, 0.0, vt)
    ws = workspace(y0.size, size, tab.c.shape[0])
    status, t, steps, rejected = _run(
        integrate_kernel(tab, vt, m),
        vt,
        method,
        np.array(y0, dtype=float),
        float(t_out[0]),
        float(t_out[-1]),
        t_out,
        m,
        float(args[8]),
        vt,
        tab,
        tol,
        np.array([0.0, 1e-4, 0.0]),
        _angles(stops),
        out,
        np.empty((0, size)),
        np.empty((0, N_CHECK)),
        off,
        ws,
    )
    return out, dict(status=int(status), t=float(t), steps=int(steps), rejected=int(rejected))
