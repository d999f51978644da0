"""Deprecated: use :mod:`springdyn.core.io`."""
from ._deprecated import alias

alias(__name__, "springdyn.core.io")
