"""Calibration of model parameters against rig records (issue 15, Build 1).

The closed-form damping is not a prediction until it is calibrated (correction LSD-6 of
docs/references.md).  :func:`calibrate`

1. identifies K and C at every speed from the records, exactly as
   :func:`~springdyn.lsd.identify.identify` does (one or two excitations per speed);
2. predicts what that identification would give for the model: the nonlinear force laws
   of the rig (:mod:`springdyn.lsd.equivalent`) are evaluated along the first harmonic of
   each record's *measured* displacement (same amplitude, same motion, same speed), and
   the predicted force phasors go through the same K, C algebra;
3. fits the named parameters (default ``leakage_factor``) by least squares on the relative
   differences of the identified direct coefficients over all speeds (damping always; the
   stiffness too when a fitted parameter changes it);
4. reports each value with a Student-t confidence interval from the Jacobian,
   ``t_(1 - alpha/2, m - n) s sqrt(diag((J^T J)^-1))`` with ``s^2 = SSR / (m - n)``
   (m residuals, n parameters), and the residuals per speed.

Comparing predicted and identified *identifications* (not raw forces) keeps the
calibration in the quantities a rotordynamicist uses, and makes it independent of where
the records start and of the sensors' noise at harmonics other than the first.
"""

from __future__ import annotations

import dataclasses
import re

import numpy as np

from ..core.errors import InputError, SolverError
from ..core.params import field_specs
from ..core.results import Result
from .equivalent import harmonic_forces
from .identify import IdentificationSeries, _cycles, _frequency, _phasors, _solve_full, _solve_single, identify
from .model import LSDModel
from .parameters import LSDParameters

__all__ = ["calibrate", "Calibration", "fittable_parameters", "update_toml_text", "DEFAULT_FIT", "MIN_SPEEDS"]

#: What is fitted unless told otherwise.
DEFAULT_FIT = ("leakage_factor",)
#: Quadrature points per period of the model's first harmonic [-].
SAMPLES = 1024
_DIRECT = {"kxx": (0, 0), "kyy": (1, 1), "cxx": (0, 0), "cyy": (1, 1)}


def fittable_parameters() -> list[str]:
    """Names of the ``[lsd]`` keys :func:`calibrate` can fit (the scalar quantities)."""
    return [f.name for f, meta in field_specs(LSDParameters) if meta["kind"] == "quantity"]


def _specs(names):
    allowed = fittable_parameters()
    meta = {f.name: m for f, m in field_specs(LSDParameters)}
    names = list(names)
    if not names:
        raise InputError("fit is empty: name at least one parameter to fit, e.g. leakage_factor")
    for n in names:
        if n not in allowed:
            raise InputError(f"fit: {n!r} is not a parameter calibrate can fit; choose from {', '.join(allowed)}")
    if len(set(names)) != len(names):
        raise InputError(f"fit = {names} names a parameter twice")
    return names, [meta[n] for n in names]


