"""Shared fixtures of the CFCS tests: the Table 1 mechanism of the CFCS paper."""

import pytest

from springdyn.cfcs import CFCS, CFCSParams

#: Table 1 of the CFCS paper (r2, r3 [m]; K3 [N*m/rad] as printed).
R2, R3, K3_TABLE1 = 0.085, 0.095, 2.5308


@pytest.fixture(scope="session")
def table1() -> CFCSParams:
    return CFCSParams.example("table1")


@pytest.fixture(scope="session")
def table1_k3() -> CFCSParams:
    """Table 1 with K3 given directly as printed (2.5308 N*m/rad), as reading notes 2.3 use it."""
    p = CFCSParams.example("table1")
    return p.replace(torsional_stiffness=K3_TABLE1, pivot_width=None, pivot_thickness=None, pivot_length=None)


@pytest.fixture(scope="session")
def model(table1) -> CFCS:
    return CFCS(table1)
