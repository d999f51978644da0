"""Generated references (tools/gen_docs.py): complete, reproducible, committed up to date."""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import inspect
import re
import sys
from importlib import resources
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tools"))
import gen_docs as docs  # noqa: E402  (tools/ is not part of the installed package)

from springdyn.app.cli import docs_cmd
from springdyn.app.cli.main import build_parser
from springdyn.core.errors import InputError
from springdyn.core.params import load_toml
from tests.paths import ROOT

REFERENCE = ROOT / "docs" / "reference"


@pytest.fixture(scope="module")
def generated():
    return {name: getattr(docs, gen)() for name, gen in docs.REFERENCE_FILES.items()}


def _parameter_classes():
    return {table: docs._load(path) for table, (path, _) in docs.PARAMETER_TABLES.items()}


def _walk_parsers(parser, path="springdyn"):
    yield path, parser
    for name, _, sub in docs._subparsers(parser):
        yield from _walk_parsers(sub, f"{path} {name}")


# --------------------------------------------------------------------------- drift
@pytest.mark.parametrize("name", list(docs.REFERENCE_FILES))
def test_committed_reference_is_up_to_date(generated, name):
    committed = (REFERENCE / name).read_text(encoding="utf-8")
    assert committed == generated[name], (
        f"docs/reference/{name} is out of date: run `springdyn docs` (or `python tools/gen_docs.py`) and commit it"
    )


def test_generation_is_reproducible(generated):
    again = {name: getattr(docs, gen)() for name, gen in docs.REFERENCE_FILES.items()}
    assert again == generated
    for text in generated.values():
        assert not re.search(r" at 0x[0-9a-f]+", text)
        assert str(ROOT) not in text


# --------------------------------------------------------------------------- TOML
def test_every_parameter_class_of_springdyn_is_documented():
    """A new dataclass declared with config.param must get a TOML table in the reference."""
    documented = set(_parameter_classes().values())
    found = set()
    for name in [*docs._public_modules(), "springdyn.app.report.valve"]:  # the report's own [report] table
        for obj in vars(importlib.import_module(name)).values():
            if inspect.isclass(obj) and dataclasses.is_dataclass(obj) and obj.__module__.startswith("springdyn"):
                if any("kind" in f.metadata for f in dataclasses.fields(obj)):
                    found.add(obj)
    assert found == documented


def test_toml_reference_lists_every_field_with_unit_default_and_range(generated):
    text = generated["toml.md"]
    for table, cls in _parameter_classes().items():
        section = text.split(f"## `[{table}]`", 1)[1].split("\n## ", 1)[0]
        for f in dataclasses.fields(cls):
            assert f"`{f.name}`" in section, f"[{table}] {f.name} missing from the TOML reference"
            meta = f.metadata
            if "kind" not in meta:
                assert "are not TOML keys" in section
                continue
            row = next(line for line in section.splitlines() if line.startswith(f"| `{f.name}` |"))
            cells = [c.strip() for c in row.strip("|").split("|")]
            assert len(cells) == 8, row
            if meta["unit"]:
                assert cells[2] == f"`{meta['unit']}`"
            if meta.get("display"):
                assert cells[3] == f"`{meta['display']}`"
            required = f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
            assert (cells[4] == "**required**") == required, row
            if meta.get("choices"):
                assert all(f'"{c}"' in cells[5] for c in meta["choices"])
            elif meta.get("positive"):
                assert cells[5] == "> 0"
            elif meta.get("nonnegative"):
                assert cells[5] == ">= 0"
            assert cells[7] == " ".join(meta["doc"].split()).replace("|", "\\|")


def test_toml_defaults_read_back_to_the_declared_defaults():
    """Each default as printed (display unit) loads back to the SI default."""
    for cls in _parameter_classes().values():
        for f, meta in docs.field_specs(cls):
            if f.default is dataclasses.MISSING or f.default is None or meta["kind"] not in ("quantity",):
                continue
            shown = docs._toml_value(f.default, meta).strip('"')
            from springdyn.core.units import to_si

            assert to_si(shown, meta["unit"], f.name) == pytest.approx(f.default, rel=1e-4, abs=1e-12)


