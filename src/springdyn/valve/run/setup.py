"""The engine's set-up for one spring, cam and valve train: everything that does not depend
on the speed (document, "Initial condition & position").

:func:`prepare` samples the cam (:data:`CAM_SAMPLES` per revolution), checks the lift
against coil contact and finds the initial state (static equilibrium on the base circle);
:class:`SimulationSetup` holds the result and runs speeds with the compiled engine.  The
run settings every analysis shares (tolerances, the largest step, the Runge-Kutta pair per
model) are defined here.
"""

import math
import warnings
from dataclasses import dataclass

import numpy as np

from ...core.errors import InputError
from ..cam.definition import Cam
from ..engine import (
    run_speeds,
    series_force_compiled,
)
from ..engine.cam_table import CamTable
from ..spring.definition import ValveSpring
from ..spring.solid_length import check_coil_bind
from ..spring.statics import series_force
from ..train.definition import KERNEL_SIZE, ValveTrain
from .periodicity import BAND_REVOLUTIONS, MAX_REVOLUTIONS, PERIODICITY_TOL

__all__ = [
    "SimulationSetup",
    "prepare",
    "check_run_settings",
    "output_angles",
    "DEFAULT_RTOL",
    "DEFAULT_ATOL",
    "TRAIN_RTOL",
    "TRAIN_ATOL",
    "default_tolerances",
    "CAM_SAMPLES",
    "MAX_STEP_FRACTION",
    "VELOCITY_TOLERANCE_DIVISOR",
    "PAIR",
    "BS3_MIN_ELEMENTS",
    "PERIODICITY_TOL",
    "MAX_REVOLUTIONS",
    "BAND_REVOLUTIONS",
]

#: Default integration tolerances (relative; absolute on displacements [m] and velocities
#: [m/s]).  Chosen by the refinement study of the tests: halving them changes peak forces
#: by far less than 0.05 %.
DEFAULT_RTOL = 1e-6
DEFAULT_ATOL = 1e-9
#: With a valve train the defaults are a hundred times tighter: its contacts open and close
#: with impacts (lash take-up, landings), and at 1e-6 those repeat from one revolution to the
#: next only to a few per cent of Fset (the pushrod example: 3.7 % at 1000 cam rpm, no speed
#: settles to the periodic steady state); at 1e-8 every speed below the first lift-off settles
#: within 0.2 % in 4-5 revolutions (docs/valve.md, "Periodic steady state").
TRAIN_RTOL = 1e-8
TRAIN_ATOL = 1e-11
#: The fewest periods of the spring's first surge mode a cam event may last for its speed to be
#: an operating point (:meth:`SimulationSetup.check_speeds`).
MIN_EVENT_SURGE_PERIODS = 1.0
#: Cam speed [rev/min] above any engine's (a racing engine's 20 000 rpm is 10 000 cam rpm): a
#: refused speed above it is likely a typing slip, and the message suggests a tenth of it.
MAX_CAM_RPM = 12000.0
#: Cam table resolution for the engine (samples per revolution, 0.05 deg).
CAM_SAMPLES = 7200
#: Maximum step [fraction of a revolution] so that no step can jump over a short event.
MAX_STEP_FRACTION = 1.0 / 720.0
#: The spring's velocities get the absolute tolerance ``atol 2 pi f1 / VELOCITY_TOLERANCE_DIVISOR``
#: [m/s] (:meth:`SimulationSetup.atol_velocity`; the study in docs/valve.md).
VELOCITY_TOLERANCE_DIVISOR = 30.0
#: The embedded Runge-Kutta pair of the compiled engine per spring model, chosen by
#: measurement (docs/valve.md, "Stepping"): Type C's step is set by accuracy, where the
#: 5th-order Dormand-Prince pair takes the fewest right-hand sides; the distributed chain's
#: by the stability of its stiffness-proportionally damped top modes (real eigenvalues to
#: -2.7e5 1/s for 50 elements), where the Bogacki-Shampine 3(2) pair takes 1.3x more steps
#: for half the right-hand sides each, and still holds the end forces within 0.05 % of Fset.
PAIR = {"type-c": "dopri5", "distributed": "bs3"}
#: Below this many elements the distributed chain's explicit step is set by accuracy, not by
#: stability, and Dormand-Prince is the faster pair (measured, one-step example at 1500 and
#: 3000 cam rpm: 25 elements 3.0 against 4.2 ms, 40 elements 6.2 against 6.7 ms, 50 elements
#: 10.4 against 9.6 ms; docs/valve.md "Stepping").
BS3_MIN_ELEMENTS = 40


