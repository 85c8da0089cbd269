"""A self-contained HTML document from report sections (plots embedded as data URIs).

The page needs no network and no files beside it: styles inline, PNGs in
base64.  Same sections, same bytes.
"""

from __future__ import annotations

import base64
import html
from dataclasses import dataclass
from typing import Sequence, Union

from camcam.workers import Pending, resolve
from camcam.verdict import Verdict

__all__ = ["Figure", "Drawing", "KeyValues", "DataTable", "Paragraph", "Code", "VerdictBlock", "Section", "render_html"]


@dataclass(frozen=True)
class Figure:
    """A PNG plot with a caption."""

    png: bytes | Pending  # a plot still being drawn is collected when the page is rendered
    caption: str


@dataclass(frozen=True)
class Drawing:
    """An inline SVG picture (text made by camcam, e.g. :mod:`camcam.report.setup_picture`) with a caption."""

    svg: str
    caption: str


@dataclass(frozen=True)
class KeyValues:
    """A two-column table of labelled values (already formatted, units included)."""

    rows: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class DataTable:
    """A table with a header row; cells already formatted."""

    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    caption: str = ""


@dataclass(frozen=True)
class Paragraph:
    text: str


@dataclass(frozen=True)
class Code:
    """Preformatted text (a piece of the NC program) with a caption."""

    text: str
    caption: str = ""


@dataclass(frozen=True)
class VerdictBlock:
    """The PASS/FAIL banner and the table of checks (:class:`camcam.verdict.Verdict`)."""

    verdict: Verdict


Block = Union[Figure, Drawing, KeyValues, DataTable, Paragraph, Code, VerdictBlock]


@dataclass(frozen=True)
class Section:
    """A titled part of the page; ``sheet``: printed on page 1 with the other sheet sections, alone there."""

    title: str
    blocks: tuple[Block, ...]
    sheet: bool = False


_STYLE = """
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:2em auto;max-width:1100px;color:#1b1b1b;padding:0 1em}
h1{font-size:1.6em;margin-bottom:.2em}h2{font-size:1.25em;border-bottom:2px solid #2a6fb0;padding-bottom:.2em;margin-top:1.8em}
.sub{color:#555;margin-top:0}table{border-collapse:collapse;margin:.6em 0;font-size:.92em}
td,th{border:1px solid #ccc;padding:.25em .6em;text-align:right}th{background:#eef3f8}
td:first-child,th:first-child{text-align:left}table.kv td{text-align:left}table.kv td:first-child{font-weight:600;background:#f7f7f7}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #ddd}figure.drawing svg{max-width:100%;height:auto;border:1px solid #ddd}figcaption{color:#444;font-size:.9em}
pre{background:#f6f8fa;border:1px solid #ddd;padding:.6em;font-size:.85em;overflow-x:auto}
.ok{color:#176b2c;font-weight:600}.bad{color:#a11;font-weight:600}
.verdict{font-size:1.5em;font-weight:700;padding:.4em .8em;border-radius:4px;color:#fff;display:inline-block}
.verdict.pass{background:#176b2c}.verdict.warn{background:#b36b00}.verdict.fail{background:#b3191f}
@page{size:A4;margin:12mm}
@media print{body{max-width:none;margin:0;padding:0;font-size:10pt}h2{page-break-after:avoid;break-after:avoid}
figure,tr{page-break-inside:avoid;break-inside:avoid}table{font-size:8pt}td,th{padding:.1em .3em}
pre{white-space:pre-wrap;word-break:break-all;font-size:7.5pt}figure img{max-height:120mm;max-width:100%}
.sheet{page-break-after:always;break-after:page}.sheet h1{font-size:13pt;margin:0}.sheet .sub{margin:0 0 .3em}
.sheet h2{font-size:11pt;margin:.5em 0 .2em}.sheet table{font-size:7.5pt;margin:.2em 0}.sheet p{margin:.2em 0}
.sheet .verdict{font-size:12pt;padding:.15em .5em}.sheet figure.drawing{margin:.3em 0}
.sheet figure.drawing svg{height:42mm;width:auto}}
"""


def _block(b: Block) -> str:
    e = html.escape
    if isinstance(b, VerdictBlock):
        v = b.verdict
        head = f'<p class="verdict {v.status.lower()}">{e(v.status)}</p>'
        if v.accepted and not v.passed:
            head += "<p>Out of tolerance, accepted by the spec (accept_out_of_tolerance = true).</p>"
        head += "".join(f'<p class="bad">warning: {e(c.describe())}</p>' for c in v.warnings)
        rows = "".join(f'<tr><td>{e(c.name)}</td><td>{c.value:.5g} {e(c.unit)}</td><td>{c.limit:g} {e(c.unit)}</td>'
                       f'<td class="{"ok" if c.ok else "bad"}">{"within" if c.ok else ("FAIL" if c.fails else "WARN")}'
                       f'</td><td>{e(c.where)}</td><td>{e("" if c.ok else c.advice)}</td></tr>' for c in v.checks)
        return (head + "<table><thead><tr><th>check</th><th>measured</th><th>limit</th><th>result</th><th>where</th>"
                f"<th>way out</th></tr></thead><tbody>{rows}</tbody></table>")
    if isinstance(b, Figure):
        data = base64.b64encode(resolve(b.png)).decode("ascii")
        return f'<figure><img alt="{e(b.caption)}" src="data:image/png;base64,{data}"><figcaption>{e(b.caption)}</figcaption></figure>'
    if isinstance(b, Drawing):
        return f'<figure class="drawing">{b.svg}<figcaption>{e(b.caption)}</figcaption></figure>'
    if isinstance(b, KeyValues):
        rows = "".join(f"<tr><td>{e(k)}</td><td>{e(v)}</td></tr>" for k, v in b.rows)
        return f'<table class="kv">{rows}</table>'
    if isinstance(b, DataTable):
        head = "".join(f"<th>{e(h)}</th>" for h in b.header)
        body = "".join("<tr>" + "".join(f"<td>{e(c)}</td>" for c in r) + "</tr>" for r in b.rows)
        cap = f"<caption>{e(b.caption)}</caption>" if b.caption else ""
        return f"<table>{cap}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
    if isinstance(b, Paragraph):
        return f"<p>{e(b.text)}</p>"
    if isinstance(b, Code):
        cap = f"<figcaption>{e(b.caption)}</figcaption>" if b.caption else ""
        return f"<figure><pre>{e(b.text)}</pre>{cap}</figure>"
    raise TypeError(f"not a report block: {type(b).__name__}")


def render_html(title: str, subtitle: str, sections: Sequence[Section]) -> str:
    """The whole page as text.

    Examples
    --------
    >>> page = render_html("cam", "demo", [Section("Job", (KeyValues((("tolerance", "0.01 mm"),)),))])
    >>> "<td>tolerance</td><td>0.01 mm</td>" in page
    True
    """
    e = html.escape
    sheet = any(s.sheet for s in sections)
    parts = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{e(title)}</title><style>{_STYLE}</style></head><body>",
        *(['<div class="sheet">'] if sheet else []),
        f"<h1>{e(title)}</h1><p class=\"sub\">{e(subtitle)}</p>",
    ]
    for i, s in enumerate(sections):
        parts.append(f"<section><h2>{e(s.title)}</h2>")
        parts.extend(_block(b) for b in s.blocks)
        parts.append("</section>")
        if sheet and s.sheet and not (i + 1 < len(sections) and sections[i + 1].sheet):
            parts.append("</div>")  # the sheet ends: the print breaks the page here
            sheet = False
    parts.append("</body></html>\n")
    return "\n".join(parts)
