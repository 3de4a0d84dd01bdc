"""Statically determinate support of one throw: simple supports at the main-bearing centres.

The model of IACS UR M53 (section 2.1: "the crankthrow is a statically determinate
system ... supported in the centre of the adjacent main journals"), built in FE as:

* each journal's bearing surface (``journal_1``, ``journal_2``) is tied to a reference
  point at its main-bearing centre by a *distributing* coupling (RBE3 type) that adds no
  stiffness.  The throw model ends at the centre plane of each main bearing (the journal
  of a throw is half a main bearing, docs/geometry.md; UR M53 2.1 and its FE appendix
  model a throw "from main-bearing centre to main-bearing centre"), so the reference
  point is the centre of the end face (``end_1``, ``end_2``): the longer lever of the
  two possible choices (the other being the centroid of the modelled bearing surface),
  i.e. the conservative one.  A force R at the reference point loads the surface with the
  RBE3 distribution about the surface's area centroid c, with the consistent nodal areas
  w_i = int_S N_i dA / A: f_i = w_i R + w_i (theta x d_i), d_i = x_i - c, where
  I theta = (x_ref - c) x R and I = sum_i w_i (|d_i|^2 1 - d_i d_i^T) (the transfer
  moment of R from the reference point to c, spread as a rigid-rotation pattern); the
  nodal forces sum to R and their moment about x_ref is zero.
* the reference points are simple supports: radial x and y at both bearing centres,
  axial z at one (the torque end's journal), no rotations held;
* the torque M_z is reacted at the end face where the power is taken off (``end_2``,
  flywheel side, by default) as the shear flow of a round shaft, t = T r e_theta / J.

These six reactions are statically determinate: for any load they follow from the six
equilibrium equations of the throw alone, R = -A^-1 (F, M), where column k of A is the
resultant (force, moment about the origin) of reaction component k as distributed on the
mesh.  Applying them as loads makes the load vector self-equilibrated, so the solution
equals the Lagrange-multiplier RBE3 model with the reference points simply supported
(the multipliers are these reactions, the constraint forces G^T lambda their
distribution).  The six rigid-body modes are then removed by six single-dof point
constraints (a 3-2-1 set picked by pivoted QR among the end-face nodes); with a
self-equilibrated load they carry zero reaction to round-off, which every solve checks.
The stiffness stays symmetric positive definite (PARDISO SPD path, one factorisation for
every unit case) and no stiffness parameter enters the answer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
from skfem import ElementTetP2

from fe_crank.errors import MeshError, SolverError
from fe_crank.fe.core.assembly import assemble_surface_load
from fe_crank.fe.core.loads import face_torque_load
from fe_crank.fe.core.supports import boundary_facets, facet_basis, rigid_body_modes

SURFACE_INTORDER = 4
#: a point constraint may carry at most this fraction of the load scale (round-off only)
POINT_REACTION_TOL = 1e-8


@dataclass(frozen=True)
class DeterminateLayout:
    """Where the determinate reactions act; see module doc.

    ``journals``: the two bearing surfaces; ``torque_face``: the end face that reacts M_z;
    ``axial``: the journal whose bearing centre holds u_z; ``centre_faces``: the end face
    whose centre is each journal's main-bearing centre (None: the area centroid of the
    bearing surface itself).
    """

    journals: tuple[str, str] = ("journal_1", "journal_2")
    torque_face: str = "end_2"
    axial: str = "journal_2"
    centre_faces: tuple[str, str] | None = ("end_1", "end_2")


@dataclass
class DeterminateSupport:
    """The distributed unit reactions of a layout on one basis and their resultants."""

    layout: DeterminateLayout
    centres: dict[str, np.ndarray]  # journal -> main-bearing centre (reference point of its coupling)
    names: tuple[str, ...]  # reaction components, e.g. "journal_1.Fx", ..., "end_2.Mz"
    owner: tuple[str, ...]  # support each component belongs to
    G: sp.csc_matrix  # (3 N, 6) nodal loads of a unit value of each component (sparse)
    A: np.ndarray  # (6, 6) resultants (F, M about the origin) of the columns of G
    held: np.ndarray  # (6,) vector dofs of the point constraints
    points: np.ndarray  # (3, N) node coordinates

    def reactions(self, f: np.ndarray) -> np.ndarray:
        """Reaction components (6,) or (6, k) that balance the load(s) f: R = -A^-1 (F, M)."""
        return np.linalg.solve(self.A, -_resultants(f, self.points))

    def self_equilibrated(self, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(f + G R, R): the load with its reactions applied, and the reactions."""
        R = self.reactions(f)
        return f + np.asarray(self.G @ R).reshape(f.shape), R

    def reaction_resultants(self, R: np.ndarray) -> dict[str, np.ndarray]:
        """Generalised force (Fx, Fy, Fz, Mx, My, Mz about the origin) of each support."""
        out: dict[str, np.ndarray] = {}
        for k, who in enumerate(self.owner):
            out[who] = out.get(who, np.zeros(6)) + R[k] * self.A[:, k]
        return out


