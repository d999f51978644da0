"""``springdyn cfcs ...``: the command line of the CFCS model (no physics here)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from springdyn.app.cli.common import (
    add_output_options,
    as_options,
    emit,
    parse_range,
    print_notes,
    print_table,
    quantity,
)
from springdyn.cfcs.params import EXAMPLES, CFCSParams
from springdyn.core.errors import InputError
from springdyn.core.units import format_quantity

#: The default stroke of the sinusoidal motion (``springdyn.cfcs.model.DEFAULT_AMPLITUDE``,
#: a fraction of r2 + r3; a test checks the two agree).
DEFAULT_AMPLITUDE = "40 %"
#: The default preload offset (``springdyn.cfcs.model.DEFAULT_OFFSET``; a test checks the two agree).
DEFAULT_OFFSET = "2.5 %"

__all__ = ["register"]

#: Library argument -> CLI option, for the library's error messages.
_OPTIONS = dict(
    omega="--omega",
    amplitude="--amplitude",
    offset="--offset",
    stroke="--stroke",
    stroke_fraction="--stroke-fraction",
    force="--force",
    n="--points",
    cycles="--cycles",
    samples_per_cycle="--samples",
)

_CFG_HELP = f"mechanism TOML file with a [cfcs] table, or a built-in example ({', '.join(EXAMPLES)})"
_TOGGLE_NOTE = (
    "The motion starts by default from a preload offset of 2.5% of r2 + r3 inside the constant-force "
    "band.  At the toggle (theta2 = 0) dx/dtheta2 vanishes and tau_AF / tau_CF turned into a slider "
    "force diverge: inside the toggle zone (theta2 below toggle_cutoff, default 5 deg) they use "
    "dx/dtheta2 frozen at its cut-off value; a motion that enters the zone has its statistics computed "
    "at the cut-off and at twice it, and those that change by more than 1% are flagged "
    "toggle-dominated.  The spring and inertia forces are finite there and computed exactly."
)


def register(subparsers) -> None:
    """Add ``cfcs`` and its sub-commands to the ``springdyn`` parser."""
    p = subparsers.add_parser(
        "cfcs",
        help="constant-force compression springs (pseudo-rigid-body model)",
        description="Constant-force compression spring: statics, dynamics, sweeps, design. " + _TOGGLE_NOTE,
    )
    sub = p.add_subparsers(dest="cfcs_command", metavar="ACTION", required=True)

    s = _command(sub, "static", _static, help="force-deflection curve, PCF and pivot stress")
    s.add_argument("--stroke", help="stroke from the toggle (default 40%% of r2 + r3), e.g. 72mm")
    s.add_argument("--points", type=int, default=721, help="samples of the curve (default 721)")
    s.add_argument(
        "--offset",
        default=DEFAULT_OFFSET,
        help="start of the working range over which the dissipative "
        "branches are rated (default 2.5%% of r2 + r3, a preload), e.g. 5mm or 0",
    )
    _model_and_output_options(s)

    d = _command(
        sub,
        "dynamic",
        _dynamic,
        help="slider force along a prescribed periodic motion (inverse dynamics)",
        description="Force needed to drive the slider along x(t) = offset + amplitude (1 - cos wt)/2 "
        "or a periodic motion from a CSV (columns time_s, deflection_m). " + _TOGGLE_NOTE,
    )
    _motion_options(d, omega_help="circular frequency [rad/s] of the input (required without --motion)")
    d.add_argument(
        "--motion",
        metavar="X.csv",
        help="periodic x(t) from a CSV (time_s, deflection_m); with --omega its period is rescaled to 2 pi/omega",
    )
    d.add_argument("--cycles", type=int, default=2, help="cycles to output (default 2)")
    d.add_argument(
        "--samples", type=int, help="samples per cycle (default 400; 2000 with a compliant drive, per period)"
    )
    d.add_argument("--no-dissipation", action="store_true", help="switch off tau_CF, tau_AF and slider friction")
    d.add_argument(
        "--drive-stiffness",
        help="stiffness of what pushes the slider, e.g. '20 kN/m': the motion then moves the drive's far end and "
        "the crank is integrated through the toggle with its inertia (forward dynamics, no cut-off); default "
        "drive_stiffness of the configuration, unset: the slider follows the motion rigidly",
    )
    d.add_argument("--drive-damping", help="damping of the drive, e.g. '5 N*s/m' (default drive_damping, 0)")
    d.add_argument("--periods", type=int, help="compliant drive: periods integrated, statistics over the last (6)")
    d.add_argument("--rtol", help="compliant drive: relative tolerance of the integrator (default 1e-8)")
    d.add_argument("--max-step", help="compliant drive: largest integration step (default period/400), e.g. 1ms")
    d.add_argument(
        "--sign-smoothing", help="compliant drive: speed v_s of tanh(theta2'/v_s), the Coulomb sign [rad/s] (0.001)"
    )
    _model_and_output_options(d)

    w = _command(sub, "sweep", _sweep, help="mean/median/peak-to-peak force and PCF vs omega (Figs. 5-7)")
    _motion_options(w, omega_help="frequencies START:STOP:STEP or a comma list [rad/s], e.g. 1:50:0.5", required=True)
    w.add_argument("--samples", type=int, default=400, help="samples per cycle (default 400)")
    w.add_argument("--quiet", action="store_true", help="no progress bar")
    _model_and_output_options(w)

    f = _command(sub, "forward", _forward, help="response of the slider to a force or to a spring from a moving base")
    f.add_argument("--t-end", required=True, help="simulated time, e.g. 2s")
    f.add_argument("--force", help="constant slider force (positive in compression), e.g. 13N")
    f.add_argument("--base-stiffness", help="stiffness of the drive spring, e.g. 2000N/m")
    f.add_argument("--base-damping", default="0", help="damping of the drive spring, e.g. 1N*s/m")
    _motion_options(f, omega_help="circular frequency of the base motion [rad/s]", prefix="base-")
    f.add_argument("--x0", default="1mm", help="initial deflection (default 1mm; the toggle itself is an equilibrium)")
    f.add_argument("--v0", default="0", help="initial slider velocity [m/s] (default 0)")
    f.add_argument("--points", type=int, default=2001, help="output samples (default 2001)")
    f.add_argument("--sign-smoothing", default="0.01", help="velocity scale of the smoothed Coulomb sign [rad/s]")
    _model_and_output_options(f)

    g = _command(
        sub,
        "design",
        _design,
        config=False,
        help="choose r2/r3, K3 and the flexure for a target force and stroke",
        description="Sizes the strip with the beam (elastica) model by default and checks the "
        "stress (safety factor 1.5), the PCF, buckling of the strip and the thickness tolerance.  "
        "Exit status 1 when no design holds (the binding check and the smallest changes are "
        "printed).",
    )
    g.add_argument("--force", required=True, help="target constant force, e.g. 12.8N")
    g.add_argument("--stroke", required=True, help="working stroke from the toggle, e.g. 40mm")
    g.add_argument("--material-modulus", required=True, help="Young's modulus of the flexure, e.g. 207GPa")
    g.add_argument("--allowable-stress", required=True, help="allowable bending stress, e.g. 1.5GPa")
    g.add_argument("--stroke-fraction", default="0.4", help="stroke / (r2 + r3) (default 0.4)")
    g.add_argument("--length", help="r2 + r3 (overrides --stroke-fraction), e.g. 180mm")
    g.add_argument("--pivot-length-ratio", default="0.1", help="flexure length / r3 (default 0.1)")
    g.add_argument("--max-width", help="largest flexure width (default r3)")
    g.add_argument("--safety-factor", default="1.5", help="design stress = allowable / this (default 1.5)")
    g.add_argument(
        "--min-pcf", default="90", help="smallest percent constant force over the working range [%%] (default 90)"
    )
    g.add_argument(
        "--thickness-tolerance", default="5%", help="strip thickness tolerance (default 5%%; the force goes as h^3)"
    )
    g.add_argument("--preload", default="0", help="start of the working range (default 0, the toggle), e.g. 3mm")
    g.add_argument(
        "--plate-bending",
        choices=("auto", "true", "false"),
        default="auto",
        help="strip modulus E/(1 - nu^2) (true) or E (false); auto: plate when the width >= the length (beam model)",
    )
    g.add_argument("--poisson-ratio", default="0.3", help="Poisson's ratio of the strip (default 0.3)")
    _model_option(g, default="beam")
    g.add_argument("--toml", metavar="OUT.toml", help="write the design as a [cfcs] table")
    add_output_options(g)


def _command(sub, name: str, func, *, config: bool = True, **kw):
    """The sub-command ``name`` (``help``, ``description`` in ``kw``) that runs ``func``; its first
    argument the mechanism (``CFG.toml`` or a built-in example) unless ``config`` is False."""
    p = sub.add_parser(name, **kw)
    if config:
        p.add_argument("config", metavar="CFG.toml", help=_CFG_HELP)
    p.set_defaults(func=func)
    return p


def _model_and_output_options(p) -> None:
    """The options every mechanism command ends with: ``--model``, then ``--csv``, ``--plot``, ``--json``."""
    _model_option(p)
    add_output_options(p)


def _model_option(p, default=None):
    p.add_argument(
        "--model",
        choices=("prbm", "beam"),
        default=default,
        help="flexure model: prbm (pin with K3 = EI/l) or beam (large-deflection elastica of the strip)"
        + ("" if default else "; default: flexure_model of the configuration (prbm)"),
    )


def _motion_options(p, *, omega_help, required=False, prefix=""):
    """``--omega``, ``--amplitude`` and ``--offset`` of the sinusoid; with ``prefix`` (``"base-"``) those
    of the forward problem's moving base, which starts at 0 (no preload)."""
    if prefix:
        amplitude_help = "stroke of the base sinusoid: a length such as 72mm or a percentage of r2 + r3 such as "
        offset, offset_help = "0", "base position at t = 0 (default 0), e.g. 5mm"
    else:
        amplitude_help = (
            "stroke of the sinusoid: a length such as 72mm (a bare number is metres) or a percentage of "
            "r2 + r3 such as "
        )
        offset = DEFAULT_OFFSET
        offset_help = (
            "deflection at t = 0: a preload, a length or a percentage of r2 + r3 (default 2.5%%); "
            "0 starts at the toggle"
        )
    p.add_argument(f"--{prefix}omega", required=required, help=omega_help)
    p.add_argument(f"--{prefix}amplitude", default=DEFAULT_AMPLITUDE, help=amplitude_help + "'40%%' (default 40%%)")
    p.add_argument(f"--{prefix}offset", default=offset, help=offset_help)


