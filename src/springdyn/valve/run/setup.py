"""The engine's set-up for one spring, cam and valve train: everything that does not depend
on the speed (document, "Initial condition & position").

:func:`prepare` samples the cam (:data:`~springdyn.valve.run.settings.CAM_SAMPLES` per
revolution), checks the lift against coil contact, finds the initial state (static
equilibrium on the base circle) and writes the valve train's parameter vector (with the gas
force's and a drawn lever's tables); :class:`SimulationSetup` is the record of it, data
only.  Beside it, the functions of a set-up: its static force at a lift
(:func:`static_force`) and along a revolution's output grid (:func:`static_force_along_grid`,
kept for the last few cams), and the check of its speeds against the spring's first surge
mode (:func:`check_speeds`).  The engine runs a set-up through
:func:`springdyn.valve.run.runner.run_speeds`.
"""

import dataclasses
import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from ...core.errors import InputError
from ...core.units import rpm_to_omega
from ..cam.definition import Cam
from ..engine import series_force_compiled
from ..engine.cam_table import CamTable
from ..engine.layout import VT_GAS_N, VT_GEOM_N, VT_SIZE, extra_layout
from ..spring.definition import ValveSpring
from ..spring.pack import SpringPack
from ..spring.solid_length import check_coil_bind
from ..spring.statics import series_force
from ..train.definition import KERNEL_SIZE, ValveTrain
from .settings import CAM_SAMPLES, MAX_CAM_RPM, MIN_EVENT_SURGE_PERIODS

__all__ = [
    "SimulationSetup",
    "prepare",
    "output_angles",
    "static_force_at_lift",
    "static_force_along_grid",
    "check_speeds",
    "with_gas_force",
    "STATIC_CACHE_SIZE",
]

#: Set-ups (spring, cam and output grid) whose static force along the grid is kept
#: (:func:`static_force_along_grid`): a Newton solve per angle costs about 5 % of a Type C
#: simulation, and runs of one spring and cam at many speeds share it.
STATIC_CACHE_SIZE = 8


def output_angles(points: int) -> np.ndarray:
    """The cam angles [rad] of the output samples of a revolution, ``2 pi j / points``.

    Parameters
    ----------
    points : int
        Samples per revolution [-].
    """
    return np.arange(int(points)) * (2.0 * math.pi / int(points))


@dataclass(frozen=True)
class SimulationSetup:
    """Everything the engine needs for one spring, cam and valve train (speed-independent; data
    only, made by :func:`prepare`)."""

    spring: ValveSpring | SpringPack
    cam: Cam
    valve_train: ValveTrain | None
    #: The lift table the engine reads (the lobe's, or a drawn lever's equivalent lobe lift).
    table: CamTable
    #: The valve train's parameter vector, then the gas force's samples and a lever's table
    #: (layout ``VT_*`` of :mod:`springdyn.valve.engine.layout`).
    vt: np.ndarray
    #: The initial state: static equilibrium on the base circle [m, m/s].
    y0: np.ndarray
    #: Coil-bind figures of the cam's largest lift (:func:`springdyn.valve.spring.solid_length.check_coil_bind`).
    coil_bind: dict | None = None
    #: Cam angles [rad] where the engine's lift table is not smooth (its steps land on them):
    #: the cam's breakpoints, or where a lever's roller meets them.
    breakpoints: np.ndarray = field(default_factory=lambda: np.empty(0))
    #: Cam angle [rad] over which the cam lifts (its event), from the engine's cam table.
    event_angle: float = 2.0 * math.pi
    #: The cylinder's gas force on the valve (:class:`springdyn.valve.train.gas_force.GasForce`), or None.
    gas_force: object = None

    @property
    def n_masses(self) -> int:
        """Masses of the spring's chain (a spring pack's: of all its chains)."""
        return len(self.spring.spring_model.chain.masses)

    @property
    def n_chains(self) -> int:
        """Parallel chains: the springs of a pack, 1 for one spring."""
        return len(self.spring.springs) if isinstance(self.spring, SpringPack) else 1

    @property
    def layout(self) -> dict:
        """The engine's extra outputs by name (:func:`springdyn.valve.engine.extra_layout`)."""
        return extra_layout(self.n_masses, self.n_chains)

    @property
    def nfree(self) -> int:
        """Degrees of freedom: the chain's masses, plus the valve train's (valve, lever, lifter)."""
        return self.n_masses + (self.valve_train.degrees_of_freedom if self.valve_train is not None else 0)


