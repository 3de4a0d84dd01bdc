"""A piece of the shaft condensed exactly onto the nodes of its two end faces.

With the piece's dofs split into interface b (the P2 nodes of ``end_1`` and ``end_2``) and
interior i, static condensation (Guyan 1965; exact for static loads, the Schur
complement of K_ii):

    S = K_bb - K_bi K_ii^-1 K_ib          (the piece's stiffness on its end faces)
    X = [-K_ii^-1 K_ib; 1]                (the piece's displacement for unit end-face displacements)
    L_p = [K_ii^-1 f_i,p; 0]              (local load p with the end faces held)
    g_p = f_b,p - K_bi K_ii^-1 f_i,p      (the load p carried to the end faces)

so that for end-face displacements v and local loads sum_p a_p f_p the piece's field is
u = sum_p a_p L_p + X v, exactly.  S and g come from the rows b of K times X and L
(S = K_b X, g_p = f_b,p - K_b L_p), X column by column from K_ii solves (``fe.shaft.interior``).
X is kept only where it is needed: at the recovery nodes (stresses), and through the
functionals Phi (the bearing couplings' reference displacements): Phi X, Phi L.  On a
piece mirrored across z = 0 only the columns of ``end_1`` are solved: the column of the
mirror-image dof on ``end_2`` is s_c R X_j = s_c (X_j,sym - X_j,anti) (s_c = -1 for the
axial component), half the solves.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
from skfem import Basis, Mesh

from fe_crank.errors import MeshError
from fe_crank.fe.core.assembly import assemble_stiffness
from fe_crank.fe.core.bases import cell_basis
from fe_crank.fe.core.symmetric import mesh_mirror
from fe_crank.fe.core.system import stiffness_rows
from fe_crank.fe.shaft.interior import Interior, MirroredInterior

#: interface columns solved at once (PARDISO's time per right-hand side falls up to about 128)
BLOCK = 128


@dataclass
class Condensed:
    """One piece condensed onto its end faces (module doc); local frame of the piece."""

    mesh: Mesh
    basis: Basis
    faces: dict[str, np.ndarray]  # "end_1"/"end_2" -> P2 node numbers (ascending)
    b: np.ndarray  # interface vector dofs: end_1 nodes x (x, y, z), then end_2's
    S: np.ndarray  # (nb, nb)
    names: tuple[str, ...]  # local load patterns
    L: np.ndarray  # (3 N, n_pat) local loads' responses with the end faces held
    g: np.ndarray  # (nb, n_pat)
    resultant: np.ndarray  # (6, n_pat): force and moment about the local origin of each pattern
    rec_nodes: np.ndarray  # recovery nodes
    X_rec: np.ndarray  # (3 n_rec, nb) X at the recovery nodes
    phi_names: tuple[str, ...]
    phi_L: np.ndarray  # (n_phi, n_pat)
    phi_X: np.ndarray  # (n_phi, nb)
    mirrored: bool
    timings: dict[str, float] = field(default_factory=dict)
    #: with ``condense(..., keep=True)``: the interior's factorisation and the rows K_b of the
    #: stiffness, for whole fields later (``fe.shaft.fields``); ``free`` releases them
    interior: Any = None  # a factorisation handle (``fe.core.symmetric``), or None
    K_b: Any = None  # a sparse matrix, or None

    def free(self) -> None:
        if self.interior is not None:
            self.interior.free()
        self.interior = self.K_b = None

    def column(self, name: str) -> int:
        return self.names.index(name)

    def face_points(self, face: str) -> np.ndarray:
        """(n, 3) coordinates of the face's nodes (local frame), in interface order."""
        return self.basis.doflocs[:, self.faces[face]].T


def face_nodes(basis, mesh, name: str) -> np.ndarray:
    if name not in (mesh.boundaries or {}):
        raise MeshError(f"the piece has no end face {name!r}")
    return np.unique(basis.get_dofs(mesh.boundaries[name]).all())


