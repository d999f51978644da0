"""Where the repository's folders are, for tests that read its examples and docs: never
relative to the working directory (``tests/test_architecture.py`` rejects such paths)."""

from pathlib import Path

#: The repository's root folder.
ROOT = Path(__file__).resolve().parents[1]
#: The example definitions.
EXAMPLES = ROOT / "examples"
#: The user guides.
DOCS = ROOT / "docs"


def example(relative: str) -> str:
    """The path of an example file, ``example("valve/cam_345.toml")``, as a string (a CLI argument).

    Parameters
    ----------
    relative : str
        The file's path below ``examples/``.
    """
    return str(EXAMPLES / relative)
