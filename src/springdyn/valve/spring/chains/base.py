"""The interface of a valve-spring model and the chain of masses every model builds.

:class:`Chain` holds masses, element laws and damping; :class:`SpringModel` derives
statics, modes and design figures from it (the statics and modes from its
:attr:`~SpringModel.static_chain`, which a model may give without the damping).  The models
themselves live in :mod:`.type_c` and :mod:`.distributed`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ....core.errors import InputError
from ....core.units import format_mm
from .. import formulas, stress
from ..elements import damping_coefficient, law_force, law_stiffness
from ..modes import chain_frequencies, mode_labels, surge_margin
from ..results import StaticCurve
from ..solid_length import check_coil_bind
from ..statics import element_compressions, series_force, series_state
from ..wire import equivalent_diameters, stress_per_force

__all__ = ["Chain", "SpringModel"]


#: Most points of a static curve (:meth:`SpringModel.static_curve`): 0.1 um steps over 100 mm.
MAX_CURVE_POINTS = 1_000_000


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

    @cached_property
    def c0_array(self) -> np.ndarray:
        """Damping coefficient of every element at its initial rate [N s/m], shape (n + 1,)
        (computed once: a chain is immutable; a writable copy, the array type the compiled
        engine is compiled for)."""
        return np.array(np.broadcast_to(np.asarray(self.c0, dtype=float), (self.laws.shape[0],)))

    def tangent_stiffness(self, compressions) -> np.ndarray:
        """Element tangent stiffnesses [N/m] at the given compressions [m].

        Parameters
        ----------
        compressions : array_like
            Element compressions [m], one per element.
        """
        return np.stack([law_stiffness(x, law) for x, law in zip(compressions, self.laws)])

    def damping(self, compressions) -> np.ndarray:
        """Element damping coefficients [N s/m] at the given compressions [m].

        Parameters
        ----------
        compressions : array_like
            Element compressions [m], one per element.
        """
        return np.stack([damping_coefficient(x, law, c) for x, law, c in zip(compressions, self.laws, self.c0_array)])


class SpringModel:
    """Interface of a valve-spring model (see the module docstring).

    Subclasses define :attr:`name`, :meth:`internal_parameters`, :attr:`chain` and
    :attr:`min_length`; statics, modes and design figures follow from the chain.  The statics
    and modes read :attr:`static_chain` and :attr:`coil_contact_force`, which a model whose
    damping or parameters cost more than its laws may give without them.
    """

    #: The ``[spring] model`` name.
    name = ""
    #: What the model is, for people.
    description = ""
    #: The meaning of a parameter where this model's definition differs from
    #: :data:`~springdyn.valve.spring.formulas.PARAMETER_UNITS`' (``{key: meaning}``).
    PARAMETER_MEANINGS: dict = {}

    def parameter_meaning(self, key: str) -> str:
        """What the internal parameter ``key`` is in this model (its definition named).

        Parameters
        ----------
        key : str
            A key of :meth:`internal_parameters`.
        """
        from ..formulas import PARAMETER_UNITS  # (here: formulas sits beside the chains; kept out of import time)

        return self.PARAMETER_MEANINGS.get(key, PARAMETER_UNITS[key][2])

    @property
    def surge_frequency_definition(self) -> str:
        """The definition of the one first surge frequency every margin and check uses."""
        return f"the {self.name} chain's first mode, ends fixed"

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
        return (
            f"<{type(self).__name__}: {self.description}; {s.type} spring, "
            f"{len(self.chain.masses)} masses, K1 = {p['K1']:.6g} N/m, f1 = {p['f1']:.5g} Hz, "
            f"Fset = {p['Fset']:.5g} N>"
        )

    # ------------------------------------------------------------------ to define
    def internal_parameters(self) -> dict:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def chain(self) -> Chain:  # pragma: no cover - abstract
        raise NotImplementedError

    @property
    def static_chain(self) -> Chain:
        """The chain the statics and modes read: its masses, element laws, set-up compressions
        and set-up force, the same as :attr:`chain`'s; its damping may be left out (here: the
        chain itself)."""
        return self.chain

    @property
    def coil_contact_force(self) -> float:
        """The coil-contact force Fcon [N] (:meth:`internal_parameters`' ``Fcon``), which
        :attr:`min_length` scales."""
        return self._parameters["Fcon"]

    def contact_compressions(self) -> np.ndarray:  # pragma: no cover - abstract
        """Compression [m] of each element beyond which its coils touch (``inf``: never flagged)."""
        raise NotImplementedError

    @cached_property
    def contact_forces(self) -> np.ndarray:
        """Static force [N] at which each element reaches its contact compression (``inf``
        where it never counts as contact); the laws are strictly increasing."""
        return np.array(
            [
                float(law_force(x, law)) if np.isfinite(x) else np.inf
                for x, law in zip(self.contact_compressions(), self.static_chain.laws)
            ]
        )

    #: Coil clash needs the static spring at the same lift to hold the element open by at
    #: least this much force [fraction of Fset]: a slow closing at the force of its gap, or
    #: the surge of a few per cent of Fset at low speed, is contact, not clash.
    CLASH_MARGIN = 0.05

    def clash(self, contact, static_force) -> np.ndarray:
        """Coil clash: an element in coil contact where the static (massless) spring at the
        same lift holds it open, by :attr:`CLASH_MARGIN` of Fset or more.  Coils that close
        quasi-statically (a two-step spring's transition at full lift) are contact, not clash.

        Parameters
        ----------
        contact : ndarray of bool (N + 1, ...)
            Each element past its contact compression [-].
        static_force : ndarray (...)
            The static spring force at the same instants [N].

        Returns
        -------
        ndarray of bool (N + 1, ...)
        """
        shape = (-1,) + (1,) * np.ndim(static_force)
        margin = self.CLASH_MARGIN * self.static_chain.setup_force
        below = np.asarray(static_force)[None, ...] < self.contact_forces.reshape(shape) - margin
        return np.asarray(contact, bool) & below

    def element_setup_forces(self) -> np.ndarray:
        """The set-up force [N] each element's coil clash is graded over (N + 1,): the spring's Fset
        (a spring pack's: each element's own spring's, :class:`springdyn.valve.spring.pack.PackModel`)."""
        ch = self.static_chain
        return np.full(len(ch.laws), float(ch.setup_force))

    def contact_share(self, elastic_force) -> np.ndarray:
        """The part of each element's elastic force [N] that closed coils pass through their
        contact, not the wire in torsion (the wire's torsion is the rest).

        Beyond an element's contact compression its coils touch: a further force goes
        through the contact, so the wire's torsion stays at the force of first contact
        (the Type C chain's ``Fcon``).  The distributed chain refines this per turn-slice.

        Parameters
        ----------
        elastic_force : ndarray (N + 1, ...)
            Elastic (law) force of each element [N].

        Returns
        -------
        ndarray (N + 1, ...)
            Force through the contact [N], ``>= 0``; NaN for an element that is no wire.
        """
        f = np.asarray(elastic_force, dtype=float)
        out = np.zeros_like(f)
        for j, (x, law) in enumerate(zip(self.contact_compressions(), self.static_chain.laws)):
            if np.isfinite(x):
                out[j] = np.maximum(f[j] - float(law_force(x, law)), 0.0)
        return out

    def wire_forces(self, compression, force) -> np.ndarray:
        """The wire's torsion of each element, as an axial force [N]: the element force less
        what closed coils pass through their contact (:meth:`contact_share`).

        Parameters
        ----------
        compression : ndarray (N + 1, ...)
            Element compressions [m].
        force : ndarray (N + 1, ...)
            Element forces [N] (elastic and damping).

        Returns
        -------
        ndarray (N + 1, ...)
            [N]; NaN for an element that is no wire (the distributed chain's end contacts).
        """
        x = np.asarray(compression, dtype=float)
        elastic = np.stack([law_force(x[j], law) for j, law in enumerate(self.static_chain.laws)])
        return np.asarray(force, dtype=float) - self.contact_share(elastic)

    @cached_property
    def contact_gaps(self) -> np.ndarray:
        """:meth:`contact_compressions` as the engine reads it: a contiguous array [m] (``inf``: never)."""
        return np.ascontiguousarray(self.contact_compressions(), dtype=float)

    @cached_property
    def fastest_mode(self) -> float:
        """Highest natural frequency of the chain at installed length [Hz]."""
        return float(self.modes(self.spring.installed_length, len(self.static_chain.masses))[-1])

    @cached_property
    def lift_at_coil_contact(self) -> float:
        """Lift [m] from the installed length at which the static force reaches Fcon."""
        return self.spring.installed_length - self.length_at_force(self.coil_contact_force)

    @cached_property
    def force_table(self) -> tuple:
        """Static force [N] at 129 total compressions [m] from zero to the model's limit (the
        starts of the engine's compiled Newton solver: two or three iterations instead of ten)."""
        x = np.linspace(0.0, self.spring.free_length - self.min_length, 129)
        return x, np.asarray(series_force(x, self.static_chain.laws), dtype=float)

    # ------------------------------------------------------------------ statics
    @cached_property
    def min_length(self) -> float:
        """Shortest length [m] springdyn evaluates: where the static force is 10 Fcon.

        Note that the document's solid length ``Lc = Dw (N1 + N2 + 0.5)`` is *not* the
        model's limit: the element laws reach Fcon at a shorter length (25.9 mm against
        Lc = 28 mm for the one-step example), so Lc is reported as a design figure only.
        """
        return self.length_at_force(self.LIMIT_FORCE_FACTOR * self.coil_contact_force)

    def _compression(self, length, name: str = "length"):
        length = np.asarray(length, dtype=float)
        lo = self.min_length
        bad = ~np.isfinite(length) | (length > self.spring.free_length) | (length < lo)
        if np.any(bad):
            raise InputError(
                f"{name} = {format_mm(float(np.ravel(length)[np.ravel(bad)][0]))} is outside the range of the spring: "
                f"it must lie between {format_mm(lo)} (where the force reaches {self.LIMIT_FORCE_FACTOR:g} Fcon, far past "
                f"coil contact) and the free length Lf = {format_mm(self.spring.free_length)}"
            )
        return self.spring.free_length - length

    def static_state(self, length):
        """Static force [N], element compressions [m] and tangent stiffness [N/m] at a length [m].

        Parameters
        ----------
        length : float or array_like
            Spring length [m].
        """
        return series_state(self._compression(length), self.static_chain.laws)

    def static_force(self, length):
        """Static (massless) spring force [N] at spring length ``length`` [m].

        Series equilibrium of the six elements: equal force, compressions summing to
        ``Lf - length`` (correction MMS-10 of docs/references.md).  Valid from the free length down to :attr:`min_length`.

        Parameters
        ----------
        length : float or array_like
            Spring length [m].
        """
        return self.static_state(length)[0]

    def static_stiffness(self, length):
        """Static tangent stiffness ``-dF/dL`` [N/m] at spring length ``length`` [m].

        Parameters
        ----------
        length : float or array_like
            Spring length [m].
        """
        return self.static_state(length)[2]

    def length_at_force(self, force: float) -> float:
        """Spring length [m] at which the static force is ``force`` [N].

        Parameters
        ----------
        force : float
            Static force [N], from 0 to the model's limit.
        """
        return float(self.spring.free_length - element_compressions(force, self.static_chain.laws).sum())

    def initial_condition(self, total_compression: float):
        """Static state at a total compression ``dL = (Lf - Ls) + lift`` [m] (correction MMS-10 of docs/references.md).

        Parameters
        ----------
        total_compression : float
            Total compression ``(Lf - Ls) + lift`` [m].


        Returns
        -------
        dict
            ``force`` [N], ``compressions`` (6,) [m], ``displacements`` (5,) [m] of the
            masses towards the seat, measured from their set-up positions (the document's
            ``x_j - x_OSZY``), ``stiffness`` [N/m].
        """
        length = self.spring.free_length - total_compression
        force, x, kt = self.static_state(length)
        dx = x - self.static_chain.setup_compressions
        return dict(force=float(force), compressions=x, displacements=np.cumsum(dx)[:-1], stiffness=float(kt))

    def static_curve(self, start: float | None = None, stop: float | None = None, points: int = 400):
        """Static force and stiffness against length, from ``start`` down to ``stop`` [m].

        Defaults: from the free length to the length where the force reaches three times
        the coil-contact force Fcon (well past coil contact).

        Parameters
        ----------
        start, stop : float, optional
            Lengths [m] (default: the free length down to the model's limit).
        points : int
            Samples [-].
        """
        if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or not 2 <= points <= MAX_CURVE_POINTS:
            raise InputError(
                f"points = {points!r} must be a whole number of at least 2 and at most {MAX_CURVE_POINTS} (a curve "
                "of more points shows nothing new and would not fit in memory)"
            )
        start = self.spring.free_length if start is None else float(start)
        if stop is None:
            stop = self.length_at_force(3.0 * self.coil_contact_force)
        self._compression(np.array([start]), "start")
        self._compression(np.array([stop]), "stop")
        length = np.linspace(start, stop, points)
        force, x, k = self.static_state(length)
        ch = self.static_chain
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
            How many, from the lowest (at most the number of masses) [-].
        """
        ch = self.static_chain
        n = len(ch.masses)
        if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or not 1 <= count <= n:
            raise InputError(f"count = {count!r} must be a whole number from 1 to {n} (the chain has {n} masses)")
        _, x, _ = self.static_state(float(length))
        return chain_frequencies(ch.masses, ch.tangent_stiffness(x), count)

    @cached_property
    def stress_per_force(self) -> float:
        """The wire's largest corrected shear stress per newton of spring force [Pa/N]
        (:func:`springdyn.valve.spring.wire.stress_per_force`: the section's factor; the
        distributed model takes the largest over its coils)."""
        return stress_per_force(self.spring)

    @cached_property
    def first_mode_installed(self) -> float:
        """First natural frequency of the chain at installed length [Hz] (kept: every run checks it)."""
        return float(self.modes(self.spring.installed_length, 1)[0])

    def linear_rate_force(self, length):
        """EN 13906-1's linear-rate force at a spring length [N]: ``K1`` from free length, a
        two-step spring's ``K2`` below the installed length, no coil closing
        (:func:`springdyn.valve.spring.formulas.linear_rate_force`; the figure a spring maker
        checks a drawing's load points with).

        Parameters
        ----------
        length : float or array_like
            Spring length [m].
        """
        sp = self.spring
        n1, n2, nb = sp.low_pitch_coils, sp.high_pitch_coils, sp.dead_coils
        g, d, dm = sp.shear_modulus, equivalent_diameters(sp)["rate"], sp.mean_diameter
        k1 = formulas.free_length_stiffness(g, d, dm, formulas.active_coils_free(n1, n2, nb))
        k2 = formulas.free_length_stiffness(g, d, dm, formulas.active_coils_setup(n1, n2, nb, sp.two_step))
        return formulas.linear_rate_force(length, sp.free_length, sp.installed_length, k1, k2)

    def stiffening_start_length(self) -> float | None:
        """Length [m] below which the model's force law stiffens by a rule rather than by coils
        that touch (Type C: above its F1); None for a model that follows the coils.
        """
        return None

    def load_point_check(self) -> list[dict]:
        """The model's static force at each load point of the drawing (``load_points``).

        Returns
        -------
        list of dict
            ``length_m``, ``force_N`` (the drawing's), ``model_force_N``, ``linear_force_N``
            (EN 13906-1's linear rate, :meth:`linear_rate_force`), ``stiffened_by_law`` (the
            model's law stiffens there while the coils are open, :meth:`stiffening_start_length`),
            ``deviation_N`` (model minus drawing), ``deviation_percent``, ``tolerance_N`` (None:
            not given) and ``within_tolerance`` (None without a tolerance).
        """
        rows = []
        for p in self.spring.load_point_table:
            if not self.min_length <= p["length"] <= self.spring.free_length:
                raise InputError(
                    f"load point at {p['length'] * 1e3:.4g} mm lies outside the spring's range "
                    f"({self.min_length * 1e3:.4g} mm to the free length {self.spring.free_length * 1e3:.4g} mm)"
                )
            f = float(self.static_force(p["length"]))
            dev = f - p["force"]
            tol = p["tolerance"]
            start = self.stiffening_start_length()
            rows.append(
                dict(
                    length_m=p["length"],
                    force_N=p["force"],
                    model_force_N=f,
                    linear_force_N=float(self.linear_rate_force(p["length"])),
                    stiffened_by_law=bool(start is not None and p["length"] < start),
                    deviation_N=dev,
                    deviation_percent=100.0 * dev / p["force"],
                    tolerance_N=tol,
                    within_tolerance=None if tol is None else bool(abs(dev) <= tol),
                )
            )
        return rows

    def mode_labels(self, length: float, count: int = 5) -> list[str]:
        """What each of :meth:`modes` is: ``"surge n"`` or ``"end mass"``
        (:func:`springdyn.valve.spring.modes.mode_labels`).

        Parameters
        ----------
        length : float
            Spring length [m].
        count : int
            How many, from the lowest [-].
        """
        _, x, _ = self.static_state(float(length))
        ch = self.static_chain
        return mode_labels(ch.masses, ch.tangent_stiffness(x), count)

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
            ``spring_index``, ``bergstraesser_factor``, ``wahl_factor``, ``solid_length_m``
            (and its ``solid_length_source``), ``total_coils``, ``active_coils``,
            ``dead_coils_per_end``, ``load_points`` (with load points,
            :func:`springdyn.valve.design.calibrate.load_point_check`), ``spring_mass_kg``,
            ``rate_free_N_per_m``, ``model`` (and ``elements``), ``surge_frequency_definition``,
            ``surge_frequency_free_Hz`` (the chain's at free length) and, per state (``installed``,
            ``open`` if lift is given, ``coil_contact``): ``length_m``, ``force_N``,
            ``shear_stress_Pa`` (corrected by the section's factor, ``stress_factor``, of
            ``wire_section``: Bergstraesser's for round and ovate wire, Goehner's for rectangular;
            ``stress_factor_name`` says which; ``bergstraesser_factor`` is Bergstraesser's at
            ``D/b`` whatever the wire), ``surge_frequency_Hz`` (first
            mode of the linearised chain) and, with ``cam_rpm``, ``surge_margin``.
        """
        if cam_rpm is not None and (
            isinstance(cam_rpm, bool)
            or not isinstance(cam_rpm, (int, float, np.number))
            or not (np.isfinite(cam_rpm) and cam_rpm >= 0.1)
        ):
            raise InputError(
                f"cam_rpm = {cam_rpm!r} must be a finite camshaft speed of at least 0.1 rev/min: the surge "
                "margin is the surge frequency over the camshaft frequency"
            )
        p = self.internal_parameters()
        wire = self.spring.wire
        c = wire.spring_index(self.spring.mean_diameter)
        kb = stress.bergstraesser_factor(c)
        out = dict(
            spring_index=c,
            bergstraesser_factor=kb,
            wahl_factor=stress.wahl_factor(c),
            wire_section=wire.label,
            stress_factor=float(wire.stress_factor(self.spring.mean_diameter)),
            stress_factor_name=wire.stress_factor_name,
            **{k: v for k, v in self.spring.coil_facts.items() if k != "free_length_m"},
            spring_mass_kg=p["M"],
            rate_free_N_per_m=p["K1"],
            model=self.name,
            surge_frequency_definition=self.surge_frequency_definition,
            surge_frequency_free_Hz=float(self.modes(self.spring.free_length, 1)[0]),
        )
        if "elements" in p:
            out["elements"] = int(p["elements"])
        states = {"installed": self.spring.installed_length}
        if lift is not None:
            if not lift > 0:
                raise InputError(f"lift = {format_mm(lift)} must be positive")
            states["open"] = self.spring.installed_length - lift
            out["coil_bind"] = check_coil_bind(self.spring, lift, f"lift = {format_mm(lift)}")
        states["coil_contact"] = self.length_at_force(p["Fcon"])
        lc = out["solid_length_m"]
        if states["coil_contact"] < lc - 1e-9:
            out["coil_contact_note"] = (
                f"the {self.name} model's coil-contact force Fcon = {p['Fcon']:.4g} N is reached at "
                f"{format_mm(states['coil_contact'])}, {format_mm(lc - states['coil_contact'])} below the solid "
                f"length {format_mm(lc)}: its forces between the two lengths are not those of a solid spring"
            )
        if self.spring.load_points:
            out["load_points"] = self.load_point_check()
        for name, length in states.items():
            force = float(self.static_force(length)) if name != "open" else float(self._open_force(length, lift))
            f_surge = float(self.modes(length, 1)[0])
            st = dict(
                length_m=length,
                force_N=force,
                shear_stress_Pa=float(force * self.stress_per_force),
                surge_frequency_Hz=f_surge,
            )
            if cam_rpm is not None:
                st["surge_margin"] = surge_margin(f_surge, cam_rpm)
            out[name] = st
        if "open" in out:  # fatigue of the static cycle installed -> open (issue 13)
            fat = stress.fatigue_assessment(self.spring, out["installed"]["force_N"], out["open"]["force_N"])
            copied = "min_shear_stress_Pa max_shear_stress_Pa endurance_shear_strength_Pa ultimate_shear_strength_Pa"
            out["fatigue"] = dict(
                static_fatigue_safety_factor=fat["fatigue_safety_factor"],
                **{key: fat[key] for key in copied.split()},
                strength_defaults=fat["strength_defaults"],
                note="the dynamic factor needs a simulation: valve simulate reports it beside this one",
            )
        return out

    def _open_force(self, length: float, lift: float) -> float:
        if length < self.min_length:
            raise InputError(
                f"lift = {format_mm(lift)} drives the spring far past coil contact: installed_length - lift = "
                f"{format_mm(length)} is below {format_mm(self.min_length)}, where the force reaches "
                f"{self.LIMIT_FORCE_FACTOR:g} Fcon"
            )
        return self.static_force(length)
