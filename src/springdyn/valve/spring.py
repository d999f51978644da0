"""The valve spring: parameters (TOML keys), validation, and the MMS Type C chain."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import cached_property
from importlib import resources

import numpy as np

from ..core.params import check_fields, describe_value, from_mapping, load_toml, param
from ..core.errors import InputError
from ..core.units import format_quantity
from . import design, formulas
from .elements import damping_coefficient, hardening_law, law_stiffness, linear_law, low_pitch_law
from .modes import chain_frequencies
from .statics import element_compressions, series_state

__all__ = ["ValveSpring", "Chain", "EXAMPLES"]

#: Built-in example springs (reading notes 1.6), shipped in ``springdyn/data``.
EXAMPLES = {"one-step": "valve_one_step.toml", "two-step": "valve_two_step.toml"}

ONE_STEP_ELEMENTS = ("K", "Kh1", "Kh2", "Kh2", "Kh1", "K")
TWO_STEP_ELEMENTS = ("K", "Ks", "Kh1", "Kh2", "Kh1", "K")
ONE_STEP_MASSES = ("me", "m1", "m2", "m1", "me")
TWO_STEP_MASSES = ("me", "m1", "m2", "m2", "me")


@dataclass(frozen=True)
class Chain:
    """The 5-mass, 6-element chain of a spring (notes 1.2), SI throughout.

    Elements are numbered from the seat (element 0 touches the fixed seat, element 5 the
    retainer); mass ``i`` sits between elements ``i`` and ``i + 1``.
    """

    element_names: tuple
    mass_names: tuple
    masses: np.ndarray  # (5,) [kg]
    laws: np.ndarray  # (6, 3, 4)
    c0: float  # [N s/m]
    setup_compressions: np.ndarray  # (6,) [m], every element at Fset
    setup_force: float  # [N]
    free_length: float  # [m]
    installed_length: float  # [m]

    def tangent_stiffness(self, compressions) -> np.ndarray:
        """Element tangent stiffnesses [N/m] at the given compressions [m]."""
        return np.stack([law_stiffness(x, law) for x, law in zip(compressions, self.laws)])

    def damping(self, compressions) -> np.ndarray:
        """Element damping coefficients [N s/m] at the given compressions [m]."""
        return np.stack([damping_coefficient(x, law, self.c0) for x, law in zip(compressions, self.laws)])


def _mm(value: float) -> str:
    return format_quantity(value, "m", "mm")


@dataclass(frozen=True)
class ValveSpring:
    """A helical valve spring for the MMS Type C model (one-step or two-step).

    All values SI.  Build from TOML with :meth:`from_toml` (keys as the attribute names,
    values with units such as ``"22 mm"``), from a dict with :meth:`from_dict`, or take a
    built-in example with :meth:`example`.

    Examples
    --------
    >>> s = ValveSpring.example("one-step")
    >>> round(s.internal_parameters()["Fset"], 2)
    251.43
    >>> round(float(s.static_force(s.installed_length)), 2)
    251.43
    """

    type: str = param(None, "spring kind", kind="str", choices=("one-step", "two-step"))
    mean_diameter: float = param("m", "mean coil diameter", symbol="Do", display="mm", positive=True)
    wire_diameter: float = param("m", "wire diameter", symbol="Dw", display="mm", positive=True)
    free_length: float = param("m", "free length", symbol="Lf", display="mm", positive=True)
    installed_length: float = param("m", "set-up (installed) length, valve closed", symbol="Ls", display="mm", positive=True)
    dead_coils: float = param("", "dead coils per end", symbol="Nb", nonnegative=True)
    low_pitch_coils: float = param("", "low-pitch coils (0 for one-step)", symbol="N1", nonnegative=True)
    high_pitch_coils: float = param("", "high-pitch coils", symbol="N2", positive=True)
    youngs_modulus: float = param("Pa", "Young's modulus", symbol="E", display="GPa", positive=True)
    shear_modulus: float = param("Pa", "shear modulus", symbol="G'", display="GPa", positive=True)
    density: float = param("kg/m^3", "density", symbol="rho'", positive=True)
    damping_ratio: float = param("", "damping ratio", symbol="Cps", nonnegative=True)

    # ------------------------------------------------------------------ construction
    def __post_init__(self):
        check_fields(self)
        self._check_geometry()
        self._check_model()

    @classmethod
    def from_dict(cls, mapping, *, source: str | None = None) -> "ValveSpring":
        """Build from a mapping of the ``[spring]`` keys (values with units or SI numbers)."""
        return from_mapping(cls, mapping, section="spring", source=source)

    @classmethod
    def from_toml(cls, path) -> "ValveSpring":
        """Read the ``[spring]`` table of a TOML file."""
        return cls.from_dict(load_toml(path, "spring"), source=str(path))

    @classmethod
    def example(cls, name: str = "one-step") -> "ValveSpring":
        """A built-in example spring of reading notes 1.6: ``"one-step"`` or ``"two-step"``."""
        if name not in EXAMPLES:
            raise InputError(f"example = {name!r} is not a built-in valve spring; choose one of {', '.join(EXAMPLES)}")
        with resources.as_file(resources.files("springdyn.data") / EXAMPLES[name]) as p:
            return cls.from_toml(p)

    def replace(self, **changes) -> "ValveSpring":
        """A copy with some fields changed (validated again)."""
        return dataclasses.replace(self, **changes)

    @property
    def two_step(self) -> bool:
        return self.type == "two-step"

    def _field(self, name: str) -> str:
        meta = {f.name: f.metadata for f in dataclasses.fields(self)}[name]
        return f"{name} = {describe_value(getattr(self, name), meta)}"

    def _check_geometry(self) -> None:
        if self.installed_length >= self.free_length:
            raise InputError(
                f"{self._field('installed_length')} must be shorter than {self._field('free_length')}"
            )
        if not self.two_step and self.low_pitch_coils != 0:
            raise InputError(
                f"{self._field('low_pitch_coils')} must be 0 for a one-step spring "
                "(set type = \"two-step\" for a spring with low-pitch coils)"
            )
        n1, n2, nb = self.low_pitch_coils, self.high_pitch_coils, self.dead_coils
        if formulas.active_coils_free(n1, n2, nb) <= 0:
            raise InputError(
                f"active coils N1 + N2 - 2 Nb = {n1:g} + {n2:g} - 2*{nb:g} = "
                f"{formulas.active_coils_free(n1, n2, nb):g} must be positive "
                "(low_pitch_coils + high_pitch_coils - 2 dead_coils)"
            )
        if n2 - nb <= 0:
            raise InputError(
                f"active coils at set-up N2 - Nb = {n2:g} - {nb:g} must be positive (high_pitch_coils > dead_coils)"
            )
        lc = formulas.coil_contact_length(self.wire_diameter, n1, n2)
        if self.installed_length <= lc:
            raise InputError(
                f"{self._field('installed_length')} is at or below coil contact: it must be longer than the "
                f"solid length Lc = Dw (N1 + N2 + 0.5) = {_mm(lc)}"
            )

    def _check_model(self) -> None:
        p = self.internal_parameters()
        k = p["K"]
        if self.two_step:
            if k <= 3.0 * p["K2"]:
                raise InputError(
                    f"contact stiffness K = {k:.6g} N/m must exceed 3 K2 = {3 * p['K2']:.6g} N/m for a two-step "
                    "spring (else Kh1, Kh2 are negative): increase mean_diameter or youngs_modulus"
                )
            if not 0 < p["Ks"] < np.inf:
                raise InputError(
                    f"low-pitch stiffness Ks = K K1 K2/(K K2 + K1 K2 - K K1) = {p['Ks']:.6g} N/m must be positive: "
                    f"low_pitch_coils = {self.low_pitch_coils:g} must exceed dead_coils = {self.dead_coils:g}"
                )
        elif k <= 2.0 * p["K1"]:
            raise InputError(
                f"contact stiffness K = {k:.6g} N/m must exceed 2 K1 = {2 * p['K1']:.6g} N/m for a one-step "
                "spring (else Kh1, Kh2 are negative): increase mean_diameter or youngs_modulus"
            )
        factor = 3.0 if self.two_step else 2.0
        if k <= factor * p["K3"]:
            raise InputError(
                f"contact stiffness K = {k:.6g} N/m must exceed {factor:g} K3 = {factor * p['K3']:.6g} N/m "
                "(else the stiffened rates Kh1', Kh2' are negative)"
            )
        for name in ("m1", "m2"):
            if p[name] <= 0:
                raise InputError(
                    f"chain mass {name} = {p[name]:.6g} kg must be positive: the closed-form mass formulas of "
                    f"the document break down for this spring (f1 = {p['f1']:.1f} Hz, f2 = {p['f2']:.1f} Hz); "
                    "check the coil counts (low_pitch_coils, high_pitch_coils, dead_coils) and the lengths"
                )
        if p["me"] <= 0:
            raise InputError(
                f"end mass me = {p['me']:.6g} kg must be positive: the closed-form masses m1, m2 exceed the "
                f"spring mass M = {p['M']:.6g} kg (check density, the coil counts and the diameters)"
            )
        if p["F1"] <= 0:
            raise InputError(
                f"first nonlinear force F1 = Fset + (Ls - Lc - Pc) K2 = {p['F1']:.6g} N must be positive: "
                f"{self._field('installed_length')} is too close to coil contact"
            )
        if not p["Fcon"] > max(p["F1"], p["Fset"]):
            raise InputError(
                f"coil-contact force Fcon = {p['Fcon']:.6g} N must exceed F1 = {p['F1']:.6g} N and "
                f"Fset = {p['Fset']:.6g} N: {self._field('installed_length')} is at or below coil contact"
            )

    # ------------------------------------------------------------------ parameters
    def internal_parameters(self) -> dict:
        """Internal parameters and model variables (SI), under the CLI's JSON keys.

        ``K, K1, K2, K3, Kh1, Kh2, Ks`` (two-step only) [N/m], ``m1, m2, me, M`` [kg],
        ``f1, f2`` [Hz], ``n1p, n2p`` [-], ``Pc, Lc`` [m], ``Fset, F1, F2, Fcon`` [N],
        ``C0`` [N s/m].
        """
        return dict(self._parameters)

    @cached_property
    def _parameters(self) -> dict:
        do, dw = self.mean_diameter, self.wire_diameter
        lf, ls = self.free_length, self.installed_length
        n1, n2, nb = self.low_pitch_coils, self.high_pitch_coils, self.dead_coils
        g, rho = self.shear_modulus, self.density
        na1 = formulas.active_coils_free(n1, n2, nb)
        na2 = formulas.active_coils_setup(n1, n2, nb, self.two_step)
        k = formulas.contact_stiffness(do, self.youngs_modulus)
        k1 = formulas.free_length_stiffness(g, dw, do, na1)
        k2 = formulas.setup_stiffness(g, dw, do, na2) if self.two_step else k1
        n1p = formulas.pitch_correction_free(lf, dw, n1, n2, na1, do)
        n2p = formulas.pitch_correction_setup(ls, dw, n1, n2, na2, do)
        f1 = formulas.surge_frequency(g, rho, dw, do, na1 + n1p)
        f2 = formulas.surge_frequency(g, rho, dw, do, na2 + n2p)
        m_total = formulas.total_mass(rho, do, dw, n1, n2)
        pc = formulas.coil_pitch(ls, dw, n1, n2)
        lc = formulas.coil_contact_length(dw, n1, n2)
        fset = formulas.setup_force(lf, ls, k1)
        k3 = formulas.stiffened_rate(k2)
        f_1 = formulas.first_nonlinear_force(fset, ls, lc, pc, k2)
        f_2 = formulas.second_nonlinear_force(f_1, pc, k3)
        fcon = formulas.coil_contact_force(k1, k2, lf, ls, dw, n1, n2)
        if self.two_step:
            mv = formulas.twostep_model_variables(k, k1, k2, f1, f2, m_total)
        else:
            mv = formulas.onestep_model_variables(k, k1, f1, m_total)
        c0 = 2.0 * self.damping_ratio * np.sqrt(m_total * k1)
        p = dict(K=k, K1=k1, K2=k2, K3=k3, Kh1=mv["Kh1"], Kh2=mv["Kh2"])
        if self.two_step:
            p["Ks"] = mv["Ks"]
        p.update(
            m1=mv["m1"], m2=mv["m2"], me=mv["me"], M=m_total, f1=f1, f2=f2, n1p=n1p, n2p=n2p,
            Pc=pc, Lc=lc, Fset=fset, F1=f_1, F2=f_2, Fcon=fcon, C0=float(c0),
        )
        return p

    def breakpoints(self) -> dict:
        """Breakpoints of every nonlinear law [m] (and ``Kh1c``, ``Kh2c``, ``Kh1p``, ``Kh2p`` [N/m]).

        Keys follow the document: ``x11..x14`` (Kh1), ``x21..x24`` (Kh2) and, for a
        two-step spring, ``x1, x2`` (Ks).
        """
        return dict(self._laws[1])

    @cached_property
    def _laws(self):
        p = self._parameters
        kh1p, kh2p = formulas.stiffened_chain_rates(p["K"], p["K3"], self.two_step)
        law_h1, b1 = hardening_law(p["Kh1"], kh1p, p["F1"], p["F2"], p["Fcon"], p["Pc"])
        law_h2, b2 = hardening_law(p["Kh2"], kh2p, p["F1"], p["F2"], p["Fcon"], p["Pc"])
        law_k = linear_law(p["K"])
        bp = {f"x1{i}": b1[f"x{i}"] for i in range(1, 5)}
        bp.update({f"x2{i}": b2[f"x{i}"] for i in range(1, 5)})
        bp.update(Kh1p=kh1p, Kh2p=kh2p, Kh1c=b1["kc"], Kh2c=b2["kc"])
        named = {"K": law_k, "Kh1": law_h1, "Kh2": law_h2}
        if self.two_step:
            named["Ks"], bs = low_pitch_law(p["Ks"], p["Fset"], self.wire_diameter)
            bp.update(x1=bs["x1"], x2=bs["x2"])
        return named, bp

    @cached_property
    def chain(self) -> Chain:
        """The lumped 5-mass chain with its element laws and damping (notes 1.2)."""
        p = self._parameters
        named, _ = self._laws
        enames = TWO_STEP_ELEMENTS if self.two_step else ONE_STEP_ELEMENTS
        mnames = TWO_STEP_MASSES if self.two_step else ONE_STEP_MASSES
        laws = np.stack([named[n] for n in enames])
        return Chain(
            element_names=enames,
            mass_names=mnames,
            masses=np.array([p[n] for n in mnames]),
            laws=laws,
            c0=p["C0"],
            setup_compressions=element_compressions(p["Fset"], laws),
            setup_force=p["Fset"],
            free_length=self.free_length,
            installed_length=self.installed_length,
        )

    # ------------------------------------------------------------------ statics
    #: The model is evaluated down to the length where the static force reaches this
    #: multiple of Fcon; beyond ``2 Fcon`` the coil-contact branch is already an
    #: extrapolation (notes 1.3.9), beyond ``10 Fcon`` springdyn refuses.
    LIMIT_FORCE_FACTOR = 10.0

    @cached_property
    def min_length(self) -> float:
        """Shortest length [m] springdyn evaluates: where the static force is 10 Fcon.

        Note that the document's solid length ``Lc = Dw (N1 + N2 + 0.5)`` is *not* the
        model's limit: the element laws reach Fcon at a shorter length (25.9 mm against
        Lc = 28 mm for the one-step example), so Lc is reported as a design figure only.
        """
        return self.length_at_force(self.LIMIT_FORCE_FACTOR * self._parameters["Fcon"])

    def _compression(self, length, name: str = "length"):
        length = np.asarray(length, dtype=float)
        lo = self.min_length
        bad = ~np.isfinite(length) | (length > self.free_length) | (length < lo)
        if np.any(bad):
            raise InputError(
                f"{name} = {_mm(float(np.ravel(length)[np.ravel(bad)][0]))} is outside the range of the spring: "
                f"it must lie between {_mm(lo)} (where the force reaches {self.LIMIT_FORCE_FACTOR:g} Fcon, far past "
                f"coil contact) and the free length Lf = {_mm(self.free_length)}"
            )
        return self.free_length - length

    def static_state(self, length):
        """Static force [N], element compressions [m] and tangent stiffness [N/m] at a length [m]."""
        return series_state(self._compression(length), self.chain.laws)

    def static_force(self, length):
        """Static (massless) spring force [N] at spring length ``length`` [m].

        Series equilibrium of the six elements: equal force, compressions summing to
        ``Lf - length`` (notes 1.5).  Valid from the free length down to :attr:`min_length`.
        """
        return self.static_state(length)[0]

    def static_stiffness(self, length):
        """Static tangent stiffness ``-dF/dL`` [N/m] at spring length ``length`` [m]."""
        return self.static_state(length)[2]

    def length_at_force(self, force: float) -> float:
        """Spring length [m] at which the static force is ``force`` [N]."""
        return float(self.free_length - element_compressions(force, self.chain.laws).sum())

    def initial_condition(self, total_compression: float):
        """Static state at a total compression ``dL = (Lf - Ls) + lift`` [m] (notes 1.5).

        Returns
        -------
        dict
            ``force`` [N], ``compressions`` (6,) [m], ``displacements`` (5,) [m] of the
            masses towards the seat, measured from their set-up positions (the document's
            ``x_j - x_OSZY``), ``stiffness`` [N/m].
        """
        length = self.free_length - total_compression
        force, x, kt = self.static_state(length)
        dx = x - self.chain.setup_compressions
        return dict(force=float(force), compressions=x, displacements=np.cumsum(dx)[:-1], stiffness=float(kt))

    def static_curve(self, start: float | None = None, stop: float | None = None, points: int = 400):
        """Static force and stiffness against length, from ``start`` down to ``stop`` [m].

        Defaults: from the free length to the length where the force reaches three times
        the coil-contact force Fcon (well past coil contact).
        """
        from .results import StaticCurve

        if points < 2:
            raise InputError(f"points = {points} must be at least 2")
        start = self.free_length if start is None else float(start)
        if stop is None:
            stop = self.length_at_force(3.0 * self.internal_parameters()["Fcon"])
        self._compression(np.array([start]), "--from")
        self._compression(np.array([stop]), "--to")
        length = np.linspace(start, stop, points)
        force, _, k = self.static_state(length)
        return StaticCurve(self, length, force, k)

    # ------------------------------------------------------------------ modes
    def modes(self, length: float, count: int = 5) -> np.ndarray:
        """Natural frequencies [Hz], ascending, of the chain linearised at ``length`` [m], ends fixed."""
        if not 1 <= count <= 5:
            raise InputError(f"count = {count} must be between 1 and 5 (the chain has 5 masses)")
        _, x, _ = self.static_state(float(length))
        return chain_frequencies(self.chain.masses, self.chain.tangent_stiffness(x))[:count]

    # ------------------------------------------------------------------ design
    def design_figures(self, lift: float | None = None, cam_rpm: float | None = None) -> dict:
        """Design figures at installed length, at maximum lift and at coil contact.

        Parameters
        ----------
        lift : float, optional
            Maximum valve lift [m]; the open length is ``Ls - lift``.
        cam_rpm : float, optional
            Camshaft speed [rev/min], for the surge margin.

        Returns
        -------
        dict
            ``spring_index``, ``bergstraesser_factor``, ``wahl_factor``, ``solid_length_m``,
            ``spring_mass_kg``, ``rate_free_N_per_m`` and, per state (``installed``,
            ``open`` if lift is given, ``coil_contact``): ``length_m``, ``force_N``,
            ``shear_stress_Pa`` (Bergstraesser-corrected), ``surge_frequency_Hz`` (first
            mode of the linearised chain) and, with ``cam_rpm``, ``surge_margin``.
        """
        p = self.internal_parameters()
        c = design.spring_index(self.mean_diameter, self.wire_diameter)
        kb = design.bergstraesser_factor(c)
        out = dict(
            spring_index=c,
            bergstraesser_factor=kb,
            wahl_factor=design.wahl_factor(c),
            solid_length_m=p["Lc"],
            spring_mass_kg=p["M"],
            rate_free_N_per_m=p["K1"],
            surge_frequency_free_Hz=p["f1"],
            surge_frequency_setup_Hz=p["f2"],
        )
        states = {"installed": self.installed_length}
        if lift is not None:
            if not lift > 0:
                raise InputError(f"lift = {_mm(lift)} must be positive")
            states["open"] = self.installed_length - lift
        states["coil_contact"] = self.length_at_force(p["Fcon"])
        for name, length in states.items():
            force = float(self.static_force(length)) if name != "open" else float(self._open_force(length, lift))
            f_surge = float(self.modes(length, 1)[0])
            st = dict(
                length_m=length,
                force_N=force,
                shear_stress_Pa=design.shear_stress(force, self.mean_diameter, self.wire_diameter, kb),
                surge_frequency_Hz=f_surge,
            )
            if cam_rpm is not None:
                st["surge_margin"] = design.surge_margin(f_surge, cam_rpm)
            out[name] = st
        return out

    def _open_force(self, length: float, lift: float) -> float:
        if length < self.min_length:
            raise InputError(
                f"lift = {_mm(lift)} drives the spring far past coil contact: installed_length - lift = "
                f"{_mm(length)} is below {_mm(self.min_length)}, where the force reaches "
                f"{self.LIMIT_FORCE_FACTOR:g} Fcon"
            )
        return self.static_force(length)
