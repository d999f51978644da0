"""Large-deflection (elastica) model of the CFCS flexure, beside the pseudo-rigid-body pin.

Geometry (issue 14 of springdyn, docs/cfcs.md): the flexure is a straight strip of length
``l`` at the slider end of the coupler, clamped to the slider with its tangent along the
slider axis (straight at the toggle).  The pseudo-rigid-body pin sits at the middle of the
strip, so the rigid part of the coupler, from the end of the strip to the crank pin, is
``a = r3 - l/2``, and at the toggle the clamp stands at ``r2 + r3 + l/2`` from the ground pin.
The slider deflection is measured as in the PRBM, ``x = r2 + r3 + l/2 - X_clamp``.

The crank is a two-force member (frictionless pins, quasi-static), so the load on the
coupler at the crank pin B is ``P (cos theta2, sin theta2)``, along the crank; its moment
about a point r of the strip is ``M = P (y cos theta2 - x sin theta2)`` (the line of action
passes through the ground pin).  The inextensible elastica (Euler-Bernoulli, no shear, no
axial strain) of the strip is ``EI dphi/ds = M(s)`` with ``dx/ds = cos phi``,
``dy/ds = sin phi``, ``phi(0) = pi`` at the clamp.  The crank pin must close the loop::

    x(l) + a cos phi(l) = r2 cos theta2,    y(l) + a sin phi(l) = r2 sin theta2

two equations for the two unknowns ``(P, theta2)`` at a given deflection.  The slider force
is ``F = P cos theta2`` (the guide takes the normal component and the clamp moment).

Two independent solvers:

- :func:`beam_force_curve`: shooting.  A fixed-step RK4 integration of the elastica and of
  its sensitivities to ``(P, theta2)`` (so Newton gets the exact Jacobian of the discrete
  map), continued along the stroke from the toggle with a secant predictor and step halving.
  At the toggle the straight strip is an equilibrium for every P: the force as
  ``x -> 0+`` is the bifurcation load where the linearised loop-closure residual vanishes
  (:func:`beam_force_at_toggle`).
- :func:`chain_equilibrium`: the strip as a chain of rigid links with torsional springs
  ``EI/h`` (Hencky's bar chain, second order in ``h``), the minimum of its elastic energy
  under the loop-closure constraint by Newton on the Lagrange conditions; the multipliers
  are the force at the crank pin.

With ``l/r3 -> 0`` the strip's curvature concentrates and the model tends to the PRBM
(a pin with ``K3 = EI/l`` at its middle).
"""

from __future__ import annotations

import math

import numpy as np

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError, SolverError
from ..numerics.jit import kernel
from .kinematics import spring_angle, theta2_from_deflection
from .statics import static_force

