"""Deprecated: use :mod:`springdyn.numerics.erk`."""
from ._deprecated import alias

alias(__name__, "springdyn.numerics.erk")
