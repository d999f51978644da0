"""Leaf spring dampers for rotors (the leaf-spring-damper thesis, Kim 2000).

An inner ring carrying a rolling bearing is held by ``N`` packs of leaf springs; the
spaces between the packs are oil chambers joined by narrow passages.  Modules:

- :mod:`~springdyn.lsd.leafpack` -- load sharing between leaves, pack stiffness (2.4)-(2.10);
- :mod:`~springdyn.lsd.stiffness` -- stiffness matrix of packs at any angles (3.4), preload check;
- :mod:`~springdyn.lsd.damping` -- O-ring and inter-leaf friction (2.21)-(2.28), the oil
  network ``C_visc = B^T G^+ B`` and (3.5)-(3.6), passage conductance (2.17), passage
  inertance, duct impedance and the squeeze Reynolds number;
- :mod:`~springdyn.lsd.forces` -- the nonlinear force laws in time: pack springs with lift-off,
  inter-leaf and O-ring Coulomb friction (2.21), (2.25)-(2.27);
- :mod:`~springdyn.lsd.film` -- the oil network in time: passage inertia, film rupture
  (cavitation) against the supply pressure, its describing function and the speed x orbit map;
- :mod:`~springdyn.lsd.parameters` -- :class:`LSDParameters` (TOML ``[lsd]`` table, Types A-C);
- :mod:`~springdyn.lsd.model` -- :class:`LSDModel`, :class:`LSDCoefficients` (K, C vs rpm);
- :mod:`~springdyn.lsd.rig` -- time-domain test-rig simulation (Chapter 4) of a model with those
  laws, :class:`RigRecord`;
- :mod:`~springdyn.lsd.identify` -- identification (4.1)-(4.22) with the corrected algebra;
- :mod:`~springdyn.lsd.equivalent` -- describing-function coefficients of the nonlinear laws at an amplitude;
- :mod:`~springdyn.lsd.calibrate` -- fit parameters (``leakage_factor`` ...) to rig records;
- :mod:`~springdyn.lsd.jeffcott` -- amplitude-consistent unbalance response of a simple rotor;
- :mod:`~springdyn.lsd.rotordynamics` -- the damper as a ``ross.BearingElement`` (never extrapolating),
  its nonlinear force in ROSS's time response;
- :mod:`~springdyn.lsd.rotor_time` -- time response of a ROSS rotor with the film solved implicitly;
- :mod:`~springdyn.lsd.plots` -- the figures of the results.

The names below load their modules on first use, so that ``import springdyn.lsd`` stays quick.
"""

from __future__ import annotations

from .._lazy import lazy_package

_EXPORTS = {
    "boundary_conductance": "damping",
    "chamber_volume_matrix": "damping",
    "coulomb_equivalent_damping": "damping",
    "hysteresis_damping_matrix": "damping",
    "leaf_loss_factor": "damping",
    "passage_conductance_rectangular": "damping",
    "passage_conductance_thesis": "damping",
    "viscous_damping_matrix": "damping",
    "viscous_damping_thesis": "damping",
    "passage_inertance": "damping",
    "squeeze_reynolds_number": "damping",
    "duct_profile_factor": "damping",
    "duct_impedance_ratio": "damping",
    "FilmMap": "film",
    "FilmNetwork": "film",
    "FilmWarning": "film",
    "film_effect_map": "film",
    "film_harmonic": "film",
    "film_network": "film",
    "simulate_film": "film",
    "rotor_time_response": "rotor_time",
    "unbalance_runup": "rotor_time",
    "small_orbit_element": "rotordynamics",
    "Calibration": "calibrate",
    "calibrate": "calibrate",
    "equivalent_matrices": "equivalent",
    "forward_whirl_coefficient": "equivalent",
    "harmonic_forces": "equivalent",
    "JeffcottRotor": "jeffcott",
    "UnbalanceResponse": "jeffcott",
    "simulate_time_response": "jeffcott",
    "unbalance_response": "jeffcott",
    "bearing_at_frequency": "rotordynamics",
    "whirl_consistent_mode": "rotordynamics",
    "amplitude_consistent_response": "rotordynamics",
    "orbit_dependent_element": "rotordynamics",
    "ConsistentResponse": "rotordynamics",
    "nonlinear_force": "rotordynamics",
    "Identification": "identify",
    "IdentificationSeries": "identify",
    "RigData": "identify",
    "direct_coefficients": "identify",
    "identify": "identify",
    "identify_series": "identify",
    "read_rig_data": "identify",
    "load_ratios": "leafpack",
    "load_ratios_direct": "leafpack",
    "pack_stiffness": "leafpack",
    "stiffness_factor": "leafpack",
    "LSDCoefficients": "model",
    "LSDModel": "model",
    "LSDParameters": "parameters",
    "RigRecord": "rig",
    "Trajectory": "rig",
    "circular_orbit": "rig",
    "linear_shake": "rig",
    "simulate_rig": "rig",
    "trajectory_from_samples": "rig",
    "PreloadExceededWarning": "stiffness",
    "equally_spaced_angles": "stiffness",
    "isotropic_stiffness": "stiffness",
    "stiffness_matrix": "stiffness",
}

__all__ = [
    "LSDParameters",
    "LSDModel",
    "LSDCoefficients",
    "RigRecord",
    "Trajectory",
    "RigData",
    "Identification",
    "IdentificationSeries",
    "PreloadExceededWarning",
    "circular_orbit",
    "linear_shake",
    "trajectory_from_samples",
    "simulate_rig",
    "read_rig_data",
    "identify",
    "identify_series",
    "direct_coefficients",
    "load_ratios",
    "load_ratios_direct",
    "stiffness_factor",
    "pack_stiffness",
    "equally_spaced_angles",
    "stiffness_matrix",
    "isotropic_stiffness",
    "coulomb_equivalent_damping",
    "leaf_loss_factor",
    "hysteresis_damping_matrix",
    "passage_conductance_thesis",
    "passage_conductance_rectangular",
    "boundary_conductance",
    "chamber_volume_matrix",
    "viscous_damping_matrix",
    "viscous_damping_thesis",
    "calibrate",
    "Calibration",
    "harmonic_forces",
    "equivalent_matrices",
    "forward_whirl_coefficient",
    "JeffcottRotor",
    "UnbalanceResponse",
    "unbalance_response",
    "simulate_time_response",
    "bearing_at_frequency",
    "whirl_consistent_mode",
    "nonlinear_force",
    "small_orbit_element",
    "passage_inertance",
    "squeeze_reynolds_number",
    "duct_profile_factor",
    "duct_impedance_ratio",
    "FilmMap",
    "FilmNetwork",
    "FilmWarning",
    "film_effect_map",
    "film_harmonic",
    "film_network",
    "simulate_film",
    "rotor_time_response",
    "unbalance_runup",
]


lazy_package(__name__, _EXPORTS)
