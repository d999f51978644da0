"""Cam lift laws of valve-cam practice (not in [MMS]): shapes, derivatives, ramps, tables and bad input."""

import math
import warnings

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve.cam.definition import Cam, polydyne_coefficients, rise_law

LAWS = ["cycloidal", "3-4-5", "4-5-6-7", "polydyne"]
DUR = math.radians(120)


def test_polydyne_coefficients_stoddart():
    """The 2-10-14-18 polydyne coefficients of the literature (exact rationals)."""
    np.testing.assert_allclose(polydyne_coefficients(), [-105 / 64, 63 / 32, -15 / 8, 35 / 64], rtol=1e-13)


@pytest.mark.parametrize("law", LAWS)
def test_rise_law_boundary_conditions(law):
    p, dp, ddp = rise_law(law, np.array([0.0, 1.0]))
    np.testing.assert_allclose(p, [0, 1], atol=1e-14)
    np.testing.assert_allclose(dp, [0, 0], atol=1e-13)
    np.testing.assert_allclose(ddp[0], 0, atol=1e-12)  # all four start with zero acceleration


def test_closed_forms_of_the_rise_laws():
    u = np.linspace(0, 1, 11)
    np.testing.assert_allclose(rise_law("3-4-5", u)[0], 10 * u**3 - 15 * u**4 + 6 * u**5, atol=1e-15)
    np.testing.assert_allclose(rise_law("4-5-6-7", u)[0], 35 * u**4 - 84 * u**5 + 70 * u**6 - 20 * u**7, atol=1e-14)
    np.testing.assert_allclose(rise_law("cycloidal", u)[0], u - np.sin(2 * np.pi * u) / (2 * np.pi), atol=1e-15)


@pytest.mark.parametrize("ramps", [False, True])
@pytest.mark.parametrize("law", LAWS)
def test_event_shape_and_derivatives(law, ramps):
    kw = dict(ramp_height=0.3e-3, ramp_duration=math.radians(15)) if ramps else {}
    cam = Cam(law=law, lift=9e-3, duration=DUR, **kw)
    total = cam.event_duration
    th = np.linspace(0, 2 * np.pi, 72001)[:-1]
    h, dh, ddh = cam.evaluate(th)
    assert h.max() == pytest.approx(9e-3, rel=1e-9)
    assert cam.lift_at(total / 2) == pytest.approx(9e-3, rel=1e-12)
    assert np.all(h[th > total + 1e-9] == 0)
    # symmetric event
    np.testing.assert_allclose(cam.lift_at(total / 2 - th[:100]), cam.lift_at(total / 2 + th[:100]), atol=1e-15)
    # analytic derivatives against central differences, away from the junctions (event
    # ends, ramp ends, nose) where jerk (or, at a ramp start, velocity) steps by design
    d = th[1] - th[0]
    phi = cam.ramp_duration
    junctions = np.array([0.0, phi, total / 2, total - phi, total, 2 * np.pi])
    inner = np.min(np.abs(th[:, None] - junctions[None, :]), axis=1) > 2.5 * d
    num_dh = (np.roll(h, -1) - np.roll(h, 1)) / (2 * d)
    num_ddh = (np.roll(dh, -1) - np.roll(dh, 1)) / (2 * d)
    scale_v, scale_a = np.abs(dh).max(), np.abs(ddh).max()
    assert np.max(np.abs(num_dh - dh)[inner]) < 1e-6 * scale_v  # O(d^2) truncation
    assert np.max(np.abs(num_ddh - ddh)[inner]) < 1e-6 * scale_a
    if ramps:
        phi = math.radians(15)
        v_r = 0.3e-3 / phi
        # velocity and acceleration continuous where the ramp meets the main rise
        e = 1e-9
        vel, acc = cam.evaluate([phi - e, phi + e])[1:]
        assert vel[0] == pytest.approx(v_r, rel=1e-6) and vel[1] == pytest.approx(v_r, rel=1e-6)
        assert abs(acc[1]) < 1e-6 * scale_a


