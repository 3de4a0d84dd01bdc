"""Case reports: ``results.json``, a self-contained ``report.html`` (pictures embedded;
the PNGs also beside it), ``.vtu`` fields.

``write_case_report(folder, result, outputs, notes, *, options, trace)``
writes into a folder that the pipeline later renames into place (see
``fe_crank.pipeline.case``).  The report only formats: every number it shows was computed
by a stage (``fe_crank.outputs.CaseOutputs``).  Pictures: matplotlib for curves
(``fe_crank.report.plots``), pyvista offscreen for the stress fields
(``fe_crank.report.render``, imported lazily).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from fe_crank.files import write_atomic
from fe_crank.notes import Note
from fe_crank.outputs import CaseOutputs
from fe_crank.records import CaseResult
from fe_crank.report.html import Page, criteria_table, esc, header_html, table, timings_table
from fe_crank.report.inputs import cad_features_html, criteria_rows, engine_rows, section_rows
from fe_crank.report.locations import location_text
from fe_crank.results import CriterionResult


def write_case_report(
    folder: str | Path,
    result: CaseResult,
    out: CaseOutputs,
    notes: tuple[Note, ...],
    *,
    options=None,
    trace: str = "",
) -> None:
    """Write ``results.json``, pictures, fields and ``report.html`` into ``folder``."""
    folder = Path(folder)
    page = Page(f"fe-crank: {result.name}")
    if result.criteria:
        page.section("Verdict: safety factors and criteria").append(criteria_table(result, notes))
    lc = out.loadcase
    if lc is not None:
        inputs = page.section("Inputs and assumptions")
        if lc.description:
            inputs.append(f"<p>{esc(lc.description)}</p>")
        inputs.append(table(["quantity", "value"], engine_rows(lc)))
        if lc.material is not None:
            from fe_crank.assess.factors import material_rows

            rows = section_rows(lc.material) + material_rows(lc.material)
            inputs.append("<h3>material</h3>" + table(["key", "value"], rows))
        if lc.criteria is not None:
            inputs.append("<h3>acceptance criteria</h3>" + table(["key", "value"], criteria_rows(lc.criteria)))
        inputs.append("<h3>FE model and bearings</h3>" + table(["key", "value"], section_rows(lc.fe)))
        if out.geometry is not None and out.geometry.cad is not None:
            inputs.append(cad_features_html(out.geometry.cad))
    from fe_crank.report import sections  # the stage sections import every stage: loaded when a report is written

    for heading, builder in sections.BUILDERS:
        parts = builder(folder, out, options)
        if parts:
            page.section(heading).extend(parts)
    if trace:
        page.section("Traceback (internal error)").append(f"<pre>{esc(trace)}</pre>")
        write_atomic(folder / "error.txt", trace)
    page.section("Stage timings").append(timings_table(result))
    if out.assessment is not None and result.criteria:
        write_atomic(folder / "results.json", results_json(out, result.criteria, result=result, notes=notes))
    write_atomic(folder / "report.html", page.html(header_html(result, notes), folder=folder))


def results_json(
    out: CaseOutputs, criteria: tuple[CriterionResult, ...], *, result: CaseResult, notes: tuple[Note, ...] = ()
) -> str:
    """``results.json``: the assessment's document (``fe_crank.assess.to_json``, schema
    ``fe_crank/data/results.schema.json``) with the verdict's criteria (every stage's,
    ``fe_crank.pipeline.verdict``), the FE fields, the provenance and the ``warnings`` (the
    notes shown beside the verdict).  Written only for cases whose assessment ran; the
    pipeline's own record (status, message, timings) is ``case.json``."""
    from fe_crank.assess.results import criterion_json, to_json

    assert out.assessment is not None
    by_model = [  # each criterion's value in each model, its location in words
        {
            "criterion": v.criterion,
            "model": v.model,
            "value": _num(v.value),
            "location": location_text(v.where),
            "governs": v.governs,
        }
        for v in out.assessment.by_model
    ]
    doc = {
        **to_json(out.assessment),
        **({"criteria_by_model": by_model} if by_model else {}),
        **fe_results(out, result),
    }
    doc["criteria"] = [criterion_json(c) for c in criteria]
    doc["passed"] = bool(all(c.passed for c in criteria))
    if result.provenance is not None:
        doc["provenance"] = result.provenance.to_dict()
    doc["warnings"] = [n.to_dict() for n in notes]
    return json.dumps(doc, indent=2, allow_nan=False, default=_plain)


def _plain(o):
    """numpy scalars in provenance statistics -> Python numbers."""
    if hasattr(o, "item"):
        return o.item()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def _num(x: float) -> float | None:
    return float(x) if math.isfinite(x) else None


def fe_results(out: CaseOutputs, result: CaseResult | None = None) -> dict:
    """FE fields of results.json: ``support_model`` (text) and, when the study ran,
    ``mesh_convergence`` (throw key -> ``ConvergenceStudy.to_dict()``); with the whole
    shaft its ``whole_shaft`` object (``result``: the stage timings, of its fields)."""
    res: dict = {}
    units = out.unit_solutions
    if units:
        res["support_model"] = next(iter(units.values())).support_model
    if out.convergence:
        res["mesh_convergence"] = {str(k): v.to_dict() for k, v in out.convergence.items()}
    if out.whole_shaft is not None:
        from fe_crank.report.shaft import shaft_results

        assert out.assessment is not None and out.assessment.shaft is not None
        seconds = {t.stage: t.seconds for t in result.timings} if result is not None else {}
        res["whole_shaft"] = shaft_results(
            out.whole_shaft, out.assessment.shaft, seconds.get("shaft_fields") if out.shaft_fields else None
        )
    return res
