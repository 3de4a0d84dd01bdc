"""The overspeed picture and the ``_overspeed`` VTU fields show the state the overspeed
table judges: the cycle recomputed at the overspeed with rod and piston inertia
(fe_crank.mechanism.cycles), at the crank angle of the governing group's maximum.

Real components: the small test throw of tests/data with two counterweights added,
meshed by gmsh (``test`` preset), solved by scikit-fem, rendered offscreen by pyvista.
The expected values come from an independent path: the assessment's unit stresses
(recovered per unit case at the assessed nodes, then superposed over every angle of the
overspeed cycle), where the drawn state (fe_crank.assess.states) superposes the displacements of one angle and
recovers the stress of the sum.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np
import pytest
from helpers.images import image_statistics
from helpers.pipeline import stage_outputs, write_report

import fe_crank.assess as assess
from fe_crank.assess.superpose import combine, load_coefficients
from fe_crank.fe.core.stress import von_mises
from fe_crank.mechanism.cycles import overspeed_cycles

pytestmark = pytest.mark.heavy  # one test-preset mesh and solve, three renders: about 30 s

DATA = Path(__file__).resolve().parents[1] / "data"

#: counterweights on both webs of the small throw (journal radius 16 mm, web 40 mm wide)
COUNTERWEIGHT = """
[counterweight]
outer_radius = "40 mm"
inner_radius = "18 mm"
angle = "140 deg"
fillet_radius = "3 mm"
webs = [1, 2]
"""


@pytest.fixture(scope="module")
def case(tmp_path_factory, mesh_cache):
    tmp = tmp_path_factory.mktemp("overspeed")
    (tmp / "geometry_small.toml").write_text((DATA / "geometry_small.toml").read_text() + COUNTERWEIGHT)
    text = (DATA / "small_pass.toml").read_text()
    text = text.replace(
        "min_overspeed_safety = 1.5", 'min_overspeed_safety = 1.5\nmax_counterweight_overspeed_stress = "200 MPa"'
    )
    (tmp / "case.toml").write_text(text)
    so = stage_outputs(tmp / "case.toml", mesh_cache)
    out = tmp / "out"
    write_report(out, so)
    assert so.loadcase is not None and so.cycles is not None and so.assessment is not None
    return out, so.loadcase, so.cycles.operating, so.unit_solutions["1"], so.assessment


def _overspeed_von_mises(lc, dyn, units, nodes) -> tuple[np.ndarray, np.ndarray]:
    """(theta, von Mises (n_angles, n_nodes)) over the overspeed cycle at the mesh nodes
    ``nodes``, by the assessment's path (unit stresses, then superposition), of the overspeed
    cycle with the largest von Mises (the criterion takes the worst of the motored curve and
    zero gas)."""
    us = assess.unit_stresses(units)
    j = np.searchsorted(us.node_ids, nodes)
    assert np.array_equal(us.node_ids[j], nodes)
    best = None
    for cyc in overspeed_cycles(lc.engine, lc.operating, dyn):
        tl = cyc.dynamics.throws["1"]
        c = load_coefficients(
            tl.pin_force, tl.torque_front, lc.operating.overspeed, cases=us.cases, torque_mz=us.torque_mz
        )
        s = combine(us.stress[:, :, j], c)  # (n_angles, 6, n)
        vm = von_mises(s.transpose(1, 0, 2))  # (6, n_angles, n) -> (n_angles, n)
        if best is None or vm.max() > best[1].max():
            best = (np.asarray(cyc.dynamics.theta), vm)
    return best


def _governing_state(hist: np.ndarray) -> tuple[int, int]:
    """(angle index, node index) of the group's maximum as the assessment names it
    (``assess.group.assessment.first_extreme``, ties within 1e-9 = ``TIE_RTOL``): the first node whose
    cycle maximum ties with the group's, then that node's first angle of its maximum.  Ties
    are real: the motored cycle repeats every revolution (TDC at 0 and 360 deg alike), and
    on a mirrored mesh a node and its mirror image peak at mirrored crank angles."""
    node_peak = hist.max(axis=0)
    k = int(np.argmax(node_peak >= node_peak.max() * (1 - 1e-9)))
    i = int(np.argmax(hist[:, k] >= hist[:, k].max() * (1 - 1e-9)))
    return i, k


def _caption(out) -> str:
    html = (out / "report.html").read_text()
    m = re.search(r"<figcaption>(Throw 1 at overspeed[^<]*)</figcaption>", html)
    assert m, "no overspeed caption"
    return m.group(1)


def test_vtu_overspeed_field_is_the_governing_state_of_the_table(case):
    import meshio

    out, lc, dyn, units, a = case
    m = meshio.read(out / "throw1.vtu")
    vm = m.point_data["von_mises_overspeed_Pa"]
    groups = {g.group: g for g in a.throws[0].groups}
    gov = max(groups.values(), key=lambda g: g.max_von_mises_overspeed.value)
    # the criterion: S = R_e / max over groups and angles (docs/assessment.md); the file's
    # state gives it back over the assessed nodes
    s = next(c for c in a.criteria if c.quantity == "overspeed_safety")
    assessed = m.point_data["assessed_group"] >= 0
    assert np.nanmax(vm[assessed]) == pytest.approx(lc.material.yield_strength / s.value, rel=1e-9)
    # the independent path over the whole overspeed cycle: the governing angle is the
    # angle of the group's maximum, and the file holds that angle's field
    nodes = np.asarray(gov.fields["node_ids"])
    theta, hist = _overspeed_von_mises(lc, dyn, units, nodes)
    i, k = _governing_state(hist)
    assert hist[i, k] == pytest.approx(gov.max_von_mises_overspeed.value, rel=1e-9)
    assert float(m.field_data["overspeed_crank_angle_deg"][0]) == pytest.approx(math.degrees(theta[i]), abs=1e-9)
    assert float(m.field_data["overspeed_rpm"][0]) == pytest.approx(3600.0, rel=1e-12)
    # same unit fields superposed in another order: equal to rounding (1e-9); one angle
    # step earlier or later moves the group's maximum by far more (checked: > 1e-5)
    np.testing.assert_allclose(vm[nodes], hist[i], rtol=1e-9, atol=1e-9 * hist[i].max())
    n = hist.shape[0]
    for step in (-1, 1):
        assert abs(hist[(i + step) % n].max() / hist[i, k] - 1) > 1e-5
    # the displacement is the overspeed state's, not the operating one's
    assert not np.allclose(m.point_data["displacement_overspeed_m"], m.point_data["displacement_m"])


def test_overspeed_picture_marks_the_table_peak_and_the_counterweight_maximum(case):
    out, lc, dyn, units, a = case
    cap = _caption(out)
    groups = {g.group: g for g in a.throws[0].groups}
    gov = max(groups.values(), key=lambda g: g.max_von_mises_overspeed.value)
    nodes = np.asarray(gov.fields["node_ids"])
    theta, hist = _overspeed_von_mises(lc, dyn, units, nodes)
    i, _ = _governing_state(hist)
    # caption: speed, angle, gas assumption, deformation scale
    assert f"at overspeed 3600 rpm, crank angle {math.degrees(theta[i]):.0f} deg" in cap
    assert "motored: no combustion" in cap and "rod and piston inertia" in cap
    assert re.search(r"deformation exaggerated x [0-9.e+]+", cap)
    # the hot-spot marker's value is the table's peak (4 significant digits printed)
    hot = re.search(r"magenta: the overspeed hot spot, (\w+) at \(([-0-9., ]+)\) mm, ([0-9.e+]+) MPa", cap)
    assert hot, cap
    assert hot.group(1) == gov.group
    assert float(hot.group(3)) == pytest.approx(gov.max_von_mises_overspeed.value / 1e6, rel=5e-4)
    k = int(np.argmax(hist[i]))  # the group's node of that maximum, from the independent path
    point = np.array([float(v) for v in hot.group(2).split(",")]) / 1e3
    np.testing.assert_allclose(point, units.points[:, nodes[k]], atol=0.06e-3)  # printed to 0.1 mm
    # the counterweight marker: the largest von Mises of the counterweight groups in this
    # state, found here from the unit stresses at the counterweight nodes at angle i
    cws = [g for g in groups.values() if g.group in ("counterweight_1", "counterweight_2")]  # the bodies
    assert len(cws) == 2
    best = None
    for g in cws:
        ids = np.asarray(g.fields["node_ids"])
        _, h = _overspeed_von_mises(lc, dyn, units, ids)
        j = int(np.argmax(h[i]))
        if best is None or h[i, j] > best[0]:
            best = (h[i, j], g.group, units.points[:, ids[j]])
    cw = re.search(
        r"black: the largest von Mises of (\w+) in this state, ([0-9.e+]+) MPa at "
        r"\(([-0-9., ]+)\) mm",
        cap,
    )
    assert cw, cap
    assert cw.group(1) == best[1]
    assert float(cw.group(2)) == pytest.approx(best[0] / 1e6, rel=5e-4)
    point = np.array([float(v) for v in cw.group(3).split(",")]) / 1e3
    np.testing.assert_allclose(point, best[2], atol=0.06e-3)  # printed to 0.1 mm
    st = image_statistics(out / "throw1_overspeed.png")
    assert st["coverage"] > 0.05 and st["std"] > 0.01
