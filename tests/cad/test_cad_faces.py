"""CAD route, ``[cad.faces]``: where a rule cannot decide, one message names the faces
in doubt and the key; naming the faces settles it and gives the features the rules give
on a file without the doubt."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers.cad_files import parametric_step, pegged_step

from fe_crank.cad import CadInput, FaceOverride, recognise
from fe_crank.cad.survey import survey
from fe_crank.errors import InputError
from fe_crank.gmsh_io import gmsh_session
from fe_crank.io.geometry import load_geometry

pytestmark = pytest.mark.heavy


def _face(path, kind, radius, centre_xy) -> int:
    """The face of ``kind`` and ``radius`` whose axis passes through ``centre_xy``."""
    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        gmsh.model.occ.importShapes(str(path))
        gmsh.model.occ.synchronize()
        faces = survey(gmsh, [t for _, t in gmsh.model.getEntities(2)], 1e-9)
    hits = [
        f.tag
        for f in faces.values()
        if f.kind == kind
        and abs(f.radius - radius) < 1e-9
        and np.linalg.norm(np.cross(f.origin - [*centre_xy, 0.0], f.direction)) < 1e-9
    ]
    assert len(hits) == 1, hits
    return hits[0]


@pytest.fixture(scope="module")
def small():
    from pathlib import Path

    return load_geometry(Path(__file__).resolve().parents[2] / "tests" / "data" / "geometry_small.toml")


def test_a_peg_like_a_crankpin_is_refused_until_the_crankpins_are_named(small, tmp_path):
    g = small
    plain = recognise(CadInput(parametric_step(g, tmp_path / "plain.step"), density=g.density)).throws[0]
    path = pegged_step(g, tmp_path / "pegged.step")
    peg = _face(path, "cylinder", 0.003, (0.014, 0.025))
    with pytest.raises(InputError) as e:
        recognise(CadInput(path, density=g.density))
    assert e.value.key == "cad.faces.crankpin" and e.value.file == str(path)
    assert f"the cylinder [{peg}] parallel to the crank axis" in str(e.value) and "no web behind" in str(e.value)
    pin = _face(path, "cylinder", g.crankpin_diameter / 2, (0.0, g.crank_radius))
    named = CadInput(path, density=g.density, faces=(FaceOverride("crankpin", (pin,)),))
    t = recognise(named).throws[0]
    assert t.crankpin.faces == (pin,)
    assert t.crank_radius == pytest.approx(plain.crank_radius, abs=1e-9)
    assert [f.radius for f in t.fillets] == pytest.approx([f.radius for f in plain.fillets], abs=1e-9)
    # the peg's material is part of web 1's side of the model (journal 1's slab): more mass than the plain throw
    assert t.mass.total.mass > plain.mass.total.mass


def test_naming_a_fillets_faces(small, tmp_path):
    g = small
    path = parametric_step(g, tmp_path / "throw.step")
    auto = recognise(CadInput(path, density=g.density)).throws[0]
    f1 = auto.fillet("crankpin_fillet_1")
    named = CadInput(path, density=g.density, faces=(FaceOverride("crankpin_fillet_1", f1.faces),))
    t = recognise(named).throws[0]
    assert t.fillet("crankpin_fillet_1") == f1 and t.webs == auto.webs
    wrong = dataclasses.replace(named, faces=(FaceOverride("crankpin_fillet_1", auto.crankpin.faces),))
    with pytest.raises(InputError) as e:  # the pin's own face is no fillet: it meets no web face beyond the pin
        recognise(wrong)
    assert e.value.key == "cad.faces.crankpin_fillet_1" and "meet no web face" in str(e.value)
    missing = dataclasses.replace(named, faces=(FaceOverride("oil_bore", (9999,)),))
    with pytest.raises(InputError) as e:
        recognise(missing)
    assert e.value.key == "cad.faces.oil_bore" and "[9999] are not holes" in str(e.value)
    none = dataclasses.replace(named, faces=(FaceOverride("oil_bore", ()),))
    assert recognise(none).throws[0].oil_bores == ()  # oil_bore = []: the throw has none
