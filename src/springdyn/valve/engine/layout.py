"""The engine's array layouts and constants, by name (numba freezes module-level numbers into the code).

- ``VT_*``: the valve train's parameter vector (:meth:`springdyn.valve.train.definition.ValveTrain.kernel_parameters`).
- ``TRAIN_*``: the kinds of valve train (slot :data:`VT_KIND`), each with its own equations
  (:func:`springdyn.valve.engine.equations.train_rhs`) and degrees of freedom (:data:`TRAIN_DOF`).
- ``S_*``, ``H_*``: the train's states, after the chain's (:data:`TRAIN_STATES`).
- ``X_*``, ``XT_*``: the right-hand side's ``extra`` outputs after the ``2 (N + 1)`` element
  forces and compressions (:func:`extra_layout`).
- ``P_*``: the constants of the compiled hydraulic laws (the adjuster's, :mod:`springdyn.valve.train.hla`
  imports them from here).
- ``EXT_*``: the monitor's per-speed extremes (:data:`EXT`).
- ``EV_*``: the columns and kinds of the monitor's event table (:data:`EVENT_KINDS`).
- ``CHK_*``: the forces sampled every revolution to judge periodicity (:data:`N_CHECK`).
"""

from __future__ import annotations

__all__ = [
    "VT_SIZE",
    "TRAIN_KINDS",
    "TRAIN_DOF",
    "TRAIN_STATES",
    "EXTRA",
    "EXT",
    "N_EXT",
    "N_CHECK",
    "EVENT_KINDS",
    "MAX_EVENTS",
    "STATUS",
    "P_ATM",
    "P_CAVITATION",
    "CHECK_VALVE_TRANSITION",
    "extra_layout",
]

