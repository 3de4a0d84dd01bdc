"""The counterweight study with a ``[torsion]`` section (docs/study.md): each candidate's
torsional stage on the throws' inertias of the geometry it writes, its first natural
frequency, UR M53's Q with its own vibratory journal torques, its bolted joints with the
torsional angular acceleration and its counterweights' stress with the vibratory loads,
against the check of the load case the study writes for that candidate (two candidates
of different counterweight mass) and the frequency against Holzer's residual computed
here; the study's whole shaft with [torsion] (every journal its own torque in every state,
the operating speed's firing state on the candidate's own torsional journal torques)
against the check's whole-shaft stage of the load case the study writes.  The chain takes
the FE throw stiffness (``throw_stiffness = "fe"``): each candidate's is that of the
geometry it writes, against the check's torque unit case; Carter's chain against the
check's too.  One study and the checks of the written case at mass factor 0 and 1 serve
every test here."""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from helpers.bolted_study import bolted_case, torsion_section
from helpers.cw_peak import brute_peak, counterweight_peak
from helpers.paths import DATA

from fe_crank.assess.shaft import piece_unit_stresses
from fe_crank.assess.throw import fe_coefficients
from fe_crank.cli import main
from fe_crank.fe.throw.pin_patches import rod_loads
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.outputs import CaseOutputs, FeModels
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.shaft_stage import whole_shaft_stage
from fe_crank.pipeline.stages import assess_stage, fe_stage, geometry_stage, mesh_stage
from fe_crank.pipeline.torsion_stage import torsion_stage
from fe_crank.rules.m53.basis import m53_basis
from fe_crank.study.bodies import candidate_bodies
from fe_crank.study.candidates import Candidate, ThrowSolidCache, web_shape
from fe_crank.study.joints import candidate_joints
from fe_crank.study.outputs import to_toml, write_candidate, write_tables
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
from fe_crank.study.spec import JOINT_LIMITS, parse_study
from fe_crank.study.torsion import ThrowStiffnessCache, screen_torsion, written_geometry
from fe_crank.torsion.build import shear_modulus
from fe_crank.torsion.stiffness import carter_throw_stiffness

#: 11 speeds over 2000-4800 rpm: every claim here is an equality between the study and the
#: check of the same load case on the same speed sweep (or a property of the chain, which
#: does not depend on the speeds), so a shorter sweep checks it as well as a finer one;
#: the chain on the FE throw stiffness of each candidate's written geometry
TORSION = torsion_section(11).replace("[torsion]\n", '[torsion]\nthrow_stiffness = "fe"\n', 1)

STUDY = """[study]
name = "small inline-4 with torsion"
rotating_rate_percent = [0, 100]
envelope = "45 mm"
stresses = "static"
[study.limits]
min_m53_acceptability = 1.0
[[study.placements]]
name = "8"
webs = "all"
"""


def torsion_case(folder: Path) -> Path:
    """tests/data/small_shaft.toml (the small inline-4, a counterweight on every web) with a
    ``[torsion]`` section (flywheel and a brake on a soft coupling), written into ``folder``."""
    (folder / "geometry_small_shaft.toml").write_text((DATA / "geometry_small_shaft.toml").read_text())
    path = folder / "small_shaft_torsion.toml"
    path.write_text((DATA / "small_shaft.toml").read_text() + TORSION)
    return path


@pytest.fixture(scope="module")
def screened(tmp_path_factory, mesh_cache):
    """The study of the bolted small inline-4 with [torsion], 0 % and 100 % on every web,
    and the FE throw stiffness cache it filled (``run_study``'s ``stiffness``)."""
    d = tmp_path_factory.mktemp("torsion_study")
    (d / "study.toml").write_text(STUDY)
    cache = mesh_cache  # the run's meshes: the bolted inline-4's are test_study_counterweights' too
    lc = load_loadcase(bolted_case(d, TORSION))
    stiffness = ThrowStiffnessCache(lc, size="test", cache_dir=cache)
    res = run_study(lc, parse_study(d / "study.toml"), size="test", cache_dir=cache, stiffness=stiffness)
    return res, d, cache, stiffness


@pytest.fixture(scope="module")
def study(screened):
    res, d, cache, _ = screened
    return res, d, cache


@pytest.fixture(scope="module")
def stiffness(screened):
    """The FE throw stiffness of the candidates the tests screen themselves: the study's
    own function and cache (a written solid the study solved is not solved again)."""
    return screened[3]


