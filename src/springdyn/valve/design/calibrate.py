"""The spring against its drawing's load points, and a fit of the model to them.

:func:`load_point_check` gives the model's static force at each load point of the
``[spring]`` table (``load_points``) with its deviation and whether it lies within the
tolerance; :func:`calibrate` fits the shear modulus or the active coils so that the model
meets the load points in the least-squares sense (each deviation weighted by its
tolerance), and says how well (:func:`load_point_lines`), and which ``[spring]`` keys a
calibrated definition writes (:func:`calibrated_keys`); :func:`calibrate_trace` fits the damping
and the coils' contact stiffness to a measured retainer-force trace.
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.optimize import least_squares, minimize_scalar

from ...core.errors import InputError
from ...core.io import read_csv_columns
from ..run.simulation import simulate
from ..spring.materials import MATERIALS

__all__ = [
    "load_point_check",
    "calibrate",
    "calibrate_trace",
    "read_force_trace",
    "check_force_trace",
    "calibrated_keys",
    "load_point_lines",
    "FIT_PARAMETERS",
    "TRACE_PARAMETERS",
]

#: The cost of a value the spring's checks refuse (finite, so the minimiser's arithmetic stays finite).
REFUSED = 1e30
#: What :func:`calibrate` can fit, with the search range as factors of the given value.
FIT_PARAMETERS = {"shear_modulus": (0.5, 2.0), "active_coils": (0.5, 2.0)}
#: How far a fitted shear modulus may leave the named wires' (:data:`springdyn.valve.spring.materials.MATERIALS`,
#: 79.5-81.5 GPa) before the fit says so [-]: EN 13906-1's values hold to a few per cent; a larger
#: correction points at the geometry (coils, diameter) or the load points, not at the steel.
PLAUSIBLE_SHEAR_MODULUS_MARGIN = 0.05


def load_point_check(spring) -> list[dict]:
    """The model's static force at each load point of the drawing
    (:meth:`springdyn.valve.spring.chains.SpringModel.load_point_check`).

    Parameters
    ----------
    spring : ValveSpring
        With ``load_points``.
    """
    return spring.spring_model.load_point_check()


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
        (:func:`load_point_check`), ``rms_weighted_residual`` (after) [-], ``notes`` (a
        fitted shear modulus outside the spring wires' plausible range, also warned).
    """
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
    notes = []
    if fit == "shear_modulus":
        g = [m.shear_modulus for m in MATERIALS.values()]
        lo_g, hi_g = min(g) * (1 - PLAUSIBLE_SHEAR_MODULUS_MARGIN), max(g) * (1 + PLAUSIBLE_SHEAR_MODULUS_MARGIN)
        if not lo_g <= after <= hi_g:
            notes.append(
                f"the fitted shear modulus {after / 1e9:.4g} GPa lies outside {lo_g / 1e9:.4g}-{hi_g / 1e9:.4g} GPa "
                f"(the spring wires' {min(g) / 1e9:g}-{max(g) / 1e9:g} GPa, EN 13906-1, +-"
                f"{PLAUSIBLE_SHEAR_MODULUS_MARGIN:.0%}): no steel is that {'stiff' if after > hi_g else 'soft'}; "
                "check the coils, the diameters and the load points, or fit active_coils"
            )
            warnings.warn(notes[-1], stacklevel=2)
    return dict(
        parameter=fit,
        before=float(before),
        after=after,
        spring=fitted,
        load_points_before=load_point_check(spring),
        load_points_after=load_point_check(fitted),
        rms_weighted_residual=float(np.sqrt(np.mean(r**2))),
        notes=notes,
    )


#: What :func:`calibrate_trace` can fit to a measured force trace (fitted in log space).
TRACE_PARAMETERS = ("damping_ratio", "contact_stiffness")


#: The columns of a measured retainer-force trace.
TRACE_COLUMNS = ("cam_angle_deg", "retainer_force_N")


