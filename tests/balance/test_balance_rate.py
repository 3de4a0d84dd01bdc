"""The balance rate in results.json: built m r / required m r of each throw and of the
shaft, against the balance stage's required m r and the counterweights' own m r from the
geometry's mass properties, summed in the test (no mesh, no FE; the B-rep mass
properties take about half a minute per case: heavy)."""

from __future__ import annotations

import math
from pathlib import Path

import jsonschema
import pytest

from fe_crank.assess.case import Assessment
from fe_crank.assess.counterweight import check_counterweight
from fe_crank.assess.results import load_schema, to_json
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.balance.analysis import analyse_balance
from fe_crank.geometry.mass import throw_solids
from fe_crank.io.loadcase import load_loadcase
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.stages import geometry_stage

ROOT = Path(__file__).resolve().parents[2]


def _document(lc):
    """results.json of an assessment holding the geometry stage's counterweight checks."""
    balance = analyse_balance(lc.engine, lc.operating.speed, lc.balance)
    geo = geometry_stage(lc, CheckOptions(mesh_size="test"), balance)
    throws = tuple(
        ThrowAssessment(
            name,
            (),
            counterweights=tuple(check_counterweight(c, lc.operating.speed, None) for c in tg.counterweights),
        )
        for name, tg in geo.throws.items()
    )
    a = Assessment(lc.name, lc.source_file, lc.operating.speed, None, lc.material, throws, ())
    doc = to_json(a)
    jsonschema.validate(doc, load_schema())
    return doc, balance


def _built(lc, throw: str) -> float:
    """|sum of the throw's counterweights' m r vectors| from the geometry's B-rep mass properties."""
    g = lc.geometry
    spec = g.throw(throw if throw in {t.name for t in g.throws} else None)
    props = throw_solids(g, (spec.name,)).of(spec.name)
    parts = [props.parts[f"counterweight_{cw.web}"] for cw in spec.counterweights]
    return math.hypot(sum(p.unbalance_vector[0] for p in parts), sum(p.unbalance_vector[1] for p in parts))


@pytest.mark.heavy
@pytest.mark.parametrize("case", ["single_cylinder.toml", "inline4_rated.toml"])
def test_balance_rate_of_each_throw_and_of_the_shaft(case):
    """Each throw's counterweights serve one balance plane of the balance stage (one plane
    per throw on both shipped cranks): the throw's rate is its built m r over that plane's
    required m r, the shaft's the sums over all throws and all planes."""
    lc = load_loadcase(ROOT / "loadcases" / case)
    doc, balance = _document(lc)
    planes = balance.design.counterweights
    assert len(planes) == len(lc.engine.throws)
    built = {t.name: _built(lc, t.name) for t in lc.engine.throws}
    by_throw = {t["name"]: t for t in doc["throws"]}
    for t in lc.engine.throws:
        plane = min(planes, key=lambda p: abs(p.z - t.axial_position))
        assert by_throw[t.name]["balance_rate"] == pytest.approx(built[t.name] / plane.unbalance, rel=1e-9)
    shaft = sum(built.values()) / sum(p.unbalance for p in planes)
    assert doc["balance_rate"] == pytest.approx(shaft, rel=1e-9)
    assert doc["schema_version"] == "1.6"


@pytest.mark.heavy
def test_single_cylinder_rate_is_the_warned_excess():
    """The shipped single-cylinder crank carries 131 % more m r than required: rate 2.31."""
    doc, _ = _document(load_loadcase(ROOT / "loadcases" / "single_cylinder.toml"))
    assert doc["balance_rate"] == pytest.approx(2.31, abs=0.005)