@dataclasses.dataclass(repr=False)
class Calibration(Result):
    """Fitted parameters with confidence intervals, residuals per speed, the calibrated damper.

    Attributes
    ----------
    values : dict
        Fitted value of each parameter [SI unit of its key].
    intervals : dict
        ``(low, high)`` confidence interval of each, or ``None`` (see ``notes``).
    params : LSDParameters
        The calibrated damper.
    identified : IdentificationSeries
        K and C identified from the records.
    residuals : list of dict
        Per speed: ``rpm`` and, for each fitted coefficient, identified and model values
        and the relative difference.
    caveat : str or None
        What a calibration on fewer than :data:`MIN_SPEEDS` speeds (a single orbit) cannot say, and
        what to record instead; None with enough speeds.
    """

    values: dict
    intervals: dict
    confidence: float
    params: LSDParameters
    identified: IdentificationSeries
    residuals: list
    coefficients: list
    dof: int
    rms_relative_residual: float
    notes: list = dataclasses.field(default_factory=list)
    caveat: str | None = None

    def to_dict(self) -> dict:
        """JSON-ready: each fitted key by its TOML name, ``<name>_ci`` ([low, high] or None), ``residuals``."""
        d = {}
        for name, value in self.values.items():
            d[name] = float(value)
            ci = self.intervals[name]
            d[f"{name}_ci"] = None if ci is None else [float(ci[0]), float(ci[1])]
        d["confidence"] = self.confidence
        d["dof"] = self.dof
        d["fitted_coefficients"] = list(self.coefficients)
        d["rms_relative_residual"] = self.rms_relative_residual
        d["speeds"] = len(self.residuals)
        d["caveat"] = self.caveat
        d["residuals"] = self.residuals
        if self.notes:
            d["notes"] = list(self.notes)
        return d

    title = "leaf spring damper calibration"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.params.name}, {self.identified.rpm.size} speeds, dof {self.dof}"

    def _summary(self) -> dict:
        """The JSON of ``springdyn lsd calibrate`` without the per-speed residuals (in
        :meth:`to_xarray` and the CSV): fitted values, ``<name>_ci``, the fit's figures."""
        d = {k: v for k, v in self.to_dict().items() if k != "residuals"}
        d.setdefault("notes", [])
        return d

    def to_xarray(self):
        """Identified and calibrated-model coefficients per speed (dimension ``rpm``)."""
        import xarray as xr

        rpm = np.array([r["rpm"] for r in self.residuals], dtype=float)
        data = {}
        for k in self.coefficients:
            unit, tag = ("N/m", "N_per_m") if k[0] == "k" else ("N*s/m", "Ns_per_m")
            data[f"{k}_identified"] = (
                "rpm",
                np.array([r[f"{k}_identified_{tag}"] for r in self.residuals]),
                {"units": unit, "long_name": f"{k} identified from the records"},
            )
            data[f"{k}_model"] = (
                "rpm",
                np.array([r[f"{k}_model_{tag}"] for r in self.residuals]),
                {"units": unit, "long_name": f"{k} of the calibrated model"},
            )
            data[f"{k}_relative"] = (
                "rpm",
                np.array([r[f"{k}_relative"] for r in self.residuals]),
                {"units": "", "long_name": f"model / identified - 1 for {k}"},
            )
        return xr.Dataset(
            data, coords={"rpm": ("rpm", rpm, {"units": "rpm"})}, attrs={k: float(v) for k, v in self.values.items()}
        )

    def _plot(self, ax=None):
        from ..core.plotting import new_figure

        if ax is None:
            fig, ax = new_figure(1, 1, figsize=(7, 4.5))
        ds = self.to_xarray()
        for i, k in enumerate(self.coefficients):
            ax.plot(ds["rpm"], ds[f"{k}_identified"], "o", color=f"C{i}", label=f"{k} identified")
            ax.plot(ds["rpm"], ds[f"{k}_model"], "-", color=f"C{i}", label=f"{k} calibrated model")
        fitted = ", ".join(f"{k} = {v:.4g}" for k, v in self.values.items())
        ax.set_title(f"calibration: {fitted}", fontsize=9)
        ax.set_xlabel("speed [rpm]")
        ax.set_ylabel("coefficient [SI]")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        return ax.figure

    def toml_text(self, text: str) -> str:
        """``text`` (a TOML definition) with the fitted keys of ``[lsd]`` set to the calibrated values.

        Parameters
        ----------
        text : str
            A TOML definition with an ``[lsd]`` table [-].
        """
        comments = {}
        for name in self.values:
            ci = self.intervals[name]
            rng = "" if ci is None else f", {100 * self.confidence:g} % CI {ci[0]:.4g} to {ci[1]:.4g}"
            comments[name] = f"calibrated by springdyn lsd calibrate{rng}"
        sources = sorted({src for it in self.identified.items for src in it.sources})
        shown = ", ".join(sources[:6]) + (", ..." if len(sources) > 6 else "")
        header = (
            f"# Calibrated by springdyn lsd calibrate on {len(self.identified.items)} speed(s) "
            f"({shown}): {', '.join(self.values)} fitted; rms relative residual "
            f"{self.rms_relative_residual:.3g}. Comments below that predate the calibration may be stale.\n"
        )
        return header + update_toml_text(text, {k: float(v) for k, v in self.values.items()}, comments)


