"""Progress reporting for long jobs: a bar on a terminal, a line now and then in a log, silent
with ``quiet``."""

from __future__ import annotations

import sys
import time
from collections.abc import Iterable, Iterator
from typing import TypeVar

T = TypeVar("T")

__all__ = ["progress", "LOG_INTERVAL"]

#: Seconds between the progress lines written where stderr is not a terminal (a log, CI, a pipe) [s]:
#: a long job says how far it is, a short one says nothing.
LOG_INTERVAL = 30.0


def progress(iterable: Iterable[T], *, total: int | None = None, desc: str = "", quiet: bool = False) -> Iterator[T]:
    """Wrap ``iterable`` in a progress bar when stderr is a terminal; elsewhere write a line
    ``springdyn: DESC: 12/64 (19 %) after 31 s`` every :data:`LOG_INTERVAL` seconds; nothing
    with ``quiet``."""
    if quiet:
        yield from iterable
        return
    if not sys.stderr.isatty():
        yield from _logged(iterable, total, desc)
        return
    from tqdm.auto import tqdm

    yield from tqdm(iterable, total=total, desc=desc, leave=False, file=sys.stderr)


def _logged(iterable: Iterable[T], total: int | None, desc: str) -> Iterator[T]:
    start = last = time.monotonic()
    for done, item in enumerate(iterable, start=1):
        yield item
        now = time.monotonic()
        if now - last >= LOG_INTERVAL:
            last = now
            share = f"/{total} ({100.0 * done / total:.0f} %)" if total else ""
            print(
                f"springdyn: {desc or 'working'}: {done}{share} after {now - start:.0f} s", file=sys.stderr, flush=True
            )
