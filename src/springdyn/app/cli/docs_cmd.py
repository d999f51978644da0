"""``springdyn docs``: regenerate the TOML, CLI and API references.

The generator lives in ``tools/gen_docs.py`` of a source checkout (it is not part of the
installed package); this command runs it when springdyn is installed from a checkout.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

from springdyn.core.errors import InputError

__all__ = ["register", "cmd_docs", "generator_path"]


def generator_path() -> Path:
    """``tools/gen_docs.py`` of the source checkout springdyn was installed from."""
    return Path(__file__).resolve().parents[4] / "tools" / "gen_docs.py"


def register(subparsers) -> None:
    """Add the ``docs`` command to the ``springdyn`` sub-command parsers."""
    p = subparsers.add_parser(
        "docs",
        help="write the generated TOML, CLI and API references (Markdown; needs a source checkout)",
        description="Write toml.md, cli.md and the API reference (api.md and a page per topic), generated from the code, into a folder.",
    )
    p.add_argument("--out", default="docs/reference", help="output folder (default: docs/reference)")
    p.set_defaults(func=cmd_docs)


def cmd_docs(args) -> int:
    """Write the references into ``args.out`` and list the files."""
    path = generator_path()
    if not path.is_file():
        raise InputError(
            "springdyn docs needs a source checkout of springdyn (tools/gen_docs.py); "
            f"it is not beside this installation ({path})"
        )
    spec = importlib.util.spec_from_file_location("springdyn_gen_docs", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    for written in module.write_docs(args.out):
        print(written)
    return 0
