"""Stiffness matrix (3.4): isotropy, rotation invariance, preload warning."""

import warnings

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.lsd import LSDModel, LSDParameters, PreloadExceededWarning
from springdyn.lsd.film import FilmWarning
from springdyn.lsd.stiffness import equally_spaced_angles, isotropic_stiffness, stiffness_matrix

KS = 1.0e5


@pytest.mark.parametrize("n", [3, 4, 5, 6, 8, 12])
def test_equally_spaced_packs_are_isotropic(n):
    # thesis after (3.6): Kxx = Kyy = N k_s / 2, Kxy = Kyx = 0 for N >= 3 (round-off tolerance)
    for first in (0.0, 0.3, 1.7):
        K = stiffness_matrix(KS, equally_spaced_angles(n, first))
        np.testing.assert_allclose(K, isotropic_stiffness(n, KS) * np.eye(2), atol=1e-9 * KS)


def test_rotating_all_packs_rotates_K():
    # K(phi + alpha) = R K(phi) R^T for any layout (a tensor); trace and determinant invariant
    rng = np.random.default_rng(7)
    phi = np.sort(rng.uniform(0, 2 * np.pi, 5))
    for alpha in (0.4, 2.0, -1.1):
        R = np.array([[np.cos(alpha), -np.sin(alpha)], [np.sin(alpha), np.cos(alpha)]])
        np.testing.assert_allclose(
            stiffness_matrix(KS, phi + alpha), R @ stiffness_matrix(KS, phi) @ R.T, atol=1e-9 * KS
        )
    K = stiffness_matrix(KS, phi)
    assert np.trace(K) == pytest.approx(5 * KS, rel=1e-12)  # sum cos^2 + sin^2 = N
    np.testing.assert_allclose(K, K.T)


def test_two_packs_general_angles_but_no_shortcut():
    # two opposite packs stiffen only along their axis; the isotropic shortcut refuses N < 3
    K = stiffness_matrix(KS, [0.0, np.pi])
    np.testing.assert_allclose(K, [[2 * KS, 0], [0, 0]], atol=1e-9 * KS)
    with pytest.raises(InputError, match="at least 3"):
        isotropic_stiffness(2, KS)


def test_model_with_explicit_angles():
    p = LSDParameters.example("C").replace(packs=4, pack_angles=list(np.radians([0.0, 80.0, 180.0, 260.0])))
    m = LSDModel(p)
    np.testing.assert_allclose(m.stiffness_matrix, stiffness_matrix(m.pack_stiffness, m.angles))
    assert m.stiffness_matrix[0, 0] != pytest.approx(m.stiffness_matrix[1, 1])


def test_preload_warning():
    m = LSDModel(LSDParameters.example("A"))  # preload 0.1 mm
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.simplefilter("ignore", FilmWarning)  # Type A's film cavitates at 1000 rpm (test_film.py)
        assert not m.coefficients([1000], amplitude=50e-6).preload_exceeded
    with pytest.warns(PreloadExceededWarning, match="exceeds the pack preload"):
        assert m.coefficients([1000], amplitude=150e-6).preload_exceeded
