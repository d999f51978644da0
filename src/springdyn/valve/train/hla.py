"""Hydraulic lash adjuster (HLA): the ``[hla]`` table and its hydraulics.

An HLA is a plunger in a body over a high-pressure chamber (HPC) of oil.  A check valve
(a ball) lets oil in from the supply (the low-pressure reservoir fed by the engine's oil
gallery) when the chamber pressure falls below the supply pressure; oil leaks out through
the annular clearance between plunger and body when the chamber pressure exceeds it.  The
plunger spring extends the plunger to take up lash on the base circle; under the cam load
the oil column carries the load and leaks down a little each event.  Collapse ``y`` is
the plunger's travel into the body (positive in the direction that loses valve lift).

The oil (its viscosity, density and bulk modulus with free air) is the train's one ``[oil]``
(:mod:`.oil`); its keys may still be given here by their older names, with one meaning.

One place per equation:

- :func:`leak_conductance` -- laminar (Poiseuille) flow through the plunger's annular
  clearance, ``G = pi D c^3 (1 + 1.5 e^2) / (12 mu L)`` (Merritt 1967, eq. 3-59);
- :func:`check_valve_flow` -- the check valve as a sharp-edged orifice,
  ``Q = Cd A sqrt(2 dp / rho)``, laminarised below a transition pressure;
- :func:`chamber_pressure_rate` -- oil continuity in the chamber,
  ``dp/dt = beta_e / V (A_p dy/dt + Q_in - Q_leak)``;
- :func:`leak_down_time` -- the leak-down test in closed form: a constant load ``W`` on the
  plunger collapses it by ``s`` in ``t = s (A_p + pi D c / 2) / (G (W - F_s) / A_p)``
  (quasi-static, incompressible; the Couette term of the moving plunger included);
- :func:`leak_down_test` -- the same test integrated with the plunger's mass, the aerated
  oil's compressibility and the check valve, the check of the closed form.

Sources: docs/references.md, [Merritt], [ASTM D341], [Gholizadeh].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...core.errors import InputError
from ...core.params import Parameters, param
from ..engine.hydraulics import orifice_flow
from ..engine.layout import P_ATM
from .oil import HoldsOil, Oil

__all__ = [
    "P_ATM",
    "HLA",
    "leak_conductance",
    "check_valve_flow",
    "chamber_pressure_rate",
    "leak_down_time",
    "leak_down_test",
    "LeakDownTest",
]

# Standard atmospheric pressure P_ATM [Pa], the cavitation pressure P_CAVITATION [Pa] and the
# check valve's laminar transition CHECK_VALVE_TRANSITION [Pa] are defined once, in the
# engine's layout, and the orifice law once, in springdyn.valve.engine.hydraulics: the
# compiled laws use them too (the engine imports nothing from train/).

#: The integrator of :func:`leak_down_test` (an implicit one: the oil spring is stiff).
LEAK_DOWN_METHOD = "Radau"


def leak_conductance(diameter, radial_clearance, length, viscosity, eccentricity=0.0):
    """Laminar leakage conductance [m^3/(s Pa)] of the plunger's annular clearance.

    ``G = pi D c^3 (1 + 1.5 e^2) / (12 mu L)``: Poiseuille flow through a narrow annulus
    of radial clearance ``c`` and length ``L``, ``e`` the eccentricity over ``c``
    (Merritt 1967, eq. 3-59 and 3-62).

    Parameters
    ----------
    diameter : float
        Plunger diameter [m].
    radial_clearance : float
        Radial clearance between plunger and body [m].
    length : float
        Sealing length of the clearance [m].
    viscosity : float
        Dynamic viscosity of the oil [Pa s].
    eccentricity : float
        Eccentricity ratio of the plunger in its bore [-], 0 (concentric) to 1.
    """
    return math.pi * diameter * radial_clearance**3 * (1.0 + 1.5 * eccentricity**2) / (12.0 * viscosity * length)


def check_valve_flow(dp, area, discharge_coefficient, density):
    """Flow [m^3/s] through the open check valve at a pressure drop ``dp`` [Pa] (> 0 opens it).

    A sharp-edged orifice, ``Q = Cd A sqrt(2 dp / rho)``, laminarised below
    :data:`springdyn.valve.engine.layout.CHECK_VALVE_TRANSITION` (linear in ``dp``, the same flow at the transition);
    no flow for ``dp <= 0`` (the ball seats).

    Parameters
    ----------
    dp : float
        Supply pressure less the cracking pressure less the chamber pressure [Pa].
    area : float
        Flow area of the open valve [m^2].
    discharge_coefficient : float
        Discharge coefficient [-].
    density : float
        Oil density [kg/m^3].
    """
    return orifice_flow(dp, discharge_coefficient * area * math.sqrt(2.0 / density))


def chamber_pressure_rate(beta, volume, area, collapse_rate, q_in, q_leak):
    """Rate of the chamber pressure [Pa/s] from oil continuity.

    ``dp/dt = beta / V (A_p dy/dt + Q_in - Q_leak)``: a collapsing plunger (``dy/dt > 0``)
    and inflow raise the pressure, leakage lowers it.

    Parameters
    ----------
    beta : float
        Effective bulk modulus [Pa].
    volume : float
        Chamber volume [m^3].
    area : float
        Plunger area [m^2].
    collapse_rate : float
        Plunger velocity into the body [m/s].
    q_in, q_leak : float
        Check-valve inflow and leakage outflow [m^3/s].
    """
    return beta / volume * (area * collapse_rate + q_in - q_leak)


def leak_down_time(load, travel, plunger_diameter, radial_clearance, conductance, spring_force=0.0):
    """Time [s] a constant load takes to collapse the plunger by ``travel``: the leak-down test.

    Quasi-static and incompressible: the chamber carries ``dp = (W - F_s) / A_p`` above the
    supply; the leak ``G dp`` leaves at the plunger speed ``v`` through the plunger area,
    less the oil the plunger drags into the clearance (Couette, ``pi D c v / 2``), so
    ``v (A_p + pi D c / 2) = G dp`` and ``t = travel / v``.

    Parameters
    ----------
    load : float
        Load on the plunger [N].
    travel : float
        Collapse to time [m].
    plunger_diameter : float
        Plunger diameter [m].
    radial_clearance : float
        Radial clearance [m].
    conductance : float
        Leakage conductance :func:`leak_conductance` [m^3/(s Pa)].
    spring_force : float
        Plunger-spring force, which the load overcomes [N].
    """
    area = 0.25 * math.pi * plunger_diameter**2
    dp = (load - spring_force) / area
    if not dp > 0:
        raise InputError(f"load = {load:g} N must exceed the plunger-spring force {spring_force:g} N to leak down")
    v = conductance * dp / (area + 0.5 * math.pi * plunger_diameter * radial_clearance)
    return travel / v


@dataclass(frozen=True)
class HLA(HoldsOil, Parameters):
    """The ``[hla]`` table: a hydraulic lash adjuster's plunger, chamber, check valve and oil.

    Defaults describe a 12 mm HLA of a passenger-car finger-follower train (sources in
    docs/valve-train.md, "Hydraulic lash adjuster").

    Examples
    --------
    >>> h = HLA()
    >>> round(h.leak_down_seconds(200.0, 1e-3, h.oil.temperature), 1) > 0
    True
    """

    #: The oil (not a key: ``[oil]``, or the older keys of this table, :data:`.oil.OLDER_KEYS`).
    oil: Oil = field(default_factory=Oil)

    plunger_diameter: float = param("m", "plunger diameter", display="mm", positive=True, default=12e-3)
    radial_clearance: float = param(
        "m", "radial clearance between plunger and body", display="um", positive=True, default=4e-6
    )
    leak_length: float = param(
        "m", "sealing length of the plunger's clearance", display="mm", positive=True, default=8e-3
    )
    eccentricity: float = param(
        "", "eccentricity ratio of the plunger in its bore (0 concentric, < 1)", nonnegative=True, default=0.0
    )
    chamber_volume: float = param(
        "m^3", "high-pressure chamber volume on the base circle", display="mm^3", positive=True, default=400e-9
    )
    plunger_mass: float = param("kg", "plunger mass", display="g", positive=True, default=8e-3)
    plunger_spring_force: float = param("N", "plunger-spring force", positive=True, default=15.0)
    collapse_travel: float = param(
        "m", "plunger travel into the body before it bottoms", display="mm", positive=True, default=2.5e-3
    )
    extension_travel: float = param(
        "m", "plunger travel out of the body before its retaining clip", display="mm", positive=True, default=1.0e-3
    )
    supply_pressure: float = param("Pa", "oil supply pressure (gauge)", display="bar", nonnegative=True, default=2.0e5)
    check_valve_diameter: float = param(
        "m", "flow diameter of the open check valve", display="mm", positive=True, default=1.5e-3
    )
    cracking_pressure: float = param(
        "Pa", "pressure difference that opens the check valve", display="bar", nonnegative=True, default=5.0e3
    )
    discharge_coefficient: float = param("", "check valve discharge coefficient", positive=True, default=0.7)
    socket_stiffness: float = param(
        "N/m",
        "contact stiffness of the lever's socket on the plunger (a hydraulic bucket: the plunger on the stem)",
        display="N/um",
        positive=True,
        default=1.0e8,
    )
    pivot_mass: float = param(
        "kg",
        "lever mass carried at the socket (the finger's pivot end; a bucket's body is [valve_train] follower_mass)",
        display="g",
        positive=True,
        default=10e-3,
    )

    table = "hla"

    def _validate(self) -> None:
        if not self.eccentricity < 1.0:
            raise InputError(f"eccentricity = {self.eccentricity:g} must be below 1 (the plunger touching its bore)")
        if not self.radial_clearance < 0.05 * self.plunger_diameter:
            raise InputError(
                f"radial_clearance = {self.radial_clearance * 1e6:g} um is not a narrow clearance of a "
                f"{self.plunger_diameter * 1e3:g} mm plunger (at most 5 % of the diameter)"
            )
        if not self.chamber_volume > self.area * self.collapse_travel:
            raise InputError(
                f"chamber_volume = {self.chamber_volume * 1e9:g} mm^3 must exceed the volume the plunger sweeps "
                f"over its collapse_travel ({self.area * self.collapse_travel * 1e9:.4g} mm^3)"
            )

    # -- derived values ---------------------------------------------------------------
    @property
    def area(self) -> float:
        """Plunger area [m^2]."""
        return 0.25 * math.pi * self.plunger_diameter**2

    def conductance(self, temperature: float | None = None) -> float:
        """Leakage conductance [m^3/(s Pa)] at a temperature (:func:`leak_conductance`).

        Parameters
        ----------
        temperature : float, optional
            Oil temperature [K].
        """
        return leak_conductance(
            self.plunger_diameter,
            self.radial_clearance,
            self.leak_length,
            self.oil.dynamic_viscosity(temperature),
            self.eccentricity,
        )

    def leak_down_seconds(self, load: float, travel: float, temperature: float | None = None) -> float:
        """Closed-form leak-down time [s] (:func:`leak_down_time`) of a load over a travel.

        Parameters
        ----------
        load : float
            Load on the plunger [N].
        travel : float
            Collapse [m].
        temperature : float, optional
            Oil temperature [K].
        """
        return leak_down_time(
            load,
            travel,
            self.plunger_diameter,
            self.radial_clearance,
            self.conductance(temperature),
            self.plunger_spring_force,
        )

    @property
    def check_valve_area(self) -> float:
        """Flow area of the open check valve [m^2]."""
        return 0.25 * math.pi * self.check_valve_diameter**2


@dataclass(frozen=True)
class LeakDownTest:
    """A leak-down test integrated in time (:func:`leak_down_test`) beside its closed form."""

    load_N: float
    travel_m: float
    time_s: float  #: integrated time to collapse the travel [s]
    closed_form_s: float  #: :func:`leak_down_time` [s]
    peak_pressure_Pa: float  #: chamber pressure above the supply in the test [Pa]

    @property
    def deviation(self) -> float:
        """Integrated over closed-form time, less one [-]."""
        return self.time_s / self.closed_form_s - 1.0


def leak_down_test(hla: HLA, load: float, travel: float, temperature: float | None = None) -> LeakDownTest:
    """The leak-down test integrated: the plunger (mass), the aerated chamber, the check valve.

    As a leak-down tester does, the ``load`` is applied and the chamber brought to the
    pressure that carries it, ``p = p_s + (W - F_s) / A_p``, with the free air compressed to
    that pressure (the collapse ``int dp / beta_e`` over the chamber); from that loaded state
    the state ``(y, v, p)`` follows ``m v' = W - F_s - (p - p_s) A_p`` and
    :func:`chamber_pressure_rate` (the Couette drag ``pi D c v / 2`` into the clearance
    included) until the plunger has collapsed ``travel`` further.  Its time checks
    :func:`leak_down_time`, which neglects the plunger's inertia and the oil's compression.

    Parameters
    ----------
    hla : HLA
        The adjuster.
    load : float
        Load on the plunger [N].
    travel : float
        Collapse to time [m].
    temperature : float, optional
        Oil temperature [K] (default: the adjuster's).
    """
    from scipy.integrate import quad, solve_ivp  # (here: scipy.integrate costs start-up of every valve command)

    closed = hla.leak_down_seconds(load, travel, temperature)
    a = hla.area
    g = hla.conductance(temperature)
    rho = hla.oil.density(temperature)
    ps = P_ATM + hla.supply_pressure
    drag = 0.5 * math.pi * hla.plunger_diameter * hla.radial_clearance
    p1 = ps + (load - hla.plunger_spring_force) / a

    beta = hla.oil.bulk_modulus_at

    y0 = hla.chamber_volume * quad(lambda p: 1.0 / beta(p), ps, p1, limit=200)[0] / a
    if not 0 < y0 + travel < hla.collapse_travel:
        raise InputError(
            f"travel = {travel * 1e3:g} mm and the {y0 * 1e3:.3g} mm the load first compresses exceed the "
            f"collapse_travel {hla.collapse_travel * 1e3:g} mm"
        )

    def rhs(t, s):
        y, v, p = s
        q_in = check_valve_flow(ps - hla.cracking_pressure - p, hla.check_valve_area, hla.discharge_coefficient, rho)
        q_leak = g * (p - ps) - drag * v
        dp = chamber_pressure_rate(beta(p), hla.chamber_volume - a * y, a, v, q_in, q_leak)
        return [v, (load - hla.plunger_spring_force - (p - ps) * a) / hla.plunger_mass, dp]

    def reached(t, s):
        return s[0] - y0 - travel

    reached.terminal = True
    v0 = (
        g * (p1 - ps) / (a + drag)
    )  # the leak's quasi-static speed (from rest, the 12 kHz oil-spring ringing costs minutes)
    sol = solve_ivp(
        rhs,
        (0.0, 10.0 * closed),
        [y0, v0, p1],
        method=LEAK_DOWN_METHOD,
        rtol=1e-10,
        atol=[1e-13, 1e-12, 1e-3],
        events=reached,
    )
    if not sol.t_events[0].size:
        raise InputError(f"the plunger did not collapse {travel * 1e3:g} mm under {load:g} N (check the [hla] values)")
    return LeakDownTest(
        load_N=load,
        travel_m=travel,
        time_s=float(sol.t_events[0][0]),
        closed_form_s=closed,
        peak_pressure_Pa=float(np.max(sol.y[2]) - ps),
    )