def _holzer_residual(inertia: np.ndarray, stiffness: np.ndarray, omega: float) -> float:
    """The torque left after the last mass of a free-free chain (Den Hartog sec. 5.5)."""
    theta, torque = 1.0, 0.0
    for i, j in enumerate(inertia):
        torque += omega**2 * j * theta
        if i < stiffness.size:
            theta -= torque / stiffness[i]
    return torque


def _check(res, r, folder: Path, cache: Path, joints: bool):
    """The check of the load case the study writes for ``r`` (the ``test`` mesh, the study's
    cached meshes): its geometry, mesh, FE and torsional stages and its per-throw assessment,
    judged by UR M53's Q and, with ``joints``, every joint criterion (limits low enough to
    pass); also its geometry and meshes (for its whole-shaft stage)."""
    _, lc_path = write_candidate(res, r, folder)
    data = tomllib.loads(lc_path.read_text())
    data["criteria"] = {"min_m53_acceptability": 1.0}
    if joints:
        data["criteria"] |= {k: 1.0 if k.startswith("max_") else 0.01 for k in JOINT_LIMITS}
    lc_path.write_text(to_toml(data))
    lc = load_loadcase(lc_path)
    geo = geometry_stage(lc, CheckOptions(mesh_size="test", cache_dir=str(cache)))
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    meshes = mesh_stage(lc, geo)
    solved = fe_stage(lc, geo, meshes.throws)
    torsion = torsion_stage(lc, geo, solved, cycles)
    out = CaseOutputs(lc, cycles, None, geo, None, FeModels(solved), torsion)
    criteria = {c.quantity: c.value for c in assess_stage(lc, out, False).criteria}
    return lc, solved, torsion, criteria, geo, meshes, cycles


def _all_at_one(res) -> Candidate:
    """Every drawn counterweight at mass factor 1 (the drawn shapes: the same meshes)."""
    drawn, layout = res.drawn, res.shaft.layout
    shapes = tuple(web_shape(w, 1.0, drawn[w], layout, res.spec, layout.geometry.density) for w in drawn)
    return Candidate(99, "all at 1", math.nan, 0.0, 0.0, dict.fromkeys(drawn, 1.0), shapes)


@pytest.fixture(scope="module")
def written_zero(study):
    """The check (``_check``) of the load case the study writes for its 0 % row (no
    counterweight: another solid than the drawn one)."""
    res, d, cache = study
    return _check(res, res.results[0], d / "written_zero", cache, False)


@pytest.fixture(scope="module")
def written_one(study):
    """The check (``_check``, joint criteria judged) of the load case the study writes for
    every drawn counterweight at mass factor 1."""
    res, d, cache = study
    r = dataclasses.replace(res.results[0], candidate=_all_at_one(res))
    return _check(res, r, d / "written_one", cache, True)