# --- valve-train parameters ------------------------------------------------------------
VT_ENABLED = 0  #: 1 with a valve train, 0 for the spring alone [-]
VT_MASS = 1  #: valve-side mass M_v [kg]
VT_K_CAM = 2  #: cam-contact stiffness k_c [N/m]
VT_C_CAM = 3  #: cam-contact damping c_c [N s/m]
VT_K_SEAT = 4  #: valve-seat stiffness k_s [N/m]
VT_C_SEAT = 5  #: valve-seat damping c_s [N s/m]
VT_LASH = 6  #: lash at the valve side [m]
#: the train's degrees of freedom, the states after the chain's (:data:`TRAIN_DOF` of its kind;
#: array sizes only: the equations choose by :data:`VT_KIND`) [-]
VT_DOF = 7
VT_RATIO = 8  #: lever ratio r [-]
VT_M_LEVER = 9  #: lever (rocker) mass at its tip M_r [kg]
VT_K_TIP = 10  #: lever-tip contact stiffness k_t [N/m]
VT_C_TIP = 11  #: lever-tip contact damping c_t [N s/m]
VT_M_LIFTER = 12  #: lifter mass M_f [kg]
VT_K_PUSH = 13  #: pushrod stiffness k_p [N/m]
VT_C_PUSH = 14  #: pushrod damping c_p [N s/m]
VT_LOBE_LASH = 15  #: lobe lift that starts the event [m]
# hydraulic lash adjuster at a finger follower's pivot or in a bucket (:mod:`springdyn.valve.train.hla`;
# zeros without one)
VT_HLA = 16  #: 1 with the adjuster's dynamics (kinds TRAIN_BUCKET_HLA, TRAIN_LEVER_HLA), 0 without [-]
VT_HLA_AREA = 17  #: plunger area A_p [m^2]
VT_HLA_V0 = 18  #: chamber volume at the initial plunger position [m^3]
VT_HLA_Y0 = 19  #: initial plunger position (finger) or collapse (bucket) [m]
VT_HLA_MP = 20  #: plunger mass [kg]
VT_HLA_MA = 21  #: lever mass at the socket (the pivot end), or the bucket body's mass [kg]
VT_HLA_FS = 22  #: plunger-spring force [N]
VT_HLA_KS = 23  #: socket contact stiffness [N/m]
VT_HLA_CS = 24  #: socket contact damping [N s/m]
VT_HLA_G = 25  #: leakage conductance [m^3/(s Pa)]
VT_HLA_DRAG = 26  #: Couette drag area pi D c / 2 [m^2]
VT_HLA_PS = 27  #: supply pressure, absolute [Pa]
VT_HLA_PCRACK = 28  #: check-valve cracking pressure [Pa]
VT_HLA_KCV = 29  #: check-valve flow coefficient Cd A sqrt(2 / rho) [m^3/(s Pa^0.5)]
VT_HLA_BETA = 30  #: bulk modulus of air-free oil [Pa]
VT_HLA_AIR = 31  #: free-air volume fraction at atmospheric pressure [-]
VT_HLA_N = 32  #: polytropic index of the air [-]
VT_HLA_YMAX = 33  #: plunger travel into the body to its bottom (from the initial position) [m]
VT_HLA_YMIN = 34  #: plunger travel out of the body to its clip (negative) [m]
VT_HLA_KSTOP = 35  #: stiffness of the plunger's travel stops [N/m]
VT_HLA_CSTOP = 36  #: damping of the plunger in its bore and stops [N s/m]
#: samples of the gas force on the valve over one revolution (0: none); the samples follow
#: the vector's fixed entries (:mod:`springdyn.valve.train.gas_force`) [-]
VT_GAS_N = 37
#: cam angular acceleration alpha [rad/s^2] of a speed ramp: the cam angle is
#: ``omega t + alpha t^2 / 2`` (0: constant speed; :mod:`springdyn.valve.run.run_up`)
VT_ALPHA = 38
# lever kinematics from the 2-D geometry (:mod:`springdyn.valve.train.lever`; zeros: the constant ratio)
VT_GEOM = 39  #: 1 with the lever's geometry (layout rocker), 0 for the constant ratio [-]
VT_PAD_A = 40  #: the pad's A = (P_0 - O) . d [m] (:func:`springdyn.valve.train.lever.valve_side_lift`)
VT_PAD_R2 = 41  #: A^2 + B^2 [m^2]
VT_LEVER_J = 42  #: the lever's inertia about its pivot, roller included [kg m^2]
#: samples of the lever's ratio table ``c, dc/dtheta, n . d, d(n . d)/dtheta`` over a
#: revolution, after the gas force's samples (0: none) [-]
VT_GEOM_N = 43
#: the adjuster's collapse as a periodicity force: the force [N] per metre of collapse that the
#: train would see through it (:meth:`springdyn.valve.train.definition.ValveTrain.hla_check_stiffness`) [N/m]
VT_HLA_KCHK = 44
#: the kind of train (``TRAIN_*`` below): which equations the engine runs [-]
VT_KIND = 45
#: Slots of the parameter vector; the gas force's samples and the lever's table follow them.
VT_SIZE = 46

# --- kinds of valve train (slot VT_KIND) ---------------------------------------------------
TRAIN_SPRING_ALONE = 0  #: no train: the retainer end follows the cam (the all-zero vector)
TRAIN_DIRECT = 1  #: direct-acting (bucket tappet): the cam on the valve body
TRAIN_LEVER = 2  #: finger follower / rocker arm on a fixed pivot (constant ratio or drawn geometry)
TRAIN_PUSHROD = 3  #: OHV: lifter, pushrod, rocker
TRAIN_BUCKET_HLA = 4  #: hydraulic bucket tappet: the adjuster inside the bucket (``[hla]``, direct-acting)
TRAIN_LEVER_HLA = 5  #: finger follower on a hydraulic lash adjuster at its pivot (``[hla]``, rocker)
#: The kinds' names.
TRAIN_KINDS = {
    TRAIN_SPRING_ALONE: "spring alone",
    TRAIN_DIRECT: "direct-acting",
    TRAIN_LEVER: "lever",
    TRAIN_PUSHROD: "pushrod",
    TRAIN_BUCKET_HLA: "hydraulic bucket",
    TRAIN_LEVER_HLA: "lever on a hydraulic lash adjuster",
}

