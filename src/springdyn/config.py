"""Deprecated: use :mod:`springdyn.core.params`."""
from ._deprecated import alias

alias(__name__, "springdyn.core.params")
