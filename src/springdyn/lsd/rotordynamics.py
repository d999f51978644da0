"""The leaf spring damper as a ROSS bearing element (optional extra ``springdyn[ross]``).

ROSS (``ross-rotordynamics``) takes bearing and damper elements with frequency-dependent
``kxx, kxy, kyx, kyy, cxx, cxy, cyx, cyy`` (``ross.BearingElement(n, kxx, cxx, ...,
frequency=...)``, frequencies in rad/s).  ROSS is imported only here, when asked for.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import InputError

__all__ = ["bearing_element", "DEFAULT_FREQUENCIES"]

#: Default frequencies [rad/s]: 500 to 3000 rpm, the speed range of the thesis' rig.
DEFAULT_FREQUENCIES = 2.0 * np.pi * np.linspace(500.0, 3000.0, 11) / 60.0


def bearing_element(model, n: int, frequencies=None, *, amplitude: float = 50e-6, motion: str = "linear", **kwargs):
    """Build ``ross.BearingElement`` at node ``n`` from an :class:`~springdyn.lsd.LSDModel`.

    Parameters
    ----------
    model : LSDModel
    n : int
        Rotor node number [-].
    frequencies : array_like, optional
        Frequencies [rad/s] at which the coefficients are tabulated (ROSS interpolates
        between them); default :data:`DEFAULT_FREQUENCIES`.
    amplitude : float
        Vibration amplitude [m] for the amplitude-dependent friction damping.
    motion : {"linear", "circular"}
        Motion assumed for the O-ring Coulomb equivalent.
    **kwargs
        Passed on (``tag``, ``n_link``, ``scale_factor``...).
    """
    try:
        import ross
    except ImportError:
        raise InputError(
            "to_ross() needs the optional package ross-rotordynamics (pip install 'springdyn[ross]')"
        ) from None
    w = DEFAULT_FREQUENCIES if frequencies is None else np.atleast_1d(np.asarray(frequencies, dtype=float))
    if w.ndim != 1 or w.size < 1 or np.any(~np.isfinite(w)) or np.any(w <= 0) or np.any(np.diff(w) <= 0):
        raise InputError(f"frequencies = {w.tolist()} rad/s must be positive and increasing")
    coeffs = model.coefficients(60.0 * w / (2.0 * np.pi), amplitude=amplitude, motion=motion)
    K, C = coeffs.K, coeffs.C
    kwargs.setdefault("tag", f"LSD {model.params.name}")
    return ross.BearingElement(
        n=n,
        kxx=K[:, 0, 0], kxy=K[:, 0, 1], kyx=K[:, 1, 0], kyy=K[:, 1, 1],
        cxx=C[:, 0, 0], cxy=C[:, 0, 1], cyx=C[:, 1, 0], cyy=C[:, 1, 1],
        frequency=w,
        **kwargs,
    )
