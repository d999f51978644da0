"""Equivalent (describing-function) coefficients of the nonlinear damper at a given amplitude.

The coefficient model of Chapter 3 linearises each mechanism with closed forms at one
amplitude.  Here the nonlinear force laws of the time-domain rig (pack springs with lift-off,
inter-leaf Coulomb friction on the instantaneous pack load, O-ring Coulomb friction:
:mod:`springdyn.lsd.forces`; the oil network) are evaluated along a harmonic ring motion of
given amplitude and frequency, and their first harmonic gives the equivalent stiffness and
damping, mechanism by mechanism (the describing function; e.g. Gelb and Vander Velde,
*Multiple-input describing functions*, 1968).  This is what a rig identifies at that
amplitude, and what an amplitude-consistent rotor response (:mod:`springdyn.lsd.jeffcott`)
needs.

Motions: ``"linear"`` -- an x shake and a y shake of amplitude ``A`` (one column of the
2 x 2 matrices each); ``"circular"`` -- a forward and a backward orbit of radius ``A``
(``H = F X^-1``).  Phasors: ``x(t) = Re(X exp(j w t))``.
"""

from __future__ import annotations

import numpy as np

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError
from .forces import interleaf_friction_forces, oring_friction_force, pack_spring_forces

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    samples : int
        Quadrature points per period [-].
    model : LSDModel
        The damper.
    omega : float
        Vibration frequency [rad/s].
    """
)


__all__ = ["MECHANISMS", "harmonic_forces", "equivalent_matrices", "forward_whirl_coefficient", "DEFAULT_SAMPLES"]

#: The force laws, in the order of :func:`harmonic_forces`.
MECHANISMS = ("spring", "leaf_friction", "oring_friction", "oil")
#: Samples per period of the first-harmonic quadrature [-].  The friction forces jump where
#: a deflection rate changes sign; the midpoint rule's error there is ~1/samples of the
#: friction force (0.05 % at 2048).
DEFAULT_SAMPLES = 2048


@_DOCS.fill
def harmonic_forces(model, X, Y, omega, samples: int = DEFAULT_SAMPLES, film: bool = False) -> dict:
    """First-harmonic force phasors of each mechanism along ``x = Re(X e^(jwt)), y = Re(Y e^(jwt))``.

    Parameters
    ----------
    {model}
    X, Y : complex
        Displacement phasors [m].
    {omega samples}
    film : bool
        Oil force from the film network with passage inertia and cavitation at its
        periodic steady state (:func:`springdyn.lsd.film.film_harmonic`; its details under
        the key ``"film"``); otherwise the thesis' incompressible, inertia-free network
        ``j omega C_visc X`` (as the default rig, :func:`springdyn.lsd.rig.simulate_rig`).

    Returns
    -------
    dict
        ``{mechanism: (Fx, Fy)}`` complex force phasors [N] for the mechanisms of
        :data:`MECHANISMS` (the force the shaft applies to the ring, as the rig measures).
    """
    if not (np.isfinite(omega) and omega > 0):
        raise InputError(f"omega = {omega!r} rad/s must be positive")
    n = int(samples)
    if n < 64:
        raise InputError(f"samples = {samples!r} must be at least 64")
    theta = 2.0 * np.pi * (np.arange(n) + 0.5) / n  # midpoints: no sample on a symmetric switch
    e = np.exp(1j * theta)
    x, y = np.real(X * e), np.real(Y * e)
    vx, vy = np.real(1j * omega * X * e), np.real(1j * omega * Y * e)
    p = model.params
    fx, fy, loads = pack_spring_forces(model.angles, model.pack_stiffness, p.preload, x, y)
    forces = {
        "spring": (fx, fy),
        "leaf_friction": interleaf_friction_forces(model.angles, loads, p.leaf_friction, model.slip_factor, vx, vy),
        "oring_friction": oring_friction_force(p.oring_friction, p.oring_normal_force, vx, vy),
    }
    conj = np.conj(e) * (2.0 / n)
    out = {k: (complex(np.sum(a * conj)), complex(np.sum(b * conj))) for k, (a, b) in forces.items()}
    if film:
        from .film import film_harmonic

        fx_oil, fy_oil, info = film_harmonic(model, X, Y, omega)
        out["oil"] = (fx_oil, fy_oil)
        out["film"] = info
    else:
        f = 1j * omega * model.viscous_damping @ np.array([X, Y], dtype=complex)
        out["oil"] = (complex(f[0]), complex(f[1]))
    return out


@_DOCS.fill
def equivalent_matrices(
    model, omega, amplitude, motion: str = "linear", samples: int = DEFAULT_SAMPLES, film: bool = False
):
    """Equivalent K and C (2 x 2) at vibration frequency ``omega`` and amplitude, per mechanism.

    Parameters
    ----------
    {model omega}
    amplitude : float
        Shake amplitude or orbit radius [m].
    motion : {"linear", "circular"}
        x and y shakes, or forward and backward orbits.
    {samples}
    film : bool
        Oil from the film network with inertia and cavitation (:func:`harmonic_forces`).

    Returns
    -------
    dict
        ``{mechanism: (K, C)}`` [N/m], [N s/m]; the totals are the sums (the oil's ``K`` is
        its added mass times ``-omega^2``).  With ``film``, ``"film"`` holds
        ``cavitated`` (either motion) and ``min_pressure_Pa`` (absolute, lowest of both).
    """
    if not (np.isfinite(amplitude) and amplitude > 0):
        raise InputError(f"amplitude = {amplitude!r} m must be positive")
    if motion == "linear":
        X = np.array([[amplitude, 0.0], [0.0, amplitude]], dtype=complex)
    elif motion == "circular":
        X = np.array([[amplitude, amplitude], [-1j * amplitude, 1j * amplitude]])
    else:
        raise InputError(f"motion = {motion!r} is not allowed; choose 'linear' or 'circular'")
    cols = [harmonic_forces(model, X[0, k], X[1, k], omega, samples, film=film) for k in range(2)]
    Xinv = np.linalg.inv(X)
    out = {}
    if film:
        out["film"] = {
            "cavitated": any(c["film"]["cavitated"] for c in cols),
            "min_pressure_Pa": min(c["film"]["min_pressure_Pa"] for c in cols),
        }
    for mech in MECHANISMS:
        F = np.array([[cols[0][mech][0], cols[1][mech][0]], [cols[0][mech][1], cols[1][mech][1]]])
        H = F @ Xinv
        out[mech] = (H.real, H.imag / omega)
    return out


@_DOCS.fill
def forward_whirl_coefficient(model, omega, amplitude, samples: int = DEFAULT_SAMPLES) -> complex:
    """Complex forward-whirl describing function ``H = F_z / z`` [N/m] of the damper.

    On a forward circular orbit ``z = x + j y = A e^(jwt)`` the first harmonic of the
    damper force ``F_z = F_x + j F_y`` is ``H z``; ``Re H`` is the equivalent stiffness and
    ``Im H / omega`` the equivalent damping of an isotropic support at that amplitude.

    Parameters
    ----------
    {model}
    omega : float
        Whirl frequency [rad/s].
    amplitude : float
        Orbit radius [m].
    {samples}
    """
    if not (np.isfinite(amplitude) and amplitude > 0):
        raise InputError(f"amplitude = {amplitude!r} m must be positive")
    f = harmonic_forces(model, amplitude, -1j * amplitude, omega, samples)
    Fx = sum(f[k][0] for k in MECHANISMS)
    Fy = sum(f[k][1] for k in MECHANISMS)
    return (Fx + 1j * Fy) / (2.0 * amplitude)
