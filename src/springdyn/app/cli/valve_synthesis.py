"""``springdyn valve synthesize``, ``synthesize-inner``, ``tolerance`` and ``life``: valve springs
from requirements, a pack's inner spring for its outer spring, proven across tolerances, relaxed
and loaded by a spectrum (thin layer over :mod:`springdyn.valve.design.synthesis`,
:mod:`springdyn.valve.design.pack_synthesis`, :mod:`springdyn.valve.design.tolerances` and
:mod:`springdyn.valve.design.life`)."""

from __future__ import annotations

import springdyn.valve as valve
import springdyn.valve.design as design
from springdyn.app.cli.common import add_output_options, announce_written, close_figure, print_json
from springdyn.app.cli.valve_options import add_inputs, add_speed_options, cam_rpm_from_args, model_of, run_options
from springdyn.core.errors import InputError

__all__ = [
    "register",
    "register_tolerance",
    "register_life",
    "register_inner",
    "cmd_synthesize",
    "cmd_tolerance",
    "cmd_life",
    "cmd_synthesize_inner",
]


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
    p.add_argument(
        "--judge-all",
        action="store_true",
        help="run the distributed model on every candidate (by default the runs stop at the lightest candidate that "
        "meets every requirement: no heavier one can rank above it)",
    )
    add_output_options(p)
    p.set_defaults(func=cmd_synthesize)


def cmd_synthesize(args) -> int:
    """``springdyn valve synthesize``: search, check, rank, write."""
    from springdyn.core.io import check_output_folder
    from springdyn.core.progress import progress

    if not 1 <= args.per_kind <= 20:
        raise InputError(f"--per-kind = {args.per_kind} must be from 1 to 20")
    check_output_folder(args.out_dir, "--out")  # before the search (an empty name ran it all)
    req, base = design.read_requirements(args.requirements)

    def bar(items, desc):
        return progress(items, desc=desc, quiet=args.quiet)

    res = design.synthesize(req, per_kind=args.per_kind, base_dir=base, judge_all=args.judge_all, progress=bar)
    written = design.write_candidates(res, args.out_dir, str(args.requirements))
    written.append(res.to_csv(args.csv if args.csv else f"{args.out_dir}/candidates.csv"))
    if args.plot:
        close_figure(res.plot(args.plot))
        written.append(args.plot)
    announce_written(written, args)
    if args.json:
        print_json(dict(res.summary, candidates_table=res.rows, written=[str(p) for p in written]))
    else:
        print(res.describe(str(args.requirements), str(args.out_dir)))
    return 0


