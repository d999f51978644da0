"""The distributed (coil-by-coil) valve-spring model.

The active wire, from the seat's dead coils to the retainer's, is cut into ``elements``
pieces (:attr:`DistributedModel.element_turns`): coils closed at set-up get pieces up to
:data:`MAX_ELEMENT_STRETCH` times longer than the open coils' (length ~ sqrt of the
tangent over the open rate, :func:`stiffness_graded_edges`), so that no piece limits the
explicit step more than the others.  Each piece is an element with the axial stiffness and
the mass of its wire at the local mean diameter and pitch (:mod:`springdyn.valve.spring.geometry`);
its mass is lumped half to each end node.  The closed dead coils move with the end nodes
(their mass is added there) and touch seat and retainer through the end contacts, as in
Type C: ``seat -K- node 0 -k_1- node 1 ... node n -K- retainer``.  The same chain, laws and
engine as Type C (:class:`~springdyn.valve.spring.chains.Chain`), so statics, modes, frequency
response and dynamics are shared.

**Element law** (:func:`graded_coil_law`): an element is :data:`SLICES` turn-slices in
series (:func:`slice_states`).  A slice of ``ds`` turns has the open rate
``1 / (c_turn ds)`` (open-coil compliance per turn, Wahl) while its gap ``(p - Dw) ds`` is
open; when its compression reaches the gap its coils touch and the contact stiffness of a
closed turn, ``K / ds``, acts in parallel with the wire, built up linearly over the onset
``ds * CONTACT_ONSET * Dw`` (:func:`coil_law`).  The element's law follows the series of
its slices exactly at :data:`CLOSING_PIECES` knots, so graded coils (transitions, low-pitch
coils), whose slices close one after the other, converge with the element count.  ``K`` is
the spring's ``contact_stiffness``, by default ``pi D E / 1e3``, the document's "stiffness
for fully contact" of one coil ([MMS]), the stiffness Type C gives its end contacts.

**End contacts**: linear ``K`` at the end diameters, compression only (correction MMS-7).

**Damping**: every element carries ``c(x) = beta k0 sqrt(k(x)/k0)`` (the document's law
``C0 sqrt(k(x)/k(0))`` with ``C0 = beta k0`` per element): stiffness-proportional
(Kelvin-Voigt) damping of the wire, which gives mode ``j`` the damping ratio
``beta w_j / 2``.  ``beta`` is set so that the first mode at the set-up length has exactly
``damping_ratio``; the higher surge modes get ``damping_ratio * f_j / f_1`` (about ``j``
times it for the harmonic series), and the element-scale modes, which are artefacts of
the discretisation, are strongly damped.  Finding ``beta`` is an eigenvalue problem, so it
is left until the damping is asked for (:attr:`DistributedModel.chain`): the statics read
:attr:`DistributedModel.static_chain`, the chain without its damping, and the coil-contact
force comes from :meth:`DistributedModel.closing_forces`.
"""

from __future__ import annotations

import dataclasses
from functools import cached_property

import numpy as np

