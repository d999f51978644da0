"""Speed sweeps (and design-variable sweeps) of the valve spring, locally or on Dask.

The work is cut into chunks of speeds; each chunk integrates its speeds with the
compiled engine (which releases the GIL, so local threads run in parallel) and reduces
the states to the forces the results need.  Locally a thread pool runs the chunks; with a
``dask.distributed.Client`` the same chunk function runs on the cluster, so the results
are identical bit for bit.
"""

from __future__ import annotations

import contextlib
import dataclasses
import math
import os
import socket
import struct
import time
import warnings
from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path

import numpy as np

from ...core.docstrings import ParameterDocs
from ...core.errors import InputError
from ...core.io import atomic_path, write_csv
from ...core.params import describe_value
from ...core.progress import progress
from ...core.results import Result, notes_lines, units_from_name
from ...core.units import rpm_to_omega
from ..cam.definition import Cam
from ..cam.timing import CrankAngles
from ..engine import EXT
from ..spring.definition import ValveSpring
from ..spring.results import coil_line
from ..train.definition import ValveTrain
from . import verdicts
from .periodicity import PERIODICITY_TOL, PeriodicStates
from .results import locate_intervals
from .runner import run_speeds, run_speeds_from, solver_error
from .separation import PHASES, cam_phases, float_speed_of_scan, liftoffs, neighbour_band, phase_mask
from .settings import SWEEP_POINTS_PER_REVOLUTION, RunSettings
from .setup import SimulationSetup, check_speeds, output_angles, prepare, static_force_along_grid, static_force_at_lift
from .train_modes import natural_frequencies, resonance_speeds

__all__ = ["sweep", "SpeedSweep", "run_chunk", "connect", "describe_design_value", "SCHEDULER_TIMEOUT"]

#: Parameter descriptions shared by this module's docstrings (``{name}`` lines).
_DOCS = ParameterDocs(
    """
    out_dir : str or Path
        Output folder [-].
    prefix : str
        File name prefix [-].
    """
)

#: Seconds to wait for a Dask scheduler before giving up.
SCHEDULER_TIMEOUT = 5.0


def run_chunk(
    setup: SimulationSetup,
    cam_rpm: np.ndarray,
    settings: RunSettings,
    points: int,
    starts: PeriodicStates | None = None,
) -> dict:
    """Integrate a chunk of speeds and reduce each to its last revolution's forces.

    To the periodic steady state (``settings.revolutions`` None) each speed starts from the
    state the slower speed before it in the chunk ended in (a continuation: the chunk's speeds
    ascending), the first from rest; ``revolutions`` runs every speed from rest.  With
    ``starts`` (to the periodic state only) each speed starts from the nearest known periodic
    state instead (known before the sweep, or of the chunk's speeds before it) and returns its
    own (``state``; :func:`~springdyn.valve.run.runner.run_speeds_from`).

    Parameters
    ----------
    setup : SimulationSetup
        Spring, cam and valve train prepared for the engine.
    cam_rpm : ndarray
        Camshaft speeds [rev/min], ascending.
    settings : RunSettings
        Revolutions or the periodic steady state, tolerances (:class:`RunSettings`).
    points : int
        Output points per revolution [-].
    starts : PeriodicStates, optional
        Known periodic states to start from (warm starts).

    Returns
    -------
    dict
        Arrays with a leading speed dimension: ``retainer``, ``seat``, ``contact`` (any
        element past its coil-contact compression), ``closing`` (such an element where the
        static spring at the same lift has it open, :meth:`SpringModel.clash`), ``clash`` (a
        severity above :data:`~springdyn.valve.run.verdicts.MAX_CLASH_SEVERITY`),
        ``clash_severity``, ``clash_contact_share``, ``clash_closing_velocity_m_per_s``,
        ``clash_transition``, ``clash_active`` (:func:`springdyn.valve.run.verdicts.coil_clash`),
        ``contact_force`` (largest force of
        such an element), ``wire_min``, ``wire_max`` (each element's wire torsion as an
        axial force, :meth:`SpringModel.wire_forces`, NaN for no wire), ``periodicity`` (the largest change of the seat, retainer,
        cam-contact and valve-seat forces from the revolution before, / Fset),
        ``revolutions`` (run), ``settled`` (periodic within the tolerance), ``band_lo``,
        ``band_hi`` (the extremes' band over the last revolutions of a speed that does not
        settle, layout :data:`springdyn.valve.engine.EXT`), ``ext`` (true extremes of the last revolution from the
        dense output, layout :data:`springdyn.valve.engine.EXT`), ``separation`` (end
        separation events located in the last revolution), ``status``, ``t``, ``steps``
        and, with a valve train, ``cam_contact``, ``valve_lift``, ``static``.
    """
    cam_rpm = np.asarray(cam_rpm, dtype=float)
    warm = starts is not None and settings.periodic
    if warm:
        # the chunk starts from the states known before the sweep and its own (not from those
        # another chunk records meanwhile: the same starts however the chunks run); the sweep
        # records its states after its chunks (_run_speeds)
        mon = run_speeds_from(setup, rpm_to_omega(cam_rpm), settings, points, starts.copy())
    else:
        mon = run_speeds(setup, rpm_to_omega(cam_rpm), settings, points, warm_start=settings.periodic)
    ex, status = mon["extra"], mon["status"]
    last = slice(0, points)
    lay = setup.layout
    f = ex[:, :, lay["force"]]
    contact = ex[:, last, lay["compression"]] >= setup.spring.spring_model.contact_gaps
    ev = mon["events"]
    model = setup.spring.spring_model
    wire = model.wire_forces(
        np.moveaxis(ex[:, last, lay["compression"]], -1, 0), np.moveaxis(f[:, last], -1, 0)
    )  # (N + 1, speeds, points)
    out = dict(
        retainer=ex[:, last, lay["retainer_total"]],
        seat=ex[:, last, lay["seat_total"]],
        contact=contact.any(axis=2),
        contact_force=np.where(contact, f[:, last], 0.0).max(axis=2),
        **{key: mon[key] for key in ("periodicity", "revolutions", "settled", "band_lo", "band_hi", "ext")},
        wire_min=wire.min(axis=2).T,
        wire_max=wire.max(axis=2).T,
        separation=np.sum(ev[:, :, 0] == 0.0, axis=1),
        status=status,
        t=mon["t_end"],
        steps=mon["steps"],
    )
    if setup.valve_train is not None:
        out["cam_contact"] = ex[:, last, lay["cam_contact_force"]]
        out["valve_lift"] = ex[:, last, lay["top_displacement"]]
        out["liftoff"] = _liftoff_rows(setup, cam_rpm, mon, ex[:, last, lay["cam_gap"]], points)
    if warm:
        out["state"] = mon["state"]
    # copies, so that the chunk's full engine output (every element, every point) is freed
    out = {k: np.array(v, copy=True) for k, v in out.items()}
    if setup.valve_train is not None:
        valid = status == 0
        static = np.full(out["valve_lift"].shape, np.nan)
        static[valid] = static_force_at_lift(setup, out["valve_lift"][valid])
        out["static"] = static
    else:
        static = np.broadcast_to(static_force_along_grid(setup, points), out["retainer"].shape)
    x = np.moveaxis(ex[:, last, lay["compression"]], -1, 0)
    cc = verdicts.coil_clash(model, x, static, 60.0 / cam_rpm)
    out["closing"] = cc["closing"].any(axis=(0, 2))
    for key in ("severity", "contact_share", "closing_velocity_m_per_s", "transition", "active", "clash"):
        out[f"clash_{key}" if key != "clash" else "clash"] = np.asarray(cc[key])
    if setup.n_chains > 1:  # a spring pack: each spring's retainer force, static force and coil clash
        lift = out["valve_lift"] if setup.valve_train is not None else ex[:, last, lay["lift"]]
        out.update(_pack_columns(setup.spring, f[:, last], x, static, lift, cam_rpm))
    return out


