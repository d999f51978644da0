"""Natural frequencies of the lumped chain linearised about a static state.

The chain is the 5-mass, 6-element chain of [MMS], "Model variable for One-Step spring"
and "for Two-Step spring" (Figs. 40.32-40.33; topology in docs/valve-spring.md), linearised
with the tangent stiffnesses of its "Nonlinear characteristics".
"""

from __future__ import annotations

import math

import numpy as np

from ...core.docstrings import ParameterDocs
from ...core.errors import InputError
from ...core.units import rpm_to_hz

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    masses : ndarray, shape (n,)
        Lumped masses [kg].
    k : ndarray, shape (n + 1,)
        Element tangent stiffnesses [N/m].
    """
)


__all__ = ["chain_stiffness_matrix", "chain_frequencies", "chain_eigenvalues", "mode_labels", "surge_margin"]

#: Largest chain [-] solved as a dense matrix (LAPACK's symmetric solver; above it, the
#: tridiagonal solver of SciPy, which selects the lowest modes).
_DENSE_MAX = 64


def chain_stiffness_matrix(k: np.ndarray) -> np.ndarray:
    """Tridiagonal stiffness matrix [N/m] of masses joined in series, both ends fixed.

    Parameters
    ----------
    k : ndarray, shape (n + 1,)
        Element (tangent) stiffnesses from the seat to the retainer [N/m]; element j
        joins mass j-1 and mass j (mass -1 is the seat, mass n the retainer).

    Returns
    -------
    ndarray, shape (n, n)
    """
    k = np.asarray(k, dtype=float)
    n = k.size - 1
    kmat = np.diag(k[:-1] + k[1:])
    i = np.arange(n - 1)
    kmat[i, i + 1] = kmat[i + 1, i] = -k[1:-1]
    return kmat


def _mass_normalised(masses, k) -> tuple:
    """The masses and the diagonal and off-diagonal of ``M^-1/2 K M^-1/2`` of the chain [kg, 1/s^2]."""
    m = np.asarray(masses, dtype=float)
    k = np.asarray(k, dtype=float)
    return m, (k[:-1] + k[1:]) / m, -k[1:-1] / np.sqrt(m[:-1] * m[1:])


@_DOCS.fill
def chain_frequencies(masses: np.ndarray, k: np.ndarray, count: int | None = None) -> np.ndarray:
    """Natural frequencies [Hz], ascending, of the chain with both ends fixed.

    Solves ``K phi = w^2 M phi``: the mass-normalised matrix ``M^-1/2 K M^-1/2`` is
    symmetric tridiagonal (LAPACK's symmetric eigensolver; the tridiagonal one for long chains).
    At free length the one-step chain's first mode is close to f1 of [MMS], "Natural
    Frequency for free length" (the check of docs/valve-spring.md, "The physics in a page", Modes).

    Parameters
    ----------
    {masses k}
    count : int, optional
        Only the lowest ``count`` frequencies [-].
    """
    m, d, e = _mass_normalised(masses, k)
    if m.size <= _DENSE_MAX:  # small chains (Type C): NumPy's dense solver, no SciPy import
        w2 = np.linalg.eigvalsh(np.diag(d) + np.diag(e, 1) + np.diag(e, -1))[:count]
    else:
        import scipy.linalg  # (here: it costs a tenth of a second of every command's start)

        if count is None or count >= m.size:
            w2 = scipy.linalg.eigh_tridiagonal(d, e, eigvals_only=True)
        else:
            w2 = scipy.linalg.eigh_tridiagonal(d, e, eigvals_only=True, select="i", select_range=(0, count - 1))
    return np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * np.pi)


#: A mode whose kinetic energy lies at least this much in the chain's two end masses is an
#: end-mass mode (the end masses bouncing on their stiff end contacts), not a surge mode.
END_MASS_ENERGY = 0.5


@_DOCS.fill
def mode_labels(masses: np.ndarray, k: np.ndarray, count: int | None = None) -> list[str]:
    """What each of the lowest natural modes of the chain is: ``"surge n"`` (the n-th
    standing wave along the coils) or ``"end mass"`` (the end masses bouncing on their stiff
    end contacts: at least :data:`END_MASS_ENERGY` of the kinetic energy in the two end masses).

    Parameters
    ----------
    {masses k}
    count : int, optional
        Only the lowest ``count`` modes [-].

    Examples
    --------
    >>> mode_labels(np.ones(3), np.array([1e6, 1.0, 1.0, 1e6]))  # heavy end contacts, soft middle
    ['surge 1', 'end mass', 'end mass']
    """
    m, d, e = _mass_normalised(masses, k)
    _, vec = np.linalg.eigh(np.diag(d) + np.diag(e, 1) + np.diag(e, -1))  # mass-normalised shapes
    labels, surge = [], 0
    for j in range(vec.shape[1] if count is None else min(count, vec.shape[1])):
        energy = vec[:, j] ** 2  # kinetic energy per mass of the mass-normalised shape
        if m.size > 2 and (energy[0] + energy[-1]) / energy.sum() >= END_MASS_ENERGY:
            labels.append("end mass")
        else:
            surge += 1
            labels.append(f"surge {surge}")
    return labels


def chain_eigenvalues(masses, stiffness, damping) -> np.ndarray:
    """Eigenvalues [1/s] of the damped chain ``M u'' + C u' + K u = 0``, both ends fixed.

    The eigenvalues of the first-order (state-space) matrix: complex pairs for the
    underdamped modes, real ones for the overdamped; the largest magnitude bounds an
    explicit integrator's step (``|lambda| h`` within its stability interval).

    Parameters
    ----------
    masses : ndarray (n,)
        Lumped masses [kg].
    stiffness, damping : ndarray (n + 1,)
        Element tangent stiffnesses [N/m] and damping coefficients [N s/m].

    Returns
    -------
    ndarray (2 n,), complex
    """
    n = len(masses)
    minv = 1.0 / np.asarray(masses, dtype=float)[:, None]
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    a[n:, :n] = -minv * chain_stiffness_matrix(stiffness)
    a[n:, n:] = -minv * chain_stiffness_matrix(damping)
    return np.linalg.eigvals(a)


def surge_margin(surge_frequency: float, cam_speed_rpm: float) -> float:
    """Ratio of the spring's surge frequency to the camshaft frequency [-].

    A common rule of thumb of valve-train practice (not in [MMS]) asks for 10-13 or more:
    cam-order harmonics up to that order then stay below the first surge mode.

    Parameters
    ----------
    surge_frequency : float
        First surge frequency of the spring [Hz] ([Wahl]; [MMS], f1 and f2).
    cam_speed_rpm : float
        Camshaft speed [rev/min], positive.

    Raises
    ------
    InputError
        ``cam_speed_rpm`` is not a positive, finite speed (the margin needs a rotating cam).
    """
    if not (math.isfinite(cam_speed_rpm) and cam_speed_rpm > 0):
        raise InputError(f"cam_speed_rpm = {cam_speed_rpm!r} must be a positive, finite speed [rev/min]")
    return surge_frequency / rpm_to_hz(cam_speed_rpm)
