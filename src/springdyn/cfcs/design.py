"""Design of a CFCS for a target constant force over a stroke.

Scaling: with all lengths divided by ``L = r2 + r3`` the static force is
``F = (K3 / L) f(rho, x / L)`` with ``rho = r2 / r3``, so the flatness over a stroke
depends only on ``rho`` and the stroke fraction ``x / L`` (default 0.4, the paper's
"40 %").  The procedure:

1. ``L = stroke / stroke_fraction`` (or given).
2. For ``rho`` on a grid (refined by a bounded search), the PCF ``Fmin/Fmax`` over the
   stroke; the flattest ``rho`` among the designs that meet the limits below.
3. ``K3`` so that the target force is the mid-band ``(Fmin + Fmax)/2``.
4. Flexure: length ``l = pivot_length_ratio * r3`` (default 0.1, the small-length
   flexural-pivot condition of the PRBM, Table 1 has 9.5/95); thickness ``h`` from the
   stress limit at the end of the stroke, ``h = 2 (sigma_allow/n) l / (E theta_K3,max)``;
   width ``b = 12 K3 l / (E h^3)`` (Eq. (1) of the CFCS paper).
5. The design is feasible if ``b <= max_width`` (default ``r3``).  Otherwise no design of
   this length meets the stress limit; the result says so plainly and gives the
   shortest ``r2 + r3`` that would.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from ..core.errors import InputError
from ..core.io import atomic_open
from ..core.plotting import new_figure
from ..core.units import format_quantity
from .beam import beam_force_curve
from .kinematics import kinematic_limit_deflection, spring_angle, theta2_from_deflection
from .pivot import FLEXURE_MODELS, allowable_spring_angle, default_plate_bending, plate_modulus, strip_buckling_load
from .results import _Table
from .statics import percent_constant_force_energy, static_force

__all__ = ["design_flattest", "DesignResult", "design", "normalized_pcf", "min_ratio_for_stroke"]


#: Largest stroke fraction ``stroke / (r2 + r3)`` the design accepts: beyond it the
#: smallest r2/r3 that reaches the stroke exceeds 0.98 (see :func:`min_ratio_for_stroke`).
MAX_STROKE_FRACTION = 0.9


def design_flattest(
    force, stroke, youngs_modulus, allowable_stress, *, max_total_length=None, **kwargs
) -> DesignResult:
    """:func:`design`, then again at the length it suggests when the first one does not hold or is not flat.

    When the design at the first size is not feasible, or its ratio is more than 1 point of
    PCF below the flattest one, and :func:`design` suggests a total length at which the
    flattest ratio fits (``suggested_total_length_m``, within ``max_total_length`` if given),
    the design is repeated at that length.

    Parameters
    ----------
    force : float
        Target constant force [N].
    stroke : float
        Working stroke [m].
    youngs_modulus : float
        Young's modulus of the flexure [Pa].
    allowable_stress : float
        Allowable bending stress of the flexure [Pa].
    max_total_length : float, optional
        Largest r2 + r3 the envelope allows [m].
    **kwargs
        Further arguments of :func:`design`.
    """
    first = design(force, stroke, youngs_modulus, allowable_stress, **kwargs)
    s = first.summary
    longer = s.get("suggested_total_length_m")
    poor = not first.feasible or s["pcf_percent"] < s["pcf_flattest_percent"] - 1.0
    if poor and longer and (max_total_length is None or longer <= max_total_length):
        kwargs = {k: v for k, v in kwargs.items() if k not in ("stroke_fraction", "total_length")}
        return design(force, stroke, youngs_modulus, allowable_stress, total_length=longer, **kwargs)
    return first


def min_ratio_for_stroke(stroke_fraction):
    """Smallest ``r2/r3`` whose kinematic limit reaches ``stroke_fraction (r2 + r3)``.

    The limit is ``L (1 - sqrt((1 - rho)/(1 + rho)))``, so ``rho >= (1 - q^2)/(1 + q^2)``
    with ``q = 1 - stroke_fraction``.

    Parameters
    ----------
    stroke_fraction : float
        Stroke as a fraction of r2 + r3 [-].
    """
    q = 1.0 - stroke_fraction
    return (1.0 - q * q) / (1.0 + q * q)


def _ratio_grid(reach, points):
    """``points`` ratios r2/r3 where the design looks for the flattest force: from the smallest whose
    kinematic limit reaches ``reach (r2 + r3)`` (:func:`min_ratio_for_stroke`; at least 0.02) to 0.995."""
    lo = min(max(min_ratio_for_stroke(reach) * (1 + 1e-9), 0.02), 0.995)
    return np.linspace(lo, 0.995, points)


def _geometry(ratio, total_length):
    r3 = total_length / (1.0 + ratio)
    return ratio * r3, r3


def normalized_pcf(ratio, stroke_fraction, n=401, start_fraction=0.0):
    """PCF [%] over ``[s0, s0 + stroke_fraction] (r2 + r3)`` for ``r2/r3 = ratio`` (independent of K3 and size).

    Parameters
    ----------
    ratio : float
        Crank-to-coupler length ratio r2/r3 [-].
    stroke_fraction : float
        Stroke as a fraction of r2 + r3 [-].
    n : int
        Number of samples along the stroke [-].
    start_fraction : float
        Start of the working range s0 as a fraction of r2 + r3 [-] (0: the toggle).
    """
    r2, r3 = _geometry(ratio, 1.0)
    x = np.linspace(start_fraction, start_fraction + stroke_fraction, n)
    f = static_force(theta2_from_deflection(x, r2, r3), 1.0, r2, r3)
    return 100.0 * float(np.min(f) / np.max(f))


@dataclasses.dataclass(repr=False)
class DesignResult(_Table):
    """A CFCS design and its verification (force curve, PCF, stress)."""

    summary: dict
    deflection: np.ndarray
    force: np.ndarray
    stress: np.ndarray

    dim = "deflection_m"
    title = "constant-force spring design"

    @property
    def feasible(self) -> bool:
        return bool(self.summary["feasible"])

    def _repr_caption(self) -> str:
        return "feasible" if self.feasible else "NOT feasible"

    def columns(self) -> dict:
        return {"deflection_m": self.deflection, "force_N": self.force, "stress_Pa": self.stress}

    def to_params(self, crank_mass, coupler_mass, slider_mass, **extra):
        """A :class:`~springdyn.cfcs.params.CFCSParams` of this design (masses are not designed).

        Parameters
        ----------
        crank_mass, coupler_mass, slider_mass : float
            Link masses [kg] (not designed).
        """
        from .params import CFCSParams

        s = self.summary
        return CFCSParams(
            crank_length=s["crank_length_m"],
            coupler_length=s["coupler_length_m"],
            crank_mass=crank_mass,
            coupler_mass=coupler_mass,
            slider_mass=slider_mass,
            pivot_width=s["pivot_width_m"],
            pivot_thickness=s["pivot_thickness_m"],
            pivot_length=s["pivot_length_m"],
            youngs_modulus=s["youngs_modulus_Pa"],
            allowable_stress=s["allowable_stress_Pa"],
            **{
                "flexure_model": s.get("flexure_model", "prbm"),
                "plate_bending": s.get("plate_bending"),
                "poisson_ratio": s.get("poisson_ratio", 0.3),
                **extra,
            },
        )

    def to_toml(self, path) -> Path:
        """Write a ``[cfcs]`` table of the design (masses to be filled in by the user).

        Parameters
        ----------
        path : str or Path
            The TOML file to write [-].
        """
        s = self.summary
        mm = lambda v: f'"{v * 1e3:.6g} mm"'  # noqa: E731
        text = (
            f"# CFCS designed by springdyn for {s['target_force_N']:.6g} N over {s['stroke_m'] * 1e3:.6g} mm\n"
            f"# PCF {s['pcf_percent']:.2f} %, max pivot stress {s['max_stress_Pa'] / 1e9:.4g} GPa"
            f"{'' if s['feasible'] else ' -- NOT FEASIBLE: ' + s['message']}\n"
            "# The masses are not part of the design: replace them with your own.\n[cfcs]\n"
            f"crank_length = {mm(s['crank_length_m'])}\ncoupler_length = {mm(s['coupler_length_m'])}\n"
            'crank_mass = "0.025 kg"\ncoupler_mass = "0.028 kg"\nslider_mass = "0.087 kg"\n'
            f"pivot_width = {mm(s['pivot_width_m'])}\npivot_thickness = {mm(s['pivot_thickness_m'])}\n"
            f"pivot_length = {mm(s['pivot_length_m'])}\n"
            f'youngs_modulus = "{s["youngs_modulus_Pa"] / 1e9:.6g} GPa"\n'
            f'allowable_stress = "{s["allowable_stress_Pa"] / 1e9:.6g} GPa"\n'
            'friction_model = "none"\naxial_force = false\n'
            f'flexure_model = "{s.get("flexure_model", "prbm")}"\n'
            f"plate_bending = {'true' if s.get('plate_bending') else 'false'}\n"
            f"poisson_ratio = {s.get('poisson_ratio', 0.3):g}\n"
            f"# working range {s.get('working_start_m', 0.0) * 1e3:.6g} .. "
            f"{s.get('working_end_m', s['stroke_m']) * 1e3:.6g} mm of deflection\n"
        )
        with atomic_open(path, "w", encoding="utf-8") as fh:
            fh.write(text)
        return Path(path)

    def _plot(self, ax=None):
        fig, ax = new_figure() if ax is None else (ax.figure, ax)
        s = self.summary
        ax.plot(self.deflection * 1e3, self.force)
        ax.axhline(s["target_force_N"], ls=":", color="k", label="target")
        ax.set_xlabel("slider deflection [mm]")
        ax.set_ylabel("force [N]")
        ax.set_title(
            f"CFCS design r2/r3 = {s['ratio']:.3f}, PCF {s['pcf_percent']:.1f} %, "
            f"{'feasible' if s['feasible'] else 'NOT feasible'}"
        )
        ax.grid(True, alpha=0.3)
        ax.legend()
        return fig


def _flexure(ratio, total_length, stroke, force, modulus, allowable, pivot_length_ratio, n, start=0.0):
    """K3, l, h, b and the force curve for one ratio over ``[start, start + stroke]`` (module docstring)."""
    r2, r3 = _geometry(ratio, total_length)
    x = np.linspace(start, start + stroke, n)
    th = theta2_from_deflection(x, r2, r3)
    f1 = static_force(th, 1.0, r2, r3)
    k3 = force / (0.5 * (np.min(f1) + np.max(f1)))
    length = pivot_length_ratio * r3
    th_max = float(spring_angle(th[-1], r2, r3))
    h = 2.0 * allowable * length / (modulus * th_max)
    b = 12.0 * k3 * length / (modulus * h**3)
    return dict(r2=r2, r3=r3, k3=k3, l=length, h=h, b=b, x=x, th=th, f=k3 * f1)


#: Default safety factor of the design on the allowable stress (static spring-steel practice).
DEFAULT_SAFETY_FACTOR = 1.5
#: Default minimum percent constant force [%] over the working range.
DEFAULT_MIN_PCF = 90.0
#: Default thickness tolerance of the strip [-] (+-5 %: the force goes as h^3, +-15 %).
DEFAULT_THICKNESS_TOLERANCE = 0.05


def _check_design_inputs(given: dict) -> None:
    """Check :func:`design`'s arguments, ``given`` by name (its ``locals()`` on entry)."""
    for name in ("force", "stroke", "youngs_modulus", "allowable_stress", "pivot_length_ratio", "safety_factor"):
        v = given[name]
        if (
            isinstance(v, bool)
            or not isinstance(v, (int, float, np.floating, np.integer))
            or not (np.isfinite(v) and v > 0)
        ):
            raise InputError(f"{name} = {v!r} must be positive (a number in SI units)")
    max_width, min_pcf, tolerance = given["max_width"], given["min_pcf"], given["thickness_tolerance"]
    if max_width is not None and not max_width > 0:
        raise InputError(f"max_width = {max_width!r} must be positive")
    if not 0.0 <= min_pcf < 100.0:
        raise InputError(f"min_pcf = {min_pcf!r} must lie in [0, 100) %")
    if not 0.0 <= tolerance < 0.5:
        raise InputError(f"thickness_tolerance = {tolerance!r} must lie in [0, 0.5) (a fraction of h)")
    flexure_model, plate_bending = given["flexure_model"], given["plate_bending"]
    if flexure_model not in FLEXURE_MODELS:
        raise InputError(
            f"flexure_model = {flexure_model!r} is not allowed; choose one of "
            f"{', '.join(repr(m) for m in FLEXURE_MODELS)}"
        )
    if plate_bending not in (None, True, False):
        raise InputError(f"plate_bending = {plate_bending!r} must be true, false or None (chosen by b/l)")
    poisson_ratio, preload = given["poisson_ratio"], given["preload"]
    if not 0.0 <= poisson_ratio <= 0.49:
        raise InputError(f"poisson_ratio = {poisson_ratio!r} must lie in [0, 0.49]")
    if not (np.isfinite(preload) and preload >= 0):
        raise InputError(f"preload = {preload!r} m must be zero or positive")