def _pack_columns(pack, force, compression, static, lift, cam_rpm) -> dict:
    """A spring pack's per-spring arrays of a chunk (speeds, springs): the retainer force's extremes
    on the output grid (the spring's last element), the static force's at the smallest and the
    largest lift (:meth:`~springdyn.valve.spring.pack.SpringPack.static_forces`, exact for each
    spring) and the coil clash (:func:`springdyn.valve.run.verdicts.spring_clashes`)."""
    ranges = pack.spring_model.element_ranges()
    retainer = np.stack([force[:, :, r.stop - 1] for r in ranges], axis=1)  # (speeds, springs, points)
    z = np.asarray(lift, dtype=float)
    lo = pack.static_forces(np.maximum(np.nanmin(z, axis=1), 0.0))  # (springs, speeds)
    hi = pack.static_forces(np.nanmax(z, axis=1))
    each = verdicts.spring_clashes(pack.spring_model, compression, static, 60.0 / cam_rpm).values()
    out = dict(spring_retainer_min=retainer.min(axis=2), spring_retainer_max=retainer.max(axis=2))
    out.update(spring_static_min=lo.T, spring_static_max=hi.T)
    for key in ("severity", "transition", "active", "clash"):
        out[f"spring_clash_{key}"] = np.stack([np.asarray(c[key]) for c in each], axis=1)
    return out


def _clash_line(table: dict, speed) -> str:
    """The sweep's coil clash in words: the speeds whose coils close where the static spring is
    open, by class (transition-coil seating, active coils), the largest severity against its
    limit, and the speeds that clash (:func:`springdyn.valve.run.verdicts.coil_clash`)."""
    limit = verdicts.MAX_CLASH_SEVERITY
    sev = np.asarray(table["clash_severity"], dtype=float)
    n = sev.size
    seat, active = (np.asarray(table[k], bool) for k in ("transition_seating", "active_coil_closing"))
    clash = np.asarray(table["coil_clash"], bool)
    if not (seat.any() or active.any()):
        return f"coil clash: none (no coil closes where the static spring is open, {n} runs)"
    k = int(np.argmax(sev))
    text = (
        f"coils close where the static spring is open: transition coils seat at {int(seat.sum())} of {n} runs, "
        f"active coils at {int(active.sum())}; largest severity {100 * sev[k]:.1f} % of Fset at "
        f"{speed(table['cam_rpm'][k])} (force through contact / Fset, limit {100 * limit:g} %)"
    )
    if clash.any():
        first = float(np.min(np.asarray(table["cam_rpm"])[clash]))
        return text + f"; COIL CLASH (severity above the limit) at {int(clash.sum())} runs, from {speed(first)}"
    return text + "; no coil clash (every severity within the limit)"


#: Lift-offs kept per speed of a sweep (rows of ``data["liftoff"]``; more are counted).
MAX_LIFTOFFS = 16
#: Columns of ``data["liftoff"]``: start, end and duration [deg], the phase (index into
#: :data:`springdyn.valve.run.separation.PHASES`, 5 the base circle) and the largest gap [m].
LIFTOFF_COLUMNS = ("start_deg", "end_deg", "duration_deg", "phase", "max_gap_m")


def _liftoff_rows(setup, cam_rpm, mon, gap, points) -> np.ndarray:
    """The located lift-offs of each speed's last revolution, classified by phase
    (:func:`springdyn.valve.run.separation.liftoffs`), NaN-padded to :data:`MAX_LIFTOFFS` rows."""
    phases = cam_phases(setup.cam, setup.valve_train.lobe_lash)
    names = {name: k for k, name in enumerate((*PHASES, "base circle"))}
    rows = np.full((cam_rpm.size, MAX_LIFTOFFS, len(LIFTOFF_COLUMNS)), np.nan)
    theta = output_angles(points)
    for i, rpm in enumerate(cam_rpm):
        omega = rpm_to_omega(rpm)
        if mon["status"][i] != 0:
            continue
        t0 = (int(mon["revolutions"][i]) - 1) * (2.0 * np.pi / omega)
        ivals = locate_intervals(mon["events"][i, : int(mon["n_events"][i])], omega, t0).get((2, 0), [])
        for j, r in enumerate(liftoffs(ivals, phases, float(rpm), theta, -gap[i])[:MAX_LIFTOFFS]):
            rows[i, j] = (r["start_deg"], r["end_deg"], r["duration_deg"], names[r["phase"]], r["max_gap_m"])
    return rows


#: Largest first message of a Dask scheduler [bytes] (its handshake: a few hundred bytes).
MAX_GREETING = 2**20


def _probe_scheduler(address: str, timeout: float) -> None:
    """Check within ``timeout`` s that a Dask scheduler answers at ``address`` (tcp): connect,
    read its first message (a Dask comm greets first with its handshake: an 8-byte length (native order, as dask writes it), an
    8-byte frame count, the frames' lengths and msgpack frames naming its ``pickle-protocol``)
    and refuse anything else before ``dask.distributed.Client`` is given the address (issue 40:
    a port that is not a scheduler's made it allocate 3 EiB, exit 70, or wait for ever)."""
    from distributed.comm.addressing import parse_address, parse_host_port  # (here: dask is an optional extra)

    where = f"scheduler = {address!r}"
    expected = "expected a Dask scheduler's address, e.g. tcp://127.0.0.1:8786 (the one `dask scheduler` prints)"
    try:
        scheme, loc = parse_address(address)
        if scheme != "tcp":
            return  # tls, inproc, ucx: the Client's own bounded connect judges them
        host, port = parse_host_port(loc, default_port=8786)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{where}: not an address ({exc}); {expected}") from None
    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection((host, int(port)), timeout=timeout)
    except TimeoutError:
        raise InputError(f"{where}: no answer within {timeout:g} s; {expected}") from None
    except OSError as exc:
        raise InputError(
            f"{where}: cannot reach a Dask scheduler there ({exc.strerror or exc}); is it running? {expected}"
        ) from None
    got = b""

    def read(n: int) -> bytes:
        nonlocal got
        while len(got) < n:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError()
            sock.settimeout(left)
            part = sock.recv(min(n - len(got), 65536))
            if not part:
                raise ConnectionError()
            got += part
        return got[:n]

    def shown() -> str:
        nonlocal got
        if len(got) < 40:  # the rest of its first line, if it came with it
            with contextlib.suppress(OSError):
                sock.settimeout(0.05)
                got += sock.recv(40 - len(got))
        line = got[:40].replace(b"\r", b"\n").split(b"\n")[0]
        if line and all(32 <= b < 127 for b in line):
            return repr(line.decode("ascii"))  # a text protocol's greeting: 'HTTP/1.1 400 Bad Request'
        return f"the bytes {got[:16].hex(' ')}"

    with sock:
        try:
            (size,) = struct.unpack("Q", read(8))
            if not 16 <= size <= MAX_GREETING:
                raise ValueError()
            (frames,) = struct.unpack("Q", read(16)[8:])
            if not 1 <= frames <= 64 or 8 + 8 * frames > size:
                raise ValueError()
            lengths = struct.unpack(f"{frames}Q", read(16 + 8 * frames)[16:])
            if sum(lengths) != size - 8 - 8 * frames:
                raise ValueError()
            if b"pickle-protocol" not in read(8 + size):
                raise ValueError()
        except TimeoutError:
            what = (
                f"something listens there but sent no Dask greeting within {timeout:g} s"
                if not got
                else f"what answers there is not a Dask scheduler (it sent {shown()} and no more within {timeout:g} s)"
            )
            raise InputError(f"{where}: {what}; {expected}") from None
        except (ConnectionError, OSError):
            what = "the connection was closed without a Dask greeting" if not got else f"it sent {shown()} and closed"
            raise InputError(f"{where}: not a Dask scheduler ({what}); {expected}") from None
        except ValueError:
            raise InputError(
                f"{where}: what answers there is not a Dask scheduler (it sent {shown()}, not a Dask message); {expected}"
            ) from None