def _q(text, unit: str, option: str) -> float:
    """A CLI quantity; a bare number is SI (also for units pint treats as dimensionless-like, rad/s)."""
    return quantity(text, unit, option, bare_unit=unit)


def _load(config: str, model: str | None = None) -> CFCSParams:
    path = Path(config)
    if path.is_file():
        params = CFCSParams.from_toml(path)
    elif config in EXAMPLES:
        params = CFCSParams.example(config)
    else:
        raise InputError(f"{config}: no such file (and not a built-in example: {', '.join(EXAMPLES)})")
    if model is not None and model != params.flexure_model:
        with as_options(flexure_model="--model"):
            params = params.replace(flexure_model=model)
    return params


def _yields(safety, sep: str = "") -> str:
    """The word beside a pivot safety factor below 1 (issue 40: 0.42 was printed without it)."""
    if safety is None or safety >= 1.0:
        return ""
    return f"{sep}YIELDS: the pivot's stress exceeds the allowable (the mechanism takes a set)"


def _fmt(value, unit="", display=None, digits=5):
    if value is None:
        return "n/a"
    if isinstance(value, str):
        return value
    return format_quantity(float(value), unit, display, digits)


def _show(args, result, rows) -> int:
    """Write ``--csv`` and ``--plot``; print the summary as JSON with ``--json``, else the table
    ``rows(summary)`` and the notes."""
    if not emit(result, args):
        print_table(rows(result.summary), headers=("quantity", "value", "note"))
        print_notes(result.summary)
    return 0


