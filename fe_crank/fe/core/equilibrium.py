"""Reactions and the equilibrium check of a solved :class:`~fe_crank.fe.core.system.System`.

For a solution u of the load f, the reaction of each support is the resultant
(Fx, Fy, Fz, Mx, My, Mz about the origin) of its forces on the body: a foundation's
springs -K_s u; a coupling's or a Dirichlet set's nodal residual K u + K_s u - f on its
nodes; the determinate supports' statically determined reactions R = -A^-1 (F, M) and the
residual at their six point dofs (round-off only, ``fe.core.determinate``).  The equilibrium
error is max(|sum F| / F_scale, |sum M| / M_scale) of the applied loads plus every
reaction, F_scale the sum of the nodal forces' magnitudes and M_scale that of their
moments about the origin.  The residual is formed on the constrained rows only (every
term lives there): the same sums, in the same order, as on the whole vector.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import scipy.sparse as sp

from fe_crank.fe.core.determinate import DeterminateSupport
from fe_crank.fe.core.supports import Coupling

#: generalised loads (Fx, Fy, Fz, Mx, My, Mz) at couplings' reference points, by boundary
RefLoads = Mapping[str, np.ndarray]


class EquilibriumChecks:
    """The reaction and equilibrium methods of ``System``, on the fields declared here
    (``System``'s, see there)."""

    rows: np.ndarray
    K_rows: sp.csr_matrix
    Ks: sp.csr_matrix
    determinate: DeterminateSupport | None
    foundation_dofs: dict[str, np.ndarray]
    couplings: tuple[Coupling, ...]
    slave_dofs: dict[str, np.ndarray]
    ref_points: dict[str, np.ndarray]
    dirichlet_dofs: np.ndarray
    point_dofs: np.ndarray

    @property
    def points(self) -> np.ndarray:
        """Coordinates (3, N) of the nodes (``System.points``)."""
        raise NotImplementedError

    def reactions(self, u: np.ndarray, f: np.ndarray, ref_loads: RefLoads | None = None) -> dict[str, np.ndarray]:
        """Resultant reaction on the body of each support, (Fx, Fy, Fz, Mx, My, Mz) about the origin.

        Foundations: the spring forces -K_s u.  Couplings and Dirichlet sets: the nodal
        residual K u + K_s u - f on their nodes, less the loads applied at the reference point.
        Determinate supports: each support's statically determined reaction, and the six
        point constraints (``point_constraints``: round-off).

        The residual is formed on the constrained rows only (``rows``), where every term
        above lives: (f + G R)[rows] = f[rows] + G[rows] R and (K_s u)[rows] = K_s[rows] u
        are the same sums in the same order as on the whole vector, so the numbers are
        those of the whole-vector formulas without their 3 N-long temporaries.
        """
        x = self.points
        out: dict[str, np.ndarray] = {}
        f_rows = f[self.rows]
        if self.determinate is not None:
            R = self.determinate.reactions(f)
            out.update(self.determinate.reaction_resultants(R))
            f_rows = f_rows + self._rows_of(self.determinate.G) @ R  # (f + G R)[rows]
        if self.foundation_dofs:
            rs = -(self.Ks @ u)
            for name, sdofs in self.foundation_dofs.items():
                out[name] = _resultant(rs, x, sdofs)
        r_rows = self.K_rows @ u + self._ks_rows(u) - f_rows
        if self.couplings or self.dirichlet_dofs.size:
            resid = np.zeros_like(u)
            resid[self.rows] = r_rows
            for c in self.couplings:
                r = _resultant(resid, x, self.slave_dofs[c.boundary])
                if ref_loads and c.boundary in ref_loads:
                    r = r - _generalised_at_origin(ref_loads[c.boundary], self.ref_points[c.boundary])
                out[c.boundary] = r
            if self.dirichlet_dofs.size:
                mask = np.zeros(resid.size, bool)
                mask[self.dirichlet_dofs] = True
                out["dirichlet"] = _resultant(np.where(mask, resid, 0.0), x, np.arange(x.shape[1]))
        if self.point_dofs.size:
            out["point_constraints"] = self._point_resultant(r_rows[np.searchsorted(self.rows, self.point_dofs)])
        return out

    def _rows_of(self, M: sp.spmatrix) -> sp.csr_matrix:
        """M[rows] (sparse), kept: the same rows are read for every case."""
        key = ("rows", id(M))
        memo = self.__dict__.setdefault("_memo", {})
        if key not in memo:
            memo[key] = (M, M[self.rows])
        return memo[key][1]

    def _ks_rows(self, u: np.ndarray) -> np.ndarray:
        """(K_s u)[rows]; zeros when there is no foundation (as the empty product gives)."""
        if self.Ks.nnz == 0:
            return np.zeros(self.rows.size)
        return self._rows_of(self.Ks) @ u

    def _point_resultant(self, r: np.ndarray) -> np.ndarray:
        """Resultant of the residuals r at the point dofs (the other components of their nodes
        zero), as ``_resultant`` of the whole residual vector on the point dofs' nodes."""
        nodes = np.unique(self.point_dofs // 3)
        fn = np.zeros((nodes.size, 3))
        fn[np.searchsorted(nodes, self.point_dofs // 3), self.point_dofs % 3] = r
        return _resultant_of(fn, x=self.points[:, nodes].T)

    def applied(self, f: np.ndarray, ref_loads: RefLoads | None = None) -> tuple[np.ndarray, float, float]:
        """Resultant of the applied loads and the force and moment scales used for errors.

        One cross product x_i x f_i serves the moment and the moment scale."""
        fn = np.ascontiguousarray(f.reshape(-1, 3))
        mom = np.cross(self.points.T, fn)
        res = np.concatenate([fn.sum(axis=0), mom.sum(axis=0)])
        fscale = np.linalg.norm(fn, axis=1).sum()
        mscale = np.linalg.norm(mom, axis=1).sum()
        for name, load in (ref_loads or {}).items():
            g = _generalised_at_origin(load, self.ref_points[name])
            res = res + g
            fscale += np.linalg.norm(load[:3])
            mscale += np.linalg.norm(g[3:])
        return res, fscale, mscale

    def equilibrium_error(
        self,
        u: np.ndarray,
        f: np.ndarray,
        ref_loads: RefLoads | None = None,
        *,
        applied: tuple[np.ndarray, float, float] | None = None,
    ) -> tuple[float, dict[str, np.ndarray]]:
        """max(|sum F|/F_scale, |sum M|/M_scale) of applied loads plus reactions, and the reactions.

        F_scale is the sum of the magnitudes of the nodal loads, M_scale the sum of the
        magnitudes of their moments about the origin.  ``applied``: ``self.applied(f,
        ref_loads)`` when the caller has it already.
        """
        reac = self.reactions(u, f, ref_loads)
        total, fs, ms = self.applied(f, ref_loads) if applied is None else applied
        for r in reac.values():
            total = total + r
        ef = np.linalg.norm(total[:3]) / fs if fs > 0 else np.linalg.norm(total[:3])
        em = np.linalg.norm(total[3:]) / ms if ms > 0 else np.linalg.norm(total[3:])
        return float(max(ef, em)), reac


def _resultant(v: np.ndarray, x: np.ndarray, sdofs: np.ndarray) -> np.ndarray:
    return _resultant_of(v.reshape(-1, 3)[sdofs], x[:, sdofs].T)


def _resultant_of(fn: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(sum f_i, sum x_i x f_i) of nodal forces fn (n, 3) at points x (n, 3)."""
    return np.concatenate([fn.sum(axis=0), np.cross(x, fn).sum(axis=0)])


def _generalised_at_origin(load: np.ndarray, x0: np.ndarray) -> np.ndarray:
    load = np.asarray(load, float)
    return np.concatenate([load[:3], load[3:] + np.cross(x0, load[:3])])
