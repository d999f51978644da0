"""Spring models of a valve-spring definition: the document's MMS Type C chain.

A :class:`~springdyn.valve.spring.ValveSpring` is the definition (geometry, material,
damping, the ``model`` key); a model turns it into equations.  Every model offers the
same interface, :class:`SpringModel`: the chain the dynamics engine integrates (masses,
element laws, damping), the static force and stiffness against length, the natural
frequencies, and the design figures.  :data:`MODELS` maps the ``[spring] model`` names to
the classes; a new model is a new class registered there.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..core.errors import InputError
from ..core.units import format_quantity
from . import design, formulas
from .elements import damping_coefficient, hardening_law, law_compression, law_stiffness, linear_law, low_pitch_law
from .modes import chain_frequencies
from .statics import element_compressions, series_state

__all__ = ["SpringModel", "TypeCModel", "Chain", "MODELS", "make_model", "PARAMETER_UNITS"]

ONE_STEP_ELEMENTS = ("K", "Kh1", "Kh2", "Kh2", "Kh1", "K")
TWO_STEP_ELEMENTS = ("K", "Ks", "Kh1", "Kh2", "Kh1", "K")
ONE_STEP_MASSES = ("me", "m1", "m2", "m1", "me")
TWO_STEP_MASSES = ("me", "m1", "m2", "m2", "me")


#: SI unit, display unit and meaning of each internal parameter of :meth:`TypeCModel.internal_parameters`.
PARAMETER_UNITS = {
    "K": ("N/m", "N/mm", "contact stiffness of a coil"),
    "K1": ("N/m", "N/mm", "spring rate at free length"),
    "K2": ("N/m", "N/mm", "spring rate at set-up length"),
    "K3": ("N/m", "N/mm", "stiffened rate 1.15 K2"),
    "Kh1": ("N/m", "N/mm", "chain element Kh1"),
    "Kh2": ("N/m", "N/mm", "chain element Kh2"),
    "Ks": ("N/m", "N/mm", "low-pitch element Ks"),
    "m1": ("kg", "g", "chain mass m1"),
    "m2": ("kg", "g", "chain mass m2"),
    "me": ("kg", "g", "end mass me"),
    "M": ("kg", "g", "spring mass"),
    "f1": ("Hz", "Hz", "surge frequency, free length"),
    "f2": ("Hz", "Hz", "surge frequency, set-up length"),
    "n1p": ("", "", "pitch term n1'"),
    "n2p": ("", "", "pitch term n2'"),
    "Pc": ("m", "mm", "coil gap term"),
    "Lc": ("m", "mm", "solid length"),
    "Fset": ("N", "N", "set-up force"),
    "F1": ("N", "N", "first nonlinear force"),
    "F2": ("N", "N", "second nonlinear force"),
    "Fcon": ("N", "N", "coil-contact force"),
    "C0": ("N*s/m", "N*s/m", "element damping C0"),
    "f_continuum": ("Hz", "Hz", "continuum surge frequency of the active coils"),
    "elements": ("", "", "wire elements"),
    "beta": ("s", "s", "stiffness-proportional damping (mode 1 at set-up gets damping_ratio)"),
    "pitch_max": ("m", "mm", "largest pitch of the unloaded spring"),
}


@dataclass(frozen=True)
class Chain:
    """A spring as a chain of point masses joined by nonlinear elements, SI throughout.

    Elements are numbered from the seat (element 0 touches the fixed seat, the last one
    the retainer); mass ``i`` sits between elements ``i`` and ``i + 1``.
    """

    element_names: tuple
    mass_names: tuple
    masses: np.ndarray  # (n,) [kg]
    laws: np.ndarray  # (n + 1, segments, 4)
    c0: float | np.ndarray  # [N s/m], one value or one per element
    setup_compressions: np.ndarray  # (n + 1,) [m], every element at Fset
    setup_force: float  # [N]
    free_length: float  # [m]
    installed_length: float  # [m]

    @property
    def c0_array(self) -> np.ndarray:
        """Damping coefficient of every element at its initial rate [N s/m], shape (n + 1,)."""
        return np.ascontiguousarray(np.broadcast_to(np.asarray(self.c0, dtype=float), (self.laws.shape[0],)))

    def tangent_stiffness(self, compressions) -> np.ndarray:
        """Element tangent stiffnesses [N/m] at the given compressions [m]."""
        return np.stack([law_stiffness(x, law) for x, law in zip(compressions, self.laws)])

    def damping(self, compressions) -> np.ndarray:
        """Element damping coefficients [N s/m] at the given compressions [m]."""
        return np.stack([damping_coefficient(x, law, c) for x, law, c in zip(compressions, self.laws, self.c0_array)])


def _mm(value: float) -> str:
    return format_quantity(value, "m", "mm")


class SpringModel:
    """Interface of a valve-spring model (see the module docstring).

    Subclasses define :attr:`name`, :meth:`internal_parameters`, :attr:`chain` and
    :attr:`min_length`; statics, modes and design figures follow from the chain.
    """

    #: The ``[spring] model`` name.
    name = ""
    #: What the model is, for people.
    description = ""
    #: The model is evaluated down to the length where the static force reaches this
    #: multiple of Fcon; beyond ``2 Fcon`` the coil-contact branch is already an
    #: extrapolation (correction MMS-9 of docs/references.md), beyond ``10 Fcon``
    #: springdyn refuses.
    LIMIT_FORCE_FACTOR = 10.0

    def __init__(self, spring):
        self.spring = spring

    def __repr__(self) -> str:
        p = self.internal_parameters()
        s = self.spring
        return (f"<{type(self).__name__}: {self.description}; {s.type} spring, "
                f"{len(self.chain.masses)} masses, K1 = {p['K1']:.6g} N/m, f1 = {p['f1']:.5g} Hz, "
                f"Fset = {p['Fset']:.5g} N>")

    # ------------------------------------------------------------------ to define
    def internal_parameters(self) -> dict:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def chain(self) -> Chain:  # pragma: no cover - abstract
        raise NotImplementedError

    def contact_compressions(self) -> np.ndarray:  # pragma: no cover - abstract
        """Compression [m] of each element beyond which its coils touch (``inf``: never flagged)."""
        raise NotImplementedError

    # ------------------------------------------------------------------ statics
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
        bad = ~np.isfinite(length) | (length > self.spring.free_length) | (length < lo)
        if np.any(bad):
            raise InputError(
                f"{name} = {_mm(float(np.ravel(length)[np.ravel(bad)][0]))} is outside the range of the spring: "
                f"it must lie between {_mm(lo)} (where the force reaches {self.LIMIT_FORCE_FACTOR:g} Fcon, far past "
                f"coil contact) and the free length Lf = {_mm(self.spring.free_length)}"
            )
        return self.spring.free_length - length

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
        return float(self.spring.free_length - element_compressions(force, self.chain.laws).sum())

    def initial_condition(self, total_compression: float):
        """Static state at a total compression ``dL = (Lf - Ls) + lift`` [m] (notes 1.5).

        Returns
        -------
        dict
            ``force`` [N], ``compressions`` (6,) [m], ``displacements`` (5,) [m] of the
            masses towards the seat, measured from their set-up positions (the document's
            ``x_j - x_OSZY``), ``stiffness`` [N/m].
        """
        length = self.spring.free_length - total_compression
        force, x, kt = self.static_state(length)
        dx = x - self.chain.setup_compressions
        return dict(force=float(force), compressions=x, displacements=np.cumsum(dx)[:-1], stiffness=float(kt))

    def static_curve(self, start: float | None = None, stop: float | None = None, points: int = 400):
        """Static force and stiffness against length, from ``start`` down to ``stop`` [m].

        Defaults: from the free length to the length where the force reaches three times
        the coil-contact force Fcon (well past coil contact).
        """
        from .results import StaticCurve

        if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or points < 2:
            raise InputError(f"points = {points!r} must be a whole number of at least 2")
        start = self.spring.free_length if start is None else float(start)
        if stop is None:
            stop = self.length_at_force(3.0 * self.internal_parameters()["Fcon"])
        self._compression(np.array([start]), "start")
        self._compression(np.array([stop]), "stop")
        length = np.linspace(start, stop, points)
        force, x, k = self.static_state(length)
        ch = self.chain
        kt = ch.tangent_stiffness(x)
        freq = np.array([chain_frequencies(ch.masses, kt[:, i], 1)[0] for i in range(length.size)])
        return StaticCurve(self.spring, length, force, k, model=self.name, frequency=freq)

    # ------------------------------------------------------------------ modes
    def modes(self, length: float, count: int = 5) -> np.ndarray:
        """Natural frequencies [Hz], ascending, of the chain linearised at ``length`` [m], ends fixed.

        Parameters
        ----------
        length : float
            Spring length [m].
        count : int
            How many, from the lowest (at most the number of masses).
        """
        n = len(self.chain.masses)
        if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or not 1 <= count <= n:
            raise InputError(f"count = {count!r} must be a whole number from 1 to {n} (the chain has {n} masses)")
        _, x, _ = self.static_state(float(length))
        return chain_frequencies(self.chain.masses, self.chain.tangent_stiffness(x), count)

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
        c = design.spring_index(self.spring.mean_diameter, self.spring.wire_diameter)
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
        states = {"installed": self.spring.installed_length}
        if lift is not None:
            if not lift > 0:
                raise InputError(f"lift = {_mm(lift)} must be positive")
            states["open"] = self.spring.installed_length - lift
        states["coil_contact"] = self.length_at_force(p["Fcon"])
        for name, length in states.items():
            force = float(self.static_force(length)) if name != "open" else float(self._open_force(length, lift))
            f_surge = float(self.modes(length, 1)[0])
            st = dict(
                length_m=length,
                force_N=force,
                shear_stress_Pa=design.shear_stress(force, self.spring.mean_diameter, self.spring.wire_diameter, kb),
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





class TypeCModel(SpringModel):
    """The document's MMS Type C: 5 masses and 6 nonlinear spring-damper elements.

    Closed-form parameters of [MMS] ("Internal parameters", "Model variables"), the
    element laws with coil contact (corrections MMS-1 to MMS-9 of docs/references.md)
    and the chain topology of one-step and two-step springs:

    - one-step: ``seat -K- me -Kh1- m1 -Kh2- m2 -Kh2- m1 -Kh1- me -K- retainer``;
    - two-step: ``seat -K- me -Ks- m1 -Kh1- m2 -Kh2- m2 -Kh1- me -K- retainer``.

    Examples
    --------
    >>> from springdyn.valve import ValveSpring
    >>> m = TypeCModel(ValveSpring.example("one-step"))
    >>> round(m.internal_parameters()["Fset"], 2)
    251.43
    """

    name = "type-c"
    description = "MMS Type C (5 masses, 6 elements)"

    def __init__(self, spring):
        super().__init__(spring)
        self.check()

    @property
    def two_step(self) -> bool:
        return self.spring.two_step

    def _field(self, name: str) -> str:
        return self.spring._field(name)

    def check(self) -> None:
        """Conditions under which the closed-form parameters make a valid chain (raise InputError)."""
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
                    f"low_pitch_coils = {self.spring.low_pitch_coils:g} must exceed dead_coils = {self.spring.dead_coils:g}"
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
        do, dw = self.spring.mean_diameter, self.spring.wire_diameter
        lf, ls = self.spring.free_length, self.spring.installed_length
        n1, n2, nb = self.spring.low_pitch_coils, self.spring.high_pitch_coils, self.spring.dead_coils
        g, rho = self.spring.shear_modulus, self.spring.density
        na1 = formulas.active_coils_free(n1, n2, nb)
        na2 = formulas.active_coils_setup(n1, n2, nb, self.two_step)
        k = formulas.contact_stiffness(do, self.spring.youngs_modulus)
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
        c0 = 2.0 * self.spring.damping_ratio * np.sqrt(m_total * k1)
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
            named["Ks"], bs = low_pitch_law(p["Ks"], p["Fset"], self.spring.wire_diameter)
            bp.update(x1=bs["x1"], x2=bs["x2"])
        return named, bp

    def contact_compressions(self) -> np.ndarray:
        """Compression [m] of each element beyond which its coils touch: the Fcon breakpoint.

        Only the Kh1/Kh2 elements have one (x13/x23 of [MMS], element force laws).  The end
        elements K already stand for contacting coils and the low-pitch element Ks is closed
        by design from set-up on, so neither is ever flagged (``inf``).
        """
        fcon = self._parameters["Fcon"]
        return np.array([float(law_compression(fcon, law)) if name.startswith("Kh") else np.inf
                         for name, law in zip(self.chain.element_names, self.chain.laws)])

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
            free_length=self.spring.free_length,
            installed_length=self.spring.installed_length,
        )


def _models() -> dict:
    from .distributed import DistributedModel

    return {TypeCModel.name: TypeCModel, DistributedModel.name: DistributedModel}


#: The spring models, by their ``[spring] model`` name.
MODELS = _models()


def make_model(spring, name: str | None = None) -> SpringModel:
    """The model ``name`` (default: the definition's ``model`` key) of a spring definition.

    Parameters
    ----------
    spring : ValveSpring
        The spring definition.
    name : str, optional
        A key of :data:`MODELS`; overrides ``spring.model``.
    """
    name = spring.model if name is None else name
    if name not in MODELS:
        raise InputError(f"model = {name!r} is not a valve-spring model; choose one of {', '.join(map(repr, MODELS))}")
    return MODELS[name](spring)
