"""Vectorised assembly of vector-P2 forms from the scalar P2 basis (no element loops).

Degrees of freedom are interleaved like scikit-fem's ``ElementVector``: the vector dof
of component ``i`` at scalar dof ``s`` is ``3 s + i``.  Element matrices are contracted
with ``numpy.einsum`` in chunks of elements and summed by ``numpy.bincount`` into a
precomputed block pattern (the stiffness) or into the load vector.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import Basis, FacetBasis

from fe_crank.fe.core.forms import lame_parameters

# Hand-written rather than the weak form because measured faster: 27x skfem asm(linear_elasticity)
# (512 curved P2 tets, 2499 dofs, best of 3 in one run, load average 6, when it replaced asm),
# same K to 4e-16.  The block pattern by a packed sort (``unique_inverse``) instead of np.unique:
# 4.1 -> 3.1 CPU s for the whole kernel on the coarse single-cylinder throw (114k elements, best of 3), K
# bit for bit the same.  Not taken: a kernel of the blocks a <= b only, mirrored (2.8 CPU s, K
# exactly symmetric): it moves K by 3e-16 and the shipped figures by up to 5e-12.
CHUNK = 20000  # elements per einsum chunk: ~60 MB of element matrices


def shape_gradients(basis) -> np.ndarray:
    """Scalar basis gradients, shape (n_local, 3, n_elements, n_qp)."""
    return np.stack([b[0].grad for b in basis.basis])


def _values(basis) -> np.ndarray:
    """Scalar basis values, shape (n_local, n_elements, n_qp)."""
    return np.stack([np.asarray(b[0]) for b in basis.basis])


def vector_dofs(scalar_dofs: np.ndarray) -> np.ndarray:
    """Vector dofs (..., 3) of scalar dofs, interleaved 3 s + i."""
    s = np.asarray(scalar_dofs)
    return 3 * s[..., None] + np.arange(3)


def _coo_to_csr(ke: np.ndarray, edofs: np.ndarray, n: int) -> sp.csr_matrix:
    """Sum element matrices ke (ne, m, m) with local-to-global map edofs (ne, m)."""
    ne, m = edofs.shape
    rows = np.broadcast_to(edofs[:, :, None], (ne, m, m)).ravel()
    cols = np.broadcast_to(edofs[:, None, :], (ne, m, m)).ravel()
    return sp.coo_matrix((ke.ravel(), (rows, cols)), shape=(n, n)).tocsr()


def unique_inverse(key: np.ndarray, key_bound: int) -> tuple[np.ndarray, np.ndarray]:
    """``np.unique(key, return_inverse=True)`` of non-negative int64 keys below ``key_bound``.

    The same two arrays, from one ``np.sort`` of (key, index) packed into one int64 when
    both fit in 63 bits: numpy sorts plain integers several times faster than it argsorts
    them (``np.unique`` argsorts); falls back to ``np.unique`` when they do not fit.
    """
    n = key.size
    shift = max(int(n - 1).bit_length(), 1)
    if n == 0 or int(key_bound - 1).bit_length() + shift > 63:
        uniq, inv = np.unique(key, return_inverse=True)
        return uniq, inv.reshape(-1)
    packed = np.left_shift(key, shift)
    packed |= np.arange(n, dtype=np.int64)
    packed.sort()
    order = packed & ((1 << shift) - 1)
    packed >>= shift  # the sorted keys
    first = np.empty(n, bool)
    first[0] = True
    np.not_equal(packed[1:], packed[:-1], out=first[1:])
    uniq = packed[first]
    inv = np.empty(n, np.intp)
    inv[order] = np.cumsum(first) - 1
    return uniq, inv


def block_pattern(edofs: np.ndarray, n_nodes: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Sparsity of the node-to-node (3x3 block) matrix of element connectivity ``edofs`` (m, ne).

    Returns (indptr, indices, position) with position (ne, m*m) the block slot that each
    element's (a, b) pair adds into: one sort of ne m^2 keys instead of a COO of 9 times
    as many scalar entries.
    """
    n_nodes = int(n_nodes)
    e = edofs.T.astype(np.int64)
    ne, m = e.shape
    key = (e[:, :, None] * n_nodes + e[:, None, :]).ravel()
    uniq, pos = unique_inverse(key, n_nodes * n_nodes)
    del key
    rows = uniq // n_nodes
    indices = (uniq - rows * n_nodes).astype(np.int32)
    indptr = np.zeros(n_nodes + 1, dtype=np.int64)
    np.cumsum(np.bincount(rows, minlength=n_nodes), out=indptr[1:])
    return indptr, indices, pos.reshape(ne, m * m)


