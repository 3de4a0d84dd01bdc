"""Warnings beside the verdict (fe_crank.notes, fe_crank.report.quality) and the
provenance input hash (fe_crank.provenance), on real files and plain stage data."""

from __future__ import annotations

import hashlib
from pathlib import Path

from fe_crank.notes import Note, from_stage
from fe_crank.provenance import input_files, input_hash
from fe_crank.report.html import criteria_table, header_html
from fe_crank.report.quality import case_notes
from fe_crank.results import CaseResult, CriterionResult

ROOT = Path(__file__).resolve().parents[1]


def test_a_note_concerns_its_criteria_by_full_or_short_key():
    n = Note("M53 averaging check failed", criteria=("criteria.min_fatigue_safety",))
    assert n.concerns("criteria.min_fatigue_safety") and n.concerns("min_fatigue_safety")
    assert not n.concerns("criteria.min_static_safety")
    assert Note("whole case").concerns("anything")


def test_stage_outputs_contribute_their_notes_and_warnings():
    class Stage:  # any stage result with these attributes
        warnings = ("engine has no gas pressure",)
        notes = ("overspeed: centrifugal alone", Note("targeted", "assumption", ("min_static_safety",)))

    got = from_stage("dynamics", Stage())
    assert [(n.level, n.text) for n in got] == [
        ("warning", "engine has no gas pressure"),
        ("assumption", "overspeed: centrifugal alone"),
        ("assumption", "targeted"),
    ]


def test_test_mesh_averaging_and_missing_fast_solver_are_flagged():
    prov = {
        "mesh": {"preset": "test", "sign_off": False, "sign_off_rule": "coarse or finer"},
        "solver": {"used": ["superlu"], "requested": "auto", "fast_available": False},
    }
    # 6.1 % > the 5 % of UR M53's FE appendix; 4.9 % is within it
    so = {"averaging": {"1": {"journal_fillet_1": 0.061, "crankpin_fillet_1": 0.049}}}
    texts = [n.text for n in case_notes(so, prov)]
    assert any(t.startswith("NOT A SIGN-OFF: mesh preset 'test'") for t in texts)
    assert any("journal_fillet_1" in t and "+6.1 % > 5 %" in t for t in texts)
    assert not any("crankpin_fillet_1" in t for t in texts)
    assert any("fast direct solver" in t and "superlu" in t for t in texts)
    prov["mesh"].update(preset="coarse", sign_off=True)
    prov["solver"]["fast_available"] = True
    assert not any("SIGN-OFF" in n.text or "fast" in n.text for n in case_notes({"averaging": {}}, prov))


def test_the_banner_and_the_notes_sit_beside_the_verdict():
    c = CriterionResult("criteria.min_fatigue_safety", True, 2.0, 1.5, 2.0 / 1.5 - 1)
    s = CriterionResult("criteria.min_static_safety", True, 4.0, 2.0, 1.0)
    r = CaseResult("c", "c.toml", "pass", criteria=(c, s), provenance={"mesh": {"preset": "test", "sign_off": False}})
    notes = [Note("averaging 6.1 % > 5 %", criteria=("criteria.min_fatigue_safety",)), Note("case-wide")]
    head, tab = header_html(r, notes), criteria_table(r, notes)
    assert "NOT A SIGN-OFF (test mesh)" in head and "case-wide" in head and "averaging" not in head
    row_fat = next(row for row in tab.split("<tr>") if "min_fatigue_safety" in row)
    row_sta = next(row for row in tab.split("<tr>") if "min_static_safety" in row)
    assert "averaging 6.1 %" in row_fat and "averaging" not in row_sta


def test_input_hash_follows_the_referenced_files():
    case = ROOT / "loadcases" / "single_cylinder.toml"
    files = input_files(case)
    names = sorted(p.name for p in files)
    # the load case names its engine and geometry files
    assert names == sorted(["single_cylinder.toml"] * 3)
    h = hashlib.sha256()
    base = case.parent
    import os

    for p in files:  # independent: "<relative path>\0<bytes>", in sorted order
        h.update(Path(os.path.relpath(p, base)).as_posix().encode() + b"\0" + p.read_bytes())
    assert input_hash(case)["sha256"] == h.hexdigest()
