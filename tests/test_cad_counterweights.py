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
from cad_files import _write, cad_loadcase, half_disc_throw_step, plain_throw

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
