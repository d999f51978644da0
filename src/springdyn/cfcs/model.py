"""The CFCS model: statics, inverse and forward dynamics and sweeps on one mechanism.

A thin layer over the physics functions of :mod:`~springdyn.cfcs.kinematics`,
:mod:`~springdyn.cfcs.statics`, :mod:`~springdyn.cfcs.dynamics` and
:mod:`~springdyn.cfcs.pivot`; it validates inputs and builds result objects.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np
from scipy.optimize import minimize_scalar

from ..core.errors import InputError, SolverError
from ..core.progress import progress
from ..core.units import format_quantity, to_si
from .beam import band_error_over_range_ends, beam_force_at_toggle, beam_force_curve, prbm_error
from .drive import (
    DRIVE_SIGN_SMOOTHING,
    RIGID_DRIVE_FREQUENCY_RATIO,
    RIGID_DRIVE_LAG,
    TOGGLE_REST_FACTOR,
    drive_force,
    energy_balance,
    integrate_driven,
    slider_effective_mass,
    toggle_sticking,
)
from .dynamics import energy, integrate_forward, inverse_dynamics
from .kinematics import deflection_from_theta2, slider_jacobian, spring_angle, theta2_from_deflection
from .motion import MAX_OMEGA, SinusoidMotion, TabulatedMotion, amplitude_to_si, check_stroke, offset_to_si
from .params import CFCSParams
from .pivot import (
    bending_stress,
    default_plate_bending,
    max_stroke_for_stress,
    plate_modulus,
    safety_factor,
    strip_first_frequency,
)
from .results import DrivenResult, DynamicResult, ForwardResult, FrequencySweep, StaticResult
from .statics import (
    dissipative_torque,
    frozen_jacobian,
    percent_constant_force,
    percent_constant_force_energy,
    spring_energy,
    static_force,
    static_force_at_toggle,
)

__all__ = ["BEAM_CHECK_SAMPLES", "CFCS", "DEFAULT_AMPLITUDE", "DEFAULT_OFFSET", "TOGGLE_TOLERANCE", "toggle_check"]

#: Samples of the elastica in the beam check of a PRBM result (a test halves and doubles them:
#: the band error moves by less than 1e-4 of itself).
BEAM_CHECK_SAMPLES = 401

#: Share of a range [-] over whose last part the range's end is moved to show how the PRBM's band error
#: depends on it (``beam_band_error_min_percent``, ``..._max_percent``).
BAND_ERROR_END_SHARE = 0.1

#: Default sinusoid amplitude: 40 % of r2 + r3 (the paper's "40 % mechanism deflection",
#: correction CFCS-4 of docs/references.md).
DEFAULT_AMPLITUDE = "40 %"

#: Default preload offset of the motion and start of the quasi-static working range: 2.5 % of
#: r2 + r3 (4.5 mm and a crank angle of 13.5 deg for Table 1).  A constant-force spring is worked
#: inside its constant-force band, not through the toggle, where the dissipative terms of
#: Eqs. (21)-(22) turned into a slider force diverge (correction CFCS-5 of docs/references.md).
DEFAULT_OFFSET = "2.5 %"

#: Relative change of a statistic [-] between the preload offset and half or twice it beyond which the
#: statistic is named in ``offset_sensitive_statistics`` (issue 40: the dissipative figures move 20-50 %).
OFFSET_TOLERANCE = 0.10

#: Statistics of a dynamic result given at half and twice the preload offset.
_OFFSET_STATS = (
    "mean_force_N",
    "peak_to_peak_N",
    "force_max_N",
    "force_min_N",
    "pcf_percent",
    "hysteresis_energy_per_cycle_J",
)

#: Relative change of a statistic [-] between the toggle cut-off and twice it above which the
#: statistic is reported ``toggle_dominated``.
TOGGLE_TOLERANCE = 0.01

#: Defaults of the driven model (:meth:`CFCS.driven`): periods integrated, output samples per period,
#: relative tolerance.  Halving and doubling each moves the statistics of the seed's case by less than
#: 1 % (tests/cfcs/test_drive.py).
DRIVEN_PERIODS = 6
DRIVEN_SAMPLES = 2000
DRIVEN_RTOL = 1e-8

#: Largest change of the driven statistics between the last two periods [-] (relative to the
#: peak-to-peak force) beyond which the result says it is not periodic yet.
DRIVEN_PERIODICITY = 0.01

#: Share of the last period [-] the crank must rest within the shear angle of the toggle for a driven
#: result to be flagged ``toggle_sticking`` (a crank that only turns round there rests for a few samples).
TOGGLE_STICKING_SHARE = 0.01

#: Relative change of the peak-to-peak force [-] by tau_AF beyond which a driven run whose crank passes
#: within the shear angle without stopping gets a note.
AXIAL_FRICTION_EFFECT = 0.1

#: Statistics of the driven run repeated without tau_AF (``<name>_without_axial_friction_<unit>``).
_WITHOUT_AF = ("mean_force_N", "peak_to_peak_N", "force_max_N", "force_min_N")

#: A constant forward-dynamics force may be at most this many times the mechanism's largest
#: spring force (beyond it the slider hits the end of its travel within a step).
FORCE_LIMIT_FACTOR = 1000.0


def toggle_check(at_cutoff: dict, at_double: dict, keys) -> list:
    """Names of the statistics that change by more than :data:`TOGGLE_TOLERANCE` (relative)
    when the toggle cut-off doubles.

    Parameters
    ----------
    at_cutoff, at_double : dict
        Statistics computed with the cut-off and with twice it.
    keys : iterable of str
        The statistics to compare.
    """
    out = []
    for k in keys:
        a, b = at_cutoff[k], at_double[k]
        if a is None or b is None:
            continue
        scale = max(abs(a), abs(b))
        if abs(a - b) > TOGGLE_TOLERANCE * scale and abs(a - b) > 1e-12:
            out.append(k)
    return out


def _double_cutoff(cutoff: float) -> float:
    """Twice the cut-off, kept below the kinematic limit (90 deg)."""
    return min(2.0 * cutoff, 0.5 * (cutoff + 0.5 * np.pi))


#: Statistics of a dynamic result checked against the cut-off.
_DYNAMIC_STATS = (
    "mean_force_N",
    "median_force_N",
    "peak_to_peak_N",
    "pcf_percent",
    "force_max_N",
    "force_min_N",
    "hysteresis_energy_per_cycle_J",
)


class CFCS:
    """A constant-force compression spring (pseudo-rigid-body model).

    Parameters
    ----------
    params : CFCSParams
        The mechanism.

    Examples
    --------
    >>> m = CFCS(CFCSParams.example("table1"))
    >>> round(m.static().summary["force_max_N"], 3)
    12.97
    """

    def __init__(self, params: CFCSParams):
        if not isinstance(params, CFCSParams):
            raise InputError(f"params = {params!r} must be a CFCSParams")
        self.params = params

    @classmethod
    def from_toml(cls, path) -> CFCS:
        """The mechanism of a TOML file's ``[cfcs]`` table.

        Parameters
        ----------
        path : str or Path
            A TOML file with a ``[cfcs]`` table [-].
        """
        return cls(CFCSParams.from_toml(path))

    @classmethod
    def example(cls, name: str = "table1") -> CFCS:
        """A built-in example mechanism.

        Parameters
        ----------
        name : str
            A built-in example (``table1``) [-].
        """
        return cls(CFCSParams.example(name))

    def __repr__(self) -> str:
        p = self.params
        return (
            f"CFCS(r2={p.r2 * 1e3:.4g} mm, r3={p.r3 * 1e3:.4g} mm, K3={p.k3:.5g} N*m/rad, "
            f"flexure_model={p.flexure_model!r}, friction={p.friction_model!r}, "
            f"axial_force={p.axial_force})"
        )

    # -- helpers ------------------------------------------------------------------------
    @property
    def beam(self) -> bool:
        """True when the flexure is the large-deflection strip (``flexure_model = 'beam'``)."""
        return self.params.flexure_model == "beam"

    def with_flexure_model(self, model: str) -> CFCS:
        """The same mechanism with another flexure model ('prbm' or 'beam').

        Parameters
        ----------
        model : str
            ``prbm`` or ``beam`` [-].
        """
        return CFCS(self.params.replace(flexure_model=model))

    def beam_curve(self, deflection) -> dict:
        """The elastica solution at increasing deflections [m] (see :func:`springdyn.cfcs.beam.beam_force_curve`).

        Adds ``stress`` [Pa], the peak bending stress ``E' (h/2) max|curvature|``.

        Parameters
        ----------
        deflection : array_like
            Slider deflections [m], increasing.
        """
        p = self.params
        c = beam_force_curve(deflection, p.r2, p.r3, p.pivot_length, p.bending_stiffness("beam"))
        c["stress"] = p.bending_modulus("beam") * 0.5 * p.pivot_thickness * c["max_curvature"]
        return c

    def _beam_table(self, hi: float):
        """Cubic splines of the beam's force and stress over ``[0, hi]`` (cached; 401 points)."""
        from scipy.interpolate import CubicSpline

        cache = getattr(self, "_beam_cache", None)
        if cache is not None and cache[0] >= hi:
            return cache[1]
        x = np.linspace(0.0, hi, 401)
        c = self.beam_curve(x)
        table = {"x_max": hi, "force": CubicSpline(x, c["force"]), "stress": CubicSpline(x, c["stress"])}
        self._beam_cache = (hi, table)
        return table

    def spring_force(self, x, theta2=None):
        """Quasi-static slider force [N] of the flexure model at deflections ``x`` [m].

        Parameters
        ----------
        x : float or array_like
            Slider deflections [m].
        theta2 : float or array_like, optional
            The crank angles of ``x`` [rad] (computed when omitted).
        """
        p = self.params
        if self.beam:
            return self._beam_table(max(float(np.max(x)), 1e-9))["force"](np.asarray(x, dtype=float))
        th = theta2_from_deflection(x, p.r2, p.r3) if theta2 is None else theta2
        return static_force(th, p.k3, p.r2, p.r3)

    def stress(self, theta2, deflection=None):
        """Pivot bending stress [Pa] at crank angles ``theta2`` (NaN without flexure dimensions).

        PRBM: ``E (h/2) theta_K3 / l``; beam model: ``E' (h/2) max|curvature|`` at the
        deflections (from the tabulated elastica).

        Parameters
        ----------
        theta2 : float or array_like
            Crank angles [rad].
        deflection : float or array_like, optional
            The slider deflections at ``theta2`` [m] (the beam model needs them).
        """
        p = self.params
        th_k3 = spring_angle(np.asarray(theta2, dtype=float), p.r2, p.r3)
        if not p.has_flexure:
            return np.full_like(th_k3, np.nan)
        if self.beam:
            x = deflection_from_theta2(theta2, p.r2, p.r3) if deflection is None else np.asarray(deflection)
            return self._beam_table(max(float(np.max(x)), 1e-9))["stress"](x)
        return bending_stress(th_k3, p.bending_modulus("prbm"), p.pivot_thickness, p.pivot_length)

    def _stress_summary(self, theta2, deflection=None, stress=None) -> dict:
        p = self.params
        out = {"max_stress_Pa": None, "safety_factor": None, "max_stroke_for_stress_m": None}
        if p.has_flexure:
            smax = float(np.max(self.stress(theta2, deflection) if stress is None else stress))
            out["max_stress_Pa"] = smax
            if p.allowable_stress is not None and smax > 0:  # unloaded: no finite factor, a note says so
                out["safety_factor"] = float(safety_factor(p.allowable_stress, smax))
                out["max_stroke_for_stress_m"] = self.max_stroke_for_stress()
        return out

    def _note_nulls(self, summary: dict) -> dict:
        """Say why a figure is ``None`` (``notes`` of the summary): no figure without a reason."""
        p = self.params
        notes = summary.setdefault("notes", [])
        if summary.get("max_stress_Pa") is None and "max_stress_Pa" in summary:
            notes.append(
                "stress figures need the flexure's dimensions (pivot_width, pivot_thickness, "
                "pivot_length, youngs_modulus); this definition gives torsional_stiffness"
            )
        elif summary.get("safety_factor") is None and "safety_factor" in summary and p.allowable_stress is None:
            notes.append("safety_factor and max_stroke_for_stress_m need allowable_stress in [cfcs]")
        elif summary.get("safety_factor") is None and summary.get("max_stress_Pa") == 0.0:
            notes.append("safety_factor: the flexure carries no stress over the motion (unbounded, not a failure)")
        if "toggle_cutoff_rad" in summary and summary["toggle_cutoff_rad"] is None:
            notes.append("toggle_cutoff_rad: the forward problem integrates through the toggle without a cut-off")
        return summary

    def max_stroke_for_stress(self) -> float | None:
        """Largest deflection [m] at which the flexure stress stays within the allowable stress."""
        p = self.params
        if not (p.has_flexure and p.allowable_stress is not None):
            return None
        if not self.beam:
            return max_stroke_for_stress(
                p.allowable_stress, p.bending_modulus("prbm"), p.pivot_thickness, p.pivot_length, p.r2, p.r3
            )
        lim = p.max_deflection
        x = np.linspace(0.0, lim, 401)
        s = self._beam_table(lim)["stress"](x)
        over = np.flatnonzero(s > p.allowable_stress)
        if over.size == 0:
            return float(lim)
        i = int(over[0])
        from scipy.optimize import brentq

        spl = self._beam_table(lim)["stress"]
        return float(brentq(lambda xx: spl(xx) - p.allowable_stress, x[i - 1], x[i], xtol=1e-12))

    def _common_summary(self) -> dict:
        p = self.params
        out = {
            "toggle_cutoff_rad": p.toggle_cutoff,
            "friction_model": p.friction_model,
            "axial_force": p.axial_force,
            "k3_N_m_per_rad": p.k3,
            "flexure_model": p.flexure_model,
            "plate_bending": p.uses_plate_bending(),
            "poisson_ratio": p.poisson_ratio,
        }
        if p.has_flexure:
            out["bending_stiffness_N_m2"] = p.bending_stiffness()
        return out

    def beam_check(self, hi: float, lo: float = 0.0, working: float | None = None, n: int = BEAM_CHECK_SAMPLES) -> dict:
        """The PRBM's static force against the elastica of the same strip over ``[lo, hi]`` [m].

        The check every PRBM result carries (issue 30): the elastica of :mod:`.beam` with the
        PRBM's own modulus (so that it measures the pin, not the modulus), on ``n`` samples of
        ``[0, hi]`` plus ``lo`` and ``working``.  Keys (None, with a note saying why, when the
        elastica cannot be evaluated: no strip dimensions, or a continuation that fails):

        - ``beam_force_min_N``, ``beam_force_max_N``: the elastica's force band over ``[lo, hi]``;
        - ``beam_band_error_percent``: ``100 (B_prbm - B_beam) / B_beam`` over ``[lo, hi]``
          (:func:`springdyn.cfcs.beam.prbm_error`);
        - ``beam_force_error_percent``: ``100 max |F_prbm - F_beam| / F0`` over ``[lo, hi]``, F0 the
          elastica's force at the toggle;
        - with ``working``: ``beam_working_band_error_percent`` over ``[working, hi]``.

        Parameters
        ----------
        hi : float
            Largest deflection [m].
        lo : float
            Smallest deflection [m].
        working : float, optional
            Start of a working range [m] rated separately.
        n : int
            Samples of ``[0, hi]`` [-].
        """
        lo = 0.0 if lo <= hi / (n - 1) else float(lo)  # within a grid step of the toggle: from the toggle
        key = (float(hi), lo, working, n)
        cache = self.__dict__.setdefault("_beam_check_cache", {})
        if key not in cache:
            extra = [v for v in (lo, working) if v is not None and v > 0]
            x = np.unique(np.concatenate([np.linspace(0.0, hi, n), extra]))
            cache[key] = self._beam_check_on(x, lo, working)[0]
        out = dict(cache[key])
        out["notes"] = list(out["notes"])
        return out

    def _beam_check_on(self, x, lo: float = 0.0, working: float | None = None):
        """:meth:`beam_check` on the samples ``x`` (from 0, increasing); also the elastica's force there (or None)."""
        p = self.params
        keys = [
            "beam_force_min_N",
            "beam_force_max_N",
            "beam_band_error_percent",
            "beam_force_error_percent",
            "beam_band_error_min_percent",
            "beam_band_error_max_percent",
            "beam_band_error_ends_m",
        ]
        if working is not None:
            keys.append("beam_working_band_error_percent")
        out = dict.fromkeys(keys)
        notes = []
        out["notes"] = notes
        if not p.has_flexure:
            notes.append(
                "beam check: the elastica needs the strip (pivot_width, pivot_thickness, pivot_length, "
                "youngs_modulus); this definition gives torsional_stiffness only, so the PRBM's error is not known"
            )
            return out, None
        try:
            fb = beam_force_curve(x, p.r2, p.r3, p.pivot_length, p.bending_stiffness("prbm"))["force"]
        except SolverError as exc:
            notes.append(f"beam check not available: {exc}")
            return out, None
        fp = static_force(theta2_from_deflection(x, p.r2, p.r3), p.k3, p.r2, p.r3)
        sel = x >= lo
        e = prbm_error(x[sel], fp[sel], fb[sel], fb[0])
        out.update(
            beam_force_min_N=float(np.min(fb[sel])),
            beam_force_max_N=float(np.min(fb[sel]) + e["band_beam"]),
            beam_band_error_percent=_finite(100.0 * e["band_error"]),
            beam_force_error_percent=100.0 * e["force_error"],
        )
        # the band error's dependence on where the range ends (issue 40): over the ends in its last tenth
        xs = x[sel]
        ends = xs[xs >= xs[0] + (1.0 - BAND_ERROR_END_SHARE) * (xs[-1] - xs[0])]
        be = band_error_over_range_ends(xs, fp[sel], fb[sel], ends)
        if ends.size > 1 and np.all(np.isfinite(be)):
            out.update(
                beam_band_error_min_percent=float(100.0 * np.min(be)),
                beam_band_error_max_percent=float(100.0 * np.max(be)),
                beam_band_error_ends_m=[float(ends[0]), float(ends[-1])],
            )
            notes.append(
                f"beam check: the PRBM band error depends on where the range ends (a difference of extremes): "
                f"{100 * np.min(be):+.3g} to {100 * np.max(be):+.3g} % for ends from "
                f"{format_quantity(ends[0], 'm', 'mm', 4)} to {format_quantity(ends[-1], 'm', 'mm', 4)} (the last "
                f"{100 * BAND_ERROR_END_SHARE:g} % of the range); the force error, max |F PRBM - F elastica| / F0 = "
                f"{100 * e['force_error']:.3g} % over the whole range, is a largest difference and only grows with it"
            )
        if working is not None:
            w = x >= working
            out["beam_working_band_error_percent"] = _finite(
                100.0 * prbm_error(x[w], fp[w], fb[w], fb[0])["band_error"]
            )
        if out["beam_band_error_percent"] is None:
            notes.append("beam check: the range is a single deflection, so there is no force band to compare")
        if p.plate_bending is None and default_plate_bending(p.pivot_width, p.pivot_length):
            factor = plate_modulus(p.youngs_modulus, p.poisson_ratio) / p.youngs_modulus
            notes.append(
                f"beam check: the strip (b/l = {p.pivot_width / p.pivot_length:.3g}) bends as a plate, "
                f"{100 * (factor - 1):.3g} % stiffer than Eq. (1) gives (the beam model's default, "
                "plate_bending = true); the check uses the PRBM's modulus E and measures the pin alone"
            )
        return out, fb

    def _add_beam_check(self, summary: dict, hi: float, lo: float = 0.0, working: float | None = None) -> dict:
        """Add :meth:`beam_check` to a PRBM result's summary (nothing for the beam model)."""
        if self.beam:
            return summary
        check = self.beam_check(hi, lo, working)
        notes = check.pop("notes")
        summary.update(check)
        summary.setdefault("notes", []).extend(notes)
        return summary

    def _stroke(self, stroke) -> float:
        p = self.params
        value = 0.4 * p.extended_length if stroke is None else float(stroke)
        if not value > 0:
            raise InputError(f"stroke = {format_quantity(value, 'm', 'mm')} must be positive")
        check_stroke(
            0.0, value, p.max_deflection, f"stroke = {format_quantity(value, 'm', 'mm')}", "give a shorter stroke"
        )
        return value

    # -- statics ------------------------------------------------------------------------
    def static(self, stroke: float | None = None, n: int = 721, *, offset=DEFAULT_OFFSET) -> StaticResult:
        """Force-deflection by virtual work over ``[0, stroke]`` [m] (default 40 % of r2 + r3).

        Also the quasi-static compression and extension branches with tau_CF, tau_AF and
        slider friction as configured, the maximum force (refined by a bounded scalar
        search), PCF (``Fmin/Fmax``) and its energy variant, and the pivot stress.

        The curve starts at the toggle (the reference values of the elastic force are given
        from there); the statistics of the dissipative branches (``pcf_compression_percent``)
        are taken over the working range ``[offset, stroke]``, by default from the preload
        offset :data:`DEFAULT_OFFSET` (a length [m] or a percentage of r2 + r3).  If the working
        range reaches into the toggle zone they are computed at the cut-off and at twice it,
        and ``toggle_dominated`` says whether they differ by more than 1 %.

        Parameters
        ----------
        stroke : float, optional
            Largest deflection [m] (default 40 % of r2 + r3).
        n : int
            Samples [-].
        offset : float or str
            Smallest deflection, a length or a fraction of r2 + r3 [m or %].
        """
        p = self.params
        stroke = self._stroke(stroke)
        if not (isinstance(n, (int, np.integer)) and n >= 3):
            raise InputError(f"n = {n} must be a whole number >= 3")
        start = offset_to_si(offset, p.extended_length)
        if not 0.0 <= start < stroke:
            raise InputError(
                f"offset = {format_quantity(start, 'm', 'mm')} must lie in [0, stroke) = "
                f"[0, {format_quantity(stroke, 'm', 'mm')})"
            )
        x = np.linspace(0.0, stroke, n)
        starts = {"half": 0.5 * start, "double": 2.0 * start if 2.0 * start < stroke else None}
        if start > 0:  # the start of the working range is a sample, and half and twice it (issue 40)
            x = np.unique(np.concatenate([x, [start], [v for v in starts.values() if v is not None]]))
        th = theta2_from_deflection(x, p.r2, p.r3)
        f_prbm = static_force(th, p.k3, p.r2, p.r3)
        extra = {}
        if self.beam:
            bc = self.beam_curve(x)
            f, stress = bc["force"], bc["stress"]
            extra = {"force_prbm_N": f_prbm, "theta2_beam_rad": bc["theta2"], "end_rotation_rad": bc["end_rotation"]}
            if p.has_flexure:
                extra["stress_prbm_Pa"] = bending_stress(
                    spring_angle(th, p.r2, p.r3), p.bending_modulus("prbm"), p.pivot_thickness, p.pivot_length
                )
        else:
            f, stress = f_prbm, self.stress(th)
        work = x >= start

        def branches(cutoff):
            tau = dissipative_torque(th, f, p.pin_friction, p.friction_model, p.shear_angle, p.axial_force, p.r2, p.r3)
            return tau / frozen_jacobian(th, p.r2, p.r3, cutoff) + p.slider_friction

        fd = branches(p.toggle_cutoff)
        fmax, xmax = _refined_max(
            x,
            f,
            None if self.beam else (lambda xx: static_force(theta2_from_deflection(xx, p.r2, p.r3), p.k3, p.r2, p.r3)),
        )
        stats = {"pcf_compression_percent": percent_constant_force((f + fd)[work])}
        offsets = {"offset_sensitive_statistics": []}
        for tag, s0 in starts.items():
            value = None if (start == 0 or s0 is None) else percent_constant_force((f + fd)[x >= s0])
            offsets[f"pcf_compression_at_{tag}_offset_percent"] = value
            offsets[f"working_start_{tag}_offset_m"] = None if value is None else float(s0)
            # the dissipative figure is the deficit 100 - PCF (the band the friction adds)
            gap, ref = 100.0 - (value or 0.0), 100.0 - stats["pcf_compression_percent"]
            if value is not None and abs(gap - ref) > OFFSET_TOLERANCE * max(abs(ref), abs(gap), 1e-12):
                offsets["offset_sensitive_statistics"] = ["pcf_compression_percent"]
        if offsets["offset_sensitive_statistics"]:
            shown = [
                f"{format_quantity(starts[tag], 'm', 'mm', 3)}: {offsets[f'pcf_compression_at_{tag}_offset_percent']:.4g} %"
                for tag in ("half", "double")
                if offsets[f"pcf_compression_at_{tag}_offset_percent"] is not None
            ]
            offsets["notes"] = [
                f"PRELOAD OFFSET: the compression branch's PCF over the working range from "
                f"{format_quantity(start, 'm', 'mm', 3)} is {stats['pcf_compression_percent']:.4g} %, from "
                f"{' and from '.join(shown)} (its deficit 100 - PCF, the band the friction adds, moves by more than "
                f"{100 * OFFSET_TOLERANCE:g} %: tau_AF of Eq. (22) turned into a slider force goes as 1/theta2); the "
                "offset is the installation's preload, not a property of the spring: give the application's (--offset)"
            ]
        in_zone = bool(np.any(th[work] < p.toggle_cutoff))
        dominated, check = [], {}
        if in_zone:
            fd2 = branches(_double_cutoff(p.toggle_cutoff))
            check = {"pcf_compression_percent": percent_constant_force((f + fd2)[work])}
            dominated = toggle_check(stats, check, stats)
        f_zero = (
            beam_force_at_toggle(p.r2, p.r3, p.pivot_length, p.bending_stiffness("beam"))
            if self.beam
            else static_force_at_toggle(p.k3, p.r2, p.r3)
        )
        summary = {
            "force_at_zero_N": float(f_zero),
            "force_max_N": float(fmax),
            "deflection_at_force_max_m": float(xmax),
            "force_min_N": float(np.min(f)),
            "pcf_percent": 100.0 * float(np.min(f)) / float(fmax),
            "pcf_energy_percent": percent_constant_force_energy(x, f),
            **stats,
            "pcf_working_percent": percent_constant_force(f[work]),
            "working_start_m": float(start),
            "working_end_m": float(stroke),
            **{k: v for k, v in offsets.items() if k != "notes"},
            "stroke_m": stroke,
            "kinematic_limit_m": p.max_deflection,
            **self._stress_summary(th, x, stress),
            **self._common_summary(),
            **self._toggle_summary(in_zone, dominated, check),
        }
        if self.beam:
            pm, pxm = _refined_max(
                x, f_prbm, lambda xx: static_force(theta2_from_deflection(xx, p.r2, p.r3), p.k3, p.r2, p.r3)
            )
            summary.update(
                {
                    "prbm_force_max_N": float(pm),
                    "prbm_deflection_at_force_max_m": float(pxm),
                    "prbm_pcf_percent": 100.0 * float(np.min(f_prbm)) / float(pm),
                    "max_force_difference_to_prbm_N": float(np.max(np.abs(f - f_prbm))),
                    "prbm_max_stress_Pa": float(np.max(extra["stress_prbm_Pa"])),
                }
            )
        summary.setdefault("notes", []).extend(offsets.get("notes", []))
        if not self.beam:
            check, fb = self._beam_check_on(x, 0.0, start)
            summary.setdefault("notes", []).extend(check.pop("notes"))
            summary.update(check)
            if fb is not None:
                extra["force_beam_N"] = fb
        return StaticResult(x, th, f, f + fd, f - fd, stress, self._note_nulls(summary), extra)

    def _toggle_summary(self, in_zone: bool, dominated: list, check: dict) -> dict:
        """The toggle flag of a result: which statistics a factor 2 in the cut-off moves by > 1 %."""
        out = {"toggle_dominated": bool(dominated), "toggle_dominated_statistics": list(dominated)}
        if in_zone:
            out["toggle_cutoff_doubled_rad"] = _double_cutoff(self.params.toggle_cutoff)
            out["statistics_at_doubled_cutoff"] = dict(check)
        notes = []
        if dominated:
            notes.append(
                f"toggle-dominated: {', '.join(dominated)} change by more than "
                f"{100 * TOGGLE_TOLERANCE:g} % when the toggle cut-off doubles; they depend on a numerical "
                "setting, not on the mechanism (start the motion from a preload offset inside the "
                "constant-force band, or give the drive's stiffness, drive_stiffness / --drive-stiffness, to "
                "integrate the crank through the toggle with its inertia: CFCS.driven)"
            )
        elif in_zone:
            notes.append(
                "the motion enters the toggle zone, but no statistic changes by more than "
                f"{100 * TOGGLE_TOLERANCE:g} % when the cut-off doubles"
            )
        out["notes"] = notes
        return out

    # -- inverse dynamics ---------------------------------------------------------------
    def motion(self, omega=None, amplitude=DEFAULT_AMPLITUDE, offset=DEFAULT_OFFSET, csv=None):
        """Build the prescribed motion: the default sinusoid or a periodic CSV (see :mod:`.motion`).

        Parameters
        ----------
        omega : float, optional
            Angular frequency of the motion [rad/s].
        amplitude : float or str
            Amplitude, a length or a fraction of r2 + r3 [m or %].
        offset : float or str
            Smallest deflection, a length or a fraction of r2 + r3 [m or %].
        csv : str or Path, optional
            A periodic motion table (``time_s, deflection_m``) [-].
        """
        p = self.params
        if csv is not None:
            mot = TabulatedMotion.from_csv(csv, omega=omega)
        else:
            if omega is None:
                raise InputError("omega is required for the sinusoidal input (or give a motion CSV)")
            omega = to_si(omega, "rad/s", "omega", bare_unit="rad/s")
            if not omega > 0:
                raise InputError(f"omega = {omega:g} rad/s must be positive")
            off = offset_to_si(offset, p.extended_length)
            mot = SinusoidMotion(omega, amplitude_to_si(amplitude, p.extended_length), off)
        lo, hi = mot.bounds
        check_stroke(lo, hi, p.max_deflection, f"the motion {mot.describe()}")
        return mot

    def dynamic(
        self,
        omega=None,
        amplitude=DEFAULT_AMPLITUDE,
        offset=DEFAULT_OFFSET,
        *,
        cycles: int = 2,
        samples_per_cycle: int = 400,
        motion=None,
        offset_sensitivity: bool = True,
    ) -> DynamicResult:
        """Slider force along a prescribed periodic motion (inverse dynamics, Eqs. (19)-(25)).

        The slider follows the motion rigidly (``drive_stiffness`` of the parameters is not used
        here: :meth:`driven` is the same motion through the compliant drive, and the CLI's
        ``cfcs dynamic`` switches to it when a drive stiffness is given).

        Parameters
        ----------
        omega : float, optional
            Circular frequency [rad/s] of the sinusoid (required unless ``motion`` is given).
        amplitude : float or str
            Stroke of the sinusoid: a length [m] (a bare number is metres) or a percentage of
            r2 + r3 such as "40 %" (the default).
        offset : float or str
            Deflection at t = 0 [m], or a percentage of r2 + r3 (default :data:`DEFAULT_OFFSET`,
            a preload inside the constant-force band).  A motion that enters the toggle zone
            (crank angle below ``toggle_cutoff``) has its statistics computed at the cut-off and
            at twice it; ``toggle_dominated`` flags those that change by more than 1 %.
        cycles, samples_per_cycle : int
            Time grid [-]; statistics use whole cycles.
        motion : SinusoidMotion or TabulatedMotion, optional
            A ready-made motion (overrides omega/amplitude/offset).
        offset_sensitivity : bool
            Also give the statistics with the sinusoid started at half and at twice its offset
            (``statistics_at_half_offset``, ``statistics_at_double_offset``, ``offset_sensitive_statistics``
            and a note): the dissipative figures depend on where the motion starts, as tau_AF of Eq. (22)
            turned into a slider force goes as ``1/theta2`` (issue 40) [-].
        """
        p = self.params
        if not (isinstance(cycles, (int, np.integer)) and cycles >= 1):
            raise InputError(f"cycles = {cycles!r} must be a whole number >= 1")
        if not (isinstance(samples_per_cycle, (int, np.integer)) and samples_per_cycle >= 8):
            raise InputError(f"samples_per_cycle = {samples_per_cycle!r} must be a whole number >= 8")
        mot = motion if motion is not None else self.motion(omega, amplitude, offset)
        if motion is not None:
            lo, hi = mot.bounds
            check_stroke(lo, hi, p.max_deflection, f"the motion {mot.describe()}")
        n = cycles * samples_per_cycle
        t = np.arange(n + 1) * (mot.period / samples_per_cycle)
        lo_hi = (0.0, p.max_deflection)

        def clipped(tt):  # spline/rounding noise at the ends only (the bounds were checked)
            x, xd, xdd = mot(tt)
            return np.clip(x, *lo_hi), xd, xdd

        vals = self._values(hi=mot.bounds[1])
        c = inverse_dynamics(clipped, t, mot.period, theta2_cutoff=p.toggle_cutoff, **vals)
        x, xd = c["deflection"], c["velocity"]
        f = c["force"]
        stats = _dynamic_stats(t, f, xd, samples_per_cycle)
        in_zone = bool(np.any(c["in_toggle_zone"]))
        dominated, check = [], {}
        if in_zone:
            c2 = inverse_dynamics(clipped, t, mot.period, theta2_cutoff=_double_cutoff(p.toggle_cutoff), **vals)
            check = _dynamic_stats(t, c2["force"], xd, samples_per_cycle)
            dominated = toggle_check(stats, check, _DYNAMIC_STATS)
        summary = {
            "omega_rad_per_s": float(mot.omega),
            "motion": mot.describe(),
            **stats,
            "toggle_zone_samples": int(np.count_nonzero(c["in_toggle_zone"])),
            "toggle_limit_samples": int(np.count_nonzero(c["at_toggle"])),
            **self._stress_summary(c["theta2"], x),
            **self._common_summary(),
            **self._beam_dynamics_summary(mot.omega),
            **self._toggle_summary(in_zone, dominated, check),
        }
        if offset_sensitivity:
            extra = self._offset_sensitivity(mot, t, stats, samples_per_cycle)
            summary["notes"] = list(summary.get("notes", [])) + extra.pop("notes", [])
            summary.update(extra)
        self._add_beam_check(summary, float(np.max(x)), float(np.min(x)))
        comps = {k: c[k] for k in ("force_inertia", "force_pin", "force_axial", "force_slider")}
        return DynamicResult(
            t, x, xd, c["theta2"], f, c["force_static"], comps, c["in_toggle_zone"], self._note_nulls(summary)
        )

    def _offset_sensitivity(self, mot, t, stats: dict, samples_per_cycle: int) -> dict:
        """The statistics of a sinusoid started at half and at twice its offset (None beyond the kinematic
        limit, or for a motion that is not a sinusoid from a positive offset), and a note."""
        p = self.params
        out = {
            "offset_m": None,
            "statistics_at_half_offset": None,
            "statistics_at_double_offset": None,
            "offset_sensitive_statistics": [],
        }
        if not (isinstance(mot, SinusoidMotion) and mot.offset > 0):
            return out
        out["offset_m"] = float(mot.offset)
        changed, parts = set(), []
        for tag, factor in (("half", 0.5), ("double", 2.0)):
            other = dataclasses.replace(mot, offset=factor * mot.offset)
            lo, hi = other.bounds
            if hi > p.max_deflection:
                parts.append(f"at twice the offset the motion passes the kinematic limit ({tag}: not computed)")
                continue
            vals = self._values(hi=hi)

            def clipped(tt, other=other):
                x, xd, xdd = other(tt)
                return np.clip(x, 0.0, p.max_deflection), xd, xdd

            c = inverse_dynamics(clipped, t, other.period, theta2_cutoff=p.toggle_cutoff, **vals)
            st = {k: v for k, v in _dynamic_stats(t, c["force"], c["velocity"], samples_per_cycle).items()}
            st["offset_m"] = float(other.offset)
            st["toggle_zone_samples"] = int(np.count_nonzero(c["in_toggle_zone"]))
            out[f"statistics_at_{tag}_offset"] = st
            for k in _OFFSET_STATS:
                a, b = stats[k], st[k]
                if abs(b - a) > OFFSET_TOLERANCE * max(abs(a), abs(b)) and abs(b - a) > 1e-12:
                    changed.add(k)
            parts.append(
                f"{format_quantity(other.offset, 'm', 'mm', 3)}: peak-to-peak {st['peak_to_peak_N']:.4g} N "
                f"({_change(stats['peak_to_peak_N'], st['peak_to_peak_N'])}), largest {st['force_max_N']:.4g} N, "
                f"PCF {st['pcf_percent']:.3g} %, hysteresis {st['hysteresis_energy_per_cycle_J']:.3g} J"
                + (" (in the toggle zone)" if st["toggle_zone_samples"] else "")
            )
        out["offset_sensitive_statistics"] = [k for k in _OFFSET_STATS if k in changed]
        if changed:
            out["notes"] = [
                f"PRELOAD OFFSET: {', '.join(out['offset_sensitive_statistics'])} move by more than "
                f"{100 * OFFSET_TOLERANCE:g} % when the motion starts at half or twice its offset "
                f"{format_quantity(mot.offset, 'm', 'mm', 3)} (tau_AF of Eq. (22) turned into a slider force goes "
                f"as 1/theta2): from {'; from '.join(parts)}. The offset is the installation's preload, not a "
                "property of the spring: give the application's (--offset)"
            ]
        return out

    def sweep(
        self,
        omegas,
        amplitude=DEFAULT_AMPLITUDE,
        offset=DEFAULT_OFFSET,
        *,
        samples_per_cycle: int = 400,
        quiet: bool = True,
    ) -> FrequencySweep:
        """Mean, median, peak-to-peak force and PCF vs omega (Figs. 5-7 of the CFCS paper).

        Each frequency is one whole cycle of the sinusoid (the inverse problem has no
        transient); the statistics are given as configured and without tau_CF, tau_AF
        and slider friction (``*_no_dissipation_*``), and the peak-to-peak force and the PCF
        with the sinusoid started at half and at twice the offset (``peak_to_peak_at_half_offset_N``,
        ``..._at_double_offset_...``; issue 40: they depend on it through tau_AF).

        Parameters
        ----------
        omegas : array_like
            Angular frequencies [rad/s].
        amplitude : float or str
            Amplitude, a length or a fraction of r2 + r3 [m or %].
        offset : float or str
            Smallest deflection [m or %].
        samples_per_cycle : int
            Samples per cycle [-].
        quiet : bool
            No progress bar [-].
        """
        omegas = np.atleast_1d(np.asarray(omegas, dtype=float))
        if omegas.size == 0 or np.any(~np.isfinite(omegas)) or np.any(omegas <= 0):
            bad = omegas[~(omegas > 0)] if omegas.size else omegas
            raise InputError(f"omega = {bad[0] if bad.size else 'empty'!r}: every omega must be positive")
        if np.any(omegas > MAX_OMEGA):
            raise InputError(
                f"omega = {omegas.max():g} rad/s is beyond {MAX_OMEGA:g} rad/s: far above any motion of "
                "a constant-force mechanism (its inertia forces would overflow)"
            )
        ideal = CFCS(self.params.without_dissipation())
        names = ("mean_force", "median_force", "peak_to_peak", "pcf")
        stats = {f"{k}_{'percent' if k == 'pcf' else 'N'}": np.empty(omegas.size) for k in names}
        stats.update({f"{k}_no_dissipation_{'percent' if k == 'pcf' else 'N'}": np.empty(omegas.size) for k in names})
        keys = {
            "mean_force": "mean_force_N",
            "median_force": "median_force_N",
            "peak_to_peak": "peak_to_peak_N",
            "pcf": "pcf_percent",
        }
        zone = 0
        flags = np.zeros(omegas.size)
        dominated = set()
        at_offsets = {}
        for i, w in enumerate(progress(omegas, total=omegas.size, desc="cfcs sweep", quiet=quiet)):
            for model, suffix in ((self, ""), (ideal, "_no_dissipation")):
                r = model.dynamic(
                    w, amplitude, offset, cycles=1, samples_per_cycle=samples_per_cycle, offset_sensitivity=not suffix
                )
                for k, src in keys.items():
                    unit = "percent" if k == "pcf" else "N"
                    stats[f"{k}{suffix}_{unit}"][i] = r.summary[src]
                for tag in ("half", "double") if not suffix else ():
                    st = r.summary[f"statistics_at_{tag}_offset"]
                    if st is not None:
                        at_offsets.setdefault(f"peak_to_peak_at_{tag}_offset_N", np.empty(omegas.size))[i] = st[
                            "peak_to_peak_N"
                        ]
                        at_offsets.setdefault(f"pcf_at_{tag}_offset_percent", np.empty(omegas.size))[i] = st[
                            "pcf_percent"
                        ]
                if r.summary["toggle_dominated"]:
                    flags[i] = 1.0
                    dominated.update(
                        f"{s[:-2]}{suffix}{s[-2:]}"
                        if s.endswith("_N")
                        else s.replace("_percent", f"{suffix}_percent")
                        if s.endswith("_percent")
                        else s
                        for s in r.summary["toggle_dominated_statistics"]
                    )
                zone = max(zone, r.summary["toggle_zone_samples"])
        stats.update(at_offsets)
        stats["toggle_dominated"] = flags
        notes = (
            [
                f"toggle-dominated at {int(flags.sum())} of {omegas.size} frequencies ({', '.join(sorted(dominated))}"
                " change by more than 1 % when the toggle cut-off doubles)"
            ]
            if flags.any()
            else []
        )
        summary = {
            "motion": r.summary["motion"].replace(f"{omegas[-1]:.6g} t", "w t"),
            "toggle_zone_samples_per_cycle": zone,
            "toggle_dominated": bool(flags.any()),
            "toggle_dominated_statistics": sorted(dominated),
            "notes": notes,
            **self._common_summary(),
        }
        lo, hi = self.motion(omegas[-1], amplitude, offset).bounds
        self._add_beam_check(summary, hi, lo)
        return FrequencySweep(omegas, stats, summary)

    # -- forward dynamics through a compliant drive ----------------------------------------
    def driven(
        self,
        omega=None,
        amplitude=DEFAULT_AMPLITUDE,
        offset=DEFAULT_OFFSET,
        *,
        motion=None,
        drive_stiffness: float | None = None,
        drive_damping: float | None = None,
        periods: int = DRIVEN_PERIODS,
        samples_per_period: int = DRIVEN_SAMPLES,
        rtol: float = DRIVEN_RTOL,
        max_step: float | None = None,
        sign_smoothing: float = DRIVE_SIGN_SMOOTHING,
        compare_without_axial_friction: bool | None = None,
    ) -> DrivenResult:
        """The slider driven along x_d(t) through a drive spring and damper (forward dynamics).

        The motion is that of :meth:`dynamic` (the sinusoid, or ``motion``) but it moves the far
        end of the drive, which pushes the slider with ``k_d (x_d - x) + c_d (x_d' - x')``
        (:mod:`springdyn.cfcs.drive`).  The crank angle is integrated, signed, through the toggle
        with the links' inertia, with no cut-off; the statistics are those of the drive force over
        the last of ``periods`` periods, and ``periodicity_change_percent`` says how much they
        moved from the period before (a note when more than 1 %).  The energy balance
        ``W = Delta(T + V + V_d) + D_f + D_c`` is reported with its residual.

        A crank that rests within the shear angle alpha of the toggle for more than 1 % of the last
        period is flagged ``toggle_sticking`` (share, stop angle, release force): it is held there by
        tau_AF of Eq. (22) taken with the static force, which inside alpha is not a model of the
        mechanism, and the peak force is set by that term.  Whenever the crank comes within alpha
        the same run without tau_AF (pin and slider friction only) is repeated and its statistics
        reported beside the headline (``peak_to_peak_without_axial_friction_N`` etc.; about 1.3 s
        more for the seed's case), with a note when tau_AF changes the peak-to-peak by more than 10 %.

        A drive stiff enough to be rigid is not integrated (issue 40: 1e9 N/m took 49 s, 1e15 N/m did not
        end): when ``k_d / (m_eff omega^2)``, the squared ratio of the slider's frequency on the drive to the
        motion's (``m_eff = M / G^2``, the largest over the motion), is at least
        :data:`~springdyn.cfcs.drive.RIGID_DRIVE_FREQUENCY_RATIO` and the drive deflects at most
        :data:`~springdyn.cfcs.drive.RIGID_DRIVE_LAG` of the stroke under the largest spring force, the result
        is the rigid drive's, :meth:`dynamic` over one period (a :class:`DynamicResult`, ``rigid_drive`` true,
        with a note); a motion into the toggle zone with such a drive is refused (the rigid drive has no
        finite force there).  Every result carries the ratios (``drive_frequency_ratio_squared``,
        ``drive_lag_share``, ``drive_damping_ratio``, ``rigid_drive_stiffness_N_per_m``).

        Parameters
        ----------
        omega : float, optional
            Circular frequency of the sinusoid [rad/s] (required unless ``motion`` is given).
        amplitude : float or str
            Stroke of the sinusoid, a length or a percentage of r2 + r3 [m or %].
        offset : float or str
            Drive position at t = 0, a length or a percentage of r2 + r3 [m or %]; 0 works the
            mechanism through its toggle.
        motion : SinusoidMotion or TabulatedMotion, optional
            A ready-made motion of the drive (overrides omega/amplitude/offset) [m].
        drive_stiffness : float, optional
            k_d [N/m] (default: ``drive_stiffness`` of the parameters; one of the two is required).
        drive_damping : float, optional
            c_d [N*s/m] (default: ``drive_damping`` of the parameters).
        periods : int
            Periods integrated [-]; statistics over the last one.
        samples_per_period : int
            Output samples per period [-] (the statistics are taken on them).
        rtol : float
            Relative tolerance of the integrator [-].
        max_step : float, optional
            Largest integration step [s] (default period / 400).
        sign_smoothing : float
            Speed v_s of the smoothed Coulomb sign tanh(theta2'/v_s) [rad/s].
        compare_without_axial_friction : bool, optional
            Repeat the run without tau_AF: ``None`` (default) when the crank comes within the shear
            angle of the toggle and tau_AF is on, ``True`` whenever tau_AF is on, ``False`` never [-].
        """
        p = self.params
        k_d = p.drive_stiffness if drive_stiffness is None else float(drive_stiffness)
        c_d = p.drive_damping if drive_damping is None else float(drive_damping)
        if k_d is None:
            raise InputError(
                "the compliant drive needs drive_stiffness (the stiffness of what pushes the slider, e.g. "
                '"20 kN/m") in [cfcs] or as an argument'
            )
        if not (np.isfinite(k_d) and k_d > 0):
            raise InputError(f"drive_stiffness = {k_d!r} N/m must be a positive number")
        if not (np.isfinite(c_d) and c_d >= 0):
            raise InputError(f"drive_damping = {c_d!r} N*s/m must be zero or positive")
        if not (isinstance(periods, (int, np.integer)) and periods >= 2):
            raise InputError(f"periods = {periods!r} must be a whole number >= 2 (the last two are compared)")
        if not (isinstance(samples_per_period, (int, np.integer)) and samples_per_period >= 50):
            raise InputError(f"samples_per_period = {samples_per_period!r} must be a whole number >= 50")
        if not (0 < rtol < 1e-2):
            raise InputError(f"rtol = {rtol!r} must lie in (0, 0.01)")
        if not sign_smoothing > 0:
            raise InputError(f"sign_smoothing = {sign_smoothing!r} rad/s must be positive")
        mot = motion if motion is not None else self.motion(omega, amplitude, offset)
        if motion is not None:
            lo, hi = mot.bounds
            check_stroke(lo, hi, p.max_deflection, f"the motion {mot.describe()}")
        period = mot.period
        h = period / 400.0 if max_step is None else float(max_step)
        if not h > 0:
            raise InputError(f"max_step = {max_step!r} s must be positive")
        stiffness = self._drive_stiffness_ratios(mot, k_d, c_d)
        if stiffness["rigid_drive"]:
            return self._rigid_drive(mot, stiffness, samples_per_period)
        vals = self._values(hi=p.max_deflection if self.beam else None)
        # start at rest where the drive balances the static force at t = 0 (away from the toggle)
        xd0 = float(mot(np.array([0.0]))[0][0])
        floor = 1e-4 * p.extended_length
        x0 = xd0 - float(self.spring_force(max(xd0, floor))) / k_d
        x0 = min(max(x0, floor), p.max_deflection)
        th0 = float(theta2_from_deflection(x0, p.r2, p.r3))
        t = np.arange(periods * samples_per_period + 1) * (period / samples_per_period)
        f_ref = float(static_force_at_toggle(p.k3, p.r2, p.r3))
        e_scale = f_ref * p.extended_length
        y = integrate_driven(
            mot, k_d, c_d, vals, t, th0, 0.0, sign_smoothing=sign_smoothing, rtol=rtol, max_step=h, energy_scale=e_scale
        )
        th, thd = y[0], y[1]
        x = deflection_from_theta2(th, p.r2, p.r3)
        v = slider_jacobian(th, p.r2, p.r3) * thd
        xd_all = mot(t)
        xd, vd = np.asarray(xd_all[0], dtype=float), np.asarray(xd_all[1], dtype=float)
        f = drive_force(xd, vd, x, v, k_d, c_d)
        fs = self.spring_force(x) if self.beam else static_force(th, p.k3, p.r2, p.r3)
        strain = self._beam_table(p.max_deflection)["force"].antiderivative() if self.beam else None
        residual = energy_balance(th, thd, xd, y[2], y[3], y[4], k_d, vals, strain)
        n = samples_per_period
        last, prev = slice(len(t) - 1 - n, len(t)), slice(len(t) - 1 - 2 * n, len(t) - n)
        stats = _dynamic_stats(t[last], f[last], v[last], n)
        before = _dynamic_stats(t[prev], f[prev], v[prev], n)
        scale = max(stats["peak_to_peak_N"], 1e-12 * f_ref)
        change = max(
            abs(stats[k] - before[k]) for k in ("mean_force_N", "peak_to_peak_N", "force_max_N", "force_min_N")
        )
        work_total = float(y[2][-1] - y[2][0])
        gross = float(np.sum(np.abs(np.diff(y[2])))) or e_scale
        summary = {
            "omega_rad_per_s": float(mot.omega),
            "motion": "drive " + mot.describe().replace("x(t)", "x_d(t)"),
            **stiffness,
            **stats,
            "actuator_work_per_cycle_J": float(y[2][-1] - y[2][-1 - n]),
            "periodicity_change_percent": 100.0 * change / scale,
            "energy_balance_residual_J": float(np.max(np.abs(residual))),
            "energy_balance_relative": float(np.max(np.abs(residual))) / gross,
            "actuator_work_J": work_total,
            "deflection_min_m": float(np.min(x[last])),
            "deflection_max_m": float(np.max(x[last])),
            "drive_lag_max_m": float(np.max(np.abs(xd[last] - x[last]))),
            "toggle_crossings_per_period": int(np.count_nonzero(np.diff(np.sign(th[last])) != 0)),
            "periods": int(periods),
            "samples_per_period": int(n),
            "rtol": float(rtol),
            "max_step_s": float(h),
            "sign_smoothing_rad_per_s": float(sign_smoothing),
            **self._stress_summary(th[last], x[last]),
            **self._common_summary(),
            **self._beam_dynamics_summary(mot.omega),
        }
        summary["toggle_cutoff_rad"] = None  # integrated through the toggle: no cut-off
        notes = summary.setdefault("notes", [])
        rest = TOGGLE_REST_FACTOR * sign_smoothing
        share, stop, release = toggle_sticking(th[last], thd[last], f[last], p.shear_angle, rest)
        sticking = share > TOGGLE_STICKING_SHARE
        summary.update(
            toggle_sticking=bool(sticking),
            toggle_sticking_share=share,
            toggle_stop_angle_rad=stop,
            toggle_stop_angle_over_shear_angle=None if stop is None else abs(stop) / p.shear_angle,
            toggle_release_force_N=release,
            toggle_rest_speed_rad_per_s=float(rest),
            toggle_zone_share=float(np.mean(np.abs(th[last]) < p.shear_angle)),
        )
        held_by = (
            "the axial-force friction term tau_AF of Eq. (22), taken with the static force F_static inside the "
            "shear angle, where docs/cfcs.md says (22) is not a model of the mechanism (it would lock it)"
            if p.axial_force
            else "the pin friction (the axial-force term is off)"
        )
        if sticking:
            notes.append(
                f"TOGGLE STICKING: the crank rests at theta2 = {stop * 1e3:.3g} mrad ({abs(stop) / p.shear_angle:.2g} "
                f"of the shear angle alpha = {p.shear_angle:g} rad) for {100 * share:.3g} % of the period, held by "
                f"{held_by}, until the drive reaches {release:.4g} N; the peak force is set by that term, not by "
                "the mechanism"
            )
        if stop is None:
            notes.append(
                "toggle_stop_angle_rad, toggle_release_force_N: null, the crank never rests within the shear angle "
                "of the toggle"
            )
        entered = summary["toggle_zone_share"] > 0
        compare = entered if compare_without_axial_friction is None else bool(compare_without_axial_friction)
        compare = compare and p.axial_force
        other = None
        if compare:
            other = (
                self.__class__(p.replace(axial_force=False))
                .driven(
                    motion=mot,
                    drive_stiffness=k_d,
                    drive_damping=c_d,
                    periods=periods,
                    samples_per_period=samples_per_period,
                    rtol=rtol,
                    max_step=h,
                    sign_smoothing=sign_smoothing,
                    compare_without_axial_friction=False,
                )
                .summary
            )
        for k in _WITHOUT_AF:
            name, unit = k.rsplit("_", 1)
            summary[f"{name}_without_axial_friction_{unit}"] = None if other is None else other[k]
        summary["periodicity_change_without_axial_friction_percent"] = (
            None if other is None else other["periodicity_change_percent"]
        )
        summary["toggle_sticking_without_axial_friction"] = None if other is None else other["toggle_sticking"]
        if other is not None:
            notes.append(
                f"without tau_AF (pin friction tau_CF and slider friction only) the same run gives "
                f"{other['force_min_N']:.4g} .. {other['force_max_N']:.4g} N, peak-to-peak "
                f"{other['peak_to_peak_N']:.4g} N" + (" (its crank sticks too)" if other["toggle_sticking"] else "")
            )
            change = abs(stats["peak_to_peak_N"] - other["peak_to_peak_N"]) / max(other["peak_to_peak_N"], 1e-12)
            if not sticking and entered and change > AXIAL_FRICTION_EFFECT:
                notes.append(
                    f"the crank passes within the shear angle alpha = {p.shear_angle:g} rad of the toggle without "
                    f"stopping, but tau_AF of Eq. (22), taken with F_static there, changes the peak-to-peak force "
                    f"by {100 * change:.3g} % ({other['peak_to_peak_N']:.4g} N without it): inside alpha (22) is not "
                    "a model of the mechanism"
                )
        elif not p.axial_force:
            notes.append(
                "*_without_axial_friction_*: axial_force is off, the statistics above are already without tau_AF"
            )
        else:
            notes.append(
                "*_without_axial_friction_*: the crank never comes within the shear angle of the toggle, so the run "
                "without tau_AF is not repeated (compare_without_axial_friction=True repeats it)"
            )
        if summary["periodicity_change_percent"] > 100 * DRIVEN_PERIODICITY:
            notes.append(
                f"not periodic yet: the statistics moved by {summary['periodicity_change_percent']:.3g} % of the "
                f"peak-to-peak force from period {periods - 1} to {periods}; integrate more periods"
            )
        self._add_beam_check(summary, float(np.max(x[last])), float(np.min(x[last])))
        return DrivenResult(t, xd, x, v, th, thd, f, fs, y[2], y[3], y[4], residual, self._note_nulls(summary))

    def _drive_stiffness_ratios(self, mot, k_d: float, c_d: float) -> dict:
        """How stiff the drive is for this motion: ``(w_n/omega)^2 = k_d / (m_eff omega^2)`` with the largest
        slider-referred mass over the motion (crank angles from the toggle cut-off up), and the drive's
        deflection under the largest static force over the stroke; rigid when both pass their bounds."""
        p = self.params
        lo, hi = mot.bounds
        x_cut = float(deflection_from_theta2(p.toggle_cutoff, p.r2, p.r3))
        x = np.linspace(max(lo, x_cut), max(hi, x_cut), 101)
        th = theta2_from_deflection(x, p.r2, p.r3)
        m_eff = float(np.max(slider_effective_mass(th, p.crank_mass, p.coupler_mass, p.slider_mass, p.r2, p.r3)))
        xs = np.linspace(max(lo, 0.0), hi, 101)
        f_max = float(np.max(np.abs(self.spring_force(xs))))
        ratio = k_d / (m_eff * mot.omega**2)
        lag = f_max / (k_d * max(hi - lo, 1e-12))
        return {
            "rigid_drive": bool(ratio >= RIGID_DRIVE_FREQUENCY_RATIO and lag <= RIGID_DRIVE_LAG),
            "drive_stiffness_N_per_m": float(k_d),
            "drive_damping_N_s_per_m": float(c_d),
            "drive_frequency_ratio_squared": float(ratio),
            "drive_lag_share": float(lag),
            "drive_damping_ratio": float(c_d / (2.0 * np.sqrt(k_d * m_eff))),
            "slider_effective_mass_kg": m_eff,
            "rigid_drive_stiffness_N_per_m": float(
                max(RIGID_DRIVE_FREQUENCY_RATIO * m_eff * mot.omega**2, f_max / (RIGID_DRIVE_LAG * max(hi - lo, 1e-12)))
            ),
            "enters_toggle_zone": bool(lo < x_cut),
        }

    def _rigid_drive(self, mot, stiffness: dict, samples_per_period: int) -> DynamicResult:
        """A drive stiff enough to be rigid: the inverse dynamics of :meth:`dynamic` over one period."""
        p = self.params
        k_d = stiffness["drive_stiffness_N_per_m"]
        bound = (
            f"(w_n/omega)^2 = k_d / (m_eff omega^2) >= {RIGID_DRIVE_FREQUENCY_RATIO:g} and a drive deflection under "
            f"the largest spring force <= {RIGID_DRIVE_LAG:g} of the stroke"
        )
        if stiffness["enters_toggle_zone"]:
            raise InputError(
                f"drive_stiffness = {k_d:.4g} N/m is a rigid drive for this motion ({bound}), and the motion "
                f"reaches the toggle (crank angles below toggle_cutoff = {p.toggle_cutoff:.4g} rad), where the "
                "rigid drive's force has no finite value (it scales with the cut-off: cfcs dynamic without a drive "
                "flags it toggle-dominated); give a drive below "
                f"{stiffness['rigid_drive_stiffness_N_per_m']:.3g} N/m, or start the motion from a preload offset"
            )
        res = self.dynamic(motion=mot, cycles=1, samples_per_cycle=samples_per_period)
        s = res.summary
        s.update(stiffness)
        s["motion"] = "drive " + s["motion"].replace("x(t)", "x_d(t)") + " (rigid: the slider follows it)"
        note = (
            f"RIGID DRIVE: k_d = {k_d:.4g} N/m (rigid from {stiffness['rigid_drive_stiffness_N_per_m']:.3g} N/m) gives (w_n/omega)^2 = {stiffness['drive_frequency_ratio_squared']:.3g} "
            f"(m_eff = {stiffness['slider_effective_mass_kg']:.3g} kg) and deflects "
            f"{stiffness['drive_lag_share']:.2g} of the stroke under the largest spring force; with {bound} the "
            "slider follows the motion (without friction a critically damped drive at the bound is within 0.03 % of "
            "the peak-to-peak), so this is the inverse dynamics of the rigid drive (one period, no integration)"
        )
        if stiffness["drive_damping_ratio"] < 1.0:
            note += (
                f"; with a damping ratio of {stiffness['drive_damping_ratio']:.2g} a real drive rings after each "
                "reversal of the friction, with an overshoot set by the damping ratio, not the stiffness "
                "(docs/cfcs.md, the rigid limit), which this result does not hold"
            )
        s.setdefault("notes", []).insert(0, note)
        return res

    # -- forward dynamics ---------------------------------------------------------------
    def forward(
        self,
        t_end: float,
        *,
        force: float | Callable | None = None,
        base_motion: Callable | None = None,
        base_stiffness: float | None = None,
        base_damping: float = 0.0,
        x0: float = 1e-3,
        v0: float = 0.0,
        n: int = 2001,
        sign_smoothing: float = 1e-2,
        rtol: float = 1e-9,
    ) -> ForwardResult:
        """Integrate the slider's response to a force, or to a spring from a moving base.

        Parameters
        ----------
        t_end : float
            End time [s].
        force : float or callable, optional
            Slider force [N] (positive in compression), constant or ``force(t)``.
        base_motion : callable, optional
            ``base_motion(t) -> x_b`` or ``(x_b, x_b', ...)`` [m]; the slider is driven by
            ``k (x_b - x) + c (x_b' - x')``.
        base_stiffness, base_damping : float
            k [N/m] and c [N*s/m] of the drive spring.
        x0, v0 : float
            Initial deflection [m] (> 0: the toggle is an equilibrium the slider cannot
            leave) and velocity [m/s].
        n : int
            Output samples [-].
        sign_smoothing : float
            Velocity scale v_s [rad/s] of ``tanh(theta2'/v_s)`` replacing the Coulomb sign.
        rtol : float
            Relative tolerance of the integration [-].
        """
        p = self.params
        if (force is None) == (base_motion is None):
            raise InputError("forward dynamics needs exactly one drive: a force or a base_motion with base_stiffness")
        if base_motion is not None and not (base_stiffness is not None and base_stiffness > 0):
            raise InputError(f"base_stiffness = {base_stiffness!r} N/m must be positive with a base_motion")
        if not t_end > 0:
            raise InputError(f"t_end = {t_end!r} s must be positive")
        if not sign_smoothing > 0:
            raise InputError(f"sign_smoothing = {sign_smoothing!r} rad/s must be positive")
        check_stroke(
            x0, x0, p.max_deflection, f"x0 = {format_quantity(x0, 'm', 'mm')}", "start at a smaller deflection x0"
        )
        th0 = float(theta2_from_deflection(x0, p.r2, p.r3))
        g0 = float(slider_jacobian(th0, p.r2, p.r3))
        if g0 == 0.0 and v0 != 0.0:
            raise InputError("x0 = 0 (the toggle) admits no slider velocity; start at x0 > 0")
        thd0 = v0 / g0 if g0 > 0 else 0.0

        if force is not None and not callable(force):
            x_all = np.linspace(0.0, p.max_deflection, 721)
            scale = float(np.max(np.abs(static_force(theta2_from_deflection(x_all, p.r2, p.r3), p.k3, p.r2, p.r3))))
            if not (np.isfinite(force) and abs(force) <= FORCE_LIMIT_FACTOR * scale):
                raise InputError(
                    f"force = {force!r} N is beyond reason for this mechanism: it must be finite and within "
                    f"{FORCE_LIMIT_FACTOR:g} times its largest spring force ({scale:.4g} N), i.e. +-{FORCE_LIMIT_FACTOR * scale:.4g} N"
                )
        if force is not None:
            force_fn = (lambda t, x, xd, f0=float(force): f0) if not callable(force) else (lambda t, x, xd: force(t))
        else:

            def force_fn(t, x, xd):
                b = base_motion(t)
                xb, vb = (b[0], b[1]) if isinstance(b, tuple) else (b, 0.0)
                return drive_force(xb, vb, x, xd, base_stiffness, base_damping)

        t = np.linspace(0.0, t_end, n)
        vals = self._values(hi=p.max_deflection if self.beam else None)
        th, thd = integrate_forward(force_fn, vals, t, th0, thd0, sign_smoothing=sign_smoothing, rtol=rtol)
        x = deflection_from_theta2(th, p.r2, p.r3)
        xd = slider_jacobian(th, p.r2, p.r3) * thd
        fspring = static_force(th, p.k3, p.r2, p.r3) if not self.beam else self.spring_force(x)
        fapplied = np.array([force_fn(ti, xi, vi) for ti, xi, vi in zip(t, x, xd)], dtype=float)
        summary = {
            "sign_smoothing_rad_per_s": sign_smoothing,
            "x0_m": x0,
            "v0_m_per_s": v0,
            "max_deflection_m": float(np.max(x)),
            "min_deflection_m": float(np.min(x)),
            "toggle_crossings": int(np.count_nonzero(np.diff(np.sign(th)) != 0)),
            **self._stress_summary(th, x),
            **self._common_summary(),
        }
        summary["toggle_cutoff_rad"] = None  # the forward problem needs no cut-off
        self._add_beam_check(summary, float(np.max(x)), float(np.min(x)))
        self._note_nulls(summary)
        if self.beam:  # T + the strip's strain energy, the integral of its quasi-static force
            e = (
                energy(th, thd, vals)
                - spring_energy(th, p.k3, p.r2, p.r3)
                + self._beam_table(p.max_deflection)["force"].antiderivative()(x)
            )
        else:
            e = energy(th, thd, vals)
        return ForwardResult(t, x, xd, th, thd, fapplied, fspring, e, summary)

    def _values(self, hi=None) -> dict:
        """The SI values of the physics functions; with the beam model, its tabulated force over [0, hi]."""
        vals = self.params.values()
        if self.beam:
            table = self._beam_table(max(float(hi), 1e-9))
            vals["spring_force"] = table["force"]
        return vals

    def _beam_dynamics_summary(self, omega: float) -> dict:
        """Where the beam's quasi-static force with the PRBM's inertia holds (beam model only)."""
        p = self.params
        if not self.beam:
            return {}
        ei = p.bending_stiffness("beam")
        # steel-like density assumed for the strip's mass (the [cfcs] table gives no density)
        mass_per_length = 7850.0 * p.pivot_width * p.pivot_thickness
        w1 = strip_first_frequency(ei, mass_per_length, p.pivot_length)
        return {
            "strip_first_frequency_rad_per_s": w1,
            "strip_frequency_ratio": float(omega) / w1,
            "strip_mass_kg": mass_per_length * p.pivot_length,
        }


