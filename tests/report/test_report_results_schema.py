"""results.json 1.4 against its schema: the bolted joints per bolt, sigma_add per group and
the oil-bore outlet's UR M53 result (a shipped case with an oil bore writes one)."""

from __future__ import annotations

import math

import jsonschema
from helpers.joints import JOINT
from helpers.joints import joint_loads as _loads

from fe_crank.assess.case import Assessment
from fe_crank.assess.cw_joint import check_joint
from fe_crank.assess.group.assessment import Extreme, GroupResult
from fe_crank.assess.results import load_schema, to_json
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.io.material import load_material
from fe_crank.rules.m53.calculation import M53Fillet


def test_joints_sigma_add_and_the_oil_bore_outlet_validate():
    ext = Extreme(100e6, "journal_fillet_1", 7, (0.0, 0.03, 0.04), math.radians(30))
    g = GroupResult("journal_fillet_1", 3, ext, None, 3.0, None, ext, None, additional_bending=10e6)
    bore = M53Fillet("oil_bore", "empirical, UR M53 3.4", 2.8, 0.0, 3.7, 1.0, 1.0, 1.0, 1.0, 2.7)
    joint = check_joint("counterweight_1", JOINT, _loads(), 210e9)
    t = ThrowAssessment("1", (g,), m53=(bore,), joints=(joint,))
    doc = to_json(Assessment("c", "c.toml", 300.0, None, load_material("C45"), (t,), ()))
    jsonschema.validate(doc, load_schema())
    assert tuple(int(x) for x in doc["schema_version"].split(".")) >= (1, 4)  # the 1.4 fields in every later minor
    (j,) = doc["throws"][0]["joints"]
    assert (
        j["separation_safety"] == joint.separation_safety and j["axial_load_overspeed"] == joint.loads.axial_overspeed
    )
    assert doc["throws"][0]["groups"][0]["additional_bending"] == 10e6
