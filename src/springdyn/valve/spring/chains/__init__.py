"""The spring models: a valve-spring definition turned into a chain of masses and elements.

A :class:`~springdyn.valve.spring.definition.ValveSpring` is the definition (geometry, material,
damping, the ``model`` key); a model turns it into equations.  Every model offers the
same interface, :class:`~.base.SpringModel`: the chain the engine integrates (masses,
element laws, damping), the static force and stiffness against length, the natural
frequencies and the design figures.

- :mod:`.base` -- :class:`Chain` (masses, element laws, damping) and :class:`SpringModel`
  (statics, modes, design figures from the chain);
- :mod:`.type_c` -- :class:`TypeCModel`, the document's MMS Type C chain of 5 masses;
- :mod:`.distributed` -- :class:`DistributedModel`, the coil-by-coil chain from the geometry.

:data:`MODELS` maps the ``[spring] model`` names to the classes; a new model is a new
class registered there.
"""

from __future__ import annotations

from ....core.errors import InputError
from .base import Chain, SpringModel
from .distributed import DistributedModel
from .type_c import PARAMETER_UNITS, TypeCModel

__all__ = ["Chain", "SpringModel", "TypeCModel", "DistributedModel", "MODELS", "make_model", "PARAMETER_UNITS"]

#: The spring models, by their ``[spring] model`` name.
MODELS = {TypeCModel.name: TypeCModel, DistributedModel.name: DistributedModel}


def make_model(spring, name: str | None = None) -> SpringModel:
    """The model ``name`` (default: the definition's ``model`` key) of a spring definition.

    Parameters
    ----------
    spring : ValveSpring
        The spring definition.
    name : str, optional
        A key of :data:`MODELS`; overrides ``spring.model``.
    """
    name = spring.model if name is None else name
    if name not in MODELS:
        raise InputError(f"model = {name!r} is not a valve-spring model; choose one of {', '.join(map(repr, MODELS))}")
    return MODELS[name](spring)
