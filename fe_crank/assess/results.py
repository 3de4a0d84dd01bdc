"""``to_json(assessment) -> dict``: the versioned results document.

The schema is ``fe_crank/data/results.schema.json`` (JSON Schema draft 2020-12),
documented in docs/results.md.  Stresses in Pa, forces in N, unbalance in kg m, angles
in degrees (``*_deg``), coordinates in m; safety factors and margins are pure numbers.
Infinite values (no load at all) are written as null.
"""

from __future__ import annotations

import importlib.resources
import json
import math
from pathlib import Path

from fe_crank.assess.case import SCHEMA_VERSION, Assessment


def _num(x):
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def _extreme(e):
    if e is None:
        return None
    return {"value": _num(e.value), "group": e.group, "node": e.node, "point": [float(c) for c in e.point],
            "angle_deg": None if e.angle is None else math.degrees(e.angle)}


def _group(g):
    return {
        "group": g.group, "n_nodes": g.n_nodes,
        "max_von_mises": _extreme(g.max_von_mises),
        "max_von_mises_overspeed": _extreme(g.max_von_mises_overspeed),
        "static_safety": _num(g.static_safety), "overspeed_safety": _num(g.overspeed_safety),
        "fatigue_safety": _extreme(g.fatigue_safety), "gough_pollard_safety": _extreme(g.gough_pollard_safety),
        "amplitude_at_critical": _num(g.amplitude_at_critical), "mean_at_critical": _num(g.mean_at_critical),
    }


def _m53(f):
    return {"fillet": f.fillet, "scf_source": f.scf_source, "scf_bending": f.scf_bending,
            "scf_shear": f.scf_shear, "scf_torsion": f.scf_torsion, "bending": f.bending, "torsion": f.torsion,
            "equivalent": f.equivalent, "fatigue_strength": f.fatigue_strength,
            "acceptability": _num(f.acceptability), "out_of_range": list(f.out_of_range)}


def _cw(c):
    return {"name": c.name, "built_unbalance": c.built_unbalance, "required_unbalance": _num(c.required_unbalance),
            "unbalance_error": _num(c.unbalance_error), "bolt_load": _num(c.bolt_load),
            "bolt_utilisation": _num(c.bolt_utilisation)}


def to_json(assessment: Assessment) -> dict:
    """The assessment as a JSON-ready dict following results.schema.json."""
    a = assessment
    m = a.material
    return {
        "schema": "fe-crank/results",
        "schema_version": SCHEMA_VERSION,
        "case": a.case,
        "source_file": a.source_file,
        "passed": a.passed,
        "speed_rpm": a.speed * 30.0 / math.pi,
        "overspeed_rpm": None if a.overspeed is None else a.overspeed * 30.0 / math.pi,
        "material": {
            "name": m.name, "source": m.source,
            "yield_strength": _num(m.yield_strength), "tensile_strength": _num(m.tensile_strength),
            "fatigue_limit_bending": _num(m.fatigue_limit_bending),
            "fatigue_limit_torsion": _num(m.fatigue_limit_torsion), "fatigue_factor": m.fatigue_factor,
        },
        "criteria": [
            {"name": c.name, "quantity": c.quantity, "sense": c.sense, "value": _num(c.value),
             "limit": c.limit, "margin": _num(c.margin), "passed": c.passed, "unit": c.unit,
             "location": c.location, "description": c.description}
            for c in a.criteria
        ],
        "throws": [
            {"name": t.name, "n_angles": t.n_angles, "groups": [_group(g) for g in t.groups],
             "m53": [_m53(f) for f in t.m53],
             "m53_nominal": None if t.m53_nominal is None else {
                 "bending": t.m53_nominal.bending, "shear": t.m53_nominal.shear,
                 "torsion_pin": t.m53_nominal.torsion_pin, "torsion_journal": t.m53_nominal.torsion_journal},
             "counterweights": [_cw(c) for c in t.counterweights]}
            for t in a.throws
        ],
        "notes": list(a.notes),
    }


def schema_path() -> Path:
    return Path(str(importlib.resources.files("fe_crank") / "data" / "results.schema.json"))


def load_schema() -> dict:
    return json.loads(schema_path().read_text())