# --- the train's states: offsets from its first, ``s[nm + S_*]``, after the chain's nm masses;
# each velocity at ``s[nfree + nm + S_*]`` (a first-order state has an unused velocity slot)
S_VALVE = 0  #: every kind: the valve body's lift z [m]
S_LEVER = 1  #: lever, pushrod, lever on an adjuster: the lever's valve-side tip [m]
S_LIFTER = 2  #: pushrod: the lifter on the cam [m]
S_PIVOT = 2  #: lever on an adjuster: the finger's pivot end y_a (collapse direction positive) [m]
S_BUCKET = 1  #: hydraulic bucket: the bucket body on the cam y_b [m]
S_LEVER_HLA = 3  #: lever on an adjuster: the adjuster's first state (``H_*`` from here)
S_BUCKET_HLA = 2  #: hydraulic bucket: the adjuster's first state (``H_*`` from here)
# the adjuster's states, from its first (S_LEVER_HLA or S_BUCKET_HLA)
H_PLUNGER = 0  #: the plunger y_p [m]
H_PRESSURE = 1  #: the chamber pressure, absolute [Pa] (first order)
H_INFLOW = 2  #: oil in through the check valve since the start [m^3] (first order)
H_LEAK = 3  #: oil out through the clearance since the start [m^3] (first order)
N_HLA_STATES = 4
#: The train's states of each kind, in order (their offsets are their positions) [-].
TRAIN_STATES = {
    TRAIN_SPRING_ALONE: (),
    TRAIN_DIRECT: ("valve",),
    TRAIN_LEVER: ("valve", "lever"),
    TRAIN_PUSHROD: ("valve", "lever", "lifter"),
    TRAIN_BUCKET_HLA: ("valve", "bucket", "plunger", "pressure", "inflow", "leak"),
    TRAIN_LEVER_HLA: ("valve", "lever", "pivot", "plunger", "pressure", "inflow", "leak"),
}
#: Degrees of freedom of each kind (slot :data:`VT_DOF`) [-].
TRAIN_DOF = {kind: len(states) for kind, states in TRAIN_STATES.items()}

# --- constants of the compiled hydraulic laws (springdyn.valve.train.hla and .oil use these) -------
#: Standard atmospheric pressure [Pa]: gauge pressures of the ``[hla]`` table are above it.
P_ATM = 101325.0
#: Lowest absolute chamber pressure [Pa]: below it the oil releases its air and vapour
#: (the chamber cavitates); the pressure is held there and the check valve refills.
P_CAVITATION = 2000.0
#: Pressure difference [Pa] below which the check valve's orifice flow is taken as laminar
#: (linear in the pressure difference), so that the flow has a finite slope at zero.
CHECK_VALVE_TRANSITION = 2000.0

# --- the right-hand side's extra outputs: offsets after the 2 (N + 1) element values ----
X_LIFT = 0  #: cam lift [m]
X_DLIFT = 1  #: cam lift rate [m/s]
X_CAM_FORCE = 2  #: cam contact force [N]
X_SEAT_FORCE = 3  #: valve-seat force [N]
X_TOP = 4  #: displacement of the retainer end (the valve lift with a train) [m]
X_DISP = 5  #: first of the N mass displacements [m]; the tail ``XT_*`` follows them
# the tail: offsets after the N displacements, ``extra[2 (N + 1) + X_DISP + N + XT_*]``
XT_CAM_GAP = 0  #: the signed cam-contact gap [m] (positive in contact; 1 for the spring alone)
XT_HLA_COLLAPSE = 1  #: the adjuster's collapse from its base-circle position [m] (0 without)
XT_HLA_PRESSURE = 2  #: the chamber pressure above the supply [Pa]
XT_SOCKET_FORCE = 3  #: the socket force [N]
XT_HLA_INFLOW = 4  #: oil in through the check valve since the start [m^3]
XT_HLA_LEAK = 5  #: oil out through the clearance since the start [m^3]
XT_HLA_CHECK = 6  #: the collapse as a periodicity force [N] (:data:`CHK_HLA`)
N_HLA_EXTRA = 6  #: the adjuster's outputs in the tail [-]
# a spring pack's parallel chains (one chain: the end elements' own values)
XT_SEAT_TOTAL = 7  #: the seat force, the sum of every chain's first element [N]
XT_RETAINER_TOTAL = 8  #: the retainer force, the sum of every chain's last element [N]
XT_SEAT_COMPRESSION = 9  #: the smallest compression of the chains' seat contacts [m]
XT_RETAINER_COMPRESSION = 10  #: the smallest compression of the chains' retainer contacts [m]
XT_DAMPER_FORCE = 11  #: a friction damper's force on its node (:data:`DAMPER_SIZE`) [N]
XT_DAMPER_SLIP = 12  #: its sliding velocity, the node's less its counterpart's [m/s]
#: the power the chains dissipate, their elements' damping and the friction damper [W]
XT_DISSIPATION = 13
N_TAIL = 14

