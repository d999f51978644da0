"""Identify the stiffness and damping of a leaf spring damper from rig CSV files.

The rig CSV format is ``time_s, x_m, y_m, fx_N, fy_N`` (SI, uniform time steps), the
format the test rig writes and ``springdyn lsd identify`` reads.  Without arguments the
script first writes two such files with the API: the Type C damper of the thesis shaken
along x and then along y at 1000 rpm (50 um, with 2 N of force noise).  Given CSV paths it
reads those instead: one file identifies what a single excitation can (for a circular
orbit ``Kxx + w Cxy`` and ``Cxx - Kxy/w``, docs/references.md), two independent
excitations at the same speed identify the full 2 x 2 matrices K and C.

Run:  python examples/lsd/identify_from_csv.py [--out DIR] [FIRST.csv [SECOND.csv]] [--mass KG]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from springdyn.core.io import write_json
from springdyn.lsd import LSDModel, LSDParameters, identify, linear_shake, read_rig_data, simulate_rig

RPM, AMPLITUDE = 1000.0, 50e-6


def write_rig_csvs(out: Path, model: LSDModel) -> list[Path]:
    """Simulate an x shake and a y shake of ``model`` and write them as rig CSV files."""
    paths = []
    for seed, axis in enumerate(("x", "y")):
        record = simulate_rig(model, linear_shake(RPM, AMPLITUDE, axis, revolutions=20), force_noise=2.0, seed=seed)
        paths.append(record.to_csv(out / f"rig_{axis}_shake_{RPM:.0f}rpm.csv"))
    return [Path(p) for p in paths]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", nargs="*", help="one or two rig CSV files (default: simulate and write two)")
    parser.add_argument("--out", default=None, help="output folder (default: a new temporary folder)")
    parser.add_argument(
        "--mass",
        type=float,
        default=None,
        help="moving mass removed from the forces [kg] (default: the Type C ring mass)",
    )
    args = parser.parse_args(argv)
    if len(args.csv) > 2:
        parser.error("give at most two CSV files (two independent excitations at one speed)")
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="springdyn-lsd-identify-"))
    out.mkdir(parents=True, exist_ok=True)

    model = LSDModel(LSDParameters.example("C"))
    paths = [Path(p) for p in args.csv] or write_rig_csvs(out, model)
    if not args.csv:
        print("wrote " + ", ".join(str(p) for p in paths))
    records = [read_rig_data(p) for p in paths]
    mass = model.params.ring_mass if args.mass is None else args.mass
    ident = identify(records[0], records[1] if len(records) > 1 else None, mass=mass)
    print(
        f"identified at {ident.rpm:.0f} rpm ({ident.frequency:.2f} Hz) from {ident.cycles} cycles, mode: {ident.mode}"
    )
    for label, M, U, unit, scale in (
        ("K", ident.K, ident.K_uncertainty, "N/mm", 1e-3),
        ("C", ident.C, ident.C_uncertainty, "N s/m", 1.0),
    ):
        for (i, j), name in zip(np.ndindex(2, 2), ("xx", "xy", "yx", "yy")):
            if np.isfinite(M[i, j]):
                print(f"  {label}{name} = {M[i, j] * scale:10.3f} +- {U[i, j] * scale:.3f} {unit}")
    if ident.caveat:
        print(f"note: {ident.caveat}")
    if not args.csv:
        coeffs = model.coefficients([RPM], amplitude=AMPLITUDE)
        print(
            f"model (coefficient formulas) at {RPM:.0f} rpm: Kxx = {coeffs.K[0][0, 0] * 1e-3:.3f} N/mm, "
            f"Cxx = {coeffs.C[0][0, 0]:.1f} N s/m"
        )
    path = write_json(out / "identified.json", ident.to_dict())
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
