"""The convergence study's factors in the assessment (``fe_crank.assess.refinement``, passed
once into ``assess.criteria.judge.judge_criteria``), the verdict aggregating (``pipeline.verdict.decide``):
the FE stress criteria at the hot spots the study follows are taken at the finest level's
peak (or its Richardson extrapolation), never below the assessed mesh's; the sign-off fails
as not converged when the assessed mesh and the finest level differ by more than 5 %.
Plain study data here (the levels' peaks written out); the real study is run in
``test_check_convergence`` and below for the oil bore."""

from __future__ import annotations

import math

import pytest

from fe_crank.assess.case import Assessment
from fe_crank.assess.criteria.judge import judge_criteria
from fe_crank.assess.group.assessment import Extreme, GroupResult
from fe_crank.assess.loads import FIRING
from fe_crank.assess.refinement import StudyFactors, criterion, surface_factor
from fe_crank.assess.speeds import StateResults
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.fe.refinement.convergence import (
    COUNTERWEIGHT_PREFIX,
    OIL_BORE_PREFIX,
    ConvergenceLevel,
    ConvergenceStudy,
    richardson,
)
from fe_crank.io.criteria import build_criteria
from fe_crank.io.material import load_material
from fe_crank.outputs import CaseOutputs
from fe_crank.pipeline.verdict import decide
from fe_crank.report.locations import criterion_location, location_text
from fe_crank.throw_scope import ALL_THROWS


def _study(peaks: dict[str, list[float]], divisions=(4.0, 6.0, 8.0)) -> ConvergenceStudy:
    levels = tuple(
        ConvergenceLevel(
            n, 1000, {}, {k: v[i] for k, v in peaks.items()}, dict.fromkeys(peaks, "crankpin_fillet_1"), 0.0
        )
        for i, n in enumerate(divisions)
    )
    changes = {k: [abs(b - a) / b for a, b in zip(v, v[1:])] for k, v in peaks.items()}
    return ConvergenceStudy(levels, {}, 0.05, changes)


def test_richardson_recovers_an_exact_power_law():
    """s(h) = 100 + 20 h^1.7 at h = 1, 2/3, 1/2 (r/4, r/6, r/8 relative): s* = 100, p = 1.7."""
    h = [1.0, 2 / 3, 0.5]
    s = [100 + 20 * x**1.7 for x in h]
    s_star, p = richardson(h, s)
    assert s_star == pytest.approx(100.0, rel=1e-9) and p == pytest.approx(1.7, rel=1e-6)
    # a rising sequence: s = 100 - 20 h^1.2 -> s* = 100 above the finest 100 - 20 x 0.5^1.2
    s = [100 - 20 * x**1.2 for x in h]
    assert richardson(h, s)[0] == pytest.approx(100.0, rel=1e-9)
    # not monotone, or steps that do not shrink: no extrapolation
    assert richardson(h, [100.0, 110.0, 105.0]) is None
    assert richardson(h, [100.0, 105.0, 112.0]) is None


def _ext(value, group, node, angle=None):
    return Extreme(value, group, node, (0.001 * node, 0.0, 0.002), angle)


def _group(name, node, vm, fat=None):
    return GroupResult(
        group=name,
        n_nodes=3,
        max_von_mises=_ext(vm, name, node, math.radians(30)),
        max_von_mises_overspeed=None,
        static_safety=600e6 / vm,
        overspeed_safety=None,
        fatigue_safety=None if fat is None else _ext(fat, name, node + 1),
        gough_pollard_safety=None,
    )


def _assessment(groups, criteria_toml: dict, studies=None) -> Assessment:
    throws = (ThrowAssessment("1", tuple(groups)),)
    judged = judge_criteria(
        build_criteria(criteria_toml, "c.toml"), throws, factors=StudyFactors(studies) if studies else None
    )
    return Assessment(
        "c", "c.toml", 1.0, None, load_material("C45"), throws, judged.criteria, refinements=judged.refinements
    )


