"""Rendering of report sections to one self-contained HTML page."""

from __future__ import annotations

import base64
import datetime as _dt
import html
from dataclasses import dataclass, field
from pathlib import Path

from springdyn import __version__
from springdyn.core.io import atomic_open

__all__ = ["Section", "render_html", "parameter_rows", "fmt"]


@dataclass
class Section:
    """One report section: a model definition with its inputs, results and figures.

    ``inputs`` and ``derived`` are rows ``(name, value with unit, meaning)``; ``figures``
    are ``(png path, caption)``; ``findings`` are plain sentences computed from results;
    ``commands`` reproduce the section from the CLI.
    """

    family: str
    title: str
    source: str
    commands: list[str] = field(default_factory=list)
    inputs: list[tuple] = field(default_factory=list)
    derived: list[tuple] = field(default_factory=list)
    findings: list[str] = field(default_factory=list)
    figures: list[tuple] = field(default_factory=list)
    tables: list[tuple] = field(default_factory=list)  # (caption, headers, rows)
    files: list[Path] = field(default_factory=list)

    @property
    def anchor(self) -> str:
        return "".join(c if c.isalnum() else "-" for c in f"{self.family}-{self.title}".lower())


_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:0;color:#1d2733;background:#f6f7f9}
header{background:#1f3a5f;color:#fff;padding:1.2em 2em}header h1{margin:0 0 .2em 0;font-size:1.6em}
header p{margin:.2em 0;opacity:.85}main{max-width:1200px;margin:0 auto;padding:1em 2em 3em}
nav{background:#fff;border:1px solid #dde3ea;border-radius:8px;padding:.6em 1.2em;margin:1em 0}
nav li{margin:.2em 0}section{background:#fff;border:1px solid #dde3ea;border-radius:8px;padding:1em 1.6em;margin:1.4em 0}
section h2{margin-top:.2em;color:#1f3a5f}h3{color:#33475b;margin-bottom:.4em}
table{border-collapse:collapse;font-size:.9em;margin:.4em 0 1em}td,th{border-bottom:1px solid #e4e8ee;padding:.25em .8em;text-align:left}
th{background:#eef2f6}td.v{font-family:ui-monospace,Menlo,monospace;white-space:nowrap}
pre{background:#0f1b2a;color:#e6edf3;padding:.7em 1em;border-radius:6px;overflow-x:auto;font-size:.85em}
ul.findings li{margin:.3em 0}.grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(520px,1fr));gap:1em}
figure{margin:0;background:#fafbfc;border:1px solid #e4e8ee;border-radius:6px;padding:.5em}
figure img{width:100%;height:auto}figcaption{font-size:.85em;color:#4b5b6b;margin-top:.3em}
.two{display:grid;grid-template-columns:1fr 1fr;gap:1.5em}.src{color:#6b7b8b;font-size:.85em}
"""

_JS = """
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.querySelectorAll('img'));
  var ok = imgs.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  var empty = Array.prototype.slice.call(document.querySelectorAll('section')).filter(function (s) {
    return s.querySelectorAll('img').length === 0 || s.querySelectorAll('ul.findings li').length === 0; }).length;
  document.body.setAttribute('data-figures-loaded', ok + '/' + imgs.length);
  document.body.setAttribute('data-empty-sections', String(empty));
});
"""


def fmt(value: float, unit: str = "", digits: int = 5) -> str:
    """A number with its unit for tables and sentences: ``fmt(251.432, "N") -> '251.43 N'``."""
    return f"{float(value):.{digits}g} {unit}".strip()


def parameter_rows(obj) -> list[tuple]:
    """``(key, value in its display unit, meaning)`` for every declared field of a parameter dataclass."""
    import dataclasses

    from springdyn.core.params import describe_value

    rows = []
    for f in dataclasses.fields(obj):
        meta = f.metadata
        value = getattr(obj, f.name)
        if value is None or f.name.startswith("table_"):
            continue
        if "kind" in meta and meta["kind"] == "quantity" and isinstance(value, (int, float)) and not isinstance(value, bool):
            shown = describe_value(value, meta)
        elif "kind" in meta and meta["kind"] == "quantity_list":
            shown = ", ".join(describe_value(v, {**meta, "kind": "quantity"}) for v in value)
        else:
            shown = str(value)
        doc = meta.get("doc", "")
        if meta.get("symbol"):
            doc = f"{doc} ({meta['symbol']})" if doc else meta["symbol"]
        rows.append((f.name, shown, doc))
    return rows


def _table(rows, headers=("quantity", "value", "meaning")) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in headers)
    body = []
    for r in rows:
        cells = [f'<td class="v">{html.escape(str(c))}</td>' if i == 1 else f"<td>{html.escape(str(c))}</td>"
                 for i, c in enumerate(r)]
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<table><tr>{head}</tr>{''.join(body)}</table>"


def _img(path: Path, embed: bool, base: Path) -> str:
    path = Path(path)
    if embed:
        data = base64.b64encode(path.read_bytes()).decode("ascii")
        return f'<img alt="{html.escape(path.stem)}" src="data:image/png;base64,{data}">'
    rel = path.resolve().relative_to(base.resolve()) if path.resolve().is_relative_to(base.resolve()) else path
    return f'<img alt="{html.escape(path.stem)}" src="{html.escape(str(rel))}">'


def render_html(sections: list[Section], path, *, title: str = "springdyn report", embed: bool = True,
                subtitle: str = "") -> Path:
    """Write the report page (figures embedded as data URIs unless ``embed=False``)."""
    path = Path(path)
    base = path.parent
    parts = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        f"<title>{html.escape(title)}</title><style>{_CSS}</style><script>{_JS}</script></head><body>",
        f"<header><h1>{html.escape(title)}</h1><p>{html.escape(subtitle)}</p>"
        f"<p>springdyn {__version__} &middot; {_dt.datetime.now().strftime('%Y-%m-%d %H:%M')} &middot; "
        "SI units unless stated; files beside this page hold every table (CSV/JSON, SI, unit in the column name).</p></header>",
        "<main><nav><strong>Sections</strong><ul>",
    ]
    parts += [f"<li><a href='#{s.anchor}'>{html.escape(s.title)}</a> <span class='src'>({html.escape(s.source)})</span></li>"
              for s in sections]
    parts.append("</ul></nav>")
    for s in sections:
        parts.append(f"<section id='{s.anchor}' data-family='{html.escape(s.family)}'><h2>{html.escape(s.title)}</h2>")
        parts.append(f"<p class='src'>definition: {html.escape(s.source)}</p>")
        parts.append("<h3>Findings</h3><ul class='findings'>" + "".join(f"<li>{html.escape(f)}</li>" for f in s.findings)
                     + "</ul>")
        parts.append("<div class='two'><div><h3>Inputs</h3>" + _table(s.inputs) + "</div>"
                     + "<div><h3>Derived parameters</h3>" + _table(s.derived) + "</div></div>")
        for caption, headers, rows in s.tables:
            parts.append(f"<h3>{html.escape(caption)}</h3>" + _table(rows, headers))
        parts.append("<h3>Figures</h3><div class='grid'>")
        for fig, caption in s.figures:
            parts.append(f"<figure>{_img(fig, embed, base)}<figcaption>{html.escape(caption)}</figcaption></figure>")
        parts.append("</div><h3>Reproduce from the command line</h3><pre>"
                     + html.escape("\n".join(s.commands)) + "</pre>")
        if s.files:
            links = ", ".join(
                f"<a href='{html.escape(str(Path(f).resolve().relative_to(base.resolve())))}'>{html.escape(Path(f).name)}</a>"
                for f in s.files if Path(f).resolve().is_relative_to(base.resolve())
            )
            parts.append(f"<p class='src'>data files: {links}</p>")
        parts.append("</section>")
    parts.append("</main></body></html>")
    with atomic_open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(parts))
    return path
