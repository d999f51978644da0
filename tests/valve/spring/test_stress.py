"""Wire stress and fatigue building blocks (springdyn.valve.spring.stress) against their closed forms."""

import math

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve.spring import stress as du


@pytest.mark.parametrize("w", [3.0, 4.0, 6.2857, 10.0, 20.0])
def test_en13906_factor_is_bergstraesser(w):
    """EN 13906-1's (w + 0.5)/(w - 0.75) and Bergstraesser's (4w + 2)/(4w - 3) are one expression."""
    assert du.bergstraesser_factor(w) == pytest.approx((4 * w + 2) / (4 * w - 3), rel=1e-14)


def test_corrected_stress_of_the_example_spring_by_hand():
    """Fset = 251.43 N on D = 22 mm, d = 3.5 mm: k = 6.7857/5.5357 = 1.22581, tau = k 8 F D/(pi d^3)."""
    k = (22 / 3.5 + 0.5) / (22 / 3.5 - 0.75)
    by_hand = k * 8 * 251.43 * 0.022 / (math.pi * 0.0035**3)
    assert du.corrected_shear_stress(251.43, 0.022, 0.0035) == pytest.approx(by_hand, rel=1e-12)
    assert by_hand == pytest.approx(402.7e6, rel=1e-4)  # the report prints it rounded: "403 MPa installed"


def test_goodman_limits():
    """Static stress: n = tau_u/tau; fully reversed: n = tau_e/tau_a; on the line n = 1."""
    assert du.goodman_safety_factor(300e6, 300e6, 400e6, 1200e6) == pytest.approx(4.0)
    assert du.goodman_safety_factor(-200e6, 200e6, 400e6, 1200e6) == pytest.approx(2.0)
    tau_e, tau_u = 400e6, 1200e6
    mean = 600e6
    amp = tau_e * (1 - mean / tau_u)  # a point on the Goodman line
    assert du.goodman_safety_factor(mean - amp, mean + amp, tau_e, tau_u) == pytest.approx(1.0)


def test_zimmerli_point_lies_on_its_goodman_line():
    """The endurance strength derived from Zimmerli's peened point puts that point at n = 1."""
    s_su = du.ultimate_shear_strength(1960e6)
    tau_e = du.zimmerli_endurance_shear_strength(s_su)
    s_sa, s_sm = du.ZIMMERLI_PEENED
    assert du.goodman_safety_factor(s_sm - s_sa, s_sm + s_sa, tau_e, s_su) == pytest.approx(1.0, rel=1e-12)


def test_bad_inputs():
    with pytest.raises(InputError):
        du.bergstraesser_factor(0.5)
    with pytest.raises(InputError):
        du.goodman_safety_factor(2.0, 1.0, 1.0, 1.0)
    with pytest.raises(InputError):
        du.goodman_safety_factor(0.0, 0.0, 1.0, 1.0)
    assert np.all(du.goodman_safety_factor(np.array([1e8, 2e8]), np.array([3e8, 4e8]), 4e8, 1.2e9) > 0)


# --- the assessment over a cycle --------------------------------------------------
import math as _math

from springdyn.valve import Cam as _Cam
from springdyn.valve import ValveSpring as _VS
from springdyn.valve import simulate as _simulate
from springdyn.valve import sweep as _sweep
from springdyn.valve.spring.stress import fatigue_assessment, spring_strengths


def test_example_spring_goodman_factor_by_hand():
    # hand calculation: w = 22/3.5, k = (w + 0.5)/(w - 0.75), tau = k 8 F D / (pi d^3);
    # tau_u = 0.67 x 2000 MPa, tau_e = 398 / (1 - 534/1340) MPa (Zimmerli, peened)
    s = _VS.example("one-step")
    w = 22 / 3.5
    k = (w + 0.5) / (w - 0.75)
    tau = lambda f: k * 8 * f * 22e-3 / (_math.pi * 3.5e-3**3)  # noqa: E731
    fmin, fmax = 251.43, 486.4
    tu, te = 0.67 * 2000e6, 398e6 / (1 - 534e6 / 1340e6)
    n = 1 / ((tau(fmax) - tau(fmin)) / 2 / te + (tau(fmax) + tau(fmin)) / 2 / tu)
    out = fatigue_assessment(s, fmin, fmax)
    assert out["fatigue_safety_factor"] == pytest.approx(n, rel=1e-12)
    assert spring_strengths(s)["strength_defaults"] == ["tensile_strength", "endurance_shear_strength"]
    given = s.replace(tensile_strength=1.9e9, endurance_shear_strength=600e6)
    assert spring_strengths(given)["strength_defaults"] == []


@pytest.mark.parametrize("model", ["type-c", "distributed"])
def test_dynamic_factor_equals_static_at_low_speed_and_falls_with_surge(model):
    s = _VS.example("one-step").with_model(model)
    cam = _Cam(law="3-4-5", lift=9e-3, duration=_math.radians(120))
    slow = _simulate(s, cam, 300.0, 2).summary
    # quasi-static: the element forces follow the static force within the surge of 300 rpm
    assert slow["fatigue_safety_factor"] == pytest.approx(slow["static_fatigue_safety_factor"], rel=5e-3)
    fast = _simulate(s, cam, 3500.0, 2).summary
    assert fast["fatigue_safety_factor"] < 0.95 * fast["static_fatigue_safety_factor"]
    assert any("default wire strengths" in n for n in fast["notes"])


