"""Averaged nodal stresses of many displacement fields at selected nodes, in one pass.

The same stress as ``fe.stress.stress_at_selected_nodes`` (the P2 field's gradient at the
element's own node, Hooke's law, the average over every element sharing the node), for k
fields at once: at each (element, node) pair the gradient of all k fields is one small
matrix product, grad u = G^T U with G (m x 3) the shape functions' gradients there and U
(m x 3k) the element's nodal displacements of every field, so the cost no longer grows
with a pass per field.  The fields are given on a subset of the nodes (``rows``: the
nodes that carry them; every node of an element around a selected node must be among
them), as the whole shaft keeps its condensed fields (``fe.substructure``).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from fe_crank.errors import MeshError
from fe_crank.fe.forms import lame_parameters
from fe_crank.fe.stress import NODE_CHUNK, _node_dofs, elements_of_nodes, node_gradients

#: (element, node) pairs per block (the block's gathered fields, m x 3k each, stay small)
PAIRS = 2048


def stress_of_fields(
    mesh, rows: np.ndarray, U: np.ndarray, youngs_modulus: float, poisson_ratio: float, nodes, *, dofs=None
) -> np.ndarray:
    """(k, 6, len(nodes)) averaged nodal stress (Voigt xx yy zz xy yz zx, Pa) of the k fields
    ``U`` (3 len(rows), k), interleaved per node of ``rows`` (module doc)."""
    dofs = _node_dofs(mesh, dofs)
    nodes = np.asarray(nodes, dtype=np.int64)
    rows = np.asarray(rows, dtype=np.int64)
    n_all = int(dofs.element_dofs.max()) + 1
    k = U.shape[1]
    Un = np.asarray(U, float).reshape(rows.size, 3, k)
    row_of = np.full(n_all, -1, dtype=np.int64)
    row_of[rows] = np.arange(rows.size)
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    elements = elements_of_nodes(dofs.element_dofs, nodes, n_all)
    local = np.full(n_all, -1, dtype=np.int64)
    local[nodes] = np.arange(nodes.size)
    out = np.zeros((6 * k, nodes.size))
    count = np.zeros(nodes.size)
    for _, G, ed in node_gradients(mesh, dofs, NODE_CHUNK, elements=elements):  # G (m, 3, nc, m)
        loc = local[ed.T]
        e_p, q_p = np.nonzero(loc >= 0)
        where = loc[e_p, q_p]
        count += np.bincount(where, minlength=nodes.size)
        r = row_of[ed]
        if np.any(r[:, np.unique(e_p)] < 0):
            raise MeshError("a field is missing at a node of an element around a selected node")
        for b in range(0, e_p.size, PAIRS):
            sl = slice(b, b + PAIRS)
            Gp = G[:, :, e_p[sl], q_p[sl]].transpose(2, 1, 0)  # (P, 3, m)
            Ue = Un[r[:, e_p[sl]]].transpose(1, 0, 2, 3)  # (P, m, 3, k)
            P, m = Ue.shape[0], Ue.shape[1]
            H = np.matmul(Gp, Ue.reshape(P, m, 3 * k)).reshape(P, 3, 3, k)  # H[p, j, i] = du_i/dx_j
            tr = H[:, 0, 0] + H[:, 1, 1] + H[:, 2, 2]  # (P, k)
            S = np.empty((P, 6, k))
            for c, (i, j) in enumerate(((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0))):
                S[:, c] = mu * (H[:, j, i] + H[:, i, j]) + (lam * tr if i == j else 0.0)
            A = sp.csr_matrix((np.ones(P), (where[sl], np.arange(P))), shape=(nodes.size, P))
            out += (A @ S.reshape(P, 6 * k)).T
    if np.any(count == 0):
        raise MeshError("stress requested at nodes that belong to no element")
    return (out / count).reshape(6, k, nodes.size).transpose(1, 0, 2)
