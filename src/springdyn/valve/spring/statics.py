"""Static (massless) behaviour of the element chain: series equilibrium.

In statics every element of the series chain carries the same force and the element
compressions add up to the total compression ``Lf - L`` (correction MMS-10 of docs/references.md).  Because each
element law has a non-decreasing tangent stiffness, the total compression is a concave,
strictly increasing function of the force; Newton's method started below the root
converges monotonically, which :func:`series_force` exploits (vectorised over lengths).
This exact equilibrium replaces the document's residual spreading
``x_j = x_j' + eps x_j'/sum(x')`` ("Initial condition & position"), which it satisfies
with ``eps = 0``.
"""

from __future__ import annotations

import numpy as np

from ...core.errors import SolverError
from .elements import law_compression, law_force, law_stiffness

__all__ = ["element_compressions", "element_forces", "series_compliance", "series_force", "series_state"]


def element_compressions(force, laws: np.ndarray) -> np.ndarray:
    """Compression of every element [m] under a common force [N].

    Parameters
    ----------
    force : float or ndarray, shape (n,)
        Force carried by the chain [N].
    laws : ndarray, shape (n_elements, S, 4)
        Element laws [m, N]: per element, segments ``x_start [m], a [N/m^2], b [N/m], c [N]``
        (see :mod:`springdyn.valve.spring.elements`).

    Returns
    -------
    ndarray, shape (n_elements,) or (n_elements, n)
        Compressions [m].
    """
    force = np.asarray(force, dtype=float)
    return law_compression(np.broadcast_to(force, (laws.shape[0],) + force.shape), laws)


def series_compliance(force, laws: np.ndarray):
    """Tangent compliance ``sum_j 1/k_j`` [m/N] of the chain at a common force [N].

    Parameters
    ----------
    force : float or ndarray
        Force carried by the chain [N].
    laws : ndarray, shape (n_elements, S, 4)
        Element laws [m, N]: per element, segments ``x_start [m], a [N/m^2], b [N/m], c [N]``
        (see :mod:`springdyn.valve.spring.elements`).
    """
    x = element_compressions(force, laws)
    return np.sum(1.0 / law_stiffness(x, laws), axis=0)


def series_force(total_compression, laws: np.ndarray, *, rtol: float = 1e-12, max_iter: int = 100):
    """Force [N] of the chain compressed by ``total_compression`` [m] in total.

    Solves ``sum_j x_j(F) = dL`` by Newton's method from the linear-chain force
    ``K1 dL``, which lies below the root (monotone convergence for the concave,
    increasing ``sum_j x_j(F)``).

    Parameters
    ----------
    total_compression : float or ndarray
        ``Lf - L`` [m]; negative values (tension) follow the linear laws.
    laws : ndarray, shape (n_elements, S, 4)
        Element laws [m, N]: per element, segments ``x_start [m], a [N/m^2], b [N/m], c [N]``
        (see :mod:`springdyn.valve.spring.elements`).
    rtol : float
        Relative size [-] of the last Newton step at which to stop; Newton converges
        quadratically, so the force is then exact to round-off (about 1e-14 relative,
        where round-off of the compression sum makes further steps oscillate).
    max_iter : int
        Most Newton steps [-] before a :class:`SolverError` (the loop is bounded).

    Raises
    ------
    SolverError
        If Newton's method does not converge (it always does for valid laws).
    """
    dl = np.asarray(total_compression, dtype=float)
    k_lin = 1.0 / np.sum(1.0 / laws[:, 0, 2])
    # Start at the force of the all-linear chain: exact in the linear range and, because
    # the elements only stiffen, never above the root (so convergence stays monotone).
    force = dl * k_lin
    for _ in range(max_iter):
        x = element_compressions(force, laws)
        resid = dl - x.sum(axis=0)
        comp = np.sum(1.0 / law_stiffness(x, laws), axis=0)
        step = resid / comp
        force = force + step
        if np.all(np.abs(step) <= rtol * np.maximum(np.abs(force), 1e-300) + 1e-300):
            return force
    raise SolverError(f"static equilibrium did not converge for total compression {np.atleast_1d(dl).max():.6g} m")


def series_state(total_compression, laws: np.ndarray):
    """Force [N], element compressions [m] and tangent stiffness [N/m] of the chain.

    Parameters
    ----------
    total_compression : float or ndarray
        ``Lf - L`` [m].
    laws : ndarray, shape (n_elements, S, 4)
        Element laws [m, N]: per element, segments ``x_start [m], a [N/m^2], b [N/m], c [N]``
        (see :mod:`springdyn.valve.spring.elements`).

    Returns
    -------
    force : float or ndarray
    compressions : ndarray, shape (6,) or (6, n)
    stiffness : float or ndarray
        ``1 / sum_j (1/k_j)`` [N/m].
    """
    force = series_force(total_compression, laws)
    x = element_compressions(force, laws)
    return force, x, 1.0 / np.sum(1.0 / law_stiffness(x, laws), axis=0)


def element_forces(compressions, laws: np.ndarray) -> np.ndarray:
    """Force of every element [N] at its compression [m].

    Parameters
    ----------
    compressions : ndarray, shape (n_elements,) or (n_elements, n)
        Element compressions [m].
    laws : ndarray, shape (n_elements, S, 4)
        Element laws [m, N]: per element, segments ``x_start [m], a [N/m^2], b [N/m], c [N]``
        (see :mod:`springdyn.valve.spring.elements`).
    """
    return law_force(np.asarray(compressions, dtype=float), laws)
