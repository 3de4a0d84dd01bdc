"""CAD route: counterweights recognised whatever their outline.

The forged shape: webs whose sides run straight from the pin to the axis (stadiums of
half width rw) and a half disc about the crank axis on the far side, of radius R + rw
(the web's outer radius) or larger.  The only arc about the axis the web shows is then
the counterweight's own outline; the counterweight is the material on the far side
beyond the web's half width rw: a half annulus rw..rc, thickness t, whose m r is
``rho t 2/3 (rc^3 - rw^3)`` (first moment of a half annulus about its diameter).  A
counterweight criterion on a drawing without a recognised counterweight is refused
by ``fe-crank validate`` naming what was looked for and ``counterweight_radius``."""

from __future__ import annotations

import math

import pytest
from helpers.cad_files import _write, cad_loadcase, half_disc_throw_step, plain_throw

from fe_crank.cad import CadInput, feature_lines, mesh_cad_throw, recognise
from fe_crank.cli import main
from fe_crank.gmsh_io import gmsh_session

RHO, T, RW, R = 7850.0, 0.014, 0.03, 0.03
CRITERION = 'max_counterweight_stress = "300 MPa"'


def half_annulus(rc: float, rw: float = RW) -> tuple[float, float]:
    """Mass and m r of a half annulus rw..rc of thickness T."""
    return RHO * T * math.pi / 2 * (rc**2 - rw**2), RHO * T * 2 / 3 * (rc**3 - rw**3)


@pytest.mark.parametrize("rc", [R + RW, 0.075])
def test_half_disc_counterweights_of_the_webs_outer_radius_or_larger(tmp_path, rc):
    f = recognise(CadInput(half_disc_throw_step(tmp_path / "hd.step", rc=rc), density=RHO))
    t = f.throws[0]
    mass, mr = half_annulus(rc)
    assert sorted(c.web for c in t.counterweights) == [1, 2]
    for c in t.counterweights:
        assert c.radius == pytest.approx(RW, abs=1e-9)
        assert c.mass.mass == pytest.approx(mass, rel=1e-6)
        assert c.mass.unbalance == pytest.approx(mr, rel=1e-6)
        assert c.mass.centroid[1] < 0
        assert c.fillet_radius is None  # sharp: the half disc's flat meets the web's sides at 90 deg
    lines = feature_lines(f)
    assert any(s.startswith("  counterweight_1: beyond r = 30 mm, mass ") and "kg mm^2" in s for s in lines), lines


def test_forged_half_discs_with_transition_fillets(tmp_path):
    f = recognise(CadInput(half_disc_throw_step(tmp_path / "hd.step", fillet=0.004), density=RHO))
    t = f.throws[0]
    _, mr = half_annulus(R + RW)
    assert sorted(c.web for c in t.counterweights) == [1, 2]
    for c in t.counterweights:
        assert c.radius == pytest.approx(RW, abs=1e-9)
        assert c.fillet_radius == pytest.approx(0.004, abs=1e-9)
        assert len(c.fillet_faces) == 2
        # the region is bounded by y = 0: the fillets' material stays with the web
        assert c.mass.unbalance == pytest.approx(mr, rel=1e-6)


@pytest.mark.heavy
def test_forged_half_discs_are_meshed_as_counterweights(tmp_path):
    step = half_disc_throw_step(tmp_path / "hd.step", fillet=0.004)
    tm = mesh_cad_throw(CadInput(step, density=RHO), "1", size="test", cache_dir=tmp_path / "cache")
    assert {"counterweight_1", "counterweight_2"} <= set(tm.mesh.subdomains)
    assert {"counterweight_fillet_1", "counterweight_fillet_2"} <= set(tm.mesh.boundaries)


def test_a_counterweight_criterion_needs_a_recognised_counterweight(tmp_path, capsys):
    half_disc_throw_step(tmp_path / "hd.step", fillet=0.004)
    lc = cad_loadcase(tmp_path, "hd.step", radius="30 mm", criteria=CRITERION)
    assert main(["validate", str(lc)]) == 0, capsys.readouterr().err
    capsys.readouterr()
    with gmsh_session() as gmsh:
        plain_throw(gmsh)
        _write(gmsh, tmp_path / "plain.step")
    f = recognise(CadInput(tmp_path / "plain.step", density=RHO))
    assert not f.throws[0].counterweights
    assert any(s.startswith("  counterweight_2: none recognised") for s in feature_lines(f))
    lc = cad_loadcase(tmp_path, "plain.step", radius="30 mm", criteria=CRITERION, name="plain.toml")
    before = sorted(p.name for p in tmp_path.iterdir())
    assert main(["validate", str(lc)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"error {lc}: criteria.max_counterweight_stress: "), err
    for words in ("none is recognised in the CAD file plain.step", "far side of the crank axis", "r = 30 mm (web_1)"):
        assert words in err, err
    assert "counterweight_radius" in err and str(lc) in err
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_bolted_counterweights_with_their_bolt_holes(tmp_path):
    """Annular sectors (30..60 mm, 160 deg, 14 mm) drawn as separate solids beside each web
    with two 8 mm axial bolt holes each at (+-25, -40) mm: per web, the body's mass and
    m r (the sector's less the holes') and its holes."""
    from helpers.cad_files import _sector

    a, r1, r2, rh, hx, hy = math.radians(160), 0.03, 0.06, 0.004, 0.025, 0.04
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        shaft = plain_throw(gmsh)
        cws = [(3, _sector(occ, r1, r2, a, z0, T)) for z0 in (-0.041, 0.027)]
        holes = [(3, occ.addCylinder(x, -hy, -0.05, 0, 0, 0.1, rh)) for x in (-hx, hx)]
        out, _ = occ.cut([(3, shaft), *cws], holes)
        assert len(out) == 3
        step = _write(gmsh, tmp_path / "bolted.step")
    f = recognise(CadInput(step, density=RHO, bodies="bolted"))
    hole = RHO * math.pi * rh**2 * T
    mass = RHO * a / 2 * (r2**2 - r1**2) * T - 2 * hole
    mr = RHO * T * 2 / 3 * (r2**3 - r1**3) * math.sin(a / 2) - 2 * hole * hy
    assert sorted(b.web for b in f.bolted) == [1, 2]
    for b in f.bolted:
        assert b.throw == "1"
        assert b.mass.mass == pytest.approx(mass, rel=1e-6)
        assert b.mass.unbalance == pytest.approx(mr, rel=1e-6)
        assert len(b.holes) == 2
        for h, x in zip(b.holes, (-hx, hx), strict=True):
            assert h.diameter == pytest.approx(2 * rh, abs=1e-9)
            assert h.point[:2] == pytest.approx((x, -hy), abs=1e-9)
            assert h.pitch_radius == pytest.approx(math.hypot(hx, hy), abs=1e-9)
            assert abs(h.direction[2]) == pytest.approx(1.0, abs=1e-12)
    assert any("bolt hole faces" in s and "diameter 8 mm" in s for s in feature_lines(f))
