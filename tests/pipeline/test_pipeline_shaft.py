"""The whole-shaft stage inside the check, on real meshes and solves at the test mesh:

* a throw alone on its two bearings is statically determinate in both models: the whole
  shaft (condensation and force method) gives the per-throw model's stresses (a direct
  solve with its supports) at every assessed node;
* every journal of the whole shaft carries its own torque, the torsional stage's;
* the stresses at the assessed nodes from the condensed fields equal those of the whole
  fields solved afresh at an angle (two routes), and the picture's peak is the assessed one;
* results.json follows its schema and gives the fields of every main bearing;
* with the hot-spot convergence study, the whole shaft's own states are studied in the
  per-throw zones (``fe.shaft.refinement``): on the determinate throw the whole shaft's
  load set of the per-throw study's pin-force loads gives the per-throw load set's peaks
  (an independent route: condensation, force method and the piece's interior solve against
  the throw's direct solve), and the check's study holds the whole shaft's states of its
  largest crankpin force and journal torque, its factors the largest over both models'.
"""

from __future__ import annotations

import json
from pathlib import Path

import jsonschema
import numpy as np
import pytest
from helpers.pipeline import stage_outputs, write_report

from fe_crank.assess.refinement import StudyFactors
from fe_crank.assess.results import schema_path
from fe_crank.assess.shaft import piece_unit_stresses
from fe_crank.fe.core.stress import stress_at_selected_nodes
from fe_crank.fe.refinement.convergence import estimate
from fe_crank.fe.refinement.levels import COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX
from fe_crank.fe.refinement.zone_study import zone_convergence
from fe_crank.fe.shaft.fields import piece_fields, piece_states
from fe_crank.fe.shaft.refinement import WHOLE_SHAFT_SET, governing_states, piece_of, zone_loads
from fe_crank.fe.shaft.whole_shaft import analyse_whole_shaft, throw_masses
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mesh.shaft import mesh_shaft
from fe_crank.pipeline.stages import shaft_layout

DATA = Path(__file__).resolve().parents[1] / "data"
pytestmark = pytest.mark.heavy


@pytest.fixture(scope="module")
def swept_single(tmp_path_factory, mesh_cache):
    """The small single (tests/data/geometry_small.toml with a [shaft] section whose end
    journals end at the bearing centres: the throw on its two bearings) over two speeds
    with its misfire case, checked at ``test`` with the hot-spot convergence study
    (``helpers.check_shaft``): the stages' outputs and the whole-shaft stage's own (its unit
    cases and its sweep)."""
    from helpers.check_shaft import stage_outputs_with_shaft
    from helpers.sweep import SWEPT

    folder = tmp_path_factory.mktemp("swept_single")
    (folder / "case.toml").write_text(SWEPT.format(sweep='speeds = ["2000 rpm", "3000 rpm"]'))
    g = (DATA / "geometry_small.toml").read_text() + '\n[shaft]\nend_journal_length = "12 mm"\n'
    (folder / "geometry_small.toml").write_text(g)
    return stage_outputs_with_shaft(folder / "case.toml", mesh_cache, convergence=True)


def test_a_throw_on_its_two_bearings_is_the_per_throw_model(swept_single):
    """The small single on its two bearings (``swept_single``): the whole shaft is the throw
    on its two bearings, the torque leaving at the rear face, as the per-throw model; both
    give the same stress at every assessed node (to the solvers' round-off), at every speed
    and load state."""
    out, _ = swept_single
    assert out.whole_shaft is not None and len(out.whole_shaft.layout.bearings) == 2
    (per,) = out.assessment.throws
    (whole,) = out.assessment.shaft.throws
    by = {g.group: g for g in per.groups if not g.group.startswith("counterweight_")}
    assert {g.group for g in whole.groups} == set(by)
    for g in whole.groups:
        p = by[g.group]
        assert g.max_von_mises.value == pytest.approx(p.max_von_mises.value, rel=1e-8)
        assert g.max_von_mises_overspeed.value == pytest.approx(p.max_von_mises_overspeed.value, rel=1e-8)
        assert g.fatigue_safety.value == pytest.approx(p.fatigue_safety.value, rel=1e-8)
        assert g.fatigue_safety.node == p.fatigue_safety.node  # one shared mesh: the same node numbers
    values = [v for v in out.assessment.by_model if v.criterion == "criteria.min_static_safety"]
    assert [v.model for v in values] == ["per-throw model", "whole-shaft model"]
    assert values[0].value == pytest.approx(values[1].value, rel=1e-8)


