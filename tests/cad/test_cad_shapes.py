"""CAD route on shapes the parametric generator cannot make, end to end: recognition, the
mesh with its named groups and fillet rule, the FE unit cases, the features' report;
the counterweight's mass against a closed form and an independent OpenCASCADE
construction; BREP and IGES files of a throw."""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import subprocess
import sys

import numpy as np
import pytest
from helpers.cad_files import lightened_throw_step, parametric_step, recessed_throw_step, sector_throw_step
from helpers.shared import copy_of, locked, shared_file

from fe_crank.assess.cad_inputs import m53_geometry_of_cad, m53_scope
from fe_crank.assess.group.nodes import assessed_groups
from fe_crank.cad import CadInput, cad_record, feature_lines, mesh_cad_throw, recognise
from fe_crank.errors import InputError
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.gmsh_io import gmsh_session
from fe_crank.io.geometry import load_geometry
from fe_crank.mesh import MeshOptions

pytestmark = pytest.mark.heavy
RHO = 7850.0
CASES = ("centrifugal", "pin_y", "torque")


@dataclasses.dataclass(frozen=True)
class Steel:
    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3
    density: float = RHO


def test_an_annular_sector_beyond_the_web_is_the_counterweight(tmp_path):
    r0, r1, angle, t = 0.03, 0.06, math.radians(160), 0.014
    f = recognise(CadInput(sector_throw_step(tmp_path / "sector.step", r1=r1, angle=angle), density=RHO))
    th = f.throws[0]
    # annular sector r0..r1, angle a, thickness t: m = rho t a (r1^2 - r0^2)/2, centroid at
    # (2/3) (r1^3 - r0^3)/(r1^2 - r0^2) sin(a/2)/(a/2) from the axis: m r = (2/3) rho t sin(a/2) (r1^3 - r0^3)
    m = RHO * t * angle / 2 * (r1**2 - r0**2)
    mr = RHO * t * 2 / 3 * math.sin(angle / 2) * (r1**3 - r0**3)
    assert [c.web for c in th.counterweights] == [1, 2]
    for c in th.counterweights:
        assert c.radius == pytest.approx(r0, abs=1e-9)
        assert c.mass.mass == pytest.approx(m, rel=1e-6)
        assert c.mass.unbalance == pytest.approx(mr, rel=1e-6)
        assert c.mass.unbalance_vector[1] < 0 and c.fillet_radius is None  # on -y; no transition fillet


@pytest.fixture(scope="module")
def lightened(tmp_path_factory):
    """The lightened throw, from the one export of it in the run that
    tests/cad/test_cad_check.py checks too (``helpers.shared``)."""
    p = shared_file(tmp_path_factory, "lightened.step", lightened_throw_step)
    return CadInput(copy_of(p, tmp_path_factory.mktemp("cad") / "lightened.step"), density=RHO)


def _region_mass(path, web_range, radius):
    """Mass and m r (x, y) of the solid at y < 0 beyond ``radius`` with z in ``web_range``,
    built here with OpenCASCADE booleans (the file's frame is the throw frame)."""
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        (solid,) = occ.importShapes(str(path))
        z0, z1 = web_range
        box = occ.addBox(-1, -1, z0, 2, 1, z1 - z0)
        cyl = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, radius)
        region, _ = occ.cut([(3, box)], [(3, cyl)])
        out, _ = occ.intersect([solid], region)
        occ.synchronize()
        v = sum(occ.getMass(3, t) for _, t in out)
        c = sum(occ.getMass(3, t) * np.array(occ.getCenterOfMass(3, t)) for _, t in out) / v
        return RHO * v, RHO * v * c[:2]


def test_a_trapezoidal_counterweight_and_lightening_holes_recognised(lightened):
    f = recognise(lightened)
    th = f.throws[0]
    assert [fl.radius for fl in th.fillets] == pytest.approx([0.003] * 4, abs=1e-9)
    assert th.oil_bores == ()  # the holes open on the webs only: no oil bore
    for w in th.webs:
        assert w.side_radius == pytest.approx(0.036, abs=1e-9)
        assert w.width == pytest.approx(0.072, abs=1e-9)  # across the web at y = 16.5 mm, the hole inside it
        # the line y = 16.5 mm crosses each 8 mm hole (centre y = 14 mm) over 2 sqrt(4^2 - 2.5^2) mm
        assert w.solid_width == pytest.approx(0.072 - 4 * math.sqrt(0.004**2 - 0.0025**2), abs=1e-9)
    assert m53_geometry_of_cad(th, lightened) is None and "opening" in m53_scope(th)
    for c, web_range in zip(th.counterweights, ((-0.027, -0.013), (0.013, 0.027)), strict=True):
        assert c.fillet_radius == pytest.approx(0.004, abs=1e-9) and len(c.fillet_faces) == 2
        m, mr = _region_mass(lightened.file, web_range, c.radius)
        assert c.mass.mass == pytest.approx(m, rel=1e-6)
        assert c.mass.unbalance_vector == pytest.approx(tuple(mr), rel=1e-6, abs=1e-12)
    text = "\n".join(feature_lines(f))
    assert "counterweight_1: beyond r = 36 mm" in text and "of it material" in text


