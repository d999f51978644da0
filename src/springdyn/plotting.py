"""Deprecated: use :mod:`springdyn.core.plotting`."""
from ._deprecated import alias

alias(__name__, "springdyn.core.plotting")
