"""The options and the model of every ``springdyn valve`` command: the run options, the spring
model option, the speed options, and the :class:`~springdyn.valve.ValveModel` built from a
command's files and options (:func:`model_of`)."""

from __future__ import annotations

import re

import numpy as np

import springdyn.valve as valve
from springdyn.app.cli.common import as_options, parse_range, quantity
from springdyn.core.errors import InputError

__all__ = [
    "RUN_OPTIONS",
    "run_options",
    "model_of",
    "run_settings",
    "cam_rpm_from_args",
    "add_inputs",
    "add_backend_option",
    "add_model_option",
    "add_speed_options",
    "add_revolution_options",
    "add_tolerance_options",
    "add_gas_options",
]

#: The API arguments of a dynamic run and the options that set them (for error messages).
RUN_OPTIONS = dict(
    cam_rpm="--cam-rpm",
    revolutions="--revolutions",
    periodicity_tol="--periodicity-tol",
    max_revolutions="--max-revolutions",
    allow_extreme_speeds="--allow-extreme-speeds",
    rtol="--rtol",
    atol="--atol",
    points_per_revolution="--points-per-revolution",
    resolution="--resolution",
    lift="--lift",
    backend="--backend",
)


# ----------------------------------------------------------------------------- options
#: The help of ``--cam`` where the cam is required.
CAM_HELP = "file with a [cam] table"
#: The help of an optional ``--valve-train`` that adds the train to the spring and cam.
TRAIN_HELP = "file with a [valve_train] table: adds lift-off"


def add_inputs(
    p, *, cam: bool = True, cam_help: str = CAM_HELP, train: str | None = None, train_required: bool = False
) -> None:
    """The spring file, ``--model``, ``--cam`` (required unless ``cam_help`` says otherwise) and,
    with its help ``train``, ``--valve-train``."""
    p.add_argument("spring", metavar="SPRING.toml", help="file with a [spring] table")
    add_model_option(p)
    if cam:
        p.add_argument("--cam", required=cam_help == CAM_HELP, metavar="CAM.toml", help=cam_help)
    if train is not None:
        p.add_argument("--valve-train", required=train_required, metavar="VT.toml", help=train)


def add_backend_option(p) -> None:
    p.add_argument(
        "--backend", choices=valve.BACKENDS, default="compiled", help="compiled engine (default) or the SciPy reference"
    )


def add_tolerance_options(p) -> None:
    p.add_argument(
        "--rtol",
        type=float,
        help=f"relative tolerance (default {valve.DEFAULT_RTOL:g}, {valve.TRAIN_RTOL:g} with a valve train)",
    )
    p.add_argument(
        "--atol",
        type=float,
        help="absolute tolerance on displacements in m, velocities get it x 2 pi f1/30 "
        f"(default {valve.DEFAULT_ATOL:g}, {valve.TRAIN_ATOL:g} with a valve train)",
    )


def add_revolution_options(p) -> None:
    p.add_argument(
        "--revolutions",
        type=int,
        metavar="N",
        help="run exactly N cam revolutions from rest (default: to the periodic steady state)",
    )
    p.add_argument(
        "--periodicity-tol",
        default=f"{100 * valve.PERIODICITY_TOL:g} %",
        metavar="TOL",
        help="periodic steady state: the last two revolutions' seat, retainer, cam-contact and valve-seat forces "
        f"agree within TOL of Fset (default {100 * valve.PERIODICITY_TOL:g} %%)",
    )
    p.add_argument(
        "--max-revolutions",
        type=int,
        default=valve.MAX_REVOLUTIONS,
        metavar="N",
        help=f"periodic steady state: at most N revolutions per speed (default {valve.MAX_REVOLUTIONS})",
    )
    p.add_argument(
        "--allow-extreme-speeds",
        action="store_true",
        help="compute speeds at which the cam event is shorter than one surge period (refused otherwise), flagged",
    )