def test_the_lightened_throw_meshed_and_solved(lightened, tmp_path_factory, mesh_cache):
    with locked(tmp_path_factory, "lightened_test_mesh"):  # the mesh the check of it takes (test_cad_check)
        tm = mesh_cad_throw(lightened, size="test", cache_dir=mesh_cache)
    assert {"counterweight_fillet_1", "counterweight_fillet_2", "end_1", "end_2", "crankpin"} <= set(tm.mesh.boundaries)
    assert {"counterweight_1", "counterweight_2", "web_1", "web_2"} <= set(tm.mesh.subdomains)
    units = solve_unit_cases(tm, Steel(), FeOptions(cases=CASES))  # reactions checked against the loads
    groups = assessed_groups(units)
    assert {"junction_1", "junction_2", "counterweight_1", "crankpin_fillet_1"} <= set(groups)
    assert max(c.equilibrium_error for c in units.cases.values()) < 1e-6


@pytest.fixture(scope="module")
def recessed(tmp_path_factory, request):
    root = request.config.rootpath
    g = load_geometry(root / "tests" / "data" / "geometry_small.toml")
    g = dataclasses.replace(g, crankpin_undercut=0.0008, journal_undercut=0.0003)
    return g, CadInput(recessed_throw_step(g, tmp_path_factory.mktemp("cad") / "recessed.step"), density=RHO)


def test_recessed_fillets_and_an_oblique_oil_drilling_recognised(recessed):
    g, cad = recessed
    th = recognise(cad).throws[0]
    for name, u, r in (("crankpin_fillet", 0.0008, g.crankpin_fillet), ("journal_fillet", 0.0003, g.journal_fillet)):
        for side in (1, 2):
            fl = th.fillet(f"{name}_{side}")
            assert fl.undercut == pytest.approx(u, abs=1e-9) and fl.radius == pytest.approx(r, abs=1e-9)
    (bore,) = th.oil_bores
    zw = g.crankpin_length / 2 + g.web_thickness
    d = np.array([0.0, g.crank_radius + g.crankpin_diameter / 2 + g.journal_diameter / 2, zw + g.journal_length / 2])
    assert abs(np.dot(bore.direction, d / np.linalg.norm(d))) == pytest.approx(1.0, abs=1e-12)
    assert bore.diameter == pytest.approx(0.004, abs=1e-9)
    assert bore.ends_on == ("crankpin", "journal_1")
    with pytest.raises(InputError) as e:  # UR M53's recess is the designer's to state
        m53_geometry_of_cad(th, cad)
    assert e.value.key == "cad.pin_recess" and "0.8 mm into the web" in str(e.value)
    m53 = m53_geometry_of_cad(th, dataclasses.replace(cad, pin_recess=0.0008, journal_recess=0.0003))
    assert (m53.pin_recess, m53.journal_recess) == (0.0008, 0.0003)
    assert m53.oil_bore_diameter == pytest.approx(0.004, abs=1e-9)


def test_the_recessed_throw_meshed_to_r_over_4_in_its_fillets_and_solved(recessed, tmp_path):
    g, cad = recessed
    # fillet edges at most r/4; away from them the size grows four times as fast as at
    # ``test`` (grading 8 m/m, not 2) up to a crankpin diameter (not two thirds of it): the
    # claim is the fillets' element size and a solved model with the oil bore's group,
    # which the mesh beyond the fillets does not change (65 000 elements, not 93 000)
    opt = MeshOptions(coarse_divisions=1.0, fillet_divisions=4.0, grading=8.0)
    tm = mesh_cad_throw(cad, size=opt, cache_dir=tmp_path / "cache")
    assert set(tm.fillet_radii) == {"crankpin_fillet_1", "crankpin_fillet_2", "journal_fillet_1", "journal_fillet_2"}
    for name, h in tm.stats.fillet_max_edge.items():
        assert h <= tm.fillet_radii[name] / 4 * (1 + 1e-9)  # IACS UR M53 App. III: at most r/4
    assert "oil_bore" in tm.mesh.boundaries
    units = solve_unit_cases(tm, Steel(), FeOptions(cases=CASES))
    assert "oil_bore" in assessed_groups(units)