def _change(reference: float, value: float) -> str:
    """``value`` against ``reference`` as a signed percentage, e.g. ``+35 %``."""
    if reference == 0:
        return "n/a"
    return f"{100.0 * (value / reference - 1.0):+.3g} %"


def _finite(value: float) -> float | None:
    """``value``, or None when it is not a finite number."""
    return float(value) if np.isfinite(value) else None


def _refined_max(x, f, fun=None):
    """Largest value of a sampled curve and where: a bounded search on ``fun`` if given, else the
    vertex of the parabola through the largest sample and its neighbours."""
    i = int(np.argmax(f))
    fmax, xmax = float(f[i]), float(x[i])
    if 0 < i < x.size - 1:
        lo, hi = x[i - 1], x[i + 1]
        if fun is not None:
            res = minimize_scalar(lambda xx: -fun(xx), bounds=(lo, hi), method="bounded", options={"xatol": 1e-10})
            if -res.fun > fmax:
                fmax, xmax = float(-res.fun), float(res.x)
        else:
            coef = np.polyfit(x[i - 1 : i + 2] - x[i], f[i - 1 : i + 2], 2)
            if coef[0] < 0:
                dx = -coef[1] / (2 * coef[0])
                if abs(dx) <= hi - lo:
                    fmax, xmax = float(np.polyval(coef, dx)), float(x[i] + dx)
    return fmax, xmax


def _dynamic_stats(t, f, xd, samples_per_cycle) -> dict:
    """Force statistics of a dynamic record over its whole cycles."""
    whole = f[:-1]
    return {
        "mean_force_N": float(np.mean(whole)),
        "median_force_N": float(np.median(whole)),
        "peak_to_peak_N": float(np.ptp(whole)),
        "pcf_percent": percent_constant_force(whole),
        "force_max_N": float(np.max(whole)),
        "force_min_N": float(np.min(whole)),
        "hysteresis_energy_per_cycle_J": float(_cycle_work(t, f, xd, samples_per_cycle)),
    }


def _cycle_work(t, force, xdot, samples_per_cycle):
    """Work ``int F x' dt`` over the last whole cycle [J] (trapezoid rule)."""
    sl = slice(len(t) - 1 - samples_per_cycle, len(t))
    p = force[sl] * xdot[sl]
    return np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(t[sl]))
