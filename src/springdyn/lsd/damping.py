"""Damping of the leaf spring damper: O-ring friction, inter-leaf friction, oil network.

Three sources add up (Sections 2.2 and 3 of the leaf-spring-damper thesis):

- Coulomb friction of the O-rings, as an equivalent viscous coefficient ``C_f`` (2.21)-(2.22);
- friction between the leaves of each pack, as a hysteretic loss factor (2.23)-(2.28);
- the oil squeezed between the chambers (the spaces between packs) through narrow
  passages (2.11)-(2.20), (3.5)-(3.6), written here as the network
  ``C_visc = B^T G^+ B`` (correction LSD-3 of docs/references.md).

Units: SI throughout (m, N, Pa, Pa s, rad/s).
"""

from __future__ import annotations

import numpy as np

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError

__all__ = [
    "coulomb_equivalent_damping",
    "interleaf_slip_factor",
    "leaf_loss_factor",
    "hysteresis_damping_matrix",
    "hydraulic_diameter",
    "passage_conductance_thesis",
    "passage_conductance_rectangular",
    "boundary_conductance",
    "chamber_volume_matrix",
    "chamber_laplacian",
    "chamber_pressures",
    "viscous_damping_matrix",
    "viscous_damping_thesis",
    "compliant_chamber_coefficients",
    "duct_flow_series",
    "duct_profile_factor",
    "duct_impedance_ratio",
    "passage_inertance",
    "squeeze_reynolds_number",
    "ATMOSPHERIC_PRESSURE",
]