def connect(address: str, timeout: float = SCHEDULER_TIMEOUT):
    """A ``dask.distributed.Client`` for ``address``, or an InputError within about ``timeout`` s.

    A tcp address is probed first (:func:`_probe_scheduler`): what answers must greet as a
    Dask scheduler does within ``timeout``; a port that is closed, silent or another server's
    is refused naming the address and what is expected.  The client's own connection is
    bounded by ``timeout`` too.

    Parameters
    ----------
    address : str
        Scheduler address, e.g. ``tcp://127.0.0.1:8786``.
    timeout : float
        Seconds [s] to wait for the scheduler (the probe, then the client, each).
    """
    if not isinstance(address, str) or not address.strip():
        raise InputError(f"scheduler = {address!r}: give a Dask scheduler's address, e.g. tcp://127.0.0.1:8786")
    try:
        from dask.distributed import Client  # (here: dask is an optional extra)
    except ImportError:
        raise InputError(f"scheduler = {address!r}: Dask is not installed; install springdyn[dask]") from None
    _probe_scheduler(address, timeout)
    try:
        # not the process's default client: the runs hand it their chunks themselves, and a
        # default one outlives its close in dask's configuration (later dask computations,
        # xarray's among them, would then ask a scheduler that is gone)
        return Client(address, timeout=f"{timeout}s", set_as_default=False)
    except (OSError, TimeoutError, ValueError) as exc:
        raise InputError(
            f"scheduler = {address!r}: cannot reach a Dask scheduler there within {timeout:g} s ({type(exc).__name__}: "
            f"{str(exc).splitlines()[0] if str(exc) else 'no answer'})"
        ) from None


#: Largest engine output of one chunk [bytes]: bounds the memory of sweeps of big chains.
CHUNK_BYTES = 32 * 2**20


#: Most speeds in a chunk: each chunk continues its speeds from one to the next, and the
#: chunks are shared out to the workers.
CHUNK_SPEEDS = 25
#: Chunks a sweep is cut into at least, where it has the speeds.
MIN_CHUNKS = 8


def _chunks(cam_rpm: np.ndarray, max_size: int) -> list[np.ndarray]:
    """The speeds (ascending) cut into chunks that depend on the speeds alone, not on the
    workers: a local and a Dask sweep continue the same speeds from the same neighbours,
    so their results agree bit for bit."""
    size = max(1, min(math.ceil(cam_rpm.size / MIN_CHUNKS), CHUNK_SPEEDS, max_size))
    return [cam_rpm[i : i + size] for i in range(0, cam_rpm.size, size)]