__all__ = [
    "beam_force_at_toggle",
    "beam_force_curve",
    "chain_equilibrium",
    "force_band",
    "band_error_over_range_ends",
    "prbm_error",
    "prbm_error_map",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    length : float
        Strip length l [m].
    ei : float
        Bending stiffness of the strip [N*m^2].
    deflection : array_like
        Increasing slider deflections [m].
    steps : int
        RK4 steps along the strip [-].
    r2, r3 : float
        Crank and coupler lengths [m].
    force_prbm : array_like
        PRBM static force at the deflections [N].
    force_beam : array_like
        Elastica force of the same strip at the deflections [N].
    """
)

#: RK4 steps along the strip in the shooting solver (a test checks 2x steps changes F by < 1e-9 F0).
SHOOTING_STEPS = 200


# -- shooting ------------------------------------------------------------------------------
@kernel
def _rhs(st, p, c2, s2, inv_ei):
    x, y, ph, xp, yp, pp, xt, yt, pt = st
    cp, sp = math.cos(ph), math.sin(ph)
    dist = y * c2 - x * s2
    out = np.empty(9)
    out[0] = cp
    out[1] = sp
    out[2] = p * dist * inv_ei
    out[3] = -sp * pp
    out[4] = cp * pp
    out[5] = (dist + p * (yp * c2 - xp * s2)) * inv_ei
    out[6] = -sp * pt
    out[7] = cp * pt
    out[8] = p * ((yt * c2 - xt * s2) - (y * s2 + x * c2)) * inv_ei
    return out


@kernel
def _shoot(p, theta2, x_clamp, length, rigid, r2, ei, steps):
    """Residual of the loop closure, its Jacobian and the largest |curvature| [1/m]."""
    c2, s2 = math.cos(theta2), math.sin(theta2)
    inv_ei = 1.0 / ei
    st = np.zeros(9)
    st[0] = x_clamp
    st[2] = math.pi
    h = length / steps
    kmax = abs(p * (st[1] * c2 - st[0] * s2)) * inv_ei
    for _ in range(steps):
        k1 = _rhs(st, p, c2, s2, inv_ei)
        k2 = _rhs(st + 0.5 * h * k1, p, c2, s2, inv_ei)
        k3 = _rhs(st + 0.5 * h * k2, p, c2, s2, inv_ei)
        k4 = _rhs(st + h * k3, p, c2, s2, inv_ei)
        st = st + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        k = abs(p * (st[1] * c2 - st[0] * s2)) * inv_ei
        if k > kmax:
            kmax = k
    x, y, ph, xp, yp, pp, xt, yt, pt = st
    cp, sp = math.cos(ph), math.sin(ph)
    res = np.array([x + rigid * cp - r2 * c2, y + rigid * sp - r2 * s2])
    jac = np.array(
        [[xp - rigid * sp * pp, xt - rigid * sp * pt + r2 * s2], [yp + rigid * cp * pp, yt + rigid * cp * pt - r2 * c2]]
    )
    return res, jac, ph, kmax


def _geometry(r2, r3, length):
    if not (length > 0 and length < 2.0 * r3):
        raise InputError(
            f"pivot_length = {length * 1e3:.6g} mm must be positive and shorter than twice the coupler "
            f"length r3 = {r3 * 1e3:.6g} mm (the rigid part of the coupler is r3 - l/2)"
        )
    return r3 - 0.5 * length, r2 + r3 + 0.5 * length


@_DOCS.fill
def beam_force_at_toggle(r2, r3, length, ei, *, steps=SHOOTING_STEPS):
    """Slider force [N] of the elastica model as ``x -> 0+`` (the bifurcation load at the toggle).

    The straight strip at the toggle is an equilibrium for every P; the bent branch leaves it
    where the linearised residual ``d R_y / d theta2`` vanishes (secant iteration from the
    PRBM value ``K3 r2 / (r3 (r2 + r3))`` with ``K3 = EI/l``).

    Parameters
    ----------
    {r2_r3 length ei steps}
    """
    rigid, x_clamp = _geometry(r2, r3, length)

    def g(p):
        _, jac, _, _ = _shoot(p, 0.0, x_clamp, length, rigid, r2, ei, steps)
        return jac[1, 1]

    p0 = ei / length * r2 / (r3 * (r2 + r3))
    a, b = p0, 1.01 * p0
    ga, gb = g(a), g(b)
    for _ in range(60):
        if gb == ga:
            break
        c = b - gb * (b - a) / (gb - ga)
        a, ga, b, gb = b, gb, c, g(c)
        if abs(b - a) <= 1e-14 * abs(b):
            return float(b)
    if abs(gb) <= 1e-9 * abs(g(p0)) or abs(b - a) <= 1e-12 * abs(b):
        return float(b)
    raise SolverError("beam model: the bifurcation load at the toggle did not converge (secant iteration)")


def _newton(p, th, x_clamp, length, rigid, r2, ei, steps, scale):
    for _ in range(30):
        res, jac, ph, kmax = _shoot(p, th, x_clamp, length, rigid, r2, ei, steps)
        try:
            dp, dth = np.linalg.solve(jac, -res)
        except np.linalg.LinAlgError:
            return None
        if not (np.isfinite(dp) and np.isfinite(dth)) or abs(dth) > 0.2:
            return None
        p, th = p + dp, th + dth
        if abs(dp) <= 1e-13 * scale and abs(dth) <= 1e-13:
            res, _, ph, kmax = _shoot(p, th, x_clamp, length, rigid, r2, ei, steps)
            if np.max(np.abs(res)) <= 1e-12 * r2:
                return p, th, ph, kmax
    return None


@_DOCS.fill
def beam_force_curve(deflection, r2, r3, length, ei, *, steps=SHOOTING_STEPS):
    """Elastica solution along a stroke by shooting and continuation (see the module docstring).

    Parameters
    ----------
    deflection : array_like
        Slider deflections [m], increasing, from 0 (the toggle) or above.
    r2, r3 : float
        Crank and coupler lengths [m] (r3 to the PRBM pin at the middle of the strip).
    {length ei steps}

    Returns
    -------
    dict of arrays
        ``force`` slider force [N], ``theta2`` crank angle [rad], ``end_rotation`` rotation of
        the strip's end (and of the rigid coupler) from the slider axis [rad] (the PRBM's
        theta_K3), ``max_curvature`` largest |curvature| along the strip [1/m].

    Raises
    ------
    SolverError
        When the continuation cannot follow the branch (typically near the kinematic limit).
    """
    x = np.asarray(deflection, dtype=float)
    if x.ndim != 1 or x.size == 0 or np.any(np.diff(x) <= 0) or x[0] < 0:
        raise InputError("deflection must be an increasing array of deflections >= 0 [m]")
    rigid, x_top = _geometry(r2, r3, length)
    f0 = beam_force_at_toggle(r2, r3, length, ei, steps=steps)
    out = {k: np.empty(x.size) for k in ("force", "theta2", "end_rotation", "max_curvature")}
    hist = []  # (x, P, theta2) of solved points, for the secant predictor
    xs = x.copy()
    start = 0
    if xs[0] == 0.0:
        out["force"][0], out["theta2"][0], out["end_rotation"][0], out["max_curvature"][0] = f0, 0.0, 0.0, 0.0
        start = 1
    k3 = ei / length

    def predict(xq):
        if len(hist) >= 2:
            (xa, pa, ta), (xb, pb, tb) = hist[-2], hist[-1]
            w = (xq - xb) / (xb - xa)
            return pb + w * (pb - pa), tb + w * (tb - ta)
        th = float(theta2_from_deflection(xq, r2, r3))
        f = float(static_force(th, k3, r2, r3)) if not hist else hist[-1][1] * math.cos(hist[-1][2])
        if not hist:
            f = f * f0 / float(static_force(0.0, k3, r2, r3))
        return f / math.cos(th), th

    def solve_at(xq, depth=0):
        p_guess, th_guess = predict(xq)
        sol = _newton(p_guess, th_guess, x_top - xq, length, rigid, r2, ei, steps, f0)
        if sol is not None and sol[1] > 0:
            return sol
        if depth >= 12:
            return None
        prev = hist[-1][0] if hist else 0.0
        mid = 0.5 * (prev + xq)
        s = solve_at(mid, depth + 1)
        if s is None:
            return None
        hist.append((mid, s[0], s[1]))
        return solve_at(xq, depth + 1)

    for i in range(start, x.size):
        xq = xs[i]
        if not hist and xq > 0:
            # begin the branch close to the toggle, where the PRBM guess is within Newton's reach
            first = min(xq, 1e-4 * (r2 + r3))
            if first < xq:
                s = solve_at(first)
                if s is None:
                    raise SolverError(f"beam model: no elastica solution near the toggle (x = {first * 1e3:.3g} mm)")
                hist.append((first, s[0], s[1]))
        sol = solve_at(xq)
        if sol is None:
            raise SolverError(
                f"beam model: the continuation of the elastica lost the branch at x = {xq * 1e3:.4g} mm "
                "(beyond the strip's kinematic limit, or too close to it): reduce the stroke"
            )
        p, th, ph, kmax = sol
        hist.append((xq, p, th))
        out["force"][i] = p * math.cos(th)
        out["theta2"][i] = th
        out["end_rotation"][i] = math.pi - ph
        out["max_curvature"][i] = kmax
    return out


# -- discretised chain ---------------------------------------------------------------------
@_DOCS.fill
def chain_equilibrium(deflection, r2, r3, length, ei, *, links=200, guess=None):
    """Elastica by a discretised rigid-link chain: energy minimum under the loop closure.

    The strip is Hencky's bar chain: node angles ``phi_k`` at ``s_k = k h`` (``h = l/N``,
    ``phi_0 = pi`` at the clamp), each node carrying a rigid link of length h centred on it
    (h/2 at both ends), joint springs ``EI/h`` between neighbours; elastic energy
    ``E = sum EI/(2h) (phi_k - phi_(k-1))^2`` and the rigid coupler continuing the last link.
    Stationarity of ``E - lambda . (B(phi) - r2 e(theta2))`` is solved by Newton (dense,
    analytic Hessian); ``lambda`` is the load at the crank pin, so the slider force is
    ``lambda_x``.  The scheme is the trapezoidal rule of the elastica, error O(h^2):
    Richardson extrapolation of N and 2N links gives O(h^4).

    Parameters
    ----------
    deflection : float
        Slider deflection [m] (> 0).
    {r2_r3 length ei}
    links : int
        Number of links N [-].
    guess : dict, optional
        A previous result of this function (continuation); else the PRBM configuration.

    Returns
    -------
    dict
        ``force`` [N], ``theta2`` [rad], ``end_rotation`` [rad], ``phi`` (link angles) and
        ``lam`` (load at the crank pin) [N].
    """
    rigid, x_top = _geometry(r2, r3, length)
    n = int(links)
    h = length / n
    xc = x_top - deflection - 0.5 * h  # the half link at the clamp lies along the axis
    if guess is None:
        th = float(theta2_from_deflection(deflection, r2, r3))
        tk = float(spring_angle(th, r2, r3))
        s_mid = (np.arange(n) + 1.0) * h
        # PRBM-like start: the rotation builds up over the strip
        phi = np.pi - tk * np.clip(s_mid / length, 0.0, 1.0)
        f = float(static_force(th, ei / length, r2, r3))
        lam = np.array([f, f * math.tan(th)])
    else:
        phi, th, lam = guess["phi"].copy(), guess["theta2"], guess["lam"].copy()
    w = np.full(n, ei / h)
    lengths = np.full(n, h)
    lengths[-1] = 0.5 * h
    for _ in range(60):
        c, s = np.cos(phi), np.sin(phi)
        lev = lengths.copy()
        lev[-1] += rigid  # the rigid coupler continues the last link
        # energy gradient
        d = np.diff(phi)
        grad = np.zeros(n)
        grad[0] += w[0] * (phi[0] - np.pi)
        grad[:-1] -= w[1:] * d
        grad[1:] += w[1:] * d
        b = np.array([xc + np.sum(lev * c), np.sum(lev * s)])
        db = np.vstack([-lev * s, lev * c])  # dB/dphi_i
        e2 = np.array([math.cos(th), math.sin(th)])
        de2 = np.array([-math.sin(th), math.cos(th)])
        r_phi = grad - lam @ db
        r_th = r2 * (lam @ de2)
        r_c = b - r2 * e2
        res = np.concatenate([r_phi, [r_th], r_c])
        # Jacobian
        m = n + 3
        jac = np.zeros((m, m))
        hess = np.zeros((n, n))
        idx = np.arange(n)
        hess[idx, idx] += w * 0.0
        hess[0, 0] += w[0]
        for_k = np.arange(1, n)
        hess[for_k, for_k] += w[1:]
        hess[for_k - 1, for_k - 1] += w[1:]
        hess[for_k, for_k - 1] -= w[1:]
        hess[for_k - 1, for_k] -= w[1:]
        hess[idx, idx] += lam[0] * lev * c + lam[1] * lev * s  # -lam . d2B/dphi^2, d2B = -lev (c, s)
        jac[:n, :n] = hess
        jac[:n, n] = 0.0
        jac[:n, n + 1 :] = -db.T
        jac[n, n] = -r2 * (lam @ e2)
        jac[n, n + 1 :] = r2 * de2
        jac[n + 1 :, :n] = db
        jac[n + 1 :, n] = -r2 * de2
        step = np.linalg.solve(jac, -res)
        phi = phi + step[:n]
        th = th + step[n]
        lam = lam + step[n + 1 :]
        if np.max(np.abs(step[: n + 1])) < 1e-13 and np.max(np.abs(step[n + 1 :])) < 1e-12 * max(1.0, abs(lam[0])):
            return {
                "force": float(lam[0]),
                "theta2": float(th),
                "end_rotation": float(np.pi - phi[-1]),
                "phi": phi,
                "lam": lam,
            }
    raise SolverError(f"beam model (chain): Newton did not converge at x = {deflection * 1e3:.4g} mm")


# -- the PRBM's error against the elastica -----------------------------------------------------
@_DOCS.fill
def force_band(deflection, force):
    """Force band ``F_max - F_min`` [N] of a sampled force curve, its interior extrema refined.

    An extremum at an interior sample is replaced by the vertex of the parabola through it and
    its two neighbours (the curves are smooth), so the band converges as the square of the
    sample spacing to the third order instead of the first: 401 samples give the band of a
    99.7 % flat curve to 1e-6 of itself (a test halves and doubles the samples).

    Parameters
    ----------
    {deflection}
    force : array_like
        Force at those deflections [N].
    """
    x = np.asarray(deflection, dtype=float)
    f = np.asarray(force, dtype=float)

    def extreme(sign):
        g = sign * f
        i = int(np.argmax(g))
        best = float(g[i])
        h1, h2 = (x[i] - x[i - 1], x[i + 1] - x[i]) if 0 < i < x.size - 1 else (0.0, 0.0)
        if min(h1, h2) > 0.25 * max(h1, h2):  # an interior extremum between fairly even samples
            h = h1 + h2
            u = (x[i - 1 : i + 2] - x[i]) / h  # scaled abscissae: a well-conditioned fit
            coef = np.linalg.solve(np.vander(u, 3), g[i - 1 : i + 2])
            if coef[0] < 0:
                du = -coef[1] / (2.0 * coef[0])
                if abs(du) <= 1.0:
                    best = max(best, float(np.polyval(coef, du)))
        return sign * best

    return extreme(1.0) - extreme(-1.0)


@_DOCS.fill
def prbm_error(deflection, force_prbm, force_beam, force_ref):
    """Band error and force error of the pseudo-rigid-body model against the elastica over a stroke.

    ``band_error = (B_prbm - B_beam) / B_beam`` with ``B = F_max - F_min`` over the samples
    (:func:`force_band`), positive when the PRBM promises a wider band than the strip gives;
    ``force_error = max |F_prbm - F_beam| / F_ref``.  springdyn's definitions (issue 30); the
    elastica is the reference.

    Parameters
    ----------
    {deflection force_prbm force_beam}
    force_ref : float
        Reference force F0 [N] of the force error (the elastica's force at the toggle).

    Returns
    -------
    dict
        ``band_prbm``, ``band_beam`` [N], ``band_error`` (NaN when the elastica's band is zero:
        a single deflection), ``force_error`` [-].
    """
    bp = force_band(deflection, force_prbm)
    bb = force_band(deflection, force_beam)
    diff = np.max(np.abs(np.asarray(force_prbm, dtype=float) - np.asarray(force_beam, dtype=float)))
    return {
        "band_prbm": bp,
        "band_beam": bb,
        "band_error": (bp - bb) / bb if bb > 0 else float("nan"),
        "force_error": float(diff) / float(force_ref),
    }


@_DOCS.fill
def band_error_over_range_ends(deflection, force_prbm, force_beam, ends):
    """Band error ``(B_prbm - B_beam) / B_beam`` [-] of the ranges from the first deflection to each end.

    The band error (:func:`prbm_error`) compares two differences of extremes, so it depends on where
    the range ends: the flatter the elastica's force near the end, the more (issue 40: Table 1's
    +18.6 % over 0-72 mm is +23.6 % over 0-71.5 mm).  The force error, a largest difference,
    only grows with the range (0.940 % and 0.965 % of F0 there).

    Parameters
    ----------
    {deflection force_prbm force_beam}
    ends : array_like
        Ends of the ranges, samples of ``deflection`` [m].

    Returns
    -------
    numpy.ndarray
        The band error of each range [-] (NaN where the elastica's band is zero).
    """
    x = np.asarray(deflection, dtype=float)
    fp, fb = np.asarray(force_prbm, dtype=float), np.asarray(force_beam, dtype=float)
    out = []
    for e in np.atleast_1d(np.asarray(ends, dtype=float)):
        k = x <= e * (1.0 + 1e-12)
        out.append(prbm_error(x[k], fp[k], fb[k], 1.0)["band_error"] if np.count_nonzero(k) > 1 else np.nan)
    return np.array(out, dtype=float)


def prbm_error_map(ratio, length_ratios, stroke_fractions, *, start_fraction=0.0, n=401):
    """PRBM band and force errors against the elastica vs flexure length and stroke (dimensionless).

    With every length scaled by ``r2 + r3`` and forces by ``EI / (l (r2 + r3))`` the errors
    depend only on ``r2/r3``, ``l/r3``, the stroke fraction and where the stroke starts (the
    PRBM's ``K3 = EI/l``; the elastica of the same strip with the same modulus).  Each stroke
    runs over ``[s0, s0 + f] (r2 + r3)``.

    Parameters
    ----------
    ratio : float
        Crank-to-coupler length ratio r2/r3 [-].
    length_ratios : array_like
        Strip lengths l/r3 [-].
    stroke_fractions : array_like
        Strokes as fractions of r2 + r3 [-].
    start_fraction : float
        Start of the stroke s0 as a fraction of r2 + r3 [-] (0: the toggle).
    n : int
        Samples per stroke [-].

    Returns
    -------
    dict of 2-D arrays (length ratio x stroke fraction)
        ``band_error`` and ``force_error`` [-]; NaN where the elastica's continuation fails
        (beyond the strip's reach).
    """
    lr = np.atleast_1d(np.asarray(length_ratios, dtype=float))
    sf = np.atleast_1d(np.asarray(stroke_fractions, dtype=float))
    r3 = 1.0 / (1.0 + ratio)
    r2 = ratio * r3
    band = np.full((lr.size, sf.size), np.nan)
    force = np.full((lr.size, sf.size), np.nan)
    for i, q in enumerate(lr):
        length = q * r3
        k3 = 1.0 / length  # EI = 1
        for j, f in enumerate(sf):
            x = np.linspace(start_fraction, start_fraction + f, n)
            if start_fraction > 0:
                x = np.concatenate([[0.0], x])
            try:
                fb = beam_force_curve(x, r2, r3, length, 1.0)["force"]
            except SolverError:
                continue
            fp = static_force(theta2_from_deflection(x, r2, r3), k3, r2, r3)
            e = prbm_error(x[-n:], fp[-n:], fb[-n:], fb[0])
            band[i, j], force[i, j] = e["band_error"], e["force_error"]
    return {"band_error": band, "force_error": force}
