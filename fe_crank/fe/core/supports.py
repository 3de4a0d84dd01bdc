"""Supports: elastic radial foundations on bearing surfaces and rigid end-face couplings.

* :class:`Foundation` -- a Winkler foundation (stiffness per area, N/m^3) acting along the
  radial direction of a journal surface; ``arc`` limits it to the loaded arc.  With a large
  stiffness it is the "rigid bearing" model (a penalty constraint).
* :class:`Coupling` -- the face's nodes follow a reference point rigidly,
  u = u0 + theta x (x - x0) (an RBE2-type kinematic coupling, as the end-face couplings of
  the IACS UR M53 FE appendix), eliminated by a master-slave transformation; any of the
  reference point's six dofs (ux, uy, uz, rx, ry, rz) may be held.
* ``dirichlet`` -- components of every node of a boundary held at zero (for verification
  models with symmetry planes or clamps).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import ElementTetP2

from fe_crank.errors import MeshError
from fe_crank.fe.core.assembly import assemble_foundation
from fe_crank.fe.core.bases import (  # noqa: F401
    InverseMapError,
    RobustIsoparametric,
    cell_basis,
    facet_basis,
    mesh_dofs,
    prime_edge_tables,
    robust_mapping,
)

REF_DOFS = ("ux", "uy", "uz", "rx", "ry", "rz")


@dataclass(frozen=True)
class Foundation:
    """Radial elastic foundation on ``boundary`` (stiffness per area k, N/m^3).

    ``arc``: (centre angle, half angle) in rad, angles measured about the crank (z) axis
    from +y towards +x; None = the whole surface.
    """

    boundary: str
    stiffness: float
    arc: tuple[float, float] | None = None


@dataclass(frozen=True)
class Coupling:
    """Rigid coupling of ``boundary`` to a reference point (default: the face's area centroid).

    ``fixed``: names from ``REF_DOFS`` held at zero; ``load``: generalised force
    (Fx, Fy, Fz, Mx, My, Mz) applied at the reference point, N and N m.
    """

    boundary: str
    fixed: tuple[str, ...] = ()
    ref_point: tuple[float, float, float] | None = None


@dataclass(frozen=True)
class Dirichlet:
    """Components (0, 1, 2 = x, y, z) of all nodes of ``boundary`` held at zero."""

    boundary: str
    components: tuple[int, ...] = (0, 1, 2)


def boundary_facets(mesh, name: str, needed_by: str):
    """The facets of a named boundary, or a MeshError naming what needs it."""
    bnd = mesh.boundaries or {}
    if name not in bnd:
        have = ", ".join(sorted(bnd)) or "none"
        raise MeshError(f"mesh has no boundary {name!r}, needed by {needed_by}; it has: {have}")
    return bnd[name]


def radial_direction(x, n):
    """Unit normal with its axial (z) part removed: the radial direction on a journal."""
    d = np.array(n, dtype=float, copy=True)
    d[2] = 0.0
    norm = np.sqrt(d[0] ** 2 + d[1] ** 2)
    if np.any(norm < 1e-6):
        raise MeshError("foundation boundary has facets normal to the crank axis: not a bearing surface")
    return d / norm


def assemble_foundation_matrix(mesh, found: Foundation, intorder: int = 4) -> sp.csr_matrix:
    """Stiffness matrix of one :class:`Foundation` (see ``assemble_foundation``)."""
    facets = boundary_facets(mesh, found.boundary, "a bearing support")
    fb = facet_basis(mesh, ElementTetP2(), facets, intorder, "the bearing support")
    k = found.stiffness
    if found.arc is not None:
        x = np.asarray(fb.global_coordinates())
        centre, half = found.arc
        ang = np.arctan2(x[0], x[1])  # from +y towards +x
        dang = np.angle(np.exp(1j * (ang - centre)))
        k = found.stiffness * (np.abs(dang) <= half)
    return assemble_foundation(fb, k, radial_direction)


def face_centroid(mesh, facets, intorder: int = 4) -> np.ndarray:
    """Area-weighted centroid of a set of facets."""
    fb = facet_basis(mesh, ElementTetP2(), facets, intorder, "the end-face coupling")
    x = np.asarray(fb.global_coordinates())
    return np.einsum("ieq,eq->i", x, fb.dx) / fb.dx.sum()


def rigid_body_modes(points: np.ndarray) -> np.ndarray:
    """The six rigid-body displacement fields at points (3, N), interleaved: (3 N, 6)."""
    x, y, z = points
    N = points.shape[1]
    B = np.zeros((N, 3, 6))
    B[:, 0, 0] = B[:, 1, 1] = B[:, 2, 2] = 1.0
    # rotation about x: (0, -z, y); about y: (z, 0, -x); about z: (-y, x, 0)
    B[:, 1, 3], B[:, 2, 3] = -z, y
    B[:, 0, 4], B[:, 2, 4] = z, -x
    B[:, 0, 5], B[:, 1, 5] = -y, x
    return B.reshape(3 * N, 6)


def coupling_rows(d: np.ndarray) -> np.ndarray:
    """Matrix T (3, 6) per node with u = T [u0, theta], d = x - x0: shape (N, 3, 6)."""
    dx, dy, dz = d
    N = d.shape[1]
    T = np.zeros((N, 3, 6))
    T[:, 0, 0] = T[:, 1, 1] = T[:, 2, 2] = 1.0
    T[:, 0, 4], T[:, 0, 5] = dz, -dy
    T[:, 1, 3], T[:, 1, 5] = -dz, dx
    T[:, 2, 3], T[:, 2, 4] = dy, -dx
    return T
