"""A valve spring's service life: relaxation at its temperature and a load spectrum (``[spectrum]``).

What spring calculators give (Hexagon's FED1+, IST's Spring Calculator), with springdyn's
dynamics underneath:

- **Relaxation**: the installed force after ``hours`` at ``temperature`` from the wire's
  relaxation table (:func:`springdyn.valve.spring.materials.relaxed_force`, the uncorrected initial
  stress at the installed length); the relaxed spring is the same spring with its free length
  shortened so that its installed force is the relaxed one (the set the wire takes), and its
  float speed is computed again when a valve train is given.
- **Load spectrum**: per speed of the spectrum its share of the running time; each speed is
  simulated to its periodic steady state (:func:`springdyn.valve.sweep`), its worst wire
  element's Goodman safety (the dynamic stress cycle, surge included) is read as a load factor
  on the material's S-N line, and Miner's sum gives the damage per hour and the life
  (:func:`springdyn.valve.spring.materials.spectrum_life`).  One load cycle per cam revolution.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, param
from ...core.results import Result, notes_lines, text_table
from ...core.units import omega_to_rpm, rpm_to_hz
from ..run.float_search import float_speed
from ..run.sweeps import sweep
from ..spring.materials import material, relaxed_force, spectrum_life

__all__ = ["LoadSpectrum", "service_life", "ServiceLife", "relaxed_spring", "FLOAT_RESOLUTION"]

#: Resolution of the float speeds before and after relaxation [rev/min] (a bisection: the
#: relaxation's change of the float speed is some tens of rpm).
FLOAT_RESOLUTION = 2.0


@dataclass(frozen=True)
class LoadSpectrum(Parameters):
    """The ``[spectrum]`` table: speeds and their time shares, temperature, hours, material."""

    cam_rpm: list = param(
        "rad/s", "cam speeds of the spectrum", kind="quantity_list", display="rpm", bare_unit="rpm", positive=True
    )
    share: list = param(
        "", "share of the running time at each speed (summing to 1)", kind="quantity_list", nonnegative=True
    )
    temperature: float = param("K", "spring temperature in service", display="degC", positive=True, default=393.15)
    hours: float = param(
        "s", "running time of the relaxation", display="h", bare_unit="h", positive=True, default=3000.0 * 3600.0
    )
    material: str = param(
        None,
        "the wire's relaxation and S-N data (springdyn.valve.spring.materials: SiCr, SiCrV, CrV, music-wire)",
        kind="str",
        default="SiCr",
    )

    table = "spectrum"

    def _validate(self) -> None:
        if len(self.cam_rpm) != len(self.share):
            raise InputError(
                f"[spectrum] cam_rpm has {len(self.cam_rpm)} speeds but share has {len(self.share)}: one share per speed"
            )
        if not math.isclose(sum(self.share), 1.0, abs_tol=1e-6):
            raise InputError(f"[spectrum] share sums to {sum(self.share):.6g}; the shares of the running time sum to 1")
        if len(self.cam_rpm) > 200:
            raise InputError("[spectrum] cam_rpm: at most 200 speeds")

        material(self.material)

    @property
    def speeds_rpm(self) -> np.ndarray:
        """The spectrum's cam speeds [rev/min]."""
        return omega_to_rpm(np.asarray(self.cam_rpm, dtype=float))

    @property
    def hours_h(self) -> float:
        """The relaxation's running time [h]."""
        return self.hours / 3600.0


def relaxed_spring(spring, spectrum: LoadSpectrum, peak_force: float | None = None):
    """The spring after relaxation: a shorter free length (the rate unchanged) by the force
    ``dF`` it loses.  Returns the spring and its installed force's loss ``dF / F_set`` [fraction].

    ``dF`` is read at the peak stress of the service cycle, ``F_peak - relaxed_force(F_peak)``
    (service relaxation follows the peak stress: issue 40, where the installed stress gave
    1.59 % and the peak 4.55 % from the same table), with ``peak_force``; without it at the
    installed stress, ``F_set - relaxed_force(F_set)`` (a spring held at its installed length).

    Parameters
    ----------
    spring : ValveSpring
    spectrum : LoadSpectrum
        Temperature, hours and material.
    peak_force : float, optional
        The spring's force at the peak of its service cycle [N] (the full-lift force).
    """

    p = spring.spring_model.internal_parameters()
    f0 = float(p["Fset"])
    held = f0 if peak_force is None else float(peak_force)
    lost = held - float(
        relaxed_force(
            held, spectrum.material, spectrum.temperature, spring.mean_diameter, spring.wire_diameter, spectrum.hours_h
        )
    )
    k1 = float(p["K1"])
    relaxed = dataclasses.replace(spring, free_length=spring.free_length - lost / k1)
    return relaxed, lost / f0


