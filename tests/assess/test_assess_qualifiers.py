"""The M53 verdict line says what the number is: UR M53 on a machine outside the rule's
scope (the shipped air motor) is an analogy, and a quasi-static journal torque accepted in
place of UR M53 2.2's forced-vibration calculation is not UR M53-conform."""

from __future__ import annotations

from fe_crank.assess.criteria.judge import evaluate_criteria
from fe_crank.assess.criteria.qualifiers import ANALOGY, QUASI_STATIC, criterion_qualifiers
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.io.criteria import build_criteria
from fe_crank.io.loadcase import load_loadcase
from fe_crank.report.locations import criterion_location
from fe_crank.rules.m53.basis import m53_basis
from fe_crank.rules.m53.calculation import M53Fillet


def _fillet(q: float) -> M53Fillet:
    return M53Fillet("pin", "empirical", 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, q)


def test_air_motor_m53_verdict_line_says_analogy(root):
    lc = load_loadcase(root / "loadcases" / "v4_90_pneumatic_operating.toml")
    assert not lc.engine.internal_combustion
    basis = m53_basis(lc.engine, lc.material, None)
    q = criterion_qualifiers(basis, lc.criteria, torsion=False)
    assert ANALOGY in q["m53_acceptability"]
    crit = build_criteria({"min_m53_acceptability": 1.15, "min_static_safety": 1.5}, "c.toml")
    (m,) = evaluate_criteria(
        build_criteria({"min_m53_acceptability": 1.15}, "c.toml"),
        (ThrowAssessment("A", (), m53=(_fillet(1.9),)),),
        qualifiers=q,
    )
    assert criterion_location(m) == f"throw A, pin fillet (empirical); {q['m53_acceptability']}"
    assert "not an internal-combustion engine" in criterion_location(m)
    assert crit.limit("static_safety") is not None and "static_safety" not in q


def test_ic_engine_without_quasi_static_flag_has_no_qualifier(root):
    lc = load_loadcase(root / "loadcases" / "single_cylinder.toml")
    basis = m53_basis(lc.engine, lc.material, None)
    assert criterion_qualifiers(basis, lc.criteria, torsion=False) == {}


def test_quasi_static_torque_flag_on_the_m53_line(root):
    lc = load_loadcase(root / "loadcases" / "inline4_rated.toml")
    assert lc.criteria.m53_quasi_static_torque
    basis = m53_basis(lc.engine, lc.material, None)
    assert criterion_qualifiers(basis, lc.criteria, torsion=False) == {"m53_acceptability": QUASI_STATIC}
    assert criterion_qualifiers(basis, lc.criteria, torsion=True) == {}