from ....core.docstrings import ParameterDocs
from ....core.errors import InputError
from ....core.units import format_quantity
from .. import formulas
from ..geometry import (
    CoilGeometry,
    check_profile_span,
    default_pitch_knots,
    end_allowance,
    parse_profile,
    turn_compliance,
    wire_length_per_turn,
)
from ..modes import chain_eigenvalues, chain_frequencies
from ..statics import element_compressions, series_force
from ..wire import equivalent_diameters, section_along, section_profile, stress_per_force, wire_stack
from .base import Chain, SpringModel

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    force : float or ndarray (...)
        Axial force [N], ``>= 0``.
    """,
    slices="k_slice, gap, k_contact, onset : ndarray (n,)\n    Per slice: open rate [N/m], gap [m], contact stiffness [N/m], onset width [m].",
)


__all__ = ["DistributedModel", "coil_law", "CONTACT_ONSET", "DEFAULT_ELEMENTS", "modal_damping"]

#: Default number of wire elements (convergence study in docs/valve-spring.md: peak and minimum
#: forces of the one-step example at 3000 and 4000 cam rpm change by less than 0.1 % of
#: Fset from 50 to 100 elements, and the surge modes 1-5 are within 1 % of the harmonic
#: series).
DEFAULT_ELEMENTS = 50
#: Width of the contact onset per turn, as a fraction of the wire diameter: the contact
#: stiffness builds up over ``0.05 Dw`` of closure per turn (coils touch first at their
#: high points).  A regularisation that makes the law C1; docs/valve-spring.md shows its effect.
CONTACT_ONSET = 0.05


def coil_law(k_wire: float, gap: float, k_contact: float, onset: float) -> np.ndarray:
    """Element law of a piece of wire with coil contact (the ``(3, 4)`` law format).

    ``F = k_w x`` for ``x < g``; ``F = k_w x + k_c (x - g)^2 / (2 w)`` for
    ``g <= x < g + w``; ``F = k_w x + k_c (x - g - w/2)`` beyond: C1 with the tangent
    stiffness rising from ``k_w`` to ``k_w + k_c``.

    Parameters
    ----------
    k_wire : float
        Rate of the open wire [N/m].
    gap : float
        Compression at which the coils touch [m], ``>= 0``.
    k_contact : float
        Contact stiffness added once closed [N/m].
    onset : float
        Compression over which the contact stiffness builds up [m], ``> 0``.
    """
    a = k_contact / (2.0 * onset)
    law = np.empty((3, 4))
    law[0] = (-np.inf, 0.0, k_wire, 0.0)
    law[1] = (gap, a, k_wire - 2.0 * a * gap, a * gap * gap)
    law[2] = (gap + onset, 0.0, k_wire + k_contact, -k_contact * (gap + 0.5 * onset))
    return law


#: Quadratic pieces with which an element's law follows the closing of its turn-slices
#: (:func:`graded_coil_law`): the tangent stiffness at the knots rises geometrically from the
#: open wire's to the closed coil's, so the compression error of the law against its
#: slices in series is below 6 % of the element's gap spread ``int |p - p_mean| ds / 2``.
CLOSING_PIECES = 8
#: Turn-slices per element for its integrals and its closing law.
SLICES = 64
#: Nodes of each element's table of the force through closed coils (:meth:`DistributedModel.contact_share`).
SHARE_NODES = 1200
#: Fine turn-slices over the active wire for the set-up state that places the element edges.
MESH_SLICES = 4000
#: Largest ratio of element lengths: coils closed at set-up get elements up to this much
#: longer than the open coils' (:func:`stiffness_graded_edges`; docs/valve-spring.md: 2 halves the
#: explicit steps against equal lengths and keeps clash forces within 1 % of Fset of 4x the
#: elements).
MAX_ELEMENT_STRETCH = 2.0


@_DOCS.fill
def slice_states(force, k_slice, gap, k_contact, onset) -> tuple[np.ndarray, np.ndarray]:
    """Compression [m] and tangent stiffness [N/m] of each turn-slice at ``force``.

    Each slice has the law of :func:`coil_law`: its open rate until its gap closes, then the
    contact stiffness of the closed turn added in parallel, built up over its onset.

    Parameters
    ----------
    {force slices}

    Returns
    -------
    e, k : ndarray (..., n)
        Compression [m] and tangent stiffness [N/m] of every slice.
    """
    f = np.asarray(force, dtype=float)[..., None]
    d, u = _slice_closing(f, k_slice, gap, k_contact, onset)
    closed = u >= onset
    e = np.where(
        d < 0, f / k_slice, np.where(closed, (f + k_contact * (gap + 0.5 * onset)) / (k_slice + k_contact), gap + u)
    )
    return e, _slice_tangent(d, u, k_slice, k_contact, onset)


def _slice_closing(f, k_slice, gap, k_contact, onset):
    """``d``, each slice's force beyond the closing of its gap [N] (< 0: open), and ``u``, its
    closure beyond the gap [m] (the root of ``k_slice u + k_contact u^2 / (2 onset) = d``)."""
    d = f - k_slice * gap
    u = 2.0 * d / (k_slice + np.sqrt(k_slice * k_slice + 2.0 * k_contact / onset * np.maximum(d, 0.0)))
    return d, u


def _slice_tangent(d, u, k_slice, k_contact, onset):
    """Tangent stiffness [N/m] of each slice from :func:`_slice_closing`'s ``d`` and ``u``."""
    closed = u >= onset
    return np.where(
        d < 0, k_slice, np.where(closed, k_slice + k_contact, k_slice + k_contact * np.maximum(u, 0.0) / onset)
    )