def _resultants(f: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(F, M about the origin) of nodal load vector(s) f (3 N,) or (3 N, k)."""
    F = f.reshape(x.shape[1], 3, -1)
    force = F.sum(axis=0)
    moment = np.cross(x.T[:, :, None], F, axis=1).sum(axis=0)
    out = np.concatenate([force, moment])
    return out[:, 0] if f.ndim == 1 else out


def bearing_surface_load(basis, boundary: str) -> tuple[np.ndarray, np.ndarray, float]:
    """Nodal weights of the distributing coupling on ``boundary``.

    Returns (w, centre, area): w (N,) = int_S N_i dA / A (sums to 1), the area centroid
    centre = int_S x dA / A (= sum_i w_i x_i, since the P2 shape functions interpolate x
    exactly on the isoparametric surface) and the area A.
    """
    mesh = basis.mesh
    fb = facet_basis(
        mesh,
        ElementTetP2(),
        boundary_facets(mesh, boundary, "a bearing support"),
        SURFACE_INTORDER,
        f"the bearing support on {boundary}",
    )
    area = float(fb.dx.sum())
    f = assemble_surface_load(
        fb, lambda x, n: np.stack([np.ones_like(x[0]) / area, np.zeros_like(x[0]), np.zeros_like(x[0])])
    )
    w = f.reshape(-1, 3)[:, 0]
    x = np.asarray(fb.global_coordinates())
    centre = np.einsum("ieq,eq->i", x, fb.dx) / area
    return w, centre, area


def face_centre(basis, boundary: str) -> np.ndarray:
    """Area centroid of a named face (the main-bearing centre on an end face)."""
    mesh = basis.mesh
    fb = facet_basis(
        mesh,
        ElementTetP2(),
        boundary_facets(mesh, boundary, "a main-bearing centre"),
        SURFACE_INTORDER,
        f"the bearing centre on {boundary}",
    )
    x = np.asarray(fb.global_coordinates())
    return np.einsum("ieq,eq->i", x, fb.dx) / float(fb.dx.sum())


def transfer_moment_load(w: np.ndarray, x: np.ndarray, c: np.ndarray, moment: np.ndarray) -> np.ndarray:
    """Nodal forces (3 N,) of the RBE3 moment distribution: f_i = w_i (theta x d_i) with
    d_i = x_i - c, I theta = M, I = sum_i w_i (|d_i|^2 1 - d_i d_i^T).  For weights w that
    sum to 1 with centroid c (sum_i w_i d_i = 0) they sum to zero force and to the moment
    M about c (any point)."""
    on = np.flatnonzero(w)
    d = x[:, on].T - c  # (n, 3)
    wi = w[on]
    inertia = np.einsum("i,i->", wi, np.einsum("ij,ij->i", d, d)) * np.eye(3) - np.einsum("i,ij,ik->jk", wi, d, d)
    theta = np.linalg.solve(inertia, moment)
    out = np.zeros((x.shape[1], 3))
    out[on] = wi[:, None] * np.cross(theta, d)
    return out.reshape(-1)


def point_constraints(points: np.ndarray, candidates: np.ndarray) -> np.ndarray:
    """Six vector dofs that remove the rigid-body modes (a 3-2-1 set).

    Picked by QR with column pivoting of the rigid-body modes restricted to the candidate
    nodes (B^T, 6 x 3n): the first six pivots are the best-conditioned choice of rows,
    so that B[held] is invertible (checked).
    """
    B = rigid_body_modes(points[:, candidates])  # (3 n, 6)
    scale = np.ptp(points, axis=1).max()
    B[:, 3:] /= scale  # rotations in length units
    _, R, piv = sla.qr(B.T, pivoting=True, mode="economic")
    rows = piv[:6]
    if abs(R[5, 5]) < 1e-6 * abs(R[0, 0]):
        raise MeshError("cannot pick six point constraints against the rigid-body modes (end faces degenerate?)")
    node = candidates[rows // 3]
    return 3 * node + rows % 3


def determinate_support(basis, layout: DeterminateLayout, *, candidate_faces=("end_1", "end_2")) -> DeterminateSupport:
    """Distributed unit reactions, their resultants and the point constraints (module doc)."""
    mesh = basis.mesh
    N = basis.N
    x = basis.doflocs
    cols, names, owner, centres = [], [], [], {}
    for i, j in enumerate(layout.journals):
        w, c, _ = bearing_surface_load(basis, j)
        ref = c if layout.centre_faces is None else face_centre(basis, layout.centre_faces[i])
        centres[j] = ref
        comps = ("Fx", "Fy", "Fz") if j == layout.axial else ("Fx", "Fy")
        for k, comp in enumerate(comps):
            g = np.zeros(3 * N)
            g[k::3] = w
            unit = np.zeros(3)
            unit[k] = 1.0
            g += transfer_moment_load(w, x, c, np.cross(ref - c, unit))
            cols.append(g)
            names.append(f"{j}.{comp}")
            owner.append(j)
    if layout.axial not in layout.journals:
        raise MeshError(f"axial support {layout.axial!r} is not one of the journals {layout.journals}")
    cols.append(face_torque_load(basis, 1.0, boundary=layout.torque_face))
    names.append(f"{layout.torque_face}.Mz")
    owner.append(layout.torque_face)
    G = np.column_stack(cols)
    A = _resultants(G, x)
    G = sp.csc_matrix(G)  # non-zero on the bearing surfaces and the torque face only
    if np.linalg.cond(A) > 1e10:
        raise SolverError("determinate supports cannot balance every load (bearing centres coincide?)")
    cand = np.unique(
        np.concatenate(
            [basis.get_dofs(boundary_facets(mesh, f, "the point constraints")).all() for f in candidate_faces]
        )
    )
    held = point_constraints(x, cand)
    sup = DeterminateSupport(
        layout=layout, centres=centres, names=tuple(names), owner=tuple(owner), G=G, A=A, held=held, points=x
    )
    return sup