@pytest.mark.parametrize(
    "table,rule,change",
    [(t, text, change) for t, rules in docs.CROSS_KEY_RULES.items() for text, change in rules],
)
def test_listed_cross_key_rules_are_enforced(table, rule, change):
    path, example = docs.PARAMETER_TABLES[table]
    cls = docs._load(path)
    with resources.as_file(resources.files("springdyn.data") / example) as p:
        mapping = dict(load_toml(p, table))
        cls.from_dict(mapping)  # the example itself is valid
    for key, value in change.items():
        if value is None:
            mapping.pop(key, None)
        else:
            mapping[key] = value
    with pytest.raises(InputError) as err:
        cls.from_dict(mapping)
    assert any(key in str(err.value) for key in change) or "K =" in str(err.value)


# --------------------------------------------------------------------------- CLI
def test_cli_reference_lists_every_command_and_option(generated):
    text = generated["cli.md"]
    parser = build_parser()
    n_options = 0
    for path, p in _walk_parsers(parser):
        assert f"`{path}`" in text, f"command {path} missing"
        section = text.split(f"`{path}`\n", 1)[1]
        section = re.split(r"\n#+ `", section, maxsplit=1)[0]
        for action in p._actions:
            if isinstance(action, (argparse._HelpAction, argparse._SubParsersAction)):
                continue
            for opt in action.option_strings:
                n_options += 1
                assert f"`{opt}`" in section, f"{path}: option {opt} missing"
            if not action.option_strings:
                assert f"`{action.metavar or action.dest}` (positional)" in section
            if action.choices and not isinstance(action, argparse._SubParsersAction):
                assert all(f"`{c}`" in section for c in action.choices)
            if action.default not in (None, False, argparse.SUPPRESS) and action.nargs != 0:
                assert f"`{action.default}`" in section, f"{path}: default of {action.dest} missing"
    assert n_options > 50


def test_docs_command_writes_the_references(tmp_path, capsys):
    parser = argparse.ArgumentParser(prog="springdyn")
    sub = parser.add_subparsers(dest="command", required=True)
    docs_cmd.register(sub)
    args = parser.parse_args(["docs", "--out", str(tmp_path / "ref")])
    assert args.func(args) == 0
    written = sorted(p.name for p in (tmp_path / "ref").iterdir())
    assert written == sorted(docs.REFERENCE_FILES)
    assert "toml.md" in capsys.readouterr().out
    assert (tmp_path / "ref" / "toml.md").read_text(encoding="utf-8") == docs.toml_reference()
    assert "springdyn docs" in docs.cli_reference(parser)


# --------------------------------------------------------------------------- API
def test_api_reference_lists_every_public_name(generated):
    text = "".join(v for k, v in generated.items() if k.startswith("api-"))
    modules = docs._public_modules()
    assert {"springdyn", "springdyn.valve", "springdyn.cfcs", "springdyn.lsd", "springdyn.core.params"} <= set(modules)
    for modname in modules:
        section = text.split(f"\n## {modname}\n", 1)[1].split("\n## ", 1)[0]
        for name in importlib.import_module(modname).__all__:
            assert f"`{name}`" in section or f"`{modname}.{name}" in section, f"{modname}.{name} missing"


def test_api_reference_keeps_units_and_parameters_sections(generated):
    from springdyn.valve import float_speed

    text = generated["api-valve.md"]
    head = f"#### `{float_speed.__module__}.float_speed("
    assert head in text
    entry = text.split(head, 1)[1].split("\n#### ", 1)[0]
    assert "*Returns*" in entry and "float_cam_rpm" in entry
    assert "[rev/min]" in entry