def add_model_option(p) -> None:
    p.add_argument(
        "--model",
        choices=valve.MODEL_NAMES,
        help="spring model (default: the [spring] model key, else 'type-c', the document's MMS Type C)",
    )


def add_gas_options(p) -> None:
    p.add_argument(
        "--gas-pressure",
        metavar="P.csv",
        help="cylinder pressure against crank angle (columns crank_angle_deg, pressure_bar|_Pa|_kPa|_MPa, absolute): "
        "its force on the valve head over [valve_train] seat_diameter, phased by the cam's [timing]",
    )
    p.add_argument(
        "--port-pressure",
        default=None,
        metavar="P",
        help="with --gas-pressure: pressure behind the valve head, absolute (default 1 atm; bare number: Pa)",
    )


def add_speed_options(p, *, ranged: bool, ramp: bool = False, required: bool = True, what: str = "") -> None:
    """``--cam-rpm`` or ``--engine-rpm`` (a speed, or with ``ranged`` a range or list; ``what``:
    what the speed is for, when it is optional), and with ``ramp`` ``--speed-ramp``."""
    g = p.add_mutually_exclusive_group(required=required)
    what = what or ("START:STOP:STEP or a list" if ranged else "a speed")
    g.add_argument("--cam-rpm", metavar="RPM", help=f"camshaft speed, {what} (bare numbers: rpm)")
    g.add_argument(
        "--engine-rpm", metavar="RPM", help=f"engine speed, {what} (four-stroke: cam speed = engine speed / 2)"
    )
    if ramp:
        g.add_argument(
            "--speed-ramp",
            metavar="START:END:RATE",
            help="a cam-speed ramp (a run-up, or a run-down when END < START): cam speeds and the rate of the cam "
            "speed (bare numbers: rpm and rpm/s), from the periodic steady state at START; lift-off, float and "
            "seat landings per revolution against the momentary speed (needs --valve-train)",
        )


# ----------------------------------------------------------------------------- the model
def run_settings(args) -> valve.RunSettings:
    """The run options of a command as one :class:`~springdyn.valve.RunSettings` (checked once)."""
    given = {}
    if getattr(args, "revolutions", None) is not None and args.max_revolutions != valve.MAX_REVOLUTIONS:
        raise InputError("--revolutions runs a fixed number of revolutions: --max-revolutions applies without it")
    if hasattr(args, "periodicity_tol"):
        given.update(
            revolutions=args.revolutions,
            periodicity_tol=quantity(args.periodicity_tol, "", "--periodicity-tol"),
            max_revolutions=args.max_revolutions,
            allow_extreme_speeds=args.allow_extreme_speeds,
        )
    for key in ("rtol", "atol", "points_per_revolution", "backend"):
        if getattr(args, key, None) is not None:
            given[key] = getattr(args, key)
    with as_options(**RUN_OPTIONS):
        return valve.RunSettings(**given)


def model_of(args, *, cam: bool = True, train: bool = True) -> valve.ValveModel:
    """The :class:`~springdyn.valve.ValveModel` of a command's files and options: the spring
    (``--model``), the cam and valve train when the command has them, the run settings, crank
    angles with an engine speed, the gas force of ``--gas-pressure``."""
    with as_options(**RUN_OPTIONS):
        model = valve.ValveModel.from_files(
            args.spring,
            getattr(args, "cam", None) if cam else None,
            getattr(args, "valve_train", None) if train else None,
            model=getattr(args, "model", None),
            settings=run_settings(args),
            crank_angles=True if getattr(args, "engine_rpm", None) is not None else None,
        )
    port = getattr(args, "port_pressure", None)
    if port is not None and not getattr(args, "gas_pressure", None):
        raise InputError(f"--port-pressure = {port!r} needs --gas-pressure (the cylinder pressure it acts against)")
    if getattr(args, "gas_pressure", None):
        p_port = quantity(port if port is not None else "1 atm", "Pa", "--port-pressure")
        if p_port < 0:
            raise InputError(f"--port-pressure = {port!r} is an absolute pressure: it must be 0 or more")
        with as_options(path="--gas-pressure", port_pressure="--port-pressure"):
            model = model.with_gas_pressure(args.gas_pressure, p_port)
    return model