def output_angles(points: int) -> np.ndarray:
    """The cam angles [rad] of the output samples of a revolution, ``2 pi j / points``.

    Parameters
    ----------
    points : int
        Samples per revolution [-].
    """
    return np.arange(int(points)) * (2.0 * math.pi / int(points))


@dataclass
class SimulationSetup:
    """Everything the engine needs for one spring, cam and valve train (speed-independent)."""

    spring: ValveSpring
    cam: Cam
    valve_train: ValveTrain | None
    table: CamTable
    vt: np.ndarray
    y0: np.ndarray
    #: coil-bind figures of the cam's largest lift (:func:`springdyn.valve.spring.solid_length.check_coil_bind`)
    coil_bind: dict | None = None
    #: Cam angles [rad] where the engine's lift table is not smooth: the cam's breakpoints, or
    #: where a lever's roller meets them (:meth:`springdyn.valve.train.lever.LeverKinematics.breakpoint_angles`);
    #: None: the cam's.
    lobe_breakpoints: np.ndarray | None = None

    @property
    def breakpoints(self) -> np.ndarray:
        """Cam angles [rad] where the engine's lift table is not smooth (its steps land on them)."""
        return np.asarray(self.cam.breakpoints if self.lobe_breakpoints is None else self.lobe_breakpoints)

    def static_force(self, lift) -> np.ndarray:
        """Static (massless) spring force [N] at cam or valve lift(s) [m].

        Parameters
        ----------
        lift : float or array_like
            Cam (spring alone) or valve lift [m].
        """
        sp = self.spring
        lift = np.asarray(lift, dtype=float)
        dl = np.ascontiguousarray((sp.free_length - sp.installed_length) + lift.ravel())
        force = np.empty_like(dl)
        series_force_compiled(dl, sp.spring_model.chain.laws, force, *sp.spring_model.force_table)
        return force.reshape(lift.shape)

    @property
    def event_angle(self) -> float:
        """Cam angle [rad] over which the cam lifts (its event), from the engine's cam table."""
        if "_event" not in self.__dict__:
            h = self.table.h
            self.__dict__["_event"] = 2.0 * math.pi * float(np.count_nonzero(h > 1e-9 * float(h.max()))) / h.size
        return self.__dict__["_event"]

    def check_speeds(self, cam_rpm, allow_extreme: bool = False) -> list[str]:
        """Refuse cam speeds outside physical reason: the cam event shorter than one period
        of the spring's first surge mode at installed length (a surge margin below
        :data:`MIN_EVENT_SURGE_PERIODS` periods per event; valve trains keep about 10 and more
        cam orders below f1).  With ``allow_extreme`` such speeds run and the returned notes
        flag them.

        Parameters
        ----------
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
        event = self.event_angle
        f1 = self.spring.spring_model.first_mode_installed
        t_event = event / (rpm * 2.0 * math.pi / 60.0)
        bad = rpm[t_event * f1 < MIN_EVENT_SURGE_PERIODS]
        if not bad.size:
            return []
        r = float(bad[0])
        t = event / (r * 2.0 * math.pi / 60.0)
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

    def static_force_along_cam(self, points: int) -> np.ndarray:
        """Static (massless) force [N] of the spring alone at the cam angles ``2 pi j / points``,
        ``j = 0 .. points - 1``: at the lift of the engine's cam table there.

        It depends on the spring, the cam and ``points`` only, not on the speed, so the
        spring keeps it for its last :attr:`STATIC_CACHE_SIZE` cams (a Newton solve per
        angle costs about 5 % of a Type C simulation).  Read-only: results share it.

        Parameters
        ----------
        points : int
            Samples per revolution [-].
        """
        store = self.spring.spring_model.static_force_cache
        key = (id(self.cam), int(points))  # the entry holds the cam: its id is not reused meanwhile
        hit = store.get(key)
        if hit is None:
            lift = self.table.at(output_angles(points))[0]
            force = self.static_force(lift)
            force.flags.writeable = False
            hit = store[key] = (self.cam, force)
            while len(store) > self.STATIC_CACHE_SIZE:
                store.pop(next(iter(store)), None)  # the oldest
        return hit[1]

    #: Cams per spring whose static force along the output grid is kept.
    STATIC_CACHE_SIZE = 8

    def with_gas_force(self, gas) -> "SimulationSetup":
        """The same set-up with the gas force on the valve (:class:`springdyn.valve.train.gas_force.GasForce`).

        Parameters
        ----------
        gas : GasForce or None
            The force over one camshaft revolution [N] (None: the set-up itself).
        """
        import dataclasses

        from ..engine.layout import VT_GAS_N, VT_SIZE

        if gas is None:
            return self
        if self.valve_train is None:
            raise InputError(
                "a gas force acts on the valve: it needs a valve train (--valve-train / [valve_train]); the spring "
                "alone has no valve"
            )
        n_gas = int(self.vt[VT_GAS_N])
        vt = np.concatenate([self.vt[:VT_SIZE], gas.force, self.vt[VT_SIZE + n_gas :]])  # a lever table follows
        vt[VT_GAS_N] = float(gas.force.size)
        return dataclasses.replace(self, vt=vt)

    def args(self, omega: float) -> tuple:
        """The engine's argument tuple (:func:`springdyn.valve.engine.model_of` reads it).

        Parameters
        ----------
        omega : float
            Cam speed [rad/s].
        """
        ch = self.spring.spring_model.chain
        return (
            ch.masses,
            ch.laws,
            ch.setup_compressions,
            ch.c0_array,
            self.table.h,
            self.table.dh,
            self.table.ddh,
            self.table.dth,
            omega,
            self.vt,
        )

    @property
    def n_masses(self) -> int:
        """Masses of the spring's chain."""
        return len(self.spring.spring_model.chain.masses)

    @property
    def nfree(self) -> int:
        """Degrees of freedom: the chain's masses, plus the valve train's (valve, lever, lifter)."""
        return self.n_masses + (self.valve_train.degrees_of_freedom if self.valve_train is not None else 0)

    def run(
        self,
        omegas,
        revolutions: int | None,
        points: int,
        *,
        rtol: float,
        atol: float,
        method: str | None = None,
        periodicity_tol: float = PERIODICITY_TOL,
        max_revolutions: int = MAX_REVOLUTIONS,
        warm_start: bool = False,
    ) -> dict:
        """Integrate the speeds ``omegas`` [rad/s] with the compiled engine to their periodic
        steady state (``revolutions`` None) or for ``revolutions``, monitoring the last
        revolution (true extremes and events on the dense output, see
        :func:`springdyn.valve.engine.run_speeds`).

        Parameters
        ----------
        omegas : array_like
            Cam speeds [rad/s].
        revolutions : int or None
            Revolutions per speed [-]; None: until two revolutions repeat.
        points : int
            Output samples per revolution [-].
        rtol : float
            Relative tolerance [-].
        atol : float
            Absolute tolerance of the displacements [m].
        method : str, optional
            Runge-Kutta pair (default: the model's, :data:`PAIR`) [-].
        periodicity_tol : float
            Periodic steady state: the largest change of the seat, retainer, cam-contact and
            valve-seat forces from one revolution to the next [fraction of Fset].
        max_revolutions : int
            Periodic steady state: the most revolutions per speed [-].
        warm_start : bool
            Start each speed from the state the one before ended in (speeds ascending).

        Returns
        -------
        dict
            :func:`springdyn.valve.engine.run_speeds`'s outputs, ``periodicity`` as a
            fraction of Fset.
        """
        fset = self.spring.spring_model.internal_parameters()["Fset"]
        periodic = revolutions is None
        res = run_speeds(
            self.y0,
            omegas,
            max_revolutions if periodic else revolutions,
            points,
            self.args(0.0),
            rtol=rtol,
            atol=atol,
            max_step_fraction=MAX_STEP_FRACTION,
            gaps=self.spring.spring_model.contact_gaps,
            atol_velocity=self.atol_velocity(atol),
            method=self.method if method is None else method,
            stop_angles=self.table.stop_angles(self.breakpoints),
            periodicity_tol=periodicity_tol * fset if periodic else 0.0,
            warm_start=warm_start,
            band_revolutions=BAND_REVOLUTIONS if periodic else 0,
        )
        res["periodicity"] = res["periodicity"] / fset
        return res

    @property
    def method(self) -> str:
        """The engine's Runge-Kutta pair for this spring model (:data:`PAIR`); a distributed
        chain of fewer than :data:`BS3_MIN_ELEMENTS` elements steps with Dormand-Prince."""
        if self.spring.model == "distributed" and self.spring.elements < BS3_MIN_ELEMENTS:
            return "dopri5"
        return PAIR[self.spring.model]

    def atol_velocity(self, atol: float) -> np.ndarray:
        """Absolute tolerances of the velocities [m/s] for ``atol`` [m] on the displacements.

        The spring's masses: ``atol 2 pi f1 / VELOCITY_TOLERANCE_DIVISOR`` (the velocity of
        a displacement ``atol`` oscillating at a thirtieth of the first surge frequency);
        the valve train's bodies keep ``atol`` (their stiff contacts make the contact forces
        sensitive to velocity errors).

        Measured (benchmarks/valve_tolerances.py, docs/valve.md): over 112 runs per model
        (two springs, four cams, 14 speeds) the worst end-force extreme against a tight
        reference is 0.014 % of Fset for Type C (0.0087 % with ``atol`` for every
        component, which takes 1.4 times more steps) and 0.0035 % for the distributed
        chain; ``/ 10`` reaches 0.028 %, a factor 1.8 to the 0.05 % target only (and 0.27 %
        on a ramp cam before the engine landed its steps on the ramps' ends).

        Parameters
        ----------
        atol : float
            Absolute tolerance of the displacements [m].
        """
        out = np.full(self.nfree, float(atol))
        out[: self.n_masses] = (
            atol
            * 2.0
            * math.pi
            * float(self.spring.spring_model.internal_parameters()["f1"])
            / VELOCITY_TOLERANCE_DIVISOR
        )
        return out