def test_every_journal_carries_its_own_torque(tmp_path, mesh_cache):
    """tests/data/small_torsion.toml (a twin with a flywheel and a driven machine): the
    torque through every bearing plane of the whole shaft, the moment about the axis of
    the forces its pieces exchange there, is the journal torque the assessment takes (the
    torsional stage's, vibratory part included) at every angle; and the condensed stresses
    at the assessed nodes are those of the whole field solved afresh."""
    from fe_crank.balance.analysis import analyse_balance
    from fe_crank.mechanism.cycles import engine_cycles
    from fe_crank.pipeline.options import CheckOptions
    from fe_crank.pipeline.stages import fe_stage, geometry_stage, mesh_stage
    from fe_crank.pipeline.torsion_stage import torsion_stage

    lc = load_loadcase(DATA / "small_torsion.toml")
    # the check's stages up to the torsional one (the calls of ``pipeline.stages.run_stages``):
    # the journal torques the assessment takes; the whole shaft is solved here
    balance = analyse_balance(lc.engine, lc.operating.speed, lc.balance)
    geo = geometry_stage(lc, CheckOptions(mesh_size="test", cache_dir=str(mesh_cache)), balance)
    units = fe_stage(lc, geo, mesh_stage(lc, geo).throws)
    dyn = torsion_stage(lc, geo, units, engine_cycles(lc.engine, lc.operating)).dynamics
    layout = shaft_layout(lc)
    sm = mesh_shaft(layout, size=geo.plan.options, cache_dir=mesh_cache)
    result, cases = analyse_whole_shaft(sm, lc.material, dyn, mass=throw_masses(layout), torque_flow=True)
    W = result.cycles[0].weights
    sense = layout.sense
    for k, pp in enumerate(cases.model.pieces):
        if pp.kind != "throw":
            continue
        c = pp.cond
        f = c.S @ (cases.V[k] @ W.T) - c.g @ (cases.coef[k] @ W.T)  # forces of the neighbours on the piece
        x = c.basis.doflocs
        n1 = 3 * c.faces["end_1"].size
        tl = dyn.throws[pp.throw]
        for face, rows, torque, sign in (
            ("end_1", slice(0, n1), tl.torque_front, -1.0),
            ("end_2", slice(n1, None), tl.torque_rear, 1.0),
        ):
            nodes = c.faces[face]
            ff = f[rows].reshape(nodes.size, 3, -1)
            mz = np.einsum("n,nk->k", x[0, nodes], ff[:, 1]) - np.einsum("n,nk->k", x[1, nodes], ff[:, 0])
            scale = np.abs(tl.torque_rear).max()
            # the downstream resists the driving torque: M_z = sense T at the rear face, the
            # upstream drives it: -sense T at the front face (a torque T about -sense z); to the
            # round-off of S v - g a, a difference of terms a stiffness times larger (1.6e-6 seen)
            np.testing.assert_allclose(mz, sign * sense * torque, rtol=0, atol=2e-5 * scale)
    # the journal torques are not the quasi-static ones: the throws' inertia torque is carried
    tl = dyn.throws["1"]
    assert np.abs(tl.torque_rear - tl.torque_front - tl.torque).max() > 0.01 * np.abs(tl.torque).max()
    # two routes to the stresses at the assessed nodes at the governing angle
    k = next(i for i, pp in enumerate(cases.model.pieces) if pp.kind == "throw")
    unit = piece_unit_stresses(cases, k, lc.material)
    row = int(np.argmax(np.abs(W[:, cases.names.index("pin_y@1")])))
    u = piece_fields(cases, W[row], lc.material)[k]
    c = cases.model.pieces[k].cond
    direct = stress_at_selected_nodes(
        c.mesh, [u], lc.material.youngs_modulus, lc.material.poisson_ratio, unit.node_ids, dofs=c.basis.dofs
    )[0]
    combined = np.tensordot(W[row], unit.stress, axes=(0, 0))
    np.testing.assert_allclose(combined, direct, rtol=0, atol=1e-8 * np.abs(direct).max())


