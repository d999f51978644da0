"""``springdyn docs``: regenerate the TOML, CLI and API references (:mod:`springdyn.docs`)."""

from __future__ import annotations

__all__ = ["register", "cmd_docs"]


def register(subparsers) -> None:
    """Add the ``docs`` command to the ``springdyn`` sub-command parsers."""
    p = subparsers.add_parser(
        "docs",
        help="write the generated TOML, CLI and API references (Markdown)",
        description="Write toml.md, cli.md and api.md, generated from the code, into a folder.",
    )
    p.add_argument("--out", default="docs/reference", help="output folder (default: docs/reference)")
    p.set_defaults(func=cmd_docs)


def cmd_docs(args) -> int:
    """Write the references into ``args.out`` and list the files."""
    from ..docs import write_docs

    for path in write_docs(args.out):
        print(path)
    return 0
