"""The spring wing's results: :class:`StaticCurve`, the static force, stiffness and first
natural frequency of a spring against its length, on the shared
:class:`~springdyn.core.results.Result` (its figure: :mod:`.plots`); and the spring's figures
that describe themselves: :class:`SpringParameters`, :class:`ChainModes`,
:class:`DesignFigures`, with the lines every valve output states (:func:`coil_line`,
:func:`load_points_text`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.results import Result, dataset_columns, text_table
from ...core.units import format_quantity
from .formulas import PARAMETER_UNITS

__all__ = ["StaticCurve", "SpringParameters", "ChainModes", "DesignFigures", "coil_line", "load_points_text"]


@dataclass(repr=False)
class StaticCurve(Result):
    """Static force and tangent stiffness of a spring against its length (SI)."""

    spring: object
    length: np.ndarray  # [m]
    force: np.ndarray  # [N]
    stiffness: np.ndarray  # [N/m]
    model: str = "type-c"
    frequency: np.ndarray | None = None  # first natural frequency, ends fixed [Hz]

    title = "valve spring static curve"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return f"{self.spring.type} spring, {self.model} model, {self.length.size} points"

    def _summary(self) -> dict:
        return dict(
            model=self.model,
            points=int(self.length.size),
            length_max_m=float(self.length.max()),
            length_min_m=float(self.length.min()),
            force_min_N=float(self.force.min()),
            force_max_N=float(self.force.max()),
            stiffness_min_N_per_m=float(self.stiffness.min()),
            stiffness_max_N_per_m=float(self.stiffness.max()),
            **(
                {}
                if self.frequency is None
                else dict(first_mode_min_Hz=float(self.frequency.min()), first_mode_max_Hz=float(self.frequency.max()))
            ),
        )

    def columns(self) -> dict:
        """``length_m, force_N, stiffness_N_per_m`` (the CSV columns)."""
        return dataset_columns(self.to_xarray())

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        data = {
            "force": ("length", self.force, {"units": "N", "long_name": "static spring force"}),
            "stiffness": ("length", self.stiffness, {"units": "N/m", "long_name": "tangent stiffness -dF/dL"}),
        }
        if self.frequency is not None:
            data["first_mode_frequency"] = (
                "length",
                self.frequency,
                {"units": "Hz", "long_name": "first natural frequency, ends fixed"},
            )
        return xr.Dataset(
            data,
            coords={"length": ("length", self.length, {"units": "m", "long_name": "spring length"})},
            attrs={"model": self.model, "spring_type": self.spring.type},
        )

    def describe(self) -> str:
        """The curve as a table of about 20 lengths: force, stiffness, first mode."""
        step = max(1, len(self.length) // 20)
        rows = [
            (f"{l * 1e3:.3f}", f"{f:.2f}", f"{k / 1e3:.2f}", f"{n:.1f}")
            for l, f, k, n in zip(
                self.length[::step], self.force[::step], self.stiffness[::step], self.frequency[::step]
            )
        ]
        return text_table(rows, headers=("length [mm]", "force [N]", "stiffness [N/mm]", "first mode [Hz]"))

    def _plot(self, ax=None):
        """Force and stiffness vs length with Ls, F1, F2 and Fcon marked."""
        from .plots import plot_static_curve  # (here: matplotlib costs 0.3 s of start-up)

        return plot_static_curve(self, ax=ax)


def coil_line(facts: dict) -> str:
    """The one line every valve output states about the spring it ran: its coils, solid length
    (and where it comes from) and free length (:attr:`ValveSpring.coil_facts`).

    Parameters
    ----------
    facts : dict
        :attr:`ValveSpring.coil_facts` [-, m].
    """
    return (
        f"spring: {facts['total_coils']:g} coils, {facts['active_coils']:g} active; solid length "
        f"{facts['solid_length_m'] * 1e3:.3f} mm ({facts['solid_length_source']}); free length "
        f"{facts['free_length_m'] * 1e3:.3f} mm"
    )


def load_points_text(rows: list) -> str:
    """The drawing's load points against the model's static force, as a table
    (:meth:`SpringModel.load_point_check`).

    Parameters
    ----------
    rows : list of dict
        ``length_m`` [m], ``force_N``, ``model_force_N``, ``linear_force_N``, ``deviation_N`` [N],
        ``deviation_percent`` [%], ``tolerance_N`` [N], ``within_tolerance`` and
        ``stiffened_by_law`` per load point.
    """
    text = "load points of the drawing against the model's static force:\n" + text_table(
        [
            (
                f"{r['length_m'] * 1e3:.3f}",
                f"{r['force_N']:.1f}",
                f"{r['model_force_N']:.1f}",
                f"{r['linear_force_N']:.1f}",
                f"{r['deviation_N']:+.1f} ({r['deviation_percent']:+.2f} %)",
                "-" if r["tolerance_N"] is None else f"+-{r['tolerance_N']:.1f}",
                {None: "-", True: "ok", False: "OUTSIDE"}[r["within_tolerance"]],
            )
            for r in rows
        ],
        headers=(
            "length [mm]",
            "drawing [N]",
            "model [N]",
            "linear rate [N]",
            "deviation [N]",
            "tolerance [N]",
            "",
        ),
    )
    stiff = [r for r in rows if r.get("stiffened_by_law")]
    if stiff:
        worst = max(stiff, key=lambda r: abs(r["model_force_N"] / r["linear_force_N"] - 1.0))
        text += (
            "\nnote: Type C stiffens above its F1 by its law, not by coils that touch: at "
            + ", ".join(f"{r['length_m'] * 1e3:.3f}" for r in stiff)
            + f" mm it reads up to {worst['model_force_N'] / worst['linear_force_N'] - 1.0:+.2%} against EN 13906-1's "
            "linear rate (the spring maker's figure); the distributed model follows the coils"
        )
    return text


@dataclass(frozen=True)
class SpringParameters:
    """A spring model's internal parameters with their units and meaning, its coils and the
    drawing's load points (``springdyn valve params``)."""

    spring: object
    #: The internal parameters [SI] (:meth:`SpringModel.internal_parameters`).
    parameters: dict
    #: The load points against the model (empty without ``load_points``).
    load_points: list

    @classmethod
    def of(cls, spring) -> SpringParameters:
        """The parameters of a spring's model.

        Parameters
        ----------
        spring : ValveSpring
            The spring (its model gives the parameters).
        """
        model = spring.spring_model
        return cls(spring, model.internal_parameters(), model.load_point_check() if spring.load_points else [])

    def to_dict(self) -> dict:
        """The internal parameters [SI] (the JSON of ``valve params``)."""
        return dict(self.parameters)

    def describe(self) -> str:
        """The parameters as a table with their units and meaning, the coils, the load points."""

        sp = self.spring
        model = sp.spring_model
        rows = []
        for key, value in self.parameters.items():
            unit, display, _ = PARAMETER_UNITS[key]
            rows.append((key, format_quantity(value, unit, display), model.parameter_meaning(key)))
        lines = [
            f"{sp.type} valve spring, {model.description}",
            f"coils: {sp.total_coils:g} total, {sp.active_coils:g} active ({sp.dead_coils:g} dead per end); "
            f"solid length {sp.solid_length * 1e3:.3f} mm ({sp.coil_facts['solid_length_source']})"
            + f"; free length {sp.free_length * 1e3:.3f} mm"
            + (", pitch profile given" if sp.pitch_profile else ""),
            f"first surge frequency {model.first_mode_installed:.1f} Hz at installed length "
            f"({model.surge_frequency_definition}; every surge margin and check uses it)",
            text_table(rows, headers=("parameter", "value", "meaning")),
        ]
        if self.load_points:
            lines.append(load_points_text(self.load_points))
        return "\n".join(lines)


