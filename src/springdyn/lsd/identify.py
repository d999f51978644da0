"""Identification of stiffness and damping from rig records, Eqs. (4.1)-(4.22) corrected.

The rig moves the inner ring harmonically at ``omega`` and measures displacements and
reaction forces.  With ``x = a1 cos wt + a2 sin wt`` and ``F = c1 cos wt + c2 sin wt``
(Fourier coefficients over whole periods, Eqs. (4.6), (4.15)) and
``F = K x + C x' + m x''`` (4.1), the complex ratio ``H = F/X = K - m w^2 + j w C``
with the phasors ``X = a1 - j a2``, ``F = c1 - j c2``.  Hence (docs/references.md)::

    K = [a1 (c1 + m w^2 a1) + a2 (c2 + m w^2 a2)] / (a1^2 + a2^2)
    C = (a2 c1 - a1 c2) / (w (a1^2 + a2^2))

The printed (4.19)-(4.22) are wrong (denominator ``a1^2 - a2^2``, signs, ``m w`` for
``m w^2``); :func:`thesis_printed_direct_coefficients` keeps them only to show it.

One circular orbit identifies only ``Kxx + w Cxy`` and ``Cxx - Kxy/w`` (likewise for y):
the cross-coupling caveat.  Two independent excitations (x and y shakes, or a forward
and a backward orbit) give the full 2 x 2 matrices from ``H = F X^-1``.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
from scipy.optimize import minimize_scalar

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError
from ..core.io import read_csv_columns
from ..core.results import Result
from ..core.units import rpm_to_hz
from .model import COEFFICIENT_NAMES
from .rig import RIG_COLUMNS, RigRecord

__all__ = [
    "RIG_COLUMNS",
    "RigData",
    "read_rig_data",
    "estimate_frequency",
    "harmonic_coefficients",
    "direct_coefficients",
    "thesis_printed_direct_coefficients",
    "identify",
    "identify_series",
    "Identification",
    "IdentificationSeries",
    "CROSS_COUPLING_CAVEAT",
]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    mass : float
        Moving mass [kg].
    omega : float
        Vibration frequency [rad/s].
    signal : array_like
        Signal samples [signal unit].
    time : array_like
        Sample times [s].
    """
)

#: Columns of a rig record (CSV header or TDMS channel names).

CROSS_COUPLING_CAVEAT = (
    "one circular orbit cannot separate direct and cross-coupled terms: the reported kxx is "
    "Kxx + w*Cxy and cxx is Cxx - Kxy/w (likewise for y); give a second, independent "
    "excitation (--second) for the full 2 x 2 K and C"
)


class RigData(RigRecord):
    """A measured rig record: time [s], displacements [m], reaction forces [N].

    The same class as :class:`~springdyn.lsd.rig.RigRecord` (one record type for simulated
    and measured data), with the constructor of a measured record: the speed is not known
    until it is identified, the name is the source.
    """

    def __init__(self, time, x, y, fx, fy, source: str = "<data>", row_offset: int = 2):
        super().__init__(
            name=source,
            excitation="measured",
            rpm=float("nan"),
            time=time,
            x=x,
            y=y,
            fx=fx,
            fy=fy,
            source=source,
            row_offset=row_offset,
        )


def _read_tdms(path: Path) -> dict:
    try:
        from nptdms import TdmsFile
    except ImportError:
        raise InputError(
            f"{path}: reading TDMS needs the optional package nptdms (pip install 'springdyn[tdms]')"
        ) from None
    import logging
    import warnings

    try:
        # nptdms warns and logs about a garbage file before it fails: the message below says it once
        nptdms_log = logging.getLogger("nptdms")
        level, nptdms_log.level = nptdms_log.level, logging.CRITICAL
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                tdms = TdmsFile.read(path)
        finally:
            nptdms_log.setLevel(level)
    except Exception as exc:  # nptdms raises several types on bad files
        raise InputError(f"{path}: not a readable TDMS file: {exc}") from None
    found = {}
    for group in tdms.groups():
        for ch in group.channels():
            found.setdefault(ch.name, np.asarray(ch[:], dtype=float))
    return found


