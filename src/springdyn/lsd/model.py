"""The leaf spring damper model: stiffness and damping coefficients vs speed and amplitude."""

from __future__ import annotations

import dataclasses
import warnings
from functools import cached_property

import numpy as np

from ..core.docstrings import ParameterDocs
from ..core.errors import InputError
from ..core.results import Result
from ..core.units import omega_to_rpm, rpm_to_omega
from . import damping, leafpack, stiffness
from .parameters import LSDParameters

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    motion : {"linear", "circular"}
        Motion for the O-ring Coulomb equivalent.
    omega : float or array
        Vibration frequency [rad/s].
    """,
    omega_instead="omega : float or array_like, optional\n    Vibration frequencies [rad/s] instead of ``rpm``.",
)


__all__ = ["LSDModel", "LSDCoefficients", "COEFFICIENT_NAMES", "MASS_NAMES", "FILM_EFFECT_THRESHOLD"]

#: The eight coefficients in ROSS order, with their SI unit suffix.
COEFFICIENT_NAMES = ("kxx", "kxy", "kyx", "kyy", "cxx", "cxy", "cyx", "cyy")

#: Smallest vibration amplitude [m] of the coefficients (:data:`springdyn.lsd.damping.MIN_AMPLITUDE`).
MIN_AMPLITUDE = damping.MIN_AMPLITUDE


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

    @property
    def _passage(self) -> tuple:
        """Width, clearance and length of a passage between two chambers [m]."""
        p = self.params
        return p.passage_width, p.passage_clearance, p.passage_length

    @cached_property
    def conductance(self) -> float:
        """``C_D`` between neighbouring chambers [m^3/(s Pa)]."""
        p = self.params
        return damping.boundary_conductance(
            *self._passage,
            p.oil_viscosity,
            passages=p.passages_per_boundary,
            model=p.conductance_model,
            leakage_factor=p.leakage_factor,
        )

    @cached_property
    def viscous_damping(self) -> np.ndarray:
        """``C_visc = B^T G^+ B`` (2 x 2) [N s/m], independent of frequency."""
        return damping.viscous_damping_matrix(self.volume_matrix, self.conductance)

    @cached_property
    def inertance(self) -> float:
        """Inertance ``I`` of the passages between two chambers [Pa s^2/m^3] (:func:`damping.passage_inertance`)."""
        p = self.params
        return damping.passage_inertance(
            *self._passage, p.oil_density, passages=p.passages_per_boundary, leakage_factor=p.leakage_factor
        )

    @cached_property
    def film_time_constant(self) -> float:
        """``tau = I C_D`` of the passages [s]: the oil force is ``C_visc (1 + j omega tau) j omega X``."""
        return self.inertance * self.conductance

    @cached_property
    def added_mass(self) -> np.ndarray:
        """Added mass of the oil in the passages ``M_a = tau C_visc`` (2 x 2) [kg].

        With identical passages ``R + j omega I`` the network's coefficient is
        ``j omega B^T G^+ B (1 + j omega tau) = j omega C_visc - omega^2 tau C_visc``: the damping
        is unchanged and the inertia adds the mass ``tau C_visc`` (a negative stiffness
        ``-omega^2 M_a``).
        """
        return self.film_time_constant * self.viscous_damping

    @_DOCS.fill
    def film_diagnostics(self, omega, amplitude: float) -> dict:
        """Squeeze Reynolds number, inertia ratio and linear pressure amplitude at ``omega`` [rad/s].

        Parameters
        ----------
        {omega}
        amplitude : float
            Orbit radius or shake amplitude [m]; the pressure amplitude is the larger of a
            forward orbit's and the x and y shakes' (the orbit's for three or more packs).

        Returns
        -------
        dict
            ``squeeze_reynolds`` (``rho omega h_o^2 / mu``), ``inertia_ratio`` (``omega tau``:
            inertial over viscous pressure drop in the passages, the relative change of the oil
            force by inertia), ``pressure_amplitude_Pa`` (largest chamber pressure amplitude of
            the inertial linear network), ``cavitation_margin_Pa`` (``p_s - p_cav``, absolute).
        """
        p = self.params
        w = np.atleast_1d(np.asarray(omega, dtype=float))
        z = 1.0 + 1j * w * self.film_time_constant
        motions = np.array([[1.0, 1j], [1.0, 0.0], [0.0, 1.0]], dtype=complex) * amplitude
        per_unit = np.abs(damping.chamber_pressures(self.volume_matrix, self.conductance, motions)).max()
        return {
            "squeeze_reynolds": damping.squeeze_reynolds_number(p.oil_density, p.oil_viscosity, w, p.passage_clearance),
            "inertia_ratio": w * self.film_time_constant,
            "pressure_amplitude_Pa": per_unit * w * np.abs(z),
            "cavitation_margin_Pa": p.supply_pressure_absolute - p.cavitation_pressure,
            "cavitation_pressure_Pa": p.cavitation_pressure,
        }

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

    @_DOCS.fill
    def damping_matrix(self, omega, amplitude: float, motion: str = "linear", parts: bool = False):
        """Total damping ``C = C_f I + C_h + C_visc`` [N s/m], shape ``omega.shape + (2, 2)``.

        Parameters
        ----------
        {omega}
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

    @_DOCS.fill
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
        {motion omega_instead}
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
        film = self.film_diagnostics(w, amplitude)
        _warn_film(film, rpm)
        M = np.broadcast_to(self.added_mass, C.shape).copy()
        return self._coefficients(rpm, amplitude, K, C, M, parts, preload_exceeded=unloads, film=film)

    @_DOCS.fill
    def equivalent_coefficients(
        self,
        rpm=None,
        amplitude: float = 50e-6,
        motion: str = "linear",
        *,
        omega=None,
        samples: int = 2048,
        film: bool = False,
    ) -> LSDCoefficients:
        """K, C and M of the nonlinear force laws at this amplitude (describing function).

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
        {omega_instead}
        samples : int
            Quadrature points per period [-].
        film : bool
            Oil force from the time-domain film network with passage inertia and cavitation
            at its periodic steady state (:func:`springdyn.lsd.film.film_harmonic`), instead
            of the linear network with inertia (``j omega C_visc - omega^2 M_a``).  Then the
            oil's damping and added mass depend on amplitude and speed.
        """
        from .equivalent import equivalent_matrices

        rpm_, w = _speeds(rpm, omega)
        mats = [equivalent_matrices(self, wi, amplitude, motion, samples, film=film) for wi in w]
        # the film's real part is its added mass (-omega^2 M); the rest of K is the packs'.
        # Without the film network the oil is linear: its added mass is exactly tau C_visc.
        if film:
            M = np.array([-m["oil"][0] / wi**2 for m, wi in zip(mats, w)])
        else:
            M = np.broadcast_to(self.added_mass, (w.size, 2, 2)).copy()
        from .equivalent import MECHANISMS

        K = np.array([sum(m[k][0] for k in MECHANISMS if k != "oil") for m in mats])
        C = np.array([sum(m[k][1] for k in MECHANISMS) for m in mats])
        diag = self.film_diagnostics(w, amplitude)
        if film:
            diag["cavitated"] = np.array([m["film"]["cavitated"] for m in mats])
            diag["min_pressure_Pa"] = np.array([m["film"]["min_pressure_Pa"] for m in mats])
        else:
            _warn_film(diag, rpm_)
        parts = {
            "oring": np.array([m["oring_friction"][1] for m in mats]),
            "hysteresis": np.array([m["leaf_friction"][1] for m in mats]),
            "viscous": np.array([m["oil"][1] for m in mats]),
        }
        return self._coefficients(
            omega_to_rpm(w),
            amplitude,
            K,
            C,
            M,
            parts,
            preload_exceeded=bool(amplitude > self.params.preload),
            method="describing function, film network" if film else "describing function",
            film=diag,
        )

    def _coefficients(self, rpm, amplitude, K, C, M, parts, **more) -> LSDCoefficients:
        """The coefficients of this damper at ``rpm`` [rev/min] and ``amplitude`` [m]: ``K``
        [N/m], ``C`` [N s/m], ``M`` [kg] and the damping's ``parts``, with the pack's stiffness
        and load ratios (``more``: the further fields of :class:`LSDCoefficients`)."""
        return LSDCoefficients(
            name=self.params.name,
            rpm=rpm,
            amplitude=float(amplitude),
            K=K,
            C=C,
            parts=parts,
            pack_stiffness=self.pack_stiffness,
            load_ratios=self.load_ratios.copy(),
            M=M,
            **more,
        )

    @_DOCS.fill
    def to_ross(self, n: int, frequencies=None, amplitude: float = 50e-6, motion: str = "linear", **options):
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
        {motion}
        **options
            The table's keywords of :func:`springdyn.lsd.rotordynamics.bearing_element`
            (``rpm_range``: default 0 to 20 000 rpm, below 60 rpm the 60 rpm values;
            ``points``, at least 30; ``outside``, ``"raise"`` or ``"clamp"``; ``omega``, an
            explicit table [rad/s]; ``added_mass``, also give ROSS the oil's added mass
            ``mxx`` ... [kg], default true), then those of ``BearingElement`` (``tag``,
            ``n_link``, ...).

        Notes
        -----
        Needs the optional extra ``springdyn[ross]`` (``ross-rotordynamics``).
        """
        from .rotordynamics import bearing_element

        return bearing_element(self, n, frequencies, amplitude=amplitude, motion=motion, **options)


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
    M: np.ndarray | None = None
    film: dict | None = None

    title = "leaf spring damper coefficients"

    def __post_init__(self):
        if self.M is None:
            self.M = np.zeros_like(np.asarray(self.K, dtype=float))
        self.film = dict(self.film or {})

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
            added_mass_xx_max_kg=float(self.M[:, 0, 0].max()),
        )
        f = self.film
        if f:
            s["squeeze_reynolds_max"] = float(np.max(f["squeeze_reynolds"]))
            s["inertia_ratio_max"] = float(np.max(f["inertia_ratio"]))
            s["pressure_amplitude_max_Pa"] = float(np.max(f["pressure_amplitude_Pa"]))
            s["cavitation_margin_Pa"] = float(f["cavitation_margin_Pa"])
            notes = _film_notes(f, self.rpm)
            if notes:
                s["notes"] = notes
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
        for k, (i, j) in zip(MASS_NAMES, [(0, 0), (0, 1), (1, 0), (1, 1)]):
            out[f"{k}_kg"] = self.M[:, i, j]
        f = self.film
        for key, col in (
            ("squeeze_reynolds", "squeeze_reynolds"),
            ("inertia_ratio", "inertia_ratio"),
            ("pressure_amplitude_Pa", "pressure_amplitude_Pa"),
        ):
            if key in f:
                out[col] = np.broadcast_to(np.asarray(f[key], dtype=float), self.rpm.shape)
        return out

    def to_dict(self) -> dict:
        """JSON-ready dict: the columns as lists plus pack data and the amplitude."""
        d = {k: np.asarray(v).tolist() for k, v in self.columns().items()}
        d["pack_stiffness_N_per_m"] = self.pack_stiffness
        d["load_ratios"] = self.load_ratios.tolist()
        d["amplitude_m"] = self.amplitude
        d["preload_exceeded"] = self.preload_exceeded
        if "cavitation_margin_Pa" in self.film:
            d["cavitation_margin_Pa"] = float(self.film["cavitation_margin_Pa"])
        if "cavitated" in self.film:
            d["cavitated"] = np.asarray(self.film["cavitated"]).tolist()
            d["min_pressure_Pa"] = np.asarray(self.film["min_pressure_Pa"]).tolist()
        d["notes"] = _film_notes(self.film, self.rpm)
        return d

    def to_xarray(self):
        """``xarray.Dataset`` with ``K`` and ``C`` over ``(rpm, row, col)`` (the CSV: one column per entry)."""
        import xarray as xr

        coords = {"rpm": ("rpm", self.rpm, {"units": "rpm"}), "row": ["x", "y"], "col": ["x", "y"]}
        ds = xr.Dataset(
            {
                "K": (("rpm", "row", "col"), self.K, {"units": "N/m", "csv_columns": _names(True, "N_per_m")}),
                "C": (("rpm", "row", "col"), self.C, {"units": "N*s/m", "csv_columns": _names(False, "Ns_per_m")}),
                "M": (
                    ("rpm", "row", "col"),
                    self.M,
                    {"units": "kg", "csv_columns": ",".join(f"{n}_kg" for n in MASS_NAMES)},
                ),
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


#: The added-mass coefficients, ROSS order.
MASS_NAMES = ("mxx", "mxy", "myx", "myy")
#: Relative change of the oil force [-] beyond which the film warnings speak (10 %).
FILM_EFFECT_THRESHOLD = 0.10


def _film_notes(film: dict, rpm) -> list:
    """Plain-language notes where fluid inertia or cavitation change the oil force."""
    notes = []
    if not film:
        return notes
    rpm = np.atleast_1d(rpm)
    ratio = np.broadcast_to(np.asarray(film["inertia_ratio"], dtype=float), rpm.shape)
    over = ratio > FILM_EFFECT_THRESHOLD
    if np.any(over):
        i = int(np.argmax(over))
        re_s = np.broadcast_to(np.asarray(film["squeeze_reynolds"], dtype=float), rpm.shape)
        notes.append(
            f"fluid inertia changes the oil force by more than {FILM_EFFECT_THRESHOLD:.0%} from {rpm[i]:g} rpm "
            f"(omega tau = {ratio[i]:.3g}, squeeze Reynolds number {re_s[i]:.3g}; up to {ratio.max():.3g} at "
            f"{rpm[int(np.argmax(ratio))]:g} rpm): the added mass M is part of the damper's force"
        )
    amp = np.broadcast_to(np.asarray(film["pressure_amplitude_Pa"], dtype=float), rpm.shape)
    margin = float(film["cavitation_margin_Pa"])
    cav = amp > margin
    if "cavitated" in film:
        cav = np.asarray(film["cavitated"], dtype=bool)
        if np.any(cav):
            notes.append(
                f"the film cavitates from {rpm[int(np.argmax(cav))]:g} rpm: coefficients from the film "
                "network's first harmonic (they depend on amplitude and speed)"
            )
    elif np.any(cav):
        i = int(np.argmax(cav))
        notes.append(
            f"from {rpm[i]:g} rpm the linear chamber pressure amplitude ({amp[i] / 1e5:.3g} bar) exceeds "
            f"p_s - p_cav = {margin / 1e5:.3g} bar: the film cavitates and the linear oil coefficients "
            "overstate its force; use equivalent_coefficients(..., film=True) (CLI --film)"
        )
    # the figure for air-saturated oil beside it (issue 40): gaseous cavitation near atmospheric pressure
    from .film import AERATED_CAVITATION_PRESSURE

    supply = margin + float(film.get("cavitation_pressure_Pa", 0.0))
    aerated = supply - AERATED_CAVITATION_PRESSURE
    if (
        "cavitation_pressure_Pa" in film
        and film["cavitation_pressure_Pa"] < AERATED_CAVITATION_PRESSURE
        and np.any(amp > aerated)  # only where it matters: air-saturated oil would cavitate at some speed
    ):
        over = amp > aerated
        where = f"from {rpm[int(np.argmax(over))]:g} rpm" if np.any(over) else "at none of these speeds"
        notes.append(
            f"cavitation pressure {film['cavitation_pressure_Pa'] / 1e5:.3g} bar abs (p_s - p_cav = {margin / 1e5:.3g} "
            f"bar); oil saturated with air releases it near {AERATED_CAVITATION_PRESSURE / 1e5:.3g} bar (gaseous "
            f"cavitation, p_s - p_cav = {aerated / 1e5:.3g} bar, {margin / aerated:.3g} times less): its film "
            f"would cavitate {where} (largest linear pressure amplitude {amp.max() / 1e5:.3g} bar)"
        )
    return notes


def _warn_film(film: dict, rpm) -> None:
    """Warn where the film cavitates: the linear oil coefficients are then wrong.

    Inertia is only noted (``summary["notes"]``, printed by the CLI): its added mass is part
    of the result (``M``) and of the ROSS elements.
    """
    from .film import FilmWarning

    for note in _film_notes(film, rpm):
        if not note.startswith(("fluid inertia", "cavitation pressure")):  # noted, not warned
            warnings.warn(note, FilmWarning, stacklevel=3)


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
