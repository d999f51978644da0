"""The rules that judge a simulated revolution, one home each.

A :class:`~springdyn.valve.run.results.Simulation` (one revolution) and a
:class:`~springdyn.valve.run.sweeps.SpeedSweep` (a revolution per speed, stacked) both call
these functions on their arrays, so that one spring gets one answer whichever way it ran:

- :func:`valve_open`: the valve off its seat with the lobe past the lash, before its first
  landing in the revolution (where a lift-off counts as one, not as seat bounce);
- :func:`floats_over_nose`: float, the valve leaving the cam over the nose;
- :func:`coil_clash`: coils closing where the static spring at the same lift is open (a dynamic
  closing), classed as transition-coil seating or active-coil clash and graded by its severity,
  the force the closed coils pass through their contact, against :data:`MAX_CLASH_SEVERITY`;
- :func:`valve_held_open` and :func:`pumps_up`: a hydraulic lash adjuster holding the valve
  off its seat on the base circle (pump-up), above :data:`PUMP_UP_THRESHOLD`;
- :func:`wire_fatigue`: the Goodman safety of the wire's torsion over the revolution, its
  peak stress against the limit (:mod:`springdyn.valve.spring.stress`).
"""

from __future__ import annotations

import numpy as np

from ...core.docstrings import ParameterDocs
from ..cam.definition import BASE_CIRCLE_LIFT, OPEN_LIFT
from ..spring import stress
from ..spring.elements import law_force

