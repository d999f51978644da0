"""Natural frequencies of spring and valve train under the cam, and the resonance speeds.

The same element and contact laws as the simulation, linearised by central differences of
the accelerations at static equilibrium: with the cam contact closed, on the base circle and
at full lift (:func:`natural_frequencies`); with it open, the separated train held at a
valve lift (:func:`separated_frequencies`, the "jump" frequency of float).
"""

import math

import numpy as np

from ...core.errors import InputError, SolverError
from ...core.results import text_table
from ..cam.definition import Cam
from ..engine import NO_EXTRA, chain_rhs, model_of, train_of
from ..engine.layout import VT_LASH, VT_M_LEVER, VT_M_LIFTER, VT_MASS
from ..spring.definition import ValveSpring
from ..train.definition import ValveTrain
from .runner import engine_args
from .setup import SimulationSetup, prepare, static_force_at_lift

__all__ = ["natural_frequencies", "separated_frequencies", "separated_train_text", "resonance_speeds"]


def _static_accelerations(setup: SimulationSetup, theta: float, u: np.ndarray) -> np.ndarray:
    """Accelerations [m/s^2] of the masses at rest at positions ``u`` [m], cam at ``theta`` [rad]."""
    nf = setup.nfree
    omega = 1e-9  # quasi-static: the cam's velocity terms vanish
    y = np.concatenate([u, np.zeros(nf)])
    out = np.empty(2 * nf)
    chain_rhs(theta / omega, y, model_of(engine_args(setup, omega)), omega, train_of(setup.vt), out, NO_EXTRA)
    return out[nf:]