def _run_speeds(setup, cam_rpm, settings, points, workers, client, quiet, desc, starts=None):
    """Run all speeds for one setup; returns the chunk outputs concatenated in the order of
    ``cam_rpm`` (the chunks run them ascending)."""
    per_speed = 8 * points * (setup.layout["size"] + 1)  # the last revolution's outputs
    max_size = max(1, CHUNK_BYTES // per_speed)
    order = np.argsort(cam_rpm, kind="stable")
    chunks = _chunks(cam_rpm[order], max_size)
    if client is not None:
        remote_setup = client.scatter(setup, broadcast=True)
        futures = [client.submit(run_chunk, remote_setup, c, settings, points, starts, pure=False) for c in chunks]
        from dask.distributed import as_completed as dask_completed  # (here: dask is an optional extra)

        done = dask_completed(futures, loop=client.loop)  # this client's: connect() sets no default client
        for _ in progress(done, total=len(futures), desc=desc, quiet=quiet):
            pass
        parts = [f.result() for f in futures]
    else:
        workers = workers or min(os.cpu_count() or 1, 2)
        with ThreadPoolExecutor(max_workers=workers) as pool:
            futures = [pool.submit(run_chunk, setup, c, settings, points, starts) for c in chunks]
            for _ in progress(as_completed(futures), total=len(futures), desc=desc, quiet=quiet):
                pass
            parts = [f.result() for f in futures]
    back = np.empty_like(order)
    back[order] = np.arange(order.size)
    out = {k: np.concatenate([p[k] for p in parts])[back] for k in parts[0]}
    if "state" in out:  # warm starts: the sweep's periodic states, for the runs after it
        _record_states(starts, setup, cam_rpm, out)
    return out


def _record_states(starts: PeriodicStates, setup: SimulationSetup, cam_rpm, out: dict) -> None:
    """Record the periodic states of a sweep's speeds (``out["state"]``, ``out["status"]``)
    into ``starts``, in speed order (the order of the chunks' finishing does not matter)."""
    for rpm, state, status in zip(cam_rpm, out.pop("state"), out["status"]):
        if status == 0:
            starts.add(float(rpm), state, setup.y0)


@dataclass(repr=False)
class SpeedSweep(CrankAngles, Result):
    """Results of a speed sweep, optionally over a design variable (SI).

    ``plot(path)`` draws the forces against speed; :meth:`plot_all` writes every sweep
    figure (forces, speed x angle map, Campbell diagram, contact force) into a folder and
    :meth:`write` the NetCDF, the summary CSV and the figures.
    """

    spring: ValveSpring
    cam: Cam
    valve_train: ValveTrain | None
    cam_rpm: np.ndarray  # (n_rpm,)
    cam_angle: np.ndarray  # (n_angle,) [rad]
    lift: np.ndarray  # (n_angle,) [m]
    vary_name: str | None
    vary_values: np.ndarray  # (n_vary,), [nan] without a design variable
    springs: list  # ValveSpring per vary value
    data: dict  # arrays (n_vary, n_rpm, ...) and static (n_vary, [n_rpm,] n_angle)
    skipped: list  # (value, reason) of invalid design values
    #: The tolerance [fraction of Fset] under which a speed's last two revolutions repeat.
    periodicity_tol: float = PERIODICITY_TOL
    #: Notes on how the sweep was asked for (speeds beyond reason computed on request).
    flags: list = dataclasses.field(default_factory=list)
    #: Crank angles and engine speeds beside the cam's (:mod:`springdyn.valve.cam.timing`; the
    #: CLI sets it for an engine speed or a ``[timing]`` table): None for cam angles only.
    crank_axis: object = None

    title = "valve spring speed sweep"

    @property
    def engine_rpm(self) -> np.ndarray | None:
        """Engine speeds [rev/min] of the sweep's cam speeds (None without a crank axis)."""
        return None if self.crank_axis is None else self.crank_axis.per_cam * self.cam_rpm

    def _repr_caption(self) -> str:
        text = (
            f"{self.spring.type} spring, {self.cam.law} cam, {self.cam_rpm.size} speeds "
            f"{self.cam_rpm.min():g}-{self.cam_rpm.max():g} cam rpm"
        )
        return text + (f", {self.vary_values.size} values of {self.vary_name}" if self.vary_name else "")

    def vary_label(self, k: int) -> str:
        """``'installed_length = 36 mm'`` for the design value ``k``.

        Parameters
        ----------
        k : int
            Index of the design value [-].
        """
        return describe_design_value(self.vary_name, self.vary_values[k]) if self.vary_name else ""

    def _summary(self) -> dict:
        t = self.summary_table()
        s = dict(
            spring=self.spring.coil_facts,  # the coils and solid length the sweep used
            speeds=int(self.cam_rpm.size),
            cam_rpm_min=float(self.cam_rpm.min()),
            cam_rpm_max=float(self.cam_rpm.max()),
            design_values=int(self.vary_values.size),
            vary=self.vary_name or "none",
            max_retainer_force_N=float(np.max(t["max_retainer_force_N"])),
            min_retainer_force_N=float(np.min(t["min_retainer_force_N"])),
            max_seat_force_N=float(np.max(t["max_seat_force_N"])),
            min_seat_force_N=float(np.min(t["min_seat_force_N"])),
            max_retainer_surge_amplitude_N=float(np.max(t["retainer_surge_amplitude_N"])),
            speeds_with_coil_contact=int(np.count_nonzero(t["coil_contact"])),
            speeds_with_coil_clash=int(np.count_nonzero(t["coil_clash"])),
            speeds_with_transition_seating=int(np.count_nonzero(t["transition_seating"])),
            speeds_with_active_coil_closing=int(np.count_nonzero(t["active_coil_closing"])),
            max_clash_severity=float(np.max(t["clash_severity"])),
            clash_severity_limit=verdicts.MAX_CLASH_SEVERITY,
            skipped_design_values=len(self.skipped),
        )
        s["max_periodicity_error"] = float(np.max(t["periodicity_error"])) if "periodicity_error" in t else None
        s["speeds_not_periodic"] = int(np.count_nonzero(~t["periodic"]))
        s["max_revolutions_run"] = int(np.max(t["revolutions"]))
        if self.valve_train is not None:
            fl = self.float_speeds()
            s["lowest_float_cam_rpm"] = float(np.nanmin(fl)) if np.isfinite(fl).any() else None
            first = self.first_separation_speeds()
            s["lowest_first_separation_cam_rpm"] = float(np.nanmin(first)) if np.isfinite(first).any() else None
            s["max_seat_landings"] = int(np.max(t["seat_landings"]))
            s["max_seat_rebound_height_m"] = float(np.max(t["seat_rebound_height_m"]))
        s["min_fatigue_safety_factor"] = float(np.min(t["fatigue_safety_factor"]))
        s["peak_shear_stress_Pa"] = float(np.max(t["peak_shear_stress_Pa"]))
        bad = np.flatnonzero(~t["wire_stress_ok"])
        s["speeds_with_wire_overstress"] = int(bad.size)
        notes = list(self.flags)
        if bad.size:
            k = int(bad[np.argmax(t["peak_shear_stress_Pa"][bad])])
            notes.append(
                f"WIRE OVERSTRESS at {bad.size} speeds: the worst, element {t['peak_shear_stress_element'][k]} at "
                f"{t['cam_rpm'][k]:g} cam rpm, {t['peak_shear_stress_Pa'][k] / 1e6:.0f} MPa above the wire's limit "
                "(shear_yield_strength, else the ultimate shear strength)"
            )
        if s["speeds_not_periodic"]:
            notes.append(
                f"{s['speeds_not_periodic']} speeds did not settle within their revolutions (the last two differ by "
                f"more than {100 * self.periodicity_tol:g} % of Fset): their extremes are reported as bands over the "
                "last revolutions (columns *_lo_N, *_hi_N)"
            )
        if self.spring.model == "distributed" and s["speeds_with_coil_contact"]:
            notes.append(
                "coil contact at some speeds: the distributed model's clash forces depend on the element "
                "count (docs/valve.md); valve simulate at such a speed measures how much"
            )
        if notes:
            s["notes"] = notes
        return s

    def describe(self, where: str = "") -> str:
        """The sweep in words (what ``springdyn valve sweep`` prints): the speeds, the peak
        retainer force, coil contact and clash, periodicity, float and first lift-off per design
        value, pump-up, the notes, skipped design values and the first mode's resonances.

        Parameters
        ----------
        where : str
            Where it ran (``"locally"``, ``"on tcp://..."``), for the first line [-].
        """
        table = self.summary_table()
        sm = self.summary
        engine = self.crank_axis is not None

        def speed(rpm):  # a cam speed, with the engine's beside it when the sweep has crank angles
            return f"{rpm:g} cam rpm" + (f" ({self.crank_axis.per_cam * rpm:g} engine rpm)" if engine else "")

        rpms = self.cam_rpm
        out = [
            coil_line(self.spring.coil_facts),
            f"swept {rpms.size} speeds ({rpms.min():g}-{rpms.max():g} cam rpm"
            + (f", {self.engine_rpm.min():g}-{self.engine_rpm.max():g} engine rpm)" if engine else ")")
            + (f" x {self.vary_values.size} values of {self.vary_name}" if self.vary_name else "")
            + (f" {where}" if where else ""),
        ]
        k = int(np.argmax(table["max_retainer_force_N"]))
        out.append(
            f"peak retainer force {table['max_retainer_force_N'][k]:.1f} N at {speed(table['cam_rpm'][k])} "
            f"(static peak {table['max_static_force_N'][k]:.1f} N); coil contact at "
            f"{int(np.sum(table['coil_contact']))} of {table['cam_rpm'].size} runs"
        )
        out.append(_clash_line(table, speed))
        out.append(
            f"periodic steady state: {table['cam_rpm'].size - sm['speeds_not_periodic']} of {table['cam_rpm'].size} "
            f"runs settled within {100 * self.periodicity_tol:g} % of Fset ({np.mean(table['revolutions']):.1f} "
            "revolutions on average)"
            + (
                f"; {sm['speeds_not_periodic']} did not settle in {int(np.max(table['revolutions']))} revolutions: "
                "their extremes are bands (*_lo_N, *_hi_N in sweep_summary.csv)"
                if sm["speeds_not_periodic"]
                else ""
            )
        )
        if self.valve_train is not None:
            for v, f, first in zip(self.vary_values, self.float_speeds(), self.first_separation_speeds()):
                tag = f"{describe_design_value(self.vary_name, v)}: " if self.vary_name else ""
                out.append(
                    f"{tag}float speed "
                    + (
                        f"~{speed(f)} (lowest swept speed from which the valve leaves the cam over the nose at every "
                        "higher one; refine with 'springdyn valve float')"
                        if np.isfinite(f)
                        else "above the swept range"
                    )
                    + (f"; first lift-off at {speed(first)}" if np.isfinite(first) else "")
                )
        if "pump_up" in table:
            pumped = np.flatnonzero(np.asarray(table["pump_up"], dtype=bool))
            if pumped.size:
                out.append(
                    f"PUMP-UP: the hydraulic lash adjuster holds the valve open on the base circle from "
                    f"{speed(table['cam_rpm'][int(pumped[0])])} (up to {np.max(table['valve_held_open_m']) * 1e3:.3f} "
                    "mm; column valve_held_open_m)"
                )
        # every caveat (the periodicity one is the line above)
        out += notes_lines(sm, skip=(f"{sm['speeds_not_periodic']} speeds did not settle",))
        for value, reason in self.skipped:
            out.append(f"skipped {describe_design_value(self.vary_name, value)}: {reason}")
        first = [r for r in self.resonance_table() if r["mode"] == 1]
        if first:
            out.append(
                f"cam-order resonances of the first mode ({first[0]['frequency_Hz']:.0f} Hz at full lift): "
                + ", ".join(f"N={r['order']} at {r['cam_rpm']:.0f}" for r in first)
                + " cam rpm (all modes: sweep_resonances.csv)"
            )
        return "\n".join(out)

    # ---------------------------------------------------------------- summary
    def summary_table(self) -> dict:
        """One row per (design value, speed): peaks, surge, coil contact, lift-off."""
        d = self.data
        nv, nr = d["retainer"].shape[:2]
        static = d["static"] if d["static"].ndim == 3 else np.broadcast_to(d["static"][:, None, :], d["retainer"].shape)
        cols = {}
        if self.vary_name:
            unit = _field_unit(self.vary_name)
            cols[f"{self.vary_name}_{unit}" if unit else self.vary_name] = np.repeat(self.vary_values, nr)
        cols["cam_rpm"] = np.tile(self.cam_rpm, nv)
        if self.crank_axis is not None:
            cols["engine_rpm"] = np.tile(self.engine_rpm, nv)
        flat = lambda a: a.reshape(nv * nr, *a.shape[2:])  # noqa: E731
        r, s, st = flat(d["retainer"]), flat(d["seat"]), flat(np.ascontiguousarray(static))
        ext = flat(d["ext"])
        col = {name: i for i, name in enumerate(EXT)}
        cols.update(
            # true extremes from the dense output (never less extreme than the grid samples)
            max_retainer_force_N=np.maximum(ext[:, col["max_retainer_force"]], r.max(axis=1)),
            min_retainer_force_N=np.minimum(ext[:, col["min_retainer_force"]], r.min(axis=1)),
            max_seat_force_N=np.maximum(ext[:, col["max_seat_force"]], s.max(axis=1)),
            min_seat_force_N=np.minimum(ext[:, col["min_seat_force"]], s.min(axis=1)),
            max_static_force_N=st.max(axis=1),
            min_static_force_N=st.min(axis=1),
            retainer_surge_amplitude_N=np.abs(r - st).max(axis=1),
            seat_surge_amplitude_N=np.abs(s - st).max(axis=1),
            coil_contact=flat(d["contact"]).any(axis=1),
            coil_clash=flat(d["clash"]),
            clash_severity=flat(d["clash_severity"]),
            transition_seating=flat(d["clash_transition"]),
            active_coil_closing=flat(d["clash_active"]),
            clash_closing_velocity_m_per_s=flat(d["clash_closing_velocity_m_per_s"]),
            clash_contact_share=flat(d["clash_contact_share"]),
            end_separation=flat(d["separation"]) > 0,
            peak_coil_contact_force_N=flat(d["contact_force"]).max(axis=1),
        )
        if np.all(np.isfinite(d["periodicity"])):  # not with 1 revolution per speed: nothing to compare
            cols["periodicity_error"] = flat(d["periodicity"])
        cols["revolutions"] = flat(d["revolutions"])
        cols["periodic"] = flat(d["periodicity"]) <= self.periodicity_tol
        # a speed that does not settle: the band of its extremes over its last revolutions
        # (a settled one: the value itself)
        lo, hi = flat(d["band_lo"]), flat(d["band_hi"])
        for name in ("max_retainer_force", "min_retainer_force", "max_seat_force", "min_seat_force"):
            k = col[name]
            value = cols[f"{name}_N"]
            cols[f"{name}_lo_N"] = np.where(cols["periodic"], value, np.minimum(lo[:, k], value))
            cols[f"{name}_hi_N"] = np.where(cols["periodic"], value, np.maximum(hi[:, k], value))
        if self.valve_train is not None:
            cols.update(self._separation_columns(cols, ext, col, lo, hi, flat, nv, nr))
        cols.update(self._fatigue_columns(cols, nv, nr))
        if "spring_retainer_min" in d:  # a spring pack: each spring's columns, <spring>_<column>
            for k, name in enumerate(self.spring.names):
                cols.update(
                    {
                        f"{name}_max_retainer_force_N": flat(d["spring_retainer_max"][:, :, k]),
                        f"{name}_min_retainer_force_N": flat(d["spring_retainer_min"][:, :, k]),
                        f"{name}_max_static_force_N": flat(d["spring_static_max"][:, :, k]),
                        f"{name}_min_static_force_N": flat(d["spring_static_min"][:, :, k]),
                        f"{name}_clash_severity": flat(d["spring_clash_severity"][:, :, k]),
                        f"{name}_coil_clash": flat(d["spring_clash_clash"][:, :, k]),
                        f"{name}_transition_seating": flat(d["spring_clash_transition"][:, :, k]),
                        f"{name}_active_coil_closing": flat(d["spring_clash_active"][:, :, k]),
                    }
                )
        return cols

    def spring_table(self, name: str) -> dict:
        """One spring's columns of a spring pack's :meth:`summary_table`, under the names of a
        single spring's (``min_retainer_force_N``, ``clash_severity``, ``fatigue_safety_factor``,
        ...): its retainer force on the output grid, its static force, its coil clash over its
        own Fset (:func:`springdyn.valve.run.verdicts.spring_clashes`) and its wire's fatigue and
        stress from its own elements (elements counted from its seat end), beside the sweep's
        ``cam_rpm``.

        Parameters
        ----------
        name : {"outer", "inner", "third"}
            The spring [-].
        """
        names = getattr(self.spring, "names", None)
        if names is None or name not in names:
            raise InputError(
                f"spring {name!r}: the sweep's spring is "
                + (f"a pack of {', '.join(names)}" if names else "one spring, not a pack (summary_table is its table)")
            )
        table = self.summary_table()
        head = {k: table[k] for k in ("cam_rpm", "engine_rpm") if k in table}
        return head | {k[len(name) + 1 :]: v for k, v in table.items() if k.startswith(f"{name}_")}

    def _separation_columns(self, cols, ext, col, lo, hi, flat, nv, nr) -> dict:
        """Lift-off by phase, float (nose separation), seat bounce and the seating velocity
        band per speed (:mod:`springdyn.valve.run.separation`)."""
        d = self.data
        rows = flat(d["liftoff"])
        phase = rows[:, :, LIFTOFF_COLUMNS.index("phase")]
        z = flat(d["valve_lift"])
        out = {}
        lash = self.valve_train.lobe_lash
        in_event = verdicts.valve_open(self.lift, z, lash)
        cc = np.where(in_event, flat(d["cam_contact"]), np.inf)
        dense = ext[:, col["min_cam_contact_force"]]
        out["liftoff"] = np.isfinite(rows[:, :, 0]).any(axis=1) | (cc <= 0.0).any(axis=1) | (dense <= 0.0)
        out["nose_separation"] = verdicts.floats_over_nose(
            (phase == PHASES.index("nose")).any(axis=1),
            phase_mask(self.cam_angle, cam_phases(self.cam, lash), "nose"),
            flat(d["cam_contact"]),
            z,
        )
        first = np.where(np.isfinite(phase[:, 0]), phase[:, 0], -1).astype(int)
        out["first_liftoff_phase"] = np.array([(*PHASES, "base circle")[k] if k >= 0 else "" for k in first])
        out["max_liftoff_gap_m"] = np.nan_to_num(
            np.nanmax(np.where(np.isfinite(rows[:, :, 4]), rows[:, :, 4], 0.0), axis=1)
        )
        grid = np.where(np.isfinite(cc.min(axis=1)), cc.min(axis=1), 0.0)
        out["min_cam_contact_force_N"] = np.maximum(np.fmin(dense, grid), 0.0)
        # seat bounce: landings per revolution, the largest rebound off the seat after the
        # first landing (the lobe back on its base circle)
        out["seat_landings"] = ext[:, col["seat_landings"]].astype(int)
        out["seat_rebound_height_m"] = verdicts.seat_rebound_height(self.lift, z, lash)
        if self.valve_train.hla is not None:
            out["valve_held_open_m"] = verdicts.valve_held_open(self.lift, z)
            out["pump_up"] = verdicts.pumps_up(out["valve_held_open_m"])
        v = ext[:, col["seat_impact_velocity"]]
        out["seat_impact_velocity_m_per_s"] = v
        # the seating velocity band: over the speeds within SEATING_BAND_RPM and, for a speed
        # that does not settle, over its last revolutions
        k = col["seat_impact_velocity"]
        vlo = np.where(cols["periodic"], v, np.minimum(lo[:, k], v))
        vhi = np.where(cols["periodic"], v, np.maximum(hi[:, k], v))
        blo, bmed, bhi = (np.empty(v.size) for _ in range(3))
        for i in range(nv):
            sl = slice(i * nr, (i + 1) * nr)
            a, _, _ = neighbour_band(self.cam_rpm, vlo[sl])
            _, m, _ = neighbour_band(self.cam_rpm, v[sl])
            _, _, b = neighbour_band(self.cam_rpm, vhi[sl])
            blo[sl], bmed[sl], bhi[sl] = a, m, b
        out["seat_impact_velocity_min_m_per_s"] = blo
        out["seat_impact_velocity_median_m_per_s"] = bmed
        out["seat_impact_velocity_max_m_per_s"] = bhi
        return out

    def _fatigue_columns(self, cols, nv, nr) -> dict:
        """Goodman fatigue factor against speed (issue 13): every element's wire torsion
        (its force less what closed coils pass through their contact) between its smallest
        and largest value of the revolution (an end element without coil contact from the
        true extremes of the end force), and the static cycle; per design value, from that
        variant's wire and strengths.  Also the largest wire stress against the limit."""
        d = self.data
        wmin = d["wire_min"].reshape(nv * nr, -1)
        wmax = d["wire_max"].reshape(nv * nr, -1)
        dyn, sta, tau, crit = (np.empty(nv * nr) for _ in range(4))
        ok = np.empty(nv * nr, dtype=bool)
        per = {}
        static_lo, static_hi = cols["min_static_force_N"], cols["max_static_force_N"]
        if "spring_static_min" in d:  # a spring pack: each spring's own static range
            static_lo, static_hi = (d[k].reshape(nv * nr, -1) for k in ("spring_static_min", "spring_static_max"))
        for k in range(nv * nr):
            f = verdicts.wire_fatigue(
                self.springs[k // nr],
                wmin[k],
                wmax[k],
                (cols["min_seat_force_N"][k], cols["min_retainer_force_N"][k]),
                (cols["max_seat_force_N"][k], cols["max_retainer_force_N"][k]),
                static_lo[k],
                static_hi[k],
            )
            dyn[k] = f["fatigue_safety_factor"] if f["fatigue_safety_factor"] is not None else 0.0
            sta[k] = f["static_fatigue_safety_factor"] if f["static_fatigue_safety_factor"] is not None else 0.0
            tau[k], crit[k], ok[k] = f["peak_shear_stress_Pa"], f["peak_shear_stress_element"] + 1, f["wire_stress_ok"]
            for name, g in f.get("springs", {}).items():  # a spring pack: each spring's own
                per.setdefault(name, []).append(g)
        out = dict(
            fatigue_safety_factor=dyn,
            static_fatigue_safety_factor=sta,
            peak_shear_stress_Pa=tau,
            peak_shear_stress_element=crit.astype(int),
            wire_stress_ok=ok,
        )
        for name, rows in per.items():
            for key in ("fatigue_safety_factor", "static_fatigue_safety_factor"):
                out[f"{name}_{key}"] = np.array([g[key] if g[key] is not None else 0.0 for g in rows])
            out[f"{name}_peak_shear_stress_Pa"] = np.array([g["peak_shear_stress_Pa"] for g in rows])
            out[f"{name}_peak_shear_stress_element"] = np.array([g["peak_shear_stress_element"] + 1 for g in rows])
            out[f"{name}_wire_stress_ok"] = np.array([g["wire_stress_ok"] for g in rows])
        return out

    def float_speeds(self) -> np.ndarray:
        """Float speed per design value [rpm]: the lowest swept speed from which the valve
        separates over the nose at every higher swept speed
        (:func:`springdyn.valve.run.separation.float_speed_of_scan`; nan: not at the highest
        speed, or no valve train)."""
        out = np.full(self.vary_values.size, np.nan)
        if self.valve_train is None:
            return out
        order = np.argsort(self.cam_rpm, kind="stable")
        nose = self.summary_table()["nose_separation"].reshape(self.vary_values.size, self.cam_rpm.size)
        for i, row in enumerate(nose):
            f = float_speed_of_scan(self.cam_rpm[order], row[order])
            out[i] = np.nan if f is None else f
        return out

    def first_separation_speeds(self) -> np.ndarray:
        """Lowest swept speed with any lift-off (any phase) per design value [rpm] (nan: none)."""
        out = np.full(self.vary_values.size, np.nan)
        if self.valve_train is None:
            return out
        lo = self.summary_table()["liftoff"].reshape(self.vary_values.size, self.cam_rpm.size)
        for i, row in enumerate(lo):
            if row.any():
                out[i] = np.min(self.cam_rpm[row])
        return out

    # ---------------------------------------------------------------- outputs
    def to_xarray(self):
        """Dataset with dimensions ``(vary,) cam_rpm, cam_angle`` (angle in degrees)."""
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        d = self.data
        dims = ("vary", "cam_rpm", "cam_angle")
        data = {
            "retainer_force": (dims, d["retainer"], {"units": "N"}),
            "seat_force": (dims, d["seat"], {"units": "N"}),
            "in_coil_contact": (
                dims,
                d["contact"].astype(np.int8),
                {"long_name": "a Kh element past its Fcon breakpoint"},
            ),
            "coil_contact_force": (
                dims,
                d["contact_force"],
                {"units": "N", "long_name": "largest force of an element in coil contact"},
            ),
            "lift": (("cam_angle",), self.lift, {"units": "m"}),
        }
        if np.all(np.isfinite(d["periodicity"])):
            data["periodicity_error"] = (
                dims[:2],
                d["periodicity"],
                {"units": "1", "long_name": "max change from the previous revolution / Fset"},
            )
        if d["static"].ndim == 3:
            data["static_force"] = (dims, d["static"], {"units": "N"})
        else:
            data["static_force"] = (("vary", "cam_angle"), d["static"], {"units": "N"})
        if self.valve_train is not None:
            data["cam_contact_force"] = (dims, d["cam_contact"], {"units": "N"})
            data["valve_lift"] = (dims, d["valve_lift"], {"units": "m"})
            data["float_cam_rpm"] = (("vary",), self.float_speeds(), {"units": "rpm"})
        for key, values in self.summary_table().items():
            if key in ("cam_rpm", "engine_rpm") or (self.vary_name and key.startswith(self.vary_name)):
                continue
            values = np.asarray(values).reshape(self.vary_values.size, self.cam_rpm.size)
            if values.dtype == bool:
                values = values.astype(np.int8)
            data[key] = (dims[:2], values, {"units": units_from_name(key)})
        ds = xr.Dataset(
            data,
            coords={
                "vary": ("vary", self.vary_values, {"long_name": self.vary_name or "none"}),
                "cam_rpm": ("cam_rpm", self.cam_rpm, {"units": "rpm"}),
                "cam_angle": ("cam_angle", np.degrees(self.cam_angle), {"units": "deg"}),
                **(
                    {
                        "engine_rpm": ("cam_rpm", self.engine_rpm, {"units": "rpm"}),
                        "crank_angle": (
                            "cam_angle",
                            self.crank_axis.crank_deg(np.degrees(self.cam_angle)),
                            {
                                "units": "deg",
                                "origin": "gas-exchange TDC" if self.crank_axis.referenced else "cam angle 0",
                            },
                        ),
                    }
                    if self.crank_axis is not None
                    else {}
                ),
            },
            attrs={
                "spring_type": self.spring.type,
                "cam_law": self.cam.law,
                "vary_name": self.vary_name or "",
                "valve_train": int(self.valve_train is not None),
            },
        )
        return ds if self.vary_name else ds.isel(vary=0, drop=True)

    def to_netcdf(self, path):
        """Write :meth:`to_xarray` to NetCDF atomically.

        Parameters
        ----------
        path : str or Path
            The NetCDF file to write [-].
        """
        with atomic_path(path, suffix=".nc") as tmp:
            self.to_xarray().to_netcdf(tmp)
        return Path(path)

    def _csv_dataset(self):
        """The summary table (one row per speed and design value) as a one-dimensional dataset."""
        import xarray as xr  # (here: xarray costs 0.4 s of start-up)

        table = self.summary_table()
        return xr.Dataset(
            {
                k: ("row", (np.asarray(v).astype(int) if np.asarray(v).dtype == bool else np.asarray(v)), {"units": ""})
                for k, v in table.items()
            },
            coords={},
        )

    def _plot(self, ax=None):
        from .plots import plot_sweep_forces  # (here: matplotlib costs 0.3 s of start-up)

        return plot_sweep_forces(self, ax=ax)

    def plot(self, path=None, ax=None, prefix: str = "sweep"):
        """Plot the forces against speed; return the figure (``path``: that PNG file).

        Earlier versions took an output folder here and wrote every sweep figure into it:
        a path that is an existing folder still does that, with a DeprecationWarning
        (use :meth:`plot_all`).

        Parameters
        ----------
        path : str or Path, optional
            The PNG file to write [-].
        ax : matplotlib Axes, optional
            Draw there [-].
        prefix : str
            File name prefix of a folder's figures [-].
        """
        if path is not None and Path(path).is_dir():
            warnings.warn(
                "SpeedSweep.plot(folder) is deprecated: use plot_all(folder)", DeprecationWarning, stacklevel=2
            )
            return self.plot_all(path, prefix)
        return super().plot(path, ax=ax)

    @_DOCS.fill
    def plot_all(self, out_dir, prefix: str = "sweep") -> list[Path]:
        """Write every sweep figure as PNG into the folder ``out_dir``; returns their paths.

        Parameters
        ----------
        {out_dir prefix}
        """
        from .plots import plot_sweep  # (here: matplotlib costs 0.3 s of start-up)

        out_dir = Path(out_dir)
        out_dir.mkdir(parents=True, exist_ok=True)
        return plot_sweep(self, out_dir, prefix)

    def resonance_table(self) -> list[dict]:
        """Cam speeds in the swept range where a cam order meets a natural frequency.

        ``cam rpm = 60 f / N`` (N up to 20) for the modes of the spring (and valve train)
        linearised at full lift (:func:`springdyn.valve.run.train_modes.natural_frequencies`; the
        base-circle modes where full lift has none).  Rows: ``mode``, ``frequency_Hz``,
        ``order``, ``cam_rpm``.
        """
        return list(self._resonances)

    @cached_property
    def _resonances(self) -> list[dict]:
        """:meth:`resonance_table`, computed once per sweep (a linearisation and a root search)."""

        nat = natural_frequencies(self.spring, self.cam, self.valve_train, count=6)
        return resonance_speeds(
            nat["full_lift_Hz"] or nat["base_circle_Hz"], float(np.min(self.cam_rpm)), float(np.max(self.cam_rpm))
        )

    @_DOCS.fill
    def write(self, out_dir, prefix: str = "sweep") -> list[Path]:
        """NetCDF, summary CSV, the cam-order resonance table and plots into ``out_dir``.

        Parameters
        ----------
        {out_dir prefix}
        """
        out_dir = Path(out_dir)
        out_dir.mkdir(parents=True, exist_ok=True)
        written = [self.to_netcdf(out_dir / f"{prefix}.nc"), self.to_csv(out_dir / f"{prefix}_summary.csv")]
        rows = self.resonance_table()
        written.append(
            write_csv(
                out_dir / f"{prefix}_resonances.csv",
                {
                    "mode": [r["mode"] for r in rows],
                    "frequency_Hz": [r["frequency_Hz"] for r in rows],
                    "cam_order": [r["order"] for r in rows],
                    "cam_rpm": [r["cam_rpm"] for r in rows],
                },
            )
        )
        return written + self.plot_all(out_dir, prefix)


def _field_unit(name: str) -> str:
    name = name.rpartition(".")[2]  # a pack's spring field: inner_spring.wire_diameter
    meta = {f.name: f.metadata for f in dataclasses.fields(ValveSpring)}
    return meta[name]["unit"].replace("/", "_per_").replace("^", "") if name in meta else ""


def sweep(
    spring: ValveSpring,
    cam: Cam,
    cam_rpm,
    *,
    valve_train: ValveTrain | None = None,
    settings: RunSettings | None = None,
    vary: tuple[str, np.ndarray] | None = None,
    on_invalid: str = "stop",
    workers: int | None = None,
    client=None,
    quiet: bool = True,
    gas_force=None,
    starts: PeriodicStates | None = None,
    **run,
) -> SpeedSweep:
    """Simulate ``spring`` at every cam speed in ``cam_rpm`` (and every design value).

    Parameters
    ----------
    spring : ValveSpring
        The spring definition.
    cam : Cam
        The cam.
    cam_rpm : array_like
        Camshaft speeds [rev/min], positive.
    valve_train : ValveTrain, optional
        Adds lift-off (see :func:`springdyn.valve.simulate`).
    settings : RunSettings, optional
        How each speed is integrated (:class:`~springdyn.valve.run.settings.RunSettings`):
        default each speed to its periodic steady state, continued from the slower speed before
        it (see :func:`run_chunk`), on 720 points a revolution; ``revolutions`` runs each speed
        from rest for that many; tolerances as for :func:`springdyn.valve.simulate` (tighter
        with a valve train); a speed that does not settle is marked (``periodic`` False) and
        reports bands; speeds beyond reason are refused unless ``allow_extreme_speeds``.
    vary : (str, array_like), optional
        A numeric :class:`ValveSpring` field and its values [SI unit of the field], an
        extra dimension; of a spring pack, one spring's field named by its table
        (``inner_spring.wire_diameter``, :meth:`springdyn.valve.spring.pack.SpringPack.spring_field`).
    on_invalid : {"stop", "skip"}
        What to do with a design value that makes the spring invalid.
    workers : int, optional
        Local threads [-] (default: both cores).
    client : dask.distributed.Client, optional
        Run the chunks on this cluster instead.
    quiet : bool
        No progress bar.
    gas_force : GasForce, optional
        The cylinder's gas force on the valve over the revolution [N], the same at every
        speed (:class:`springdyn.valve.train.gas_force.GasForce`; needs a valve train).
    starts : PeriodicStates, optional
        Warm starts (to the periodic state): each speed starts from the nearest known
        periodic state (a neighbouring design's, or this one's), not from the slower speed
        before it, and records its own (:class:`~springdyn.valve.run.periodicity.PeriodicStates`);
        the results agree with cold starts' within the periodicity tolerance.
    **run
        Fields of :class:`~springdyn.valve.run.settings.RunSettings` given one by one
        (``revolutions=3``, ``rtol=1e-7``, ...): they change ``settings``.
    """
    try:
        cam_rpm = np.atleast_1d(np.asarray(cam_rpm, dtype=float))
    except (TypeError, ValueError):
        raise InputError(f"cam_rpm = {cam_rpm!r} must be a speed or a list of speeds [rev/min]") from None
    if cam_rpm.ndim != 1:
        raise InputError(f"cam_rpm must be a flat list of speeds [rev/min], not an array of shape {cam_rpm.shape}")
    if cam_rpm.size == 0:
        raise InputError("cam_rpm is empty: give at least one speed")
    if not np.all(np.isfinite(cam_rpm)) or np.any(cam_rpm <= 0):
        bad = cam_rpm[~(np.isfinite(cam_rpm) & (cam_rpm > 0))][0]
        raise InputError(f"cam_rpm = {bad:g} must be positive (every speed of the sweep)")
    settings = RunSettings.of(settings, **run)
    if on_invalid not in ("stop", "skip"):
        raise InputError(f"on_invalid = {on_invalid!r} must be 'stop' or 'skip'")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, (int, np.integer)) or workers < 1):
        raise InputError(f"workers = {workers!r} must be a whole number of at least 1")
    springs, setups, values, skipped = _design_variants(spring, cam, valve_train, vary, on_invalid, gas_force)
    flags = []
    if gas_force is not None:
        flags.append(
            f"with the gas force on the valve{' of ' + gas_force.source if gas_force.source else ''} "
            f"(up to {float(gas_force.force.max()):.0f} N), the same trace against crank angle at every speed"
        )
    for setup in setups:
        flags += [f for f in check_speeds(setup, cam_rpm, settings.allow_extreme_speeds) if f not in flags]
    points = settings.points(SWEEP_POINTS_PER_REVOLUTION)
    theta = output_angles(points)
    lift = cam.lift_at(theta)
    results = []
    f1 = float(spring.spring_model.modes(spring.installed_length, 1)[0])
    with warnings.catch_warnings():
        warnings.simplefilter("once")
        cam.check_resolution(float(cam_rpm.min()), f1)
    for k, setup in enumerate(setups):
        desc = "valve sweep" + (f" {_describe(vary[0], values[k])}" if vary else "")
        res = _run_speeds(setup, cam_rpm, settings, points, workers, client, quiet, desc, starts)
        failed = np.flatnonzero(res["status"] != 0)
        if failed.size:
            i = int(failed[0])
            info = dict(status=int(res["status"][i]), t=float(res["t"][i]), steps=int(res["steps"][i]))
            raise solver_error(float(cam_rpm[i]), rpm_to_omega(cam_rpm[i]), info)
        if valve_train is None:
            res["static"] = static_force_along_grid(setup, points)  # the same as a simulation's
        results.append(res)
    data = {key: np.stack([r[key] for r in results]) for key in results[0]}
    return SpeedSweep(
        spring,
        cam,
        valve_train,
        cam_rpm,
        theta,
        lift,
        vary[0] if vary else None,
        values,
        springs,
        data,
        skipped,
        settings.periodicity_tol,
        flags,
    )


