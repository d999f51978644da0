"""ValveModel, the valve family's orchestrator: the same results as the functions it calls,
its derived state built once and visible, clear messages for what it lacks."""

import math

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve import Cam, ValveModel, ValveSpring, ValveTrain, simulate
from springdyn.valve.run.train_modes import natural_frequencies


@pytest.fixture(scope="module")
def model():
    return ValveModel(ValveSpring.example("one-step"), Cam(law="3-4-5", lift=9e-3, duration=math.radians(120)))


def test_the_spring_alone_is_its_chain_models(model):
    spring = model.spring
    assert model.internal_parameters()["Fset"] == pytest.approx(251.43, rel=1e-4)  # docs/valve-spring.md reference
    assert model.static_force(spring.installed_length) == pytest.approx(model.internal_parameters()["Fset"])
    assert np.array_equal(model.modes(0.038, 3), spring.spring_model.modes(0.038, 3))
    assert model.chain_model is spring.spring_model  # derived once, shared with the definition


def test_simulate_is_the_function_with_the_models_set_up(model):
    a = model.simulate(3000.0, 2, points_per_revolution=360)
    b = simulate(model.spring, model.cam, 3000.0, 2, points_per_revolution=360)
    assert a.summary["max_retainer_force_N"] == b.summary["max_retainer_force_N"]  # the same engine, bit for bit
    assert model.setup is model.setup  # a cached property: prepared once


def test_natural_frequencies_is_a_result_of_the_function(model):
    res = model.natural_frequencies(4)
    raw = natural_frequencies(model.spring, model.cam, None, 4)
    assert res.base_circle_Hz == raw["base_circle_Hz"] and res.full_lift_Hz == raw["full_lift_Hz"]
    assert res.summary["first_base_circle_Hz"] == raw["base_circle_Hz"][0]


def test_what_a_model_lacks_is_named():
    bare = ValveModel(ValveSpring.example("one-step"))
    with pytest.raises(InputError, match="simulate needs a cam"):
        bare.simulate(3000.0)
    with pytest.raises(InputError, match="float_speed needs a valve train"):
        ValveModel(bare.spring, Cam(law="3-4-5", lift=9e-3, duration=2.0)).float_speed([1000.0, 2000.0])
    with pytest.raises(InputError, match="must be a ValveSpring"):
        ValveModel("spring.toml")
    assert "valve train" in repr(ValveModel(bare.spring, None, ValveTrain.example("pushrod")))


def test_the_engine_variant_is_the_one_a_run_makes(model):
    """``engine_variant``: the pair the runs choose (``runge_kutta_pair``: Dormand-Prince for
    Type C and for a distributed chain of fewer than BS3_MIN_ELEMENTS elements, else
    Bogacki-Shampine; the settings' method above both), the spring alone or the train; a run
    makes that very variant of the engine (``engine.loop``)."""
    import dataclasses

    from springdyn.valve.engine import loop
    from springdyn.valve.run.settings import BS3_MIN_ELEMENTS
    from tests.paths import ROOT

    train = model.replace(valve_train=ValveTrain.from_toml(ROOT / "examples" / "valve" / "valve_train.toml"))
    distributed = model.with_model("distributed")
    coarse = model.replace(spring=dataclasses.replace(distributed.spring, elements=BS3_MIN_ELEMENTS - 10)).with_model(
        "distributed"
    )
    assert model.engine_variant == ("dopri5", "spring", False)
    assert distributed.engine_variant == ("bs3", "spring", False)
    assert coarse.engine_variant == ("dopri5", "spring", False)
    assert model.with_settings(method="tsit5").engine_variant == ("tsit5", "spring", False)
    assert train.engine_variant == ("dopri5", "train", False)
    for m in (model, distributed):
        m.simulate(2000.0, 1, points_per_revolution=360)
        pair, kind, pack = m.engine_variant
        assert (pair, kind + ("-pack" if pack else "")) in loop._COMPILED