def read_rig_data(path) -> RigData:
    """Read a rig record from CSV (``time_s, x_m, y_m, fx_N, fy_N``) or TDMS (same channel names).

    Parameters
    ----------
    path : str or path-like
        The CSV or TDMS file.

    Raises
    ------
    InputError
        Missing file or column, non-numeric or NaN cells, time stamps that do not increase
        or are irregular; the message names the file, the column and the row.
    """
    path = Path(path)
    if path.suffix.lower() == ".tdms":
        if not path.is_file():
            raise InputError(f"{path}: no such file")
        cols, offset = _read_tdms(path), 0
    else:
        cols, offset = read_csv_columns(path), 2
    missing = [c for c in RIG_COLUMNS if c not in cols]
    if missing:
        raise InputError(
            f"{path}: missing column {missing[0]!r} (found: {', '.join(cols) or 'none'}; need {', '.join(RIG_COLUMNS)})"
        )
    return RigData(*(cols[c] for c in RIG_COLUMNS), source=str(path), row_offset=offset)


@_DOCS.fill
def harmonic_coefficients(time, signal, omega):
    """Fourier coefficients ``(s1, s2)`` of ``s ~ s0 + s1 cos wt + s2 sin wt`` [signal units].

    A least-squares projection on ``1, cos wt, sin wt``; over whole periods of uniformly
    sampled data it equals the integrals ``(2/tau) int s cos wt dt`` of Eqs. (4.6), (4.7),
    (4.15), (4.16) and keeps the harmonics of friction out (orthogonality).
    ``signal`` may be 2-D (samples x channels).

    Parameters
    ----------
    {time signal omega}
    """
    t = np.asarray(time, dtype=float)
    A = np.column_stack([np.ones_like(t), np.cos(omega * t), np.sin(omega * t)])
    coef, *_ = np.linalg.lstsq(A, np.asarray(signal, dtype=float), rcond=None)
    return coef[1], coef[2]


@_DOCS.fill
def estimate_frequency(time, signal, source="<data>", column="x_m") -> float:
    """Fundamental frequency of a harmonic record [Hz].

    The peak of the Hann-windowed, zero-padded spectrum, refined by minimising the
    residual of a sine fit.  Raises :class:`InputError` when the record holds no clear
    periodic component or less than one period of it.

    Parameters
    ----------
    {time signal}
    source : str
        Where the record comes from, for messages.
    column : str
        Column name, for messages.
    """
    t = np.asarray(time, dtype=float)
    s = np.asarray(signal, dtype=float) - np.mean(signal)
    if not np.std(s) > 0:
        raise InputError(f"{source}: column {column!r} is constant; no frequency can be found (give --rpm)")
    dt = float(np.median(np.diff(t)))
    nfft = 8 * int(2 ** np.ceil(np.log2(s.size)))
    spec = np.abs(np.fft.rfft(s * np.hanning(s.size), nfft))
    freqs = np.fft.rfftfreq(nfft, dt)
    k = int(np.argmax(spec[1:])) + 1
    f0 = float(freqs[k])
    span = t[-1] - t[0] + dt
    if f0 * span < 1.0 or k < 2:
        raise InputError(
            f"{source}: column {column!r}: no whole period found in {span:.4g} s "
            "(the record is shorter than one cycle of its main component); give --rpm or a longer record"
        )

    def residual(f):
        a, b = harmonic_coefficients(t, s, 2 * np.pi * f)
        return float(np.sum((s - a * np.cos(2 * np.pi * f * t) - b * np.sin(2 * np.pi * f * t)) ** 2))

    df = freqs[1] - freqs[0]
    res = minimize_scalar(residual, bounds=(f0 - 2 * df, f0 + 2 * df), method="bounded", options={"xatol": 1e-10 * f0})
    f = float(res.x)
    explained = 1.0 - residual(f) / float(np.sum(s * s))
    if explained < 0.5:
        raise InputError(
            f"{source}: column {column!r}: no dominant frequency (a sine at {f:.4g} Hz explains only "
            f"{100 * explained:.0f} % of the signal); give --rpm"
        )
    return f


