"""The preload offset beside the dissipative figures (issue 40, item 8).

tau_AF of Eq. (22) turned into a slider force goes as 1/theta2, so the dissipative figures depend on
where the motion (or the rated working range) starts, which is the installation's preload, not the
spring.  Every dynamic and static result gives its figures also with half and twice the offset; the
reference is an independent run of the same model started at that offset (equal to round-off: the same
calculation on the same time grid).
"""

import pytest

from .test_cli import run

STATS = ("mean_force_N", "peak_to_peak_N", "force_max_N", "force_min_N", "pcf_percent")


def test_dynamic_gives_the_figures_at_half_and_twice_the_offset(model):
    s = model.dynamic(10.0).summary
    assert s["offset_m"] == pytest.approx(4.5e-3)  # 2.5 % of r2 + r3
    for tag, offset in (("half", 2.25e-3), ("double", 9e-3)):
        ref = model.dynamic(10.0, offset=offset).summary
        st = s[f"statistics_at_{tag}_offset"]
        assert st["offset_m"] == pytest.approx(offset)
        for k in STATS:
            assert st[k] == pytest.approx(ref[k], rel=1e-12), (tag, k)
    # the case (Table 1, 72 mm at 10 rad/s): peak-to-peak 7.54 N, 5.58 N, 4.38 N from 2.25, 4.5 and
    # 9 mm (to the printed digits); the figures that move by more than 10 % are named and a note says why
    assert s["statistics_at_half_offset"]["peak_to_peak_N"] == pytest.approx(7.538, abs=5e-4)
    assert s["peak_to_peak_N"] == pytest.approx(5.581, abs=5e-4)
    assert s["statistics_at_double_offset"]["peak_to_peak_N"] == pytest.approx(4.379, abs=5e-4)
    assert s["offset_sensitive_statistics"] == ["peak_to_peak_N", "pcf_percent"]
    note = next(n for n in s["notes"] if n.startswith("PRELOAD OFFSET"))
    assert "1/theta2" in note and "(+35.1 %)" in note and "(-21.5 %)" in note


def test_no_offset_no_sensitivity(model):
    s = model.dynamic(10.0, offset=0.0, offset_sensitivity=True).summary
    assert s["offset_m"] is None and s["statistics_at_half_offset"] is None


def test_static_rates_the_compression_branch_from_half_and_twice_the_offset(model):
    s = model.static().summary
    for tag, offset in (("half", "1.25 %"), ("double", "5 %")):
        ref = model.static(offset=offset).summary
        assert s[f"pcf_compression_at_{tag}_offset_percent"] == pytest.approx(ref["pcf_compression_percent"], rel=1e-12)
        assert s[f"working_start_{tag}_offset_m"] == pytest.approx(ref["working_start_m"])
    # Table 1 over 72 mm: 85.17 %, 90.43 %, 94.28 % from 2.25, 4.5 and 9 mm; the deficit (100 - PCF, the band
    # the friction adds) moves by +54 % and -40 %: flagged
    assert s["pcf_compression_at_half_offset_percent"] == pytest.approx(85.17, abs=0.005)
    assert s["pcf_compression_percent"] == pytest.approx(90.43, abs=0.005)
    assert s["pcf_compression_at_double_offset_percent"] == pytest.approx(94.28, abs=0.005)
    assert s["offset_sensitive_statistics"] == ["pcf_compression_percent"]
    assert any(n.startswith("PRELOAD OFFSET") for n in s["notes"])


def test_sweep_columns_at_half_and_twice_the_offset(model):
    sw = model.sweep([10.0, 20.0])
    for i, w in enumerate((10.0, 20.0)):
        s = model.dynamic(w, cycles=1).summary
        assert sw.stats["peak_to_peak_at_half_offset_N"][i] == pytest.approx(
            s["statistics_at_half_offset"]["peak_to_peak_N"], rel=1e-12
        )
        assert sw.stats["peak_to_peak_at_double_offset_N"][i] == pytest.approx(
            s["statistics_at_double_offset"]["peak_to_peak_N"], rel=1e-12
        )


def test_cli_prints_the_figures_beside(capsys):
    code, out, err = run(capsys, "cfcs", "dynamic", "table1", "--omega", "10")
    assert code == 0, err
    row = next(line for line in out.splitlines() if line.startswith("peak-to-peak force"))
    assert "OFFSET-SENSITIVE, from offset 2.25 mm: 7.538 N, 9 mm: 4.379 N" in row
    assert "note: PRELOAD OFFSET" in out