def design(
    force,
    stroke,
    youngs_modulus,
    allowable_stress,
    *,
    stroke_fraction=0.4,
    total_length=None,
    pivot_length_ratio=0.1,
    max_width=None,
    safety_factor=DEFAULT_SAFETY_FACTOR,
    n=401,
    min_pcf=DEFAULT_MIN_PCF,
    thickness_tolerance=DEFAULT_THICKNESS_TOLERANCE,
    flexure_model="beam",
    plate_bending=None,
    poisson_ratio=0.3,
    preload=0.0,
) -> DesignResult:
    """Design a CFCS: r2/r3 for the flattest force, then K3 and the flexure (b, h, l), checked.

    The ratio and a first flexure come from the PRBM (module docstring); with
    ``flexure_model = "beam"`` (default) the strip is then re-sized on its elastica, exactly:
    at fixed geometry the elastica's force is proportional to EI and its curvature does not
    depend on EI, so EI is scaled to put the target force at mid-band and the thickness to put
    the peak bending stress (largest curvature) at ``allowable_stress / safety_factor``.

    The design is feasible when every check holds: the width fits (``b <= max_width``), the
    PCF over the working range is at least ``min_pcf``, the strip does not buckle under the
    largest axial load (Euler load ``pi^2 EI / (2 l)^2``, a cantilever, over the safety factor),
    and the peak stress at the upper thickness tolerance ``h (1 + tol)`` stays within the
    allowable stress.  Otherwise ``binding_constraint`` names the check furthest from holding
    and ``suggestions`` the smallest changes of one input that would satisfy it.

    Parameters
    ----------
    force : float
        Target constant force [N] (the middle of the force band).
    stroke : float
        Working stroke [m], from ``preload``.
    youngs_modulus, allowable_stress : float
        Flexure material [Pa].
    stroke_fraction : float
        ``stroke / (r2 + r3)`` [-] when ``total_length`` is not given (default 0.4).
    total_length : float, optional
        ``r2 + r3`` [m].
    pivot_length_ratio : float
        ``l / r3`` [-] (default 0.1).
    max_width : float, optional
        Largest flexure width b [m] (default r3).
    safety_factor : float
        Safety factor on the allowable stress [-] (default :data:`DEFAULT_SAFETY_FACTOR`, 1.5).
    n : int
        Samples of the force curve [-].
    min_pcf : float
        Smallest acceptable percent constant force over the working range [%] (default 90).
    thickness_tolerance : float
        Tolerance of the strip thickness [-] (default 0.05: +-5 %, the force +-15 %).
    flexure_model : {"beam", "prbm"}
        Model the strip is sized and checked with (default "beam").
    plate_bending : bool, optional
        E / (1 - nu^2) for the strip; default: chosen by the width/length ratio (beam model).
    poisson_ratio : float
        nu of the strip [-].
    preload : float
        Start of the working range [m] (default 0, the toggle).
    """
    _check_design_inputs(locals())
    if not (isinstance(n, (int, np.integer)) and 5 <= n <= 100_000):
        raise InputError(f"n = {n!r} must be a whole number from 5 to 100000")
    if total_length is not None:
        if not total_length > stroke + preload:
            raise InputError(
                f"total_length = {format_quantity(total_length, 'm', 'mm')} must exceed the stroke "
                f"{format_quantity(stroke + preload, 'm', 'mm')}"
            )
        stroke_fraction = stroke / total_length
    if isinstance(stroke_fraction, bool) or not (np.isfinite(stroke_fraction) and 0 < stroke_fraction):
        raise InputError(f"stroke_fraction = {stroke_fraction!r} must be positive")
    length = stroke / stroke_fraction
    start_fraction = preload / length
    reach = stroke_fraction + start_fraction
    if not reach <= MAX_STROKE_FRACTION:
        raise InputError(
            f"stroke_fraction = {stroke_fraction!r}"
            + (f" with the preload ({start_fraction:.3g} of r2 + r3)" if preload else "")
            + f" must not exceed {MAX_STROKE_FRACTION:g}: a longer stroke needs a crank within 2 % of the coupler "
            f"length (r2/r3 > {min_ratio_for_stroke(MAX_STROKE_FRACTION):.3f}) and runs into the kinematic limit; "
            "use a longer mechanism (smaller stroke fraction)"
        )
    sigma = allowable_stress / safety_factor
    ratios = _ratio_grid(reach, 200)

    def width_limit(ratio):
        return max_width if max_width is not None else _geometry(ratio, length)[1]

    pcf = np.array([normalized_pcf(r, stroke_fraction, n, start_fraction) for r in ratios])
    widths = np.array(
        [_flexure(r, length, stroke, force, youngs_modulus, sigma, pivot_length_ratio, 3, preload)["b"] for r in ratios]
    )
    ok = (widths <= np.array([width_limit(r) for r in ratios])) & (pcf >= min_pcf)
    any_ok = bool(np.any(ok))
    pool = np.where(ok, pcf, -np.inf) if any_ok else pcf
    i = int(np.argmax(pool))
    best = ratios[i]
    a, b = ratios[max(i - 1, 0)], ratios[min(i + 1, ratios.size - 1)]
    if b > a:
        res = minimize_scalar(
            lambda r: -normalized_pcf(r, stroke_fraction, n, start_fraction),
            bounds=(a, b),
            method="bounded",
            options={"xatol": 1e-6},
        )
        cand = _flexure(res.x, length, stroke, force, youngs_modulus, sigma, pivot_length_ratio, 3, preload)
        if -res.fun > pool[i] and (not any_ok or cand["b"] <= width_limit(res.x)):
            best = float(res.x)
    d = _flexure(best, length, stroke, force, youngs_modulus, sigma, pivot_length_ratio, n, preload)
    pcf_best = float(np.max(pcf))
    wmax = width_limit(best)

    width, h, ei, e_eff, plate = _size_strip(
        d, force, sigma, youngs_modulus, flexure_model, plate_bending, poisson_ratio
    )
    x = d["x"]
    # verification through the model built from the sizes (independent of the sizing algebra)
    from .model import CFCS
    from .params import CFCSParams

    params = CFCSParams(
        crank_length=d["r2"],
        coupler_length=d["r3"],
        crank_mass=1.0,
        coupler_mass=1.0,
        slider_mass=1.0,
        pivot_width=width,
        pivot_thickness=h,
        pivot_length=d["l"],
        youngs_modulus=youngs_modulus,
        allowable_stress=allowable_stress,
        plate_bending=plate,
        poisson_ratio=poisson_ratio,
        flexure_model=flexure_model,
        friction_model="none",
        axial_force=False,
    )
    model = CFCS(params)
    if flexure_model == "beam":
        vc = model.beam_curve(np.concatenate([[0.0], x]) if x[0] > 0 else x)
        f, stress, th_b = (vc[k][-x.size :] for k in ("force", "stress", "theta2"))
        axial = f / np.cos(th_b)
    else:
        f = static_force(d["th"], params.k3, d["r2"], d["r3"])
        stress = model.stress(d["th"])
        axial = f / np.cos(d["th"])
    k3_check = params.k3
    smax = float(np.max(stress))
    pcf_here = 100.0 * float(np.min(f) / np.max(f))
    buckling = strip_buckling_load(params.bending_stiffness(), 2.0 * d["l"])
    tol = thickness_tolerance
    stress_tol = smax * (1.0 + tol)  # stress ~ h at the same curvature
    checks = {
        "width": (width, wmax),
        "pcf": (min_pcf, pcf_here),
        "buckling": (float(np.max(axial)) * safety_factor, buckling),
        "stress_at_thickness_tolerance": (stress_tol, allowable_stress),
    }
    failing = {k: v[0] / v[1] for k, v in checks.items() if v[0] > v[1] * (1 + 1e-9)}
    feasible = not failing
    binding = max(failing, key=failing.get) if failing else None
    need = None
    if "width" in failing or pcf_here < pcf_best - 0.5:
        need = _shortest_length_for_flattest(
            stroke,
            force,
            youngs_modulus,
            sigma,
            pivot_length_ratio,
            max_width,
            length,
            n,
            flexure_model=flexure_model,
            plate_bending=plate_bending,
            poisson_ratio=poisson_ratio,
            preload=preload,
        )
    suggestions = _suggestions(
        failing,
        width=width,
        wmax=wmax,
        sigma=sigma,
        pivot_length_ratio=pivot_length_ratio,
        need=need,
        stroke=stroke,
        pcf_best=pcf_best,
        min_pcf=min_pcf,
        n=n,
        safety_factor=safety_factor,
        tol=tol,
        allowable=allowable_stress,
        axial=float(np.max(axial)),
        buckling=buckling,
        start_fraction=start_fraction,
    )
    hint = (
        f"; at the flattest ratio a mechanism with r2 + r3 >= {need * 1e3:.4g} mm (stroke fraction <= "
        f"{stroke / need:.3g}) would meet the stress limit"
        if need
        else ""
    )
    if feasible:
        message = (
            f"design meets the stress limit and every check ({flexure_model} model): peak flexure stress {smax / 1e9:.4g} GPa = "
            f"allowable / {allowable_stress / smax:.3g}, width {width * 1e3:.4g} mm <= {wmax * 1e3:.4g} mm, "
            f"PCF {pcf_here:.1f} % >= {min_pcf:g} %"
        )
        if pcf_here < pcf_best - 0.5:
            message += (
                f"; but only at r2/r3 = {best:.3g} with PCF {pcf_here:.1f} % (the flattest ratio, "
                f"PCF {pcf_best:.1f} %, does not fit){hint}"
            )
    elif "width" in failing:
        message = (
            f"no design meets the stress limit: at {format_quantity(sigma, 'Pa', 'GPa')} the flexure must be "
            f"{h * 1e3:.3g} mm thick and {width * 1e3:.4g} mm wide, wider than the {wmax * 1e3:.4g} mm "
            f"allowed, for r2 + r3 = {length * 1e3:.4g} mm{hint}"
        )
    else:
        message = f"no feasible design: the {binding.replace('_', ' ')} check fails"
    if not feasible:
        message += ". Smallest changes: " + "; ".join(suggestions)
    summary = {
        "feasible": feasible,
        "message": message,
        "target_force_N": force,
        "stroke_m": stroke,
        "total_length_m": length,
        "stroke_fraction": stroke_fraction,
        "ratio": best,
        "crank_length_m": d["r2"],
        "coupler_length_m": d["r3"],
        "torsional_stiffness_N_m_per_rad": float(k3_check),
        "pivot_width_m": width,
        "pivot_thickness_m": h,
        "pivot_length_m": d["l"],
        "max_width_m": wmax,
        "youngs_modulus_Pa": youngs_modulus,
        "allowable_stress_Pa": allowable_stress,
        "safety_factor_target": safety_factor,
        "max_stress_Pa": smax,
        "safety_factor": allowable_stress / smax,
        "force_min_N": float(np.min(f)),
        "force_max_N": float(np.max(f)),
        "pcf_percent": pcf_here,
        "pcf_flattest_percent": pcf_best,
        "suggested_total_length_m": need,
        "pcf_energy_percent": percent_constant_force_energy(x, f),
        "kinematic_limit_m": float(kinematic_limit_deflection(d["r2"], d["r3"])),
        "allowable_spring_angle_rad": float(
            allowable_spring_angle(allowable_stress, params.bending_modulus("prbm"), h, d["l"])
        ),
        "flexure_model": flexure_model,
        "plate_bending": plate,
        "poisson_ratio": poisson_ratio,
        "working_start_m": float(x[0]),
        "working_end_m": float(x[-1]),
        "min_pcf_percent": min_pcf,
        "thickness_tolerance": tol,
        "force_min_at_thickness_tolerance_N": float(np.min(f)) * (1 - tol) ** 3,
        "force_max_at_thickness_tolerance_N": float(np.max(f)) * (1 + tol) ** 3,
        "max_stress_at_thickness_tolerance_Pa": stress_tol,
        "axial_load_max_N": float(np.max(axial)),
        "buckling_load_N": float(buckling),
        "buckling_safety_factor": float(buckling / np.max(axial)),
        "binding_constraint": binding,
        "suggestions": suggestions,
    }
    return DesignResult(summary, x, f, stress)


