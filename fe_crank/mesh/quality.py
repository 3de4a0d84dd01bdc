"""Mesh quality: fillet edge lengths, the quadratic map's Jacobian ratio, and the
straightening of poorly curved quadratic tetrahedra."""

from __future__ import annotations

import numpy as np

from fe_crank.errors import MeshError


def fillet_max_edge(mesh, names) -> dict[str, float]:
    """Longest element edge on each named fillet boundary, m."""
    out = {}
    p = mesh.p
    for name in names:
        f = mesh.facets[:, mesh.boundaries[name]]
        e = np.concatenate([np.linalg.norm(p[:, f[i]] - p[:, f[j]], axis=0) for i, j in ((0, 1), (1, 2), (0, 2))])
        out[name] = float(e.max())
    return out


def jacobian_ratio(mesh) -> float:
    """Smallest corner-Jacobian ratio of the mesh's elements (1 for straight-sided)."""
    from fe_crank.gmsh_io import corner_jacobians

    J = corner_jacobians(mesh)
    if np.any(J <= 0):
        bad = int(np.sum(np.any(J <= 0, axis=1)))
        raise MeshError(f"{bad} inverted or degenerate quadratic tetrahedra (Jacobian <= 0)")
    return float(np.min(J.min(axis=1) / J.max(axis=1)))


def tet_tags(gmsh) -> np.ndarray:
    """gmsh tags of the current model's tetrahedra."""
    _, etags, _ = gmsh.model.mesh.getElements(3)
    return np.concatenate([np.asarray(t, dtype=np.int64) for t in etags]) if etags else np.zeros(0, dtype=np.int64)


#: quadratic tetrahedra whose scaled Jacobian (gmsh ``minSJ``: min over the element of
#: det J / (product of the edge-vector norms), normalised) is at or below this are made straight-sided
STRAIGHTEN_BELOW = 0.1


def straighten_poor(gmsh, throw_name: str, threshold: float = STRAIGHTEN_BELOW, passes: int = 4) -> int:
    """Move the mid-edge nodes of poorly curved quadratic tetrahedra to their edge midpoints.

    Placing the mid-edge nodes of a curved element on the geometry can fold a flat
    element whose four vertices lie on a curved face (a boundary sliver whose height is
    of the order of the sagitta): its Jacobian falls to ~1e-3 of its maximum at a corner.
    The displacement solution barely notices, but stresses evaluated at such a corner
    (the nodal stresses the assessment reads) are extrapolations that overshoot by
    10-100x; on the shipped single-cylinder throw 3.6 % of the elements were like that.  Elements with
    gmsh ``minSJ <= threshold`` are therefore made straight-sided, which is valid whenever
    the linear tetrahedron is (checked before); the geometric error is the sagitta
    ``h^2 / (8 r)`` of their curved edges (0.5 % of r at the r/4 fillet rule).  Measured
    on the single-cylinder throw (coarse): peak fillet stresses within 2 % of gmsh's high-order
    optimiser, at a fraction of its time.  Returns the number of elements changed.
    """
    changed: set[int] = set()
    for _ in range(passes):
        tags = tet_tags(gmsh)
        q = np.asarray(gmsh.model.mesh.getElementQualities(tags, "minSJ"))
        bad = {int(b) for b in tags[q <= threshold]} - changed  # straight slivers stay as they are
        if not bad:
            break
        changed.update(bad)
        for tag in bad:
            _, nodes, _, _ = gmsh.model.mesh.getElement(int(tag))
            nodes = [int(n) for n in nodes]
            xyz = {n: np.array(gmsh.model.mesh.getNode(n)[0]) for n in nodes[:4]}
            # gmsh tet10 edges: 4:(0,1) 5:(1,2) 6:(2,0) 7:(3,0) 8:(3,2) 9:(3,1)
            for m, (a, b) in zip(nodes[4:], ((0, 1), (1, 2), (2, 0), (3, 0), (3, 2), (3, 1))):
                mid = 0.5 * (xyz[nodes[a]] + xyz[nodes[b]])
                gmsh.model.mesh.setNode(m, mid.tolist(), [])
    tags = tet_tags(gmsh)
    q = np.asarray(gmsh.model.mesh.getElementQualities(tags, "minSICN"))
    if np.any(q <= 0.0):
        raise MeshError(
            f"{int(np.sum(q <= 0))} invalid quadratic tetrahedra remain in throw {throw_name!r} after straightening"
        )
    return len(changed)
