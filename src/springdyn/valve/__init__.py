"""Valve springs: the MMS Type C multi-mass model (one-step and two-step).

Modules: :mod:`~springdyn.valve.formulas` (closed-form parameters),
:mod:`~springdyn.valve.elements` (nonlinear element laws and damping),
:mod:`~springdyn.valve.statics` (series equilibrium), :mod:`~springdyn.valve.modes`
(natural frequencies), :mod:`~springdyn.valve.design` (stress, index, surge margin),
:mod:`~springdyn.valve.spring` (the :class:`ValveSpring` parameters and chain).
"""

from .spring import Chain, ValveSpring
from .results import StaticCurve

__all__ = ["ValveSpring", "Chain", "StaticCurve"]
