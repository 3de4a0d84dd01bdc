"""CAD route, bad input: one ``InputError`` each, naming the CAD file, the key that
settles it and the reason; nothing is written (the mesh cache stays empty)."""

from __future__ import annotations

import math
import re

import pytest
from helpers.cad_files import _write, parametric_step, turned_step

from fe_crank.cad import CadInput, mesh_cad_throw, recognise
from fe_crank.errors import GeometryError, InputError
from fe_crank.gmsh_io import gmsh_session
from fe_crank.io.geometry import load_geometry


def refused(cad: CadInput, key: str, *words: str, tmp_path=None) -> InputError:
    cache = None if tmp_path is None else tmp_path / "cache"
    with pytest.raises(InputError) as e:
        if cache is None:
            recognise(cad)
        else:
            mesh_cad_throw(cad, size="test", cache_dir=cache)
    err = e.value
    assert err.file == str(cad.file)
    assert err.key == key
    for w in words:
        assert w in str(err), str(err)
    if cache is not None:  # nothing half-written
        assert not cache.exists() or not any(cache.iterdir())
    return err


def cad(path, **kw) -> CadInput:
    return CadInput(path, density=7850.0, **kw)


def test_not_a_step_file_an_empty_file_a_missing_file_and_an_unknown_format(tmp_path):
    p = tmp_path / "crank.step"
    p.write_text("solid crank\nfacet normal 0 0 1\n")
    refused(cad(p), "cad.file", "not a STEP file", tmp_path=tmp_path)
    p.write_bytes(b"")
    refused(cad(p), "cad.file", "empty", tmp_path=tmp_path)
    refused(cad(tmp_path / "none.step"), "cad.file", "not found")
    q = tmp_path / "crank.x_t"
    q.write_text("**PART1;\n")
    refused(cad(q), "cad.file", "STEP (.step, .stp), BREP (.brep) or IGES (.iges)")


def test_a_step_file_that_opencascade_cannot_read(tmp_path):
    p = tmp_path / "crank.step"
    p.write_text("ISO-10303-21;\nHEADER;\nthis is not STEP\n")
    refused(cad(p), "cad.file", "could not read the STEP file", tmp_path=tmp_path)


def test_no_solid(tmp_path):
    with gmsh_session() as gmsh:
        gmsh.model.occ.addRectangle(0, 0, 0, 0.05, 0.02)
        p = _write(gmsh, tmp_path / "face.step")
    refused(cad(p), "cad.file", "holds no solid", "1 loose faces", tmp_path=tmp_path)


def test_two_disjoint_solids(tmp_path):
    with gmsh_session() as gmsh:
        gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 0.1, 0.02)
        gmsh.model.occ.addBox(0.1, 0.1, 0, 0.02, 0.02, 0.02)
        p = _write(gmsh, tmp_path / "two.step")
    refused(cad(p), "cad.bodies", "2 solids", 'bodies = "fuse"', tmp_path=tmp_path)
    refused(cad(p, bodies="fuse"), "cad.bodies", "do not form one solid", "do not touch", tmp_path=tmp_path)


def test_brep_without_a_unit(tmp_path):
    with gmsh_session() as gmsh:
        gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 0.1, 0.02)
        gmsh.model.occ.synchronize()
        p = tmp_path / "shaft.brep"
        gmsh.write(str(p))
    refused(cad(p), "cad.length_unit", "states no length unit", tmp_path=tmp_path)


def test_no_crankpin(tmp_path):
    with gmsh_session() as gmsh:  # a stepped shaft: journals, no throw
        occ = gmsh.model.occ
        occ.fuse([(3, occ.addCylinder(0, 0, 0, 0, 0, 0.1, 0.02))], [(3, occ.addCylinder(0, 0, 0.1, 0, 0, 0.05, 0.03))])
        p = _write(gmsh, tmp_path / "bar.step")
    refused(cad(p), "cad.faces.crankpin", "no crankpin found", tmp_path=tmp_path)


def test_an_ambiguous_axis(tmp_path):
    with gmsh_session() as gmsh:  # two equal parallel bars joined by a plate: no axis has more faces
        occ = gmsh.model.occ
        a = occ.addCylinder(0, 0, 0, 0, 0, 0.1, 0.02)
        b = occ.addCylinder(0, 0.06, 0, 0, 0, 0.1, 0.02)
        plate = occ.addBox(-0.005, 0, 0.04, 0.01, 0.06, 0.02)
        occ.fuse([(3, a)], [(3, b), (3, plate)])
        p = _write(gmsh, tmp_path / "twin.step")
    err = refused(cad(p), "cad.faces.axis", "the crank axis is ambiguous", tmp_path=tmp_path)
    assert re.search(r"\[\d+(, \d+)*\] and \[\d+(, \d+)*\]", str(err))  # both sets by their faces