@dataclass(frozen=True)
class ChainModes:
    """The chain's natural frequencies at a length, both ends fixed, and what moves in each
    (``springdyn valve modes``)."""

    length: float  #: spring length [m]
    force: float  #: static force there [N]
    frequencies: list  #: ascending [Hz]
    labels: list  #: ``"surge n"`` or ``"end mass"`` per mode

    @classmethod
    def of(cls, spring, length: float, count: int = 5) -> ChainModes:
        """The modes of a spring's chain linearised at ``length``.

        Parameters
        ----------
        spring : ValveSpring
            The spring.
        length : float
            Spring length [m].
        count : int
            How many, from the lowest [-].
        """
        model = spring.spring_model
        freqs = model.modes(length, count)
        labels = model.mode_labels(length, count)
        return cls(float(length), float(model.static_force(length)), list(freqs), list(labels))

    def to_dict(self) -> dict:
        """``length_m``, ``force_N``, ``frequencies_Hz``, ``modes`` (the JSON of ``valve modes``)."""
        return {
            "length_m": self.length,
            "force_N": self.force,
            "frequencies_Hz": self.frequencies,
            "modes": self.labels,
        }

    def describe(self) -> str:
        """The modes as a table, with a word on the end-mass modes."""
        lines = [
            f"length {self.length * 1e3:.3f} mm, static force {self.force:.2f} N",
            text_table(
                [(str(i + 1), f"{f:.2f}", label) for i, (f, label) in enumerate(zip(self.frequencies, self.labels))],
                headers=("mode", "frequency [Hz]", "what moves"),
            ),
        ]
        if "end mass" in self.labels:
            lines.append(
                "end mass: the chain's end masses bouncing on their stiff end contacts (a lumped model's mode, "
                "not a surge of the coils)"
            )
        return "\n".join(lines)


