"""``springdyn valve synthesize``, ``tolerance`` and ``life``: valve springs from requirements,
proven across tolerances, relaxed and loaded by a spectrum (thin layer over
:mod:`springdyn.valve.design.synthesis`, :mod:`springdyn.valve.design.tolerances` and :mod:`springdyn.valve.design.life`)."""

from __future__ import annotations

from springdyn.app.cli.common import (
    add_output_options,
    announce_written,
    close_figure,
    print_json,
    print_notes,
    print_table,
)
from springdyn.core.errors import InputError

__all__ = ["register", "register_tolerance", "register_life", "cmd_synthesize", "cmd_tolerance", "cmd_life"]


def register(vsub) -> None:
    """Add ``synthesize`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "synthesize",
        help="valve springs from requirements: load points, space, material, Goodman, surge and float speed "
        "([requirements]); the best one-step and two-step springs as ready spring files",
    )
    p.add_argument("requirements", metavar="REQUIREMENTS.toml", help="file with a [requirements] table")
    p.add_argument("--out", dest="out_dir", required=True, metavar="DIR", help="folder for the candidate spring files")
    p.add_argument(
        "--per-kind", type=int, default=3, metavar="N", help="candidates of each kind (one-step, two-step; default 3)"
    )
    add_output_options(p)
    p.set_defaults(func=cmd_synthesize)


def cmd_synthesize(args) -> int:
    """``springdyn valve synthesize``: search, check, rank, write."""
    from springdyn.core.progress import progress
    from springdyn.valve.design.synthesis import read_requirements, synthesize, write_candidates

    if not 1 <= args.per_kind <= 20:
        raise InputError(f"--per-kind = {args.per_kind} must be from 1 to 20")
    req, base = read_requirements(args.requirements)

    def bar(items, desc):
        return progress(items, desc=desc, quiet=args.quiet)

    res = synthesize(req, per_kind=args.per_kind, base_dir=base, progress=bar)
    written = write_candidates(res, args.out_dir, str(args.requirements))
    written.append(res.to_csv(args.csv if args.csv else f"{args.out_dir}/candidates.csv"))
    if args.plot:
        close_figure(res.plot(args.plot))
        written.append(args.plot)
    announce_written(written, args)
    if args.json:
        print_json(dict(res.summary, candidates_table=res.rows, written=[str(p) for p in written]))
        return 0
    print(
        f"{len(res.rows)} candidates of {res.searched} searched for {args.requirements}: "
        f"{req.installed_force:g} N at {req.installed_length * 1e3:g} mm, {req.open_force:g} N at "
        f"{req.open_length * 1e3:g} mm (lift {req.lift * 1e3:g} mm), material {req.material}"
    )
    names = [k for k in res.rows[0] if k.startswith("margin_")]
    rows = []
    for r in res.rows:
        rows.append(
            (
                r["rank"],
                r["kind"] + ("" if r["low_pitch_coils"] == 0 else f" ({r['low_pitch_coils']:g} low)"),
                f"{r['wire_diameter_m'] * 1e3:.2f}",
                f"{r['mean_diameter_m'] * 1e3:.2f}",
                f"{r['high_pitch_coils']:.2f}",
                f"{r['free_length_m'] * 1e3:.2f}",
                f"{r['mass_kg'] * 1e3:.1f}",
                f"{r['surge_frequency_Hz']:.0f}",
                f"{r['goodman_safety']:.2f}",
                "-" if r.get("float_cam_rpm", "-") in ("-", None) else f"{r['float_cam_rpm']:.0f}",
                f"{r['smallest_margin']:+.1%} ({min(names, key=lambda k: r[k])[len('margin_') :]})",
                "yes" if r["meets_all"] else "NO",
            )
        )
    print_table(
        rows,
        headers=(
            "rank",
            "kind",
            "wire [mm]",
            "mean D [mm]",
            "N2",
            "free L [mm]",
            "mass [g]",
            "f1 [Hz]",
            "Goodman",
            "float [rpm]",
            "smallest margin",
            "meets all",
        ),
    )
    print(f"the candidates' spring files and candidates.csv are in {args.out_dir}")
    print_notes(res.summary)
    return 0


def register_tolerance(vsub, add_model_option, cam_speeds) -> None:
    """Add ``tolerance`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "tolerance",
        help="a spring across its manufacturing tolerances ([tolerances], [criteria]): Monte Carlo or Sobol "
        "variants swept over the speeds (or, with --float-only, each variant's float speed searched from the "
        "nominal's); variants.nc, percentiles, failing shares, histograms (resumable)",
    )
    p.add_argument("spring", metavar="SPRING.toml", help="file with a [spring] table")
    p.add_argument("--cam", required=True, metavar="CAM.toml", help="file with a [cam] table")
    p.add_argument("--tolerances", required=True, metavar="TOL.toml", help="file with [tolerances] (and [criteria])")
    p.add_argument("--valve-train", metavar="VT.toml", help="file with a [valve_train] table (float speed, lash)")
    p.add_argument("--samples", required=True, metavar="N", help="variants (a power of 2 for Sobol points)")
    p.add_argument(
        "--seed", default="0", metavar="S", help="seed of the sampling (default 0): the same seed, the same variants"
    )
    p.add_argument(
        "--method", choices=("sobol", "monte-carlo"), default="sobol", help="scrambled Sobol (default) or Monte Carlo"
    )
    p.add_argument("--cam-rpm", required=True, metavar="START:STOP:STEP", help="cam speeds of each variant's sweep")
    p.add_argument("--out", dest="out_dir", required=True, metavar="DIR", help="folder: variants.nc, chunks/ (resumes)")
    p.add_argument(
        "--float-only",
        action="store_true",
        help="a float-speed study: each variant's statics and float speed, searched from the nominal's (4-5 speeds "
        "a variant, not a sweep; Goodman, peak force and clash are not computed)",
    )
    p.add_argument(
        "--resolution", default="5", metavar="RPM", help="final bracket of each float speed in cam rpm (default 5)"
    )
    p.add_argument("--workers", metavar="N", help="local threads the chunks run on (default: 2, both cores)")
    p.add_argument(
        "--scheduler", metavar="ADDRESS", help="run the chunks on a Dask scheduler, e.g. tcp://127.0.0.1:8786"
    )
    p.set_defaults(engine_rpm=None)
    add_model_option(p)
    add_output_options(p)
    p.set_defaults(func=cmd_tolerance, cam_speeds=cam_speeds)


def cmd_tolerance(args) -> int:
    """``springdyn valve tolerance``: sample, run in chunks, summarise."""
    from pathlib import Path

    from springdyn.app.cli.common import as_options, quantity
    from springdyn.core.progress import progress
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.design.tolerances import FIGURES, OUTPUTS, read_tolerances, tolerance_study
    from springdyn.valve.spring.definition import ValveSpring
    from springdyn.valve.train.definition import ValveTrain

    count = quantity(args.samples, "", "--samples")
    if count != int(count) or not 1 <= count <= 10_000_000:
        raise InputError(f"--samples = {args.samples!r} must be a whole number from 1 to 10000000")
    seed = quantity(args.seed, "", "--seed")
    if seed != int(seed) or seed < 0:
        raise InputError(f"--seed = {args.seed!r} must be a whole number, 0 or more")
    spring = ValveSpring.from_toml(args.spring).with_model(args.model)
    cam = Cam.from_toml(args.cam)
    vt = ValveTrain.from_toml(args.valve_train) if args.valve_train else None
    tols, criteria = read_tolerances(args.tolerances)
    if "lash" in tols and vt is None:
        raise InputError("[tolerances] lash is the valve train's: give --valve-train")
    speeds = args.cam_speeds(args, ranged=True)
    if args.float_only and vt is None:
        raise InputError("--float-only needs --valve-train: the spring alone does not float")
    resolution = quantity(args.resolution, "rpm", "--resolution", bare_unit="rpm")
    if not resolution > 0:
        raise InputError(f"--resolution = {args.resolution!r} must be a positive speed (cam rpm)")
    workers = None
    if args.workers is not None:
        workers = quantity(args.workers, "", "--workers")
        if workers != int(workers) or workers < 1:
            raise InputError(f"--workers = {args.workers!r} must be a whole number of at least 1")
        workers = int(workers)
    client = None
    if args.scheduler:
        from springdyn.valve.run.sweeps import connect

        with as_options(scheduler="--scheduler"):
            client = connect(args.scheduler)

    def bar(items, total=None, desc=""):
        return progress(items, total=total, desc=desc, quiet=args.quiet)

    res = tolerance_study(
        spring,
        cam,
        tols,
        criteria,
        count=int(count),
        seed=int(seed),
        speeds=speeds,
        valve_train=vt,
        method=args.method,
        out_dir=args.out_dir,
        client=client,
        progress=bar,
        float_only=args.float_only,
        resolution=resolution,
        workers=workers,
    )
    written = [Path(args.out_dir) / "variants.nc"]
    plot = args.plot or str(Path(args.out_dir) / "histograms.png")
    close_figure(res.plot(plot))
    written.append(plot)
    if args.csv:
        written.append(res.to_csv(args.csv))
    announce_written(written, args)
    s = res.summary
    if args.json:
        print_json(dict(s, written=[str(p) for p in written]))
        return 0
    print(
        f"{s['variants']} variants ({s['method']}, seed {s['seed']}"
        + (f", {s['resumed_variants']} read back from {args.out_dir}/chunks" if s["resumed_variants"] else "")
        + f") of {args.spring} over {speeds[0]:g}-{speeds[-1]:g} cam rpm"
        + (": float speeds only" if args.float_only else "")
    )
    rows = []
    for k in FIGURES:
        if f"{k}_p50" not in s:
            continue
        qs = ("0.135", "2.5", "50", "97.5", "99.865")
        rows.append((k, OUTPUTS[k], f"{s[f'nominal_{k}']:.4g}", *(f"{s[f'{k}_p{q}']:.4g}" for q in qs)))
    print_table(rows, headers=("output", "unit", "nominal", "0.135 %", "2.5 %", "50 %", "97.5 %", "99.865 %"))
    fails = [(k[len("fail_share_") :], f"{v:.1%}") for k, v in s.items() if k.startswith("fail_share_")]
    print_table(fails, headers=("criterion", "variants failing"))
    print(
        f"periodic steady state: the last two revolutions of every speed run agree within "
        f"{100 * s['max_periodicity']:.3g} % of Fset (largest residual over the variants)"
    )
    print_notes(s)
    return 0


def register_life(vsub, add_model_option) -> None:
    """Add ``life`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "life",
        help="relaxation at the service temperature and life against a load spectrum ([spectrum]: speeds and time "
        "shares), from each speed's dynamic Goodman safety",
    )
    p.add_argument("spring", metavar="SPRING.toml", help="file with a [spring] table")
    p.add_argument("--cam", required=True, metavar="CAM.toml", help="file with a [cam] table")
    p.add_argument("--spectrum", required=True, metavar="SPECTRUM.toml", help="file with a [spectrum] table")
    p.add_argument(
        "--valve-train", metavar="VT.toml", help="file with a [valve_train] table (float speed, new and relaxed)"
    )
    add_model_option(p)
    add_output_options(p)
    p.set_defaults(func=cmd_life)


