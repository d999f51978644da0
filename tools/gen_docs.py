"""Reference documentation generated from the code, so that it cannot drift.

Three pure generators return Markdown strings:

- :func:`toml_reference` -- every key of every TOML parameter table, read from the
  :func:`springdyn.core.params.param` metadata of the parameter dataclasses (unit, display
  unit, default, allowed range or choices, symbol, meaning);
- :func:`cli_reference` -- every command and option of ``springdyn``, read from the
  argparse parser of :func:`springdyn.app.cli.main.build_parser`;
- :func:`api_reference` -- the public Python API (each module's ``__all__``) with
  signatures and the summary and parameter sections of the numpydoc docstrings.

:func:`write_docs` writes them to ``docs/reference/{toml,cli,api}.md`` atomically; the
command ``springdyn docs`` (or ``python tools/gen_docs.py``) calls it.  A test
regenerates the files and fails when the committed copies are out of date.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import inspect
import pkgutil
import re
from importlib import resources
from pathlib import Path

from springdyn.core.io import atomic_open
from springdyn.core.params import field_specs
from springdyn.core.units import format_quantity

__all__ = [
    "PARAMETER_TABLES",
    "CROSS_KEY_RULES",
    "toml_reference",
    "cli_reference",
    "api_reference",
    "write_docs",
    "REFERENCE_FILES",
]

#: TOML table -> (parameter class ``module:qualname``, built-in example file in ``springdyn/data``).
PARAMETER_TABLES = {
    "spring": ("springdyn.valve.spring.definition:ValveSpring", "valve_one_step.toml"),
    "pack": ("springdyn.valve.spring.pack:PackOptions", "valve_dual_spring_damper.toml"),
    "damper": ("springdyn.valve.spring.pack:FrictionDamper", "valve_dual_spring_damper.toml"),
    "cam": ("springdyn.valve.cam.definition:Cam", "valve_cam_345.toml"),
    "timing": ("springdyn.valve.cam.timing:Timing", "valve_cam_timing.toml"),
    "valve_train": ("springdyn.valve.train.definition:ValveTrain", "valve_train_direct_acting.toml"),
    "hla": ("springdyn.valve.train.hla:HLA", "valve_train_finger_hla.toml"),
    "follower": ("springdyn.valve.cam.follower:Follower", "valve_train_follower.toml"),
    "geometry": ("springdyn.valve.train.lever:LeverGeometry", "valve_train_finger_geometry.toml"),
    "friction": ("springdyn.valve.train.friction:Friction", "valve_train_follower.toml"),
    "oil": ("springdyn.valve.train.oil:Oil", "valve_train_finger_hla.toml"),
    "piston": ("springdyn.valve.train.piston:Piston", "valve_piston.toml"),
    "requirements": ("springdyn.valve.design.synthesis:Requirements", "valve_requirements.toml"),
    "criteria": ("springdyn.valve.design.criteria:Criteria", "valve_tolerances.toml"),
    "spectrum": ("springdyn.valve.design.life:LoadSpectrum", "valve_spectrum.toml"),
    "cam_card": ("springdyn.valve.cam.from_lift:CamCard", "valve_cam_card.toml"),
    "camshaft": ("springdyn.valve.camshaft.definition:Camshaft", "valve_camshaft.toml"),
    "camshaft.lobes": ("springdyn.valve.camshaft.definition:LobeDefinition", "valve_camshaft.toml"),
    "report": ("springdyn.app.report.valve:ReportSettings", "report_engine.toml"),
    "cfcs": ("springdyn.cfcs.params:CFCSParams", "cfcs_table1.toml"),
    "lsd": ("springdyn.lsd.parameters:LSDParameters", "lsd_type_c.toml"),
}

#: Checks across keys that the classes run in ``__post_init__`` / ``from_dict`` (beyond the
#: per-key ranges), each with a table that breaks it; ``tests/test_docs.py`` loads every
#: such table and requires an ``InputError``, so a rule listed here is a rule enforced.
CROSS_KEY_RULES = {
    "spring": [
        ("`installed_length` < `free_length`", {"installed_length": "50 mm"}),
        ('`low_pitch_coils` = 0 for `type = "one-step"`', {"low_pitch_coils": 2.0}),
        ("`installed_length` above the solid length Lc = Dw (N1 + N2 + 0.5)", {"installed_length": "28 mm"}),
        ("active coils N1 + N2 - 2 Nb > 0 and N2 - Nb > 0", {"dead_coils": 7.5}),
        (
            "the closed-form chain is physical: K > 2 K1 (one-step) or 3 K2 (two-step), masses and F1 positive, "
            "Fcon > F1",
            {"mean_diameter": "4 mm"},
        ),
    ],
    "cam": [
        ('`lift` and `duration` are required unless `law = "table"`', {"lift": None}),
        ("`lift` > 0", {"lift": "0 mm"}),
        ("`duration` in (0, 360] deg and `duration + 2 ramp_duration` at most one revolution", {"duration": "400 deg"}),
        ("`ramp_height` and `ramp_duration` both zero or both positive", {"ramp_height": "0.2 mm"}),
        ("`ramp_height` < `lift`", {"ramp_height": "10 mm", "ramp_duration": "20 deg"}),
        (
            '`file` only with `law = "table"`, and `law = "table"` takes no `lift`, `duration` or ramps',
            {"file": "lift.csv"},
        ),
    ],
    "timing": [
        ("`lobe_centre` from 0 to half the cycle (360 deg for a four-stroke)", {"lobe_centre": "400 deg"}),
        ("`strokes` 4 or 2", {"strokes": 3}),
    ],
    "valve_train": [],
    "hla": [
        ("`eccentricity` < 1", {"eccentricity": 1.2}),
        ("`chamber_volume` above the volume the plunger sweeps over `collapse_travel`", {"chamber_volume": "100 mm^3"}),
    ],
    "follower": [
        ('`roller_radius` for `kind = "roller"` only', {"roller_radius": "9 mm"}),
        (
            '`face_radius`, `edge_margin` and `lateral_offset` for `kind = "flat"` only; a roller needs `roller_radius`',
            {"kind": "roller", "roller_radius": "9 mm"},
        ),
        ("`edge_margin` < `face_radius`", {"edge_margin": "20 mm"}),
        ("`|lateral_offset|` + `width`/2 < `face_radius`", {"lateral_offset": "12 mm"}),
        (
            "a roller's `|offset|` < `base_circle_radius` + `roller_radius`",
            {
                "kind": "roller",
                "roller_radius": "9 mm",
                "offset": "30 mm",
                "face_radius": None,
                "edge_margin": None,
                "lateral_offset": None,
            },
        ),
        ("Poisson's ratios below 0.5", {"cam_poisson_ratio": 0.5}),
    ],
    "geometry": [
        (
            "the pad moves along the valve axis (its moment arm about the pivot at least 0.1 of its distance)",
            {"valve_angle": "0 deg"},
        ),
        ("`|valve_axis_offset|` < `stem_diameter` / 2", {"valve_axis_offset": "3 mm"}),
    ],
    "friction": [
        ("`fluid_friction` <= `boundary_friction`", {"fluid_friction": 0.2}),
    ],
    "piston": [
        ("`rod_length` above half the `stroke` plus the `pin_offset`", {"rod_length": "40 mm"}),
        ("`tdc_clearance` plus the pocket the head fits above 0", {"tdc_clearance": "-2 mm"}),
        ("`pocket_depth` needs `pocket_diameter` and `valve_head_diameter`", {"pocket_diameter": None}),
        ("`valve_head_diameter` below the `bore`", {"valve_head_diameter": "90 mm"}),
        ("`valve_angle` at most 60 deg", {"valve_angle": "70 deg"}),
        ("`clearance_table` or the geometry, not both", {"clearance_table": "checked.csv"}),
    ],
    "oil": [
        ("`viscosity_100` < `viscosity_40`", {"viscosity_100": "80 mm^2/s"}),
        ("`temperature` from -40 to 170 degC", {"temperature": 600}),
        ("`air_fraction` < 0.5, `polytropic_index` from 1 to 1.4", {"air_fraction": 0.6}),
        (
            "`viscosity` or the datasheet's viscosities (`viscosity_40`, `viscosity_100`), not both",
            {"viscosity": "8 mPa*s"},
        ),
    ],
    "requirements": [
        ("`open_force` > `installed_force`", {"open_force": "100 N"}),
        ("`lift` < `installed_length`", {"lift": "50 mm"}),
        ("`min_inner_diameter` < `max_outer_diameter`", {"min_inner_diameter": "35 mm"}),
        ("`min_float_cam_rpm` needs `cam` and `valve_train`", {"min_float_cam_rpm": "4000 rpm"}),
        ('`material = "custom"` needs the four material values', {"material": "custom"}),
    ],
    "criteria": [],
    "spectrum": [("one `share` per speed, summing to 1", {"share": [0.5, 0.4, 0.05, 0.0]})],
    "cam_card": [
        ("`duration` below 720 crank deg (360 cam deg)", {"duration": "800 deg"}),
        ("`check_height` < `lift` when both are measured at the same place", {"check_height": "9 mm"}),
        (
            "`ramp_velocity` only with ramps (`ramp_height` > 0)",
            {"ramp_height": "0 mm", "ramp_velocity": "0.01 mm/deg"},
        ),
    ],
    "report": [("`min_engine_rpm` < `max_engine_rpm`", {"min_engine_rpm": "9000 rpm"})],
    "cfcs": [
        ("`crank_length` < `coupler_length` (r2 < r3)", {"crank_length": "100 mm"}),
        (
            "either `torsional_stiffness` or all of `pivot_width`, `pivot_thickness`, `pivot_length`, "
            "`youngs_modulus`, never both",
            {"torsional_stiffness": "2.5 N*m/rad"},
        ),
        ("`toggle_cutoff` < 90 deg", {"toggle_cutoff": "95 deg"}),
        ("`drive_damping` needs `drive_stiffness`", {"drive_damping": "5 N*s/m"}),
    ],
    "lsd": [
        ("`packs` >= 2", {"packs": 1}),
        (
            "one thickness per leaf (`leaf_lengths` and `leaf_thicknesses` of equal length)",
            {"leaf_thicknesses": ["1 mm"]},
        ),
        ("`leaf_lengths` non-increasing (longest first)", {"leaf_lengths": ["20 mm", "30 mm", "40 mm"]}),
        ("`poisson_ratio` < 0.5", {"poisson_ratio": 0.6}),
        ("`passages_per_boundary` >= 1", {"passages_per_boundary": 0}),
        (
            "`supply_pressure` (gauge) + 1.01325 bar > `cavitation_pressure` (absolute)",
            {"supply_pressure": "-1.5 bar"},
        ),
        ("`pack_angles`, when given, one per pack, increasing, spanning less than 360 deg", {"pack_angles": ["0 deg"]}),
        (
            'a kinematic `oil_viscosity` ("100 cSt") needs `oil_density`',
            {"oil_viscosity": "100 cSt", "oil_density": None},
        ),
    ],
}

#: File name in the output folder -> generator.
REFERENCE_FILES = {
    "toml.md": "toml_reference",
    "cli.md": "cli_reference",
    "api.md": "api_index",
    "api-valve.md": "api_valve",
    "api-cfcs.md": "api_cfcs",
    "api-lsd.md": "api_lsd",
    "api-core.md": "api_core",
}

#: The API reference by topic (as pvlib's): file -> (title, module name prefixes).
API_TOPICS = {
    "api-valve.md": ("Valve springs", ("springdyn.valve",)),
    "api-cfcs.md": ("Constant-force compression springs", ("springdyn.cfcs",)),
    "api-lsd.md": ("Leaf spring dampers", ("springdyn.lsd",)),
    "api-core.md": ("Shared pieces: units, parameters, results, files, compiled numerics", ("springdyn",)),
}

#: Topics whose modules follow an order of their own rather than the alphabet: file -> (root
#: package, its sub-packages and modules in order, the sentence that says so on the page).  The valve family follows its wings: the
#: facade, the front door ``model`` (:class:`ValveModel`), the wings from the spring up to the
#: design, and the compiled engine, the ground floor, last.  Within a package its modules
#: follow the order in which its docstring names them (``:mod:`.name```), a sub-package's
#: modules right after it, and any module the docstring does not name alphabetically after
#: those (:func:`_package_order`).  Modules of the topic the order does not reach come last,
#: alphabetically.
API_ORDER = {
    "api-valve.md": (
        "springdyn.valve",
        ("model", "spring", "cam", "train", "run", "design", "camshaft", "engine"),
        "The modules follow the wings: the facade `springdyn.valve`, the front door `springdyn.valve.model`, "
        "then `spring`, `cam`, `train`, `run`, `design` and `camshaft`, and the compiled `engine` (the ground "
        "floor) last; "
        "in each wing its package first, then its modules in the order of the package's module map.",
    ),
}

#: Modules left out of the API reference: the command line and report layers (see cli.md).
_APPLICATION_MODULES = re.compile(
    r"^springdyn\.app(\.|$)|^springdyn\.(units|config|errors|io|plotting|progress|integration)$|\.demo$"
)

_HEADER = (
    "<!-- Generated by tools/gen_docs.py ({}); do not edit: run `springdyn docs` or `python tools/gen_docs.py`. -->\n"
)

_KIND_TEXT = {
    "quantity": "number with unit",
    "quantity_list": "list of numbers with unit",
    "int": "integer",
    "str": "string",
    "bool": "true/false",
}

_NUMPYDOC_SECTIONS = (
    "Parameters",
    "Returns",
    "Yields",
    "Raises",
    "Warns",
    "Attributes",
    "Other Parameters",
    "See Also",
    "Notes",
    "References",
    "Examples",
    "Methods",
)
_KEPT_SECTIONS = ("Parameters", "Returns", "Yields", "Raises", "Attributes")


# ----------------------------------------------------------------------------- helpers
def _load(path: str):
    """The object named ``"module:qualname"``."""
    module, _, name = path.partition(":")
    obj = importlib.import_module(module)
    for part in name.split("."):
        obj = getattr(obj, part)
    return obj


def _cell(text) -> str:
    """Text safe inside a Markdown table cell (one line, pipes escaped)."""
    return " ".join(str(text).split()).replace("|", "\\|")


def _stable(text: str) -> str:
    """Drop memory addresses from reprs so that the output is reproducible."""
    return re.sub(r" at 0x[0-9a-fA-F]+", "", text)


def _toml_value(value, meta) -> str:
    """A default value as it would be written in TOML, in the display unit."""
    kind = meta.get("kind")
    if value is None:
        return "none (optional)"
    if kind == "bool":
        return "true" if value else "false"
    if kind == "str":
        return f'"{value}"'
    if kind == "int":
        return str(value)
    unit, display = meta.get("unit") or "", meta.get("display")
    if kind == "quantity_list":
        return "[" + ", ".join(f'"{format_quantity(v, unit, display)}"' for v in value) + "]"
    shown = format_quantity(float(value), unit, display)
    return f'"{shown}"' if (display or unit) else shown


def _default_text(f: dataclasses.Field, meta) -> str:
    """The default of a field for the reference, ``required`` when it has none."""
    if f.default is not dataclasses.MISSING:
        return _toml_value(f.default, meta)
    if f.default_factory is not dataclasses.MISSING:
        return _toml_value(f.default_factory(), meta)
    return "**required**"


def _allowed_text(meta) -> str:
    """The per-key range or choice check applied on load."""
    if meta.get("choices"):
        return "one of " + ", ".join(f'`"{c}"`' for c in meta["choices"])
    if meta.get("positive"):
        return "> 0"
    if meta.get("nonnegative"):
        return ">= 0"
    if meta.get("kind") in ("quantity", "quantity_list"):
        return "finite"
    return "any"


def _markdown(text: str) -> str:
    """Sphinx roles and reST literals of a docstring as Markdown code spans.

    >>> _markdown(":class:`~springdyn.valve.Cam` and ``Fset``")
    '`springdyn.valve.Cam` and `Fset`'
    """
    text = re.sub(r":(?:mod|class|func|meth|attr|data|exc|obj):`~?([^`]+)`", r"`\1`", text)
    return re.sub(r"``([^`]+)``", r"`\1`", text)


def _first_paragraphs(doc: str | None) -> str:
    """The summary and extended summary of a docstring (text before the first section)."""
    doc = inspect.cleandoc(doc or "")
    lines = doc.splitlines()
    out = []
    for i, line in enumerate(lines):
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if line.strip() in _NUMPYDOC_SECTIONS and set(nxt.strip()) == {"-"}:
            break
        out.append(line)
    return "\n".join(out).strip()


def _sections(doc: str | None, names=_KEPT_SECTIONS) -> list[tuple[str, str]]:
    """The numpydoc sections ``names`` of a docstring, as ``(title, body)`` pairs."""
    lines = inspect.cleandoc(doc or "").splitlines()
    found, title, body = [], None, []
    for i, line in enumerate(lines):
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if line.strip() in _NUMPYDOC_SECTIONS and set(nxt.strip()) == {"-"}:
            if title in names:
                found.append((title, "\n".join(body).strip("\n")))
            title, body = line.strip(), []
            continue
        if title is not None and set(line.strip()) == {"-"} and not body:
            continue
        if title is not None:
            body.append(line)
    if title in names:
        found.append((title, "\n".join(body).strip("\n")))
    return found


# ----------------------------------------------------------------------------- TOML
def _kind_text(meta) -> str:
    """The TOML value type of a key."""
    if meta.get("kind") == "quantity" and not (meta.get("unit") or meta.get("display")):
        return "number"
    if meta.get("kind") == "quantity_list" and not (meta.get("unit") or meta.get("display")):
        return "list of numbers"
    return _KIND_TEXT.get(meta.get("kind"), str(meta.get("kind")))


def _table_rows(cls) -> list[str]:
    """Markdown rows, one per TOML key of the parameter class ``cls``."""
    rows = [
        "| key | type | SI unit | display unit | default | allowed | symbol | meaning |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for f, meta in field_specs(cls):
        unit = meta.get("unit") or ("1" if meta.get("kind") in ("quantity", "quantity_list", "int") else "")
        rows.append(
            "| `{}` | {} | {} | {} | {} | {} | {} | {} |".format(
                f.name,
                _kind_text(meta),
                f"`{unit}`" if unit else "",
                f"`{meta['display']}`" if meta.get("display") else "",
                _cell(_default_text(f, meta)),
                _allowed_text(meta),
                _cell(meta.get("symbol") or ""),
                _cell(meta.get("doc") or ""),
            )
        )
    return rows


def _python_only_fields(cls) -> list[dataclasses.Field]:
    """Dataclass fields declared without :func:`~springdyn.core.params.param`: not TOML keys."""
    declared = {f.name for f, _ in field_specs(cls)}
    return [f for f in dataclasses.fields(cls) if f.name not in declared]


def _example_file(name: str) -> str:
    """The text of a built-in example TOML file in ``springdyn/data``."""
    return resources.files("springdyn.data").joinpath(name).read_text(encoding="utf-8").strip()


def toml_reference() -> str:
    """The TOML reference: every key of every parameter table, from the code.

    Returns
    -------
    str
        Markdown: per table (``[spring]``, ``[cam]``, ``[valve_train]``, ``[cfcs]``,
        ``[lsd]``) a table of keys with type, SI unit, display unit, default, allowed
        range or choices, symbol and meaning; the fields that are not TOML keys; the
        cross-key checks of the class docstring; a built-in example file.

    Examples
    --------
    >>> text = toml_reference()
    >>> "| `mean_diameter` | number with unit | `m` | `mm` | **required** | > 0 | Do |" in text
    True
    """
    out = [
        _HEADER.format("toml_reference"),
        "# TOML reference\n",
        "Every parameter file is TOML with one table per object.  A value with a unit is a string",
        '(`"22 mm"`, `"206 GPa"`, `"120 deg"`, `"100 cSt"`); a bare number is read in the SI',
        "unit of the key.  Unknown keys, missing required keys, wrong dimensions and values outside",
        "the allowed range are rejected with a message naming the file, the key and the value.",
        "The *display unit* is the unit of tables and messages.\n",
        "| table | class | used by |",
        "|---|---|---|",
    ]
    users = {
        "spring": "`springdyn valve params/curve/modes/design/simulate/float/sweep`, `springdyn report`",
        "pack": "beside `[spring]` and `[inner_spring]` (a spring pack, springdyn.valve.spring.pack): `springdyn valve simulate/float/sweep`",
        "damper": "beside `[spring]` and `[inner_spring]`: a spring pack's friction damper, `springdyn valve simulate/float/sweep`",
        "cam": "`springdyn valve simulate/float/sweep --cam`, `springdyn report`",
        "timing": "beside `[cam]`: crank angles from TDC in `springdyn valve cam/simulate/sweep`, `springdyn report`",
        "valve_train": "`springdyn valve simulate/float/sweep/train-modes --valve-train`, `springdyn report`",
        "hla": "beside `[valve_train]` (a finger follower on a hydraulic lash adjuster, or a hydraulic bucket): `springdyn valve simulate/float/sweep`, `springdyn report`",
        "follower": "beside `[valve_train]`: `springdyn valve cam-check --valve-train`, `cam-from-lift --valve-train`",
        "geometry": "beside `[valve_train]` (layout `rocker`) and a roller `[follower]`: `springdyn valve kinematics`, `simulate/float/sweep/cam-from-lift --valve-train`, `springdyn report`",
        "friction": "beside `[valve_train]` and `[follower]`: `springdyn valve friction --valve-train`",
        "oil": "beside `[valve_train]`: the one oil of `[hla]` and `[friction]` (their older oil keys mean the same)",
        "piston": "in the valve-train, cam or spring file (once), with `[timing]`: `springdyn valve clearance`, `springdyn report`",
        "requirements": "`springdyn valve synthesize` (a file of its own)",
        "criteria": "beside `[tolerances]`: `springdyn valve tolerance --tolerances`",
        "spectrum": "`springdyn valve life --spectrum` (a file of its own)",
        "cam_card": "`springdyn valve cam-from-lift --card` (with a `[timing]` table beside it)",
        "camshaft": "`springdyn valve camshaft` (a file of its own, with its `[[camshaft.lobes]]`)",
        "camshaft.lobes": "each lobe of `[camshaft]` (`[[camshaft.lobes]]`, one table per lobe): `springdyn valve camshaft`",
        "report": "`springdyn report` (beside a `[spring]` table)",
        "cfcs": "`springdyn cfcs static/dynamic/sweep/forward`, `springdyn report`",
        "lsd": "`springdyn lsd coefficients/rig`, `lsd identify --model`, `springdyn report`",
    }
    for table, (path, _) in PARAMETER_TABLES.items():
        module, _, name = path.partition(":")
        out.append(f"| `[{table}]` | `{module}.{name}` | {users[table]} |")
    out.append("")
    for table, (path, example) in PARAMETER_TABLES.items():
        cls = _load(path)
        module, _, name = path.partition(":")
        out.append(f"## `[{table}]`: `{module}.{name}`\n")
        summary = _markdown(_first_paragraphs(cls.__doc__))
        if summary:
            out.append(summary + "\n")
        out.extend(_table_rows(cls))
        out.append("")
        extra = _python_only_fields(cls)
        if extra:
            names = ", ".join(f"`{f.name}`" for f in extra)
            out.append(
                f"Fields {names} of `{name}` are not TOML keys: they are set from Python only "
                f"(e.g. by a classmethod such as `{name}.from_table`) and are rejected in a TOML file.\n"
            )
        drawing = getattr(importlib.import_module(module), "DRAWING_KEYS", ()) if table == "spring" else ()
        if drawing:
            out.append(
                "Keys of a drawing that `[spring]` also reads and turns into the keys above: "
                + ", ".join(f"`{k}`" for k in drawing)
                + " (with `end_type` and `load_points`; see [the valve spring's guide](../valve-spring.md#the-spring-as-its-drawing-gives-it)).\n"
            )
        rules = CROSS_KEY_RULES.get(table, [])
        if rules:
            out.append("Checks across keys (an `InputError` names the keys and values):\n")
            out.extend(f"- {text}" for text, _ in rules)
            out.append("")
        out.append(f"Built-in example (`springdyn/data/{example}`):\n")
        out.append("```toml\n" + _example_file(example) + "\n```\n")
    return "\n".join(out).rstrip() + "\n"


# ----------------------------------------------------------------------------- CLI
def _subparsers(parser: argparse.ArgumentParser) -> list[tuple[str, str, argparse.ArgumentParser]]:
    """``(name, help, parser)`` of the direct sub-commands of ``parser``."""
    out = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            helps = {a.dest: a.help for a in action._choices_actions}
            seen = set()
            for name, sub in action.choices.items():
                if id(sub) in seen:
                    continue
                seen.add(id(sub))
                out.append((name, helps.get(name, "") or "", sub))
    return out


def _usage(parser: argparse.ArgumentParser) -> str:
    """The usage line at a fixed width (independent of the terminal)."""
    formatter = parser.formatter_class(prog=parser.prog, width=100)
    formatter.add_usage(parser.usage, parser._actions, parser._mutually_exclusive_groups, prefix="")
    return formatter.format_help().strip()


def _help_text(action: argparse.Action, prog: str) -> str:
    """The help of an option with ``%(default)s``-style fields filled in as argparse does."""
    text = action.help or ""
    if "%" in text:
        params = dict(vars(action), prog=prog)
        if params.get("choices") is not None:
            params["choices"] = ", ".join(map(str, params["choices"]))
        try:
            text = text % params
        except (KeyError, TypeError, ValueError):
            pass
    return text


def _option_row(action: argparse.Action, prog: str) -> str:
    """One Markdown row for an argparse action."""
    if action.option_strings:
        names = ", ".join(f"`{s}`" for s in action.option_strings)
        if action.nargs != 0:
            metavar = action.metavar or action.dest.upper()
            names += f" `{metavar if isinstance(metavar, str) else ' '.join(metavar)}`"
    else:
        names = f"`{action.metavar or action.dest}` (positional)"
    default = ""
    if action.default not in (None, argparse.SUPPRESS, False) and action.nargs != 0:
        default = f"`{_stable(str(action.default))}`"
    choices = ", ".join(f"`{c}`" for c in action.choices) if action.choices else ""
    required = "yes" if (action.required or not action.option_strings) and action.nargs not in ("?", "*") else ""
    return f"| {names} | {_cell(_help_text(action, prog))} | {default} | {choices} | {required} |"


def _parser_section(parser: argparse.ArgumentParser, level: int, path: str, help_text: str) -> list[str]:
    """The section of one command and, recursively, of its sub-commands."""
    out = [f"{'#' * min(level, 6)} `{path}`\n"]
    if help_text:
        out.append(_cell(help_text) + "\n")
    if parser.description and parser.description != help_text:
        out.append(parser.description.strip() + "\n")
    out.append("```text\nusage: " + _usage(parser) + "\n```\n")
    actions = [a for a in parser._actions if not isinstance(a, (argparse._SubParsersAction, argparse._HelpAction))]
    if actions:
        out.append("| argument | help | default | choices | required |")
        out.append("|---|---|---|---|---|")
        out.extend(_option_row(a, parser.prog) for a in actions)
        out.append("")
    subs = _subparsers(parser)
    if subs:
        out.append("| command | what it does |")
        out.append("|---|---|")
        out.extend(f"| `{path} {name}` | {_cell(h)} |" for name, h, _ in subs)
        out.append("")
        for name, h, sub in subs:
            out.extend(_parser_section(sub, level + 1, f"{path} {name}", h))
    return out


def cli_reference(parser: argparse.ArgumentParser | None = None) -> str:
    """The CLI reference: every command and option, walked from the argparse parser.

    Parameters
    ----------
    parser : argparse.ArgumentParser, optional
        The parser to document; default :func:`springdyn.app.cli.main.build_parser`.

    Returns
    -------
    str
        Markdown with one section per command (usage, every argument with its help,
        default, choices and whether it is required, the sub-commands).

    Examples
    --------
    >>> p = argparse.ArgumentParser(prog="tool")
    >>> _ = p.add_argument("--points", type=int, default=400, help="number of points")
    >>> "| `--points` `POINTS` | number of points | `400` |  |  |" in cli_reference(p)
    True
    """
    if parser is None:
        from springdyn.app.cli.main import build_parser

        parser = build_parser()
    out = [
        _HEADER.format("cli_reference"),
        "# Command-line reference\n",
        "Quantities accept units (`--speed 3000rpm`, `--stroke 72mm`); a bare number is SI unless the",
        "option says otherwise.  Exit codes: 0 success, 2 bad input (one line on stderr), 3 solver failure.\n",
    ]
    out.extend(_parser_section(parser, 2, parser.prog, ""))
    return "\n".join(out).rstrip() + "\n"


# ----------------------------------------------------------------------------- API
def _public_modules() -> list[str]:
    """Every springdyn module with an ``__all__``, packages before their modules, sorted."""
    import springdyn

    names = ["springdyn"]
    for info in pkgutil.walk_packages(springdyn.__path__, "springdyn."):
        if _APPLICATION_MODULES.search(info.name) or info.name.rsplit(".", 1)[-1].startswith("_"):
            continue
        names.append(info.name)
    mods = []
    for name in sorted(names):
        module = importlib.import_module(name)
        if getattr(module, "__all__", None):
            mods.append(name)
    return mods


def _signature(obj) -> str:
    """``name(args) -> ret`` of a callable, or the empty string when unknown."""
    try:
        return _stable(str(inspect.signature(obj)))
    except (TypeError, ValueError):
        return ""


def _doc_block(doc: str | None) -> list[str]:
    """Summary paragraphs as text, parameter/return sections as preformatted text."""
    out = []
    summary = _markdown(_first_paragraphs(doc))
    if summary:
        out.append(summary + "\n")
    for title, body in _sections(doc):
        if body.strip():
            out.append(f"*{title}*\n\n```text\n{body}\n```\n")
    return out


def _members(cls) -> list[tuple[str, object]]:
    """Public methods and properties defined on ``cls`` itself, in definition order."""
    out = []
    for name, value in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(value, (staticmethod, classmethod)):
            value = value.__func__
        if isinstance(value, (property,)) or inspect.isfunction(value) or hasattr(value, "func"):
            out.append((name, value))
    return out


def _document(name: str, obj, qualified: str) -> list[str]:
    """The reference entry of one public name."""
    if inspect.isclass(obj):
        out = [f"#### class `{qualified}{_signature(obj) if not issubclass(obj, BaseException) else ''}`\n"]
        out.extend(_doc_block(obj.__doc__))
        for mname, member in _members(obj):
            if isinstance(member, property):
                head = f"- property `{mname}`"
                doc = member.__doc__
            else:
                func = getattr(member, "func", member)
                head = f"- `{mname}{_signature(func)}`"
                doc = func.__doc__
            first = _markdown(_first_paragraphs(doc).split("\n\n")[0])
            out.append(head + (f": {_cell(first)}" if first else ""))
        if _members(obj):
            out.append("")
        return out
    if callable(obj):
        out = [f"#### `{qualified}{_signature(obj)}`\n"]
        out.extend(_doc_block(obj.__doc__))
        return out
    if inspect.ismodule(obj):
        return [f"#### `{qualified}`\n", f"The module `{obj.__name__}`.\n"]
    value = _stable(repr(obj))
    if len(value) > 200:
        value = value[:200] + " ..."
    return [f"#### `{qualified}`\n", f"Value: `{_cell(value)}`\n"]


def _topic_of(modname: str) -> str:
    """The API reference file that documents module ``modname``."""
    for filename, (_, prefixes) in API_TOPICS.items():
        if filename != "api-core.md" and any(modname == p or modname.startswith(p + ".") for p in prefixes):
            return filename
    return "api-core.md"


def _docstring_order(package: str) -> list[str]:
    """The modules a package's docstring names as ``:mod:`.name```, in the order it names them."""
    doc = importlib.import_module(package).__doc__ or ""
    return list(dict.fromkeys(re.findall(r":mod:`\.(\w+)`", doc)))


