"""The spring pack's definition, statics, modes and fit (issue 41, Deliver 1 and 5).

References, written here independently of the code they check:

- two identical springs nested have one spring's natural frequencies, each twice (the chains
  share only their ends: held at both, they are two copies of one chain), and twice its
  static force (the one spring's model, :meth:`SpringModel.static_force`);
- the coil diameter under compression from the wire length of a turn, ``sqrt((pi D)^2 + m^2)``,
  kept ([Wahl]): written out here for the hand values;
- the friction law: ``-F tanh(v / v_reg)`` ([Andersson], the smooth Coulomb model).
"""

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve.engine.equations import damper_friction
from springdyn.valve.spring import ValveSpring
from springdyn.valve.spring.pack import FrictionDamper, PackOptions, SpringPack, diameter_growth, radial_clearance

EXAMPLE = Path(__file__).parents[3] / "examples" / "valve" / "dual_spring_damper.toml"


@pytest.fixture(scope="module")
def spring():
    return ValveSpring.example("one-step")


def test_two_identical_springs_have_one_springs_modes_twice_and_twice_its_force(spring):
    pack = SpringPack((spring, spring), PackOptions(interference="ignore"))
    modes = pack.modes(0.0)["pack"]
    one = spring.spring_model.modes(spring.installed_length, 5)
    assert np.allclose(modes[0::2], one, rtol=1e-12) and np.allclose(modes[1::2], one, rtol=1e-12)
    for lift in (0.0, 4e-3, 8e-3):
        f_one = float(spring.spring_model.static_force(spring.installed_length - lift))
        assert float(pack.static_force(lift)) == pytest.approx(2.0 * f_one, rel=1e-10)


def test_the_coil_diameter_grows_as_the_wire_length_of_a_turn_says():
    """D = 24 mm, d = 3.8 mm, 5 active coils, Lf = 50 mm, Lc = 28.5 mm, compressed to 35 mm."""
    d0, d, n, lf, lc, length = 0.024, 0.0038, 5.0, 0.050, 0.0285, 0.035
    m0 = (lf - lc) / n + d  # 8.1 mm
    m = (length - lc) / n + d  # 5.1 mm
    turn = math.hypot(math.pi * d0, m0)
    hand = math.sqrt(turn**2 - m**2) / math.pi - d0
    assert float(diameter_growth(d0, d, n, lf, lc, length)) == pytest.approx(hand, rel=1e-12)
    assert 0.0 < hand < 0.2e-3  # a few hundredths of a millimetre: the growth of a valve spring
    assert float(diameter_growth(d0, d, n, lf, lc, lf)) == 0.0


def test_the_example_pack_its_clearance_and_hands():
    pack = SpringPack.from_toml(EXAMPLE)
    outer, inner = pack.springs
    assert (pack.options.outer_hand, pack.options.inner_hand) == ("right", "left")
    assert pack.damper.force == pytest.approx(60.0 * 0.15)
    # radial clearance at installed length by hand: the diameters grown by their own set-up
    grow_o = float(
        diameter_growth(0.024, 0.0038, outer.active_coils, 0.053, outer.solid_length, outer.installed_length)
    )
    grow_i = float(
        diameter_growth(0.0155, 0.0026, inner.active_coils, 0.048, inner.solid_length, inner.installed_length)
    )
    hand = 0.5 * ((0.024 + grow_o - 0.0038) - (0.0155 + grow_i + 0.0026))
    assert radial_clearance(outer, inner) == pytest.approx(hand, rel=1e-12)
    assert pack.fit["outer_inner"]["interference_m"] == 0.0
    figures = pack.static_figures(0.009)
    assert figures["open_force_N"] == pytest.approx(figures["outer_open_force_N"] + figures["inner_open_force_N"])
    assert figures["pack_solid_length_m"] == max(outer.solid_length, inner.solid_length)


def test_interfering_springs_are_refused_or_rub(spring):
    fat = spring.replace(mean_diameter=0.019, wire_diameter=0.003)  # outside 22 mm, the outer's inside 18.5 mm
    with pytest.raises(InputError, match="interfere"):
        SpringPack((spring, fat))
    with pytest.raises(InputError, match="radial_stiffness"):
        SpringPack((spring, fat), PackOptions(interference="rub"))
    pack = SpringPack((spring, fat), PackOptions(interference="rub", radial_stiffness=1e6, rubbing_friction=0.1))
    delta = pack.fit["outer_inner"]["interference_m"]
    assert delta > 1e-3
    row = pack.friction_rows()[0]
    assert row[2] == pytest.approx(0.1 * 1e6 * delta)  # mu k delta