def test_sweep_reports_the_factor_against_speed():
    s = _VS.example("one-step")
    cam = _Cam(law="3-4-5", lift=9e-3, duration=_math.radians(120))
    t = _sweep(s, cam, [400.0, 3500.0], revolutions=2).summary_table()
    assert t["fatigue_safety_factor"][0] == pytest.approx(t["static_fatigue_safety_factor"][0], rel=5e-3)
    assert t["fatigue_safety_factor"][1] < t["fatigue_safety_factor"][0]


# ---------------------------------------------------------------- wire torsion (issue 26)


def _spring(model):
    from springdyn.valve import ValveSpring

    s = ValveSpring.example("one-step")
    return s if model == "type_c" else s.with_model(model)


def test_type_c_wire_torsion_stops_at_the_contact_force():
    """Type C: beyond an element's contact compression (Fcon, [MMS]) the further force goes
    through the touching coils; below it the wire carries the whole force."""
    from springdyn.valve.spring.elements import law_force

    m = _spring("type_c").spring_model
    x_con = m.contact_compressions()
    j = int(np.flatnonzero(np.isfinite(x_con))[0])
    law = m.chain.laws[j]
    f_con = float(law_force(x_con[j], law))
    x = np.array([0.5, 0.99, 1.01, 1.5]) * x_con[j]
    comp = np.tile(x, (len(m.chain.laws), 1))
    force = np.stack([law_force(comp[i], m.chain.laws[i]) for i in range(len(m.chain.laws))])
    wire = m.wire_forces(comp, force)
    np.testing.assert_allclose(wire[j, :2], force[j, :2], rtol=1e-14)
    np.testing.assert_allclose(wire[j, 2:], f_con, rtol=1e-12)
    assert np.all(force[j, 2:] > f_con)


def test_distributed_contact_share_table_matches_the_turn_slices():
    """The tabulated force through closed coils equals the turn-slice series
    (slice_states: the force less the largest slice torsion) within 1e-3 of Fset (the
    table's geometric nodes are 0.5 % apart; the share is piecewise smooth between the
    slices' closings)."""
    from springdyn.valve.spring.chains.distributed import slice_states

    m = _spring("distributed").spring_model
    pc, sl = m._pieces, m._pieces["slices"]
    fset = m.chain.setup_force
    rng = np.random.default_rng(7)
    for i in range(pc["n"]):
        f = rng.uniform(0.0, 12 * fset, 100)
        k = 1.0 / sl["c"][i]
        e, _ = slice_states(f, k, sl["gap"][i], sl["kc"][i], sl["onset"][i])
        exact = np.maximum(f - np.max(k * e, axis=-1), 0.0)
        elastic = np.zeros((pc["n"] + 2, f.size))
        elastic[i + 1] = f
        share = m.contact_share(elastic)
        assert np.max(np.abs(share[i + 1] - exact)) <= 1e-3 * fset
        assert np.isnan(share[0]).all() and np.isnan(share[-1]).all()  # the end contacts are no wire


@pytest.mark.parametrize("model", ["type_c", "distributed"])
def test_clash_force_through_contact_is_not_wire_stress(model):
    """At a clash speed the wire's torsion never exceeds the element force, and the largest
    stress comes from the wire alone (the distributed chain passes most of the seat's clash
    peak through closed coils: its wire force stays well below the peak seat force)."""
    import math

    from springdyn.valve import Cam, simulate

    cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
    sim = simulate(_spring(model), cam, 4000.0)
    s = sim.summary
    wire = sim.spring.spring_model.wire_forces(sim.element_compression, sim.element_force)
    rows = np.isfinite(wire).all(axis=1)
    assert np.all(wire[rows] <= sim.element_force[rows] + 1e-9)
    assert s["max_wire_force_N"] <= s["max_seat_force_N"] + 1e-9
    tau = du.corrected_shear_stress(s["max_wire_force_N"], sim.spring.mean_diameter, sim.spring.wire_diameter)
    if model == "distributed":
        assert s["max_force_through_coil_contact_N"] > 0.2 * s["max_seat_force_N"]
        assert s["max_wire_force_N"] < 0.9 * s["max_seat_force_N"]
    assert s["peak_shear_stress_Pa"] == pytest.approx(tau, rel=1e-9)
    assert s["peak_shear_stress_Pa"] >= s["max_shear_stress_Pa"]  # the Goodman-critical element's
    assert s["wire_stress_ok"] is (s["peak_shear_stress_Pa"] <= s["shear_stress_limit_Pa"])
    # coil clash reported apart, as impacts: at this speed both models clash
    cc = s["coil_clash"]
    assert cc["impacts"] >= 1 and cc["duration_deg"] > 0
    assert cc["peak_force_through_contact_N"] <= s["max_force_through_coil_contact_N"] + 1e-9
    assert cc["impacts"] == sum(ev["dynamic_closing"] for ev in s["coil_contact"])
    assert cc["clash_class"] == "active" and cc["clash"] and cc["clash_severity"] > 0.1


def test_overstress_is_a_failure_naming_element_and_speed():
    """A shear_yield_strength below the cycle's largest stress fails, naming the element."""
    import math

    from springdyn.valve import Cam, simulate

    cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
    s = _spring("type_c").replace(shear_yield_strength=600e6)
    sm = simulate(s, cam, 3000.0).summary
    assert sm["shear_stress_limit_Pa"] == 600e6 and not sm["wire_stress_ok"]
    assert any(n.startswith("WIRE OVERSTRESS: element") and "3000 cam rpm" in n for n in sm["notes"])
