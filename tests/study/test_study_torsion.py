"""The counterweight study with a ``[torsion]`` section (docs/study.md): each candidate's
torsional stage on the throws' inertias of the geometry it writes, its first natural
frequency, UR M53's Q with its own vibratory journal torques, its bolted joints with the
torsional angular acceleration and its counterweights' stress with the vibratory loads,
against the check of the load case the study writes for that candidate (two candidates
of different counterweight mass) and the frequency against Holzer's residual computed
here; and the refusal, before meshing, of what the study cannot screen."""

from __future__ import annotations

import dataclasses
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from helpers.bolted_study import bolted_case, torsion_section
from helpers.cw_peak import counterweight_peak
from helpers.paths import DATA

from fe_crank.assess.throw import fe_coefficients
from fe_crank.cli import main
from fe_crank.fe.throw.pin_patches import rod_loads
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.outputs import CaseOutputs, FeModels
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.stages import assess_stage, fe_stage, geometry_stage, mesh_stage
from fe_crank.pipeline.torsion_stage import torsion_stage
from fe_crank.study.bodies import candidate_bodies
from fe_crank.study.candidates import Candidate, ThrowSolidCache, web_shape
from fe_crank.study.joints import candidate_joints
from fe_crank.study.outputs import to_toml, write_candidate, write_tables
from fe_crank.study.run import run_study
from fe_crank.study.spec import JOINT_LIMITS, parse_study
from fe_crank.study.torsion import screen_torsion

TORSION = torsion_section(41)

STUDY = """[study]
name = "small inline-4 with torsion"
rotating_rate_percent = [0, 100]
envelope = "45 mm"
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
def study(tmp_path_factory):
    """The study of the bolted small inline-4 with [torsion], 0 % and 100 % on every web."""
    d = tmp_path_factory.mktemp("torsion_study")
    (d / "study.toml").write_text(STUDY)
    cache = d / "cache"
    res = run_study(load_loadcase(bolted_case(d, TORSION)), parse_study(d / "study.toml"), size="test", cache_dir=cache)
    return res, d, cache


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
    pass)."""
    _, lc_path = write_candidate(res, r, folder)
    data = tomllib.loads(lc_path.read_text())
    data["criteria"] = {"min_m53_acceptability": 1.0}
    if joints:
        data["criteria"] |= {k: 1.0 if k.startswith("max_") else 0.01 for k in JOINT_LIMITS}
    lc_path.write_text(to_toml(data))
    lc = load_loadcase(lc_path)
    geo = geometry_stage(lc, CheckOptions(mesh_size="test", cache_dir=str(cache)))
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    solved = fe_stage(lc, geo, mesh_stage(lc, geo).throws)
    torsion = torsion_stage(lc, geo, solved, cycles)
    out = CaseOutputs(lc, cycles, None, geo, None, FeModels(solved), torsion)
    criteria = {c.quantity: c.value for c in assess_stage(lc, out, False).criteria}
    return lc, solved, torsion, criteria


@pytest.mark.heavy
def test_each_candidates_torsional_figures_equal_the_checks_of_the_written_case(study):
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
    res, d, cache = study
    lc = res.loadcase
    drawn, layout = res.drawn, res.shaft.layout
    shapes = tuple(web_shape(w, 1.0, drawn[w], layout, res.spec, layout.geometry.density) for w in drawn)
    cand = Candidate(99, "all at 1", math.nan, 0.0, 0.0, dict.fromkeys(drawn, 1.0), shapes)
    solids = ThrowSolidCache(layout)
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    ts = screen_torsion(lc, cycles, layout, cand, drawn, res.shaft.mass, solids, res.body_model, True)
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
        r = zero if label == "zero" else dataclasses.replace(res.results[0], candidate=cand)
        lc2, solved, torsion, criteria = _check(res, r, d / f"written_{label}", cache, label == "one")
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


def test_tables_carry_the_frequency_and_the_notes_say_how(study, tmp_path):
    res, _, _ = study
    paths = write_tables(res, tmp_path)
    assert "first_torsional_frequency_hz" in paths["csv"].read_text().splitlines()[0]
    assert "1st torsional natural frequency Hz" in paths["md"].read_text()
    notes = " ".join(res.notes)
    assert "torsional stage per candidate" in notes and "UR M53 Q per candidate" in notes
    assert "torsional angular acceleration" in notes


def test_validate_refuses_q_with_the_fe_throw_stiffness(tmp_path, capsys):
    """With ``throw_stiffness = "fe"`` the chain takes each candidate's own FE stiffness,
    which the study does not solve: a Q limit is refused before meshing."""
    lc = (
        torsion_case(tmp_path)
        .read_text()
        .replace("shaft_loss_factor = 0.025\n", 'shaft_loss_factor = 0.025\nthrow_stiffness = "fe"\n', 1)
    )
    (tmp_path / "small_shaft_torsion.toml").write_text(lc)
    f = tmp_path / "study.toml"
    f.write_text(STUDY)
    rc = main(["validate", str(f), "--loadcase", str(tmp_path / "small_shaft_torsion.toml")])
    err = capsys.readouterr().err
    assert rc == 2, err
    assert str(f) in err and "study.limits.min_m53_acceptability" in err and "throw_stiffness" in err
    assert len(err.strip().splitlines()) == 1