def test_table_cam_periodic_spline(tmp_path):
    cam = Cam(law="3-4-5", lift=9e-3, duration=DUR)
    deg = np.arange(0, 360, 0.5)
    f = tmp_path / "lift.csv"
    f.write_text(
        "cam_angle_deg,lift_mm\n" + "".join(f"{a},{float(cam.lift_at(math.radians(a))) * 1e3!r}\n" for a in deg)
    )
    tab = Cam.from_dict({"law": "table", "file": str(f)})
    th = np.radians(np.linspace(0, 359.9, 3001))
    np.testing.assert_allclose(tab.lift_at(th), cam.lift_at(th), atol=2e-7)  # 0.5 deg cubic spline of a quintic
    # periodic: value and two derivatives match across 360 deg
    e = 1e-9
    for k in range(3):
        assert tab.evaluate(2 * np.pi - e)[k] == pytest.approx(tab.evaluate(e)[k], abs=1e-6 * (1 + k * 1e-2))
    # SI columns and a closing row at 360 deg are accepted
    f2 = tmp_path / "si.csv"
    rows = [(math.radians(a), float(cam.lift_at(math.radians(a)))) for a in np.append(deg, 360)]
    f2.write_text("cam_angle_rad,lift_m\n" + "".join(f"{a!r},{h!r}\n" for a, h in rows))
    np.testing.assert_allclose(
        Cam.from_dict({"law": "table", "file": str(f2)}).lift_at(th), tab.lift_at(th), atol=1e-12
    )


def test_table_relative_to_toml(tmp_path):
    (tmp_path / "t.csv").write_text("cam_angle_deg,lift_mm\n" + "".join(f"{a},0\n" for a in range(0, 360, 10)))
    (tmp_path / "c.toml").write_text('[cam]\nlaw = "table"\nfile = "t.csv"\n')
    assert Cam.from_toml(tmp_path / "c.toml").max_lift == 0.0


def test_coarse_table_warns():
    th = np.radians(np.arange(0, 360, 10.0))
    cam = Cam.from_table(th, Cam(law="cycloidal", lift=9e-3, duration=DUR).lift_at(th), "coarse")
    # f1 = 450 Hz is cam order 90 at 300 rpm: beyond the table's Nyquist order 18
    with pytest.warns(UserWarning, match="largest step of 10 deg resolves cam orders up to 18"):
        cam.check_resolution(300, 450.0)
    with warnings.catch_warnings():  # order 9 at 3000 rpm: resolved
        warnings.simplefilter("error")
        cam.check_resolution(3000, 450.0)


@pytest.mark.parametrize(
    "mapping,pattern",
    [
        ({"law": "5-6-7", "lift": "9 mm", "duration": "120 deg"}, r"law = '5-6-7' is not allowed"),
        ({"law": "3-4-5", "lift": "0 mm", "duration": "120 deg"}, r"lift = 0 mm must be positive"),
        ({"law": "3-4-5", "lift": "-1 mm", "duration": "120 deg"}, r"lift = -1 mm must be positive"),
        ({"law": "3-4-5", "lift": "9 mm", "duration": "0 deg"}, r"duration = 0 deg must lie in \(0, 360\] deg"),
        ({"law": "3-4-5", "lift": "9 mm", "duration": "400 deg"}, r"duration = 400 deg must lie in \(0, 360\] deg"),
        ({"law": "3-4-5", "lift": "9 mm"}, r"law = '3-4-5' needs duration"),
        (
            {"law": "3-4-5", "lift": "9 mm", "duration": "120 deg", "ramp_height": "0.3 mm"},
            r"ramp_height is given without ramp_duration",
        ),
        ({"law": "3-4-5", "lift": "9 mm", "duraton": "120 deg"}, r"unknown key 'duraton'"),
        ({"law": "table"}, r'law = "table" needs file'),
    ],
)
def test_bad_cam(mapping, pattern):
    with pytest.raises(InputError, match=pattern):
        Cam.from_dict(mapping)


@pytest.mark.parametrize(
    "rows,pattern",
    [
        ([(a, 1.0) for a in range(0, 200, 10)], r"must cover one whole revolution"),
        ([(a, 1.0) for a in range(0, 400, 10)], r"more than one revolution"),
        ([(a, 1.0) for a in [0, 10, 20, 15, 30, 40, 50, 60, 70, 80]], r"cam angle must increase: row 5 \(15 deg\)"),
        ([(a, -1.0 if a == 50 else 0.0) for a in range(0, 360, 10)], r"lift must not be negative: row 7 has -1 mm"),
    ],
)
def test_bad_table(tmp_path, rows, pattern):
    f = tmp_path / "bad.csv"
    f.write_text("cam_angle_deg,lift_mm\n" + "".join(f"{a},{h}\n" for a, h in rows))
    with pytest.raises(InputError, match=pattern):
        Cam.from_dict({"law": "table", "file": str(f)})