def check_force_trace(cam_angle_deg, retainer_force, name: str = "the trace") -> None:
    """A measured retainer-force trace a fit can use, else the row and its value named.

    The cam angles increase (no repeated or backward angle) over at most one revolution; the
    forces are finite and none negative (the spring pushes on its retainer), and not all zero
    (a trace of nothing measured).  Rows count as a CSV file's: the header is row 1.

    Parameters
    ----------
    cam_angle_deg : array_like
        Cam angles [deg].
    retainer_force : array_like
        Retainer forces [N].
    name : str
        The trace, for messages (its file) [-].
    """
    angle = np.asarray(cam_angle_deg, dtype=float)
    force = np.asarray(retainer_force, dtype=float)
    if angle.ndim != 1 or angle.shape != force.shape or angle.size < 8:
        raise InputError(
            f"{name}: a trace needs at least 8 samples of cam angle and retainer force of one length "
            f"(found {angle.size} and {force.size})"
        )
    for column, values in zip(TRACE_COLUMNS, (angle, force)):
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            raise InputError(f"{name}: row {bad[0] + 2}, column {column}: {values[bad[0]]} is not a finite number")
    steps = np.diff(angle)
    if np.any(steps <= 0):
        i = int(np.argmax(steps <= 0))
        how = "repeats" if steps[i] == 0 else "goes back from"
        raise InputError(
            f"{name}: row {i + 3}, column cam_angle_deg: {angle[i + 1]:.6g} deg {how} the row before "
            f"({angle[i]:.6g} deg): the cam angles of a trace increase (one revolution, each angle once)"
        )
    if angle[-1] - angle[0] >= 360.0:
        raise InputError(
            f"{name}: the cam angles span {angle[-1] - angle[0]:.6g} deg, one revolution or more: give one "
            "revolution, each angle once (average the revolutions of a measurement first)"
        )
    if np.any(force < 0):
        i = int(np.argmax(force < 0))
        raise InputError(
            f"{name}: row {i + 2}, column retainer_force_N: {force[i]:.6g} N is negative: the spring pushes on its "
            "retainer (a compressive force is positive here)"
        )
    if not np.any(force > 0):
        raise InputError(f"{name}: every retainer_force_N is zero: the trace holds no measured force")


def read_force_trace(path):
    """A measured retainer-force trace from a CSV file (:data:`TRACE_COLUMNS`), checked
    (:func:`check_force_trace`, naming the file, the row and the value).

    Parameters
    ----------
    path : str or path-like
        The CSV file.

    Returns
    -------
    cam_angle, retainer_force : ndarray
        Cam angles [rad] and retainer forces [N].
    """
    cols = read_csv_columns(path)
    missing = [c for c in TRACE_COLUMNS if c not in cols]
    if missing:
        raise InputError(
            f"{path}: no column {missing[0]!r}; a trace has the columns {' and '.join(TRACE_COLUMNS)} "
            f"(found: {', '.join(cols)})"
        )
    check_force_trace(cols["cam_angle_deg"], cols["retainer_force_N"], str(path))
    return np.radians(cols["cam_angle_deg"]), cols["retainer_force_N"]


