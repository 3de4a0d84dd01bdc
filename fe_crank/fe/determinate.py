"""Statically determinate support of one throw: simple supports at the main-bearing centres.

The model of IACS UR M53 (section 2.1: "the crankthrow is a statically determinate
system ... supported in the centre of the adjacent main journals"), built in FE as:

* each journal's bearing surface (``journal_1``, ``journal_2``) is tied to a reference
  point at its bearing centre by a *distributing* coupling (RBE3 type): the reference
  point's translation is the area-weighted mean of the surface's, u_ref = sum_i w_i u_i /
  sum_i w_i with w_i = int_S N_i dA (the consistent nodal areas), and a force R at the
  reference point loads the surface with the nodal forces f_i = R w_i / sum_i w_i (a
  uniform traction R / A on the discretised surface).  It adds no stiffness.
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
from skfem import ElementTetP2

from fe_crank.errors import MeshError, SolverError
from fe_crank.fe.assembly import assemble_surface_load
from fe_crank.fe.loads import face_torque_load
from fe_crank.fe.supports import boundary_facets, facet_basis, rigid_body_modes

SURFACE_INTORDER = 4
#: a point constraint may carry at most this fraction of the load scale (round-off only)
POINT_REACTION_TOL = 1e-8


@dataclass(frozen=True)
class DeterminateLayout:
    """Where the determinate reactions act; see module doc.

    ``journals``: the two bearing surfaces; ``torque_face``: the end face that reacts M_z;
    ``axial``: the journal whose bearing centre holds u_z.
    """

    journals: tuple[str, str] = ("journal_1", "journal_2")
    torque_face: str = "end_2"
    axial: str = "journal_2"


@dataclass
class DeterminateSupport:
    """The distributed unit reactions of a layout on one basis and their resultants."""

    layout: DeterminateLayout
    centres: dict[str, np.ndarray]      # journal -> bearing centre (area centroid of its bearing surface)
    names: tuple[str, ...]              # reaction components, e.g. "journal_1.Fx", ..., "end_2.Mz"
    owner: tuple[str, ...]              # support each component belongs to
    G: np.ndarray                       # (3 N, 6) nodal loads of a unit value of each component
    A: np.ndarray                       # (6, 6) resultants (F, M about the origin) of the columns of G
    held: np.ndarray                    # (6,) vector dofs of the point constraints
    points: np.ndarray                  # (3, N) node coordinates

    def reactions(self, f: np.ndarray) -> np.ndarray:
        """Reaction components (6,) or (6, k) that balance the load(s) f: R = -A^-1 (F, M)."""
        return np.linalg.solve(self.A, -_resultants(f, self.points))

    def self_equilibrated(self, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(f + G R, R): the load with its reactions applied, and the reactions."""
        R = self.reactions(f)
        return f + self.G @ R, R

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
    fb = facet_basis(mesh, ElementTetP2(), boundary_facets(mesh, boundary, "a bearing support"),
                     SURFACE_INTORDER, f"the bearing support on {boundary}")
    area = float(fb.dx.sum())
    f = assemble_surface_load(fb, lambda x, n: np.stack([np.ones_like(x[0]) / area,
                                                         np.zeros_like(x[0]), np.zeros_like(x[0])]))
    w = f.reshape(-1, 3)[:, 0]
    x = np.asarray(fb.global_coordinates())
    centre = np.einsum("ieq,eq->i", x, fb.dx) / area
    return w, centre, area


def point_constraints(points: np.ndarray, candidates: np.ndarray) -> np.ndarray:
    """Six vector dofs that remove the rigid-body modes (a 3-2-1 set).

    Picked by QR with column pivoting of the rigid-body modes restricted to the candidate
    nodes (B^T, 6 x 3n): the first six pivots are the best-conditioned choice of rows,
    so that B[held] is invertible (checked).
    """
    B = rigid_body_modes(points[:, candidates])                  # (3 n, 6)
    scale = np.ptp(points, axis=1).max()
    B[:, 3:] /= scale                                            # rotations in length units
    _, R, piv = sla.qr(B.T, pivoting=True, mode="economic")
    rows = piv[:6]
    if abs(R[5, 5]) < 1e-6 * abs(R[0, 0]):
        raise MeshError("cannot pick six point constraints against the rigid-body modes "
                        "(end faces degenerate?)")
    node = candidates[rows // 3]
    return 3 * node + rows % 3


def determinate_support(basis, layout: DeterminateLayout, *, candidate_faces=("end_1", "end_2")
                        ) -> DeterminateSupport:
    """Distributed unit reactions, their resultants and the point constraints (module doc)."""
    mesh = basis.mesh
    N = basis.N
    x = basis.doflocs
    cols, names, owner, centres = [], [], [], {}
    for j in layout.journals:
        w, c, _ = bearing_surface_load(basis, j)
        centres[j] = c
        comps = ("Fx", "Fy", "Fz") if j == layout.axial else ("Fx", "Fy")
        for k, comp in enumerate(comps):
            g = np.zeros(3 * N)
            g[k::3] = w
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
    if np.linalg.cond(A) > 1e10:
        raise SolverError("determinate supports cannot balance every load (bearing centres coincide?)")
    cand = np.unique(np.concatenate([basis.get_dofs(boundary_facets(mesh, f, "the point constraints")).all()
                                     for f in candidate_faces]))
    held = point_constraints(x, cand)
    sup = DeterminateSupport(layout=layout, centres=centres, names=tuple(names), owner=tuple(owner),
                             G=G, A=A, held=held, points=x)
    return sup
