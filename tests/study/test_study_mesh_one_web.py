"""A throw with a counterweight on one web only (the study writes such throws for a
"4 of 8" placement) is meshed whole, without the mirror plane z = 0; its bare web's
pear outline then meets gmsh uncut.  Before the web's arcs were broken at the circle's
parametric seam (``geometry.solid``) gmsh stopped on such a throw with "the 1D mesh
seems not to be forming a closed loop"."""

from __future__ import annotations

from fe_crank.io.geometry import load_geometry
from fe_crank.mesh import mesh_throw
from fe_crank.mesh.planes import mesh_planes

PEAR_ONE_WEB = """
name = "inline-4 throw (geometry/inline4.toml without its oil bore), one counterweight"
density = "7850 kg/m^3"
crank_radius = "43 mm"
[journal]
diameter = "56 mm"
length = "12 mm"
fillet_radius = "2.5 mm"
[crankpin]
diameter = "48 mm"
length = "18 mm"
fillet_radius = "2.5 mm"
[web]
thickness = "12 mm"
outline = "pear"
journal_end_radius = "42 mm"
pin_end_radius = "33 mm"
[[throws]]
name = "1"
angle = "0 deg"
counterweight = { outer_radius = "80 mm", inner_radius = "35 mm", angle = "120 deg", webs = [1] }
"""


def test_a_pear_throw_with_one_counterweight_meshes_whole(tmp_path):
    path = tmp_path / "pear.toml"
    path.write_text(PEAR_ONE_WEB)
    g = load_geometry(path)
    assert mesh_planes(g, "1") == ()  # meshed whole: both webs' outlines reach gmsh
    tm = mesh_throw(g, "1", size="test", cache_dir=None)
    assert {"web_1", "web_2", "counterweight_1"} <= set(tm.mesh.subdomains)
    assert tm.stats.min_quality > 0.0
