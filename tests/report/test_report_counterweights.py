"""Counterweight section of the report: required vs built m*r from the assessment's
counterweight checks (an assessment holding only them)."""

from __future__ import annotations

import numpy as np
from helpers.images import image_statistics

from fe_crank.assess.case import Assessment
from fe_crank.assess.counterweight import CounterweightData, check_counterweight
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.io.material import load_material
from fe_crank.outputs import CaseOutputs
from fe_crank.report.tables import counterweight_section


def _outputs(*throws: ThrowAssessment) -> CaseOutputs:
    a = Assessment("c", "c.toml", 314.16, None, load_material("C45"), throws, ())
    return CaseOutputs(assessment=a)


def test_required_vs_built_table_and_chart(tmp_path):
    # the V4-90 counterweight (Voronkov): sector r1 71, r2 32 mm, 180 deg, b 19 mm, rho 7400 -> m = 0.887 kg at 34.3 mm
    built = CounterweightData("counterweight_1", mass=0.887, centroid_radius=0.0343, required_unbalance=0.03017)
    c = check_counterweight(built, omega=314.16, overspeed=None)
    parts = counterweight_section(tmp_path, _outputs(ThrowAssessment("A", (), counterweights=(c,))), None)
    html = "".join(parts)
    assert "throw A: cw 1" in html
    # |0.887 * 0.0343 - 0.03017| / 0.03017 = 0.84 %
    expected = abs(0.887 * 0.0343 - 0.03017) / 0.03017
    assert f"{100 * expected:.1f} %" in html
    st = image_statistics(tmp_path / "counterweight_mr.png")
    assert st["coverage"] > 0.05 and np.isfinite(st["std"])


def test_no_counterweights_no_section(tmp_path):
    assert counterweight_section(tmp_path, _outputs(ThrowAssessment("1", ())), None) == []
    assert counterweight_section(tmp_path, CaseOutputs(), None) == []
    assert list(tmp_path.iterdir()) == []


def test_the_bolted_joints_vdi_2230_table(tmp_path):
    """The joints the assessment checked, per bolt: the hand-calculated M12 10.9 example of
    test_assess_cw_joint (S_F 1.1327, S_D 5.2705, S_sep 2.1914, S_G 16.932, Phi_K 0.12936)."""
    from helpers.joints import JOINT
    from helpers.joints import joint_loads as _loads

    from fe_crank.assess.cw_joint import check_joint

    j = check_joint("counterweight_1", JOINT, _loads(), 210e9)
    built = CounterweightData("counterweight_1", mass=2.0, centroid_radius=0.06)
    c = check_counterweight(built, omega=314.16, overspeed=None)
    html = "".join(
        counterweight_section(tmp_path, _outputs(ThrowAssessment("1", (), counterweights=(c,), joints=(j,))), None)
    )
    assert "VDI 2230" in html and "throw 1: counterweight_1" in html
    for text in ("1.133", "5.271", "2.191", "16.932", "0.129", "64.90 / 40.56"):
        assert text in html, text
