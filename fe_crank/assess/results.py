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
from typing import Any

from fe_crank.assess.case import SCHEMA_VERSION, Assessment
from fe_crank.assess.counterweight import CounterweightCheck, balance_rate
from fe_crank.assess.cw_joint import JointCheck
from fe_crank.assess.factors import factors
from fe_crank.assess.group.assessment import Extreme, GroupResult
from fe_crank.io.material import Material
from fe_crank.results import CriterionResult
from fe_crank.rules.m53.calculation import M53Fillet


def _num(x: float | None) -> float | None:
    if x is None:
        return None
    x = float(x)
    return x if math.isfinite(x) else None


def _extreme(e: Extreme | None) -> dict[str, Any] | None:
    if e is None:
        return None
    return {
        "value": _num(e.value),
        "group": e.group,
        "node": e.node,
        "point": [float(c) for c in e.point],
        "angle_deg": None if e.angle is None else math.degrees(e.angle),
    }


def group_json(g: GroupResult) -> dict[str, Any]:
    """One ``GroupResult`` as results.json writes it (``$defs/group`` of the schema)."""
    return _group(g)


def _group(g: GroupResult) -> dict[str, Any]:
    return {
        "group": g.group,
        "n_nodes": g.n_nodes,
        "max_von_mises": _extreme(g.max_von_mises),
        "max_von_mises_overspeed": _extreme(g.max_von_mises_overspeed),
        "static_safety": _num(g.static_safety),
        "overspeed_safety": _num(g.overspeed_safety),
        "fatigue_safety": _extreme(g.fatigue_safety),
        "gough_pollard_safety": _extreme(g.gough_pollard_safety),
        "additional_bending": g.additional_bending,
        "amplitude_at_critical": _num(g.amplitude_at_critical),
        "mean_at_critical": _num(g.mean_at_critical),
        "fatigue_factors": None
        if g.fatigue_factors is None
        else {
            "surface": g.fatigue_factors.surface,
            "size": g.fatigue_factors.size,
            "reliability": g.fatigue_factors.reliability,
            "treatment": g.fatigue_factors.treatment,
            "notch_support": g.fatigue_factors.notch_support,
            "product": g.fatigue_factors.product,
            "diameter": _num(g.fatigue_factors.diameter),
            "surface_basis": g.fatigue_factors.surface_basis,
        },
    }


def _material(m: Material) -> dict[str, Any]:
    """Material table: library values and the fatigue factors common to every section
    (``fatigue_factor`` = surface x reliability x treatment x notch support, x size when
    the size factor is given; otherwise the size factor is per section, in each group)."""
    ff = factors(m, None)
    common = ff.surface * ff.reliability * ff.treatment * ff.notch_support
    if m.size_factor is not None:
        common *= m.size_factor
    return {
        "name": m.name,
        "source": m.source,
        "yield_strength": _num(m.yield_strength),
        "tensile_strength": _num(m.tensile_strength),
        "fatigue_limit_bending": _num(m.fatigue_limit_bending),
        "fatigue_limit_torsion": _num(m.fatigue_limit_torsion),
        "fatigue_factor": common,
        "surface_finish": None if m.surface_factor is not None else m.surface_finish,
        "surface_factor": ff.surface,
        "size_factor": _num(m.size_factor),
        "reliability": m.reliability,
        "reliability_factor": ff.reliability,
        "treatment_factor": ff.treatment,
        "notch_support_factor": ff.notch_support,
    }


def _m53(f: M53Fillet) -> dict[str, Any]:
    return {
        "fillet": f.fillet,
        "scf_source": f.scf_source,
        "scf_bending": f.scf_bending,
        "scf_shear": f.scf_shear,
        "scf_torsion": f.scf_torsion,
        "bending": f.bending,
        "torsion": f.torsion,
        "equivalent": f.equivalent,
        "fatigue_strength": f.fatigue_strength,
        "acceptability": _num(f.acceptability),
        "out_of_range": list(f.out_of_range),
    }


def _cw(c: CounterweightCheck) -> dict[str, Any]:
    return {
        "name": c.name,
        "built_unbalance": c.built_unbalance,
        "required_unbalance": _num(c.required_unbalance),
        "unbalance_error": _num(c.unbalance_error),
        "bolt_load": _num(c.bolt_load),
        "bolt_utilisation": _num(c.bolt_utilisation),
    }


