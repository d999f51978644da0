"""The one set of pass/fail criteria of a valve spring: names, limits, defaults, the rule of each.

Three studies judge a spring: the report (its criteria table), the tolerance study (the share
of variants failing each criterion) and the synthesis (each candidate's margins).  They all
judge through this module:

- :class:`Criteria` is the ``[criteria]`` table: every limit with its default (the report's
  ``[report]`` keys ``min_surge_margin``, ``float_margin``, ``min_goodman_safety``,
  ``max_seating_velocity`` and ``max_clash_severity`` are the same limits);
- :data:`RULES` names each criterion once: what it judges, how (its sense), its label;
- :func:`margin` is the one measure of how far a value is inside its limit (a fraction,
  ``>= 0`` where met), and :func:`passes` its verdict;
- :class:`Verdict` is one judged criterion as the report shows it, with the model that judged it
  and the other model's figure beside it (:func:`verdict`).

A study that changes a limit (its own ``[criteria]`` table) or a rule (here) changes every
consumer with it: ``tests/valve/test_one_home.py`` checks that, and
``tests/valve/design/test_criteria.py`` the rules and the table.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, param
from ...core.units import omega_to_rpm
from ..cam.timing import crank_words
from ..run import verdicts

__all__ = [
    "Criteria",
    "Rule",
    "RULES",
    "margin",
    "passes",
    "Verdict",
    "verdict",
    "MIN_GOODMAN_SAFETY",
    "MIN_SURGE_MARGIN",
    "FLOAT_MARGIN",
    "MAX_SEATING_VELOCITY",
    "MAX_CLASH_SEVERITY",
    "JUDGING_MODEL",
    "spring_verdicts",
    "float_verdict",
    "pump_up_verdict",
    "seating_verdict",
    "MIN_VALVE_PISTON_CLEARANCE",
    "clearance_verdict",
]

#: Smallest fatigue safety factor on the Goodman line (1.1-1.3 in spring practice) [-].
MIN_GOODMAN_SAFETY = 1.1
#: Smallest surge margin f1 / cam frequency at the top speed (rule of thumb 10-13) [-].
MIN_SURGE_MARGIN = 10.0
#: How far above the rated (top) speed the float speed must lie [fraction].
FLOAT_MARGIN = 0.1
#: Largest seat impact velocity of the valve up to the top speed [m/s] (a common design limit of
#: passenger-car valve trains is about 0.5 m/s).
MAX_SEATING_VELOCITY = 0.5
#: Smallest valve-to-piston clearance of the simulated valve (float and bounce included) along
#: its axis [m].  Engine builders ask 2.0 mm (0.080 in) at the intake and 2.5 mm (0.100 in) at the
#: exhaust of the seated valve's travel less the cam's lift, checked by hand with light springs
#: [LC Engineering], [moparts]: a margin that covers float, rod stretch, thermal growth and bearing
#: clearances together.  The simulated lift carries the float and the bounce itself, so the limit
#: on it keeps only the rest: 1 mm (rod stretch 0.1-0.3 mm at speed, the valve's growth 0.2-0.3 mm,
#: bearing clearances and the timing drive's stretch).
MIN_VALVE_PISTON_CLEARANCE = 1.0e-3
#: Largest clash severity [fraction of Fset] (:data:`springdyn.valve.run.verdicts.MAX_CLASH_SEVERITY`, its home).
MAX_CLASH_SEVERITY = verdicts.MAX_CLASH_SEVERITY
#: The spring model whose runs judge the criteria where it runs the spring: the distributed
#: chain (converged in its elements, every surge mode, coils closing turn by turn).
JUDGING_MODEL = "distributed"


@dataclass(frozen=True)
class Rule:
    """One criterion: its ``name``, its ``label`` for people, the ``sense`` of its limit
    (``">="``: at least, ``"<="``: at most, ``">0"``: above zero, ``"within"``: inside a range,
    ``"none"``: must not happen),
    the :class:`Criteria` field holding its limit (None: the limit comes with the value, e.g.
    the wire's own strength) and what it judges."""

    name: str
    label: str
    sense: str
    limit_field: str | None
    definition: str


#: Every criterion a valve spring is judged by, once.
RULES = {
    r.name: r
    for r in (
        Rule(
            "surge_margin",
            "surge margin",
            ">=",
            "min_surge_margin",
            "first natural frequency at installed length / camshaft frequency",
        ),
        Rule(
            "solid_length",
            "solid length",
            "<=",
            None,
            "the solid length below the open length (the spring's length at full lift)",
        ),
        Rule(
            "coil_bind",
            "coil-bind clearance at full lift",
            ">=",
            None,
            "installed length - cam lift - solid length against the coil-bind clearance",
        ),
        Rule(
            "coil_clash",
            "coil clash",
            "<=",
            "max_clash_severity",
            "the force coils closing where the static spring is open pass through their contact, over Fset",
        ),
        Rule(
            "min_retainer_force",
            "minimum retainer force (dynamic)",
            ">0",
            None,
            "at 0 N the spring end leaves the retainer",
        ),
        Rule("wire_stress", "peak wire stress", "<=", None, "the corrected stress of the wire's torsion alone"),
        Rule(
            "goodman",
            "fatigue safety factor (Goodman)",
            ">=",
            "min_goodman_safety",
            "every element's wire torsion range with surge, on the modified Goodman line",
        ),
        Rule(
            "float_speed",
            "float speed",
            ">=",
            None,
            "the lowest cam speed from which the valve leaves the cam over the nose at every higher speed",
        ),
        Rule(
            "seating_velocity",
            "seating velocity",
            "<=",
            "max_seating_velocity",
            "the valve's impact on its seat",
        ),
        Rule(
            "pump_up",
            "valve closes (no pump-up)",
            "<=",
            None,
            "the valve lift a hydraulic lash adjuster holds on the base circle",
        ),
        Rule(
            "valve_piston_clearance",
            "valve-to-piston clearance",
            ">=",
            "min_valve_piston_clearance",
            "the seated valve's travel to the piston less its simulated lift (float and bounce included), the "
            "smallest over the cycle and the speeds, along the valve's axis",
        ),
        Rule(
            "max_retainer_force",
            "largest retainer force",
            "<=",
            "max_retainer_force",
            "the largest retainer force over the speeds",
        ),
        Rule(
            "outer_diameter",
            "outer coil diameter",
            "<=",
            None,
            "D + d within the spring pocket (the synthesis' space)",
        ),
        Rule(
            "inner_diameter",
            "inner coil diameter",
            ">=",
            None,
            "D - d around the valve guide and stem seal (the synthesis' space)",
        ),
        Rule(
            "solid_stress",
            "stress at solid length",
            "<=",
            None,
            "EN 13906-1's permissible uncorrected stress at solid length, 0.5 Rm for cold-coiled springs",
        ),
        Rule(
            "spring_index",
            "spring index",
            "within",
            None,
            "D/d inside the range in which the coils stay stable in coiling (4 to 16 for valve springs)",
        ),
        Rule(
            "installed_force",
            "installed force",
            "<=",
            "installed_force_band",
            "the deviation of Fset from the nominal spring's",
        ),
    )
}


def margin(name: str, value, limit):
    """How far a value lies inside its limit [fraction]: ``>= 0`` where the criterion ``name``
    is met (:data:`RULES`).

    ``">="`` rules give ``value / limit - 1``, ``"<="`` rules ``1 - value / limit``, ``">0"``
    rules ``value / limit`` (``limit`` a positive scale, e.g. Fset; met above 0), ``"within"``
    rules ``min(value - lo, hi - value) / lo`` (``limit`` the range ``(lo, hi)``) and ``"none"``
    rules ``-1`` where it happens (``value`` true) and ``0`` where it does not.

    Parameters
    ----------
    name : str
        A key of :data:`RULES`.
    value : float or array_like
        The judged figure [its unit; bool for ``"none"`` rules].
    limit : float or array_like
        Its limit [the same unit], or the scale of a ``">0"`` rule.

    Examples
    --------
    >>> round(margin("goodman", 1.21, 1.1), 6), round(margin("seating_velocity", 0.4, 0.5), 6)
    (0.1, 0.2)
    """
    rule = RULES[name]
    v = np.asarray(value, dtype=float)
    if rule.sense == ">=":
        out = v / limit - 1.0
    elif rule.sense == "<=":
        out = 1.0 - v / limit
    elif rule.sense == ">0":
        out = v / limit
    elif rule.sense == "within":
        lo, hi = limit
        out = np.minimum(v - lo, hi - v) / lo
    else:
        out = -v.astype(bool).astype(float)
    return float(out) if out.ndim == 0 else out


def passes(name: str, value, limit) -> bool:
    """Whether ``value`` meets the criterion ``name`` (:func:`margin` at least 0; above 0 for a
    ``">0"`` rule).

    Parameters
    ----------
    name : str
        A key of :data:`RULES`.
    value : float or array_like
        The judged figure [its unit].
    limit : float or array_like
        Its limit [the same unit].
    """
    m = np.asarray(margin(name, value, limit))
    ok = m > 0.0 if RULES[name].sense == ">0" else m >= 0.0
    return bool(ok) if ok.ndim == 0 else ok


@dataclass(frozen=True)
class Criteria(Parameters):
    """The ``[criteria]`` table: what a valve spring must meet (every study's limits).

    Examples
    --------
    >>> Criteria().min_goodman_safety
    1.1
    """

    min_goodman_safety: float = param(
        "",
        "smallest Goodman safety over the speeds (1.1-1.3 in spring practice)",
        positive=True,
        default=MIN_GOODMAN_SAFETY,
    )
    min_surge_margin: float = param(
        "",
        "smallest surge margin f1 / cam frequency at the top speed (rule of thumb 10-13)",
        positive=True,
        default=MIN_SURGE_MARGIN,
    )
    float_margin: float = param(
        "",
        "how far above the top speed the float speed must lie (a fraction, e.g. '10 %'; the report's criterion)",
        nonnegative=True,
        default=FLOAT_MARGIN,
    )
    min_float_cam_rpm: float = param(
        "rad/s",
        "smallest float speed (default: the top of the speed range: no float within it; the report: the top speed "
        "plus float_margin)",
        display="rpm",
        bare_unit="rpm",
        positive=True,
        default=None,
    )
    max_seating_velocity: float = param(
        "m/s",
        "largest seat impact velocity of the valve up to the top speed (about 0.5 m/s for passenger-car trains)",
        positive=True,
        default=MAX_SEATING_VELOCITY,
    )
    no_coil_clash: bool = param(
        None, "no coil clash within the speed range (a severity above max_clash_severity)", kind="bool", default=True
    )
    max_clash_severity: float = param(
        "",
        "largest clash severity: the force coils closing where the static spring is open pass through their "
        "contact, a fraction of Fset (e.g. '10 %'; transition coils seating pass a few per cent)",
        positive=True,
        default=MAX_CLASH_SEVERITY,
    )
    max_retainer_force: float = param(
        "N", "largest retainer force over the speeds (optional)", positive=True, default=None
    )
    min_valve_piston_clearance: float = param(
        "m",
        "smallest valve-to-piston clearance of the simulated valve along its axis, with [piston] (builders ask "
        "2-2.5 mm of the static check; the simulated float is in the figure, the rest of the margin about 1 mm)",
        display="mm",
        positive=True,
        default=MIN_VALVE_PISTON_CLEARANCE,
    )
    installed_force_band: float = param(
        "",
        "largest deviation of Fset from the nominal spring's (a fraction, e.g. '10 %'; optional)",
        positive=True,
        default=None,
    )

    table = "criteria"

    def limit(self, name: str, default=None):
        """The limit of the criterion ``name`` (its :data:`RULES` field), else ``default``.

        Parameters
        ----------
        name : str
            A key of :data:`RULES`.
        default : float, optional
            The limit of a criterion whose limit comes with its value [its unit].
        """
        field = RULES[name].limit_field
        value = getattr(self, field) if field is not None else None
        return default if value is None else value

    def float_speed_needed(self, rated_cam_rpm: float | None) -> float | None:
        """The float speed the criteria ask for [rev/min]: ``min_float_cam_rpm``, else the rated
        speed plus :attr:`float_margin` (None: neither given).

        Parameters
        ----------
        rated_cam_rpm : float or None
            The highest cam speed in service [rev/min].
        """
        if self.min_float_cam_rpm is not None:
            return omega_to_rpm(self.min_float_cam_rpm)
        return None if rated_cam_rpm is None else rated_cam_rpm * (1.0 + self.float_margin)


@dataclass(frozen=True)
class Verdict:
    """One judged criterion as a report shows it: the criterion, the figure and its limit in
    words, pass (True), fail (False) or not applicable (None), a note, and the model that
    judged it (with the other model's figure in the note)."""

    name: str
    label: str
    value: str
    limit: str
    passed: bool | None
    note: str = ""
    model: str = ""


def verdict(name: str, value, limit, *, label: str, value_text: str, limit_text: str, note: str = "", model: str = ""):
    """A :class:`Verdict` of the criterion ``name`` (:func:`passes`).

    Parameters
    ----------
    name : str
        A key of :data:`RULES`.
    value : float or bool or None
        The judged figure [its unit] (None: not applicable).
    limit : float
        Its limit (or scale) [the same unit].
    label : str
        The criterion as the report names it (with its range) [-].
    value_text, limit_text : str
        The figure and the limit in words [-].
    note : str
        What it rests on, and the other model's figure [-].
    model : str
        The model that judged it [-].
    """
    if name not in RULES:
        raise InputError(f"criterion {name!r} is not one of {', '.join(RULES)}")
    ok = None if value is None else passes(name, value, limit)
    return Verdict(name, label, value_text, limit_text, ok, note, model)


def _model_name(model: str) -> str:
    return "distributed" if model == "distributed" else "Type C"


def spring_verdicts(
    criteria: Criteria,
    design: dict,
    table: dict,
    speeds,
    *,
    model: str,
    rated_cam_rpm: float,
    wire_limit: float,
    beside: dict | None = None,
    beside_design: dict | None = None,
) -> list[Verdict]:
    """The spring's criteria over a sweep: surge margin, solid length and coil bind, coil
    clash, minimum retainer force, peak wire stress and Goodman safety.

    Parameters
    ----------
    criteria : Criteria
        The limits.
    design : dict
        The spring's design figures at the cam's lift and the rated speed
        (:meth:`~springdyn.valve.spring.chains.SpringModel.design_figures`).
    table : dict
        The judging model's sweep summary table
        (:meth:`~springdyn.valve.run.sweeps.SpeedSweep.summary_table`).
    speeds : array_like
        The sweep's cam speeds [rev/min].
    model : str
        The judging model's name.
    rated_cam_rpm : float
        The top speed in service [rev/min].
    wire_limit : float
        The wire's shear stress limit [Pa] (:func:`springdyn.valve.spring.stress.spring_strengths`).
    beside : dict, optional
        The other model's sweep summary table over the same speeds: its figure goes in each note.
    beside_design : dict, optional
        The other model's design figures (its surge margin goes in the note).
    """
    speeds = np.asarray(speeds, dtype=float)
    top = rated_cam_rpm
    name = _model_name(model)
    rng = f"{speeds[0]:.0f}-{speeds[-1]:.0f} cam rpm, {name}"

    def other(text):
        return f"; Type C: {text}" if beside is not None else ""

    margin_value = design["installed"]["surge_margin"]
    f1 = design["installed"]["surge_frequency_Hz"]
    other_margin = (
        f"; Type C: {beside_design['installed']['surge_margin']:.1f} (f1 "
        f"{beside_design['installed']['surge_frequency_Hz']:.1f} Hz)"
        if beside_design is not None and model != "type-c"
        else ""
    )
    out = [
        verdict(
            "surge_margin",
            margin_value,
            criteria.min_surge_margin,
            label=f"surge margin at {top:.0f} cam rpm, {name}",
            value_text=f"{margin_value:.1f} (f1 {f1:.1f} Hz)",
            limit_text=f">= {criteria.min_surge_margin:g} ([report] min_surge_margin; rule of thumb 10-13)",
            note=RULES["surge_margin"].definition + f" (f1: the {name} chain's first mode, ends fixed)" + other_margin,
            model=name,
        )
    ]
    cb = design.get("coil_bind")
    if cb is not None:
        out.append(
            verdict(
                "solid_length",
                cb["solid_length_m"],
                cb["open_length_m"],
                label="solid length",
                value_text=f"{cb['solid_length_m'] * 1e3:.2f} mm",
                limit_text=f"below the open length {cb['open_length_m'] * 1e3:.2f} mm",
                note=f"the spring's one solid length ({cb.get('solid_length_source', 'EN 13906-1')}), the same in "
                "both models; the spring's length at full lift is the open length",
                model="statics",
            )
        )
        out.append(
            Verdict(
                "coil_bind",
                "coil-bind clearance at full lift"
                + (" (dynamic)" if cb["coil_bind_clearance_source"].startswith("EN 13906-1 dynamic") else ""),
                f"{cb['coil_bind_margin_m'] * 1e3:.2f} mm above solid ({cb['solid_length_m'] * 1e3:.2f} mm)",
                f">= {cb['coil_bind_clearance_m'] * 1e3:.2f} mm ({cb['coil_bind_clearance_source']})",
                bool(cb["coil_bind_ok"]),
                "THROUGH SOLID (through_solid = true): forces rest on the closed coils' contact stiffness"
                if cb["through_solid"]
                else "installed length - cam lift - solid length"
                + (
                    f"; EN 13906-1's static Sa {cb['static_sum_of_gaps_m'] * 1e3:.2f} mm is "
                    + ("met" if cb["static_gaps_ok"] else "missed too")
                    if "static_sum_of_gaps_m" in cb
                    else ""
                ),
                "statics",
            )
        )

    limit = criteria.max_clash_severity

    def clash_text(t):
        sev = np.asarray(t["clash_severity"], dtype=float)
        k = int(np.argmax(sev))
        over = sev > limit
        seat, act = (int(np.count_nonzero(t[c])) for c in ("transition_seating", "active_coil_closing"))
        return (
            f"largest severity {100 * sev[k]:.1f} % of Fset at {speeds[k]:.0f} cam rpm; above the limit at "
            f"{int(over.sum())} of {sev.size} speeds"
            + (f" from {speeds[over][0]:.0f} cam rpm" if over.any() else "")
            + f" (transition coils seat at {seat}, active coils close at {act})"
        )

    sev = np.asarray(table["clash_severity"], dtype=float)
    out.append(
        verdict(
            "coil_clash",
            float(np.max(sev)) if criteria.no_coil_clash else 0.0,
            limit,
            label=f"coil clash, {rng}",
            value_text=clash_text(table),
            limit_text=f"<= {100 * limit:g} % of Fset ([criteria] max_clash_severity)"
            if criteria.no_coil_clash
            else "not judged ([criteria] no_coil_clash = false)",
            note=RULES["coil_clash"].definition
            + "; transition coils seating earlier than the static spring pass a few per cent, surge-driven impacts "
            "of the active coils more"
            + other(clash_text(beside) if beside is not None else "")
            + (f"; {design['coil_contact_note']}" if "coil_contact_note" in design else ""),
            model=name,
        )
    )
    k = int(np.argmin(table["min_retainer_force_N"]))
    fmin = float(table["min_retainer_force_N"][k])
    kb = int(np.argmin(beside["min_retainer_force_N"])) if beside is not None else 0
    out.append(
        verdict(
            "min_retainer_force",
            fmin,
            1.0,
            label=f"minimum retainer force (dynamic), {rng}",
            value_text=f"{fmin:.1f} N at {speeds[k]:.0f} cam rpm",
            limit_text="> 0 N",
            note=f"static minimum {float(np.min(table['min_static_force_N'])):.1f} N; at 0 N the spring end leaves the "
            "retainer"
            + other(
                f"{float(beside['min_retainer_force_N'][kb]):.1f} N at {speeds[kb]:.0f} cam rpm"
                if beside is not None
                else ""
            ),
            model=name,
        )
    )
    peak = np.asarray(table["peak_shear_stress_Pa"], dtype=float)
    k = int(np.argmax(peak))
    out.append(
        Verdict(
            "wire_stress",
            f"peak wire stress, {rng}",
            f"{peak[k] / 1e6:.0f} MPa at {speeds[k]:.0f} cam rpm (element {int(table['peak_shear_stress_element'][k])})",
            f"<= {wire_limit / 1e6:.0f} MPa",
            bool(np.all(table["wire_stress_ok"])),
            "EN 13906-1 corrected stress of the wire's torsion alone (force closed coils pass through their contact "
            "excluded); limit: shear_yield_strength, else the ultimate shear strength"
            + other(f"{float(np.max(beside['peak_shear_stress_Pa'])) / 1e6:.0f} MPa" if beside is not None else ""),
            name,
        )
    )
    dyn = np.asarray(table["fatigue_safety_factor"], dtype=float)
    k = int(np.argmin(dyn))
    fat = design.get("fatigue", {})
    defaults = fat.get("strength_defaults", [])
    out.append(
        verdict(
            "goodman",
            dyn[k],
            criteria.min_goodman_safety,
            label=f"fatigue safety factor (Goodman), {rng}",
            value_text=f"{dyn[k]:.2f} at {speeds[k]:.0f} cam rpm",
            limit_text=f">= {criteria.min_goodman_safety:g} ([report] min_goodman_safety)",
            note=f"static (installed to open) {fat.get('static_fatigue_safety_factor', float('nan')):.2f}; the "
            "dynamic factor uses every element's wire torsion range with surge"
            + other(f"{float(np.min(beside['fatigue_safety_factor'])):.2f}" if beside is not None else "")
            + (f"; default wire strengths for {', '.join(defaults)}" if defaults else ""),
            model=name,
        )
    )
    return out


def float_verdict(
    criteria: Criteria,
    float_result,
    rated_cam_rpm: float,
    first_lift_off: str = "",
    *,
    model: str = "",
    beside: str = "",
) -> Verdict:
    """The float speed against the speed the criteria ask for (:meth:`Criteria.float_speed_needed`).

    Parameters
    ----------
    criteria : Criteria
        The limits.
    float_result : FloatSpeedResult
        The float speed search (:meth:`springdyn.valve.ValveModel.float_speed_above`).
    rated_cam_rpm : float
        The top speed in service [rev/min].
    first_lift_off : str
        Words on the first lift-off below the float speed, for the note [-].
    model : str
        The spring model of the search (``"type-c"``, ``"distributed"``; empty: not named) [-].
    beside : str
        The other model's float speed in words, for the note [-].
    """
    need = criteria.float_speed_needed(rated_cam_rpm)
    name = _model_name(model) if model else ""
    label = f"float speed, {name}" if name else "float speed"
    other = f"; {beside}" if beside else ""
    f = float_result.float_cam_rpm
    limit = f">= {need:.0f} cam rpm ({100 * criteria.float_margin:g} % above the top speed {rated_cam_rpm:.0f} cam rpm)"
    if f is None:
        return verdict(
            "float_speed",
            float_result.cam_rpm[-1],
            need,
            label=label,
            value_text=f"above {float_result.cam_rpm[-1]:.0f} cam rpm",
            limit_text=limit,
            note="the valve does not leave the cam over the nose at the highest scanned speed" + first_lift_off + other,
            model=name,
        )
    return verdict(
        "float_speed",
        f,
        need,
        label=label,
        value_text=f"{f:.0f} cam rpm (+-{float_result.resolution_rpm / 2:g})",
        limit_text=limit,
        note="lowest cam speed from which the valve leaves the cam over the nose at every higher scanned speed"
        + first_lift_off
        + other,
        model=name,
    )


def pump_up_verdict(held_open: float, rated_cam_rpm: float, *, model: str = "") -> Verdict:
    """The valve closes at the rated speed: no pump-up of the hydraulic lash adjuster, judged by
    its rule (:func:`springdyn.valve.run.verdicts.pumps_up`).

    Parameters
    ----------
    held_open : float
        The valve lift the adjuster holds on the base circle [m].
    rated_cam_rpm : float
        The top speed in service [rev/min].
    model : str
        The spring model of the run (empty: not named) [-].
    """
    name = _model_name(model) if model else ""
    return Verdict(
        "pump_up",
        f"valve closes at {rated_cam_rpm:.0f} cam rpm (no pump-up)" + (f", {name}" if name else ""),
        f"held open {held_open * 1e3:.3f} mm",
        "0 mm on the base circle",
        not verdicts.pumps_up(held_open),
        "the hydraulic lash adjuster must not extend into a lift-off and hold the valve open",
        name,
    )


def seating_verdict(
    criteria: Criteria, velocity: float, rated_cam_rpm: float, *, model: str = "", beside: str = ""
) -> Verdict:
    """The largest seat impact velocity up to the rated speed.

    Parameters
    ----------
    criteria : Criteria
        The limits.
    velocity : float
        The largest seating velocity band's top up to the rated speed [m/s].
    rated_cam_rpm : float
        The top speed in service [rev/min].
    model : str
        The spring model of the scan (empty: not named) [-].
    beside : str
        The other model's figure in words, for the note [-].
    """
    name = _model_name(model) if model else ""
    return verdict(
        "seating_velocity",
        velocity,
        criteria.max_seating_velocity,
        label=f"seating velocity up to {rated_cam_rpm:.0f} cam rpm" + (f", {name}" if name else ""),
        value_text=f"{velocity:.2f} m/s",
        limit_text=f"<= {criteria.max_seating_velocity:g} m/s ([report] max_seating_velocity)",
        note="the valve's impact on its seat, the largest of the band over the scanned speeds within 25 rpm and, "
        "where a speed does not settle, its last revolutions" + (f"; {beside}" if beside else ""),
        model=name,
    )


def clearance_verdict(criteria: Criteria, clearance, *, model: str = "") -> Verdict:
    """The smallest valve-to-piston clearance over the speeds against
    :attr:`Criteria.min_valve_piston_clearance`.

    Parameters
    ----------
    criteria : Criteria
        The limits.
    clearance : ValveClearance
        The clearance over the speeds (:meth:`springdyn.valve.ValveModel.valve_clearance`).
    model : str
        The spring model of the runs (empty: not named) [-].
    """
    s = clearance.summary
    name = _model_name(model) if model else ""
    limit = criteria.min_valve_piston_clearance
    rpm = clearance.cam_rpm
    return verdict(
        "valve_piston_clearance",
        s["min_clearance_m"],
        limit,
        label=f"{s['valve']} valve-to-piston clearance, {rpm[0]:.0f}-{rpm[-1]:.0f} cam rpm"
        + (f", {name}" if name else ""),
        value_text=f"{s['min_clearance_m'] * 1e3:.2f} mm at {s['min_clearance_cam_rpm']:.0f} cam rpm, "
        f"{crank_words(s['min_clearance_crank_angle_deg'])}",
        limit_text=f">= {limit * 1e3:g} mm ([criteria] min_valve_piston_clearance)",
        note=f"static (rigid train) {s['static_min_clearance_m'] * 1e3:.2f} mm at "
        f"{crank_words(s['static_min_clearance_crank_angle_deg'])}; "
        + RULES["valve_piston_clearance"].definition
        + "; [piston] geometry or measured table",
        model=name,
    )