def _package_order(package: str, modules: set[str]) -> list[str]:
    """``package`` (when documented) and the documented modules below it, in reading order.

    Its modules follow the order of its docstring's module map, each sub-package followed by its
    own modules the same way; modules its docstring does not name come after, alphabetically.
    """
    children = sorted({m[len(package) + 1 :].split(".")[0] for m in modules if m.startswith(package + ".")})
    named = [c for c in _docstring_order(package) if c in children] if children else []
    out = [package] if package in modules else []
    for child in named + [c for c in children if c not in named]:
        out.extend(_package_order(f"{package}.{child}", modules))
    return out


def _topic_modules(topic: str, all_modules: list[str] | None = None) -> list[str]:
    """The documented modules of one API topic, in the order its page lists them.

    Packages before their modules, alphabetically, unless :data:`API_ORDER` orders the topic.

    Examples
    --------
    >>> valve = _topic_modules("api-valve.md")
    >>> valve[:3]
    ['springdyn.valve', 'springdyn.valve.model', 'springdyn.valve.spring']
    >>> valve[-1].startswith("springdyn.valve.engine.")
    True
    """
    all_modules = _public_modules() if all_modules is None else all_modules
    mods = [m for m in all_modules if _topic_of(m) == topic]
    if topic not in API_ORDER:
        return mods
    root, parts, _ = API_ORDER[topic]
    present = set(mods)
    out = [root] if root in present else []
    for part in parts:
        out.extend(m for m in _package_order(f"{root}.{part}", present) if m not in out)
    return out + [m for m in mods if m not in out]


