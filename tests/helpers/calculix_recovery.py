"""CalculiX's nodal-stress recovery of a C3D10 element, reproduced on a P2 field: an
independent recovery that the tests compare fe-crank's with, and that
benchmarks/verification/ccx_recovery.py uses to explain the two programs' differences.

CalculiX 2.20 (``extrapolate.f``, C3D10, stresses in the global frame) recovers nodal
stresses in three steps:

1. the stress at the element's 4 integration points (the 4-point tetrahedron rule:
   barycentric coordinates a at the point's own corner and b at the three others,
   a = (5 + 3 sqrt 5) / 20 = 0.58541, b = (5 - sqrt 5) / 20 = 0.13820);
2. corner values by the linear (C3D4) interpolation through those four values: a
   linear field L with corner values L_k has at point k the value
   v_k = (a - b) L_k + b sum_j L_j, and sum_k v_k = (a + 3 b) sum_j L_j = sum_j L_j,
   so L_k = (v_k - b sum_j v_j) / (a - b): diagonal (1 - b)/(a - b) = 1.92705, off the
   diagonal -b/(a - b) = -0.30902 (CalculiX tabulates these two to 5 digits, a 1e-5
   difference from the exact values used here);
3. each mid-edge node gets the mean of its edge's two corner values, and every node the
   unweighted mean over the elements that share it.

fe-crank (``fe.core.stress.stress_at_selected_nodes``) evaluates each element's stress at its
10 nodes from the P2 field itself and averages the same way.  On a straight-sided
element the stress is linear, so steps 1-3 reproduce it exactly and both recoveries give
the same nodal average; they differ only where a curved (isoparametric) element shares
the node: there the stress is not linear in the element and the linear extrapolation
differs from the value at the node.
"""

from __future__ import annotations

import numpy as np
from skfem import Basis, ElementTetP2

from fe_crank.fe.core.stress import elements_of_nodes, stress_at_quadrature

GAUSS_A = (5.0 + 3.0 * np.sqrt(5.0)) / 20.0
GAUSS_B = (5.0 - np.sqrt(5.0)) / 20.0


def _edges() -> np.ndarray:
    """(6, 2) corner pairs of the P2 tetrahedron's mid-edge nodes 4..9 (scikit-fem order),
    found from the reference node positions."""
    X = np.asarray(ElementTetP2().doflocs, float)  # (10, 3)
    pairs = []
    for m in range(4, 10):
        pairs.append(next((i, j) for i in range(4) for j in range(i + 1, 4) if np.allclose(0.5 * (X[i] + X[j]), X[m])))
    return np.array(pairs)


EDGES = _edges()


def gauss_points() -> np.ndarray:
    """(3, 4) reference coordinates of the 4-point rule, point k nearest corner k (corner
    0 at the origin, corner k = e_k): barycentric a at its own corner, b elsewhere."""
    a, b = GAUSS_A, GAUSS_B
    lam = np.full((4, 4), b) + np.eye(4) * (a - b)  # lam[k, j]: point k, corner j
    return lam[:, 1:].T.copy()  # (x, y, z) = (lam1, lam2, lam3)


def calculix_recovery(mesh, dofs, youngs_modulus: float, poisson_ratio: float, displacements, nodes) -> np.ndarray:
    """(k, 6, len(nodes)) CalculiX's C3D10 nodal stresses (module docstring) of interleaved
    P2 displacement vectors on ``mesh`` (a ``MeshTet2``; ``dofs`` its scalar P2 ``Dofs``)."""
    nodes = np.asarray(nodes, dtype=np.int64)
    n_all = int(dofs.element_dofs.max()) + 1
    els = elements_of_nodes(dofs.element_dofs, nodes, n_all)
    gb = Basis(mesh, ElementTetP2(), quadrature=(gauss_points(), np.full(4, 1.0 / 24.0)), elements=els, dofs=dofs)
    ed = dofs.element_dofs[:, els]  # (10, ne)
    local = np.full(n_all, -1, dtype=np.int64)
    local[nodes] = np.arange(nodes.size)
    loc = local[ed]
    keep = loc >= 0
    count = np.bincount(loc[keep], minlength=nodes.size)
    out = np.zeros((len(displacements), 6, nodes.size))
    for j, u in enumerate(displacements):
        v = stress_at_quadrature(gb, np.asarray(u, float), youngs_modulus, poisson_ratio)  # (6, ne, 4)
        corners = (v - GAUSS_B * v.sum(axis=2, keepdims=True)) / (GAUSS_A - GAUSS_B)
        mids = 0.5 * (corners[:, :, EDGES[:, 0]] + corners[:, :, EDGES[:, 1]])
        el = np.concatenate([corners, mids], axis=2).transpose(0, 2, 1)  # (6, 10, ne)
        for k in range(6):
            out[j, k] = np.bincount(loc[keep], el[k][keep], minlength=nodes.size)
    return out / count
