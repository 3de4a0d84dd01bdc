"""UR M53 needs its torque: the M53 criterion on a multi-cylinder engine needs the
torsional stage, or an explicit acceptance of the quasi-static journal torque."""

from __future__ import annotations

from pathlib import Path

import pytest

from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase

ROOT = Path(__file__).resolve().parents[1]
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


def test_single_cylinder_needs_no_torsional_stage():
    lc = load_loadcase(ROOT / "loadcases" / "single_cylinder.toml")
    assert lc.criteria.limit("m53_acceptability") is not None and not lc.criteria.m53_quasi_static_torque


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
