"""Natural frequencies of spring and valve train under the cam, and the resonance speeds.

The same element and contact laws as the simulation, linearised by central differences of
the accelerations at static equilibrium, on the base circle and at full lift.
"""

import math

import numpy as np

from .cam import Cam
from .engine.layout import VT_LASH, VT_M_LEVER, VT_M_LIFTER, VT_MASS
from .setup import SimulationSetup, prepare
from .spring import ValveSpring
from .valvetrain import ValveTrain

__all__ = ["natural_frequencies", "resonance_speeds"]


def _static_accelerations(setup: SimulationSetup, theta: float, u: np.ndarray) -> np.ndarray:
    """Accelerations [m/s^2] of the masses at rest at positions ``u`` [m], cam at ``theta`` [rad]."""
    from .engine import NO_EXTRA, chain_rhs, model_of, train_of

    nf = setup.nfree
    omega = 1e-9  # quasi-static: the cam's velocity terms vanish
    y = np.concatenate([u, np.zeros(nf)])
    out = np.empty(2 * nf)
    chain_rhs(theta / omega, y, model_of(setup.args(omega)), omega, train_of(setup.vt), out, NO_EXTRA)
    return out[nf:]


def _frequencies(setup: SimulationSetup, theta: float, u: np.ndarray, dofs: np.ndarray, count: int) -> list:
    """Natural frequencies [Hz] of the system linearised at rest at ``u`` (central differences
    of the accelerations over the degrees of freedom ``dofs``; the others held)."""
    from scipy.linalg import eigvals

    h = 1e-9
    jac = np.empty((dofs.size, dofs.size))
    for c, j in enumerate(dofs):
        up, dn = u.copy(), u.copy()
        up[j] += h
        dn[j] -= h
        jac[:, c] = (_static_accelerations(setup, theta, up)[dofs] - _static_accelerations(setup, theta, dn)[dofs]) / (
            2 * h
        )
    w2 = np.sort(np.real(eigvals(-jac)))
    w2 = w2[w2 > (2 * math.pi * 1.0) ** 2]  # rigid-body (unloaded) motions have none
    return [float(math.sqrt(v) / (2 * math.pi)) for v in w2[:count]]


def natural_frequencies(spring: ValveSpring, cam: Cam, valve_train: ValveTrain | None = None, count: int = 8) -> dict:
    """Natural frequencies of spring and valve train, linearised on the base circle and at full lift.

    The same element and contact laws as the simulation (:func:`springdyn.valve.engine.chain_rhs`),
    linearised by central differences of the accelerations at static equilibrium: on the
    base circle (the initial state of :func:`simulate`) and at the cam's largest lift (the
    static equilibrium found from the rigid-train guess).  With a mechanical lash the lever
    and lifter rest unloaded on the base circle: their modes are not defined there and
    only the spring and the seated valve are linearised (a note says so).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain, optional
        Without it, the spring alone between the seat and the cam-driven retainer.
    count : int
        Frequencies to return per state [-].

    Returns
    -------
    dict
        ``base_circle_Hz``, ``full_lift_Hz`` (ascending lists), ``full_lift_cam_angle_deg``,
        ``notes``.
    """
    from scipy.optimize import root

    setup = prepare(spring, cam, valve_train)
    nf = setup.nfree
    nm = setup.n_masses
    notes = []
    u0 = setup.y0[:nf]
    dofs = np.arange(nf)
    if valve_train is not None and not valve_train.hydraulic and valve_train.lash > 0 and nf > nm + 1:
        dofs = np.arange(nm + 1)
        notes.append(
            "base circle: the lash is open and the lever/lifter rest unloaded on the cam; only the spring "
            "and the seated valve are linearised there"
        )
    base = _frequencies(setup, 0.0, u0, dofs, count)
    i_max = int(np.argmax(setup.table.h))
    theta = i_max * setup.table.dth
    h_max = float(setup.table.h[i_max])
    # rigid-train guess, then the static equilibrium of every mass
    sp_setup = spring.free_length - spring.installed_length
    if valve_train is None:
        z = h_max
        guess = spring.spring_model.initial_condition(sp_setup + z)["displacements"]
    else:
        f = float(setup.static_force(valve_train.ratio * h_max))
        z = valve_train.ratio * h_max - setup.vt[VT_LASH] - f / valve_train.stiffness_at_valve
        guess = np.concatenate(
            [
                spring.spring_model.initial_condition(sp_setup + z)["displacements"],
                valve_train.static_state(h_max, z, f),
            ]
        )
    scale = max(h_max, 1e-3)
    mass = np.asarray(spring.spring_model.chain.masses, dtype=float)
    if valve_train is not None:
        mass = np.concatenate([mass, [setup.vt[VT_MASS], setup.vt[VT_M_LEVER], setup.vt[VT_M_LIFTER]][: nf - nm]])

    def residual(x):  # forces [N]: better scaled than accelerations across light and heavy masses
        return _static_accelerations(setup, theta, x * scale) * mass

    sol = root(residual, guess / scale, method="hybr", options=dict(xtol=1e-14, maxfev=200 * (nf + 1)))
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-6 * spring.spring_model.internal_parameters()["Fset"]:
        sol = root(residual, guess / scale, method="lm", options=dict(xtol=1e-15, ftol=1e-15, maxiter=200 * (nf + 1)))
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-6 * spring.spring_model.internal_parameters()["Fset"]:
        notes.append(f"full lift: the static equilibrium was not found ({sol.message}); its frequencies are omitted")
        full = []
    else:
        full = _frequencies(setup, theta, sol.x * scale, np.arange(nf), count)
    return dict(base_circle_Hz=base, full_lift_Hz=full, full_lift_cam_angle_deg=math.degrees(theta), notes=notes)


def resonance_speeds(frequencies, cam_rpm_min: float, cam_rpm_max: float, max_order: int = 20) -> list:
    """Cam speeds where a cam harmonic meets a natural frequency: ``60 f / N`` [rev/min].

    Parameters
    ----------
    frequencies : sequence of float
        Natural frequencies [Hz].
    cam_rpm_min, cam_rpm_max : float
        Speed range [rev/min].
    max_order : int
        Highest cam order ``N`` [-] (20: higher harmonics of a valve-train cam are weak).

    Returns
    -------
    list of dict
        ``mode`` (1-based), ``frequency_Hz``, ``order``, ``cam_rpm``, ascending in speed.

    Examples
    --------
    >>> [r["cam_rpm"] for r in resonance_speeds([450.0], 2000, 3000)]
    [2076.923076923077, 2250.0, 2454.5454545454545, 2700.0, 3000.0]
    """
    rows = []
    for m, f in enumerate(frequencies, start=1):
        for n in range(1, max_order + 1):
            rpm = 60.0 * f / n
            if cam_rpm_min <= rpm <= cam_rpm_max:
                rows.append(dict(mode=m, frequency_Hz=float(f), order=n, cam_rpm=rpm))
    return sorted(rows, key=lambda r: r["cam_rpm"])
