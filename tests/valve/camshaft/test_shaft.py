"""The camshaft as a torsional chain (springdyn.valve.camshaft.shaft, .definition): its modes
against the closed form of the discrete chain, its stiffness against Saint-Venant torsion, its
periodic response against a single-degree-of-freedom closed form.

References, written out here and not taken from the code under test:

- fixed-free chain of N equal inertias J and N equal springs k (the first spring to ground):
  omega_n = 2 sqrt(k/J) sin((2n - 1) pi / (2 (2N + 1))), n = 1..N ([Rao], the eigenvalues of
  the tridiagonal matrix tridiag(-1, 2, -1) with its last diagonal entry 1);
- torsion of a round tube: k = G pi (d^4 - d_i^4) / (32 L);
- a damped oscillator J x'' + c x' + k x = T cos(w t): amplitude T / sqrt((k - J w^2)^2 + (c w)^2).

Tolerances: the eigenvalue solver's round-off (1e-9 relative); the FFT's round-off (1e-9).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from springdyn.core.errors import InputError
from springdyn.valve.camshaft.coupled import CamshaftModel
from springdyn.valve.camshaft.definition import Camshaft, Lobe, read_camshaft
from springdyn.valve.camshaft.shaft import periodic_twist
from tests.paths import example


def _lobes(n, positions=None, inertia=1e-4):
    """n lobes of the example's valve (their valves are not run by these tests)."""
    _, ex = read_camshaft(example("valve/camshaft_4lobe.toml"))
    lb = ex[0]
    positions = positions if positions is not None else [0.05 * (i + 1) for i in range(n)]
    return tuple(Lobe(f"l{i}", p, 0.0, inertia, lb.spring, lb.cam, lb.valve_train) for i, p in enumerate(positions))


@pytest.mark.parametrize("n_nodes", [2, 5, 9])
def test_modes_of_a_uniform_chain_match_the_closed_form(n_nodes):
    k, j = 2.0e4, 1.0e-4
    shaft = Camshaft(sprocket_inertia=j, drive_stiffness=k, segment_stiffness=[k] * (n_nodes - 1), lobe_inertia=j)
    model = CamshaftModel(shaft, _lobes(n_nodes - 1, inertia=j))
    f = model.modes().frequency
    n = np.arange(1, n_nodes + 1)
    closed = 2.0 * math.sqrt(k / j) * np.sin((2 * n - 1) * math.pi / (2 * (2 * n_nodes + 1))) / (2 * math.pi)
    np.testing.assert_allclose(f, closed, rtol=1e-9)


def test_segment_stiffness_and_inertia_of_a_tube():
    d, di, g, rho = 0.025, 0.015, 80e9, 7850.0
    shaft = Camshaft(
        sprocket_inertia=1e-3,
        drive_stiffness=1e4,
        shaft_diameter=d,
        shaft_bore=di,
        shear_modulus=g,
        density=rho,
        lobe_inertia=3e-5,
    )
    model = CamshaftModel(shaft, _lobes(2, positions=[0.04, 0.13], inertia=3e-5))
    ip = math.pi * (d**4 - di**4) / 32.0
    np.testing.assert_allclose(model.chain.stiffness, [g * ip / 0.04, g * ip / 0.09], rtol=1e-12)
    # half of each segment's rho I_p L on each of its nodes
    expect = [1e-3 + rho * ip * 0.02, 3e-5 + rho * ip * (0.02 + 0.045), 3e-5 + rho * ip * 0.045]
    np.testing.assert_allclose(model.chain.inertia, expect, rtol=1e-12)


def test_periodic_twist_of_one_node_matches_the_oscillator():
    j, c, k, w = 2e-3, 0.4, 1.0e4, 150.0
    n = 256
    psi = np.arange(n) * 2 * math.pi / n
    order = 7
    torque = 3.0 * np.cos(order * psi)[None, :]
    spec = periodic_twist(np.array([[j]]), np.array([[k]]), np.array([[c]]), torque, w)
    ww = order * w
    amp = 3.0 / math.hypot(k - j * ww**2, c * ww)
    lag = math.atan2(c * ww, k - j * ww**2)
    phi = np.fft.irfft(spec, n=n)[0]
    np.testing.assert_allclose(phi, amp * np.cos(order * psi - lag), rtol=0, atol=1e-9 * amp)


def test_a_mean_torque_twists_by_the_drive_stiffness():
    """Static twist by hand: each spring carries the torque of the nodes beyond it."""
    shaft = Camshaft(sprocket_inertia=1e-3, drive_stiffness=1e4, segment_stiffness=[3e4, 3e4], lobe_inertia=3e-5)
    model = CamshaftModel(shaft, _lobes(2))
    j, k, c = model.chain.matrices
    spec = periodic_twist(j, k, c, np.zeros((3, 64)), 300.0, mean_torque=[0.0, -1.0, -1.0])
    expect = [-2.0 / 1e4, -2.0 / 1e4 - 2.0 / 3e4, -2.0 / 1e4 - 2.0 / 3e4 - 1.0 / 3e4]
    np.testing.assert_allclose(np.fft.irfft(spec, n=64), np.repeat(np.array(expect)[:, None], 64, 1), rtol=1e-9)


def test_bad_shafts_are_refused():
    with pytest.raises(InputError, match="shaft_diameter"):
        Camshaft(sprocket_inertia=1e-3, drive_stiffness=1e4)
    shaft = Camshaft(sprocket_inertia=1e-3, drive_stiffness=1e4, shaft_diameter=0.025, sprocket_position=0.1)
    with pytest.raises(InputError, match="one side"):
        CamshaftModel(shaft, _lobes(2, positions=[0.05, 0.15]))
    with pytest.raises(InputError, match="segment_stiffness has 1"):
        CamshaftModel(Camshaft(sprocket_inertia=1e-3, drive_stiffness=1e4, segment_stiffness=[1e4]), _lobes(2))


def test_the_example_reads_its_four_lobes():
    shaft, lobes = read_camshaft(example("valve/camshaft_4lobe.toml"))
    assert [round(math.degrees(lb.phase)) for lb in lobes] == [0, 270, 90, 180]  # firing order 1-3-4-2
    assert lobes[0].spring is lobes[3].spring  # one file, read once
    assert shaft.drive_stiffness == 1e4