@pytest.mark.heavy
def test_each_candidates_torsional_figures_equal_the_checks_of_the_written_case(
    study, written_zero, written_one, stiffness
):
    """Two candidates of different counterweight mass: the study's 0 % row (no counterweight)
    and every drawn counterweight at mass factor 1 (the drawn shapes: the same meshes), the
    latter screened by the study's own per-candidate functions (``study.torsion
    .screen_torsion``, ``study.bodies``, ``study.joints``).  Against the check of the load
    case the study writes for each (its torsional stage and per-throw assessment, ``test``
    mesh): the first natural frequency, UR M53's Q (the check's ``min_m53_acceptability``),
    and, at factor 1, every VDI 2230 figure of the bolted joints (the check's joint
    criteria) and the counterweights' peak von Mises stress over every counterweight node,
    angle and load state of the check's per-throw model (the check's coefficients with the
    vibration, evaluated at every node here), each to 1e-9.  The frequency is a root of
    Holzer's residual of the check's chain (computed here, no eigenproblem), the first one,
    and the chains' throws differ by the candidates' polar-inertia change."""
    res, _, _ = study
    lc = res.loadcase
    drawn, layout = res.drawn, res.shaft.layout
    cand = _all_at_one(res)
    solids = ThrowSolidCache(layout)
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    ts = screen_torsion(lc, cycles, layout, cand, drawn, res.shaft.mass, solids, res.body_model, True, stiffness)
    assert ts.joints is not None and res.body_model is not None and ts.m53 is not None
    joints = candidate_joints(ts.joints, cand, solids, res.shaft.mass)
    bodies = candidate_bodies(res.body_model, ts.loads, dict.fromkeys(drawn, 1.0))
    assert joints is not None and joints.refused is None and joints.joints == len(drawn)
    zero = res.results[0]
    assert zero.counterweight_mass == 0.0 and zero.torsional_frequency is not None and zero.m53 is not None
    chains = []
    for label, f1, q in (
        ("zero", zero.torsional_frequency, zero.m53.acceptability),
        ("one", ts.frequency, ts.m53.acceptability),
    ):
        lc2, solved, torsion, criteria, *_ = written_zero if label == "zero" else written_one
        assert f1 == pytest.approx(float(torsion.result.modes.elastic_hz[0]), rel=1e-9, abs=0.0)
        assert q == pytest.approx(criteria["m53_acceptability"], rel=1e-9, abs=0.0)
        model = torsion.result.model
        w = 2 * math.pi * f1
        assert abs(_holzer_residual(model.inertia, model.stiffness, w)) <= 1e-8 * w**2 * float(model.inertia.sum())
        below = [_holzer_residual(model.inertia, model.stiffness, x * w) for x in np.linspace(0.05, 0.98, 40)]
        assert all(v > 0 for v in below) or all(v < 0 for v in below)  # no root below f1
        chains.append(model)
        if label == "zero":
            continue
        for key in JOINT_LIMITS:
            assert joints.values[key] == pytest.approx(criteria[key.split("_", 1)[1]], rel=1e-9, abs=0.0), key
        assert torsion.loads is not None
        ref = counterweight_peak(
            lc2,
            solved,
            torsion.loads.speeds,
            lambda unit, tc, state, sense, places: fe_coefficients(
                unit,
                tc.pin_force,
                tc.torque_in,
                state.speed,
                sense=sense,
                rod_loads=rod_loads(tc, places),
                angular_acceleration=tc.angular_acceleration,
                fe_pin_force=tc.fe_pin_force,
                fe_rod_loads=tc.fe_rod_loads(places) if tc.fe_rods else None,
            ),
        )
        assert bodies.peak == pytest.approx(ref, rel=1e-9, abs=0.0)
    names = [t.name for t in layout.throws]
    dj = sum(chains[1].inertia[chains[1].throw_mass[n]] - chains[0].inertia[chains[0].throw_mass[n]] for n in names)
    assert dj == pytest.approx(-zero.polar_inertia_change, rel=1e-9)
    assert ts.frequency < zero.torsional_frequency  # heavier throws, lower frequency
    assert all(r.bodies is not None and r.joints is not None for r in res.results[1:])