@dataclass(frozen=True)
class DesignFigures:
    """The design figures of a spring (``springdyn valve design``): spring index, corrected
    stresses and surge frequencies at installed, open and coil-contact length, coil bind, the
    static fatigue (:meth:`SpringModel.design_figures`, ``figures``)."""

    spring: object
    figures: dict
    #: The cam speed of the surge margins [rev/min] (None: no margins), named in the table.
    cam_rpm: float | None = None

    def to_dict(self) -> dict:
        """The figures [SI] (the JSON of ``valve design``)."""
        return dict(self.figures)

    def __getitem__(self, key):
        return self.figures[key]

    def __contains__(self, key) -> bool:
        return key in self.figures

    def describe(self) -> str:
        """The figures in words and a table per state."""
        fig = self.figures
        round_wire = fig.get("wire_section", "round").startswith("round")
        factor = f"stress factor {fig['stress_factor']:.4f} ({fig['stress_factor_name']})"
        lines = [
            (
                f"spring index C = {fig['spring_index']:.3f}, {factor}, Wahl k = {fig['wahl_factor']:.4f} (beside it)"
                if round_wire
                else f"wire {fig['wire_section']}, spring index D/b = {fig['spring_index']:.3f}, {factor}"
            ),
            f"coils: {fig['total_coils']:g} total, {fig['active_coils']:g} active ({fig['dead_coils_per_end']:g} dead "
            f"per end); solid length Lc = {fig['solid_length_m'] * 1e3:.3f} mm ({fig['solid_length_source']}); "
            f"spring mass M = {fig['spring_mass_kg'] * 1e3:.2f} g",
            f"surge f1: {self.spring.spring_model.surge_frequency_definition}, at each state's length",
        ]
        rows = []
        for state in ("installed", "open", "coil_contact"):
            if state in fig:
                s = fig[state]
                rows.append(
                    (
                        state,
                        f"{s['length_m'] * 1e3:.3f}",
                        f"{s['force_N']:.1f}",
                        f"{s['shear_stress_Pa'] / 1e6:.0f}",
                        f"{s['surge_frequency_Hz']:.1f}",
                        f"{s['surge_margin']:.2f}" if "surge_margin" in s else "-",
                    )
                )
        lines.append(
            text_table(
                rows,
                headers=(
                    "state",
                    "length [mm]",
                    "force [N]",
                    "stress [MPa]",
                    "surge f1 [Hz]",
                    "surge margin" if self.cam_rpm is None else f"surge margin at {self.cam_rpm:g} cam rpm",
                ),
            )
        )
        if "coil_bind" in fig:
            cb = fig["coil_bind"]
            verdict = "ok" if cb["coil_bind_ok"] else ("THROUGH SOLID" if cb["through_solid"] else "BELOW CLEARANCE")
            lines.append(
                f"coil bind: {cb['coil_bind_margin_m'] * 1e3:.3f} mm above solid at full lift "
                f"(clearance {cb['coil_bind_clearance_m'] * 1e3:.3f} mm, {cb['coil_bind_clearance_source']}"
                + (
                    f"; static Sa {cb['static_sum_of_gaps_m'] * 1e3:.3f} mm"
                    if cb["coil_bind_clearance_source"] != "min_coil_bind_clearance"
                    else ""
                )
                + f"): {verdict}"
            )
        if "coil_contact_note" in fig:
            lines.append(f"note: {fig['coil_contact_note']}")
        if "load_points" in fig:
            lines.append(load_points_text(fig["load_points"]))
        if "fatigue" in fig:
            f = fig["fatigue"]
            lines.append(
                f"fatigue (Goodman, installed -> open): safety factor {f['static_fatigue_safety_factor']:.2f}; "
                f"endurance {f['endurance_shear_strength_Pa'] / 1e6:.0f} MPa, ultimate shear "
                f"{f['ultimate_shear_strength_Pa'] / 1e6:.0f} MPa"
                + (f" (defaults for {', '.join(f['strength_defaults'])})" if f["strength_defaults"] else "")
            )
        return "\n".join(lines)