def assemble_stiffness(
    basis: Basis, youngs_modulus: float, poisson_ratio: float, *, chunk: int = CHUNK
) -> sp.csr_matrix:
    """Stiffness matrix of isotropic linear elasticity on a scalar ``basis``.

    K_(a i)(b j) = sum_q w_q [ lambda g_a,i g_b,j + mu (delta_ij g_a . g_b + g_a,j g_b,i) ]
    with g_a the physical gradient of scalar shape function a at quadrature point q:
    the Galerkin form of sigma(u) : eps(v) (Zienkiewicz & Taylor, The Finite Element
    Method, vol. 1, ch. 6).  Equal to scikit-fem's ``asm(linear_elasticity(...))`` on
    ``ElementVector(basis.elem)`` (tested).  Element blocks (a, b) of 3x3 are summed into a
    block-sparse (BSR) matrix over the scalar connectivity, then converted to CSR.
    """
    return stiffness_from_gradients(
        shape_gradients(basis), basis.dx, basis.element_dofs, basis.N, youngs_modulus, poisson_ratio, chunk=chunk
    )


def part_stiffness(
    basis: Basis,
    elements: np.ndarray,
    nodes: np.ndarray,
    youngs_modulus: float,
    poisson_ratio: float,
    *,
    chunk: int = CHUNK,
) -> sp.csr_matrix:
    """Stiffness (3 n, 3 n) of the elements ``elements`` of ``basis`` in the numbering of
    ``nodes`` (sorted, every node of those elements; node ``nodes[i]`` is local node i).

    The whole mesh's basis already holds the gradients and weights of every element, so
    they are taken from it (the same numbers a basis on the elements alone computes, each
    element's mapping being its own); numbering by rank in ``nodes`` keeps the order of
    every block key, so the matrix is entry for entry K[ldofs][:, ldofs] of the stiffness
    assembled on those elements in the whole numbering, without that matrix.
    """
    first = basis.basis[0][0].grad
    g = np.empty((len(basis.basis), 3, elements.size, first.shape[-1]))
    for a, b in enumerate(basis.basis):
        np.take(b[0].grad, elements, axis=1, out=g[a])
    edofs = np.searchsorted(nodes, basis.element_dofs[:, elements])
    return stiffness_from_gradients(
        g, basis.dx[elements], edofs, nodes.size, youngs_modulus, poisson_ratio, chunk=chunk
    )


def upper_triangle(K: sp.csr_matrix) -> sp.csr_matrix:
    """The upper triangle (diagonal included) of a CSR matrix with sorted indices, explicit
    zeros kept: the matrix ``scipy.sparse.triu(K, format="csr")`` returns, by one mask over
    the entries instead of its round trip through COO."""
    n = K.shape[0]
    keep = K.indices >= np.repeat(np.arange(n, dtype=K.indices.dtype), np.diff(K.indptr))
    kept_before = np.zeros(keep.size + 1, np.int64)
    np.cumsum(keep, out=kept_before[1:])
    return sp.csr_matrix((K.data[keep], K.indices[keep], kept_before[K.indptr]), shape=K.shape)