@pytest.mark.heavy
def test_whole_shaft_with_torsion_equals_the_checks_whole_shaft_stage(study, written_one, stiffness):
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
    taken).  The module's study (its 100 % candidate and Q limit do not touch the whole
    shaft's screening of a given candidate) and its check of the written case (its
    criteria do not enter the whole-shaft stage)."""
    res, _, _ = study
    lc = res.loadcase
    assert TORSION_SHAFT in res.notes
    assert "torque_front" in res.shaft.cases.names
    drawn, layout, mat = res.drawn, res.shaft.layout, lc.material
    assert mat is not None
    cand = _all_at_one(res)
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    ts = screen_torsion(
        lc, cycles, layout, cand, drawn, res.shaft.mass, ThrowSolidCache(layout), None, False, stiffness
    )
    assert ts.dynamics is not None
    states = engine_states(lc.engine, lc.operating, cycles)  # the study's (``run_study``'s) on these cycles
    assert [s.speed for s in states] == [s.speed for s in res.states]
    quasi = [state_base(res.shaft, s) for s in states]
    bases = with_operating_dynamics(res.shaft, quasi, cycles.operating, ts.dynamics)
    ones = dict.fromkeys(drawn, 1.0)
    loads = [candidate_loads(res.shaft, b, ones, drawn) for b in bases]

    # the check of the load case the study writes for it: its whole-shaft stage after its
    # FE and torsional stages
    lc2, solved, torsion, _, geo, meshes, cycles2 = written_one
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
        peak = brute_peak(units, st.weights, SHAFT_KINDS)
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
    assert os.peak == pytest.approx(brute_peak(units, os_weights, None), rel=1e-9, abs=0.0)


def test_tables_carry_the_frequency_and_the_notes_say_how(study, tmp_path):
    res, _, _ = study
    paths = write_tables(res, tmp_path)
    assert "first_torsional_frequency_hz" in paths["csv"].read_text().splitlines()[0]
    assert "1st torsional natural frequency Hz" in paths["md"].read_text()
    notes = " ".join(res.notes)
    assert "torsional stage per candidate" in notes and "UR M53 Q per candidate" in notes
    assert "torsional angular acceleration" in notes


def _carter(lc):
    """The load case with ``throw_stiffness = "carter"``, its [torsion] otherwise as it is."""
    assert lc.torsion is not None and lc.torsion.throw_stiffness == "fe"
    return dataclasses.replace(lc, torsion=dataclasses.replace(lc.torsion, throw_stiffness="carter"))


@pytest.mark.heavy
def test_fe_throw_stiffness_per_candidate_equals_the_checks(study, written_zero, written_one, stiffness):
    """The study's FE throw stiffness (``study.torsion.ThrowStiffnessCache``: the torque
    case alone on the first throw model of the check's mesh plan of the written geometry)
    for two candidates, two solids: the 0 % row (no counterweight: not the study shaft's
    drawn solid) and every drawn counterweight at mass factor 1 (the drawn solid).  Against
    the check of the load case the study writes for each (its FE stage's torque unit case,
    solved there with every other unit case; its torsional stage), to 1e-9 (the same
    ``test`` meshes): the stiffness and every throw's vibratory journal torque histories
    (handed to the whole shaft and to UR M53; the frequency and Q: the test above).  The
    stiffness lies in the band of Carter's formula that docs/torsion.md states (FE 5-16 %
    stiffer, as tests/torsion/test_torsion_stiffness.py on the inline-4's throw).  With
    ``throw_stiffness = "carter"`` the study's chain equals the check's too (frequency and
    journal torques, 1e-9, no FE case read), and differs from the FE one: the first mode is
    the flywheel's on its soft coupling (the crank nearly rigid in it), which Carter's 10 %
    softer throws move by a few 1e-6 only, a thousand times the tolerance."""
    res, _, _ = study
    lc = res.loadcase
    assert lc.material is not None and lc.torsion is not None and lc.torsion.throw_stiffness == "fe"
    assert any("FE throw stiffness per candidate" in n for n in res.notes)
    layout, drawn = res.shaft.layout, res.drawn
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    solids = ThrowSolidCache(layout)
    k_carter = carter_throw_stiffness(layout.geometry, shear_modulus(lc.material))
    for cand, written in ((res.results[0].candidate, written_zero), (_all_at_one(res), written_one)):
        lc2, solved, torsion, _, geo, _, cycles2 = written
        by_carter = torsion_stage(_carter(lc2), geo, solved, cycles2)
        for case, ref in ((lc, torsion), (_carter(lc), by_carter)):
            ts = screen_torsion(case, cycles, layout, cand, drawn, res.shaft.mass, solids, None, False, stiffness)
            assert ts.frequency == pytest.approx(float(ref.result.modes.elastic_hz[0]), rel=1e-9, abs=0.0)
            assert ts.dynamics is not None
            for name, tl in ref.dynamics.throws.items():
                mine = ts.dynamics.throws[name]
                for a, b in ((mine.torque_front, tl.torque_front), (mine.torque_rear, tl.torque_rear)):
                    assert np.abs(a - b).max() <= 1e-9 * np.abs(b).max()
            if case is lc:
                assert torsion.result.stiffness["used"] == "fe" and ts.fe_stiffness is not None
                assert ts.fe_stiffness == pytest.approx(torsion.result.stiffness["fe"], rel=1e-9, abs=0.0)
                assert 0.84 < k_carter / ts.fe_stiffness < 0.95
                f_fe = ts.frequency
            else:
                assert ts.fe_stiffness is None
                assert abs(ts.frequency / f_fe - 1.0) > 1e-6
    # one model per distinct written solid: the study's candidates' and the two above
    written = []
    for c in (*(r.candidate for r in res.results), _all_at_one(res)):
        g = written_geometry(layout, c)
        if g not in written:
            written.append(g)
    assert len(stiffness.solved) == len(written) >= 2


def test_validate_takes_q_with_the_fe_throw_stiffness(tmp_path, capsys):
    """With ``throw_stiffness = "fe"`` the study runs each candidate's torsional stage on
    the FE throw stiffness of the geometry it writes: a Q limit is screened, not refused."""
    lc = torsion_case(tmp_path)
    assert 'throw_stiffness = "fe"' in lc.read_text()
    f = tmp_path / "study.toml"
    f.write_text(STUDY)
    rc = main(["validate", str(f), "--loadcase", str(lc)])
    captured = capsys.readouterr()
    assert rc == 0, captured.err
    assert f"ok    {f}" in captured.out and "2 candidates" in captured.out
