"""Deprecated: use :mod:`springdyn.core.errors`."""
from ._deprecated import alias

alias(__name__, "springdyn.core.errors")
