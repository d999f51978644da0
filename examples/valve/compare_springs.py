"""Compare the one-step and the two-step example valve springs over the speed range.

Both springs (docs/references.md) run on the same 3-4-5 cam (7.5 mm lift, 120 cam degrees; 9 mm would drive the two-step spring past solid)
from 500 to 4000 cam rpm.  The script prints, at a few speeds, the peak and minimum
retainer force, the seat force and the surge amplitude (largest departure of the
retainer force from the static force), and writes a comparison plot and the summary
CSV of each sweep.

Run:  python examples/valve/compare_springs.py [--out DIR] [--step RPM]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np

from springdyn.core.io import write_csv
from springdyn.core.plotting import new_figure, save_figure
from springdyn.valve import Cam, ValveSpring, sweep

SPEEDS_SHOWN = (1000.0, 2000.0, 3000.0, 4000.0)


def run_sweeps(step: float) -> dict:
    """Sweep both example springs over 500-4000 cam rpm; return ``{name: summary table}``."""
    cam = Cam(law="3-4-5", lift=0.0075, duration=np.radians(120.0))
    rpm = np.arange(500.0, 4000.0 + 0.5 * step, step)
    out = {}
    for name in ("one-step", "two-step"):
        result = sweep(ValveSpring.example(name), cam, rpm, points_per_revolution=720)
        out[name] = result.summary_table()
    return out


def plot(tables: dict, path: Path) -> Path:
    """Peak and minimum retainer force and surge amplitude vs speed for both springs."""
    fig, (ax1, ax2) = new_figure(2, 1, figsize=(8.0, 7.0), sharex=True)
    for name, t in tables.items():
        (line,) = ax1.plot(t["cam_rpm"], t["max_retainer_force_N"], label=f"{name}: max (dynamic)")
        ax1.plot(
            t["cam_rpm"], t["min_retainer_force_N"], ls="--", color=line.get_color(), label=f"{name}: min (dynamic)"
        )
        ax1.plot(t["cam_rpm"], t["max_static_force_N"], ls=":", color=line.get_color(), label=f"{name}: max (static)")
        ax2.plot(t["cam_rpm"], t["retainer_surge_amplitude_N"], color=line.get_color(), label=name)
    ax1.set_ylabel("retainer force [N]")
    ax1.legend(fontsize=8)
    ax1.grid(True, alpha=0.3)
    ax2.set_xlabel("cam speed [rpm]")
    ax2.set_ylabel("surge amplitude [N]")
    ax2.legend()
    ax2.grid(True, alpha=0.3)
    ax1.set_title("One-step vs two-step valve spring, 3-4-5 cam 7.5 mm / 120 deg")
    return save_figure(fig, path)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="output folder (default: a new temporary folder)")
    parser.add_argument("--step", type=float, default=50.0, help="speed step [cam rpm] (default 50)")
    args = parser.parse_args(argv)
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="springdyn-compare-"))
    out.mkdir(parents=True, exist_ok=True)

    tables = run_sweeps(args.step)
    print(
        f"{'spring':9s} {'cam rpm':>8s} {'max F [N]':>10s} {'min F [N]':>10s} {'static max':>10s} "
        f"{'surge [N]':>10s} {'seat min [N]':>12s} {'coil contact':>12s}"
    )
    for name, t in tables.items():
        write_csv(out / f"sweep_{name}.csv", t)
        for rpm in SPEEDS_SHOWN:
            i = int(np.argmin(np.abs(t["cam_rpm"] - rpm)))
            print(
                f"{name:9s} {t['cam_rpm'][i]:8.0f} {t['max_retainer_force_N'][i]:10.1f} "
                f"{t['min_retainer_force_N'][i]:10.1f} {t['max_static_force_N'][i]:10.1f} "
                f"{t['retainer_surge_amplitude_N'][i]:10.1f} {t['min_seat_force_N'][i]:12.1f} "
                f"{'yes' if t['coil_contact'][i] else 'no':>12s}"
            )
    for name, t in tables.items():
        i = int(np.argmax(t["retainer_surge_amplitude_N"]))
        print(f"{name}: largest surge {t['retainer_surge_amplitude_N'][i]:.1f} N at {t['cam_rpm'][i]:.0f} cam rpm")
    path = plot(tables, out / "compare_springs.png")
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
