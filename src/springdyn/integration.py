"""Deprecated: use :mod:`springdyn.numerics.dopri`."""
from ._deprecated import alias

alias(__name__, "springdyn.numerics.dopri")