#: Smallest vibration amplitude [m] of the coefficients: 1 nm, below any measurable damper
#: vibration (the friction equivalents grow as 1 / amplitude).
MIN_AMPLITUDE = 1e-9

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    clearance : float
        Passage clearance h_o [m].
    width : float
        Passage width b_o [m].
    terms : int
        Odd terms per direction [-].
    conductance : float
        Conductance C_D between neighbouring chambers [m^3/(s Pa)].
    length : float
        Passage length L_h [m].
    leakage_factor : float
        Calibration factor on the conductance [-].
    width, clearance : float
        Sides of the duct [m].
    density : float
        Oil density rho [kg/m^3].
    passages : int
        Parallel passages between two chambers [-].
    volume_matrix : numpy.ndarray
        ``B`` (N x 2) from :func:`chamber_volume_matrix` [m^2].
    omega : float or array
        Vibration frequency [rad/s].
    angles : array_like
        Pack angles phi_i [rad].
    """,
    omega_one="omega : float\n    Vibration frequency [rad/s].",
)

#: Standard atmosphere [Pa]: gauge + ATMOSPHERIC_PRESSURE = absolute.
ATMOSPHERIC_PRESSURE = 101325.0


@_DOCS.fill
def coulomb_equivalent_damping(friction_coefficient, normal_force, omega, amplitude, motion="linear"):
    """Equivalent viscous damping of a Coulomb friction force [N s/m], Eq. (2.22).

    Equal dissipation per cycle.  For a straight-line harmonic motion of amplitude ``A``
    the friction ``mu F_N`` dissipates ``4 mu F_N A`` (Eq. (2.21)), so
    ``C_f = 4 mu F_N / (pi omega A)``, the thesis' formula.  On a circular orbit of
    radius ``A`` (the thesis' own test rig) the friction force is constant and opposes
    the velocity, dissipating ``2 pi A mu F_N`` per turn: ``C_f = mu F_N / (omega A)``.

    Parameters
    ----------
    friction_coefficient : float
        ``mu_o`` [-].
    normal_force : float
        O-ring normal force ``F_N`` [N].
    {omega}
    amplitude : float
        Vibration amplitude ``A`` [m].
    motion : {"linear", "circular"}
        Straight-line shake (thesis) or circular orbit.
    """
    omega = np.asarray(omega, dtype=float)
    if amplitude <= 0:
        raise InputError(f"amplitude = {amplitude!r} m must be positive")
    factor = {"linear": 4.0 / np.pi, "circular": 1.0}.get(motion)
    if factor is None:
        raise InputError(f"motion = {motion!r} is not allowed; choose 'linear' or 'circular'")
    return factor * friction_coefficient * normal_force / (omega * amplitude)


def interleaf_slip_factor(load_ratios, deflection_ratios, thicknesses, lengths):
    """Bracket of Eqs. (2.27)-(2.28): ``t_1/L_1 + 2 sum_(i>=2) phi_i (delta_i/delta_1) t_i/L_i`` [-].

    It converts the pack tip deflection into the friction work between the leaves:
    the slip at the tip of leaf ``i`` is ``3 delta_i t_i / (2 L_i)`` (Eq. (2.26)) and
    leaves ``i >= 2`` slip on both faces.

    Parameters
    ----------
    load_ratios : array_like
        Leaf load ratios phi_i = P_i/P_1 of Eq. (2.7) [-].
    deflection_ratios : array_like
        Leaf tip deflection ratios delta_i/delta_1 [-].
    thicknesses : array_like
        Leaf thicknesses t_i [m].
    lengths : array_like
        Leaf lengths L_i, longest first [m].
    """
    phi = np.asarray(load_ratios, dtype=float)
    r = np.asarray(deflection_ratios, dtype=float)
    t = np.asarray(thicknesses, dtype=float)
    L = np.asarray(lengths, dtype=float)
    return float(t[0] / L[0] + 2.0 * np.sum(phi[1:] * r[1:] * t[1:] / L[1:]))


def leaf_loss_factor(friction_coefficient, preload, amplitude, slip_factor, normal_load="peak"):
    """Hysteretic loss factor ``zeta`` of a pack from inter-leaf friction, Eq. (2.28) [-].

    ``zeta = E_d / (pi k_s delta_1^2)`` with the dissipated energy ``E_d`` of Eq. (2.27).

    - ``normal_load="peak"`` (thesis): the leaves press on each other with the peak pack
      load ``k_s (delta_1 + delta_pre)`` all cycle long:
      ``zeta = (6 mu_s / pi) (1 + delta_pre/delta_1) S``.
    - ``normal_load="instantaneous"``: the normal load follows the pack load
      ``k_s (delta_pre + delta(t))``, as in springdyn's time-domain rig model; over a
      harmonic cycle with ``delta_1 <= delta_pre`` the ``delta(t)`` part cancels and
      ``zeta = (6 mu_s / pi) (delta_pre/delta_1) S``.

    The thesis calls this factor xi (like the stiffness factor of (2.9)) and its
    hysteretic coefficient eta in (3.1); springdyn names it ``loss_factor``
    (correction LSD-3 of docs/references.md).  (2.23) is read as ``F_s = k_s (1 + j zeta) delta``
    (the printed time derivative is a typo, same note).

    Parameters
    ----------
    friction_coefficient : float
        ``mu_s`` between leaves [-].
    preload : float
        ``delta_pre`` [m].
    amplitude : float
        Pack deflection amplitude ``delta_1`` [m].
    slip_factor : float
        ``S`` from :func:`interleaf_slip_factor` [-].
    normal_load : {"peak", "instantaneous"}
    """
    if amplitude <= 0:
        raise InputError(f"amplitude = {amplitude!r} m must be positive")
    if normal_load == "peak":
        load = 1.0 + preload / amplitude
    elif normal_load == "instantaneous":
        load = preload / amplitude
    else:
        raise InputError(f"normal_load = {normal_load!r} is not allowed; choose 'peak' or 'instantaneous'")
    return 6.0 * friction_coefficient / np.pi * load * slip_factor


@_DOCS.fill
def hysteresis_damping_matrix(loss_factor, pack_stiffness, omega, angles):
    """Equivalent viscous damping of the packs' hysteresis, ``C_h = zeta k_s / omega`` [N s/m].

    Eq. (2.24) per pack, summed over the packs like the stiffness (the second term of
    each coefficient of (3.5)).  Returns an array of shape ``omega.shape + (2, 2)``.

    Parameters
    ----------
    loss_factor : float
        Loss factor zeta of the packs' hysteresis, Eq. (2.28) [-].
    pack_stiffness : float
        Stiffness k_s of one pack [N/m].
    {omega_one angles}
    """
    phi = np.asarray(angles, dtype=float)
    c, s = np.cos(phi), np.sin(phi)
    geometry = np.array([[np.sum(c * c), np.sum(s * c)], [np.sum(s * c), np.sum(s * s)]])
    omega = np.asarray(omega, dtype=float)
    return (loss_factor * pack_stiffness / omega)[..., None, None] * geometry


@_DOCS.fill
def hydraulic_diameter(width, clearance):
    """Hydraulic diameter of a rectangular passage ``d_h = 2 b_o h_o / (b_o + h_o)`` [m], Eq. (2.17).

    Parameters
    ----------
    {width clearance}
    """
    return 2.0 * width * clearance / (width + clearance)


@_DOCS.fill
def passage_conductance_thesis(width, clearance, length, viscosity):
    """Conductance of one passage as printed in Eq. (2.17): ``pi d_h^4 / (142 eta L_h)`` [m^3/(s Pa)].

    The thesis' ``C_D`` has a factor 2 in front (two passages per chamber boundary);
    springdyn applies that count separately (``passages_per_boundary``).  The constant
    142 is the author's (it gives the 639 = 9 x 71 of (3.6)); docs/references.md.

    Parameters
    ----------
    width, clearance : float
        ``b_o``, ``h_o`` [m].
    {length}
    viscosity : float
        Dynamic viscosity ``eta`` [Pa s].
    """
    dh = hydraulic_diameter(width, clearance)
    return np.pi * dh**4 / (142.0 * viscosity * length)


@_DOCS.fill
def passage_conductance_rectangular(width, clearance, length, viscosity, terms=50):
    """Exact laminar conductance of a rectangular duct [m^3/(s Pa)].

    ``Q/dp = b h^3 / (12 eta L) [1 - (192 h / (pi^5 b)) sum_(n odd) tanh(n pi b / (2h)) / n^5]``
    with ``h <= b`` the smaller side (the classical series solution; White, *Viscous Fluid
    Flow*, Eq. (3-48)).  For the thin slots of the thesis it is 1.7 to 14 times Eq. (2.17)
    (correction LSD-3 of docs/references.md).

    Parameters
    ----------
    width, clearance : float
        Sides of the passage [m] (either order).
    {length}
    viscosity : float
        Dynamic viscosity [Pa s].
    terms : int
        Number of odd terms of the series [-].
    """
    b, h = max(width, clearance), min(width, clearance)
    n = 2.0 * np.arange(terms) + 1.0
    series = np.sum(np.tanh(n * np.pi * b / (2.0 * h)) / n**5)
    return b * h**3 / (12.0 * viscosity * length) * (1.0 - 192.0 * h / (np.pi**5 * b) * series)


@_DOCS.fill
def boundary_conductance(width, clearance, length, viscosity, passages=2, model="exact", leakage_factor=1.0):
    """Conductance ``C_D`` between two neighbouring chambers [m^3/(s Pa)].

    ``passages`` parallel passages of the chosen ``model`` ("exact" rectangular duct or
    "thesis" Eq. (2.17)), times the calibration ``leakage_factor`` (correction LSD-6
    of docs/references.md: the closed form over-predicts damping; a leakage factor > 1 lowers it).

    Parameters
    ----------
    {width clearance length}
    viscosity : float
        Dynamic oil viscosity [Pa s].
    {passages}
    model : str
        Conductance model: 'exact' (rectangular duct, correction LSD-2 of docs/references.md) or 'thesis' (Eq. (2.17)).
    {leakage_factor}
    """
    if model == "exact":
        single = passage_conductance_rectangular(width, clearance, length, viscosity)
    elif model == "thesis":
        single = passage_conductance_thesis(width, clearance, length, viscosity)
    else:
        raise InputError(f"conductance_model = {model!r} is not allowed; choose 'exact' or 'thesis'")
    return passages * leakage_factor * single


def chamber_volume_matrix(angles, ring_width, ring_diameter, leaf_length):
    """Volume squeezed out of each chamber per unit ring displacement, Eq. (2.15) [m^2].

    Chamber ``i`` lies between packs ``i`` and ``i+1`` (cyclic).  Row ``i`` is
    ``[b d_o/2 (sin phi_(i+1) - sin phi_i) + 3bL/8 (cos phi_i - cos phi_(i+1)),
    b d_o/2 (cos phi_i - cos phi_(i+1)) + 3bL/8 (sin phi_i - sin phi_(i+1))]``:
    the ring surface term (2.12) plus the leaf bending terms (2.14), whose deflection
    shape (2.13) sweeps ``3 b L / 8`` per unit tip deflection.  The rows sum to zero
    (the oil is incompressible and only moves between chambers).

    Parameters
    ----------
    angles : array_like
        Pack angles [rad], in increasing order around the ring.
    ring_width : float
        ``b`` [m].
    ring_diameter : float
        ``d_o`` [m].
    leaf_length : float
        ``L`` of the pack (its longest leaf) [m].
    """
    phi = np.asarray(angles, dtype=float)
    nxt = np.roll(phi, -1)
    ring = 0.5 * ring_width * ring_diameter
    leaf = 3.0 * ring_width * leaf_length / 8.0
    bx = ring * (np.sin(nxt) - np.sin(phi)) + leaf * (np.cos(phi) - np.cos(nxt))
    by = ring * (np.cos(phi) - np.cos(nxt)) + leaf * (np.sin(phi) - np.sin(nxt))
    return np.column_stack([bx, by])


@_DOCS.fill
def chamber_laplacian(chambers: int, conductance: float) -> np.ndarray:
    """Conductance matrix ``G`` of a ring of chambers joined to their two neighbours [m^3/(s Pa)].

    ``(G p)_i = C_D (2 p_i - p_(i-1) - p_(i+1))`` is the outflow of chamber ``i``
    (Eq. (2.16) with ``C_DR = C_DL = C_D``).  For two chambers they share two boundaries.

    Parameters
    ----------
    chambers : int
        Number of oil chambers [-].
    {conductance}
    """
    n = int(chambers)
    if n < 2:
        raise InputError(f"packs = {n}: an oil network needs at least 2 chambers (2 packs)")
    G = 2.0 * np.eye(n)
    for i in range(n):
        G[i, (i + 1) % n] -= 1.0
        G[i, (i - 1) % n] -= 1.0
    return conductance * G


@_DOCS.fill
def chamber_pressures(volume_matrix, conductance, velocity):
    """Chamber gauge pressures ``p = G^+ B v`` [Pa] for ring velocity ``v`` [m/s].

    Continuity (2.16), (2.18): the outflow ``G p`` equals the squeeze rate ``B v``.  The
    pseudo-inverse picks the solution of zero mean (the mean pressure is not set by the
    network).  Eq. (2.19) prints ``-p`` (correction LSD-3 of docs/references.md): squeezing raises the
    chamber pressure.

    Parameters
    ----------
    {volume_matrix}
    conductance : float
        ``C_D`` [m^3/(s Pa)].
    velocity : array_like
        ``(vx, vy)`` [m/s], or shape ``(T, 2)``; complex phasors are kept complex.
    """
    B = np.asarray(volume_matrix, dtype=float)
    Gp = np.linalg.pinv(chamber_laplacian(B.shape[0], conductance))
    v = np.asarray(velocity)
    v = v.astype(complex if np.iscomplexobj(v) else float)
    return v @ (Gp @ B).T


@_DOCS.fill
def viscous_damping_matrix(volume_matrix, conductance):
    """Damping of the oil network ``C_visc = B^T G^+ B`` [N s/m] (correction LSD-3 of docs/references.md).

    The force needed to move the ring is ``B^T p`` (virtual work of the chamber
    pressures on the squeezed volumes), so the matrix is symmetric and positive
    semi-definite.  Equal to (3.5) with the ``C_yy`` typo fixed
    (:func:`viscous_damping_thesis`).

    Parameters
    ----------
    volume_matrix : ndarray
        Chamber volume change per unit ring displacement, B (N x 2) [m^2].
    {conductance}
    """
    B = np.asarray(volume_matrix, dtype=float)
    Gp = np.linalg.pinv(chamber_laplacian(B.shape[0], conductance))
    C = B.T @ Gp @ B
    return 0.5 * (C + C.T)


@_DOCS.fill
def viscous_damping_thesis(angles, ring_width, ring_diameter, leaf_length, conductance):
    """Viscous part of Eq. (3.5) of the thesis, with the ``C_yy`` typo fixed [N s/m].

    ``C_xx = lambda sum_i {(pbar_(x,i-1) - pbar_(x,i)) cos phi_i
    + (4 d_o/(3L)) pbar_(x,i) (sin phi_i - sin phi_(i+1))}`` and likewise the others, with
    ``lambda = 9 b^2 L^2 / (64 C_D)`` (3.6) and ``pbar = 8 C_D/(3 b L) p`` where ``p`` solves
    (2.19) as printed.  The printed ``C_yy`` has ``pbar_(x,i-1)``; it must be
    ``pbar_(y,i-1)`` (correction LSD-3 of docs/references.md).  Written out term by term as in the
    thesis, as an independent check of :func:`viscous_damping_matrix`.

    Parameters
    ----------
    {angles}
    ring_width : float
        Inner ring width b [m].
    ring_diameter : float
        Inner ring outer diameter d_o [m].
    leaf_length : float
        Length of the longest leaf L_1 [m].
    {conductance}
    """
    phi = np.asarray(angles, dtype=float)
    n = phi.size
    b, L, do = ring_width, leaf_length, ring_diameter
    B = chamber_volume_matrix(phi, b, do, L)
    # (2.19) as printed: p_(i-1) - 2 p_i + p_(i+1) = (B v)_i / C_D, i.e. -Laplacian p = B v / C_D
    lap = -chamber_laplacian(n, 1.0)
    p_printed = np.linalg.pinv(lap) @ (B / conductance)  # columns: d p / d xdot, d p / d ydot
    pbar = 8.0 * conductance / (3.0 * b * L) * p_printed
    lam = 9.0 * b * b * L * L / (64.0 * conductance)
    k = 4.0 * do / (3.0 * L)
    px, py = pbar[:, 0], pbar[:, 1]
    px_prev, py_prev = np.roll(px, 1), np.roll(py, 1)
    c, s = np.cos(phi), np.sin(phi)
    c_next, s_next = np.roll(c, -1), np.roll(s, -1)
    cxx = lam * np.sum((px_prev - px) * c + k * px * (s - s_next))
    cxy = lam * np.sum((py_prev - py) * c + k * py * (s - s_next))
    cyx = lam * np.sum((px_prev - px) * s - k * px * (c - c_next))
    cyy = lam * np.sum((py_prev - py) * s - k * py * (c - c_next))  # typo fixed: py_prev
    return np.array([[cxx, cxy], [cyx, cyy]])


@_DOCS.fill
def compliant_chamber_coefficients(volume_matrix, conductance, chamber_compliance, omega):
    """Stiffness and damping of the oil network with compliant chambers [N/m], [N s/m].

    Each chamber stores ``c_ch dp/dt`` (``c_ch = V / beta_eff``: chamber volume over the
    effective bulk modulus of the oil, lowered by entrained air), so continuity (2.16),
    (2.18) becomes ``G p + c_ch dp/dt = B v`` and, for a harmonic motion,
    ``H(omega) = j omega B^T (G + j omega c_ch I)^-1 B``: ``K = Re H``, ``C = Im H / omega``.
    For ``c_ch -> 0`` it is ``C_visc = B^T G^+ B`` with no stiffness; at high frequency or
    with thick oil the chambers stop passing oil and ``H -> B^T B / c_ch``: a stiffness that
    does not depend on the viscosity, and a damping force that saturates.  **Not part of
    the coefficient model** (no chamber volume or air content is known for the thesis'
    dampers): an analysis tool for the weak viscosity dependence of correction LSD-7 of
    docs/references.md.

    Parameters
    ----------
    {volume_matrix}
    conductance : float
        ``C_D`` between neighbouring chambers [m^3/(s Pa)].
    chamber_compliance : float
        ``c_ch = V / beta_eff`` of each chamber [m^3/Pa]; 0 is incompressible oil.
    {omega_one}

    Returns
    -------
    tuple of numpy.ndarray
        ``(K, C)``, each 2 x 2.
    """
    if not (np.isfinite(chamber_compliance) and chamber_compliance >= 0):
        raise InputError(f"chamber_compliance = {chamber_compliance!r} m^3/Pa must be zero or positive")
    if not (np.isfinite(omega) and omega > 0):
        raise InputError(f"omega = {omega!r} rad/s must be positive")
    B = np.asarray(volume_matrix, dtype=float)
    G = chamber_laplacian(B.shape[0], conductance)
    if chamber_compliance == 0:
        return np.zeros((2, 2)), viscous_damping_matrix(B, conductance)
    A = G + 1j * omega * chamber_compliance * np.eye(B.shape[0])
    H = 1j * omega * B.T @ np.linalg.solve(A, B)
    return H.real, H.imag / omega


# ---------------------------------------------------------------- fluid inertia in the passages


@_DOCS.fill
def duct_flow_series(width, clearance, terms=101):
    """Weights and eigenvalues of the laminar flow in a rectangular duct [-], [1/m^2].

    The velocity of a flow driven by a pressure gradient in a ``b x h`` duct (no slip on the
    walls) expands in the eigenfunctions ``sin(m pi y/b) sin(n pi z/h)`` (``m, n`` odd) of the
    Laplacian, with eigenvalues ``lambda_mn = pi^2 (m^2/b^2 + n^2/h^2)`` and weights
    ``w_mn = 64 / (pi^4 m^2 n^2)``.  Steady flow: ``Q = (A dp / (mu L)) sum w/lambda``;
    oscillating flow of frequency ``omega``: each term becomes ``w / (lambda (1 + j omega /
    (nu lambda)))`` (every mode is a parallel resistance-inertance branch; the plane-channel
    limit is the classical solution of Womersley type, e.g. White, *Viscous Fluid Flow*,
    3rd ed., 2006, Sec. 3-4.2).

    Parameters
    ----------
    width, clearance : float
        Sides of the duct ``b``, ``h`` [m].
    {terms}

    Returns
    -------
    tuple of numpy.ndarray
        ``(w, lambda)``, flattened.
    """
    if not (width > 0 and clearance > 0):
        raise InputError(f"duct sides {width!r} m x {clearance!r} m must be positive")
    k = 2.0 * np.arange(int(terms)) + 1.0
    m, n = np.meshgrid(k, k, indexing="ij")
    w = 64.0 / (np.pi**4 * m**2 * n**2)
    lam = np.pi**2 * (m**2 / width**2 + n**2 / clearance**2)
    return w.ravel(), lam.ravel()


@_DOCS.fill
def duct_profile_factor(width, clearance, terms=101):
    """Inertance factor ``kappa = A int(u^2) dA / (int u dA)^2`` of laminar duct flow [-].

    The kinetic energy of the Poiseuille profile is ``kappa`` times that of a plug flow of the
    same rate, so a slowly oscillating flow sees the inertance ``kappa rho L / A``
    (low-frequency limit of the exact impedance, :func:`duct_impedance_ratio`).
    ``kappa = 6/5`` between parallel plates (``b >> h``) and ``4/3`` in a circular pipe
    (e.g. Bruus, *Theoretical Microfluidics*, 2008, Sec. 4.5 on hydraulic inertance); for a
    rectangular duct ``kappa = S2 / S1^2`` with the sums ``S1 = sum w/lambda`` and
    ``S2 = sum w/lambda^2`` of :func:`duct_flow_series` (``int u dA = A S1 dp/(mu L)``,
    ``int u^2 dA = A S2 (dp/(mu L))^2``).

    Parameters
    ----------
    {width_clearance terms}
    """
    w, lam = duct_flow_series(width, clearance, terms)
    s1, s2 = np.sum(w / lam), np.sum(w / lam**2)
    return float(s2 / s1**2)


@_DOCS.fill
def duct_impedance_ratio(width, clearance, kinematic_viscosity, omega, terms=101):
    """Exact oscillating-flow impedance of a rectangular duct over its steady resistance ``Z/R`` [-].

    ``Z(omega)/R = sum(w/lambda) / sum(w / (lambda + j omega/nu))`` (:func:`duct_flow_series`).
    Low frequency: ``1 + j omega tau`` with ``tau = kappa rho L / (A R)``, the lumped
    resistance-inertance passage of springdyn's film model; at high frequency the profile
    flattens (Stokes layers), the resistance rises and the inertance falls to ``rho L / A``.

    Parameters
    ----------
    {width_clearance}
    kinematic_viscosity : float
        ``nu = mu / rho`` [m^2/s].
    omega : float or array
        Frequency [rad/s].
    {terms}
    """
    w, lam = duct_flow_series(width, clearance, terms)
    om = np.asarray(omega, dtype=float)
    steady = np.sum(w / lam)
    osc = np.sum(w / (lam + 1j * om[..., None] / kinematic_viscosity), axis=-1)
    return steady / osc


@_DOCS.fill
def passage_inertance(width, clearance, length, density, passages=2, leakage_factor=1.0):
    """Inertance ``I`` of the passages between two neighbouring chambers [Pa s^2/m^3].

    One passage: ``kappa rho L_h / (b_o h_o)`` with the profile factor ``kappa`` of
    :func:`duct_profile_factor` (6/5 for a thin slot); ``passages`` in parallel divide it,
    and so does the calibration ``leakage_factor``, read as that many equivalent parallel
    passages (so that the time constant ``I C_D`` of the boundary, and with it the
    importance of inertia, is a property of the passage geometry and the oil only).  The
    pressure drop is ``R q + I dq/dt`` with ``R = 1 / C_D``.

    Parameters
    ----------
    {width clearance length density passages leakage_factor}
    """
    kappa = duct_profile_factor(width, clearance)
    return kappa * density * length / (width * clearance) / (passages * leakage_factor)


@_DOCS.fill
def squeeze_reynolds_number(density, viscosity, omega, clearance):
    """Squeeze Reynolds number of the passage flow ``Re_s = rho omega h^2 / mu`` [-].

    The usual measure of fluid inertia in squeeze-film dampers (San Andres, *Squeeze film
    dampers*, lecture notes, Texas A&M, 2010, Eq. (4)), here with the passage clearance
    ``h_o``: the ratio of the local (temporal) inertia to the viscous term across the gap.
    Between plates the inertial pressure drop is ``omega tau = Re_s / 10`` of the viscous
    one (``kappa/12 = 1/10``); for the thesis' rectangular passages see
    :func:`duct_profile_factor`.

    Parameters
    ----------
    {density}
    viscosity : float
        Dynamic oil viscosity mu [Pa s].
    {omega clearance}
    """
    return density * np.asarray(omega, dtype=float) * clearance**2 / viscosity
