"""Compare two output folders of springdyn (a demo, a report, a study) file by file.

Usage::

    python tools/compare_outputs.py BEFORE_DIR AFTER_DIR [--rtol 0] [--quiet]

Every CSV and JSON file under BEFORE_DIR is read beside its namesake under AFTER_DIR:

- a CSV column by column (its header names, then every number, exactly or within ``--rtol``);
- a JSON document key by key, recursively (numbers exactly or within ``--rtol``; strings,
  booleans, lists and key order as they are).

It prints one line per file (``same``, ``same within rtol`` with the largest relative
difference, or the first differences: a missing or added file, column or key, a changed
value) and a last line with the counts.  Exit status 0 when every file is the same (within
``--rtol``), 1 otherwise.  Figures (PNG) and the HTML are not compared: they embed dates and
renderer details.
"""

from __future__ import annotations

import argparse
import csv
import json
import math
import sys
from pathlib import Path


def _number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def _close(a: float, b: float, rtol: float) -> tuple[bool, float]:
    if a == b or (math.isnan(a) and math.isnan(b)):
        return True, 0.0
    scale = max(abs(a), abs(b))
    rel = abs(a - b) / scale if scale else math.inf
    return rel <= rtol, rel


def compare_csv(a: Path, b: Path, rtol: float) -> tuple[list[str], float]:
    with open(a, newline="", encoding="utf-8") as fa, open(b, newline="", encoding="utf-8") as fb:
        ra, rb = list(csv.reader(fa)), list(csv.reader(fb))
    if not ra or not rb:
        return ([] if ra == rb else ["one file is empty"]), 0.0
    ha, hb = ra[0], rb[0]
    out, worst = [], 0.0
    if ha != hb:
        gone, new = [c for c in ha if c not in hb], [c for c in hb if c not in ha]
        out.append(f"columns differ: removed {gone}, added {new}" if gone or new else "columns reordered")
    if len(ra) != len(rb):
        out.append(f"{len(ra) - 1} rows before, {len(rb) - 1} after")
    cols = [c for c in ha if c in hb]
    ia, ib = {c: ha.index(c) for c in cols}, {c: hb.index(c) for c in cols}
    for c in cols:
        bad = 0
        for row, (x, y) in enumerate(zip(ra[1:], rb[1:]), start=1):
            u, v = x[ia[c]], y[ib[c]]
            if u == v:
                continue
            nu, nv = _number(u), _number(v)
            if nu is None or nv is None:
                bad += 1
                if bad == 1:
                    out.append(f"column {c}, row {row}: {u!r} -> {v!r}")
                continue
            ok, rel = _close(nu, nv, rtol)
            worst = max(worst, rel)
            if not ok:
                bad += 1
                if bad == 1:
                    out.append(f"column {c}, row {row}: {u} -> {v} (relative {rel:.3g})")
        if bad > 1:
            out.append(f"column {c}: {bad} values differ")
    return out, worst


def _walk(x, y, path: str, rtol: float, out: list, worst: list) -> None:
    if isinstance(x, dict) and isinstance(y, dict):
        if list(x) != list(y):
            gone, new = [k for k in x if k not in y], [k for k in y if k not in x]
            out.append(f"{path or '/'}: keys removed {gone}, added {new}" if gone or new else f"{path}: keys reordered")
        for k in x:
            if k in y:
                _walk(x[k], y[k], f"{path}/{k}", rtol, out, worst)
        return
    if isinstance(x, list) and isinstance(y, list):
        if len(x) != len(y):
            out.append(f"{path}: {len(x)} items before, {len(y)} after")
        for i, (u, v) in enumerate(zip(x, y)):
            _walk(u, v, f"{path}[{i}]", rtol, out, worst)
        return
    if isinstance(x, bool) or isinstance(y, bool) or not isinstance(x, (int, float)) or not isinstance(y, (int, float)):
        if x != y:
            out.append(f"{path}: {x!r} -> {y!r}")
        return
    ok, rel = _close(float(x), float(y), rtol)
    worst[0] = max(worst[0], rel)
    if not ok:
        out.append(f"{path}: {x!r} -> {y!r} (relative {rel:.3g})")


def compare_json(a: Path, b: Path, rtol: float) -> tuple[list[str], float]:
    x = json.loads(a.read_text(encoding="utf-8"))
    y = json.loads(b.read_text(encoding="utf-8"))
    out, worst = [], [0.0]
    _walk(x, y, "", rtol, out, worst)
    return out, worst[0]


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("before", type=Path)
    p.add_argument("after", type=Path)
    p.add_argument("--rtol", type=float, default=0.0, help="relative tolerance on numbers (default 0: exact)")
    p.add_argument("--quiet", action="store_true", help="only the files that differ and the counts")
    p.add_argument("--most", type=int, default=5, help="differences shown per file (default 5)")
    args = p.parse_args(argv)
    files = sorted(f.relative_to(args.before) for f in args.before.rglob("*") if f.suffix in (".csv", ".json"))
    added = sorted(
        f.relative_to(args.after)
        for f in args.after.rglob("*")
        if f.suffix in (".csv", ".json") and not (args.before / f.relative_to(args.after)).exists()
    )
    same = differ = 0
    for rel in files:
        b = args.after / rel
        if not b.exists():
            print(f"{rel}: missing after")
            differ += 1
            continue
        diffs, worst = (compare_csv if rel.suffix == ".csv" else compare_json)(args.before / rel, b, args.rtol)
        if diffs:
            differ += 1
            print(f"{rel}: DIFFERS")
            for d in diffs[: args.most]:
                print(f"    {d}")
            if len(diffs) > args.most:
                print(f"    ... {len(diffs) - args.most} more")
        else:
            same += 1
            if not args.quiet:
                print(f"{rel}: same" + (f" within rtol (largest relative difference {worst:.2g})" if worst else ""))
    for rel in added:
        print(f"{rel}: added after")
    print(f"{same} files the same, {differ} differ, {len(added)} added")
    return 0 if differ == 0 and not added else 1


if __name__ == "__main__":
    sys.exit(main())