# --- a spring pack: parallel chains between the seat and the one retainer ------------------
#: A friction damper's row of ``EngineModel.damper``: the node it acts on (a
#: mass index), its counterpart (a mass index, or -1 for the seat), the Coulomb force [N]
#: and the regularising velocity [m/s] (0 force: no damper).
DAMPER_NODE, DAMPER_OTHER, DAMPER_FORCE, DAMPER_VREG = range(4)
DAMPER_SIZE = 4

#: Names of the ``extra`` outputs for the 5-mass Type C chain (:func:`extra_layout` for any N).
EXTRA = (
    "f1",
    "f2",
    "f3",
    "f4",
    "f5",
    "f6",
    "x1",
    "x2",
    "x3",
    "x4",
    "x5",
    "x6",
    "lift",
    "dlift",
    "cam_contact_force",
    "valve_seat_force",
    "top_displacement",
    "u1",
    "u2",
    "u3",
    "u4",
    "u5",
    "cam_gap",
    "hla_collapse",
    "hla_pressure",
    "socket_force",
    "hla_inflow",
    "hla_leak",
    "hla_check",
    "seat_total",
    "retainer_total",
    "seat_compression",
    "retainer_compression",
    "damper_force",
    "damper_slip",
    "dissipation",
)


def extra_layout(n_masses: int, n_chains: int = 1) -> dict:
    """Slices / indices of the ``extra`` output of the right-hand side for a chain of ``n_masses``.

    A spring pack's chains lie one after the other: ``n_masses`` masses in all and
    ``n_masses + n_chains`` elements, each chain's from its seat element to its retainer element.

    Parameters
    ----------
    n_masses : int
        Number of chain masses (5 for Type C), of all the pack's chains [-].
    n_chains : int
        Parallel chains between the seat and the retainer (the springs of a pack) [-].

    Returns
    -------
    dict
        ``force`` and ``compression`` (slices over the ``n_masses + 1`` elements), ``lift``,
        ``dlift``, ``cam_contact_force``, ``valve_seat_force``, ``top_displacement`` (ints),
        ``displacement`` (slice over the masses), ``cam_gap``, the adjuster's ``hla_collapse``
        [m], ``hla_pressure`` [Pa], ``socket_force`` [N], ``hla_inflow`` and ``hla_leak``
        (volumes since the start [m^3]), ``hla_check`` (the collapse as a periodicity force
        [N], :data:`CHK_HLA`), the pack's totals ``seat_total``, ``retainer_total`` [N],
        ``seat_compression``, ``retainer_compression`` [m], the friction damper's
        ``damper_force`` [N], ``damper_slip`` [m/s] and the chains' ``dissipation`` [W]
        (ints) and ``size``.
    """
    ne = n_masses + n_chains
    b = 2 * ne
    tail = b + X_DISP + n_masses
    return dict(
        force=slice(0, ne),
        compression=slice(ne, b),
        lift=b + X_LIFT,
        dlift=b + X_DLIFT,
        cam_contact_force=b + X_CAM_FORCE,
        valve_seat_force=b + X_SEAT_FORCE,
        top_displacement=b + X_TOP,
        displacement=slice(b + X_DISP, tail),
        cam_gap=tail + XT_CAM_GAP,
        hla_collapse=tail + XT_HLA_COLLAPSE,
        hla_pressure=tail + XT_HLA_PRESSURE,
        socket_force=tail + XT_SOCKET_FORCE,
        hla_inflow=tail + XT_HLA_INFLOW,
        hla_leak=tail + XT_HLA_LEAK,
        hla_check=tail + XT_HLA_CHECK,
        seat_total=tail + XT_SEAT_TOTAL,
        retainer_total=tail + XT_RETAINER_TOTAL,
        seat_compression=tail + XT_SEAT_COMPRESSION,
        retainer_compression=tail + XT_RETAINER_COMPRESSION,
        damper_force=tail + XT_DAMPER_FORCE,
        damper_slip=tail + XT_DAMPER_SLIP,
        dissipation=tail + XT_DISSIPATION,
        size=tail + N_TAIL,
    )


