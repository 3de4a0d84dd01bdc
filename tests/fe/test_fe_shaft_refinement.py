"""The whole shaft's load sets in the hot-spot convergence study (``fe.shaft.refinement``),
on the small single on its two bearings checked at ``test`` with the study forced on:

* a throw alone on its two bearings is statically determinate in both models, so the
  whole shaft's displacement of a load set is the per-throw model's up to a rigid motion:
  the per-throw study's pin-force load set given as the whole shaft's (the same weights on
  the shaft's unit cases, its piece's displacement and zone loads) gives, in the same
  zones, the per-throw load set's peaks at the assessed mesh and at a finer level (an
  independent route: condensation, force method and the piece's interior solve against
  the throw's direct solve);
* the check's study of the throw mesh holds the whole shaft's own load sets (the states of
  its largest crankpin force and journal torque), and the criteria's factors are the
  largest over both models' load sets.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from fe_crank.assess.refinement import StudyFactors
from fe_crank.fe.refinement.convergence import estimate
from fe_crank.fe.refinement.levels import COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX
from fe_crank.fe.refinement.zone_study import zone_convergence
from fe_crank.fe.shaft.fields import piece_states
from fe_crank.fe.shaft.refinement import WHOLE_SHAFT_SET, governing_states, piece_of, zone_loads

DATA = Path(__file__).resolve().parents[1] / "data"
pytestmark = pytest.mark.heavy


@pytest.fixture(scope="module")
def studied_single(tmp_path_factory, mesh_cache):
    """The small single (tests/data/geometry_small.toml, end journals ending at the bearing
    centres: the throw on its two bearings) at its operating speed, checked at ``test`` with
    the convergence study (``helpers.check_shaft``): the stages' outputs and the whole-shaft
    stage's own (its unit cases)."""
    from helpers.check_shaft import stage_outputs_with_shaft
    from helpers.sweep import SWEPT

    folder = tmp_path_factory.mktemp("studied_single")
    (folder / "case.toml").write_text(SWEPT.format(sweep=""))
    g = (DATA / "geometry_small.toml").read_text() + '\n[shaft]\nend_journal_length = "12 mm"\n'
    (folder / "geometry_small.toml").write_text(g)
    return stage_outputs_with_shaft(folder / "case.toml", mesh_cache, convergence=True)


def test_zone_loads_maps_the_shaft_patterns_to_the_zone_cases():
    """Pin patterns as themselves, the spin-up as the angular acceleration (the same body
    force rho (-y, x, 0)), the throw's and its counterweights' centrifugal force as the
    whole throw's when their coefficients agree, as the parts otherwise; the bearing
    surfaces' and end faces' patterns (driven faces) left out."""
    names = ("pin_x", "pin_030", "centrifugal", "centrifugal_cw", "spin_up", "journal_1.P0", "torque_end_2")
    got = zone_loads(names, np.array([2.0, 0.0, 5.0, 5.0, -3.0, 7.0, 11.0]))
    assert got == {"pin_x": 2.0, "angular_acceleration": -3.0, "centrifugal": 5.0}
    got = zone_loads(names, np.array([2.0, 0.0, 5.0, 0.0, 0.0, 7.0, 11.0]))
    assert got == {"pin_x": 2.0, "centrifugal_throw": 5.0}
    got = zone_loads(names, np.array([0.0, 1.0, 5.0, 4.0, 0.0, 0.0, 0.0]))
    assert got == {"pin_030": 1.0, "centrifugal_throw": 5.0, "centrifugal_cw_1": 4.0, "centrifugal_cw_2": 4.0}


def test_the_shafts_load_set_of_a_determinate_throw_is_the_per_throw_models(studied_single):
    """The per-throw study's pin-force load set (its pin cases and the centrifugal force)
    as weights of the whole shaft's unit cases (``pin_<deg>@1``, ``centrifugal`` and
    ``centrifugal_cw`` alike), given to the zone study as the whole shaft's load set beside
    the per-throw one: the same peaks at the assessed mesh and at a finer level's zones, at
    the same surfaces."""
    out, ws = studied_single
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


def test_the_check_studies_the_whole_shafts_own_states(studied_single):
    """The throw mesh's study holds the whole shaft's states of its largest crankpin force
    and journal torque (``governing_states``: named by throw and angle, at the dynamics'
    own maxima), beside the per-throw model's two load sets; each group's factor is the
    largest ratio over all of them (>= 1), in both models."""
    out, ws = studied_single
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
    assert governing_states(ws.cases, ws.dynamics, ["1"]) == expected
    assert set(st.loads) == {"peak pin force", "peak torque", *expected}
    assert st.method == "zones" and all(lv.zones > 0 for lv in st.levels[1:])
    assert set(st.levels[-1].peaks) == set(st.levels[0].peaks) >= set(expected)
    factors = StudyFactors(out.convergence)
    fillets = [e for e in st.changes if not e.startswith((COUNTERWEIGHT_PREFIX, OIL_BORE_PREFIX))]
    assert set(fillets) == set(st.loads)
    k = max(1.0, max(estimate(st, e)[0] for e in fillets))
    assert factors.factor("1", "crankpin_fillet_1") == pytest.approx(k, rel=1e-12)
