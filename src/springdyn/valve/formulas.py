"""Closed-form parameters of the MMS Type C valve-spring model.

Every function is a pure function of SI floats.  Equation references are to section
40.3.2.1 "Specification of MMS Type C" of the valve-spring document
(``shared/seeds/valve-spring-mms-type-c.txt``); "notes 1.x" are the sections of the
project's reading notes, which fix the document's typos.

The document writes some formulas in mm and N/mm; each is dimensionally consistent in
SI (notes 1.1), so all of them are evaluated in SI here.
"""

from __future__ import annotations

import math

__all__ = [
    "active_coils_free",
    "active_coils_setup",
    "contact_stiffness",
    "free_length_stiffness",
    "setup_stiffness",
    "pitch_correction_free",
    "pitch_correction_setup",
    "surge_frequency",
    "total_mass",
    "coil_pitch",
    "coil_contact_length",
    "setup_force",
    "onestep_model_variables",
    "twostep_model_variables",
    "first_nonlinear_force",
    "stiffened_rate",
    "second_nonlinear_force",
    "coil_contact_force",
    "stiffened_chain_rates",
]


def active_coils_free(n1: float, n2: float, nb: float) -> float:
    """Active coils at free length, ``N1 + N2 - 2 Nb`` (notes 1.1)."""
    return n1 + n2 - 2.0 * nb


def active_coils_setup(n1: float, n2: float, nb: float, two_step: bool) -> float:
    """Active coils at set-up length.

    Two-step: ``N2 - Nb`` (the low-pitch coils are closed at set-up; document, K2).
    One-step: the document sets ``K2 = K1``, i.e. the set-up active coil count equals the
    free one, ``N1 + N2 - 2 Nb``; springdyn uses it for n2' and f2 too, so that K2, n2'
    and f2 describe the same coils (the document prints the two-step count only).
    """
    return n2 - nb if two_step else active_coils_free(n1, n2, nb)


def contact_stiffness(do: float, e: float) -> float:
    """Stiffness of a fully contacting coil, ``K = pi Do E / 1e3`` [N/m].

    Parameters
    ----------
    do : float
        Mean coil diameter [m].
    e : float
        Young's modulus [Pa].

    Notes
    -----
    Document, "Stiffness for fully contact".  The 1e3 is part of the empirical formula;
    with Do in m and E in Pa it gives N/m (notes 1.1).
    """
    return math.pi * do * e / 1e3


def free_length_stiffness(g: float, dw: float, do: float, n_active: float) -> float:
    """Helical spring rate ``G Dw^4 / (8 n Do^3)`` [N/m].

    With ``n = N1 + N2 - 2 Nb`` this is the document's K1 (free length); with
    ``n = N2 - Nb`` it is K2 (set-up length, two-step).

    Parameters
    ----------
    g : float
        Shear modulus G' [Pa].
    dw : float
        Wire diameter [m].
    do : float
        Mean coil diameter [m].
    n_active : float
        Number of active coils [-].
    """
    return g * dw**4 / (8.0 * n_active * do**3)


setup_stiffness = free_length_stiffness


def pitch_correction_free(lf: float, dw: float, n1: float, n2: float, n_active: float, do: float) -> float:
    """Pitch term ``n1' = (Lf - Dw (N1 + N2 - 1)) / ((N1 + N2 - 2 Nb) Do)`` [-].

    Document, n'1.  ``n_active`` is the free active coil count.
    """
    return (lf - dw * (n1 + n2 - 1.0)) / (n_active * do)


def pitch_correction_setup(ls: float, dw: float, n1: float, n2: float, n_active: float, do: float) -> float:
    """Pitch term ``n2' = (Ls - Dw (N1 + N2 - 1)) / (n_setup Do)`` [-] (document, n'2)."""
    return (ls - dw * (n1 + n2 - 1.0)) / (n_active * do)


def surge_frequency(g: float, rho: float, dw: float, do: float, n_eff: float) -> float:
    """First surge frequency ``sqrt(G/(2 rho)) Dw / (2 pi n Do^2)`` [Hz].

    The document's f1 uses ``n = N1 + N2 - 2 Nb + n1'`` and f2 uses
    ``n = N2 - Nb + n2'``; with the plain active coil count it is the textbook surge
    frequency of a spring with both ends fixed (notes 1.7).

    Parameters
    ----------
    g : float
        Shear modulus [Pa].
    rho : float
        Density [kg/m^3].
    dw, do : float
        Wire and mean coil diameters [m].
    n_eff : float
        Effective number of coils [-].
    """
    return math.sqrt(g / (2.0 * rho)) * dw / (2.0 * math.pi * n_eff * do**2)


def total_mass(rho: float, do: float, dw: float, n1: float, n2: float) -> float:
    """Total spring mass ``M = pi^2/4 rho Do Dw^2 (N1 + N2 - 0.7)`` [kg] (document, M)."""
    return math.pi**2 / 4.0 * rho * do * dw**2 * (n1 + n2 - 0.7)