def test_one_hand_warns_and_a_damper_needs_one_force(spring):
    inner = spring.replace(mean_diameter=0.0145, wire_diameter=0.0025, high_pitch_coils=8.0)
    with pytest.warns(UserWarning, match="both right-hand"):
        SpringPack((spring, inner), PackOptions(inner_hand="right"))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        SpringPack((spring, inner))
    with pytest.raises(InputError, match="friction_force, or normal_load"):
        FrictionDamper(friction_force=10.0, normal_load=50.0, friction_coefficient=0.2)
    with pytest.raises(InputError, match="friction_force, or normal_load"):
        FrictionDamper(normal_load=50.0)
    with pytest.raises(InputError, match="third"):
        SpringPack((spring, inner), damper=FrictionDamper(friction_force=5.0, against="third"))


def test_the_friction_law_is_coulomb_regularised():
    for v in (-2.0, -0.01, 0.0, 0.003, 1.0):
        assert damper_friction(20.0, v, 0.01) == pytest.approx(-20.0 * math.tanh(v / 0.01), abs=1e-15)
    assert damper_friction(20.0, 5.0, 0.01) == pytest.approx(-20.0, rel=1e-12)  # sliding: the Coulomb force


@pytest.mark.parametrize("table", ["inner_spring", "third_spring", "pack", "damper"])
def test_a_pack_file_is_no_single_spring(tmp_path, table):
    """ValveSpring.from_toml refuses a file with a pack's table rather than read its outer spring
    alone; the message names the table and the readers of packs."""
    doc = EXAMPLE.read_text().split("[inner_spring]")[0]
    body = {"inner_spring": "[inner_spring]\n", "third_spring": "[third_spring]\n", "pack": "[pack]\n"}
    f = tmp_path / "pack.toml"
    f.write_text(doc + body.get(table, "[damper]\nfriction_force = '5 N'\n"))
    with pytest.raises(InputError, match=rf"\[{table}\] makes this file a spring pack.*SpringPack.from_toml"):
        ValveSpring.from_toml(f)
    f.write_text(doc)  # its outer spring alone is one spring
    assert ValveSpring.from_toml(f) == SpringPack.from_toml(EXAMPLE).outer


def test_the_packs_design_figures_against_the_rate_by_hand():
    """The example pack at 9 mm lift: each spring's force is its rate G d^4 / (8 D^3 n) (n the active
    coils of the Type C chain, N2 - 2 Nb) times its compression (Lf - Ls, and + 9 mm), written from the
    TOML's values; the pack's forces are their sums.  Installed to 1e-9; at full lift to 1e-3: the
    Type C element laws leave their straight line past F1 (measured 1e-4 of the force here)."""
    pack = SpringPack.from_toml(EXAMPLE)
    fig = pack.design_figures(9e-3, cam_rpm=3500.0)
    g = 78.5e9
    rate = {"outer": g * 3.8e-3**4 / (8 * 24e-3**3 * (7 - 2)), "inner": g * 2.6e-3**4 / (8 * 15.5e-3**3 * (9 - 2))}
    set_up = {"outer": 53e-3 - 43e-3, "inner": 48e-3 - 41e-3}
    for name in ("outer", "inner"):
        own = fig["springs"][name]
        assert own["installed"]["force_N"] == pytest.approx(rate[name] * set_up[name], rel=1e-9)
        assert own["open"]["force_N"] == pytest.approx(rate[name] * (set_up[name] + 9e-3), rel=1e-3)
        assert own["stress_factor_name"].startswith("Bergstraesser")
    hand_installed = sum(rate[n] * set_up[n] for n in rate)
    assert fig["installed_force_N"] == pytest.approx(hand_installed, rel=1e-9)
    opened = [fig["springs"][n]["open"]["force_N"] for n in ("outer", "inner")]
    assert fig["open_force_N"] == pytest.approx(sum(opened), rel=1e-12)
    assert fig["force_share"]["inner"] == pytest.approx(opened[1] / sum(opened), rel=1e-12)
    # the modes with the ends held are each spring's own, labelled by it (the chains share their ends)
    assert fig["modes_Hz"] == sorted(fig["modes_Hz"])
    for name, s in zip(pack.names, pack.springs):
        own = [f for f, n in zip(fig["modes_Hz"], fig["mode_springs"]) if n == name]
        assert np.allclose(own, s.spring_model.modes(s.installed_length, 3), rtol=1e-12)
    assert fig["pack_solid_length_m"] == pytest.approx(max(s.solid_length for s in pack.springs))
    # the static figures' stress is the wire's section's: an inner of rectangular wire, Roark's factor
    flat = pack.replace_spring(
        1, pack.springs[1].replace(wire_shape="rectangular", wire_width=2.4e-3, wire_height=2.6e-3)
    )
    s = flat.springs[1]
    force = flat.static_figures(9e-3)["inner_open_force_N"]
    w = 15.5e-3 / 2.4e-3
    roark = 1 + 1.2 / w + 0.56 / w**2 + 0.5 / w**3
    z = s.wire.stress_modulus  # the section's T / tau_max (tests/valve/spring/test_wire.py: Timoshenko's table)
    assert flat.static_figures(9e-3)["inner_max_shear_stress_Pa"] == pytest.approx(
        roark * force * 15.5e-3 / 2 / z, rel=1e-9
    )