def _link(modname: str, here: str) -> str:
    anchor = "#" + modname.replace(".", "")
    target = _topic_of(modname)
    return anchor if target == here else target + anchor


def api_reference(topic: str | None = None) -> str:
    """The Python API reference of one topic: each public module's ``__all__`` with docstrings.

    Parameters
    ----------
    topic : str, optional
        A file of :data:`API_TOPICS` (default: every module, one page).

    Returns
    -------
    str
        Markdown: per module (in the topic's order, :func:`_topic_modules`: the valve
        family by wing, :data:`API_ORDER`; else packages before their modules,
        alphabetically) the names of its ``__all__`` with signature, summary, and the
        Parameters/Returns/Raises/Attributes sections.  A name re-exported by a package is
        documented once, where it is defined, and the package links there.

    Examples
    --------
    >>> "#### class `springdyn.valve.spring.definition.ValveSpring(" in api_reference("api-valve.md")
    True
    """
    all_modules = _public_modules()
    modules = all_modules if topic is None else _topic_modules(topic, all_modules)
    here = topic or ""
    title = "Python API reference" + (f": {API_TOPICS[topic][0]}" if topic else "")
    out = [
        _HEADER.format(f"api_reference({topic!r})" if topic else "api_reference"),
        f"# {title}\n",
        "Generated from the docstrings of every module that declares `__all__` (the command-line",
        "layer is in [cli.md](cli.md); the topics in [api.md](api.md)).  Units are SI unless a",
        "docstring says otherwise; units are given in brackets, source equation numbers in parentheses.\n",
    ]
    if topic in API_ORDER:
        out.append(API_ORDER[topic][2] + "\n")
    out.append("Modules: " + ", ".join(f"[`{m}`](#{m.replace('.', '')})" for m in modules) + "\n")
    for modname in modules:
        module = importlib.import_module(modname)
        out.append(f"## {modname}\n")
        summary = _markdown(_first_paragraphs(module.__doc__))
        if summary:
            out.append(summary + "\n")
        for name in module.__all__:
            obj = getattr(module, name)
            home = getattr(obj, "__module__", None) if (inspect.isclass(obj) or callable(obj)) else modname
            if (
                home
                and home != modname
                and home in all_modules
                and name in getattr(importlib.import_module(home), "__all__", ())
            ):
                out.append(f"- `{name}`: see [`{home}`]({_link(home, here)})")
                continue
            if out[-1].startswith("- `"):
                out.append("")
            out.extend(_document(name, obj, f"{modname}.{name}"))
        if out[-1].startswith("- `"):
            out.append("")
    return "\n".join(out).rstrip() + "\n"