def update_toml_text(text: str, values: dict, comments: dict | None = None) -> str:
    """Set keys of the ``[lsd]`` table of a TOML text (SI numbers), keeping everything else.

    A key present in the table is rewritten in place; a missing one is added after the
    ``[lsd]`` header.

    Parameters
    ----------
    text : str
        The TOML text.
    values : dict
        ``{key: number}`` in SI.
    comments : dict, optional
        ``{key: comment}`` appended to each line.
    """
    comments = comments or {}
    lines = text.splitlines()
    start = next((i for i, line in enumerate(lines) if re.match(r"\s*\[lsd\]\s*(#.*)?$", line)), None)
    if start is None:
        raise InputError("the definition has no [lsd] table to write the calibration into")
    end = next((i for i in range(start + 1, len(lines)) if re.match(r"\s*\[", lines[i])), len(lines))
    for key, value in values.items():
        new = f"{key} = {value:.8g}" + (f"  # {comments[key]}" if key in comments else "")
        for i in range(start + 1, end):
            if re.match(rf"\s*{re.escape(key)}\s*=", lines[i]):
                lines[i] = new
                break
        else:
            lines.insert(start + 1, new)
            end += 1
    return "\n".join(lines) + "\n"


def _record_phasors(records, seconds, rpms):
    """Frequency and displacement phasors ``[(X, Y), ...]`` of each speed's records."""
    out = []
    for k, rec in enumerate(records):
        rpm = None if rpms is None else rpms[k]
        freq = _frequency(rec, rpm)
        omega = 2 * np.pi * freq
        group = [rec] if seconds is None else [rec, seconds[k]]
        ph = []
        for r in group:
            _, (a, b) = _cycles(r, freq)
            P = _phasors(r, a, b, omega)
            ph.append((P[0], P[1]))
        out.append((60.0 * freq, omega, ph))
    out.sort(key=lambda item: item[0])
    return out


def _predict(model, omega, ph):
    """What the identification gives for the model along these displacement phasors."""
    P = []
    for X, Y in ph:
        f = harmonic_forces(model, X, Y, omega, SAMPLES)
        P.append(np.array([X, Y, sum(v[0] for v in f.values()), sum(v[1] for v in f.values())]))
    if len(P) == 1:
        K, C, _ = _solve_single(P[0], 0.0, omega)
        return K, C
    return _solve_full(P[0], P[1], 0.0, omega, ["model", "model"])


