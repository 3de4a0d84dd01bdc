"""The web size control of UR M53 App. III 2.2 (at least 6 elements across the web
thickness in an SCF model) in the CAD route: the small test throw exported to STEP and
meshed by the CAD route at the ``test`` preset has about two elements across its 12 mm
webs; with ``web_divisions = 6`` (what the SCF stage's refinement sets,
``rules.m53.scf_refine``) each recognised web gets edges of at most 0.7 W/6 and at least 6
elements across (``rules.m53.web_mesh``'s measure), as the parametric route does."""

from __future__ import annotations

import dataclasses

import pytest

from fe_crank.cad import CadInput, mesh_cad_throw
from fe_crank.mesh import PRESETS
from fe_crank.rules.m53.web_mesh import MIN_ELEMENTS_ACROSS, web_elements_across, web_groups

pytestmark = pytest.mark.heavy


def test_cad_webs_meshed_to_six_elements_across(small_throw_step, mesh_cache):
    g, step = small_throw_step
    cad = CadInput(step, density=g.density)
    plain = mesh_cad_throw(cad, "1", size="test", cache_dir=mesh_cache)
    across = web_elements_across(plain.mesh, web_groups(plain.mesh), g.web_thickness)
    assert len(across) == 2 and min(w.across for w in across) < MIN_ELEMENTS_ACROSS
    opts = dataclasses.replace(PRESETS["test"], web_divisions=6.0)
    webbed = mesh_cad_throw(cad, "1", size=opts, cache_dir=mesh_cache)
    assert webbed.key != plain.key and webbed.options.web_divisions == 6.0
    across = web_elements_across(webbed.mesh, web_groups(webbed.mesh), g.web_thickness)
    assert len(across) == 2 and all(w.across >= MIN_ELEMENTS_ACROSS for w in across)
