"""A spring proven across its manufacturing tolerances: the ``[tolerances]`` table and
:func:`tolerance_study`.

**The table** names the parameters under their own names (:data:`TOLERANCED`): the spring's
``wire_diameter``, ``mean_diameter`` (or the drawing's ``outer_diameter`` / ``inner_diameter``),
``free_length``, ``installed_length``,
``shear_modulus``, ``youngs_modulus``, ``density``, the coils' ``pitch`` (the mean pitch of the
active coils, :func:`mean_active_pitch`: the coiling tool's systematic error, which shows as
free length), the cam's ``lift`` and the valve train's ``lash``.  A value is a band, uniform between its limits (``wire_diameter = "+-0.02 mm"``,
``shear_modulus = "+-2 %"``), or a distribution (``wire_diameter = { distribution =
"normal", sigma = "0.01 mm" }``; ``"uniform"`` takes ``limits``).  A ``[criteria]`` table
beside it sets the limits each variant is judged against
(:class:`springdyn.valve.design.criteria.Criteria`, the one set of criteria).

**Sampling** (:func:`sample`): scrambled Sobol points (``scipy.stats.qmc.Sobol``, a
low-discrepancy sequence: percentiles converge faster than with random points) or Monte
Carlo (``numpy.random.default_rng``), both reproducible from the seed; a point ``u`` in the
unit cube becomes ``nominal + (2u - 1) band`` (uniform) or ``nominal + sigma Phi^-1(u)``
(normal, ``scipy.special.ndtri``).

**Each variant** (:func:`run_variant`) is the spring, cam and train with the sampled values,
swept over the speed range (:func:`springdyn.valve.sweep`, every speed to its periodic
steady state): ``Fset`` and ``f1`` (the model's), the float speed (the lowest swept speed
from which the valve leaves the cam over the nose at every higher one, narrowed to the
resolution), the peak retainer force, the lowest speed with coil clash, and the smallest
Goodman safety over the speeds (both extremes also at the rated speed and refined around the
worst swept speeds).  A **float-speed study** (``float_only``, :func:`run_variant_float`)
runs no sweep: each variant's float speed is searched from the nominal's
(:func:`springdyn.valve.run.float_search.float_speed_near`, four to five speeds a variant).
A **screened study** (``screen``, :func:`_screened`, :mod:`.screening`) runs every variant's
statics, fits a quadratic response surface to each dynamic figure on a designed part of the
sample, checks it on a hold-out, and simulates only the variants the surface cannot judge.

**Outputs**: ``variants.nc`` (dimension ``variant``: the inputs under their names and the
outputs, each variant's ``settled`` flag), percentiles, the share of variants that fail each
criterion, histograms; a variant that did not settle (a residual above ``periodicity_tol``)
is counted and left out of the percentiles, shares and histograms.  The sample is drawn chunk
by chunk as the chunks are submitted (:func:`sample_chunks`), a few chunks in flight per
thread: a study of any size starts at once and holds a few chunks, not its whole sample.  The
variants run in chunks of :data:`CHUNK`, on the local threads or a Dask cluster, written to
``DIR/chunks/`` as they finish: a killed run resumes from them (a chunk belongs to its
sample: the seed, the count, the method, the table, the speeds, the resolution and the kind
of study).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import threading
import warnings
import zipfile
from concurrent.futures import FIRST_COMPLETED, ThreadPoolExecutor, wait
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy.special import ndtri
from scipy.stats import qmc

from ...core.docstrings import ParameterDocs
from ...core.errors import InputError
from ...core.io import atomic_path, direct_outputs, glob_escape
from ...core.params import load_toml
from ...core.results import Result, notes_lines, text_table
from ...core.units import format_quantity, omega_to_rpm, to_si
from .. import run
from ..run.float_search import FLOAT_RESOLUTION
from ..run.periodicity import PERIODICITY_TOL
from ..spring.formulas import active_coils_free
from ..spring.pack import SPRING_TABLES, SpringPack
from ..train.piston import static_valve_lift
from . import criteria, screening
from .criteria import Criteria

__all__ = [
    "TOLERANCED",
    "Tolerance",
    "mean_active_pitch",
    "Criteria",
    "read_tolerances",
    "sample",
    "sample_chunks",
    "run_variant",
    "run_variant_float",
    "tolerance_study",
    "ToleranceStudy",
    "OUTPUTS",
    "FLOAT_OUTPUTS",
    "PACK_TOLERANCED",
    "PACK_FIGURES",
    "tolerances_for",
    "pack_nominal_values",
    "pack_variant",
    "pack_figures",
]

#: Parameter descriptions shared by the sample's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    tolerances : dict
        name -> (Tolerance, relative) (:func:`read_tolerances`).
    nominal : dict
        name -> nominal value [SI] (:func:`nominal_values`).
    count : int
        Variants [-].
    seed : int
        Seed of the generator [-].
    method : {"sobol", "monte-carlo"}
        Scrambled Sobol points or pseudo-random ones.
    """
)

#: The parameters a ``[tolerances]`` table may name, with their SI unit and where they live
#: (a drawing's outer or inner diameter is the coil diameter as drawn: the mean diameter is
#: ``De - d`` or ``Di + d`` with the variant's wire diameter; one of the three is toleranced).
TOLERANCED = {
    "wire_diameter": ("m", "spring"),
    "mean_diameter": ("m", "spring"),
    "free_length": ("m", "spring"),
    "installed_length": ("m", "spring"),
    "shear_modulus": ("Pa", "spring"),
    "youngs_modulus": ("Pa", "spring"),
    "density": ("kg/m^3", "spring"),
    "outer_diameter": ("m", "drawing"),
    "inner_diameter": ("m", "drawing"),
    "pitch": ("m", "coiling"),
    "lift": ("m", "cam"),
    "lash": ("m", "valve_train"),
}
#: The outputs per variant, with their units.  A float speed or clash onset beyond the speed
#: range is the range's top speed (a lower bound) with ``float_in_range`` / ``clash_in_range``
#: 0; a variant the model refuses has ``refused`` 1 and zeros (no NaN in an output);
#: ``periodicity`` is the largest change between the last two revolutions of any speed the
#: variant ran [fraction of Fset] (the residual beside its figures), ``simulations`` the speeds
#: it ran, each to its periodic steady state.  ``variants.nc`` adds ``settled``: 0 where the
#: residual is above the study's ``periodicity_tol`` (the variant is kept there, flagged, and
#: left out of the percentiles and the failing shares, with a note "N of M variants did not
#: settle").
OUTPUTS = {
    "Fset": "N",
    "f1": "Hz",
    "float_cam_rpm": "rpm",
    "max_retainer_force": "N",
    "clash_onset_cam_rpm": "rpm",
    "max_clash_severity": "1",
    "goodman_safety": "1",
    "float_in_range": "1",
    "clash_in_range": "1",
    "refused": "1",
    "periodicity": "1",
    "simulations": "1",
}
#: The outputs of a float-speed study (``float_only``): the statics and the float speed.
FLOAT_OUTPUTS = ("Fset", "f1", "float_cam_rpm", "float_in_range", "refused", "periodicity", "simulations")
#: The outputs of a variant's statics (:func:`variant_statics`): a screened study has them of every variant.
STATIC_OUTPUTS = ("Fset", "f1", "refused")
#: The outputs that are figures (percentiles and histograms); the others are flags.
FIGURES = (
    "Fset",
    "f1",
    "float_cam_rpm",
    "max_retainer_force",
    "clash_onset_cam_rpm",
    "max_clash_severity",
    "goodman_safety",
)
#: Percentiles reported of every output [%].
PERCENTILES = (0.135, 2.5, 50.0, 97.5, 99.865)
#: Variants beyond which the 0.135 % and 99.865 % percentiles lie inside the sample: fewer, and
#: those columns are the sample's extremes (the sample resolves a tail of 1/n at best), and
#: ``{figure}_p0.135_normal`` / ``_p99.865_normal`` give the normal fit's mean -+ 3 sigma beside them.
TAIL_VARIANTS = math.ceil(100.0 / PERCENTILES[0])
#: Variants per chunk on disk (a killed run loses at most one chunk's work; the chunks run
#: in parallel on the local threads or the Dask workers).
CHUNK = 25


@dataclass(frozen=True)
class Tolerance:
    """One toleranced parameter: ``kind`` "uniform" (``half_width``) or "normal" (``sigma``), in SI."""

    name: str
    kind: str
    half_width: float = 0.0
    sigma: float = 0.0

    def values(self, nominal: float, u: np.ndarray) -> np.ndarray:
        """Sampled values [SI] from points ``u`` in (0, 1).

        Parameters
        ----------
        nominal : float
            Nominal value [SI].
        u : ndarray
            Points in (0, 1) [-].
        """
        if self.kind == "uniform":
            return nominal + (2.0 * u - 1.0) * self.half_width

        return nominal + self.sigma * ndtri(np.clip(u, 1e-12, 1.0 - 1e-12))


def _quantity(text, unit: str, field_name: str, nominal_percent: bool):
    """A tolerance width: ``"0.02 mm"`` [unit] or ``"2 %"`` (a fraction, flagged)."""
    if isinstance(text, str) and text.strip().endswith("%"):
        return float(to_si(text, "", field_name)), True
    return float(to_si(text, unit, field_name)), False


def parse_tolerance(name: str, value) -> tuple[Tolerance, bool]:
    """A ``[tolerances]`` entry: the tolerance and whether its width is relative (a %).

    Parameters
    ----------
    name : str
        A key of :data:`TOLERANCED`.
    value : str or dict
        ``"+-0.02 mm"``, ``"+-2 %"``, or ``{distribution = "normal", sigma = "0.01 mm"}``.
    """
    where = f"[tolerances] {name}"
    unit = unit_of(name)
    if isinstance(value, str):
        text = value.strip()
        for prefix in ("+-", "±", "+/-"):
            if text.startswith(prefix):
                width, rel = _quantity(text[len(prefix) :].strip(), unit, where, True)
                if not width > 0:
                    raise InputError(f"{where} = {value!r}: the band must be positive")
                return Tolerance(name, "uniform", half_width=width), rel
        raise InputError(
            f'{where} = {value!r}: give a band "+-0.02 mm" (or "+-2 %") or a table {{ distribution = "normal", sigma = "0.01 mm" }}'
        )
    if isinstance(value, dict):
        dist = value.get("distribution")
        extra = sorted(set(value) - {"distribution", "sigma", "limits"})
        if extra:
            raise InputError(
                f"{where}: unknown key {extra[0]!r}; allowed: distribution, sigma (normal), limits (uniform)"
            )
        if dist == "normal":
            if "sigma" not in value:
                raise InputError(f'{where}: distribution = "normal" needs sigma (e.g. sigma = "0.01 mm")')
            sigma, rel = _quantity(value["sigma"], unit, f"{where}.sigma", True)
            if not sigma > 0:
                raise InputError(f"{where}.sigma must be positive")
            return Tolerance(name, "normal", sigma=sigma), rel
        if dist == "uniform":
            if "limits" not in value:
                raise InputError(f'{where}: distribution = "uniform" needs limits (e.g. limits = "+-0.02 mm")')
            return parse_tolerance(name, value["limits"])
        raise InputError(f'{where}: distribution = {dist!r} must be "normal" or "uniform"')
    raise InputError(f"{where} = {value!r}: give a band string or a distribution table")