def _joint(j: JointCheck) -> dict[str, Any]:
    """One bolted counterweight's VDI 2230 results, per bolt (``cw_joint.JointCheck``)."""
    ld = j.loads
    return {
        "name": j.name,
        "preload_max": j.preload_max,
        "preload_min": j.preload_min,
        "embedding_loss": j.embedding_loss,
        "load_factor": j.load_factor,
        "tightening_torque": j.tightening_torque,
        "axial_load_max": ld.axial_max,
        "axial_load_min": ld.axial_min,
        "axial_load_overspeed": ld.axial_overspeed,
        "transverse_load_max": ld.transverse_max,
        "assembly_utilisation": j.assembly_utilisation,
        "working_safety": _num(j.working_safety),
        "fatigue_amplitude": j.fatigue_amplitude,
        "endurance_limit": j.endurance_limit,
        "fatigue_safety": _num(j.fatigue_safety),
        "residual_clamp": j.residual_clamp,
        "separation_safety": _num(j.separation_safety),
        "slip_safety": _num(j.slip_safety),
        "moment_max": ld.moment_max,
        "moment_min": ld.moment_min,
        "moment_overspeed": ld.moment_overspeed,
        "web_moment": ld.web_moment,
        "web_model": ld.web_model,
        "eccentric_load_factor": _num(j.eccentric_load_factor),
        "moment_load_factor": j.moment_load_factor,
        "opening_limit": j.opening_limit,
        "bending_amplitude": j.bending_amplitude,
        "s_sym": None if ld.eccentric is None else ld.eccentric.s_sym,
        "a": None if ld.eccentric is None else ld.eccentric.a,
        "interface_width": None if ld.eccentric is None else ld.eccentric.width,
        "interface_length": None if ld.eccentric is None else ld.eccentric.length,
        "thread_friction": j.friction[0],
        "head_friction": j.friction[1],
        "interface_friction": j.friction[2],
    }


def criterion_json(c: CriterionResult) -> dict[str, Any]:
    """One criterion of results.json (an infinite value, an unloaded part's safety, is null)."""
    return {
        "name": c.name,
        "quantity": c.quantity,
        "sense": c.sense,
        "value": _num(c.value),
        "limit": c.limit,
        "margin": _num(c.margin),
        "passed": c.passed,
        "unit": c.unit,
        "location": c.location,
        "description": c.description,
        "speed_rpm": c.speed_rpm,
        "per_speed": [{"speed_rpm": p.speed_rpm, "value": _num(p.value), "location": p.location} for p in c.per_speed],
    }


def to_json(assessment: Assessment) -> dict[str, Any]:
    """The assessment as a JSON-ready dict following results.schema.json (the criteria's
    locations in words and ``criteria_by_model`` are the report's, ``report.results_json``)."""
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
        "material": _material(m),
        "criteria": [criterion_json(c) for c in a.criteria],
        "throws": [
            {
                "name": t.name,
                "n_angles": t.n_angles,
                "groups": [_group(g) for g in t.groups],
                "m53": [_m53(f) for f in t.m53],
                "m53_nominal": None
                if t.m53_nominal is None
                else {
                    "bending": t.m53_nominal.bending,
                    "shear": t.m53_nominal.shear,
                    "torsion_pin": t.m53_nominal.torsion_pin,
                    "torsion_journal": t.m53_nominal.torsion_journal,
                    "ke": t.m53_nominal.ke,
                },
                "counterweights": [_cw(c) for c in t.counterweights],
                "balance_rate": _num(balance_rate(t.counterweights)),
                **({"joints": [_joint(j) for j in t.joints]} if t.joints else {}),
            }
            for t in a.throws
        ],
        "balance_rate": _num(balance_rate(c for t in a.throws for c in t.counterweights)),
        "notes": [n.display for n in a.notes],
    }


def schema_path() -> Path:
    return Path(str(importlib.resources.files("fe_crank") / "data" / "results.schema.json"))


def load_schema() -> dict[str, Any]:
    schema: dict[str, Any] = json.loads(schema_path().read_text())
    return schema