def _cutoff_row(summary):
    cut = summary.get("toggle_cutoff_rad")
    return ("toggle cut-off", _fmt(cut, "rad", "deg", 4) if cut is not None else "none (forward problem)", "")


def _static(args) -> int:
    from springdyn.cfcs.model import CFCS

    model = CFCS(_load(args.config, args.model))
    stroke = _q(args.stroke, "m", "--stroke") if args.stroke else None
    with as_options(**_OPTIONS):
        res = model.static(stroke, n=args.points, offset=args.offset)
    return _show(args, res, _static_rows)


def _static_rows(s) -> list:
    beam = s["flexure_model"] == "beam"
    prbm_rows = (
        [
            (
                "PRBM maximum force",
                _fmt(s["prbm_force_max_N"], "N"),
                f"at {_fmt(s['prbm_deflection_at_force_max_m'], 'm', 'mm')}",
            ),
            ("PRBM PCF Fmin/Fmax", _fmt(s["prbm_pcf_percent"], "%", digits=4), ""),
            ("max |beam - PRBM| force", _fmt(s["max_force_difference_to_prbm_N"], "N"), ""),
            ("PRBM max pivot stress", _fmt(s["prbm_max_stress_Pa"], "Pa", "GPa", 4), "mean curvature theta_K3/l"),
        ]
        if beam
        else []
    )
    return [
        (
            "flexure model",
            s["flexure_model"],
            ("elastica of the strip, " if beam else "pin with K3 = EI/l, ")
            + ("plate E/(1 - nu^2)" if s["plate_bending"] else "beam modulus E"),
        ),
        ("stroke", _fmt(s["stroke_m"], "m", "mm"), ""),
        ("force at the toggle", _fmt(s["force_at_zero_N"], "N"), ""),
        ("maximum force", _fmt(s["force_max_N"], "N"), f"at {_fmt(s['deflection_at_force_max_m'], 'm', 'mm')}"),
        ("minimum force", _fmt(s["force_min_N"], "N"), ""),
        ("PCF Fmin/Fmax", _fmt(s["pcf_percent"], "%", digits=4), ""),
        ("PCF energy-based", _fmt(s["pcf_energy_percent"], "%", digits=4), ""),
        (
            "PCF compression branch",
            _fmt(s["pcf_compression_percent"], "%", digits=4),
            f"friction {s['friction_model']}, tau_AF {'on' if s['axial_force'] else 'off'}" + _static_offsets(s),
        ),
        (
            "max pivot stress",
            _fmt(s["max_stress_Pa"], "Pa", "GPa", 4),
            "largest curvature of the strip" if beam else "E (h/2) theta_K3 / l",
        ),
        ("safety factor", _fmt(s["safety_factor"], digits=3), _yields(s["safety_factor"])),
        *prbm_rows,
        *_beam_check_rows(s),
        ("max stroke for stress", _fmt(s["max_stroke_for_stress_m"], "m", "mm"), ""),
        ("kinematic limit", _fmt(s["kinematic_limit_m"], "m", "mm"), ""),
        (
            "working range",
            f"{_fmt(s['working_start_m'], 'm', 'mm')} .. {_fmt(s['working_end_m'], 'm', 'mm')}",
            "PCF compression branch rated here",
        ),
        _cutoff_row(s),
        _toggle_row(s),
    ]


