"""The robust inverse of the isoparametric map used for every surface integral."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import ElementTetP2, FacetBasis, MeshTet, MeshTet2

from fe_crank.errors import MeshError
from fe_crank.fe.core.supports import RobustIsoparametric, facet_basis


def curved_cube() -> MeshTet2:
    """A unit cube of quadratic tetrahedra bent by a smooth map (every element curved)."""
    m = MeshTet2.from_mesh(MeshTet().refined(1))
    x, y, z = m.doflocs
    bent = np.array([x + 0.15 * y**2, y + 0.1 * z**2, z + 0.1 * x**2])
    return MeshTet2(bent, m.t)


def test_inverse_map_recovers_reference_points():
    m = curved_cube()
    mp = RobustIsoparametric(m, m.elem(), m.bndelem)
    rng = np.random.default_rng(1)
    ne = m.nelements
    # random barycentric points inside, and points on the faces (one coordinate zero)
    b = rng.dirichlet(np.ones(4), size=(ne, 6))
    b[:, 3:, 0] = 0.0
    b /= b.sum(axis=-1, keepdims=True)
    X = np.moveaxis(b[..., 1:], -1, 0)  # (3, ne, 6)
    x = mp.F(X, np.arange(ne))
    Y = mp.invF(x, np.arange(ne))
    assert np.abs(Y - X).max() < 1e-10


def test_facet_integrals_agree_with_scikit_fem_where_it_converges():
    m = curved_cube()
    facets = m.boundary_facets()
    ours = facet_basis(m, ElementTetP2(), facets, 4, "test")
    theirs = FacetBasis(m, ElementTetP2(), facets=facets, intorder=4)
    assert float(ours.dx.sum()) == pytest.approx(float(theirs.dx.sum()), rel=1e-12)
    assert np.allclose(np.asarray(ours.normals), np.asarray(theirs.normals), atol=1e-10)


def test_degenerate_element_is_a_mesh_error():
    m = MeshTet2.from_mesh(MeshTet())
    p = m.doflocs.copy()
    p[2] = 0.0  # flatten the cube: every tetrahedron degenerate
    flat = MeshTet2(p, m.t)
    with pytest.raises(MeshError, match="too distorted"):
        facet_basis(flat, ElementTetP2(), flat.boundary_facets(), 2, "the flattened cube")


def test_shared_bases_are_bit_for_bit_the_scikit_fem_ones():
    """``cell_basis``/``facet_basis`` reuse one inverse Jacobian per basis, one dof numbering
    per mesh and one Newton inverse per facet basis: memos only, so every number must
    equal the basis scikit-fem builds from scratch (fresh mapping, own ``Dofs``), exactly."""
    from skfem import Basis

    from fe_crank.fe.core.supports import cell_basis

    m = curved_cube()
    ours = cell_basis(m, 2)
    ref = Basis(m, ElementTetP2(), intorder=2)
    assert np.array_equal(ours.dx, ref.dx) and np.array_equal(ours.doflocs, ref.doflocs)
    assert np.array_equal(ours.element_dofs, ref.element_dofs)
    for a, b in zip(ours.basis, ref.basis):
        assert np.array_equal(a[0].grad, b[0].grad) and np.array_equal(np.asarray(a[0]), np.asarray(b[0]))
    facets = m.boundary_facets()
    for _ in range(2):  # a second build on the same mesh: the memos are cleared
        fb = facet_basis(m, ElementTetP2(), facets, 4, "test")
        fresh = FacetBasis(
            m, ElementTetP2(), mapping=RobustIsoparametric(m, m.elem(), m.bndelem), facets=facets, intorder=4
        )
        assert np.array_equal(fb.dx, fresh.dx)
        assert np.array_equal(np.asarray(fb.normals), np.asarray(fresh.normals))
        assert np.array_equal(np.asarray(fb.global_coordinates()), np.asarray(fresh.global_coordinates()))
        for a, b in zip(fb.basis, fresh.basis):
            assert np.array_equal(a[0].grad, b[0].grad) and np.array_equal(np.asarray(a[0]), np.asarray(b[0]))


def test_edge_tables_are_scikit_fem_s():
    """``prime_edge_tables`` fills facets, t2f, edges, t2e and f2e by integer keys; scikit-fem's own
    ``np.unique(axis=1)`` build on a second copy of the mesh is the reference (equal
    arrays, dtypes and memory layout: the P2 edge-node numbering depends on them)."""
    from fe_crank.fe.core.supports import prime_edge_tables

    m = curved_cube()
    ours, ref = MeshTet2(m.doflocs, m.t), MeshTet2(m.doflocs, m.t)
    prime_edge_tables(ours)
    for name in ("facets", "t2f", "edges", "t2e", "f2e"):
        a, b = getattr(ours, name), getattr(ref, name)
        assert a.dtype == b.dtype and a.flags.c_contiguous == b.flags.c_contiguous
        assert np.array_equal(a, b), name


def test_a_mesh_s_mapping_and_numbering_are_shared_while_held_and_freed_with_it():
    """One mapping and one dof numbering per mesh while a basis holds them; nothing is stored
    on the mesh, and once the mesh and its bases are dropped they are collected."""
    import gc
    import weakref

    from fe_crank.fe.core.bases import cell_basis, mesh_dofs, robust_mapping

    m = curved_cube()
    cb = cell_basis(m, 2)
    fb = facet_basis(m, ElementTetP2(), m.boundary_facets(), 2, "test")
    assert fb.dofs is cb.dofs is mesh_dofs(m, ElementTetP2())
    assert fb.mapping is cb.mapping is robust_mapping(m)
    assert not {k for k in vars(m) if k.startswith("_fe_crank")}
    other = curved_cube()  # equal as a dataclass, another mesh: its own numbering
    assert mesh_dofs(other, ElementTetP2()) is not cb.dofs
    dead = weakref.ref(m)
    del m, cb, fb, other
    gc.collect()
    assert dead() is None
