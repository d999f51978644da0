"""The valve section of the report for a spring pack (issue 41, Deliver 1: "... float, sweeps,
report"), and the report's words for the wire's stress factor (Deliver 2).

References, written here independently of the code they check:

- each spring's static force is its rate ``G d^4 / (8 D^3 n)`` (n the Type C chain's active coils,
  ``N2 - 2 Nb``) times its compression, ``Lf - Ls`` installed and ``+ lift`` open, from the
  example's TOML values; the pack's force is their sum;
- each spring's criteria are its own: the Goodman row shows the smallest of that spring's column
  of the sweep the report writes (sweep.nc), the float row the pack's (one valve).
"""

import tomllib

import numpy as np
import pytest

from springdyn.app.report.build import _jobs
from springdyn.app.report.valve import _stress_words, load, section
from springdyn.core.errors import InputError
from springdyn.valve import ValveSpring
from tests.paths import EXAMPLES

PACK_FILES = ("valve/dual_spring_damper.toml", "valve/cam_polydyne_ramps.toml", "valve/valve_train.toml")
G = 78.5e9
#: The example's rates by hand [N/m] and set-up compressions [m].
RATE = {"outer": G * 3.8e-3**4 / (8 * 24e-3**3 * (7 - 2)), "inner": G * 2.6e-3**4 / (8 * 15.5e-3**3 * (9 - 2))}
SET_UP = {"outer": 53e-3 - 43e-3, "inner": 48e-3 - 41e-3}


def _definition(tmp_path, report: str):
    """The example pack with the polydyne cam and the bucket train in one definition, and a [report]."""
    f = tmp_path / "dual.toml"
    f.write_text("\n".join((EXAMPLES / p).read_text() for p in PACK_FILES) + "\n[report]\n" + report)
    return f


def test_a_pack_definition_is_read_as_a_pack(tmp_path):
    """The report takes a pack's tables; the example report definition holds the three example files'
    tables; the studies of one spring ([report] requirements, tolerances) refuse a pack."""
    f = _definition(tmp_path, "max_engine_rpm = 7000\n")
    doc = tomllib.loads(f.read_text())
    assert [j[0] for j in _jobs([f])] == ["valve"]
    d = load(doc, f)
    assert d.spring.names == ("outer", "inner") and d.spring.damper.force == pytest.approx(9.0)
    shipped = tomllib.loads((EXAMPLES / "report" / "report_valve_dual_spring.toml").read_text())
    assert {k: v for k, v in shipped.items() if k != "report"} == {k: v for k, v in doc.items() if k != "report"}
    (tmp_path / "tol.toml").write_text("[tolerances]\n")
    g = _definition(tmp_path, 'tolerances = "tol.toml"\n')
    with pytest.raises(InputError, match=r"\[report\] tolerances studies one spring.*spring pack"):
        load(tomllib.loads(g.read_text()), g)


def test_the_stress_factor_is_named_by_the_wire():
    """Rectangular wire: Goehner's factor (Roark), not Bergstraesser's; round wire: Bergstraesser's."""
    one = ValveSpring.example("one-step")
    flat = one.replace(wire_shape="rectangular", wire_width=3.6e-3, wire_height=3.0e-3, wire_diameter=3.0e-3)
    for spring, name in ((one, "Bergstraesser"), (flat, "Goehner")):
        figs = spring.spring_model.design_figures(2e-3)
        words = _stress_words(figs, 2e-3)
        assert name in words and f"= {figs['stress_factor']:.3f}" in words
        assert ("Bergstraesser" in words) == (name == "Bergstraesser")


@pytest.mark.slow  # the pack's section: 3 runs, 6 speeds, the float search (about 40 s)
def test_the_report_of_the_dual_spring_on_the_bucket_train(tmp_path):
    f = _definition(
        tmp_path, 'min_engine_rpm = 2000\nmax_engine_rpm = 7000\nengine_rpm_step = 1000\nmodels = "type-c"\n'
    )
    d = load(tomllib.loads(f.read_text()), f)
    out = tmp_path / "out"
    sec = section(d, source=str(f), out_dir=out)
    ((caption, headers, rows),) = sec.tables
    assert headers == ("quantity", "outer", "inner", "pack")
    row = {r[0].split(" [")[0]: r[1:] for r in rows}
    installed = row["static force installed"]
    for k, name in enumerate(("outer", "inner")):
        assert float(installed[k]) == pytest.approx(RATE[name] * SET_UP[name], abs=0.05)  # shown to 0.1 N
        opened = float(row["static force at 9 mm lift"][k].split()[0])
        assert opened == pytest.approx(RATE[name] * (SET_UP[name] + 9e-3), rel=1e-3)  # Type C past F1: 1e-4
    assert float(installed[2]) == pytest.approx(sum(RATE[n] * SET_UP[n] for n in RATE), abs=0.05)
    assert "Bergstraesser" in row["corrected shear stress installed / at 9 mm lift"][0]
    # each spring judged by its own figures, the pack's valve by the float speed
    crit = {c.name: c for c in sec.criteria}
    import xarray as xr

    with xr.open_dataset(out / "sweep.nc") as ds:
        for name in ("outer", "inner"):
            rows_of = [c for c in crit if c.startswith(f"{name} spring: ")]
            assert len(rows_of) == 7, rows_of
            goodman = crit[f"{name} spring: fatigue safety factor (Goodman), 1000-3500 cam rpm, Type C"]
            k = int(np.argmin(ds[f"{name}_fatigue_safety_factor"].values))
            assert (
                goodman.value
                == f"{float(ds[f'{name}_fatigue_safety_factor'][k]):.2f} at {ds.cam_rpm.values[k]:.0f} cam rpm"
            )
            clash = crit[f"{name} spring: coil clash, 1000-3500 cam rpm, Type C"]
            assert "own Fset" in clash.note
            assert crit[f"{name} spring: solid length"].passed
    assert crit["float speed, Type C"].passed
    assert any("dissipated" in x and "by the friction damper" in x for x in sec.findings)
    assert any(x.startswith("Natural frequencies of the pack with its ends held") for x in sec.findings)
    assert any("radial clearance is 1.06 mm installed" in x for x in sec.findings)
    assert (out / "sweep_springs.png").is_file() and any(p.name == "sweep_springs.png" for p, _ in sec.figures)
    assert not any("valve params" in c for c in sec.commands)  # a pack's commands only