def _frequencies(setup: SimulationSetup, theta: float, u: np.ndarray, dofs: np.ndarray, count: int) -> list:
    """Natural frequencies [Hz] of the system linearised at rest at ``u`` (central differences
    of the accelerations over the degrees of freedom ``dofs``; the others held)."""
    h = 1e-9
    jac = np.empty((dofs.size, dofs.size))
    for c, j in enumerate(dofs):
        up, dn = u.copy(), u.copy()
        up[j] += h
        dn[j] -= h
        jac[:, c] = (_static_accelerations(setup, theta, up)[dofs] - _static_accelerations(setup, theta, dn)[dofs]) / (
            2 * h
        )
    from scipy.linalg import eigvals  # (here: 0.5 s of every run's start-up)

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

    See Also
    --------
    separated_frequencies : the same train with the cam contact open (the jump frequency).
    """
    notes = []
    if valve_train is not None and valve_train.adjuster_placement:
        notes.append(f"adjuster: {valve_train.adjuster_placement}")
    with_hla = valve_train  # the train with its adjuster's dynamics (None: no [hla])
    if valve_train is not None and valve_train.hla is not None:
        valve_train = valve_train.without_hla_dynamics()  # the base circle: the supply pressure
    else:
        with_hla = None
    setup = prepare(spring, cam, valve_train)
    nf = setup.nfree
    nm = setup.n_masses
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
    if with_hla is not None:
        # full lift: the oil column at the chamber pressure that carries the full-lift force
        # (issue 40: at the supply pressure it was 3.3 N/um at the valve instead of ~66 N/um)
        f_lift = float(static_force_at_lift(setup, valve_train.ratio * h_max))
        base_k = valve_train.hla_stiffness
        valve_train = with_hla.without_hla_dynamics(valve_force=f_lift)
        setup = prepare(spring, cam, valve_train)
        notes.append(
            "the hydraulic lash adjuster is linearised as its oil column with the plunger-spring preload: "
            f"{base_k / 1e6:.3g} N/um at the valve on the base circle (the supply pressure), "
            f"{valve_train.hla_stiffness / 1e6:.3g} N/um at full lift (the chamber at "
            f"{with_hla.hla_chamber_pressure(f_lift) / 1e5:.3g} bar carries {f_lift:.0f} N at the valve)"
        )
    # rigid-train guess, then the static equilibrium of every mass
    sp_setup = spring.free_length - spring.installed_length
    if valve_train is None:
        z = h_max
        guess = spring.spring_model.initial_condition(sp_setup + z)["displacements"]
    else:
        f = float(static_force_at_lift(setup, valve_train.ratio * h_max))
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

    from scipy.optimize import root  # (here: 0.5 s of every run's start-up)

    sol = root(residual, guess / scale, method="hybr", options=dict(xtol=1e-14, maxfev=200 * (nf + 1)))
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-6 * spring.spring_model.internal_parameters()["Fset"]:
        sol = root(residual, guess / scale, method="lm", options=dict(xtol=1e-15, ftol=1e-15, maxiter=200 * (nf + 1)))
    if not sol.success or np.max(np.abs(residual(sol.x))) > 1e-6 * spring.spring_model.internal_parameters()["Fset"]:
        notes.append(f"full lift: the static equilibrium was not found ({sol.message}); its frequencies are omitted")
        full = []
    else:
        full = _frequencies(setup, theta, sol.x * scale, np.arange(nf), count)
    return dict(base_circle_Hz=base, full_lift_Hz=full, full_lift_cam_angle_deg=math.degrees(theta), notes=notes)


def _contacts(setup: SimulationSetup, theta: float, u: np.ndarray) -> tuple:
    """Cam contact force [N], valve-seat force [N] and signed cam gap [m] (negative: open)
    of the masses at rest at positions ``u`` [m], cam at ``theta`` [rad]."""
    nf = setup.nfree
    omega = 1e-9
    lay = setup.layout
    extra = np.zeros(lay["size"])
    out = np.empty(2 * nf)
    y = np.concatenate([u, np.zeros(nf)])
    chain_rhs(theta / omega, y, model_of(engine_args(setup, omega)), omega, train_of(setup.vt), out, extra)
    return float(extra[lay["cam_contact_force"]]), float(extra[lay["valve_seat_force"]]), float(extra[lay["cam_gap"]])


def separated_frequencies(
    spring: ValveSpring,
    cam: Cam,
    valve_train: ValveTrain | None,
    count: int = 8,
    valve_lift: float | None = None,
) -> dict:
    """Natural frequencies of the separated valve train: the cam contact open, the valve off its seat.

    In float the follower leaves the cam and the follower system -- valve, retainer and
    follower (direct-acting: one rigid body), the lever (rocker, finger follower: its inertia
    and the roller referred to the valve tip) and the lifter with half the pushrod (pushrod
    layout), joined by their links -- oscillates on the spring alone, without the cam.  Its
    first natural frequency is the *jump frequency* of the classic "free lifter" hand model,
    ``sqrt(k / (M + m_s / 3)) / (2 pi)`` for a valve-side mass ``M`` on a spring of rate
    ``k`` and mass ``m_s``; here the spring is its chain (Type C or distributed, with its
    tangent element rates at the lift) and the links are the simulation's own.

    The state linearised: the train held statically at ``valve_lift`` by the cam force at
    the follower (every chain mass and link in static equilibrium, the links compressed by
    the spring force), then the cam moved away -- the engine's equations evaluated at the
    cam's lowest lift, where the unilateral cam contact is open -- so that the Jacobian
    (central differences of the accelerations, as :func:`natural_frequencies`) has no cam
    contact stiffness; the seat is open since the valve is lifted.

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
        Sets the default lift (and is checked against coil contact, as for a run).
    valve_train : ValveTrain
        Required: without a valve train the retainer end has no mass of its own (it follows
        the cam), so nothing is left to oscillate once the cam lets go.
    count : int
        Frequencies to return [-].
    valve_lift : float, optional
        Valve lift of the held state [m], above 0 (off the seat).  Default: full lift, the
        valve lift of the static equilibrium at the cam's largest lift with the contact
        closed (the rigid train's lift less the lash and the train's elastic deflection).

    Returns
    -------
    dict
        ``frequencies_Hz`` (ascending list) [Hz], ``jump_frequency_Hz`` (the first of them)
        [Hz], ``valve_lift_m`` [m], ``spring_force_N`` (static spring force at that lift) [N].

    Raises
    ------
    InputError
        Without a valve train; for a valve lift that is not above 0 (or so small that the
        follower still touches the cam's lowest lift) or that drives the spring beyond its
        range; when the cam never lifts the valve off its seat.
    SolverError
        When the held static state is not found.

    See Also
    --------
    natural_frequencies : the train with the cam contact closed.
    """
    if valve_train is None:
        raise InputError(
            "separated-train modes (cam contact open) need a valve train: without one the retainer "
            "end follows the cam and has no mass of its own, so nothing is left to oscillate once "
            "the cam lets go; give a valve train (--valve-train / [valve_train])"
        )
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)) or count < 1:
        raise InputError(f"count = {count!r} must be a whole number of at least 1")
    valve_train = valve_train.without_hla_dynamics()  # linearised: the adjuster's oil column
    setup = prepare(spring, cam, valve_train)
    nf = setup.nfree
    nm = setup.n_masses
    r = valve_train.ratio
    lash = float(setup.vt[VT_LASH])
    k_train = valve_train.stiffness_at_valve
    sp_setup = spring.free_length - spring.installed_length
    fset = spring.spring_model.internal_parameters()["Fset"]

    def force(z):
        return float(static_force_at_lift(setup, z))

    if valve_lift is None:
        top = r * float(np.max(setup.table.h)) - lash  # the rigid train's valve lift
        if not top > 0.0:
            raise InputError(
                f"the cam never lifts the valve off its seat (largest valve lift {r * np.max(setup.table.h) * 1e3:.4g} mm "
                f"against the lash {lash * 1e3:.4g} mm): give a valve lift (valve_lift, --valve-lift)"
            )
        # static equilibrium of the closed train at full lift: k_train (top - z) = F(z)
        from scipy.optimize import brentq  # (here: 0.5 s of every run's start-up)

        z = brentq(
            lambda z: k_train * (top - z) - force(z), top - (force(top) + fset) / k_train - 1e-9, top, xtol=1e-16
        )
        what = "the full-lift valve lift"
    else:
        z = float(valve_lift)
        what = "valve_lift ="
    if not (math.isfinite(z) and z > 0.0):
        raise InputError(
            f"{what} {z * 1e3:.4g} mm must be above 0: the separated train is linearised with the valve off its seat"
        )
    length = spring.installed_length - z
    if length < spring.spring_model.min_length:
        raise InputError(
            f"{what} {z * 1e3:.4g} mm drives the spring to {length * 1e3:.4g} mm, below "
            f"{spring.spring_model.min_length * 1e3:.4g} mm, the shortest length the model evaluates"
        )
    theta = int(np.argmin(setup.table.h)) * setup.table.dth  # the cam's lowest lift: its contact open
    f = force(z)
    lobe = (z + lash + f / k_train) / r  # the lobe lift that would hold the valve at z
    guess = np.concatenate(
        [spring.spring_model.initial_condition(sp_setup + z)["displacements"], valve_train.static_state(lobe, z, f)]
    )
    scale = max(z, 1e-3)
    mass = np.concatenate(
        [
            np.asarray(spring.spring_model.chain.masses, dtype=float),
            [setup.vt[VT_MASS], setup.vt[VT_M_LEVER], setup.vt[VT_M_LIFTER]][: nf - nm],
        ]
    )
    held = nf - 1  # the follower at the cam: valve (direct-acting), lever tip (rocker), lifter (pushrod)

    def residual(x):  # forces [N]; the follower's own balance (the cam force) becomes "valve at z"
        res = _static_accelerations(setup, theta, x * scale) * mass
        res[held] = (x[nm] * scale - z) * k_train
        return res

    from scipy.optimize import root  # (here: 0.5 s of every run's start-up)

    sol = root(residual, guess / scale, method="hybr", options=dict(xtol=1e-14, maxfev=200 * (nf + 1)))
    x = sol.x * scale
    if not np.max(np.abs(residual(sol.x))) <= 1e-6 * fset:
        raise SolverError(
            f"separated train: the held static state at valve lift {z * 1e3:.4g} mm was not found ({sol.message})"
        )
    f_cam, f_seat, gap = _contacts(setup, theta, x)
    if not (f_cam == 0.0 and f_seat == 0.0 and gap < -1e-8 and x[nm] > 1e-8):  # open beyond the differences' 1 nm
        raise InputError(
            f"{what} {z * 1e3:.4g} mm is too small for the separated train: the valve or its follower "
            "still touches the seat or the cam's lowest lift; give a larger lift"
        )
    freqs = _frequencies(setup, theta, x, np.arange(nf), count)
    return dict(frequencies_Hz=freqs, jump_frequency_Hz=freqs[0], valve_lift_m=z, spring_force_N=f)


def separated_train_text(res: dict) -> str:
    """The separated train's modes in words (what ``springdyn valve train-modes --cam-contact
    open`` prints).

    Parameters
    ----------
    res : dict
        :func:`separated_frequencies`'s result: ``frequencies_Hz``, ``jump_frequency_Hz`` [Hz],
        ``valve_lift_m`` [m], ``spring_force_N`` [N].
    """
    return "\n".join(
        [
            f"separated train (cam contact open, valve off its seat) at valve lift {res['valve_lift_m'] * 1e3:.3f} mm, "
            f"static spring force {res['spring_force_N']:.1f} N",
            text_table(
                [(str(i + 1), f"{f:.1f}") for i, f in enumerate(res["frequencies_Hz"])],
                headers=("mode", "frequency [Hz]"),
            ),
            f"jump frequency (first mode of the separated train): {res['jump_frequency_Hz']:.1f} Hz",
        ]
    )


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