def coil_pitch(ls: float, dw: float, n1: float, n2: float) -> float:
    """Gap term ``Pc = 2 (Ls - Dw (N1 + N2 - 1)) / N2`` [m] (document, Pc).

    Twice the mean coil gap of the high-pitch coils at set-up length.
    """
    return 2.0 * (ls - dw * (n1 + n2 - 1.0)) / n2


def coil_contact_length(dw: float, n1: float, n2: float) -> float:
    """Solid (coil contact) length ``Lc = Dw (N1 + N2 + 0.5)`` [m] (document, Lc; notes 1.3.5)."""
    return dw * (n1 + n2 + 0.5)


def setup_force(lf: float, ls: float, k1: float) -> float:
    """Set-up load ``Fset = (Lf - Ls) K1`` [N] (document, Fset)."""
    return (lf - ls) * k1


def onestep_model_variables(k: float, k1: float, f1: float, m_total: float) -> dict:
    """Stiffnesses and masses of the one-step chain (document, Fig. 40.32).

    Chain (notes 1.2): ``seat -K- me -Kh1- m1 -Kh2- m2 -Kh2- m1 -Kh1- me -K- retainer``.

    Parameters
    ----------
    k : float
        End-element (contact) stiffness K [N/m].
    k1 : float
        Free-length spring rate K1 [N/m].
    f1 : float
        Free-length surge frequency [Hz].
    m_total : float
        Spring mass M [kg].

    Returns
    -------
    dict
        ``Kh1, Kh2`` [N/m] and ``m1, m2, me`` [kg].
    """
    q = k * k1 / (k - 2.0 * k1)
    w = math.pi**2 * f1**2
    m1 = 8.0 / 15.0 / w * q
    m2 = 4.0 / 9.0 / w * q
    return dict(Kh1=16.0 / 5.0 * q, Kh2=16.0 / 3.0 * q, m1=m1, m2=m2, me=(m_total - 2.0 * m1 - m2) / 2.0)


def twostep_model_variables(k: float, k1: float, k2: float, f1: float, f2: float, m_total: float) -> dict:
    """Stiffnesses and masses of the two-step chain (document, Fig. 40.33).

    Chain (notes 1.2): ``seat -K- me -Ks- m1 -Kh1- m2 -Kh2- m2 -Kh1- me -K- retainer``.
    ``m2 = Kh1 / (2 pi f2)^2`` is the in-phase mode of the two m2 masses with m1 blocked;
    ``m1`` is the dynamic condensation of the chain at ``w1 = 2 pi f1``.

    Returns
    -------
    dict
        ``Kh1, Kh2, Ks`` [N/m] and ``m1, m2, me`` [kg].
    """
    q = k * k2 / (k - 3.0 * k2)
    kh1 = 8.0 / 3.0 * q
    kh2 = 4.0 * q
    ks = k * k1 * k2 / (k * k2 + k1 * k2 - k * k1)
    m2 = kh1 / (4.0 * math.pi**2 * f2**2)
    w1sq = (2.0 * math.pi * f1) ** 2
    m1 = (
        kh1
        + ks
        - kh1**2 * (kh1 + kh2 - m2 * w1sq) / ((kh1 + 2.0 * kh2 - m2 * w1sq) * (kh1 - m2 * w1sq))
    ) / w1sq
    return dict(Kh1=kh1, Kh2=kh2, Ks=ks, m1=m1, m2=m2, me=(m_total - 2.0 * m2 - m1) / 2.0)


def first_nonlinear_force(fset: float, ls: float, lc: float, pc: float, k2: float) -> float:
    """``F1 = Fset + (Ls - Lc - Pc) K2`` [N]: force where the chain elements start to stiffen."""
    return fset + (ls - lc - pc) * k2


def stiffened_rate(k2: float) -> float:
    """``K3 = 1.15 K2`` [N/m]: spring rate between F1 and F2 (document)."""
    return 1.15 * k2


def second_nonlinear_force(f1_force: float, pc: float, k3: float) -> float:
    """``F2 = F1 + Pc K3`` [N] (document)."""
    return f1_force + pc * k3


def coil_contact_force(k1: float, k2: float, lf: float, ls: float, dw: float, n1: float, n2: float) -> float:
    """``Fcon = K1 (Lf - Ls) + K2 (Ls - Dw (N1 + N2 - 0.5))`` [N]: coil-contact force (document)."""
    return k1 * (lf - ls) + k2 * (ls - dw * (n1 + n2 - 0.5))


def stiffened_chain_rates(k: float, k3: float, two_step: bool) -> tuple[float, float]:
    """``Kh1'``, ``Kh2'`` [N/m]: the chain rates that reproduce K3 (document; notes 1.3.6).

    One-step: ``(16/5, 16/3) K K3 / (K - 2 K3)``; two-step: ``(8/3, 4) K K3 / (K - 3 K3)``.
    """
    if two_step:
        q = k * k3 / (k - 3.0 * k3)
        return 8.0 / 3.0 * q, 4.0 * q
    q = k * k3 / (k - 2.0 * k3)
    return 16.0 / 5.0 * q, 16.0 / 3.0 * q
