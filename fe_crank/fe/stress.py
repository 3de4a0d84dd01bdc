"""Stress recovery: at quadrature points, at element nodes (unaveraged) and averaged at nodes.

Stress components are in Voigt order (xx, yy, zz, xy, yz, zx), shape (6, ...), Pa.
sigma = 2 mu eps + lambda tr(eps) I with eps = sym(grad u) (Hooke's law).
"""

from __future__ import annotations

import numpy as np
from skfem import Basis, ElementTetP2

from fe_crank.errors import MeshError
from fe_crank.fe.assembly import _gradients
from fe_crank.fe.forms import lame_parameters

VOIGT = ("xx", "yy", "zz", "xy", "yz", "zx")
_IJ = ((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0))


def _stress_from_gradients(G: np.ndarray, edofs: np.ndarray, u: np.ndarray, lam: float, mu: float) -> np.ndarray:
    """sigma (6, ne, nq) from scalar gradients G (m, 3, ne, nq) and element dofs (m, ne)."""
    U = u.reshape(-1, 3)[edofs]                      # (m, ne, 3)
    H = np.einsum("aei,ajeq->ijeq", U, G)            # grad u, H_ij = du_i/dx_j
    eps = 0.5 * (H + H.transpose(1, 0, 2, 3))
    tr = eps[0, 0] + eps[1, 1] + eps[2, 2]
    s = np.empty((6,) + tr.shape)
    for k, (i, j) in enumerate(_IJ):
        s[k] = 2.0 * mu * eps[i, j] + (lam * tr if i == j else 0.0)
    return s


NODE_CHUNK = 40000  # elements per node-basis chunk (the full basis of a 1M-dof mesh is ~1 GB)


def node_bases(mesh, dofs=None, chunk: int = NODE_CHUNK):
    """Yield (element indices, scalar P2 basis whose 'quadrature points' are the element's nodes).

    Chunks of ``chunk`` elements share one ``Dofs`` numbering (``dofs``, e.g. the solution
    basis's ``.dofs``), so node numbers are those of the solution.
    """
    e = ElementTetP2()
    X = np.asarray(e.doflocs, float).T               # (3, m) reference nodes
    W = np.full(X.shape[1], 1.0 / X.shape[1])
    if dofs is None:
        from skfem.assembly import Dofs

        dofs = Dofs(mesh, e)
    ne = mesh.t.shape[1]
    for start in range(0, ne, chunk):
        idx = np.arange(start, min(ne, start + chunk))
        yield idx, Basis(mesh, e, quadrature=(X, W), elements=idx, dofs=dofs, disable_doflocs=True)


def element_nodal_stress(mesh, u: np.ndarray, youngs_modulus: float, poisson_ratio: float,
                         *, dofs=None) -> tuple[np.ndarray, np.ndarray]:
    """Unaveraged stress at each element's nodes: (6, m, ne) and the node numbers (m, ne)."""
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    ne = mesh.t.shape[1]
    out = np.empty((6, 10, ne))
    nodes = np.empty((10, ne), dtype=np.int64)
    for idx, nb in node_bases(mesh, dofs):
        s = _stress_from_gradients(_gradients(nb), nb.element_dofs, u, lam, mu)   # (6, n, m): points = nodes
        out[:, :, idx] = s.transpose(0, 2, 1)
        nodes[:, idx] = nb.element_dofs
    return out, nodes


def _average(s_el: np.ndarray, nodes: np.ndarray, n: int) -> np.ndarray:
    count = np.bincount(nodes.ravel(), minlength=n)
    out = np.stack([np.bincount(nodes.ravel(), s_el[k].ravel(), minlength=n) for k in range(6)])
    return out / np.maximum(count, 1)


def stress_at_nodes(mesh, u: np.ndarray, youngs_modulus: float, poisson_ratio: float, *, dofs=None) -> np.ndarray:
    """Nodal stress (6, n_nodes) averaged over the elements sharing each P2 node."""
    s, nodes = element_nodal_stress(mesh, u, youngs_modulus, poisson_ratio, dofs=dofs)
    return _average(s, nodes, u.size // 3)


def stress_at_quadrature(basis: Basis, u: np.ndarray, youngs_modulus: float, poisson_ratio: float) -> np.ndarray:
    """Stress (6, ne, nq) at the quadrature points of ``basis`` (scalar P2)."""
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    return _stress_from_gradients(_gradients(basis), basis.element_dofs, u, lam, mu)


def von_mises(s: np.ndarray) -> np.ndarray:
    """sigma_v = sqrt(((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2 + 3 (t12^2 + t23^2 + t31^2)) (von Mises 1913)."""
    sxx, syy, szz, sxy, syz, szx = s
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                   + 3.0 * (sxy**2 + syz**2 + szx**2))


def tensor(s: np.ndarray) -> np.ndarray:
    """Symmetric 3x3 tensors (..., 3, 3) from Voigt stress (6, ...)."""
    sxx, syy, szz, sxy, syz, szx = s
    return np.stack([np.stack([sxx, sxy, szx], -1), np.stack([sxy, syy, syz], -1),
                     np.stack([szx, syz, szz], -1)], -2)


def principal(s: np.ndarray) -> np.ndarray:
    """Principal stresses (3, ...), sigma_1 >= sigma_2 >= sigma_3 (eigenvalues of the tensor)."""
    w = np.linalg.eigvalsh(tensor(s))
    return np.moveaxis(w[..., ::-1], -1, 0)


def max_shear(s: np.ndarray) -> np.ndarray:
    """Maximum shear stress tau_max = (sigma_1 - sigma_3) / 2 (Tresca)."""
    p = principal(s)
    return 0.5 * (p[0] - p[2])


def averaging_indicator(mesh, u: np.ndarray, youngs_modulus: float, poisson_ratio: float,
                        groups, *, dofs=None) -> dict[str, float]:
    """IACS UR M53 FE-appendix mesh check for each fillet boundary in ``groups``.

    At the node of the fillet with the highest averaged von Mises stress, the largest
    unaveraged (element) value is compared with the averaged one:
    (max_elements sigma_v - sigma_v,avg) / sigma_v,avg.  M53 asks for agreement within 5 %.
    """
    s_el, nodes = element_nodal_stress(mesh, u, youngs_modulus, poisson_ratio, dofs=dofs)
    n = u.size // 3
    vm_avg = von_mises(_average(s_el, nodes, n))
    vm_el = von_mises(s_el).ravel()
    vm_max = np.zeros(n)
    np.maximum.at(vm_max, nodes.ravel(), vm_el)
    if dofs is None:
        from skfem.assembly import Dofs

        dofs = Dofs(mesh, ElementTetP2())
    out = {}
    for g in groups:
        if g not in (mesh.boundaries or {}):
            raise MeshError(f"mesh has no boundary {g!r}, needed by the averaging check")
        fn = dofs.get_facet_dofs(mesh.boundaries[g]).all()
        i = fn[np.argmax(vm_avg[fn])]
        out[g] = float((vm_max[i] - vm_avg[i]) / vm_avg[i]) if vm_avg[i] > 0 else 0.0
    return out
