"""Where MMS Type C agrees with the distributed model: the agreement map of docs/which-model.md.

Both example springs (docs/references.md) run on a 3-4-5 cam of 120 cam degrees at the cam
lifts that stay above solid (the coil-bind check drops the others: 9 mm drives the two-step
spring past solid) from 500 to 4000 cam rpm, each speed to its periodic steady state, once
with the Type C model and once with the distributed model (50 elements, the criteria model).
Per (lift, speed) the script takes the Type C minus distributed difference of the peak and
minimum retainer force and of the peak and minimum seat force, each model's force in % of its
own set-up force Fset, and calls the largest of the four (in magnitude) the force error. It
also compares the two verdicts of a spring alone: end separation (minimum retainer force at
or below zero) and coil clash (the sweep table's ``coil_clash``).

It prints the static forces of both models (installed length and full lift), then per spring
and lift the highest speed up to which the force error stays within 5 % and 10 % of Fset
(Type C's valid range) and the first speed where a verdict differs, and writes
``model_agreement.csv`` (one row per spring, lift and speed) and ``model_agreement.png`` (the
force error over speed and lift, one panel per spring).

Run:  python examples/valve/model_agreement.py [--out DIR] [--step RPM] [--workers N]
"""

from __future__ import annotations

import argparse
import tempfile
import warnings
from pathlib import Path

import numpy as np

from springdyn import InputError
from springdyn.core.io import write_csv
from springdyn.core.plotting import new_figure, save_figure
from springdyn.valve import Cam, ValveSpring, sweep
from springdyn.valve.spring.solid_length import check_coil_bind

SPRINGS = ("one-step", "two-step")
#: Candidate cam lifts [m]; those that drive a spring past solid are dropped.
LIFTS = (5e-3, 6e-3, 7e-3, 8e-3, 9e-3)
#: Cam duration [rad].
DURATION = np.radians(120.0)
#: The two models: Type C first (the difference is Type C minus distributed).
MODELS = ("type-c", "distributed")
#: The four compared forces: sweep-table column stem.
FORCES = ("max_retainer_force", "min_retainer_force", "max_seat_force", "min_seat_force")
#: Force-error limits [% of Fset] of the printed table and the map's contour lines.
LIMITS = (5.0, 10.0)
#: Engine revolutions per cam revolution (four-stroke).
ENGINE_PER_CAM = 2.0


def usable_lifts(name: str, lifts=LIFTS) -> tuple[list, dict]:
    """The lifts that keep the spring above solid.

    Parameters
    ----------
    name : str
        Example spring name [-].
    lifts : sequence of float
        Candidate cam lifts [m].

    Returns
    -------
    kept : list of float
        The lifts the coil-bind check accepts [m].
    refused : dict
        Refused lift [m] -> the check's message.
    """
    spring = ValveSpring.example(name)
    kept, refused = [], {}
    for lift in lifts:
        try:
            check_coil_bind(spring, lift, f"the cam lift {lift * 1e3:g} mm")
            kept.append(lift)
        except InputError as exc:
            refused[lift] = str(exc)
    return kept, refused


def static_forces(name: str, lifts) -> dict:
    """Static force of each model at the installed length and at each full lift.

    Parameters
    ----------
    name : str
        Example spring name [-].
    lifts : sequence of float
        Cam lifts [m].

    Returns
    -------
    dict
        ``{model: {"Fset": [N], "installed": [N], "full_lift": [N] per lift}}``.
    """
    spring = ValveSpring.example(name)
    out = {}
    for model in MODELS:
        chain = spring.with_model(model).spring_model
        out[model] = dict(
            Fset=float(chain.internal_parameters()["Fset"]),
            installed=float(chain.static_force(spring.installed_length)),
            full_lift=[float(chain.static_force(spring.installed_length - lift)) for lift in lifts],
        )
    return out