def calibrate(
    params: LSDParameters, records, seconds=None, *, fit=DEFAULT_FIT, mass=None, rpms=None, confidence: float = 0.95
) -> Calibration:
    """Fit damper parameters to rig records at several speeds (least squares, Student-t intervals).

    Parameters
    ----------
    params : LSDParameters
        The damper before calibration (the starting values of the fitted keys).
    records : list of RigData
        One record per speed (displacements [m], forces [N]).
    seconds : list of RigData, optional
        Second, independent excitations, same order: full 2 x 2 identification.
    fit : sequence of str
        ``[lsd]`` keys to fit (:func:`fittable_parameters`); default ``leakage_factor``.
    mass : float, optional
        Moving mass whose inertia the identification removes [kg]; default the damper's
        ``ring_mass``.
    rpms : list of float, optional
        Speeds [rev/min]; by default found in the data.
    confidence : float
        Confidence level of the intervals, in (0, 1) [-].

    Returns
    -------
    Calibration

    Raises
    ------
    InputError
        Unknown parameter, bad records, no coefficient the fitted parameters change.
    SolverError
        The least-squares fit does not converge.
    """
    from scipy import stats
    from scipy.optimize import least_squares

    if not isinstance(params, LSDParameters):
        raise InputError(f"calibrate needs LSDParameters, got {type(params).__name__}")
    if isinstance(fit, str):
        fit = [s.strip() for s in fit.split(",") if s.strip()]
    names, metas = _specs(fit)
    if not (0.0 < confidence < 1.0):
        raise InputError(f"confidence = {confidence!r} must lie between 0 and 1")
    records = list(records)
    if not records:
        raise InputError("calibrate needs at least one record")
    if seconds is not None and len(seconds) != len(records):
        raise InputError(f"{len(records)} first records but {len(seconds)} second records; pair them one to one")
    if rpms is not None and len(rpms) != len(records):
        raise InputError(f"{len(records)} records but {len(rpms)} speeds; give one speed per record")
    mass = params.ring_mass if mass is None else float(mass)
    items = [
        identify(r, None if seconds is None else seconds[k], mass=mass, rpm=None if rpms is None else rpms[k])
        for k, r in enumerate(records)
    ]
    items.sort(key=lambda it: it.rpm)
    series = IdentificationSeries(items, name="identified")
    speeds = _record_phasors(records, seconds, rpms)

    start = np.array([float(getattr(params, n)) for n in names])
    scale = np.where(start > 0, np.abs(start), 1.0)
    lower = (
        np.array([(np.finfo(float).tiny if m["positive"] else 0.0 if m["nonnegative"] else -np.inf) for m in metas])
        / scale
    )
    minimum = np.array([-np.inf if m["minimum"] is None else m["minimum"] for m in metas]) / scale
    lower = np.maximum(lower, minimum)
    upper = np.array([np.inf if m["maximum"] is None else m["maximum"] for m in metas]) / scale

    def model_at(x):
        try:
            return LSDModel(params.replace(**{n: float(v * s) for n, v, s in zip(names, x, scale)}))
        except InputError as exc:
            raise SolverError(f"calibrate: the fit left the allowed range of a parameter: {exc}") from None

    def predictions(x):
        m = model_at(x)
        return [_predict(m, omega, ph) for _, omega, ph in speeds]

    # which identified direct coefficients the fitted parameters change (K only for stiffness parameters)
    x0 = start / scale
    base = predictions(x0)
    keys = []
    for key, (i, j) in _DIRECT.items():
        ident = np.array([(it.K if key[0] == "k" else it.C)[i, j] for it in items])
        if not np.all(np.isfinite(ident)):
            continue
        sens = 0.0
        for p in range(len(names)):
            x = x0.copy()
            x[p] = x[p] * 1.05 if x[p] != 0 else 0.05
            pert = predictions(x)
            for b, q in zip(base, pert):
                mb, mq = (b[0] if key[0] == "k" else b[1])[i, j], (q[0] if key[0] == "k" else q[1])[i, j]
                sens = max(sens, abs(mq - mb) / max(abs(mb), 1e-300))
        if sens > 1e-6:
            keys.append(key)
    if not keys:
        raise InputError(f"none of the identified coefficients depends on {', '.join(names)}: nothing to fit")
    target = {k: np.array([(it.K if k[0] == "k" else it.C)[_DIRECT[k]] for it in items]) for k in keys}
    for k, v in target.items():
        if np.any(np.abs(v) <= 0):
            raise InputError(f"an identified {k} is zero: it cannot be fitted in relative terms")

    def residual(x):
        pred = predictions(x)
        r = []
        for k in keys:
            mdl = np.array([(p[0] if k[0] == "k" else p[1])[_DIRECT[k]] for p in pred])
            r.append((mdl - target[k]) / np.abs(target[k]))
        return np.concatenate(r)

    x0 = np.clip(x0, lower, upper)
    sol = least_squares(
        residual, x0, bounds=(lower, upper), x_scale=1.0, max_nfev=200 * (len(names) + 1), diff_step=1e-4
    )
    if not sol.success:
        raise SolverError(f"calibrate: the least-squares fit of {', '.join(names)} did not converge ({sol.message})")
    r = sol.fun
    m, n = r.size, len(names)
    dof = m - n
    notes = []
    values = {nm: float(v * s) for nm, v, s in zip(names, sol.x, scale)}
    intervals = {nm: None for nm in names}
    J = sol.jac
    if dof <= 0:
        notes.append(
            f"{m} residuals for {n} parameters: no degrees of freedom left for confidence intervals "
            "(record more speeds or a second excitation)"
        )
    elif np.linalg.matrix_rank(J) < n:
        notes.append(
            "the fitted parameters are not separately identifiable from these records (singular Jacobian): "
            "no confidence intervals; fit fewer parameters"
        )
    else:
        s2 = float(r @ r) / dof
        cov = s2 * np.linalg.inv(J.T @ J)
        t = float(stats.t.ppf(0.5 + confidence / 2.0, dof))
        for k, (nm, s) in enumerate(zip(names, scale)):
            half = t * np.sqrt(max(cov[k, k], 0.0)) * s
            intervals[nm] = (values[nm] - half, values[nm] + half)
    caveat = _caveat(items, seconds is not None, names, m, dof, confidence)
    if caveat:
        notes.insert(0, caveat)
    calibrated = params.replace(**values)
    final = predictions(sol.x)
    residuals = []
    for idx, it in enumerate(items):
        row = {"rpm": float(it.rpm)}
        for k in keys:
            unit = "N_per_m" if k[0] == "k" else "Ns_per_m"
            mdl = float((final[idx][0] if k[0] == "k" else final[idx][1])[_DIRECT[k]])
            row[f"{k}_identified_{unit}"] = float(target[k][idx])
            row[f"{k}_model_{unit}"] = mdl
            row[f"{k}_relative"] = mdl / float(target[k][idx]) - 1.0
        residuals.append(row)
    return Calibration(
        values=values,
        intervals=intervals,
        confidence=float(confidence),
        params=calibrated,
        identified=series,
        residuals=residuals,
        coefficients=keys,
        dof=int(dof),
        rms_relative_residual=float(np.sqrt(np.mean(r * r))),
        notes=notes,
        caveat=caveat,
    )


