"""The page both report kinds share: A4 print layout, title block, tables and figures.

One HTML file that reads the same on screen and on paper: the text column is the A4 text
width (170 mm) in both; in print (WeasyPrint) every page carries a running header (project
and plan name) and "page n of N", table rows never split across pages and table headers
repeat on each page. Figures are drawn at the width they are printed, so their lettering
prints at its real size.
"""

from __future__ import annotations

import base64
import html
import io
import math
import re

from liftplan.model.version import __version__
from liftplan.planner.problem.plausibility import problem_warnings

#: A4 text width [mm]: 210 mm less 20 mm margins each side. Figures are drawn to it.
TEXT_WIDTH_MM = 170.0
#: Page margins [mm]: top, right, bottom, left.
MARGINS_MM = (18.0, 20.0, 18.0, 20.0)
#: Figure lettering [pt] at print size.
FONT_PT = 7.5

_CSS = """
@page {
  size: A4;
  margin: %(top)smm %(right)smm %(bottom)smm %(left)smm;
  @top-center { content: %(header)s; font: 7.5pt sans-serif; color: #555; }
  @bottom-left { content: %(footer)s; font: 7.5pt sans-serif; color: #555; }
  @bottom-right { content: "page " counter(page) " of " counter(pages);
                  font: 7.5pt sans-serif; color: #555; }
}
@media screen {
  body { max-width: %(width)smm; margin: 2em auto; padding: 0 1em; }
  footer { margin-top: 2em; border-top: 1px solid #999; font-size: 7.5pt; color: #555; }
}
@media print {
  footer { display: none; }
}
body { font-family: sans-serif; font-size: 9pt; line-height: 1.3; color: #222; }
h1 { font-size: 16pt; margin: 0.2em 0 0.4em; }
h2 { font-size: 12pt; margin: 1.2em 0 0.3em; border-bottom: 1px solid #999;
     break-after: avoid; }
h3 { font-size: 10pt; margin: 1em 0 0.3em; break-after: avoid; }
p { margin: 0.4em 0; }
h2.appendix { break-before: page; }
table { border-collapse: collapse; margin: 0.6em 0 1em; font-size: 7.5pt; }
table.full { width: 100%%; }
table.keep { break-inside: avoid; }
caption { caption-side: top; text-align: left; font-weight: bold; font-size: 8pt;
          padding: 0.2em 0; break-after: avoid; }
thead { display: table-header-group; }
tr { break-inside: avoid; }
th, td { border: 1px solid #bbb; padding: 0.2em 0.35em; text-align: right;
         vertical-align: top; overflow-wrap: break-word; }
th { background: #eee; font-weight: bold; hyphens: auto; }
td:first-child, th:first-child { text-align: left; }
td.text, th.text { text-align: left; }
td.nw, th.nw { white-space: nowrap; }
table.title-block { width: 100%%; font-size: 9pt; margin-top: 0; }
table.title-block td { text-align: left; height: 1.6em; vertical-align: middle; }
table.title-block td.k { width: 17%%; background: #eee; font-weight: bold; }
table.sign-off td:nth-child(3) { width: 30%%; }
.status { font-weight: bold; padding: 0.3em 0.5em; border: 1px solid #999; }
.status.fail { color: #a00; border-color: #a00; }
.warning { padding: 0.3em 0.5em; border: 1px solid #b60; color: #733; }
figure { margin: 0.8em 0; break-inside: avoid; }
figure img { display: block; max-width: 100%%; }
figcaption { font-size: 8pt; color: #333; margin-top: 0.2em; }
ul { margin: 0.3em 0; padding-left: 1.4em; }
li { margin: 0.2em 0; }
"""


def css_string(text):
    """``text`` as a quoted CSS string, safe inside a ``<style>`` element."""
    out = []
    for ch in text:
        out.append(f"\\{ord(ch):x} " if ch in '\\"<>&' or ord(ch) < 32 else ch)
    return '"' + "".join(out) + '"'


