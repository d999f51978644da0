"""Valve-spring wire materials: elastic constants, tensile strength, relaxation, load-spectrum life.

Three data layers, each a small table with its source (docs/references.md: [EN 10270],
[EN 13906-1], [SpringONE], [Shigley], [FKM], [Feltham], and the public pages [metalleschmidt],
[hengming], [herteux], [federnshop] that reproduce rows and rules of the standards):

- :data:`MATERIALS` -- the named wires a ``[spring]`` table can take as ``material = "SiCr"``
  (:func:`material`): oil-tempered valve-spring wire EN 10270-2 VDSiCr (``"SiCr"``), the
  high-strength VDSiCrV (``"SiCrV"``), VDCrV (``"CrV"``) and patented music wire EN 10270-1
  DH / ASTM A228 (``"music-wire"``).  :meth:`Material.spring_keys` gives the ``[spring]``
  keys of a wire diameter in SI.
- :func:`relaxation_loss`, :func:`relaxed_force` -- the loss of force of a spring held at a
  length at a temperature, from a per-material table at 48 h and a logarithmic time law.
- :func:`spectrum_life` -- Miner's damage sum over a load spectrum (share of time and cam
  frequency per operating point) on a Basquin S-N line with its knee at the endurance
  strength, and the life in hours.

Tensile strength: EN 10270-1/-2 give the tensile strength of each grade as a band
(minimum-maximum) per diameter range.  The mid-diameter rows of those tables could not be
had from a public source for this module, so :meth:`Material.tensile_strength` is a **fit of
the band minima**, ``Rm = min(Rm_cap, A - B log10(d / 1 mm))`` with the constants of the
open-source spring calculator [SpringONE] (its material database), checked here against the
rows of the standards that are public (the 0.50 mm row of EN 10270-2, the 0.20 and 0.28-0.30 mm rows of
EN 10270-1 DH, see the tests).  Being a fit of the minima it is the conservative value for a
strength check; a measured strength from the wire's certificate is better and is given as
``tensile_strength`` in the ``[spring]`` table.

Fatigue: the fully reversed torsional endurance strength of shot-peened wire is Zimmerli's
(:func:`springdyn.valve.spring.stress.zimmerli_endurance_shear_strength`, Shigley Sec. 10-9: one
set of data for peened springs of every spring steel up to 10 mm), at this material's
ultimate shear strength (0.67 Rm, Shigley Sec. 10-4).  No public source gave grade-specific
endurance values (EN 13906-1's Goodman diagrams for shot-peened VDSiCr and VDSiCrV were not
available); the cleaner VD grades' better fatigue strength is therefore not credited.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...core.errors import InputError, fmt_value
from .stress import (
    ULTIMATE_SHEAR_FRACTION,
    nominal_shear_stress,
    ultimate_shear_strength,
    zimmerli_endurance_shear_strength,
)

__all__ = [
    "Material",
    "MATERIALS",
    "ALIASES",
    "material",
    "material_names",
    "RELAXATION_TEMPERATURES_C",
    "RELAXATION_STRESSES",
    "RELAXATION_REFERENCE_HOURS",
    "RELAXATION_TIME_CONSTANT_HOURS",
    "relaxation_loss",
    "relaxation_time_factor",
    "relaxed_force",
    "SN_SLOPE",
    "SN_KNEE_CYCLES",
    "cycles_to_failure",
    "spectrum_life",
]

#: Shear-modulus change with temperature of EN 10270-1/-2 wire [1/K]:
#: ``G(T) = G20 (1 - 0.25e-3 (T - 20 degC))`` ([EN 13906-1], as in [SpringONE]).
SHEAR_MODULUS_TEMPERATURE_COEFFICIENT = 0.25e-3
#: Celsius zero [K].
_ZERO_C = 273.15

# ----------------------------------------------------------------------------- relaxation grid
#: Temperatures of the relaxation tables [degC] (the nodes of :attr:`Material.relaxation_percent`).
RELAXATION_TEMPERATURES_C = (20.0, 80.0, 120.0, 160.0)
#: Initial shear stresses of the relaxation tables [Pa]: the **uncorrected** stress
#: ``8 F D / (pi d^3)`` of EN 13906-1's relaxation charts (they are drawn without the stress
#: correction factor k; [EN 13906-1], as the public calculator [herteux] states).
RELAXATION_STRESSES = (200e6, 400e6, 600e6, 800e6, 1000e6)
#: Holding time of the tables [h]: EN 13906-1's relaxation charts are for 48 h
#: ([EN 13906-1]; Gutekunst [federnshop]: "the relaxation values after 48 hours are the
#: characteristic values, although relaxation is not complete then").
RELAXATION_REFERENCE_HOURS = 48.0
#: Time constant ``c`` [h] of the logarithmic time law (:func:`relaxation_time_factor`);
#: engineering judgement: with c = 0.1 h the law is proportional to log(t) over the
#: hours-to-years range a valve spring is judged on, and zero at t = 0.
RELAXATION_TIME_CONSTANT_HOURS = 0.1

# ----------------------------------------------------------------------------- S-N line
#: Slope ``k`` of the S-N (Basquin) line ``N = N_D (tau_e / tau)^k`` above the knee [-]: the
#: FKM guideline's slope for shear stress, k = 8 ([FKM]; its k = 5 is for normal stress).
#: Shot-peened spring wire is usually given k = 5 to 9; k = 8 sits in that range.
SN_SLOPE = 8.0
#: Cycles at the knee of the S-N line [-]: the endurance strength of springs is stated at
#: 10^7 cycles (Zimmerli's data, Shigley Sec. 10-9; EN 13906-1's fatigue diagrams).
SN_KNEE_CYCLES = 1.0e7


@dataclass(frozen=True)
class Material:
    """A named valve-spring wire: elastic constants, tensile-strength fit, relaxation table.

    All values SI.  Get one by name with :func:`material`; every value's source is in
    :attr:`sources`.

    Attributes
    ----------
    name : str
        The name the ``[spring]`` table takes (``"SiCr"``).
    grade : str
        The standard and grade (``"EN 10270-2 VDSiCr"``).
    description : str
        What the wire is.
    shear_modulus : float
        Shear modulus G at 20 degC [Pa].
    youngs_modulus : float
        Young's modulus E at 20 degC [Pa].
    density : float
        Density [kg/m^3].
    strength_fit : tuple of float
        ``(A, B, Rm_cap)`` [Pa] of ``Rm = min(Rm_cap, A - B log10(d / 1 mm))``.
    diameter_range : tuple of float
        Wire diameters the grade and the fit cover ``(d_min, d_max)`` [m].
    relaxation_percent : tuple of tuple of float
        Loss of force after :data:`RELAXATION_REFERENCE_HOURS` [% of the initial force], one row
        per :data:`RELAXATION_TEMPERATURES_C`, one column per :data:`RELAXATION_STRESSES`.
    sources : dict
        The source of each value (keys as the attributes).

    Examples
    --------
    >>> m = material("sicr")
    >>> m.grade
    'EN 10270-2 VDSiCr'
    >>> round(m.tensile_strength(0.5e-3) / 1e6)
    2080
    """

    name: str
    grade: str
    description: str
    shear_modulus: float
    youngs_modulus: float
    density: float
    strength_fit: tuple
    diameter_range: tuple
    relaxation_percent: tuple
    sources: dict = field(default_factory=dict, compare=False, hash=False)

    # ------------------------------------------------------------------ strength
    def _check_diameter(self, wire_diameter) -> np.ndarray:
        d = np.asarray(wire_diameter, dtype=float)
        lo, hi = self.diameter_range
        bad = ~np.isfinite(d) | (d < lo * (1 - 1e-12)) | (d > hi * (1 + 1e-12))
        if np.any(bad):
            shown = d[bad].flat[0] if d.ndim else float(d)
            raise InputError(
                f"wire_diameter = {fmt_value(float(shown) * 1e3, 'mm')} is outside the diameters of "
                f"{self.grade} ({self.name!r}): it must lie between {fmt_value(lo * 1e3, 'mm')} and "
                f"{fmt_value(hi * 1e3, 'mm')} (the range of the tensile-strength fit)"
            )
        return d

    def tensile_strength(self, wire_diameter):
        """Minimum tensile strength of the wire [Pa] at a diameter (the fit of the band minima).

        ``Rm = min(Rm_cap, A - B log10(d / 1 mm))`` with :attr:`strength_fit` ([SpringONE]'s
        fit of the EN 10270-1/-2 band minima; see the module notes).

        Parameters
        ----------
        wire_diameter : float or array_like
            Wire diameter ``d`` [m], inside :attr:`diameter_range`.

        Returns
        -------
        float or ndarray
            Tensile strength [Pa].
        """
        d = self._check_diameter(wire_diameter)
        a, b, cap = self.strength_fit
        rm = np.minimum(cap, a - b * np.log10(d / 1e-3))
        return float(rm) if rm.ndim == 0 else rm

    def ultimate_shear_strength(self, wire_diameter):
        """Torsional ultimate strength ``0.67 Rm`` [Pa] (Shigley Sec. 10-4, as :mod:`durability`).

        Parameters
        ----------
        wire_diameter : float or array_like
            Wire diameter [m].
        """
        return ultimate_shear_strength(self.tensile_strength(wire_diameter), ULTIMATE_SHEAR_FRACTION)

    def endurance_shear_strength(self, wire_diameter) -> float:
        """Fully reversed torsional endurance strength of shot-peened wire [Pa] at 10^7 cycles.

        Zimmerli's peened data through the Goodman line at this wire's ultimate shear strength
        (:func:`springdyn.valve.spring.stress.zimmerli_endurance_shear_strength`; Shigley Sec. 10-9).
        Zimmerli's point is one for every steel, so a weaker wire gets a *larger* fully reversed
        intercept (a steeper Goodman line); compare grades by the safety factor at the working
        stresses, not by this value.

        Parameters
        ----------
        wire_diameter : float
            Wire diameter [m].
        """
        return float(zimmerli_endurance_shear_strength(float(self.ultimate_shear_strength(wire_diameter))))

    def shear_modulus_at(self, temperature):
        """Shear modulus at a temperature [Pa]: ``G20 (1 - 0.25e-3 (T - 20 degC))`` ([EN 13906-1]).

        Parameters
        ----------
        temperature : float or array_like
            Wire temperature [K].
        """
        t = np.asarray(temperature, dtype=float)
        g = self.shear_modulus * (1.0 - SHEAR_MODULUS_TEMPERATURE_COEFFICIENT * (t - _ZERO_C - 20.0))
        return float(g) if g.ndim == 0 else g

    def spring_keys(self, wire_diameter: float, endurance: bool = False) -> dict:
        """The ``[spring]`` table's material keys for this wire at a diameter, in SI.

        Parameters
        ----------
        wire_diameter : float
            Wire diameter [m].
        endurance : bool
            Add ``endurance_shear_strength`` (:meth:`endurance_shear_strength`).  Off by default:
            it is Zimmerli's value at this tensile strength, the one
            :func:`springdyn.valve.spring.stress.spring_strengths` takes by itself when the key is
            absent (and then reports as a default, which it is: no grade-specific value).

        Returns
        -------
        dict
            ``shear_modulus`` [Pa], ``youngs_modulus`` [Pa], ``density`` [kg/m^3] and
            ``tensile_strength`` [Pa] (the fit's minimum at this diameter); with ``endurance``
            also ``endurance_shear_strength`` [Pa].

        Examples
        --------
        >>> sorted(material("SiCr").spring_keys(3.5e-3))
        ['density', 'shear_modulus', 'tensile_strength', 'youngs_modulus']
        """
        d = float(wire_diameter)
        keys = dict(
            shear_modulus=self.shear_modulus,
            youngs_modulus=self.youngs_modulus,
            density=self.density,
            tensile_strength=float(self.tensile_strength(d)),
        )
        if endurance:
            keys["endurance_shear_strength"] = self.endurance_shear_strength(d)
        return keys


# ----------------------------------------------------------------------------- the table
_EN13906_OT = "EN 13906-1 reference value for oil-tempered wire EN 10270-2 (as in [SpringONE])"
_EN13906_DH = "EN 13906-1 reference value for patented wire EN 10270-1 (as in [SpringONE])"
_RHO = "EN 13906-1 density of spring steel, 7.85 kg/dm^3 (as in [SpringONE])"
_ZIMMERLI = "Zimmerli's peened data through Goodman at 0.67 Rm (Shigley Sec. 10-9, 10-4; durability.py)"
_RELAX = (
    "engineering judgement: no public relaxation chart could be had; values shaped after the "
    "form of EN 13906-1's 48 h charts (loss rising with stress and temperature, concave upward)"
)


def _fit_source(grade: str, rows: str) -> str:
    return (
        f"fit of the {grade} band minima, constants of [SpringONE]'s material database; "
        f"checked against the public rows {rows}"
    )


def _wire(
    name,
    grade,
    description,
    standard,
    strength_fit,
    strength_rows,
    relaxation_percent,
    relaxation_note="",
    *,
    shear_modulus=79.5e9,
    diameter_range=(0.5e-3, 10e-3),
) -> Material:
    """A wire of the table: E and rho as EN 13906-1 gives them for every grade, the sources named."""
    return Material(
        name=name,
        grade=grade,
        description=description,
        shear_modulus=shear_modulus,
        youngs_modulus=206e9,
        density=7850.0,
        strength_fit=strength_fit,
        diameter_range=diameter_range,
        relaxation_percent=relaxation_percent,
        sources=dict(
            shear_modulus=standard,
            youngs_modulus=standard,
            density=_RHO,
            tensile_strength=_fit_source(grade, strength_rows),
            endurance_shear_strength=_ZIMMERLI,
            relaxation_percent=_RELAX + relaxation_note,
        ),
    )


#: The named wires (keys: the names ``material = "..."`` takes, see :func:`material`); relaxation
#: rows at 20, 80, 120 and 160 degC.
MATERIALS: dict[str, Material] = {
    "SiCr": _wire(
        "SiCr",
        "EN 10270-2 VDSiCr",
        "oil-tempered Si-Cr valve-spring wire (high fatigue grade; ASTM A877, JIS SWOSC-V)",
        _EN13906_OT,
        (2125e6, 466e6, 2080e6),
        "d = 0.50 mm: 2080-2230 MPa ([metalleschmidt])",
        ((0.0, 0.1, 0.3, 0.6, 1.2), (0.2, 0.5, 1.0, 1.8, 3.0), (0.5, 1.2, 2.2, 3.6, 5.5), (1.0, 2.5, 4.5, 7.0, 10.0)),
    ),
    "SiCrV": _wire(
        "SiCrV",
        "EN 10270-2 VDSiCrV",
        "oil-tempered Si-Cr-V valve-spring wire, the high-strength grade",
        _EN13906_OT,
        (2270e6, 475e6, 2230e6),
        "d = 0.50 mm: 2230-2380 MPa ([metalleschmidt])",
        ((0.0, 0.1, 0.2, 0.4, 0.8), (0.1, 0.3, 0.7, 1.2, 2.0), (0.3, 0.8, 1.5, 2.5, 3.8), (0.7, 1.7, 3.0, 4.8, 7.0)),
        "; vanadium grade about 0.7 of SiCr (its better sag resistance)",
    ),
    "CrV": _wire(
        "CrV",
        "EN 10270-2 VDCrV",
        "oil-tempered Cr-V valve-spring wire (ASTM A232 class)",
        _EN13906_OT,
        (1900e6, 518e6, 1910e6),
        "(none: no public row was found)",
        ((0.0, 0.2, 0.4, 0.8, 1.6), (0.3, 0.7, 1.4, 2.5, 4.0), (0.8, 1.8, 3.2, 5.0, 7.5), (1.6, 3.6, 6.3, 9.5, 13.5)),
        "; Cr-V about 1.3-1.4 of SiCr",
    ),
    "music-wire": _wire(
        "music-wire",
        "EN 10270-1 DH",
        "patented cold-drawn music wire (EN 10270-1 DH, ASTM A228)",
        _EN13906_DH,
        (2218e6, 817e6, 2800e6),
        "d = 0.20 mm: 2800-3110 MPa, 0.28-0.30 mm: 2660-2940 MPa ([hengming])",
        (
            (0.1, 0.3, 0.6, 1.2, 2.2),
            (0.6, 1.5, 3.0, 5.0, 8.0),
            (2.0, 4.5, 8.0, 12.0, 17.0),
            (4.5, 9.0, 15.0, 21.0, 28.0),
        ),
        "; cold-drawn carbon wire relaxes much more above about 80 degC",
        shear_modulus=81.5e9,
        diameter_range=(0.05e-3, 20e-3),
    ),
}

#: Other spellings :func:`material` takes (lower case): the grades' own names.
ALIASES = {
    "vdsicr": "SiCr",
    "sicr": "SiCr",
    "cr-si": "SiCr",
    "crsi": "SiCr",
    "vdsicrv": "SiCrV",
    "sicrv": "SiCrV",
    "vdcrv": "CrV",
    "crv": "CrV",
    "music-wire": "music-wire",
    "music_wire": "music-wire",
    "musicwire": "music-wire",
    "dh": "music-wire",
    "a228": "music-wire",
}


def material_names() -> tuple[str, ...]:
    """The names of :data:`MATERIALS` (what ``material = "..."`` takes)."""
    return tuple(MATERIALS)


def material(name) -> Material:
    """The named wire of :data:`MATERIALS` (case-insensitive; grade names too, :data:`ALIASES`).

    Parameters
    ----------
    name : str or Material
        ``"SiCr"``, ``"SiCrV"``, ``"CrV"``, ``"music-wire"`` (or ``"VDSiCr"``, ``"DH"``, ...);
        a :class:`Material` is returned as it is.

    Raises
    ------
    InputError
        An unknown name; the message lists the names allowed.

    Examples
    --------
    >>> material("VDSICRV").name
    'SiCrV'
    """
    if isinstance(name, Material):
        return name
    key = str(name).strip().lower() if isinstance(name, str) else None
    if key is None or key not in ALIASES:
        raise InputError(
            f"material = {name!r} is not a known spring wire; choose one of "
            f"{', '.join(repr(n) for n in MATERIALS)} (case-insensitive; grade names such as "
            "'VDSiCr', 'VDSiCrV', 'VDCrV', 'DH' are taken too)"
        )
    return MATERIALS[ALIASES[key]]


#: :func:`material` under a name the functions below can use beside their ``material`` argument.
_lookup = material


# ----------------------------------------------------------------------------- relaxation
def relaxation_time_factor(
    hours, reference_hours: float = RELAXATION_REFERENCE_HOURS, time_constant: float = RELAXATION_TIME_CONSTANT_HOURS
):
    """Ratio of the relaxation after ``hours`` to that after ``reference_hours`` [-].

    The logarithmic relaxation law of metals, ``loss(t) = s ln(1 + t / c)`` ([Feltham]'s form;
    proportional to log t once t >> c), gives

        loss(t) / loss(t_ref) = ln(1 + t / c) / ln(1 + t_ref / c).

    Parameters
    ----------
    hours : float or array_like
        Holding time [h], positive and finite.
    reference_hours : float
        Time of the table [h] (48 h, EN 13906-1).
    time_constant : float
        ``c`` [h] (:data:`RELAXATION_TIME_CONSTANT_HOURS`, engineering judgement).

    Examples
    --------
    >>> round(relaxation_time_factor(48.0), 12)
    1.0
    """
    t = np.asarray(hours, dtype=float)
    if np.any(~np.isfinite(t)) or np.any(t <= 0):
        raise InputError(f"hours = {hours!r} must be a positive, finite holding time [h]")
    if not (reference_hours > 0 and time_constant > 0):
        raise InputError("reference_hours and time_constant must be positive [h]")
    f = np.log1p(t / time_constant) / math.log1p(reference_hours / time_constant)
    return float(f) if f.ndim == 0 else f


def _bilinear(x_nodes, y_nodes, table, x, y):
    """Bilinear interpolation of ``table[i][j]`` at (x, y) inside the node ranges (checked by the caller)."""
    xn, yn, z = np.asarray(x_nodes), np.asarray(y_nodes), np.asarray(table, dtype=float)
    i = np.clip(np.searchsorted(xn, x, side="right") - 1, 0, len(xn) - 2)
    j = np.clip(np.searchsorted(yn, y, side="right") - 1, 0, len(yn) - 2)
    tx = (x - xn[i]) / (xn[i + 1] - xn[i])
    ty = (y - yn[j]) / (yn[j + 1] - yn[j])
    return (
        (1 - tx) * (1 - ty) * z[i, j]
        + tx * (1 - ty) * z[i + 1, j]
        + (1 - tx) * ty * z[i, j + 1]
        + tx * ty * z[i + 1, j + 1]
    )


def relaxation_loss(
    material,
    temperature,
    shear_stress,
    hours=RELAXATION_REFERENCE_HOURS,
    time_constant: float = RELAXATION_TIME_CONSTANT_HOURS,
):
    """Loss of force of a spring held at a length [fraction of the initial force].

    Bilinear interpolation in the material's 48 h table (:attr:`Material.relaxation_percent`,
    over :data:`RELAXATION_TEMPERATURES_C` and :data:`RELAXATION_STRESSES`), times the
    logarithmic time law for other holding times (:func:`relaxation_time_factor`).  Outside
    the table it refuses (:class:`InputError` naming the range) rather than extrapolate.

    Parameters
    ----------
    material : str or Material
        The wire (:func:`material`).
    temperature : float or array_like
        Spring temperature [K].
    shear_stress : float or array_like
        Initial shear stress at the held length [Pa], **uncorrected** ``8 F D / (pi d^3)`` as
        EN 13906-1's relaxation charts (:func:`springdyn.valve.spring.stress.nominal_shear_stress`;
        :func:`relaxed_force` computes it from the force).
    hours : float or array_like
        Holding time [h] (48 h: the table itself).
    time_constant : float
        Time constant of the time law [h].

    Returns
    -------
    float or ndarray
        Loss of force [-] (0.02 for 2 %).

    Examples
    --------
    >>> round(relaxation_loss("SiCr", 393.15, 800e6), 12)  # a node of the table: 3.6 % at 120 degC
    0.036
    """
    m = _lookup(material)
    t_c = np.asarray(temperature, dtype=float) - _ZERO_C
    tau = np.asarray(shear_stress, dtype=float)
    t_lo, t_hi = RELAXATION_TEMPERATURES_C[0], RELAXATION_TEMPERATURES_C[-1]
    s_lo, s_hi = RELAXATION_STRESSES[0], RELAXATION_STRESSES[-1]
    eps = 1e-9
    bad_t = ~np.isfinite(t_c) | (t_c < t_lo - eps) | (t_c > t_hi + eps)
    if np.any(bad_t):
        v = float(np.atleast_1d(t_c)[np.atleast_1d(bad_t)][0])
        raise InputError(
            f"temperature = {v:.6g} degC ({v + _ZERO_C:.6g} K) is outside the relaxation table of "
            f"{m.name!r}: it must lie between {t_lo:g} and {t_hi:g} degC "
            f"({t_lo + _ZERO_C:.6g} to {t_hi + _ZERO_C:.6g} K); springdyn does not extrapolate relaxation"
        )
    bad_s = ~np.isfinite(tau) | (tau < s_lo * (1 - eps)) | (tau > s_hi * (1 + eps))
    if np.any(bad_s):
        v = float(np.atleast_1d(tau)[np.atleast_1d(bad_s)][0])
        raise InputError(
            f"shear_stress = {v / 1e6:.6g} MPa is outside the relaxation table of {m.name!r}: it must lie "
            f"between {s_lo / 1e6:g} and {s_hi / 1e6:g} MPa (uncorrected stress 8 F D / (pi d^3), as "
            "EN 13906-1's charts); springdyn does not extrapolate relaxation"
        )
    t_c = np.clip(t_c, t_lo, t_hi)
    tau = np.clip(tau, s_lo, s_hi)
    loss48 = _bilinear(RELAXATION_TEMPERATURES_C, RELAXATION_STRESSES, m.relaxation_percent, t_c, tau) / 100.0
    loss = loss48 * relaxation_time_factor(hours, RELAXATION_REFERENCE_HOURS, time_constant)
    loss = np.asarray(loss, dtype=float)
    return float(loss) if loss.ndim == 0 else loss


def relaxed_force(
    force,
    material,
    temperature,
    mean_diameter: float,
    wire_diameter: float,
    hours=RELAXATION_REFERENCE_HOURS,
    time_constant: float = RELAXATION_TIME_CONSTANT_HOURS,
):
    """Force of a spring held at its length for a time at a temperature [N].

    ``F (1 - loss)`` with the loss of :func:`relaxation_loss` at the uncorrected initial stress
    ``8 F D / (pi d^3)`` (:func:`springdyn.valve.spring.stress.nominal_shear_stress`).

    Parameters
    ----------
    force : float or array_like
        Initial force at the held length (e.g. the installed force) [N], positive.
    material : str or Material
        The wire (:func:`material`).
    temperature : float
        Spring temperature [K].
    mean_diameter, wire_diameter : float
        Mean coil diameter ``D`` and wire diameter ``d`` [m].
    hours : float
        Holding time [h].
    time_constant : float
        Time constant of the time law [h].

    Returns
    -------
    float or ndarray
        Force after relaxation [N].
    """
    f = np.asarray(force, dtype=float)
    if np.any(~np.isfinite(f)) or np.any(f <= 0):
        raise InputError(f"force = {force!r} must be a positive, finite force [N]")
    tau = nominal_shear_stress(f, mean_diameter, wire_diameter)
    out = f * (1.0 - np.asarray(relaxation_loss(material, temperature, tau, hours, time_constant)))
    return float(out) if out.ndim == 0 else out


# ----------------------------------------------------------------------------- spectrum life
def cycles_to_failure(
    stress_ratio, slope: float = SN_SLOPE, knee_cycles: float = SN_KNEE_CYCLES, haibach: bool = False
):
    """Cycles to failure on the S-N line at a stress ratio ``s = tau / tau_e`` [-].

    ``N = N_D s^-k`` above the knee (``s > 1``; Basquin).  At or below the knee the endurance
    strength is a true endurance limit (``N = inf``), or, with ``haibach``, the line goes on with
    the slope ``2k - 1`` (Haibach's modification, as the FKM guideline's modified Miner rule).

    Parameters
    ----------
    stress_ratio : float or array_like
        Stress over the endurance strength [-], non-negative.
    slope : float
        ``k`` [-] (:data:`SN_SLOPE`).
    knee_cycles : float
        ``N_D`` [-] (:data:`SN_KNEE_CYCLES`).
    haibach : bool
        Continue below the knee with the slope ``2k - 1``.

    Examples
    --------
    >>> cycles_to_failure(2.0, slope=5.0, knee_cycles=1e7)
    312500.0
    """
    s = np.asarray(stress_ratio, dtype=float)
    if np.any(~np.isfinite(s)) or np.any(s < 0):
        raise InputError(f"stress_ratio = {stress_ratio!r} must be finite and non-negative")
    if not (slope > 0 and knee_cycles > 0):
        raise InputError(f"slope = {slope!r} and knee_cycles = {knee_cycles!r} must be positive")
    with np.errstate(divide="ignore"):
        above = knee_cycles * s ** (-slope)
        below = knee_cycles * s ** (-(2.0 * slope - 1.0)) if haibach else np.full_like(s, np.inf)
    n = np.where(s > 1.0, above, below)
    return float(n) if n.ndim == 0 else n


def _vector(name: str, value, n: int | None = None) -> np.ndarray:
    v = np.atleast_1d(np.asarray(value, dtype=float))
    if v.ndim != 1 or (n is not None and len(v) != n):
        raise InputError(f"{name} = {value!r} must be one value per operating point ({n} points)")
    if np.any(~np.isfinite(v)):
        raise InputError(f"{name} = {value!r} must be finite")
    return v


def spectrum_life(
    shares,
    cycles_per_second,
    *,
    amplitude=None,
    mean=None,
    safety_factor=None,
    endurance_shear: float | None = None,
    ultimate_shear: float | None = None,
    material=None,
    wire_diameter: float | None = None,
    slope: float = SN_SLOPE,
    knee_cycles: float = SN_KNEE_CYCLES,
    haibach: bool = False,
) -> dict:
    """Fatigue damage per hour and life of a load spectrum (Miner's rule on an S-N line).

    Per operating point ``i`` (a speed): its share of the running time ``p_i``, its load cycles
    per second ``f_i`` (the cam's revolutions per second: one valve event per revolution), and
    the load of the worst wire element there (the caller takes it from
    :func:`springdyn.valve.spring.stress.fatigue_assessment`), either as

    - ``amplitude`` and ``mean`` [Pa]: the Goodman-equivalent fully reversed amplitude
      ``tau_ar = tau_a / (1 - tau_m / tau_u)`` (Shigley Sec. 6-14, the Goodman line as
      :mod:`durability`) against the endurance strength: ``s_i = tau_ar / tau_e``; or
    - ``safety_factor``: the Goodman factor ``n_i``, read as a load factor along the load
      line: ``s_i = 1 / n_i``.

    Both put the knee (``s = 1``) on the Goodman line.  Cycles to failure ``N_i`` follow
    :func:`cycles_to_failure`; the damage per hour is ``D = sum p_i f_i 3600 / N_i`` (Miner,
    failure at ``D t = 1``) and the life ``1 / D`` hours.  Without ``haibach`` a point at or
    below the endurance strength does no damage (a true endurance limit); every point below
    gives an infinite life.

    Parameters
    ----------
    shares : array_like
        Share of the running time per point [-], non-negative, summing to 1.
    cycles_per_second : array_like
        Load cycles per second per point [1/s] (cam revolutions per second), positive.
    amplitude, mean : array_like, optional
        Shear-stress amplitude and mean of the worst element per point [Pa] (corrected
        stress, as :mod:`durability`).
    safety_factor : array_like, optional
        Goodman safety factor per point [-], positive (instead of ``amplitude``/``mean``).
    endurance_shear, ultimate_shear : float, optional
        Fully reversed endurance and ultimate shear strengths [Pa], for ``amplitude``/``mean``;
        or give ``material`` and ``wire_diameter`` to take them from the material.
    material : str or Material, optional
        The wire (:func:`material`).
    wire_diameter : float, optional
        Wire diameter [m] (with ``material``).
    slope : float
        S-N slope ``k`` [-] (:data:`SN_SLOPE`).
    knee_cycles : float
        Cycles at the knee [-] (:data:`SN_KNEE_CYCLES`).
    haibach : bool
        Haibach's modification below the knee (slope ``2k - 1``) instead of an endurance limit.

    Returns
    -------
    dict
        ``damage_per_hour`` [1/h], ``life_hours`` [h] (``inf`` for no damage),
        ``cycles_per_hour`` [1/h] (all points), ``life_cycles`` [-], ``per_point`` (a list of
        dicts: ``share``, ``cycles_per_second``, ``stress_ratio``, ``cycles_to_failure``,
        ``damage_per_hour``, ``damage_share``), and the S-N line used (``slope``,
        ``knee_cycles``, ``haibach``, ``stress_measure``).

    Examples
    --------
    One point at twice the endurance strength, 50 cycles/s, k = 5: N = 1e7 / 32, life
    N / (50 * 3600) h.

    >>> out = spectrum_life([1.0], [50.0], safety_factor=[0.5], slope=5.0)
    >>> round(out["life_hours"], 4)
    1.7361
    """
    p = _vector("shares", shares)
    n_pts = len(p)
    f = _vector("cycles_per_second", cycles_per_second, n_pts)
    if np.any(p < 0):
        raise InputError(f"shares = {shares!r} must not be negative")
    if abs(float(p.sum()) - 1.0) > 1e-6:
        raise InputError(
            f"shares = {shares!r} sum to {float(p.sum()):.6g}: they are shares of the running time and "
            "must sum to 1 (divide each by their sum; percentages by 100)"
        )
    if np.any(f <= 0):
        raise InputError(f"cycles_per_second = {cycles_per_second!r} must be positive [1/s]")
    by_stress = amplitude is not None or mean is not None
    if by_stress == (safety_factor is not None):
        raise InputError(
            "give the load per point either as amplitude and mean [Pa] or as safety_factor [-], not both or neither"
        )
    if safety_factor is not None:
        n = _vector("safety_factor", safety_factor, n_pts)
        if np.any(n <= 0):
            raise InputError(f"safety_factor = {safety_factor!r} must be positive")
        s = 1.0 / n
        measure = "1 / Goodman safety factor"
    else:
        if amplitude is None or mean is None:
            raise InputError("amplitude and mean go together: give both [Pa], one value per point")
        a = _vector("amplitude", amplitude, n_pts)
        m = _vector("mean", mean, n_pts)
        if np.any(a < 0):
            raise InputError(f"amplitude = {amplitude!r} must not be negative [Pa]")
        if endurance_shear is None or ultimate_shear is None:
            if material is None or wire_diameter is None:
                raise InputError(
                    "amplitude and mean need the strengths: endurance_shear and ultimate_shear [Pa], "
                    "or material and wire_diameter"
                )
            mat = _lookup(material)
            endurance_shear = (
                mat.endurance_shear_strength(wire_diameter) if endurance_shear is None else endurance_shear
            )
            ultimate_shear = (
                float(mat.ultimate_shear_strength(wire_diameter)) if ultimate_shear is None else ultimate_shear
            )
        if not (endurance_shear > 0 and ultimate_shear > 0):
            raise InputError("endurance_shear and ultimate_shear must be positive [Pa]")
        mp = np.maximum(m, 0.0)  # a compressive mean does not help, as durability.goodman_safety_factor
        if np.any(mp >= ultimate_shear):
            i = int(np.argmax(mp >= ultimate_shear))
            raise InputError(
                f"mean[{i}] = {m[i] / 1e6:.6g} MPa reaches the ultimate shear strength "
                f"{ultimate_shear / 1e6:.6g} MPa: the wire fails statically, there is no fatigue life"
            )
        s = a / (1.0 - mp / ultimate_shear) / endurance_shear
        measure = "Goodman-equivalent fully reversed amplitude / endurance strength"
    n_f = np.atleast_1d(cycles_to_failure(s, slope, knee_cycles, haibach))
    rate = p * f * 3600.0
    with np.errstate(divide="ignore"):
        damage = np.where(np.isfinite(n_f), rate / n_f, 0.0)
    total = float(damage.sum())
    cycles_per_hour = float(rate.sum())
    life = math.inf if total == 0.0 else 1.0 / total
    per_point = [
        dict(
            share=float(p[i]),
            cycles_per_second=float(f[i]),
            stress_ratio=float(s[i]),
            cycles_to_failure=float(n_f[i]),
            damage_per_hour=float(damage[i]),
            damage_share=float(damage[i] / total) if total > 0 else 0.0,
        )
        for i in range(n_pts)
    ]
    return dict(
        damage_per_hour=total,
        life_hours=life,
        cycles_per_hour=cycles_per_hour,
        life_cycles=life * cycles_per_hour,
        per_point=per_point,
        slope=float(slope),
        knee_cycles=float(knee_cycles),
        haibach=bool(haibach),
        stress_measure=measure,
    )
