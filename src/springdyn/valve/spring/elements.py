"""Nonlinear force laws of the six chain elements ([MMS], "Nonlinear characteristics").

A law is stored as an ``(S, 4)`` float array (``S >= 3`` segments: 3 for Type C's laws,
``CLOSING_PIECES + 2`` for the distributed model's), one row per segment
``(x_start, a, b, c)``: on ``x_start <= x < next x_start`` the element force is
``F = a x^2 + b x + c``.  The first segment starts at ``-inf`` and is linear (tension
continues the linear law, correction MMS-9 of docs/references.md); unused rows have ``x_start = +inf``.  The same
arrays feed the NumPy functions here and the compiled kernels of the dynamics.

Every law is C1-continuous and has a non-decreasing tangent stiffness, so force is
strictly increasing in compression and the inverse (force -> compression) is unique.
"""

from __future__ import annotations

import math

import numpy as np

from ...core.docstrings import ParameterDocs

__all__ = [
    "quadratic_through",
    "linear_law",
    "hardening_law",
    "low_pitch_law",
    "law_force",
    "law_stiffness",
    "law_compression",
    "damping_coefficient",
    "law_energy",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    law : ndarray, shape (S, 4) or (E, S, 4)
        Element law, rows ``(x_start [m], a [N/m^2], b [N/m], c [N])``; or the laws of ``E``
        elements at once, the first axis of ``x`` (or ``force``) then the element's.
    x : float or array_like
        Element compression [m].
    """
)

_INF = math.inf


def quadratic_through(x0: float, f0: float, k0: float, x1: float, f1: float) -> tuple[float, float, float]:
    """Coefficients of ``F = a x^2 + b x + c`` through ``(x0, f0)`` with slope ``k0`` there
    and through ``(x1, f1)``.

    This is the closed-form solution of the document's 3x3 systems
    ``[[x0^2, x0, 1], [x1^2, x1, 1], [2 x0, 1, 0]] (a, b, c) = (f0, f1, k0)``
    (better conditioned than solving the matrix numerically); [MMS], "Nonlinear
    characteristics of Kh1" / "of Kh2" / "of Ks".

    Parameters
    ----------
    x0, x1 : float
        Compressions [m], ``x1 != x0``.
    f0, f1 : float
        Forces [N].
    k0 : float
        Slope at ``x0`` [N/m].
    """
    h = x1 - x0
    a = (f1 - f0 - k0 * h) / h**2
    b = k0 - 2.0 * a * x0
    c = f0 - a * x0**2 - b * x0
    return a, b, c


def _upper_root(a: float, b: float, c: float, force: float) -> float:
    """Compression where the rising branch of ``a x^2 + b x + c`` reaches ``force``."""
    return 2.0 * (force - c) / (b + math.sqrt(b * b + 4.0 * a * (force - c)))


def linear_law(k: float) -> np.ndarray:
    """Law of a linear element ``F = k x`` (the end elements K).

    Parameters
    ----------
    k : float
        Element stiffness [N/m].

    Returns
    -------
    law : ndarray, shape (S, 4)

    Notes
    -----
    [MMS], "Stiffness for fully contact" gives K no nonlinear law; the end elements are
    linear in compression (correction MMS-7 of docs/references.md).
    """
    law = np.full((3, 4), _INF)
    law[0] = (-_INF, 0.0, k, 0.0)
    return law


def hardening_law(k0: float, k_prime: float, f1: float, f2: float, fcon: float, pc: float):
    """Law of a Kh1 or Kh2 element with its breakpoints ([MMS], "Nonlinear characteristics
    of Kh1" and "of Kh2").

    Linear ``k0 x`` up to ``x_1 = F1/k0``; then the quadratic through ``(x_1, F1)`` with
    slope ``k0`` and through ``(x_2, F2)``, ``x_2 = x_1 + (F2 - F1)/k'`` (document's
    x12 / x22 with corrections MMS-1 and MMS-2 of docs/references.md: ``Kh1'``/``Kh2'`` and ``x11``/``x21``);
    from ``x_3`` (where that quadratic reaches Fcon) the coil-contact quadratic through
    ``(x_3, Fcon)`` with the slope there (``Kh1c``/``Kh2c``) and through
    ``(x_4, 2 Fcon)``, ``x_4 = x_3 + Pc/10``; beyond ``x_4`` it continues
    (correction MMS-9 of docs/references.md).

    Parameters
    ----------
    k0 : float
        Initial rate Kh1 or Kh2 [N/m].
    k_prime : float
        Stiffened rate Kh1' or Kh2' [N/m].
    f1, f2, fcon : float
        Breakpoint forces F1, F2 and Fcon [N], ``0 < F1 < F2`` and ``F1 < Fcon``.
    pc : float
        Coil gap term Pc [m].

    Returns
    -------
    law : ndarray, shape (S, 4)
    breakpoints : dict
        ``x1, x2, x3, x4`` [m] (the document's x11..x14 or x21..x24) and ``kc`` [N/m]
        (Kh1c or Kh2c).
    """
    x1 = f1 / k0
    x2 = (f2 - f1) / k_prime + x1
    a1, b1, c1 = quadratic_through(x1, f1, k0, x2, f2)
    x3 = _upper_root(a1, b1, c1, fcon)
    kc = 2.0 * a1 * x3 + b1
    x4 = x3 + pc / 10.0
    a2, b2, c2 = quadratic_through(x3, fcon, kc, x4, 2.0 * fcon)
    law = np.array([(-_INF, 0.0, k0, 0.0), (x1, a1, b1, c1), (x3, a2, b2, c2)])
    return law, dict(x1=x1, x2=x2, x3=x3, x4=x4, kc=kc)


def low_pitch_law(ks: float, fset: float, dw: float):
    """Law of the two-step low-pitch element Ks (document, "Nonlinear characteristics of Ks").

    Linear ``Ks x`` up to ``x_1 = Fset/Ks``; then the quadratic through ``(x_1, Fset)``
    with slope Ks and through ``(x_2, 5 Ks x_2)``, ``x_2 = x_1 + Dw/10``.

    Parameters
    ----------
    ks : float
        Low-pitch section rate [N/m].
    fset : float
        Set-up force [N].
    dw : float
        Wire diameter [m].

    Returns
    -------
    law : ndarray, shape (S, 4)
    breakpoints : dict
        ``x1, x2`` [m].
    """
    x1 = fset / ks
    x2 = x1 + dw / 10.0
    a, b, c = quadratic_through(x1, fset, ks, x2, 5.0 * ks * x2)
    law = np.full((3, 4), _INF)
    law[0] = (-_INF, 0.0, ks, 0.0)
    law[1] = (x1, a, b, c)
    return law, dict(x1=x1, x2=x2)


def _coefficients(x, law, rows=None):
    """The segment coefficients ``a, b, c`` of ``law`` at ``x``, shaped like ``x``.

    ``law`` is one law ``(S, 4)`` or one law per element ``(E, S, 4)``; with ``E`` laws the first
    axis of ``x`` is the element's (``x`` of shape ``(E, ...)``), so a whole chain is evaluated at
    once.  The segment of ``x`` is the last whose start (``rows``, by default the laws' ``x_start``
    column) it reaches.
    """
    x = np.asarray(x, dtype=float)
    starts = law[..., 1:, 0] if rows is None else rows
    if law.ndim == 2:
        seg = np.zeros(x.shape, dtype=np.intp)
        for start in starts:
            seg += x >= start
        return law[seg, 1], law[seg, 2], law[seg, 3]
    e = law.shape[0]
    flat = x.reshape(e, -1)
    seg = np.count_nonzero(flat[:, None, :] >= starts[:, :, None], axis=1)
    a, b, c = (np.take_along_axis(law[:, :, j], seg, axis=1).reshape(x.shape) for j in (1, 2, 3))
    return a, b, c


@_DOCS.fill
def law_force(x, law: np.ndarray):
    """Element force [N] at compression ``x`` [m] (scalar or array).

    Parameters
    ----------
    x : float or array_like
        Element compression from its free state [m].
    {law}

    Notes
    -----
    [MMS], "Spring load for Kh1 becomes as follows" (and likewise Kh2, Ks).
    """
    x = np.asarray(x, dtype=float)
    a, b, c = _coefficients(x, law)
    return (a * x + b) * x + c


@_DOCS.fill
def law_stiffness(x, law: np.ndarray):
    """Tangent stiffness ``dF/dx`` [N/m] at compression ``x`` [m].

    Parameters
    ----------
    {x law}

    Notes
    -----
    Derivative of the law of [MMS], "Nonlinear characteristics" (the ``K(x)`` of
    "Damping Coefficient").
    """
    x = np.asarray(x, dtype=float)
    a, b, _ = _coefficients(x, law)
    return 2.0 * a * x + b


@_DOCS.fill
def law_compression(force, law: np.ndarray):
    """Inverse law: compression [m] at which the element carries ``force`` [N].

    Parameters
    ----------
    force : float or array_like
        Element force [N].
    {law}

    Notes
    -----
    The rising root of the law of [MMS], "Nonlinear characteristics" (as ``x13`` there);
    used for the series equilibrium of correction MMS-10 of docs/references.md.
    """
    force = np.asarray(force, dtype=float)
    starts = law[..., 1:, 0]
    with np.errstate(invalid="ignore"):  # unused rows: inf starts, their force inf below
        f_start = law_force(starts, law)  # force at each later segment start (inf if unused)
    f_start = np.where(np.isfinite(starts), f_start, np.inf)
    a, b, c = _coefficients(force, law, f_start)
    d = force - c
    return 2.0 * d / (b + np.sqrt(np.maximum(b * b + 4.0 * a * d, 0.0)))


@_DOCS.fill
def damping_coefficient(x, law: np.ndarray, c0: float):
    """Element damping ``c(x) = C0 sqrt(k(x)/k(0))`` [N s/m] ([MMS], "Damping Coefficient").

    ``k(x)`` is the tangent stiffness of the element's law and ``k(0)`` its initial
    (linear) rate; ``C0 = 2 Cps sqrt(M K1)`` (correction MMS-8 of docs/references.md).

    Parameters
    ----------
    {x law}
    c0 : float
        Base damping coefficient C0 [N s/m].
    """
    return c0 * np.sqrt(law_stiffness(x, law) / law[0, 2])


@_DOCS.fill
def law_energy(x, law: np.ndarray):
    """Strain energy ``int_0^x F(s) ds`` [J] stored in an element compressed by ``x`` [m].

    Exact integral of the piecewise quadratic law of [MMS], "Nonlinear characteristics"
    (used for energy balances).

    Parameters
    ----------
    {x law}
    """
    x = np.asarray(x, dtype=float)
    energy = np.where(x < 0, 0.5 * law[0, 2] * x * x, 0.0)
    xp = np.maximum(x, 0.0)
    starts = np.concatenate([[0.0], np.maximum(law[1:, 0], 0.0), [np.inf]])
    for seg in range(law.shape[0]):
        lo = starts[seg]
        hi = np.minimum(xp, starts[seg + 1])
        if not np.isfinite(lo):
            break
        a, b, c = law[seg, 1], law[seg, 2], law[seg, 3]
        hi = np.maximum(hi, lo)
        energy = energy + a / 3 * (hi**3 - lo**3) + b / 2 * (hi**2 - lo**2) + c * (hi - lo)
    return energy
