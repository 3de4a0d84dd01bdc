"""CAD route: mass properties exact whatever unit the file's numbers are in.

A throw with annular-sector counterweights written as STEP in millimetres (its own
unit), then the same solid as a BREP in millimetres (no unit in the format:
``length_unit``) and as a STEP whose header states metres while its numbers are
millimetres (``length_unit`` overrides it): every mass property equals the STEP's in
its own unit to 1e-6.  Read with ``length_unit = "cm"`` the solid is ten times larger:
volume x 1e3, m r x 1e4, inertia x 1e5 (the powers of a similarity)."""

from __future__ import annotations

import pytest
from helpers.cad_files import sector_throw_step

from fe_crank.cad import CadInput, recognise
from fe_crank.gmsh_io import gmsh_session


def cad(path, **kw) -> CadInput:
    return CadInput(path, density=7850.0, **kw)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("units")
    step = sector_throw_step(d / "throw.step")
    text = step.read_text()
    assert text.count("SI_UNIT(.MILLI.,.METRE.)") == 1
    wrong = d / "throw_wrong_header.step"
    wrong.write_text(text.replace("SI_UNIT(.MILLI.,.METRE.)", "SI_UNIT($,.METRE.)"))
    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "MM")
        gmsh.model.occ.importShapes(str(step))
        gmsh.model.occ.synchronize()
        x0, _, _, x1, _, _ = gmsh.model.getBoundingBox(-1, -1)
        assert x1 - x0 > 50  # numbers in millimetres
        brep = d / "throw.brep"
        gmsh.write(str(brep))
    return step, wrong, brep


def _props(features):
    t = features.throws[0]
    cws = {c.web: c.mass for c in t.counterweights}
    assert sorted(cws) == [1, 2]
    return t.mass.total, cws


def test_a_brep_and_an_overridden_unit_give_the_step_s_own_mass_properties(files):
    step, wrong, brep = files
    ref, ref_cw = _props(recognise(cad(step)))
    for path in (brep, wrong):
        got, cw = _props(recognise(cad(path, length_unit=1e-3, length_unit_text="mm")))
        assert got.volume == pytest.approx(ref.volume, rel=1e-6)
        assert got.mass == pytest.approx(ref.mass, rel=1e-6)
        assert got.inertia_axis == pytest.approx(ref.inertia_axis, rel=1e-6)
        for web in (1, 2):
            assert cw[web].unbalance == pytest.approx(ref_cw[web].unbalance, rel=1e-6)
            assert cw[web].mass == pytest.approx(ref_cw[web].mass, rel=1e-6)


def test_a_larger_unit_scales_by_the_powers_of_a_similarity(files):
    step, _, _ = files
    ref, ref_cw = _props(recognise(cad(step)))
    got, cw = _props(recognise(cad(step, length_unit=1e-2, length_unit_text="cm")))
    assert got.volume == pytest.approx(1e3 * ref.volume, rel=1e-6)
    assert got.inertia_axis == pytest.approx(1e5 * ref.inertia_axis, rel=1e-6)
    for web in (1, 2):
        assert cw[web].unbalance == pytest.approx(1e4 * ref_cw[web].unbalance, rel=1e-6)