def direct_coefficients(a1, a2, c1, c2, mass, omega):
    """Direct stiffness and damping from one axis' Fourier coefficients (corrected (4.19)-(4.22)).

    ``K = [a1 (c1 + m w^2 a1) + a2 (c2 + m w^2 a2)] / (a1^2 + a2^2)`` [N/m] and
    ``C = (a2 c1 - a1 c2) / (w (a1^2 + a2^2))`` [N s/m] (docs/references.md).

    Parameters
    ----------
    a1, a2 : float
        Displacement cosine/sine coefficients [m].
    c1, c2 : float
        Force cosine/sine coefficients [N].
    mass : float
        Moving mass ``m`` [kg] (its inertia is removed).
    omega : float
        Frequency [rad/s].
    """
    d = a1 * a1 + a2 * a2
    K = (a1 * (c1 + mass * omega**2 * a1) + a2 * (c2 + mass * omega**2 * a2)) / d
    C = (a2 * c1 - a1 * c2) / (omega * d)
    return K, C


@_DOCS.fill
def thesis_printed_direct_coefficients(a1, a2, c1, c2, mass, omega):
    """Eqs. (4.19), (4.21) exactly as printed in the thesis -- WRONG, kept for the record.

    ``K = [a1 w (c1 + a1 w^2 m) - a2 w (c2 + a2 m w)] / ((a1^2 - a2^2) w)`` and
    ``C = [-a2 (c1 + a1 m w^2) + a1 w (c2 + a2 m w)] / ((a1^2 - a2^2) w)``: the
    denominator vanishes when ``|a1| = |a2|`` (a 45 deg phase of the record), ``m w``
    appears where ``m w^2`` belongs, and the result depends on where the record starts.
    Use :func:`direct_coefficients` (docs/references.md).

    Parameters
    ----------
    a1 : float
        Cosine coefficient of the displacement [m].
    a2 : float
        Sine coefficient of the displacement [m].
    c1 : float
        Cosine coefficient of the force [N].
    c2 : float
        Sine coefficient of the force [N].
    {mass omega}
    """
    d = (a1 * a1 - a2 * a2) * omega
    K = (a1 * omega * (c1 + a1 * omega**2 * mass) - a2 * omega * (c2 + a2 * mass * omega)) / d
    C = (-a2 * (c1 + a1 * mass * omega**2) + a1 * omega * (c2 + a2 * mass * omega)) / d
    return K, C


def _phasors(data: RigData, start: int, stop: int, omega):
    """Complex amplitudes ``X = a1 - j a2`` of x, y, fx, fy over samples ``start:stop``."""
    signals = np.column_stack([data.x, data.y, data.fx, data.fy])[start:stop]
    s1, s2 = harmonic_coefficients(data.time[start:stop], signals, omega)
    return s1 - 1j * s2


def _cycles(data: RigData, freq: float):
    """Index ranges of the whole periods in the record (and the window of all of them)."""
    period = 1.0 / freq
    # half a sample of tolerance: a record of exactly n periods must count n
    n = int(np.floor((data.duration + 0.5 / data.sample_rate) / period))
    if n < 1:
        raise InputError(
            f"{data.source}: the record spans {data.duration:.4g} s, less than one whole period "
            f"({period:.4g} s at {freq:.4g} Hz)"
        )
    t = data.time - data.time[0]
    edges = np.searchsorted(t, np.arange(n + 1) * period - 0.5 / data.sample_rate)
    edges[-1] = min(edges[-1], t.size)
    per_cycle = np.diff(edges)
    if np.any(per_cycle < 8):
        raise InputError(f"{data.source}: fewer than 8 samples per period at {freq:.4g} Hz; sample faster")
    return [(edges[k], edges[k + 1]) for k in range(n)], (edges[0], edges[-1])


#: Largest relative difference between a given speed and the fundamental found in the
#: data that identification accepts (a larger one is a wrong speed, not a drift).
RPM_MISMATCH = 0.05


