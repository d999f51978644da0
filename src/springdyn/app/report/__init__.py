"""The springdyn report: one self-contained HTML page over any mix of model definitions.

:func:`build_report` reads TOML definition files (a ``[spring]`` table with optional
``[cam]`` and ``[valve_train]``, a ``[cfcs]`` table, an ``[lsd]`` table, in any mix),
runs each family's analyses through ``springdyn.app.report.<family>.section``, writes their
tables and figures beside the page, and renders ``index.html`` with the figures
embedded.  ``springdyn demo`` is this report over the built-in example definitions.

- :mod:`.build` -- reads the definitions, runs the sections, writes the page;
- :mod:`.html` -- the page itself;
- :mod:`.valve`, :mod:`.cfcs`, :mod:`.lsd` -- each family's section.
"""

from .build import DEMO_DEFINITIONS, build_report, demo_definitions
from .html import Section, render_html

__all__ = ["Section", "render_html", "build_report", "demo_definitions", "DEMO_DEFINITIONS"]