def test_table_missing_columns(tmp_path):
    f = tmp_path / "bad.csv"
    f.write_text("angle,lift\n0,0\n")
    with pytest.raises(InputError, match="needs columns cam_angle_deg"):
        Cam.from_dict({"law": "table", "file": str(f)})


@pytest.mark.parametrize("cell", ["nan", "inf", "-inf"])
def test_nan_in_lift_table_names_file_row_and_column(tmp_path, cell):
    """A ``nan`` in a lift table CSV crashed with a traceback."""
    f = tmp_path / "nan.csv"
    f.write_text("cam_angle_deg,lift_mm\n" + "".join(f"{a},{cell if a == 40 else 1.0}\n" for a in range(0, 360, 10)))
    with pytest.raises(InputError, match=rf"{f}: row 6, column 'lift_mm': '{cell}' is not a finite number"):
        Cam.from_dict({"law": "table", "file": str(f)})


@pytest.mark.parametrize(
    "angle,lift,pattern",
    [
        (
            np.radians(np.arange(0, 360, 10.0)),
            np.where(np.arange(36) == 4, np.nan, 0.0),
            r"table: row 6, column lift: nan is not a finite number",
        ),
        (
            np.where(np.arange(36) == 0, np.inf, np.radians(np.arange(0, 360, 10.0))),
            np.zeros(36),
            r"table: row 2, column cam angle: inf is not a finite number",
        ),
        (np.radians(np.arange(0, 360, 10.0)), np.zeros(35), r"two flat arrays of the same length"),
        (np.radians(np.arange(0, 360, 10.0)), ["a"] * 36, r"arrays of numbers"),
    ],
)
def test_bad_table_arrays(angle, lift, pattern):
    """The Python API (``Cam.from_table``) is checked like the CSV reader."""
    with pytest.raises(InputError, match=pattern):
        Cam.from_table(angle, lift)


def test_cam_and_valve_train_use_the_parameters_base(tmp_path):
    """One from_dict/from_toml; a relative table path is resolved by ``_prepare``
    from the ``base_dir`` context (and left alone without it)."""
    from springdyn.core.params import Parameters
    from springdyn.valve import ValveTrain

    assert issubclass(Cam, Parameters) and Cam.table == "cam"
    assert issubclass(ValveTrain, Parameters) and ValveTrain.table == "valve_train"
    (tmp_path / "t.csv").write_text("cam_angle_deg,lift_mm\n" + "".join(f"{a},0\n" for a in range(0, 360, 10)))
    cam = Cam.from_dict({"law": "table", "file": "t.csv"}, base_dir=tmp_path)
    assert cam.file == str(tmp_path / "t.csv")
    with pytest.raises(InputError, match="t.csv: no such file"):
        Cam.from_dict({"law": "table", "file": "t.csv"}, base_dir=tmp_path / "elsewhere")
    (tmp_path / "vt.toml").write_text('[valve_train]\nvalve_mass = "50 g"\nlash = "0.1 mm"\n')
    vt = ValveTrain.from_toml(tmp_path / "vt.toml")
    assert vt.valve_mass == pytest.approx(0.05) and vt.lash == pytest.approx(1e-4)
    with pytest.raises(InputError, match=r"\[valve_train\] unknown key 'valve_mas'"):
        ValveTrain.from_dict({"valve_mas": 0.05})


def test_the_cam_table_interpolates_the_law_it_samples():
    """CamTable (the cam as the engine sees it): at its nodes it returns the sampled lift and
    slope exactly; between them the quintic Hermite interpolant of a smooth law (3-4-5, 9 mm
    over 120 deg) stays within 1e-9 m of the law's own lift (the interpolation error of a
    quintic on a 0.05 deg grid, h^6 f^(6) / 46080 ~ 1e-15 m, far below; the bound allows for
    the law's evaluation round-off); its angles repeat every revolution."""
    from springdyn.valve.engine import CamTable

    cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(120))
    table = CamTable.of(cam, 7200)
    lift, slope = table.at(np.arange(7200) * table.dth)
    np.testing.assert_allclose(lift, table.h, rtol=0, atol=1e-15)
    np.testing.assert_allclose(slope, table.dh, rtol=0, atol=1e-12)
    theta = (np.arange(7200) + 0.37) * table.dth
    fine = CamTable.of(cam, 7200 * 8)
    np.testing.assert_allclose(table.at(theta)[0], fine.at(theta)[0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(table.at(theta + 2 * math.pi)[0], table.at(theta)[0], rtol=0, atol=1e-15)
