"""The damper as a ROSS bearing element in a small rotor (optional extra springdyn[ross])."""

import warnings

import numpy as np
import pytest

from springdyn.lsd import LSDModel, LSDParameters


@pytest.mark.slow  # importing ross takes about 10 s
def test_ross_rotor_modal_analysis():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        rs = pytest.importorskip("ross")
    # Type C with 20x the passage conductance: damping ratio ~0.18, so the rigid-body
    # bounce mode is an underdamped pair that run_modal reports cleanly
    model = LSDModel(LSDParameters.example("C").replace(leakage_factor=20.0))
    w = 2 * np.pi * np.linspace(500, 3000, 11) / 60
    b0 = model.to_ross(0, w, tag="lsd0")
    b1 = model.to_ross(2, w, tag="lsd1")
    assert isinstance(b0, rs.BearingElement)
    res = model.coefficients(60 * w / (2 * np.pi))
    # the eight tabulated coefficients are handed over unchanged ...
    np.testing.assert_allclose(b0.kxx, res.K[:, 0, 0])
    np.testing.assert_allclose(b0.cyy, res.C[:, 1, 1])
    np.testing.assert_allclose(b0.cxy, res.C[:, 0, 1])
    # ... and ROSS evaluates them through a smoothing spline (UnivariateSpline, s = number of
    # points), not an interpolating one: 0.1 % tolerance at a tabulated frequency
    np.testing.assert_allclose(b0.K(w[3])[:2, :2], res.K[3], rtol=1e-3, atol=1e-6 * res.K[3, 0, 0])
    np.testing.assert_allclose(b0.C(w[3])[:2, :2], res.C[3], rtol=1e-3, atol=1e-6 * res.C[3, 0, 0])

    steel = rs.Material(name="steel_lsd_test", rho=7810, E=211e9, G_s=81.2e9)
    shaft = [rs.ShaftElement(0.1, 0.0, 0.08, material=steel, shear_effects=True, rotary_inertia=True,
                             gyroscopic=True) for _ in range(2)]
    disk = rs.DiskElement.from_geometry(n=1, material=steel, width=0.05, i_d=0.08, o_d=0.2)
    rotor = rs.Rotor(shaft, [disk], [b0, b1])
    speed = 2 * np.pi * 1000 / 60
    modal = rotor.run_modal(speed=speed, num_modes=8)
    # independent check: a rigid rotor of mass M on two dampers, bounce mode
    # wn = sqrt(2 Kxx / M), zeta = 2 Cxx / (2 sqrt(2 Kxx M)), log dec = 2 pi zeta / sqrt(1 - zeta^2).
    # Tolerances 1 % / 2 %: the 0.2 m, 80 mm shaft is nearly rigid (bending modes far higher)
    c = model.coefficients([1000.0])
    K, C, M = c.K[0, 0, 0], c.C[0, 0, 0], rotor.m
    wn = np.sqrt(2 * K / M)
    zeta = 2 * C / (2 * np.sqrt(2 * K * M))
    assert modal.wn[0] == pytest.approx(wn, rel=0.01)
    assert modal.log_dec[0] == pytest.approx(2 * np.pi * zeta / np.sqrt(1 - zeta**2), rel=0.02)
