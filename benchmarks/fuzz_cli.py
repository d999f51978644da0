"""Fuzz the ``springdyn`` command line and classify every outcome (issue 11).

Each case runs ``springdyn`` in a fresh process on a mutated example definition (a key
changed to an extreme, malformed, wrong-typed or wrongly-united value, a key or table
added or removed, a broken file) and/or mutated options (ranges, lists, negative,
NaN, huge, percent, missing units, output paths that cannot be written), or runs a
valid command and kills it with SIGTERM/SIGINT part way.  Outcomes:

- ``valid``: exit 0, and every number printed as JSON or written to CSV is finite;
- ``rejected``: exit 2 with one line on stderr that names a key or option;
- ``solver``: exit 3 with one line;
- ``traceback``: a Python traceback on stderr, or exit 1 or 70 (a bug);
- ``hang``: no exit within the time limit;
- ``nan``: exit 0 with NaN/inf/null-without-a-note in an output;
- ``unclear``: exit 2/3 with a message of several lines or naming no key or option;
- ``leftover``: a hidden temporary file left in the output folder;
- ``mixed``: after a kill, the output folder holds files of two different runs.

Run it: ``python benchmarks/fuzz_cli.py --cases 1500 --budget 1500`` (seconds); it prints a
table of counts and the reproducers of every bad outcome, and exits 1 if any was found.
"""

from __future__ import annotations

import argparse
import json
import math
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
import tomllib
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EX = ROOT / "examples"
CLI = [sys.executable, "-c", "import sys; from springdyn.app.cli.main import main; sys.exit(main())"]
BAD = ("traceback", "hang", "nan", "unclear", "leftover", "mixed")

#: Example definitions and the commands that read them (spring files also hold [cam]/[valve_train]).
DEFINITIONS = {
    "valve": (EX / "report" / "report_valve_one_step.toml", "spring"),
    "valve2": (EX / "report" / "report_valve_two_step.toml", "spring"),
    "valve3": (EX / "valve" / "ohv_pushrod.toml", "spring"),
    "cfcs": (EX / "cfcs" / "table1.toml", "cfcs"),
    "lsd": (EX / "lsd" / "type_c.toml", "lsd"),
}

EXTREME_VALUES = [
    "nan",
    "inf",
    "-inf",
    0,
    -1,
    1e-300,
    1e300,
    5e-324,
    "1e400 m",
    10**400,
    "",
    " ",
    "abc",
    "22",
    "22 kg",
    "22 mm",
    "5 %",
    "-5 %",
    "3,8 mm",
    "3000,5",
    "1:2:3",
    True,
    [1, 2],
    {"a": 1},
    "1e-9 m",
    "1e9 m",
    "0.5",
    "2**1000",
    "1/0",
    "()",
    "22 mm mm",
    "22 furlong",
    "\u00b5m",
    "1e3 GPa",
    "7850 kg/m^3",
    "100 cSt",
    3,
    2.5,
]

OPTION_VALUES = [
    "nan",
    "inf",
    "-1",
    "0",
    "1e308",
    "1e-320",
    "3000,5",
    "4000:1000:250",
    "1:50:100",
    "1:2:0",
    "-3000",
    "50Hz",
    "3,8mm",
    "5%",
    "40%",
    "abc",
    "",
    "1e9",
    "10 kg",
    "2.5",
    "1:1e9:1",
    "0:0:0",
    "300:4000:25",
    "1000,2000",
]


def _commands(kind: str, path: str, out: Path) -> list[list[str]]:
    """Commands that read a definition of this kind (short ones: the fuzz is about input)."""
    if kind.startswith("valve"):
        return [
            ["valve", "params", path, "--json"],
            ["valve", "curve", path, "--points", "50", "--csv", str(out / "c.csv")],
            ["valve", "modes", path, "--length", "38mm", "--json"],
            ["valve", "design", path, "--lift", "9mm", "--cam-rpm", "3000", "--json"],
            [
                "valve",
                "simulate",
                path,
                "--cam",
                path,
                "--cam-rpm",
                "2500",
                "--revolutions",
                "2",
                "--points-per-revolution",
                "360",
                "--json",
            ],
            [
                "valve",
                "simulate",
                path,
                "--cam",
                path,
                "--valve-train",
                path,
                "--cam-rpm",
                "2000",
                "--revolutions",
                "2",
                "--points-per-revolution",
                "360",
                "--json",
            ],
            ["valve", "train-modes", path, "--cam", path, "--valve-train", path, "--json"],
        ]
    if kind == "cfcs":
        return [
            ["cfcs", "static", path, "--json"],
            ["cfcs", "dynamic", path, "--omega", "14.7", "--json"],
        ]
    return [
        ["lsd", "coefficients", path, "--rpm", "500:3000:500", "--json"],
    ]