def _frequency(data: RigData, rpm):
    col, sig = ("x_m", data.x) if np.std(data.x) >= np.std(data.y) else ("y_m", data.y)
    if rpm is not None:
        if not (np.isfinite(rpm) and rpm > 0):
            raise InputError(f"rpm = {rpm!r} must be a positive shaft speed")
        try:  # the check needs a fundamental that the record shows (a short record has none)
            found = estimate_frequency(data.time, sig, data.source, col) if np.std(sig) > 0 else None
        except InputError:
            found = None
        if found is not None:
            if abs(rpm_to_hz(rpm) - found) > RPM_MISMATCH * found:
                raise InputError(
                    f"rpm = {rpm:g} does not match the record {data.source}: its fundamental is {found:.4g} Hz "
                    f"({60 * found:.4g} rpm), {100 * abs(rpm_to_hz(rpm) / found - 1):.0f} % away (at most "
                    f"{100 * RPM_MISMATCH:g} % is accepted); leave the speed out to use the one found in the data"
                )
        return rpm_to_hz(rpm)
    return estimate_frequency(data.time, sig, data.source, col)


def _solve_full(P1, P2, mass, omega, sources):
    """Full K, C from two excitations: ``H = F X^-1``, ``K = Re H + m w^2``, ``C = Im H / w``."""
    X = np.array([[P1[0], P2[0]], [P1[1], P2[1]]])
    F = np.array([[P1[2], P2[2]], [P1[3], P2[3]]])
    cond = np.linalg.cond(X)
    if not np.isfinite(cond) or cond > 1e3:
        raise InputError(
            f"{sources[0]} and {sources[1]}: the two excitations are not independent "
            f"(condition number {cond:.3g} of the displacement matrix); use x and y shakes or "
            "forward and backward orbits"
        )
    H = F @ np.linalg.inv(X)
    return H.real + mass * omega**2 * np.eye(2), H.imag / omega


def _solve_single(P, mass, omega):
    """K, C entries available from one excitation (NaN where unknown) and the mode."""
    K = np.full((2, 2), np.nan)
    C = np.full((2, 2), np.nan)
    X, Y, Fx, Fy = P
    ax, ay = abs(X), abs(Y)
    if ay < 0.02 * ax:
        mode, axes = "x", [(0, X, Fx, Fy)]
    elif ax < 0.02 * ay:
        mode, axes = "y", [(1, Y, Fy, Fx)]
    else:
        mode, axes = "orbit", [(0, X, Fx, None), (1, Y, Fy, None)]
    for i, U, Fd, Fc in axes:
        H = Fd / U
        K[i, i], C[i, i] = H.real + mass * omega**2, H.imag / omega
        if Fc is not None:  # single-axis shake: the cross terms are exact too
            Hc = Fc / U
            K[1 - i, i], C[1 - i, i] = Hc.real, Hc.imag / omega
    return K, C, mode