def compare(name: str, lift: float, cam_rpm, workers=None) -> dict:
    """Both models of one spring on one cam lift over the speeds: the agreement columns.

    Parameters
    ----------
    name : str
        Example spring name [-].
    lift : float
        Cam lift [m].
    cam_rpm : array_like
        Cam speeds [rev/min].
    workers : int, optional
        Local threads of each sweep [-] (default: both cores).

    Returns
    -------
    dict
        Equal-length columns, SI with the unit in the name; the differences and the force
        error in % of Fset, each model's force divided by its own Fset.
    """
    spring = ValveSpring.example(name)
    cam = Cam(law="3-4-5", lift=lift, duration=DURATION)
    rpm = np.asarray(cam_rpm, dtype=float)
    cols = dict(spring=np.full(rpm.size, name), lift_m=np.full(rpm.size, lift), cam_rpm=rpm)
    cols["engine_rpm"] = ENGINE_PER_CAM * rpm
    rel = {}
    for model in MODELS:
        variant = spring.with_model(model)
        fset = float(variant.spring_model.internal_parameters()["Fset"])
        table = sweep(variant, cam, rpm, workers=workers).summary_table()
        key = model.replace("-", "_")
        cols[f"{key}_Fset_N"] = np.full(rpm.size, fset)
        for force in (*FORCES, "max_static_force"):
            cols[f"{key}_{force}_N"] = table[f"{force}_N"]
        rel[model] = {force: 100.0 * table[f"{force}_N"] / fset for force in (*FORCES, "max_static_force")}
        cols[f"{key}_end_separation"] = table["min_retainer_force_N"] <= 0.0
        cols[f"{key}_coil_clash"] = np.asarray(table["coil_clash"], bool)
        cols[f"{key}_periodic"] = np.asarray(table["periodic"], bool)
    for force in (*FORCES, "max_static_force"):
        cols[f"{force}_diff_percent_Fset"] = rel["type-c"][force] - rel["distributed"][force]
    cols["force_error_percent_Fset"] = np.max([np.abs(cols[f"{f}_diff_percent_Fset"]) for f in FORCES], axis=0)
    cols["separation_differs"] = cols["type_c_end_separation"] != cols["distributed_end_separation"]
    cols["clash_differs"] = cols["type_c_coil_clash"] != cols["distributed_coil_clash"]
    cols["verdicts_differ"] = cols["separation_differs"] | cols["clash_differs"]
    return cols


def agreement_table(lifts: dict, cam_rpm, workers=None) -> dict:
    """:func:`compare` for every spring and lift, stacked into one table.

    Parameters
    ----------
    lifts : dict
        Example spring name -> its cam lifts [m].
    cam_rpm : array_like
        Cam speeds [rev/min].
    workers : int, optional
        Local threads of each sweep [-].
    """
    parts = [compare(name, lift, cam_rpm, workers) for name, ls in lifts.items() for lift in ls]
    return {key: np.concatenate([p[key] for p in parts]) for key in parts[0]}


def rows_of(table: dict, name: str, lift: float) -> np.ndarray:
    """Boolean mask of one spring's rows at one lift, in speed order."""
    return (table["spring"] == name) & np.isclose(table["lift_m"], lift)


def valid_up_to(table: dict, name: str, lift: float, limit: float) -> float:
    """The highest speed up to which the force error stays within ``limit``.

    Parameters
    ----------
    table : dict
        :func:`agreement_table`.
    name : str
        Example spring name [-].
    lift : float
        Cam lift [m].
    limit : float
        Force-error limit [% of Fset].

    Returns
    -------
    float
        Cam speed [rev/min]: the last speed before the first one beyond ``limit`` (the
        highest speed if none is beyond); NaN if the lowest speed is already beyond.
    """
    m = rows_of(table, name, lift)
    rpm, err = table["cam_rpm"][m], table["force_error_percent_Fset"][m]
    beyond = np.flatnonzero(err > limit)
    if beyond.size == 0:
        return float(rpm[-1])
    return float(rpm[beyond[0] - 1]) if beyond[0] > 0 else float("nan")