@pytest.mark.heavy
def test_a_shaft_in_millimetres_stated_as_inches_is_refused_and_length_unit_settles_it(tmp_path, root):
    g = load_geometry(root / "geometry" / "single_cylinder.toml")
    p = parametric_step(g, tmp_path / "crank.step")
    text = p.read_text()
    pattern = r"#(\d+) = \( LENGTH_UNIT\(\) NAMED_UNIT\(\*\) SI_UNIT\(\.MILLI\.,\.METRE\.\) \);"
    assert re.search(pattern, text)

    def inch(m):  # the same unit entity, now the inch of 25.4 mm (ISO 10303-41 conversion-based unit)
        n = int(m.group(1))
        a, b, c = 900000 + 3 * n, 900001 + 3 * n, 900002 + 3 * n
        return (
            f"#{n} = ( CONVERSION_BASED_UNIT('INCH',#{a}) LENGTH_UNIT() NAMED_UNIT(#{b}) );\n"
            f"#{a} = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#{c});\n"
            f"#{b} = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n"
            f"#{c} = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );"
        )

    p.write_text(re.sub(pattern, inch, text))
    err = refused(cad(p), "cad.length_unit", "outside the range of crankshafts", "inch", tmp_path=tmp_path)
    assert "1524 mm" in str(err)  # the 60 mm journal, 25.4 times too large
    t = recognise(cad(p, length_unit=1e-3, length_unit_text="mm")).throws[0]
    assert t.crank_radius == pytest.approx(0.064, abs=1e-9)
    assert t.journals[0].diameter == pytest.approx(0.060, abs=1e-9)


@pytest.mark.heavy
def test_a_mesh_over_the_element_budget_is_refused_before_gmsh_meshes(tmp_path, root):
    g = load_geometry(root / "tests" / "data" / "geometry_small.toml")
    p = parametric_step(g, tmp_path / "throw.step")
    with pytest.raises(GeometryError) as e:
        mesh_cad_throw(cad(p), size="test", cache_dir=tmp_path / "cache", max_elements=1000)
    assert e.value.file == str(p) and "more than the limit" in str(e.value) and "--max-elements" in str(e.value)
    assert not any((tmp_path / "cache").iterdir())  # nothing half-written


@pytest.mark.heavy
def test_a_shaft_drawn_along_x_gives_the_same_throw(tmp_path, root):
    g = load_geometry(root / "tests" / "data" / "geometry_small.toml")
    p = parametric_step(g, tmp_path / "along_z.step")
    along_z = recognise(cad(p)).throws[0]
    along_x = recognise(cad(turned_step(p, tmp_path / "along_x.step", (2, 0, 1)))).throws[0]
    assert along_x.rotation[2] == (1.0, 0.0, 0.0)  # the crank axis: +x of the file
    assert along_x.crank_radius == pytest.approx(along_z.crank_radius, abs=1e-9)
    assert along_x.pin_length == pytest.approx(along_z.pin_length, abs=1e-9)
    for a, b in zip(along_x.fillets, along_z.fillets, strict=True):
        assert (a.name, a.radius) == (b.name, pytest.approx(b.radius, abs=1e-9))
    for part in ("journal_1", "crankpin", "web_2", "total"):
        a = along_x.mass.total if part == "total" else along_x.mass.parts[part]
        b = along_z.mass.total if part == "total" else along_z.mass.parts[part]
        assert a.mass == pytest.approx(b.mass, rel=1e-9)
        assert a.centroid == pytest.approx(b.centroid, abs=1e-9)
        assert a.inertia_axis == pytest.approx(b.inertia_axis, rel=1e-9)


@pytest.mark.heavy
def test_an_oblique_axis_is_refused_with_what_to_do(tmp_path, root):
    g = load_geometry(root / "tests" / "data" / "geometry_small.toml")
    from fe_crank.geometry.solid import throw_solid

    axis = (math.sin(0.4) * math.cos(0.3), math.sin(0.4) * math.sin(0.3), math.cos(0.4))
    with gmsh_session() as gmsh:
        solid, _ = throw_solid(g)
        occ = gmsh.model.occ
        # turn z into ``axis`` (about the normal of both), then move the shaft away from the origin
        occ.rotate([(3, solid)], 0, 0, 0, -axis[1], axis[0], 0.0, 0.4)
        occ.translate([(3, solid)], 0.3, -0.2, 0.1)
        p = _write(gmsh, tmp_path / "oblique.step")
    refused(cad(p), "cad.axis", "along none of the file's coordinate axes", tmp_path=tmp_path)
    # its web faces are off the planes normal to the axis by round-off: no exact split
    refused(cad(p, axis=axis), "cad.file", "along a coordinate axis of the file", tmp_path=tmp_path)


def test_a_step_file_with_an_empty_data_section_holds_no_solid(tmp_path):
    p = tmp_path / "empty.step"
    p.write_text(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('empty','',(''),(''),'','','');\n"
        "FILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n"
    )
    err = refused(cad(p), "cad.file", "holds no solid", "no geometry at all", tmp_path=tmp_path)
    assert "length" not in str(err)


def test_a_triangulated_surface_is_not_a_cad_solid(tmp_path):
    for suffix, name in ((".stl", "STL"), (".obj", "OBJ")):
        q = tmp_path / f"crank{suffix}"
        q.write_text("solid crank\nendsolid crank\n")
        refused(cad(q), "cad.file", f"{name} is not supported (a CAD solid is needed: STEP, BREP or IGES)")
