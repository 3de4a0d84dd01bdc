"""Models that are not a sign-off do not look like one, and a quality warning says on the
verdict line which verdicts it concerns (``fe_crank.pipeline.notes``, ``fe_crank.notes.verdict_remarks``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fe_crank.assess.case import Assessment
from fe_crank.assess.states import HotSpot, ModelStates
from fe_crank.cli.check import format_plain
from fe_crank.io.loadcase import load_loadcase
from fe_crank.io.material import load_material
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.notes import WARNING, verdict_remarks
from fe_crank.outputs import CaseOutputs
from fe_crank.pipeline.notes import case_notes
from fe_crank.records import CaseResult, InputHash, MeshRecord, Provenance
from fe_crank.report.html import header_html
from fe_crank.report.locations import location_text
from fe_crank.results import CriterionResult, Location

ROOT = Path(__file__).resolve().parents[2]
SMALL = ROOT / "tests" / "data" / "small_pass.toml"


def _crit(key: str, quantity: str, where: Location) -> CriterionResult:
    return CriterionResult(
        f"criteria.{key}",
        True,
        2.0,
        1.5,
        2.0 / 1.5 - 1,
        location=location_text(where),
        quantity=quantity,
        sense="min",
        where=where,
    )


CRITERIA = (
    _crit("min_static_safety", "static_safety", Location("group", "1", "crankpin_fillet_2", 7, (1e-3, 2e-3, 3e-3), 20)),
    _crit("min_fatigue_safety", "fatigue_safety", Location("group", "1", "journal_fillet_1", 9, (1e-3, 2e-3, 3e-3))),
)


def _outputs(path: Path, averaging: dict[str, float], criteria=CRITERIA) -> CaseOutputs:
    lc = load_loadcase(path)
    hot = HotSpot("1", "journal_fillet_1", 0, (0.0, 0.0, 0.0), 0.0, "fatigue")
    states = ModelStates(("1",), ("1",), hot, 0, 0.0, np.zeros(3), averaging)
    a = Assessment("c", "c.toml", 1.0, None, load_material("42CrMo4"), (), criteria, (), (states,))
    return CaseOutputs(loadcase=lc, assessment=a)


def _result(notes, preset="test", sign_off=False) -> CaseResult:
    prov = Provenance("0", "", "3", "linux", InputHash(None, ()), MeshRecord(preset, sign_off, "coarse or finer"))
    warnings = tuple(n for n in notes if n.level == WARNING)
    return CaseResult("c", "c.toml", "pass", criteria=CRITERIA, provenance=prov, warnings=warnings)


def test_test_mesh_pass_beside_a_failed_averaging_check_names_the_verdict_it_concerns():
    """The averaging check failed at journal_fillet_1 (+49 %): it concerns the fatigue
    criterion located there, not the static one at crankpin_fillet_2; the verdict line
    (report header, summary table) says so after 'not a sign-off'."""
    notes = case_notes(
        _outputs(SMALL, {"journal_fillet_1": 0.49}), preset="test", sign_off=False, rule="r", solver=None
    )
    (avg,) = [n for n in notes if "averaging" in n.text]
    assert avg.criteria == ("criteria.min_fatigue_safety",)
    assert "the governing location of min_fatigue_safety" in avg.text
    remarks = verdict_remarks(notes)
    assert remarks.startswith(
        "not a sign-off: test mesh (preset 'test'); averaging check failed at journal_fillet_1 (+49 %): "
        "concerns min_fatigue_safety;"  # then: inertia loads only (the small case has no gas pressure)
    )
    r = _result(notes)
    assert remarks in header_html(r, notes).replace("&#x27;", "'")
    assert remarks in format_plain([r])


def test_an_averaging_check_at_no_criterion_s_location_concerns_every_fe_stress_criterion():
    notes = case_notes(
        _outputs(SMALL, {"crankpin_fillet_1": -0.07}), preset="coarse", sign_off=True, rule="r", solver=None
    )
    (avg,) = [n for n in notes if "averaging" in n.text]
    assert avg.criteria == ("criteria.min_static_safety", "criteria.min_fatigue_safety")
    assert verdict_remarks(notes).startswith(
        "averaging check failed at crankpin_fillet_1 (-7 %): concerns min_static_safety, min_fatigue_safety;"
    )


def test_a_foundation_support_is_not_a_sign_off(tmp_path):
    text = SMALL.read_text().replace(
        "[material]", '[fe]\nsupport = "foundation"\nbearing_stiffness = "2e12 N/m^3"\n\n[material]'
    )
    p = tmp_path / "foundation.toml"
    p.write_text(text)
    (tmp_path / "geometry_small.toml").write_text((SMALL.parent / "geometry_small.toml").read_text())
    notes = case_notes(_outputs(p, {}), preset="coarse", sign_off=True, rule="r", solver=None)
    (f,) = [n for n in notes if "foundation" in n.text]
    assert f.level == WARNING and f.criteria == () and f.text.startswith("NOT A SIGN-OFF")
    assert verdict_remarks(notes).startswith("not a sign-off: foundation support;")
    head = header_html(_result(notes, "coarse", True), notes)
    assert 'class="banner">NOT A SIGN-OFF: support = ' in head.replace("&#x27;", "'")
    # the determinate supports of the same case: no such note
    plain = case_notes(_outputs(SMALL, {}), preset="coarse", sign_off=True, rule="r", solver=None)
    assert not any("foundation" in n.text for n in plain) and "sign-off" not in verdict_remarks(plain)


def test_no_gas_pressure_warns_on_the_fatigue_and_m53_verdicts():
    """tests/data/small_pass.toml has no pressure table: its dynamics warn case-wide, and the
    fatigue and M53 criteria carry the warning themselves (and the verdict line names them)."""
    path = SMALL
    crit = CRITERIA + (
        _crit("min_m53_acceptability", "m53_acceptability", Location("m53", "1", "pin", detail="empirical")),
    )
    out = _outputs(path, {}, crit)
    lc = out.loadcase
    import dataclasses

    out = dataclasses.replace(out, cycles=engine_cycles(lc.engine, lc.operating))
    notes = case_notes(out, preset="coarse", sign_off=True, rule="r", solver=None)
    assert any(n.text == "engine has no gas pressure: inertia forces only" for n in notes)
    (n,) = [n for n in notes if n.text.startswith("inertia loads only")]
    assert n.criteria == ("criteria.min_fatigue_safety", "criteria.min_m53_acceptability")
    assert verdict_remarks(notes) == (
        "inertia loads only (no gas pressure): concerns min_fatigue_safety, min_m53_acceptability"
    )