def first_verdict_difference(table: dict, name: str, lift: float) -> str:
    """The first speed where a verdict differs, in words ("none" if none does)."""
    m = rows_of(table, name, lift)
    idx = np.flatnonzero(table["verdicts_differ"][m])
    if idx.size == 0:
        return "none"
    i = idx[0]
    rpm = table["cam_rpm"][m][i]
    what = []
    for verdict, key in (("coil clash", "coil_clash"), ("end separation", "end_separation")):
        tc, di = table[f"type_c_{key}"][m][i], table[f"distributed_{key}"][m][i]
        if tc != di:
            what.append(f"{verdict}: {'Type C' if tc else 'distributed'} only")
    return f"{rpm:.0f} cam rpm ({'; '.join(what)})"


def plot(table: dict, lifts: dict, path: Path) -> Path:
    """The force error over speed and lift, one panel per spring, with the 5 % and 10 %
    contours and markers where a verdict differs."""
    fig, axes = new_figure(1, len(lifts), figsize=(10.0, 4.6))
    axes = np.atleast_1d(axes)
    vmax = 30.0
    for ax, (name, ls) in zip(axes, lifts.items()):
        rpm = table["cam_rpm"][rows_of(table, name, ls[0])]
        z = np.array([table["force_error_percent_Fset"][rows_of(table, name, lift)] for lift in ls])
        y = 1e3 * np.asarray(ls)
        mesh = ax.pcolormesh(rpm, y, z, shading="nearest", cmap="viridis", vmin=0.0, vmax=vmax)
        if len(ls) > 1 and rpm.size > 1:
            cs = ax.contour(rpm, y, z, levels=list(LIMITS), colors=["white", "red"], linewidths=1.5)
            ax.clabel(cs, fmt="%g %%", fontsize=9)
        for key, marker, label in (
            ("type_c", "v", "coil clash: Type C only"),
            ("distributed", "^", "coil clash: distributed only"),
        ):
            other = "distributed" if key == "type_c" else "type_c"
            hits = [
                (r, 1e3 * lift)
                for lift in ls
                for r, a, b in zip(
                    rpm,
                    table[f"{key}_coil_clash"][rows_of(table, name, lift)],
                    table[f"{other}_coil_clash"][rows_of(table, name, lift)],
                )
                if a and not b
            ]
            if hits:
                hx, hy = zip(*hits)
                ax.scatter(hx, hy, marker=marker, s=28, facecolor="none", edgecolor="k", label=label)
        sep = [
            (r, 1e3 * lift)
            for lift in ls
            for r, d in zip(rpm, table["separation_differs"][rows_of(table, name, lift)])
            if d
        ]
        if sep:
            sx, sy = zip(*sep)
            ax.scatter(sx, sy, marker="x", s=28, color="k", label="end separation differs")
        ax.set_title(f"{name} spring", fontsize=11)
        ax.set_xlabel("cam speed [rpm]")
        ax.set_yticks(y)
        ax.set_ylim(1e3 * (min(LIFTS) - 5e-4), 1e3 * (max(LIFTS) + 5e-4))
        top = ax.secondary_xaxis("top", functions=(lambda x: ENGINE_PER_CAM * x, lambda x: x / ENGINE_PER_CAM))
        top.set_xlabel("engine speed [rpm], four-stroke")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8, loc="lower left", framealpha=0.8)
    axes[0].set_ylabel("cam lift [mm]")
    fig.colorbar(mesh, ax=list(axes), extend="max", label="force error, Type C - distributed [% of Fset]")
    fig.suptitle("Type C against the distributed model, 3-4-5 cam, 120 cam deg", fontsize=12)
    return save_figure(fig, path, dpi=100)