def api_index() -> str:
    """The API reference's first page: the topics and their modules.

    Examples
    --------
    >>> "[api-valve.md](api-valve.md)" in api_index()
    True
    """
    out = [
        _HEADER.format("api_index"),
        "# Python API reference\n",
        "By topic, as the model families are; each page is generated from the docstrings of",
        "every module that declares `__all__`.\n",
        "| topic | page | modules |",
        "|---|---|---|",
    ]
    modules = _public_modules()
    for filename, (title, _) in API_TOPICS.items():
        mods = _topic_modules(filename, modules)
        out.append(f"| {title} | [{filename}]({filename}) | " + ", ".join(f"`{m}`" for m in mods) + " |")
    return "\n".join(out) + "\n"


def api_valve() -> str:
    """The valve family's API reference page."""
    return api_reference("api-valve.md")


def api_cfcs() -> str:
    """The CFCS family's API reference page."""
    return api_reference("api-cfcs.md")


def api_lsd() -> str:
    """The LSD family's API reference page."""
    return api_reference("api-lsd.md")


def api_core() -> str:
    """The shared pieces' API reference page."""
    return api_reference("api-core.md")


# ----------------------------------------------------------------------------- files
def write_docs(out_dir: str | Path = "docs/reference") -> list[Path]:
    """Write the reference files of :data:`REFERENCE_FILES` into ``out_dir`` (atomically).

    Parameters
    ----------
    out_dir : str or Path
        Output folder, created if missing.

    Returns
    -------
    list of Path
        The files written.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    for filename, generator in REFERENCE_FILES.items():
        text = globals()[generator]()
        path = out / filename
        with atomic_open(path, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        written.append(path)
    return written


if __name__ == "__main__":  # pragma: no cover
    import sys

    for p in write_docs(sys.argv[1] if len(sys.argv) > 1 else "docs/reference"):
        print(p)
