"""A small, dependency-free HTML page builder for case reports.

The page is self-contained: inline CSS, no scripts, no network, and its pictures
embedded as ``data:image/png;base64`` URIs (``Page.html(folder=...)``), so
``report.html`` alone is the whole document (mailed, archived, printed).  The PNG
files stay beside it for other uses.
"""

from __future__ import annotations

import base64
import html
import re
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from fe_crank.files import write_atomic
from fe_crank.notes import blocks_sign_off, verdict_remarks
from fe_crank.records import CaseResult, Provenance
from fe_crank.results import STATUS_ERROR, STATUS_FAIL, STATUS_PASS

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
.banner{border:3px solid #c62828;background:#fdecea;color:#b71c1c;font-weight:700;padding:.6em 1em;margin:.8em 0;
font-size:1.15em}
ul.warn{margin:.3em 0 .6em 1.2em;padding:0} ul.warn li{color:#8a4b00} td ul.warn{margin:0;font-size:.9em}
@media print{body{max-width:none;margin:0;font-size:10pt} figure{display:block;page-break-inside:avoid}
figure img{max-width:100%} h2{page-break-after:avoid} table{page-break-inside:auto} tr{page-break-inside:avoid}
.badge{border:1px solid #000;-webkit-print-color-adjust:exact;print-color-adjust:exact}}
"""


def esc(x: object) -> str:
    return html.escape(str(x), quote=True)


def badge(status: str) -> str:
    text = {STATUS_PASS: "PASS", STATUS_FAIL: "FAIL", STATUS_ERROR: "ERROR"}.get(status, status.upper())
    return f'<span class="badge {esc(status)}">{text}</span>'


def table(header: Sequence[str], rows: Sequence[Sequence[object]], *, num_cols: set[int] | None = None) -> str:
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

    def html(self, head_html: str = "", folder: str | Path | None = None) -> str:
        body = [f"<h1>{esc(self.title)}</h1>", head_html]
        for heading, parts in self.sections:
            if not parts:
                continue
            body.append(f"<h2>{esc(heading)}</h2>")
            body.extend(parts)
        return (
            (
                '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
                f"<title>{esc(self.title)}</title><style>{CSS}</style></head><body>\n"
                + "\n".join(body)
                + "\n</body></html>\n"
            )
            if folder is None
            else embed_images(self.html(head_html), folder)
        )


_IMG = re.compile(r'<img src="([^"]+)"')


def embed_images(text: str, folder: str | Path) -> str:
    """Replace every ``<img src="file.png">`` by the picture's bytes as a base64 data
    URI (a picture that is missing keeps only its alt text and caption)."""

    def repl(m: re.Match) -> str:
        src = html.unescape(m.group(1))
        if src.startswith("data:"):
            return m.group(0)
        p = Path(folder) / src
        if not p.is_file():
            return "<img"
        data = base64.b64encode(p.read_bytes()).decode("ascii")
        return f'<img src="data:image/png;base64,{data}"'

    return _IMG.sub(repl, text)


def header_html(result: CaseResult, notes=()) -> str:
    """Verdict badge with the verdict-line remarks (``notes.verdict_remarks``: not a
    sign-off, which criteria a quality warning concerns), the "not a sign-off" banner when
    the mesh is below the sign-off rule or the support is a foundation, the warnings that
    concern the whole case, and where the result came from."""
    w = result.worst
    worst = f"worst criterion <b>{esc(w.name)}</b>, margin {100 * w.margin:+.1f} %" if w else ""
    msg = f"<pre>{esc(result.message)}</pre>" if result.message else ""
    prov = result.provenance
    banner = ""
    if prov is not None and prov.mesh.preset and not prov.mesh.sign_off:
        banner = (
            f'<div class="banner">NOT A SIGN-OFF (test mesh): mesh preset "{esc(prov.mesh.preset)}" is below '
            f"the sign-off rule ({esc(prov.mesh.sign_off_rule)}). Run with "
            "--mesh-size coarse or finer before trusting this verdict.</div>"
        )
    for n in notes:  # the other models that are not a sign-off (a foundation support)
        if blocks_sign_off(n) and n.source != "mesh":
            banner += f'<div class="banner">{esc(n.text)}</div>'
    case_wide = [n for n in notes if not n.criteria]
    remarks = verdict_remarks(notes)
    line = f"{worst}" + (f" &nbsp; <b>{esc(remarks)}</b>" if remarks else "")
    return (
        f"{banner}<p>{badge(result.status)} &nbsp; {line}</p>{notes_list(case_wide)}"
        f'<p class="note">load case file <code>{esc(result.source)}</code></p>{msg}' + provenance_table(prov)
    )


def notes_list(notes) -> str:
    """A list of notes, warnings first, each marked with its level."""
    if not notes:
        return ""
    items = sorted(notes, key=lambda n: n.level != "warning")
    return '<ul class="warn">' + "".join(f"<li><b>{esc(n.level)}</b>: {esc(n.display)}</li>" for n in items) + "</ul>"


def provenance_table(prov: Provenance | None) -> str:
    """What produced the result: version, date, input hash, mesh, solver, support."""
    if prov is None:
        return ""
    mesh = prov.mesh
    rows = [
        ["fe-crank version", prov.version],
        ["run started (UTC)", prov.started],
        [
            "input SHA-256 (load case and the files it was read from)",
            Raw(f"<code>{esc(prov.input.sha256 or prov.input.error or '-')}</code>"),
        ],
        [
            "mesh preset",
            f"{mesh.preset} ({'meets' if mesh.sign_off else 'below'} the sign-off rule: {mesh.sign_off_rule})",
        ],
    ]
    for key, st in mesh.throws.items():
        rows.append(
            [
                f"mesh {key}",
                f"{st.elements} quadratic tetrahedra, {st.nodes} nodes, {st.p2_dofs} DOF, "
                f"min quality {st.min_quality:.3g}",
            ]
        )
    if prov.solver is not None:
        rows.append(
            [
                "linear solver",
                f"{', '.join(prov.solver.used)} (requested {prov.solver.requested}; "
                f"fast direct solver {'available' if prov.solver.fast_available else 'NOT available'})",
            ]
        )
    for s in prov.support:
        k = s.bearing_stiffness
        rows.append(
            [
                f"support, throw {s.throw}",
                s.model or (f"{s.support} journal support" + (f", k = {k:.3g} N/m^3" if k is not None else "")),
            ]
        )
    rows.append(["Python, platform", f"{prov.python}, {prov.platform}"])
    return "<details open><summary>Provenance</summary>" + table(["item", "value"], rows) + "</details>"


def display(value: float, unit: str) -> tuple[str, str]:
    """A criterion's value in the unit a designer reads (stresses in MPa)."""
    if unit == "Pa":
        return f"{value / 1e6:.4g}", "MPa"
    if unit == "m":  # an oil film's thickness
        return f"{value * 1e6:.4g}", "um"
    return f"{value:.4g}", unit


def criteria_table(result: CaseResult, notes=()) -> str:
    """The verdict table; each criterion's row lists the warnings and assumptions that
    concern it (``fe_crank.notes.Note.concerns``) except the case-wide ones, which the
    header shows once."""
    rows = []
    for c in sorted(result.criteria, key=lambda c: c.margin):
        (v, unit), (lim, _) = display(c.value, c.unit), display(c.limit, c.unit)
        mine = [n for n in notes if n.criteria and n.concerns(c.name)]
        rows.append(
            [
                c.name,
                c.description,
                c.location,
                v,
                lim,
                unit,
                f"{100 * c.margin:+.1f} %",
                Raw(badge(STATUS_PASS if c.passed else STATUS_FAIL)),
                Raw(notes_list(mine)),
            ]
        )
    return table(
        ["criterion", "what", "where", "value", "limit", "unit", "margin", "verdict", "warnings and assumptions"],
        rows,
        num_cols={3, 4, 6},
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