def test_brep_and_iges_files_of_a_throw(root, tmp_path):
    g = load_geometry(root / "tests" / "data" / "geometry_small.toml")
    step = recognise(CadInput(parametric_step(g, tmp_path / "t.step"), density=RHO)).throws[0]
    from fe_crank.geometry.solid import throw_solid

    with gmsh_session() as gmsh:
        throw_solid(g)
        gmsh.model.occ.synchronize()
        gmsh.write(str(tmp_path / "t.brep"))  # OpenCASCADE's own format: no unit; the numbers are metres
    # OpenCASCADE's IGES writer takes the model's unit from a setting global to the process
    # (the last STEP read sets it): written in a process of its own, the model's numbers
    # (scaled to millimetres) go out as millimetres, the unit IGES states
    script = (
        "from fe_crank.io.geometry import load_geometry\n"
        "from fe_crank.geometry.solid import throw_solid\n"
        "from fe_crank.gmsh_io import gmsh_session\n"
        f"g = load_geometry({str(root / 'tests' / 'data' / 'geometry_small.toml')!r})\n"
        "with gmsh_session() as gmsh:\n"
        "    throw_solid(g)\n"
        "    gmsh.model.occ.synchronize()\n"
        "    gmsh.model.occ.dilate(gmsh.model.getEntities(), 0, 0, 0, 1000, 1000, 1000)\n"
        "    gmsh.model.occ.synchronize()\n"
        f"    gmsh.write({str(tmp_path / 't.igs')!r})\n"
    )
    subprocess.run([sys.executable, "-c", script], check=True, capture_output=True, timeout=300)
    brep = recognise(CadInput(tmp_path / "t.brep", density=RHO, length_unit=1.0, length_unit_text="m"))
    iges = recognise(CadInput(tmp_path / "t.igs", density=RHO))
    assert brep.source.format == "BREP" and iges.source.format == "IGES" and iges.source.unit.name == "mm"
    for t in (brep.throws[0], iges.throws[0]):
        assert t.crank_radius == pytest.approx(step.crank_radius, abs=1e-6)
        assert t.pin_length == pytest.approx(step.pin_length, abs=1e-6)
        assert [f.radius for f in t.fillets] == pytest.approx([f.radius for f in step.fillets], abs=1e-6)
    assert brep.throws[0].mass.total.mass == pytest.approx(step.mass.total.mass, rel=1e-9)
    # IGES carries B-spline surfaces only; OpenCASCADE integrates over them less exactly
    # (measured 0.4 % on this throw): the features are exact, the mass properties are not
    assert iges.throws[0].mass.total.mass == pytest.approx(step.mass.total.mass, rel=0.01)


def test_counterweights_drawn_as_bodies_fused_or_kept_bolted(tmp_path):
    r0, r1, angle, t = 0.03, 0.06, math.radians(160), 0.014
    from helpers.cad_files import bolted_sector_step

    path = bolted_sector_step(tmp_path / "bodies.step", r1=r1, angle=angle)
    mr = RHO * t * 2 / 3 * math.sin(angle / 2) * (r1**3 - r0**3)  # annular sector, as above
    fused = recognise(CadInput(path, density=RHO, bodies="fuse"))
    assert fused.source.solids == 3 and fused.bolted == ()
    assert [c.mass.unbalance for c in fused.throws[0].counterweights] == pytest.approx([mr, mr], rel=1e-6)
    bolted = recognise(CadInput(path, density=RHO, bodies="bolted"))
    assert bolted.throws[0].counterweights == ()  # the shaft alone: plain webs
    assert sorted(b.web for b in bolted.bolted) == [1, 2] and {b.throw for b in bolted.bolted} == {"1"}
    for b in bolted.bolted:
        assert b.mass.unbalance == pytest.approx(mr, rel=1e-6) and b.mass.unbalance_vector[1] < 0
    assert any(line.startswith("bolted body 1 (not in the FE model): throw 1") for line in feature_lines(bolted))
    # the bolted bodies' m r is the built m r of their webs' counterweights, and the bolts' load
    from fe_crank import model
    from fe_crank.assess.throw_geometry import cad_throws

    engine = model.Engine("e", 4, (model.Shaft("main"),), (model.Throw("1", "main", 0.0, 0.03),), ())
    cws = cad_throws(bolted, CadInput(path, density=RHO, bodies="bolted"), {"1": "1"}, engine, None)["1"].counterweights
    assert sorted(c.name for c in cws) == ["bolted_body_1", "bolted_body_2"] and all(c.bolted for c in cws)
    assert [c.built_unbalance for c in cws] == pytest.approx([mr, mr], rel=1e-6)
    record = json.loads(json.dumps(cad_record(bolted)))  # the provenance's record is plain data
    assert record["source"]["bodies"] == "bolted" and len(record["bolted"]) == 2
    assert record["source"]["sha256"] == hashlib.sha256(path.read_bytes()).hexdigest()
