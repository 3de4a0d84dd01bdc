"""The counterweight study with turned counterweights (``study.offset``, docs/study.md) on
the small inline-4 of tests/data/small_shaft.toml at the ``test`` mesh: each offset is
screened on the drawn counterweights turned to it (their own solids, mesh and unit
cases), so a turned candidate's bearing loads are those of a full whole-shaft solve of
the geometry it writes on the same mesh; its balance term points along its m r."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from fe_crank.fe.shaft.whole_shaft import analyse_whole_shaft, throw_masses
from fe_crank.geometry.shaft import engine_shaft_layout
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mesh.shaft import mesh_shaft
from fe_crank.study.candidates import Candidate, residual, web_shape
from fe_crank.study.outputs import write_candidate
from fe_crank.study.run import run_study
from fe_crank.study.screen import candidate_loads, state_base
from fe_crank.study.spec import parse_study

CASE = Path(__file__).resolve().parents[1] / "data" / "small_shaft.toml"
TURN = math.radians(15.0)
STUDY = """
[study]
name = "small inline-4 turned"
rotating_rate_percent = [100]
offset = ["0 deg", "15 deg"]
stresses = "off"
"""


@pytest.fixture(scope="module")
def study(tmp_path_factory, mesh_cache):
    d = tmp_path_factory.mktemp("study")
    (d / "study.toml").write_text(STUDY)
    cache = mesh_cache  # the run's mesh cache: a mesh another file of the run built is read back
    res = run_study(load_loadcase(CASE), parse_study(d / "study.toml"), size="test", cache_dir=cache)
    return res, d, cache


def test_each_offset_is_a_candidate_on_the_counterweights_turned_to_it(study):
    res, _, _ = study
    assert [r.candidate.offset for r in res.results] == [0.0, TURN]
    assert set(res.by_offset) == {0.0, TURN}
    plain, turned = res.by_offset[0.0][1], res.by_offset[TURN][1]
    for w, d in turned.items():
        assert d.spec.offset == TURN and plain[w].spec.offset == 0.0
        # the same shape turned: the same mass and m r, the vector turned by the offset
        assert d.mass == pytest.approx(plain[w].mass, rel=1e-9)
        c, s = math.cos(TURN), math.sin(TURN)
        ux, uy = plain[w].unbalance_vector
        assert np.asarray(d.unbalance_vector) == pytest.approx(
            [c * ux - s * uy, s * ux + c * uy], abs=1e-9 * d.unbalance
        )
    # the turned candidate's mass factors are the plain one's (the same m r to reach)
    a, b = res.results
    assert all(b.candidate.factors[w] == pytest.approx(k, rel=1e-9) for w, k in a.candidate.factors.items())
    assert "turned 15 deg" in b.candidate.label and "turned" not in a.candidate.label


def test_balance_term_points_along_the_turned_m_r(study):
    """One web's counterweight alone (throw 1 at 0 deg, the engine's inline-4 has no first-order
    free force of its own): the residual's first-order force at crank angle 0 is k omega^2 times
    that web's m r vector, in the direction the solid's exact mass properties give it."""
    res, _, _ = study
    shaft, drawn = res.by_offset[TURN]
    engine = res.loadcase.engine
    w, k, omega = ("1", 1), 0.7, 300.0
    factors = {x: (k if x == w else 0.0) for x in drawn}
    ff = residual(engine, omega, drawn, factors)
    bare = residual(engine, omega, drawn, dict.fromkeys(drawn, 0.0))
    f0 = ff.total(1.0, None).force[:, 0] - bare.total(1.0, None).force[:, 0]  # (Fx, Fy) at theta = 0
    assert engine.throw("1").angle == 0.0
    assert f0 == pytest.approx(k * omega**2 * np.asarray(drawn[w].unbalance_vector), rel=1e-12, abs=1e-9)
    turn = math.degrees(math.atan2(f0[0], -f0[1]))  # from opposite the pin towards +x
    assert turn == pytest.approx(15.0, abs=1e-6)


def test_turned_candidate_bearing_loads_equal_a_full_solve_of_the_geometry_it_writes(study):
    """Every drawn counterweight at mass factor 1, turned 15 deg: the geometry the candidate
    writes is the drawn one turned, its mesh the study's turned one (the same cache entry);
    a full whole-shaft solve of it gives the screened bearing loads and web moments to 1e-9."""
    res, d, cache = study
    shaft, drawn = res.by_offset[TURN]
    layout = shaft.layout
    shapes = tuple(web_shape(w, 1.0, drawn[w], layout, res.spec, layout.geometry.density) for w in drawn)
    ones = dict.fromkeys(drawn, 1.0)
    cand = Candidate(99, "all at 1", math.nan, 0.0, TURN, ones, shapes)
    r = dataclasses.replace(res.results[1], candidate=cand)
    geo_path, lc_path = write_candidate(res, r, d / "written")
    assert 'offset = "15 deg"' in geo_path.read_text()
    lc2 = load_loadcase(lc_path)
    assert {cw.offset for t in lc2.geometry.throws for cw in t.counterweights} == {TURN}
    layout2 = engine_shaft_layout(lc2.geometry, lc2.engine, geometry_file="g", engine_file="e")
    sm = mesh_shaft(layout2, size="test", cache_dir=cache)
    state = res.states[0]
    full, _ = analyse_whole_shaft(sm, lc2.material, state.dynamics, mass=throw_masses(layout2))
    base = state_base(shaft, state)
    on = candidate_loads(shaft, base, ones, drawn)
    ref = np.stack([b.load_n for b in full.cycles[0].bearings], axis=1)
    assert np.abs(on.bearings - ref).max() <= 1e-9 * np.abs(ref).max()
    web_ref = np.stack([w.with_counterweights.bending_moment_nm for w in full.webs], axis=1)
    assert np.abs(on.webs - web_ref).max() <= 1e-9 * np.abs(web_ref).max()
    # and they differ from the unturned counterweights' by far more than that
    plain_shaft, plain_drawn = res.by_offset[0.0]
    plain = candidate_loads(plain_shaft, state_base(plain_shaft, state), ones, plain_drawn)
    assert np.abs(plain.bearings - ref).max() > 1e-3 * np.abs(ref).max()
