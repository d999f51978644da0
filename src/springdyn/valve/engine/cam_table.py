"""The cam as the engine sees it: a periodic table of lift and its first two derivatives,
interpolated by quintic Hermite polynomials (C2), and the angles a step must land on.

One place for the cam table: :class:`CamTable` samples a :class:`~springdyn.valve.cam.definition.Cam`
(:meth:`CamTable.of`) and evaluates the interpolant on arrays (:meth:`CamTable.at`); the
compiled engine evaluates the same interpolant (:func:`.equations.hermite5`, through
:func:`.equations.cam_at`) on the same arrays.
"""

from __future__ import annotations

import math
import threading
import weakref
from dataclasses import dataclass

import numpy as np

from .equations import hermite5

__all__ = ["CamTable", "CACHE_SIZE"]

#: Cams whose tables :meth:`CamTable.of` keeps.
CACHE_SIZE = 16
#: ``(id(cam), samples) -> (weak reference to the cam, table)``, oldest first.
_CACHE: dict = {}
_LOCK = threading.Lock()


@dataclass(frozen=True, eq=False)
class CamTable:
    """Lift [m] and its derivatives [m/rad, m/rad^2] at the cam angles ``k * dth``, one revolution."""

    h: np.ndarray  #: lift at the nodes [m]
    dh: np.ndarray  #: dh/dtheta at the nodes [m/rad]
    ddh: np.ndarray  #: d2h/dtheta2 at the nodes [m/rad^2]
    dth: float  #: node spacing [rad]

    @classmethod
    def of(cls, cam, samples: int) -> CamTable:
        """The table of ``cam`` with ``samples`` nodes per revolution.

        Sampling a cam costs about as much as a Type C simulation, so the tables of the
        last :data:`CACHE_SIZE` cams are kept (:data:`_CACHE`, keyed on the cam object: a
        cam is immutable; a weak reference checks that the key's cam still exists).

        Parameters
        ----------
        cam : Cam
            The cam (its :meth:`~springdyn.valve.cam.definition.Cam.sampled` values).
        samples : int
            Nodes per revolution [-].
        """
        key = (id(cam), int(samples))
        with _LOCK:
            hit = _CACHE.get(key)
            if hit is not None and hit[0]() is cam:
                return hit[1]
        h, dh, ddh = cam.sampled(samples)
        table = cls(np.ascontiguousarray(h), np.ascontiguousarray(dh), np.ascontiguousarray(ddh), 2 * math.pi / samples)
        # (shared by every run of this cam; left writable: numba compiles read-only arrays
        # as another type, and so the engine once more)
        with _LOCK:
            _CACHE[key] = (weakref.ref(cam), table)
            while len(_CACHE) > CACHE_SIZE:
                _CACHE.pop(next(iter(_CACHE)))  # the oldest
        return table

    @property
    def samples(self) -> int:
        """Nodes per revolution [-]."""
        return int(self.h.size)

    def at(self, theta):
        """Lift [m] and ``dh/dtheta`` [m/rad] at cam angles ``theta`` [rad] (any real, arrays too).

        Parameters
        ----------
        theta : float or array_like
            Cam angles [rad].
        """
        theta = np.asarray(theta, dtype=float)
        n, dth = self.h.size, self.dth
        th = np.mod(theta, n * dth)
        i0 = np.minimum((th / dth).astype(np.intp), n - 1)
        i1 = (i0 + 1) % n
        lift, slope = hermite5(
            th / dth - i0,
            self.h[i0],
            self.dh[i0] * dth,
            self.ddh[i0] * dth**2,
            self.h[i1],
            self.dh[i1] * dth,
            self.ddh[i1] * dth**2,
        )
        return lift, slope / dth

    def stop_angles(self, breakpoints) -> np.ndarray:
        """The table nodes around each breakpoint, on which the engine lands its steps [rad].

        The table smooths a jump of the lift law over the interval that holds it; landing on
        the nodes from one before to two after each breakpoint lets the integrator take that
        interval as a step of its own.

        Parameters
        ----------
        breakpoints : array_like
            Cam angles [rad] where the lift law is not smooth (:attr:`springdyn.valve.cam.definition.Cam.breakpoints`).

        Returns
        -------
        ndarray
            Ascending cam angles [rad] in [0, 2 pi).
        """
        b = np.asarray(breakpoints, dtype=float)
        if b.size == 0:
            return np.empty(0)
        k = np.floor(b / self.dth).astype(np.int64)
        nodes = np.mod((k[:, None] + np.arange(-1, 3)[None, :]).ravel(), self.samples)
        return np.unique(nodes) * self.dth

    def angle_deg(self, i: int) -> float:
        """The cam angle [deg] of node ``i``.

        Parameters
        ----------
        i : int
            Node index [-].
        """
        return 360.0 * int(i) / self.samples
