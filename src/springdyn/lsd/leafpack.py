"""Leaf pack statics: load sharing between the leaves and the pack stiffness.

A pack is ``n`` cantilever leaves stacked on each other, clamped together at the root;
leaf 1 (the longest, ``L1 >= L2 >= ...``) carries the tip load ``P1`` from the inner ring
and rests on leaf 2 at ``x = L2``, leaf 2 rests on leaf 3 at ``x = L3``, and so on.  The
contact forces ``P_i`` follow from equal deflections at the contact points (Eq. (2.6) of
the leaf-spring-damper thesis).  Everything here is SI: lengths [m], ``EI`` [N m^2],
forces [N], stiffnesses [N/m].
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import solve_banded

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError

__all__ = [
    "second_moment_of_area",
    "cantilever_deflection",
    "load_ratios",
    "load_ratios_direct",
    "tip_deflection_ratios",
    "stiffness_factor",
    "pack_stiffness",
    "clamped_pack_stiffness",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    lengths : array_like
        Leaf lengths L_i, longest first [m].
    flexural_rigidities : array_like
        Flexural rigidities (E I)_i of the leaves [N m^2].
    """,
    lengths_any_order="lengths : array_like\n    Leaf lengths [m].",
    rigidities="flexural_rigidities : array_like\n    ``(EI)_i`` [N m^2].",
)


def _leaves(lengths, flexural_rigidities):
    L = np.asarray(lengths, dtype=float).ravel()
    EI = np.asarray(flexural_rigidities, dtype=float).ravel()
    if L.size == 0:
        raise InputError("leaf_lengths is empty; a pack needs at least one leaf")
    if EI.shape != L.shape:
        raise InputError(
            f"leaf_lengths has {L.size} entries but there are {EI.size} flexural rigidities; give one per leaf"
        )
    if np.any(~np.isfinite(L)) or np.any(L <= 0):
        raise InputError(f"leaf_lengths = {L.tolist()} m must all be positive")
    if np.any(~np.isfinite(EI)) or np.any(EI <= 0):
        raise InputError(f"flexural rigidities = {EI.tolist()} N m^2 must all be positive")
    if np.any(np.diff(L) > 0):
        i = int(np.argmax(np.diff(L) > 0))
        raise InputError(
            f"leaf_lengths must be non-increasing (L1 >= L2 >= ...): leaf {i + 2} "
            f"({L[i + 1] * 1e3:g} mm) is longer than leaf {i + 1} ({L[i] * 1e3:g} mm)"
        )
    return L, EI


def second_moment_of_area(width, thickness):
    """Second moment of area of a rectangular leaf ``b t^3 / 12`` [m^4].

    Parameters
    ----------
    width : float or array
        Leaf width ``b`` [m].
    thickness : float or array
        Leaf thickness ``t`` [m].
    """
    return np.asarray(width, dtype=float) * np.asarray(thickness, dtype=float) ** 3 / 12.0


def cantilever_deflection(x, load_position, flexural_rigidity):
    """Deflection per unit load of a cantilever at ``x`` under a point load at ``a`` [m/N].

    ``w(x) = x^2 (3a - x) / (6 EI)`` for ``x <= a`` and ``a^2 (3x - a) / (6 EI)`` beyond
    (the textbook influence function behind Eqs. (2.4)-(2.5) of the thesis).

    Parameters
    ----------
    x : float
        Position along the leaf from the clamp [m].
    load_position : float
        Position of the point load ``a`` [m].
    flexural_rigidity : float
        ``EI`` of the leaf [N m^2].
    """
    a = load_position
    if x <= a:
        return x * x * (3.0 * a - x) / (6.0 * flexural_rigidity)
    return a * a * (3.0 * x - a) / (6.0 * flexural_rigidity)


def load_ratios(lengths, flexural_rigidities):
    """Contact-load ratios ``phi_i = P_i / P_1`` of a leaf pack, Eq. (2.7) of the thesis.

    Solves the tridiagonal system ``a_i phi_(i-1) + d_i phi_i + c_i phi_(i+1) = 0``,
    ``i = 2..n``, with ``phi_1 = 1`` and ``phi_(n+1) = 0``, where
    ``a_i = (3 L_(i-1) - L_i) L_i^2 / L_1^3``,
    ``c_i = (EI)_(i-1)/(EI)_i a_(i+1)`` and
    ``d_i = -2 (L_i/L_1)^3 (1 + (EI)_(i-1)/(EI)_i)``.

    The thesis prints ``a_i = (3 L_(i-1) - L_i) L_i^2 / L_i^3``; the denominator must be
    ``L_1^3`` like in ``d_i`` (typo, docs/references.md).

    Parameters
    ----------
    lengths : array_like
        Leaf lengths ``L_1 >= L_2 >= ...`` [m].
    flexural_rigidities : array_like
        ``(EI)_i`` of each leaf [N m^2].

    Returns
    -------
    numpy.ndarray
        ``phi`` (length ``n``, ``phi[0] = 1``) [-].
    """
    L, EI = _leaves(lengths, flexural_rigidities)
    n = L.size
    if n == 1:
        return np.ones(1)
    L1 = L[0]
    i = np.arange(1, n)  # zero-based index of leaves 2..n
    a = (3.0 * L[i - 1] - L[i]) * L[i] ** 2 / L1**3
    r = EI[i - 1] / EI[i]
    d = -2.0 * (L[i] / L1) ** 3 * (1.0 + r)
    a_next = np.append(a[1:], 0.0)
    c = r * a_next
    rhs = np.zeros(n - 1)
    rhs[0] = -a[0]  # b_2 = -a_2 (phi_1 = 1 moved to the right-hand side)
    ab = np.zeros((3, n - 1))
    ab[0, 1:] = c[:-1]  # super-diagonal
    ab[1, :] = d
    ab[2, :-1] = a[1:]  # sub-diagonal
    phi = solve_banded((1, 1), ab, rhs)
    return np.concatenate(([1.0], phi))


