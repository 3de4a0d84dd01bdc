"""The case report from real stage outputs (dynamics, FE unit cases, assessment) on a
small bar model: every section present, pictures not blank, results.json valid
against the assessment schema, the VTU fields consistent with the assessment."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from helpers.images import image_statistics
from helpers.pipeline import assess_inputs, write_report
from helpers.verification_meshes import as_throw_mesh
from skfem import MeshTet, MeshTet2

import fe_crank.assess as assess
import fe_crank.fe as fe
import fe_crank.mechanism.dynamics as dynamics
from fe_crank.io.loadcase import load_loadcase
from fe_crank.outputs import CaseOutputs, FeModels

pytestmark = pytest.mark.heavy  # one small FE solve and six renders: about 9 s

R, L = 0.02, 0.12

CASE = """
name = "bar throw"
[operating]
speed = "3000 rpm"
overspeed = "3600 rpm"
[material]
name = "42CrMo4"
[criteria]
min_static_safety = 1.5
min_fatigue_safety = 1.2
max_counterweight_overspeed_stress = "150 MPa"
[engine]
name = "single"
strokes = 4
[[engine.throws]]
name = "1"
crank_radius = "20 mm"
[[engine.cylinders]]
name = "1"
throw = "1"
bore = "60 mm"
rod_length = "110 mm"
rod_mass = "0.4 kg"
rod_cg_from_big_end = "30 mm"
piston_mass = "0.3 kg"
"""


def _bar() -> MeshTet2:
    """A round bar standing in for a throw: journals at the ends, 'pin' in the middle."""
    m = MeshTet.init_tensor(np.linspace(-1, 1, 4), np.linspace(-1, 1, 4), np.linspace(0, 1, 10))
    x, y, z = m.p
    p = np.array([R * x * np.sqrt(1 - y**2 / 2), R * y * np.sqrt(1 - x**2 / 2), L * z])
    m2 = MeshTet2.from_mesh(MeshTet(p, m.t))
    e = 1e-9

    def side(x):
        return (x[2] > e) & (x[2] < L - e)

    m2 = m2.with_boundaries(
        {
            "end_1": lambda x: np.abs(x[2]) < e,
            "end_2": lambda x: np.abs(x[2] - L) < e,
            "journal_1": lambda x: side(x) & (x[2] < L / 3),
            "journal_2": lambda x: side(x) & (x[2] > 2 * L / 3),
            "crankpin": lambda x: side(x) & (x[2] > L / 3) & (x[2] < 2 * L / 3),
            "crankpin_fillet_1": lambda x: side(x) & (np.abs(x[2] - L / 3) < L / 12),
        }
    )
    return m2.with_subdomains(
        {"counterweight_1": lambda x: x[2] < L / 6, "web_1": lambda x: (x[2] > L / 6) & (x[2] < L / 3)}
    )


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("rep")
    (tmp / "c.toml").write_text(CASE)
    lc = load_loadcase(tmp / "c.toml")
    units = fe.solve_unit_cases(as_throw_mesh(_bar()), lc.material, fe.FeOptions(solver="superlu"))
    inputs = assess_inputs(lc, {"1": units})
    a = assess.assess_case(inputs, fields=True)
    so = CaseOutputs(loadcase=lc, cycles=inputs.cycles, fe=FeModels({"1": units}), assessment=a)
    out = tmp / "out"
    res = write_report(out, so)
    return out, a, units, res


def test_results_json_follows_the_assessment_schema(report):
    import jsonschema  # a declared dependency: a failed import must fail the test

    from fe_crank.assess.results import load_schema

    out, a, _, res = report
    doc = json.loads((out / "results.json").read_text())
    jsonschema.validate(doc, load_schema())
    assert [c["name"] for c in doc["criteria"]] == [c.name for c in res.criteria]
    assert doc["passed"] == (res.status == "pass")


def test_every_section_and_every_picture(report):
    out, _, _, _ = report
    html = (out / "report.html").read_text()
    for heading in (
        "Verdict",
        "Inputs and assumptions",
        "Kinematics, forces and torque",
        "Stresses and safety factors",
        "Stress field renders",
        "Mesh statistics and FE quality",
    ):
        assert f"<h2>{heading}" in html
    imgs = re.findall(r'<img src="([^"]+)"', html)
    assert len(imgs) >= 4 and all(s.startswith("data:image/png;base64,") for s in imgs)  # embedded
    for name in ("throw1_von_mises.png", "throw1_hotspot.png", "throw1_overspeed.png", "crankpin_polar.png"):
        st = image_statistics(out / name)  # also beside the report, not blank
        assert st["coverage"] > 0.02 and st["std"] > 0.01, name
    assert re.search(r"deformation exaggerated x [0-9.e+]+", html)
    assert "equilibrium error, case centrifugal" in html
    assert "42CrMo4" in html and "statically determinate (IACS UR M53 2.1)" in html


def test_vtu_field_matches_the_assessment_at_the_critical_angle(report):
    """The von Mises field written for ParaView (displacements superposed, then stress
    recovered) equals, at the fatigue hot spot and the pictured angle, the value from
    the assessment's path (unit stresses recovered, then superposed): linearity."""
    import pyvista as pv

    from fe_crank.assess.superpose import combine, load_coefficients

    out, a, units, _ = report
    grid = pv.read(out / "throw1.vtu")
    assert grid.n_points == units.points.shape[1]
    g = min((g for g in a.throws[0].groups if g.fatigue_safety is not None), key=lambda g: g.fatigue_safety.value)
    ext = g.fatigue_safety
    np.testing.assert_allclose(grid.points[ext.node], units.points[:, ext.node], atol=1e-12)
    dyn = dynamics.analyse(*_lc_parts(out))
    angle = ext.angle if ext.angle is not None else g.max_von_mises.angle  # the angle the report draws
    i = int(np.argmin(np.abs(dyn.theta - angle)))
    us = assess.unit_stresses(units)
    c = load_coefficients(
        dyn.throws["1"].pin_force[i : i + 1],
        dyn.throws["1"].torque_front[i : i + 1],
        dyn.speed,
        cases=us.cases,
        torque_mz=us.torque_mz,
    )
    j = int(np.searchsorted(us.node_ids, ext.node))
    s = combine(us.stress[:, :, j : j + 1], c)[0, :, 0]
    vm_assess = float(units.von_mises(s[:, None])[0])
    vm_vtu = float(grid.point_data["von_mises_Pa"][ext.node])
    assert vm_assess > 0
    assert vm_vtu == pytest.approx(vm_assess, rel=1e-6)


def _lc_parts(out):
    lc = load_loadcase(out.parent / "c.toml")
    return lc.engine, lc.operating