def identify(
    data: RigData, second: RigData | None = None, *, mass: float = 0.0, rpm: float | None = None
) -> Identification:
    """Identify K and C from one or two rig records at one speed.

    Parameters
    ----------
    data : RigData
        First record.
    second : RigData, optional
        Second, independent excitation at the same speed: gives the full 2 x 2 matrices.
    mass : float
        Moving mass whose inertia is removed [kg].
    rpm : float, optional
        Shaft speed [rev/min]; by default the frequency is found in the data.

    Returns
    -------
    Identification
        Coefficients and their uncertainty (standard error of the mean over the whole
        periods of the record, from the cycle-to-cycle scatter); confidence intervals
        with the Student-t factor from :meth:`Identification.intervals`.
    """
    if not (np.isfinite(mass) and mass >= 0):
        raise InputError(f"mass = {mass!r} kg must be zero or positive")
    freq = _frequency(data, rpm)
    if second is not None:
        f2 = _frequency(second, rpm)
        if abs(f2 - freq) > 0.01 * freq:
            raise InputError(
                f"{data.source} ({freq:.4g} Hz) and {second.source} ({f2:.4g} Hz): the two excitations "
                "must be at the same frequency"
            )
    omega = 2 * np.pi * freq
    records = [data] if second is None else [data, second]
    windows = [_cycles(r, freq) for r in records]
    for r, w in zip(records, windows):
        p = _phasors(r, w[1][0], w[1][1], omega)
        scale = max(float(np.max(np.abs(np.column_stack([r.x, r.y])))), np.finfo(float).tiny)
        if not np.max(np.abs(p[:2])) > 1e-9 * scale or not np.max(np.abs(p[:2])) > 0:
            raise InputError(
                f"{r.source}: the displacements have no component at {freq:.4g} Hz: there is "
                "nothing to identify (is the record all zeros, or the speed wrong?)"
            )

    def solve(slices):
        P = [_phasors(r, a, b, omega) for r, (a, b) in zip(records, slices)]
        if second is None:
            return _solve_single(P[0], mass, omega)
        K, C = _solve_full(P[0], P[1], mass, omega, [r.source for r in records])
        return K, C, "two excitations"

    K, C, mode = solve([w[1] for w in windows])
    n = min(len(w[0]) for w in windows)
    per = [solve([w[0][k] for w in windows]) for k in range(n)] if n >= 2 else []
    if per:
        Ks, Cs = np.array([p[0] for p in per]), np.array([p[1] for p in per])
        K_unc, C_unc = Ks.std(axis=0, ddof=1) / np.sqrt(n), Cs.std(axis=0, ddof=1) / np.sqrt(n)
    else:
        K_unc = np.full((2, 2), np.nan)
        C_unc = np.full((2, 2), np.nan)
    return Identification(
        rpm=60.0 * freq,
        frequency=freq,
        K=K,
        C=C,
        K_uncertainty=K_unc,
        C_uncertainty=C_unc,
        mass=float(mass),
        cycles=n,
        mode=mode,
        sources=[r.source for r in records],
        caveat=CROSS_COUPLING_CAVEAT if mode == "orbit" else "",
    )


@dataclasses.dataclass
class Identification:
    """Identified coefficients at one speed.

    ``K``, ``C`` are 2 x 2 ``[[xx, xy], [yx, yy]]`` [N/m], [N s/m]; entries one record
    cannot give are NaN.  ``mode`` is ``"orbit"``, ``"x"``, ``"y"`` or ``"two excitations"``.
    """

    rpm: float
    frequency: float
    K: np.ndarray
    C: np.ndarray
    K_uncertainty: np.ndarray
    C_uncertainty: np.ndarray
    mass: float
    cycles: int
    mode: str
    sources: list
    caveat: str = ""

    #: Confidence level of the intervals ``..._ci`` [-].
    confidence = 0.95

    def interval_factor(self, confidence: float | None = None) -> float:
        """Student-t factor ``t_(1 - alpha/2, n - 1)`` turning a standard error into a half-interval [-].

        The uncertainties are standard errors of the mean over ``n = cycles`` periods, whose
        scatter is estimated from the same ``n`` periods: the interval needs Student's t with
        ``n - 1`` degrees of freedom, not the normal quantile (1.96 for 95 %), which is 15 %
        too narrow with 10 periods and 38 % with 4.  NaN with fewer than 2 periods.

        Parameters
        ----------
        confidence : float, optional
            Confidence level in (0, 1) [-]; default :attr:`confidence` (0.95).
        """
        from scipy import stats

        level = self.confidence if confidence is None else float(confidence)
        if not 0.0 < level < 1.0:
            raise InputError(f"confidence = {confidence!r} must lie between 0 and 1")
        if self.cycles < 2:
            return float("nan")
        return float(stats.t.ppf(0.5 + level / 2.0, self.cycles - 1))

    def intervals(self, confidence: float | None = None):
        """Half-widths of the confidence intervals of K and C, ``t * uncertainty`` [N/m], [N s/m].

        Parameters
        ----------
        confidence : float, optional
            Confidence level in (0, 1) [-]; default 0.95.
        """
        t = self.interval_factor(confidence)
        return t * self.K_uncertainty, t * self.C_uncertainty

    def to_dict(self) -> dict:
        """JSON-ready dict: ``kxx_N_per_m`` ... with ``_uncertainty`` and ``_ci`` twins (known entries only).

        ``_uncertainty`` is the standard error of the mean over the periods; ``_ci`` the
        95 % confidence interval ``[low, high]`` with the Student-t factor of
        :meth:`interval_factor`.  An uncertainty that the record cannot give (a single
        period) is ``None``, and ``notes`` says why; entries the excitation cannot separate
        are left out.
        """
        d = {
            "rpm": self.rpm,
            "frequency_Hz": self.frequency,
            "mode": self.mode,
            "cycles": self.cycles,
            "mass_kg": self.mass,
            "sources": list(self.sources),
        }
        t = self.interval_factor()
        if np.isfinite(t):
            d["interval_factor"] = t
        notes = []
        idx = [(0, 0), (0, 1), (1, 0), (1, 1)]
        for names, value, unc, unit in (
            (COEFFICIENT_NAMES[:4], self.K, self.K_uncertainty, "N_per_m"),
            (COEFFICIENT_NAMES[4:], self.C, self.C_uncertainty, "Ns_per_m"),
        ):
            for name, (i, j) in zip(names, idx):
                if np.isfinite(value[i, j]):
                    d[f"{name}_{unit}"] = float(value[i, j])
                    u = float(unc[i, j])
                    d[f"{name}_{unit}_uncertainty"] = u if np.isfinite(u) else None
                    v = float(value[i, j])
                    d[f"{name}_{unit}_ci"] = [v - t * u, v + t * u] if np.isfinite(u * t) else None
                    if not np.isfinite(u) and not notes:
                        notes.append(
                            "uncertainties need at least 2 periods of the record (they come from the "
                            "scatter between periods)"
                        )
        if any(not np.isfinite(v) for v in np.concatenate([self.K.ravel(), self.C.ravel()])):
            notes.append(
                "one excitation cannot separate the direct and cross-coupled terms: the entries it "
                "cannot give are left out (record a second, independent excitation)"
            )
        if self.caveat:
            d["caveat"] = self.caveat
        if notes:
            d["notes"] = notes
        return d


