"""Rendering of report sections to one self-contained HTML page."""

from __future__ import annotations

import base64
import datetime as _dt
import html
from dataclasses import dataclass, field
from pathlib import Path

from springdyn import __version__
from springdyn.core.io import atomic_open

__all__ = ["Section", "Criterion", "render_html", "parameter_rows", "fmt", "add_result", "png_min_font_px"]


@dataclass
class Criterion:
    """One row of a section's criteria table: a figure checked against its limit.

    ``passed`` is True (pass), False (fail) or None (not applicable, with ``note`` saying why).
    """

    name: str
    value: str
    limit: str
    passed: bool | None
    note: str = ""
    #: The model whose figure is judged ("distributed", "Type C", "statics"; empty: no model).
    model: str = ""

    @property
    def verdict(self) -> str:
        return {True: "pass", False: "fail", None: "n/a"}[self.passed]


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
    criteria: list[Criterion] = field(default_factory=list)

    @property
    def anchor(self) -> str:
        return "".join(c if c.isalnum() else "-" for c in f"{self.family}-{self.title}".lower())


_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Roboto,sans-serif;margin:0;color:#1d2733;background:#f6f7f9;
font-size:16px;line-height:1.45}
header{background:#1f3a5f;color:#fff;padding:1.2em 2em}header h1{margin:0 0 .2em 0;font-size:1.6em}
header p{margin:.2em 0;opacity:.9}main{max-width:1240px;margin:0 auto;padding:1em 2em 3em}
nav{background:#fff;border:1px solid #dde3ea;border-radius:8px;padding:.6em 1.2em;margin:1em 0}
nav li{margin:.2em 0}section{background:#fff;border:1px solid #dde3ea;border-radius:8px;padding:1em 1.6em;margin:1.4em 0}
section h2{margin-top:.2em;color:#1f3a5f}h3{color:#33475b;margin-bottom:.4em}
.scroll{overflow-x:auto;max-width:100%}
table{border-collapse:collapse;font-size:.92em;margin:.4em 0 1em}td,th{border-bottom:1px solid #e4e8ee;padding:.3em .8em;
text-align:left;vertical-align:top}th{background:#eef2f6}td.v{font-family:ui-monospace,Menlo,monospace;white-space:nowrap}
table.criteria td.verdict{font-weight:700;text-transform:uppercase;letter-spacing:.03em;white-space:nowrap}
tr.pass td.verdict{color:#fff;background:#2e7d32}tr.fail td.verdict{color:#fff;background:#c62828}
tr.na td.verdict{color:#1d2733;background:#e0e4e8}tr.fail td{background:#fdecea}
pre{background:#0f1b2a;color:#e6edf3;padding:.7em 1em;border-radius:6px;overflow-x:auto;font-size:.85em}
ul.findings li{margin:.3em 0}.figs{display:grid;grid-template-columns:1fr;gap:1.2em}
figure{margin:0;background:#fafbfc;border:1px solid #e4e8ee;border-radius:6px;padding:.5em}
figure img{width:100%;height:auto;display:block;cursor:zoom-in}figcaption{font-size:.92em;color:#4b5b6b;margin-top:.3em}
.two{display:grid;grid-template-columns:1fr 1fr;gap:1.5em}.two>div{min-width:0}.src{color:#5b6b7b;font-size:.9em}
@media (max-width:900px){main{padding:.5em .8em 2em}.two{grid-template-columns:1fr}section{padding:.8em .9em}
header{padding:1em}}
"""

_JS = """
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.querySelectorAll('img'));
  var ok = imgs.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  var empty = Array.prototype.slice.call(document.querySelectorAll('section')).filter(function (s) {
    return s.querySelectorAll('img').length === 0 || s.querySelectorAll('ul.findings li').length === 0
      || s.querySelectorAll('table.criteria tr.criterion').length === 0; }).length;
  var minFont = Infinity;
  imgs.forEach(function (i) {
    var native = parseFloat(i.getAttribute('data-min-font-px'));
    if (i.naturalWidth > 0 && !isNaN(native)) {
      minFont = Math.min(minFont, native * i.getBoundingClientRect().width / i.naturalWidth);
    }
  });
  var verdicts = Array.prototype.slice.call(document.querySelectorAll('table.criteria td.verdict')).map(function (c) {
    return c.textContent.trim() + ':' + getComputedStyle(c).backgroundColor; });
  document.body.setAttribute('data-figures-loaded', ok + '/' + imgs.length);
  document.body.setAttribute('data-empty-sections', String(empty));
  document.body.setAttribute('data-min-figure-font-px', isFinite(minFont) ? minFont.toFixed(1) : 'none');
  document.body.setAttribute('data-page-width', String(document.documentElement.clientWidth));
  document.body.setAttribute('data-criteria-verdicts', verdicts.join('|'));
  document.body.setAttribute('data-page-overflow',
    String(document.documentElement.scrollWidth > document.documentElement.clientWidth + 1));
});
"""


def add_result(files: list, figures: list, result, png: Path, caption: str) -> None:
    """Write a result's table and figure for a section: its CSV beside the PNG ``png`` (same
    name), listed in ``files``, and the PNG with its ``caption`` in ``figures``."""
    from springdyn.core.plotting import plt

    files.append(result.to_csv(png.with_suffix(".csv")))
    plt.close(result.plot(png))
    figures.append((png, caption))


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
        if (
            "kind" in meta
            and meta["kind"] == "quantity"
            and isinstance(value, (int, float))
            and not isinstance(value, bool)
        ):
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
        cells = [
            f'<td class="v">{html.escape(str(c))}</td>' if i == 1 else f"<td>{html.escape(str(c))}</td>"
            for i, c in enumerate(r)
        ]
        body.append("<tr>" + "".join(cells) + "</tr>")
    return f"<div class='scroll'><table><tr>{head}</tr>{''.join(body)}</table></div>"


def _criteria(criteria: list[Criterion]) -> str:
    rows = []
    for c in criteria:
        css = {"pass": "pass", "fail": "fail", "n/a": "na"}[c.verdict]
        rows.append(
            f"<tr class='criterion {css}'><td>{html.escape(c.name)}</td><td>{html.escape(c.model or '-')}</td>"
            f"<td class='v'>{html.escape(c.value)}</td><td>{html.escape(c.limit)}</td>"
            f"<td class='verdict'>{c.verdict}</td><td>{html.escape(c.note)}</td></tr>"
        )
    head = "".join(f"<th>{h}</th>" for h in ("criterion", "judged by", "value", "limit", "verdict", "note"))
    return f"<div class='scroll'><table class='criteria'><tr>{head}</tr>{''.join(rows)}</table></div>"


def png_min_font_px(path) -> float | None:
    """The ``springdyn:min-font-px`` text chunk of a PNG written by springdyn (None if absent)."""
    data = Path(path).read_bytes()
    pos = 8
    while pos + 8 <= len(data):
        length = int.from_bytes(data[pos : pos + 4], "big")
        kind = data[pos + 4 : pos + 8]
        if kind == b"tEXt":
            key, _, value = data[pos + 8 : pos + 8 + length].partition(b"\x00")
            if key == b"springdyn:min-font-px":
                try:
                    return float(value)
                except ValueError:
                    return None
        if kind == b"IDAT":
            return None
        pos += 12 + length
    return None


def _img(path: Path, embed: bool, base: Path) -> str:
    """The figure, linked to its full-size PNG beside the page (a click opens it)."""
    path = Path(path)
    rel = path.resolve().relative_to(base.resolve()) if path.resolve().is_relative_to(base.resolve()) else path
    font = png_min_font_px(path)
    font_attr = f' data-min-font-px="{font:.2f}"' if font is not None else ""
    if embed:
        data = base64.b64encode(path.read_bytes()).decode("ascii")
        src = f"data:image/png;base64,{data}"
    else:
        src = html.escape(str(rel))
    return (
        f'<a href="{html.escape(str(rel))}" target="_blank" title="open the full-size figure">'
        f'<img alt="{html.escape(path.stem)}" src="{src}"{font_attr}></a>'
    )


def render_html(
    sections: list[Section], path, *, title: str = "springdyn report", embed: bool = True, subtitle: str = ""
) -> Path:
    """Write the report page (figures embedded as data URIs unless ``embed=False``)."""
    path = Path(path)
    base = path.parent
    parts = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><meta name='viewport' content='width=device-width, initial-scale=1'>",
        f"<title>{html.escape(title)}</title><style>{_CSS}</style><script>{_JS}</script></head><body>",
        f"<header><h1>{html.escape(title)}</h1><p>{html.escape(subtitle)}</p>"
        f"<p>springdyn {__version__} &middot; {_dt.datetime.now().strftime('%Y-%m-%d %H:%M')} &middot; "
        "SI units unless stated; files beside this page hold every table (CSV/JSON, SI, unit in the column name).</p></header>",
        "<main><nav><strong>Sections</strong><ul>",
    ]
    parts += [
        f"<li><a href='#{s.anchor}'>{html.escape(s.title)}</a> <span class='src'>({html.escape(s.source)})</span></li>"
        for s in sections
    ]
    parts.append("</ul></nav>")
    for s in sections:
        parts.append(f"<section id='{s.anchor}' data-family='{html.escape(s.family)}'><h2>{html.escape(s.title)}</h2>")
        parts.append(f"<p class='src'>definition: {html.escape(s.source)}</p>")
        parts.append("<h3>Criteria</h3>" + _criteria(s.criteria))
        parts.append(
            "<h3>Findings</h3><ul class='findings'>"
            + "".join(f"<li>{html.escape(f)}</li>" for f in s.findings)
            + "</ul>"
        )
        parts.append(
            "<div class='two'><div><h3>Inputs</h3>"
            + _table(s.inputs)
            + "</div>"
            + "<div><h3>Derived parameters</h3>"
            + _table(s.derived)
            + "</div></div>"
        )
        for caption, headers, rows in s.tables:
            parts.append(f"<h3>{html.escape(caption)}</h3>" + _table(rows, headers))
        parts.append("<h3>Figures</h3><p class='src'>Click a figure to open it full size.</p><div class='figs'>")
        for fig, caption in s.figures:
            parts.append(f"<figure>{_img(fig, embed, base)}<figcaption>{html.escape(caption)}</figcaption></figure>")
        parts.append(
            "</div><h3>Reproduce from the command line</h3><pre>" + html.escape("\n".join(s.commands)) + "</pre>"
        )
        if s.files:
            links = ", ".join(
                f"<a href='{html.escape(str(Path(f).resolve().relative_to(base.resolve())))}'>{html.escape(Path(f).name)}</a>"
                for f in s.files
                if Path(f).resolve().is_relative_to(base.resolve())
            )
            parts.append(f"<p class='src'>data files: {links}</p>")
        parts.append("</section>")
    parts.append("</main></body></html>")
    with atomic_open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(parts))
    return path
