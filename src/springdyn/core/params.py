"""Declarative parameter fields and TOML loading with validation.

A model's parameters are a dataclass whose fields are declared with :func:`param`
(SI unit, meaning, bounds).  :func:`from_mapping` turns a TOML table (values with units
as strings, or bare SI numbers) into that dataclass, rejecting unknown keys, missing
keys, wrong dimensions and out-of-range values with one message that names the field,
the value and what is allowed.  :func:`check_fields` runs the same per-field checks on
an instance built directly in Python (call it from ``__post_init__``).
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import numbers
import tomllib
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from .errors import InputError
from .units import format_quantity, to_si

__all__ = [
    "KNOWN_TABLES",
    "read_text_file",
    "decode_utf8",
    "Parameters",
    "param",
    "param_like",
    "from_mapping",
    "check_fields",
    "load_toml",
    "field_specs",
    "describe_value",
]

REQUIRED = dataclasses.MISSING


def param(
    unit: str | None = "",
    doc: str = "",
    *,
    default: Any = REQUIRED,
    symbol: str = "",
    kind: str = "quantity",
    display: str | None = None,
    choices: tuple | None = None,
    positive: bool = False,
    nonnegative: bool = False,
    bare_unit: str | None = None,
    minimum: float | None = None,
    maximum: float | None = None,
) -> Any:
    """Declare a parameter field.

    Parameters
    ----------
    unit : str
        SI unit of the stored float (``"m"``, ``"Pa"``, ``""`` for dimensionless).
    doc : str
        What the field means (used in messages and the generated TOML reference).
    default : optional
        Default value (already SI); omitted means the key is required.
    symbol : str
        Symbol of the source document (``"Do"``).
    kind : {"quantity", "int", "str", "bool", "quantity_list"}
        How to read the TOML value.
    display : str, optional
        Unit for human-readable tables (``"mm"``).
    choices : tuple, optional
        Allowed values of a ``str`` field.
    positive, nonnegative : bool
        Range checks applied on load and in :func:`check_fields`.
    bare_unit : str, optional
        Unit of a bare number if it is not SI (rarely needed).
    minimum, maximum : float, optional
        Inclusive bounds [SI unit of the field] checked like ``positive`` (e.g. a count
        that sizes a matrix needs a maximum).
    """
    meta = dict(
        unit=unit or "",
        doc=doc,
        symbol=symbol,
        kind=kind,
        display=display,
        choices=choices,
        positive=positive,
        nonnegative=nonnegative,
        bare_unit=bare_unit,
        minimum=minimum,
        maximum=maximum,
    )
    if isinstance(default, list):
        return dataclasses.field(default_factory=lambda d=default: list(d), metadata=meta)
    return dataclasses.field(default=default, metadata=meta)


def param_like(cls, name: str, note: str = "") -> Any:
    """A parameter field declared as the field ``name`` of the parameter class ``cls`` is: the
    same unit, checks and default (one declaration of a key two tables take).

    Parameters
    ----------
    cls : type
        A :class:`Parameters` dataclass.
    name : str
        Its field.
    note : str
        Appended to the field's description, in parentheses (``"the [criteria] key"``).
    """
    field = next(f for f in dataclasses.fields(cls) if f.name == name)
    meta = dict(field.metadata)
    if note:  # inside the description's closing parenthesis, or in its own
        doc = meta["doc"]
        meta["doc"] = f"{doc[:-1]}; {note})" if doc.endswith(")") else f"{doc} ({note})"
    return dataclasses.field(default=field.default, metadata=meta)


def field_specs(cls) -> list[tuple[dataclasses.Field, dict]]:
    """The declared parameter fields of a dataclass with their metadata."""
    return [(f, f.metadata) for f in dataclasses.fields(cls) if "kind" in f.metadata]


def describe_value(value: float, meta: Mapping) -> str:
    """A value in its display unit for messages: ``'38 mm'``."""
    if meta.get("kind") in ("quantity",) and isinstance(value, (int, float)):
        return format_quantity(float(value), meta["unit"], meta.get("display"))
    return repr(value)


def _convert(name: str, value: Any, meta: Mapping, where: str) -> Any:
    label = f"{where}{name}"
    kind = meta["kind"]
    if kind == "quantity":
        return to_si(value, meta["unit"], label, bare_unit=meta.get("bare_unit"))
    if kind == "quantity_list":
        if not isinstance(value, list) or not value:
            raise InputError(f'{label} = {value!r} must be a non-empty list, e.g. ["38 mm", "34 mm"]')
        return [to_si(v, meta["unit"], f"{label}[{i}]", bare_unit=meta.get("bare_unit")) for i, v in enumerate(value)]
    if kind == "int":
        if isinstance(value, bool) or not isinstance(value, int):
            if isinstance(value, float) and value.is_integer():
                return int(value)
            raise InputError(f"{label} = {value!r} must be a whole number")
        return value
    if kind == "bool":
        if not isinstance(value, bool):
            raise InputError(f"{label} = {value!r} must be true or false")
        return value
    if kind == "str":
        if not isinstance(value, str):
            raise InputError(f"{label} = {value!r} must be a string")
        choices = meta.get("choices")
        if choices and value not in choices:
            raise InputError(f"{label} = {value!r} is not allowed; choose one of {_allowed(choices)}")
        return value
    raise AssertionError(f"unknown field kind {kind}")


#: The largest magnitude of a machine element's quantity by its SI unit (far above any spring,
#: damper or valve train: a value beyond it is a unit slip or a typo, such as 1e30).
PLAUSIBLE_MAX = {
    "m": 1e3,
    "kg": 1e5,
    "Pa": 1e14,
    "N": 1e10,
    "N/m": 1e14,
    "N*s/m": 1e10,
    "N*m": 1e9,
    "N*m/rad": 1e10,
    "kg*m^2": 1e6,
    "kg/m^3": 1e6,
    "Pa*s": 1e6,
    "rad": 1e4,
    "rad/s": 1e7,
    "m/s": 1e5,
}


def _check_one(name: str, value: Any, meta: Mapping, where: str = "", plausible: bool = True) -> None:
    label = f"{where}{name}"
    values = value if isinstance(value, list) else [value]
    for i, v in enumerate(values):
        if isinstance(v, bool) or not isinstance(v, (int, float)):
            continue
        sub = f"{label}[{i}]" if isinstance(value, list) else label
        if isinstance(v, int) and not -1e300 < v < 1e300:  # beyond any float (and any spring)
            raise InputError(f"{sub} is an integer of {v.bit_length()} bits: too large; it must be a finite number")
        shown = describe_value(v, {**meta, "kind": "quantity"}) if meta.get("unit") or meta.get("display") else repr(v)
        if not math.isfinite(v):
            raise InputError(f"{sub} = {shown} must be a finite number")
        limit = PLAUSIBLE_MAX.get(meta.get("unit") or "")
        if plausible and limit is not None and meta.get("kind") in ("quantity", "quantity_list") and abs(v) > limit:
            bound = describe_value(limit, {**meta, "kind": "quantity"})
            raise InputError(
                f"{sub} = {shown} is beyond any machine element ({meta.get('doc') or 'a value'}): at most {bound} "
                "in magnitude; check its unit"
            )
        if meta.get("positive") and not v > 0:
            raise InputError(f"{sub} = {shown} must be positive ({meta.get('doc') or 'a size'})")
        if meta.get("nonnegative") and not v >= 0:
            raise InputError(f"{sub} = {shown} must be zero or positive ({meta.get('doc') or 'a size'})")
        lo, hi = meta.get("minimum"), meta.get("maximum")
        if (lo is not None and v < lo) or (hi is not None and v > hi):
            rng = (
                f"from {lo:g} to {hi:g}"
                if lo is not None and hi is not None
                else f"at least {lo:g}"
                if lo is not None
                else f"at most {hi:g}"
            )
            raise InputError(f"{sub} = {shown} must be {rng} ({meta.get('doc') or 'a count'})")


def _allowed(choices) -> str:
    """The allowed values of a choice key for a message ('' is "leave the key out")."""
    named = ", ".join(repr(c) for c in choices if c != "")
    return named + (" (or leave the key out for its default)" if "" in choices else "")


def _check_type(name: str, value: Any, meta: Mapping, default: Any) -> None:
    """Types are checked like values: a wrong type is an InputError naming the field."""
    if value is None and default is None:
        return
    kind = meta["kind"]
    unit = meta.get("unit") or "-"
    if kind == "quantity":
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise InputError(
                f"{name} = {value!r} must be a number in SI units [{unit}] (values with units such "
                "as '22 mm' are read by from_dict and from_toml)"
            )
    elif kind == "int":
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise InputError(f"{name} = {value!r} must be a whole number")
    elif kind == "quantity_list":
        if isinstance(value, (list, tuple)) and not value and default == []:
            return
        if (
            not isinstance(value, (list, tuple))
            or not value
            or any(isinstance(v, bool) or not isinstance(v, numbers.Real) for v in value)
        ):
            raise InputError(f"{name} = {value!r} must be a non-empty list of numbers in SI units [{unit}]")
    elif kind == "str":
        if not isinstance(value, str):
            raise InputError(f"{name} = {value!r} must be a string")
    elif kind == "bool":
        if not isinstance(value, bool):
            raise InputError(f"{name} = {value!r} must be true or false")


def check_fields(obj) -> None:
    """Per-field type, range and choice checks on a parameter dataclass instance."""
    for f, meta in field_specs(type(obj)):
        value = getattr(obj, f.name)
        default = (
            f.default
            if f.default is not dataclasses.MISSING
            else f.default_factory()
            if f.default_factory is not dataclasses.MISSING
            else REQUIRED
        )
        _check_type(f.name, value, meta, default)
        if meta["kind"] == "str" and meta.get("choices") and value not in meta["choices"]:
            raise InputError(f"{f.name} = {value!r} is not allowed; choose one of {_allowed(meta['choices'])}")
        _check_one(f.name, value, meta, plausible=getattr(type(obj), "plausible_ranges", True))


#: A speed key of either shaft has its twin on the other: ``min_float_cam_rpm`` is also
#: given as ``min_float_engine_rpm``, ``max_engine_rpm`` as ``max_cam_rpm``.
SPEED_TWINS = ("cam_rpm", "engine_rpm")


def speed_twin(name: str) -> str | None:
    """The other shaft's name of a speed key (``"min_cam_rpm"`` -> ``"min_engine_rpm"``), or None.

    Parameters
    ----------
    name : str
        A key of a table.
    """
    cam, engine = SPEED_TWINS
    if cam in name:
        return name.replace(cam, engine)
    if engine in name:
        return name.replace(engine, cam)
    return None


def _resolve_speed_twins(specs, mapping: dict, where: str, cam_per_crank: float) -> dict:
    """Read each given twin of a speed field into the field: an engine speed times
    ``cam_per_crank`` (the camshaft's turns per crankshaft turn), a cam speed divided by it; a
    field given both ways is an error naming both."""
    out = dict(mapping)
    for name, (_f, meta) in specs.items():
        twin = speed_twin(name)
        if twin is None or twin not in out or twin in specs:
            continue
        if name in out:
            raise InputError(
                f"{where}{name} = {out[name]!r} and {twin} = {out[twin]!r} give the same speed twice: give one of them"
            )
        value = _convert(twin, out.pop(twin), meta, where)  # SI, in the field's unit
        factor = cam_per_crank if SPEED_TWINS[1] in twin else 1.0 / cam_per_crank
        unit = meta.get("unit", "")
        # the converted speed with its SI unit, read as given (a bare number would be rpm)
        values = [f"{v * factor!r} {unit}" for v in (value if isinstance(value, list) else [value])]
        out[name] = values if isinstance(value, list) else values[0]
    return out


def from_mapping(
    cls, mapping: Mapping[str, Any], *, section: str = "", source: str | None = None, cam_per_crank: float = 0.5
):
    """Build the parameter dataclass ``cls`` from a TOML table.

    Unknown keys, missing required keys, bad units and out-of-range values raise
    :class:`~springdyn.core.errors.InputError` naming the file, the key and the value.  A
    speed field named with ``cam_rpm`` or ``engine_rpm`` also takes its twin on the other
    shaft (:func:`speed_twin`), converted with ``cam_per_crank`` (0.5: a four-stroke engine's
    camshaft turns once per two crankshaft turns).
    """
    where = f"{source}: " if source else ""
    prefix = f"[{section}] " if section else ""
    specs = {f.name: (f, meta) for f, meta in field_specs(cls)}
    if not isinstance(mapping, Mapping):
        raise InputError(f"{where}{prefix or 'the table'} must be a table of keys")
    mapping = _resolve_speed_twins(specs, mapping, f"{where}{prefix}", cam_per_crank)
    unknown = [k for k in mapping if k not in specs]
    if unknown:
        k = unknown[0]
        twins = [t for t in map(speed_twin, specs) if t is not None and t not in specs]
        allowed = [*specs, *getattr(cls, "extra_keys", ()), *twins]  # with the keys the class reads into its own
        close = difflib.get_close_matches(k, allowed, n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise InputError(f"{where}{prefix}unknown key {k!r}{hint}; allowed keys: {', '.join(allowed)}")
    kwargs = {}
    for name, (f, meta) in specs.items():
        if name in mapping:
            kwargs[name] = _convert(name, mapping[name], meta, f"{where}{prefix}")
            _check_one(name, kwargs[name], meta, f"{where}{prefix}", getattr(cls, "plausible_ranges", True))
        elif f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
            example = meta.get("display") or meta.get("unit")
            raise InputError(
                f"{where}{prefix}missing key {name!r} ({meta.get('doc')}"
                + (f', e.g. {name} = "... {example}")' if example else ")")
            )
    try:
        return cls(**kwargs)
    except InputError as exc:
        message = str(exc) + _bare_number_hint(cls, specs, mapping, kwargs)
        if source and not message.startswith(where):
            # a cross-key check names its table itself ("[friction] fluid_friction = ..."): once
            tagged = message if message.startswith(f"[{section}]") else f"{prefix}{message}"
            raise InputError(f"{where}{tagged}") from None
        if message != str(exc):
            raise InputError(message) from None
        raise


#: The keys that choose what a table describes (its kind): checked before the table's other keys.
KIND_KEYS = ("type", "kind", "law", "layout", "end_type")


def _check_choices(cls, mapping: Mapping, where: str) -> None:
    """The keys of a table that choose its kind (:data:`KIND_KEYS`: ``type``, ``end_type``, ``law``),
    checked before the other keys are read: a bad kind is named as such, not as the problem it
    makes of another key (``type = "twostep"`` beside ``low_pitch`` is a bad type, not a pitch
    missing)."""
    for f, meta in field_specs(cls):
        if f.name in KIND_KEYS and meta.get("kind") == "str" and meta.get("choices") and f.name in mapping:
            _convert(f.name, mapping[f.name], meta, where)


def _bare_number_hint(cls, specs, mapping, kwargs) -> str:
    """When a bare number (read in SI) makes the table invalid and the same number in the
    key's display unit makes it valid: ``"; a bare number is SI: did you mean '120 deg'?"``."""
    for name, (_f, meta) in specs.items():
        value = mapping.get(name)
        display, unit = meta.get("display"), meta.get("unit")
        if meta.get("kind") != "quantity" or isinstance(value, bool) or not isinstance(value, (int, float)):
            continue
        if not display or display == unit:
            continue
        try:
            trial = {**kwargs, name: to_si(f"{value} {display}", unit, name)}
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                cls(**trial)
        except (InputError, ValueError, TypeError):
            continue
        return f" (a bare number is read in SI: {name} = {value!r} is {value:g} {unit}; did you mean '{value:g} {display}'?)"
    return ""


#: Every table a springdyn definition file may hold; any other table is an error.
KNOWN_TABLES = (
    "spring",
    "inner_spring",
    "third_spring",
    "pack",
    "damper",
    "cam",
    "timing",
    "valve_train",
    "hla",
    "follower",
    "geometry",
    "friction",
    "oil",
    "piston",
    "requirements",
    "tolerances",
    "criteria",
    "spectrum",
    "cam_card",
    "report",
    "cfcs",
    "lsd",
)
#: Largest definition file springdyn reads [bytes]: definitions are a few kB.
MAX_TOML_BYTES = 1_000_000


def read_text_file(path: str | Path, what: str, *, max_bytes: int) -> tuple[Path, bytes]:
    """The bytes of a definition or data file, with one clear message for every way it fails.

    Parameters
    ----------
    path : str or path-like
        The file.
    what : str
        What the file should be, for messages (``"TOML"``, ``"CSV"``).
    max_bytes : int
        Largest size accepted [bytes].
    """
    path = Path(path)
    if str(path) == "":
        raise InputError("an empty file name was given")
    if any(len(part.encode("utf-8", "surrogateescape")) > 255 for part in path.parts):
        raise InputError(f"{str(path)[:60]}...: the file name is longer than 255 bytes")
    if path.is_dir():
        raise InputError(f"{path}: is a folder, not a {what} file")
    if not path.exists():
        raise InputError(f"{path}: no such file")
    if not path.is_file():
        raise InputError(f"{path}: is not a regular file")
    try:
        size = path.stat().st_size
        if size > max_bytes:
            raise InputError(
                f"{path}: {size} bytes is larger than any {what} file springdyn reads ({max_bytes} bytes at most)"
            )
        data = path.read_bytes()
    except OSError as exc:
        raise InputError(f"{path}: cannot be read ({exc.strerror or exc})") from None
    if not data.strip():
        raise InputError(f"{path}: the file is empty")
    if b"\x00" in data:
        hint = " (it looks like UTF-16: save it as UTF-8)" if data[:2] in (b"\xff\xfe", b"\xfe\xff") else ""
        raise InputError(f"{path}: is not a {what} text file (it holds NUL bytes){hint}")
    return path, data


def decode_utf8(path: Path, data: bytes, what: str) -> str:
    """Text of a UTF-8 file (a BOM is allowed), or an InputError naming the line."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        raise InputError(
            f"{path}: line {line} is not UTF-8 text (byte {data[exc.start]:#04x}); save the {what} file as UTF-8"
        ) from None


def load_toml(path: str | Path, section: str | None = None, *, allowed: tuple = KNOWN_TABLES) -> dict:
    """Read a TOML definition file; return the whole document or one of its tables.

    Parameters
    ----------
    path : str or path-like
        The TOML file.
    section : str, optional
        The table to return (default: the whole document).
    allowed : tuple of str
        The top-level tables the file may hold (default: every springdyn table); any
        other table or top-level key is an error, with the nearest allowed name.

    Raises
    ------
    InputError
        The file is missing, a folder, empty, too large, not UTF-8, not valid TOML,
        nested absurdly deep, holds an unknown table, or lacks ``section``.
    """
    path, data = read_text_file(path, "TOML", max_bytes=MAX_TOML_BYTES)
    text = decode_utf8(path, data, "TOML")
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{path}: not valid TOML: {exc}") from None
    except RecursionError:
        raise InputError(f"{path}: not a springdyn definition: its tables or arrays are nested too deeply") from None
    except ValueError as exc:  # an integer of more than 4300 digits (Python's conversion limit)
        raise InputError(f"{path}: a number in it is too long to read ({exc}); give a finite number") from None
    unknown = [k for k in doc if k not in allowed]
    if unknown:
        k = unknown[0]
        close = difflib.get_close_matches(k, list(allowed), n=1)
        hint = f" (did you mean [{close[0]}]?)" if close else ""
        what = "table" if isinstance(doc[k], dict) else "top-level key"
        raise InputError(
            f"{path}: unknown {what} [{k}]{hint}; a definition holds " + ", ".join(f"[{t}]" for t in allowed)
        )
    if section is None:
        return doc
    if section not in doc:
        tables = ", ".join(f"[{k}]" for k in doc) or "none"
        raise InputError(f"{path}: no [{section}] table (tables found: {tables})")
    if not isinstance(doc[section], dict):
        raise InputError(f"{path}: [{section}] must be a table of keys")
    return doc[section]


def _same(a, b) -> bool:
    try:
        return bool(a == b)
    except (TypeError, ValueError):  # arrays
        return False


class Parameters:
    """Base of every parameter table (a frozen dataclass of :func:`param` fields).

    A subclass names its TOML table and its built-in examples; it gets
    :meth:`from_dict`, :meth:`from_toml`, :meth:`example` and :meth:`replace`, and the
    per-field checks of :func:`check_fields` on construction followed by its own
    cross-key checks in :meth:`_validate`.

    Examples
    --------
    >>> import dataclasses
    >>> @dataclasses.dataclass(frozen=True)
    ... class Rod(Parameters):
    ...     table = "rod"
    ...     length: float = param("m", "rod length", positive=True)
    >>> Rod.from_dict({"length": "22 mm"}).length
    0.022
    """

    #: TOML table of the definition, e.g. ``"spring"``.
    table: str = ""
    #: Built-in examples: name -> TOML file in ``springdyn/data``.
    examples: dict = {}
    #: Example returned by :meth:`example` without a name.
    default_example: str = ""
    #: Refuse quantities beyond :data:`PLAUSIBLE_MAX` (a class with finer ranges of its own,
    #: with did-you-mean hints, turns this off).
    plausible_ranges: bool = True
    #: Keys the table takes besides the fields (:meth:`_prepare` reads them into fields): they
    #: stand in the allowed-keys list of an unknown key's message.
    extra_keys: tuple = ()

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        # class attributes of the base are configuration, not dataclass fields
        for name in ("table", "examples", "default_example", "plausible_ranges", "extra_keys"):
            if name in cls.__dict__ and name in getattr(cls, "__annotations__", {}):  # pragma: no cover
                raise TypeError(f"{cls.__name__}.{name} must not be annotated")
        # the display repr, kept by the dataclass decorator (it does not replace a __repr__
        # the class defines)
        if "__repr__" not in cls.__dict__:
            cls.__repr__ = Parameters._display_repr

    def _display_repr(self) -> str:
        """``Cam(law='3-4-5', lift='9 mm', duration='120 deg')``: the keys that differ from
        their defaults, quantities in their display units (as a TOML table would say them)."""
        parts = []
        for f, meta in field_specs(type(self)):
            value = getattr(self, f.name)
            if f.default is not dataclasses.MISSING and _same(value, f.default):
                continue
            unitless = not (meta.get("unit") or meta.get("display"))
            if meta.get("kind") == "quantity" and isinstance(value, (int, float)) and not isinstance(value, bool):
                shown = f"{float(value):g}" if unitless else repr(describe_value(float(value), meta))
                parts.append(f"{f.name}={shown}")
            elif meta.get("kind") == "quantity_list" and isinstance(value, (list, tuple)) and not unitless:
                shown = [describe_value(float(v), {**meta, "kind": "quantity"}) for v in value]
                parts.append(f"{f.name}={shown!r}")
            else:
                parts.append(f"{f.name}={value!r}")
        return f"{type(self).__name__}({', '.join(parts)})"

    def __post_init__(self):
        check_fields(self)
        self._validate()

    def _validate(self) -> None:
        """Cross-key checks of the subclass (raise :class:`InputError`)."""

    @classmethod
    def from_dict(cls, mapping: Mapping[str, Any], *, source: str | None = None, **context):
        """Build from a mapping of the table's keys (values with units, or SI numbers)."""
        where = f"{source}: " if source else ""
        if not isinstance(mapping, Mapping):
            raise InputError(f"{where}[{cls.table}] must be a table of keys")
        _check_choices(cls, mapping, f"{where}[{cls.table}] " if cls.table else where)
        try:
            prepared = cls._prepare(dict(mapping), source=source, **context)
        except InputError as exc:  # a key the table reads into others: the file and the table named once
            text = str(exc)
            if source and not text.startswith(where):
                text = f"{where}{text if text.startswith(f'[{cls.table}]') else f'[{cls.table}] {text}'}"
                raise InputError(text) from None
            raise
        return from_mapping(
            cls,
            prepared,
            section=cls.table,
            source=source,
            cam_per_crank=context.get("cam_per_crank", 0.5),
        )

    @classmethod
    def _prepare(cls, mapping: dict, **context) -> dict:
        """Hook: adjust the raw table before conversion (e.g. resolve relative paths).

        ``context`` holds ``source`` (the file, for messages) and ``base_dir`` (its folder).
        """
        return mapping

    @classmethod
    def from_toml(cls, path):
        """Read the table :attr:`table` of a TOML file."""
        return cls.from_dict(load_toml(path, cls.table), source=str(path), base_dir=Path(path).parent)

    @classmethod
    def example(cls, name: str | None = None):
        """A built-in example definition (see :attr:`examples`)."""
        from importlib import resources

        name = cls.default_example if name is None else name
        key = cls._example_key(name)
        if key not in cls.examples:
            raise InputError(
                f"example = {name!r} is not a built-in {cls.table or cls.__name__}; "
                f"choose one of {', '.join(map(repr, cls.examples))}"
            )
        with resources.as_file(resources.files("springdyn.data") / cls.examples[key]) as path:
            return cls.from_toml(path)

    @classmethod
    def _example_key(cls, name: str) -> str:
        return name

    def replace(self, **changes):
        """A copy with some fields changed (SI values), validated again."""
        return dataclasses.replace(self, **changes)