def _static_offsets(s) -> str:
    """The compression branch's PCF with the working range from half and twice the offset (issue 40)."""
    parts = [
        f"{_fmt(s[f'working_start_{tag}_offset_m'], 'm', 'mm', 3)}: {s[f'pcf_compression_at_{tag}_offset_percent']:.4g} %"
        for tag in ("half", "double")
        if s.get(f"pcf_compression_at_{tag}_offset_percent") is not None
    ]
    if not parts:
        return ""
    flag = "OFFSET-SENSITIVE, " if s.get("offset_sensitive_statistics") else ""
    return f"; {flag}from " + ", ".join(parts)


def _beam_check_rows(summary) -> list:
    """The beam check of a PRBM result (empty for the beam model)."""
    if "beam_band_error_percent" not in summary:
        return []
    s = summary
    if s["beam_band_error_percent"] is None:
        return [("beam check", "n/a", "see the notes")]
    working = s.get("beam_working_band_error_percent")
    return [
        (
            "beam check: elastica band",
            f"{s['beam_force_min_N']:.5g} .. {s['beam_force_max_N']:.5g} N",
            "the strip as an elastica, same modulus",
        ),
        (
            "PRBM band error",
            f"{s['beam_band_error_percent']:+.3g} %",
            "(band PRBM - band elastica) / band elastica"
            + (f"; working range {working:+.3g} %" if working is not None else ""),
        ),
        *(
            [
                (
                    "  ... with the range's end",
                    f"{s['beam_band_error_min_percent']:+.3g} .. {s['beam_band_error_max_percent']:+.3g} %",
                    f"ends {_fmt(s['beam_band_error_ends_m'][0], 'm', 'mm', 4)} .. "
                    f"{_fmt(s['beam_band_error_ends_m'][1], 'm', 'mm', 4)}: it depends on where the range ends; "
                    "the force error only grows with it",
                )
            ]
            if s.get("beam_band_error_min_percent") is not None
            else []
        ),
        ("PRBM force error", f"{s['beam_force_error_percent']:.3g} % of F0", "max |F PRBM - F elastica| / F0"),
    ]


