"""Old module paths keep working (issue 10 "Keep"): same objects, with a DeprecationWarning."""

import importlib
import sys

import pytest

MOVED = {
    "springdyn.units": "springdyn.core.units",
    "springdyn.config": "springdyn.core.params",
    "springdyn.errors": "springdyn.core.errors",
    "springdyn.io": "springdyn.core.io",
    "springdyn.plotting": "springdyn.core.plotting",
    "springdyn.progress": "springdyn.core.progress",
    "springdyn.integration": "springdyn.numerics.erk",
    "springdyn.numerics.dopri": "springdyn.numerics.erk",
}


@pytest.mark.parametrize("old, new", MOVED.items())
def test_old_module_path_warns_and_is_the_new_module(old, new):
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=new.replace(".", r"\.")):
        module = importlib.import_module(old)
    assert module is importlib.import_module(new)
