"""CAD route, bad input through ``fe-crank validate``: every wrong CAD geometry of a load
case is one message on stderr naming the file, the key that settles it and the reason,
exit code 2, nothing written; ``validate`` reads and recognises the file and checks it
against the engine as the check's geometry stage does.  A right one is "ok"."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import pytest
from helpers.cad_files import _write, cad_loadcase, sector_throw_step
from helpers.shared import copy_of

from fe_crank.cad import CadInput, recognise
from fe_crank.cad.engine import engine_keys
from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.gmsh_io import gmsh_session
from fe_crank.io.engine import load_engine
from fe_crank.io.geometry import load_geometry
from fe_crank.throw_scope import ALL_THROWS

ROOT = Path(__file__).resolve().parents[2]
SMALL = ROOT / "tests" / "data" / "geometry_small.toml"


def refused(capsys, lc: Path, file: Path, key: str, *words: str) -> str:
    """``fe-crank validate lc`` exits 2 with one line naming ``file`` and ``key``."""
    before = sorted(p.name for p in lc.parent.iterdir())
    assert main(["validate", str(lc)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert err.startswith(f"error {file}: {key}: "), err
    for w in words:
        assert w in err, err
    assert sorted(p.name for p in lc.parent.iterdir()) == before  # nothing written
    return err


@pytest.fixture(scope="module")
def small_step(small_throw_step) -> Path:
    """The run's export of ``tests/data/geometry_small.toml``'s throw (``tests/cad/conftest.py``)."""
    return small_throw_step[1]


def test_a_cad_load_case_is_valid(tmp_path, small_step, capsys):
    (tmp_path / "throw.step").write_bytes(small_step.read_bytes())
    lc = cad_loadcase(tmp_path, "throw.step")
    assert main(["validate", str(lc)]) == 0
    out = capsys.readouterr().out
    assert "STEP file throw.step: 1 throw(s) recognised, crank radius 20 mm" in out
    # the same through a TOML file holding [cad]
    (tmp_path / "throw_cad.toml").write_text('[cad]\nfile = "throw.step"\ndensity = "7850 kg/m^3"\n')
    text = lc.read_text().replace('geometry = "throw.step"', 'geometry = "throw_cad.toml"')
    lc2 = tmp_path / "case2.toml"
    lc2.write_text(re.sub(r"\[cad\]\ndensity = [^\n]*\n", "", text))
    assert main(["validate", str(lc2), str(tmp_path / "throw_cad.toml")]) == 0
    out = capsys.readouterr().out
    assert out.count("1 throw(s) recognised") == 2 and out.startswith("ok ")


def test_not_a_step_file_an_empty_one_and_a_missing_one(tmp_path, capsys):
    p = tmp_path / "crank.step"
    p.write_text("solid crank\nfacet normal 0 0 1\n")
    lc = cad_loadcase(tmp_path, "crank.step")
    refused(capsys, lc, p, "geometry", "not a STEP file")
    p.write_bytes(b"")
    refused(capsys, lc, p, "geometry", "the CAD file is empty")
    p.unlink()
    refused(capsys, lc, p, "geometry", "not found")


def test_a_triangulated_surface_as_the_geometry(tmp_path, capsys):
    p = tmp_path / "crank.stl"
    p.write_text("solid crank\nendsolid crank\n")
    lc = cad_loadcase(tmp_path, "crank.stl")  # with its [cad] section
    refused(capsys, lc, lc, "geometry", "STL is not supported (a CAD solid is needed: STEP, BREP or IGES)")
    lc.write_text(lc.read_text().replace('[cad]\ndensity = "7850 kg/m^3"\n', ""))
    refused(capsys, lc, lc, "geometry", "STL is not supported (a CAD solid is needed: STEP, BREP or IGES)")
    (tmp_path / "crank_cad.toml").write_text('[cad]\nfile = "crank.stl"\ndensity = "7850 kg/m^3"\n')
    lc.write_text(lc.read_text().replace('geometry = "crank.stl"', 'geometry = "crank_cad.toml"'))
    refused(capsys, lc, p, "cad.file", "STL is not supported")


def test_an_empty_data_section_holds_no_solid(tmp_path, capsys):
    p = tmp_path / "empty.step"
    p.write_text("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\nENDSEC;\nEND-ISO-10303-21;\n")
    err = refused(capsys, cad_loadcase(tmp_path, "empty.step"), p, "geometry", "holds no solid")
    assert "length" not in err


def test_no_solid_and_two_disjoint_solids(tmp_path, capsys):
    with gmsh_session() as gmsh:
        gmsh.model.occ.addRectangle(0, 0, 0, 0.05, 0.02)
        face = _write(gmsh, tmp_path / "face.step")
    refused(capsys, cad_loadcase(tmp_path, "face.step"), face, "geometry", "holds no solid")
    with gmsh_session() as gmsh:
        gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, 0.1, 0.02)
        gmsh.model.occ.addBox(0.1, 0.1, 0, 0.02, 0.02, 0.02)
        two = _write(gmsh, tmp_path / "two.step")
    refused(capsys, cad_loadcase(tmp_path, "two.step"), two, "cad.bodies", "2 solids", 'bodies = "fuse"')
    lc = cad_loadcase(tmp_path, "two.step", cad='density = "7850 kg/m^3"\nbodies = "fuse"')
    refused(capsys, lc, two, "cad.bodies", "do not form one solid")


def test_a_shaft_without_a_crankpin(tmp_path, capsys):
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        occ.fuse([(3, occ.addCylinder(0, 0, 0, 0, 0, 0.1, 0.02))], [(3, occ.addCylinder(0, 0, 0.1, 0, 0, 0.05, 0.03))])
        bar = _write(gmsh, tmp_path / "bar.step")
    refused(capsys, cad_loadcase(tmp_path, "bar.step"), bar, "cad.faces.crankpin", "no crankpin found")


def _in_inches(step: Path) -> None:
    """The file's numbers stay millimetres, its unit entity becomes the inch (ISO 10303-41
    conversion-based unit): a shaft 25.4 times too large."""
    text = step.read_text()
    pattern = r"#(\d+) = \( LENGTH_UNIT\(\) NAMED_UNIT\(\*\) SI_UNIT\(\.MILLI\.,\.METRE\.\) \);"

    def inch(m):
        n = int(m.group(1))
        a, b, c = 900000 + 3 * n, 900001 + 3 * n, 900002 + 3 * n
        return (
            f"#{n} = ( CONVERSION_BASED_UNIT('INCH',#{a}) LENGTH_UNIT() NAMED_UNIT(#{b}) );\n"
            f"#{a} = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#{c});\n"
            f"#{b} = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n"
            f"#{c} = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );"
        )

    assert re.search(pattern, text)
    step.write_text(re.sub(pattern, inch, text))


def test_a_step_file_25_times_too_large_is_refused_against_the_engine(tmp_path, small_step, capsys):
    # the small throw in inches is within the plausible sizes (an 813 mm journal), so the
    # engine's stroke catches it
    p = tmp_path / "throw.step"
    p.write_bytes(small_step.read_bytes())
    _in_inches(p)
    lc = cad_loadcase(tmp_path, "throw.step")
    err = refused(capsys, lc, p, "cad.length_unit", "508 mm", "20 mm", "25.4 times the engine's", "engine.throws[0]")
    assert str(lc) in err  # where length_unit goes
    lc = cad_loadcase(tmp_path, "throw.step", cad='density = "7850 kg/m^3"\nlength_unit = "mm"')
    assert main(["validate", str(lc)]) == 0


def test_a_crank_radius_other_than_the_engines(tmp_path, small_step, capsys):
    (tmp_path / "throw.step").write_bytes(small_step.read_bytes())
    lc = cad_loadcase(tmp_path, "throw.step", radius="25 mm")
    refused(capsys, lc, tmp_path / "throw.step", "geometry", "crank radius of 20 mm", "one of 25 mm", "not the shaft")


def test_the_load_cases_cad_keys(tmp_path, small_step, capsys):
    (tmp_path / "throw.step").write_bytes(small_step.read_bytes())
    lc = cad_loadcase(tmp_path, "throw.step")
    text = lc.read_text()
    lc.write_text(text.replace('[cad]\ndensity = "7850 kg/m^3"\n', ""))
    refused(capsys, lc, lc, "cad", "needs a [cad] table", "length unit")
    lc.write_text(text.replace("[cad]\n", '[cad]\nfile = "throw.step"\n'))
    refused(capsys, lc, lc, "cad.file", "geometry names the CAD file")
    lc.write_text(text.replace('geometry = "throw.step"\n', ""))
    refused(capsys, lc, lc, "geometry", "add geometry")
    lc.write_text(text.replace('geometry = "throw.step"', f'geometry = "{SMALL.name}"'))
    (tmp_path / SMALL.name).write_bytes(SMALL.read_bytes())
    refused(capsys, lc, lc, "cad", "goes with a CAD file")
    lc.write_text(text.replace('density = "7850 kg/m^3"', 'density = "-7850 kg/m^3"'))
    refused(capsys, lc, lc, "cad.density", "density must be positive")
    torsion = (ROOT / "tests" / "data" / "small_torsion.toml").read_text()
    lc.write_text(text + "\n" + torsion[torsion.index("[torsion]") :])
    refused(capsys, lc, lc, "torsion", "with a CAD geometry it is not available")


def test_a_counterweight_stress_criterion_on_a_sharp_counterweight(tmp_path, capsys):
    sector_throw_step(tmp_path / "sector.step")  # annular sectors without transition fillets
    lc = cad_loadcase(tmp_path, "sector.step", radius="30 mm", criteria='max_counterweight_stress = "200 MPa"')
    refused(capsys, lc, lc, "criteria.max_counterweight_stress", "sharp edge", "sector.step", "counterweight_1")


@pytest.mark.heavy
def test_a_whole_shaft_against_the_engines_throws(tmp_path, inline4_drawing, inline4_throw_step):
    """The run's one drawing of the inline-4 (``tests/cad/conftest.py``: its throws 92 mm
    apart, as the engine puts them) against its engine and engines that differ."""
    g = load_geometry(ROOT / "geometry" / "inline4.toml")
    engine = load_engine(ROOT / "engines" / "inline4.toml")
    _, shared_step, f = inline4_drawing
    step = copy_of(shared_step, tmp_path / shared_step.name)
    cad = CadInput(step, density=g.density)
    kw = dict(engine_file="engines/inline4.toml", loadcase="loadcases/x.toml")
    assert engine_keys(f, cad, engine, **kw) == {n: n for n in ("1", "2", "3", "4")}
    turned = dataclasses.replace(
        engine, throws=tuple(dataclasses.replace(t, angle=math.pi / 2) if t.name == "2" else t for t in engine.throws)
    )
    with pytest.raises(InputError) as e:
        engine_keys(f, cad, turned, **kw)
    assert e.value.key == "cad.throws" and e.value.file == str(step)
    assert "throw 2 of the CAD file has its crankpin at 180 deg" in str(e.value) and "the engine's at 90 deg" in str(
        e.value
    )
    assert "throws[1].angle" in str(e.value)
    three = dataclasses.replace(engine, throws=engine.throws[:3])
    with pytest.raises(InputError, match=r"holds 4 throws, named \['1', '2', '3', '4'\].*the engine 3") as e:
        engine_keys(f, cad, three, **kw)
    assert e.value.key == "cad.throws"
    # one throw of the file stands for every throw of the engine
    one = recognise(CadInput(inline4_throw_step[1], density=g.density))  # the run's export (tests/cad/conftest.py)
    assert engine_keys(one, cad, engine, **kw) == {ALL_THROWS: "1"}


def test_a_refused_cad_case_in_the_check_writes_its_error_and_nothing_else(tmp_path):
    from fe_crank.pipeline import CheckOptions
    from fe_crank.pipeline.case import run_case

    (tmp_path / "empty.step").write_bytes(b"")
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        occ.fuse([(3, occ.addCylinder(0, 0, 0, 0, 0, 0.1, 0.02))], [(3, occ.addCylinder(0, 0, 0.1, 0, 0, 0.05, 0.03))])
        _write(gmsh, tmp_path / "bar.step")
    opts = CheckOptions(mesh_size="test", cache_dir=str(tmp_path / "cache"), render=False, write_vtu=False)
    out = tmp_path / "reports"
    for step, stage, words in (
        ("empty.step", "load", "the CAD file is empty"),
        ("bar.step", "geometry", "no crankpin"),
    ):
        r = run_case(cad_loadcase(tmp_path, step, name=f"{Path(step).stem}.toml"), out, opts)
        assert (r.status, r.error_stage) == ("error", stage) and words in r.message
        names = {p.name for p in Path(r.folder).iterdir()}  # the report of the stages that ran, no results
        assert {"case.json", "report.html"} <= names and not {n for n in names if n.endswith((".json", ".vtu"))} - {
            "case.json"
        }
    assert sorted(p.name for p in out.iterdir()) == ["bar", "empty"]  # no partial folders
    assert not (tmp_path / "cache").exists() or not any((tmp_path / "cache").iterdir())


def test_a_main_bearing_criterion_is_refused_before_meshing(tmp_path, small_step, capsys):
    from fe_crank.assess.criteria.judge import EVALUATORS
    from fe_crank.assess.criteria.models import no_throw_value
    from fe_crank.io.loadcase import WHOLE_SHAFT_QUANTITIES

    assert sorted(WHOLE_SHAFT_QUANTITIES) == sorted(q for q, ev in EVALUATORS.items() if ev.find is no_throw_value)
    (tmp_path / "throw.step").write_bytes(small_step.read_bytes())
    lc = cad_loadcase(tmp_path, "throw.step", criteria='max_main_bearing_load = "20 kN"')
    refused(capsys, lc, lc, "criteria.max_main_bearing_load", "whole-shaft model", "throw.step")


def test_a_file_recognised_again_with_the_same_bytes_and_keys_is_not_read_again(small_throw_step, tmp_path):
    """``validate`` and the check of one load case recognise its drawing once: the same
    bytes under the same name with the same describing keys give the same features, whatever
    folder, TOML file or bearings (the whole-shaft stage's) name them; another density or
    other bytes are recognised anew."""
    g, step = small_throw_step
    first = recognise(CadInput(step, density=g.density))
    moved = copy_of(step, tmp_path / step.name)
    assert recognise(CadInput(moved, density=g.density, toml=str(tmp_path / "c.toml"), bearing_width=0.02)) is first
    heavier = recognise(CadInput(step, density=2 * g.density))
    assert heavier.throws[0].mass.total.mass == pytest.approx(2 * first.throws[0].mass.total.mass, rel=1e-12)
    moved.write_bytes(step.read_bytes() + b"\n")  # other bytes, the same solid
    changed = recognise(CadInput(moved, density=g.density))
    assert changed is not first and changed.source.sha256 != first.source.sha256
    assert changed.throws == first.throws