def prepare(spring: ValveSpring, cam: Cam, valve_train: ValveTrain | None = None) -> SimulationSetup:
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
    """
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
    coil_bind = check_coil_bind(
        spring,
        max(float(h[i_max]) - lash, 0.0),
        f"the cam (valve lift {h[i_max] * 1e3:.4g} mm at {deg(i_max):.1f} cam deg"
        + (f", less the lash {lash * 1e3:.4g} mm)" if lash else ")"),
    )
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
        peak = float(
            series_force(spring.free_length - spring.installed_length + h[i_max], spring.spring_model.chain.laws)
        )
        warnings.warn(
            f"the cam lift drives the spring into coil contact even statically: from cam angle "
            f"{deg(over[0]):.1f} deg to {deg(over[-1]):.1f} deg the static force "
            f"exceeds Fcon = {p['Fcon']:.1f} N, peaking at {peak:.1f} N at "
            f"{deg(i_max):.1f} deg (lift {h[i_max] * 1e3:.3g} mm)",
            stacklevel=3,
        )
    y0, lash = _initial_state(spring, table.h[0], valve_train)
    vt = valve_train.kernel_parameters(lash=lash) if valve_train is not None else np.zeros(KERNEL_SIZE)
    if lever is None:
        return SimulationSetup(spring, cam, valve_train, table, vt, y0, coil_bind)
    from ..engine.layout import VT_GEOM_N

    vt = np.concatenate([vt, lever["geometry"]])
    vt[VT_GEOM_N] = float(lever["geometry"].size // 4)
    return SimulationSetup(spring, cam, valve_train, table, vt, y0, coil_bind, lever["breakpoints"])


def _initial_state(spring: ValveSpring, lift0: float, valve_train: ValveTrain | None):
    """Static equilibrium at cam angle 0: displacements from set-up, zero velocities.

    Returns the state and the lash the engine uses [m]: the train's own, or, with a
    hydraulic adjuster, the one at which the train rests on the cam with the plunger
    force (the seat carries the rest of the spring force).
    """
    setup = spring.free_length - spring.installed_length
    nm = len(spring.spring_model.chain.masses)
    if valve_train is None:
        if lift0 == 0.0:  # the set-up state itself: every displacement is zero by definition
            return np.zeros(2 * nm), 0.0
        u = spring.initial_condition(setup + lift0)["displacements"]
        return np.concatenate([u, np.zeros(nm)]), 0.0
    from scipy.optimize import brentq  # (imported here: scipy.optimize costs 0.2 s of start-up)

    laws = spring.spring_model.chain.laws
    vt = valve_train
    r = vt.ratio
    k_train = vt.stiffness_at_valve
    fset = spring.spring_model.internal_parameters()["Fset"]

    def seat(z):
        return -vt.seat_stiffness * z if z < 0 else 0.0

    def spring_force(z):
        return float(series_force(setup + z, laws))

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
    u = spring.spring_model.initial_condition(setup + z0)["displacements"]
    pos = vt.static_state(lift0, z0, force)
    return np.concatenate([u, pos, np.zeros(nm + pos.size)]), float(lash)


def default_tolerances(valve_train, rtol: float | None = None, atol: float | None = None) -> tuple:
    """The integration tolerances of a run: those given, else the defaults of the spring alone
    (:data:`DEFAULT_RTOL`, :data:`DEFAULT_ATOL`) or of a valve train (:data:`TRAIN_RTOL`,
    :data:`TRAIN_ATOL`).

    Parameters
    ----------
    valve_train : ValveTrain or None
        The run's valve train [-].
    rtol, atol : float, optional
        Given tolerances [-, m].
    """
    train = valve_train is not None
    return (
        (TRAIN_RTOL if train else DEFAULT_RTOL) if rtol is None else rtol,
        (TRAIN_ATOL if train else DEFAULT_ATOL) if atol is None else atol,
    )


def check_run_settings(
    revolutions, points_per_revolution, rtol, atol, periodicity_tol=PERIODICITY_TOL, max_revolutions=MAX_REVOLUTIONS
) -> None:
    """Check the run settings of :func:`simulate` and the sweeps (raise :class:`InputError`).

    Parameters
    ----------
    revolutions : int or None
        Cam revolutions [-], 1 to 1000; None: to the periodic steady state.
    points_per_revolution : int
        Output samples per revolution [-], 16 to 100 000.
    rtol : float
        Relative tolerance [-], 1e-12 to 1e-2.
    atol : float
        Absolute tolerance [m, m/s], 1e-15 to 1e-5.
    periodicity_tol : float
        Periodic steady state: tolerance [fraction of Fset], 1e-7 to 0.5.
    max_revolutions : int
        Periodic steady state: the most revolutions [-], 2 to 1000.
    """
    number = (int, float, np.integer, np.floating)
    if revolutions is None:
        if (
            isinstance(periodicity_tol, bool)
            or not isinstance(periodicity_tol, number)
            or not 1e-7 <= periodicity_tol <= 0.5
        ):
            raise InputError(
                f"periodicity_tol = {periodicity_tol!r} must be a fraction of Fset from 1e-07 to 0.5 "
                f"(default {PERIODICITY_TOL:g}, i.e. {100 * PERIODICITY_TOL:g} %)"
            )
        if not isinstance(max_revolutions, bool) and isinstance(max_revolutions, number) and max_revolutions < 2:
            raise InputError(f"max_revolutions = {max_revolutions!r} must be at least 2: two revolutions are compared")
        count = ("max_revolutions", max_revolutions, 2, 1000)
    else:
        count = ("revolutions", revolutions, 1, 1000)
    for name, value, lo, hi in (
        count,
        ("points_per_revolution", points_per_revolution, 16, 100_000),
    ):
        if (
            isinstance(value, bool)
            or not isinstance(value, number)
            or not math.isfinite(value)
            or value != int(value)
            or not lo <= value <= hi
        ):
            raise InputError(f"{name} = {value!r} must be a whole number of at least {lo} and at most {hi}")
    for name, value, lo, hi in (("rtol", rtol, 1e-12, 1e-2), ("atol", atol, 1e-15, 1e-5)):
        if isinstance(value, bool) or not isinstance(value, number) or not lo <= value <= hi:
            raise InputError(
                f"{name} = {value!r} is outside the allowed range {lo:g} <= {name} <= {hi:g} "
                "(integration tolerance"
                + (
                    ": absolute, on displacements [m]; velocities get it times 2 pi f1/30)"
                    if name == "atol"
                    else ", relative)"
                )
            )
