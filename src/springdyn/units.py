"""Deprecated: use :mod:`springdyn.core.units`."""
from ._deprecated import alias

alias(__name__, "springdyn.core.units")