def read_tolerances(path) -> tuple[dict, Criteria]:
    """The ``[tolerances]`` (name -> (Tolerance, relative)) and ``[criteria]`` tables of a file.

    Parameters
    ----------
    path : str or path-like
        The tolerance file.
    """
    doc = load_toml(path, allowed=("tolerances", "criteria"))
    if "tolerances" not in doc or not doc["tolerances"]:
        raise InputError(f'{path}: no [tolerances] table (e.g. wire_diameter = "+-0.02 mm")')
    tols = {k: parse_tolerance(k, v) for k, v in _flat_tolerances(doc["tolerances"]).items()}
    _check_diameters(tols, str(path))
    return tols, Criteria.from_dict(doc.get("criteria", {}), source=str(path))


def _check_diameters(tols: dict, where: str) -> None:
    """One toleranced coil diameter a spring (mean, or the drawing's outer or inner)."""
    for prefix in {split_name(k)[0] for k in tols}:
        table = "" if prefix is None else f"{prefix}."
        diameters = [table + k for k in ("mean_diameter", "outer_diameter", "inner_diameter") if table + k in tols]
        if len(diameters) > 1:
            raise InputError(
                f"{where}: [tolerances] {diameters[0]} and {diameters[1]} both vary the coil diameter; give one of "
                "them (the drawing's)"
            )


def nominal_values(spring, cam, valve_train) -> dict:
    """The nominal value of every toleranced parameter [SI] (:data:`TOLERANCED`; a spring
    pack's, :func:`pack_nominal_values`).

    Parameters
    ----------
    spring : ValveSpring or SpringPack
    cam : Cam
    valve_train : ValveTrain or None
    """
    if isinstance(spring, SpringPack):
        return pack_nominal_values(spring, cam, valve_train)
    out = {k: float(getattr(spring, k)) for k, (_, where) in TOLERANCED.items() if where == "spring"}
    out["outer_diameter"] = float(spring.mean_diameter + spring.wire.width)  # the wire across the coil
    out["inner_diameter"] = float(spring.mean_diameter - spring.wire.width)
    out["pitch"] = mean_active_pitch(spring)
    out["lift"] = float(cam.max_lift)
    out["lash"] = float(valve_train.lash) if valve_train is not None else 0.0
    return out


def mean_active_pitch(spring) -> float:
    """The mean pitch of the active coils of the unloaded spring [m]:
    ``(Lf - (2 Nb + 1) Dw) / (N1 + N2 - 2 Nb)`` (the free length less the dead coils' and the
    end wire's height, over the active coils of :func:`springdyn.valve.spring.formulas.active_coils_free`).

    A pitch tolerance is the coiling tool's systematic error of this pitch: every active coil
    longer by ``dp`` makes the spring ``(N1 + N2 - 2 Nb) dp`` longer (:func:`variant`).

    Parameters
    ----------
    spring : ValveSpring
        The spring (its free length [m], wire diameter [m] and coil counts [-]).
    """

    na = active_coils_free(spring.low_pitch_coils, spring.high_pitch_coils, spring.dead_coils)
    return (spring.free_length - (2.0 * spring.dead_coils + 1.0) * spring.wire_diameter) / na


@_DOCS.fill
def sample(tolerances: dict, nominal: dict, count: int, seed: int, method: str = "sobol") -> dict:
    """Sampled values of the toleranced parameters [SI], reproducible from the seed.

    Parameters
    ----------
    {tolerances nominal count seed method}
    """
    return next(sample_chunks(tolerances, nominal, count, seed, method, size=max(int(count), 1)))[2]


@_DOCS.fill
def sample_chunks(tolerances: dict, nominal: dict, count: int, seed: int, method: str = "sobol", size: int = 0):
    """The sample of :func:`sample` drawn lazily, ``size`` variants at a time: ``(lo, hi,
    values)`` for the variants ``lo`` to ``hi - 1``, each chunk drawn when it is asked for
    from one stream (the same values to the bit as :func:`sample` draws at once), so that a
    study of 10,000,000 variants holds one chunk of its sample, not all of it.  The bands
    are checked (:func:`_check_band`) before the first chunk.

    Parameters
    ----------
    {tolerances nominal count seed method}
    size : int
        Variants per chunk [-] (0: :data:`CHUNK`).
    """
    names = list(tolerances)
    if method == "sobol":
        engine = qmc.Sobol(d=len(names), scramble=True, seed=seed)

        def draw(n):
            with warnings.catch_warnings():  # balanced at powers of 2; ToleranceStudy notes it
                warnings.simplefilter("ignore")
                return engine.random(n)

    elif method == "monte-carlo":
        rng = np.random.default_rng(seed)

        def draw(n):  # one double a number, row by row: chunks give the values of one draw
            return rng.random((n, len(names)))

    else:
        raise InputError(f"method = {method!r} must be 'sobol' or 'monte-carlo'")
    bands = {}
    for name in names:
        tol, rel = tolerances[name]
        scale = nominal[name] if rel else 1.0
        t = dataclasses.replace(tol, half_width=tol.half_width * scale, sigma=tol.sigma * scale)
        _check_band(name, t, nominal[name])
        bands[name] = t
    return _draw_chunks(names, bands, nominal, int(count), draw, int(size) or CHUNK)


def _draw_chunks(names, bands, nominal, count, draw, size):
    """The chunks of :func:`sample_chunks` (a generator: nothing is drawn before it is asked for)."""
    for lo in range(0, count, size):
        hi = min(lo + size, count)
        u = draw(hi - lo)
        yield lo, hi, {name: bands[name].values(nominal[name], u[:, j]) for j, name in enumerate(names)}


#: The parameters that may be zero (no lash is a lash); every other toleranced one must stay positive.
MAY_BE_ZERO = ("lash",)


def _check_band(name: str, tol: Tolerance, nominal: float) -> None:
    """Refuse a band whose lowest sample leaves the parameter's range (issue 40: ``lash =
    "+-1 mm"`` on 0.15 mm simulated negative lash): a uniform band's ``nominal - half_width``,
    a normal one's ``nominal - 7.03 sigma`` (the sampler's most extreme point, u = 1e-12)."""
    low = nominal - (tol.half_width if tol.kind == "uniform" else 7.03 * tol.sigma)
    if low < 0.0 or (low == 0.0 and name not in MAY_BE_ZERO):
        unit = unit_of(name)
        display = {"m": "mm", "Pa": "GPa"}.get(unit, unit)
        band = (
            f"+-{format_quantity(tol.half_width, unit, display)}"
            if tol.kind == "uniform"
            else f"sigma {format_quantity(tol.sigma, unit, display)}"
        )
        raise InputError(
            f"[tolerances] {name} = {band} on the nominal {format_quantity(nominal, unit, display)} reaches "
            f"{format_quantity(low, unit, display)}: a band must keep {name} "
            + ("at 0 or more" if name in MAY_BE_ZERO else "positive")
            + (" (a normal band reaches 7 sigma in the sample)" if tol.kind == "normal" else "")
        )


def variant(spring, cam, valve_train, values: dict):
    """The spring, cam and train with the values ``values`` [SI] (name -> value; a spring
    pack's, :func:`pack_variant`).

    Parameters
    ----------
    spring : ValveSpring or SpringPack
    cam : Cam
    valve_train : ValveTrain or None
    values : dict
        Values of toleranced parameters [SI].
    """
    if isinstance(spring, SpringPack):
        return pack_variant(spring, cam, valve_train, values)
    spring_changes = {k: float(v) for k, v in values.items() if TOLERANCED[k][1] == "spring"}
    if "wire_diameter" in spring_changes and spring.wire_shape != "round":
        raise InputError(
            f"[tolerances] wire_diameter: the spring's wire is {spring.wire_shape} (wire_width by wire_height); "
            "a tolerance of its section is not supported: tolerance the other keys"
        )
    wire = spring_changes.get("wire_diameter", spring.wire.width)  # across the coil: D = De - b = Di + b
    if "outer_diameter" in values:  # the drawn coil diameter with this variant's wire
        spring_changes["mean_diameter"] = float(values["outer_diameter"]) - wire
    if "inner_diameter" in values:
        spring_changes["mean_diameter"] = float(values["inner_diameter"]) + wire
    if "pitch" in values:  # the coils' pitch error shows as free length (mean_active_pitch)
        if spring.pitch_profile:
            raise InputError(
                "[tolerances] pitch: the spring has a pitch_profile; tolerance its profile's own values instead"
            )

        na = active_coils_free(spring.low_pitch_coils, spring.high_pitch_coils, spring.dead_coils)
        lf = spring_changes.get("free_length", spring.free_length)
        spring_changes["free_length"] = lf + na * (float(values["pitch"]) - mean_active_pitch(spring))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sp = dataclasses.replace(spring, **spring_changes) if spring_changes else spring
    c = cam.scaled(float(values["lift"]) / cam.max_lift) if "lift" in values else cam
    vt = valve_train
    if "lash" in values and vt is not None:
        vt = dataclasses.replace(vt, lash=max(float(values["lash"]), 0.0))
    return sp, c, vt


# ----------------------------------------------------------------------------- spring packs
#: The toleranced values of a spring pack beyond its springs' (``[damper]``'s Coulomb force).
PACK_TOLERANCED = {"damper.friction_force": ("N", "damper")}
#: Where a spring's own keys live in :data:`TOLERANCED` (the spring, its drawing, its coiling).
SPRING_KEYS = ("spring", "drawing", "coiling")
#: A pack variant's figures per spring, ``<spring>_<figure>`` (``outer_Fset``, ``inner_f1``, ...),
#: with their units: its installed force and first mode (its model's, as the single spring's
#: ``Fset`` and ``f1``), its static force at full valve lift and its static Goodman safety
#: (installed to full lift); beside them ``<a>_<b>_radial_clearance`` [m], the smaller of two
#: neighbours' clearances installed and at coil bind (:func:`springdyn.valve.spring.pack.radial_clearance`).
PACK_FIGURES = {"Fset": "N", "f1": "Hz", "open_force": "N", "static_goodman_safety": "1"}


