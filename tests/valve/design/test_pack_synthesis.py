"""The inner spring of a pack for an outer spring and a force split (issue 41, Deliver 1).

References, written here independently of the code they check: the spring rate
``k = G d^4 / (8 D^3 n)`` and the corrected shear stress ``tau = k_B 8 F D / (pi d^3)`` with
Bergstraesser's ``k_B = (w + 0.5) / (w - 0.75)``, ``w = D / d`` (EN 13906-1), and the
diameters: the inner's outside ``D_i + d_i`` is the outer's inside ``D_o - d_o`` less twice the
clearance.
"""

import math
from pathlib import Path

import pytest

from springdyn.core.errors import InputError
from springdyn.valve.design.pack_synthesis import inner_spring_for
from springdyn.valve.spring import ValveSpring

#: The outer spring of the dual-spring example: 24 x 3.8 mm, 7 coils, Lf 53 mm, Ls 43 mm, G 78.5 GPa.
EXAMPLE = Path(__file__).parents[3] / "examples" / "valve" / "dual_spring_damper.toml"


def _tau(force, d_mean, d_wire):
    w = d_mean / d_wire
    return (w + 0.5) / (w - 0.75) * 8.0 * force * d_mean / (math.pi * d_wire**3)


def test_the_inner_spring_carries_its_share_at_the_outers_stress():
    outer = ValveSpring.from_toml(EXAMPLE)
    share, lift, clearance = 0.33, 9e-3, 1e-3
    r = inner_spring_for(outer, share, lift, clearance, installed_length=0.041)
    inner = r["spring"]
    # the outer spring's forces (its model, linear-rate range) and the inner's share of the pack
    f_set_o = float(outer.spring_model.static_force(0.043))
    f_open_o = float(outer.spring_model.static_force(0.043 - lift))
    for f_o, f_i in ((f_set_o, r["set_force_N"]), (f_open_o, r["open_force_N"])):
        assert f_i / (f_i + f_o) == pytest.approx(share, rel=1e-6)  # the Type C chain is linear below Fcon
    # the rate by hand, from the inner's own wire, diameter and active coils
    d, dm, n = inner.wire_diameter, inner.mean_diameter, inner.active_coils
    k = 78.5e9 * d**4 / (8.0 * dm**3 * n)
    assert k * lift == pytest.approx(r["open_force_N"] - r["set_force_N"], rel=1e-9)
    # equal corrected stress at full lift, and the space inside the outer
    assert _tau(r["open_force_N"], dm, d) == pytest.approx(_tau(f_open_o, 0.024, 0.0038), rel=1e-6)
    assert dm + d == pytest.approx(0.024 - 0.0038 - 2 * clearance, rel=1e-12)
    assert r["pack"].options.inner_hand != r["pack"].options.outer_hand
    assert r["coil_bind_margin_m"] > 0.0


def test_an_impossible_split_is_refused():
    outer = ValveSpring.from_toml(EXAMPLE)
    with pytest.raises(InputError, match="share"):
        inner_spring_for(outer, 0.9, 9e-3)