def _size_strip(d, force, sigma, youngs_modulus, flexure_model, plate_bending, poisson_ratio):
    """Width, thickness, EI, modulus and plate choice of the strip for a PRBM sizing ``d`` (see :func:`design`)."""

    def modulus_for(width, strip_length):
        plate = (
            plate_bending
            if plate_bending is not None
            else (flexure_model == "beam" and default_plate_bending(width, strip_length))
        )
        return (plate_modulus(youngs_modulus, poisson_ratio) if plate else youngs_modulus), bool(plate)

    e_eff, plate = modulus_for(d["b"], d["l"])
    ei = d["k3"] * d["l"]
    h = d["h"] * youngs_modulus / e_eff  # same stress at the same curvature
    x = d["x"]
    if flexure_model == "beam":
        for _ in range(3):  # the plate choice may follow the width; it settles in one or two rounds
            bc = beam_force_curve(np.concatenate([[0.0], x]) if x[0] > 0 else x, d["r2"], d["r3"], d["l"], ei)
            fb = bc["force"][-x.size :]
            kmax = bc["max_curvature"][-x.size :]
            ei *= force / (0.5 * (np.min(fb) + np.max(fb)))  # the force scales with EI at fixed geometry
            h = 2.0 * sigma / (e_eff * float(np.max(kmax)))  # the curvature does not depend on EI
            width = 12.0 * ei / (e_eff * h**3)
            e_new, plate_new = modulus_for(width, d["l"])
            if plate_new == plate:
                break
            h *= e_eff / e_new
            e_eff, plate = e_new, plate_new
    width = 12.0 * ei / (e_eff * h**3)
    return width, h, ei, e_eff, plate