def test_the_verdict_takes_the_finest_level_at_the_studied_hot_spots():
    # shaft fillets: peaks rise 100 -> 104 -> 106 (steps 4, 2: Richardson), the torque set less;
    # counterweight fillets 50 -> 53 -> 56 (steps do not shrink: the finest), oil bore falls (no credit)
    shaft = [100.0, 104.0, 106.0]
    st = _study(
        {
            "peak pin force": shaft,
            "peak torque": [40.0, 40.4, 40.5],
            COUNTERWEIGHT_PREFIX + "peak pin force": [50.0, 53.0, 56.0],
            OIL_BORE_PREFIX + "peak pin force": [80.0, 79.0, 78.0],
        }
    )
    k = richardson([1 / 4, 1 / 6, 1 / 8], shaft)[0] / 100.0
    assert k > 1.06
    groups = [
        _group("journal_fillet_2", 3, 200e6, fat=1.6),  # static 3.0
        _group("oil_bore", 7, 195e6, fat=1.62),  # static 3.077: governs after the fillet's k
        _group("counterweight_fillet_1", 11, 100e6),
        _group("junction_1", 13, 110e6),  # not studied: keeps its 110 MPa
    ]
    limits = {"min_static_safety": 2.0, "min_fatigue_safety": 1.5, "max_counterweight_stress": "150 MPa"}
    plain = _assessment(groups, limits)
    by0 = {c.quantity: c for c in plain.criteria}
    assert location_text(by0["static_safety"].where).startswith("throw 1, journal_fillet_2")
    assert by0["counterweight_stress"].value == 110e6
    a = _assessment(groups, limits, {ALL_THROWS: st})
    v = decide(CaseOutputs(assessment=a, convergence={ALL_THROWS: st}))
    by = {c.quantity: c for c in v.criteria}
    fat = by["fatigue_safety"]  # the fillet's 1.6 / k = 1.505 < the oil bore's 1.62
    assert fat.value == pytest.approx(1.6 / k, rel=1e-12) and fat.location.startswith("throw 1, journal_fillet_2")
    assert "Richardson extrapolation of r/4, r/6, r/8" in fat.location and f"x{k:.3f}" in fat.location
    # static: the fillet's 3.0 / k = 2.83 drops below the oil bore's 3.077 (no credit there: x1)
    stat = by["static_safety"]
    assert stat.value == pytest.approx(3.0 / k, rel=1e-12)
    # counterweight stress: the transition fillet's 100 MPa x 56/50 = 112 MPa now governs the junction's 110
    cw = by["counterweight_stress"]
    assert cw.value == pytest.approx(112e6, rel=1e-12) and cw.location.startswith("throw 1, counterweight_fillet_1")
    assert "finest level r/8" in cw.location
    # the study's criterion: assessed vs finest, 6/56 = 10.7 % on the counterweight fillets > 5 %
    conv = by["mesh_convergence"]
    assert conv.value == pytest.approx(6.0 / 56.0) and not conv.passed and "NOT CONVERGED" in conv.location
    assert v.status == "fail"
    # the factors each criterion was taken at, kept by the assessment (the notes read them)
    assert {r.criterion for r in a.refinements} == {
        "criteria.min_static_safety",
        "criteria.min_fatigue_safety",
        "criteria.max_counterweight_stress",
    }
    # without the study: the assessment's criteria as they are, in words
    assert [c.value for c in decide(CaseOutputs(assessment=plain)).criteria] == [c.value for c in plain.criteria]


def test_oil_bore_without_credit_and_a_study_per_throw_found_by_name():
    st = _study({"peak pin force": [100.0, 101.0, 101.5], OIL_BORE_PREFIX + "peak pin force": [80.0, 79.0, 78.0]})
    groups = [_group("oil_bore", 7, 200e6), _group("crankpin_fillet_1", 3, 150e6)]
    c, _ = _assessment(groups, {"min_static_safety": 2.0}, {"1": st}).criteria
    words = criterion_location(c)
    assert c.value == 3.0 and "x1.000" in words and "oil-bore outlet" in words
    assert "the peak falls with refinement: no credit taken" in words
    same, _ = _assessment(groups, {"min_static_safety": 2.0}, {"2": st}).criteria  # no study for throw 1
    assert same == _assessment(groups, {"min_static_safety": 2.0}).criteria[0]
    conv = criterion({"1": st})
    assert conv.passed and conv.value == pytest.approx(2.0 / 78.0)  # 2.6 % <= 5 %
    ok = criterion({"1": _study({"peak pin force": [100.0, 101.0, 101.5]})})
    assert ok.passed and ok.value == pytest.approx(1.5 / 101.5)
    assert criterion_location(ok) == "throw 1, crankpin_fillet_1, peak pin force, r/4 (assessed) -> r/8 (finest)"


