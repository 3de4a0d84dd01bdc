"""Case reports: ``results.json``, a self-contained ``report.html`` (pictures embedded;
the PNGs also beside it), ``.vtu`` fields.

``write_case_report(folder, result, stage_out, *, options, trace)`` writes into a
folder that the pipeline later renames into place (see ``fe_crank.check.case``).
Pictures: matplotlib for curves (``fe_crank.report.plots``), pyvista offscreen for
the stress fields (``fe_crank.report.render``, imported lazily).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from fe_crank.fe import convergence
from fe_crank.files import write_atomic
from fe_crank.report.html import Page, criteria_table, esc, header_html, table, timings_table
from fe_crank.results import CaseResult


def _engine_rows(lc) -> list[list[object]]:
    e = lc.engine
    rows = [["engine", e.name], ["strokes", e.strokes], ["cylinders", len(e.cylinders)], ["throws", len(e.throws)]]
    if e.source:
        rows.append(["engine source", e.source])
    c0 = e.cylinders[0]
    t0 = e.throw(c0.throw)
    rows += [
        ["bore", f"{1e3 * c0.bore:.1f} mm"],
        ["crank radius", f"{1e3 * t0.crank_radius:.1f} mm (stroke {2e3 * t0.crank_radius:.1f} mm)"],
        ["rod length", f"{1e3 * c0.rod.length:.1f} mm"],
        ["rod mass", f"{c0.rod.mass:.3f} kg"],
        ["piston group mass", f"{c0.piston_mass:.3f} kg"],
        ["speed", f"{lc.operating.speed * 30 / math.pi:.0f} rpm"],
    ]
    if lc.operating.overspeed:
        rows.append(["overspeed", f"{lc.operating.overspeed * 30 / math.pi:.0f} rpm"])
    if e.gas is not None:
        rows.append(
            [
                "peak cylinder pressure",
                f"{e.gas.pressure.max() / 1e6:.2f} MPa (abs.)" + (f", source: {e.gas.source}" if e.gas.source else ""),
            ]
        )
    return rows


def _section_rows(obj) -> list[list[object]]:
    """Fields of a frozen section object (material, criteria, FE options) as rows."""
    from dataclasses import fields, is_dataclass

    if obj is None:
        return []
    if hasattr(obj, "limits"):  # acceptance criteria: one row per limit, with its meaning
        try:
            from fe_crank.io.criteria import QUANTITIES
        except ModuleNotFoundError:  # pragma: no cover - the criteria parser is part of the package
            QUANTITIES = {}
        rows = []
        for lim in obj.limits:
            q = QUANTITIES.get(lim.quantity)
            unit = "MPa" if q is not None and q.unit_kind == "pressure" else ""
            val = lim.value / 1e6 if unit else lim.value
            rows.append(
                [
                    lim.key.split(".")[-1],
                    f"{'>=' if lim.sense == 'min' else '<='} {val:.4g} {unit}".strip()
                    + (f"  ({q.meaning})" if q is not None else ""),
                ]
            )
        return rows
    if is_dataclass(obj):
        return [
            [f.name, _fmt_property(f.name, getattr(obj, f.name))] for f in fields(obj) if not f.name.startswith("_")
        ]
    return [["value", obj]]


_MPA = ("yield_strength", "tensile_strength", "fatigue_limit_bending", "fatigue_limit_torsion")


def _fmt_property(name: str, v) -> object:
    """SI values of the input tables in the units a designer reads."""
    if not isinstance(v, float):
        return v
    if name in _MPA:
        return f"{v / 1e6:.4g} MPa"
    if name == "youngs_modulus":
        return f"{v / 1e9:.4g} GPa"
    if name == "density":
        return f"{v:.5g} kg/m^3"
    if name == "bearing_stiffness":
        return f"{v:.4g} N/m^3"
    if name.endswith("_angle"):
        return f"{math.degrees(v):.4g} deg"
    return f"{v:.4g}"


def write_case_report(
    folder: str | Path, result: CaseResult, stage_out: dict, *, options=None, trace: str = ""
) -> None:
    """Write ``results.json``, pictures, fields and ``report.html`` into ``folder``."""
    folder = Path(folder)
    page = Page(f"fe-crank: {result.name}")
    notes = stage_out.get("notes") or []
    if result.criteria:
        page.section("Verdict: safety factors and criteria").append(criteria_table(result, notes))
    lc = stage_out.get("loadcase")
    if lc is not None:
        inputs = page.section("Inputs and assumptions")
        if lc.description:
            inputs.append(f"<p>{esc(lc.description)}</p>")
        inputs.append(table(["quantity", "value"], _engine_rows(lc)))
        for title, obj in (
            ("material", lc.material),
            ("acceptance criteria", lc.criteria),
            ("FE model and bearings", lc.fe),
        ):
            rows = _section_rows(obj)
            if title == "material":
                from fe_crank.assess.factors import material_rows

                rows += material_rows(obj)
            if rows:
                inputs.append(f"<h3>{esc(title)}</h3>" + table(["key", "value"], rows))
    from fe_crank.report import sections  # the stage sections import every stage: loaded when a report is written

    for heading, builder in sections.BUILDERS:
        parts = builder(folder, stage_out, options)
        if parts:
            page.section(heading).extend(parts)
    if trace:
        page.section("Traceback (internal error)").append(f"<pre>{esc(trace)}</pre>")
        write_atomic(folder / "error.txt", trace)
    page.section("Stage timings").append(timings_table(result))
    if stage_out.get("assessment") is not None:
        studies = stage_out.get("mesh_convergence")
        extra_criteria = (convergence.criterion(studies),) if studies else ()
        write_atomic(
            folder / "results.json",
            results_json(
                stage_out["assessment"],
                fe_results(stage_out),
                extra_criteria,
                provenance=result.provenance,
                notes=notes,
            ),
        )
    write_atomic(folder / "report.html", page.html(header_html(result, notes), folder=folder))


def results_json(
    assessment, extra: dict | None = None, criteria=(), *, provenance: dict | None = None, notes=()
) -> str:
    """``results.json``: the assessment's document (``fe_crank.assess.to_json``, schema
    ``fe_crank/data/results.schema.json``) plus ``extra`` top-level fields, ``criteria``
    (``CriterionResult``) of other stages, ``provenance`` (``fe_crank.provenance``) and
    ``warnings`` (the notes shown beside the verdict, ``fe_crank.notes.Note``).  Written
    only for cases whose assessment ran; the pipeline's own record (status, message,
    timings) is ``case.json``."""
    from fe_crank.assess import to_json

    doc = {**to_json(assessment), **(extra or {})}
    if criteria:  # criteria of other stages join the verdict (as in case.json)
        from dataclasses import asdict

        doc["criteria"] = [*doc["criteria"], *(asdict(c) for c in criteria)]
        doc["passed"] = bool(doc["passed"] and all(c.passed for c in criteria))
    if provenance:
        doc["provenance"] = provenance
    doc["warnings"] = [n.to_dict() for n in notes]
    return json.dumps(doc, indent=2, allow_nan=False, default=_plain)


def _plain(o):
    """numpy scalars in provenance statistics -> Python numbers."""
    if hasattr(o, "item"):
        return o.item()
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def fe_results(stage_out: dict) -> dict:
    """FE fields of results.json: ``support_model`` (text) and, when the study ran,
    ``mesh_convergence`` (throw key -> ``ConvergenceStudy.to_dict()``)."""
    out = {}
    units = stage_out.get("units") or {}
    if units:
        out["support_model"] = next(iter(units.values())).support_model
    if stage_out.get("mesh_convergence"):
        out["mesh_convergence"] = {k: v.to_dict() for k, v in stage_out["mesh_convergence"].items()}
    return out
