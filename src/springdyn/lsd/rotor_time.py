"""Time response of a ROSS rotor with leaf spring dampers whose oil film is solved implicitly.

ROSS 2.3's ``add_to_RHS`` hook (:func:`springdyn.lsd.rotordynamics.nonlinear_force`) adds a
force computed from the state of the step before.  That is enough for a force that changes
slowly with the state, but not for a cavitating film with inertia: when a voided chamber
refills, the oil columns in the passages stop within a step (an inelastic impact of the oil,
a pressure impulse), and the lagged impulse on a light bearing node makes the explicit
coupling unstable.  :func:`rotor_time_response` therefore integrates the rotor's own
matrices (``M``, ``C``, ``K``, ``G``, ``Ksdt`` taken from the ``ross.Rotor``) together with the
dampers' film networks (:mod:`springdyn.lsd.film`) in one implicit step:

- rotor: Newmark's scheme (slightly damped, ``gamma = 0.6``; ROSS's ``newmark`` uses the
  undamped average acceleration) with equilibrium at the end of each step, on the
  symmetric parts of ``M``, ``C``, ``K``; the skew and non-symmetric parts (gyroscopic
  ``omega(t) G``, cross-coupled bearings, ``Ksdt`` times the angular acceleration) are taken
  at the start of the step;
- damper packs: the linear pack stiffness (3.4) is part of the implicit ``K``; lift-off and
  friction (inter-leaf, O-ring; :mod:`springdyn.lsd.forces`) at the start of the step;
- oil: the film networks' pressures at the end of the step solve one linear complementarity
  problem together with the rotor's velocities (the rotor's velocity is linear in the oil
  forces, so the squeeze of every damper is too): ``p >= p_cav``, ``void >= 0``, complementary.
  The coupled matrix ``M_film + dt B P S^-1 P^T B^T`` is symmetric positive definite because
  the implicit rotor matrix ``S`` is; ``scipy.optimize.nnls`` solves it as in
  :func:`springdyn.lsd.film.solve_lcp`.

``film=False`` gives the linearised damper in the same integrator (pack stiffness, ``C_visc``
and the added mass ``M_a`` in the implicit matrices): the reference the film is compared with.

The rotor handed in must carry a bearing element with zero coefficients at each damper node
(``ross.BearingElement(n, kxx=0, cxx=0)``): the dampers are added here.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from scipy.linalg import cho_factor, cho_solve
from scipy.optimize import nnls

from ..core.errors import InputError
from .film import film_network
from .forces import interleaf_friction_forces, oring_friction_force, pack_spring_forces

__all__ = ["rotor_time_response", "RotorTimeResponse", "unbalance_runup"]


@dataclasses.dataclass
class RotorTimeResponse:
    """Displacements of every degree of freedom and the dampers' oil pressures vs time.

    Attributes
    ----------
    time : numpy.ndarray
        Time [s].
    speed : numpy.ndarray
        Spin speed [rad/s].
    displacement : numpy.ndarray
        ``(T, ndof)`` [m, rad].
    pressures : dict
        Node -> ``(T, N)`` absolute chamber pressures [Pa] (``film=True``).
    voids : dict
        Node -> ``(T, N)`` void volumes [m^3] (``film=True``).
    number_dof : int
        Degrees of freedom per node [-].
    """

    time: np.ndarray
    speed: np.ndarray
    displacement: np.ndarray
    pressures: dict
    voids: dict
    number_dof: int

    def orbit_radius(self, node: int) -> np.ndarray:
        """``sqrt(x^2 + y^2)`` of a node [m].

        Parameters
        ----------
        node : int
            Rotor node [-].
        """
        i = self.number_dof * int(node)
        return np.hypot(self.displacement[:, i], self.displacement[:, i + 1])


def unbalance_runup(ndof: int, number_dof: int, node: int, unbalance: float, time, speed_start, speed_end):
    """Linear run-up from ``speed_start`` to ``speed_end`` [rad/s] and the unbalance force it gives.

    ``phi = w0 t + alpha t^2 / 2``, ``F_x = U (w^2 cos phi + alpha sin phi)``,
    ``F_y = U (w^2 sin phi - alpha cos phi)`` on the x, y degrees of freedom of ``node``
    (the force of a mass ``m`` at radius ``e``, ``U = m e``, spun up at the constant angular
    acceleration ``alpha``).

    Parameters
    ----------
    ndof : int
        Degrees of freedom of the rotor [-].
    number_dof : int
        Degrees of freedom per node [-].
    node : int
        Node of the unbalance [-].
    unbalance : float
        ``U = m e`` [kg m].
    time : array_like
        Time [s], starting at 0.
    speed_start, speed_end : float
        Spin speeds at the first and the last time [rad/s].

    Returns
    -------
    tuple
        ``(speed [rad/s], F [N] of shape (T, ndof))``.
    """
    t = np.asarray(time, dtype=float)
    if t.ndim != 1 or t.size < 2 or t[0] != 0.0:
        raise InputError("time must be a 1-D array starting at 0 s")
    alpha = (speed_end - speed_start) / t[-1]
    w = speed_start + alpha * t
    phi = speed_start * t + 0.5 * alpha * t**2
    F = np.zeros((t.size, int(ndof)))
    i = int(number_dof) * int(node)
    F[:, i] = unbalance * (w**2 * np.cos(phi) + alpha * np.sin(phi))
    F[:, i + 1] = unbalance * (w**2 * np.sin(phi) - alpha * np.cos(phi))
    return w, F


def rotor_time_response(
    rotor, dampers: dict, speed, F, time, *, film: bool = True, gamma: float = 0.6, beta: float = 0.3025, progress=None
):
    """Integrate a ROSS rotor with leaf spring dampers at given nodes (module docstring).

    Parameters
    ----------
    rotor : ross.Rotor
        The rotor, with a zero-coefficient bearing element at every damper node.
    dampers : dict
        ``{node: LSDModel}`` (or ``{node: (LSDModel, count)}`` for ``count`` identical dampers
        on one node).
    speed : float or array_like
        Spin speed [rad/s], constant or one value per time.
    F : numpy.ndarray
        External force, ``(T, ndof)`` [N].
    time : array_like
        Uniform time steps [s].
    film : bool
        Oil from the film networks (inertia, cavitation); ``False``: the linearised damper.
    gamma, beta : float
        Newmark parameters [-]; the default ``gamma = 0.6``, ``beta = (gamma + 1/2)^2 / 4`` damps
        the step-to-step oscillation that the oil's inertia (a pressure proportional to the
        acceleration) would otherwise carry (Hughes, *The Finite Element Method*, 1987,
        Sec. 9.1); its numerical damping ratio ``(gamma - 1/2) omega dt / 2`` is 1e-3 at
        200 rad/s and 0.1 ms.  ``gamma = 1/2, beta = 1/4`` is ROSS's average acceleration.
    progress : callable, optional
        Called as ``progress(fraction)`` every 1 % of the steps.

    Returns
    -------
    RotorTimeResponse
    """
    t = np.asarray(time, dtype=float)
    if t.ndim != 1 or t.size < 2:
        raise InputError("time must be a 1-D array of at least 2 samples")
    dt = float(t[1] - t[0])
    if not (dt > 0 and np.all(np.abs(np.diff(t) - dt) <= 1e-6 * dt)):
        raise InputError("rotor_time_response needs uniform, increasing time steps")
    ndof, per_node = int(rotor.ndof), int(rotor.number_dof)
    F = np.asarray(F, dtype=float)
    if F.shape != (t.size, ndof):
        raise InputError(f"F has shape {F.shape}; expected {(t.size, ndof)} (time x rotor.ndof)")
    w = np.broadcast_to(np.asarray(speed, dtype=float), t.shape).copy()
    accel = np.gradient(w, t)

    M = np.array(rotor.M(), dtype=float)
    C0 = np.array(rotor.C(float(np.mean(w))), dtype=float)
    K0 = np.array(rotor.K(float(np.mean(w))), dtype=float)
    G = np.array(rotor.G(), dtype=float)
    Ksdt = np.array(rotor.Ksdt(), dtype=float)

    w_ref = float(np.mean(w))
    for brg in getattr(rotor, "bearing_elements", []):
        if int(getattr(brg, "n", -1)) in {int(k) for k in dampers}:
            coeffs = [np.abs(np.asarray(f(w_ref), dtype=float)).max() for f in (brg.K, brg.C, brg.M)]
            if max(coeffs) > 0:
                raise InputError(
                    f"the rotor's bearing element at damper node {brg.n} has non-zero coefficients: build it "
                    "with zeros (ross.BearingElement(n, kxx=0, cxx=0)); rotor_time_response adds the damper"
                )
    items = []
    for node, spec in dampers.items():
        model, count = spec if isinstance(spec, tuple) else (spec, 1)
        i = per_node * int(node)
        if not (0 <= i + 1 < ndof):
            raise InputError(f"damper node {node!r} is not a node of the rotor ({ndof // per_node} nodes)")
        P = np.zeros((2, ndof))
        P[0, i], P[1, i + 1] = 1.0, 1.0
        K0 += count * P.T @ model.stiffness_matrix @ P
        if not film:
            C0 += count * P.T @ model.viscous_damping @ P
            M += count * P.T @ model.added_mass @ P
        items.append(
            dict(node=int(node), model=model, count=float(count), P=P, net=film_network(model) if film else None)
        )

    Ms, Cs, Ks = 0.5 * (M + M.T), 0.5 * (C0 + C0.T), 0.5 * (K0 + K0.T)
    Cr, Kr, Mr = C0 - Cs, K0 - Ks, M - Ms  # explicit remainders (cross-coupling)
    g, b = float(gamma), float(beta)
    if not (g >= 0.5 and b >= 0.25 * (g + 0.5) ** 2 - 1e-12):
        raise InputError(f"gamma = {gamma!r}, beta = {beta!r}: need gamma >= 1/2 and beta >= (gamma + 1/2)^2 / 4")
    # Newmark in velocity form: a1 = (v1 - v0 - dt (1 - g) a0) / (g dt), x1 = x0 + dt v0 + dt^2 ((1/2 - b) a0 + b a1)
    S = Ms / (g * dt) + Cs + Ks * (b * dt / g)
    S_f = cho_factor(S)

    x = np.zeros(ndof)
    v = np.zeros(ndof)
    X = np.zeros((t.size, ndof))
    pressures = {it["node"]: np.zeros((t.size, it["model"].params.packs)) for it in items} if film else {}
    voids = {it["node"]: np.zeros((t.size, it["model"].params.packs)) for it in items} if film else {}
    for it in items:
        if film:
            it["net"].reset()
            pressures[it["node"]][0] = it["net"].supply_pressure
    # the oil coupling: rows of B P for every damper, stacked
    if film:
        BP = np.vstack([it["net"].volume_matrix @ it["P"] for it in items])
        scale = np.concatenate([np.full(it["net"].chambers, it["count"]) for it in items])
        coupling = dt * (scale[:, None] * (BP @ cho_solve(S_f, BP.T)) * scale[None, :])
        sizes = [it["net"].chambers for it in items]
        offsets = np.cumsum([0] + sizes)
    a = np.linalg.solve(M, F[0])  # at rest: M a0 = F(0)
    every = max(1, (t.size - 1) // 100)
    for k in range(t.size - 1):
        # explicit forces at the start of the step
        E = -(w[k] * G + Cr) @ v - (Kr + accel[k] * Ksdt) @ x - Mr @ a
        for it in items:
            m, P, p = it["model"], it["P"], it["model"].params
            xn, vn = P @ x, P @ v
            fx, fy, loads = pack_spring_forces(m.angles, m.pack_stiffness, p.preload, xn[:1], xn[1:])
            lift = np.array([fx[0], fy[0]]) - m.stiffness_matrix @ xn
            lx, ly = interleaf_friction_forces(m.angles, loads, p.leaf_friction, m.slip_factor, vn[:1], vn[1:])
            ox, oy = oring_friction_force(p.oring_friction, p.oring_normal_force, vn[:1], vn[1:])
            E -= it["count"] * P.T @ (lift + np.array([lx[0] + ox[0], ly[0] + oy[0]]))
        c1 = -(v + dt * (1.0 - g) * a) / (g * dt)  # a1 = v1 / (g dt) + c1
        c2 = x + dt * v + dt * dt * ((0.5 - b) * a + b * c1)  # x1 = (b dt / g) v1 + c2
        rhs = F[k + 1] + E - Ms @ c1 - Ks @ c2
        v_free = cho_solve(S_f, rhs)
        if film:
            Mc = coupling.copy()
            rs, cav, terms = [], [], []
            for j, it in enumerate(items):
                net = it["net"]
                Mf, base, beta, h = net.step_terms(dt)
                sl = slice(offsets[j], offsets[j + 1])
                Mc[sl, sl] += it["count"] * Mf
                rs.append(it["count"] * (base - dt * net.volume_matrix @ (it["P"] @ v_free)))
                cav.append(np.full(net.chambers, net.cavitation_pressure))
                terms.append((beta, h))
            r_shift = np.concatenate(rs)  # already for u = p - p_cav (FilmNetwork.step_terms)
            pc = np.concatenate(cav)
            L = np.linalg.cholesky(Mc)
            u, _ = nnls(L.T, -np.linalg.solve(L, r_shift))
            pall = pc + u
            wvec = Mc @ u + r_shift
            force = np.zeros(ndof)
            for j, it in enumerate(items):
                sl = slice(offsets[j], offsets[j + 1])
                net = it["net"]
                net.commit(pall[sl], wvec[sl] / it["count"], *terms[j])
                force -= it["count"] * it["P"].T @ (pall[sl] @ net.volume_matrix)
                pressures[it["node"]][k + 1] = pall[sl]
                voids[it["node"]][k + 1] = net.void
            v_new = v_free + cho_solve(S_f, force)
        else:
            v_new = v_free
        a_new = v_new / (g * dt) + c1
        x = x + dt * v + dt * dt * ((0.5 - b) * a + b * a_new)
        v, a = v_new, a_new
        X[k + 1] = x
        if progress is not None and (k + 1) % every == 0:
            progress((k + 1) / (t.size - 1))
    return RotorTimeResponse(t, w, X, pressures, voids, per_node)
