"""Linearised dynamic stiffness of a valve spring: seat fixed, retainer driven.

At a static length the chain is linearised (tangent stiffness and damping of every
element, :class:`~springdyn.valve.spring.chains.Chain`); a harmonic retainer displacement
``X e^(i w t)`` then gives node displacements from the tridiagonal system
``(K - w^2 M + i w C) u = z_N X e_N``, ``z_j = k_j + i w c_j``, and the forces per unit
retainer displacement

- at the retainer: ``z_N (1 - u_N / X)``,
- at the seat: ``z_0 u_0 / X``.

For a uniform continuous spring of static rate K and first surge frequency f1 these are
``K theta cot(theta)`` and ``K theta / sin(theta)``, ``theta = pi f / f1`` (the wave
equation with both ends as here; e.g. Wolansky, Valve-spring dynamics), which the tests
check.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.errors import InputError
from ...core.results import Result, text_table
from .modes import chain_frequencies

__all__ = ["dynamic_stiffness", "FrequencyResponse"]


@dataclass(repr=False)
class FrequencyResponse(Result):
    """Dynamic stiffness of a valve spring against frequency (SI; complex values)."""

    spring: object
    model: str
    length: float  # [m]
    frequency: np.ndarray  # [Hz]
    retainer: np.ndarray  # complex [N/m]
    seat: np.ndarray  # complex [N/m]
    static_stiffness: float  # [N/m]
    modes: np.ndarray  # natural frequencies at the length, ends fixed [Hz]

    title = "valve spring dynamic stiffness"
    cheap_plot = True

    def _repr_caption(self) -> str:
        return (
            f"{self.spring.type} spring, {self.model} model, at {self.length * 1e3:.3f} mm, "
            f"{self.frequency[0]:g}-{self.frequency[-1]:g} Hz"
        )

    def describe(self) -> str:
        """The static rate, the modes and the dynamic stiffness at about 25 frequencies."""
        step = max(1, self.frequency.size // 25)
        rows = [
            (f"{f:.1f}", f"{abs(r) / 1e3:.3f}", f"{abs(st) / 1e3:.3f}")
            for f, r, st in zip(self.frequency[::step], self.retainer[::step], self.seat[::step])
        ]
        return "\n".join(
            [
                f"{self.spring.type} spring, {self.model} model, at {self.length * 1e3:.3f} mm: static rate "
                f"{self.static_stiffness / 1e3:.3f} N/mm, modes " + ", ".join(f"{f:.1f}" for f in self.modes) + " Hz",
                text_table(rows, headers=("frequency [Hz]", "retainer [N/mm]", "seat [N/mm]")),
            ]
        )

    def _summary(self) -> dict:
        return dict(
            model=self.model,
            length_m=self.length,
            points=int(self.frequency.size),
            frequency_min_Hz=float(self.frequency.min()),
            frequency_max_Hz=float(self.frequency.max()),
            static_stiffness_N_per_m=self.static_stiffness,
            first_mode_Hz=float(self.modes[0]),
            max_retainer_dynamic_stiffness_N_per_m=float(np.abs(self.retainer).max()),
            max_seat_dynamic_stiffness_N_per_m=float(np.abs(self.seat).max()),
        )

    def to_dict(self) -> dict:
        """The JSON of ``springdyn valve frf``: frequencies and magnitudes (SI)."""
        return dict(
            frequency_Hz=self.frequency.tolist(),
            retainer_dynamic_stiffness_N_per_m=np.abs(self.retainer).tolist(),
            seat_dynamic_stiffness_N_per_m=np.abs(self.seat).tolist(),
        )

    def to_xarray(self):
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        dims = ("frequency",)
        return xr.Dataset(
            {
                "retainer_dynamic_stiffness": (
                    dims,
                    np.abs(self.retainer),
                    {"units": "N/m", "long_name": "|retainer force / retainer displacement|"},
                ),
                "seat_dynamic_stiffness": (
                    dims,
                    np.abs(self.seat),
                    {"units": "N/m", "long_name": "|seat force / retainer displacement|"},
                ),
                "retainer_phase": (dims, np.degrees(np.angle(self.retainer)), {"units": "deg"}),
                "seat_phase": (dims, np.degrees(np.angle(self.seat)), {"units": "deg"}),
            },
            coords={"frequency": ("frequency", self.frequency, {"units": "Hz"})},
            attrs={"model": self.model, "length_m": self.length, "spring_type": self.spring.type},
        )

    def _plot(self, ax=None):
        from ...core.plotting import new_figure  # (here: matplotlib costs 0.3 s of start-up)

        if ax is None:
            fig, (ax, ax_p) = new_figure(2, 1, figsize=(8, 7), sharex=True)
        else:
            fig, ax_p = ax.figure, None
        ax.semilogy(self.frequency, np.abs(self.retainer) / 1e3, color="C0", label="retainer")
        ax.semilogy(self.frequency, np.abs(self.seat) / 1e3, color="C1", label="seat")
        ax.axhline(self.static_stiffness / 1e3, color="k", ls=":", lw=1, label="static rate")
        for f in self.modes:
            if self.frequency[0] <= f <= self.frequency[-1]:
                ax.axvline(f, color="0.6", lw=0.8)
        ax.set_ylabel("dynamic stiffness [N/mm]")
        ax.set_title(
            f"{self.spring.type} spring, {self.model} model, at {self.length * 1e3:.2f} mm "
            "(seat fixed, retainer driven)"
        )
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        if ax_p is not None:
            ax_p.plot(self.frequency, np.degrees(np.angle(self.retainer)), color="C0")
            ax_p.plot(self.frequency, np.degrees(np.angle(self.seat)), color="C1")
            ax_p.set_ylabel("phase [deg]")
            ax_p.set_xlabel("frequency [Hz]")
            ax_p.grid(True, alpha=0.3)
        else:
            ax.set_xlabel("frequency [Hz]")
        return fig


def dynamic_stiffness(spring, frequency, length: float | None = None) -> FrequencyResponse:
    """Linearised dynamic stiffness of the spring's model at a length, seat fixed.

    Parameters
    ----------
    spring : ValveSpring
        The spring (its ``model`` decides the chain).
    frequency : array_like
        Frequencies [Hz], positive.
    length : float, optional
        Spring length [m] of the static state (default: the installed length).

    Returns
    -------
    FrequencyResponse
        Retainer and seat force per unit retainer displacement (complex) [N/m].
    """
    from scipy.linalg import solve_banded  # (here: scipy.linalg costs start-up of every valve command)

    f = np.atleast_1d(np.asarray(frequency, dtype=float))
    if f.size == 0 or not np.all(np.isfinite(f)) or np.any(f <= 0):
        raise InputError(f"frequency must hold positive frequencies in Hz, got {frequency!r}")
    length = spring.installed_length if length is None else float(length)
    model = spring.spring_model
    _, x, kstat = model.static_state(length)
    ch = model.chain
    k = ch.tangent_stiffness(x)
    c = ch.damping(x)
    m = ch.masses
    n = m.size
    retainer = np.empty(f.size, complex)
    seat = np.empty(f.size, complex)
    for i, fi in enumerate(f):
        w = 2 * np.pi * fi
        z = k + 1j * w * c
        ab = np.zeros((3, n), complex)
        ab[1] = z[:-1] + z[1:] - w * w * m
        ab[0, 1:] = -z[1:-1]
        ab[2, :-1] = -z[1:-1]
        rhs = np.zeros(n, complex)
        rhs[-1] = z[-1]
        u = solve_banded((1, 1), ab, rhs)
        retainer[i] = z[-1] * (1.0 - u[-1])
        seat[i] = z[0] * u[0]

    return FrequencyResponse(
        spring, model.name, length, f, retainer, seat, float(kstat), chain_frequencies(m, k, min(5, n))
    )
