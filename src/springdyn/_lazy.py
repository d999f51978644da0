"""Packages whose public names load their modules on first use (PEP 562), keeping
``import springdyn.<family>`` quick."""

from __future__ import annotations

import importlib
import sys
import types


def lazy_package(name: str, exports: dict) -> None:
    """Make the package ``name`` load each of ``exports`` (public name -> submodule) on first use.

    A public function named like its own submodule (``springdyn.cfcs.design``, the
    function, in ``design.py``) stays the function: the import system's record of the
    submodule on the package is kept out of the way (the module is in ``sys.modules``).
    """
    package = sys.modules[name]

    def __getattr__(attr):
        if attr in exports:
            value = getattr(importlib.import_module(f"{name}.{exports[attr]}"), attr)
            if exports[attr] != attr:
                package.__dict__[attr] = value
            return value
        raise AttributeError(f"module {name!r} has no attribute {attr!r}")

    def __dir__():
        return sorted(set(package.__dict__) | set(exports))

    shadowed = [a for a, mod in exports.items() if a == mod]
    if shadowed:
        namespace = {}
        for attr in shadowed:

            def get(self, attr=attr):
                return getattr(importlib.import_module(f"{name}.{attr}"), attr)

            def set_(self, value, attr=attr):
                if not isinstance(value, types.ModuleType):  # the import system records the submodule here
                    self.__dict__[attr] = value

            namespace[attr] = property(get, set_)
        package.__class__ = type(f"_{name.replace('.', '_')}_package", (types.ModuleType,), namespace)
    package.__getattr__ = __getattr__
    package.__dir__ = __dir__