@_DOCS.fill
def slice_series_stiffness(force, k_slice, gap, k_contact, onset):
    """Tangent stiffness [N/m] of turn-slices in series at ``force``: :func:`slice_response`'s
    second output without their compressions (the closing law's grid needs only it).

    Parameters
    ----------
    {force slices}
    """
    d, u = _slice_closing(np.asarray(force, dtype=float)[..., None], k_slice, gap, k_contact, onset)
    return 1.0 / np.sum(1.0 / _slice_tangent(d, u, k_slice, k_contact, onset), axis=-1)


@_DOCS.fill
def slice_response(force, k_slice, gap, k_contact, onset):
    """Compression [m] and tangent stiffness [N/m] of turn-slices in series at ``force``
    (:func:`slice_states`): they carry the same force, so their compressions add and their
    compliances add.

    Parameters
    ----------
    {force slices}

    Returns
    -------
    x : ndarray (...)
        Compression of the slices together [m].
    k : ndarray (...)
        Their tangent stiffness in series [N/m].
    """
    e, k = slice_states(force, k_slice, gap, k_contact, onset)
    return e.sum(axis=-1), 1.0 / np.sum(1.0 / k, axis=-1)


def stiffness_graded_edges(turns: np.ndarray, stiffening: np.ndarray, elements: int, stretch: float) -> np.ndarray:
    """Element edges [turns] whose lengths grow as ``sqrt(stiffening)``, at most ``stretch``
    times the shortest.

    An element of length ``L`` whose tangent stiffness is ``kappa`` times its open rate has
    its fastest local mode at ``sqrt(kappa)/L`` times an open element's of unit length: with
    ``L ~ sqrt(kappa)`` every element limits the explicit step alike.

    Parameters
    ----------
    turns : ndarray (m + 1,)
        Edges of fine slices [turns], ascending.
    stiffening : ndarray (m,)
        Tangent over open rate of each fine slice [-], ``>= 1``.
    elements : int
        Number of elements [-].
    stretch : float
        Largest ratio of element lengths [-], ``>= 1``.
    """
    density = np.maximum(stiffening**-0.5, 1.0 / stretch) * np.diff(turns)
    measure = np.concatenate([[0.0], np.cumsum(density)])
    return np.interp(np.linspace(0.0, measure[-1], elements + 1), measure, turns)


@_DOCS.fill
def graded_coil_law(k_slice, gap, k_contact, onset, pieces: int = CLOSING_PIECES) -> np.ndarray:
    """Element law (``(pieces + 2, 4)``, the format of :mod:`springdyn.valve.spring.elements`) of
    turn-slices in series that close one after the other (:func:`slice_response`).

    Linear at the open rate until the first slice touches; then ``pieces`` quadratics
    whose tangent stiffness is exact at knots where it has risen by equal factors towards
    the closed rate (knots at the exact compressions; C1, convex); then linear at the
    closed rate.  A uniform element (every slice with the same gap) gives exactly
    :func:`coil_law`.

    Parameters
    ----------
    {slices}
    pieces : int
        Quadratic pieces over the closing [-].
    """
    k_open = 1.0 / np.sum(1.0 / k_slice)
    k_closed = 1.0 / np.sum(1.0 / (k_slice + k_contact))
    if all(np.ptp(v) == 0.0 for v in (k_slice, gap, k_contact, onset)):
        # a uniform element (its slices alike, as along a constant pitch): coil_law exactly,
        # the rows the pieces would fill unused
        law = np.full((pieces + 2, 4), np.inf)
        law[:3] = coil_law(k_open, float(np.sum(gap)), k_closed - k_open, float(np.sum(onset)))
        return law
    f_first = float(np.min(k_slice * gap))
    f_last = float(np.max(k_slice * (gap + onset) + 0.5 * k_contact * onset))
    f_grid = f_first + (f_last - f_first) * np.linspace(0.0, 1.0, 801) ** 3
    k_grid = slice_series_stiffness(f_grid, k_slice, gap, k_contact, onset)
    k_knots = k_open * (k_closed / k_open) ** (np.arange(pieces + 1) / pieces)
    f_knots = np.interp(np.log(k_knots), np.log(np.maximum.accumulate(k_grid)), f_grid)
    f_knots[0], f_knots[-1] = f_first, f_last
    x_knots = slice_response(f_knots, k_slice, gap, k_contact, onset)[0]
    law = np.empty((pieces + 2, 4))
    law[0] = (-np.inf, 0.0, k_open, 0.0)
    force = k_open * x_knots[0]
    for j in range(pieces):
        x0, x1, k0, k1 = x_knots[j], x_knots[j + 1], k_knots[j], k_knots[j + 1]
        if not x1 > x0:  # a degenerate piece (uniform element): no width
            law[j + 1] = (x0, 0.0, k0, force - k0 * x0)
            continue
        a = (k1 - k0) / (2.0 * (x1 - x0))
        b = k0 - 2.0 * a * x0
        law[j + 1] = (x0, a, b, force - (a * x0 + b) * x0)
        force += 0.5 * (k0 + k1) * (x1 - x0)
    law[-1] = (x_knots[-1], 0.0, k_closed, force - k_closed * x_knots[-1])
    return law