__all__ = [
    "PUMP_UP_THRESHOLD",
    "OPEN_LIFT",
    "BASE_CIRCLE_LIFT",
    "valve_open",
    "first_landing",
    "seat_rebound_height",
    "floats_over_nose",
    "MAX_CLASH_SEVERITY",
    "CLASH_CLASSES",
    "transition_elements",
    "coil_clash",
    "spring_clashes",
    "clashes",
    "valve_held_open",
    "pumps_up",
    "wire_fatigue",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    lobe_lift : array_like (n,)
        Lobe lift on the output grid [m].
    valve_lift : array_like (..., n)
        Valve lift on the same grid [m].
    """
)

#: Valve lift held on the base circle [m] above which a hydraulic lash adjuster has pumped up
#: (a micrometre: the adjuster's leak-down per cycle is some 0.3 um, its collapse under the
#: valve spring some 10 um; a valve held a micrometre open no longer seals).
PUMP_UP_THRESHOLD = 1e-6
#: Largest clash severity [fraction of Fset] that is seating, not clash (springdyn's definition,
#: :func:`coil_clash`): the force closed coils pass through their contact where the static spring
#: holds them open.  10 % of Fset is the band a drawing gives the installed force (some 5-10 %):
#: an impact that passes less than it changes the end forces no more than the spring's own
#: tolerance does.  The seating of the transition coils of closed ends at low speed passes a few
#: per cent (0-5 % of Fset for the one-step example below 2500 cam rpm); surge-driven impacts of
#: the active coils pass from some 10 % on, up to several Fset near float.
MAX_CLASH_SEVERITY = 0.10
#: The classes of a revolution's dynamic closings (:func:`coil_clash`), in rising order.
CLASH_CLASSES = ("none", "transition", "active")
# The lobe-lift thresholds OPEN_LIFT (in its event past the lash) and BASE_CIRCLE_LIFT live with
# the cam (springdyn.valve.cam.definition), whose checks judge the valve open by the same rule.


def first_landing(valve_lift) -> np.ndarray:
    """Whether the valve has landed on its seat at or before each output sample of the
    revolution (its first return to the seat; along the last axis).

    Parameters
    ----------
    valve_lift : array_like (..., n)
        Valve lift over the revolution's output grid [m].
    """
    z = np.asarray(valve_lift, dtype=float)
    landing = (z[..., :-1] > 0) & (z[..., 1:] <= 0)
    start = np.zeros(z.shape[:-1] + (1,), dtype=bool)
    return np.cumsum(np.concatenate([start, landing], axis=-1), axis=-1) > 0


@_DOCS.fill
def valve_open(lobe_lift, valve_lift, lobe_lash: float) -> np.ndarray:
    """The valve open in its event: off its seat, the lobe past the lash (by :data:`OPEN_LIFT`),
    and before its first landing in the revolution (later separations are seat bounces; the
    cam leaving a seated valve is no lift-off).

    Parameters
    ----------
    {lobe_lift valve_lift}
    lobe_lash : float
        Lobe lift that starts the event [m] (:attr:`ValveTrain.lobe_lash`).
    """
    z = np.asarray(valve_lift, dtype=float)
    return (np.asarray(lobe_lift) > lobe_lash + OPEN_LIFT) & (z > 0.0) & ~first_landing(z)


@_DOCS.fill
def seat_rebound_height(lobe_lift, valve_lift, lobe_lash: float) -> np.ndarray:
    """Seat bounce: the largest lift [m] the valve rebounds to after its first landing in the
    revolution, while the lobe is back on its base circle (past the event).

    Parameters
    ----------
    {lobe_lift valve_lift}
    lobe_lash : float
        Lobe lift that starts the event [m].
    """
    z = np.asarray(valve_lift, dtype=float)
    rebound = first_landing(z) & ~(np.asarray(lobe_lift) > lobe_lash + OPEN_LIFT)
    out = np.max(np.where(rebound, z, 0.0), axis=-1)
    return float(out) if out.ndim == 0 else out


def floats_over_nose(liftoff_in_nose, nose, cam_contact_force, valve_lift) -> np.ndarray:
    """Float: the valve leaves the cam over the nose in the revolution.  A lift-off that
    starts in the nose, or the follower off the cam (no contact force) with the valve off its
    seat at an output angle of the nose (a lift-off that began on the flank and lasts into
    the nose, or a valve that never caught up with the cam).

    Parameters
    ----------
    liftoff_in_nose : bool or array_like (...)
        Whether a located lift-off of the revolution starts in the nose [-]
        (:func:`springdyn.valve.run.separation.liftoffs`).
    nose : array_like of bool (n,)
        The output grid's samples in the nose [-] (:func:`springdyn.valve.run.separation.phase_mask`).
    cam_contact_force, valve_lift : array_like (..., n)
        Cam contact force [N] and valve lift [m] on the grid.

    Returns
    -------
    bool or ndarray of bool (...)
    """
    off_cam = (np.asarray(cam_contact_force) <= 0.0) & (np.asarray(valve_lift) > 0.0) & np.asarray(nose, bool)
    out = np.asarray(liftoff_in_nose, bool) | off_cam.any(axis=-1)
    return bool(out) if out.ndim == 0 else out


def transition_elements(spring_model) -> np.ndarray:
    """The elements of the transition coils [-]: coils that close statically before the active
    coils, their force at contact (:attr:`SpringModel.contact_forces`) below the largest finite
    one by more than the model's :attr:`~SpringModel.CLASH_MARGIN` of Fset.

    The distributed chain's elements in the pitch transition of closed ends (and the low-pitch
    coils of a two-step spring that are still open at set-up) are such; the Type C chain's
    contacting elements all close at ``Fcon`` (its end elements K stand for the closed end
    coils and never count as contact), so it has none: every closing of its coils is one of the
    active coils.

    Parameters
    ----------
    spring_model : SpringModel
        The spring's model [-].

    Returns
    -------
    ndarray of bool (N + 1,)
        (A spring pack's: each spring's, one after the other.)
    """
    models = getattr(spring_model, "models", None)
    if models is not None:  # a spring pack: each spring against its own coils
        return np.concatenate([transition_elements(m) for m in models])
    f = np.asarray(spring_model.contact_forces, dtype=float)
    finite = np.isfinite(f)
    if not finite.any():
        return np.zeros(f.shape, bool)
    margin = spring_model.CLASH_MARGIN * spring_model.chain.setup_force
    return finite & (f < np.max(f[finite]) - margin)


def clashes(severity, limit: float | None = None):
    """Coil clash: a severity (:func:`coil_clash`) above the limit.

    Parameters
    ----------
    severity : float or array_like
        Clash severity [fraction of Fset].
    limit : float, optional
        Largest severity that is no clash [fraction of Fset] (default :data:`MAX_CLASH_SEVERITY`).
    """
    out = np.asarray(severity, dtype=float) > (MAX_CLASH_SEVERITY if limit is None else limit)
    return bool(out) if out.ndim == 0 else out


def coil_clash(spring_model, compression, static_force, period, limit: float | None = None) -> dict:
    """Coil clash over a revolution, classed and graded (springdyn's definition; one home for a
    simulation, a sweep and the studies).

    A *dynamic closing* is an element in coil contact where the static (massless) spring at
    the same lift holds it open (:meth:`SpringModel.clash`, the model's own margin).  Its
    *class*: ``"transition"`` where only the transition coils close so
    (:func:`transition_elements`: the pitch transition of closed ends seating earlier than the
    static spring does), ``"active"`` where an active coil does (the surge closing the active
    coils), ``"none"`` without one.  Its *severity* [fraction of Fset]: the largest force the
    dynamically closed coils pass through their contact (:meth:`SpringModel.contact_share`,
    the force that is no torsion of the wire) over the set-up force (a spring pack's: each
    spring's over its own, :meth:`SpringModel.element_setup_forces`).  That force is the
    impact: the momentum of the closing coils stopped by the contact stiffness of closed turns,
    it loads the coil surfaces (wear, noise) and adds to the end forces; an element merely
    reaching its gap passes none.  The same figure from each model's own chain and contact law
    puts Type C and the distributed model on one scale.  Clash is a severity above ``limit``
    (:data:`MAX_CLASH_SEVERITY`); the closing velocity and the contact's share of the element
    force at the worst instant are reported beside it, not judged.

    Parameters
    ----------
    spring_model : SpringModel
        The spring's model [-].
    compression : array_like (N + 1, ..., n)
        Each element's compression over the revolution's output grid, uniform in cam angle [m].
    static_force : array_like (..., n)
        The static spring force at the same instants [N].
    period : float or array_like (...)
        Duration of the revolution [s] (``60 / cam_rpm``).
    limit : float, optional
        Largest severity that is no clash [fraction of Fset] (default :data:`MAX_CLASH_SEVERITY`).

    Returns
    -------
    dict
        ``closing`` (bool (N + 1, ..., n): the dynamic closings), ``severity`` [-],
        ``contact_share`` (the force through contact over the element's force at the worst
        instant) [-], ``closing_velocity_m_per_s`` (the largest rate of compression of an element
        as it closes dynamically) [m/s], ``transition`` and ``active`` (bool: dynamic closings of
        transition or active coils), ``class_index`` (into :data:`CLASH_CLASSES`) and ``clash``
        (severity above ``limit``), each of shape (...).
    """
    model = spring_model
    x = np.asarray(compression, dtype=float)
    static = np.asarray(static_force, dtype=float)
    contact = x >= model.contact_gaps.reshape((-1,) + (1,) * (x.ndim - 1))
    closing = np.asarray(model.clash(contact, static), bool)
    elastic = np.stack([law_force(x[j], law) for j, law in enumerate(model.chain.laws)])
    share = np.nan_to_num(model.contact_share(elastic))
    through = np.where(closing, share, 0.0)
    # over each element's own spring's Fset (a spring pack's springs each over its own)
    graded = through / model.element_setup_forces().reshape((-1,) + (1,) * (x.ndim - 1))
    severity = graded.max(axis=(0, -1))
    # the contact's share of the element's force where the graded force through contact is largest
    lead = severity.shape
    pick = lambda a: np.moveaxis(a, 0, -2).reshape(lead + (-1,))  # noqa: E731
    k = np.argmax(pick(graded), axis=-1)[..., None]
    worst = np.take_along_axis(pick(through), k, axis=-1)[..., 0]
    at_worst = np.take_along_axis(pick(elastic), k, axis=-1)[..., 0]
    frac = np.where(worst > 0.0, worst / np.where(at_worst > 0.0, at_worst, 1.0), 0.0)
    # the closing velocity: the compression's rate over the sample before each dynamic closing starts
    dt = np.asarray(period, dtype=float)[..., None] / x.shape[-1]
    rate = (x - np.roll(x, 1, axis=-1)) / dt
    entry = closing & ~np.roll(closing, 1, axis=-1)
    velocity = np.where(entry, np.maximum(rate, 0.0), 0.0).max(axis=(0, -1))
    rows = closing.any(axis=-1)
    trans = transition_elements(model).reshape((-1,) + (1,) * (rows.ndim - 1))
    transition = (rows & trans).any(axis=0)
    active = (rows & ~trans).any(axis=0)
    out = dict(
        closing=closing,
        severity=severity,
        contact_share=frac,
        closing_velocity_m_per_s=velocity,
        transition=transition & ~active,
        active=active,
        class_index=np.where(active, 2, np.where(transition, 1, 0)),
        clash=clashes(severity, limit),
    )
    return {key: (v if v.ndim else v[()]) for key, v in ((key, np.asarray(v)) for key, v in out.items())}


def spring_clashes(spring_model, compression, static_force, period, limit: float | None = None) -> dict:
    """Each spring's coil clash in a spring pack: :func:`coil_clash` of its own chain, on its own
    elements, against its share of the pack's static force (its share at installed length, as
    :meth:`springdyn.valve.spring.pack.PackModel.clash` splits it), its severity over its own
    set-up force.  The pack's :func:`coil_clash` is its worst spring's (each element over its own
    spring's Fset, :meth:`~springdyn.valve.spring.chains.SpringModel.element_setup_forces`).

    Parameters
    ----------
    spring_model : PackModel
        The pack's model (one spring's model: no springs) [-].
    compression : array_like (N + C, ..., n)
        Every chain's element compressions, one chain after the other [m].
    static_force : array_like (..., n)
        The pack's static force at the same instants [N].
    period : float or array_like (...)
        Duration of the revolution [s].
    limit : float, optional
        Largest severity that is no clash [fraction of the spring's Fset].

    Returns
    -------
    dict
        Spring name -> :func:`coil_clash`'s dict (empty for one spring).
    """
    models = getattr(spring_model, "models", None)
    if models is None:
        return {}
    pack = spring_model.pack
    share = np.array(pack.setup_forces) / sum(pack.setup_forces)
    x, static = np.asarray(compression, dtype=float), np.asarray(static_force, dtype=float)
    return {
        name: coil_clash(m, x[r], share[k] * static, period, limit)
        for k, (name, m, r) in enumerate(zip(pack.names, models, spring_model.element_ranges()))
    }


def _pack_wire_fatigue(pack, wire_lo, wire_hi, static_lo, static_hi) -> dict:
    """:func:`wire_fatigue` of a spring pack: each spring's from its own elements (its end
    elements' ranges from the output grid) and its own static force range (``static_lo``,
    ``static_hi`` per spring; a pack's total alone: its share at installed length); the pack's figures are the Goodman-critical spring's, the peak stress
    the largest of any spring, ``critical_spring`` names it; ``springs`` holds each spring's
    figures by name (its elements counted from its own seat end)."""
    lo = np.asarray(wire_lo, dtype=float)
    hi = np.asarray(wire_hi, dtype=float)
    share = np.array(pack.setup_forces) / sum(pack.setup_forces)
    if np.ndim(static_lo) == 0:  # the pack's total: split by the shares at installed length
        static_lo, static_hi = share * float(static_lo), share * float(static_hi)
    each, own = [], {}
    for k, (spring, r) in enumerate(zip(pack.springs, pack.spring_model.element_ranges())):
        f = wire_fatigue(
            spring,
            lo[r],
            hi[r],
            (lo[r][0], lo[r][-1]),
            (hi[r][0], hi[r][-1]),
            float(static_lo[k]),
            float(static_hi[k]),
        )
        own[pack.names[k]] = dict(f)
        f["fatigue_critical_element"] += r.start
        f["peak_shear_stress_element"] += r.start
        each.append(f)
    k = min(range(len(each)), key=lambda i: each[i]["fatigue_safety_factor"] or np.inf)
    top = max(range(len(each)), key=lambda i: each[i]["peak_shear_stress_Pa"])
    out = dict(each[k], critical_spring=pack.names[k], springs=own)
    out.update(
        peak_shear_stress_Pa=each[top]["peak_shear_stress_Pa"],
        peak_shear_stress_element=each[top]["peak_shear_stress_element"],
        wire_stress_ok=all(f["wire_stress_ok"] for f in each),
        max_wire_force_N=max(f["max_wire_force_N"] for f in each),
    )
    return out


@_DOCS.fill
def valve_held_open(lobe_lift, valve_lift) -> np.ndarray:
    """The smallest valve lift [m] while the lobe is on its base circle (0 when it closes;
    with a hydraulic lash adjuster that pumped up, the lift it holds the valve open by).

    Parameters
    ----------
    {lobe_lift valve_lift}
    """
    base = ~(np.asarray(lobe_lift) > BASE_CIRCLE_LIFT)
    z = np.asarray(valve_lift, dtype=float)
    out = np.maximum(np.min(np.where(base, z, np.inf), axis=-1), 0.0)
    out = np.where(np.isfinite(out), out, 0.0)
    return float(out) if out.ndim == 0 else out


def pumps_up(held_open) -> np.ndarray:
    """Pump-up: the adjuster holds the valve open on the base circle by more than
    :data:`PUMP_UP_THRESHOLD`.

    Parameters
    ----------
    held_open : float or array_like
        :func:`valve_held_open` [m].
    """
    out = np.asarray(held_open, dtype=float) > PUMP_UP_THRESHOLD
    return bool(out) if out.ndim == 0 else out


def wire_fatigue(spring, wire_lo, wire_hi, end_lo, end_hi, static_lo: float, static_hi: float) -> dict:
    """The wire's fatigue over a revolution (issue 13): the Goodman safety of every element's
    wire torsion between its smallest and largest value, beside the static cycle's, and the
    largest stress against the wire's limit.

    Each element's wire torsion is its force less what closed coils pass through their
    contact (:meth:`SpringModel.wire_forces`); an end element that can never close its coils
    (the Type C chain's contacts) carries the end force itself, and its range is widened to
    the true extremes of that force (the engine's dense output), ``end_lo``/``end_hi``.

    Parameters
    ----------
    spring : ValveSpring
        Its wire, coil diameter and strengths (:func:`springdyn.valve.spring.stress.spring_strengths`).
    wire_lo, wire_hi : array_like (N + 1,)
        Each element's smallest and largest wire torsion as an axial force [N] (NaN: no wire).
    end_lo, end_hi : array_like (2,)
        The smallest and largest seat and retainer forces [N] (true extremes).
    static_lo, static_hi : float or array_like (springs,)
        The static force's range over the cycle [N] (installed to open); of a spring pack, each
        spring's (a pack's total alone is split by the springs' shares at installed length).

    Returns
    -------
    dict
        ``fatigue_safety_factor`` (None: no stress), ``static_fatigue_safety_factor``,
        ``min_shear_stress_Pa``/``max_shear_stress_Pa`` (the Goodman-critical element's),
        ``fatigue_critical_element`` (index from the seat), ``static_min_shear_stress_Pa``,
        ``static_max_shear_stress_Pa``, ``peak_shear_stress_Pa`` and ``peak_shear_stress_element``
        (the largest stress of any element, index), ``shear_stress_limit_Pa`` and its source,
        ``wire_stress_ok``, the strengths and ``max_wire_force_N``.
    """
    if getattr(spring, "springs", None) is not None:
        return _pack_wire_fatigue(spring, wire_lo, wire_hi, static_lo, static_hi)
    lo = np.array(wire_lo, dtype=float)
    hi = np.array(wire_hi, dtype=float)
    rows = np.flatnonzero(np.isfinite(lo) & np.isfinite(hi))
    plain = ~np.isfinite(spring.spring_model.contact_compressions())
    for end, k in ((0, 0), (lo.size - 1, 1)):
        if plain[end] and end in rows:
            lo[end] = min(lo[end], end_lo[k])
            hi[end] = max(hi[end], end_hi[k])
    dyn = stress.fatigue_assessment(spring, lo[rows], hi[rows])
    sta = stress.fatigue_assessment(spring, static_lo, static_hi)
    peak = stress.fatigue_assessment(spring, np.zeros(rows.size), hi[rows])  # the largest stress
    return dict(
        fatigue_safety_factor=dyn["fatigue_safety_factor"],
        static_fatigue_safety_factor=sta["fatigue_safety_factor"],
        min_shear_stress_Pa=dyn["min_shear_stress_Pa"],
        max_shear_stress_Pa=dyn["max_shear_stress_Pa"],
        fatigue_critical_element=int(rows[dyn["critical_element"]]),
        static_min_shear_stress_Pa=sta["min_shear_stress_Pa"],
        static_max_shear_stress_Pa=sta["max_shear_stress_Pa"],
        peak_shear_stress_Pa=peak["max_shear_stress_Pa"],
        peak_shear_stress_element=int(rows[peak["critical_element"]]),
        shear_stress_limit_Pa=dyn["shear_stress_limit_Pa"],
        shear_stress_limit_source=dyn["shear_stress_limit_source"],
        wire_stress_ok=bool(peak["max_shear_stress_Pa"] <= dyn["shear_stress_limit_Pa"]),
        endurance_shear_strength_Pa=dyn["endurance_shear_strength_Pa"],
        ultimate_shear_strength_Pa=dyn["ultimate_shear_strength_Pa"],
        strength_defaults=dyn["strength_defaults"],
        max_wire_force_N=float(np.max(hi[rows])),
    )