def resultants(F: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(6, k): force and moment about the origin of nodal loads F (3 N, k) at x (3, N)."""
    Fn = F.reshape(x.shape[1], 3, -1)
    return np.concatenate([Fn.sum(axis=0), np.cross(x.T[:, :, None], Fn, axis=1).sum(axis=0)])


def condense(
    mesh,
    youngs_modulus: float,
    poisson_ratio: float,
    patterns: dict[str, np.ndarray],
    functionals: dict[str, np.ndarray],
    rec_nodes: np.ndarray,
    *,
    basis=None,
    mirrored: bool = False,
    solver: str = "auto",
    block: int = BLOCK,
    keep: bool = False,
) -> Condensed:
    """Condense ``mesh`` onto ``end_1`` and ``end_2`` (module doc).  ``patterns``: local
    loads (3 N,) by name; ``functionals``: rows (3 N,) whose products with the piece's
    field are wanted; ``rec_nodes``: where X is kept; ``mirrored``: the mesh is its own
    image across z = 0 with ``end_1`` <-> ``end_2`` (verified, else the whole piece);
    ``keep``: the factorisation stays (``Condensed.interior``, released by ``free``)."""
    t = {}
    t0 = time.perf_counter()
    E, nu = youngs_modulus, poisson_ratio
    basis = basis if basis is not None else cell_basis(mesh, 2)
    faces = {f: face_nodes(basis, mesh, f) for f in ("end_1", "end_2")}
    b = np.concatenate([(3 * faces[f][:, None] + np.arange(3)).ravel() for f in ("end_1", "end_2")])
    nb, N = b.size, basis.N
    mirror = mesh_mirror(mesh, basis, (2,)) if mirrored else None
    if mirror is not None:
        img = mirror.perm[2][faces["end_1"]]
        if not np.array_equal(np.sort(img), faces["end_2"]):
            mirror = None
    if mirror is not None:
        K_b = stiffness_rows(basis, E, nu, b)
        t["assembly"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        interior: MirroredInterior | Interior = MirroredInterior(basis, mirror, E, nu, b, solver)
    else:
        K = assemble_stiffness(basis, E, nu)
        K_b = K[b].tocsr()
        t["assembly"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        interior = Interior(K, b, solver)
        del K
    t["factorisation"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    names = tuple(patterns)
    P = np.column_stack([patterns[n] for n in names])
    L = interior.solve(P)
    g = P[b] - K_b @ L
    resultant = resultants(P, basis.doflocs)
    del P  # the patterns live on in L, g and their resultants
    phi_names = tuple(functionals)
    Phi = sp.csr_matrix(np.vstack([functionals[n] for n in phi_names])) if phi_names else sp.csr_matrix((0, 3 * N))
    t["local_cases"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    # X is needed at: the recovery nodes, the nodes K_b couples to (for S), the functionals' support
    need = np.unique(
        np.concatenate([np.asarray(rec_nodes, int), K_b.indices // 3, Phi.indices // 3, faces["end_1"], faces["end_2"]])
    )
    nd = (3 * need[:, None] + np.arange(3)).ravel()
    pos = np.full(3 * N, -1)
    pos[nd] = np.arange(nd.size)
    Kb_need = K_b[:, nd]
    Phi_need = Phi[:, nd]
    rec = pos[(3 * np.asarray(rec_nodes, int)[:, None] + np.arange(3)).ravel()]
    S = np.zeros((nb, nb))
    phi_X = np.zeros((Phi.shape[0], nb))
    X_rec = np.zeros((rec.size, nb))
    KbT = K_b.T.tocsc()
    n1 = faces["end_1"].size * 3
    if mirror is not None:
        pos2 = {int(n): i for i, n in enumerate(faces["end_2"])}
        partner = np.array([3 * pos2[int(img[j // 3])] + j % 3 for j in range(n1)]) + n1
        sign = np.where(np.arange(n1) % 3 == 2, -1.0, 1.0)
        todo = np.arange(n1)
    else:
        todo = np.arange(nb)

    def store(cols, X):
        X[pos[b[cols]], np.arange(cols.size)] = 1.0
        S[:, cols] = Kb_need @ X
        phi_X[:, cols] = Phi_need @ X
        X_rec[:, cols] = X[rec]

    for start in range(0, todo.size, block):
        cols = todo[start : start + block]
        R = -KbT[:, cols]
        if isinstance(interior, MirroredInterior):
            us, ua = interior.solve_split(R, need)
            X = us + ua
            store(cols, X)
            del X
            us -= ua
            del ua
            us *= sign[cols]
            store(partner[cols], us)
            del us
        else:
            store(cols, interior.solve(R.toarray())[nd])
    if not keep:
        interior.free()
    t["interface_columns"] = time.perf_counter() - t0
    return Condensed(
        mesh=mesh,
        basis=basis,
        faces=faces,
        b=b,
        S=0.5 * (S + S.T),
        names=names,
        L=L,
        g=g,
        resultant=resultant,
        rec_nodes=np.asarray(rec_nodes),
        X_rec=X_rec,
        phi_names=phi_names,
        phi_L=np.asarray(Phi @ L),
        phi_X=phi_X,
        mirrored=mirror is not None,
        timings=t,
        interior=interior if keep else None,
        K_b=K_b if keep else None,
    )
