"""The oil's scalar laws that the compiled adjuster and the Python one share.

Plain Python on floats: :mod:`.equations` compiles them as twins inside the adjuster's
chamber (a compiled kernel calls code of the engine's folder only, whose contents key its
cache: :func:`springdyn.numerics.jit.source_group`), and :mod:`springdyn.valve.train.oil`
and :mod:`springdyn.valve.train.hla` call them as they are.  Each law lives here once.

- :func:`effective_bulk_modulus` -- aerated oil: the oil's bulk modulus in series with free air;
- :func:`orifice_flow` -- a sharp-edged orifice, laminarised near zero pressure drop.
"""

from __future__ import annotations

import math

from .layout import CHECK_VALVE_TRANSITION, P_ATM, P_CAVITATION

__all__ = ["effective_bulk_modulus", "orifice_flow"]


def effective_bulk_modulus(p_abs, oil_bulk_modulus, air_fraction, polytropic_index=1.0):
    """Bulk modulus [Pa] of oil with free air at an absolute pressure.

    The free air takes the volume fraction ``x`` of the oil at atmospheric pressure, so
    ``x (p_atm / p)^(1/n)`` of the oil volume and is ``n p`` stiff, in series with the oil:
    ``beta_e = (V_o + V_a) / (V_o / beta + V_a / (n p))`` (Merritt 1967, eq. 2-19).  Below the
    cavitation pressure (:data:`.layout.P_CAVITATION`) the oil releases its air and vapour:
    the pressure is held there.

    Parameters
    ----------
    p_abs : float
        Absolute pressure [Pa].
    oil_bulk_modulus : float
        Bulk modulus of the air-free oil [Pa].
    air_fraction : float
        Free-air volume fraction at atmospheric pressure [-].
    polytropic_index : float
        Polytropic index of the bubbles' compression [-] (1 isothermal, 1.4 adiabatic).

    Examples
    --------
    >>> round(effective_bulk_modulus(101325.0, 1.5e9, 0.0) / 1e9, 6)
    1.5
    """
    p = p_abs if p_abs > P_CAVITATION else P_CAVITATION
    v_air = air_fraction * (P_ATM / p) ** (1.0 / polytropic_index)
    v_oil = 1.0 - air_fraction
    return (v_oil + v_air) / (v_oil / oil_bulk_modulus + v_air / (polytropic_index * p))


def orifice_flow(dp, k):
    """Flow [m^3/s] through an open sharp-edged orifice at a pressure drop ``dp`` [Pa].

    ``Q = k sqrt(dp)`` with ``k = Cd A sqrt(2 / rho)`` (Merritt 1967, eq. 3-6), laminarised
    below :data:`.layout.CHECK_VALVE_TRANSITION` (linear in ``dp``, the same flow at the
    transition, so that the flow has a finite slope at zero); no flow for ``dp <= 0`` (the
    check valve's ball seats).

    Parameters
    ----------
    dp : float
        Pressure drop across the orifice [Pa].
    k : float
        Flow coefficient ``Cd A sqrt(2 / rho)`` [m^3/s/Pa^0.5].

    Examples
    --------
    >>> orifice_flow(-1.0, 1e-7), orifice_flow(1e4, 1e-7) == 1e-7 * 100.0
    (0.0, True)
    """
    if dp <= 0.0:
        return 0.0
    if dp < CHECK_VALVE_TRANSITION:
        return k * dp / math.sqrt(CHECK_VALVE_TRANSITION)
    return k * math.sqrt(dp)