def _suggestions(
    failing,
    *,
    width,
    wmax,
    sigma,
    pivot_length_ratio,
    need,
    stroke,
    pcf_best,
    min_pcf,
    n,
    safety_factor,
    tol,
    allowable,
    axial,
    buckling,
    start_fraction,
):
    """The smallest change of one input that satisfies each failing check (scaling laws of the sizing)."""
    out = []
    if "width" in failing:
        q = width / wmax  # b ~ K3 E^2 theta^3 / (sigma^3 l^2)
        out.append(f"max_width >= {width * 1e3:.4g} mm")
        out.append(f"allowable_stress / safety_factor >= {sigma * q ** (1 / 3) / 1e9:.4g} GPa")
        if pivot_length_ratio * q**0.5 <= 0.5:  # beyond, the strip is no small-length flexure
            out.append(f"pivot_length_ratio >= {pivot_length_ratio * q**0.5:.3g}")
        if need:
            out.append(f"r2 + r3 >= {need * 1e3:.4g} mm (stroke fraction <= {stroke / need:.3g})")
    if "pcf" in failing:
        frac = _largest_fraction_for_pcf(min_pcf, n, start_fraction)
        out.append(
            f"stroke fraction <= {frac:.3g} (the flattest ratio reaches {min_pcf:g} % there; here at best "
            f"{pcf_best:.1f} %)"
            if frac
            else f"min_pcf <= {pcf_best:.1f} %"
        )
    if "buckling" in failing:
        # the Euler load goes as EI / l^2 = K3 / l at fixed K3
        out.append(f"pivot_length_ratio <= {pivot_length_ratio * buckling / (axial * safety_factor):.3g}")
    if "stress_at_thickness_tolerance" in failing:
        out.append(f"safety_factor >= {1 + tol:.3g}")
    return out


