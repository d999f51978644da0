"""The results of every study before and after a change of the engine or the studies (issue 42).

Run (two steps; the first with each tree's ``src`` on ``PYTHONPATH``)::

    PYTHONPATH=OLD/src python benchmarks/compare_studies.py run --out before.json
    PYTHONPATH=NEW/src python benchmarks/compare_studies.py run --out after.json
    python benchmarks/compare_studies.py compare before.json after.json

``run`` runs, with whichever springdyn is imported (it prints its path):

1. the demo's valve analyses: ``springdyn report`` of the demo's two valve definitions
   (``springdyn demo`` without the cfcs and lsd examples), every figure of the JSON and CSV
   files it writes;
2. the synthesis example, step 1 of the worked example of docs/valve-design.md:
   ``synthesize(examples/valve/requirements.toml)``, every candidate's figures;
3. the worked example's step 2: the first candidate (distributed) across
   ``examples/valve/tolerances_new_spring.toml``, 1500-3800 cam rpm (``--worked-samples``
   variants, 32 in the guide);
4. the tolerance example of the README: ``examples/valve/tolerances.toml`` on the one-step
   spring, bucket train and polydyne cam, the full study over 2000-3000 cam rpm
   (``--samples``, 64 in the README) and the float-speed study over 1500-3300 cam rpm
   (``--float-samples``, 1024 in the README);

and writes their figures with the wall time of each part to one JSON file.  ``compare`` reads
two such files and judges each figure by its kind (its name's unit):

- a force [N]: within ``--tol`` (default 0.2 %, the periodicity tolerance) of the spring's
  installed force Fset (the smallest static force of its analysis, or its ``Fset``);
- a float speed (a searched one: ``float_cam_rpm`` and its percentiles): within its resolution
  (the study's ``float_resolution_rpm``, the float result's ``resolution``, else 5 rpm);
- a path figure (revolutions, simulations, steps, periodicity residuals, band ends, times, a
  screened study's ``simulated`` and ``float_searched`` flags): not compared (a warm start
  changes the path, not the periodic state), on one side only too;
- anything else: within ``--rtol`` (default 1 %) of its value, or of 1 % of the largest
  value of its array (a safety factor, a stress, a gap, a severity).

It prints every difference and a last line with the counts, and exits 1 on any difference
(or a figure missing on one side), 0 otherwise.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples" / "valve"

#: Figures that follow the integration's path, not the periodic state: not compared.
PATH_WORDS = (
    "revolutions",
    "simulations",
    "evaluations",
    "steps",
    "periodicity",
    "_lo_",
    "_hi_",
    "seconds",
    "resumed",
    "t_end",
    "simulated",  # a screened study's flags: how a variant's figures were obtained
    "float_searched",
)
#: Searched float speeds: compared within their resolution.
FLOAT_WORDS = ("float_cam_rpm", "float_engine_rpm")
DEFAULT_RESOLUTION = 5.0


def _numbers(value, prefix, out):
    """Every number of a JSON-ready value, flattened to ``prefix/key`` -> number or list."""
    if isinstance(value, bool):
        out[prefix] = float(value)
    elif isinstance(value, (int, float)):
        out[prefix] = float(value)
    elif isinstance(value, dict):
        for k, v in value.items():
            _numbers(v, f"{prefix}/{k}", out)
    elif isinstance(value, (list, tuple)):
        if value and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
            out[prefix] = [float(v) for v in value]
        elif value and all(v is None or isinstance(v, (int, float)) for v in value):
            out[prefix] = [math.nan if v is None else float(v) for v in value]
        else:
            for i, v in enumerate(value):
                _numbers(v, f"{prefix}/{i}", out)
    elif value is not None and hasattr(value, "tolist"):  # numpy scalars and arrays
        _numbers(value.tolist(), prefix, out)


def _csv_columns(path: Path) -> dict:
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    out = {}
    if len(rows) < 2:
        return out
    for j, name in enumerate(rows[0]):
        try:
            out[name] = [float(r[j]) if r[j] != "" else math.nan for r in rows[1:]]
        except (ValueError, IndexError):
            continue  # a text column
    return out


def _folder_figures(folder: Path, prefix: str) -> dict:
    """Every number of the JSON and CSV files under ``folder`` (the long time series of a
    single simulation, ``simulate_<rpm>.csv``, left out: its summary holds its figures)."""
    out = {}
    for f in sorted(folder.rglob("*")):
        rel = f.relative_to(folder).as_posix()
        if f.suffix == ".json":
            _numbers(json.loads(f.read_text(encoding="utf-8")), f"{prefix}/{rel}", out)
        elif f.suffix == ".csv" and not (
            f.name.startswith("simulate_") or f.name in ("static_curve.csv", "run_up.csv")
        ):
            for k, v in _csv_columns(f).items():
                out[f"{prefix}/{rel}/{k}"] = v
    return out


def _fset_of(figures: dict, prefix: str) -> float:
    """The installed force of a part [N]: its ``Fset`` figure, else its smallest static force."""
    cands = [v for k, v in figures.items() if k.startswith(prefix) and k.endswith("/Fset") and isinstance(v, float)]
    if cands:
        return min(cands)
    stat = []
    for k, v in figures.items():
        if k.startswith(prefix) and k.endswith("min_static_force_N"):
            stat += v if isinstance(v, list) else [v]
    stat = [s for s in stat if s == s and s > 0]
    return min(stat) if stat else math.nan


def part_demo(tmp: Path) -> dict:
    from springdyn.app.cli.main import main as cli  # (here: the CLI only for this part)
    from springdyn.app.report.build import demo_definitions

    valve = [str(p) for p in demo_definitions() if p.name.startswith("report_valve")]
    out = tmp / "demo"
    rc = cli(["report", *valve, "--out", str(out), "--quiet"])
    if rc != 0:
        raise RuntimeError(f"springdyn report of the demo's valve definitions exited {rc}")
    figures = {}
    for sub in sorted(p for p in out.iterdir() if p.is_dir() and p.name.startswith("valve-")):
        part = _folder_figures(sub, f"demo/{sub.name}")
        part[f"demo/{sub.name}/Fset"] = _fset_of(part, f"demo/{sub.name}")
        figures.update(part)
    return figures


def _synthesis(tmp: Path):
    from springdyn.valve.design import synthesis

    req, base = synthesis.read_requirements(EXAMPLES / "requirements.toml")
    res = synthesis.synthesize(req, base_dir=base)
    synthesis.write_candidates(res, tmp / "springs")
    figures = {}
    for i, row in enumerate(res.rows):
        _numbers({k: v for k, v in row.items() if not isinstance(v, str)}, f"synthesis/{i:02d}", figures)
        figures[f"synthesis/{i:02d}/Fset"] = float(res.springs[i].spring_model.internal_parameters()["Fset"])
    return figures, sorted((tmp / "springs").glob("candidate_01_*.toml"))


def _study_figures(study, prefix: str) -> dict:
    figures = {}
    _numbers({k: v for k, v in study.summary.items() if k != "notes"}, f"{prefix}/summary", figures)
    ds = study.dataset
    for k in ds.data_vars:
        figures[f"{prefix}/variants/{k}"] = [float(v) for v in ds[k].values]
    _numbers(study.nominal, f"{prefix}/nominal", figures)
    figures[f"{prefix}/Fset"] = float(study.nominal["Fset"])
    figures[f"{prefix}/float_resolution_rpm"] = float(ds.attrs.get("float_resolution_rpm", DEFAULT_RESOLUTION))
    return figures


def part_worked(first_candidate: Path, samples: int) -> dict:
    import numpy as np

    from springdyn.valve import Cam, ValveSpring, ValveTrain
    from springdyn.valve.design.tolerances import read_tolerances, tolerance_study

    spring = ValveSpring.from_toml(first_candidate).with_model("distributed")
    tols, crit = read_tolerances(EXAMPLES / "tolerances_new_spring.toml")
    study = tolerance_study(
        spring,
        Cam.from_toml(EXAMPLES / "cam_polydyne_ramps.toml"),
        tols,
        crit,
        count=samples,
        seed=0,
        speeds=np.arange(1500.0, 3801.0, 100.0),
        valve_train=ValveTrain.from_toml(EXAMPLES / "valve_train.toml"),
    )
    return _study_figures(study, "worked")


def part_tolerances(samples: int, float_samples: int) -> dict:
    import numpy as np

    from springdyn.valve import Cam, ValveSpring, ValveTrain
    from springdyn.valve.design.tolerances import read_tolerances, tolerance_study

    spring = ValveSpring.from_toml(EXAMPLES / "one_step_spring.toml")
    cam = Cam.from_toml(EXAMPLES / "cam_polydyne_ramps.toml")
    vt = ValveTrain.from_toml(EXAMPLES / "valve_train.toml")
    tols, crit = read_tolerances(EXAMPLES / "tolerances.toml")
    full = tolerance_study(
        spring, cam, tols, crit, count=samples, seed=0, speeds=np.arange(2000.0, 3001.0, 100.0), valve_train=vt
    )
    figures = _study_figures(full, "tolerance")
    fl = tolerance_study(
        spring,
        cam,
        tols,
        crit,
        count=float_samples,
        seed=0,
        speeds=np.arange(1500.0, 3301.0, 100.0),
        valve_train=vt,
        float_only=True,
    )
    figures.update(_study_figures(fl, "tolerance_float"))
    return figures


def run(args) -> int:
    import springdyn

    warnings.simplefilter("ignore")
    print(f"springdyn from {Path(springdyn.__file__).parent}")
    figures, seconds = {}, {}
    with tempfile.TemporaryDirectory(prefix="compare_studies_") as tmp:
        tmp = Path(tmp)
        parts = [("demo", lambda: part_demo(tmp))]
        first = []

        def synth():
            f, cands = _synthesis(tmp)
            first.extend(cands)
            return f

        parts.append(("synthesis", synth))
        parts.append(("worked", lambda: part_worked(first[0], args.worked_samples)))
        parts.append(("tolerance", lambda: part_tolerances(args.samples, args.float_samples)))
        for name, fn in parts:
            if args.only and name not in args.only:
                continue
            t = time.perf_counter()
            figures.update(fn())
            seconds[name] = time.perf_counter() - t
            print(f"{name}: {seconds[name]:.1f} s", flush=True)
    doc = dict(springdyn=str(Path(springdyn.__file__).parent), seconds=seconds, figures=figures)
    Path(args.out).write_text(json.dumps(doc, indent=1, allow_nan=True), encoding="utf-8")
    print(f"wrote {len(figures)} figures to {args.out}")
    return 0


def _kind(key: str) -> str:
    name = key.rsplit("/", 1)[-1]
    if any(w in key for w in PATH_WORDS):
        return "path"
    if any(w in name for w in FLOAT_WORDS):
        return "float"
    forces = ("force", "Fset", "_N")
    if any(w in name for w in forces) and not any(
        w in name for w in ("share", "band", "ratio", "factor", "angle", "_per_")
    ):
        return "force"
    return "other"


def _part_of(key: str) -> str:
    parts = key.split("/")
    return "/".join(parts[:2]) if parts[0] in ("demo", "synthesis") else parts[0]


def _as_list(v):
    return v if isinstance(v, list) else [v]


def compare(args) -> int:
    a = json.loads(Path(args.before).read_text(encoding="utf-8"))
    b = json.loads(Path(args.after).read_text(encoding="utf-8"))
    fa, fb = a["figures"], b["figures"]
    diffs, counts, largest = [], dict(compared=0, skipped=0), {}
    for key in sorted(set(fa) | set(fb)):
        kind = _kind(key)
        if kind == "path":  # (one side's alone too: a path flag a version added)
            counts["skipped"] += 1
            continue
        if key not in fa or key not in fb:
            diffs.append(f"{key}: only {'after' if key in fb else 'before'}")
            continue
        va, vb = _as_list(fa[key]), _as_list(fb[key])
        if len(va) != len(vb):
            diffs.append(f"{key}: {len(va)} values before, {len(vb)} after")
            continue
        part = _part_of(key)
        if kind == "force":
            allowed = args.tol * fa.get(f"{part}/Fset", math.nan)
            what = f"{100 * args.tol:g} % Fset"
        elif kind == "float":
            res = fa.get(f"{part}/float_resolution_rpm") or _resolution(fa, key)
            allowed = res * (1.0 + 1e-9)
            what = f"the resolution {res:g} rpm"
        else:
            finite = [abs(x) for x in va if x == x]
            allowed = None
            what = f"{100 * args.rtol:g} %"
            scale = max(finite) if finite else 0.0
        counts["compared"] += 1
        worst, at = 0.0, None
        for i, (x, y) in enumerate(zip(va, vb)):
            if x != x or y != y:
                if (x != x) != (y != y):
                    worst, at = math.inf, i
                continue
            lim = allowed if allowed is not None else max(args.rtol * max(abs(x), abs(y)), args.rtol * scale)
            if not (lim == lim):  # a force without its part's Fset: relative
                lim = args.rtol * max(abs(x), abs(y))
            share = abs(x - y) / lim if lim > 0 else (0.0 if x == y else math.inf)
            if share > largest.get(kind, (0.0, ""))[0]:
                largest[kind] = (share, f"{key}{'' if len(va) == 1 else f'[{i}]'}: {x:.6g} -> {y:.6g}")
            if abs(x - y) > lim and abs(x - y) - lim > worst:
                worst, at = abs(x - y) - lim, i
        if at is not None:
            where = "" if len(va) == 1 else f"[{at}]"
            diffs.append(f"{key}{where}: {va[at]:.6g} before, {vb[at]:.6g} after (allowed: {what})")
    for d in diffs:
        print(d)
    for kind, (share, where) in sorted(largest.items()):
        print(f"largest {kind} difference: {100 * share:.3g} % of its allowance ({where})")
    ta, tb = a.get("seconds", {}), b.get("seconds", {})
    for k in ta:
        if k in tb:
            print(f"time {k}: {ta[k]:.1f} s before, {tb[k]:.1f} s after ({ta[k] / tb[k]:.2f}x)")
    print(
        f"{counts['compared']} figures compared, {counts['skipped']} path figures skipped, {len(diffs)} differences: "
        + ("SAME within the tolerances" if not diffs else "DIFFERENT")
    )
    return 1 if diffs else 0


def _resolution(figures: dict, key: str) -> float:
    """The resolution of a float result beside ``key`` (its JSON's ``resolution``), else 5 rpm."""
    folder = key.rsplit("/", 1)[0]
    for k, v in figures.items():
        if k.startswith(folder) and k.endswith("/resolution") and isinstance(v, float):
            return v
    return DEFAULT_RESOLUTION


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run", help="run the studies and write their figures to a JSON file")
    r.add_argument("--out", required=True, help="the JSON file to write")
    r.add_argument("--samples", type=int, default=16, help="variants of the full tolerance example (README: 64)")
    r.add_argument("--float-samples", type=int, default=64, help="variants of the float-speed example (README: 1024)")
    r.add_argument("--worked-samples", type=int, default=4, help="variants of the worked example's step 2 (guide: 32)")
    r.add_argument("--only", nargs="*", choices=("demo", "synthesis", "worked", "tolerance"), help="only these parts")
    c = sub.add_parser("compare", help="compare two JSON files of `run`")
    c.add_argument("before")
    c.add_argument("after")
    c.add_argument("--tol", type=float, default=0.002, help="forces: fraction of Fset (default 0.002)")
    c.add_argument("--rtol", type=float, default=0.01, help="other figures: relative (default 0.01)")
    args = ap.parse_args(argv)
    return run(args) if args.command == "run" else compare(args)


if __name__ == "__main__":
    sys.exit(main())