def _toggle_row(summary):
    dom = summary.get("toggle_dominated_statistics") or []
    return (
        "toggle-dominated",
        "YES" if summary.get("toggle_dominated") else "no",
        (", ".join(dom) + " move > 1 % when the cut-off doubles") if dom else "",
    )


def _dynamic(args) -> int:
    from springdyn.cfcs.model import CFCS

    params = _load(args.config, args.model)
    if args.no_dissipation:
        params = params.without_dissipation()
    model = CFCS(params)
    omega = _q(args.omega, "rad/s", "--omega") if args.omega else None
    driven = args.drive_stiffness is not None or params.drive_stiffness is not None
    if not driven:
        given = [
            o
            for o, v in (
                ("--drive-damping", args.drive_damping),
                ("--periods", args.periods),
                ("--rtol", args.rtol),
                ("--max-step", args.max_step),
                ("--sign-smoothing", args.sign_smoothing),
            )
            if v is not None
        ]
        if given:
            raise InputError(
                f"{', '.join(given)} {'needs' if len(given) == 1 else 'need'} a compliant drive: give "
                "--drive-stiffness (e.g. '20 kN/m')"
            )
    with as_options(**_OPTIONS):
        mot = model.motion(omega, args.amplitude, args.offset, csv=args.motion)
        if driven:
            return _driven(args, model, mot)
        res = model.dynamic(
            motion=mot, cycles=args.cycles, samples_per_cycle=400 if args.samples is None else args.samples
        )
    return _show(args, res, _dynamic_rows)


def _at_offsets(s, key: str, unit: str, digits: int = 4) -> str:
    """The figure ``key`` with the motion started at half and at twice the preload offset (issue 40)."""
    parts = []
    for tag in ("half", "double"):
        st = s.get(f"statistics_at_{tag}_offset")
        if st is not None:
            parts.append(f"{_fmt(st['offset_m'], 'm', 'mm', 3)}: {st[key]:.{digits}g} {unit}")
    if not parts:
        return ""
    flag = "OFFSET-SENSITIVE, " if key in (s.get("offset_sensitive_statistics") or []) else ""
    return f"{flag}from offset " + ", ".join(parts)


def _dynamic_rows(s) -> list:
    return [
        ("input", s["motion"], ""),
        ("mean force", _fmt(s["mean_force_N"], "N"), _at_offsets(s, "mean_force_N", "N")),
        ("median force", _fmt(s["median_force_N"], "N"), ""),
        ("peak-to-peak force", _fmt(s["peak_to_peak_N"], "N"), _at_offsets(s, "peak_to_peak_N", "N")),
        ("largest force", _fmt(s["force_max_N"], "N"), _at_offsets(s, "force_max_N", "N")),
        (
            "PCF Fmin/Fmax",
            _fmt(s["pcf_percent"], "%", digits=4),
            "over one cycle" + (f"; {_at_offsets(s, 'pcf_percent', '%', 3)}" if s.get("offset_m") else ""),
        ),
        (
            "hysteresis per cycle",
            _fmt(s["hysteresis_energy_per_cycle_J"], "J"),
            _at_offsets(s, "hysteresis_energy_per_cycle_J", "J", 3),
        ),
        (
            "max pivot stress",
            _fmt(s["max_stress_Pa"], "Pa", "GPa", 4),
            f"safety factor {_fmt(s['safety_factor'], digits=3)}" + _yields(s["safety_factor"], "; "),
        ),
        *_beam_check_rows(s),
        _cutoff_row(s),
        ("samples in toggle zone", str(s["toggle_zone_samples"]), ""),
        _toggle_row(s),
    ]


def _sticking_row(s: dict) -> tuple:
    """The driven table's row on the crank resting within the shear angle of the toggle."""
    if s["toggle_stop_angle_rad"] is None:
        return ("toggle sticking", "no", "the crank never rests within the shear angle")
    stop = (
        f"{100 * s['toggle_sticking_share']:.3g} % of the period at theta2 {s['toggle_stop_angle_rad'] * 1e3:.3g} mrad"
    )
    return (
        "toggle sticking",
        ("YES: " if s["toggle_sticking"] else "no: ") + stop,
        f"{s['toggle_stop_angle_over_shear_angle']:.2g} alpha, released at {_fmt(s['toggle_release_force_N'], 'N')}",
    )


