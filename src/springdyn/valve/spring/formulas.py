"""Closed-form parameters of the MMS Type C valve-spring model.

Every function is a pure function of SI floats.  Equation references are to section
40.3.2.1 "Specification of MMS Type C" of [MMS] (see docs/references.md), by the names
the document gives them ("Internal Parameter", "Model variable for One-Step spring",
"Nonlinear characteristics"); its typos are fixed as numbered there (MMS-1 ... MMS-10).

The document writes some formulas in mm and N/mm; each is dimensionally consistent in
SI (``K = pi Do E / 1e3`` is N/m with Do in m and E in Pa), so all of them are evaluated
in SI here.
"""

from __future__ import annotations

import math

import numpy as np

from ...core.docstrings import ParameterDocs

__all__ = [
    "PARAMETER_UNITS",
    "active_coils_free",
    "active_coils_setup",
    "contact_stiffness",
    "free_length_stiffness",
    "setup_stiffness",
    "active_coils_for_rate",
    "pitch_correction",
    "surge_frequency",
    "total_mass",
    "coil_pitch",
    "coil_contact_length",
    "setup_force",
    "linear_rate_force",
    "onestep_model_variables",
    "twostep_model_variables",
    "first_nonlinear_force",
    "stiffened_rate",
    "second_nonlinear_force",
    "coil_contact_force",
    "stiffened_chain_rates",
]


