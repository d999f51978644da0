"""The cam checks (springdyn.valve.cam.checks, springdyn.valve.cam.follower) against closed forms:
the eccentric circle cam under a flat face and a roller, Hertz line contact by hand, the
crowned (Hamrock-Brewe) contact against the exact elliptic-integral Hertz solution and its
sphere and line limits, the kinematic load by hand; and the failures they must flag."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from springdyn.core.errors import InputError
from springdyn.valve import Cam, ValveSpring, ValveTrain
from springdyn.valve.cam.checks import (
    check_cam,
    elliptical_contact,
    kinematic_cam_force,
    line_contact,
    pitch_curve_curvature,
    roller_cam_curvature,
)
from springdyn.valve.cam.follower import Follower
from tests.paths import EXAMPLES as ALL_EXAMPLES

EXAMPLES = ALL_EXAMPLES / "valve"
VT_FOLLOWER = EXAMPLES / "valve_train_with_follower.toml"
SPRING = EXAMPLES / "one_step_spring.toml"
E_STAR = 206e9 / (2 * (1 - 0.3**2))  # steel on steel [Pa]

R, ECC = 0.020, 0.004  # eccentric circle: radius 20 mm, eccentricity 4 mm


class EccentricFlat:
    """The eccentric circle under a flat face: h = e (1 - cos theta), exactly."""

    law = "eccentric"

    def evaluate(self, theta):
        t = np.asarray(theta, dtype=float)
        return ECC * (1 - np.cos(t)), ECC * np.sin(t), ECC * np.cos(t)


class EccentricRoller:
    """The eccentric circle under a roller of radius r whose axis is ``offset`` off the cam
    centre: the roller centre lies on the circle of radius R + r about the eccentric centre
    ``c = (e sin theta, -e cos theta)``: ``y = -e cos theta + S``, ``S = sqrt(A^2 - u^2)``,
    ``u = offset - e sin theta``, ``A = R + r``; ``h = y - d0`` (exact derivatives)."""

    law = "eccentric"

    def __init__(self, r, offset=0.0):
        self.a, self.eps = R + r, offset
        self.d0 = math.sqrt((R - ECC + r) ** 2 - offset**2)

    def evaluate(self, theta):
        t = np.asarray(theta, dtype=float)
        u, du, ddu = self.eps - ECC * np.sin(t), -ECC * np.cos(t), ECC * np.sin(t)
        s = np.sqrt(self.a**2 - u**2)
        ds = -u * du / s
        dds = -(du**2 + u * ddu) / s - (u * du) ** 2 / s**3
        return -ECC * np.cos(t) + s - self.d0, ECC * np.sin(t) + ds, ECC * np.cos(t) + dds


def flat(**kw):
    return Follower(kind="flat", base_circle_radius=kw.pop("base_circle_radius", R - ECC), width=0.012, **kw)


def roller(r=0.009, **kw):
    return Follower(
        kind="roller", base_circle_radius=kw.pop("base_circle_radius", R - ECC), roller_radius=r, width=0.012, **kw
    )


# ----------------------------------------------------------------------------- geometry
def test_eccentric_circle_under_a_flat_face_is_the_circle():
    """rho = R_b + h + h'' = (R - e) + e(1 - cos) + e cos = R exactly; the profile is the circle
    of radius R about (0, -e) in the cam frame; the contact sits e sin(theta) off the axis
    ([Norton]: the eccentricity equals h').  Round-off only: 1e-12."""
    res = check_cam(EccentricFlat(), None, flat(), samples=720)
    assert np.allclose(res.radius, R, rtol=0, atol=1e-12)
    assert np.allclose(np.hypot(res.x, res.y + ECC), R, rtol=0, atol=1e-12)
    assert np.allclose(res.excursion, ECC * np.sin(res.cam_angle), rtol=0, atol=1e-15)
    s = res.summary
    assert s["min_radius_of_curvature_m"] == pytest.approx(R, abs=1e-12)
    assert s["max_excursion_m"] == pytest.approx(ECC, rel=1e-5)  # the 0.5 deg grid's peak: cos(0.25 deg)
    assert not s["undercut"] and s["ok"]


def test_eccentric_circle_from_a_lift_table():
    """The same cam as a law = "table" (0.5 deg rows, periodic cubic spline): rho = R to the
    spline's second-derivative error, about e d^2 / 12 = 2.5e-8 m for d = 0.5 deg; 1e-7 m."""
    a = np.radians(np.arange(0.0, 360.0, 0.5))
    cam = Cam.from_table(a, ECC * (1 - np.cos(a)))
    res = check_cam(cam, None, flat(), samples=3600)
    assert np.abs(res.radius - R).max() < 1e-7


@pytest.mark.parametrize("offset", [0.0, 0.003])
def test_eccentric_circle_under_a_roller(offset):
    """Its roller centre runs on the circle of radius R + r about the eccentric centre (0, -e),
    the cam surface is the circle of radius R (rho = rho_p - r = R), and the contact normal
    runs through the eccentric centre: its angle to the axis is atan2(-u, S) of the class's
    construction (offset 0: sin(phi) = e sin(theta)/(R + r)).  Round-off only: 1e-9."""
    r = 0.009
    cam = EccentricRoller(r, offset)
    res = check_cam(cam, None, roller(r, offset=offset), samples=720)
    assert np.allclose(np.hypot(res.pitch_x, res.pitch_y + ECC), R + r, rtol=0, atol=1e-12)
    assert np.allclose(np.hypot(res.x, res.y + ECC), R, rtol=0, atol=1e-12)
    assert np.allclose(res.radius, R, rtol=1e-9)
    assert np.allclose(1.0 / res.pitch_curvature, R + r, rtol=1e-9)
    t = res.cam_angle
    u = offset - ECC * np.sin(t)
    phi = np.arctan2(-u, np.sqrt((R + r) ** 2 - u**2))
    assert np.allclose(res.pressure_angle, phi, rtol=0, atol=1e-12)
    if offset == 0.0:
        assert np.allclose(np.sin(res.pressure_angle), ECC * np.sin(t) / (R + r), rtol=0, atol=1e-12)
    assert not res.summary["undercut"]


def test_pitch_curvature_of_the_base_circle_and_the_undercut_rule():
    """On the base circle (h = 0) the pitch curve is a circle of radius d0: curvature 1/d0; the
    cam surface r inside it has curvature 1/(d0 - r); a convex pitch radius below r folds."""
    k = pitch_curve_curvature(0.0, 0.0, 0.0, 0.025)
    assert float(k) == pytest.approx(1 / 0.025, rel=1e-14)
    kc, undercut = roller_cam_curvature(k, 0.009)
    assert float(kc) == pytest.approx(1 / 0.016, rel=1e-14) and not undercut
    _, undercut = roller_cam_curvature(1 / 0.008, 0.009)
    assert undercut


# ----------------------------------------------------------------------------- contact
def test_line_contact_by_hand():
    """[Johnson] 4.2, two steel cylinders of 10 mm under 1000 N over 10 mm:
    E* = 206e9 / (2 (1 - 0.3^2)) = 113.1868 GPa, R = 5 mm,
    p0 = sqrt(1000 x 113.1868e9 / (pi x 0.01 x 0.005)) = 848.86 MPa,
    b = sqrt(4 x 1000 x 0.005 / (pi x 0.01 x 113.1868e9)) = 0.074997 mm (to the digits shown)."""
    p, b = line_contact(1000.0, 0.01, 1 / (1 / 0.01 + 1 / 0.01), E_STAR)
    assert float(p) == pytest.approx(848.86e6, rel=1e-5)
    assert float(b) == pytest.approx(0.074997e-3, rel=1e-5)
    f = Follower(kind="roller", base_circle_radius=0.015, roller_radius=0.01, width=0.01)
    assert f.reduced_modulus == pytest.approx(113.1868e9, rel=1e-6)


def _hertz_exact(force, rx, ry, e_star):
    """The exact Hertz point contact ([Johnson] 4.2) in complete elliptic integrals: with the
    semi-major axis a along the larger radius and m = 1 - (b/a)^2, the curvature ratio is
    R_y/R_x = (E(m)/(1 - m) - K(m)) / (K(m) - E(m)) and a^3 = 3 F R_y (K - E) / (pi m E*)."""
    ratio = ry / rx
    m = brentq(lambda m: (ellipe(m) / (1 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - ratio, 1e-12, 1 - 1e-15)
    k, e = ellipk(m), ellipe(m)
    a = (3 * force * ry * (k - e) / (math.pi * m * e_star)) ** (1 / 3)
    b = a * math.sqrt(1 - m)
    return 3 * force / (2 * math.pi * a * b), b, a


def test_crowned_contact_is_exact_for_a_sphere():
    """alpha = 1: Hamrock-Brewe's k = 1 and E = pi/2 are exact, so the contact is Hertz's
    sphere: a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2) (1e-12)."""
    rx = 0.007
    p, ax, ay = elliptical_contact(500.0, rx, rx, E_STAR)
    a = (3 * 500.0 * rx / (4 * E_STAR)) ** (1 / 3)
    assert float(ax) == pytest.approx(a, rel=1e-12) and float(ay) == pytest.approx(a, rel=1e-12)
    assert float(p) == pytest.approx(3 * 500.0 / (2 * math.pi * a * a), rel=1e-12)


@pytest.mark.parametrize("alpha", [1.5, 2.0, 5.0, 10.0, 30.0, 100.0])
def test_crowned_contact_against_the_exact_hertz_solution(alpha):
    """Within Hamrock and Brewe's fitted range (radius ratio 1-100) their formulas stay within
    a few per cent of the exact solution (the largest deviation found is 1.6 % at alpha = 5,
    on p0; 2.6 % on the long semi-axis); the test allows 2 % on p0 and the short semi-axis and
    3 % on the long one.  Axes swapped (R_x > R_y) give the same contact, turned."""
    rx, ry = 0.005, 0.005 * alpha
    p_ex, b_ex, a_ex = _hertz_exact(800.0, rx, ry, E_STAR)
    p, ax, ay = elliptical_contact(800.0, rx, ry, E_STAR)
    assert float(p) == pytest.approx(p_ex, rel=0.02)
    assert float(ax) == pytest.approx(b_ex, rel=0.02)
    assert float(ay) == pytest.approx(a_ex, rel=0.03)
    p2, ax2, ay2 = elliptical_contact(800.0, ry, rx, E_STAR)
    assert (float(p2), float(ax2), float(ay2)) == pytest.approx((float(p), float(ay), float(ax)), rel=1e-14)


def test_crowned_contact_tends_to_the_line_contact():
    """As the crown flattens the ellipse becomes a strip whose centre section is a line contact
    of radius R_x: p0 = E* b / (2 R_x) ([Johnson] 4.2, the 2D Hertz relation).  The exact
    solution approaches it as 0.45/alpha; the test allows 2/alpha at alpha = 1e4."""
    rx = 0.005
    p, ax, _ = elliptical_contact(800.0, rx, rx * 1e4, E_STAR)
    assert float(p) / (E_STAR * float(ax) / (2 * rx)) == pytest.approx(1.0, abs=2e-4)


def test_kinematic_force_by_hand():
    """F = r (F_s + M z'') while open, r F_0 closed: 1.5 x 15 = 22.5 N on the base circle,
    1.5 x (300 - 0.1 x 1000) = 300 N open."""
    f = kinematic_cam_force([0.0, 1e-3], [0.0, -1000.0], [250.0, 300.0], 0.1, 1.5, base_force=15.0)
    assert f.tolist() == pytest.approx([22.5, 300.0], rel=1e-15)


def test_check_cam_assembles_the_load_and_the_stress_by_hand():
    """At the nose of the example lobe at 3000 cam rpm: F = F_s(L_inst - z) + (M + m_s/3) h'' w^2
    (ratio 1), normal to the flat face; stress = sqrt(F E* / (pi L rho)), rho = R_b + h + h''."""
    cam = Cam(
        law="polydyne", lift=8.15e-3, duration=math.radians(140), ramp_height=0.25e-3, ramp_duration=math.radians(20)
    )
    vt = ValveTrain.from_toml(VT_FOLLOWER)
    follower = Follower.in_file(VT_FOLLOWER)
    spring = ValveSpring.from_toml(SPRING)
    res = check_cam(cam, vt, follower, spring, cam_rpm=3000.0, samples=7200)
    i = 1800  # 90 deg: the nose (ramp 20 + 140/2)
    h, _, ddh = (float(a) for a in cam.evaluate(res.cam_angle[i]))
    w = 3000 * 2 * math.pi / 60
    m = vt.moving_mass + spring.spring_model.internal_parameters()["M"] / 3
    f = float(spring.spring_model.static_force(spring.installed_length - (h - vt.lash))) + m * ddh * w**2
    assert res.force[i] == pytest.approx(f, rel=1e-12)
    rho = follower.base_circle_radius + h + ddh
    assert res.stress[i] == pytest.approx(math.sqrt(f * E_STAR / (math.pi * follower.width * rho)), rel=1e-12)
    s = res.summary
    assert s["ok"] and s["follower_stays_on_cam"] and s["load"] == "kinematic"
    assert s["max_contact_stress_Pa"] < follower.allowable_contact_stress


def test_a_given_contact_force_and_the_crowned_limit():
    """A given constant force on a flat face gives the line contact everywhere; a spherical face
    so flat (500 m) that its ellipse outgrows the width is edge loaded and reports the line
    contact's stress (the larger of the two)."""
    cam = Cam(law="3-4-5", lift=8e-3, duration=math.radians(150))
    f = flat(base_circle_radius=0.03)
    theta = np.radians(np.arange(0.0, 360.0, 1.0))
    res = check_cam(cam, None, f, contact_force=np.full(theta.size, 600.0), contact_angle=theta)
    rho = res.radius
    assert np.allclose(res.stress, np.sqrt(600.0 * E_STAR / (math.pi * f.width * rho)), rtol=1e-12)
    assert rho.min() > 0
    crowned = check_cam(cam, None, flat(base_circle_radius=0.03, crown_radius=500.0), contact_force=np.full(360, 600.0))
    assert crowned.edge_loaded.all()
    rx = 1 / (1 / rho + 1 / 500.0)  # a spherical face is curved along the rolling direction too
    assert np.allclose(crowned.stress, np.sqrt(600.0 * E_STAR / (math.pi * f.width * rx)), rtol=1e-12)
    assert any("edge loaded" in n for n in crowned.summary["notes"])


# ----------------------------------------------------------------------------- failures
def test_a_cusp_under_a_flat_face_is_flagged():
    """3-4-5, 9 mm over 60 deg on a 5 mm base circle: the nose needs h'' of about -0.19 m/rad^2,
    far below -(R_b + h): rho < 0."""
    cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(60))
    s = check_cam(cam, None, flat(base_circle_radius=0.005)).summary
    assert s["concave"] and s["undercut"] and not s["ok"]
    assert "radius of curvature" in s["checks_failed"] and s["min_radius_of_curvature_m"] < 0


def test_an_undercut_roller_cam_is_flagged():
    """The same lobe under a 12 mm roller on a 5 mm base circle: the pitch curve's convex radius
    falls below the roller's (the nose's deceleration sharpens the pitch curve)."""
    cam = Cam(law="3-4-5", lift=9e-3, duration=math.radians(60))
    s = check_cam(cam, None, roller(0.012, base_circle_radius=0.005)).summary
    assert s["undercut"] and "radius of curvature" in s["checks_failed"]
    assert s["min_pitch_radius_m"] < 0.012
    gentle = Cam(law="3-4-5", lift=9e-3, duration=math.radians(150))  # the same roller on a gentler lobe
    assert check_cam(gentle, None, roller(0.012, base_circle_radius=0.02)).summary["undercut"] is False


def test_excursion_beyond_the_face_and_an_exceeded_allowable_are_flagged():
    cam = Cam(
        law="polydyne", lift=8.15e-3, duration=math.radians(140), ramp_height=0.25e-3, ramp_duration=math.radians(20)
    )
    spring = ValveSpring.from_toml(SPRING)
    small = flat(base_circle_radius=0.017, face_radius=0.010, allowable_contact_stress=100e6)
    s = check_cam(cam, None, small, spring, 1000.0).summary
    assert s["excursion_ok"] is False and s["contact_stress_ok"] is False
    assert set(s["checks_failed"]) == {"contact excursion", "contact stress"}
    # the reach of the contact line's end: sqrt(e^2 + (|lateral| + w/2)^2)
    assert s["max_face_reach_m"] == pytest.approx(math.hypot(s["max_excursion_m"], 0.006), rel=1e-12)


def test_follower_table_is_validated():
    with pytest.raises(InputError, match="roller_radius"):
        Follower.from_dict({"kind": "roller", "base_circle_radius": "15 mm", "width": "12 mm"})
    with pytest.raises(InputError, match="face_radius"):
        Follower.from_dict(
            {
                "kind": "roller",
                "base_circle_radius": "15 mm",
                "width": "12 mm",
                "roller_radius": "9 mm",
                "face_radius": "16 mm",
            }
        )
    with pytest.raises(InputError, match="must be positive"):
        Follower.from_dict({"kind": "flat", "base_circle_radius": "-15 mm", "width": "12 mm"})
    with pytest.raises(InputError, match="allowable_contact_stress"):
        Follower.from_dict(
            {"kind": "flat", "base_circle_radius": "15 mm", "width": "12 mm", "allowable_contact_stress": "9 GPa"}
        )
    f = Follower.in_file(VT_FOLLOWER)
    assert f.kind == "flat" and f.margin == pytest.approx(1e-3)
    assert Follower.in_file(EXAMPLES / "valve_train.toml") is None


def test_check_cam_rejects_a_double_load():
    cam = Cam(law="3-4-5", lift=8e-3, duration=math.radians(150))
    spring = ValveSpring.from_toml(SPRING)
    with pytest.raises(InputError, match="not both"):
        check_cam(cam, None, flat(), spring, contact_force=np.ones(360))
    with pytest.raises(InputError, match="needs the spring"):
        check_cam(cam, None, flat(), cam_rpm=3000.0)


def test_result_interface(tmp_path):
    cam = Cam(law="3-4-5", lift=8e-3, duration=math.radians(150))
    res = check_cam(cam, None, roller(0.009, base_circle_radius=0.017), ValveSpring.from_toml(SPRING), 2000.0)
    ds = res.to_xarray()
    assert {"profile_x", "profile_y", "pitch_x", "curvature", "pressure_angle", "contact_stress"} <= set(ds)
    path = res.to_csv(tmp_path / "c.csv")
    assert "contact_stress_Pa" in path.read_text().splitlines()[0]
    fig = res.plot(tmp_path / "c.png")
    assert (tmp_path / "c.png").stat().st_size > 0 and len(fig.axes) == 4
    assert "cam check" in repr(res)


# ----------------------------------------------------------------------------- CLI
def run(capsys, *argv):
    from springdyn.app.cli.main import main

    code = main(list(map(str, argv)))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_cam_check_on_the_examples(capsys, tmp_path):
    cam = EXAMPLES / "cam_polydyne_ramps.toml"
    code, out, _ = run(capsys, "valve", "cam-check", cam, "--valve-train", VT_FOLLOWER)
    assert code == 0 and "radius of curvature" in out and "no load given" in out
    code, out, _ = run(
        capsys,
        "valve",
        "cam-check",
        cam,
        "--valve-train",
        VT_FOLLOWER,
        "--spring",
        SPRING,
        "--engine-rpm",
        "6000",
        "--json",
    )
    data = json.loads(out)
    assert code == 0 and data["cam_rpm"] == 3000.0 and "max_contact_stress_Pa" in data
    # this lobe (9 mm over 110 deg) is too sharp for a 17 mm base circle under a flat face
    assert data["concave"] and not data["ok"]
    code, out, _ = run(
        capsys,
        "valve",
        "cam-check",
        cam,
        "--valve-train",
        VT_FOLLOWER,
        "--csv",
        tmp_path / "c.csv",
        "--plot",
        tmp_path / "c.png",
    )
    assert code == 0 and (tmp_path / "c.csv").is_file() and (tmp_path / "c.png").is_file()


def test_cli_cam_check_bad_input(capsys):
    cam = EXAMPLES / "cam_polydyne_ramps.toml"
    code, _, err = run(capsys, "valve", "cam-check", cam, "--valve-train", EXAMPLES / "valve_train.toml")
    assert code == 2 and "no [follower] table" in err
    code, _, err = run(capsys, "valve", "cam-check", cam, "--valve-train", VT_FOLLOWER, "--cam-rpm", "3000")
    assert code == 2 and "--spring" in err


def test_the_base_circle_load_does_not_flicker_with_an_adjuster():
    """Issue 39: with a hydraulic adjuster (no lash) the base circle's round-off lift (+-1e-54 m)
    counted as open, and the load alternated between the plunger force and the spring's
    (24.75 <-> 459.5 N in the report).  The valve is open where the lobe is past the lash by
    OPEN_LIFT, the run's rule: below it the load is the adjuster's force alone."""
    import dataclasses

    from springdyn.valve.cam.definition import OPEN_LIFT

    path = str(ALL_EXAMPLES / "valve" / "valve_train_with_follower.toml")
    vt = dataclasses.replace(ValveTrain.from_toml(path), lash_adjuster="hydraulic", lash=0.0)
    lobe = Cam.from_toml(str(ALL_EXAMPLES / "valve" / "cam_345.toml"))
    res = check_cam(lobe, vt, Follower.in_file(path), spring=ValveSpring.example("one-step"), cam_rpm=3000.0)
    closed = res.lift <= OPEN_LIFT
    assert closed.sum() > 10 and (res.lift[closed] > 0).any()  # round-off lifts among them
    assert np.all(res.force[closed] == pytest.approx(vt.ratio * vt.hla_force, rel=1e-12))
    assert res.force[np.argmax(res.lift > 10 * OPEN_LIFT)] > 5 * vt.hla_force  # open: the spring's force
