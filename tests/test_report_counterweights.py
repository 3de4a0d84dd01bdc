"""Counterweight section of the report: required vs built m*r from the assessment's
counterweight checks (a plain-data stand-in for the assessment object)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from fe_crank.assess.counterweight import CounterweightData, check_counterweight
from fe_crank.report.render import image_statistics
from fe_crank.report.sections import counterweight_section


def test_required_vs_built_table_and_chart(tmp_path):
    # seed 003: sector r1 71, r2 32 mm, 180 deg, b 19 mm, rho 7400 -> m = 0.887 kg at 34.3 mm
    built = CounterweightData("counterweight_1", mass=0.887, centroid_radius=0.0343, required_unbalance=0.03017)
    c = check_counterweight(built, omega=314.16, overspeed=None)
    assessment = SimpleNamespace(throws=(SimpleNamespace(name="A", counterweights=(c,)),))
    parts = counterweight_section(tmp_path, {"assessment": assessment}, None)
    html = "".join(parts)
    assert "throw A: cw 1" in html
    # |0.887 * 0.0343 - 0.03017| / 0.03017 = 0.84 %
    expected = abs(0.887 * 0.0343 - 0.03017) / 0.03017
    assert f"{100 * expected:.1f} %" in html
    st = image_statistics(tmp_path / "counterweight_mr.png")
    assert st["coverage"] > 0.05 and np.isfinite(st["std"])


def test_no_counterweights_no_section(tmp_path):
    assessment = SimpleNamespace(throws=(SimpleNamespace(name="1", counterweights=()),))
    assert counterweight_section(tmp_path, {"assessment": assessment}, None) == []
    assert counterweight_section(tmp_path, {}, None) == []
    assert list(tmp_path.iterdir()) == []
