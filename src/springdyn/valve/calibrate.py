"""The spring against its drawing's load points, and a fit of the model to them.

:func:`load_point_check` gives the model's static force at each load point of the
``[spring]`` table (``load_points``) with its deviation and whether it lies within the
tolerance; :func:`calibrate` fits the shear modulus or the active coils so that the model
meets the load points in the least-squares sense (each deviation weighted by its
tolerance), and says how well.
"""

from __future__ import annotations

import numpy as np

from ..core.errors import InputError

__all__ = ["load_point_check", "calibrate", "FIT_PARAMETERS"]

#: The cost of a value the spring's checks refuse (finite, so the minimiser's arithmetic stays finite).
REFUSED = 1e30
#: What :func:`calibrate` can fit, with the search range as factors of the given value.
FIT_PARAMETERS = {"shear_modulus": (0.5, 2.0), "active_coils": (0.5, 2.0)}


def load_point_check(spring) -> list[dict]:
    """The model's static force at each load point of the drawing.

    Parameters
    ----------
    spring : ValveSpring
        With ``load_points``.

    Returns
    -------
    list of dict
        ``length_m``, ``force_N`` (the drawing's), ``model_force_N``, ``deviation_N``
        (model minus drawing), ``deviation_percent``, ``tolerance_N`` (None: not given) and
        ``within_tolerance`` (None without a tolerance).
    """
    rows = []
    model = spring.spring_model
    for p in spring.load_point_table:
        if not model.min_length <= p["length"] <= spring.free_length:
            raise InputError(
                f"load point at {p['length'] * 1e3:.4g} mm lies outside the spring's range "
                f"({model.min_length * 1e3:.4g} mm to the free length {spring.free_length * 1e3:.4g} mm)"
            )
        f = float(model.static_force(p["length"]))
        dev = f - p["force"]
        tol = p["tolerance"]
        rows.append(
            dict(
                length_m=p["length"],
                force_N=p["force"],
                model_force_N=f,
                deviation_N=dev,
                deviation_percent=100.0 * dev / p["force"],
                tolerance_N=tol,
                within_tolerance=None if tol is None else bool(abs(dev) <= tol),
            )
        )
    return rows


def _weighted_residuals(spring) -> np.ndarray:
    """Deviations over their tolerances (1 % of the force where none is given) [-]."""
    return np.array([r["deviation_N"] / (r["tolerance_N"] or 0.01 * r["force_N"]) for r in load_point_check(spring)])


def _with(spring, name: str, value: float):
    if name == "shear_modulus":
        return spring.replace(shear_modulus=value)
    # active coils: the high-pitch coils carry the change (dead and low-pitch coils as drawn)
    return spring.replace(high_pitch_coils=value - spring.low_pitch_coils + 2 * spring.dead_coils)


def calibrate(spring, fit: str = "shear_modulus") -> dict:
    """Fit the shear modulus or the active coils to the drawing's load points.

    Minimises the sum of squared deviations over their tolerances (1 % of the force where
    none is given) over the parameter, between half and twice its given value (bounded
    scalar minimisation, to 1e-10 relative).

    Parameters
    ----------
    spring : ValveSpring
        With at least one load point.
    fit : {"shear_modulus", "active_coils"}
        The parameter to fit [-].

    Returns
    -------
    dict
        ``parameter``, ``before`` and ``after`` (its value: [Pa] or [-]), ``spring`` (the
        calibrated :class:`ValveSpring`), ``load_points_before`` and ``load_points_after``
        (:func:`load_point_check`), ``rms_weighted_residual`` (after) [-].
    """
    from scipy.optimize import minimize_scalar

    if fit not in FIT_PARAMETERS:
        raise InputError(f"fit = {fit!r}: calibrate fits one of {', '.join(FIT_PARAMETERS)}")
    if not spring.load_point_table:
        raise InputError(
            'calibrate needs load points in the [spring] table: load_points = [{ length = "38 mm", force = '
            '"250 N", tolerance = "5 %" }, ...]'
        )
    before = spring.shear_modulus if fit == "shear_modulus" else spring.active_coils
    lo, hi = (f * before for f in FIT_PARAMETERS[fit])

    def cost(value):
        try:
            return float(np.sum(_weighted_residuals(_with(spring, fit, value)) ** 2))
        except InputError:  # a value the spring's checks refuse (e.g. a load point beyond solid)
            return REFUSED

    res = minimize_scalar(cost, bounds=(lo, hi), method="bounded", options=dict(xatol=1e-10 * before))
    if not res.fun < REFUSED:
        raise InputError(f"calibrate: no {fit} between {lo:.4g} and {hi:.4g} meets the load points")
    after = float(res.x)
    fitted = _with(spring, fit, after)
    r = _weighted_residuals(fitted)
    return dict(
        parameter=fit,
        before=float(before),
        after=after,
        spring=fitted,
        load_points_before=load_point_check(spring),
        load_points_after=load_point_check(fitted),
        rms_weighted_residual=float(np.sqrt(np.mean(r**2))),
    )
