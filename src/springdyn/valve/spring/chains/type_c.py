"""The document's MMS Type C chain: 5 masses and 6 nonlinear elements from closed forms.

The internal parameters ([MMS], :mod:`springdyn.valve.spring.formulas`) give the masses and the
element laws (:mod:`springdyn.valve.spring.elements`) of the one-step and two-step chains
(topologies in docs/valve-spring.md); the rest of the interface comes from
:class:`~.base.SpringModel`.
"""

from __future__ import annotations

import warnings
from functools import cached_property

import numpy as np

from ....core.errors import FactWarning, InputError
from .. import formulas
from ..elements import hardening_law, law_compression, linear_law, low_pitch_law
from ..formulas import PARAMETER_UNITS
from ..statics import element_compressions
from ..wire import equivalent_diameters
from .base import Chain, SpringModel  # noqa: F401 (Chain: the return type)

__all__ = ["TypeCModel", "PARAMETER_UNITS"]

ONE_STEP_ELEMENTS = ("K", "Kh1", "Kh2", "Kh2", "Kh1", "K")
TWO_STEP_ELEMENTS = ("K", "Ks", "Kh1", "Kh2", "Kh1", "K")
ONE_STEP_MASSES = ("me", "m1", "m2", "m1", "me")
TWO_STEP_MASSES = ("me", "m1", "m2", "m2", "me")


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
    PARAMETER_MEANINGS = {
        "f1": "Wahl closed form with n1', free length (calibrates the chain; comparison)",
        "f2": "Wahl closed form with n2', set-up length (calibrates the chain; comparison)",
        "Lc": "solid length (the spring's: F1 at Lc, Fcon at Lc - Dw as [MMS])",
    }

    def __init__(self, spring):
        super().__init__(spring)
        self.check()
        if spring.diameter_profile:  # (a wire_diameter_profile it takes: wire.equivalent_diameters)
            warnings.warn(
                FactWarning(
                    f"Type C and diameter_profile: the document's closed forms take one mean_diameter "
                    f'({spring.mean_diameter * 1e3:.4g} mm), not the profile; model = "distributed" follows it '
                    "coil by coil",
                    key=f"type c profile|{spring.diameter_profile!r}",
                ),
                stacklevel=3,
            )

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
    def stiffening_start_length(self) -> float:
        """Length [m] where the elements' force reaches F1 and the law stiffens (1.15 K2 above
        it, [MMS]): ``Ls - (F1 - Fset) / K2``, a rule of the document, not coils that touch."""
        p = self.internal_parameters()
        return float(self.spring.installed_length - (p["F1"] - p["Fset"]) / p["K2"])

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
        k = self.spring.contact_stiffness or formulas.contact_stiffness(do, self.spring.youngs_modulus)
        # the wire's section: the round wires of its rate, surge and mass (wire.py); dw stacks axially
        wire = equivalent_diameters(self.spring)
        k1 = formulas.free_length_stiffness(g, wire["rate"], do, na1)
        k2 = formulas.setup_stiffness(g, wire["rate"], do, na2) if self.two_step else k1
        n1p = formulas.pitch_correction(lf, dw, n1, n2, na1, do)
        n2p = formulas.pitch_correction(ls, dw, n1, n2, na2, do)
        f1 = formulas.surge_frequency(g, rho, wire["surge"], do, na1 + n1p)
        f2 = formulas.surge_frequency(g, rho, wire["surge"], do, na2 + n2p)
        m_total = formulas.total_mass(rho, do, wire["mass"], n1, n2)
        pc = formulas.coil_pitch(ls, dw, n1, n2)
        lc = self.spring.solid_length  # the spring's one solid length (the document's without end_type)
        fset = formulas.setup_force(lf, ls, k1)
        k3 = formulas.stiffened_rate(k2)
        f_1 = formulas.first_nonlinear_force(fset, ls, lc, pc, k2)
        f_2 = formulas.second_nonlinear_force(f_1, pc, k3)
        fcon = formulas.coil_contact_force(k1, k2, lf, ls, lc, dw)
        if self.two_step:
            mv = formulas.twostep_model_variables(k, k1, k2, f1, f2, m_total)
        else:
            mv = formulas.onestep_model_variables(k, k1, f1, m_total)
        c0 = 2.0 * self.spring.damping_ratio * np.sqrt(m_total * k1)
        p = dict(K=k, K1=k1, K2=k2, K3=k3, Kh1=mv["Kh1"], Kh2=mv["Kh2"])
        if self.two_step:
            p["Ks"] = mv["Ks"]
        p.update(
            m1=mv["m1"],
            m2=mv["m2"],
            me=mv["me"],
            M=m_total,
            f1=f1,
            f2=f2,
            n1p=n1p,
            n2p=n2p,
            Pc=pc,
            Lc=lc,
            Fset=fset,
            F1=f_1,
            F2=f_2,
            Fcon=fcon,
            C0=float(c0),
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
        return np.array(
            [
                float(law_compression(fcon, law)) if name.startswith("Kh") else np.inf
                for name, law in zip(self.chain.element_names, self.chain.laws)
            ]
        )

    @cached_property
    def chain(self) -> Chain:
        """The lumped 5-mass chain with its element laws and damping ([MMS], Figs. 40.32-40.33; topology in docs/valve-spring.md)."""
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