def modal_damping(masses, stiffness, damping) -> tuple[np.ndarray, np.ndarray]:
    """Natural frequencies [Hz] and damping ratios of a damped chain, ascending: its
    underdamped eigenvalues (:func:`springdyn.valve.spring.modes.chain_eigenvalues`).

    Parameters
    ----------
    masses, stiffness, damping : ndarray
        As for ``chain_eigenvalues``: lumped masses [kg] (n), element stiffnesses [N/m]
        and damping coefficients [N s/m] (n + 1 each).
    """

    lam = chain_eigenvalues(masses, stiffness, damping)
    lam = lam[lam.imag > 0]
    lam = lam[np.argsort(np.abs(lam))]
    return np.abs(lam) / (2 * np.pi), -lam.real / np.abs(lam)


class DistributedModel(SpringModel):
    """The distributed coil-by-coil model (see the module docstring).

    Examples
    --------
    >>> from springdyn.valve import ValveSpring
    >>> m = ValveSpring.example("one-step").with_model("distributed").spring_model
    >>> len(m.chain.masses)
    51
    """

    name = "distributed"
    description = "distributed coil-by-coil chain"
    PARAMETER_MEANINGS = {
        "f1": "the chain's first mode, ends fixed, free length",
        "f2": "the chain's first mode, ends fixed, set-up length",
        "f_continuum": "Wahl closed form of the active coils, free length (comparison)",
        "Fcon": "force at which the last coil closes (solid)",
    }

    def __init__(self, spring):
        super().__init__(spring)
        n = spring.elements
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 4 <= n <= 2000:
            raise InputError(f"elements = {n!r} must be a whole number from 4 to 2000")
        _ = self.geometry  # builds and checks the geometry
        # and the element laws and the set-up state: what can refuse a spring (the damping and the
        # frequencies, found only when asked for, raise no InputError)
        _ = self.static_chain

    def __repr__(self) -> str:
        p = self._parameters
        return (
            f"<DistributedModel: {self.spring.type} spring, {self.spring.elements} elements over "
            f"{self.geometry.turns - 2 * self.geometry.dead_coils:g} active turns, K1 = {p['K1']:.6g} N/m, "
            f"f1 = {p['f1']:.5g} Hz, Fset = {p['Fset']:.5g} N>"
        )

    # ------------------------------------------------------------------ geometry
    @cached_property
    def geometry(self) -> CoilGeometry:
        """Pitch and diameter profiles (given, or the defaults from the ``[spring]`` keys)."""
        sp = self.spring
        n_total = sp.low_pitch_coils + sp.high_pitch_coils
        wire = section_profile(sp)  # a wire diameter that varies along the coil (None: one wire)
        if wire is not None:
            check_profile_span(wire[0], n_total, "wire_diameter_profile")
            allowance = sp.solid_length - wire_stack(sp)  # Lc: the spring's one solid length
        else:
            allowance = end_allowance(sp.solid_length, sp.wire_diameter, n_total)  # Lc: the spring's one solid length
        if sp.pitch_profile:
            ps, pv = parse_profile(sp.pitch_profile, "pitch_profile", {"pitch_mm": 1e-3, "pitch_m": 1.0})
            check_profile_span(ps, n_total, "pitch_profile")
            if np.any(pv < sp.wire_diameter * (1 - 1e-9)) and wire is None:
                raise InputError(
                    f"pitch_profile: a pitch below the wire diameter {format_quantity(sp.wire_diameter, 'm', 'mm')} "
                    "is impossible (the coils would overlap)"
                )
        else:
            ps, pv = default_pitch_knots(
                n_total,
                sp.dead_coils,
                sp.wire_diameter,
                sp.free_length,
                sp.installed_length,
                sp.low_pitch_coils if sp.two_step else 0.0,
                sp._field,
                allowance,
                transition=sp.transition_turns,
            )
        if sp.diameter_profile:
            ds, dv = parse_profile(sp.diameter_profile, "diameter_profile", {"diameter_mm": 1e-3, "diameter_m": 1.0})
            check_profile_span(ds, n_total, "diameter_profile")
            if np.any(dv <= sp.wire_diameter):
                raise InputError("diameter_profile: the mean diameter must exceed the wire diameter everywhere")
        else:
            ds, dv = np.array([0.0, n_total]), np.full(2, sp.mean_diameter)
        g = CoilGeometry(
            n_total, sp.dead_coils, sp.wire_diameter, ps, pv, ds, dv, allowance, *(wire if wire is not None else ())
        )
        if wire is not None:
            grid = np.linspace(0.0, n_total, 4001)
            thin = g.height(grid)
            if np.any(g.pitch(grid) < thin * (1 - 1e-9)) or np.any(g.diameter(grid) <= thin):
                raise InputError(
                    "wire_diameter_profile: the wire diameter must stay below the pitch (the coils would overlap) "
                    "and below the mean diameter at every turn"
                )
        if sp.pitch_profile and abs(g.free_length - sp.free_length) > 0.005 * sp.free_length:
            raise InputError(
                f"pitch_profile gives the free length a + int p ds = {format_quantity(g.free_length, 'm', 'mm')} "
                f"(end allowance a = {format_quantity(allowance, 'm', 'mm')}), "
                f"but {sp._field('free_length')}: they must agree within 0.5 %"
            )
        if not sp.installed_length > g.solid_length:
            raise InputError(
                f"{sp._field('installed_length')} must exceed the solid length "
                f"{format_quantity(g.solid_length, 'm', 'mm')} ({sp.coil_facts['solid_length_source']})"
            )
        return g

    @cached_property
    def element_turns(self) -> np.ndarray:
        """Edges of the wire elements [turns from the seat end], ``elements + 1`` values.

        Coils closed at set-up get longer elements (:func:`stiffness_graded_edges`, at most
        :data:`MAX_ELEMENT_STRETCH` times the open coils'): the set-up state of
        :data:`MESH_SLICES` turn-slices in series with the end contacts gives each slice's
        tangent over open rate.
        """
        sp, g = self.spring, self.geometry
        edges = np.linspace(g.dead_coils, g.turns - g.dead_coils, MESH_SLICES + 1)
        sl = self._turn_slices(0.5 * (edges[:-1] + edges[1:]), np.diff(edges))
        k_slice = 1.0 / sl["c"]
        laws = (k_slice, sl["gap"], sl["kc"], sl["onset"])
        ends = 1.0 / self.turn_contact_stiffness(g.diameter(0.0)) + 1.0 / self.turn_contact_stiffness(
            g.diameter(g.turns)
        )
        setup = sp.free_length - sp.installed_length

        def excess(force):
            return slice_response(force, *laws)[0] + force * float(ends) - setup

        from scipy.optimize import brentq  # (here: scipy.optimize costs start-up of every valve command)

        force = brentq(excess, 0.0, setup * float(np.max(k_slice + sl["kc"])), xtol=1e-9, rtol=1e-10)
        stiffening = slice_states(force, *laws)[1] / k_slice
        return stiffness_graded_edges(edges, stiffening, sp.elements, MAX_ELEMENT_STRETCH)

    def _turn_slices(self, s, width) -> dict:
        """Turn-slices of the wire at positions ``s`` [turns] of ``width`` [turns] (arrays of
        one shape): open compliance ``c`` [m/N], ``gap`` [m], contact stiffness ``kc`` [N/m],
        ``onset`` [m] (:func:`slice_states`), and wire ``length`` [m]."""
        sp, g = self.spring, self.geometry
        d, p = g.diameter(s), g.pitch(s)
        wire = section_along(sp, s)  # the section at each slice (wire.py)
        h = wire["height"]
        c = turn_compliance(
            d,
            wire.get("wire_diameter"),
            p,
            sp.shear_modulus,
            sp.youngs_modulus,
            wire.get("torsion_constant"),
            wire.get("bending_inertia"),
        )
        return dict(
            c=c * width,
            gap=np.maximum(p - h, 0.0) * width,
            kc=self.turn_contact_stiffness(d) / width,
            onset=np.broadcast_to(CONTACT_ONSET * h * width, np.shape(s)),
            length=wire_length_per_turn(d, p) * width,
            area=wire["area"],
        )

    @cached_property
    def _pieces(self) -> dict:
        """Per wire element: gap [m], wire mass [kg], law, closing force [N]; dead-coil masses [kg]."""
        sp, g = self.spring, self.geometry
        edges = self.element_turns
        n = edges.size - 1
        frac = (np.arange(SLICES) + 0.5) / SLICES  # midpoint turn-slices: integrals and the closing law
        s = edges[:-1, None] + (edges[1:] - edges[:-1])[:, None] * frac  # (n, SLICES)
        sl = self._turn_slices(s, np.broadcast_to(((edges[1:] - edges[:-1]) / SLICES)[:, None], s.shape))
        laws = [graded_coil_law(1.0 / sl["c"][i], sl["gap"][i], sl["kc"][i], sl["onset"][i]) for i in range(n)]
        # the last turn-slice of the element touches: the element is closed throughout
        closing = np.max(sl["gap"] / sl["c"], axis=1)
        dead = np.linspace(0.0, g.dead_coils, 65)
        dead_mass = [
            sp.density
            * float(np.trapezoid(section_along(sp, x)["area"] * wire_length_per_turn(g.diameter(x), g.pitch(x)), x))
            for x in (dead, g.turns - dead[::-1])
        ]
        return dict(
            gap=np.sum(sl["gap"], axis=1),
            mass=sp.density * np.sum(sl["area"] * sl["length"], axis=1),
            laws=laws,
            closing=closing,
            dead_mass=dead_mass,
            n=n,
            slices=sl,
        )

    # ------------------------------------------------------------------ the chain
    @cached_property
    def static_chain(self) -> Chain:
        """The chain without its damping (``c0 = 0``): the masses, element laws and set-up state
        the statics and modes read, built without the eigenvalue problem of the damping."""
        sp, g, pc = self.spring, self.geometry, self._pieces
        n = pc["n"]
        k_seat = float(self.turn_contact_stiffness(g.diameter(0.0)))
        k_ret = float(self.turn_contact_stiffness(g.diameter(g.turns)))
        rows = CLOSING_PIECES + 2
        laws = np.full((n + 2, rows, 4), np.inf)
        laws[0, 0] = (-np.inf, 0.0, k_seat, 0.0)
        laws[1:-1] = np.stack(pc["laws"])
        laws[-1, 0] = (-np.inf, 0.0, k_ret, 0.0)
        masses = np.zeros(n + 1)
        masses[:-1] += pc["mass"] / 2
        masses[1:] += pc["mass"] / 2
        masses[0] += pc["dead_mass"][0]
        masses[-1] += pc["dead_mass"][1]
        fset = float(series_force(sp.free_length - sp.installed_length, laws))
        enames = ("seat",) + tuple(f"w{i + 1}" for i in range(n)) + ("retainer",)
        mnames = tuple(f"n{i}" for i in range(n + 1))
        return Chain(
            element_names=enames,
            mass_names=mnames,
            masses=masses,
            laws=laws,
            c0=0.0,
            setup_compressions=element_compressions(fset, laws),
            setup_force=fset,
            free_length=sp.free_length,
            installed_length=sp.installed_length,
        )

    @cached_property
    def _beta(self) -> float:
        """Stiffness-proportional damping coefficient [s]: mode 1 at set-up gets ``damping_ratio``."""
        zeta = self.spring.damping_ratio
        if zeta == 0:
            return 0.0
        ch = self.static_chain
        x = ch.setup_compressions
        k = ch.tangent_stiffness(x)
        w1 = 2 * np.pi * chain_frequencies(ch.masses, k, 1)[0]
        beta = 2 * zeta / w1
        for _ in range(6):  # the contact elements' sqrt law makes it not exactly proportional
            c = beta * ch.laws[:, 0, 2] * np.sqrt(k / ch.laws[:, 0, 2])
            z1 = modal_damping(ch.masses, k, c)[1][0]
            if abs(z1 - zeta) < 1e-6 * zeta:
                break
            beta *= zeta / z1
        return float(beta)

    @cached_property
    def chain(self) -> Chain:
        """The chain of ``elements + 1`` masses and ``elements + 2`` elements: :attr:`static_chain`
        with its damping ``c0 = beta k0`` per element (``beta``, an eigenvalue problem, found here)."""
        ch = self.static_chain
        return dataclasses.replace(ch, c0=self._beta * ch.laws[:, 0, 2])

    def contact_compressions(self) -> np.ndarray:
        """Compression [m] at which each wire element is closed throughout (its mean coil
        gap); ``inf`` for the end contacts and for elements already closed at set-up (closed
        by design, like Type C's low-pitch element, so never flagged)."""
        pc = self._pieces
        closed_at_setup = self.closing_forces() <= self._parameters_setup_force
        return np.concatenate([[np.inf], np.where(closed_at_setup, np.inf, pc["gap"]), [np.inf]])

    @cached_property
    def _parameters_setup_force(self) -> float:
        return float(self.static_chain.setup_force)

    @cached_property
    def stress_per_force(self) -> float:
        """The wire's largest corrected shear stress per newton of spring force over the active
        coils [Pa/N] (:func:`springdyn.valve.spring.wire.stress_per_force` at each coil's mean
        diameter and wire: a beehive's largest coil, a profile's thinnest wire)."""
        g = self.geometry
        s = np.linspace(g.dead_coils, g.turns - g.dead_coils, 401)
        return stress_per_force(self.spring, g.diameter(s), s)

    @property
    def element_positions(self) -> np.ndarray:
        """Middle of each wire element [turns from the seat end]."""
        e = self.element_turns
        return 0.5 * (e[:-1] + e[1:])

    # ------------------------------------------------------------------ parameters
    @cached_property
    def _parameters(self) -> dict:
        sp, g, pc = self.spring, self.geometry, self._pieces
        ch = self.static_chain
        laws = ch.laws
        k1 = 1.0 / np.sum(1.0 / laws[:, 0, 2])
        fcon = self.coil_contact_force
        f_free = chain_frequencies(ch.masses, laws[:, 0, 2], 1)[0]
        k_set = ch.tangent_stiffness(ch.setup_compressions)
        f_set = chain_frequencies(ch.masses, k_set, 1)[0]
        kset = 1.0 / np.sum(1.0 / k_set)
        active = g.turns - 2 * g.dead_coils
        return dict(
            K=float(self.turn_contact_stiffness(sp.mean_diameter)),
            K1=float(k1),
            K2=float(kset),
            M=float(ch.masses.sum()),
            f1=float(f_free),
            f2=float(f_set),
            f_continuum=float(
                formulas.surge_frequency(
                    sp.shear_modulus, sp.density, equivalent_diameters(sp)["surge"], sp.mean_diameter, active
                )
            ),
            Lc=float(g.solid_length),
            Fset=float(ch.setup_force),
            Fcon=fcon,
            elements=int(pc["n"]),
            beta=float(self._beta),
            pitch_max=float(g.pitch_v.max()),
        )

    def internal_parameters(self) -> dict:
        """Parameters of the distributed chain (SI), under the CLI's JSON keys.

        ``K`` contact stiffness of a coil [N/m] ([MMS]), ``K1`` rate at free length and
        ``K2`` at set-up [N/m], ``M`` mass of the wire [kg], ``f1`` first mode at free
        length and ``f2`` at set-up [Hz], ``f_continuum`` the continuum surge frequency of
        the active coils [Hz], ``Lc`` solid length (wire stack) [m], ``Fset`` set-up force,
        ``Fcon`` force at which the last coil closes (solid) [N], ``elements``, ``beta``
        stiffness-proportional damping [s], ``pitch_max`` largest pitch [m].
        """
        return dict(self._parameters)

    def breakpoints(self) -> dict:
        """Coil gap of every wire element [m] (``gap_1`` at the seat end ...)."""
        return {f"gap_{i + 1}": float(v) for i, v in enumerate(self._pieces["gap"])}

    @cached_property
    def _contact_share_tables(self) -> list:
        """Per wire element: elastic forces [N] (geometric, from the first turn-slice's
        closing to 100 Fset, :data:`SHARE_NODES`) and the force through the contact there."""
        sl = self._pieces["slices"]
        top = 100.0 * self.static_chain.setup_force
        tables = []
        for i in range(self._pieces["n"]):
            k = 1.0 / sl["c"][i]
            first = float(np.min(k * sl["gap"][i]))
            f = np.concatenate([[0.0], np.geomspace(max(first, 1e-9), max(top, 2 * first), SHARE_NODES)])
            e, _ = slice_states(f, k, sl["gap"][i], sl["kc"][i], sl["onset"][i])
            tables.append((f, np.maximum(f - np.max(k * e, axis=-1), 0.0)))
        return tables

    def contact_share(self, elastic_force) -> np.ndarray:
        """The force [N] closed coils pass through their contact, per element: the element's
        force less the largest torsion of its turn-slices (:func:`slice_states`: an open
        slice's wire carries the whole force, a closed one's no more than it did when it
        closed, plus its share of a further compression); NaN for the end contacts.

        Tabulated per element against the elastic force (:data:`SHARE_NODES` geometric nodes
        up to 100 Fset, linear between; the tests check it against the slices).

        Parameters
        ----------
        elastic_force : ndarray (N + 1, ...)
            Elastic (law) force of each element [N].
        """
        f = np.asarray(elastic_force, dtype=float)
        out = np.full_like(f, np.nan)
        for i, (nodes, share) in enumerate(self._contact_share_tables):
            out[i + 1] = np.interp(f[i + 1], nodes, share)
        return out

    # ------------------------------------------------------------------ outputs
    @cached_property
    def coil_contact_force(self) -> float:
        """The coil-contact force Fcon [N]: the largest of :meth:`closing_forces`, where the last
        coil closes (solid)."""
        return float(np.max(self.closing_forces()))

    def closing_forces(self) -> np.ndarray:
        """Static force [N] at which each wire element is closed throughout (its last
        turn-slice touches), from the seat end."""
        return self._pieces["closing"]

    def turn_contact_stiffness(self, mean_diameter):
        """Contact stiffness of one closed turn [N/m] at a mean diameter [m]: the spring's
        ``contact_stiffness``, or ``pi D E / 1e3`` ([MMS], :func:`formulas.contact_stiffness`).

        Parameters
        ----------
        mean_diameter : float or ndarray
            Mean coil diameter D [m].
        """
        given = self.spring.contact_stiffness
        if given is not None:
            return np.full(np.shape(mean_diameter), float(given))
        return formulas.contact_stiffness(mean_diameter, self.spring.youngs_modulus)

    def clashing_coils(self, sim) -> list[int]:
        """Coils (1 = the seat's first coil) that clash: an element of the coil is closed at a
        cam angle where the static (massless) spring at the same lift has it open.  Coils
        that close quasi-statically (the transitions at full lift) are not clashes.

        Parameters
        ----------
        sim : Simulation
            A simulation of this model.
        """
        # the static element is open while the static force is below the force at its gap
        clash = self.clash(sim.element_contact, sim.static_force)
        closing = set(np.flatnonzero(clash.any(axis=1)).tolist())
        pos = self.element_positions
        return sorted({int(np.floor(pos[j - 1])) + 1 for j in closing if 1 <= j <= pos.size})
