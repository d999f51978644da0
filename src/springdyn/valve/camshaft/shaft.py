"""The camshaft as a discrete torsional chain: its matrices, its modes and its periodic twist.

The shaft is a chain of rotating inertias (the sprocket, the lobes) joined by torsional springs
(the shaft between them, ``G I_p / L``), driven at the sprocket's end through the timing drive
(a spring and a damper to the crankshaft's sprocket, which turns at the nominal speed); the
bearings' oil films damp the node nearest each bearing against the head.  Twist ``phi`` is each
node's angle ahead of the nominal (rigid) camshaft angle ``Omega t``.

Equations of motion, per node (``J`` diagonal, ``K`` and ``C`` tridiagonal plus the drive):

    J phi'' + C phi' + K phi = -Q(t) - c_b Omega

with ``Q`` the lobes' load torques (the followers' resistance, positive against the rotation)
and ``c_b Omega`` the bearings' mean drag.  The response to a periodic ``Q`` is linear: per
harmonic ``k`` of the cam speed, ``(K - (k Omega)^2 J + i k Omega C) Phi_k = -Q_k``
(:func:`periodic_twist`; harmonic balance, exact for the linear chain).

The modes are the undamped chain's with the crankshaft's sprocket held (its inertia, referred
to the camshaft through the 2:1 drive, is some hundred times the camshaft's):
``K v = omega^2 J v`` (:func:`torsional_modes`).  The closed form that checks them, a
fixed-free chain of ``N`` equal inertias ``J`` and springs ``k``:
``omega_n = 2 sqrt(k/J) sin((2n - 1) pi / (2 (2N + 1)))`` ([Rao], the eigenvalues of the
tridiagonal chain matrix).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "polar_moment",
    "segment_stiffness",
    "segment_inertia",
    "chain_matrices",
    "torsional_modes",
    "periodic_twist",
    "harmonics_on_grid",
]


def polar_moment(diameter: float, bore: float = 0.0) -> float:
    """Polar second moment of area of a (hollow) round shaft [m^4]: ``pi (d^4 - d_i^4) / 32``.

    Parameters
    ----------
    diameter : float
        Outer diameter [m].
    bore : float
        Inner diameter [m] (0: solid).
    """
    return math.pi * (diameter**4 - bore**4) / 32.0


def segment_stiffness(shear_modulus: float, polar: float, length):
    """Torsional stiffness of a round shaft segment [N m/rad]: ``G I_p / L`` (Saint-Venant torsion).

    Parameters
    ----------
    shear_modulus : float
        G [Pa].
    polar : float
        Polar second moment of area I_p [m^4] (:func:`polar_moment`).
    length : float or ndarray
        Segment length [m].
    """
    return shear_modulus * polar / np.asarray(length, dtype=float)


def segment_inertia(density: float, polar: float, length):
    """Mass moment of inertia of a round shaft segment about its axis [kg m^2]: ``rho I_p L``.

    Parameters
    ----------
    density : float
        rho [kg/m^3].
    polar : float
        Polar second moment of area I_p [m^4].
    length : float or ndarray
        Segment length [m].
    """
    return density * polar * np.asarray(length, dtype=float)


def chain_matrices(inertia, stiffness, drive_stiffness, drive_damping=0.0, ground_damping=None):
    """Inertia, stiffness and damping matrices of the torsional chain driven at node 0.

    Parameters
    ----------
    inertia : array_like (N,)
        Inertia of each node [kg m^2], node 0 the sprocket.
    stiffness : array_like (N-1,)
        Torsional stiffness between node j and j+1 [N m/rad].
    drive_stiffness : float
        The timing drive's stiffness between the crankshaft's sprocket and node 0 [N m/rad].
    drive_damping : float
        The timing drive's damping [N m s/rad].
    ground_damping : array_like (N,), optional
        Each node's damping against the head (the bearings' oil films) [N m s/rad].

    Returns
    -------
    J, K, C : ndarray (N, N)
        [kg m^2], [N m/rad], [N m s/rad].
    """
    j = np.asarray(inertia, dtype=float)
    k = np.asarray(stiffness, dtype=float)
    n = j.size
    if k.size != n - 1:
        raise ValueError(f"{n} nodes need {n - 1} stiffnesses, not {k.size}")
    kk = np.zeros((n, n))
    for i, ki in enumerate(k):
        kk[i, i] += ki
        kk[i + 1, i + 1] += ki
        kk[i, i + 1] -= ki
        kk[i + 1, i] -= ki
    kk[0, 0] += drive_stiffness
    cc = np.diag(np.zeros(n) if ground_damping is None else np.asarray(ground_damping, dtype=float))
    cc[0, 0] += drive_damping
    return np.diag(j), kk, cc


def torsional_modes(inertia_matrix, stiffness_matrix):
    """Natural frequencies and mode shapes of the undamped chain: ``K v = omega^2 J v``.

    Parameters
    ----------
    inertia_matrix, stiffness_matrix : ndarray (N, N)
        J [kg m^2] and K [N m/rad] (:func:`chain_matrices`).

    Returns
    -------
    frequency : ndarray (N,)
        Natural frequencies [Hz], ascending.
    shapes : ndarray (N, N)
        Mode shapes in columns, each scaled to a largest node angle of 1 [-].
    """
    from scipy.linalg import eigh  # (here: scipy.linalg costs start-up of every valve command)

    w2, v = eigh(stiffness_matrix, inertia_matrix)
    v = v / v[np.argmax(np.abs(v), axis=0), np.arange(v.shape[1])]
    return np.sqrt(np.maximum(w2, 0.0)) / (2.0 * math.pi), v


def periodic_twist(inertia_matrix, stiffness_matrix, damping_matrix, torque, omega: float, mean_torque=None):
    """The periodic twist of the chain under periodic node torques, per harmonic of the cam speed.

    ``(K - (k omega)^2 J + i k omega C) Phi_k = T_k`` for each harmonic ``k`` of the torque's
    discrete Fourier series (the mean, ``k = 0``, through ``K``: the drive spring holds it).

    Parameters
    ----------
    inertia_matrix, stiffness_matrix, damping_matrix : ndarray (N, N)
        J [kg m^2], K [N m/rad], C [N m s/rad] (:func:`chain_matrices`).
    torque : ndarray (N, n)
        Torque on each node [N m] at the cam angles ``2 pi j / n`` of one revolution (positive
        along the rotation).
    omega : float
        Cam speed [rad/s].
    mean_torque : array_like (N,), optional
        A constant torque on each node besides [N m] (the bearings' drag).

    Returns
    -------
    ndarray (N, n//2 + 1)
        The twist's spectrum [rad] (numpy.fft.rfft's convention: ``phi_j = irfft(Phi)``); the
        Nyquist harmonic of an even ``n`` is set to zero (its derivatives are not defined).
    """
    t = np.fft.rfft(np.asarray(torque, dtype=float), axis=-1)
    if mean_torque is not None:
        t[:, 0] += np.asarray(mean_torque, dtype=float) * torque.shape[-1]
    out = np.zeros_like(t)
    n = torque.shape[-1]
    top = t.shape[-1] - (1 if n % 2 == 0 else 0)
    w = (np.arange(top) * omega)[:, None, None]
    a = stiffness_matrix[None] - w * w * inertia_matrix[None] + 1j * w * damping_matrix[None]
    out[:, :top] = np.linalg.solve(a, t[:, :top].T[:, :, None])[:, :, 0].T  # one system per harmonic
    return out


def harmonics_on_grid(spectrum, n_from: int, points: int, shift: float = 0.0):
    """A periodic function given by its spectrum, and its first two derivatives, on another grid.

    The trigonometric interpolant of samples at ``2 pi j / n_from`` (their rfft ``spectrum``),
    evaluated with its derivatives at ``2 pi j / points + shift``.

    Parameters
    ----------
    spectrum : ndarray (..., n_from//2 + 1)
        numpy.fft.rfft of the samples [their unit, e.g. rad].
    n_from : int
        Samples the spectrum was taken from [-].
    points : int
        Samples of the new grid [-] (a coarser grid keeps the harmonics it resolves).
    shift : float
        Angle added to the new grid [rad].

    Returns
    -------
    f, df, ddf : ndarray (..., points)
        The function [its unit], per rad, per rad^2.
    """
    x = np.asarray(spectrum)
    k = np.arange(x.shape[-1])
    x = x * np.exp(1j * k * shift) * (points / n_from)
    pad = np.zeros(x.shape[:-1] + (points // 2 + 1,), dtype=complex)
    top = min(x.shape[-1], points // 2)  # harmonics the new grid resolves (its Nyquist one left out)
    pad[..., :top] = x[..., :top]
    kk = np.arange(pad.shape[-1])
    return tuple(np.fft.irfft(pad * (1j * kk) ** p, n=points, axis=-1) for p in (0, 1, 2))