def split_name(name: str) -> tuple:
    """``(table, key)`` of a ``[tolerances]`` name: ``("inner_spring", "wire_diameter")`` for
    ``inner_spring.wire_diameter``, ``(None, "wire_diameter")`` for a bare key.

    Parameters
    ----------
    name : str
        The name [-].
    """
    table, dot, key = str(name).rpartition(".")
    return (table, key) if dot else (None, key)


def unit_of(name: str) -> str:
    """The SI unit of a toleranced name (a bare key, a pack spring's ``<table>.<key>`` or
    ``damper.friction_force``); refuses any other name.

    Parameters
    ----------
    name : str
        The name [-].
    """
    if name in PACK_TOLERANCED:
        return PACK_TOLERANCED[name][0]
    table, key = split_name(name)
    if table is None and key in TOLERANCED:
        return TOLERANCED[key][0]
    if table in SPRING_TABLES and TOLERANCED.get(key, ("", ""))[1] in SPRING_KEYS:
        return TOLERANCED[key][0]
    spring_keys = [k for k, (_, where) in TOLERANCED.items() if where in SPRING_KEYS]
    raise InputError(
        f"[tolerances] {name}: not a toleranced parameter; allowed: {', '.join(TOLERANCED)}; for a spring pack "
        f"also a spring's own, {' or '.join(f'{t}.<key>' for t in SPRING_TABLES)} (<key>: {', '.join(spring_keys)}), "
        f"and {', '.join(PACK_TOLERANCED)}"
    )


def _flat_tolerances(table: dict) -> dict:
    """The ``[tolerances]`` table with a pack's sub-tables (``inner_spring.wire_diameter = ...``,
    a dotted key, or ``[tolerances.inner_spring]``) as dotted names."""
    out = {}
    for k, v in table.items():
        if isinstance(v, dict) and (k in SPRING_TABLES or k == "damper"):
            out.update({f"{k}.{key}": value for key, value in v.items()})
        else:
            out[k] = v
    return out


def tolerances_for(spring, tolerances: dict) -> dict:
    """The tolerances of a study of ``spring``, every name naming one value of its definition.

    A single spring takes the bare keys.  A spring pack takes each spring's own keys under its
    table, ``spring.<key>`` (the outer), ``inner_spring.<key>``, ``third_spring.<key>``, and
    ``damper.friction_force``; a bare drawing key (``wire_diameter``) is every spring's, drawn
    independently for each (the springs are made separately: ``spring.wire_diameter``,
    ``inner_spring.wire_diameter``, ...); the bare ``installed_length`` is the head's (one seat,
    one retainer: the same shift of every spring's installed length, added to a spring's own
    ``<table>.installed_length``, its seat step); ``lift`` and ``lash`` are the cam's and the train's.

    Parameters
    ----------
    spring : ValveSpring or SpringPack
        The design [-].
    tolerances : dict
        name -> (Tolerance, relative) (:func:`read_tolerances`).

    Returns
    -------
    dict
        name -> (Tolerance, relative), a pack's drawing keys expanded to each spring's.
    """
    if not isinstance(spring, SpringPack):
        named = [k for k in tolerances if split_name(k)[0] is not None]
        if named:
            raise InputError(
                f"[tolerances] {named[0]} names a spring of a pack, but the spring file holds one spring: name its "
                f"keys without a table ({split_name(named[0])[1]}), or give a pack file ([inner_spring])"
            )
        return dict(tolerances)
    tables = SPRING_TABLES[: len(spring.springs)]
    out = {}
    for name, tol in tolerances.items():
        table, key = split_name(name)
        if table is None and TOLERANCED[key][1] in SPRING_KEYS and key != "installed_length":
            for t in tables:
                if f"{t}.{key}" in tolerances:
                    raise InputError(
                        f"[tolerances] {key} (every spring's) and {t}.{key} (that spring's) both vary {t}'s {key}: "
                        "give one of them"
                    )
                out[f"{t}.{key}"] = tol
        elif table in SPRING_TABLES and table not in tables:
            raise InputError(f"[tolerances] {name}: the pack has no [{table}] (its springs: {', '.join(tables)})")
        elif table == "damper" and spring.damper is None:
            raise InputError(f"[tolerances] {name}: the pack has no [damper]")
        else:
            out[name] = tol
    _check_diameters(out, "the spring pack")
    return out


def pack_nominal_values(pack, cam, valve_train) -> dict:
    """The nominal value of every toleranced value of a spring pack [SI] (:func:`tolerances_for`):
    each spring's under its table's name, the head's ``installed_length`` (the outer spring's),
    ``lift``, ``lash`` and, with a damper, ``damper.friction_force``.

    Parameters
    ----------
    pack : SpringPack
    cam : Cam
    valve_train : ValveTrain or None
    """
    out = {}
    for table, s in zip(SPRING_TABLES, pack.springs):
        one = nominal_values(s, cam, valve_train)
        out.update({f"{table}.{k}": v for k, v in one.items() if TOLERANCED[k][1] in SPRING_KEYS})
    out.update({k: v for k, v in one.items() if TOLERANCED[k][1] not in SPRING_KEYS})  # the cam's, the train's
    out["installed_length"] = float(pack.installed_length)
    if pack.damper is not None:
        out["damper.friction_force"] = float(pack.damper.force)
    return out


def pack_variant(pack, cam, valve_train, values: dict):
    """The pack, cam and train with the values ``values`` [SI] (name -> value, names of
    :func:`tolerances_for`): each spring the single spring's :func:`variant` of its own values,
    every installed length shifted by the head's, the damper's force, the cam's lift and the
    train's lash.  A pack whose springs then interfere is refused as the pack refuses it
    (:class:`springdyn.valve.spring.pack.SpringPack`).

    Parameters
    ----------
    pack : SpringPack
    cam : Cam
    valve_train : ValveTrain or None
    values : dict
        Values of toleranced parameters [SI].
    """
    shift = float(values["installed_length"]) - pack.installed_length if "installed_length" in values else 0.0
    springs = []
    for table, s in zip(SPRING_TABLES, pack.springs):
        own = {split_name(k)[1]: float(v) for k, v in values.items() if split_name(k)[0] == table}
        if shift:
            own["installed_length"] = own.get("installed_length", s.installed_length) + shift
        springs.append(variant(s, cam, None, own)[0])
    damper = pack.damper
    if "damper.friction_force" in values:
        force = float(values["damper.friction_force"])
        damper = damper.replace(friction_force=force, normal_load=None, friction_coefficient=None)
    _, c, vt = variant(pack.outer, cam, valve_train, {k: values[k] for k in ("lift", "lash") if k in values})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the nominal pack's warnings (its hands) were given once
        return SpringPack(springs, pack.options, damper), c, vt


def pack_outputs(pack) -> dict:
    """The outputs of a pack variant beyond :data:`OUTPUTS` (:data:`PACK_FIGURES`), name -> unit.

    Parameters
    ----------
    pack : SpringPack
    """
    out = {f"{name}_{k}": unit for name in pack.names for k, unit in PACK_FIGURES.items()}
    out.update({f"{pair}_radial_clearance": "m" for pair in pack.fit})
    return out


def pack_figures(pack, cam, valve_train) -> dict:
    """A pack variant's figures per spring (:data:`PACK_FIGURES`) and its radial clearances [SI].

    The full valve lift is the rigid train's (:func:`springdyn.valve.train.piston.static_valve_lift`,
    the cam's lift for the spring alone); the static Goodman safety is each spring's between its
    installed force and its force there (:meth:`springdyn.valve.spring.pack.SpringPack.stress`).

    Parameters
    ----------
    pack : SpringPack
    cam : Cam
    valve_train : ValveTrain or None
    """
    lift = float(np.max(static_valve_lift(cam, valve_train, np.linspace(0.0, 2.0 * math.pi, 3600, endpoint=False))))
    forces = pack.static_forces(np.array([0.0, lift]))
    goodman = pack.stress(forces[:, 0], forces[:, 1])
    out = {}
    for k, (name, s) in enumerate(zip(pack.names, pack.springs)):
        out[f"{name}_Fset"] = float(s.spring_model.internal_parameters()["Fset"])
        out[f"{name}_f1"] = float(s.spring_model.first_mode_installed)
        out[f"{name}_open_force"] = float(forces[k, 1])
        out[f"{name}_static_goodman_safety"] = float(goodman[name]["fatigue_safety_factor"] or 0.0)
    for pair, fit in pack.fit.items():
        out[f"{pair}_radial_clearance"] = float(
            min(fit["radial_clearance_installed_m"], fit["radial_clearance_at_bind_m"])
        )
    return out


def run_variant(
    spring,
    cam,
    valve_train,
    speeds,
    rated_rpm: float | None = None,
    resolution: float = FLOAT_RESOLUTION,
    max_clash_severity: float | None = None,
    periodicity_tol: float | None = None,
    starts=None,
) -> dict:
    """The outputs of :data:`OUTPUTS` of one variant over the speeds [rev/min]: its statics and
    its speed study (:func:`springdyn.valve.run.studies.speed_study`: the float speed to
    ``resolution``, the smallest Goodman safety and the largest retainer force up to
    ``rated_rpm``, refined around the worst speeds, the clash onset above ``max_clash_severity``
    and the largest clash severity).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain or None
    speeds : array_like
        Cam speeds [rev/min], ascending.
    rated_rpm : float, optional
        The highest speed in service [rev/min] (the criteria's float speed: above it the
        valve may float and the spring is not loaded in service).
    resolution : float
        Width of the float speed's final bracket [rev/min].
    max_clash_severity : float, optional
        Largest clash severity that is no clash [fraction of Fset] (``[criteria]``; default the run's,
        :data:`springdyn.valve.run.verdicts.MAX_CLASH_SEVERITY`).
    periodicity_tol : float, optional
        The periodic steady state each speed runs to [fraction of Fset] (default the run's,
        :data:`springdyn.valve.run.periodicity.PERIODICITY_TOL`).
    starts : PeriodicStates, optional
        Warm starts: the nominal's periodic states (:func:`_warm_starts`), receiving the variant's.
    """
    top = float(np.max(speeds))
    r = run.speed_study(
        spring, cam, valve_train, speeds, rated_rpm, resolution, max_clash_severity, periodicity_tol, starts
    )
    return dict(
        variant_statics(spring, cam, valve_train),
        float_cam_rpm=top if r["float_cam_rpm"] is None else r["float_cam_rpm"],
        max_retainer_force=r["max_retainer_force"],
        clash_onset_cam_rpm=top if r["clash_onset_cam_rpm"] is None else r["clash_onset_cam_rpm"],
        max_clash_severity=r["max_clash_severity"],
        goodman_safety=r["goodman_safety"],
        float_in_range=float(r["float_cam_rpm"] is not None),
        clash_in_range=float(r["clash_onset_cam_rpm"] is not None),
        periodicity=r["periodicity"],
        simulations=float(r["simulations"]),
    )


