"""What other integrators would pay for one periodic revolution of the valve chain (issue 42).

Run:  python tools/integrator_survey.py [--speeds 600 3000] [--models type-c distributed]

A survey, not a benchmark (it claims no speed of springdyn): for the one-step example spring
on the 3-4-5 cam of 9 mm over 120 cam degrees (the 1000-speed sweeps' case), it starts from a
state on the periodic orbit (three revolutions of SciPy's DOP853 at tight tolerances) and
integrates one revolution at the engine's default tolerances with

- the compiled engine (its pair for the model: Dormand-Prince 5(4) for Type C, Bogacki-Shampine
  3(2) for the 50-element distributed chain);
- SciPy's ``solve_ivp`` methods on the same compiled right-hand side: ``RK45`` (the same
  Dormand-Prince pair, to calibrate SciPy's RMS error norm against the engine's), ``DOP853``
  (explicit, 8th order), and the implicit ``Radau`` (5th order), ``BDF`` and ``LSODA``
  (variable order, stiff switching).

It prints the steps and the right-hand-side evaluations of each, the implicit methods' finite-
difference Jacobians counted apart (``n`` evaluations each, which an analytic banded Jacobian
would replace) with their LU decompositions. The ratio ``rhs / engine`` is what an integrator of
that class would spend in right-hand sides against the engine, before the cost of its linear
algebra; it bounds what replacing the engine's pair could gain per revolution. Results of
2026-11-28 in docs/performance.md ("What another integrator would pay").
"""

from __future__ import annotations

import argparse
import math
import time
import warnings

import numpy as np


def survey(model: str, rpm: float) -> list[tuple]:
    """Rows ``(method, steps, rhs evaluations, Jacobians, LUs, seconds)`` of one revolution."""
    from scipy.integrate import solve_ivp

    from springdyn.numerics.erk import TABLEAUS
    from springdyn.valve import ValveSpring
    from springdyn.valve.cam.definition import Cam
    from springdyn.valve.engine import NO_EXTRA, atol_vector, integrate, model_of, rhs_kernel, train_of
    from springdyn.valve.run import runge_kutta_pair
    from springdyn.valve.run.runner import engine_args, velocity_tolerance
    from springdyn.valve.run.settings import DEFAULT_ATOL, DEFAULT_RTOL, MAX_STEP_FRACTION, RunSettings
    from springdyn.valve.run.setup import prepare

    spring = ValveSpring.example("one-step")
    if model != "type-c":
        spring = spring.with_model(model)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the example's coil-bind fact: not this survey's subject
        setup = prepare(spring, Cam(law="3-4-5", lift=9e-3, duration=math.radians(120)))
    omega = rpm * 2.0 * math.pi / 60.0
    period = 2.0 * math.pi / omega
    args = engine_args(setup, omega)
    m = model_of(args)
    vt = train_of(setup.vt)
    rhs = rhs_kernel(m)
    n = setup.y0.size
    v_atol = velocity_tolerance(setup, DEFAULT_ATOL)
    atol = atol_vector(n, DEFAULT_ATOL, v_atol)

    def fun(t, y):
        d = np.empty(n)
        rhs(t, y, m, omega, vt, d, NO_EXTRA)
        return d

    y = setup.y0.copy()
    for k in range(3):  # onto the periodic orbit
        y = solve_ivp(fun, (k * period, (k + 1) * period), y, method="DOP853", rtol=1e-9, atol=atol * 1e-2).y[:, -1]
    t0, t1 = 3.0 * period, 4.0 * period
    rows = []
    pair = runge_kutta_pair(setup, RunSettings())
    stages = TABLEAUS[pair].c.shape[0] - 1  # right-hand sides a step (first same as last)

    def engine():
        return integrate(
            y,
            np.array([t0, t1]),
            args,
            rtol=DEFAULT_RTOL,
            atol=DEFAULT_ATOL,
            h_max=MAX_STEP_FRACTION * period,
            atol_velocity=v_atol,
            method=pair,
        )

    engine()  # compile or load first
    start = time.perf_counter()
    _, info = engine()
    wall = time.perf_counter() - start
    rows.append((f"engine {pair}", info["steps"], (info["steps"] + info["rejected"]) * stages, 0, 0, wall))
    for method in ("RK45", "DOP853", "Radau", "BDF", "LSODA"):
        start = time.perf_counter()
        sol = solve_ivp(fun, (t0, t1), y, method=method, rtol=DEFAULT_RTOL, atol=atol)
        wall = time.perf_counter() - start
        # LSODA's count (ODEPACK's NFE) includes its finite-difference Jacobians' evaluations,
        # SciPy's Radau and BDF leave them out of ``nfev``
        nfev = sol.nfev - sol.njev * n if method == "LSODA" else sol.nfev
        rows.append((method, sol.t.size - 1, nfev, sol.njev, sol.nlu, wall))
    return rows


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--speeds", type=float, nargs="+", default=[600.0, 3000.0], help="cam speeds [rpm]")
    p.add_argument("--models", nargs="+", default=["type-c", "distributed"], choices=["type-c", "distributed"])
    a = p.parse_args(argv)
    from springdyn.valve.run.settings import DEFAULT_ATOL, DEFAULT_RTOL

    print(
        f"one revolution on the periodic orbit, rtol {DEFAULT_RTOL:g}, atol {DEFAULT_ATOL:g} m (the engine's defaults)"
    )
    print(
        f"{'model':12s} {'cam rpm':>7s} {'method':14s} {'steps':>7s} {'rhs':>8s} {'rhs/engine':>10s} "
        f"{'Jacobians':>9s} {'LUs':>6s} {'time [s]':>8s}"
    )
    for model in a.models:
        for rpm in a.speeds:
            rows = survey(model, rpm)
            ref = rows[0][2]
            for method, steps, nfev, njev, nlu, wall in rows:
                print(
                    f"{model:12s} {rpm:7.0f} {method:14s} {steps:7d} {nfev:8d} {nfev / ref:10.2f} "
                    f"{njev:9d} {nlu:6d} {wall:8.3f}"
                )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
