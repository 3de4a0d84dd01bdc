"""The "Inputs and assumptions" tables of a case report: the engine, the material, the
criteria and the FE model, each value in the unit a designer reads (no Python reprs);
for a CAD geometry, the features recognised in the file (``cad_features_html``)."""

from __future__ import annotations

import math
from dataclasses import fields, is_dataclass

import numpy as np

from fe_crank.cad.features import CadFeatures
from fe_crank.cad.record import feature_lines
from fe_crank.io.criteria import QUANTITIES, Criteria
from fe_crank.io.loadcase import LoadCase
from fe_crank.report.html import esc

_MPA = ("yield_strength", "tensile_strength", "fatigue_limit_bending", "fatigue_limit_torsion")


def engine_rows(lc: LoadCase) -> list[list[object]]:
    e = lc.engine
    rows: list[list[object]] = [
        ["engine", e.name],
        ["strokes", e.strokes],
        ["cylinders", len(e.cylinders)],
        ["throws", len(e.throws)],
    ]
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


def criteria_rows(criteria: Criteria) -> list[list[object]]:
    """One row per limit, with its meaning."""
    rows: list[list[object]] = []
    for lim in criteria.limits:
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


def section_rows(obj: object) -> list[list[object]]:
    """Fields of a frozen section object (material, FE options) as rows."""
    if obj is None or not is_dataclass(obj):
        return []
    return [[f.name, plain(f.name, getattr(obj, f.name))] for f in fields(obj) if not f.name.startswith("_")]


def plain(name: str, v: object) -> str:
    """A value as a designer reads it: SI values of the input tables in their usual units,
    lists as comma-separated words, "-" for a value not given."""
    if v is None:
        return "-"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, (tuple, list)):
        return ", ".join(plain(name, x) for x in v) if v else "-"
    if isinstance(v, dict):
        return "; ".join(f"{k}: {plain(name, x)}" for k, x in v.items()) if v else "-"
    if isinstance(v, (float, np.floating)):
        v = float(v)
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
    return str(v)


def cad_features_html(features: CadFeatures) -> str:
    """The CAD file and every feature recognised in it, one line each with the file's face
    numbers and dimensions (``fe_crank.cad.record.feature_lines``)."""
    lines = "\n".join(feature_lines(features))
    return f"<h3>geometry from CAD: recognised features</h3><pre>{esc(lines)}</pre>"