def _option_cases(out: Path) -> list[list[str]]:
    v = str(EX / "report" / "report_valve_one_step.toml")
    c = str(EX / "cfcs" / "table1.toml")
    lsd = str(EX / "lsd" / "type_c.toml")
    return [
        ["valve", "design", v, "--lift", "{x}", "--cam-rpm", "3000", "--json"],
        ["valve", "design", v, "--lift", "9mm", "--cam-rpm", "{x}", "--json"],
        ["valve", "modes", v, "--length", "{x}", "--json"],
        ["valve", "modes", v, "--length", "38mm", "--count", "{x}"],
        ["valve", "curve", v, "--points", "{x}", "--csv", str(out / "c.csv")],
        ["valve", "curve", v, "--from", "{x}", "--csv", str(out / "c.csv")],
        [
            "valve",
            "simulate",
            v,
            "--cam",
            v,
            "--cam-rpm",
            "{x}",
            "--revolutions",
            "2",
            "--points-per-revolution",
            "360",
            "--json",
        ],
        ["valve", "simulate", v, "--cam", v, "--cam-rpm", "2500", "--revolutions", "{x}", "--json"],
        ["valve", "simulate", v, "--cam", v, "--cam-rpm", "2500", "--rtol", "{x}", "--json"],
        [
            "valve",
            "float",
            v,
            "--cam",
            v,
            "--valve-train",
            v,
            "--cam-rpm",
            "2000:3000:500",
            "--resolution",
            "{x}",
            "--json",
            "--quiet",
        ],
        [
            "valve",
            "sweep",
            v,
            "--cam",
            v,
            "--cam-rpm",
            "{x}",
            "--revolutions",
            "2",
            "--points-per-revolution",
            "180",
            "--out",
            str(out / "sw"),
            "--quiet",
        ],
        ["cfcs", "static", c, "--stroke", "{x}", "--json"],
        ["cfcs", "dynamic", c, "--omega", "{x}", "--json"],
        ["cfcs", "dynamic", c, "--omega", "14.7", "--amplitude", "{x}", "--json"],
        ["cfcs", "sweep", c, "--omega", "{x}", "--json"],
        ["cfcs", "design", "--force", "{x}", "--stroke", "40mm", "--json"],
        ["lsd", "coefficients", lsd, "--rpm", "{x}", "--json"],
        ["lsd", "coefficients", lsd, "--rpm", "1000", "--amplitude", "{x}", "--json"],
        ["lsd", "rig", lsd, "--rpm", "{x}", "--eccentricity", "50um", "--csv", str(out / "r.csv")],
        ["lsd", "rig", lsd, "--rpm", "1000", "--revolutions", "{x}", "--csv", str(out / "r.csv")],
    ]


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def _dump(doc: dict) -> str:
    lines = []
    for table, keys in doc.items():
        lines.append(f"[{table}]")
        for k, v in keys.items():
            lines.append(f"{k} = {_toml_value(v)}")
        lines.append("")
    return "\n".join(lines)


