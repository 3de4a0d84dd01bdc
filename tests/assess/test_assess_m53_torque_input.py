"""UR M53 needs its torque: the M53 criterion on every engine, one cylinder included,
needs the torsional stage, or an explicit acceptance of the quasi-static journal torque
(then said on the criterion's verdict line)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from fe_crank.assess.criteria.judge import evaluate_criteria
from fe_crank.assess.criteria.qualifiers import criterion_qualifiers
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.report.locations import criterion_location
from fe_crank.rules.m53.basis import m53_basis
from fe_crank.rules.m53.calculation import M53Fillet

ROOT = Path(__file__).resolve().parents[2]
FLAG = "m53_quasi_static_torque = true"


def variant(tmp_path, name: str, old: str, new: str) -> Path:
    text = (ROOT / "loadcases" / name).read_text()
    assert old in text
    for folder in ("geometry", "engines", "loadcases"):
        (tmp_path / folder).mkdir(exist_ok=True)
    for folder in ("geometry", "engines"):
        for f in (ROOT / folder).glob("*.toml"):
            (tmp_path / folder / f.name).write_text(f.read_text())
    p = tmp_path / "loadcases" / name
    p.write_text(text.replace(old, new, 1))
    return p


def test_shipped_multi_cylinder_cases_state_it():
    lc = load_loadcase(ROOT / "loadcases" / "inline4_rated.toml")
    assert lc.criteria.m53_quasi_static_torque is True
    assert load_loadcase(ROOT / "loadcases" / "inline4_genset_torsion.toml").criteria.m53_quasi_static_torque is False


def test_m53_on_a_multi_cylinder_engine_without_torsion_is_refused(tmp_path, capsys):
    p = variant(tmp_path, "inline4_rated.toml", FLAG, "")
    with pytest.raises(InputError, match="forced-vibration calculation: give the \\[torsion\\] section") as err:
        load_loadcase(p)
    assert err.value.file == str(p) and err.value.key == "criteria.min_m53_acceptability"
    assert "criteria.m53_quasi_static_torque = true" in str(err.value)
    assert main(["validate", str(p)]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_single_cylinder_without_its_train_is_refused(tmp_path, capsys):
    """UR M53 on every engine, one cylinder included: without the [torsion] section the
    single-cylinder case is refused before any work, naming the M53 criterion."""
    text = (ROOT / "loadcases" / "single_cylinder.toml").read_text()
    train = text[text.index("\n# The crank train: ASSUMED") :]
    p = variant(tmp_path, "single_cylinder.toml", train, "\n")
    with pytest.raises(InputError, match="torsional stress of every engine \\(this one has 1 cylinder\\)") as err:
        load_loadcase(p)
    assert err.value.file == str(p) and err.value.key == "criteria.min_m53_acceptability"
    assert main(["validate", str(p)]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_single_cylinder_with_the_quasi_static_torque_accepted_says_so(tmp_path):
    """The statement accepts the case; the M53 criterion's own verdict line (its location,
    as results.json, the report and JUnit carry it) then says it is not UR M53-conform."""
    text = (ROOT / "loadcases" / "single_cylinder.toml").read_text()
    train = text[text.index("\n# The crank train: ASSUMED") :]
    p = variant(tmp_path, "single_cylinder.toml", train, "\n")
    p.write_text(p.read_text().replace("[criteria]\n", f"[criteria]\n{FLAG}\n", 1))
    lc = load_loadcase(p)
    assert lc.torsion is None and lc.criteria.m53_quasi_static_torque
    words = criterion_qualifiers(m53_basis(lc.engine, lc.material, None), lc.criteria, torsion=False)
    fillet = M53Fillet("pin", "empirical", 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.88)
    m53_only = dataclasses.replace(lc.criteria, limits=(lc.criteria.limit("m53_acceptability"),))
    (m,) = evaluate_criteria(m53_only, (ThrowAssessment("1", (), (fillet,)),), qualifiers=words)
    assert criterion_location(m) == "throw 1, pin fillet (empirical); not UR M53-conform (quasi-static torque)"
    assert m.passed and "not UR M53-conform" in m.description


def test_shipped_single_cylinder_case_has_its_train():
    lc = load_loadcase(ROOT / "loadcases" / "single_cylinder.toml")
    assert lc.torsion is not None and not lc.criteria.m53_quasi_static_torque
    assert [d.name for d in lc.torsion.driven] == ["reducer", "generator"]


def test_the_flag_with_a_torsional_stage_is_refused(tmp_path):
    p = variant(tmp_path, "inline4_genset_torsion.toml", "[criteria]\n", f"[criteria]\n{FLAG}\n")
    with pytest.raises(InputError, match="applies only without one") as err:
        load_loadcase(p)
    assert err.value.key == "criteria.m53_quasi_static_torque"


def test_the_flag_is_true_or_false(tmp_path):
    p = variant(tmp_path, "inline4_rated.toml", FLAG, 'm53_quasi_static_torque = "yes"')
    with pytest.raises(InputError, match="must be true or false") as err:
        load_loadcase(p)
    assert err.value.key == "criteria.m53_quasi_static_torque"