def _driven(args, model, mot) -> int:
    """``cfcs dynamic`` with a compliant drive: forward dynamics through the toggle."""
    from springdyn.cfcs.drive import DRIVE_SIGN_SMOOTHING
    from springdyn.cfcs.model import DRIVEN_PERIODS, DRIVEN_RTOL, DRIVEN_SAMPLES

    kw = dict(
        drive_stiffness=_q(args.drive_stiffness, "N/m", "--drive-stiffness") if args.drive_stiffness else None,
        drive_damping=_q(args.drive_damping, "N*s/m", "--drive-damping") if args.drive_damping else None,
        periods=DRIVEN_PERIODS if args.periods is None else args.periods,
        samples_per_period=DRIVEN_SAMPLES if args.samples is None else args.samples,
        rtol=_q(args.rtol, "", "--rtol") if args.rtol else DRIVEN_RTOL,
        max_step=_q(args.max_step, "s", "--max-step") if args.max_step else None,
        sign_smoothing=_q(args.sign_smoothing, "rad/s", "--sign-smoothing")
        if args.sign_smoothing
        else DRIVE_SIGN_SMOOTHING,
    )
    with as_options(
        periods="--periods",
        samples_per_period="--samples",
        rtol="--rtol",
        max_step="--max-step",
        drive_stiffness="--drive-stiffness",
    ):
        res = model.driven(motion=mot, **kw)
    return _show(args, res, _driven_rows if res.summary["rigid_drive"] is False else _rigid_drive_rows)


def _rigid_drive_rows(s) -> list:
    """A drive stiff enough to be rigid (``CFCS.driven`` gave the inverse dynamics)."""
    return [
        (
            "drive",
            f"k_d {s['drive_stiffness_N_per_m']:.4g} N/m: RIGID (from {s['rigid_drive_stiffness_N_per_m']:.3g} N/m)",
            f"(w_n/omega)^2 {s['drive_frequency_ratio_squared']:.3g}, lag {s['drive_lag_share']:.2g} of the stroke",
        ),
        *_dynamic_rows(s),
    ]


def _driven_rows(s) -> list:
    return [
        ("input", s["motion"], "moves the drive's far end"),
        (
            "drive",
            f"k_d {_fmt(s['drive_stiffness_N_per_m'], 'N/m', 'kN/m')}, "
            f"c_d {_fmt(s['drive_damping_N_s_per_m'], 'N*s/m')}",
            "force k_d (x_d - x) + c_d (x_d' - x')",
        ),
        ("mean force", _fmt(s["mean_force_N"], "N"), f"last of {s['periods']} periods"),
        ("median force", _fmt(s["median_force_N"], "N"), ""),
        ("peak-to-peak force", _fmt(s["peak_to_peak_N"], "N"), ""),
        ("force range", f"{_fmt(s['force_min_N'], 'N')} .. {_fmt(s['force_max_N'], 'N')}", ""),
        ("PCF Fmin/Fmax", _fmt(s["pcf_percent"], "%", digits=4), "over the last period"),
        (
            "slider range",
            f"{_fmt(s['deflection_min_m'], 'm', 'mm')} .. {_fmt(s['deflection_max_m'], 'm', 'mm')}",
            f"largest drive lag {_fmt(s['drive_lag_max_m'], 'm', 'mm')}",
        ),
        ("toggle crossings", str(s["toggle_crossings_per_period"]), "per period, through the crank's inertia"),
        _sticking_row(s),
        (
            "p-p without tau_AF",
            _fmt(s["peak_to_peak_without_axial_friction_N"], "N"),
            "same run, pin and slider friction only"
            if s["peak_to_peak_without_axial_friction_N"] is not None
            else "not repeated (see notes)",
        ),
        (
            "friction heat per cycle",
            _fmt(s["hysteresis_energy_per_cycle_J"], "J"),
            "work of the drive on the slider",
        ),
        ("actuator work per cycle", _fmt(s["actuator_work_per_cycle_J"], "J"), "includes the drive's damper"),
        (
            "periodicity",
            f"{s['periodicity_change_percent']:.3g} %",
            "change of the statistics from the period before",
        ),
        ("energy balance", f"{s['energy_balance_relative']:.2g}", "max |W - dE - D| / gross actuator work"),
        (
            "max pivot stress",
            _fmt(s["max_stress_Pa"], "Pa", "GPa", 4),
            f"safety factor {_fmt(s['safety_factor'], digits=3)}" + _yields(s["safety_factor"], "; "),
        ),
        *_beam_check_rows(s),
        (
            "numerics",
            f"rtol {s['rtol']:.2g}, max step {_fmt(s['max_step_s'], 's', 'ms', 3)}, "
            f"{s['samples_per_period']} samples/period, v_s {s['sign_smoothing_rad_per_s']:.2g} rad/s",
            "",
        ),
        _cutoff_row(s),
    ]