def print_statics(lifts: dict) -> None:
    """Static forces of both models: installed length and each full lift."""
    print("static force [N] (% of the model's own Fset)")
    for name, ls in lifts.items():
        st = static_forces(name, ls)
        tc, di = st["type-c"], st["distributed"]
        print(f"{name}: installed Type C {tc['installed']:.1f}, distributed {di['installed']:.1f}")
        for k, lift in enumerate(ls):
            a, b = tc["full_lift"][k], di["full_lift"][k]
            print(
                f"  full lift {lift * 1e3:g} mm: Type C {a:.1f} ({100 * a / tc['Fset']:.1f} %), "
                f"distributed {b:.1f} ({100 * b / di['Fset']:.1f} %)"
            )


def first_speed(table: dict, name: str, lift: float, column: str) -> str:
    """The first speed where a boolean column is true, in words ("none" if never)."""
    m = rows_of(table, name, lift)
    idx = np.flatnonzero(table[column][m])
    return f"{table['cam_rpm'][m][idx[0]]:.0f} cam rpm" if idx.size else "none"


def print_agreement(table: dict, lifts: dict) -> None:
    """Per spring and lift: Type C's valid range, then the verdicts of both models."""
    print(
        f"{'spring':9s} {'lift [mm]':>9s} {'within 5 % up to':>17s} {'within 10 % up to':>18s} "
        f"{'error at 500':>12s} {'largest error':>24s}"
    )
    for name, ls in lifts.items():
        for lift in ls:
            m = rows_of(table, name, lift)
            err, rpm = table["force_error_percent_Fset"][m], table["cam_rpm"][m]
            upto = [valid_up_to(table, name, lift, limit) for limit in LIMITS]
            text = ["none" if np.isnan(u) else f"{u:.0f} cam rpm" for u in upto]
            i = int(np.argmax(err))
            print(
                f"{name:9s} {lift * 1e3:9g} {text[0]:>17s} {text[1]:>18s} {err[0]:10.1f} % "
                f"{err[i]:8.1f} % at {rpm[i]:4.0f} cam rpm"
            )
    print(
        f"{'spring':9s} {'lift [mm]':>9s} {'Type C clash from':>18s} {'distributed from':>17s}  "
        "first verdict difference"
    )
    for name, ls in lifts.items():
        for lift in ls:
            clash = [first_speed(table, name, lift, f"{model}_coil_clash") for model in ("type_c", "distributed")]
            print(
                f"{name:9s} {lift * 1e3:9g} {clash[0]:>18s} {clash[1]:>17s}  "
                f"{first_verdict_difference(table, name, lift)}"
            )


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="output folder (default: a new temporary folder)")
    parser.add_argument("--step", type=float, default=100.0, help="speed step [cam rpm] (default 100)")
    parser.add_argument("--workers", type=int, default=None, help="threads per sweep (default: both cores)")
    args = parser.parse_args(argv)
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="springdyn-agreement-"))
    out.mkdir(parents=True, exist_ok=True)
    # the example springs sit below EN 13906-1's coil-bind clearance at the larger lifts (on purpose)
    warnings.filterwarnings("ignore", message="coil bind: .* less than the coil-bind clearance")

    lifts = {}
    for name in SPRINGS:
        lifts[name], refused = usable_lifts(name)
        for lift, why in refused.items():
            print(f"{name}: {lift * 1e3:g} mm dropped: {why.split(';')[0]}")
    print_statics(lifts)
    rpm = np.arange(500.0, 4000.0 + 0.5 * args.step, args.step)
    table = agreement_table(lifts, rpm, args.workers)
    print("force error: largest |Type C - distributed| of peak/min retainer and seat force, % of each model's Fset")
    print_agreement(table, lifts)
    for model in ("type_c", "distributed"):
        print(
            f"{model}: end separation at {int(table[f'{model}_end_separation'].sum())} of {rpm.size * sum(map(len, lifts.values()))} runs"
        )
    print(f"wrote {write_csv(out / 'model_agreement.csv', table)}")
    print(f"wrote {plot(table, lifts, out / 'model_agreement.png')}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