def cmd_life(args) -> int:
    """``springdyn valve life``: relaxation and spectrum life."""
    from springdyn.app.cli.common import emit
    from springdyn.core.params import load_toml
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.design.life import LoadSpectrum, service_life
    from springdyn.valve.spring.definition import ValveSpring
    from springdyn.valve.train.definition import ValveTrain

    spring = ValveSpring.from_toml(args.spring).with_model(args.model)
    cam = Cam.from_toml(args.cam)
    vt = ValveTrain.from_toml(args.valve_train) if args.valve_train else None
    spec = LoadSpectrum.from_dict(load_toml(args.spectrum, "spectrum"), source=str(args.spectrum))
    res = service_life(spring, cam, spec, vt)
    if emit(res, args, json_data=dict(res.summary)):
        return 0
    s = res.summary
    print(
        f"{args.spring} ({s['material']}): after {s['relaxation_hours']:g} h at {s['temperature_degC']:g} degC the "
        f"installed force relaxes by {s['relaxation_loss']:.2%}, {s['installed_force_N']:.1f} N to "
        f"{s['relaxed_installed_force_N']:.1f} N"
    )
    if "float_cam_rpm_new" in s:
        new, old = s["float_cam_rpm_new"], s["float_cam_rpm_relaxed"]
        fmt = lambda v: "above the scan" if v is None else f"{v:.0f} cam rpm"  # noqa: E731
        print(f"float speed: new {fmt(new)}, relaxed {fmt(old)}")
    cols = res.columns()
    print_table(
        [
            (f"{r:.0f}", f"{p:.3g}", f"{g:.3f}", f"{d:.1%}")
            for r, p, g, d in zip(cols["cam_rpm"], cols["share"], cols["goodman_safety"], cols["damage_share"])
        ],
        headers=("cam rpm", "time share", "Goodman (dynamic)", "share of the damage"),
    )
    print(
        "life: infinite (every speed at or below the endurance strength)"
        if s["infinite_life"]
        else f"life: {s['life_hours']:.4g} h (Miner, damage {s['damage_per_hour']:.3g} per hour)"
    )
    print_notes(s)
    return 0
