"""The leaf spring damper model: stiffness and damping coefficients vs speed and amplitude."""

from __future__ import annotations

import dataclasses
import warnings
from functools import cached_property

import numpy as np

from ..core.errors import InputError
from ..core.results import Result
from ..core.units import omega_to_rpm, rpm_to_omega
from . import damping, leafpack, stiffness
from .parameters import LSDParameters

__all__ = ["LSDModel", "LSDCoefficients", "COEFFICIENT_NAMES"]

#: The eight coefficients in ROSS order, with their SI unit suffix.
COEFFICIENT_NAMES = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")

#: Smallest vibration amplitude [m] of the coefficients: 1 nm, below any measurable damper
#: vibration (the friction equivalents grow as 1 / amplitude).
MIN_AMPLITUDE = 1e-9


class LSDModel:
    """Linearised stiffness and damping of a leaf spring damper (thesis, Chapters 2-3).

    Parameters
    ----------
    params : LSDParameters
        The damper.

    Examples
    --------
    >>> m = LSDModel(LSDParameters.example("C"))
    >>> round(m.pack_stiffness / 1e3, 1)   # k_s [N/mm], docs/references.md
    106.9
    """

    def __init__(self, params: LSDParameters):
        if not isinstance(params, LSDParameters):
            raise InputError(f"LSDModel needs LSDParameters, got {type(params).__name__}")
        self.params = params

    # ---------------------------------------------------------------- leaf pack
    @cached_property
    def flexural_rigidities(self) -> np.ndarray:
        """``E I_i`` of each leaf [N m^2]."""
        p = self.params
        return p.youngs_modulus * leafpack.second_moment_of_area(p.leaf_width, np.asarray(p.leaf_thicknesses))

    @cached_property
    def load_ratios(self) -> np.ndarray:
        """``phi_i = P_i / P_1``, Eq. (2.7) [-]."""
        return leafpack.load_ratios(self.params.leaf_lengths, self.flexural_rigidities)

    @cached_property
    def deflection_ratios(self) -> np.ndarray:
        """``delta_i / delta_1`` [-]."""
        return leafpack.tip_deflection_ratios(self.params.leaf_lengths, self.flexural_rigidities)

    @cached_property
    def stiffness_factor(self) -> float:
        """``xi`` of Eq. (2.9) [-]."""
        return leafpack.stiffness_factor(self.params.leaf_lengths, self.flexural_rigidities)

    @cached_property
    def pack_stiffness_unclamped(self) -> float:
        """``k_p`` of Eq. (2.8) [N/m]; with ``leaf_bending = "beam"`` without the ``1/(1 - nu^2)``."""
        nu = self.params.poisson_ratio if self.params.leaf_bending == "plate" else 0.0
        return leafpack.pack_stiffness(self.params.leaf_lengths, self.flexural_rigidities, nu)

    @cached_property
    def pack_stiffness(self) -> float:
        """``k_s`` of Eq. (2.10) [N/m]."""
        p = self.params
        return leafpack.clamped_pack_stiffness(self.pack_stiffness_unclamped, p.clamp_overhang, p.leaf_lengths[0])

    @cached_property
    def slip_factor(self) -> float:
        """Bracket ``S`` of Eq. (2.28) [-]."""
        p = self.params
        return damping.interleaf_slip_factor(
            self.load_ratios, self.deflection_ratios, p.leaf_thicknesses, p.leaf_lengths
        )

    # ---------------------------------------------------------------- layout
    @cached_property
    def angles(self) -> np.ndarray:
        """Pack angles [rad]."""
        p = self.params
        if p.pack_angles:
            return np.asarray(p.pack_angles, dtype=float)
        return stiffness.equally_spaced_angles(p.packs, p.first_pack_angle)

    @cached_property
    def stiffness_matrix(self) -> np.ndarray:
        """``K`` (2 x 2), Eq. (3.4) [N/m]."""
        return stiffness.stiffness_matrix(self.pack_stiffness, self.angles)

    # ---------------------------------------------------------------- oil
    @cached_property
    def volume_matrix(self) -> np.ndarray:
        """``B`` (N x 2), Eq. (2.15) [m^2]."""
        p = self.params
        return damping.chamber_volume_matrix(self.angles, p.ring_width, p.ring_outer_diameter, p.leaf_lengths[0])

    @cached_property
    def conductance(self) -> float:
        """``C_D`` between neighbouring chambers [m^3/(s Pa)]."""
        p = self.params
        return damping.boundary_conductance(
            p.passage_width,
            p.passage_clearance,
            p.passage_length,
            p.oil_viscosity,
            passages=p.passages_per_boundary,
            model=p.conductance_model,
            leakage_factor=p.leakage_factor,
        )

    @cached_property
    def viscous_damping(self) -> np.ndarray:
        """``C_visc = B^T G^+ B`` (2 x 2) [N s/m], independent of frequency."""
        return damping.viscous_damping_matrix(self.volume_matrix, self.conductance)

    # ---------------------------------------------------------------- damping
    def loss_factor(self, amplitude: float, normal_load: str | None = None) -> float:
        """Inter-leaf loss factor ``zeta`` at vibration amplitude ``amplitude`` [m], Eq. (2.28).

        Parameters
        ----------
        amplitude : float
            Vibration amplitude [m].
        normal_load : str, optional
            How the leaves are pressed together [-] (default: the definition's).
        """
        p = self.params
        return damping.leaf_loss_factor(
            p.leaf_friction, p.preload, amplitude, self.slip_factor, normal_load or p.leaf_normal_load
        )

    def damping_matrix(self, omega, amplitude: float, motion: str = "linear", parts: bool = False):
        """Total damping ``C = C_f I + C_h + C_visc`` [N s/m], shape ``omega.shape + (2, 2)``.

        Parameters
        ----------
        omega : float or array
            Vibration frequency [rad/s].
        amplitude : float
            Vibration amplitude [m] (pack deflection amplitude ``delta_1``).
        motion : {"linear", "circular"}
            Motion used for the O-ring Coulomb equivalent (:func:`damping.coulomb_equivalent_damping`).
        parts : bool
            Also return the three parts as a dict.
        """
        p = self.params
        omega = np.asarray(omega, dtype=float)
        if np.any(omega <= 0):
            raise InputError(f"omega = {omega.tolist()} rad/s must be positive for the damping coefficients")
        cf = damping.coulomb_equivalent_damping(p.oring_friction, p.oring_normal_force, omega, amplitude, motion)
        c_f = cf[..., None, None] * np.eye(2)
        c_h = damping.hysteresis_damping_matrix(self.loss_factor(amplitude), self.pack_stiffness, omega, self.angles)
        c_v = np.broadcast_to(self.viscous_damping, omega.shape + (2, 2))
        total = c_f + c_h + c_v
        if parts:
            return total, {"oring": c_f, "hysteresis": c_h, "viscous": np.array(c_v)}
        return total

    def coefficients(
        self, rpm=None, amplitude: float = 50e-6, motion: str = "linear", *, omega=None
    ) -> LSDCoefficients:
        """K and C at the shaft speeds ``rpm`` [rev/min] (or vibration frequencies ``omega`` [rad/s]).

        On the thesis' rig the ring vibrates once per shaft revolution, so the vibration
        frequency is ``omega = 2 pi rpm / 60``; give exactly one of ``rpm`` and ``omega``.
        Warns (:class:`~springdyn.lsd.stiffness.PreloadExceededWarning`) when the
        amplitude exceeds the preload.

        Parameters
        ----------
        rpm : float or array_like, optional
            Speeds [rev/min].
        amplitude : float
            Vibration amplitude [m] of the friction equivalents.
        motion : {"linear", "circular"}
            Motion for the O-ring Coulomb equivalent.
        omega : float or array_like, optional
            Vibration frequencies [rad/s] instead of ``rpm``.
        """
        rpm, w = _speeds(rpm, omega)
        if isinstance(amplitude, bool) or not isinstance(amplitude, (int, float, np.integer, np.floating)):
            raise InputError(f"amplitude = {amplitude!r} must be a vibration amplitude in m, e.g. 50e-6")
        if not (np.isfinite(amplitude) and amplitude >= MIN_AMPLITUDE):
            raise InputError(
                f"amplitude = {amplitude!r} m must be at least {MIN_AMPLITUDE:g} m: the friction equivalents "
                "grow as 1 / amplitude (a vanishing amplitude gives infinite damping)"
            )
        if amplitude > 0.01:
            warnings.warn(
                f"amplitude = {amplitude:g} m is far larger than any damper vibration (1 um to 1 mm): "
                # a bare number is read in m (50 -> 50 m: meant 50 um); a length in mm is 1000
                # times too large (50 mm -> 0.05 m: meant 50 um)
                f"did you mean {amplitude if amplitude >= 1 else amplitude * 1e3:g} um?",
                stacklevel=2,
            )
        unloads = stiffness.warn_if_unloading(amplitude, self.params.preload)
        C, parts = self.damping_matrix(w, amplitude, motion, parts=True)
        K = np.broadcast_to(self.stiffness_matrix, C.shape).copy()
        return LSDCoefficients(
            name=self.params.name,
            rpm=rpm,
            amplitude=float(amplitude),
            K=K,
            C=C,
            parts=parts,
            pack_stiffness=self.pack_stiffness,
            load_ratios=self.load_ratios.copy(),
            preload_exceeded=unloads,
        )

    def equivalent_coefficients(
        self, rpm=None, amplitude: float = 50e-6, motion: str = "linear", *, omega=None, samples: int = 2048
    ) -> LSDCoefficients:
        """K and C of the nonlinear force laws at this amplitude (describing function).

        Unlike :meth:`coefficients` (the closed forms of Chapters 2-3), every mechanism is
        evaluated with the force laws of the time-domain rig (lift-off of the packs,
        inter-leaf friction on the instantaneous pack load, each pack at its own deflection
        amplitude, O-ring friction, oil) along a harmonic motion, and the first harmonic
        of the force gives the coefficients (:mod:`springdyn.lsd.equivalent`).  This is
        what a rig identifies at that amplitude.

        Parameters
        ----------
        rpm : float or array_like, optional
            Speeds [rev/min] (one vibration per revolution).
        amplitude : float
            Shake amplitude or orbit radius [m].
        motion : {"linear", "circular"}
            x and y shakes, or forward and backward orbits.
        omega : float or array_like, optional
            Vibration frequencies [rad/s] instead of ``rpm``.
        samples : int
            Quadrature points per period [-].
        """
        from .equivalent import equivalent_matrices

        _, w = _speeds(rpm, omega)
        mats = [equivalent_matrices(self, wi, amplitude, motion, samples) for wi in w]
        K = np.array([sum(m[k][0] for k in m) for m in mats])
        C = np.array([sum(m[k][1] for k in m) for m in mats])
        parts = {
            "oring": np.array([m["oring_friction"][1] for m in mats]),
            "hysteresis": np.array([m["leaf_friction"][1] for m in mats]),
            "viscous": np.array([m["oil"][1] for m in mats]),
        }
        return LSDCoefficients(
            name=self.params.name,
            rpm=omega_to_rpm(w),
            amplitude=float(amplitude),
            K=K,
            C=C,
            parts=parts,
            pack_stiffness=self.pack_stiffness,
            load_ratios=self.load_ratios.copy(),
            preload_exceeded=bool(amplitude > self.params.preload),
            method="describing function",
        )

    def to_ross(
        self,
        n: int,
        frequencies=None,
        amplitude: float = 50e-6,
        motion: str = "linear",
        *,
        rpm_range=(0.0, 20000.0),
        points: int = 40,
        outside: str = "raise",
        omega=None,
        **kwargs,
    ):
        """A ``ross.BearingElement`` with the eight coefficients tabulated over ``rpm_range``.

        The table is dense (``points`` >= 30, log-spaced) and the element **never
        extrapolates**: asked beyond ``rpm_range`` it raises an ``InputError``
        (``outside="raise"``, the default) or holds the end values (``outside="clamp"``).
        The table's ``frequency`` is the vibration frequency [rad/s]; ROSS 2.3 evaluates it
        at the spin speed, which is right for unbalance (synchronous) responses; for modal
        analysis see :func:`springdyn.lsd.rotordynamics.whirl_consistent_mode`.

        Parameters
        ----------
        n : int
            Rotor node of the damper [-].
        frequencies : array_like, optional
            Deprecated alias of ``omega`` [rad/s].
        amplitude : float
            Vibration amplitude [m] for the amplitude-dependent friction terms.
        motion : {"linear", "circular"}
            Motion for the O-ring Coulomb equivalent.
        rpm_range : tuple of float
            ``(start, stop)`` vibration frequencies [rev/min]; default 0 to 20 000 rpm
            (below 60 rpm the 60 rpm values are used).
        points : int
            Table points [-], at least 30.
        outside : {"raise", "clamp"}
            Beyond the range: raise (default) or clamp.
        omega : array_like, optional
            Explicit table [rad/s] instead of ``rpm_range``.
        **kwargs
            Passed to ``BearingElement`` (``tag``, ``n_link``, ...).

        Notes
        -----
        Needs the optional extra ``springdyn[ross]`` (``ross-rotordynamics``).
        """
        from .rotordynamics import bearing_element

        return bearing_element(
            self,
            n,
            frequencies,
            amplitude=amplitude,
            motion=motion,
            rpm_range=rpm_range,
            points=points,
            outside=outside,
            omega=omega,
            **kwargs,
        )


