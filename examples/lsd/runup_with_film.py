"""An unbalance run-up of a ROSS rotor on two Type C dampers with the oil film in the time domain.

A small rotor (two 0.1 m shaft elements, 80 mm, a 0.2 m disk; 18 kg) sits on two Type C
leaf spring dampers (leakage factor 3, no leaf friction: the film alone).  It is run up from
0 to 4000 rpm in 1 s through its bounce critical (~1800 rpm) with two unbalances, and three
answers are compared:

- ROSS's own Newmark run-up with the dampers' small-orbit linearisation
  (``small_orbit_element``: pack stiffness, ``C_visc`` and the passages' added mass ``M_a``);
- ``rotor_time_response(..., film=False)``: the same linear dampers in springdyn's integrator
  of the ROSS matrices (a check of the integrator);
- ``rotor_time_response(..., film=True)``: the film network of each damper (passage inertia,
  cavitation with air release at 0.9 bar absolute, supply at atmospheric pressure) solved
  implicitly with the rotor.

At the small unbalance the three agree (the film stays whole); at the large one the film
ruptures above ~1800 rpm and the disk orbits up to 22 % wider than the linear dampers predict.

Run:  python examples/lsd/runup_with_film.py [--out DIR]
"""

import argparse
import warnings
from pathlib import Path

import numpy as np

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    try:
        import ross as rs
    except ModuleNotFoundError:
        raise SystemExit(
            "this example needs ROSS: pip install 'springdyn[ross]' (or .venv/bin/pip install -e '.[ross]')"
        ) from None

from springdyn.lsd import LSDModel, LSDParameters, rotor_time_response, small_orbit_element, unbalance_runup

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", default=".", help="folder for runup_with_film.png and .csv (default: here)")
out = Path(parser.parse_args().out)
out.mkdir(parents=True, exist_ok=True)

model = LSDModel(LSDParameters.example("C").replace(leakage_factor=3.0, leaf_friction=0.0, cavitation_pressure=0.9e5))
steel = rs.Material(name="steel_lsd_runup_example", rho=7810, E=211e9, G_s=81.2e9)


def rotor(b0, b1):
    shaft = [rs.ShaftElement(0.1, 0.0, 0.08, material=steel) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=steel, width=0.05, i_d=0.08, o_d=0.2)
    return rs.Rotor(shaft, [disk], [b0, b1])


linear = rotor(small_orbit_element(model, 0, tag="a"), small_orbit_element(model, 2, tag="b"))
free = rotor(rs.BearingElement(0, kxx=0.0, cxx=0.0, tag="a"), rs.BearingElement(2, kxx=0.0, cxx=0.0, tag="b"))
dt = 1e-4
t = np.arange(0.0, 1.0 + dt / 2, dt)
d = linear.number_dof  # the disk's x dof (node 1)
print(
    f"rotor {linear.m:.2f} kg; per damper K = {model.stiffness_matrix[0, 0] / 1e3:.1f} N/mm, "
    f"C_visc = {model.viscous_damping[0, 0]:.0f} N s/m, added mass M_a = {model.added_mass[0, 0]:.3f} kg"
)
bands = np.arange(0.0, 4001.0, 500.0)
rows, curves = [], {}
for U in (2e-4, 1e-3):
    speed, F = unbalance_runup(linear.ndof, linear.number_dof, 1, U, t, 0.0, 4000 * np.pi / 30)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        _, y, _ = linear.time_response(speed, F, t, method="newmark")
    ross_r = np.hypot(y[:, d], y[:, d + 1])
    lin = rotor_time_response(free, {0: model, 2: model}, speed, F, t, film=False)
    film = rotor_time_response(free, {0: model, 2: model}, speed, F, t, film=True)
    rpm = speed * 30 / np.pi
    curves[U] = (rpm, ross_r, lin.orbit_radius(1), film.orbit_radius(1))
    print(f"\nunbalance {U * 1e3:g} g m: largest disk orbit per speed band [um]; lowest chamber pressure [bar abs]")
    print("   rpm       ROSS linear   springdyn linear   film   film/linear   p_min")
    for lo, hi in zip(bands[:-1], bands[1:]):
        sel = (rpm >= lo) & (rpm < hi)
        a, b, c = ross_r[sel].max(), curves[U][2][sel].max(), curves[U][3][sel].max()
        pmin = film.pressures[0][sel].min() / 1e5
        print(f"{lo:5.0f}-{hi:<5.0f} {a * 1e6:10.2f} {b * 1e6:14.2f} {c * 1e6:10.2f} {c / a:10.3f} {pmin:9.3f}")
        rows.append((U, lo, hi, a, b, c, pmin * 1e5))

np.savetxt(
    out / "runup_with_film.csv",
    np.array(rows),
    delimiter=",",
    header="unbalance_kg_m,rpm_low,rpm_high,ross_linear_m,springdyn_linear_m,film_m,min_pressure_Pa",
    comments="",
)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
for ax, (U, (rpm, a, b, c)) in zip(axes, curves.items()):
    ax.plot(rpm, a * 1e6, lw=2.5, alpha=0.5, label="ROSS Newmark, linearised dampers")
    ax.plot(rpm, b * 1e6, "--", lw=1, label="springdyn integrator, linearised")
    ax.plot(rpm, c * 1e6, lw=0.8, label="springdyn integrator, film (inertia, cavitation)")
    ax.set_title(f"unbalance {U * 1e3:g} g m")
    ax.set_xlabel("speed [rpm]")
    ax.set_ylabel("disk orbit radius [um]")
    ax.grid(True, alpha=0.3)
axes[0].legend(fontsize=8)
fig.suptitle("Type C (leakage factor 3) run-up 0-4000 rpm in 1 s; air release at 0.9 bar abs")
fig.tight_layout()
fig.savefig(out / "runup_with_film.png", dpi=110)
print(f"\nwrote {out / 'runup_with_film.png'} and {out / 'runup_with_film.csv'}")
