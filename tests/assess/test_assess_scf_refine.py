"""Rejected FE SCFs never count: the SCF mode's mesh is checked against UR M53 App. III
(fillet elements <= r/4, >= 6 elements across the web, the principal-stress or averaging
criterion at each peak); the check refines it until the appendix accepts it (bounded), and
a result it still rejects refuses the M53 criterion with a message naming why."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fe_crank.assess.criteria.judge import evaluate_criteria
from fe_crank.assess.superpose import UnitStresses
from fe_crank.assess.throw import ThrowContext, assess_throw
from fe_crank.errors import InputError
from fe_crank.io.criteria import build_criteria
from fe_crank.io.material import load_material
from fe_crank.rules.m53.scf_mode import web_centres_of
from fe_crank.rules.m53.scf_refine import FILLET_STEP, accepted_scf, refined_options


@pytest.fixture(scope="module")
def rejected(big_fillet_scf):
    return big_fillet_scf


def test_the_web_check_is_part_of_the_appendix_verdict(rejected):
    """The coarse test mesh has one element across the 12 mm webs: not accepted, and said so."""
    r = rejected
    assert [w.web for w in r.web_elements] == ["web_1", "web_2"]
    assert all(w.across < 6 for w in r.web_elements) and not r.web_ok and not r.mesh_ok
    assert "elements across the web (>= 6 required)" in r.summary()
    assert "mesh NOT accepted" in r.summary()


def test_next_mesh_options_refine_what_the_appendix_rejected(rejected, big_fillet):
    _, tm = big_fillet
    opts = tm.options
    new, why = refined_options(opts, rejected)
    # fillet elements longer than r/4 on this mesh: the fillet edge shrinks; the web gets its W/6 control
    assert new.fillet_divisions == pytest.approx(opts.fillet_divisions * FILLET_STEP)
    assert new.web_divisions == 6.0 and opts.web_divisions is None
    assert "fillet elements longer than r/4" in why and "elements across the web" in why
    # a web still short of 6 is scaled by 6/n with 10 % to spare
    short = dataclasses.replace(
        rejected, web_elements=tuple(dataclasses.replace(w, across=5.0) for w in rejected.web_elements)
    )
    again, _ = refined_options(new, short)
    assert again.web_divisions == pytest.approx(6.0 * 1.1 * 6.0 / 5.0)


@pytest.fixture(scope="module")
def thick_web(tmp_path_factory):
    """A throw outside UR M53's range (3.8 mm fillets on the 28 mm pin) with 36 mm webs
    (one web refinement of a thick web is the cheapest real case: the thicker the web, the
    longer its W/6 edge and the fewer the elements; about 300 k dofs), meshed at the test
    size, and the SCF stage on it with no refinement allowed (``max_refinements=0``): the
    SCF stage's first mesh, the check's at r/4 in the fillets with 2.6 elements across the
    webs, as the appendix judged it.  The refusal test reads
    that result; the refinement test continues from it (``accepted_scf(first=...)``), so
    the first mesh is solved once."""
    from pathlib import Path

    from fe_crank.assess.adapters import m53_geometry_of
    from fe_crank.io.geometry import load_geometry
    from fe_crank.mesh import MeshOptions, mesh_throw

    g = load_geometry(Path(__file__).resolve().parents[1] / "data" / "geometry_small.toml")
    g = dataclasses.replace(g, crankpin_fillet=0.0038, journal_fillet=0.0038, web_thickness=0.036)
    tm = mesh_throw(
        g,
        size=MeshOptions(coarse_divisions=1.2, fillet_divisions=0.8, grading=2.5),
        cache_dir=tmp_path_factory.mktemp("thick_web_cache"),
    )
    geo = m53_geometry_of(g)
    r0 = accepted_scf(tm, g, load_material("42CrMo4"), geo, web_centres=web_centres_of(g), max_refinements=0)
    return g, tm, geo, r0


@pytest.mark.heavy
def test_a_rejected_scf_refuses_the_m53_criterion(thick_web):
    _, _, geo, r0 = thick_web
    assert geo.web_thickness == 0.036 and geo.pin_fillet_radius / geo.pin_diameter > 0.13  # outside UR M53 3.1
    # no refinement allowed: the SCF stage's first mesh (the check's at r/4 in the fillets,
    # 2.6 elements across the webs) is returned as the appendix judged it, rejected
    assert not r0.mesh_ok and r0.size_ok and not r0.web_ok and r0.refinement == ()
    assert all(w.across < 6 for w in r0.web_elements)
    theta = np.deg2rad(np.arange(0.0, 720.0, 5.0))
    unit = UnitStresses(stress=np.zeros((2, 6, 1)), points=np.zeros((3, 1)), groups={}, cases=("pin_y", "torque"))
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            theta,
            np.column_stack([np.zeros(theta.size), 2e4 * np.cos(theta)]),
            300.0 * np.sin(theta),
            omega=0.0,
            overspeed=None,
            material=load_material("42CrMo4"),
            crank_radius=0.02,
            m53_geometry=geo,
            scf=r0,
        )
    )
    pin, journal = t.m53
    assert not pin.scf_accepted and not journal.scf_accepted
    with pytest.raises(InputError) as e:
        evaluate_criteria(build_criteria({"min_m53_acceptability": 1.15}, "c.toml"), (t,), file="c.toml")
    msg = str(e.value)
    assert e.value.key == "criteria.min_m53_acceptability" and "c.toml" in msg
    assert "App. III does not accept" in msg and "mesh NOT accepted" in msg and "throw 1, pin fillet" in msg


@pytest.mark.heavy
def test_the_check_refines_the_scf_mesh_until_the_appendix_accepts_it(thick_web):
    """The thick-web throw (``thick_web``): the test-size mesh has 2.6 elements across the
    web; the SCF stage re-meshes with the web control and ends accepted, fillets within
    r/4, >= 6 across, every peak within App. III 2.3, and says which mesh it refined and
    why.  It starts from the first mesh's result the fixture solved (the same call with
    ``max_refinements=0``) rather than solving that mesh again."""
    g, tm, geo, r0 = thick_web
    r = accepted_scf(tm, g, load_material("42CrMo4"), geo, web_centres=web_centres_of(g), first=r0)
    assert r.mesh_ok and r.size_ok and r.web_ok and all(w.across >= 6 for w in r.web_elements)
    assert all(q["mesh_ok"] for q in r.quality.values())
    assert len(r.refinement) >= 1 and "elements across the web" in r.refinement[0]
    assert r.refinement[0].startswith("fillets r/4")  # the first SCF mesh: the check's at r/4
    assert "mesh accepted" in r.summary() and "refinement(s)" in r.summary()


def test_web_divisions_are_a_checked_mesh_option():
    from fe_crank.errors import MeshError
    from fe_crank.mesh import MeshOptions

    assert MeshOptions().web_divisions is None and MeshOptions(web_divisions=6.0).web_divisions == 6.0
    for bad in (0.0, -6.0, float("nan"), float("inf")):
        with pytest.raises(MeshError, match="web_divisions must be positive"):
            MeshOptions(web_divisions=bad)
