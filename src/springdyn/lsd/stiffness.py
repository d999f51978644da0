"""Stiffness matrix of the leaf spring damper from its packs, Eq. (3.4) of the thesis.

Pack ``i`` sits at angle ``phi_i`` from the x axis; a ring displacement ``(dx, dy)``
deflects it by ``delta_i = dx cos phi_i + dy sin phi_i`` (positive: the ring moves
towards the pack and compresses it).  Packs are preloaded by ``delta_pre``: while
``|delta_i| < delta_pre`` every pack stays in contact and the model is linear.
"""

from __future__ import annotations

import warnings

import numpy as np

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError

__all__ = [
    "equally_spaced_angles",
    "pack_deflections",
    "stiffness_matrix",
    "isotropic_stiffness",
    "PreloadExceededWarning",
    "warn_if_unloading",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    packs : int
        Number of packs N [-].
    """
)


class PreloadExceededWarning(UserWarning):
    """The vibration amplitude exceeds the pack preload: packs lift off, K and C are no longer linear."""


@_DOCS.fill
def equally_spaced_angles(packs: int, first_angle: float = 0.0) -> np.ndarray:
    """Angles of ``packs`` equally spaced packs [rad], the first at ``first_angle`` [rad].

    Parameters
    ----------
    {packs}
    first_angle : float
        Angle of the first pack [rad].
    """
    if int(packs) != packs or packs < 1:
        raise InputError(f"packs = {packs!r} must be a whole number of at least 1")
    return first_angle + 2.0 * np.pi * np.arange(int(packs)) / int(packs)


def pack_deflections(angles, dx, dy):
    """Pack deflections ``delta_i = dx cos phi_i + dy sin phi_i`` [m].

    Parameters
    ----------
    angles : array_like
        Pack angles ``phi_i`` [rad], shape ``(N,)``.
    dx, dy : float or array
        Ring displacement [m]; arrays of shape ``(T,)`` give a ``(T, N)`` result.
    """
    phi = np.asarray(angles, dtype=float)
    dx = np.asarray(dx, dtype=float)[..., None]
    dy = np.asarray(dy, dtype=float)[..., None]
    return dx * np.cos(phi) + dy * np.sin(phi)


def stiffness_matrix(pack_stiffness, angles):
    """Stiffness matrix of packs at arbitrary angles, Eq. (3.4) of the thesis [N/m].

    ``K = k_s sum_i [[cos^2, sin cos], [sin cos, sin^2]](phi_i)``.

    Parameters
    ----------
    pack_stiffness : float
        ``k_s`` of one pack [N/m].
    angles : array_like
        Pack angles [rad].

    Returns
    -------
    numpy.ndarray
        2 x 2 matrix ``[[Kxx, Kxy], [Kyx, Kyy]]`` [N/m].
    """
    phi = np.asarray(angles, dtype=float)
    c, s = np.cos(phi), np.sin(phi)
    return pack_stiffness * np.array([[np.sum(c * c), np.sum(s * c)], [np.sum(s * c), np.sum(s * s)]])


@_DOCS.fill
def isotropic_stiffness(packs: int, pack_stiffness: float) -> float:
    """``Kxx = Kyy = N k_s / 2`` of ``N >= 3`` equally spaced packs (thesis, after (3.6)) [N/m].

    Parameters
    ----------
    {packs}
    pack_stiffness : float
        Stiffness k_s of one pack [N/m].

    Raises
    ------
    InputError
        Fewer than 3 packs: the shortcut does not hold (use :func:`stiffness_matrix`).
    """
    if packs < 3:
        raise InputError(
            f"packs = {packs}: the isotropic shortcut Kxx = Kyy = N k_s/2 needs at least 3 equally "
            "spaced packs; use stiffness_matrix(k_s, angles) for other layouts"
        )
    return 0.5 * packs * pack_stiffness


def warn_if_unloading(amplitude: float, preload: float, *, stacklevel: int = 3) -> bool:
    """Warn (:class:`PreloadExceededWarning`) when ``amplitude > preload``; return whether it did.

    Parameters
    ----------
    amplitude : float
        Shake amplitude [m].
    preload : float
        Pack preload deflection delta_pre [m].
    stacklevel : int
        Stack level of the warning [-].
    """
    if amplitude > preload:
        warnings.warn(
            f"vibration amplitude {amplitude * 1e6:.4g} um exceeds the pack preload "
            f"{preload * 1e6:.4g} um: packs lift off during the cycle and the linear "
            "coefficients no longer hold (the rig simulation models the lift-off)",
            PreloadExceededWarning,
            stacklevel=stacklevel,
        )
        return True
    return False
