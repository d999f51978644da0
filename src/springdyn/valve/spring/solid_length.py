"""Coil bind: the solid length against the shortest length a cam or a design lift asks for.

:func:`min_sum_of_gaps` is EN 13906-1's minimum sum of gaps Sa between the working length and
the solid length of a statically loaded spring (cold or hot coiled); :func:`dynamic_sum_of_gaps`
is the standard's practice under dynamic load (1.5 Sa cold coiled, 2 Sa hot coiled), the
clearance a valve spring, dynamically loaded by definition, is judged by
(:func:`coil_bind_clearance`, one home); :func:`check_coil_bind` compares the shortest length
with the solid length and that clearance, refuses a spring driven past solid (unless
``through_solid`` is set) and warns below the clearance.  :func:`springdyn.valve.run.setup.prepare` (every cam-driven analysis)
and :meth:`~springdyn.valve.spring.chains.SpringModel.design_figures` call it.
"""

from __future__ import annotations

import warnings

from ...core.docstrings import ParameterDocs
from ...core.errors import FactWarning, InputError
from ...core.units import format_mm
from .formulas import coil_contact_length
from .wire import end_height, wire_stack

__all__ = [
    "COILINGS",
    "DYNAMIC_GAP_FACTOR",
    "min_sum_of_gaps",
    "dynamic_sum_of_gaps",
    "coiling_of",
    "coil_bind_clearance",
    "en13906_solid_length",
    "solid_length",
    "solid_length_source",
    "check_coil_bind",
]

#: How the spring is wound: cold coiled (valve springs: oil-tempered wire, EN 10270-2) or hot
#: coiled (bar stock, tapered ends; EN 13906-1 section 9).
COILINGS = ("cold", "hot")

#: EN 13906-1's factor on the minimum sum of gaps Sa under dynamic load: 1.5 for cold-coiled,
#: 2 for hot-coiled springs (the practice of EN 13906-1 calculators, e.g. SpringONE's
#: ``TCompressionSpringSolver``; docs/references.md [EN13906-1]).
DYNAMIC_GAP_FACTOR = {"cold": 1.5, "hot": 2.0}