def test_valve_api_reference_is_ordered_by_wing(generated):
    """api-valve.md: the facade, ValveModel, then spring, cam, train, run, design, engine; each
    wing's package before its modules, which follow its docstring's module map."""
    modules = [m for m in docs._public_modules() if m.startswith("springdyn.valve")]
    order = docs._topic_modules("api-valve.md")
    assert sorted(order) == sorted(modules) and len(order) == len(set(order))
    assert order[:2] == ["springdyn.valve", "springdyn.valve.model"]
    wings = [m.split(".")[2] for m in order[2:]]
    runs = [w for k, w in enumerate(wings) if k == 0 or wings[k - 1] != w]
    assert runs == ["spring", "cam", "train", "run", "design", "camshaft", "engine"], runs  # each wing in one block
    for wing in runs:
        block = [m for m in order if m.split(".")[2:3] == [wing]]
        assert block[0] == f"springdyn.valve.{wing}"
        mapped = [m for m in docs._docstring_order(block[0]) if f"{block[0]}.{m}" in block]
        assert [m.split(".")[3] for m in block[1:] if m.count(".") == 3] == mapped + sorted(
            m.split(".")[3] for m in block[1:] if m.count(".") == 3 and m.split(".")[3] not in mapped
        )
    headings = re.findall(r"^## (springdyn\.valve\S*)$", generated["api-valve.md"], re.M)
    assert headings == order
    index_row = next(line for line in generated["api.md"].splitlines() if "(api-valve.md)" in line)
    assert re.findall(r"`(springdyn[\w.]*)`", index_row) == order


# --------------------------------------------------------------------------- doctests
def _all_modules():
    import pkgutil

    import springdyn

    names = ["springdyn"] + [m.name for m in pkgutil.walk_packages(springdyn.__path__, "springdyn.")]
    return sorted(n for n in names if not n.endswith("__main__"))


@pytest.mark.parametrize("modname", _all_modules())
def test_doctests(modname):
    """The docstring examples of every springdyn module run and give what they show."""
    import doctest

    module = importlib.import_module(modname)
    finder = doctest.DocTestFinder(exclude_empty=True)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    for test in finder.find(module, modname, globs=dict(vars(module))):
        runner.run(test)
    result = runner.summarize(verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} doctest examples failed in {modname}"


def test_doctest_runner_finds_examples():
    import doctest

    for modname in ("springdyn.valve.spring.definition", "springdyn.valve.cam.definition", "springdyn.core.units"):
        module = importlib.import_module(modname)
        tests = doctest.DocTestFinder(exclude_empty=True).find(module, modname)
        assert sum(len(t.examples) for t in tests) > 0, modname


# --------------------------------------------------------------------------- guides
DOCS = ROOT / "docs"


def _slug(heading: str) -> str:
    """GitHub's anchor of a Markdown heading."""
    text = heading.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def _anchors(path: Path) -> set:
    return {_slug(m.group(1)) for m in re.finditer(r"^#+ (.+)$", path.read_text(encoding="utf-8"), re.M)}


@pytest.mark.parametrize("guide", sorted(p.name for p in DOCS.glob("*.md")))
def test_guide_links_resolve(guide):
    """Relative links of the guides point to existing files and headings."""
    path = DOCS / guide
    text = path.read_text(encoding="utf-8")
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+://", target):
            continue
        file, _, anchor = target.partition("#")
        dest = (path.parent / file).resolve() if file else path
        assert dest.exists(), f"{guide}: link to missing {file}"
        if anchor:
            assert anchor in _anchors(dest), f"{guide}: no heading #{anchor} in {file or guide}"


def test_index_lists_every_guide_and_example():
    index = (DOCS / "README.md").read_text(encoding="utf-8")
    for guide in DOCS.glob("*.md"):
        if guide.name != "README.md":
            assert f"]({guide.name})" in index, f"docs/README.md does not link {guide.name}"
    for script in (ROOT / "examples").rglob("*.py"):
        assert f"`{script.relative_to(ROOT).as_posix()}`" in index, f"docs/README.md does not list {script}"


@pytest.mark.parametrize("family", ["valve", "cfcs", "lsd"])
def test_guide_per_family_covers_the_required_parts(family):
    """Physics, assumptions, corrections with reasons, validity limits."""
    text = (DOCS / f"{family}.md").read_text(encoding="utf-8").lower()
    for part in ("physics", "assumption", "correction", "limit"):
        assert part in text, f"docs/{family}.md lacks a part on {part}"
