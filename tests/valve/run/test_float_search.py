"""The float speed near a known one (springdyn.valve.run.float_search.float_speed_near, issue 29
part 3): the search a tolerance study runs per variant, checked against the definition (the
scan and bisection of ``float_speed``), on two output grids, and at the range's ends."""

from __future__ import annotations

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve import Cam, ValveSpring, ValveTrain
from springdyn.valve.design.tolerances import variant
from springdyn.valve.run.float_search import float_speed, float_speed_near, nose_gap
from springdyn.valve.run.setup import prepare
from tests.paths import example

SPRING = example("valve/one_step_spring.toml")
CAM = example("valve/cam_polydyne_ramps.toml")
VT = example("valve/valve_train.toml")
SCAN = np.arange(2900.0, 3401.0, 100.0)


@pytest.fixture(scope="module")
def train():
    return ValveSpring.from_toml(SPRING), Cam.from_toml(CAM), ValveTrain.from_toml(VT)


def test_nose_gap_is_the_smallest_gap_over_the_nose_refined_between_grid_points():
    """On a sampled parabola the refinement gives its vertex exactly (three points fix a
    parabola); points outside the nose do not count; an end point of the nose is taken as is."""
    x = np.linspace(0.0, 1.0, 41)
    g = 3.0 * (x - 0.4123) ** 2 - 1e-6
    nose = (x > 0.2) & (x < 0.7)
    assert nose_gap(g, nose) == pytest.approx(-1e-6, abs=1e-15)
    g_out = g.copy()
    g_out[~nose] = -1.0  # separated outside the nose: not float
    assert nose_gap(g_out, nose) == pytest.approx(-1e-6, abs=1e-15)
    edge = np.where(nose, x, 5.0)  # smallest at the nose's first point
    assert nose_gap(edge, nose) == pytest.approx(x[nose][0])


def test_search_finds_the_float_speed_the_definition_gives(train):
    """The nominal and two variants (wire and free length at their tolerance limits): the
    search from a guess 60 rpm off ends in a bracket of at most the resolution that overlaps
    the bisection of the scan (``float_speed``, 1 rpm) widened by 1.5 rpm: the two detect a
    lift-off differently (the located events on the dense output against the smallest gap on
    the output grid refined by a parabola), measured 0.2-0.8 rpm apart at 0.5 rpm resolution."""
    sp, cam, vt = train
    for values in ({}, {"wire_diameter": sp.wire_diameter + 15e-6}, {"free_length": sp.free_length - 3e-4}):
        s, c, v = variant(sp, cam, vt, values) if values else (sp, cam, vt)
        ref = float_speed(s, c, v, SCAN, resolution=1.0)
        near = float_speed_near(prepare(s, c, v), ref.float_cam_rpm - 60.0, SCAN[0], SCAN[-1], resolution=2.0)
        lo, hi = near["bracket"]
        assert near["in_range"] and hi - lo <= 2.0 and near["float_cam_rpm"] == hi
        assert lo <= ref.bracket[1] + 1.5 and hi >= ref.bracket[0] - 1.5, (values, ref.bracket, near["bracket"])
        assert near["periodicity"] <= 0.002  # every trial speed settled (PERIODICITY_TOL)
        assert 2 <= near["evaluations"] <= 10


def test_search_does_not_depend_on_the_output_grid(train):
    """720 and 1440 points a revolution give float speeds within 1 rpm at 0.5 rpm resolution
    (the parabola's refinement: without it the grid's 0.5 deg moved it by 3-4 rpm)."""
    sp, cam, vt = train
    s = prepare(sp, cam, vt)
    f = [
        float_speed_near(s, 3190.0, SCAN[0], SCAN[-1], resolution=0.5, points_per_revolution=p)["float_cam_rpm"]
        for p in (720, 1440)
    ]
    assert abs(f[0] - f[1]) <= 1.0


def test_search_at_the_ends_of_the_range(train):
    """A range below the float speed: the top speed as a lower bound, not in range; a range
    above it: its lowest speed (the valve already separates there)."""
    sp, cam, vt = train
    s = prepare(sp, cam, vt)
    below = float_speed_near(s, 3000.0, 2800.0, 3100.0)
    assert below["float_cam_rpm"] == 3100.0 and not below["in_range"]
    above = float_speed_near(s, 3300.0, 3250.0, 3400.0)
    assert above["float_cam_rpm"] == 3250.0 and above["in_range"]
    with pytest.raises(InputError, match="ascending"):
        float_speed_near(s, 3000.0, 3100.0, 2800.0)
    with pytest.raises(InputError, match="resolution"):
        float_speed_near(s, 3000.0, 2800.0, 3100.0, resolution=0.0)
    with pytest.raises(InputError, match="needs a valve train"):
        float_speed_near(prepare(sp, cam), 3000.0, 2800.0, 3100.0)
