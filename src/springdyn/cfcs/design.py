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
import xarray as xr
from scipy.optimize import brentq, minimize_scalar

from ..core.errors import InputError
from ..core.io import atomic_open
from ..core.plotting import new_figure
from ..core.results import Result
from ..core.units import format_quantity
from .kinematics import deflection_from_theta2, kinematic_limit_deflection, spring_angle, theta2_from_deflection
from .pivot import allowable_spring_angle, bending_stress, flexure_stiffness
from .statics import percent_constant_force_energy, static_force

__all__ = ["DesignResult", "design", "normalized_pcf", "min_ratio_for_stroke"]


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


def _geometry(ratio, total_length):
    r3 = total_length / (1.0 + ratio)
    return ratio * r3, r3


def normalized_pcf(ratio, stroke_fraction, n=401):
    """PCF [%] over ``[0, stroke_fraction (r2 + r3)]`` for ``r2/r3 = ratio`` (independent of K3 and size).

    Parameters
    ----------
    ratio : float
        Crank-to-coupler length ratio r2/r3 [-].
    stroke_fraction : float
        Stroke as a fraction of r2 + r3 [-].
    n : int
        Number of samples along the stroke [-].
    """
    r2, r3 = _geometry(ratio, 1.0)
    x = np.linspace(0.0, stroke_fraction, n)
    f = static_force(theta2_from_deflection(x, r2, r3), 1.0, r2, r3)
    return 100.0 * float(np.min(f) / np.max(f))


@dataclasses.dataclass(repr=False)
class DesignResult(Result):
    """A CFCS design and its verification (force curve, PCF, stress)."""

    summary: dict
    deflection: np.ndarray
    force: np.ndarray
    stress: np.ndarray

    title = "constant-force spring design"

    @property
    def feasible(self) -> bool:
        return bool(self.summary["feasible"])

    def _repr_caption(self) -> str:
        return "feasible" if self.feasible else "NOT feasible"

    def columns(self) -> dict:
        return {"deflection_m": self.deflection, "force_N": self.force, "stress_Pa": self.stress}

    def to_xarray(self) -> xr.Dataset:
        ds = xr.Dataset({"force_N": ("deflection_m", self.force, {"units": "N"}),
                         "stress_Pa": ("deflection_m", self.stress, {"units": "Pa"})},
                        coords={"deflection_m": ("deflection_m", self.deflection, {"units": "m"})})
        ds.attrs.update({k: v for k, v in self.summary.items()
                         if isinstance(v, (int, float, str)) and not isinstance(v, bool)})
        return ds

    def to_params(self, crank_mass, coupler_mass, slider_mass, **extra):
        """A :class:`~springdyn.cfcs.params.CFCSParams` of this design (masses are not designed)."""
        from .params import CFCSParams

        s = self.summary
        return CFCSParams(crank_length=s["crank_length_m"], coupler_length=s["coupler_length_m"],
                          crank_mass=crank_mass, coupler_mass=coupler_mass, slider_mass=slider_mass,
                          pivot_width=s["pivot_width_m"], pivot_thickness=s["pivot_thickness_m"],
                          pivot_length=s["pivot_length_m"], youngs_modulus=s["youngs_modulus_Pa"],
                          allowable_stress=s["allowable_stress_Pa"], **extra)

    def to_toml(self, path) -> Path:
        """Write a ``[cfcs]`` table of the design (masses to be filled in by the user)."""
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
            f"youngs_modulus = \"{s['youngs_modulus_Pa'] / 1e9:.6g} GPa\"\n"
            f"allowable_stress = \"{s['allowable_stress_Pa'] / 1e9:.6g} GPa\"\n"
            'friction_model = "none"\naxial_force = false\n'
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
        ax.set_title(f"CFCS design r2/r3 = {s['ratio']:.3f}, PCF {s['pcf_percent']:.1f} %, "
                     f"{'feasible' if s['feasible'] else 'NOT feasible'}")
        ax.grid(True, alpha=0.3)
        ax.legend()
        return fig


