"""UR M53 App. III 2.2, at least 6 elements across the web thickness: on meshes in layers the
measure n = W / mean(axial extent of the crossed elements) is the number of layers exactly,
whatever the in-plane size; a real throw's webs are measured."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import MeshTet

from fe_crank.rules.m53.web_mesh import MIN_ELEMENTS_ACROSS, web_elements_across, web_groups


def _layers(layers: int, thickness: float = 0.02, n_xy: int = 5) -> MeshTet:
    """A web-like plate 60 x 40 mm in xy, ``thickness`` in z, cut into ``layers`` layers
    (each hexahedron split into tetrahedra that span its whole height)."""
    m = MeshTet.init_tensor(
        np.linspace(-0.03, 0.03, n_xy + 1), np.linspace(0.0, 0.04, n_xy), np.linspace(0.0, thickness, layers + 1)
    )
    return m.with_subdomains({"web_1": lambda x: np.ones(x.shape[1], bool)})


@pytest.mark.parametrize(("layers", "n_xy"), [(2, 4), (3, 7), (6, 5), (9, 3)])
def test_layers_are_counted_exactly(layers, n_xy):
    m = _layers(layers, n_xy=n_xy)
    dz = m.p[2, m.t].max(axis=0) - m.p[2, m.t].min(axis=0)
    assert np.allclose(dz, 0.02 / layers)  # every element spans one layer
    (w,) = web_elements_across(m, web_groups(m), 0.02)
    assert w.web == "web_1" and w.lines == 5
    assert w.across == pytest.approx(layers, rel=1e-12)
    assert w.ok == (layers >= MIN_ELEMENTS_ACROSS)


def test_sample_lines_outside_the_web_and_bad_input():
    m = _layers(3)
    with pytest.raises(ValueError, match="no sample line"):
        web_elements_across(m, web_groups(m), 0.02, points={"web_1": np.array([[1.0], [1.0]])})
    with pytest.raises(ValueError, match="thickness"):
        web_elements_across(m, web_groups(m), 0.0)


@pytest.mark.heavy
def test_webs_of_a_real_throw_at_two_presets(mesh_cache):
    """The small test throw (W = 10 mm): the coarse preset meshes its webs with more elements
    across than the test preset (measured in the report of this change).  Both meshes
    from the run's cache: they are the small throw's meshes other tests build too."""
    from fe_crank.io.geometry import load_geometry
    from fe_crank.mesh import mesh_throw

    g = load_geometry("tests/data/geometry_small.toml")
    found = {}
    for preset in ("test", "coarse"):
        tm = mesh_throw(g, size=preset, cache_dir=mesh_cache)
        webs = web_elements_across(tm.mesh, web_groups(tm.mesh), g.web_thickness)
        assert {w.web for w in webs} == {"web_1", "web_2"}
        found[preset] = min(w.across for w in webs)
    assert found["coarse"] > found["test"] > 0
