"""``springdyn lsd ...`` commands (thin layer over :mod:`springdyn.lsd`)."""

from __future__ import annotations

import numpy as np

from springdyn.app.cli.common import (
    add_output_options,
    announce_written,
    close_figure,
    emit,
    parse_range,
    print_json,
    print_notes,
    print_table,
    quantity,
)
from springdyn.core.errors import InputError
from springdyn.core.io import read_csv_columns
from springdyn.lsd.parameters import LSDParameters

__all__ = ["register"]


def register(sub) -> None:
    lsd = sub.add_parser("lsd", help="leaf spring dampers: coefficients, rig simulation, identification")
    lsub = lsd.add_subparsers(dest="lsd_command", metavar="COMMAND", required=True)

    p = lsub.add_parser("coefficients", help="stiffness and damping coefficients vs shaft speed")
    p.add_argument("config", metavar="CFG.toml", help="damper definition ([lsd] table); or A, B, C for Table 4.1")
    p.add_argument("--rpm", default="500:3000:500", help="speeds, START:STOP:STEP or a list (default 500:3000:500)")
    p.add_argument("--amplitude", default="50um", help="vibration amplitude (default 50um; bare number: m)")
    p.add_argument(
        "--motion",
        choices=("linear", "circular"),
        default="linear",
        help="motion for the O-ring Coulomb equivalent (default linear, as Eq. (2.22))",
    )
    p.add_argument(
        "--film",
        action="store_true",
        help="oil from the film network with inertia and cavitation (describing function at --amplitude)",
    )
    add_output_options(p)
    p.set_defaults(func=cmd_coefficients)

    p = lsub.add_parser("film", help="where fluid inertia and cavitation change the oil force (speed x orbit map)")
    p.add_argument("config", metavar="CFG.toml", help="damper definition; or A, B, C")
    p.add_argument(
        "--rpm",
        default="500,1000,2000,3000,4000,6000,8000,10000,12000,14100",
        help="speeds (whirl frequencies), START:STOP:STEP or a list (default 500 to 14100 rpm, 10 speeds)",
    )
    p.add_argument(
        "--amplitude",
        default="5um,10um,20um,30um,50um,70um,100um",
        help="orbit radii, a list or START:STOP:STEP (default 5um to 100um, 7 orbits)",
    )
    p.add_argument("--steps", type=int, default=512, help="time steps per period of the film simulation (default 512)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    add_output_options(p)
    p.set_defaults(func=cmd_film)

    p = lsub.add_parser(
        "rotor",
        help="unbalance response of the example ROSS rotor on two dampers, at the amplitude the damper reaches",
    )
    p.add_argument("config", metavar="CFG.toml", help="damper definition; or A, B, C")
    p.add_argument("--unbalance", required=True, help="unbalance at the disk, e.g. 0.15g*m (bare number: kg m)")
    p.add_argument("--rpm", default="1000:4000:100", help="speeds, START:STOP:STEP or a list (default 1000:4000:100)")
    p.add_argument(
        "--amplitude",
        default="consistent",
        help="'consistent' (default: each speed's coefficients at the orbit the damper reaches) or one "
        "amplitude at every speed, e.g. 50um (to_ross's default)",
    )
    p.add_argument("--rtol", type=float, default=0.01, help="tolerance of |orbit - A| / A (default 0.01)")
    p.add_argument(
        "--motion", choices=("circular", "linear"), default="circular", help="motion of the O-ring equivalent"
    )
    add_output_options(p, csv=False, plot=False)
    p.set_defaults(func=cmd_rotor)

    p = lsub.add_parser("rig", help="simulate the thesis' test rig (eccentric shaft or shakes)")
    p.add_argument("config", metavar="CFG.toml", help="damper definition; or A, B, C")
    p.add_argument("--rpm", help="shaft speed in rpm (one orbit per revolution)")
    p.add_argument("--eccentricity", help="orbit radius or shake amplitude, e.g. 50um")
    p.add_argument(
        "--path", metavar="PATH.csv", help="move the ring along a measured path instead (CSV with time_s, x_m, y_m)"
    )
    p.add_argument("--excitation", choices=("orbit", "backward-orbit", "x", "y"), default="orbit")
    p.add_argument("--revolutions", type=float, default=20.0, help="number of revolutions (default 20)")
    p.add_argument("--sample-rate", default="20kHz", help="sampling rate (default 20kHz; bare number: Hz)")
    p.add_argument("--noise", default="0N", help="force sensor noise, standard deviation (default 0N)")
    p.add_argument("--displacement-noise", default="0um", help="displacement sensor noise (default 0um)")
    p.add_argument("--seed", type=int, default=None, help="seed of the noise generator")
    p.add_argument(
        "--film", action="store_true", help="oil from the film network in time (passage inertia, cavitation)"
    )
    p.add_argument("--csv", metavar="OUT.csv", required=True, help="write time_s, x_m, y_m, fx_N, fy_N")
    p.add_argument("--plot", metavar="OUT.png", help="hysteresis loops as PNG")
    p.set_defaults(func=cmd_rig)

    p = lsub.add_parser("identify", help="identify K and C from rig records (CSV or TDMS)")
    p.add_argument(
        "data", metavar="DATA.csv", nargs="+", help="record(s) time_s, x_m, y_m, fx_N, fy_N; several = several speeds"
    )
    p.add_argument("--second", metavar="DATA2.csv", nargs="+", help="second, independent excitation(s), same order")
    p.add_argument("--rpm", help="shaft speed(s) in rpm, one per record (default: found in the data)")
    p.add_argument("--mass", default="0kg", help="moving mass whose inertia is removed (default 0kg)")
    p.add_argument("--model", metavar="CFG.toml", help="also draw this damper's model curves in --plot")
    p.add_argument("--amplitude", default="50um", help="amplitude for the --model curves (default 50um)")
    add_output_options(p)
    p.set_defaults(func=cmd_identify)

    p = lsub.add_parser("calibrate", help="fit model parameters (default leakage_factor) to rig records")
    p.add_argument("config", metavar="MODEL.toml", help="damper definition to calibrate; or A, B, C")
    p.add_argument("data", metavar="RECORDS.csv", nargs="+", help="rig record(s), one per speed (CSV or TDMS)")
    p.add_argument("--second", metavar="RECORDS2.csv", nargs="+", help="second, independent excitation(s), same order")
    p.add_argument(
        "--fit",
        default="leakage_factor",
        help="comma-separated [lsd] keys to fit (default leakage_factor), e.g. leakage_factor,leaf_friction",
    )
    p.add_argument("--rpm", help="shaft speed(s) in rpm, one per record (default: found in the data)")
    p.add_argument("--mass", help="moving mass whose inertia is removed (default: the model's ring_mass)")
    p.add_argument("--confidence", default="95%", help="confidence level of the intervals (default 95%%)")
    p.add_argument("--toml", metavar="OUT.toml", help="write the calibrated definition")
    add_output_options(p, plot=False)
    p.set_defaults(func=cmd_calibrate)


def _is_example(text: str) -> bool:
    return text.upper() in ("A", "B", "C", "TYPE_A", "TYPE_B", "TYPE_C")


def _params(text: str) -> LSDParameters:
    if _is_example(text):
        return LSDParameters.example(text)
    return LSDParameters.from_toml(text)


def _definition_text(text: str) -> str:
    """The TOML text of a definition (a file, or a built-in example)."""
    from importlib import resources
    from pathlib import Path

    from springdyn.lsd.parameters import EXAMPLES

    if _is_example(text):
        return (resources.files("springdyn.data") / EXAMPLES[LSDParameters._example_key(text)]).read_text()
    return Path(text).read_text(encoding="utf-8")


def cmd_coefficients(args) -> int:
    from springdyn.lsd.model import LSDModel

    model = LSDModel(_params(args.config))
    rpm = parse_range(args.rpm, "rpm", "--rpm")
    amplitude = quantity(args.amplitude, "m", "--amplitude")
    if args.film:
        res = model.equivalent_coefficients(rpm, amplitude=amplitude, motion=args.motion, film=True)
    else:
        res = model.coefficients(rpm, amplitude=amplitude, motion=args.motion)
    if emit(res, args):
        return 0
    print(
        f"{model.params.name}: k_s = {model.pack_stiffness / 1e3:.5g} N/mm per pack, "
        f"load ratios {np.array2string(model.load_ratios, precision=4)}, amplitude {amplitude * 1e6:.4g} um"
    )
    # round-off (1e-16 of the direct terms) shown as 0 in the table; JSON/CSV keep the numbers
    K = np.where(np.abs(res.K) < 1e-12 * np.abs(res.K).max(), 0.0, res.K) / 1e3
    C = np.where(np.abs(res.C) < 1e-12 * np.abs(res.C).max(), 0.0, res.C)
    idx = ((0, 0), (0, 1), (1, 0), (1, 1))
    re_s = np.broadcast_to(res.film["squeeze_reynolds"], res.rpm.shape)
    rows = [
        (
            f"{r:g}",
            *(f"{K[i, a, b]:.5g}" for a, b in idx),
            *(f"{C[i, a, b]:.5g}" for a, b in idx),
            f"{res.M[i, 0, 0]:.4g}",
            f"{res.M[i, 1, 1]:.4g}",
            f"{re_s[i]:.3g}",
        )
        for i, r in enumerate(res.rpm)
    ]
    print_table(
        rows,
        headers=(
            "rpm",
            "Kxx N/mm",
            "Kxy N/mm",
            "Kyx N/mm",
            "Kyy N/mm",
            "Cxx Ns/m",
            "Cxy Ns/m",
            "Cyx Ns/m",
            "Cyy Ns/m",
            "Mxx kg",
            "Myy kg",
            "Re_s",
        ),
    )
    print_notes(res.summary)
    return 0


def cmd_film(args) -> int:
    from springdyn.core.progress import progress
    from springdyn.lsd.film import film_effect_map
    from springdyn.lsd.model import LSDModel

    model = LSDModel(_params(args.config))
    rpm = parse_range(args.rpm, "rpm", "--rpm")
    amps = parse_range(args.amplitude, "m", "--amplitude")
    if args.steps < 32:
        raise InputError(f"--steps = {args.steps} must be at least 32")
    res = film_effect_map(
        model,
        rpm,
        amps,
        steps=args.steps,
        progress=lambda it: progress(it, total=rpm.size, desc="film map", quiet=args.quiet),
    )
    if emit(res, args, json_data=_film_map_json(res)):
        return 0
    p = model.params
    print(
        f"{p.name}: oil force changed by fluid inertia and by cavitation (forward orbits; supply "
        f"{res.supply_pressure / 1e5:.4g} bar abs, cavitation {res.cavitation_pressure / 1e5:.4g} bar abs); "
        "percent of the oil force"
    )
    rows = [
        (
            f"{r:g}",
            f"{res.squeeze_reynolds[i]:.3g}",
            f"{100 * res.inertia_change[i]:.3g}",
            *(f"{_percent(res.cavitation_change[i, j])}" for j in range(amps.size)),
        )
        for i, r in enumerate(res.rpm)
    ]
    print_table(rows, headers=("rpm", "Re_s", "inertia %", *(f"cav {a * 1e6:.3g}um %" for a in amps)))
    onset = res.inertia_onset_rpm()
    print(
        "inertia changes the oil force by more than 10 % "
        + (f"from {onset:.0f} rpm (omega tau = 0.1)" if onset is not None else "nowhere in the mapped speeds")
    )
    for a, r, r0 in zip(amps, res.cavitation_change_onset_rpm(), res.cavitation_start_rpm()):
        where = f"from {r:g} rpm" if np.isfinite(r) else "nowhere in the mapped speeds"
        start = f"from {r0:g} rpm" if np.isfinite(r0) else "nowhere in the mapped speeds"
        print(f"at {a * 1e6:.3g} um the film cavitates {start}; cavitation changes the force by more than 10 % {where}")
    _print_cavitation_sensitivity(res)
    return 0


def _print_cavitation_sensitivity(res) -> None:
    """The cavitation figures for air-saturated oil and at the vapour limit beside the map's (issue 40)."""
    sens = res.cavitation_sensitivity()
    top = res.rpm.max()
    print(
        f"cavitation pressure: the film stays whole at {top:g} rpm on orbits up to "
        f"{res.whole_film_orbit()[-1] * 1e6:.3g} um with p_cav {res.cavitation_pressure / 1e5:.3g} bar abs; "
        f"{sens['vapour_limit']['whole_film_orbit_at_rpm_max_m'] * 1e6:.3g} um at the vapour limit (0 bar, "
        f"degassed oil), {sens['aerated']['whole_film_orbit_at_rpm_max_m'] * 1e6:.3g} um with air-saturated oil "
        f"({sens['aerated']['cavitation_pressure_abs_Pa'] / 1e5:.3g} bar, gaseous cavitation: "
        f"{sens['whole_film_orbit_ratio']:.3g} times smaller)"
    )
    for a, r in zip(res.amplitude, sens["aerated"]["cavitation_start_rpm"]):
        where = f"from {r:g} rpm" if r is not None else "nowhere in the mapped speeds"
        print(f"  with air-saturated oil, at {a * 1e6:.3g} um the film cavitates {where}")


def _percent(change: float) -> str:
    """A relative change in percent; round-off (below 1e-6 %) shown as 0."""
    return "0" if abs(change) < 1e-8 else f"{100 * change:.3g}"


def _film_map_json(res) -> dict:
    d = {
        "rpm": res.rpm.tolist(),
        "amplitude_m": res.amplitude.tolist(),
        "squeeze_reynolds": res.squeeze_reynolds.tolist(),
        "inertia_change": res.inertia_change.tolist(),
        "cavitation_change": res.cavitation_change.tolist(),
        "total_change": res.total_change.tolist(),
        "pressure_amplitude_Pa": res.pressure_amplitude.tolist(),
        "min_pressure_Pa": res.min_pressure.tolist(),
        "inertia_onset_rpm": res.inertia_onset_rpm(),
        "cavitation_change_onset_rpm": [
            None if not np.isfinite(v) else float(v) for v in res.cavitation_change_onset_rpm()
        ],
        "cavitation_start_rpm": [None if not np.isfinite(v) else float(v) for v in res.cavitation_start_rpm()],
        "whole_film_orbit_m": res.whole_film_orbit().tolist(),
        "cavitation_sensitivity": res.cavitation_sensitivity(),
        "supply_pressure_abs_Pa": res.supply_pressure,
        "cavitation_pressure_abs_Pa": res.cavitation_pressure,
        "threshold": res.threshold,
    }
    return d


def cmd_rotor(args) -> int:
    from springdyn.core.errors import SolverError
    from springdyn.lsd.model import LSDModel
    from springdyn.lsd.rotordynamics import amplitude_consistent_response, example_rotor

    model = LSDModel(_params(args.config))
    rpm = parse_range(args.rpm, "rpm", "--rpm")
    unbalance = quantity(args.unbalance, "kg*m", "--unbalance")
    if not unbalance > 0:
        raise InputError(f"--unbalance = {args.unbalance!r} must be positive, e.g. 0.15g*m")
    consistent = args.amplitude.strip().lower() == "consistent"
    amplitude = "consistent" if consistent else quantity(args.amplitude, "m", "--amplitude")
    if not (np.isfinite(args.rtol) and 0 < args.rtol <= 0.5):
        raise InputError(f"--rtol = {args.rtol!r} must lie in (0, 0.5]")
    dampers = {0: model, 2: model}
    run = dict(rtol=args.rtol, motion=args.motion)
    res = amplitude_consistent_response(example_rotor, dampers, rpm, (1, unbalance, 0.0), amplitude=amplitude, **run)
    fixed = None
    if consistent:
        fixed = amplitude_consistent_response(example_rotor, dampers, rpm, (1, unbalance, 0.0), amplitude=50e-6, **run)
    disk = res.orbit_at(1)
    if args.json:
        data = res.to_dict()
        data["disk_orbit_m"] = disk.tolist()
        if fixed is not None:
            data["fixed_50um_disk_orbit_m"] = fixed.orbit_at(1).tolist()
        print_json(data)
        return 0
    what = "at the orbit each speed reaches" if consistent else f"at {amplitude * 1e6:.4g} um at every speed"
    print(
        f"{model.params.name} at nodes 0 and 2 of the example rotor ({res.rotor.m:.2f} kg), unbalance "
        f"{unbalance * 1e3:.4g} g m at the disk (node 1); damper coefficients {what} (rtol {args.rtol:g})"
    )
    rows = []
    for k, r in enumerate(res.rpm):
        if res.held[k]:
            status = "held"
        elif res.converged[k]:
            status = "ok"
        else:
            status = "off" if not consistent else "not converged"
        rows.append(
            (
                f"{r:g}",
                f"{res.amplitude[k, 0] * 1e6:.4g}",
                f"{res.orbit[k, 0] * 1e6:.4g}",
                f"{res.iterations[k]:d}",
                f"{res.residual[k]:.2e}",
                f"{disk[k] * 1e6:.4g}",
                status,
            )
        )
    print_table(rows, headers=("rpm", "amplitude used um", "damper orbit um", "iterations", "residual", "disk um", ""))
    try:
        peak_rpm, peak = res.peak(1)
    except SolverError as exc:
        print(f"disk peak: none ({exc})")
    else:
        k = int(np.flatnonzero(res.rpm == peak_rpm)[0])
        print(
            f"disk peak {peak * 1e6:.4g} um at {peak_rpm:g} rpm; damper amplitude {res.amplitude[k, 0] * 1e6:.4g} um, "
            f"orbit {res.orbit[k, 0] * 1e6:.4g} um (residual {res.residual[k]:.2e})"
        )
        if fixed is not None:
            f_rpm, f_peak = fixed.peak(1)
            print(
                f"with the coefficients at 50 um at every speed (to_ross's default): disk peak {f_peak * 1e6:.4g} um at "
                f"{f_rpm:g} rpm, {100 * (f_peak / peak - 1):+.1f} % against the consistent peak"
            )
    print_notes({"notes": res.notes})
    return 0


def cmd_rig(args) -> int:
    from springdyn.lsd.model import LSDModel
    from springdyn.lsd.rig import circular_orbit, linear_shake, simulate_rig

    model = LSDModel(_params(args.config))
    noise = quantity(args.noise, "N", "--noise")
    dnoise = quantity(args.displacement_noise, "m", "--displacement-noise")
    if args.path:
        tr = _measured_path(args.path, None if args.rpm is None else quantity(args.rpm, "rpm", "--rpm"))
        what = f"measured path {args.path}"
    else:
        if args.rpm is None or args.eccentricity is None:
            raise InputError("springdyn lsd rig needs --rpm and --eccentricity (or --path PATH.csv)")
        rpm = quantity(args.rpm, "rpm", "--rpm")
        ecc = quantity(args.eccentricity, "m", "--eccentricity")
        fs = quantity(args.sample_rate, "Hz", "--sample-rate")
        if args.excitation in ("orbit", "backward-orbit"):
            tr = circular_orbit(rpm, ecc, args.revolutions, fs, direction=1 if args.excitation == "orbit" else -1)
        else:
            tr = linear_shake(rpm, ecc, args.excitation, args.revolutions, fs)
        what = f"{args.excitation} at {rpm:g} rpm, {ecc * 1e6:.4g} um"
    rec = simulate_rig(model, tr, force_noise=noise, displacement_noise=dnoise, seed=args.seed, film=args.film)
    rec.to_csv(args.csv)
    if args.plot:
        close_figure(rec.plot(args.plot))
    print(
        f"{model.params.name}: {what}, {tr.time.size} samples -> {args.csv}; "
        f"peak |Fx| {np.max(np.abs(rec.fx)):.4g} N, peak |Fy| {np.max(np.abs(rec.fy)):.4g} N"
    )
    announce_written([args.csv, args.plot], args)
    if rec.film is not None:
        print(
            f"film: lowest chamber pressure {rec.film.min_pressure / 1e5:.4g} bar absolute "
            f"(cavitation at {model.params.cavitation_pressure / 1e5:.4g} bar), "
            f"largest void {rec.film.voids.max() * 1e9:.4g} mm^3"
        )
    print_notes(rec.summary)
    return 0


def _measured_path(path, rpm):
    """A measured ring path from a CSV with time_s, x_m, y_m (checked like a rig record)."""
    from springdyn.lsd.identify import RigData
    from springdyn.lsd.rig import trajectory_from_samples

    cols = read_csv_columns(path)
    for c in ("time_s", "x_m", "y_m"):
        if c not in cols:
            raise InputError(f"{path}: missing column {c!r} (found: {', '.join(cols)}; need time_s, x_m, y_m)")
    n = cols["time_s"].size
    zeros = np.zeros(n)
    data = RigData(cols["time_s"], cols["x_m"], cols["y_m"], zeros, zeros, source=str(path))
    return trajectory_from_samples(data.time, data.x, data.y, rpm=float("nan") if rpm is None else rpm)


def cmd_identify(args) -> int:
    from springdyn.lsd.identify import identify_series, read_rig_data
    from springdyn.lsd.model import LSDModel

    records = [read_rig_data(p) for p in args.data]
    seconds = [read_rig_data(p) for p in args.second] if args.second else None
    rpms = _speeds(args.rpm, records)
    mass = quantity(args.mass, "kg", "--mass")
    series = identify_series(records, seconds, mass=mass, rpms=rpms)
    if args.csv:
        series.to_csv(args.csv)
    if args.plot:
        model = None
        if args.model:
            model = LSDModel(_params(args.model)).coefficients(series.rpm, quantity(args.amplitude, "m", "--amplitude"))
        close_figure(series.plot(args.plot, model=model))
    announce_written([args.csv, args.plot], args)
    dicts = [it.to_dict() for it in series.items]
    if args.json:
        print_json(dicts[0] if len(dicts) == 1 else dicts)
        return 0
    for it, d in zip(series.items, dicts):
        print(
            f"{', '.join(it.sources)}: {it.rpm:.6g} rpm ({it.frequency:.6g} Hz), {it.cycles} whole periods, "
            f"{it.mode}, mass {it.mass:g} kg"
        )
        rows = []
        coeffs = {k: v for k, v in d.items() if k.endswith(("_N_per_m", "_Ns_per_m"))}
        for key, value in coeffs.items():
            unc = d.get(f"{key}_uncertainty")
            ci = d.get(f"{key}_ci")
            # one unit per quantity across the lsd commands: stiffness in N/mm, damping in Ns/m
            stiff = key.endswith("_N_per_m")
            scale, unit = (1e-3, "N/mm") if stiff else (1.0, "Ns/m")
            same = [abs(v) for k, v in coeffs.items() if k.endswith("_N_per_m") == stiff]
            if abs(value) < 1e-9 * max(same):  # round-off of the solver, not data
                value = 0.0
            rows.append(
                (
                    key.split("_")[0],
                    f"{value * scale:.6g}",
                    "nan" if unc is None else f"{unc * scale:.3g}",
                    "-" if ci is None else f"+-{(ci[1] - ci[0]) / 2 * scale:.3g}",
                    unit,
                )
            )
        print_table(rows, headers=("coefficient", "value", "std. error", "95 % CI (Student t)", "unit"))
        if it.caveat:
            print(f"note: {it.caveat}")
        print_notes(d, skip=(it.caveat,) if it.caveat else ())
    return 0


def _speeds(text, records):
    """The ``--rpm`` speeds of the records (one per record), or None when not given."""
    if not text:
        return None
    rpms = list(parse_range(text, "rpm", "--rpm"))
    if len(rpms) == 1 and len(records) > 1:
        raise InputError(f"--rpm gives one speed for {len(records)} records; give one per record or none")
    return rpms


def cmd_calibrate(args) -> int:
    from springdyn.core.io import atomic_open, write_csv
    from springdyn.lsd.calibrate import calibrate
    from springdyn.lsd.identify import read_rig_data

    params = _params(args.config)
    records = [read_rig_data(p) for p in args.data]
    seconds = [read_rig_data(p) for p in args.second] if args.second else None
    rpms = _speeds(args.rpm, records)
    mass = None if args.mass is None else quantity(args.mass, "kg", "--mass")
    confidence = quantity(args.confidence, "", "--confidence")
    fit = [s.strip() for s in args.fit.split(",") if s.strip()]
    try:
        cal = calibrate(params, records, seconds, fit=fit, mass=mass, rpms=rpms, confidence=confidence)
    except InputError as exc:
        text = str(exc)
        for key, option in (("fit", "--fit"), ("confidence", "--confidence"), ("mass", "--mass")):
            if text.startswith(f"{key} ") or text.startswith(f"{key}:"):
                text = option + text[len(key) :]
        raise InputError(text) from None
    if args.toml:
        with atomic_open(args.toml) as fh:
            fh.write(cal.toml_text(_definition_text(args.config)))
    if args.csv:
        cols = {k: np.array([row[k] for row in cal.residuals]) for k in cal.residuals[0]}
        write_csv(args.csv, cols)
    announce_written([args.toml, args.csv], args)
    if args.json:
        print_json(cal.to_dict())
        return 0
    print(
        f"{params.name}: calibrated on {len(records)} speed(s) "
        f"({'two excitations' if seconds else 'one excitation'} each), {cal.dof} degrees of freedom"
    )
    rows = []
    for name, value in cal.values.items():
        ci = cal.intervals[name]
        rows.append((name, f"{value:.6g}", "-" if ci is None else f"{ci[0]:.6g} to {ci[1]:.6g}"))
    print_table(rows, headers=("parameter", "value", f"{100 * cal.confidence:g} % interval"))
    rows = []
    for row in cal.residuals:
        for k in cal.coefficients:
            unit = "N_per_m" if k[0] == "k" else "Ns_per_m"
            rows.append(
                (
                    f"{row['rpm']:.6g}",
                    k,
                    f"{row[f'{k}_identified_{unit}']:.6g}",
                    f"{row[f'{k}_model_{unit}']:.6g}",
                    f"{100 * row[f'{k}_relative']:+.2f} %",
                )
            )
    print_table(rows, headers=("rpm", "coefficient", "identified", "calibrated model", "difference"))
    for note in cal.notes:
        print(note if note.startswith("CAVEAT") else f"note: {note}")
    if args.toml:
        print(f"calibrated definition -> {args.toml}")
    return 0