def _mutated_definition(rng: random.Random, kind: str, work: Path) -> Path:
    src, table = DEFINITIONS[kind]
    doc = tomllib.loads(src.read_text(encoding="utf-8"))
    for t in doc.values():  # resolve relative table files
        if isinstance(t, dict) and isinstance(t.get("file"), str):
            t["file"] = str((src.parent / t["file"]).resolve())
    how = rng.random()
    target = doc[table] if rng.random() < 0.8 or len(doc) == 1 else doc[rng.choice(list(doc))]
    if how < 0.6 and target:
        key = rng.choice(list(target))
        target[key] = rng.choice(EXTREME_VALUES)
    elif how < 0.7 and target:
        target.pop(rng.choice(list(target)))
    elif how < 0.78:
        target[rng.choice(["extra_key", "mean_diamter", "Damping_ratio"])] = 1
    elif how < 0.84:
        doc[rng.choice(["extra", "sprng", "cfc"])] = {"x": 1}
    else:  # a broken file
        path = work / f"{kind}.toml"
        raw = _dump(doc).encode()
        choice = rng.randrange(5)
        data = [
            raw[: rng.randrange(max(len(raw), 1))],
            raw.replace(b"=", b":", 1),
            raw + b"\xff\xfe",
            _dump(doc).encode("utf-16"),
            b"x = " + b"[" * 3000 + b"]" * 3000,
        ][choice]
        path.write_bytes(data)
        return path
    path = work / f"{kind}.toml"
    try:
        path.write_text(_dump(doc), encoding="utf-8")
    except TypeError:
        path.write_text(_dump({table: {}}), encoding="utf-8")
    return path


def _names_something(message: str) -> bool:
    return bool(
        re.search(
            r"--[a-z]|\b[a-z]+_[a-z_]+\b|\[[a-z_]+\]|\.toml|\.csv|\b(lift|length|count|points|"
            r"stroke|omega|rpm|amplitude|force|resolution|revolutions|file|folder|model|key|table)\b",
            message,
        )
    )


def _finite_json(text: str) -> bool:
    if re.search(r"\bNaN\b|\bInfinity\b", text):
        return False
    try:
        data = json.loads(text)
    except ValueError:
        return True  # not JSON (a table)

    def walk(obj, notes):
        if isinstance(obj, dict):
            notes = notes or bool(obj.get("notes"))
            return all(walk(v, notes) for k, v in obj.items())
        if isinstance(obj, list):
            return all(walk(v, notes) for v in obj)
        if obj is None:
            return notes  # a null needs a note saying why
        return not (isinstance(obj, float) and not math.isfinite(obj))

    return walk(data, False)


def _finite_csvs(folder: Path) -> bool:
    for f in folder.rglob("*.csv"):
        if re.search(r"(^|,)(nan|inf|-inf)(,|$)", f.read_text(errors="replace"), re.M | re.I):
            return False
    return True


def classify(argv, work: Path, timeout: float) -> tuple[str, str]:
    try:
        done = subprocess.run(
            [*CLI, *argv], capture_output=True, text=True, timeout=timeout, cwd=work, stdin=subprocess.DEVNULL
        )
    except subprocess.TimeoutExpired:
        return "hang", ""
    err = done.stderr.strip()
    if "Traceback" in err or done.returncode in (1, 70) or done.returncode < 0:
        return "traceback", err[-300:]
    if any(p.name.startswith(".") for p in work.rglob("*") if p.is_file()):
        return "leftover", ""
    if done.returncode == 0:
        if not _finite_json(done.stdout) or not _finite_csvs(work):
            return "nan", done.stdout[:200]
        return "valid", ""
    lines = [l for l in err.splitlines() if not l.startswith("springdyn: warning:")]
    if done.returncode in (2, 3):
        if len(lines) != 1 or not _names_something(lines[0]):
            return "unclear", err[:300]
        return ("rejected" if done.returncode == 2 else "solver"), lines[0][:200]
    if done.returncode == 74:
        return "rejected", err[:200]
    return "traceback", f"exit {done.returncode}: {err[:200]}"


