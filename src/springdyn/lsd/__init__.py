"""Leaf spring dampers for rotors (the leaf-spring-damper thesis, Kim 2000).

An inner ring carrying a rolling bearing is held by ``N`` packs of leaf springs; the
spaces between the packs are oil chambers joined by narrow passages.  Modules:

- :mod:`~springdyn.lsd.leafpack` -- load sharing between leaves, pack stiffness (2.4)-(2.10);
- :mod:`~springdyn.lsd.stiffness` -- stiffness matrix of packs at any angles (3.4), preload check;
- :mod:`~springdyn.lsd.damping` -- O-ring and inter-leaf friction (2.21)-(2.28), the oil
  network ``C_visc = B^T G^+ B`` and (3.5)-(3.6), passage conductance (2.17);
- :mod:`~springdyn.lsd.parameters` -- :class:`LSDParameters` (TOML ``[lsd]`` table, Types A-C);
- :mod:`~springdyn.lsd.model` -- :class:`LSDModel`, :class:`LSDCoefficients` (K, C vs rpm);
- :mod:`~springdyn.lsd.rig` -- time-domain test-rig simulation (Chapter 4), :class:`RigRecord`;
- :mod:`~springdyn.lsd.identify` -- identification (4.1)-(4.22) with the corrected algebra;
- :mod:`~springdyn.lsd.rotordynamics` -- the damper as a ``ross.BearingElement``.
"""

from .damping import (
    boundary_conductance,
    chamber_volume_matrix,
    coulomb_equivalent_damping,
    hysteresis_damping_matrix,
    leaf_loss_factor,
    passage_conductance_rectangular,
    passage_conductance_thesis,
    viscous_damping_matrix,
    viscous_damping_thesis,
)
from .identify import (
    Identification,
    IdentificationSeries,
    RigData,
    direct_coefficients,
    identify,
    identify_series,
    read_rig_data,
)
from .leafpack import load_ratios, load_ratios_direct, pack_stiffness, stiffness_factor
from .model import LSDCoefficients, LSDModel
from .parameters import LSDParameters
from .rig import RigRecord, Trajectory, circular_orbit, linear_shake, simulate_rig, trajectory_from_samples
from .stiffness import PreloadExceededWarning, equally_spaced_angles, isotropic_stiffness, stiffness_matrix

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
]
