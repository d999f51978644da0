"""Design: r2/r3 for the flattest force, K3 and the flexure (issue 5, section 2)."""

import numpy as np
import pytest

from springdyn.cfcs import CFCS, design
from springdyn.cfcs.design import min_ratio_for_stroke, normalized_pcf
from springdyn.cfcs.kinematics import kinematic_limit_deflection
from springdyn.core.errors import InputError


def test_feasible_design_verified_through_the_model():
    # the design's PCF, force band and stress recomputed by the CFCS model built from it (independent path)
    r = design(12.8, 0.040, 207e9, 1.5e9, stroke_fraction=0.2)
    s = r.summary
    assert r.feasible
    assert s["pivot_width_m"] <= s["max_width_m"]
    # target force is the middle of the band
    assert 0.5 * (s["force_min_N"] + s["force_max_N"]) == pytest.approx(12.8, rel=1e-9)
    st = CFCS(r.to_params(0.01, 0.01, 0.02)).static(0.040, n=401).summary
    assert st["pcf_percent"] == pytest.approx(s["pcf_percent"], abs=0.01)
    assert st["max_stress_Pa"] == pytest.approx(1.5e9, rel=1e-9)  # stress limit reached at the stroke end
    assert st["safety_factor"] == pytest.approx(1.0, rel=1e-9)
    assert s["pivot_length_m"] == pytest.approx(0.1 * s["coupler_length_m"])


def test_chosen_ratio_is_the_flattest():
    # no ratio on a fine grid gives a flatter force (the refined optimum is at least as good, 1e-3 %)
    r = design(12.8, 0.040, 207e9, 1.5e9, stroke_fraction=0.2)
    grid = np.linspace(min_ratio_for_stroke(0.2) + 1e-6, 0.995, 400)
    assert r.summary["pcf_percent"] >= max(normalized_pcf(q, 0.2) for q in grid) - 1e-3


def test_no_design_is_said_plainly():
    # the example at the paper's 40 %: the flexure would have to be far wider than its link
    r = design(12.8, 0.040, 207e9, 1.5e9)
    s = r.summary
    assert not r.feasible
    assert s["message"].startswith("no design meets the stress limit")
    # the suggested length is feasible at the flattest ratio, and only just
    need = s["suggested_total_length_m"]
    assert need > s["total_length_m"]
    ok = design(12.8, 0.040, 207e9, 1.5e9, total_length=need * 1.001)
    assert ok.feasible and ok.summary["pcf_percent"] >= s["pcf_flattest_percent"] - 1.0
    short = design(12.8, 0.040, 207e9, 1.5e9, total_length=need * 0.98)
    assert not (short.feasible and short.summary["pcf_percent"] >= short.summary["pcf_flattest_percent"] - 0.5)


def test_min_ratio_reaches_the_stroke():
    # at the smallest ratio, the kinematic limit is exactly the stroke (closed form vs kinematics)
    rho = min_ratio_for_stroke(0.4)
    r3 = 1.0 / (1 + rho)
    assert kinematic_limit_deflection(rho * r3, r3) == pytest.approx(0.4, rel=1e-12)


@pytest.mark.parametrize("kwargs, match", [
    (dict(force=-1.0), "force = -1.0 must be positive"),
    (dict(stroke=0.0), "stroke"),
    (dict(stroke_fraction=1.2), "stroke_fraction"),
    (dict(total_length=0.03), "must exceed the stroke"),
])
def test_bad_design_input(kwargs, match):
    args = dict(force=12.8, stroke=0.04, youngs_modulus=207e9, allowable_stress=1.5e9)
    args.update(kwargs)
    with pytest.raises(InputError, match=match):
        design(**args)


def test_design_outputs(tmp_path):
    from springdyn.cfcs import CFCSParams

    r = design(12.8, 0.040, 207e9, 1.5e9, stroke_fraction=0.2)
    p = CFCSParams.from_toml(r.to_toml(tmp_path / "d.toml"))
    assert p.k3 == pytest.approx(r.summary["torsional_stiffness_N_m_per_rad"], rel=1e-5)  # 6 digits written
    assert r.to_xarray()["force_N"].size == r.deflection.size


def test_design_flattest_moves_to_the_suggested_length():
    """The policy the report used to carry (issue 10): when the flattest ratio does not fit at
    the first size, the design is redone at the length design() suggests, and gets flatter."""
    from springdyn.cfcs.design import design, design_flattest

    first = design(12.58, 0.0316, 207e9, 1.5e9, stroke_fraction=0.2)
    best = design_flattest(12.58, 0.0316, 207e9, 1.5e9, stroke_fraction=0.2)
    if first.summary["pcf_percent"] < first.summary["pcf_flattest_percent"] - 1.0 and first.summary.get(
            "suggested_total_length_m"):
        assert best.summary["pcf_percent"] > first.summary["pcf_percent"]
        assert best.summary["total_length_m"] == pytest.approx(1.01 * first.summary["suggested_total_length_m"])
    else:
        assert best.summary == first.summary