def stiffness_from_gradients(
    g_all: np.ndarray,
    dx_all: np.ndarray,
    element_dofs: np.ndarray,
    N: int,
    youngs_modulus: float,
    poisson_ratio: float,
    *,
    chunk: int = CHUNK,
) -> sp.csr_matrix:
    """The kernel of :func:`assemble_stiffness`: gradients g_all (m, 3, ne, nq), weights
    dx_all (ne, nq), scalar element dofs (m, ne) numbered below N."""
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    m, _, ne, _ = g_all.shape
    indptr, indices, pos = block_pattern(element_dofs, N)
    nnzb = indices.size
    data = np.zeros((3, 3, nnzb))
    kij = np.empty((min(chunk, ne), m, m))
    tmp = np.empty_like(kij)
    for start in range(0, ne, chunk):
        sl = slice(start, min(start + chunk, ne))
        n = sl.stop - sl.start
        g = g_all[:, :, sl, :]
        gw = g * dx_all[None, None, sl, :]
        gg = np.einsum("akeq,bkeq->eab", gw, g, optimize=True)  # g_a . g_b
        ab = np.einsum("aieq,bjeq->ijeab", gw, g, optimize=True)  # g_a,i g_b,j
        p = pos[sl].ravel()
        k, t = kij[:n], tmp[:n]
        for i in range(3):
            for j in range(3):
                np.multiply(ab[i, j], lam, out=k)  # lam g_a,i g_b,j
                np.multiply(ab[j, i], mu, out=t)  # + mu g_a,j g_b,i
                np.add(k, t, out=k)
                if i == j:
                    np.multiply(gg, mu, out=t)
                    np.add(k, t, out=k)
                data[i, j] += np.bincount(p, k.ravel(), minlength=nnzb)
    del g_all, pos, kij, tmp
    data = np.ascontiguousarray(data.transpose(2, 0, 1))
    return sp.bsr_matrix((data, indices, indptr), shape=(3 * N, 3 * N)).tocsr()


def assemble_body_load(basis: Basis, force_density) -> np.ndarray:
    """Load vector of a body force f(x) (N/m^3): F_(a i) = sum_q w_q N_a f_i(x_q).

    ``force_density`` maps global coordinates (3, ne, nq) to (3, ne, nq).
    """
    x = np.asarray(basis.global_coordinates())
    f = np.asarray(force_density(x), float)
    N = _values(basis)  # (m, ne, nq)
    fe = np.einsum("aeq,ieq,eq->eai", N, f, basis.dx)
    dofs = vector_dofs(basis.element_dofs.T)  # (ne, m, 3)
    return np.bincount(dofs.ravel(), fe.ravel(), minlength=3 * basis.N)


def assemble_surface_load(fbasis: FacetBasis, traction) -> np.ndarray:
    """Load vector of a surface traction t(x, n) (N/m^2) on the facets of ``fbasis``.

    ``traction`` maps (x, n), each (3, nf, nq), to (3, nf, nq).  Because the P2 shape
    functions sum to one, the entries sum to int t dA under the same quadrature.
    """
    x = np.asarray(fbasis.global_coordinates())
    n = np.asarray(fbasis.normals)
    t = np.asarray(traction(x, n), float)
    N = _values(fbasis)
    fe = np.einsum("aeq,ieq,eq->eai", N, t, fbasis.dx)
    dofs = vector_dofs(fbasis.element_dofs.T)
    return np.bincount(dofs.ravel(), fe.ravel(), minlength=3 * fbasis.N)


def assemble_foundation(fbasis: FacetBasis, stiffness: float, direction) -> sp.csr_matrix:
    """Matrix of an elastic foundation k int (u . d)(v . d) dA on the facets of ``fbasis``.

    ``stiffness`` is in N/m^3 (scalar or array (nf, nq)); ``direction`` maps (x, n) to a
    unit vector field (3, nf, nq) (Winkler foundation).
    """
    x = np.asarray(fbasis.global_coordinates())
    n = np.asarray(fbasis.normals)
    d = np.asarray(direction(x, n), float)
    N = _values(fbasis)  # (m, nf, nq)
    m = N.shape[0]
    w = fbasis.dx * stiffness
    ke = np.einsum("aeq,beq,ieq,jeq,eq->eaibj", N, N, d, d, w, optimize=True)
    edofs = vector_dofs(fbasis.element_dofs.T).reshape(-1, 3 * m)
    return _coo_to_csr(ke.reshape(-1, 3 * m, 3 * m), edofs, 3 * fbasis.N)