def service_life(spring, cam, spectrum: LoadSpectrum, valve_train=None, float_speeds=None) -> ServiceLife:
    """Relaxation and load-spectrum life of a spring (module docstring).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    spectrum : LoadSpectrum
    valve_train : ValveTrain, optional
        The train (float speed before and after relaxation).
    float_speeds : array_like, optional
        Cam speeds of the float-speed scans [rev/min] (with a train; default: 60 % to 140 % of
        the spectrum's top speed, 41 speeds).
    """

    speeds = spectrum.speeds_rpm
    order = np.argsort(speeds)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sw = sweep(spring, cam, speeds[order], valve_train=valve_train)
    t = sw.summary_table()
    goodman = np.empty(speeds.size)
    goodman[order] = np.asarray(t["fatigue_safety_factor"], dtype=float)
    shares = np.asarray(spectrum.share, dtype=float)
    life = spectrum_life(shares, rpm_to_hz(speeds), safety_factor=goodman)
    # relaxation at the peak stress (the full-lift force), the installed stress's beside it
    lift = cam.max_lift * (valve_train.ratio if valve_train is not None else 1.0)
    peak = float(spring.spring_model.static_force(spring.installed_length - lift))
    relaxed, loss = relaxed_spring(spring, spectrum, peak_force=peak)
    _, loss_installed = relaxed_spring(spring, spectrum)
    out = dict(goodman=goodman, life=life, loss=loss, relaxed=relaxed, loss_installed_stress=loss_installed)
    if valve_train is not None:
        scan = (
            np.linspace(0.6 * speeds.max(), 1.4 * speeds.max(), 41)
            if float_speeds is None
            else np.sort(np.asarray(float_speeds, dtype=float))
        )
        for key, sp in (("float_new", spring), ("float_relaxed", relaxed)):
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                out[key] = float_speed(sp, cam, valve_train, scan, resolution=FLOAT_RESOLUTION)["float_cam_rpm"]
        out["scan"] = scan
    return ServiceLife(spring=spring, spectrum=spectrum, material=material(spectrum.material).name, **out)