def calibrate_trace(
    spring, cam, cam_rpm: float, cam_angle, retainer_force, fit=TRACE_PARAMETERS, valve_train=None
) -> dict:
    """Fit the damping and the contact stiffness to a measured retainer-force trace.

    Least squares (``scipy.optimize.least_squares``, trust region, in the logarithms of the
    parameters) of the simulated retainer force at the periodic steady state
    (:func:`springdyn.valve.simulate`) against the measured one at its cam angles.  The
    contact stiffness shows only where coils clash: measure at a clash speed to fit it.

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    cam_rpm : float
        Cam speed of the measurement [rev/min].
    cam_angle : array_like
        Cam angles of the samples [rad].
    retainer_force : array_like
        Measured retainer force [N].
    fit : sequence of str
        Parameters to fit, of :data:`TRACE_PARAMETERS` [-].
    valve_train : ValveTrain, optional

    Returns
    -------
    dict
        ``values`` (fitted, SI), ``before`` (given or default values), ``rms_N`` (the rms
        deviation after the fit) and ``rms_before_N`` [N], ``spring`` (the calibrated spring).
    """

    fit = list(fit)
    bad = [f for f in fit if f not in TRACE_PARAMETERS]
    if bad or not fit:
        raise InputError(f"fit = {fit!r}: a force trace fits {', '.join(TRACE_PARAMETERS)}")
    check_force_trace(np.degrees(np.asarray(cam_angle, dtype=float)), retainer_force)
    theta = np.mod(np.asarray(cam_angle, dtype=float), 2 * np.pi)
    measured = np.asarray(retainer_force, dtype=float)
    start = {
        "damping_ratio": spring.damping_ratio,
        "contact_stiffness": float(spring.spring_model.turn_contact_stiffness(spring.mean_diameter))
        if hasattr(spring.spring_model, "turn_contact_stiffness")
        else (spring.contact_stiffness or float(spring.spring_model.internal_parameters()["K"])),
    }
    if start["damping_ratio"] <= 0:
        start["damping_ratio"] = 0.02

    def spring_of(logs):
        return spring.replace(**{name: float(np.exp(v)) for name, v in zip(fit, logs)})

    def residual(logs):
        # periodic to 1e-6 of Fset: the finite differences of the fit see the parameters, not the
        # revolution the run stopped at
        sim = simulate(
            spring_of(logs),
            cam,
            cam_rpm,
            valve_train=valve_train,
            check_elements=False,
            periodicity_tol=1e-6,
            points_per_revolution=720,
        )
        order = np.argsort(sim.cam_angle)
        model = np.interp(theta, sim.cam_angle[order], sim.retainer_force[order], period=2 * np.pi)
        return model - measured

    x0 = np.log([start[name] for name in fit])
    r0 = residual(x0)
    res = least_squares(residual, x0, x_scale=1.0, diff_step=1e-2, xtol=1e-8, ftol=1e-10, max_nfev=200)
    values = {name: float(np.exp(v)) for name, v in zip(fit, res.x)}
    return dict(
        values=values,
        before={name: start[name] for name in fit},
        rms_N=float(np.sqrt(np.mean(res.fun**2))),
        rms_before_N=float(np.sqrt(np.mean(r0**2))),
        spring=spring_of(res.x),
    )


def calibrated_keys(result: dict, table: dict) -> dict:
    """The ``[spring]`` keys a calibration changes, as a definition file writes them.

    Parameters
    ----------
    result : dict
        :func:`calibrate`'s result.
    table : dict
        The definition's ``[spring]`` table as given (its coil keys decide which are written).
    """
    sp = result["spring"]
    if result["parameter"] == "shear_modulus":
        return {"shear_modulus": f"{result['after'] / 1e9:.6g} GPa"}
    # every coil key the table gives, from the calibrated spring (a drawing with both active and
    # total coils keeps them consistent: the loader refuses a pair that disagrees)
    keys = [k for k in ("active_coils", "total_coils") if k in table] or ["high_pitch_coils"]
    value = {"active_coils": sp.active_coils, "total_coils": sp.total_coils, "high_pitch_coils": sp.high_pitch_coils}
    return {key: round(float(value[key]), 6) for key in keys}


def load_point_lines(result: dict) -> list[str]:
    """The calibration in lines (a calibrated file's header): the parameter before and after,
    and each load point of the drawing against the calibrated model.

    Parameters
    ----------
    result : dict
        :func:`calibrate`'s result.
    """
    return [f"{result['before']:.6g} -> {result['after']:.6g}"] + [
        f"load point {r['length_m'] * 1e3:.4g} mm: drawing {r['force_N']:.2f} N, model {r['model_force_N']:.2f} N "
        f"({r['deviation_percent']:+.2f} %)"
        for r in result["load_points_after"]
    ]
