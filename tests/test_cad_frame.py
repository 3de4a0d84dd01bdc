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
from cad_files import parametric_step, shaft_step

from fe_crank.cad import CadInput, mesh_cad_throw
from fe_crank.cli import main
from fe_crank.io.geometry import load_geometry

pytestmark = pytest.mark.heavy
ROOT = Path(__file__).resolve().parents[1]


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


def test_fe_crank_mesh_takes_a_cad_file(tmp_path, capsys):
    g = load_geometry(ROOT / "tests" / "data" / "geometry_small.toml")
    parametric_step(g, tmp_path / "throw.step")
    toml = tmp_path / "throw_cad.toml"
    toml.write_text('[cad]\nfile = "throw.step"\ndensity = "7850 kg/m^3"\n')
    out = tmp_path / "out"
    args = ["mesh", str(toml), "-o", str(out), "--mesh-size", "test", "--no-render", "--cache-dir", str(tmp_path)]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "crankpin_fillet_1: faces " in text and "throw 1 (CAD):" in text and "quadratic tets" in text
    assert (out / "throw_throw1.msh").is_file() and (out / "throw_throw1.vtu").is_file()
    assert main([*args, "--throw", "7"]) == 2
    assert "--throw: no throw named '7'" in capsys.readouterr().err