def _names(prefix_k: bool, unit: str) -> str:
    names = COEFFICIENT_NAMES[:4] if prefix_k else COEFFICIENT_NAMES[4:]
    return ",".join(f"{n}_{unit}" for n in names)


@dataclasses.dataclass(repr=False)
class LSDCoefficients(Result):
    """Stiffness and damping coefficients of a leaf spring damper vs shaft speed.

    Attributes
    ----------
    rpm : numpy.ndarray
        Shaft speed [rev/min] (vibration frequency ``rpm/60`` Hz).
    K, C : numpy.ndarray
        Shape ``(len(rpm), 2, 2)`` [N/m], [N s/m], ``[[xx, xy], [yx, yy]]``.
    parts : dict
        Damping split into ``oring``, ``hysteresis`` and ``viscous`` [N s/m].
    """

    name: str
    rpm: np.ndarray
    amplitude: float
    K: np.ndarray
    C: np.ndarray
    parts: dict
    pack_stiffness: float
    load_ratios: np.ndarray
    preload_exceeded: bool = False
    method: str = "closed form"

    title = "leaf spring damper coefficients"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.name}, {self.rpm.size} speeds, {self.amplitude * 1e6:.3g} um amplitude"

    def _summary(self) -> dict:
        s = dict(
            name=self.name,
            speeds=int(self.rpm.size),
            rpm_min=float(self.rpm.min()),
            rpm_max=float(self.rpm.max()),
            amplitude_m=float(self.amplitude),
            pack_stiffness_N_per_m=float(self.pack_stiffness),
            kxx_min_N_per_m=float(self.K[:, 0, 0].min()),
            kxx_max_N_per_m=float(self.K[:, 0, 0].max()),
            cxx_min_N_s_per_m=float(self.C[:, 0, 0].min()),
            cxx_max_N_s_per_m=float(self.C[:, 0, 0].max()),
            preload_exceeded=bool(self.preload_exceeded),
            model=self.method,
        )
        return s

    @property
    def omega(self) -> np.ndarray:
        return rpm_to_omega(self.rpm)

    def columns(self) -> dict:
        """SI columns with units in the names (CSV/JSON)."""
        out = {"rpm": self.rpm}
        for k, (i, j) in zip(COEFFICIENT_NAMES[:4], [(0, 0), (0, 1), (1, 0), (1, 1)]):
            out[f"{k}_N_per_m"] = self.K[:, i, j]
        for k, (i, j) in zip(COEFFICIENT_NAMES[4:], [(0, 0), (0, 1), (1, 0), (1, 1)]):
            out[f"{k}_Ns_per_m"] = self.C[:, i, j]
        return out

    def to_dict(self) -> dict:
        """JSON-ready dict: the columns as lists plus pack data and the amplitude."""
        d = {k: np.asarray(v).tolist() for k, v in self.columns().items()}
        d["pack_stiffness_N_per_m"] = self.pack_stiffness
        d["load_ratios"] = self.load_ratios.tolist()
        d["amplitude_m"] = self.amplitude
        d["preload_exceeded"] = self.preload_exceeded
        return d

    def to_xarray(self):
        """``xarray.Dataset`` with ``K`` and ``C`` over ``(rpm, row, col)`` (the CSV: one column per entry)."""
        import xarray as xr

        coords = {"rpm": ("rpm", self.rpm, {"units": "rpm"}), "row": ["x", "y"], "col": ["x", "y"]}
        ds = xr.Dataset(
            {
                "K": (("rpm", "row", "col"), self.K, {"units": "N/m", "csv_columns": _names(True, "N_per_m")}),
                "C": (("rpm", "row", "col"), self.C, {"units": "N*s/m", "csv_columns": _names(False, "Ns_per_m")}),
                **{
                    f"C_{k}": (("rpm", "row", "col"), np.asarray(v), {"units": "N*s/m", "csv": "no"})
                    for k, v in self.parts.items()
                },
            },
            coords=coords,
            attrs={"name": self.name, "amplitude_m": self.amplitude, "pack_stiffness_N_per_m": self.pack_stiffness},
        )
        return ds

    def _plot(self, ax=None, identified=None):
        """Coefficients vs speed like Figs. 5.9/5.10 and 5.27/5.28 of the thesis.

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Draw the stiffness panel only, into these axes.
        identified : IdentificationSeries, optional
            Identified coefficients (:mod:`springdyn.lsd.identify`) drawn as markers
            with error bars on the same axes.
        """
        from .plots import coefficients_figure

        styles = {"xx": "-", "yy": "--", "xy": ":", "yx": "-."}

        def draw(ax_k, ax_c):
            for key, (i, j) in {"xx": (0, 0), "yy": (1, 1), "xy": (0, 1), "yx": (1, 0)}.items():
                ax_k.plot(self.rpm, self.K[:, i, j] / 1e3, styles[key], label=f"K{key} model")
                ax_c.plot(self.rpm, self.C[:, i, j], styles[key], label=f"C{key} model")
            if identified is not None:
                identified.plot_on(ax_k, ax_c)

        if ax is not None:
            for key, (i, j) in {"xx": (0, 0), "yy": (1, 1)}.items():
                ax.plot(self.rpm, self.K[:, i, j] / 1e3, styles[key], label=f"K{key} model")
            ax.set_xlabel("shaft speed [rpm]")
            ax.set_ylabel("stiffness [N/mm]")
            ax.legend(fontsize=8)
            return ax.figure
        return coefficients_figure(
            f"{self.name}: coefficients at {self.amplitude * 1e6:.3g} um amplitude",
            draw,
            None,
            damping_linthresh=max(1.0, float(np.max(np.abs(self.C))) * 1e-3),
        )


def _speeds(rpm, omega) -> tuple:
    """Speeds given as ``rpm`` [rev/min] or ``omega`` [rad/s] (exactly one): both, as arrays."""
    if (rpm is None) == (omega is None):
        raise InputError("give the speeds as rpm [rev/min] or as omega [rad/s], exactly one of them")
    name = "rpm" if omega is None else "omega"
    values = np.atleast_1d(np.asarray(rpm if omega is None else omega, dtype=float))
    if values.ndim != 1 or np.any(~np.isfinite(values)) or np.any(values <= 0):
        raise InputError(f"{name} = {values.tolist()} must be positive speeds")
    if omega is None:
        return values, rpm_to_omega(values)
    return omega_to_rpm(values), values
