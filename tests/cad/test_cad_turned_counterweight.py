"""CAD route: a drawn counterweight turned from opposite its pin (``cad.throw.
counterweight_offset``, docs/geometry.md "Geometry from CAD").

The throw of ``tests/data/geometry_small_shaft.toml`` (sector 14..40 mm, 120 deg, 2.5 mm
transition fillets) turned 20 deg (``counterweight.offset``), written to STEP by
fe-crank's own writer (``helpers.cad_files.parametric_step``) and read back:

* the recognised offset is the drawn one to 1e-9 rad (the direction of an m r vector
  known to 1e-9 relative);
* the recognised counterweight is the parametric solid's material beyond the web's side
  radius (20 mm) on the far side of y = 0, integrated independently on the parametric
  solid by OpenCASCADE (mass and m r vector to 1e-9 relative; measured 3e-13); web and
  counterweight together are the parametric route's web and counterweight (1e-9;
  measured 8e-14);
* the peaks of the pin and journal fillets and of the counterweights' transition fillets
  under the four FE unit cases agree with the parametric route's within 10 %: the
  ``test`` preset's mesh noise (tests/cad/test_cad_fe.py: two meshes of one solid with
  fillet edges about the radius put a node at the hot spot or beside it; 6 % on the
  plain small throw, 25 % on the shipped ones).  Measured on this throw: 7.9 % turned,
  6.7 % for the same throw unturned (the routes' scatter with no turn), and within
  0.84 % turned with fillet edges of r/3 (60 000 elements, not run here);
* one turned throw of a drawn two-throw shaft is recognised turned, the other not, and
  they are not taken as one solid (``cad.whole.shared_meshes``);
* a counterweight turned over y = 0 (40 deg: its flank 100 deg from opposite the pin) is
  recognised by its own sector: mass and m r vector against an independent OpenCASCADE
  integral of the parametric solid in that sector beyond the side radius (1e-9), web and
  counterweight together the parametric route's (1e-9), offset the direction of that m r
  (40.03 deg: the two flanks' fillets differ; measured 3.4e-10 rad apart); without
  fillets the offset is 40 deg to 1e-9 rad;
* one that still cannot be recognised (a 190 deg sector turned 10 deg, the fillet of its
  other flank rising above y = 0) is refused by ``fe-crank validate`` with the file, the
  key and the reason."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers.cad_files import cad_loadcase, parametric_step, shaft_step
from helpers.paths import DATA
from helpers.shared import shared_file

from fe_crank.assess.group.nodes import unit_stresses
from fe_crank.cad import CadInput, feature_lines, mesh_cad_throw, recognise
from fe_crank.cad.whole import shared_meshes
from fe_crank.cli import main
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.core.stress import von_mises
from fe_crank.geometry import mass_properties
from fe_crank.geometry.solid import throw_solid
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.gmsh_io import gmsh_session
from fe_crank.io.base import read_toml
from fe_crank.io.geometry import geometry_from_dict
from fe_crank.mesh import mesh_throw

OFFSET = 20.0  # deg
REL = 1e-9  # OpenCASCADE's B-rep integrals of one solid along two routes
#: the direction of an m r vector known to REL (relative) is known to REL rad
TOL_DEG = math.degrees(REL)
TOL_PEAK = 0.10  # two test-preset meshes of one solid (module doc)
SIDE = 0.020  # m: the web's side radius (a 40 mm wide stadium), where the counterweight begins
CASES = ("centrifugal", "pin_x", "pin_y", "torque")


def geometry(offset_deg: float, fillet: str | None = "2.5 mm") -> CrankGeometry:
    raw = {k: v for k, v in read_toml(DATA / "geometry_small_shaft.toml").items() if k not in ("throws", "shaft")}
    raw["counterweight"] = {**raw["counterweight"], "offset": f"{offset_deg:g} deg"}
    if fillet is not None:
        raw["counterweight"]["fillet_radius"] = fillet
    return geometry_from_dict(raw)


@pytest.fixture(scope="module")
def turned(tmp_path_factory):
    """The turned throw, its STEP export (once in the run: the CAD mesh's cache key holds
    the file's bytes) and what the CAD route recognises in it."""
    g = geometry(OFFSET)
    step = shared_file(tmp_path_factory, "turned_counterweight.step", lambda p: parametric_step(g, p))
    return g, step, recognise(CadInput(step, density=g.density))


def _beyond_side_in(g: CrankGeometry, corners: list[tuple[float, float]]) -> dict[int, tuple[float, np.ndarray]]:
    """Mass and m r of the parametric solid's material beyond r = SIDE inside the outline
    ``corners`` (x, y of the throw frame), per web side (z < 0, z > 0): OpenCASCADE's
    intersection of ``throw_solid`` with that prism less the cylinder r < SIDE."""
    out = {}
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        for web, (z0, z1) in ((1, (-1.0, 0.0)), (2, (0.0, 1.0))):
            solid, _ = throw_solid(g)
            pts = [occ.addPoint(x, y, z0) for x, y in corners]
            loop = occ.addCurveLoop([occ.addLine(pts[i], pts[(i + 1) % len(pts)]) for i in range(len(pts))])
            prism = occ.extrude([(2, occ.addPlaneSurface([loop]))], 0, 0, z1 - z0)
            (vol,) = [t for d, t in prism if d == 3]
            core = occ.addCylinder(0, 0, z0, 0, 0, z1 - z0, SIDE)
            region, _ = occ.cut([(3, vol)], [(3, core)])
            part, _ = occ.intersect([(3, solid)], region)
            occ.synchronize()
            v = sum(occ.getMass(3, t) for _, t in part)
            c = sum(occ.getMass(3, t) * np.asarray(occ.getCenterOfMass(3, t)) for _, t in part) / v
            out[web] = (g.density * v, g.density * v * c[:2])
            occ.remove(occ.getEntities(3), recursive=True)
    return out


def _beyond_side(g: CrankGeometry) -> dict[int, tuple[float, np.ndarray]]:
    """Mass and m r of the parametric solid's material beyond r = SIDE on y < 0, per web side."""
    return _beyond_side_in(g, [(-1.0, -1.0), (1.0, -1.0), (1.0, 0.0), (-1.0, 0.0)])


def test_turned_counterweight_recognised_with_its_offset_and_exact_mass(turned):
    g, _, features = turned
    t = features.throws[0]
    assert [c.web for c in t.counterweights] == [1, 2]
    ref = _beyond_side(g)
    param = mass_properties(g)
    for c in t.counterweights:
        assert math.degrees(c.offset) == pytest.approx(OFFSET, abs=TOL_DEG)
        assert c.radius == pytest.approx(SIDE, abs=1e-9)
        assert c.fillet_radius == pytest.approx(0.0025, abs=1e-9) and len(c.fillet_faces) == 2
        m, u = ref[c.web]
        assert c.mass.mass == pytest.approx(m, rel=REL)
        assert np.asarray(c.mass.unbalance_vector) == pytest.approx(u, abs=REL * np.hypot(*u))
        # web and counterweight together: the parametric route's (which bounds the counterweight by its sector)
        names = (f"web_{c.web}", f"counterweight_{c.web}")
        both = [t.mass.parts[n] for n in names], [param.parts[n] for n in names]
        for key in ("mass", "unbalance_vector"):
            a, b = (np.sum([np.asarray(getattr(x, key)) for x in side], axis=0) for side in both)
            assert a == pytest.approx(b, rel=REL, abs=REL * float(np.abs(b).max()))
    lines = feature_lines(features)
    assert any(
        "counterweight_1: beyond r = 20 mm" in s and "turned 20 deg from opposite its pin (-y towards +x)" in s
        for s in lines
    )


@dataclasses.dataclass(frozen=True)
class Steel:
    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3
    density: float = 7850.0


def _peaks(throw_mesh) -> dict[tuple[str, str], float]:
    """Largest von Mises stress per unit case over each mirror pair of pin and journal
    fillets and over the counterweights' transition fillets (the faces both routes name
    alike: the routes bound the counterweight's volume differently, docs/geometry.md)."""
    us = unit_stresses(solve_unit_cases(throw_mesh, Steel(), FeOptions(cases=CASES)))
    pairs = {
        "crankpin_fillet": ("crankpin_fillet_1", "crankpin_fillet_2"),
        "journal_fillet": ("journal_fillet_1", "journal_fillet_2"),
        "counterweight_fillet": ("counterweight_fillet_1", "counterweight_fillet_2"),
    }
    out = {}
    for label, names in pairs.items():
        idx = np.unique(np.concatenate([us.groups[n] for n in names]))
        for i, case in enumerate(us.cases):
            out[(label, case)] = float(von_mises(us.stress[i][:, idx]).max())
    return out


@pytest.mark.heavy
def test_turned_counterweight_fe_peaks_agree_with_the_parametric_route(turned, mesh_cache):
    g, step, _ = turned
    param = mesh_throw(g, size="test", cache_dir=mesh_cache)
    cad = mesh_cad_throw(CadInput(step, density=g.density), "1", size="test", cache_dir=mesh_cache)
    assert param.symmetry == (2,)  # a turned throw keeps z = 0 only
    assert set(cad.mesh.boundaries) == set(param.mesh.boundaries)
    assert set(cad.mesh.subdomains) == set(param.mesh.subdomains)
    a, b = _peaks(cad), _peaks(param)
    assert a.keys() == b.keys()
    worst = max(abs(a[k] / b[k] - 1) for k in a)
    assert worst <= TOL_PEAK, {k: round(a[k] / b[k] - 1, 4) for k in a}


def test_one_turned_throw_of_a_drawn_shaft(tmp_path):
    """Throw 2 of a two-throw shaft drawn with its counterweights turned 20 deg."""
    g = geometry(OFFSET)
    plain = geometry(0.0)
    spec1 = dataclasses.replace(plain.throws[0], name="1", angle=0.0)
    spec2 = dataclasses.replace(g.throws[0], name="2", angle=math.pi)
    shaft = dataclasses.replace(g, throws=(spec1, spec2))
    f = recognise(CadInput(shaft_step(shaft, tmp_path / "shaft.step"), density=g.density, throws=("1", "2")))
    first, second = f.throws
    assert [c.offset for c in first.counterweights] == [0.0, 0.0]
    assert [math.degrees(c.offset) for c in second.counterweights] == pytest.approx([OFFSET] * 2, abs=TOL_DEG)
    assert shared_meshes(f) == {"1": "1", "2": "2"}


OVER = 40.0  # deg: the sector's flank at 40 + 60 = 100 deg from -y, over y = 0 towards the pin
PIN_Y = 0.020  # m: the crankpin's centre; the web's straight sides x = +-SIDE run up to it


@pytest.fixture(scope="module")
def over(tmp_path_factory):
    """The throw turned OVER (its sector reaching over y = 0 on its +x side), its STEP
    export and what the CAD route recognises in it."""
    g = geometry(OVER)
    step = shared_file(tmp_path_factory, "over_counterweight.step", lambda p: parametric_step(g, p))
    return g, step, recognise(CadInput(step, density=g.density))


def _in_sector(g: CrankGeometry) -> dict[int, tuple[float, np.ndarray]]:
    """Mass and m r of the parametric solid's material beyond r = SIDE in the counterweight's
    sector, per web side: OpenCASCADE's intersection of ``throw_solid`` with the region
    bounded by the drawing's numbers alone: ``y < 0`` (the far side), the wedge from the
    +x axis to the flank at ``offset + angle/2`` from -y, and beyond that flank the room
    outside the web's straight side (``x > SIDE``) below the crankpin's centre, where
    only the flank's transition fillet has material."""
    cw = g.throws[0].counterweights[0]
    flank = cw.offset + cw.angle / 2  # rad from -y towards +x
    slope = -1.0 / math.tan(flank)  # the flank line y = slope x (x > 0)
    big = 1.0
    corners = [(0.0, 0.0), (-big, 0.0), (-big, -big), (big, -big), (big, PIN_Y), (SIDE, PIN_Y), (SIDE, slope * SIDE)]
    assert 0.0 < slope * SIDE < PIN_Y
    return _beyond_side_in(g, corners)


def test_counterweight_turned_over_y0_recognised_by_its_sector(over):
    """The sector spans -20 ... 100 deg from -y: its flank at 100 deg leaves the web's
    straight side 3.5 mm above y = 0.  Recognised by its own sector: its mass and m r
    vector those of the parametric solid's material in that sector beyond the side radius
    (with both transition fillets), independently integrated; web and counterweight
    together the parametric route's; its offset the direction of that m r (the fillet on
    the flank at 100 deg meets the web's flat side, the one at -20 deg its rounded end:
    the m r points 0.03 deg past the sector's mid-line; without fillets it is on it, next
    test)."""
    g, _, features = over
    t = features.throws[0]
    assert [c.web for c in t.counterweights] == [1, 2]
    ref = _in_sector(g)
    param = mass_properties(g)
    for c in t.counterweights:
        m, u = ref[c.web]
        assert c.mass.mass == pytest.approx(m, rel=REL)
        assert np.asarray(c.mass.unbalance_vector) == pytest.approx(u, abs=REL * np.hypot(*u))
        assert math.degrees(c.offset) == pytest.approx(math.degrees(math.atan2(u[0], -u[1])), abs=TOL_DEG)
        assert math.degrees(c.offset) == pytest.approx(OVER, abs=0.05)
        assert c.radius == pytest.approx(SIDE, abs=1e-9)
        assert c.fillet_radius == pytest.approx(0.0025, abs=1e-9) and len(c.fillet_faces) == 2
        names = (f"web_{c.web}", f"counterweight_{c.web}")
        both = [t.mass.parts[n] for n in names], [param.parts[n] for n in names]
        for key in ("mass", "unbalance_vector"):
            a, b = (np.sum([np.asarray(getattr(x, key)) for x in side], axis=0) for side in both)
            assert a == pytest.approx(b, rel=REL, abs=REL * float(np.abs(b).max()))


def test_a_sharp_counterweight_turned_over_y0_has_the_sectors_offset(tmp_path):
    """The same sector without transition fillets: its material beyond the side radius is
    an annular sector 20 ... 40 mm of 120 deg (the web's sliver between r = 20 mm and its
    side lies inside it), so its m r points along the sector's mid-line, 40 deg."""
    g = geometry(OVER, fillet=None)
    features = recognise(CadInput(parametric_step(g, tmp_path / "sharp.step"), density=g.density))
    ref = _in_sector(g)
    for c in features.throws[0].counterweights:
        m, u = ref[c.web]
        assert math.degrees(c.offset) == pytest.approx(OVER, abs=TOL_DEG)
        assert c.fillet_faces == () and c.mass.mass == pytest.approx(m, rel=REL)
        assert np.asarray(c.mass.unbalance_vector) == pytest.approx(u, abs=REL * np.hypot(*u))


def test_a_counterweight_with_a_fillet_over_y0_on_its_other_flank_refused_by_validate(tmp_path, capsys):
    """A 190 deg sector turned 10 deg: its flank at 105 deg reaches over y = 0, its flank
    at -85 deg leaves the web's rounded journal end with a fillet that rises above
    y = 0, which the region would cut."""
    g = geometry(10.0)
    g = dataclasses.replace(
        g,
        throws=(
            dataclasses.replace(
                g.throws[0],
                counterweights=tuple(
                    dataclasses.replace(c, angle=math.radians(190.0)) for c in g.throws[0].counterweights
                ),
            ),
        ),
    )
    step = parametric_step(g, tmp_path / "wide.step")
    capsys.readouterr()
    assert main(["validate", str(cad_loadcase(tmp_path, step.name))]) == 2
    err = capsys.readouterr().err
    assert str(step) in err and "cad.file:" in err and "reaches over y = 0 towards its pin" in err
    assert "rise above y = 0" in err and "counterweight.offset" in err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