def test_small_shaft_results_and_report(tmp_path, mesh_cache):
    """tests/data/small_shaft.toml: results.json valid against its schema with the whole
    shaft's fields, the main-bearing criteria by hand from them, the report's pictures
    and the whole shaft's .vtu (quadratic cells) whose peak at the hot spot is the
    assessed one."""
    import meshio

    out = stage_outputs(DATA / "small_shaft.toml", mesh_cache)
    folder = tmp_path / "report"
    write_report(folder, out)
    doc = json.loads((folder / "results.json").read_text())
    jsonschema.validate(doc, json.loads(Path(schema_path()).read_text()))
    ws = doc["whole_shaft"]
    n = len(doc["whole_shaft"]["main_bearings"][0]["crank_angle_deg"])
    assert [b["name"] for b in ws["main_bearings"]] == ["1", "2", "3", "4", "5"]
    assert [b["z"] for b in ws["main_bearings"]] == pytest.approx([-0.132, -0.066, 0.0, 0.066, 0.132])
    d = 0.032  # journal diameter
    for b in ws["main_bearings"]:
        for loads in (b, b["without_counterweights"]):
            f = np.asarray(loads["load_n"])
            assert f.shape == (n, 2)
            mag = np.hypot(f[:, 0], f[:, 1])
            assert loads["peak_n"] == pytest.approx(mag.max(), rel=1e-12)
            assert loads["mean_n"] == pytest.approx(mag.mean(), rel=1e-12)
            assert loads["specific_load_pa"] == pytest.approx(mag.max() / (d * b["width"]), rel=1e-12)
    assert len(ws["webs"]) == 8 and np.asarray(ws["webs"][0]["bending_moment_nm"]).shape == (n, 2)
    crit = {c["name"]: c for c in doc["criteria"]}
    load = crit["criteria.max_main_bearing_load"]
    assert load["value"] == pytest.approx(max(b["peak_n"] for b in ws["main_bearings"]), rel=1e-12)
    spec = crit["criteria.max_main_bearing_specific_load"]
    assert spec["value"] == pytest.approx(max(b["specific_load_pa"] for b in ws["main_bearings"]), rel=1e-12)
    assert load["location"].startswith("whole-shaft model: main bearing")
    assert {v["model"] for v in doc["criteria_by_model"]} == {"per-throw model", "whole-shaft model"}
    for f in (
        "shaft_bearing_polar.png",
        "shaft_bearing_loads.png",
        "shaft_web_moments.png",
        "whole_shaft_von_mises.png",
    ):
        assert (folder / f).stat().st_size > 10_000, f
    mesh = meshio.read(folder / "whole_shaft.vtu")
    assert mesh.cells[0].type == "tetra10"
    h, fields = out.assessment.shaft.governing, out.shaft_fields
    assert mesh.point_data["von_mises_Pa"][fields.hotspot_node] == pytest.approx(h.von_mises, rel=1e-6)
    assert np.linalg.norm(mesh.points[fields.hotspot_node] - np.asarray(h.point)) < 1e-9


def test_the_whole_shaft_is_assessed_at_every_speed_and_load_state(swept_single):
    """The small single over two speeds with its misfire case, on its bearings (a [shaft]
    section): the whole shaft's throws in every load state (``ShaftAssessment.states``,
    the per-throw model's pruning: each group's extremes only) have the least static and
    fatigue safety an evaluation of every node gives (``assess_groups`` on the state's
    weights, here); each criterion takes the worse model at each speed.  The states' weights
    and the unit stresses are the check's own whole-shaft stage's (``helpers.check_shaft``:
    its unit cases and its sweep over the load states), every node evaluated here."""
    from fe_crank.assess.group.assessment import assess_groups
    from fe_crank.assess.shaft import PER_THROW, WHOLE_SHAFT
    from fe_crank.rules.m53.basis import m53_basis

    out, ws = swept_single
    shaft = out.assessment.shaft
    assert [(round(s.speed * 30 / np.pi), s.case) for s in shaft.states] == [
        (2000, "all cylinders firing"),
        (2000, "cylinder 1 misfiring"),
        (3000, "all cylinders firing"),
        (3000, "cylinder 1 misfiring"),
    ]
    lc = out.loadcase
    assert ws is not None and ws.cases is not None
    layout, cases, sweep = ws.layout, ws.cases, ws.sweep
    assert len(sweep) == len(shaft.states)
    (k,) = [i for i, pp in enumerate(cases.model.pieces) if pp.kind == "throw"]
    unit = piece_unit_stresses(cases, k, lc.material)
    m53 = out.geometry.throws["1"].m53
    basis = m53_basis(lc.engine, lc.material, None)
    for st, got in zip(sweep, shaft.states):
        groups = assess_groups(
            unit,
            st.weights,
            out.assessed_dynamics.theta,
            lc.material,
            crank_radius=layout.geometry.crank_radius,
            overspeed=None,
            overspeed_coefficients=None,
            pin_diameter=m53.pin_diameter,
            journal_diameter=m53.journal_diameter,
            additional_bending=basis.additional,
        )
        (t,) = got.throws
        assert min(x.static_safety for x in t.groups) == pytest.approx(min(x.static_safety for x in groups), rel=1e-12)
        fat = [x.fatigue_safety.value for x in groups if x.fatigue_safety is not None]
        got_fat = [x.fatigue_safety.value for x in t.groups if x.fatigue_safety is not None]
        assert min(got_fat) == pytest.approx(min(fat), rel=1e-9)
    # the criteria: the worse model at each of the two speeds, at the convergence study's
    # factors (the same in both models); a throw on its two bearings is statically
    # determinate, so both models agree (to the solvers' round-off) at every speed
    crit = {c.quantity: c for c in out.assessment.criteria}
    k = StudyFactors(out.convergence).factor
    static = min(x.static_safety / k("1", x.group) for st in shaft.states for x in st.throws[0].groups)
    both = {v.model: v.value for v in out.assessment.by_model if v.criterion == crit["static_safety"].name}
    assert both[WHOLE_SHAFT] == static and both[PER_THROW] == pytest.approx(static, rel=1e-8)
    for q in ("static_safety", "fatigue_safety"):
        assert len(crit[q].per_speed) == 2
        values = {v.model: v.value for v in out.assessment.by_model if v.criterion == crit[q].name}
        assert crit[q].value == min(values.values())