def _sweep(args) -> int:
    from springdyn.cfcs.model import CFCS

    model = CFCS(_load(args.config, args.model))
    omegas = parse_range(args.omega, "rad/s", "--omega", bare_unit="rad/s")
    if np.any(omegas <= 0):
        raise InputError(f"--omega = {args.omega!r}: every omega must be positive")
    with as_options(**_OPTIONS):
        res = model.sweep(
            omegas, args.amplitude, args.offset, samples_per_cycle=args.samples, quiet=args.quiet or args.json
        )
    if emit(res, args, json_data={**res.summary, **res.columns()}):
        return 0
    st = res.stats
    extra = [k for k in ("peak_to_peak_at_half_offset_N", "peak_to_peak_at_double_offset_N") if k in st]
    rows = [
        (
            f"{w:.4g}",
            f"{st['mean_force_N'][i]:.4f}",
            f"{st['median_force_N'][i]:.4f}",
            f"{st['peak_to_peak_N'][i]:.4f}",
            *(f"{st[k][i]:.4f}" for k in extra),
            f"{st['pcf_percent'][i]:.2f}",
            f"{st['pcf_no_dissipation_percent'][i]:.2f}",
        )
        for i, w in enumerate(res.omega)
    ]
    heads = {"peak_to_peak_at_half_offset_N": "p2p_half_offset_N", "peak_to_peak_at_double_offset_N": "p2p_2x_offset_N"}
    print_table(
        rows,
        headers=(
            "omega_rad_per_s",
            "mean_N",
            "median_N",
            "p2p_N",
            *(heads[k] for k in extra),
            "pcf_%",
            "pcf_no_diss_%",
        ),
    )
    print(f"toggle cut-off {np.degrees(res.summary['toggle_cutoff_rad']):.4g} deg")
    if res.summary["toggle_dominated"]:
        print("TOGGLE-DOMINATED: " + res.summary["notes"][0])
    print_notes(res.summary, skip=("toggle-dominated at",))
    return 0


def _forward(args) -> int:
    from springdyn.cfcs.model import CFCS
    from springdyn.cfcs.motion import SinusoidMotion, amplitude_to_si

    model = CFCS(_load(args.config, args.model))
    t_end = _q(args.t_end, "s", "--t-end")
    kw = dict(
        x0=_q(args.x0, "m", "--x0"),
        v0=_q(args.v0, "m/s", "--v0"),
        n=args.points,
        sign_smoothing=_q(args.sign_smoothing, "rad/s", "--sign-smoothing"),
    )
    if args.force is not None:
        if args.base_stiffness is not None:
            raise InputError("give either --force or --base-stiffness (with --base-omega), not both")
        res = model.forward(t_end, force=_q(args.force, "N", "--force"), **kw)
    else:
        if args.base_stiffness is None or args.base_omega is None:
            raise InputError("forward needs --force, or --base-stiffness with --base-omega (and --base-amplitude)")
        base = SinusoidMotion(
            _q(args.base_omega, "rad/s", "--base-omega"),
            amplitude_to_si(args.base_amplitude, model.params.extended_length, "--base-amplitude"),
            _q(args.base_offset, "m", "--base-offset"),
        )
        res = model.forward(
            t_end,
            base_motion=lambda t: base(t)[:2],
            base_stiffness=_q(args.base_stiffness, "N/m", "--base-stiffness"),
            base_damping=_q(args.base_damping, "N*s/m", "--base-damping"),
            **kw,
        )
    return _show(args, res, _forward_rows)


def _forward_rows(s) -> list:
    return [
        (
            "deflection range",
            f"{_fmt(s['min_deflection_m'], 'm', 'mm')} .. {_fmt(s['max_deflection_m'], 'm', 'mm')}",
            "",
        ),
        ("toggle crossings", str(s["toggle_crossings"]), ""),
        ("max pivot stress", _fmt(s["max_stress_Pa"], "Pa", "GPa", 4), ""),
        ("sign smoothing", _fmt(s["sign_smoothing_rad_per_s"], "rad/s"), "tanh(theta2'/v_s)"),
        *_beam_check_rows(s),
        _cutoff_row(s),
    ]


#: design() argument -> CLI option, for the suggestions printed by the CLI.
_DESIGN_OPTIONS = dict(
    max_width="--max-width",
    pivot_length_ratio="--pivot-length-ratio",
    safety_factor="--safety-factor",
    min_pcf="--min-pcf",
)


