"""The web size control of UR M53 App. III 2.2 (at least 6 elements across the web
thickness in an SCF model) in the CAD route: the small test throw with its webs made
36 mm thick (the thick-web throw of tests/assess/test_assess_scf_refine.py, but for its
fillets), exported to STEP and meshed by the CAD route at the ``test`` preset, has fewer
than 6 elements across its webs; with ``web_divisions = 6`` (what the SCF stage's
refinement sets, ``rules.m53.scf_refine``) each recognised web gets edges of at most
0.7 W/6 and at least 6 elements across (``rules.m53.web_mesh``'s measure), as the
parametric route does.  The control sizes the edges by the web's own thickness, so the
claim is the same for every web; a thick web meets it with edges three times as long as
the 12 mm webs of the small throw would take, hence with far fewer elements."""

from __future__ import annotations

import dataclasses

import pytest
from helpers.cad_files import parametric_step
from helpers.paths import DATA

from fe_crank.cad import CadInput, mesh_cad_throw
from fe_crank.io.geometry import load_geometry
from fe_crank.mesh import PRESETS
from fe_crank.rules.m53.web_mesh import MIN_ELEMENTS_ACROSS, web_elements_across, web_groups

pytestmark = pytest.mark.heavy


def test_cad_webs_meshed_to_six_elements_across(tmp_path):
    g = dataclasses.replace(load_geometry(DATA / "geometry_small.toml"), web_thickness=0.036)
    cad = CadInput(parametric_step(g, tmp_path / "thick_web.step"), density=g.density)
    plain = mesh_cad_throw(cad, "1", size="test", cache_dir=tmp_path)
    across = web_elements_across(plain.mesh, web_groups(plain.mesh), g.web_thickness)
    assert len(across) == 2 and min(w.across for w in across) < MIN_ELEMENTS_ACROSS
    opts = dataclasses.replace(PRESETS["test"], web_divisions=6.0)
    webbed = mesh_cad_throw(cad, "1", size=opts, cache_dir=tmp_path)
    assert webbed.key != plain.key and webbed.options.web_divisions == 6.0
    across = web_elements_across(webbed.mesh, web_groups(webbed.mesh), g.web_thickness)
    assert len(across) == 2 and all(w.across >= MIN_ELEMENTS_ACROSS for w in across)