def _flexure(ratio, total_length, stroke, force, modulus, allowable, pivot_length_ratio, n):
    """K3, l, h, b and the force curve for one ratio (see the module docstring)."""
    r2, r3 = _geometry(ratio, total_length)
    x = np.linspace(0.0, stroke, n)
    th = theta2_from_deflection(x, r2, r3)
    f1 = static_force(th, 1.0, r2, r3)
    k3 = force / (0.5 * (np.min(f1) + np.max(f1)))
    length = pivot_length_ratio * r3
    th_max = float(spring_angle(th[-1], r2, r3))
    h = 2.0 * allowable * length / (modulus * th_max)
    b = 12.0 * k3 * length / (modulus * h**3)
    return dict(r2=r2, r3=r3, k3=k3, l=length, h=h, b=b, x=x, th=th, f=k3 * f1)


def design(force, stroke, youngs_modulus, allowable_stress, *, stroke_fraction=0.4, total_length=None,
           pivot_length_ratio=0.1, max_width=None, safety_factor=1.0, n=401) -> DesignResult:
    """Design a CFCS: r2/r3 for the flattest force, then K3 and the flexure (b, h, l).

    Parameters
    ----------
    force : float
        Target constant force [N].
    stroke : float
        Working stroke from the toggle [m].
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
        Safety factor [-]: the stress at the end of the stroke is ``allowable_stress / safety_factor``.
    n : int
        Samples of the force curve [-].
    """
    for name, v in (("force", force), ("stroke", stroke), ("youngs_modulus", youngs_modulus),
                    ("allowable_stress", allowable_stress), ("pivot_length_ratio", pivot_length_ratio),
                    ("safety_factor", safety_factor)):
        if not (np.isfinite(v) and v > 0):
            raise InputError(f"{name} = {v!r} must be positive")
    if max_width is not None and not max_width > 0:
        raise InputError(f"max_width = {max_width!r} must be positive")
    if total_length is not None:
        if not total_length > stroke:
            raise InputError(f"total_length = {format_quantity(total_length, 'm', 'mm')} must exceed the stroke "
                             f"{format_quantity(stroke, 'm', 'mm')}")
        stroke_fraction = stroke / total_length
    if not 0 < stroke_fraction < 1:
        raise InputError(f"stroke_fraction = {stroke_fraction!r} must lie in (0, 1)")
    length = stroke / stroke_fraction
    sigma = allowable_stress / safety_factor
    lo = min(max(min_ratio_for_stroke(stroke_fraction) * (1 + 1e-9), 0.02), 0.995)
    ratios = np.linspace(lo, 0.995, 200)

    def width_limit(ratio):
        return max_width if max_width is not None else _geometry(ratio, length)[1]

    pcf = np.array([normalized_pcf(r, stroke_fraction, n) for r in ratios])
    widths = np.array([_flexure(r, length, stroke, force, youngs_modulus, sigma, pivot_length_ratio, 3)["b"]
                       for r in ratios])
    ok = widths <= np.array([width_limit(r) for r in ratios])
    feasible = bool(np.any(ok))
    pool = np.where(ok, pcf, -np.inf) if feasible else pcf
    i = int(np.argmax(pool))
    best = ratios[i]
    a, b = ratios[max(i - 1, 0)], ratios[min(i + 1, ratios.size - 1)]
    if b > a:
        res = minimize_scalar(lambda r: -normalized_pcf(r, stroke_fraction, n), bounds=(a, b), method="bounded",
                              options={"xatol": 1e-6})
        cand = _flexure(res.x, length, stroke, force, youngs_modulus, sigma, pivot_length_ratio, 3)
        if -res.fun > pool[i] and (not feasible or cand["b"] <= width_limit(res.x)):
            best = float(res.x)
    d = _flexure(best, length, stroke, force, youngs_modulus, sigma, pivot_length_ratio, n)
    # verification through the stiffness formula and the stress function (independent of the sizing algebra)
    k3_check = flexure_stiffness(youngs_modulus, d["b"], d["h"], d["l"])
    stress = bending_stress(spring_angle(d["th"], d["r2"], d["r3"]), youngs_modulus, d["h"], d["l"])
    f = static_force(d["th"], k3_check, d["r2"], d["r3"])
    wmax = width_limit(best)
    feasible = bool(d["b"] <= wmax * (1 + 1e-9))
    pcf_best = float(np.max(pcf))
    pcf_here = 100.0 * float(np.min(f) / np.max(f))
    need = None
    if not feasible or pcf_here < pcf_best - 0.5:
        need = _shortest_length_for_flattest(stroke, force, youngs_modulus, sigma, pivot_length_ratio, max_width,
                                             length, n)
    hint = (f"; at the flattest ratio a mechanism with r2 + r3 >= {need * 1e3:.4g} mm (stroke fraction <= "
            f"{stroke / need:.3g}) would meet the stress limit" if need else "")
    if feasible:
        message = (f"design meets the stress limit: pivot stress {float(np.max(stress)) / 1e9:.4g} GPa at the end of "
                   f"the stroke, width {d['b'] * 1e3:.4g} mm <= {wmax * 1e3:.4g} mm")
        if pcf_here < pcf_best - 0.5:
            message += (f"; but only at r2/r3 = {best:.3g} with PCF {pcf_here:.1f} % (the flattest ratio, "
                        f"PCF {pcf_best:.1f} %, does not fit){hint}")
    else:
        message = (f"no design meets the stress limit: at {format_quantity(sigma, 'Pa', 'GPa')} the flexure must be "
                   f"{d['h'] * 1e3:.3g} mm thick and {d['b'] * 1e3:.4g} mm wide, wider than the {wmax * 1e3:.4g} mm "
                   f"allowed, for r2 + r3 = {length * 1e3:.4g} mm{hint}")
    summary = {
        "feasible": feasible, "message": message, "target_force_N": force, "stroke_m": stroke,
        "total_length_m": length, "stroke_fraction": stroke_fraction, "ratio": best,
        "crank_length_m": d["r2"], "coupler_length_m": d["r3"], "torsional_stiffness_N_m_per_rad": float(k3_check),
        "pivot_width_m": d["b"], "pivot_thickness_m": d["h"], "pivot_length_m": d["l"],
        "max_width_m": wmax, "youngs_modulus_Pa": youngs_modulus, "allowable_stress_Pa": allowable_stress,
        "safety_factor_target": safety_factor, "max_stress_Pa": float(np.max(stress)),
        "safety_factor": allowable_stress / float(np.max(stress)),
        "force_min_N": float(np.min(f)), "force_max_N": float(np.max(f)),
        "pcf_percent": pcf_here, "pcf_flattest_percent": pcf_best,
        "suggested_total_length_m": need, "pcf_energy_percent": percent_constant_force_energy(
            d["x"], f),
        "kinematic_limit_m": float(kinematic_limit_deflection(d["r2"], d["r3"])),
        "allowable_spring_angle_rad": float(allowable_spring_angle(allowable_stress, youngs_modulus, d["h"], d["l"])),
    }
    return DesignResult(summary, d["x"], f, stress)


def _flattest_ratio(stroke_fraction, n):
    """The ratio r2/r3 of largest PCF on a grid (no limits)."""
    lo = min(max(min_ratio_for_stroke(stroke_fraction) * (1 + 1e-9), 0.02), 0.995)
    ratios = np.linspace(lo, 0.995, 100)
    return ratios[int(np.argmax([normalized_pcf(r, stroke_fraction, n) for r in ratios]))]


def _shortest_length_for_flattest(stroke, force, modulus, sigma, ratio_l, max_width, length0, n):
    """Shortest r2 + r3 [m] above ``length0`` whose flattest design meets the limits (bisection), or None."""

    def margin(total):
        r = _flattest_ratio(stroke / total, n)
        d = _flexure(r, total, stroke, force, modulus, sigma, ratio_l, 3)
        w = max_width if max_width is not None else d["r3"]
        return np.log(w / d["b"])

    if margin(length0) > 0:
        return None
    hi = length0
    for _ in range(40):
        hi *= 1.5
        if margin(hi) > 0:
            break
    else:
        return None
    return brentq(margin, length0, hi, xtol=1e-4 * hi)
