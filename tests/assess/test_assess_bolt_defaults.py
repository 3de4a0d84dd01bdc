"""Every bolted joint that exists is checked: a load case whose geometry has bolted
counterweights and whose criteria name no joint quantity is checked with VDI 2230's usual
limits, each verdict line saying so; a bolted counterweight without the data its check needs
is refused before any meshing, naming the geometry file and the key."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import pytest

from fe_crank.assess.cw_joint import DEFAULT_LIMITS, DEFAULT_WORDS, JOINT_QUANTITIES
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.report.locations import criterion_location

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


@pytest.mark.heavy
def test_joints_without_criteria_are_checked_with_the_default_limits(tmp_path):
    from helpers.pipeline import stage_outputs

    strip = lambda t: re.sub(r"(?m)^(max|min)_bolt_\w+ = .*\n", "", t)
    p = _copy(tmp_path, case=strip)
    assert "bolt_" not in strip(p.read_text())
    out = stage_outputs(p, tmp_path / "cache")
    a = out.assessment
    got = {c.quantity: c for c in a.criteria if c.quantity in JOINT_QUANTITIES}
    assert set(got) == set(DEFAULT_LIMITS)
    joints = [j for t in a.throws for j in t.joints]
    assert len(joints) == 4  # two bolted counterweights on each of throws 1 and 4
    for q, c in got.items():
        attr, sense = JOINT_QUANTITIES[q]
        assert c.limit == DEFAULT_LIMITS[q] and c.name == f"criteria.{sense}_{q}"
        assert criterion_location(c).endswith(f"friction mu_G 0.10, mu_K 0.10, mu_T 0.10; {DEFAULT_WORDS}")
        vals = [getattr(j, attr) for j in joints]  # one speed: the operating one's joints
        assert c.value == pytest.approx(min(vals) if sense == "min" else max(vals), rel=1e-12)
    assert any("default limits" in n.text for n in a.notes)