@dataclass(frozen=True, repr=False)
class ServiceLife(Result):
    """A spring's relaxation and load-spectrum life (:func:`service_life`)."""

    spring: object
    spectrum: LoadSpectrum
    material: str
    goodman: np.ndarray  #: Goodman safety per spectrum speed [-]
    life: dict  #: :func:`springdyn.valve.spring.materials.spectrum_life`
    loss: float  #: relaxation loss of the installed force, read at the peak stress [-]
    relaxed: object  #: the relaxed spring
    loss_installed_stress: float | None = None  #: the same read at the installed stress [-] (comparison)
    float_new: float | None = None  #: float speed of the new spring [rev/min]
    float_relaxed: float | None = None  #: float speed after relaxation [rev/min]
    scan: np.ndarray | None = None
    notes: list = field(default_factory=list)

    title = "valve spring service life"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{len(self.goodman)} speeds, {self.material}"

    def describe(self, source: str = "") -> str:
        """Relaxation, float speeds new and relaxed, and the life per speed of the spectrum (what
        ``springdyn valve life`` prints).

        Parameters
        ----------
        source : str
            The spring file, for the first line [-].
        """
        s = self.summary
        out = [
            f"{source or 'the spring'} ({s['material']}): after {s['relaxation_hours']:g} h at "
            f"{s['temperature_degC']:g} degC the installed force relaxes by {s['relaxation_loss']:.2%}, "
            f"{s['installed_force_N']:.1f} N to {s['relaxed_installed_force_N']:.1f} N (read at the peak stress of "
            "the cycle"
            + (
                f"; at the installed stress alone {s['relaxation_loss_at_installed_stress']:.2%}"
                if s.get("relaxation_loss_at_installed_stress") is not None
                else ""
            )
            + ")"
        ]
        if "float_cam_rpm_new" in s:
            new, old = s["float_cam_rpm_new"], s["float_cam_rpm_relaxed"]

            def fmt(v):
                return "above the scan" if v is None else f"{2 * v:.0f} engine rpm ({v:.0f} cam rpm)"

            out.append(f"float speed: new {fmt(new)}, relaxed {fmt(old)}")
        cols = self.columns()
        out.append(
            text_table(
                [
                    (f"{2 * r:.0f}", f"{r:.0f}", f"{p:.3g}", f"{g:.3f}", f"{d:.1%}")
                    for r, p, g, d in zip(cols["cam_rpm"], cols["share"], cols["goodman_safety"], cols["damage_share"])
                ],
                headers=(
                    "engine rpm (four-stroke)",
                    "cam rpm",
                    "time share",
                    "Goodman (dynamic)",
                    "share of the damage",
                ),
            )
        )
        out.append(
            "life: none, a static failure: the spectrum runs at or above the float speed (see the note)"
            if s["static_failure"]
            else "life: infinite (every speed at or below the endurance strength)"
            if s["infinite_life"]
            else f"life: {s['life_hours']:.4g} h (Miner, damage {s['damage_per_hour']:.3g} per hour)"
        )
        return "\n".join(out + notes_lines(s))

    def _summary(self) -> dict:
        sp = self.spectrum
        fset = float(self.spring.spring_model.internal_parameters()["Fset"])
        life = self.life["life_hours"]
        s = dict(
            material=self.material,
            temperature_degC=sp.temperature - 273.15,
            relaxation_hours=sp.hours_h,
            installed_force_N=fset,
            relaxation_loss=self.loss,
            relaxation_loss_definition="the installed force's loss by the relaxation read at the peak (full-lift) "
            "stress, which service relaxation follows",
            relaxation_loss_at_installed_stress=self.loss_installed_stress,
            relaxed_installed_force_N=fset * (1.0 - self.loss),
            min_goodman_safety=float(self.goodman.min()),
            damage_per_hour=float(self.life["damage_per_hour"]),
            life_hours=None if not math.isfinite(life) else float(life),
            infinite_life=not math.isfinite(life),
        )
        if self.scan is not None:
            s["float_cam_rpm_new"] = self.float_new
            s["float_cam_rpm_relaxed"] = self.float_relaxed
        notes = list(self.notes)
        past = self.past_float()
        if past.any():
            # the valve leaves the cam there (bounce, a toss to solid): no fatigue law holds, and
            # Basquin extrapolated to a few cycles is no answer (issue 40)
            share = float(np.asarray(sp.share, dtype=float)[past].sum())
            s.update(life_hours=0.0, infinite_life=False, static_failure=True, share_past_float=share)
            notes.append(
                f"STATIC FAILURE: {share:.1%} of the running time is at or above the float speed "
                f"({min(self.float_new, self.float_relaxed or self.float_new):.0f} cam rpm, new or relaxed), where the "
                "valve leaves the cam; no fatigue life is given for such a duty (Miner over the speeds below it "
                f"alone: {self.life['life_hours']:.4g} h)"
            )
        else:
            s["static_failure"] = False
        if self.scan is not None:
            for key, what in (("float_cam_rpm_new", "new"), ("float_cam_rpm_relaxed", "relaxed")):
                if s[key] is None:
                    notes.append(f"the {what} spring does not float up to {self.scan[-1]:g} cam rpm (the scan's top)")
        notes.append(
            "relaxation tables are engineering judgement (springdyn.valve.spring.materials): replace them with the spring "
            "maker's data where you have it"
        )
        s["notes"] = notes
        return s

    def past_float(self) -> np.ndarray:
        """Per spectrum speed: at or above the float speed of the new or the relaxed spring
        (bool; all False without a valve train)."""
        floats = [f for f in (self.float_new, self.float_relaxed) if f is not None]
        speeds = self.spectrum.speeds_rpm
        return speeds >= min(floats) if floats else np.zeros(speeds.size, dtype=bool)

    def columns(self) -> dict:
        pts = self.life["per_point"]
        return {
            "cam_rpm": self.spectrum.speeds_rpm,
            "share": np.asarray(self.spectrum.share, dtype=float),
            "goodman_safety": self.goodman,
            "damage_share": np.asarray([p["damage_share"] for p in pts], dtype=float),
        }

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        c = self.columns()
        rpm = c.pop("cam_rpm")
        return xr.Dataset(
            {k: ("cam_rpm", v, {"units": "1"}) for k, v in c.items()},
            coords={
                "cam_rpm": ("cam_rpm", rpm, {"units": "rpm"}),
                "engine_rpm": ("cam_rpm", 2.0 * rpm, {"units": "rpm", "long_name": "engine speed, four-stroke"}),
            },
        )

    def _plot(self, ax=None):
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        fig, ax = (ax.figure, ax) if ax is not None else plt.subplots(figsize=(7, 4.5))
        c = self.columns()
        ax.bar(
            c["cam_rpm"],
            c["share"],
            width=0.6 * np.min(np.diff(np.sort(c["cam_rpm"]))) if c["cam_rpm"].size > 1 else 100.0,
            color="C0",
            alpha=0.6,
            label="time share",
        )
        ax.set_xlabel("cam speed [rpm]")
        ax.set_ylabel("share of the running time [-]")
        b = ax.twinx()
        b.plot(c["cam_rpm"], c["goodman_safety"], "C3o-", label="Goodman safety")
        b.axhline(1.0, color="C3", lw=0.8, ls="--")
        b.set_ylabel("Goodman safety [-]", color="C3")
        return fig
