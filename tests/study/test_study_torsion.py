"""The counterweight study with a ``[torsion]`` section (docs/study.md): each candidate's
torsional stage on the throws' inertias of the geometry it writes, its first natural
frequency and UR M53's Q with its own vibratory journal torques, against the check's
torsional stage of the load case the study writes for that candidate (two candidates of
different counterweight mass) and against Holzer's residual computed here; and the
refusal, before meshing, of what the study cannot screen."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from helpers.paths import DATA

from fe_crank.cli import main
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.stages import fe_stage, geometry_stage, mesh_stage
from fe_crank.pipeline.torsion_stage import torsion_stage
from fe_crank.study.m53 import study_m53
from fe_crank.study.outputs import write_candidate, write_tables
from fe_crank.study.run import run_study
from fe_crank.study.spec import parse_study

TORSION = """min_m53_acceptability = 1.0

[torsion]
speed_range = ["2000 rpm", "4800 rpm"]
speed_steps = 41
shaft_loss_factor = 0.025
cylinder_damping = "0.05 N*m*s/rad"

[torsion.flywheel]
inertia = "0.02 kg*m^2"
stiffness = "5e4 N*m/rad"

[[torsion.driven]]
name = "brake"
inertia = "0.01 kg*m^2"
stiffness = "2e3 N*m/rad"
loss_factor = 0.2
"""

STUDY = """[study]
name = "small inline-4 with torsion"
rotating_rate_percent = [0, 100]
envelope = "45 mm"
stresses = "off"
[study.limits]
min_m53_acceptability = 1.0
[[study.placements]]
name = "8"
webs = "all"
"""


def torsion_case(folder: Path, extra: str = "") -> Path:
    """tests/data/small_shaft.toml (the small inline-4, a counterweight on every web) with a
    ``[torsion]`` section (flywheel and a brake on a soft coupling), written into ``folder``."""
    (folder / "geometry_small_shaft.toml").write_text((DATA / "geometry_small_shaft.toml").read_text())
    path = folder / "small_shaft_torsion.toml"
    path.write_text((DATA / "small_shaft.toml").read_text() + TORSION + extra)
    return path


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    d = tmp_path_factory.mktemp("torsion_study")
    (d / "study.toml").write_text(STUDY)
    cache = d / "cache"
    res = run_study(load_loadcase(torsion_case(d)), parse_study(d / "study.toml"), size="test", cache_dir=cache)
    return res, d, cache


def _holzer_residual(inertia: np.ndarray, stiffness: np.ndarray, omega: float) -> float:
    """The torque left after the last mass of a free-free chain (Den Hartog sec. 5.5)."""
    theta, torque = 1.0, 0.0
    for i, j in enumerate(inertia):
        torque += omega**2 * j * theta
        if i < stiffness.size:
            theta -= torque / stiffness[i]
    return torque


@pytest.mark.heavy
def test_frequency_and_q_of_each_candidate_equal_the_checks_of_the_written_case(study):
    """For the 0 % and 100 % candidates (no counterweight, every web's drawn one at full
    rate: different shaft inertias), the check's torsional stage (``pipeline.torsion_stage``
    after its geometry, mesh and FE stages, ``test`` mesh) of the load case the study writes
    gives the study's first natural frequency to 1e-9, and UR M53's Q on the check's
    torsional loads (``study.m53.study_m53``, the function the no-torsion test holds equal
    to the check's ``min_m53_acceptability``) is the study's to 1e-9.  The frequency is a
    root of Holzer's residual of the check's chain (computed here, no eigenproblem), and
    the chains differ by the two candidates' polar-inertia change (exact mass properties,
    ``study.candidates.written_mass``) on the throws."""
    res, d, cache = study
    assert len(res.results) == 2
    masses = [r.counterweight_mass for r in res.results]
    assert masses[0] == 0.0 and masses[1] > 0.1
    chains = []
    for r in res.results:
        assert r.torsional_frequency is not None and r.m53 is not None
        _, lc_path = write_candidate(res, r, d / f"written_{r.candidate.index}")
        lc2 = load_loadcase(lc_path)
        geo = geometry_stage(lc2, CheckOptions(mesh_size="test", cache_dir=str(cache)))
        cycles = engine_cycles(lc2.engine, lc2.operating, file=lc2.source_file)
        out = torsion_stage(lc2, geo, fe_stage(lc2, geo, mesh_stage(lc2, geo).throws), cycles)
        f_check = float(out.result.modes.elastic_hz[0])
        assert r.torsional_frequency == pytest.approx(f_check, rel=1e-9, abs=0.0)
        assert out.loads is not None
        q = study_m53(lc2, cycles, out.loads)
        assert q is not None and r.m53.acceptability == pytest.approx(q.acceptability, rel=1e-9, abs=0.0)
        model = out.result.model
        w = 2 * math.pi * r.torsional_frequency
        scale = w**2 * float(model.inertia.sum())
        assert abs(_holzer_residual(model.inertia, model.stiffness, w)) <= 1e-8 * scale
        # no root below it: the residual keeps its sign from 0+ to just under f1
        below = [_holzer_residual(model.inertia, model.stiffness, x * w) for x in np.linspace(0.05, 0.98, 40)]
        assert all(v > 0 for v in below) or all(v < 0 for v in below)
        chains.append(model)
    names = [t.name for t in res.shaft.layout.throws]
    dj = sum(chains[1].inertia[chains[1].throw_mass[n]] - chains[0].inertia[chains[0].throw_mass[n]] for n in names)
    want = res.results[1].polar_inertia_change - res.results[0].polar_inertia_change
    assert dj == pytest.approx(want, rel=1e-9)
    assert res.results[0].torsional_frequency != res.results[1].torsional_frequency


def test_tables_carry_the_frequency_and_the_notes_say_how(study, tmp_path):
    res, _, _ = study
    paths = write_tables(res, tmp_path)
    assert "first_torsional_frequency_hz" in paths["csv"].read_text().splitlines()[0]
    assert "1st torsional natural frequency Hz" in paths["md"].read_text()
    notes = " ".join(res.notes)
    assert "torsional stage per candidate" in notes and "UR M53 Q per candidate" in notes


def test_validate_refuses_q_with_the_fe_throw_stiffness(tmp_path, capsys):
    """With ``throw_stiffness = "fe"`` the chain takes each candidate's own FE stiffness,
    which the study does not solve: a Q limit is refused before meshing."""
    lc = (
        torsion_case(tmp_path, "")
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
