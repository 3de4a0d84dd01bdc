"""The robust inverse of the isoparametric map used for every surface integral."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import ElementTetP2, FacetBasis, MeshTet, MeshTet2

from fe_crank.errors import MeshError
from fe_crank.fe.supports import RobustIsoparametric, facet_basis


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
    X = np.moveaxis(b[..., 1:], -1, 0)        # (3, ne, 6)
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
    p[2] = 0.0                                  # flatten the cube: every tetrahedron degenerate
    flat = MeshTet2(p, m.t)
    with pytest.raises(MeshError, match="too distorted"):
        facet_basis(flat, ElementTetP2(), flat.boundary_facets(), 2, "the flattened cube")
