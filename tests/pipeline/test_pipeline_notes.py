"""Warnings beside the verdict (``fe_crank.notes``, ``fe_crank.pipeline.notes``) and the
provenance's input hash (``fe_crank.pipeline.provenance``), on real files and plain stage data."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

import numpy as np

from fe_crank.assess.case import Assessment
from fe_crank.assess.states import HotSpot, ModelStates
from fe_crank.io.loadcase import load_loadcase
from fe_crank.io.material import load_material
from fe_crank.notes import ASSUMPTION, Note, from_strings, grouped
from fe_crank.outputs import CaseOutputs
from fe_crank.pipeline.notes import case_notes
from fe_crank.pipeline.provenance import input_hash
from fe_crank.records import CaseResult, InputHash, MeshRecord, Provenance, SolverRecord
from fe_crank.report.html import criteria_table, header_html
from fe_crank.results import CriterionResult
from fe_crank.throw_scope import ALL_THROWS

ROOT = Path(__file__).resolve().parents[2]


def test_a_note_concerns_its_criteria_by_full_or_short_key():
    n = Note("M53 averaging check failed", criteria=("criteria.min_fatigue_safety",))
    assert n.concerns("criteria.min_fatigue_safety") and n.concerns("min_fatigue_safety")
    assert not n.concerns("criteria.min_static_safety")
    assert Note("whole case").concerns("anything")


def test_stage_sentences_become_notes_of_their_level():
    got = from_strings(
        ("overspeed: centrifugal alone", Note("targeted", ASSUMPTION, ("min_static_safety",))), ASSUMPTION, "assessment"
    )
    assert [(n.level, n.text, n.source) for n in got] == [
        ("assumption", "overspeed: centrifugal alone", "assessment"),
        ("assumption", "targeted", ""),
    ]


def test_notes_that_differ_only_in_their_throws_are_shown_once_naming_them():
    notes = [Note("counterweight off by +30 %", throws=(t,)) for t in ("1", "2", "3", "4")]
    notes += [Note("counterweight off by +30 %", throws=("2",)), Note("case-wide"), Note("case-wide")]
    got = grouped(notes)
    assert [n.display for n in got] == ["throws 1, 2, 3, 4: counterweight off by +30 %", "case-wide"]
    assert Note("x", throws=("1",)).display == "throw 1: x"
    assert Note("x", throws=(ALL_THROWS,)).display == "all throws: x"
    assert got[0].to_dict()["throws"] == ["1", "2", "3", "4"]


def _outputs(averaging: dict[str, float]) -> CaseOutputs:
    lc = load_loadcase(ROOT / "tests" / "data" / "small_pass.toml")
    hot = HotSpot("1", "journal_fillet_1", 0, (0.0, 0.0, 0.0), 0.0, "fatigue")
    states = ModelStates(("1",), ("1",), hot, 0, 0.0, np.zeros(3), averaging)
    a = Assessment("c", "c.toml", 1.0, None, load_material("42CrMo4"), (), (), (), (states,))
    return CaseOutputs(loadcase=lc, assessment=a)


def test_test_mesh_averaging_and_missing_fast_solver_are_flagged():
    # 6.1 % > the 5 % of UR M53's FE appendix; 4.9 % is within it
    out = _outputs({"journal_fillet_1": 0.061, "crankpin_fillet_1": 0.049})
    slow = SolverRecord(("superlu",), "auto", False, ())
    texts = [n.display for n in case_notes(out, preset="test", sign_off=False, rule="coarse or finer", solver=slow)]
    assert any(t.startswith("NOT A SIGN-OFF: mesh preset 'test'") for t in texts)
    assert any(t.startswith("throw 1: ") and "journal_fillet_1" in t and "+6.1 % > 5 %" in t for t in texts)
    assert not any("crankpin_fillet_1" in t for t in texts)
    assert any("fast direct solver" in t and "superlu" in t for t in texts)
    fast = SolverRecord(("pardiso",), "auto", True, ())
    quiet = case_notes(_outputs({}), preset="coarse", sign_off=True, rule="coarse or finer", solver=fast)
    assert not any("SIGN-OFF" in n.text or "fast" in n.text for n in quiet)


def test_the_banner_and_the_notes_sit_beside_the_verdict():
    c = CriterionResult("criteria.min_fatigue_safety", True, 2.0, 1.5, 2.0 / 1.5 - 1)
    s = CriterionResult("criteria.min_static_safety", True, 4.0, 2.0, 1.0)
    prov = Provenance("0", "", "3", "linux", InputHash(None, ()), MeshRecord("test", False, "coarse or finer"))
    r = CaseResult("c", "c.toml", "pass", criteria=(c, s), provenance=prov)
    notes = [Note("averaging 6.1 % > 5 %", criteria=("criteria.min_fatigue_safety",)), Note("case-wide")]
    head, tab = header_html(r, notes), criteria_table(r, notes)
    assert "NOT A SIGN-OFF (test mesh)" in head and "case-wide" in head and "averaging" not in head
    row_fat = next(row for row in tab.split("<tr>") if "min_fatigue_safety" in row)
    row_sta = next(row for row in tab.split("<tr>") if "min_static_safety" in row)
    assert "averaging 6.1 %" in row_fat and "averaging" not in row_sta


def test_input_hash_covers_the_files_the_load_case_was_read_from():
    case = ROOT / "loadcases" / "single_cylinder.toml"
    lc = load_loadcase(case)
    names = sorted(f.path.name for f in lc.inputs)
    # the load case, the engine and the geometry file it names (the material library,
    # package data, is traced by the version)
    assert names == sorted(["single_cylinder.toml"] * 3)
    h = hashlib.sha256()
    base = case.resolve().parent
    for p in sorted(f.path for f in lc.inputs):  # independent: "<relative path>\0<bytes>", in sorted order
        h.update(Path(os.path.relpath(p, base)).as_posix().encode() + b"\0" + p.read_bytes())
        assert next(f.sha256 for f in lc.inputs if f.path == p) == hashlib.sha256(p.read_bytes()).hexdigest()
    assert input_hash(case, lc.inputs).sha256 == h.hexdigest()


def test_a_file_changed_after_it_was_read_is_said_so(tmp_path):
    case = tmp_path / "c.toml"
    case.write_text((ROOT / "tests" / "data" / "small_pass.toml").read_text())
    (tmp_path / "geometry_small.toml").write_text((ROOT / "tests" / "data" / "geometry_small.toml").read_text())
    lc = load_loadcase(case)
    case.write_text(case.read_text() + "\n# edited\n")
    got = input_hash(case, lc.inputs)
    assert got.sha256 is None and got.error == "c.toml changed while the case was checked"
