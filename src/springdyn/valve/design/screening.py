"""The response surface that screens a tolerance study's variants (issue 42): which variants
must be simulated and which the surface decides.

A screened study (``tolerance_study(..., screen=True)``) simulates a designed part of its
sample, fits each dynamic figure with a full quadratic response surface in the toleranced
parameters ([BoxDraper2007] of docs/references.md, ch. 3: the second-order model) and
simulates only the variants the surface cannot judge.  This module holds the arithmetic on
arrays; :mod:`.tolerances` runs the variants.

- :func:`quadratic_terms` -- the second-order model's columns ``1, z_i, z_i z_j``;
- :func:`fit_surface` -- least squares on standardised parameters, with every fitted point's
  leave-one-out residual (the PRESS residual ``e_i / (1 - h_ii)``, [Myers2016] sec. 2.7);
- :func:`inside_box` -- the variants within the fitted variants' range in every parameter
  (the surface is not extrapolated: a variant outside is simulated);
- :func:`screen_band` -- how far a prediction may be from the simulation, from the largest
  leave-one-out and held-out errors;
- :func:`undecided` -- the variants whose verdict the band leaves open: the rule's verdict
  at the band's two ends differs;
- :func:`screen_figure` -- one figure's surface and band, where some variants sit at the bound
  the figure is censored at (a float speed above the speed range, no coil clash).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = [
    "quadratic_terms",
    "term_count",
    "Surface",
    "fit_surface",
    "inside_box",
    "screen_band",
    "undecided",
    "screen_figure",
    "FigureScreen",
    "SAFETY",
    "FITTED_PER_TERM",
]

#: Fitted variants per term of the surface [-]: twice as many as the surface has terms keeps
#: every leave-one-out residual defined (each point's leverage ``h_ii`` well below 1).
FITTED_PER_TERM = 2
#: The band over the largest error seen [-]: a new variant's error exceeds the largest of
#: ``n`` exchangeable errors with probability ``1 / (n + 1)`` (order statistics); the factor 2
#: is the margin beyond it (the study's comparison with simulating every variant is the check:
#: tests/valve/design/test_screening.py).
SAFETY = 2.0


def term_count(parameters: int) -> int:
    """Terms of the full quadratic surface in ``parameters`` variables, ``(p + 1)(p + 2) / 2`` [-].

    Parameters
    ----------
    parameters : int
        Toleranced parameters [-].
    """
    return (parameters + 1) * (parameters + 2) // 2


def quadratic_terms(z: np.ndarray) -> np.ndarray:
    """The second-order model's design matrix: ``1``, every ``z_i`` and every ``z_i z_j``
    (``i <= j``) ([BoxDraper2007] ch. 3).

    Parameters
    ----------
    z : ndarray
        Standardised parameters, shape (n, p) [-].

    Returns
    -------
    ndarray
        Shape (n, :func:`term_count` (p)) [-].
    """
    z = np.atleast_2d(np.asarray(z, dtype=float))
    n, p = z.shape
    cols = [np.ones(n)] + [z[:, i] for i in range(p)]
    cols += [z[:, i] * z[:, j] for i in range(p) for j in range(i, p)]
    return np.column_stack(cols)


@dataclass(frozen=True)
class Surface:
    """A fitted quadratic response surface of one figure (:func:`fit_surface`)."""

    centre: np.ndarray  #: the fitted parameters' means [SI]
    scale: np.ndarray  #: their standard deviations [SI]
    coefficients: np.ndarray  #: of :func:`quadratic_terms` [the figure's unit]
    loo_residuals: np.ndarray  #: every fitted point's leave-one-out residual [the figure's unit]

    def predict(self, x: np.ndarray) -> np.ndarray:
        """The figure at the parameters ``x`` [the figure's unit].

        Parameters
        ----------
        x : ndarray
            Variants' parameters, shape (n, p) [SI].
        """
        return quadratic_terms((np.atleast_2d(x) - self.centre) / self.scale) @ self.coefficients


def fit_surface(x: np.ndarray, y: np.ndarray) -> Surface:
    """Least-squares quadratic surface of ``y`` over the parameters ``x``, standardised by
    their own mean and standard deviation, with the leave-one-out (PRESS) residuals
    ``e_i / (1 - h_ii)``, ``h`` the hat matrix's diagonal from the thin QR factor
    ([Myers2016] sec. 2.7).

    Parameters
    ----------
    x : ndarray
        Fitted parameters, shape (n, p) [SI]; ``n`` at least :func:`term_count` (p) + 1.
    y : ndarray
        The figure at them, shape (n,) [its unit].
    """
    x = np.atleast_2d(np.asarray(x, dtype=float))
    y = np.asarray(y, dtype=float)
    centre = x.mean(axis=0)
    scale = x.std(axis=0)
    scale = np.where(scale > 0.0, scale, 1.0)
    a = quadratic_terms((x - centre) / scale)
    if a.shape[0] <= a.shape[1]:
        raise ValueError(f"{a.shape[0]} points cannot fit and check a surface of {a.shape[1]} terms")
    q, r = np.linalg.qr(a)
    coef = np.linalg.lstsq(r, q.T @ y, rcond=None)[0]
    lev = np.minimum(np.sum(q * q, axis=1), 1.0 - 1e-12)
    return Surface(centre, scale, coef, (y - a @ coef) / (1.0 - lev))


def inside_box(x: np.ndarray, fitted: np.ndarray) -> np.ndarray:
    """Whether each variant lies within the fitted variants' range in every parameter, widened
    by one ``n``-th of it (the gap a sample of ``n`` leaves at each end of a uniform band).

    Parameters
    ----------
    x : ndarray
        Variants, shape (m, p) [SI].
    fitted : ndarray
        The fitted variants, shape (n, p) [SI].
    """
    lo, hi = fitted.min(axis=0), fitted.max(axis=0)
    pad = (hi - lo) / fitted.shape[0]
    return np.all((x >= lo - pad) & (x <= hi + pad), axis=1)


def screen_band(loo_residuals: np.ndarray, holdout_errors: np.ndarray, quantum: float = 0.0) -> float:
    """How far a figure's prediction may lie from its simulation: :data:`SAFETY` times the
    largest leave-one-out residual or held-out error, plus the figure's own resolution [its unit].

    Parameters
    ----------
    loo_residuals : ndarray
        The fitted variants' leave-one-out residuals [its unit].
    holdout_errors : ndarray
        Prediction minus simulation at variants not fitted [its unit].
    quantum : float
        The figure's resolution (a float speed's final bracket, a clash onset's speed step) [its unit].
    """
    seen = np.concatenate([np.abs(np.ravel(loo_residuals)), np.abs(np.ravel(holdout_errors))])
    return float(SAFETY * (seen.max() if seen.size else np.inf) + quantum)


def undecided(passes, prediction: np.ndarray, band: float) -> np.ndarray:
    """The variants whose verdict the band leaves open: ``passes`` (a monotone rule on the
    figure, vectorised) differs between ``prediction - band`` and ``prediction + band``.

    Parameters
    ----------
    passes : callable
        ``passes(values) -> bool array``: the criterion's rule on the figure.
    prediction : ndarray
        The surface's figures [its unit].
    band : float
        :func:`screen_band` [its unit].
    """
    if not np.isfinite(band):
        return np.ones(np.shape(prediction), bool)
    return np.asarray(passes(prediction - band)) != np.asarray(passes(prediction + band))


@dataclass(frozen=True)
class FigureScreen:
    """One figure's screen (:func:`screen_figure`): how it is predicted, its band and its surface."""

    how: str  #: "quadratic surface", "at its bound" or "not predicted: ..."
    band: float  #: :func:`screen_band` (0 at its bound, inf not predicted) [the figure's unit]
    surface: Surface | None = None
    bound: float | None = None  #: the value the figure is censored at [the figure's unit]

    def predict(self, x: np.ndarray) -> np.ndarray:
        """The figure at the parameters ``x``, not yet held to its bound [the figure's unit].

        Parameters
        ----------
        x : ndarray
            Variants' parameters, shape (n, p) [SI].
        """
        n = np.atleast_2d(x).shape[0]
        if self.surface is not None:
            return self.surface.predict(x)
        return np.full(n, np.nan if self.bound is None or not np.isfinite(self.band) else float(self.bound))


def screen_figure(
    x_fit: np.ndarray,
    y_fit: np.ndarray,
    x_hold: np.ndarray,
    y_hold: np.ndarray,
    bound: float | None = None,
    upper: bool = True,
    quantum: float = 0.0,
) -> FigureScreen:
    """One figure's surface and band from the fitted and the held-out variants.

    A figure censored at ``bound`` (a float speed above the range is the range's top,
    ``upper``; no coil clash is a severity of 0, not ``upper``) is known at a variant at its
    bound only to lie beyond it: the surface is fitted on the variants off the bound, and at
    every variant at the bound its prediction's shortfall of the bound counts as an error
    beside the leave-one-out residuals and the held-out errors (a censored observation's
    residual, [Tobin1958]).  No variant off the bound: the figure stays at it within the
    fitted variants' box (band 0).  Too few off it to fit the surface and check it: not
    predicted (band inf, every variant simulated).

    Parameters
    ----------
    x_fit, x_hold : ndarray
        The fitted and held-out variants' parameters, shapes (n, p) and (m, p) [SI].
    y_fit, y_hold : ndarray
        Their figures [its unit].
    bound : float, optional
        The value the figure is censored at [its unit].
    upper : bool
        The bound is an upper one (the figure's true value lies above it).
    quantum : float
        The figure's resolution [its unit] (:func:`screen_band`).
    """
    x_fit, x_hold = np.atleast_2d(x_fit), np.atleast_2d(x_hold)
    at_f = np.zeros(y_fit.shape, bool) if bound is None else y_fit == bound
    at_h = np.zeros(y_hold.shape, bool) if bound is None else y_hold == bound
    if bound is not None and at_f.all() and at_h.all():
        return FigureScreen("at its bound", 0.0, None, float(bound))
    terms = term_count(x_fit.shape[1])
    if (~at_f).sum() <= terms + 1:
        return FigureScreen(f"not predicted: {int((~at_f).sum())} fitted variants off its bound", np.inf, None, bound)
    surface = fit_surface(x_fit[~at_f], y_fit[~at_f])
    ph = surface.predict(x_hold)
    errors = [ph[~at_h] - y_hold[~at_h]]
    if bound is not None:  # at the bound: how far the prediction falls short of it
        short = (lambda p: np.maximum(bound - p, 0.0)) if upper else (lambda p: np.maximum(p - bound, 0.0))
        errors += [short(ph[at_h]), short(surface.predict(x_fit[at_f]))]
    band = screen_band(surface.loo_residuals, np.concatenate(errors), quantum)
    how = "quadratic surface" + (
        f" ({int(at_f.sum() + at_h.sum())} variants at its bound)" if at_f.any() or at_h.any() else ""
    )
    return FigureScreen(how, band, surface, bound)
