"""Solves of a piece of the shaft with its end faces held: K_ii x = f_i, factorised once.

The whole-shaft model (``fe_crank.fe.shaft.substructure``) condenses each piece onto the nodes
of its end faces (the interface dofs b); what it needs from the piece's interior i is
x = K_ii^-1 f_i for many right-hand sides.  The matrix keeps the pattern of the whole
stiffness with the interface rows and columns replaced by unit-diagonal rows and
explicit-zero couplings (so the right-hand side's interface rows are set to zero and come
back zero).

``MirroredInterior`` solves a piece whose mesh is its own mirror image across ``z = 0``
(``ThrowMesh.symmetry``, verified on the P2 nodes by ``fe.core.symmetric.mesh_mirror``) on the
two symmetry components of its half, as ``fe.core.symmetric`` does for the determinate throw
(the same projection, plane conditions and weights; here the held dofs are the end face
``end_1`` of the half instead of point constraints, so no rigid motion is left);
``solve_split`` returns the symmetric and antisymmetric parts of the solution separately,
so that the response to the mirror image of a load is had without another solve
(R u = u_sym - u_anti).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from fe_crank.errors import SolverError
from fe_crank.fe.core.assembly import part_stiffness, upper_triangle
from fe_crank.fe.core.symmetric import character_of
from fe_crank.fe.linalg.choice import choose_method
from fe_crank.fe.linalg.factorise import factorise, factorise_shared

#: relative residual a block of solutions must meet (as ``Factorisation.residual_tol``)
RESIDUAL_TOL = 1e-8


def solve_checked(fac, B: np.ndarray) -> np.ndarray:
    """X with K X = B by a prepared ``Factorisation``; many columns at once.  PARDISO is
    called directly (phase 33) and the block is checked on two random combinations of
    its columns, K (X w) = B w, instead of column by column (the check of every column
    costs as much as the solve on a block of 64)."""
    if fac.method != "pardiso" or fac._impl is None:
        return fac.solve(B)
    B = np.asarray(B, float)
    if not np.all(np.isfinite(B)):
        raise SolverError("load vector contains NaN or Inf")
    X = np.asarray(fac._solve_pardiso(B)).reshape(B.shape)
    w = np.random.default_rng(12345).standard_normal((B.shape[1], 2))
    bw = B @ w
    r = np.linalg.norm(fac._matvec(X @ w) - bw, axis=0) / np.maximum(np.linalg.norm(bw, axis=0), 1e-300)
    if not np.all(np.isfinite(X)) or np.any(r > RESIDUAL_TOL):
        raise SolverError(f"PARDISO: relative residual {np.max(r):.3e} exceeds {RESIDUAL_TOL:g}")
    return X


def _held_pattern(A: sp.csr_matrix, held: np.ndarray) -> sp.csr_matrix:
    """Upper triangle ``A`` with the dofs ``held`` (bool) as unit-diagonal rows (pattern kept)."""
    cut = np.repeat(held, np.diff(A.indptr)) | held[A.indices]
    A.data[cut] = 0.0
    diag = A.indptr[:-1]
    if not np.array_equal(A.indices[diag], np.arange(A.shape[0])):
        raise SolverError("the piece's stiffness lacks a diagonal entry")
    A.data[diag[held]] = 1.0
    return A


class Interior:
    """K_ii of a whole piece (no symmetry used)."""

    def __init__(self, K: sp.csr_matrix, interface: np.ndarray, solver: str = "auto"):
        n = K.shape[0]
        self.held = np.zeros(n, bool)
        self.held[interface] = True
        A = upper_triangle(K)
        A.sort_indices()
        method = choose_method(solver, n)
        if method == "superlu":
            A = _held_pattern(A, self.held)
            A = (A + A.T - sp.diags(A.diagonal())).tocsr()
            self.factor = factorise(A, method)
        elif method == "pardiso":  # the direct handle of the symmetry components (one matrix)
            self.factor = factorise_shared([_held_pattern(A, self.held)])[0]
        else:
            self.factor = factorise(_held_pattern(A, self.held), method, upper=True)
        self.method = method

    def solve(self, F: np.ndarray) -> np.ndarray:
        B = np.array(F, dtype=float, copy=True)
        B[self.held] = 0.0
        return solve_checked(self.factor, B)

    def free(self):
        self.factor.free()


class MirroredInterior:
    """K_ii of a piece mirrored across z = 0, on the two components of its half (module doc)."""

    def __init__(self, basis, mirror, E: float, nu: float, interface: np.ndarray, solver: str = "auto"):
        if mirror.axes != (2,):
            raise ValueError("MirroredInterior takes the mirror plane z = 0 only")
        x = basis.doflocs
        el = basis.element_dofs
        part = np.flatnonzero(x[2, el[:4]].mean(axis=0) < 0)
        if 2 * part.size != el.shape[1]:
            raise SolverError("the mirror halves do not partition the elements")
        nodes = np.unique(el[:, part])
        on = mirror.on_plane[2][nodes]
        self.nodes, self.weights, self.mirror = nodes, np.where(on, 0.5, 1.0), mirror
        self.N = basis.N
        self._local = np.full(basis.N, -1)
        self._local[nodes] = np.arange(nodes.size)
        K = upper_triangle(part_stiffness(basis, part, nodes, E, nu))
        K.sort_indices()
        held_face = np.zeros(basis.N, bool)
        held_face[np.unique(np.asarray(interface) // 3)] = True
        face = held_face[nodes]
        method = choose_method(solver, 3 * nodes.size)
        self.comps, mats = [], []
        for i, chars in enumerate(mirror.characters):
            held = np.zeros((nodes.size, 3), bool)
            held[face] = True
            sym = chars[2] == 1
            held[on, 2] |= sym  # symmetric: u_z = 0 on the plane; antisymmetric: u_x = u_y = 0
            held[on, :2] |= not sym
            A = K if i == len(mirror.characters) - 1 else K.copy()
            mats.append(_held_pattern(A, held.ravel()))
            self.comps.append([chars, held.ravel(), None])
        if method == "pardiso":
            for comp, fac in zip(self.comps, factorise_shared(mats)):
                comp[2] = fac
        else:
            for comp, A in zip(self.comps, mats):
                if method == "superlu":
                    A = (A + A.T - sp.diags(A.diagonal())).tocsr()
                comp[2] = factorise(A, method, upper=method != "superlu")
        self.method = method

    def solve_split(self, F, rows: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(u_sym, u_anti), each (3 n, k), of full loads F (3 N, k; dense or sparse) at the
        nodes ``rows`` (default all, n = N); their sum solves K_ii u = F."""
        k = F.shape[1]
        rows = np.arange(self.N) if rows is None else np.asarray(rows)
        out = []
        for chars, held, fac in self.comps:
            b = None
            for planes, p, s in self.mirror.group:
                dofs = (3 * p[self.nodes][:, None] + np.arange(3)).ravel()
                scale = character_of(chars, planes) * np.tile(s, self.nodes.size) * np.repeat(self.weights, 3)
                part = (sp.diags(scale / len(self.mirror.group)) @ F[dofs]) if sp.issparse(F) else None
                if part is None:
                    part = (scale / len(self.mirror.group))[:, None] * np.asarray(F)[dofs]
                b = part if b is None else b + part
            assert b is not None  # the group holds the identity at least
            b = b.toarray() if sp.issparse(b) else b
            b[held] = 0.0
            q = solve_checked(fac, b).reshape(self.nodes.size, 3, k)
            del b
            U = np.zeros((rows.size, 3, k))
            for planes, p, s in self.mirror.group:
                src = self._local[p[rows]]  # the part's node whose image under g is the row's node
                ok = src >= 0
                w = character_of(chars, planes) * self.weights[src[ok]]
                U[ok] += w[:, None, None] * s[None, :, None] * q[src[ok]]
            out.append((-chars[2], U.reshape(3 * rows.size, k)))
        u_sym, u_anti = (u for _, u in sorted(out, key=lambda t: t[0]))
        return u_sym, u_anti

    def solve(self, F: np.ndarray) -> np.ndarray:
        a, b = self.solve_split(np.asarray(F, float).reshape(F.shape[0], -1))
        return (a + b).reshape(F.shape)

    def free(self):
        for _, _, fac in self.comps:
            fac.free()