# --- the monitor's extremes per speed ----------------------------------------------------
EXT = (
    "max_retainer_force",
    "t_max_retainer_force",
    "min_retainer_force",
    "t_min_retainer_force",
    "max_seat_force",
    "t_max_seat_force",
    "min_seat_force",
    "t_min_seat_force",
    "min_cam_contact_force",
    "t_min_cam_contact_force",
    "seat_impact_velocity",
    "t_seat_impact",
    "seat_landings",
    "events_lost",
)
N_EXT = len(EXT)
EXT_MAX_RETAINER = 0
EXT_MIN_RETAINER = 2
EXT_MAX_SEAT = 4
EXT_MIN_SEAT = 6
EXT_MIN_CAM = 8
EXT_IMPACT_VELOCITY = 10
EXT_IMPACT_TIME = 11
EXT_LANDINGS = 12
EXT_LOST = 13

#: The extremes that are values (not times or counts): the periodicity bands cover them.
EXT_VALUES = (
    EXT_MAX_RETAINER,
    EXT_MIN_RETAINER,
    EXT_MAX_SEAT,
    EXT_MIN_SEAT,
    EXT_MIN_CAM,
    EXT_IMPACT_VELOCITY,
    EXT_LANDINGS,
)

# --- periodicity channels: the forces two revolutions must repeat ------------------------
CHK_SEAT = 0  #: seat end force [N]
CHK_RETAINER = 1  #: retainer end force [N]
CHK_CAM = 2  #: cam contact force [N] (valve train)
CHK_VALVE_SEAT = 3  #: valve-seat force [N] (valve train)
#: a hydraulic lash adjuster's collapse times :data:`VT_HLA_KCHK` [N]: an adjuster that creeps
#: (pumps up or leaks down from revolution to revolution) is not a steady state even where
#: the forces repeat
CHK_HLA = 4
N_CHECK = 5

#: Extreme signals (maximised): retainer force, -retainer force, seat force, -seat force,
#: -cam contact force while the valve is open.
SIG_RETAINER_MAX, SIG_RETAINER_MIN, SIG_SEAT_MAX, SIG_SEAT_MIN, SIG_CAM_MIN = range(5)
N_SIG = 5

# --- events --------------------------------------------------------------------------------
#: Event kinds of the monitored integration (column :data:`EV_KIND` of the event table).
EVENT_KINDS = {0: "end separation", 1: "coil contact", 2: "lift-off", 3: "valve landing"}
EV_KIND = 0  #: column: the kind (a key of EVENT_KINDS)
EV_INDEX = 1  #: column: the end (0 seat, 1 retainer) or the element
EV_START = 2  #: column: start time [s]
EV_END = 3  #: column: end time [s] (a landing: its impact velocity [m/s])
#: The kinds' codes as the event table's float column holds them.
KIND_SEPARATION, KIND_COIL_CONTACT, KIND_LIFT_OFF, KIND_LANDING = 0.0, 1.0, 2.0, 3.0
#: Event table rows per speed (further events are counted in ``events_lost``).
MAX_EVENTS = 512
#: Event channels before the coil gaps: seat end, retainer end, the train's smallest gap.
CH_SEAT, CH_RETAINER, CH_TRAIN = range(3)
N_FIXED_CHANNELS = 3

#: Status codes of the integration.
STATUS = {0: "ok", 1: "too many steps", 2: "step size collapsed", 3: "the solution is not finite (NaN/inf)"}
