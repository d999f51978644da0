"""``springdyn valve synthesize``: valve springs from requirements (thin layer over
:mod:`springdyn.valve.synthesis`)."""

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

__all__ = ["register", "cmd_synthesize"]


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
    from springdyn.valve.synthesis import read_requirements, synthesize, write_candidates

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
