"""Every result object of every family has the Result interface.

The walk finds every class of the family packages that looks like a result (it has
``to_xarray`` or ``to_csv``); each must subclass :class:`springdyn.core.results.Result` and
have a factory below that builds a small instance, which must pass the whole interface
check (summary, to_xarray with units, derived CSV, plot(path) and plot(ax), reprs).
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import numpy as np
import pytest

import springdyn
from springdyn.core.results import Result
from tests.paths import example
from tests.result_checks import check_result_interface


def _result_like_classes():
    found = {}
    for family in ("valve", "cfcs", "lsd"):
        pkg = importlib.import_module(f"springdyn.{family}")
        for info in pkgutil.walk_packages(pkg.__path__, f"springdyn.{family}."):
            module = importlib.import_module(info.name)
            for name, cls in inspect.getmembers(module, inspect.isclass):
                if cls.__module__ != module.__name__ or name.startswith("_"):
                    continue
                if hasattr(cls, "to_xarray") or hasattr(cls, "to_csv"):
                    found[f"{cls.__module__}.{name}"] = cls
    return found


def _valve_spring():
    from springdyn.valve import ValveSpring

    return ValveSpring.example("one-step")


def _valve_cam():
    from springdyn.valve import Cam

    return Cam.from_dict({"law": "3-4-5", "lift": "9 mm", "duration": "120 deg"})


def _valve_train():
    from springdyn.valve import ValveTrain

    return ValveTrain.example() if hasattr(ValveTrain, "examples") and ValveTrain.examples else None


def _cfcs():
    from springdyn.cfcs import CFCS

    return CFCS.example("table1")


def _lsd():
    from springdyn.lsd import LSDModel, LSDParameters

    return LSDModel(LSDParameters.example("C"))


def _rig(excitation="x"):
    from springdyn.lsd import simulate_rig
    from springdyn.lsd.rig import circular_orbit, linear_shake

    tr = (
        linear_shake(1000.0, 50e-6, excitation, 3, 5e3) if excitation in "xy" else circular_orbit(1000.0, 50e-6, 3, 5e3)
    )
    return simulate_rig(_lsd(), tr)


def _identified():
    from springdyn.lsd import identify_series

    return identify_series([_rig("x")], [_rig("y")], mass=0.5)


def _calibration():
    from springdyn.lsd import LSDParameters, RigData, linear_shake, simulate_rig
    from springdyn.lsd.calibrate import calibrate

    truth = _lsd().params.replace(leakage_factor=2.0)
    from springdyn.lsd import LSDModel

    recs = [simulate_rig(LSDModel(truth), linear_shake(rpm, 50e-6, "x", 4, 5e3)) for rpm in (500.0, 1500.0)]
    data = [RigData(r.time, r.x, r.y, r.fx, r.fy, source=f"x{i}.csv") for i, r in enumerate(recs)]
    return calibrate(LSDParameters.example("C"), data)


def _unbalance():
    from springdyn.lsd.jeffcott import JeffcottRotor, unbalance_response

    rotor = JeffcottRotor(disk_mass=20.0, shaft_stiffness=5e6, bearing_mass=1.0, unbalance=1e-3)
    return unbalance_response(_lsd(), rotor, [1000.0, 2000.0])


def _friction():
    """Friction of the bucket train with its [follower] and [friction] at two speeds."""
    fr = importlib.import_module("springdyn.valve.train.friction")
    path = example("valve/valve_train_with_follower.toml")
    vt = springdyn.valve.ValveTrain.from_toml(path)
    follower = importlib.import_module("springdyn.valve.cam.follower").Follower.in_file(path)
    friction = fr.Friction.from_dict(importlib.import_module("springdyn.core.params").load_toml(path)["friction"])
    cam = springdyn.valve.Cam.from_toml(example("valve/cam_polydyne_ramps.toml"))
    return [
        importlib.import_module("springdyn.valve.run.friction").simulation_friction(
            springdyn.valve.simulate(_valve_spring(), cam, rpm, valve_train=vt), follower, friction
        )
        for rpm in (1500.0, 3000.0)
    ]


def _valve_clearance():
    """The clearance map of the bucket example's [piston] over a cam lift and a raised copy of it
    (no run: the valve lifts given)."""
    from springdyn.valve.cam.timing import Timing, crank_axis
    from springdyn.valve.train.piston import Piston, clearance_map

    cam = _valve_cam()
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    lift = cam.lift_at(theta)
    return clearance_map(
        Piston.in_file(example("valve/bucket_piston.toml")),
        crank_axis(cam, Timing.from_dict({"lobe_centre": "104 deg", "valve": "exhaust"})),
        theta,
        np.stack([lift, 1.1 * lift]),
        lift,
        [2000.0, 4000.0],
        valve="exhaust",
        limit=1e-3,
    )


def _film_map():
    from springdyn.lsd.film import film_effect_map

    return film_effect_map(_lsd(), [3000.0, 14100.0], [20e-6, 100e-6], steps=128)


def _camshaft():
    return springdyn.valve.CamshaftModel.from_toml(example("valve/camshaft_4lobe.toml")).with_settings(
        points_per_revolution=360
    )


FACTORIES = {
    "springdyn.valve.camshaft.results.TorsionalModes": lambda: _camshaft().modes(),
    "springdyn.valve.camshaft.results.CamshaftRun": lambda: _camshaft().simulate(2000.0),
    "springdyn.valve.camshaft.results.CamshaftSweep": lambda: _camshaft().sweep([1500.0, 2500.0]),
    "springdyn.lsd.calibrate.Calibration": _calibration,
    "springdyn.lsd.film.FilmMap": _film_map,
    "springdyn.lsd.jeffcott.UnbalanceResponse": _unbalance,
    "springdyn.lsd.model.LSDCoefficients": lambda: _lsd().coefficients([500.0, 1000.0, 2000.0], amplitude=20e-6),
    "springdyn.lsd.rig.RigRecord": lambda: _rig("x"),
    "springdyn.lsd.identify.RigData": lambda: __import__("springdyn.lsd.identify", fromlist=["RigData"]).RigData(
        *(getattr(_rig("y"), k) for k in ("time", "x", "y", "fx", "fy")), source="measured.csv"
    ),
    "springdyn.lsd.identify.IdentificationSeries": _identified,
    "springdyn.cfcs.results.StaticResult": lambda: _cfcs().static(),
    "springdyn.cfcs.results.DynamicResult": lambda: _cfcs().dynamic(14.7),
    "springdyn.cfcs.results.FrequencySweep": lambda: _cfcs().sweep(np.array([2.0, 10.0, 20.0])),
    "springdyn.cfcs.results.ForwardResult": lambda: _cfcs().forward(0.05, force=12.8),
    "springdyn.cfcs.results.DrivenResult": lambda: _cfcs().driven(
        14.7, drive_stiffness=2e4, periods=2, samples_per_period=200
    ),
    "springdyn.cfcs.design.DesignResult": lambda: __import__("springdyn.cfcs", fromlist=["design"]).design(
        12.8, 0.02, 207e9, 1.5e9
    ),
    "springdyn.valve.spring.results.StaticCurve": lambda: _valve_spring().spring_model.static_curve(points=50),
    "springdyn.valve.run.results.Simulation": lambda: springdyn.valve.simulate(
        _valve_spring(), _valve_cam(), 2500, 2, points_per_revolution=360
    ),
    "springdyn.valve.run.results.FloatSpeedResult": lambda: springdyn.valve.run.results.FloatSpeedResult(
        [1000.0, 2000.0], [120.0, -5.0], 1800.0, [1500.0, 1800.0], 1.0
    ),
    "springdyn.valve.run.results.NaturalFrequencies": lambda: springdyn.valve.ValveModel(
        _valve_spring(), _valve_cam(), _valve_train()
    ).natural_frequencies(4),
    "springdyn.valve.run.sweeps.SpeedSweep": lambda: springdyn.valve.sweep(
        _valve_spring(),
        _valve_cam(),
        np.array([1000.0, 2000.0, 3000.0]),
        revolutions=2,
        points_per_revolution=180,
        quiet=True,
    ),
    "springdyn.valve.cam.analysis.CamAnalysis": lambda: importlib.import_module(
        "springdyn.valve.cam.analysis"
    ).analyse_cam(_valve_cam(), _valve_train(), engine_rpm=6000.0),
    "springdyn.valve.cam.checks.CamCheck": lambda: importlib.import_module("springdyn.valve.cam.checks").check_cam(
        _valve_cam(),
        springdyn.valve.ValveTrain.from_toml(example("valve/valve_train_with_follower.toml")),
        importlib.import_module("springdyn.valve.cam.follower").Follower.in_file(
            example("valve/valve_train_with_follower.toml")
        ),
        _valve_spring(),
        cam_rpm=3000.0,
    ),
    "springdyn.valve.train.friction.FrictionAnalysis": lambda: _friction()[0],
    "springdyn.valve.train.piston.ValveClearance": _valve_clearance,
    "springdyn.valve.run.friction.FrictionSweep": lambda: importlib.import_module(
        "springdyn.valve.run.friction"
    ).friction_over_speed(_friction()),
    "springdyn.valve.design.synthesis.Synthesis": lambda: importlib.import_module(
        "springdyn.valve.design.synthesis"
    ).synthesize(
        importlib.import_module("springdyn.valve.design.synthesis").Requirements.from_dict(
            dict(
                installed_length="38 mm",
                installed_force="250 N",
                lift="9 mm",
                open_force="460 N",
                max_outer_diameter="27 mm",
                min_inner_diameter="16 mm",
            )
        ),
        per_kind=1,
    ),
    "springdyn.valve.design.tolerances.ToleranceStudy": lambda: importlib.import_module(
        "springdyn.valve.design.tolerances"
    ).tolerance_study(
        _valve_spring(),
        _valve_cam(),
        {
            "wire_diameter": importlib.import_module("springdyn.valve.design.tolerances").parse_tolerance(
                "wire_diameter", "+-0.02 mm"
            )
        },
        count=8,
        seed=1,
        speeds=[2000.0],
    ),
    "springdyn.valve.design.life.ServiceLife": lambda: importlib.import_module(
        "springdyn.valve.design.life"
    ).service_life(
        _valve_spring(),
        _valve_cam(),
        importlib.import_module("springdyn.valve.design.life").LoadSpectrum.from_dict(
            {"cam_rpm": ["1000 rpm", "2000 rpm"], "share": [0.5, 0.5]}
        ),
    ),
    "springdyn.valve.train.lever.LeverTable": lambda: springdyn.valve.ValveTrain.from_toml(
        example("valve/finger_follower_geometry.toml")
    ).geometry.over_cam(springdyn.valve.Cam.from_toml(example("valve/cam_finger.toml")), points=720),
    "springdyn.valve.cam.from_lift.CamFromLift": lambda: importlib.import_module(
        "springdyn.valve.cam.from_lift"
    ).cam_from_card(
        importlib.import_module("springdyn.valve.cam.from_lift").CamCard.from_toml(example("valve/cam_card.toml")),
        springdyn.valve.ValveTrain.from_toml(example("valve/valve_train_with_follower.toml")),
    ),
    "springdyn.valve.run.run_up.RunUp": lambda: importlib.import_module("springdyn.valve.run.run_up").speed_ramp(
        _valve_spring(),
        _valve_cam(),
        _valve_train(),
        3000.0,
        3300.0,
        3000.0,
        points_per_revolution=360,
        float_scan=False,
    ),
    "springdyn.valve.spring.frf.FrequencyResponse": lambda: importlib.import_module(
        "springdyn.valve.spring.frf"
    ).dynamic_stiffness(_valve_spring(), np.linspace(50.0, 2000.0, 40)),
}


def test_every_result_class_is_a_result_with_a_factory():
    classes = _result_like_classes()
    assert len(classes) >= 4
    not_results = sorted(name for name, cls in classes.items() if not issubclass(cls, Result))
    assert not not_results, f"result-like classes without the Result interface: {not_results}"
    missing = sorted(set(classes) - set(FACTORIES))
    assert not missing, f"result classes with no factory in this test: {missing}"


@pytest.mark.parametrize("name", sorted(FACTORIES))
def test_result_interface(name, tmp_path):
    import springdyn.valve.run.results  # noqa: F401  (the factories use the module attributes)

    result = FACTORIES[name]()
    check_result_interface(result, tmp_path)
