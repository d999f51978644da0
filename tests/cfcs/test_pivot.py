"""Flexural pivot: Eq. (1) of the CFCS paper and reading notes 2.3."""

import numpy as np
import pytest

from springdyn.cfcs import pivot
from springdyn.cfcs.kinematics import deflection_from_theta2, spring_angle, theta2_from_deflection

from .conftest import R2, R3


def test_k3_from_table1(table1):
    # reading notes 2.3: I = 1.1615e-13 m^4, K3 = 207e9 * 1.1615e-13 / 0.0095 = 2.5308 N*m/rad (5 digits printed)
    assert pivot.second_moment_rectangle(0.0254, 0.38e-3) == pytest.approx(1.1615e-13, rel=5e-5)
    assert table1.k3 == pytest.approx(2.5308, rel=5e-5)
    assert pivot.flexure_stiffness(207e9, 0.0254, 0.38e-3, 9.5e-3) == pytest.approx(table1.k3, rel=1e-15)


def test_stress_per_radian():
    # reading notes 2.3: E (h/2) / l = 4.14 GPa per radian for Table 1 (3 digits printed)
    assert pivot.bending_stress(1.0, 207e9, 0.38e-3, 9.5e-3) == pytest.approx(4.14e9, rel=1e-3)


def test_max_stroke_for_stress_is_where_the_stress_equals_the_limit():
    # inverse of the stress along the stroke: at the returned deflection the stress equals sigma_allow (1e-12)
    x = pivot.max_stroke_for_stress(1.5e9, 207e9, 0.38e-3, 9.5e-3, R2, R3)
    th = theta2_from_deflection(x, R2, R3)
    s = pivot.bending_stress(spring_angle(th, R2, R3), 207e9, 0.38e-3, 9.5e-3)
    assert s == pytest.approx(1.5e9, rel=1e-12)
    # 40 % of the stroke is far beyond it (reading notes 2.3)
    assert x < 0.4 * (R2 + R3) / 5
    # a very strong material: the kinematic limit governs
    assert pivot.max_stroke_for_stress(1e15, 207e9, 0.38e-3, 9.5e-3, R2, R3) == pytest.approx(
        deflection_from_theta2(np.pi / 2, R2, R3)
    )


def test_safety_factor():
    assert pivot.safety_factor(1.5e9, 3.0e9) == pytest.approx(0.5)
    assert pivot.safety_factor(1.5e9, 0.0) == np.inf