def kill_case(rng: random.Random, work: Path) -> tuple[str, str]:
    """Run a command writing an output set into a folder that holds an older set; kill it part way."""
    v = str(EX / "report" / "report_valve_one_step.toml")
    argv = [
        "valve",
        "simulate",
        v,
        "--cam",
        v,
        "--cam-rpm",
        "2500",
        "--revolutions",
        "3",
        "--csv",
        str(work / "sim.csv"),
        "--plot",
        str(work / "sim.png"),
        "--json",
    ]
    first = subprocess.run([*CLI, *argv], capture_output=True, timeout=120, cwd=work)
    if first.returncode != 0:
        return "traceback", first.stderr.decode()[-200:]
    stamp = {p.name: p.stat().st_mtime_ns for p in work.iterdir()}
    proc = subprocess.Popen([*CLI, *argv], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, cwd=work)
    time.sleep(rng.uniform(0.05, 2.5))
    proc.send_signal(rng.choice([signal.SIGTERM, signal.SIGINT]))
    try:
        proc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        proc.kill()
        return "hang", "did not stop after SIGTERM/SIGINT"
    err = proc.stderr.read().decode()
    if "Traceback" in err:
        return "traceback", err[-300:]
    files = {p.name: p for p in work.iterdir()}
    if any(n.startswith(".") for n in files):
        return "leftover", ", ".join(sorted(files))
    changed = {n for n, p in files.items() if p.stat().st_mtime_ns != stamp.get(n)}
    if changed and changed != set(stamp):
        return "mixed", f"new: {sorted(changed)}, old: {sorted(set(stamp) - changed)}"
    return "valid", ""


def one_case(i: int, seed: int, timeout: float) -> tuple[str, str, str]:
    rng = random.Random(seed * 1_000_003 + i)
    work = Path(tempfile.mkdtemp(prefix="springdyn-fuzz-"))
    try:
        r = rng.random()
        if r < 0.02:
            outcome, detail = kill_case(rng, work)
            return outcome, "kill test (simulate --csv --plot, SIGTERM/SIGINT part way)", detail
        if r < 0.55:
            kind = rng.choice(list(DEFINITIONS))
            path = _mutated_definition(rng, kind, work)
            argv = rng.choice(_commands(kind, str(path), work))
            text = path.read_bytes()[:400].decode("utf-8", "replace")
            outcome, detail = classify(argv, work, timeout)
            return outcome, " ".join(argv) + "   # " + text.replace("\n", " | ")[:300], detail
        template = rng.choice(_option_cases(work))
        value = rng.choice(OPTION_VALUES)
        argv = [a.replace("{x}", value) for a in template]
        outcome, detail = classify(argv, work, timeout)
        return outcome, " ".join(argv), detail
    finally:
        shutil.rmtree(work, ignore_errors=True)


def main() -> int:
    parser = argparse.ArgumentParser(description="Fuzz the springdyn CLI and classify every outcome.")
    parser.add_argument("--cases", type=int, default=1500)
    parser.add_argument("--budget", type=float, default=1800.0, help="seconds in all (default 1800)")
    parser.add_argument("--seed", type=int, default=11)
    parser.add_argument("--timeout", type=float, default=120.0, help="seconds per case before it is a hang")
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    counts: dict[str, int] = {}
    bad: list[tuple[str, str, str]] = []
    t0 = time.monotonic()
    done = 0
    with ThreadPoolExecutor(max_workers=args.workers) as pool:
        futures = []
        for i in range(args.cases):
            futures.append(
                pool.submit(
                    lambda i=i: None if time.monotonic() - t0 > args.budget else one_case(i, args.seed, args.timeout)
                )
            )
        for f in futures:
            res = f.result()
            if res is None:
                continue
            done += 1
            outcome, argv, detail = res
            counts[outcome] = counts.get(outcome, 0) + 1
            if outcome in BAD:
                bad.append(res)
    elapsed = time.monotonic() - t0
    print(f"springdyn CLI fuzz: {done} cases in {elapsed:.0f} s (seed {args.seed})")
    print(f"{'outcome':<10} {'count':>6}")
    for name in ("valid", "rejected", "solver", *BAD):
        print(f"{name:<10} {counts.get(name, 0):>6}")
    unclear = counts.get("unclear", 0) / max(done, 1)
    print(f"unclear messages: {100 * unclear:.2f} % (target < 1 %)")
    for outcome, argv, detail in bad[:60]:
        print(f"\n[{outcome}] springdyn {argv}\n    {detail}")
    return 1 if any(counts.get(b, 0) for b in BAD if b != "unclear") or unclear >= 0.01 else 0


if __name__ == "__main__":
    sys.exit(main())