def run_variant_float(
    spring,
    cam,
    valve_train,
    speeds,
    guess_rpm: float,
    resolution: float = FLOAT_RESOLUTION,
    periodicity_tol: float | None = None,
    starts=None,
) -> dict:
    """The outputs of :data:`FLOAT_OUTPUTS` of one variant: its statics and its float speed,
    found near ``guess_rpm`` (the nominal's) within the speed range by
    :func:`springdyn.valve.run.float_search.float_speed_near` (four to five speeds, not a sweep).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain
    speeds : array_like
        Cam speeds [rev/min], ascending: the range searched is ``speeds[0]`` to ``speeds[-1]``.
    guess_rpm : float
        Where the search starts [rev/min].
    resolution : float
        Width of the float speed's final bracket [rev/min].
    periodicity_tol : float, optional
        The periodic steady state each trial speed runs to [fraction of Fset] (default the run's).
    starts : PeriodicStates, optional
        Warm starts: the nominal's periodic states (:func:`_warm_starts`), receiving the variant's.
    """

    near = run.variant_float_speed(
        spring, cam, valve_train, guess_rpm, float(speeds[0]), float(speeds[-1]), resolution, periodicity_tol, starts
    )
    return dict(
        variant_statics(spring, cam, valve_train),
        float_cam_rpm=near["float_cam_rpm"],
        float_in_range=float(near["in_range"]),
        periodicity=near["periodicity"],
        simulations=float(near["evaluations"]),
    )