#: Parameter descriptions shared by the sums of gaps (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    mean_diameter : float
        Mean coil diameter D [m].
    wire_diameter : float
        Wire diameter d [m].
    active_coils : float
        Active coils n [-].
    coiling : {"cold", "hot"}
        How the spring is wound (:data:`COILINGS`).
    """
)


@_DOCS.fill
def min_sum_of_gaps(mean_diameter: float, wire_diameter: float, active_coils: float, coiling: str = "cold") -> float:
    """Minimum sum of the gaps between the active coils at the shortest working length, static load [m].

    EN 13906-1:2013, "minimum sum of gaps between active coils" Sa: cold-coiled springs
    ``Sa = (0.0015 D^2/d + 0.1 d) n`` with D and d in mm, in SI ``Sa = (1.5e-3 D^2/d + 0.1 d) n``;
    hot-coiled springs ``Sa = 0.02 (D + d) n`` (dimensionless factor).  Under dynamic load the
    standard asks for more: :func:`dynamic_sum_of_gaps`.

    Parameters
    ----------
    {mean_diameter wire_diameter active_coils coiling}

    Examples
    --------
    >>> round(min_sum_of_gaps(22e-3, 3.5e-3, 5.5) * 1e3, 3)
    3.066
    >>> round(min_sum_of_gaps(100e-3, 20e-3, 6.0, "hot") * 1e3, 3)
    14.4
    """
    if coiling == "hot":
        return 0.02 * (mean_diameter + wire_diameter) * active_coils
    return (1.5e-3 * mean_diameter**2 / wire_diameter + 0.1 * wire_diameter) * active_coils


@_DOCS.fill
def dynamic_sum_of_gaps(
    mean_diameter: float, wire_diameter: float, active_coils: float, coiling: str = "cold"
) -> float:
    """Minimum sum of the gaps between the active coils under dynamic load [m].

    ``DYNAMIC_GAP_FACTOR[coiling] * Sa``: 1.5 Sa for cold-coiled, 2 Sa for hot-coiled springs
    (EN 13906-1:2013 practice for dynamically loaded springs; :data:`DYNAMIC_GAP_FACTOR`,
    :func:`min_sum_of_gaps`).

    Parameters
    ----------
    {mean_diameter wire_diameter active_coils coiling}

    Examples
    --------
    >>> round(dynamic_sum_of_gaps(22e-3, 3.5e-3, 5.5) * 1e3, 3)
    4.599
    """
    return DYNAMIC_GAP_FACTOR[coiling] * min_sum_of_gaps(mean_diameter, wire_diameter, active_coils, coiling)


def coiling_of(spring) -> str:
    """How ``spring`` is wound: its ``coiling`` key, else hot for tapered (hot-coiled) ends and
    cold otherwise (valve springs are cold coiled from oil-tempered wire).

    Parameters
    ----------
    spring : ValveSpring
    """
    given = getattr(spring, "coiling", "")
    if given:
        return given
    return "hot" if getattr(spring, "end_type", "") == "tapered" else "cold"


def coil_bind_clearance(spring) -> dict:
    """The coil-bind clearance ``spring`` is judged by, with the figures it comes from.

    ``min_coil_bind_clearance`` where the spring gives it; else EN 13906-1's dynamic clearance
    :func:`dynamic_sum_of_gaps` (a valve spring is dynamically loaded).

    Parameters
    ----------
    spring : ValveSpring

    Returns
    -------
    dict
        ``coil_bind_clearance_m`` (the clearance that judges) [m], ``coil_bind_clearance_source``
        (what it is: "EN 13906-1 dynamic, 1.5 Sa (cold coiled)" or "min_coil_bind_clearance"),
        ``static_sum_of_gaps_m`` (EN 13906-1's static Sa) [m], ``dynamic_sum_of_gaps_m`` [m],
        ``coiling``.
    """
    coiling = coiling_of(spring)
    active = spring.low_pitch_coils + spring.high_pitch_coils - 2.0 * spring.dead_coils
    static = min_sum_of_gaps(spring.mean_diameter, spring.wire_diameter, active, coiling)
    dynamic = DYNAMIC_GAP_FACTOR[coiling] * static
    given = spring.min_coil_bind_clearance
    return dict(
        coil_bind_clearance_m=dynamic if given is None else given,
        coil_bind_clearance_source=(
            f"EN 13906-1 dynamic, {DYNAMIC_GAP_FACTOR[coiling]:g} Sa ({coiling} coiled)"
            if given is None
            else "min_coil_bind_clearance"
        ),
        static_sum_of_gaps_m=static,
        dynamic_sum_of_gaps_m=dynamic,
        coiling=coiling,
    )


def en13906_solid_length(wire_diameter: float, total_coils: float, end_type: str) -> float:
    """Solid length of a compression spring by its ends [m].

    EN 13906-1:2013: cold-coiled springs, ends closed and ground ``Lc = n_t d``, closed and not
    ground ``Lc = (n_t + 1.5) d``; hot-coiled springs (tapered bar ends, closed and ground)
    ``Lc = (n_t - 0.3) d``.  Plain (open) ends ``Lc = (n_t + 1) d`` and plain ground ends
    ``Lc = n_t d`` (Shigley, Table 10-1: the standard covers closed ends only).

    Parameters
    ----------
    wire_diameter : float
        Wire diameter d [m].
    total_coils : float
        Total coils n_t [-].
    end_type : {"closed-ground", "closed", "open", "plain", "plain-ground", "tapered"}

    Examples
    --------
    >>> round(en13906_solid_length(3.5e-3, 7.5, "closed-ground") * 1e3, 3)
    26.25
    >>> round(en13906_solid_length(10e-3, 7.5, "tapered") * 1e3, 3)
    72.0
    """
    extra = {"closed-ground": 0.0, "closed": 1.5, "open": 1.0, "plain": 1.0, "plain-ground": 0.0, "tapered": -0.3}
    return wire_diameter * (total_coils + extra[end_type])


def solid_length(spring) -> float:
    """Solid length [m]: by the spring's ``end_type`` (:func:`en13906_solid_length`), else
    the MMS document's ``Lc = Dw (N1 + N2 + 1/2)`` ([MMS];
    :func:`springdyn.valve.spring.formulas.coil_contact_length`).  ``Dw`` is the wire's axial
    height (ovate and rectangular wire, :mod:`springdyn.valve.spring.wire`); a wire that varies
    along the coil stacks ``int d ds`` (:func:`springdyn.valve.spring.wire.wire_stack`) and the
    ends add their part at the ends' wire.

    Parameters
    ----------
    spring : ValveSpring
    """
    total = spring.low_pitch_coils + spring.high_pitch_coils
    if getattr(spring, "wire_diameter_profile", ""):
        # a wire that varies along the coil: its stack, and what the ends add at the ends' wire
        stack, end = wire_stack(spring), end_height(spring)
        if getattr(spring, "end_type", ""):
            return stack + en13906_solid_length(end, 0.0, spring.end_type)
        return stack + coil_contact_length(end, 0.0, 0.0)  # the document's half wire
    # (ovate and rectangular wire: wire_diameter is the axial height, wire.py)
    if getattr(spring, "end_type", ""):
        return en13906_solid_length(spring.wire_diameter, total, spring.end_type)
    return coil_contact_length(spring.wire_diameter, spring.low_pitch_coils, spring.high_pitch_coils)


def _spring_id(spring) -> str:
    """The spring a coil-bind fact is about (two springs in one command are two facts)."""
    return f"{spring.wire_diameter!r},{spring.mean_diameter!r},{spring.total_coils!r},{spring.installed_length!r}"


def solid_length_source(spring) -> str:
    """Which definition :func:`solid_length` took for ``spring``, for every output that states it.

    Parameters
    ----------
    spring : ValveSpring
    """
    if getattr(spring, "end_type", ""):
        return f"EN 13906-1, ends {spring.end_type}"
    return "the MMS document, Dw (N1 + N2 + 0.5)"


def check_coil_bind(spring, lift: float, source: str) -> dict:
    """Coil-bind figures of the spring compressed by ``lift`` from its installed length.

    Raises :class:`InputError` when ``installed_length - lift`` is below the solid length
    (unless the spring sets ``through_solid``); warns when the margin is below the
    coil-bind clearance (:func:`coil_bind_clearance`: ``min_coil_bind_clearance``, default
    EN 13906-1's dynamic clearance :func:`dynamic_sum_of_gaps`).

    Parameters
    ----------
    spring : ValveSpring
    lift : float
        Largest spring compression from the installed length [m] (the valve lift the cam
        can cause through the train's ratio, less the lash).
    source : str
        What causes it, for messages (e.g. ``"the cam lift 9 mm"``).

    Returns
    -------
    dict
        ``solid_length_m`` with ``solid_length_source``, ``open_length_m``, ``coil_bind_margin_m`` (open length minus solid
        length), the figures of :func:`coil_bind_clearance` (``coil_bind_clearance_m`` with
        ``coil_bind_clearance_source``, ``static_sum_of_gaps_m``, ``dynamic_sum_of_gaps_m``,
        ``coiling``), ``coil_bind_ok`` (margin at least the clearance), ``static_gaps_ok``
        (margin at least the static Sa), ``through_solid`` (the spring is driven past solid,
        allowed by ``through_solid``).
    """
    lc = solid_length(spring)
    open_length = spring.installed_length - lift
    margin = open_length - lc
    gaps = coil_bind_clearance(spring)
    clearance = gaps["coil_bind_clearance_m"]
    through = margin < -1e-9  # at the solid length itself (to rounding) is allowed
    if through and not spring.through_solid:
        raise InputError(
            f"{source} drives the spring past solid: installed_length {format_mm(spring.installed_length)} - lift "
            f"{format_mm(lift)} = {format_mm(open_length)} is {format_mm(-margin)} below the solid length "
            f"{format_mm(lc)} ({solid_length_source(spring)}); lengthen installed_length, reduce the lift, or set "
            "through_solid = true in [spring] to simulate through solid anyway"
        )
    # one fact under one key: the design figures and every run's set-up check it (the CLI says it once)
    if through:
        warnings.warn(
            FactWarning(
                f"through_solid: {source} drives the spring {format_mm(-margin)} past solid (Lc {format_mm(lc)}); "
                "the results rest on the contact stiffness of closed coils",
                key=f"through solid|{_spring_id(spring)}",
            ),
            stacklevel=3,
        )
    elif margin < clearance:
        below_static = margin < gaps["static_sum_of_gaps_m"]
        warnings.warn(
            FactWarning(
                f"coil bind: {source} leaves {format_mm(margin)} above the solid length {format_mm(lc)}, less than "
                + (
                    f"the dynamic coil-bind clearance {format_mm(clearance)} (EN 13906-1: "
                    f"{DYNAMIC_GAP_FACTOR[gaps['coiling']]:g} Sa for a dynamically loaded {gaps['coiling']}-coiled spring; static Sa {format_mm(gaps['static_sum_of_gaps_m'])}"
                    + (", also missed)" if below_static else ", met)")
                    if spring.min_coil_bind_clearance is None
                    else f"min_coil_bind_clearance {format_mm(clearance)}"
                ),
                key=f"coil bind|{_spring_id(spring)}",
            ),
            stacklevel=3,
        )
    return dict(
        solid_length_m=lc,
        solid_length_source=solid_length_source(spring),
        open_length_m=open_length,
        coil_bind_margin_m=margin,
        **gaps,
        coil_bind_ok=bool(margin >= clearance),
        static_gaps_ok=bool(margin >= gaps["static_sum_of_gaps_m"]),
        through_solid=bool(through),
    )
