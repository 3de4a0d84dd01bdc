"""CAD route: a throw of a whole shaft is meshed in its own THROW frame (the crankpin's
centre on +y at the crank radius, z = 0 midway between the webs, the bearing centres at
-+ the half span), whatever its place and angle in the file; ``fe-crank mesh`` takes a
TOML file holding ``[cad]``."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from helpers.cad_files import shaft_step

from fe_crank.cad import CadInput, mesh_cad_throw
from fe_crank.cli import main
from fe_crank.io.geometry import load_geometry

pytestmark = pytest.mark.heavy
ROOT = Path(__file__).resolve().parents[2]


def _nodes(mesh, group: str) -> np.ndarray:
    return mesh.p[:, np.unique(mesh.facets[:, mesh.boundaries[group]])]


def test_the_second_throw_of_a_shaft_is_meshed_in_its_throw_frame(tmp_path):
    g = load_geometry(ROOT / "tests" / "data" / "geometry_small.toml")
    one = dataclasses.replace(g.throws[0], name="1", angle=0.0)
    g = dataclasses.replace(g, throws=(one, dataclasses.replace(one, name="2", angle=math.radians(120))))
    step = shaft_step(g, tmp_path / "shaft.step")  # throw 2 at 120 deg, one throw span along +z
    tm = mesh_cad_throw(CadInput(step, density=g.density, throws=("1", "2")), "2", size="test", cache_dir=tmp_path)
    m = tm.mesh
    pin = _nodes(m, "crankpin")
    assert np.hypot(pin[0], pin[1] - g.crank_radius) == pytest.approx(g.crankpin_diameter / 2, abs=1e-6)
    assert pin[2].min() == pytest.approx(-pin[2].max(), abs=1e-6)
    span = g.crankpin_length / 2 + g.web_thickness + g.journal_length
    assert _nodes(m, "end_1")[2] == pytest.approx(-span, abs=1e-9)
    assert _nodes(m, "end_2")[2] == pytest.approx(span, abs=1e-9)
    journal = _nodes(m, "journal_1")
    assert np.hypot(journal[0], journal[1]) == pytest.approx(g.journal_diameter / 2, abs=1e-6)


def test_fe_crank_mesh_takes_a_cad_file(small_throw_step, mesh_cache, tmp_path, capsys):
    _, step = small_throw_step
    toml = step.parent / "throw_cad.toml"  # beside the file it names
    toml.write_text('[cad]\nfile = "throw.step"\ndensity = "7850 kg/m^3"\n')
    out = tmp_path / "out"
    args = ["mesh", str(toml), "-o", str(out), "--mesh-size", "test", "--no-render", "--cache-dir", str(mesh_cache)]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "crankpin_fillet_1: faces " in text and "throw 1 (CAD):" in text and "quadratic tets" in text
    assert (out / "throw_throw1.msh").is_file() and (out / "throw_throw1.vtu").is_file()
    assert main([*args, "--throw", "7"]) == 2
    assert "--throw: no throw named '7'" in capsys.readouterr().err


def test_the_scf_mode_and_the_convergence_study_mesh_a_cad_throw(small_throw_step, mesh_cache):
    """UR M53 App. III's SCF mode re-meshes the CAD throw at r/4 through ``mesh_cad_throw``
    and takes the nominal stresses at the recognised webs' mid-planes (those of the
    specification); the convergence study refines the CAD throw's fillets.  (The SCFs of
    both routes on this throw at r/4: docs/geometry.md.)"""
    from fe_crank import model
    from fe_crank.assess.throw_geometry import cad_throws
    from fe_crank.cad import recognise
    from fe_crank.fe.refinement.convergence import fillet_convergence
    from fe_crank.io.material import load_material
    from fe_crank.rules.m53.scf_mode import scf_mesh, web_centres_of

    g, step = small_throw_step
    cad = CadInput(step, density=g.density)
    engine = model.Engine("e", 4, (model.Shaft("main"),), (model.Throw("1", "main", 0.0, g.crank_radius),), ())
    tg = cad_throws(recognise(cad), cad, {"1": "1"}, engine, None)["1"]
    assert tg.web_centres == pytest.approx(web_centres_of(g), abs=1e-9)
    tm = mesh_cad_throw(cad, "1", size="test", cache_dir=mesh_cache)
    fine = scf_mesh(tm, cad)
    assert fine.options.fillet_divisions == 4.0 and fine.throw == "1" and fine.key != tm.key
    for name, h in fine.stats.fillet_max_edge.items():
        assert h <= fine.fillet_radii[name] / 4 * (1 + 1e-9)
    material = load_material("42CrMo4")
    study = fillet_convergence(cad, material, throw="1", base=tm.options, factors=(1.0, 1.5), cache_dir=mesh_cache)
    a, b = study.levels
    assert all(b.fillet_max_edge[k] < a.fillet_max_edge[k] for k in a.fillet_max_edge)