def _largest_fraction_for_pcf(min_pcf, n, start_fraction=0.0):
    """Largest stroke fraction whose flattest ratio reaches ``min_pcf`` [%], or None."""

    def best(frac):
        return _flattest_pcf(frac, n, start_fraction) - min_pcf

    lo, hi = 1e-3, MAX_STROKE_FRACTION - start_fraction
    if hi <= lo or best(lo) < 0:
        return None
    if best(hi) >= 0:
        return hi
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if best(mid) >= 0 else (lo, mid)
    return lo


def _flattest_pcf(stroke_fraction, n, start_fraction=0.0):
    return max(
        normalized_pcf(r, stroke_fraction, n, start_fraction) for r in _ratio_grid(stroke_fraction + start_fraction, 60)
    )


def _flattest_ratio(stroke_fraction, n):
    """The ratio r2/r3 of largest PCF on a grid (no limits)."""
    ratios = _ratio_grid(stroke_fraction, 100)
    return ratios[int(np.argmax([normalized_pcf(r, stroke_fraction, n) for r in ratios]))]


def _shortest_length_for_flattest(
    stroke,
    force,
    modulus,
    sigma,
    ratio_l,
    max_width,
    length0,
    n,
    *,
    flexure_model="prbm",
    plate_bending=None,
    poisson_ratio=0.3,
    preload=0.0,
):
    """Shortest r2 + r3 [m] above ``length0`` whose flattest design fits its width (bisection), or None.

    The strip is sized as :func:`design` sizes it (same flexure model), on a coarse curve.
    """

    def margin(total):
        r = _flattest_ratio(stroke / total, min(n, 61))
        d = _flexure(r, total, stroke, force, modulus, sigma, ratio_l, 61, preload)
        width = _size_strip(d, force, sigma, modulus, flexure_model, plate_bending, poisson_ratio)[0]
        w = max_width if max_width is not None else d["r3"]
        return np.log(w / width)

    if margin(length0) > 0:
        return None
    hi = length0
    for _ in range(40):
        hi *= 1.5
        if (stroke + preload) / hi < 1e-3:
            return None
        if margin(hi) > 0:
            break
    else:
        return None
    return 1.01 * brentq(margin, length0, hi, xtol=1e-4 * hi)  # 1 % above the root: the coarse curve