#: Fewest speeds [-] a calibration needs before its intervals say how well the parameters are known:
#: one speed cannot show the frequency dependence that tells the viscous damping (constant) from the
#: friction equivalents (~1/omega), and two leave no check of it.
MIN_SPEEDS = 3


def _caveat(items, two_excitations: bool, names, residuals: int, dof: int, confidence: float):
    """What a calibration on too few speeds cannot say (issue 40: one orbit gave an interval of -119 to
    +300 % and no word), or None."""
    from scipy import stats

    speeds = len(items)
    if speeds >= MIN_SPEEDS:
        return None
    rpm = ", ".join(f"{it.rpm:.5g}" for it in items)
    what = (
        f"calibrated on {'a single orbit' if speeds == 1 and not two_excitations else f'{speeds} speed(s)'} "
        f"({rpm} rpm{', one excitation' if not two_excitations else ', two excitations'})"
    )
    t = float(stats.t.ppf(0.5 + confidence / 2.0, dof)) if dof > 0 else None
    interval = (
        f"the {100 * confidence:g} % interval rests on {residuals} residuals and {dof} degree(s) of freedom "
        f"(t = {t:.3g}) and measures only their scatter, not that error"
        if t is not None
        else "there are no degrees of freedom left for an interval"
    )
    cross = "" if two_excitations else "; one excitation per speed mixes direct and cross terms (Cxx - Kxy/w, --second)"
    return (
        f"CAVEAT: {what}. At {'one frequency' if speeds == 1 else 'two frequencies'} the viscous damping "
        "(constant in frequency) and the friction equivalents (~1/omega) cannot be told apart, so the fitted "
        f"{', '.join(names)} absorbs whatever the other parameters get wrong; {interval}{cross}. Record orbits "
        f"at {MIN_SPEEDS} or more speeds over the range of use before using the value or its interval"
    )