def describe_design_value(name: str, value: float) -> str:
    """``'installed_length = 36 mm'`` for a design value in SI.

    Parameters
    ----------
    name : str
        A numeric :class:`ValveSpring` field.
    value : float
        Its value [SI unit of the field].
    """
    return _describe(name, value)


def _describe(name: str, value: float) -> str:
    meta = {f.name: f.metadata for f in dataclasses.fields(ValveSpring)}
    return f"{name} = {describe_value(float(value), meta[name.rpartition('.')[2]])}"


def _design_variants(spring, cam, valve_train, vary, on_invalid, gas_force=None):
    """Valid springs (and their prepared setups) for every design value."""
    if vary is None:
        return [spring], [prepare(spring, cam, valve_train, gas_force)], np.array([np.nan]), []
    name, values = vary
    numeric = [f.name for f in dataclasses.fields(ValveSpring) if f.metadata.get("kind") == "quantity"]
    pack = getattr(spring, "springs", None) is not None
    if pack:  # a spring pack: one spring's field, inner_spring.wire_diameter
        with_value = spring.with_field
        try:
            spring.spring_field(name)
        except InputError as exc:
            raise InputError(f"vary = {exc}") from None
    elif "." in name:
        raise InputError(
            f"vary = {name!r}: the spring file holds one spring: name its field ({name.rpartition('.')[2]})"
        )
    else:
        with_value = lambda n, v: spring.replace(**{n: v})  # noqa: E731
    if name.rpartition(".")[2] not in numeric:
        raise InputError(f"vary = {name!r}: not a numeric spring field; choose one of {', '.join(numeric)}")
    values = np.atleast_1d(np.asarray(values, dtype=float))
    springs, setups, kept, skipped = [], [], [], []
    for v in values:
        try:
            sp = with_value(name, float(v))
            setups.append(prepare(sp, cam, valve_train, gas_force))
            springs.append(sp)
            kept.append(v)
        except InputError as exc:
            if on_invalid == "stop":
                said = str(exc).startswith(f"{name} = ")  # the spring's message names the value already
                raise InputError(
                    f"vary: {exc if said else f'{_describe(name, v)}: {exc}'} (on_invalid='skip' leaves such values out)"
                ) from None
            skipped.append((float(v), str(exc)))
            warnings.warn(f"vary: {_describe(name, v)} skipped: {exc}", stacklevel=3)
    if not springs:
        raise InputError(f"vary = {name!r}: every value makes the spring invalid")
    return springs, setups, np.asarray(kept), skipped