def definition_fingerprint(value):
    """Every field of a definition, exactly, as JSON-ready data: nested definitions as their
    fields, floats as their ``repr`` (all digits), arrays as lists; what a study's chunk key
    hashes so that chunks of another spring, cam or train are never read back.

    Parameters
    ----------
    value : object
        A definition (a dataclass: ``ValveSpring``, ``Cam``, ``ValveTrain``, ...; a
        ``SpringPack`` as its springs, options and damper), or a field's value.
    """
    if isinstance(value, SpringPack):  # not a dataclass: its repr rounds the springs
        return ["SpringPack", *(definition_fingerprint(v) for v in (value.springs, value.options, value.damper))]
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        return [type(value).__name__] + [
            [f.name, definition_fingerprint(getattr(value, f.name))] for f in dataclasses.fields(value)
        ]
    if isinstance(value, np.ndarray):
        return [definition_fingerprint(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [definition_fingerprint(v) for v in value]
    if isinstance(value, dict):
        return [[str(k), definition_fingerprint(v)] for k, v in sorted(value.items(), key=lambda kv: str(kv[0]))]
    if isinstance(value, float | np.floating):
        return repr(float(value))
    if value is None or isinstance(value, bool | int | str):
        return value
    return repr(value)


def _key(tolerances, count, seed, method, speeds, *extra) -> str:
    """The sample's fingerprint: chunks on disk belong to it (``extra``: the definitions and
    settings that change a variant, :func:`definition_fingerprint`)."""
    spec = {k: [t.kind, t.half_width, t.sigma, rel] for k, (t, rel) in tolerances.items()}
    text = json.dumps([spec, count, seed, method, [float(s) for s in speeds], CHUNK, *extra], sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


class _Stopped(Exception):
    """A chunk left unfinished because the study was interrupted (nothing of it is stored)."""


def _chunk_outputs(plan: dict) -> tuple:
    """The outputs a chunk of ``plan`` gives: :data:`STATIC_OUTPUTS` (``plan["statics"]``),
    :data:`FLOAT_OUTPUTS` (``plan["guess"]``) or :data:`OUTPUTS`, and a pack's figures."""
    if plan.get("statics"):
        own = STATIC_OUTPUTS
    else:
        own = FLOAT_OUTPUTS if plan.get("guess") is not None else tuple(OUTPUTS)
    return own + tuple(plan.get("pack", ()))


def variant_statics(spring, cam, valve_train) -> dict:
    """The outputs of :data:`STATIC_OUTPUTS` of one variant (and a pack's figures): what a
    screened study knows of every variant without running it.

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    valve_train : ValveTrain or None
    """
    out = dict(
        Fset=float(spring.spring_model.internal_parameters()["Fset"]),
        f1=float(spring.spring_model.first_mode_installed),
        refused=0.0,
    )
    if isinstance(spring, SpringPack):
        out.update(pack_figures(spring, cam, valve_train))
    return out


def _run_chunk(spring, cam, valve_train, speeds, values: dict, plan: dict, stop=None) -> dict:
    """The variants of ``values`` (a chunk's slice of the sample: only it travels to a Dask
    worker): :func:`run_variant_float` with ``plan["guess"]``, else :func:`run_variant`.
    ``stop`` (a :class:`threading.Event`, local threads only): set, the chunk ends before its
    next variant (an interrupted study stops within one variant, its finished chunks kept)."""

    names = _chunk_outputs(plan)
    rows = {k: [] for k in names}
    for i in range(len(next(iter(values.values())))):
        if stop is not None and stop.is_set():
            raise _Stopped()
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                sp, c, vt = variant(spring, cam, valve_train, {k: v[i] for k, v in values.items()})
                starts = _variant_starts(plan)
                if plan.get("statics"):
                    r = variant_statics(sp, c, vt)
                elif plan.get("guess") is not None:
                    r = run_variant_float(
                        sp, c, vt, speeds, plan["guess"], plan["resolution"], plan.get("periodicity_tol"), starts
                    )
                else:
                    r = run_variant(
                        sp,
                        c,
                        vt,
                        speeds,
                        plan["rated"],
                        plan["resolution"],
                        plan["clash_limit"],
                        plan.get("periodicity_tol"),
                        starts,
                    )
        except InputError:  # a variant the model refuses (e.g. past solid): counted as failed
            r = dict({k: 0.0 for k in names}, refused=1.0)
        for k in names:
            rows[k].append(r[k])
    return {k: np.asarray(v, dtype=float) for k, v in rows.items()}


def tolerance_study(
    spring,
    cam,
    tolerances: dict,
    criteria: Criteria | None = None,
    *,
    count: int,
    seed: int,
    speeds,
    valve_train=None,
    method: str = "sobol",
    out_dir=None,
    client=None,
    progress=None,
    float_only: bool = False,
    resolution: float = FLOAT_RESOLUTION,
    workers: int | None = None,
    periodicity_tol: float | None = None,
    warm_starts: bool = True,
    screen: bool = False,
) -> ToleranceStudy:
    """The spring across its tolerances (module docstring).

    Parameters
    ----------
    spring : ValveSpring
    cam : Cam
    tolerances : dict
        name -> (Tolerance, relative) (:func:`read_tolerances`).
    criteria : Criteria, optional
        The limits (default: :class:`Criteria`'s).
    count : int
        Variants [-].
    seed : int
        Seed [-].
    speeds : array_like
        Cam speeds of each variant's sweep [rev/min]; a float-speed study searches between
        the first and the last.
    valve_train : ValveTrain, optional
        The train (float speed, lash).
    method : {"sobol", "monte-carlo"}
    out_dir : path-like, optional
        Folder of the chunks (resumable) and of ``variants.nc``.
    client : dask.distributed.Client, optional
        Runs the chunks on a Dask cluster.
    progress : callable, optional
        ``progress(iterable, total=, desc=)`` wrapper.
    float_only : bool
        A float-speed study: each variant's statics and float speed only
        (:func:`run_variant_float`, searched from the nominal's), no sweep; Goodman safety,
        peak force and coil clash are not computed.
    resolution : float
        Width of the float speeds' final bracket [rev/min].
    workers : int, optional
        Local threads the chunks run on [-] (default: the cores, at most 2).
    periodicity_tol : float, optional
        The periodic steady state every run of a variant goes to, and the residual a variant
        must keep to count as settled [fraction of Fset] (default
        :data:`springdyn.valve.run.periodicity.PERIODICITY_TOL`, 0.2 %): a variant whose
        largest residual is above it is flagged (``settled`` 0) and left out of the
        percentiles and the failing shares.
    warm_starts : bool
        Every variant's speeds start from the nominal's periodic states (and its own, search
        trial to trial), not from rest (:func:`_warm_starts`): fewer revolutions, the figures
        within the periodicity tolerance of cold starts' (float speeds within ``resolution``).
    screen : bool
        A screened study (:func:`_screened`, :mod:`.screening`): every variant's statics, a
        designed part of the sample simulated and fitted with a quadratic response surface per
        dynamic figure, checked on a hold-out, and only the variants the surface cannot judge
        simulated; the others' dynamic figures are the surface's, within its band (each
        figure's in ``variants.nc``'s attributes, ``simulated`` 0).  A sample smaller than
        :func:`_screen_pays` runs every variant.
    """
    import xarray as xr  # (here: xarray costs 0.4 s of start-up)

    criteria = Criteria() if criteria is None else criteria
    if not isinstance(count, int) or not 1 <= count <= 10_000_000:
        raise InputError(f"count = {count!r} must be a whole number of variants from 1 to 10000000")
    if float_only and valve_train is None:
        raise InputError("a float-speed study (float_only) needs a valve train: the spring alone does not float")
    if not (isinstance(resolution, (int, float)) and math.isfinite(resolution) and resolution > 0):
        raise InputError(f"resolution = {resolution!r} must be a positive speed [rev/min]")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InputError(f"workers = {workers!r} must be a whole number of at least 1")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not 0 <= seed < 2**63:
        # the seed goes into the NetCDF file as a 64-bit integer (a larger one failed there, after the study)
        raise InputError(f"seed = {seed!r} must be a whole number from 0 to 2^63 - 1")
    if periodicity_tol is not None and not (
        isinstance(periodicity_tol, (int, float)) and 1e-7 <= periodicity_tol <= 0.5
    ):
        raise InputError(
            f"periodicity_tol = {periodicity_tol!r} must be a fraction of Fset from 1e-07 to 0.5 "
            f"(default {PERIODICITY_TOL:g}, i.e. {100 * PERIODICITY_TOL:g} %)"
        )
    tol = PERIODICITY_TOL if periodicity_tol is None else float(periodicity_tol)
    speeds = np.sort(np.atleast_1d(np.asarray(speeds, dtype=float)))
    tolerances = tolerances_for(spring, tolerances)  # a pack's: each spring's own
    extra = pack_outputs(spring) if isinstance(spring, SpringPack) else {}
    nominal = nominal_values(spring, cam, valve_train)
    chunks = sample_chunks(tolerances, nominal, count, seed, method)  # lazy: one chunk drawn at a time
    # in service up to the float speed the criteria ask for: the Goodman safety and the peak
    # force are judged there (above it the valve may float)
    rated = None if criteria.min_float_cam_rpm is None else omega_to_rpm(criteria.min_float_cam_rpm)
    # the runs' own tolerance only when it is not theirs already (the default study's runs and
    # chunk keys are those of earlier versions)
    run_tol = None if tol == PERIODICITY_TOL else tol
    plan = dict(
        rated=rated,
        resolution=float(resolution),
        guess=None,
        clash_limit=criteria.max_clash_severity,
        periodicity_tol=run_tol,
    )
    if extra:
        plan["pack"] = tuple(extra)
    if float_only:
        # the nominal's float speed from a scan of the range (the definition), then by the
        # variants' search from there: its float speed starts every search

        nominal_states = run.PeriodicStates() if warm_starts else None
        scan = run.float_speed(
            spring,
            cam,
            valve_train,
            speeds,
            resolution=float(resolution),
            starts=nominal_states,
            **({} if run_tol is None else dict(periodicity_tol=run_tol)),
        )
        scanned = float(speeds[-1] if scan.float_cam_rpm is None else scan.float_cam_rpm)
        nominal_out = run_variant_float(
            spring, cam, valve_train, speeds, scanned, float(resolution), run_tol, nominal_states
        )
        nominal_out["float_cam_rpm_scan"] = scanned
        plan["guess"] = nominal_out["float_cam_rpm"]
        plan["starts"] = nominal_states
    elif warm_starts:
        nominal_out, plan["starts"] = _warm_starts(spring, cam, valve_train, speeds, plan)
    names = (FLOAT_OUTPUTS if float_only else tuple(OUTPUTS)) + tuple(extra)
    key = _key(
        tolerances,
        count,
        seed,
        method,
        speeds,
        float(resolution),
        bool(float_only),
        criteria.max_clash_severity,
        definition_fingerprint([spring, cam, valve_train]),  # chunks of another spring, cam or train are not these
        *(() if run_tol is None else (repr(run_tol),)),
    )
    key += "" if (rated is None or float_only) else f"r{rated:.0f}"
    chunk_dir = None if out_dir is None else Path(out_dir) / "chunks"
    if chunk_dir is not None:
        chunk_dir.mkdir(parents=True, exist_ok=True)
    base, execution = (spring, cam, valve_train, speeds), (client, workers, progress)
    screen_info = {}
    if screen and count < _screen_pays(len(tolerances)):
        screen, screen_info = False, dict(skipped=_screen_pays(len(tolerances)))
    if screen:
        values = sample(tolerances, nominal, count, seed, method)  # (a screen holds the sample)
        rules = dynamic_rules(criteria, speeds, valve_train is not None, float_only)
        outputs, simulated, screen_info, resumed = _screened(
            values, plan, names, key + "x", chunk_dir, base, execution, rules
        )
    else:
        done, resumed = _read_back(chunk_dir, key, count, names)
        todo = math.ceil(count / CHUNK) - len(done)
        # the chunks still to run, drawn from the sample as they are submitted (a chunk read
        # back is drawn too, and dropped: the stream stays the sample's)
        waiting = ((lo, values) for lo, _, values in chunks if lo not in done)
        _execute(waiting, todo, _storer(done, chunk_dir, key, names), (*base, plan), *execution)
        values = sample(tolerances, nominal, count, seed, method)  # the chunks' values, drawn at once
        stacked = np.concatenate([done[lo] for lo in range(0, count, CHUNK)], axis=1)
        done.clear()
        outputs = {k: stacked[j] for j, k in enumerate(names)}
        simulated = np.ones(count, bool)
    settled = (outputs["refused"] < 0.5) & (outputs["periodicity"] <= tol)
    units = {k: unit_of(k) for k in values}
    data = {k: ("variant", v, {"units": units[k], "long_name": f"sampled {k}"}) for k, v in values.items()}
    data.update({k: ("variant", v, {"units": OUTPUTS.get(k) or extra[k]}) for k, v in outputs.items()})
    searched = screen_info.pop("float_searched", np.zeros(count, bool))
    data["settled"] = _flag(
        settled,
        "every run of the variant settled: periodicity within periodicity_tol "
        "(0: left out of the percentiles and shares; a refused variant ran nothing)",
    )
    data["simulated"] = _flag(
        simulated,
        "1: the variant was simulated; 0: its dynamic figures are a screened study's "
        "response surface's (within the attributes' screen_band_* of a simulation)",
    )
    data["float_searched"] = _flag(
        searched,
        "1: a screened study searched the variant's float speed (float_only's search); its "
        "other dynamic figures are the response surface's",
    )
    screen_attrs = {f"screen_band_{k}": v["band"] for k, v in screen_info.get("figures", {}).items()}
    screen_attrs.update({f"screen_{k}": v["how"] for k, v in screen_info.get("figures", {}).items()})
    ds = xr.Dataset(
        data,
        coords={"variant": ("variant", np.arange(count))},
        attrs=dict(
            method=method,
            seed=int(seed),
            count=int(count),
            sample_key=key,
            study="float speed" if float_only else "full",
            float_resolution_rpm=float(resolution),
            periodicity_tol=tol,
            screened=int(bool(screen)),
            **screen_attrs,
            **{
                f"screen_{k}": int(screen_info[k])
                for k in ("fitted", "held_out", "terms", "skipped")
                if k in screen_info
            },
        ),
    )
    if not float_only and not warm_starts:
        nominal_out = run_variant(
            spring, cam, valve_train, speeds, rated, float(resolution), criteria.max_clash_severity, run_tol
        )
    study = ToleranceStudy(
        dataset=ds,
        criteria=criteria,
        nominal=nominal_out,
        speeds=speeds,
        resumed=resumed,
        floats=valve_train is not None,
        tolerances={k: (t.kind, t.half_width, t.sigma, rel) for k, (t, rel) in tolerances.items()},
        float_only=bool(float_only),
        pack_outputs=extra,
    )
    if out_dir is not None:
        with atomic_path(Path(out_dir) / "variants.nc") as tmp:
            ds.to_netcdf(tmp)
    return study


def _warm_starts(spring, cam, valve_train, speeds, plan: dict):
    """The nominal design's outputs (:func:`run_variant`) and its periodic states, recorded at
    every speed it ran: the warm starts of the variants (:func:`_variant_starts`).

    A variant starts each speed from the nominal's state at that speed about its own static
    equilibrium (:class:`springdyn.valve.run.periodicity.PeriodicStates`): the nominal is the
    centre of the bands, no farther from any variant than a band's half-width.
    """
    states = run.PeriodicStates()
    out = run_variant(
        spring,
        cam,
        valve_train,
        speeds,
        plan["rated"],
        plan["resolution"],
        plan["clash_limit"],
        plan.get("periodicity_tol"),
        states,
    )
    return out, states


def _variant_starts(plan: dict):
    """A variant's warm starts: a copy of the nominal's states (``plan["starts"]``), which the
    variant's own runs extend (its search trial to trial), or None (cold starts)."""
    nominal = plan.get("starts")
    return None if nominal is None else nominal.copy()


#: Chunks in flight per thread (local) or per worker thread (Dask): enough to keep every
#: thread busy, few enough that a study of any size holds a few chunks' samples and futures.
IN_FLIGHT = 2


def _bounded(pool, waiting, limit, spring, cam, valve_train, speeds, plan, stop):
    """``(lo, outputs)`` of each chunk of ``waiting`` as it finishes on ``pool``, at most
    ``limit`` submitted at a time (the next chunk is drawn when one finishes)."""
    pending = {}

    def top_up():
        while len(pending) < limit:
            item = next(waiting, None)
            if item is None:
                return
            lo, values = item
            pending[pool.submit(_run_chunk, spring, cam, valve_train, speeds, values, plan, stop)] = lo

    top_up()
    while pending:
        finished, _ = wait(pending, return_when=FIRST_COMPLETED)
        for fut in sorted(finished, key=lambda f: pending[f]):
            yield pending.pop(fut), fut.result()
        top_up()


def _read_back(chunk_dir, key: str, count: int, names) -> tuple:
    """The chunks of ``key`` on disk (``{key}_{lo:08d}.npz``) that hold ``names`` for their
    rows of ``count``: ``({lo: array (len(names), rows)}, rows read back)``.  An unreadable
    chunk (a torn write, a foreign file) is deleted and computed again."""
    done, resumed = {}, 0
    # the chunks on disk, not every chunk of the sample (400,000 of them at 10,000,000 variants)
    on_disk = [] if chunk_dir is None else sorted(chunk_dir.glob(f"{glob_escape(key)}_*.npz"))
    for f in on_disk:
        lo = f.name[len(key) + 1 : -len(".npz")]
        if not (lo.isdigit() and len(lo) == 8 and int(lo) % CHUNK == 0 and int(lo) < count):
            continue  # another sample's (its key goes on, e.g. r3000) or a foreign file
        lo = int(lo)
        hi = min(lo + CHUNK, count)
        try:
            with np.load(f) as z:
                got = {k: np.asarray(z[k], dtype=float) for k in names}
            if any(v.shape != (hi - lo,) or not np.all(np.isfinite(v)) for v in got.values()):
                raise ValueError("wrong shape or not finite")
        except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
            f.unlink(missing_ok=True)
            continue
        done[lo] = np.stack([got[k] for k in names])
        resumed += hi - lo
    return done, resumed


def _storer(done: dict, chunk_dir, key: str, names):
    """``store(lo, outputs)``: a finished chunk kept in ``done`` and committed to disk at once
    (not with the command's other outputs: a killed or interrupted study resumes from every
    chunk that finished, issue 40)."""

    def store(lo, res):
        done[lo] = np.stack([np.asarray(res[k], dtype=float) for k in names])  # one array a chunk
        if chunk_dir is not None:
            with direct_outputs(), atomic_path(chunk_dir / f"{key}_{lo:08d}.npz") as tmp:
                with open(tmp, "wb") as fh:
                    np.savez(fh, **res)

    return store


def _execute(waiting, todo: int, store, run_args: tuple, client, workers, progress, desc: str = "variants") -> None:
    """Every chunk ``(lo, values)`` of ``waiting`` run (:func:`_run_chunk` with ``run_args``:
    spring, cam, train, speeds, plan) on the Dask ``client`` or on local threads, each given to
    ``store`` as it finishes; ``todo`` chunks, shown by ``progress``."""
    if client is not None and todo:
        from dask.distributed import as_completed  # (here: dask is an optional extra)

        # a bounded number of chunks in flight: the sample and the futures of 10,000,000
        # variants are never held at once
        limit = IN_FLIGHT * max(1, sum(client.nthreads().values()))
        where = {}

        def submit():
            item = next(waiting, None)
            if item is None:
                return None
            fut = client.submit(_run_chunk, *run_args[:4], item[1], run_args[4], pure=False)
            where[fut.key] = item[0]
            return fut

        first = [fut for fut in (submit() for _ in range(min(limit, todo))) if fut is not None]
        it = as_completed(first, loop=client.loop)  # the study's client, not a default one (it may have none)
        for fut in progress(it, total=todo, desc=desc) if progress else it:
            store(where.pop(fut.key), fut.result())
            fut.release()
            nxt = submit()
            if nxt is not None:
                it.add(nxt)
    elif todo:
        # the engine releases the GIL: the chunks run on threads, each its variants in turn
        threads = workers or min(os.cpu_count() or 1, 2)
        stop = threading.Event()
        pool = ThreadPoolExecutor(max_workers=threads)
        try:
            it = _bounded(pool, waiting, IN_FLIGHT * threads, *run_args, stop)
            for lo, res in progress(it, total=todo, desc=desc) if progress else it:
                store(lo, res)
        except BaseException:  # Ctrl-C, SIGTERM (the CLI's), an error: stop within a variant, keep the chunks
            stop.set()
            pool.shutdown(wait=True, cancel_futures=True)
            raise
        pool.shutdown(wait=True)


def dynamic_rules(criteria_: Criteria, speeds, floats: bool, float_only: bool) -> dict:
    """The criteria a study judges on its variants' dynamic figures: criterion -> ``(figure,
    passes, limit)``, ``passes(values)`` the criterion's rule
    (:func:`springdyn.valve.design.criteria.passes`) on the figure's values (a float speed above
    the range as ``inf``) against ``limit`` [the figure's unit].

    Parameters
    ----------
    criteria_ : Criteria
        The limits.
    speeds : array_like
        The study's cam speeds [rev/min]: without ``min_float_cam_rpm`` the float speed must lie
        above the last.
    floats : bool
        The study has a float speed (a valve train).
    float_only : bool
        A float-speed study (no Goodman, clash or peak force).
    """
    c = criteria_
    out = {}
    if not float_only:
        out["goodman"] = (
            "goodman_safety",
            lambda v: criteria.passes("goodman", v, c.min_goodman_safety),
            c.min_goodman_safety,
        )
    if floats:
        need = omega_to_rpm(c.min_float_cam_rpm) if c.min_float_cam_rpm is not None else float(np.max(speeds))
        out["float_speed"] = ("float_cam_rpm", lambda v: criteria.passes("float_speed", v, need), need)
    if c.no_coil_clash and not float_only:
        out["coil_clash"] = (
            "max_clash_severity",
            lambda v: criteria.passes("coil_clash", v, c.max_clash_severity),
            c.max_clash_severity,
        )
    if c.max_retainer_force is not None and not float_only:
        out["retainer_force"] = (
            "max_retainer_force",
            lambda v: criteria.passes("max_retainer_force", v, c.max_retainer_force),
            c.max_retainer_force,
        )
    return out


#: How far a float speed searched from a guess (:func:`run_variant_float`) may lie from the
#: sweep's, beyond the resolution [rev/min]: the two brackets overlap within 1.5 rpm
#: (tests/valve/run/test_float_search.py).  A screened study simulates a variant whose searched
#: float speed lies within this and the resolution of the limit.
SEARCH_AGREEMENT = 1.5
#: The figures a screened study predicts (the others are its statics' or flags), each with the
#: bound it is censored at (``"top"``: the speed range's top, a float speed or clash onset
#: beyond the range; a number: no clash) or None.
SCREENED = {
    "float_cam_rpm": "top",
    "max_retainer_force": None,
    "clash_onset_cam_rpm": "top",
    "max_clash_severity": 0.0,
    "goodman_safety": None,
}


def _run_rows(rows, tag: str, plan: dict, values: dict, key: str, chunk_dir, base: tuple, execution: tuple, desc: str):
    """The outputs (:func:`_chunk_outputs`) of the variants ``rows`` (indices into the sample
    ``values``), run in chunks of their own under ``{key}{tag}`` (resumable), and how many
    were read back."""
    names = _chunk_outputs(plan)
    n = len(rows)
    k = f"{key}{tag}"
    done, resumed = _read_back(chunk_dir, k, n, names)
    todo = math.ceil(n / CHUNK) - len(done)
    waiting = (
        (lo, {q: v[rows[lo : lo + CHUNK]] for q, v in values.items()}) for lo in range(0, n, CHUNK) if lo not in done
    )
    _execute(waiting, todo, _storer(done, chunk_dir, k, names), (*base, plan), *execution, desc)
    stacked = np.concatenate([done[lo] for lo in range(0, n, CHUNK)], axis=1) if n else np.zeros((len(names), 0))
    return {q: stacked[j] for j, q in enumerate(names)}, resumed


def _screened(values: dict, plan: dict, names: tuple, key: str, chunk_dir, base: tuple, execution: tuple, rules: dict):
    """A screened study's outputs of every variant (module :mod:`.screening`): every variant's
    statics; the first ``2 T`` unrefused variants of the sample simulated and fitted with a
    quadratic surface per figure of :data:`SCREENED` (``T`` its terms), the next ``T``
    simulated as a hold-out; then simulated: every variant outside the fitted variants' box
    and every variant whose verdict on a criterion of ``rules`` the surface's band leaves
    open.  The others take the surface's figures.

    A variant undecided on the float speed alone (a full study) has its float speed searched
    (:func:`run_variant_float`, from the fitted variants' median) and its other figures
    predicted.

    Returns ``(outputs, simulated, info, resumed)``: the outputs over the sample, the boolean
    array of the variants simulated, the screen's figures (per figure its band and how it was
    predicted, ``float_searched``: the variants whose float speed alone was searched) and the
    variants read back from chunks.
    """
    speeds = base[3]
    top = float(np.max(speeds))
    count = len(next(iter(values.values())))
    x = np.column_stack([np.asarray(values[k], dtype=float) for k in values])
    statics, resumed = _run_rows(
        np.arange(count), "s", dict(plan, statics=True), values, key, chunk_dir, base, execution, "statics"
    )
    order = np.flatnonzero(statics["refused"] < 0.5)
    terms = screening.term_count(x.shape[1])
    fit_rows = order[: screening.FITTED_PER_TERM * terms]
    hold_rows = order[screening.FITTED_PER_TERM * terms : (screening.FITTED_PER_TERM + 1) * terms]
    fit, r1 = _run_rows(fit_rows, "f", plan, values, key, chunk_dir, base, execution, "fitted variants")
    hold, r2 = _run_rows(hold_rows, "h", plan, values, key, chunk_dir, base, execution, "held-out variants")
    resumed += r1 + r2
    tol = plan.get("periodicity_tol") or PERIODICITY_TOL
    use = (fit["refused"] < 0.5) & (fit["periodicity"] <= tol)
    figures = [k for k in names if k in SCREENED]
    prediction, info = {}, {}
    # a variant the dynamics refuse while its statics pass: the surface cannot know it, every variant is run
    dynamic_refusal = bool(np.any(fit["refused"] > 0.5) or np.any(hold["refused"] > 0.5))
    for k in figures:
        bound = top if SCREENED[k] == "top" else SCREENED[k]
        if dynamic_refusal or use.sum() <= terms:
            fs = screening.FigureScreen("not predicted", np.inf)
        else:
            quantum = {"float_cam_rpm": plan["resolution"], "clash_onset_cam_rpm": _speed_step(speeds)}.get(k, 0.0)
            fs = screening.screen_figure(
                x[fit_rows][use], fit[k][use], x[hold_rows], hold[k], bound, bound == top, quantum
            )
        prediction[k] = fs.predict(x)  # (judged as it is; reported held to its bound)
        info[k] = dict(how=fs.how, band=float(fs.band), bound=bound)
    run = np.zeros(count, bool)
    run[fit_rows] = run[hold_rows] = True
    simulate = (statics["refused"] < 0.5) & ~run
    # a variant outside the fitted ones' box, or undecided on a criterion, is simulated; one
    # undecided on the float speed alone has its float speed searched (4-5 speeds, not a sweep)
    full = ~screening.inside_box(x, x[np.concatenate([fit_rows, hold_rows])])
    search = np.zeros(count, bool)
    for figure, rule, _ in rules.values():
        if figure not in prediction:
            continue
        pred, band = prediction[figure], info[figure]["band"]
        if figure == "float_cam_rpm":  # above the range: no float within it
            judge = lambda v, rule=rule: rule(np.where(v >= top, np.inf, v))  # noqa: E731
        else:
            judge = rule
        open_ = screening.undecided(judge, np.nan_to_num(pred), band)
        if figure == "float_cam_rpm" and plan.get("guess") is None:
            search |= open_
        else:
            full |= open_
    rest_rows = np.flatnonzero(simulate & full)
    tag = "u" + hashlib.sha256(rest_rows.tobytes()).hexdigest()[:8]
    rest, r3 = _run_rows(rest_rows, tag, plan, values, key, chunk_dir, base, execution, "undecided variants")
    search_rows = np.flatnonzero(simulate & ~full & search)
    floats = fit["float_cam_rpm"][use & (fit["float_cam_rpm"] < top)] if "float_cam_rpm" in fit else np.zeros(0)
    guess = float(np.median(floats)) if floats.size else top  # where the searches start
    tag = "g" + hashlib.sha256(search_rows.tobytes() + repr(guess).encode()).hexdigest()[:8]
    searched, r4 = _run_rows(
        search_rows, tag, dict(plan, guess=guess), values, key, chunk_dir, base, execution, "float speeds searched"
    )
    resumed += r3 + r4
    if search_rows.size:
        # a searched float speed agrees with the sweep's within the resolution and SEARCH_AGREEMENT:
        # one within that of the limit is simulated (its verdict is the sweep's)
        need = rules["float_speed"][2]
        close = (searched["float_in_range"] > 0.5) & (
            np.abs(searched["float_cam_rpm"] - need) <= plan["resolution"] + SEARCH_AGREEMENT
        )
        more = search_rows[close]
        tag = "c" + hashlib.sha256(more.tobytes()).hexdigest()[:8]
        extra_rows, r5 = _run_rows(
            more, tag, plan, values, key, chunk_dir, base, execution, "float speeds at the limit"
        )
        resumed += r5
        searched = {k: v[~close] for k, v in searched.items()}
        search_rows = search_rows[~close]
        rest_rows = np.concatenate([rest_rows, more])
        rest = {k: np.concatenate([rest[k], extra_rows[k]]) for k in rest}
    outputs = {k: np.zeros(count) for k in names}
    for k in statics:
        outputs[k] = statics[k].copy()
    for k in figures:
        bound, pred = info[k].pop("bound"), np.nan_to_num(prediction[k])
        if bound is not None:  # beyond its bound a figure is reported at it, as a simulation's
            pred = np.minimum(pred, bound) if bound == top else np.maximum(pred, bound)
        outputs[k] = pred
    if "float_in_range" in outputs:
        outputs["float_in_range"] = (outputs["float_cam_rpm"] < top).astype(float)
    if "clash_in_range" in outputs:
        outputs["clash_in_range"] = (outputs["clash_onset_cam_rpm"] < top).astype(float)
    refused = statics["refused"] > 0.5
    for k in names:  # a refused variant: zeros, as a simulated one's
        if k != "refused":
            outputs[k][refused] = 0.0
    simulated = np.zeros(count, bool)
    for rows, res in ((fit_rows, fit), (hold_rows, hold), (rest_rows, rest)):
        for k in names:
            outputs[k][rows] = res[k]
        simulated[rows] = True
    for k in searched:
        outputs[k][search_rows] = searched[k]
    gone = search_rows[searched["refused"] > 0.5] if search_rows.size else search_rows
    for k in names:  # refused by the dynamics: zeros
        if k != "refused":
            outputs[k][gone] = 0.0
    float_searched = np.zeros(count, bool)
    float_searched[search_rows] = True
    info = dict(
        figures=info,
        fitted=int(fit_rows.size),
        held_out=int(hold_rows.size),
        terms=int(terms),
        float_searched=float_searched,
    )
    return outputs, simulated, info, resumed


def figure_tolerance(name: str, values, fset, resolution: float, speeds, periodicity_tol: float = PERIODICITY_TOL):
    """How far two converged runs of a variant may differ in a figure: the periodicity tolerance
    in the figure's terms (what a warm start is held to, and a screened study's prediction
    beside its band) [the figure's unit].

    Forces differ by up to ``periodicity_tol`` of the variant's Fset, a clash severity (a
    fraction of Fset) and a Goodman safety by that fraction of themselves, a float speed by the
    resolution and :data:`SEARCH_AGREEMENT` (its search against the sweep's), a clash onset by
    the swept speeds' step; the statics not at all.

    Parameters
    ----------
    name : str
        An output of :data:`OUTPUTS`.
    values : array_like
        The figure's values [its unit].
    fset : array_like
        The variants' Fset [N].
    resolution : float
        The float speeds' final bracket [rev/min].
    speeds : array_like
        The study's cam speeds [rev/min].
    periodicity_tol : float
        The periodic steady state's tolerance [fraction of Fset].
    """
    values, fset = np.asarray(values, dtype=float), np.asarray(fset, dtype=float)
    if name == "max_retainer_force":
        return periodicity_tol * fset
    if name in ("goodman_safety", "max_clash_severity"):
        return periodicity_tol * np.abs(values)
    if name == "float_cam_rpm":
        return np.full(values.shape, resolution + SEARCH_AGREEMENT)
    if name == "clash_onset_cam_rpm":
        return np.full(values.shape, _speed_step(speeds))
    return np.zeros(values.shape)


def _flag(values, long_name: str) -> tuple:
    """A boolean column of ``variants.nc`` over ``variant`` (int8, unit 1)."""
    return ("variant", np.asarray(values).astype(np.int8), {"units": "1", "long_name": long_name})


def _screen_pays(parameters: int) -> int:
    """The smallest sample a screen runs on [-]: twice the variants it simulates to fit and
    check its surfaces (:func:`_screened`), else it runs every variant.

    Parameters
    ----------
    parameters : int
        Toleranced parameters [-].
    """
    return 2 * (screening.FITTED_PER_TERM + 1) * screening.term_count(parameters)


def _speed_step(speeds) -> float:
    """The largest step of the swept speeds [rev/min] (0 for one speed)."""
    speeds = np.asarray(speeds, dtype=float)
    return float(np.max(np.diff(speeds))) if speeds.size > 1 else 0.0


@dataclass(frozen=True, repr=False)
class ToleranceStudy(Result):
    """The variants of a tolerance study (:func:`tolerance_study`): inputs, outputs, percentiles, failures."""

    dataset: object  #: xarray Dataset over ``variant``
    criteria: Criteria
    nominal: dict  #: the nominal spring's outputs
    speeds: np.ndarray  #: [rev/min]
    resumed: int = 0  #: variants read back from chunks on disk
    tolerances: dict = field(default_factory=dict)
    #: False for the spring alone (no float speed), True with a valve train.
    floats: bool = True
    #: A float-speed study: statics and float speed only (:data:`FLOAT_OUTPUTS`).
    float_only: bool = False
    #: Engine turns per cam turn [-] of the engine speeds shown beside the cam's (a
    #: four-stroke's 2; the CLI sets the ``[timing]``'s).
    engine_per_cam: float = 2.0
    #: A spring pack's figures per spring and its clearances (:func:`pack_outputs`), name -> unit.
    pack_outputs: dict = field(default_factory=dict)

    title = "tolerance study"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.dataset.sizes['variant']} variants"

    def failures(self) -> dict:
        """Per criterion the boolean array of the variants that fail it (a refused variant fails
        all), each judged by its rule (:func:`dynamic_rules`, :func:`springdyn.valve.design.criteria.passes`)."""
        ds, c = self.dataset, self.criteria
        refused = ds["refused"].values > 0.5
        out = {}
        for name, (figure, rule, _) in dynamic_rules(c, self.speeds, self.floats, self.float_only).items():
            v = ds[figure].values
            if figure == "float_cam_rpm":  # a float speed above the range is no float within it
                v = np.where(ds["float_in_range"].values > 0.5, v, np.inf)
            out[name] = refused | ~rule(v)
        if c.installed_force_band is not None:
            dev = np.abs(ds["Fset"].values / self.nominal["Fset"] - 1.0)
            out["installed_force"] = refused | ~criteria.passes("installed_force", dev, c.installed_force_band)
        return out

    def limits(self) -> dict:
        """The criteria's limits on each figure of the study, as :meth:`failures` judges them
        (the surge margin's on ``f1`` too, at the top speed).

        Returns
        -------
        dict
            Figure name -> list of ``(value, side, label)``: ``side`` is ``"min"`` (a variant
            passes at or above ``value``) or ``"max"`` (at or below); ``value`` in the figure's
            unit (:data:`OUTPUTS`) [-].
        """
        c, top = self.criteria, float(self.speeds[-1])
        out: dict = {}
        if not self.float_only:
            out["goodman_safety"] = [(c.min_goodman_safety, "min", f"min_goodman_safety {c.min_goodman_safety:g}")]
        if self.floats:
            need = omega_to_rpm(c.min_float_cam_rpm) if c.min_float_cam_rpm is not None else top
            why = "min_float_cam_rpm" if c.min_float_cam_rpm is not None else "no float in the range"
            out["float_cam_rpm"] = [(need, "min", f"{why}: {need:.0f} rpm")]
        if c.no_coil_clash and not self.float_only:
            out["clash_onset_cam_rpm"] = [(top, "min", f"no_coil_clash up to {top:.0f} rpm")]
        if c.max_retainer_force is not None and not self.float_only:
            out["max_retainer_force"] = [
                (c.max_retainer_force, "max", f"max_retainer_force {c.max_retainer_force:.0f} N")
            ]
        if c.min_surge_margin is not None:
            f1 = c.min_surge_margin * top / 60.0  # the cam frequency at the top speed [Hz]
            out["f1"] = [(f1, "min", f"min_surge_margin {c.min_surge_margin:g} at {top:.0f} rpm: {f1:.0f} Hz")]
        if c.installed_force_band is not None:
            band, f0 = c.installed_force_band, float(self.nominal["Fset"])
            out["Fset"] = [
                (f0 * (1.0 - band), "min", f"installed_force_band -{band:.1%}"),
                (f0 * (1.0 + band), "max", f"installed_force_band +{band:.1%}"),
            ]
        return out

    def unsettled(self) -> np.ndarray:
        """The variants that ran and did not settle: a run's periodicity residual above the
        study's ``periodicity_tol`` (boolean array over the variants).  They stay in
        ``variants.nc`` flagged (``settled`` 0) and are left out of the percentiles, the
        histograms and the failing shares (their figures are not a steady state's)."""
        ds = self.dataset
        tol = float(ds.attrs.get("periodicity_tol", PERIODICITY_TOL))
        return (ds["refused"].values < 0.5) & ~(ds["periodicity"].values <= tol)

    def _figures(self) -> list:
        """The outputs that are figures in this study."""
        return [k for k in FIGURES if k in self.dataset and (self.floats or k != "float_cam_rpm")] + list(
            self.pack_outputs
        )

    def _unit(self, name: str) -> str:
        """The unit of an output (:data:`OUTPUTS`, or a pack's figure's)."""
        return OUTPUTS.get(name) or self.pack_outputs[name]

    def _summary(self) -> dict:
        ds = self.dataset
        n = ds.sizes["variant"]
        s = dict(
            variants=int(n),
            study=str(ds.attrs.get("study", "full")),
            method=ds.attrs["method"],
            seed=ds.attrs["seed"],
            resumed_variants=int(self.resumed),
        )
        unsettled = self.unsettled()
        judged = ~unsettled  # the variants the percentiles and shares count (refused ones fail)
        ok = (ds["refused"].values < 0.5) & judged
        tol = float(ds.attrs.get("periodicity_tol", PERIODICITY_TOL))
        s["periodicity_tol"] = tol
        s["unsettled_variants"] = int(unsettled.sum())
        s["max_periodicity_unsettled"] = float(ds["periodicity"].values[unsettled].max()) if unsettled.any() else 0.0
        extremes = int(ok.sum()) < TAIL_VARIANTS  # the outer percentiles are the sample's extremes
        s["tails"] = "sample extremes" if extremes else "percentiles"
        for k in self._figures():
            v = ds[k].values
            s[f"nominal_{k}"] = float(self.nominal[k])
            if ok.any():
                for q, val in zip(PERCENTILES, np.percentile(v[ok], PERCENTILES)):
                    s[f"{k}_p{q:g}"] = float(val)
                if extremes:  # the normal fit's 3 sigma beside them (PERCENTILES[0] is 3 sigma's tail)
                    mean, sd = float(np.mean(v[ok])), float(np.std(v[ok], ddof=1)) if ok.sum() > 1 else 0.0
                    s[f"{k}_p{PERCENTILES[0]:g}_normal"] = mean - 3.0 * sd
                    s[f"{k}_p{PERCENTILES[-1]:g}_normal"] = mean + 3.0 * sd
        if "float_cam_rpm_scan" in self.nominal:
            s["nominal_float_cam_rpm_scan"] = float(self.nominal["float_cam_rpm_scan"])
        s["float_in_range_share"] = float(ds["float_in_range"].values[ok].mean()) if ok.any() else 0.0
        if not self.float_only:
            s["clash_in_range_share"] = float(ds["clash_in_range"].values[ok].mean()) if ok.any() else 0.0
        s["max_periodicity"] = float(ds["periodicity"].values[ok].max()) if ok.any() else 0.0
        fails = {k: f[judged] for k, f in self.failures().items()}
        for k, f in fails.items():
            s[f"fail_share_{k}"] = float(np.mean(f)) if f.size else 0.0
        s["fail_share_any"] = (
            float(np.mean(np.any(np.stack(list(fails.values())), axis=0))) if fails and judged.any() else 0.0
        )
        notes = []
        if unsettled.any():
            notes.append(
                f"{int(unsettled.sum())} of {n} variants did not settle (left out of the percentiles and the failing "
                f"shares): a run's last two revolutions differ by up to {100 * s['max_periodicity_unsettled']:.3g} % "
                f"of Fset, above the study's {100 * tol:g} %; variants.nc keeps them with settled = 0"
            )
        if self.float_only:
            notes.append(
                "a float-speed study: each variant's statics and float speed, searched from the nominal's; "
                "Goodman safety, peak force and coil clash are not computed (run without --float-only)"
            )
        refused = int((ds["refused"].values > 0.5).sum())
        if refused:
            notes.append(f"{refused} variants refused by the model (counted as failing)")
        top = float(self.speeds[-1])
        if self.floats and s["float_in_range_share"] < 1.0:
            notes.append(
                f"the float speed of {1 - s['float_in_range_share']:.0%} of the variants lies above the range: they count "
                f"as {top:g} cam rpm (a lower bound)"
            )
        if self.floats:
            notes.append(
                f"float speeds are resolved to {float(ds.attrs.get('float_resolution_rpm', FLOAT_RESOLUTION)):g} cam rpm "
                "(the final bracket of each search)"
            )
        if self.speeds.size > 1 and not self.float_only:
            step = _speed_step(self.speeds)
            notes.append(f"clash onsets are swept speeds: resolved to {step:g} cam rpm (the step of the swept speeds)")
        if not self.float_only and s["clash_in_range_share"] < 1.0:
            notes.append(f"a clash onset beyond the range counts as its top speed {top:g} cam rpm (no clash within it)")
        if extremes:
            notes.append(
                f"{int(ok.sum())} variants: the 0.135 % and 99.865 % columns are the sample's extremes (a tail that far "
                f"out lies inside a sample of {TAIL_VARIANTS} or more, and is estimated from ten beyond it with some "
                f"{10 * TAIL_VARIANTS}); the normal fit's mean -+ 3 sigma: "
                + "; ".join(
                    f"{k} {s[f'{k}_p0.135_normal']:.4g} to {s[f'{k}_p99.865_normal']:.4g}"
                    for k in self._figures()
                    if f"{k}_p0.135_normal" in s
                )
            )
        notes += self._screen_notes(s)
        if ds.attrs["method"] == "sobol" and n & (n - 1):
            notes.append(f"Sobol points are balanced at powers of 2 (e.g. {2 ** int(math.log2(n) + 1)} variants)")
        s["notes"] = notes
        return s

    def _screen_notes(self, s: dict) -> list:
        """A screened study's figures into the summary ``s`` (the variants simulated, each
        predicted figure's band) and its notes."""
        ds = self.dataset
        n = ds.sizes["variant"]
        if "screen_skipped" in ds.attrs:
            return [
                f"not screened: a screen needs {int(ds.attrs['screen_skipped'])} variants or more to pay "
                "(it simulates some 1/6 of that to fit and check its surfaces); every variant was simulated"
            ]
        if not ds.attrs.get("screened"):
            return []
        s["simulated_variants"] = int(ds["simulated"].values.sum())
        s["float_searched_variants"] = int(ds["float_searched"].values.sum()) if "float_searched" in ds else 0
        bands = []
        for k in SCREENED:
            how = ds.attrs.get(f"screen_{k}")
            if how is None:
                continue
            band = float(ds.attrs[f"screen_band_{k}"])
            s[f"screen_band_{k}"] = band if math.isfinite(band) else -1.0
            if how.startswith("quadratic surface"):
                spread = float(np.ptp(ds[k].values[ds["simulated"].values > 0])) if n else 0.0
                wide = (
                    " (wide: a quarter of its spread or more; its percentiles are the surface's, run without "
                    "--screen for the simulation's)"
                    if band >= 0.25 * spread
                    else ""
                )
                unit = "" if self._unit(k) == "1" else f" {self._unit(k)}"
                bands.append(f"{k} within {band:.3g}{unit}{wide}")
            elif how == "at its bound":
                bands.append(f"{k} at its bound (no fitted or held-out variant left it)")
            else:
                bands.append(f"{k} {how} (every undecided variant simulated)")
        return [
            f"screened: {s['simulated_variants']} of {n} variants simulated ({int(ds.attrs['screen_fitted'])} fitted "
            f"with a quadratic surface of {int(ds.attrs['screen_terms'])} terms per figure, "
            f"{int(ds.attrs['screen_held_out'])} held out to check it, and every variant outside the fitted ones' box "
            "or whose verdict the band leaves open)"
            + (
                f", {s['float_searched_variants']} more had their float speed searched (undecided on it alone)"
                if s["float_searched_variants"]
                else ""
            )
            + "; the others' dynamic figures are the surface's: "
            + "; ".join(bands)
            + ". Fset and f1 are every variant's own; the band is twice the largest leave-one-out or held-out error "
            "(plus the figure's resolution)"
        ]

    def describe(self, source: str = "", chunks: str = "") -> str:
        """The study in words and tables (what ``springdyn valve tolerance`` prints): the sample,
        the percentiles of every figure, the share of variants failing each criterion, the
        largest periodicity residual and the notes.

        Parameters
        ----------
        source : str
            The spring file, for the first line [-].
        chunks : str
            The folder of the chunks on disk, named where variants were read back [-].
        """
        s = self.summary
        speeds = self.speeds
        out = [
            f"{s['variants']} variants ({s['method']}, seed {s['seed']}"
            + (f", {s['resumed_variants']} read back from {chunks or 'the chunks'}" if s["resumed_variants"] else "")
            + f") of {source or 'the spring'} over {self.engine_per_cam * speeds[0]:g}-"
            f"{self.engine_per_cam * speeds[-1]:g} engine rpm ({speeds[0]:g}-{speeds[-1]:g} cam rpm)"
            + (": float speeds only" if self.float_only else "")
        ]
        rows = []
        qs = ("0.135", "2.5", "50", "97.5", "99.865")
        for k in (*FIGURES, *self.pack_outputs):
            if f"{k}_p50" not in s:
                continue
            rows.append((k, self._unit(k), f"{s[f'nominal_{k}']:.4g}", *(f"{s[f'{k}_p{q}']:.4g}" for q in qs)))
            if k.endswith("_cam_rpm"):  # the same speeds on the crankshaft
                e = self.engine_per_cam
                rows.append(
                    (
                        k.replace("_cam_rpm", "_engine_rpm"),
                        "rpm",
                        f"{e * s[f'nominal_{k}']:.4g}",
                        *(f"{e * s[f'{k}_p{q}']:.4g}" for q in qs),
                    )
                )
        tail = " (min)" if s.get("tails") == "sample extremes" else ""
        out.append(
            text_table(
                rows,
                headers=(
                    "output",
                    "unit",
                    "nominal",
                    f"0.135 %{tail}",
                    "2.5 %",
                    "50 %",
                    "97.5 %",
                    "99.865 %" + tail.replace("min", "max"),
                ),
            )
        )
        fails = [(k[len("fail_share_") :], f"{v:.1%}") for k, v in s.items() if k.startswith("fail_share_")]
        out.append(text_table(fails, headers=("criterion", "variants failing")))
        out.append(
            f"periodic steady state: the last two revolutions of every speed run agree within "
            f"{100 * s['max_periodicity']:.3g} % of Fset (largest residual over the "
            + ("settled variants)" if s["unsettled_variants"] else "variants)")
        )
        return "\n".join(out + notes_lines(s))

    def to_xarray(self):
        return self.dataset

    def _plot(self, ax=None):
        from ...core.plotting import plt  # (here: matplotlib costs 0.3 s of start-up)

        ds = self.dataset
        names = self._figures()
        if ax is not None:
            fig, axes = ax.figure, [ax]
            names = names[:1]
        else:
            cols = 3
            rows = math.ceil(len(names) / cols)
            fig, grid = plt.subplots(rows, cols, figsize=(11, 3.2 * rows))
            axes = list(np.ravel(grid))
            for a in axes[len(names) :]:
                a.set_visible(False)
        limits = self.limits()
        for a, k in zip(axes, names):
            v = ds[k].values
            a.hist(v[(ds["refused"].values < 0.5) & ~self.unsettled()], bins=30, color="C0", alpha=0.8)
            a.axvline(self.nominal[k], color="k", lw=1, label="nominal")
            _draw_limits(a, limits.get(k, ()))
            a.set_xlabel(f"{k} [{self._unit(k)}]")
            a.set_ylabel("variants")
            a.yaxis.get_major_locator().set_params(integer=True)
            a.ticklabel_format(axis="x", useOffset=False)
            a.legend(fontsize=7, loc="best")
        if ax is None:
            fig.suptitle("variants per figure; red: the criteria's limits, shaded where a variant fails", fontsize=9)
        fig.tight_layout()
        return fig


def _draw_limits(ax, limits) -> None:
    """The criteria's limits on a histogram: a red dashed line each, its failing side shaded."""
    if not limits:
        return
    values = [v for v, _, _ in limits]
    lo, hi = min(*ax.get_xlim(), *values), max(*ax.get_xlim(), *values)
    least = 0.04 * max(abs(hi), 1.0)  # every variant alike (no clash in the range): a readable span
    if hi - lo < least:
        lo, hi = 0.5 * (lo + hi) - least / 2, 0.5 * (lo + hi) + least / 2
    pad = 0.06 * (hi - lo)  # a limit beside the data stays in view, its failing side visible
    lo, hi = lo - pad, hi + pad
    for value, side, label in limits:
        ax.axvline(value, color="C3", lw=1.5, ls="--", label=label)
        ax.axvspan(*((lo, value) if side == "min" else (value, hi)), color="C3", alpha=0.12, lw=0)
    ax.set_xlim(lo, hi)
