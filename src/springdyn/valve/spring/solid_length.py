"""Coil bind: the solid length against the shortest length a cam or a design lift asks for.

:func:`min_sum_of_gaps` is EN 13906-1's recommended clearance between the working length and
the solid length; :func:`check_coil_bind` compares the shortest length with the solid length
and that clearance, refuses a spring driven past solid (unless ``through_solid`` is set) and
warns below the clearance.  :func:`springdyn.valve.run.setup.prepare` (every cam-driven analysis)
and :meth:`~springdyn.valve.spring.chains.SpringModel.design_figures` call it.
"""

from __future__ import annotations

import warnings

from ...core.errors import FactWarning, InputError
from ...core.units import format_mm
from .formulas import coil_contact_length

__all__ = ["min_sum_of_gaps", "en13906_solid_length", "solid_length", "solid_length_source", "check_coil_bind"]


def min_sum_of_gaps(mean_diameter: float, wire_diameter: float, active_coils: float) -> float:
    """Minimum sum of the gaps between the active coils at the shortest working length [m].

    ``Sa = (0.0015 D^2/d + 0.1 d) n`` with D and d in mm (EN 13906-1:2013, cylindrical
    helical compression springs, "minimum sum of gaps between active coils"); in SI
    ``Sa = (1.5e-3 D^2/d + 0.1 d) n``.

    Parameters
    ----------
    mean_diameter : float
        Mean coil diameter D [m].
    wire_diameter : float
        Wire diameter d [m].
    active_coils : float
        Active coils n [-].

    Examples
    --------
    >>> round(min_sum_of_gaps(22e-3, 3.5e-3, 5.5) * 1e3, 3)
    3.066
    """
    return (1.5e-3 * mean_diameter**2 / wire_diameter + 0.1 * wire_diameter) * active_coils


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
    :func:`springdyn.valve.spring.formulas.coil_contact_length`).

    Parameters
    ----------
    spring : ValveSpring
    """
    total = spring.low_pitch_coils + spring.high_pitch_coils
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
    coil-bind clearance (``min_coil_bind_clearance``, default :func:`min_sum_of_gaps`).

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
        length), ``coil_bind_clearance_m`` with ``coil_bind_clearance_source``, ``coil_bind_ok`` (margin at least the clearance),
        ``through_solid`` (the spring is driven past solid, allowed by ``through_solid``).
    """
    lc = solid_length(spring)
    open_length = spring.installed_length - lift
    margin = open_length - lc
    clearance = spring.min_coil_bind_clearance
    if clearance is None:
        active = spring.low_pitch_coils + spring.high_pitch_coils - 2.0 * spring.dead_coils
        clearance = min_sum_of_gaps(spring.mean_diameter, spring.wire_diameter, active)
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
        warnings.warn(
            FactWarning(
                f"coil bind: {source} leaves {format_mm(margin)} above the solid length {format_mm(lc)}, less than "
                f"the coil-bind clearance {format_mm(clearance)}"
                + (" (EN 13906-1's minimum sum of gaps Sa)" if spring.min_coil_bind_clearance is None else ""),
                key=f"coil bind|{_spring_id(spring)}",
            ),
            stacklevel=3,
        )
    return dict(
        solid_length_m=lc,
        solid_length_source=solid_length_source(spring),
        open_length_m=open_length,
        coil_bind_margin_m=margin,
        coil_bind_clearance_m=clearance,
        coil_bind_ok=bool(margin >= clearance),
        coil_bind_clearance_source="EN 13906-1 Sa"
        if spring.min_coil_bind_clearance is None
        else "min_coil_bind_clearance",
        through_solid=bool(through),
    )
