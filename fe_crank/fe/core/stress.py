"""Stress recovery: at quadrature points, at element nodes (unaveraged) and averaged at nodes.

Stress components are in Voigt order (xx, yy, zz, xy, yz, zx), shape (6, ...), Pa.
sigma = 2 mu eps + lambda tr(eps) I with eps = sym(grad u) (Hooke's law).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from skfem import Basis, ElementTetP2

from fe_crank.errors import MeshError
from fe_crank.fe.core.assembly import shape_gradients
from fe_crank.fe.core.forms import lame_parameters

VOIGT = ("xx", "yy", "zz", "xy", "yz", "zx")
_IJ = ((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0))


def _stress_from_gradients(G: np.ndarray, edofs: np.ndarray, u: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """sigma (6, ne, nq) from scalar gradients G (m, 3, ne, nq) and element dofs (m, ne).

    grad u: H_ij = sum_a U_ai dphi_a/dx_j, summed over the m local nodes a = 0, 1, ...
    in turn (the order ``np.einsum("aei,ajeq->ijeq")`` takes, so the same bits, at about
    two thirds of its time).
    """
    U = u.reshape(-1, 3)[edofs]  # (m, ne, 3)
    return _hooke(_grad_u(G, lambda a, i: U[a, :, i][None, :, None]), lam, mu)


def _grad_u(G: np.ndarray, coef: Callable[[int, int], np.ndarray]) -> np.ndarray:
    """H_ij = du_i/dx_j = sum_a U_ai G_aj..., a = 0, 1, ... in turn; ``coef(a, i)`` is U_ai
    shaped to broadcast against G[a] (3, ...)."""
    H = np.empty((3,) + G.shape[1:])
    tmp = np.empty(G.shape[1:])
    for i in range(3):
        acc = H[i]
        np.multiply(coef(0, i), G[0], out=acc)
        for a in range(1, G.shape[0]):
            acc += np.multiply(coef(a, i), G[a], out=tmp)
    return H


def _hooke(H: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """sigma (6, ...) from grad u (3, 3, ...): eps = sym(H), sigma = 2 mu eps + lam tr(eps) I."""
    eps = 0.5 * (H + np.swapaxes(H, 0, 1))
    tr = eps[0, 0] + eps[1, 1] + eps[2, 2]
    s = np.empty((6,) + tr.shape)
    for k, (i, j) in enumerate(_IJ):
        s[k] = 2.0 * mu * eps[i, j] + (lam * tr if i == j else 0.0)
    return s


def _stress_at_pairs(Gp: np.ndarray, edofs: np.ndarray, u: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """sigma (6, P) at P (element, point) pairs: gradients Gp (m, 3, P), element dofs (m, P).
    The operations of ``_stress_from_gradients``, value by value."""
    base = 3 * edofs
    U = [u[base + i] for i in range(3)]  # U[i][a, p]: u_i at local node a of pair p
    return _hooke(_grad_u(Gp, lambda a, i: U[i][a][None, :]), lam, mu)


#: (element, node) pairs per block of ``stress_at_selected_nodes`` (the block's gradients,
#: 10 x 3 x 4096 x 8 B = 1 MB, stay in cache while every field is evaluated on them)
PAIR_BLOCK = 4096


NODE_CHUNK = 40000  # elements per node-basis chunk (the full basis of a 1M-dof mesh is ~1 GB)


def _node_dofs(mesh, dofs):
    if dofs is None:
        from skfem.assembly import Dofs

        dofs = Dofs(mesh, ElementTetP2())
    return dofs


def node_gradients(mesh, dofs=None, chunk: int = NODE_CHUNK, elements=None):
    """Yield (element indices, scalar P2 gradients (m, 3, ne, m) at the element's own nodes,
    element dofs (m, ne)): what a scalar P2 ``CellBasis`` whose quadrature points are the
    element's nodes gives (its gradients and element dofs), without building the basis.

    grad phi_a = DF^-T grad_ref phi_a at every node of every element, from scikit-fem's
    own mapping (``mesh._mapping()``: its ``invDF`` and the element's ``lbasis``) with the
    contraction scikit-fem's ``ElementH1.gbasis`` uses, so the same bits; the inverse
    Jacobian is evaluated once per chunk instead of once per basis function (a
    ``CellBasis`` evaluates it for each of its m functions).
    """
    e = ElementTetP2()
    X = np.asarray(e.doflocs, float).T  # (3, m) reference nodes
    dofs = _node_dofs(mesh, dofs)
    mapping = mesh._mapping()
    elements = np.arange(mesh.t.shape[1]) if elements is None else np.asarray(elements)
    dphi = [e.lbasis(X, a)[1] for a in range(X.shape[1])]
    for start in range(0, elements.size, chunk):
        idx = elements[start : start + chunk]
        invDF = mapping.invDF(X, idx)
        G = np.stack([np.einsum("ijkl,il->jkl", invDF, d) for d in dphi])
        yield idx, G, dofs.element_dofs[:, idx]


def elements_of_nodes(element_dofs: np.ndarray, nodes, n_nodes: int) -> np.ndarray:
    """Ascending indices of the elements (columns of ``element_dofs`` (m, ne)) that have
    at least one of ``nodes``: every element that enters the nodal average at them."""
    mask = np.zeros(n_nodes, bool)
    mask[np.asarray(nodes)] = True
    return np.flatnonzero(mask[element_dofs].any(axis=0))


def element_nodal_stress(
    mesh, u: np.ndarray, youngs_modulus: float, poisson_ratio: float, *, dofs=None, elements=None
) -> tuple[np.ndarray, np.ndarray]:
    """Unaveraged stress at each element's nodes: (6, m, ne) and the node numbers (m, ne).

    ``elements``: only these elements (ascending), columns in that order.
    """
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    ne = mesh.t.shape[1] if elements is None else len(elements)
    out = np.empty((6, 10, ne))
    nodes = np.empty((10, ne), dtype=np.int64)
    pos = 0
    for idx, G, ed in node_gradients(mesh, dofs, elements=elements):
        sl = slice(pos, pos + idx.size)
        s = _stress_from_gradients(G, ed, u, lam, mu)  # (6, n, m): points = nodes
        out[:, :, sl] = s.transpose(0, 2, 1)
        nodes[:, sl] = ed
        pos += idx.size
    return out, nodes


def nodal_average(s_el: np.ndarray, nodes: np.ndarray, n: int) -> np.ndarray:
    """Element-nodal stresses (6, m, ne) at their node numbers (m, ne) averaged at the ``n`` nodes: (6, n)."""
    count = np.bincount(nodes.ravel(), minlength=n)
    out = np.stack([np.bincount(nodes.ravel(), s_el[k].ravel(), minlength=n) for k in range(6)])
    return out / np.maximum(count, 1)


def stress_at_nodes(mesh, u: np.ndarray, youngs_modulus: float, poisson_ratio: float, *, dofs=None) -> np.ndarray:
    """Nodal stress (6, n_nodes) averaged over the elements sharing each P2 node."""
    s, nodes = element_nodal_stress(mesh, u, youngs_modulus, poisson_ratio, dofs=dofs)
    return nodal_average(s, nodes, u.size // 3)


def stress_at_selected_nodes(
    mesh, displacements, youngs_modulus: float, poisson_ratio: float, nodes, *, dofs=None, chunk: int = NODE_CHUNK
) -> np.ndarray:
    """Averaged nodal stress of several fields at ``nodes`` only: (k, 6, len(nodes)).

    ``displacements``: k interleaved displacement vectors (a sequence or an array (k, 3 N)).
    The average at a node takes every element sharing it (``elements_of_nodes``), exactly as
    :func:`stress_at_nodes` does, so the values equal ``stress_at_nodes(mesh, u)[:, nodes]``
    (to the last bits of the summation order); only those elements are visited, and the
    node basis of each chunk (the isoparametric map at the nodes) is built once for all k
    fields instead of once per field.
    """
    dofs = _node_dofs(mesh, dofs)
    nodes = np.asarray(nodes, dtype=np.int64)
    U = [np.asarray(u, float) for u in displacements]
    n_all = U[0].size // 3
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    elements = elements_of_nodes(dofs.element_dofs, nodes, n_all)
    local = np.full(n_all, -1, dtype=np.int64)
    local[nodes] = np.arange(nodes.size)
    out = np.zeros((len(U), 6, nodes.size))
    count = np.zeros(nodes.size)
    for _, G, ed in node_gradients(mesh, dofs, chunk, elements=elements):  # ed (m, nc)
        loc = local[ed.T]  # (nc, m), -1 where not selected
        e_p, q_p = np.nonzero(loc >= 0)  # (element, local node) pairs kept, element-major
        where = loc[e_p, q_p]
        count += np.bincount(where, minlength=nodes.size)
        # the stress only where it is averaged: at the kept pairs (the same operations on
        # the same operands as on the whole chunk, so the same values)
        S = np.empty((len(U), 6, e_p.size))
        for b in range(0, e_p.size, PAIR_BLOCK):
            sl = slice(b, b + PAIR_BLOCK)
            Gp = G[:, :, e_p[sl], q_p[sl]]  # (m, 3, p)
            ep = ed[:, e_p[sl]]  # (m, p)
            for j, u in enumerate(U):
                S[j, :, sl] = _stress_at_pairs(Gp, ep, u, lam, mu)
        for j in range(len(U)):
            for k in range(6):
                out[j, k] += np.bincount(where, S[j, k], minlength=nodes.size)
    if np.any(count == 0):
        raise MeshError("stress requested at nodes that belong to no element")
    return out / count


def stress_at_quadrature(
    basis: Basis, u: np.ndarray, youngs_modulus: float, poisson_ratio: float, *, elements=None
) -> np.ndarray:
    """Stress (6, ne, nq) at the quadrature points of ``basis`` (scalar P2); ``elements``:
    only these elements of the basis (in that order)."""
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    if elements is None:
        return _stress_from_gradients(shape_gradients(basis), basis.element_dofs, u, lam, mu)
    G = np.stack([b[0].grad[:, elements] for b in basis.basis])  # slice first: no whole-mesh copy
    return _stress_from_gradients(G, basis.element_dofs[:, elements], u, lam, mu)


def von_mises(s: np.ndarray) -> np.ndarray:
    """sigma_v = sqrt(((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2 + 3 (t12^2 + t23^2 + t31^2)) (von Mises 1913)."""
    sxx, syy, szz, sxy, syz, szx = s
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * (sxy**2 + syz**2 + szx**2))


def tensor(s: np.ndarray) -> np.ndarray:
    """Symmetric 3x3 tensors (..., 3, 3) from Voigt stress (6, ...)."""
    sxx, syy, szz, sxy, syz, szx = s
    return np.stack([np.stack([sxx, sxy, szx], -1), np.stack([sxy, syy, syz], -1), np.stack([szx, syz, szz], -1)], -2)


def principal(s: np.ndarray) -> np.ndarray:
    """Principal stresses (3, ...), sigma_1 >= sigma_2 >= sigma_3 (eigenvalues of the tensor)."""
    w = np.linalg.eigvalsh(tensor(s))
    return np.moveaxis(w[..., ::-1], -1, 0)


def max_shear(s: np.ndarray) -> np.ndarray:
    """Maximum shear stress tau_max = (sigma_1 - sigma_3) / 2 (Tresca)."""
    p = principal(s)
    return 0.5 * (p[0] - p[2])


def averaging_indicator(
    mesh, u: np.ndarray, youngs_modulus: float, poisson_ratio: float, groups, *, dofs=None
) -> dict[str, float]:
    """IACS UR M53 FE-appendix mesh check for each fillet boundary in ``groups``.

    At the node of the fillet with the highest averaged von Mises stress, the largest
    unaveraged (element) value is compared with the averaged one:
    (max_elements sigma_v - sigma_v,avg) / sigma_v,avg.  M53 asks for agreement within 5 %.
    Only the elements that share a node with the groups are visited: they are all the
    elements of those nodes' averages, so the result equals the whole-mesh computation.
    """
    dofs = _node_dofs(mesh, dofs)
    n = u.size // 3
    fnodes = {}
    for g in groups:
        if g not in (mesh.boundaries or {}):
            raise MeshError(f"mesh has no boundary {g!r}, needed by the averaging check")
        fnodes[g] = dofs.get_facet_dofs(mesh.boundaries[g]).all()
    if not fnodes:
        return {}
    elements = elements_of_nodes(dofs.element_dofs, np.concatenate(list(fnodes.values())), n)
    s_el, nodes = element_nodal_stress(mesh, u, youngs_modulus, poisson_ratio, dofs=dofs, elements=elements)
    vm_avg = von_mises(nodal_average(s_el, nodes, n))
    vm_el = von_mises(s_el).ravel()
    vm_max = np.zeros(n)
    np.maximum.at(vm_max, nodes.ravel(), vm_el)
    out = {}
    for g, fn in fnodes.items():
        i = fn[np.argmax(vm_avg[fn])]
        out[g] = float((vm_max[i] - vm_avg[i]) / vm_avg[i]) if vm_avg[i] > 0 else 0.0
    return out
