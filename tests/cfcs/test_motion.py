"""Prescribed motions: the sinusoid of Fig. 4 and periodic CSV input."""

import numpy as np
import pytest

from springdyn.cfcs import SinusoidMotion, TabulatedMotion
from springdyn.cfcs.motion import amplitude_to_si
from springdyn.core.errors import InputError
from springdyn.core.io import write_csv


def test_sinusoid_derivatives():
    # analytic derivatives against central differences (h = 1e-6 s: error ~1e-10 relative)
    m = SinusoidMotion(omega=7.0, amplitude=0.05, offset=0.01)
    t = np.linspace(0, 1, 11)
    x, xd, xdd = m(t)
    h = 1e-6
    np.testing.assert_allclose(xd, (m(t + h)[0] - m(t - h)[0]) / (2 * h), atol=1e-8)
    np.testing.assert_allclose(xdd, (m(t + h)[1] - m(t - h)[1]) / (2 * h), atol=1e-6)
    assert m.bounds == (0.01, pytest.approx(0.06))
    assert x[0] == 0.01


def test_amplitude_fraction_or_length():
    # the paper's "40 %": 0.4 (r2 + r3) = 72 mm for Table 1
    assert amplitude_to_si(0.4, 0.18) == pytest.approx(0.072)
    assert amplitude_to_si("40%", 0.18) == pytest.approx(0.072)
    assert amplitude_to_si("72 mm", 0.18) == pytest.approx(0.072)
    with pytest.raises(InputError):
        amplitude_to_si("-3 mm", 0.18)


def test_csv_motion_reproduces_the_sinusoid(tmp_path, model):
    # a sinusoid sampled at 401 points and read back through the periodic spline: the inverse force agrees
    # with the analytic input to the spline's accuracy (~h^4: 1e-3 N with x'' the least accurate)
    sine = SinusoidMotion(omega=4.19, amplitude=0.05, offset=0.005)
    t = np.linspace(0.0, sine.period, 401)
    path = write_csv(tmp_path / "x.csv", {"time_s": t, "deflection_m": sine(t)[0]})
    tab = TabulatedMotion.from_csv(path)
    assert tab.period == pytest.approx(sine.period)
    a = model.dynamic(motion=sine, cycles=1)
    b = model.dynamic(motion=tab, cycles=1)
    np.testing.assert_allclose(b.force, a.force, atol=1e-3)
    # with omega the period is rescaled
    assert TabulatedMotion.from_csv(path, omega=10.0).period == pytest.approx(2 * np.pi / 10.0)


def test_csv_motion_errors(tmp_path, model):
    path = write_csv(tmp_path / "bad.csv", {"time_s": [0, 1, 2, 3], "deflection_m": [0.0, 0.01, 0.02, 0.03]})
    with pytest.raises(InputError, match="not periodic"):
        TabulatedMotion.from_csv(path)
    path = write_csv(tmp_path / "cols.csv", {"t": [0, 1], "x": [0, 0]})
    with pytest.raises(InputError, match="no column 'time_s'"):
        TabulatedMotion.from_csv(path)
    big = write_csv(tmp_path / "big.csv", {"time_s": [0, 1, 2, 3, 4], "deflection_m": [0.0, 0.1, 0.15, 0.1, 0.0]})
    with pytest.raises(InputError, match="kinematic limit"):
        model.dynamic(motion=TabulatedMotion.from_csv(big))