def _cli_names(message: str) -> str:
    """The library's argument names in a design message, as the CLI options that set them."""
    import re

    for key, opt in _DESIGN_OPTIONS.items():
        message = re.sub(rf"\b{key}\b", opt, message)
    message = message.replace("allowable_stress / --safety-factor", "--allowable-stress / --safety-factor")
    message = message.replace("r2 + r3 >=", "--length >=")
    return message


def _design(args) -> int:
    from springdyn.cfcs.design import design

    with as_options(**_OPTIONS):
        res = design(
            _q(args.force, "N", "--force"),
            _q(args.stroke, "m", "--stroke"),
            _q(args.material_modulus, "Pa", "--material-modulus"),
            _q(args.allowable_stress, "Pa", "--allowable-stress"),
            stroke_fraction=_q(args.stroke_fraction, "", "--stroke-fraction"),
            total_length=_q(args.length, "m", "--length") if args.length else None,
            pivot_length_ratio=_q(args.pivot_length_ratio, "", "--pivot-length-ratio"),
            max_width=_q(args.max_width, "m", "--max-width") if args.max_width else None,
            safety_factor=_q(args.safety_factor, "", "--safety-factor"),
            min_pcf=_q(args.min_pcf, "", "--min-pcf"),
            thickness_tolerance=_q(args.thickness_tolerance, "", "--thickness-tolerance"),
            preload=_q(args.preload, "m", "--preload"),
            flexure_model=args.model,
            plate_bending=None if args.plate_bending == "auto" else args.plate_bending == "true",
            poisson_ratio=_q(args.poisson_ratio, "", "--poisson-ratio"),
        )
    if args.toml:
        res.to_toml(args.toml)
    s = res.summary
    if not emit(res, args):
        print_table(
            [
                ("r2 + r3", _fmt(s["total_length_m"], "m", "mm"), f"stroke fraction {s['stroke_fraction']:.3g}"),
                ("r2 / r3", f"{s['ratio']:.4f}", "flattest force over the stroke"),
                ("crank r2", _fmt(s["crank_length_m"], "m", "mm"), ""),
                ("coupler r3", _fmt(s["coupler_length_m"], "m", "mm"), ""),
                ("K3", _fmt(s["torsional_stiffness_N_m_per_rad"], "N*m/rad"), ""),
                (
                    "pivot b x h x l",
                    f"{s['pivot_width_m'] * 1e3:.4g} x {s['pivot_thickness_m'] * 1e3:.4g} x "
                    f"{s['pivot_length_m'] * 1e3:.4g} mm",
                    "",
                ),
                ("force range", f"{s['force_min_N']:.4g} .. {s['force_max_N']:.4g} N", ""),
                ("PCF", _fmt(s["pcf_percent"], "%", digits=4), f"energy-based {s['pcf_energy_percent']:.4g} %"),
                (
                    "max pivot stress",
                    _fmt(s["max_stress_Pa"], "Pa", "GPa", 4),
                    f"safety factor {s['safety_factor']:.3g} (target {s['safety_factor_target']:.3g}), "
                    + ("largest curvature of the elastica" if s["flexure_model"] == "beam" else "PRBM"),
                ),
                ("flexure model", s["flexure_model"], "plate E/(1 - nu^2)" if s["plate_bending"] else "beam modulus E"),
                ("working range", f"{s['working_start_m'] * 1e3:.4g} .. {s['working_end_m'] * 1e3:.4g} mm", ""),
                (
                    f"force at h +-{100 * s['thickness_tolerance']:.3g} %",
                    f"{s['force_min_at_thickness_tolerance_N']:.4g} .. {s['force_max_at_thickness_tolerance_N']:.4g} N",
                    f"stress at +tolerance {s['max_stress_at_thickness_tolerance_Pa'] / 1e9:.4g} GPa",
                ),
                (
                    "strip buckling",
                    f"{s['buckling_load_N']:.4g} N",
                    f"{s['buckling_safety_factor']:.3g} x the largest axial load {s['axial_load_max_N']:.4g} N",
                ),
                ("binding check", s["binding_constraint"] or "none", ""),
            ],
            headers=("quantity", "value", "note"),
        )
        print(("FEASIBLE: " if res.feasible else "NO FEASIBLE DESIGN: ") + _cli_names(s["message"]))
    return 0 if res.feasible else 1
