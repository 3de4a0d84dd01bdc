"""CAD route, round trip: every shipped parametric throw exported to STEP (the one solid
``throw_solid`` builds, written by gmsh's OpenCASCADE writer) and read back gives the
features of its specification to 1e-6 m, the parametric route's mass properties to
1e-6 (relative; parts that both routes split alike), and its UR M53 dimensions (the web
width B against the closed form of the web outline).  A whole inline-4 shaft in one
file gives its four throws."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from helpers.cad_files import parametric_step, shaft_step

from fe_crank.assess.adapters import m53_geometry_of
from fe_crank.assess.cad_inputs import m53_geometry_of_cad
from fe_crank.cad import CadInput, feature_lines, recognise
from fe_crank.geometry.mass import mass_properties
from fe_crank.io.geometry import load_geometry

ROOT = Path(__file__).resolve().parents[2]
pytestmark = pytest.mark.heavy
POS = 1e-6  # m
REL = 1e-6
GEOMETRIES = (
    "geometry/single_cylinder.toml",
    "geometry/v4_90_pneumatic.toml",
    "geometry/inline4.toml",
    "tests/data/geometry_small.toml",
)


def hull_half_width(a: float, b: float, R: float, y: float) -> float:
    """Half width at height y of the convex hull of the circles (0, 0, a) and (0, R, b):
    on circle a below its tangent point, on circle b above its own, on the common
    tangent between (sin phi = (a - b)/R: the tangent's normal (cos phi, sin phi))."""
    s = (a - b) / R
    c = math.sqrt(1 - s * s)
    if y <= a * s:
        return math.sqrt(a * a - y * y)
    if y >= R + b * s:
        return math.sqrt(b * b - (y - R) ** 2)
    # the tangent line: points p with p . (c, s) = a, i.e. x = (a - y s) / c
    return (a - y * s) / c


#: the throws the run exports once for every CAD test (``tests/cad/conftest.py``)
SHARED_STEPS = {
    "geometry/single_cylinder.toml": "single_cylinder_step",
    "geometry/inline4.toml": "inline4_throw_step",
    "tests/data/geometry_small.toml": "small_throw_step",
}


@pytest.fixture(scope="module", params=GEOMETRIES, ids=lambda p: p.rsplit("/", 1)[-1])
def roundtrip(request, tmp_path_factory):
    if request.param in SHARED_STEPS:  # the same export of the same file (helpers.cad_files.parametric_step)
        g, path = request.getfixturevalue(SHARED_STEPS[request.param])
    else:
        g = load_geometry(ROOT / request.param)
        path = parametric_step(g, tmp_path_factory.mktemp("cad") / "throw.step")
    return g, recognise(CadInput(path, density=g.density))


def test_features(roundtrip):
    g, f = roundtrip
    (t,) = f.throws
    zp, zw = g.crankpin_length / 2, g.crankpin_length / 2 + g.web_thickness
    assert f.source.format == "STEP" and f.source.unit.metres == pytest.approx(1e-3, rel=1e-15)
    assert t.crank_radius == pytest.approx(g.crank_radius, abs=POS)
    assert t.crankpin.diameter == pytest.approx(g.crankpin_diameter, abs=POS)
    assert t.pin_length == pytest.approx(g.crankpin_length, abs=POS)
    assert t.origin == pytest.approx((0, 0, 0), abs=POS)
    for k, sign in ((0, -1), (1, 1)):
        j, w, b = t.journals[k], t.webs[k], t.bearings[k]
        assert j.diameter == pytest.approx(g.journal_diameter, abs=POS)
        assert w.z_inner == pytest.approx(sign * zp, abs=POS) and w.z_outer == pytest.approx(sign * zw, abs=POS)
        assert w.thickness == pytest.approx(g.web_thickness, abs=POS)
        assert w.side_radius == pytest.approx(g.web.journal_end_radius, abs=POS)
        assert b.z == pytest.approx(sign * (zw + g.journal_length), abs=POS) and b.free_end
        # the journal's cylinder runs from the end face to its fillet's tangent line
        far, near = sorted((abs(j.z_min), abs(j.z_max)), reverse=True)
        assert far == pytest.approx(zw + g.journal_length, abs=POS)
        assert near == pytest.approx(zw + g.journal_fillet, abs=POS)
    for name, r in (("crankpin_fillet", g.crankpin_fillet), ("journal_fillet", g.journal_fillet)):
        for side in (1, 2):
            fl = t.fillet(f"{name}_{side}")
            assert fl.radius == pytest.approx(r, abs=POS)
            assert fl.undercut == 0.0 and len(fl.arcs) == len(fl.faces) == 1
    if g.oil_bore is None:
        assert t.oil_bores == ()
    else:
        (bore,) = t.oil_bores
        assert bore.diameter == pytest.approx(g.oil_bore.diameter, abs=POS)
        assert bore.angle == pytest.approx(g.oil_bore.angle % math.pi, abs=1e-9)
        assert bore.point == pytest.approx((0.0, g.crank_radius, 0.0), abs=POS)
        assert bore.ends_on == ("crankpin",)
    cws = {cw.web: cw for cw in g.throws[0].counterweights}
    assert sorted(c.web for c in t.counterweights) == sorted(cws)
    for c in t.counterweights:
        assert c.fillet_radius == pytest.approx(cws[c.web].fillet_radius, abs=POS)
        assert len(c.fillet_faces) == 2  # one transition fillet each side of the sector
    lines = feature_lines(f)
    assert any(line.startswith("  crankpin_fillet_1: faces ") for line in lines)


def _same(a, b):
    assert a.volume == pytest.approx(b.volume, rel=REL)
    assert a.mass == pytest.approx(b.mass, rel=REL)
    scale = math.sqrt(b.volume ** (2 / 3))
    assert np.allclose(a.centroid, b.centroid, atol=REL * scale, rtol=0)
    assert np.allclose(a.inertia, b.inertia, atol=REL * np.abs(b.inertia).max(), rtol=0)
    assert a.inertia_axis == pytest.approx(b.inertia_axis, rel=REL)


def test_mass_properties(roundtrip):
    g, f = roundtrip
    t = f.throws[0]
    ref = mass_properties(g)
    _same(t.mass.total, ref.total)
    for part in ("journal_1", "crankpin", "journal_2"):
        _same(t.mass.parts[part], ref.parts[part])
    # the routes bound a counterweight differently (the parametric one by its sector, the
    # CAD one beyond the web's rounded end: docs/geometry.md); web and counterweight together
    for k in (1, 2):
        names = [n for n in (f"web_{k}", f"counterweight_{k}") if n in ref.parts]
        assert sum(t.mass.parts[n].volume for n in names if n in t.mass.parts) == pytest.approx(
            sum(ref.parts[n].volume for n in names), rel=REL
        )


def test_m53_dimensions(roundtrip, root):
    g, f = roundtrip
    t = f.throws[0]
    cad = CadInput(root / "x.step", density=g.density)
    got, ref = m53_geometry_of_cad(t, cad), m53_geometry_of(g)
    for field in (
        "pin_diameter",
        "journal_diameter",
        "crank_radius",
        "web_thickness",
        "pin_fillet_radius",
        "journal_fillet_radius",
        "bearing_to_web",
        "pin_length",
        "oil_bore_diameter",
        "oil_bore_angle",
        "pin_recess",
        "journal_recess",
    ):
        assert getattr(got, field) == pytest.approx(getattr(ref, field), abs=POS), field
    y = 0.5 * ((g.crank_radius - g.crankpin_diameter / 2) + g.journal_diameter / 2)
    exact = 2 * hull_half_width(g.web.journal_end_radius, g.web.pin_end_radius, g.crank_radius, y)
    assert got.web_width == pytest.approx(exact, abs=POS)


def test_a_whole_inline4_shaft(root, tmp_path):
    g = load_geometry(root / "geometry" / "inline4.toml")
    f = recognise(CadInput(shaft_step(g, tmp_path / "shaft.step"), density=g.density, throws=("1", "2", "3", "4")))
    assert [t.name for t in f.throws] == ["1", "2", "3", "4"]
    assert [math.degrees(t.angle) for t in f.throws] == pytest.approx([0, 180, 180, 0], abs=1e-9)
    zb = g.crankpin_length / 2 + g.web_thickness + g.journal_length
    ref = mass_properties(g, "2")
    for t in f.throws:
        assert t.crank_radius == pytest.approx(g.crank_radius, abs=POS)
        # each throw between its bearing centres: the middles of the shared journals,
        # the free end faces at the shaft's ends
        assert [b.z for b in t.bearings] == pytest.approx([-zb, zb], abs=POS)
        assert [b.free_end for b in t.bearings] == [t.name == "1", t.name == "4"]
        _same(t.mass.total, ref.total)
    assert len(f.axis.faces) >= 5  # five main journals and the webs' rounded ends share the axis