def static_force_at_lift(setup: SimulationSetup, lift) -> np.ndarray:
    """Static (massless) spring force [N] at cam or valve lift(s) [m] of a set-up.

    Parameters
    ----------
    setup : SimulationSetup
        The spring (its chain's laws and force table).
    lift : float or array_like
        Cam (spring alone) or valve lift [m].
    """
    sp = setup.spring
    lift = np.asarray(lift, dtype=float)
    if isinstance(sp, SpringPack):
        return sp.static_force(lift)
    dl = np.ascontiguousarray((sp.free_length - sp.installed_length) + lift.ravel())
    force = np.empty_like(dl)
    series_force_compiled(dl, sp.spring_model.chain.laws, force, *sp.spring_model.force_table)
    return force.reshape(lift.shape)


_STATIC: dict = {}


def static_force_along_grid(setup: SimulationSetup, points: int) -> np.ndarray:
    """Static (massless) force [N] of the spring alone at the cam angles ``2 pi j / points``,
    ``j = 0 .. points - 1``: at the lift of the engine's cam table there.

    It depends on the spring, the cam and ``points`` only, not on the speed: the last
    :data:`STATIC_CACHE_SIZE` are kept.  Read-only: results share it.

    Parameters
    ----------
    setup : SimulationSetup
        The spring and its cam table.
    points : int
        Samples per revolution [-].
    """
    model = setup.spring.spring_model
    key = (id(model), id(setup.cam), int(points))  # the entry holds both: their ids are not reused meanwhile
    hit = _STATIC.get(key)
    if hit is None:
        force = static_force_at_lift(setup, setup.table.at(output_angles(points))[0])
        force.flags.writeable = False
        hit = _STATIC[key] = (model, setup.cam, force)
        while len(_STATIC) > STATIC_CACHE_SIZE:
            _STATIC.pop(next(iter(_STATIC)), None)  # the oldest
    return hit[2]


def check_speeds(setup: SimulationSetup, cam_rpm, allow_extreme: bool = False) -> list[str]:
    """Refuse cam speeds outside physical reason: the cam event shorter than one period
    of the spring's first surge mode at installed length (a surge margin below
    :data:`~springdyn.valve.run.settings.MIN_EVENT_SURGE_PERIODS` periods per event; valve
    trains keep about 10 and more cam orders below f1).  With ``allow_extreme`` such speeds
    run and the returned notes flag them.

    Parameters
    ----------
    setup : SimulationSetup
        The spring and its cam's event.
    cam_rpm : float or array_like
        Cam speeds [rev/min].
    allow_extreme : bool
        Compute them anyway [-].

    Returns
    -------
    list of str
        Notes for the speeds computed beyond reason (empty when none).
    """
    rpm = np.atleast_1d(np.asarray(cam_rpm, dtype=float))
    event = setup.event_angle
    f1 = setup.spring.spring_model.first_mode_installed
    t_event = event / rpm_to_omega(rpm)
    bad = rpm[t_event * f1 < MIN_EVENT_SURGE_PERIODS]
    if not bad.size:
        return []
    r = float(bad[0])
    t = event / rpm_to_omega(r)
    what = (
        f"cam_rpm = {r:g}: the cam event of {math.degrees(event):.0f} deg lasts {t * 1e3:.3g} ms, shorter than one "
        f"period of the spring's first surge mode ({f1:.0f} Hz, {1e3 / f1:.3g} ms): no valve spring follows such a "
        "cam (valve trains run with the surge frequency some 10 cam orders or more above the cam speed)"
    )
    if not allow_extreme:
        raise InputError(
            what
            + (f"; did you mean {r / 10:g}?" if r > MAX_CAM_RPM else ".")
            + " Set allow_extreme_speeds (--allow-extreme-speeds) to compute it anyway, flagged"
            + (f" ({bad.size} speeds of the range are beyond it)" if bad.size > 1 else "")
        )
    return [f"EXTREME SPEED, computed on request: {what}" + (f" ({bad.size} speeds)" if bad.size > 1 else "")]