@dataclasses.dataclass(repr=False)
class IdentificationSeries(Result):
    """Identifications at several speeds (one :class:`Identification` each).

    The CSV holds the entries known at every speed (with their uncertainties); entries
    one excitation cannot separate, or uncertainties one period cannot give, are left
    out and the summary's ``notes`` say why.
    """

    items: list
    name: str = "identified"

    title = "identified leaf spring damper coefficients"

    def _repr_caption(self) -> str:
        return f"{self.name}, {len(self.items)} speeds"

    def _summary(self) -> dict:
        s = dict(
            name=self.name,
            speeds=len(self.items),
            rpm_min=float(self.rpm.min()),
            rpm_max=float(self.rpm.max()),
            modes=", ".join(sorted({it.mode for it in self.items})),
        )
        cols = self.columns()
        known = [k for k, v in cols.items() if k != "rpm" and not k.endswith("_uncertainty") and np.all(np.isfinite(v))]
        s["known_coefficients"] = ", ".join(known)
        notes = [d for it in self.items for d in it.to_dict().get("notes", [])]
        if notes:
            s["notes"] = sorted(set(notes))
        return s

    @property
    def rpm(self) -> np.ndarray:
        return np.array([it.rpm for it in self.items])

    def columns(self) -> dict:
        """SI columns for CSV: rpm and every coefficient with its uncertainty (NaN if unknown)."""
        out = {"rpm": self.rpm}
        idx = [(0, 0), (0, 1), (1, 0), (1, 1)]
        for name, (i, j) in zip(COEFFICIENT_NAMES[:4], idx):
            out[f"{name}_N_per_m"] = np.array([it.K[i, j] for it in self.items])
            out[f"{name}_N_per_m_uncertainty"] = np.array([it.K_uncertainty[i, j] for it in self.items])
        for name, (i, j) in zip(COEFFICIENT_NAMES[4:], idx):
            out[f"{name}_Ns_per_m"] = np.array([it.C[i, j] for it in self.items])
            out[f"{name}_Ns_per_m_uncertainty"] = np.array([it.C_uncertainty[i, j] for it in self.items])
        return out

    def _csv_dataset(self):
        import xarray as xr

        cols = {k: v for k, v in self.columns().items() if np.all(np.isfinite(v))}
        rpm = cols.pop("rpm")
        return xr.Dataset(
            {k: ("rpm", v, {"units": ""}) for k, v in cols.items()}, coords={"rpm": ("rpm", rpm, {"units": "rpm"})}
        )

    def to_xarray(self):
        import xarray as xr

        K = np.array([it.K for it in self.items])
        C = np.array([it.C for it in self.items])
        dims = ("rpm", "row", "col")
        return xr.Dataset(
            {
                "K": (dims, K, {"units": "N/m"}),
                "C": (dims, C, {"units": "N*s/m"}),
                "K_uncertainty": (dims, np.array([it.K_uncertainty for it in self.items]), {"units": "N/m"}),
                "C_uncertainty": (dims, np.array([it.C_uncertainty for it in self.items]), {"units": "N*s/m"}),
            },
            coords={"rpm": ("rpm", self.rpm, {"units": "rpm"}), "row": ["x", "y"], "col": ["x", "y"]},
            attrs={"name": self.name},
        )

    def plot_on(self, ax_k, ax_c):
        """Draw the identified coefficients as markers with 95 % (Student-t) error bars on two axes.

        Parameters
        ----------
        ax_k, ax_c : matplotlib Axes
            Axes of the stiffnesses and of the damping coefficients [-].
        """
        markers = {"xx": "o", "yy": "s", "xy": "^", "yx": "v"}
        for key, (i, j) in {"xx": (0, 0), "yy": (1, 1), "xy": (0, 1), "yx": (1, 0)}.items():
            k = np.array([it.K[i, j] for it in self.items])
            if np.all(np.isnan(k)):
                continue
            ku = np.nan_to_num(np.array([it.intervals()[0][i, j] for it in self.items]))
            c = np.array([it.C[i, j] for it in self.items])
            cu = np.nan_to_num(np.array([it.intervals()[1][i, j] for it in self.items]))
            ax_k.errorbar(
                self.rpm, k / 1e3, yerr=ku / 1e3, fmt=markers[key], ms=5, capsize=2, label=f"K{key} {self.name}"
            )
            ax_c.errorbar(self.rpm, c, yerr=cu, fmt=markers[key], ms=5, capsize=2, label=f"C{key} {self.name}")

    def _plot(self, ax=None, model=None):
        """Coefficients vs speed; with ``model`` (LSDCoefficients) the model curves too."""
        if model is not None:
            return model._plot(ax=ax, identified=self)
        if ax is not None:
            for key, (i, j) in {"xx": (0, 0), "yy": (1, 1)}.items():
                k = np.array([it.K[i, j] for it in self.items])
                if np.all(np.isfinite(k)):
                    ax.plot(self.rpm, k / 1e3, "o", label=f"K{key} {self.name}")
            ax.set_xlabel("shaft speed [rpm]")
            ax.set_ylabel("stiffness [N/mm]")
            return ax.figure
        from .plots import coefficients_figure

        return coefficients_figure(f"{self.name}: identified coefficients", self.plot_on, None)


@_DOCS.fill
def identify_series(records, seconds=None, *, mass=0.0, rpms=None, name="identified") -> IdentificationSeries:
    """Identify at several speeds at once.

    Parameters
    ----------
    records : list of RigData
        One record per speed.
    seconds : list of RigData, optional
        The matching second excitations (same order).
    {mass}
    rpms : list of float, optional
        Speeds [rev/min]; by default found in the data.
    name : str
        Label of the series in plots and outputs.
    """
    records = list(records)
    if seconds is not None and len(seconds) != len(records):
        raise InputError(f"{len(records)} first records but {len(seconds)} second records; pair them one to one")
    if rpms is not None and len(rpms) != len(records):
        raise InputError(f"{len(records)} records but {len(rpms)} speeds; give one speed per record")
    items = [
        identify(r, None if seconds is None else seconds[k], mass=mass, rpm=None if rpms is None else rpms[k])
        for k, r in enumerate(records)
    ]
    items.sort(key=lambda it: it.rpm)
    return IdentificationSeries(items, name=name)
