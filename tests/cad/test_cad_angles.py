"""CAD route: throw and oil-bore angles in [0, 360) deg (and [0, 180) for a bore's
line): a throw drawn at any angle in the file is its own first throw, at 0 deg, and
round-off of the fitted directions never lists it at 360 deg."""

from __future__ import annotations

import math

import pytest
from helpers.cad_files import _write, plain_throw

from fe_crank.cad import CadInput, feature_lines, recognise
from fe_crank.cad.frame import ANGLE_SNAP, turn_angle
from fe_crank.gmsh_io import gmsh_session


def test_turn_angle_keeps_every_angle_in_one_period():
    assert turn_angle(-1e-17) == 0.0 and turn_angle(1e-17) == 0.0
    assert turn_angle(2 * math.pi) == 0.0
    assert turn_angle(2 * math.pi - 0.5 * ANGLE_SNAP) == 0.0
    assert turn_angle(-math.pi / 2) == pytest.approx(1.5 * math.pi, rel=1e-15)
    assert turn_angle(math.pi - 1e-13, math.pi) == 0.0
    assert turn_angle(7 * math.pi / 3) == pytest.approx(math.pi / 3, rel=1e-14)


@pytest.mark.parametrize("skew", [-1e-9, 17.0, 143.0, 271.3])
def test_a_skew_throw_is_at_0_deg(tmp_path, skew):
    with gmsh_session() as gmsh:
        solid = plain_throw(gmsh)
        gmsh.model.occ.rotate([(3, solid)], 0, 0, 0, 0, 0, 1, math.radians(skew))
        step = _write(gmsh, tmp_path / "skew.step")
    f = recognise(CadInput(step, density=7850.0))
    assert f.throws[0].angle == 0.0
    assert f.throws[0].crank_radius == pytest.approx(0.03, abs=1e-9)
    line = next(s for s in feature_lines(f) if s.startswith("throw 1:"))
    assert line.startswith("throw 1: angle 0 deg,"), line
