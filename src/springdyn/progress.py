"""Deprecated: use :mod:`springdyn.core.progress`."""
from ._deprecated import alias

alias(__name__, "springdyn.core.progress")