def with_gas_force(setup: SimulationSetup, gas_force) -> SimulationSetup:
    """The same set-up with (another) gas force on the valve.

    Parameters
    ----------
    setup : SimulationSetup
        A prepared set-up with a valve train.
    gas_force : GasForce or None
        The force over one camshaft revolution [N] (:class:`springdyn.valve.train.gas_force.GasForce`);
        None removes it.
    """
    if gas_force is setup.gas_force:
        return setup
    if setup.valve_train is None:
        raise InputError(
            "a gas force acts on the valve: it needs a valve train (--valve-train / [valve_train]); the spring "
            "alone has no valve"
        )
    n_gas = int(setup.vt[VT_GAS_N])
    samples = np.empty(0) if gas_force is None else gas_force.force
    vt = np.concatenate([setup.vt[:VT_SIZE], samples, setup.vt[VT_SIZE + n_gas :]])  # a lever table follows
    vt[VT_GAS_N] = float(samples.size)
    return dataclasses.replace(setup, vt=vt, gas_force=gas_force)


def prepare(spring: ValveSpring, cam: Cam, valve_train: ValveTrain | None = None, gas_force=None) -> SimulationSetup:
    """Sample the cam, check the lift against coil contact, and find the initial state.

    Warns when the lift drives the spring into coil contact statically (force above
    Fcon), naming the cam angle and the force; raises :class:`InputError` when it would
    drive it beyond the model's range.

    Parameters
    ----------
    spring : ValveSpring
        The spring definition (its model gives the chain).
    cam : Cam
        The cam.
    valve_train : ValveTrain, optional
        Adds the valve body with cam and seat contacts.
    gas_force : GasForce, optional
        The cylinder's gas force on the valve over one camshaft revolution [N]
        (:class:`springdyn.valve.train.gas_force.GasForce`; needs a valve train).
    """
    if gas_force is not None and valve_train is None:
        raise InputError(
            "a gas force acts on the valve: it needs a valve train (--valve-train / [valve_train]); the spring "
            "alone has no valve"
        )
    table = CamTable.of(cam, CAM_SAMPLES)
    lever = None
    if valve_train is not None and valve_train.geometry is not None:
        # the lever's geometry: the engine's table is the equivalent lobe lift s(phi_k) / r_0
        # (springdyn.valve.train.lever), and a table of the ratio's change follows the train's parameters
        kin = valve_train.geometry
        lever = kin.engine_tables(table)
        lever["breakpoints"] = kin.breakpoint_angles(cam.breakpoints, table.at)
        table = CamTable(lever["h"], lever["dh"], lever["ddh"], table.dth)
    h = table.h
    deg = table.angle_deg

    p = spring.spring_model.internal_parameters()
    if valve_train is not None and valve_train.ratio != 1.0:
        h = h * valve_train.ratio  # the rigid valve lift checks the spring; the engine gets the lobe lift
    i_max = int(np.argmax(h))
    lash = valve_train.lash if valve_train is not None else 0.0
    cause = f"the cam (valve lift {h[i_max] * 1e3:.4g} mm at {deg(i_max):.1f} cam deg" + (
        f", less the lash {lash * 1e3:.4g} mm)" if lash else ")"
    )
    springs = spring.springs if isinstance(spring, SpringPack) else (spring,)
    binds = []
    for one in springs:
        binds.append(check_coil_bind(one, max(float(h[i_max]) - lash, 0.0), cause))
    coil_bind = min(binds, key=lambda b: b["coil_bind_margin_m"])  # a pack's: the spring nearest bind
    open_length = spring.installed_length - h[i_max]
    if open_length < spring.spring_model.min_length:
        raise InputError(
            f"cam lift {h[i_max] * 1e3:.4g} mm at {deg(i_max):.1f} cam deg drives the spring solid: "
            f"installed_length - lift = {open_length * 1e3:.4g} mm is below {spring.spring_model.min_length * 1e3:.4g} mm, where "
            f"the static force reaches {spring.spring_model.LIMIT_FORCE_FACTOR:g} Fcon"
        )
    # static force above Fcon <=> lift beyond the lift at which the static force is Fcon
    lift_fcon = spring.spring_model.lift_at_coil_contact
    if h[i_max] > lift_fcon:
        over = np.flatnonzero(h > lift_fcon)
        peak = float(_lift_force(spring, h[i_max]))
        warnings.warn(
            f"the cam lift drives the spring into coil contact even statically: from cam angle "
            f"{deg(over[0]):.1f} deg to {deg(over[-1]):.1f} deg the static force "
            f"exceeds Fcon = {p['Fcon']:.1f} N, peaking at {peak:.1f} N at "
            f"{deg(i_max):.1f} deg (lift {h[i_max] * 1e3:.3g} mm)",
            stacklevel=3,
        )
    y0, lash = _initial_state(spring, table.h[0], valve_train)
    vt = valve_train.kernel_parameters(lash=lash) if valve_train is not None else np.zeros(KERNEL_SIZE)
    # the tables after the fixed entries: the gas force's samples, then a lever's ratio table
    if gas_force is not None:
        vt = np.concatenate([vt[:VT_SIZE], gas_force.force])
        vt[VT_GAS_N] = float(gas_force.force.size)
    if lever is not None:
        vt = np.concatenate([vt, lever["geometry"]])
        vt[VT_GEOM_N] = float(lever["geometry"].size // 4)
    hh = table.h
    return SimulationSetup(
        spring,
        cam,
        valve_train,
        table,
        vt,
        y0,
        coil_bind,
        np.asarray(cam.breakpoints if lever is None else lever["breakpoints"]),
        event_angle=2.0 * math.pi * float(np.count_nonzero(hh > 1e-9 * float(hh.max()))) / hh.size,
        gas_force=gas_force,
    )


def _lift_force(spring, lift) -> float:
    """The static force [N] of a spring or a pack (its springs' sum) at a lift [m] from installed length."""
    if isinstance(spring, SpringPack):
        return float(spring.static_force(lift))
    return float(series_force(spring.free_length - spring.installed_length + lift, spring.spring_model.chain.laws))


def _displacements(spring, lift) -> np.ndarray:
    """The chain's (a pack's: every chain's) static mass displacements [m] at a lift [m] from installed length."""
    if isinstance(spring, SpringPack):
        return spring.initial_displacements(lift)
    return spring.spring_model.initial_condition(spring.free_length - spring.installed_length + lift)["displacements"]


def _initial_state(spring: ValveSpring, lift0: float, valve_train: ValveTrain | None):
    """Static equilibrium at cam angle 0: displacements from set-up, zero velocities.

    Returns the state and the lash the engine uses [m]: the train's own, or, with a
    hydraulic adjuster, the one at which the train rests on the cam with the plunger
    force (the seat carries the rest of the spring force).
    """
    nm = len(spring.spring_model.chain.masses)
    if valve_train is None:
        if lift0 == 0.0:  # the set-up state itself: every displacement is zero by definition
            return np.zeros(2 * nm), 0.0
        return np.concatenate([_displacements(spring, lift0), np.zeros(nm)]), 0.0

    from scipy.optimize import brentq  # (here: a train's run only; scipy.optimize costs 0.2-0.5 s of start-up)

    vt = valve_train
    r = vt.ratio
    k_train = vt.stiffness_at_valve
    fset = spring.spring_model.internal_parameters()["Fset"]

    def seat(z):
        return -vt.seat_stiffness * z if z < 0 else 0.0

    def spring_force(z):
        return _lift_force(spring, z)

    z_lo = -2.0 * (fset + 1.0) / vt.seat_stiffness
    if vt.hydraulic:
        f_h = vt.hla_force
        if not f_h < fset:
            raise InputError(
                f"[valve_train] hla_preload = {f_h:g} N must be below the spring's set-up force "
                f"Fset = {fset:.1f} N: the adjuster would open the valve"
            )
        z0 = brentq(lambda z: seat(z) + f_h - spring_force(z), z_lo, 1e-6, xtol=1e-16, rtol=1e-15)
        # the preloaded plunger: the lash at which the rigid train rests on the cam with f_h;
        # the [hla] dynamics: no lash, the plunger's position takes it up (ValveTrain.static_state)
        lash = 0.0 if vt.hla is not None else r * lift0 - z0 - f_h / k_train
        force = f_h
    else:
        lash = vt.lash

        def train(z):
            pen = r * lift0 - z - lash
            return k_train * pen if pen > 0 else 0.0

        z_hi = max(r * lift0 - lash, 0.0) + 1e-6
        z0 = brentq(lambda z: train(z) + seat(z) - spring_force(z), z_lo, z_hi, xtol=1e-16, rtol=1e-15)
        force = train(z0)
    u = _displacements(spring, z0)
    pos = vt.static_state(lift0, z0, force)
    return np.concatenate([u, pos, np.zeros(nm + pos.size)]), float(lash)
