"""A bolted counterweight without the data its check needs is refused before any meshing,
naming the geometry file and the key.  (A load case whose criteria name no joint quantity
is checked with VDI 2230's usual limits: tests/assess/test_assess_bolt_sweep.py.)"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase

ROOT = Path(__file__).resolve().parents[2]


def _copy(tmp: Path, *, geometry=lambda t: t, case=lambda t: t, name="inline4_rated.toml") -> Path:
    for sub in ("engines", "geometry"):
        shutil.copytree(ROOT / sub, tmp / sub)
    g = tmp / "geometry" / "inline4.toml"
    g.write_text(geometry(g.read_text()))
    (tmp / "loadcases").mkdir()
    p = tmp / "loadcases" / name
    p.write_text(case((ROOT / "loadcases" / name).read_text()))
    return p


@pytest.mark.parametrize("name", ["inline4_rated.toml", "inline4_genset_torsion.toml"])
def test_a_bolted_counterweight_without_its_joint_data_is_refused_at_input(tmp_path, name):
    """Throw 1's joint without its clamp length: refused by the load-case reader (what
    ``fe-crank validate`` runs), with or without joint criteria in the load case."""
    p = _copy(tmp_path, geometry=lambda t: t.replace('clamp_length = "30 mm", ', "", 1), name=name)
    with pytest.raises(InputError) as e:
        load_loadcase(p)
    assert e.value.key == "throws[0].counterweight.bolted"
    assert "clamp_length" in str(e.value) and "VDI 2230" in str(e.value)
    assert e.value.file.endswith("inline4.toml")