def document(title, body, header, footer=""):
    """The whole HTML page.

    Parameters
    ----------
    title : str
        The document's title (browser tab, PDF metadata).
    body : str
        HTML of the body.
    header : str
        Running header printed at the top of every page.
    footer : str
        Printed at the bottom left of every page (document number, revision, the software
        and its version); on screen, once below the body.
    """
    top, right, bottom, left = MARGINS_MM
    shown = f"<footer>{html.escape(footer)}</footer>\n" if footer else ""  # on screen
    css = _CSS % {
        "top": top,
        "right": right,
        "bottom": bottom,
        "left": left,
        "width": TEXT_WIDTH_MM,
        "header": css_string(header),
        "footer": css_string(footer),
    }
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<title>{html.escape(title)}</title>
<style>{css}</style></head>
<body>
{body}
{shown}</body></html>
"""


#: Per-rope columns a table holds before it is split into several (many lifting points).
ROPE_COLUMNS = 8
#: Text cells up to this many characters are not broken across lines.
NOWRAP_CHARS = 10


#: A number that rounded to zero but kept its minus sign ("-0.000", and in a list "1.2, -0.00"),
#: not after "+" (a tolerance "+-0" stays as written).
NEGATIVE_ZERO = re.compile(r"(?<![\w.+])-(0(?:\.0+)?)(?![\w.])")


def cell_text(value):
    """A table cell's text: a rounded negative zero is shown as zero (a reader takes "-0.000"
    for a value below zero)."""
    return NEGATIVE_ZERO.sub(r"\1", str(value))


def count_text(count):
    """A count for a table: the integer up to 10^9, beyond it three digits and the power of ten
    (``7.69 x 10^20``: a 21-digit integer reads as noise)."""
    count = int(count)
    if abs(count) < 10**9:
        return str(count)
    mantissa, exponent = f"{count:.2e}".split("e")
    return f"{mantissa} x 10^{int(exponent)}"


def range_text(low, high):
    """A range for a table, e.g. a boom height range [m]: ``"30 to 60"``, ``"at least 30"``,
    ``"at most 60"`` or ``"not limited"`` (not ``"-inf to inf"``)."""
    low_given, high_given = math.isfinite(low), math.isfinite(high)
    if low_given and high_given:
        return f"{low:g} to {high:g}"
    if low_given or high_given:
        return f"at least {low:g}" if low_given else f"at most {high:g}"
    return "not limited"


def table(headers, rows, caption, *, full=True, keep=None, text_columns=(), ropes=None):
    """An HTML table (:func:`one_table`), split into several when it has more than
    :data:`ROPE_COLUMNS` per-rope columns: ``ropes = (start, count)`` names them, and each part
    keeps the columns before and after them (so 26 or 64 ropes stay within the page width).
    """
    rows = [[cell_text(v) for v in row] for row in rows]
    if ropes is None or ropes[1] <= ROPE_COLUMNS:
        return one_table(headers, rows, caption, full=full, keep=keep, text_columns=text_columns)
    start, count = ropes
    stop = start + count
    if len(rows) == 1 and stop == len(headers):  # one row of values: one table, wrapped
        return _wrapped_row(headers, rows[0], caption, start, full=full, keep=keep, text_columns=text_columns)
    parts = []
    for first in range(0, count, ROPE_COLUMNS):
        last = min(first + ROPE_COLUMNS, count)
        keep_columns = [*range(start), *range(start + first, start + last), *range(stop, len(headers))]
        where = {old: new for new, old in enumerate(keep_columns)}
        parts.append(
            one_table(
                [headers[k] for k in keep_columns],
                [[row[k] for k in keep_columns] for row in rows],
                f"{caption} ({first + 1} to {last} of {count})",
                full=full,
                keep=keep,
                text_columns=tuple(where[k] for k in text_columns if k in where),
            )
        )
    return "".join(parts)


def _wrapped_row(headers, row, caption, start, *, full, keep, text_columns):
    """One row of many per-rope values as one table of :data:`ROPE_COLUMNS` ropes a line,
    each line under its own header row (the label columns repeated)."""
    keep = True if keep is None else keep
    classes = " ".join(c for c, on in (("full", full), ("keep", keep)) if on)
    label = [html.escape(str(v)) for v in row[:start]]
    lines = []
    for first in range(start, len(headers), ROPE_COLUMNS):
        names = headers[first : first + ROPE_COLUMNS]
        pad = ROPE_COLUMNS - len(names)
        blank = "<th></th>" * pad
        lines.append(
            "<tr>"
            + "".join(f'<th class="text">{html.escape(str(h))}</th>' for h in headers[:start])
            + "".join(f"<th>{html.escape(str(h))}</th>" for h in names)
            + blank
            + "</tr>"
        )
        cells = "".join(f"<td>{html.escape(str(v))}</td>" for v in row[first : first + ROPE_COLUMNS])
        text = ' class="text"'
        lines.append(
            "<tr>"
            + "".join(f"<td{text if k in text_columns else ''}>{v}</td>" for k, v in enumerate(label))
            + cells
            + "<td></td>" * pad
            + "</tr>"
        )
    return (
        f'<table class="{classes}"><caption>{html.escape(caption)}</caption>'
        f"<tbody>{''.join(lines)}</tbody></table>"
    )


def one_table(headers, rows, caption, *, full=True, keep=None, text_columns=()):
    """An HTML table with a caption, a repeated header and unsplittable rows.

    Parameters
    ----------
    headers : list of str
    rows : list of sequences
    caption : str
    full : bool
        Span the text width (columns share it); False: as narrow as the content.
    keep : bool, optional
        Keep the whole table on one page; default: when it has at most 16 rows.
    text_columns : tuple of int
        Columns of words (left-aligned); numbers are right-aligned.
    """
    keep = len(rows) <= 16 if keep is None else keep
    classes = " ".join(c for c, on in (("full", full), ("keep", keep)) if on)

    def cell(tag, k, value):
        value = str(value)
        # a short name ("crane 10", "not given") on one line: many-rope tables stay one line a row
        align = (
            (' class="text nw"' if len(value) <= NOWRAP_CHARS else ' class="text"')
            if k in text_columns
            else ""
        )
        return f"<{tag}{align}>{html.escape(value)}</{tag}>"

    head = "".join(cell("th", k, h) for k, h in enumerate(headers))
    body = "".join("<tr>" + "".join(cell("td", k, c) for k, c in enumerate(row)) + "</tr>" for row in rows)
    return (
        f'<table class="{classes}"><caption>{html.escape(caption)}</caption>'
        f"<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
    )


def figure(fig, alt, caption=""):
    """A matplotlib Figure embedded as a base64 PNG, printed at the width it was drawn
    (at most the text width), so its lettering prints at the size it was set in.
    """
    width_mm = min(fig.get_figwidth() * 25.4, TEXT_WIDTH_MM)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=160)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    note = f"<figcaption>{html.escape(caption)}</figcaption>" if caption else ""
    return (
        f'<figure><img alt="{html.escape(alt)}" style="width: {width_mm:g}mm" '
        f'src="data:image/png;base64,{data}">{note}</figure>'
    )


def figure_size(height_mm, width_mm=TEXT_WIDTH_MM):
    """(width, height) in inches for a Figure printed ``width_mm`` wide."""
    return width_mm / 25.4, height_mm / 25.4


def title_block(info, plan_name, kind, today=None):
    """Page 1's title block: the plan's name, then project, client, document, revision,
    date, and who prepared, checked and approved it, each with room to sign.

    Parameters
    ----------
    info : ReportInfo
    plan_name : str
    kind : str
        What the document is, e.g. "Lift plan: four cranes, held preload".
    today : datetime.date, optional
    """
    fields = dict(info.rows(today))
    esc = html.escape

    def row(*pairs):
        return "<tr>" + "".join(f'<td class="k">{esc(k)}</td><td>{esc(v)}</td>' for k, v in pairs) + "</tr>"

    project = (
        '<table class="title-block keep"><tbody>'
        + row(("Project", fields["Project"]), ("Document no.", fields["Document no."]))
        + row(("Client", fields["Client"]), ("Revision", fields["Revision"]))
        + row(("Subject", plan_name), ("Date", fields["Date"]))
        + "</tbody></table>"
    )
    sign = (
        '<table class="title-block sign-off keep"><tbody>'
        '<tr><td class="k"></td><td class="k">name</td><td class="k">signature</td>'
        '<td class="k">date</td></tr>'
        + "".join(
            f'<tr><td class="k">{esc(role)}</td><td>{esc(fields[role])}</td><td></td><td></td></tr>'
            for role in ("Prepared by", "Checked by", "Approved by")
        )
        + "</tbody></table>"
    )
    return f"<h1>{esc(plan_name or 'Lift plan')}</h1><p>{esc(kind)}</p>{project}{sign}"


def running_header(info, plan_name):
    """The line printed at the top of every page: project and plan name."""
    return " \u2014 ".join(t for t in (info.project, plan_name) if t) or "Lift plan"


def running_footer(info):
    """The line printed at the bottom left of every page: document number and revision, and
    the software that computed the plan, with its version (the signed report carries it)."""
    parts = [info.document] if info.document else []
    if info.revision:
        parts.append(f"rev. {info.revision}")
    return ", ".join([*parts, f"liftplan {__version__}"])


def status(checks):
    """One line: every check passed, or how many failed and which."""
    failed = [c for c in checks if not c.ok]
    if not failed:
        return f'<p class="status">All {len(checks)} checks pass (listed under "Checks to hand over").</p>'
    names = "; ".join(f"{c.title}: {c.subject}" for c in failed)
    return (
        f'<p class="status fail">{len(failed)} of {len(checks)} checks FAIL: '
        f"{html.escape(names)}. Do not lift on this plan as it stands.</p>"
    )


def warnings(problem):
    """The planning file's warnings (what the console prints as ``liftplan: warning:``), one
    paragraph each under page 1's status, or ``""``: what the signer must know of the inputs
    (water not drained, a bed that cannot carry the body, a likely unit slip)."""
    return "".join(
        f'<p class="warning"><b>Warning:</b> {html.escape(line)}</p>' for line in problem_warnings(problem)
    )
