"""CalculiX's nodal stress of a C3D10 mesh, reproduced on fe-crank's displacements, and
where each node of a throw model lies (mirror plane, point constraints, curved elements,
a fillet's edge).

The recovery itself (CalculiX 2.20's ``extrapolate.f`` for C3D10: the stress at the 4
integration points, extrapolated linearly to the corners, mid-edge nodes the mean of
their edge's corners, every node the mean over its elements) is
``tests/helpers/calculix_recovery.py``, where the test suite checks it against a closed form,
CalculiX's tabulated coefficients and fe-crank's own recovery.  The two recoveries agree
on straight-sided elements and differ only where a curved (isoparametric) element shares
the node; ``curvature`` measures that per node.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tests"))
from helpers.calculix_recovery import EDGES, calculix_recovery


def calculix_nodal_stress(units, displacements, nodes) -> np.ndarray:
    """(k, 6, len(nodes)) nodal stresses by CalculiX's C3D10 recovery (module docstring)
    of the displacement fields ``displacements`` of the FE stage's ``units``."""
    mat = units.material
    return calculix_recovery(
        units.mesh, units.system.basis.dofs, mat.youngs_modulus, mat.poisson_ratio, displacements, nodes
    )


def element_curvature(units) -> np.ndarray:
    """(ne,) largest distance of a mid-edge node from its edge's straight midpoint, over
    the edge length, of each element (0 for a straight-sided element)."""
    P = np.asarray(units.points)
    t = np.asarray(units.system.basis.element_dofs)
    a, b = P[:, t[EDGES[:, 0]]], P[:, t[EDGES[:, 1]]]  # (3, 6, ne)
    off = np.linalg.norm(P[:, t[4:]] - 0.5 * (a + b), axis=0) / np.linalg.norm(b - a, axis=0)
    return off.max(axis=0)


def places(units, nodes, axes=()) -> dict[str, np.ndarray]:
    """Per node of ``nodes``: ``plane`` on a mirror plane of the mesh (coordinate exactly 0
    across one of the mesh's mirror ``axes``, ``ThrowMesh.symmetry``), ``point`` a point-constraint node, ``near_point``
    sharing an element with one, ``curvature`` the largest ``element_curvature`` of
    its elements."""
    nodes = np.asarray(nodes)
    P = np.asarray(units.points)
    plane = np.zeros(nodes.size, bool)
    for ax in axes:
        plane |= P[ax, nodes] == 0.0
    t = np.asarray(units.system.basis.element_dofs)
    held = np.unique(np.asarray(getattr(units.system, "point_dofs", np.zeros(0, int))) // 3)
    near = np.zeros(P.shape[1], bool)
    near[np.unique(t[:, np.isin(t, held).any(axis=0)])] = True
    curv = np.zeros(P.shape[1])
    np.maximum.at(curv, t, np.broadcast_to(element_curvature(units), t.shape))
    return {"plane": plane, "point": np.isin(nodes, held), "near_point": near[nodes], "curvature": curv[nodes]}


def edge_nodes(units, group: str) -> np.ndarray:
    """Nodes of the boundary ``group`` that also lie on a boundary facet outside it: the
    group's edges (a fillet's two tangent lines; empty for a subdomain group)."""
    mesh, basis = units.mesh, units.system.basis
    if group not in (mesh.boundaries or {}):
        return np.zeros(0, dtype=np.int64)
    mine = np.asarray(mesh.boundaries[group])
    other = np.setdiff1d(mesh.boundary_facets(), mine)
    return np.intersect1d(basis.get_dofs(facets=mine).all(), basis.get_dofs(facets=other).all())
