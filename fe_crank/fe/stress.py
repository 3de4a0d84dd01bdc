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


def node_basis(mesh) -> Basis:
    """Scalar basis whose 'quadrature points' are the element's own nodes (reference doflocs)."""
    e = ElementTetP2()
    X = np.asarray(e.doflocs, float).T               # (3, m)
    W = np.full(X.shape[1], 1.0 / X.shape[1])
    return Basis(mesh, e, quadrature=(X, W))


def element_nodal_stress(mesh, u: np.ndarray, youngs_modulus: float, poisson_ratio: float,
                         *, basis: Basis | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Unaveraged stress at each element's nodes: (6, m, ne) and the node numbers (m, ne)."""
    nb = basis if basis is not None else node_basis(mesh)
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)
    s = _stress_from_gradients(_gradients(nb), nb.element_dofs, u, lam, mu)   # (6, ne, m) points = nodes
    return s.transpose(0, 2, 1), nb.element_dofs


def stress_at_nodes(mesh, u: np.ndarray, youngs_modulus: float, poisson_ratio: float,
                    *, basis: Basis | None = None) -> np.ndarray:
    """Nodal stress (6, n_nodes) averaged over the elements sharing each P2 node."""
    s, nodes = element_nodal_stress(mesh, u, youngs_modulus, poisson_ratio, basis=basis)
    n = int(nodes.max()) + 1 if basis is None else basis.N
    count = np.bincount(nodes.ravel(), minlength=n)
    out = np.stack([np.bincount(nodes.ravel(), s[k].ravel(), minlength=n) for k in range(6)])
    return out / np.maximum(count, 1)


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
                        groups, *, basis: Basis | None = None) -> dict[str, float]:
    """IACS UR M53 FE-appendix mesh check for each fillet boundary in ``groups``.

    At the node of the fillet with the highest averaged von Mises stress, the largest
    unaveraged (element) value is compared with the averaged one:
    (max_elements sigma_v - sigma_v,avg) / sigma_v,avg.  M53 asks for agreement within 5 %.
    """
    nb = basis if basis is not None else node_basis(mesh)
    s_el, nodes = element_nodal_stress(mesh, u, youngs_modulus, poisson_ratio, basis=nb)
    n = nb.N
    count = np.bincount(nodes.ravel(), minlength=n)
    s_avg = np.stack([np.bincount(nodes.ravel(), s_el[k].ravel(), minlength=n) for k in range(6)]) / np.maximum(count, 1)
    vm_avg = von_mises(s_avg)
    vm_el = von_mises(s_el).ravel()
    vm_max = np.zeros(n)
    np.maximum.at(vm_max, nodes.ravel(), vm_el)
    out = {}
    for g in groups:
        if g not in (mesh.boundaries or {}):
            raise MeshError(f"mesh has no boundary {g!r}, needed by the averaging check")
        fn = nb.get_dofs(mesh.boundaries[g]).all()
        i = fn[np.argmax(vm_avg[fn])]
        out[g] = float((vm_max[i] - vm_avg[i]) / vm_avg[i]) if vm_avg[i] > 0 else 0.0
    return out