#: SI unit, display unit and meaning of each internal parameter of the MMS Type C model
#: (:meth:`springdyn.valve.spring.chains.TypeCModel.internal_parameters`).
#: The symbols' descriptions, shared by the docstrings below (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    dw : float
        Wire diameter Dw [m].
    n1, n2 : float
        Low- and high-pitch coils N1, N2 [-].
    ls : float
        Set-up (installed) length Ls [m].
    do : float
        Mean coil diameter Do [m].
    lf : float
        Free length Lf [m].
    k1 : float
        Free-length spring rate K1 [N/m].
    k2 : float
        Set-up-length spring rate K2 [N/m].
    k : float
        End-element (contact) stiffness K [N/m].
    pc : float
        Gap term Pc [m].
    two_step : bool
        True for a two-step spring.
    k3 : float
        Stiffened rate K3 [N/m].
    m_total : float
        Spring mass M [kg].
    n2 : float
        High-pitch coils N2 [-].
    """
)

PARAMETER_UNITS = {
    "K": ("N/m", "N/mm", "contact stiffness of a coil"),
    "K1": ("N/m", "N/mm", "spring rate at free length"),
    "K2": ("N/m", "N/mm", "spring rate at set-up length"),
    "K3": ("N/m", "N/mm", "stiffened rate 1.15 K2"),
    "Kh1": ("N/m", "N/mm", "chain element Kh1"),
    "Kh2": ("N/m", "N/mm", "chain element Kh2"),
    "Ks": ("N/m", "N/mm", "low-pitch element Ks"),
    "m1": ("kg", "g", "chain mass m1"),
    "m2": ("kg", "g", "chain mass m2"),
    "me": ("kg", "g", "end mass me"),
    "M": ("kg", "g", "spring mass"),
    "f1": ("Hz", "Hz", "surge frequency, free length"),
    "f2": ("Hz", "Hz", "surge frequency, set-up length"),
    "n1p": ("", "", "pitch term n1'"),
    "n2p": ("", "", "pitch term n2'"),
    "Pc": ("m", "mm", "coil gap term"),
    "Lc": ("m", "mm", "solid length"),
    "Fset": ("N", "N", "set-up force"),
    "F1": ("N", "N", "first nonlinear force"),
    "F2": ("N", "N", "second nonlinear force"),
    "Fcon": ("N", "N", "coil-contact force"),
    "C0": ("N*s/m", "N*s/m", "element damping C0"),
    "f_continuum": ("Hz", "Hz", "continuum surge frequency of the active coils"),
    "elements": ("", "", "wire elements"),
    "beta": ("s", "s", "stiffness-proportional damping (mode 1 at set-up gets damping_ratio)"),
    "pitch_max": ("m", "mm", "largest pitch of the unloaded spring"),
}


@_DOCS.fill
def active_coils_free(n1: float, n2: float, nb: float) -> float:
    """Active coils at free length, ``N1 + N2 - 2 Nb`` [-].

    Parameters
    ----------
    n1 : float
        Low-pitch coils N1 (0 for a one-step spring) [-].
    {n2}
    nb : float
        Dead (seat-contact) coils per end Nb [-].

    Notes
    -----
    [MMS], "Internal Parameter": the coil count of K1, n'1 and f1.
    """
    return n1 + n2 - 2.0 * nb


@_DOCS.fill
def active_coils_setup(n1: float, n2: float, nb: float, two_step: bool) -> float:
    """Active coils at set-up length [-].

    Parameters
    ----------
    n1 : float
        Low-pitch coils N1 [-].
    {n2}
    nb : float
        Dead coils per end Nb [-].
    {two_step}

    Notes
    -----
    Two-step: ``N2 - Nb`` (the low-pitch coils are closed at set-up; [MMS], "Stiffness
    for set-up length", K2).  One-step: [MMS] sets ``K2 = K1`` (correction MMS-6 of
    docs/references.md), i.e. the set-up active coil count equals the free one,
    ``N1 + N2 - 2 Nb``; springdyn uses it for n2' and f2 too, so that K2, n2' and f2
    describe the same coils (the document prints the two-step count only).
    """
    return n2 - nb if two_step else active_coils_free(n1, n2, nb)


@_DOCS.fill
def contact_stiffness(do: float, e: float) -> float:
    r"""Stiffness of a fully contacting coil, ``K = pi Do E / 1e3`` [N/m].

    .. math::

        K = \frac{\pi\,D_o\,E}{10^3}

    Parameters
    ----------
    {do}
    e : float
        Young's modulus [Pa].

    Notes
    -----
    [MMS], "Stiffness for fully contact".  The 1e3 is part of the empirical formula;
    with Do in m and E in Pa it gives N/m.

    Examples
    --------
    >>> round(contact_stiffness(22e-3, 206e9))
    14237698

    References
    ----------
    .. [1] [MMS] of docs/references.md: the MMS Type C chapter, section 40.3.2.1.
    """
    return math.pi * do * e / 1e3


@_DOCS.fill
def free_length_stiffness(g: float, dw: float, do: float, n_active: float) -> float:
    r"""Helical spring rate ``G Dw^4 / (8 n Do^3)`` [N/m].

    .. math::

        K = \frac{G\,D_w^4}{8\,n\,D_o^3}

    With ``n = N1 + N2 - 2 Nb`` this is K1 of [MMS], "Stiffness for free length"; with
    ``n = N2 - Nb`` it is K2, "Stiffness for set-up length" (two-step).

    Parameters
    ----------
    g : float
        Shear modulus G' [Pa].
    dw : float
        Wire diameter [m].
    {do}
    n_active : float
        Number of active coils [-].

    Examples
    --------
    One-step example (Do 22 mm, Dw 3.5 mm, G 78.5 GPa, 6 active coils):

    >>> round(free_length_stiffness(78.5e9, 3.5e-3, 22e-3, 6.0), 1)
    23048.0

    References
    ----------
    .. [1] [MMS] of docs/references.md: the MMS Type C chapter, section 40.3.2.1.
    .. [2] A. M. Wahl, *Mechanical Springs*, 2nd ed., McGraw-Hill, 1963.
    """
    return g * dw**4 / (8.0 * n_active * do**3)


setup_stiffness = free_length_stiffness


def active_coils_for_rate(g, dw, do, rate):
    r"""The active coils ``n = G Dw^4 / (8 Do^3 K)`` [-] that give the rate ``K``: the spring
    rate :func:`free_length_stiffness` solved for ``n``.

    .. math::

        n = \frac{G\,D_w^4}{8\,D_o^3\,K}

    Parameters
    ----------
    g : float or array_like
        Shear modulus G' [Pa].
    dw : float or array_like
        Wire diameter [m].
    do : float or array_like
        Mean coil diameter [m].
    rate : float or array_like
        Spring rate [N/m].

    Examples
    --------
    >>> round(active_coils_for_rate(78.5e9, 3.5e-3, 22e-3, free_length_stiffness(78.5e9, 3.5e-3, 22e-3, 6.0)), 12)
    6.0
    """
    return free_length_stiffness(g, dw, do, 1.0) / rate  # the rate's law, solved for n (K n is constant)


@_DOCS.fill
def pitch_correction(length: float, dw: float, n1: float, n2: float, n_active: float, do: float) -> float:
    """Pitch term ``n' = (L - Dw (N1 + N2 - 1)) / (n_active Do)`` [-].

    At the free length (``L = Lf``, ``n_active = N1 + N2 - 2 Nb``) it is n'1, at the set-up length
    (``L = Ls``, :func:`active_coils_setup`) n'2.

    Parameters
    ----------
    length : float
        Spring length, Lf or Ls [m].
    {dw n1_n2}
    n_active : float
        Active coils at that length [-].
    {do}

    Notes
    -----
    [MMS], "Internal Parameter", n'1 (in f1, "Natural Frequency for free length"), and "Stiffness for
    set-up length", n'2 (in f2, "Natural frequency for set-up length").
    """
    return (length - dw * (n1 + n2 - 1.0)) / (n_active * do)


def surge_frequency(g: float, rho: float, dw: float, do: float, n_eff: float) -> float:
    r"""First surge frequency ``sqrt(G/(2 rho)) Dw / (2 pi n Do^2)`` [Hz].

    .. math::

        f = \frac{D_w}{2\pi\,n\,D_o^2}\sqrt{\frac{G}{2\rho}}

    The document's f1 uses ``n = N1 + N2 - 2 Nb + n1'`` and f2 uses
    ``n = N2 - Nb + n2'``; with the plain active coil count it is the textbook surge
    frequency of a spring with both ends fixed ([Wahl]; [MMS], "Natural Frequency for
    free length").

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

    Examples
    --------
    >>> round(surge_frequency(78.5e9, 7850.0, 3.5e-3, 22e-3, 6.0), 2)
    428.92

    References
    ----------
    .. [1] [MMS] of docs/references.md: the MMS Type C chapter, section 40.3.2.1.
    .. [2] A. M. Wahl, *Mechanical Springs*, 2nd ed., McGraw-Hill, 1963.
    """
    return math.sqrt(g / (2.0 * rho)) * dw / (2.0 * math.pi * n_eff * do**2)


@_DOCS.fill
def total_mass(rho: float, do: float, dw: float, n1: float, n2: float) -> float:
    """Total spring mass ``M = pi^2/4 rho Do Dw^2 (N1 + N2 - 0.7)`` [kg].

    Parameters
    ----------
    rho : float
        Density rho' [kg/m^3].
    {do dw n1_n2}

    Notes
    -----
    [MMS], "Total Mass of spring".
    """
    return math.pi**2 / 4.0 * rho * do * dw**2 * (n1 + n2 - 0.7)


@_DOCS.fill
def coil_pitch(ls: float, dw: float, n1: float, n2: float) -> float:
    """Gap term ``Pc = 2 (Ls - Dw (N1 + N2 - 1)) / N2`` [m].

    Twice the mean coil gap of the high-pitch coils at set-up length.

    Parameters
    ----------
    {ls dw n1_n2}

    Notes
    -----
    [MMS], "Set-up load", Pc.
    """
    return 2.0 * (ls - dw * (n1 + n2 - 1.0)) / n2


@_DOCS.fill
def coil_contact_length(dw: float, n1: float, n2: float) -> float:
    """Solid (coil contact) length ``Lc = Dw (N1 + N2 + 0.5)`` [m].

    Parameters
    ----------
    {dw n1_n2}

    Notes
    -----
    [MMS], "Set-up load", Lc; the ``+0.5`` is kept as printed (correction MMS-5 of
    docs/references.md).
    """
    return dw * (n1 + n2 + 0.5)


@_DOCS.fill
def setup_force(lf: float, ls: float, k1: float) -> float:
    """Set-up load ``Fset = (Lf - Ls) K1`` [N].

    Parameters
    ----------
    {lf ls k1}

    Notes
    -----
    [MMS], "Set-up load", Fset.
    """
    return (lf - ls) * k1


def linear_rate_force(length, lf: float, ls: float, k1: float, k2: float):
    """Static force of the standard's linear rates at a spring length [N].

    ``K1 (Lf - L)`` from the free to the installed length and ``Fset + K2 (Ls - L)`` below it
    (EN 13906-1's ``F = R s``; a two-step spring's low-pitch coils closed at the installed
    length, [MMS] K2; a one-step spring has ``K2 = K1``).  No coil closes: the figure a spring
    maker checks a drawing's load points with.

    Parameters
    ----------
    length : float or array_like
        Spring length [m].
    lf, ls : float
        Free and installed lengths [m].
    k1, k2 : float
        Rates from free length and from the installed length [N/m].

    Examples
    --------
    >>> round(float(linear_rate_force(29e-3, 48e-3, 38e-3, 25143.0, 25143.0)), 2)
    477.72
    """
    length = np.asarray(length, dtype=float)
    fset = setup_force(lf, ls, k1)
    return np.where(length >= ls, k1 * (lf - length), fset + k2 * (ls - length))


@_DOCS.fill
def onestep_model_variables(k: float, k1: float, f1: float, m_total: float) -> dict:
    """Stiffnesses and masses of the one-step chain ([MMS], "Model variable for One-Step
    spring", Fig. 40.32).

    Chain (topology in docs/valve-spring.md): ``seat -K- me -Kh1- m1 -Kh2- m2 -Kh2- m1 -Kh1- me -K- retainer``.

    Parameters
    ----------
    {k k1}
    f1 : float
        Free-length surge frequency [Hz].
    {m_total}

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


@_DOCS.fill
def twostep_model_variables(k: float, k1: float, k2: float, f1: float, f2: float, m_total: float) -> dict:
    """Stiffnesses and masses of the two-step chain ([MMS], "Model variable for Two-Step
    spring", Fig. 40.33).

    Chain (topology in docs/valve-spring.md):
    ``seat -K- me -Ks- m1 -Kh1- m2 -Kh2- m2 -Kh1- me -K- retainer``.
    ``m2 = Kh1 / (2 pi f2)^2`` is the in-phase mode of the two m2 masses with m1 blocked;
    ``m1`` is the dynamic condensation of the chain at ``w1 = 2 pi f1``.

    Parameters
    ----------
    {k k1 k2}
    f1 : float
        Free-length surge frequency f1 [Hz].
    f2 : float
        Set-up-length surge frequency f2 [Hz].
    {m_total}

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
    m1 = (kh1 + ks - kh1**2 * (kh1 + kh2 - m2 * w1sq) / ((kh1 + 2.0 * kh2 - m2 * w1sq) * (kh1 - m2 * w1sq))) / w1sq
    return dict(Kh1=kh1, Kh2=kh2, Ks=ks, m1=m1, m2=m2, me=(m_total - 2.0 * m2 - m1) / 2.0)


@_DOCS.fill
def first_nonlinear_force(fset: float, ls: float, lc: float, pc: float, k2: float) -> float:
    """``F1 = Fset + (Ls - Lc - Pc) K2`` [N]: force where the chain elements start to stiffen.

    Parameters
    ----------
    fset : float
        Set-up force Fset [N].
    {ls}
    lc : float
        Solid length Lc [m].
    {pc k2}

    Notes
    -----
    [MMS], "Nonlinear characteristics", F1.
    """
    return fset + (ls - lc - pc) * k2


@_DOCS.fill
def stiffened_rate(k2: float) -> float:
    """``K3 = 1.15 K2`` [N/m]: spring rate between F1 and F2.

    Parameters
    ----------
    {k2}

    Notes
    -----
    [MMS], "Nonlinear characteristics", K3.
    """
    return 1.15 * k2


@_DOCS.fill
def second_nonlinear_force(f1_force: float, pc: float, k3: float) -> float:
    """``F2 = F1 + Pc K3`` [N].

    Parameters
    ----------
    f1_force : float
        First nonlinear force F1 [N].
    {pc k3}

    Notes
    -----
    [MMS], "Nonlinear characteristics", F2.
    """
    return f1_force + pc * k3


@_DOCS.fill
def coil_contact_force(k1: float, k2: float, lf: float, ls: float, lc: float, dw: float) -> float:
    """``Fcon = K1 (Lf - Ls) + K2 (Ls - (Lc - Dw))`` [N]: coil-contact force.

    With the document's solid length ``Lc = Dw (N1 + N2 + 0.5)`` this is the printed
    ``K1 (Lf - Ls) + K2 (Ls - Dw (N1 + N2 - 0.5))``: the document reaches Fcon one wire
    diameter above its Lc.  springdyn anchors that length on the spring's one solid length
    (:func:`springdyn.valve.spring.solid_length.solid_length`, EN 13906-1 by the end type), so
    a drawing's spring keeps the document's offset without a second solid length.

    Parameters
    ----------
    k1, k2 : float
        Free- and set-up-length spring rates K1, K2 [N/m].
    {lf ls}
    lc : float
        Solid length Lc [m].
    {dw}

    Notes
    -----
    [MMS], "Nonlinear characteristics", Fcon; the ``-0.5`` is kept as printed
    (correction MMS-5 of docs/references.md).
    """
    return k1 * (lf - ls) + k2 * (ls - (lc - dw))


@_DOCS.fill
def stiffened_chain_rates(k: float, k3: float, two_step: bool) -> tuple[float, float]:
    """``Kh1'``, ``Kh2'`` [N/m]: the chain rates that reproduce K3.

    One-step: ``(16/5, 16/3) K K3 / (K - 2 K3)``; two-step: ``(8/3, 4) K K3 / (K - 3 K3)``.

    Parameters
    ----------
    {k k3 two_step}

    Notes
    -----
    [MMS], "Nonlinear characteristics of Kh1" / "of Kh2" (Kh1', Kh2'), with the factors
    of correction MMS-6 of docs/references.md.
    """
    if two_step:
        q = k * k3 / (k - 3.0 * k3)
        return 8.0 / 3.0 * q, 4.0 * q
    q = k * k3 / (k - 2.0 * k3)
    return 16.0 / 5.0 * q, 16.0 / 3.0 * q
