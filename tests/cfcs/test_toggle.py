"""No reported statistic may depend on the toggle cut-off (a numerical setting).

Checked on Table 1 of [CFCS] with the friction and axial-force terms of the shipped example on.
"""

import numpy as np
import pytest

from springdyn.cfcs import CFCS
from springdyn.cfcs.kinematics import slider_jacobian, theta2_from_deflection
from springdyn.cfcs.model import DEFAULT_OFFSET, toggle_check
from springdyn.cfcs.statics import axial_force_torque

CUTOFFS_DEG = (1.0, 2.0, 5.0, 10.0)
STATIC_KEYS = ("pcf_compression_percent", "pcf_percent", "force_max_N", "pcf_working_percent")
DYNAMIC_KEYS = (
    "mean_force_N",
    "median_force_N",
    "peak_to_peak_N",
    "pcf_percent",
    "force_max_N",
    "force_min_N",
    "hysteresis_energy_per_cycle_J",
)


def _at(table1, deg):
    return CFCS(table1.replace(toggle_cutoff=float(np.radians(deg))))


def test_default_motion_is_independent_of_the_cutoff(table1):
    # the default motion starts from the preload offset (theta2 = 13.6 deg for Table 1), above every
    # cut-off tried: the statistics are the same to rounding (1e-6 relative is the bound; the
    # computation is in fact identical, no sample enters the zone)
    ref_s = _at(table1, 5.0).static().summary
    ref_d = _at(table1, 5.0).dynamic(14.7).summary
    for deg in CUTOFFS_DEG:
        s = _at(table1, deg).static().summary
        d = _at(table1, deg).dynamic(14.7).summary
        for k in STATIC_KEYS:
            assert s[k] == pytest.approx(ref_s[k], rel=1e-6), (deg, k)
        for k in DYNAMIC_KEYS:
            assert d[k] == pytest.approx(ref_d[k], rel=1e-6), (deg, k)
        assert not s["toggle_dominated"] and not d["toggle_dominated"]
        assert d["toggle_zone_samples"] == 0


def test_through_the_toggle_is_flagged(table1):
    # offset 0 requested explicitly: the peak-to-peak force at 14.7 rad/s halves with each doubling of
    # the cut-off (measured: 65.5, 33.1, 13.7, 7.3 N for 1, 2, 5, 10 deg), so it must be flagged, and the
    # value the flag compares with is the one computed at twice the cut-off
    one, two = _at(table1, 1.0).dynamic(14.7, offset=0.0).summary, _at(table1, 2.0).dynamic(14.7, offset=0.0).summary
    assert one["toggle_dominated"] and "peak_to_peak_N" in one["toggle_dominated_statistics"]
    assert one["statistics_at_doubled_cutoff"]["peak_to_peak_N"] == pytest.approx(two["peak_to_peak_N"], rel=1e-12)
    assert one["peak_to_peak_N"] > 1.5 * two["peak_to_peak_N"]
    assert any("toggle-dominated" in n for n in one["notes"])
    st = _at(table1, 1.0).static(offset=0.0).summary
    assert st["toggle_dominated"] and st["toggle_dominated_statistics"] == ["pcf_compression_percent"]


def test_frictionless_through_the_toggle_is_not_flagged(table1):
    # without tau_CF, tau_AF and slider friction nothing depends on the cut-off: entering the zone is
    # reported, but no statistic is flagged
    d = CFCS(table1.without_dissipation()).dynamic(14.7, offset=0.0).summary
    assert d["toggle_zone_samples"] > 0
    assert not d["toggle_dominated"] and d["toggle_dominated_statistics"] == []


def test_toggle_check_threshold():
    assert toggle_check({"a": 100.0}, {"a": 100.9}, ["a"]) == []
    assert toggle_check({"a": 100.0}, {"a": 101.2}, ["a"]) == ["a"]
    assert toggle_check({"a": None}, {"a": 1.0}, ["a"]) == []


def test_axial_force_term_is_the_slider_force_at_the_shear_angle(table1):
    # reading of Eq. (22) in docs/cfcs.md: tau_AF = F_static G(alpha) (1 + O(alpha^2)), so its slider force
    # F_static G(alpha) / G(theta2) -> F_static alpha / theta2 near the toggle: equal to F_static at
    # theta2 = alpha, and diverging as 1 / theta2 below it. G(alpha) differs from (22) by the
    # small-angle replacements sin a -> a, cos a -> 1: relative O(alpha^2) = 2e-3 for alpha = 0.045
    p = table1
    a = p.shear_angle
    tau = axial_force_torque(1.0, a, p.r2, p.r3)
    assert tau == pytest.approx(slider_jacobian(a, p.r2, p.r3), rel=a * a)
    for th in (1e-3, 1e-2):
        ratio = tau / slider_jacobian(th, p.r2, p.r3)
        assert ratio == pytest.approx(a / th, rel=2 * a * a + 2 * th * th)
    # the default preload puts the crank well above alpha (13.6 deg vs 2.6 deg)
    start = float(theta2_from_deflection(0.025 * p.extended_length, p.r2, p.r3))
    assert DEFAULT_OFFSET == "2.5 %" and start > 5 * a
