"""Mirrored meshes of symmetric throws (``fe_crank.mesh.mirror``, ``mesh_throw`` with
``symmetric = True``): exact self-mapping, volumes, orientation, named groups, the cut
faces gone, the .msh file, the cache, quality against the unmirrored mesh."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from helpers.geometry import base_throw as _base
from skfem import Basis, ElementTetP2, Functional, MeshTet, MeshTet2

from fe_crank.geometry import mass_properties
from fe_crank.gmsh_io import corner_jacobians
from fe_crank.io.geometry import geometry_from_dict, load_geometry
from fe_crank.mesh import PRESETS, mesh_throw
from fe_crank.mesh.mirror import mirror_all, mirror_mesh, swap_side

ROOT = Path(__file__).resolve().parents[2]
SEED001 = ROOT / "geometry" / "single_cylinder.toml"
SYM = dataclasses.replace(PRESETS["test"], symmetric=True)
ONE = Functional(lambda w: 1.0 + 0.0 * w.x[0])


def _volume(m, elements=None) -> float:
    return ONE.assemble(Basis(m, ElementTetP2(), elements=elements))


def _image_index(P: np.ndarray, axis: int) -> np.ndarray:
    """For every node, the index of the node at its mirror image (exact coordinates); -1 if none."""
    Q = P.copy()
    Q[:, axis] = -Q[:, axis]
    Q[Q == 0.0] = 0.0  # -0.0 -> 0.0 for the byte-wise comparison below
    P = P.copy()
    P[P == 0.0] = 0.0
    a = np.ascontiguousarray(P).view([("", float)] * 3).ravel()
    b = np.ascontiguousarray(Q).view([("", float)] * 3).ravel()
    order = np.argsort(a)
    pos = np.minimum(np.searchsorted(a[order], b), a.size - 1)
    return np.where(a[order][pos] == b, order[pos], -1)


def _check_self_image(m, axis: int, rename) -> None:
    """Nodes, elements, subdomains and boundaries map onto themselves under x_axis -> -x_axis."""
    img = _image_index(m.doflocs.T, axis)
    assert np.all(img >= 0), "a node without an exact mirror image"
    key = lambda a: np.sort(a, axis=0).T.tolist()
    elements = {tuple(r): i for i, r in enumerate(key(m.t))}
    eimg = np.array([elements.get(tuple(r), -1) for r in key(img[m.t])])
    assert np.all(eimg >= 0), "an element without a mirror image"
    for name, idx in m.subdomains.items():
        assert np.array_equal(np.sort(eimg[idx]), np.sort(m.subdomains[rename(name)])), name
    for name, idx in m.boundaries.items():
        got = sorted(map(tuple, key(img[m.facets[:, idx]])))
        want = sorted(map(tuple, key(m.facets[:, m.boundaries[rename(name)]])))
        assert got == want, name
    # quadratic geometry mirrored too: every element's 10 nodes map onto its image's 10 nodes
    edofs = m.dofs.element_dofs
    assert np.array_equal(np.sort(img[edofs], axis=0), np.sort(edofs[:, eimg], axis=0))


def test_unit_cube_mirrored_by_hand():
    """[0,1]^3 refined once (27 vertices, 9 on x = 0) mirrored across x = 0: [-1,1]x[0,1]^2,
    volume 2, 27 + 18 = 45 vertices, 2 x 48 = 96 elements, all positively oriented; named
    groups: the face x = 1 maps to x = -1 under its own name, or to a renamed one."""
    cube = MeshTet.init_tensor(*(np.linspace(0, 1, 3),) * 3)
    m = MeshTet2.from_mesh(cube)
    far = np.flatnonzero(np.isclose(m.p[0, m.facets].mean(axis=0), 1.0))
    m = m.with_boundaries({"end_1": far}).with_subdomains({"web_1": np.arange(m.nelements)})
    full = mirror_mesh(m, 0, rename=swap_side)
    assert full.nvertices == 45 and full.nelements == 2 * cube.nelements == 96
    assert _volume(full) == pytest.approx(2.0, rel=1e-12)
    # each image keeps its element's orientation (scikit-fem's tensor mesh mixes both signs)
    J = corner_jacobians(full)
    assert np.array_equal(np.sign(J[48:]), np.sign(J[:48])) and np.all(J != 0)
    assert sorted(full.boundaries) == ["end_1", "end_2"] and sorted(full.subdomains) == ["web_1", "web_2"]
    assert np.all(full.p[0, full.facets[:, full.boundaries["end_2"]]] == -1.0)
    assert (
        full.boundary_facets().size == 2 * cube.boundary_facets().size - 2 * 8
    )  # the 8 facets of x = 0 became interior
    _check_self_image(full, 0, swap_side)
    # and a second plane: [-1,1]x[0,1]x[-1,1], volume 4
    both = mirror_all(
        MeshTet2.from_mesh(MeshTet.init_tensor(np.linspace(0, 1, 3), np.linspace(0, 1, 3), np.linspace(-1, 0, 3))),
        (0, 2),
    )
    assert _volume(both) == pytest.approx(4.0, rel=1e-12) and both.nvertices == 5 * 3 * 5


def test_mesh_on_both_sides_refused():
    from fe_crank.errors import MeshError

    m = MeshTet2.from_mesh(MeshTet.init_tensor(np.linspace(-1, 1, 3), np.linspace(0, 1, 2), np.linspace(0, 1, 2)))
    with pytest.raises(MeshError, match="both sides"):
        mirror_mesh(m, 0)


@pytest.fixture(scope="module", autouse=True)
def both_planes():
    """These tests check the mirroring across either plane and both: let ``mesh_throw``
    mirror across every exact plane (by default it uses the mid-plane only,
    ``fe_crank.mesh.planes.MESH_PLANES``)."""
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr("fe_crank.mesh.planes.MESH_PLANES", (0, 2))
        yield


@pytest.fixture(scope="module")
def seed001(tmp_path_factory, both_planes):
    g = load_geometry(SEED001)
    c = tmp_path_factory.mktemp("cache")
    sym = mesh_throw(g, size=SYM, cache_dir=c)
    plain = mesh_throw(g, size=dataclasses.replace(PRESETS["test"], symmetric=False), cache_dir=c)
    assert PRESETS["test"].symmetric is True  # mirrored meshes are the default
    return g, sym, plain, c


def test_seed001_gets_both_planes_and_maps_onto_itself(seed001):
    _, tm, plain, _ = seed001
    assert tm.symmetry == (0, 2) and tm.stats.symmetry == (0, 2) and plain.symmetry == ()
    _check_self_image(tm.mesh, 0, lambda n: n)
    _check_self_image(tm.mesh, 2, swap_side)
    assert set(tm.mesh.boundaries) == set(plain.mesh.boundaries)
    assert set(tm.mesh.subdomains) == set(plain.mesh.subdomains)


def test_seed001_volumes_match_the_solid(seed001):
    """P2 volume of the whole mirrored mesh and of each part against the OCC B-rep
    (``mass_properties``), with the tolerances of the unmirrored mesh's test (tests/mesh/test_mesh_throw.py):
    2e-4 total, 1e-3 per part (the test preset's straightened curved elements)."""
    g, tm, _, _ = seed001
    mp = mass_properties(g)
    m = tm.mesh
    assert _volume(m) == pytest.approx(mp.total.volume, rel=2e-4)
    for name, idx in m.subdomains.items():
        assert _volume(m, idx) == pytest.approx(mp.parts[name].volume, rel=1e-3), name


def test_seed001_no_facet_on_the_planes_is_a_boundary(seed001):
    _, tm, _, _ = seed001
    m = tm.mesh
    bf = m.boundary_facets()
    for axis in (0, 2):
        assert not np.any(np.all(m.p[axis][m.facets[:, bf]] == 0.0, axis=0))
        for name, idx in m.boundaries.items():
            assert not np.any(np.all(m.p[axis][m.facets[:, idx]] == 0.0, axis=0)), name
    # named boundary facets are all outer facets
    named = np.unique(np.concatenate(list(m.boundaries.values())))
    assert np.all(np.isin(named, bf))


def test_seed001_positive_jacobians_and_quality_near_unmirrored(seed001):
    """Quality against the unmirrored mesh of the same preset: gmsh meshes of the two domains
    differ, so an exact match is not expected; a margin of 20 % on minSICN and on the Jacobian
    ratio catches what a bad cut would do (slivers on the cut faces: minSICN ~0.01, or folded
    elements: ratio ~1e-3, tests/mesh/test_mesh_throw.py)."""
    _, tm, plain, _ = seed001
    assert np.all(corner_jacobians(tm.mesh) > 0)
    assert tm.stats.min_quality >= 0.8 * plain.stats.min_quality
    assert tm.stats.min_jacobian_ratio >= 0.8 * plain.stats.min_jacobian_ratio
    s = tm.stats
    assert (s.nodes, s.elements, s.p2_dofs) == (
        tm.mesh.doflocs.shape[1],
        tm.mesh.nelements,
        3 * tm.mesh.doflocs.shape[1],
    )


def test_seed001_msh_and_vtu_are_the_whole_mesh(seed001):
    import meshio

    _, tm, _, _ = seed001
    m = tm.mesh
    msh = meshio.read(tm.msh_path)
    assert msh.points.shape[0] == m.doflocs.shape[1]
    assert msh.cells_dict["tetra10"].shape[0] == m.nelements
    assert msh.cells_dict["triangle6"].shape[0] == sum(v.size for v in m.boundaries.values())
    assert set(msh.field_data) == set(m.boundaries) | set(m.subdomains)
    # read back by gmsh itself into scikit-fem (fe_crank.gmsh_io): same groups, same volumes
    from fe_crank.gmsh_io import gmsh_session, model_to_skfem

    with gmsh_session() as gmsh:
        gmsh.open(str(tm.msh_path))
        back = model_to_skfem()
    assert _volume(back) == pytest.approx(_volume(m), rel=1e-12)
    assert {k: v.size for k, v in back.boundaries.items()} == {k: v.size for k, v in m.boundaries.items()}
    for name, idx in m.subdomains.items():
        assert _volume(back, back.subdomains[name]) == pytest.approx(_volume(m, idx), rel=1e-12), name
    vtu = meshio.read(tm.vtu_path)
    assert vtu.cells_dict["tetra10"].shape == (m.nelements, 10)


def test_seed001_symmetry_survives_the_cache(seed001):
    g, tm, _, c = seed001
    again = mesh_throw(g, size=SYM, cache_dir=c)
    assert again.stats.from_cache and again.symmetry == (0, 2) and again.key == tm.key
    assert np.array_equal(again.mesh.doflocs, tm.mesh.doflocs)


def test_oblique_bore_gets_only_z():
    g = geometry_from_dict(
        _base(
            crankpin={"fillet_radius": "3 mm", "oil_bore": {"diameter": "6 mm", "angle": "45 deg"}},
            journal={"fillet_radius": "3 mm"},
        )
    )
    tm = mesh_throw(g, size=SYM, cache_dir=None)
    assert tm.symmetry == (2,)
    assert tm.msh_path is None and tm.vtu_path is None and tm.cache_dir is None  # no cache: no file written
    _check_self_image(tm.mesh, 2, swap_side)
    assert np.any(_image_index(tm.mesh.doflocs.T, 0) < 0)  # not mirrored in x
    assert _volume(tm.mesh) == pytest.approx(mass_properties(g).total.volume, rel=2e-4)


def test_counterweight_on_one_web_gets_only_x():
    g = geometry_from_dict(
        _base(
            crankpin={"fillet_radius": "3 mm"},
            journal={"fillet_radius": "3 mm"},
            counterweight={"outer_radius": "70 mm", "inner_radius": "20 mm", "angle": "120 deg", "webs": [1]},
        )
    )
    tm = mesh_throw(g, size=SYM, cache_dir=None)
    assert tm.symmetry == (0,)
    _check_self_image(tm.mesh, 0, lambda n: n)
    assert "counterweight_1" in tm.mesh.subdomains and "counterweight_2" not in tm.mesh.subdomains
    mp = mass_properties(g)
    assert _volume(tm.mesh) == pytest.approx(mp.total.volume, rel=2e-4)
    assert _volume(tm.mesh, tm.mesh.subdomains["counterweight_1"]) == pytest.approx(
        mp.parts["counterweight_1"].volume, rel=1e-3
    )