def run_options(args, model: valve.ValveModel | None = None, timing=None) -> dict:
    """:data:`RUN_OPTIONS` for :func:`~springdyn.app.cli.common.as_options`, with a cam speed
    the library refuses named as the user gave it: ``--engine-rpm = 1e+09 (a cam speed of
    5e+08 rpm): ...`` when the speed came from ``--engine-rpm``."""
    if getattr(args, "engine_rpm", None) is None:
        return dict(RUN_OPTIONS)
    if model is not None:
        per_engine = float(model.cam_rpm(1.0))
    else:
        per_engine = float(valve.cam_rpm_from_engine_rpm(1.0, timing.strokes if timing is not None else 4))

    def engine_message(text: str) -> str | None:
        found = re.match(r"^cam_rpm(?:\[\d+\])? = ([-+0-9.eEinf]+)(.*)$", text, re.S)
        if not found:
            return None
        cam = float(found.group(1))
        engine = cam / per_engine
        rest = found.group(2).replace(f"did you mean {cam / 10:g}?", f"did you mean {engine / 10:g}?")
        return f"--engine-rpm = {engine:g} (a cam speed of {cam:g} rpm){rest}"

    return dict(RUN_OPTIONS, cam_rpm=engine_message)


def cam_rpm_from_args(args, *, ranged: bool, model: valve.ValveModel | None = None, timing=None):
    """Camshaft speed(s) in rev/min from --cam-rpm or --engine-rpm (the strokes of the model's or
    the given ``[timing]``; a four-stroke without one); ``None`` when neither is given."""
    if args.cam_rpm is None and args.engine_rpm is None:
        return None
    option = "--cam-rpm" if args.cam_rpm is not None else "--engine-rpm"
    text = args.cam_rpm if args.cam_rpm is not None else args.engine_rpm

    def cam(rpm):
        if args.cam_rpm is not None:
            return rpm
        if model is not None:
            return model.cam_rpm(rpm)
        return valve.cam_rpm_from_engine_rpm(rpm, timing.strokes if timing is not None else 4)

    if ranged:
        values = cam(parse_range(text, "rpm", option, bare_unit="rpm"))
        if (values <= 0).any():
            raise InputError(f"{option} = {text!r}: every speed must be positive")
        _check_top_speed(values, option, text)
        return values
    value = cam(quantity(text, "rpm", option, bare_unit="rpm"))
    if not value > 0:
        raise InputError(f"{option} = {text!r} must be a positive speed")
    _check_top_speed(value, option, text)
    return value


#: The fastest camshaft a speed option takes [rev/min] (as the cam analysis and checks: far
#: above any engine's, 10 000 cam rpm at a racing engine's 20 000 rpm).
MAX_OPTION_CAM_RPM = 100_000.0


def _check_top_speed(cam_rpm, option: str, text: str) -> None:
    """A speed option's cam speeds below :data:`MAX_OPTION_CAM_RPM`, refused naming the option as
    the user gave it (``--engine-rpm = 1e9 (a cam speed of 5e+08 rpm)``), for every command."""
    values = np.atleast_1d(np.asarray(cam_rpm, dtype=float))
    top = float(np.max(values))
    if top <= MAX_OPTION_CAM_RPM:
        return
    one = values.size == 1  # the one value as a number (as the library's messages show it)
    shown = f"{quantity(text, 'rpm', option, bare_unit='rpm'):g}" if one else repr(text)
    cam = f" (a cam speed {'of' if one else 'up to'} {top:g} rpm)" if option == "--engine-rpm" else ""
    raise InputError(
        f"{option} = {shown}{cam}: beyond any engine, a camshaft turns at most {MAX_OPTION_CAM_RPM:g} rpm "
        "(a racing engine's 20000 rpm is 10000 cam rpm)"
    )
