"""The whole shaft's displacement and stress on its whole mesh for one combination of its
unit cases (the report's picture and ``.vtu`` at the governing angle).

The condensation keeps each piece's field only at its recovery nodes (``fe.shaft.substructure``).
On the whole mesh the field of a piece with local load coefficients a and end-face
displacements v is, exactly as there,

    u = sum_p a_p L_p + X v,   X v = [-K_ii^-1 K_ib v; v],

so each distinct piece's interior (end faces held) is solved once per placed piece, on
the factorisation the condensation kept (``ShaftFeOptions.keep_factors``) or, without it,
on its own once more; the nodal stress (averaged over the elements sharing a node,
``fe.core.stress``) is turned into the shaft frame and the pieces are joined on the conforming
whole mesh (``mesh.shaft.join``; a node on a joint plane takes the mean of its two pieces).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from fe_crank.fe.core.stress import stress_at_nodes, von_mises
from fe_crank.fe.core.symmetric import mesh_mirror
from fe_crank.fe.core.system import stiffness_rows
from fe_crank.fe.shaft.cases import ShaftCases
from fe_crank.fe.shaft.interior import Interior, MirroredInterior
from fe_crank.mesh.shaft import node_maps


@dataclass(frozen=True)
class ShaftFields:
    """One state of the whole shaft on its joined mesh (shaft frame)."""

    mesh: Any  # skfem MeshTet2 of the whole shaft (``ShaftMesh.whole``)
    displacement: np.ndarray  # (3, N) m
    von_mises: np.ndarray  # (N,) Pa, nodal averages
    hotspot_node: int = 0  # the node nearest the point asked for (``shaft_fields``'s ``mark``)


def _interior(cond, material, solver: str):
    E, nu = material.youngs_modulus, material.poisson_ratio
    if cond.mirrored:
        mirror = mesh_mirror(cond.mesh, cond.basis, (2,))
        if mirror is not None:
            return MirroredInterior(cond.basis, mirror, E, nu, cond.b, solver)
    from fe_crank.fe.core.assembly import assemble_stiffness

    return Interior(assemble_stiffness(cond.basis, E, nu), cond.b, solver)


def piece_fields(cases: ShaftCases, weights: np.ndarray, material, solver: str = "auto") -> list[np.ndarray]:
    """Per piece its displacement (3 N,) in its own frame for the case weights (n_cases,)
    (module doc): ``piece_states`` of every piece for the one state."""
    w = np.asarray(weights, float).reshape(-1, 1)
    got = piece_states(cases, dict.fromkeys(range(len(cases.model.pieces)), w), material, solver)
    return [got[k][:, 0] for k in range(len(cases.model.pieces))]


def piece_states(
    cases: ShaftCases, weights: dict[int, np.ndarray], material, solver: str = "auto"
) -> dict[int, np.ndarray]:
    """{piece: its displacements (3 N, m), own frame} for the case weights (n_cases, m) of each
    piece asked for (module doc), on the whole piece mesh: one factorisation per distinct
    piece (the condensation's where kept), all the columns of its placed pieces in one solve."""
    model = cases.model
    by_cond: dict[int, list[int]] = {}
    for k in weights:
        by_cond.setdefault(id(model.pieces[k].cond), []).append(k)
    out: dict[int, np.ndarray] = {}
    for ks in by_cond.values():
        cond = model.pieces[ks[0]].cond
        W = [np.asarray(weights[k], float).reshape(len(cases.names), -1) for k in ks]
        V = np.column_stack([cases.V[k] @ w for k, w in zip(ks, W)])
        if cond.interior is not None:
            U = cond.interior.solve(np.asarray(-(cond.K_b.T @ V)))
        else:
            K_b = stiffness_rows(cond.basis, material.youngs_modulus, material.poisson_ratio, cond.b)
            interior = _interior(cond, material, solver)
            try:
                U = interior.solve(np.asarray(-(K_b.T @ V)))
            finally:
                interior.free()
        j = 0
        for k, w in zip(ks, W):
            m = w.shape[1]
            u = U[:, j : j + m] + cond.L @ (cases.coef[k] @ w)
            u[cond.b] = V[:, j : j + m]
            out[k] = u
            j += m
    return out


def shaft_fields(
    cases: ShaftCases, weights: np.ndarray, material, solver: str = "auto", mark: np.ndarray | None = None
) -> ShaftFields:
    """The whole shaft's displacement and von Mises stress on its joined mesh for the case
    weights ``weights`` (n_cases,) (module doc); ``mark``: a point (3,) of the shaft frame
    whose nearest node is kept (``hotspot_node``)."""
    sm = cases.model.mesh
    whole = sm.whole()
    maps = node_maps(sm, whole)
    n = whole.doflocs.shape[1]
    disp = np.zeros((3, n))
    vm = np.zeros(n)
    count = np.zeros(n)
    for k, u in enumerate(piece_fields(cases, weights, material, solver)):
        pp = cases.model.pieces[k]
        c = pp.cond
        s = stress_at_nodes(c.mesh, u, material.youngs_modulus, material.poisson_ratio, dofs=c.basis.dofs)
        idx = maps[k]
        disp[:, idx] += pp.R @ u.reshape(-1, 3).T
        vm[idx] += von_mises(s)  # invariant under the rotation into the shaft frame
        count[idx] += 1
    node = 0 if mark is None else int(np.argmin(np.linalg.norm(whole.doflocs.T - np.asarray(mark, float), axis=1)))
    return ShaftFields(whole, disp / count, vm / count, node)
