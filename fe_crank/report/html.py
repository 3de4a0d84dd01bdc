"""A small, dependency-free HTML page builder for case reports.

The page is self-contained (inline CSS, no scripts, no network) and refers to its
pictures by relative file name, so the folder can be zipped, archived by CI or
opened from disk.
"""

from __future__ import annotations

import html
from dataclasses import dataclass, field
from pathlib import Path

from fe_crank.files import write_atomic
from fe_crank.results import STATUS_ERROR, STATUS_FAIL, STATUS_PASS, CaseResult

CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:2em auto;max-width:72em;
color:#222;line-height:1.45;padding:0 1em}
h1{font-size:1.6em;margin-bottom:.2em} h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
table{border-collapse:collapse;margin:.6em 0} th,td{border:1px solid #ccc;padding:.25em .6em;text-align:left}
th{background:#f3f3f3} td.num{text-align:right;font-variant-numeric:tabular-nums}
.badge{display:inline-block;padding:.15em .7em;border-radius:.3em;color:#fff;font-weight:600}
.pass{background:#2e7d32}.fail{background:#c62828}.error{background:#6a1b9a}
figure{display:inline-block;margin:.5em 1em .5em 0;vertical-align:top} figure img{max-width:34em;border:1px solid #ddd}
figcaption{font-size:.9em;color:#555;max-width:34em} pre{background:#f7f7f7;padding:.6em;overflow-x:auto}
.note{color:#555;font-size:.92em}
"""


def esc(x: object) -> str:
    return html.escape(str(x), quote=True)


def badge(status: str) -> str:
    text = {STATUS_PASS: "PASS", STATUS_FAIL: "FAIL", STATUS_ERROR: "ERROR"}.get(status, status.upper())
    return f'<span class="badge {esc(status)}">{text}</span>'


def table(header: list[str], rows: list[list[object]], *, num_cols: set[int] | None = None) -> str:
    """An HTML table; cells are escaped, columns in ``num_cols`` right-aligned."""
    num_cols = num_cols or set()
    out = ["<table><tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>"]
    for row in rows:
        cells = []
        for j, v in enumerate(row):
            cls = ' class="num"' if j in num_cols else ""
            cells.append(f"<td{cls}>{v if isinstance(v, Raw) else esc(v)}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


class Raw(str):
    """Already-escaped HTML to put in a table cell as it is."""


@dataclass
class Page:
    """Sections of a report page, in order; ``figure`` adds a picture by file name."""

    title: str
    sections: list[tuple[str, list[str]]] = field(default_factory=list)

    def section(self, heading: str) -> list[str]:
        parts: list[str] = []
        self.sections.append((heading, parts))
        return parts

    @staticmethod
    def figure(file: str, caption: str) -> str:
        return f'<figure><img src="{esc(file)}" alt="{esc(caption)}"><figcaption>{esc(caption)}</figcaption></figure>'

    def html(self, head_html: str = "") -> str:
        body = [f"<h1>{esc(self.title)}</h1>", head_html]
        for heading, parts in self.sections:
            if not parts:
                continue
            body.append(f"<h2>{esc(heading)}</h2>")
            body.extend(parts)
        return (
            "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{esc(self.title)}</title><style>{CSS}</style></head><body>\n"
            + "\n".join(body)
            + "\n</body></html>\n"
        )


def header_html(result: CaseResult) -> str:
    w = result.worst
    worst = f"worst criterion <b>{esc(w.name)}</b>, margin {100 * w.margin:+.1f} %" if w else ""
    msg = f'<pre>{esc(result.message)}</pre>' if result.message else ""
    return (
        f"<p>{badge(result.status)} &nbsp; {worst}</p>"
        f'<p class="note">load case file <code>{esc(result.source)}</code></p>{msg}'
    )


def display(value: float, unit: str) -> tuple[str, str]:
    """A criterion's value in the unit a designer reads (stresses in MPa)."""
    if unit == "Pa":
        return f"{value / 1e6:.4g}", "MPa"
    return f"{value:.4g}", unit


def criteria_table(result: CaseResult) -> str:
    rows = []
    for c in sorted(result.criteria, key=lambda c: c.margin):
        (v, unit), (lim, _) = display(c.value, c.unit), display(c.limit, c.unit)
        rows.append([
            c.name, c.description, c.location, v, lim, unit,
            f"{100 * c.margin:+.1f} %", Raw(badge(STATUS_PASS if c.passed else STATUS_FAIL)),
        ])
    return table(
        ["criterion", "what", "where", "value", "limit", "unit", "margin", "verdict"], rows, num_cols={3, 4, 6}
    )


def timings_table(result: CaseResult) -> str:
    rows = [[t.stage, f"{t.seconds:.2f}"] for t in result.timings]
    return table(["stage", "time [s]"], rows, num_cols={1})


def write_error_report(folder: Path, result: CaseResult, trace: str) -> None:
    """The smallest honest report: verdict ERROR, the message, the stage timings.

    Used when even the full report could not be written."""
    folder = Path(folder)
    page = Page(f"fe-crank: {result.name}")
    if trace:
        page.section("Traceback (internal error)").append(f"<pre>{esc(trace)}</pre>")
        write_atomic(folder / "error.txt", trace)
    page.section("Stage timings").append(timings_table(result))
    write_atomic(folder / "report.html", page.html(header_html(result)))
