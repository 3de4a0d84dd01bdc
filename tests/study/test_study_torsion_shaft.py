"""The counterweight study's whole shaft with a ``[torsion]`` section (docs/study.md): every
journal carries its own torque in every state (the check's torque-flow cases) and the
operating speed's firing state takes the journal torques of the candidate's own torsional
stage, against the check's whole-shaft stage of the load case the study writes."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers.bolted_study import bolted_case, torsion_section

from fe_crank.assess.shaft import piece_unit_stresses
from fe_crank.fe.core.stress import von_mises
from fe_crank.fe.throw.node_groups import group_kind
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.outputs import CaseOutputs, FeModels
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.shaft_stage import whole_shaft_stage
from fe_crank.pipeline.stages import fe_stage, geometry_stage, mesh_stage
from fe_crank.pipeline.torsion_stage import torsion_stage
from fe_crank.rules.m53.basis import m53_basis
from fe_crank.study.candidates import Candidate, ThrowSolidCache, web_shape
from fe_crank.study.outputs import write_candidate
from fe_crank.study.run import TORSION_SHAFT, run_study
from fe_crank.study.screen import (
    SHAFT_KINDS,
    EngineState,
    candidate_loads,
    candidate_overspeed,
    candidate_stresses,
    engine_states,
    state_base,
    with_operating_dynamics,
)
from fe_crank.study.spec import parse_study
from fe_crank.study.torsion import screen_torsion

TORSION = torsion_section(11)

STUDY = """[study]
name = "small inline-4 with torsion, whole shaft"
rotating_rate_percent = [0]
envelope = "45 mm"
stresses = "static"
[[study.placements]]
name = "8"
webs = "all"
"""


def _brute_peak(units, weights: np.ndarray, kinds) -> float:
    """The largest von Mises stress of the history sum_c W_c(theta) S_c at every node of the
    group kinds ``kinds`` (None: every assessed group) of every throw, every angle."""
    peak = 0.0
    for unit in units:
        ids = np.unique(
            np.concatenate([v for g, v in unit.groups.items() if len(v) and (kinds is None or group_kind(g) in kinds)])
        )
        s = unit.stress[:, :, ids]
        hist = (weights @ s.reshape(s.shape[0], -1)).reshape(weights.shape[0], 6, ids.size)
        peak = max(peak, float(von_mises(hist.transpose(1, 0, 2)).max()))
    return peak


@pytest.mark.heavy
def test_whole_shaft_with_torsion_equals_the_checks_whole_shaft_stage(tmp_path):
    """Every drawn counterweight at mass factor 1 (the geometry the study writes is the drawn
    one: the same mesh) on the bolted small inline-4 with [torsion]: in every load state
    of the check's sweep (each speed, every cylinder firing and each misfire case) the
    study's main-bearing loads (the stated law's, and per bearing the envelope over the
    stiffness range) and the largest von Mises stress of the shaft's fillets, oil bores and
    crankpins equal the check's whole-shaft stage's (its torque-flow cases, its operating
    firing state on the torsional stage's journal torques; its weights evaluated here at
    every node and angle) to 1e-9, and so do the bearing loads and the peak von Mises stress
    of its overspeed cycle (quasi-static journal torques, every journal its own); the
    operating state differs from the quasi-static one (the vibratory journal torques are
    taken)."""
    (tmp_path / "study.toml").write_text(STUDY)
    cache = tmp_path / "cache"
    lc = load_loadcase(bolted_case(tmp_path, TORSION))
    res = run_study(lc, parse_study(tmp_path / "study.toml"), size="test", cache_dir=cache)
    assert TORSION_SHAFT in res.notes
    assert "torque_front" in res.shaft.cases.names
    drawn, layout, mat = res.drawn, res.shaft.layout, lc.material
    assert mat is not None
    shapes = tuple(web_shape(w, 1.0, drawn[w], layout, res.spec, layout.geometry.density) for w in drawn)
    cand = Candidate(99, "all at 1", math.nan, 0.0, 0.0, dict.fromkeys(drawn, 1.0), shapes)
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    ts = screen_torsion(lc, cycles, layout, cand, drawn, res.shaft.mass, ThrowSolidCache(layout), None, False)
    assert ts.dynamics is not None
    states = engine_states(lc.engine, lc.operating, cycles)  # the study's (``run_study``'s) on these cycles
    assert [s.speed for s in states] == [s.speed for s in res.states]
    quasi = [state_base(res.shaft, s) for s in states]
    bases = with_operating_dynamics(res.shaft, quasi, cycles.operating, ts.dynamics)
    ones = dict.fromkeys(drawn, 1.0)
    loads = [candidate_loads(res.shaft, b, ones, drawn) for b in bases]

    # the check of the load case the study writes for it
    _, lc_path = write_candidate(res, dataclasses.replace(res.results[0], candidate=cand), tmp_path / "written")
    lc2 = load_loadcase(lc_path)
    geo = geometry_stage(lc2, CheckOptions(mesh_size="test", cache_dir=str(cache)))
    cycles2 = engine_cycles(lc2.engine, lc2.operating, file=lc2.source_file)
    meshes = mesh_stage(lc2, geo)
    solved = fe_stage(lc2, geo, meshes.throws)
    torsion = torsion_stage(lc2, geo, solved, cycles2)
    out = CaseOutputs(lc2, cycles2, None, geo, meshes, FeModels(solved), torsion)
    ws = whole_shaft_stage(lc2, geo, meshes, out, False)
    assert ws.cases is not None
    add = m53_basis(lc2.engine, mat, None).additional
    try:
        units = [
            piece_unit_stresses(ws.cases, k, mat) for k, pp in enumerate(ws.cases.model.pieces) if pp.kind == "throw"
        ]
    finally:
        ws.cases.model.free_factors()

    # the study's states begin with the check's sweep, in its order (then any no-load states)
    assert len(states) >= len(ws.sweep) >= 1
    own = [i for i, st in enumerate(ws.sweep) if st.weights is ws.result.cycles[0].weights]
    assert len(own) == 1 and states[own[0]].dynamics is cycles.operating
    for i, st in enumerate(ws.sweep):
        sl = loads[i]
        assert sl.state.speed == pytest.approx(st.speed, rel=1e-12)
        assert sl.bearing_sets is not None
        mags = np.hypot(sl.bearing_sets[..., 0], sl.bearing_sets[..., 1])  # (sets, n, nb)
        scale = max(float(np.abs(b.with_counterweights.load_n).max()) for b in st.bearings)
        for j, b in enumerate(st.bearings):
            s = int(np.argmax(mags[:, :, j].max(axis=1)))  # the envelope: the set of the largest peak
            assert np.abs(sl.bearing_sets[s, :, j] - b.with_counterweights.load_n).max() <= 1e-9 * scale
        assert st.weights is not None
        peak = _brute_peak(units, st.weights, SHAFT_KINDS)
        st_study = candidate_stresses(res.shaft, [sl], mat, additional_bending=add, fatigue=False)
        assert st_study.shaft_peak == pytest.approx(peak, rel=1e-9, abs=0.0)
    # the operating firing state on the stated law: the check's own cycle, not the quasi-static one
    i = own[0]
    stated = np.stack([b.load_n for b in ws.result.cycles[0].bearings], axis=1)
    assert np.abs(loads[i].bearings - stated).max() <= 1e-9 * np.abs(stated).max()
    rigid = candidate_loads(res.shaft, quasi[i], ones, drawn, envelope=False)
    assert np.abs(rigid.bearings - stated).max() > 1e-6 * np.abs(stated).max()
    # the overspeed cycles: every journal its own quasi-static torque, in both
    assert len(cycles.overspeed) == len(ws.result.overspeed) >= 1
    os_loads = [
        candidate_loads(
            res.shaft,
            state_base(res.shaft, EngineState("overspeed", c.dynamics.speed, c.dynamics)),
            ones,
            drawn,
            envelope=False,
        )
        for c in cycles.overspeed
    ]
    for sl, ref_cycle in zip(os_loads, ws.result.overspeed):
        ref = np.stack([b.load_n for b in ref_cycle.bearings], axis=1)
        assert np.abs(sl.bearings - ref).max() <= 1e-9 * np.abs(ref).max()
    os = candidate_overspeed(res.shaft, os_loads, mat)
    assert os is not None
    os_weights = np.vstack([c.weights for c in ws.result.overspeed])
    assert os.peak == pytest.approx(_brute_peak(units, os_weights, None), rel=1e-9, abs=0.0)
