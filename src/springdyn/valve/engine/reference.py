"""The NumPy / SciPy twins of the compiled engine, the references its tests compare with.

- :func:`integrate_scipy`: ``scipy.integrate.solve_ivp`` with the plain-Python
  :func:`.equations.chain_rhs` (the same equations, run by the interpreter).
"""

from __future__ import annotations

import numpy as np

from ...core.docstrings import ParameterDocs
from .equations import NO_EXTRA, chain_rhs, model_of, rhs_kernel, train_of

__all__ = ["integrate_scipy", "atol_vector"]

#: The parameters of the integrators (this one and :func:`springdyn.valve.engine.integrate`),
#: described once (springdyn.core.docstrings).
INTEGRATION_DOCS = ParameterDocs(
    """
    y0 : ndarray
        Initial state [m, m/s].
    t_out : ndarray
        Output times [s], ascending.
    rtol, atol : float
        Relative [-] and absolute [m] tolerances (velocities: ``atol_velocity``).
    h_max : float
        Largest step [s].
"""
)


def atol_vector(n_state: int, atol: float, atol_velocity: float | None = None) -> np.ndarray:
    """Absolute tolerance per state component: ``atol`` [m] on the displacements,
    ``atol_velocity`` [m/s] (default ``atol``) on the velocities.

    Parameters
    ----------
    n_state : int
        State size (displacements then velocities) [-].
    atol : float
        Absolute tolerance of the displacements [m].
    atol_velocity : float or ndarray (n_state // 2,), optional
        Absolute tolerance of the velocities [m/s], one for all or one per velocity.
    """
    half = n_state // 2
    out = np.full(n_state, float(atol))
    out[half:] = atol if atol_velocity is None else np.asarray(atol_velocity, dtype=float)
    return out


@INTEGRATION_DOCS.fill
def integrate_scipy(
    y0, t_out, args, *, rtol, atol, method="DOP853", compiled_rhs=False, h_max=np.inf, atol_velocity=None
):
    """Reference backend: ``scipy.integrate.solve_ivp`` with the plain-Python right-hand side.

    With ``compiled_rhs=True`` the compiled right-hand side is used instead (same model,
    faster); the plain one is the independent reference of the benchmarks.

    Parameters
    ----------
    {y0 t_out}
    args : tuple
        ``(masses, laws, xset, c0, cam_h, cam_dh, cam_ddh, dth, omega, vt)`` [kg, m and N,
        m, N s/m, m, m/rad, m/rad^2, rad, rad/s, -] (see :func:`springdyn.valve.engine.model_of`).
    {rtol_atol}
    method : str
        ``solve_ivp`` method name [-] (default ``"DOP853"``).
    compiled_rhs : bool
        Use the compiled right-hand side.
    {h_max}
    atol_velocity : float or ndarray, optional
        Absolute tolerance of the velocities [m/s], one for all or one per velocity
        (default ``atol``).
    """

    m = model_of(args)
    f = rhs_kernel(m) if compiled_rhs else chain_rhs
    omega = float(args[8])
    vt = train_of(args[9])
    buf = np.empty(len(y0))

    def fun(t, y):
        d = np.empty_like(buf)
        f(t, y, m, omega, vt, d, NO_EXTRA)
        return d

    from scipy.integrate import solve_ivp  # (here: scipy.integrate costs 0.4-0.9 s of every run's start-up)

    sol = solve_ivp(
        fun,
        (float(t_out[0]), float(t_out[-1])),
        np.asarray(y0, float),
        method=method,
        t_eval=t_out,
        rtol=rtol,
        atol=atol_vector(len(y0), atol, atol_velocity),
        max_step=h_max,
    )
    out = np.full((t_out.size, len(y0)), np.nan)
    out[: sol.y.shape[1]] = sol.y.T
    status = 0 if sol.status == 0 else 2
    t_reached = float(sol.t[-1]) if sol.t.size else float(t_out[0])
    return out, dict(status=status, t=t_reached, steps=int(sol.nfev), rejected=0, message=sol.message)