@pytest.mark.heavy
def test_the_oil_bore_outlet_is_refined_and_followed_by_the_study(tmp_path):
    """A real study (two levels of the small test throw with a 4 mm oil bore): the bore's
    divisions grow with the fillets' (6 -> 12 round pi d / 2) and its peak is a load set
    of its own, which the verdict's oil-bore criteria are taken at."""
    from pathlib import Path

    from fe_crank.fe.refinement.convergence import fillet_convergence
    from fe_crank.io.geometry import load_geometry
    from fe_crank.io.material import load_material as mat
    from fe_crank.mesh import MeshOptions

    text = (Path(__file__).resolve().parents[1] / "data" / "geometry_small.toml").read_text()
    text = text.replace('length = "18 mm"\n', 'length = "18 mm"\noil_bore = { diameter = "4 mm", angle = "90 deg" }\n')
    (tmp_path / "g.toml").write_text(text)
    g = load_geometry(tmp_path / "g.toml")
    assert g.oil_bore is not None
    base = MeshOptions(coarse_divisions=1.5, fillet_divisions=1.0, grading=2.0)
    st = fillet_convergence(g, mat("42CrMo4"), base=base, factors=(1.0, 2.0), cache_dir=tmp_path / "cache")
    assert [lv.bore_divisions for lv in st.levels] == [6.0, 12.0]
    bore = [n for n in st.changes if n.startswith(OIL_BORE_PREFIX)]
    assert sorted(bore) == [OIL_BORE_PREFIX + "pin_-y", OIL_BORE_PREFIX + "torque"]
    for n in bore:
        assert [lv.where[n] for lv in st.levels] == ["oil_bore", "oil_bore"]
        assert all(lv.peaks[n] > 0 for lv in st.levels)
    d = st.to_dict()
    assert d["bore_divisions"] == [6.0, 12.0] and set(bore) <= set(d["assessed_changes"])
    k, basis, _, _ = surface_factor({"1": st}, "1", "oil_bore")
    ratios = [st.levels[-1].peaks[n] / st.levels[0].peaks[n] for n in bore]
    assert k == pytest.approx(max(1.0, *ratios), rel=1e-12) and basis.startswith("finest level r/2")


def test_the_study_scales_every_speed_of_the_full_load_curve():
    """Over a sweep the study's factor applies at every speed and the worst speed is found
    again: at 1000 rpm the studied journal fillet (3.0, x1.1 -> 2.727) falls below the
    unstudied junction that governed at 2000 rpm (2.927), so the verdict moves to 1000 rpm;
    each speed's value in ``per_speed`` is scaled alike."""
    st = _study({"peak pin force": [100.0, 105.0, 110.0]})  # equal steps: the finest level, k = 1.1
    low = (ThrowAssessment("1", (_group("journal_fillet_2", 3, 200e6), _group("junction_1", 13, 190e6))),)
    high = (ThrowAssessment("1", (_group("journal_fillet_2", 3, 170e6), _group("junction_1", 13, 205e6))),)
    w_low, w_high = 1000 * math.pi / 30, 2000 * math.pi / 30
    sweep = (StateResults(w_low, FIRING, low), StateResults(w_high, FIRING, high))
    limits = build_criteria({"min_static_safety": 2.0}, "c.toml")
    crit = judge_criteria(limits, high, sweep=sweep).criteria
    assert crit[0].value == pytest.approx(600 / 205) and crit[0].speed_rpm == pytest.approx(2000)
    judged = judge_criteria(limits, high, sweep=sweep, factors=StudyFactors({ALL_THROWS: st}))
    a = Assessment("c", "c.toml", w_high, None, load_material("C45"), high, judged.criteria, sweep=sweep)
    (c, _) = decide(CaseOutputs(assessment=a, convergence={ALL_THROWS: st})).criteria
    assert c.value == pytest.approx(3.0 / 1.1, rel=1e-12) and c.speed_rpm == pytest.approx(1000)
    assert c.location.startswith("throw 1, journal_fillet_2") and "; 1000 rpm; x1.100 by the convergence" in c.location
    assert [p.value for p in c.per_speed] == pytest.approx([3.0 / 1.1, 600 / 205], rel=1e-12)
    assert [p.speed_rpm for p in c.per_speed] == pytest.approx([1000, 2000])