def test_the_shafts_load_set_of_a_determinate_throw_is_the_per_throw_models(swept_single):
    """The per-throw study's pin-force load set (its pin cases and the centrifugal force)
    as weights of the whole shaft's unit cases (``pin_<deg>@1``, ``centrifugal`` and
    ``centrifugal_cw`` alike), given to the zone study as the whole shaft's load set beside
    the per-throw one: the same peaks at the assessed mesh and at a finer level's zones, at
    the same surfaces."""
    out, ws = swept_single
    assert ws is not None and ws.cases is not None
    (key,) = out.fe.unit_solutions
    unit_solutions = out.fe.unit_solutions[key]
    per = dict(out.convergence[key].loads["peak pin force"])
    assert set(per) <= {*unit_solutions.cases, "centrifugal"} and "torque" not in per
    names = ws.cases.names
    w = np.zeros(len(names))
    for case, v in per.items():
        for target in ("centrifugal", "centrifugal_cw") if case == "centrifugal" else (f"{case}@1",):
            w[names.index(target)] += v
    k = piece_of(ws.cases, "1")
    u = piece_states(ws.cases, {k: w[:, None]}, out.loadcase.material)[k][:, 0]
    shaft = (u, zone_loads(ws.cases.model.pieces[k].cond.names, ws.cases.coef[k] @ w))
    assert shaft[1] == per  # the same loads inside the zones, by another route
    one = (1.0, 1.5)  # the assessed mesh and one finer level
    st = zone_convergence(
        out.loadcase.geometry,
        out.loadcase.material,
        out.meshes.throws[key],
        unit_solutions,
        {"per-throw": per},
        factors=one,
        driven={"shaft": shaft},
    )
    assert st.levels[1].zones > 0
    for lv in st.levels:
        assert lv.peaks["shaft"] == pytest.approx(lv.peaks["per-throw"], rel=1e-7)
        assert lv.where["shaft"] == lv.where["per-throw"]


def test_the_check_studies_the_whole_shafts_own_states(swept_single):
    """The throw mesh's study holds the whole shaft's states of its largest crankpin force
    and journal torque (``governing_states``: named by throw and angle, at the dynamics'
    own maxima), beside the per-throw model's two load sets; each group's factor is the
    largest ratio over all of them (>= 1), in both models."""
    out, ws = swept_single
    assert ws is not None and ws.cases is not None
    (key,) = out.convergence
    st = out.convergence[key]
    theta = np.asarray(ws.dynamics.theta)
    tl = ws.dynamics.throws["1"]
    i = int(np.argmax(np.hypot(*np.asarray(tl.pin_force).T)))
    j = int(np.argmax(np.maximum(np.abs(tl.torque_front), np.abs(tl.torque_rear))))
    expected = {
        f"{WHOLE_SHAFT_SET}peak pin force (throw 1, {np.degrees(theta[i]):.1f} deg)": ("1", i),
        f"{WHOLE_SHAFT_SET}peak torque (throw 1, {np.degrees(theta[j]):.1f} deg)": ("1", j),
    }
    assert governing_states(ws.dynamics, ["1"]) == expected
    assert set(st.loads) == {"peak pin force", "peak torque", *expected}
    assert st.method == "zones" and all(lv.zones > 0 for lv in st.levels[1:])
    assert set(st.levels[-1].peaks) == set(st.levels[0].peaks) >= set(expected)
    factors = StudyFactors(out.convergence)
    fillets = [e for e in st.changes if not e.startswith((COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX))]
    assert set(fillets) == set(st.loads)
    k = max(1.0, max(estimate(st, e)[0] for e in fillets))
    assert factors.factor("1", "crankpin_fillet_1") == pytest.approx(k, rel=1e-12)