@_DOCS.fill
def load_ratios_direct(lengths, flexural_rigidities):
    """Contact-load ratios by direct compatibility, an independent check of Eq. (2.7).

    Builds the compatibility conditions of Eq. (2.6) from the cantilever influence
    function (:func:`cantilever_deflection`) as a dense linear system in the unknown
    contact loads ``P_2..P_n`` for ``P_1 = 1`` and solves it with a general solver; no
    coefficient of (2.7) is used.

    Parameters
    ----------
    {lengths_any_order rigidities}

    Returns
    -------
    numpy.ndarray
        ``phi`` [-].
    """
    L, EI = _leaves(lengths, flexural_rigidities)
    n = L.size
    if n == 1:
        return np.ones(1)

    # Leaf k (0-based) carries +P_k at its tip L_k and -P_(k+1) at L_(k+1).
    def deflection_coeffs(k, x):
        row = np.zeros(n)
        row[k] += cantilever_deflection(x, L[k], EI[k])
        if k + 1 < n:
            row[k + 1] -= cantilever_deflection(x, L[k + 1], EI[k])
        return row

    A = np.zeros((n - 1, n))
    for j in range(1, n):  # contact between leaf j-1 and leaf j at x = L_j
        A[j - 1] = deflection_coeffs(j - 1, L[j]) - deflection_coeffs(j, L[j])
    P = np.linalg.solve(A[:, 1:], -A[:, 0])
    return np.concatenate(([1.0], P))


@_DOCS.fill
def tip_deflection_ratios(lengths, flexural_rigidities):
    """Tip deflection of each leaf relative to leaf 1, ``delta_i / delta_1`` [-].

    Used in the inter-leaf slip of Eqs. (2.26)-(2.28) of the thesis.

    Parameters
    ----------
    {lengths flexural_rigidities}
    """
    L, EI = _leaves(lengths, flexural_rigidities)
    phi = load_ratios(L, EI)
    n = L.size
    tips = np.empty(n)
    for k in range(n):
        tips[k] = phi[k] * cantilever_deflection(L[k], L[k], EI[k])
        if k + 1 < n:
            tips[k] -= phi[k + 1] * cantilever_deflection(L[k], L[k + 1], EI[k])
    return tips / tips[0]


@_DOCS.fill
def stiffness_factor(lengths, flexural_rigidities):
    """Stiffness factor ``xi`` of a leaf pack, Eq. (2.9) of the thesis [-].

    ``xi = 1 - phi_2 (L_2/L_1)^2 (3 - L_2/L_1) / 2``: the tip deflection of leaf 1 relative
    to a lone leaf 1.  ``xi = 1`` for one leaf and ``1/n`` for ``n`` equal leaves.
    (The thesis also calls a loss factor xi; springdyn names that one ``loss_factor``.)

    Parameters
    ----------
    {lengths flexural_rigidities}
    """
    L, EI = _leaves(lengths, flexural_rigidities)
    if L.size == 1:
        return 1.0
    phi = load_ratios(L, EI)
    q = L[1] / L[0]
    return float(1.0 - 0.5 * phi[1] * q * q * (3.0 - q))


@_DOCS.fill
def pack_stiffness(lengths, flexural_rigidities, poisson_ratio):
    r"""Leaf pack tip stiffness ``k_p = 3 (EI)_1 / (xi (1 - nu^2) L_1^3)``, Eq. (2.8) [N/m].

    .. math::

        k_p = \frac{3\,(EI)_1}{\xi\,(1 - \nu^2)\,L_1^3}

    The ``1 - nu^2`` turns the beam rigidity into the plate (wide-leaf) rigidity.

    Parameters
    ----------
    {lengths_any_order rigidities}
    poisson_ratio : float
        ``nu`` [-].

    Examples
    --------
    A single leaf, 20 mm long, 10 mm wide, 1 mm thick, of steel:

    >>> round(float(pack_stiffness([0.02], [206e9 * 0.01 * 1e-3**3 / 12], 0.3)), 1)
    70741.8

    References
    ----------
    .. [1] [LSD] of docs/references.md: the leaf-spring damper thesis, Eq. (2.8).
    """
    L, EI = _leaves(lengths, flexural_rigidities)
    xi = stiffness_factor(L, EI)
    return float(3.0 * EI[0] / (xi * (1.0 - poisson_ratio**2) * L[0] ** 3))


def clamped_pack_stiffness(pack_stiffness_value, clamp_overhang, first_length):
    """Pack stiffness with the clamp compliance ``k_s = k_p / (1 + a/L_1)``, Eq. (2.10) [N/m].

    Parameters
    ----------
    pack_stiffness_value : float
        ``k_p`` [N/m].
    clamp_overhang : float
        ``a`` of Fig. 2.3 [m] (not given in the thesis; 0 means a rigid clamp).
    first_length : float
        ``L_1`` [m].
    """
    return float(pack_stiffness_value / (1.0 + clamp_overhang / first_length))