def register_tolerance(vsub) -> None:
    """Add ``tolerance`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "tolerance",
        help="a spring (or a spring pack, each spring's own) across its manufacturing tolerances ([tolerances], "
        "[criteria]): Monte Carlo or Sobol "
        "variants swept over the speeds (or, with --float-only, each variant's float speed searched from the "
        "nominal's); variants.nc, percentiles, failing shares, histograms (resumable)",
    )
    add_inputs(p, train="file with a [valve_train] table (float speed, lash)")
    p.add_argument("--tolerances", required=True, metavar="TOL.toml", help="file with [tolerances] (and [criteria])")
    p.add_argument("--samples", required=True, metavar="N", help="variants (a power of 2 for Sobol points)")
    p.add_argument(
        "--seed", default="0", metavar="S", help="seed of the sampling (default 0): the same seed, the same variants"
    )
    p.add_argument(
        "--method", choices=("sobol", "monte-carlo"), default="sobol", help="scrambled Sobol (default) or Monte Carlo"
    )
    add_speed_options(p, ranged=True, what="the speeds of each variant's sweep, START:STOP:STEP or a list")
    p.add_argument("--out", dest="out_dir", required=True, metavar="DIR", help="folder: variants.nc, chunks/ (resumes)")
    p.add_argument(
        "--float-only",
        action="store_true",
        help="a float-speed study: each variant's statics and float speed, searched from the nominal's (4-5 speeds "
        "a variant, not a sweep; Goodman, peak force and clash are not computed)",
    )
    p.add_argument(
        "--screen",
        action="store_true",
        help="a screened study: every variant's statics; a designed part of the sample simulated and fitted with a "
        "quadratic response surface per dynamic figure, checked on a hold-out; only the variants outside the fitted "
        "ones' box or whose verdict the surface's band leaves open simulated (their count and each band printed)",
    )
    p.add_argument(
        "--resolution", default="5", metavar="RPM", help="final bracket of each float speed in cam rpm (default 5)"
    )
    p.add_argument(
        "--periodicity-tol",
        dest="variant_periodicity_tol",  # (not the run options' periodicity_tol: no --revolutions here)
        default=f"{100 * valve.PERIODICITY_TOL:g} %",
        metavar="TOL",
        help="every run of a variant goes to its periodic steady state within TOL of Fset; a variant whose runs "
        f"do not is flagged and left out of the percentiles and shares (default {100 * valve.PERIODICITY_TOL:g} %%)",
    )
    p.add_argument("--workers", metavar="N", help="local threads the chunks run on (default: 2, both cores)")
    p.add_argument(
        "--scheduler", metavar="ADDRESS", help="run the chunks on a Dask scheduler, e.g. tcp://127.0.0.1:8786"
    )
    add_output_options(p)
    p.set_defaults(func=cmd_tolerance)


def cmd_tolerance(args) -> int:
    """``springdyn valve tolerance``: sample, run in chunks, summarise."""
    from pathlib import Path

    from springdyn.app.cli.common import as_options, quantity, whole_number
    from springdyn.core.io import check_output_folder
    from springdyn.core.progress import progress

    check_output_folder(args.out_dir, "--out")  # before any work (an existing file failed with exit 74 at the end)
    count = whole_number(args.samples, "--samples", 1, 10_000_000, "from 1 to 10000000")
    seed = whole_number(args.seed, "--seed", 0, 2**63 - 1, "from 0 to 2^63 - 1")
    tol = quantity(args.variant_periodicity_tol, "", "--periodicity-tol")
    if not 1e-7 <= tol <= 0.5:
        raise InputError(
            f"--periodicity-tol = {args.variant_periodicity_tol!r} must be from 1e-05 % to 50 % of Fset "
            f"(default {100 * valve.PERIODICITY_TOL:g} %)"
        )
    model = model_of(args)
    tols, criteria = design.read_tolerances(args.tolerances)
    if "lash" in tols and model.valve_train is None:
        raise InputError("[tolerances] lash is the valve train's: give --valve-train")
    speeds = cam_rpm_from_args(args, ranged=True, model=model)
    if args.float_only and model.valve_train is None:
        raise InputError("--float-only needs --valve-train: the spring alone does not float")
    resolution = quantity(args.resolution, "rpm", "--resolution", bare_unit="rpm")
    if not resolution > 0:
        raise InputError(f"--resolution = {args.resolution!r} must be a positive speed (cam rpm)")
    workers = None if args.workers is None else whole_number(args.workers, "--workers", 1, None, "of at least 1")
    with as_options(scheduler="--scheduler"):
        client = valve.connect(args.scheduler) if args.scheduler is not None else None

    def bar(items, total=None, desc=""):
        return progress(items, total=total, desc=desc, quiet=args.quiet)

    try:
        with as_options(**run_options(args, model)):  # a speed refused named as the user gave it
            res = model.tolerance_study(
                tols,
                criteria,
                count=int(count),
                seed=int(seed),
                speeds=speeds,
                method=args.method,
                out_dir=args.out_dir,
                client=client,
                progress=bar,
                float_only=args.float_only,
                resolution=resolution,
                workers=workers,
                periodicity_tol=tol,
                screen=args.screen,
            )
    finally:
        if client is not None:
            client.close()
    written = [Path(args.out_dir) / "variants.nc", args.plot or str(Path(args.out_dir) / "histograms.png")]
    close_figure(res.plot(written[-1]))
    if args.csv:
        written.append(res.to_csv(args.csv))
    announce_written(written, args)
    if args.json:
        print_json(dict(res.summary, written=[str(p) for p in written]))
    else:
        print(res.describe(str(args.spring), f"{args.out_dir}/chunks"))
    return 0


def register_life(vsub) -> None:
    """Add ``life`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "life",
        help="relaxation at the service temperature and life against a load spectrum ([spectrum]: speeds and time "
        "shares), from each speed's dynamic Goodman safety",
    )
    add_inputs(p, train="file with a [valve_train] table (float speed, new and relaxed)")
    p.add_argument("--spectrum", required=True, metavar="SPECTRUM.toml", help="file with a [spectrum] table")
    add_output_options(p)
    p.set_defaults(func=cmd_life)


def cmd_life(args) -> int:
    """``springdyn valve life``: relaxation and spectrum life."""
    from springdyn.app.cli.common import emit
    from springdyn.core.params import load_toml

    model = model_of(args)
    spec = design.LoadSpectrum.from_dict(load_toml(args.spectrum, "spectrum"), source=str(args.spectrum))
    res = model.service_life(spec)
    if not emit(res, args, json_data=dict(res.summary)):
        print(res.describe(str(args.spring)))
    return 0


def register_inner(vsub) -> None:
    """Add ``synthesize-inner`` to the ``springdyn valve`` sub-commands ``vsub``."""
    p = vsub.add_parser(
        "synthesize-inner",
        help="the inner spring of a pack for a given outer spring and force split: its drawing (equal stress with "
        "the outer at full lift, the radial clearance kept), forces, stress, Goodman, clearance and the pack's "
        "modes; writes the pack file",
    )
    p.add_argument(
        "outer", metavar="OUTER.toml", help="file with the outer spring's [spring] table (a pack file: its [spring])"
    )
    p.add_argument(
        "--share",
        required=True,
        metavar="S",
        help="the inner spring's share of the pack's force at installed length and full lift, e.g. '35 %%' or 0.35 "
        "(5 to 70 %%)",
    )
    p.add_argument("--lift", required=True, metavar="LIFT", help="valve lift at the springs, e.g. 9mm")
    p.add_argument(
        "--clearance",
        default="0.5 mm",
        metavar="C",
        help="radial clearance between the outer spring's inside and the inner's outside (default 0.5 mm)",
    )
    p.add_argument(
        "--installed-length",
        metavar="L",
        help="the inner spring's installed length (default: the outer's; a seat step shortens it), e.g. 41mm",
    )
    p.add_argument(
        "--out", dest="pack_out", required=True, metavar="PACK.toml", help="write the pack file (outer + inner) there"
    )
    p.add_argument("--json", action="store_true", help="print JSON (SI values)")
    p.set_defaults(func=cmd_synthesize_inner)


def cmd_synthesize_inner(args) -> int:
    """``springdyn valve synthesize-inner``: the inner spring, its figures, the pack file."""
    from springdyn.app.cli.common import as_options, quantity
    from springdyn.core.io import atomic_open, check_output_file, dumps_toml
    from springdyn.core.params import load_toml

    out = check_output_file(args.pack_out, "--out")  # before any work
    share = quantity(args.share, "", "--share")
    lift = quantity(args.lift, "m", "--lift")
    clearance = quantity(args.clearance, "m", "--clearance")
    installed = quantity(args.installed_length, "m", "--installed-length") if args.installed_length else None
    doc = load_toml(args.outer)
    outer = valve.ValveSpring.outer_from_toml(args.outer)
    with as_options(share="--share", lift="--lift", clearance="--clearance"):
        result = design.inner_spring_for(outer, share, lift, clearance, installed_length=installed)
    figures = design.inner_spring_figures(result, lift)
    damper = doc.get("damper") if "third" not in (doc.get("damper") or {}).values() else None
    header = (
        f"the inner spring for {args.outer} by springdyn valve synthesize-inner --share {args.share} --lift "
        f"{args.lift} --clearance {args.clearance}"
        + (f" --installed-length {args.installed_length}" if args.installed_length else "")
        + "\n"
        + design.inner_spring_text(figures)
    )
    with atomic_open(out, "w", encoding="utf-8") as fh:
        fh.write(dumps_toml(design.pack_file_tables(doc["spring"], result, damper), header))
    announce_written([out], args)
    if args.json:
        print_json(dict(figures, written=str(out)))
    else:
        print(design.inner_spring_text(figures))
    return 0
