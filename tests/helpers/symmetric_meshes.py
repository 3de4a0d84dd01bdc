"""A throw-like body meshed on its fundamental part with gmsh and mirrored: exact mirror symmetry.

The body (crank axis z, crankpin centre on +y): two journals, two box webs and a pin,
symmetric about x = 0 and z = 0.  gmsh meshes the part x >= 0 and/or z <= 0 (linear
tetrahedra); the part is reflected node by node (on-plane nodes shared, coordinates
negated exactly), and scikit-fem's ``MeshTet2.from_mesh`` adds the mid-edge nodes, so
the P2 mesh is an exact mirror image (straight-sided elements: enough for checking the
solver, not for stress accuracy).  Boundaries: journal_1, journal_2, crankpin, end_1,
end_2, other; a z = 0 reflection swaps the _1/_2 names.
"""

from __future__ import annotations

import numpy as np

from fe_crank.gmsh_io import gmsh_session
from fe_crank.mesh.types import ThrowMesh
from helpers.verification_meshes import as_throw_mesh


def _swap(name: str) -> str:
    return name[:-1] + {"1": "2", "2": "1"}[name[-1]] if name[-2:] in ("_1", "_2") else name


def mirror(p, t, bnd, axis):
    """Reflect a linear tet mesh (p (3, n), t (4, ne), bnd name -> triangles (3, m)) across x_axis = 0."""
    scale = np.ptp(p, axis=1).max()
    on = np.abs(p[axis]) < 1e-9 * scale
    p = p.copy()
    p[axis, on] = 0.0  # on-plane nodes exactly on it
    off = np.flatnonzero(~on)
    new = np.arange(p.shape[1])
    new[off] = p.shape[1] + np.arange(off.size)
    q = p[:, off].copy()
    q[axis] = -q[axis]
    out_b: dict[str, list] = {}
    for name, tri in bnd.items():
        out_b.setdefault(name, []).append(tri)
        out_b.setdefault(_swap(name) if axis == 2 else name, []).append(new[tri])
    t2 = new[t][[1, 0, 2, 3]]  # a reflection reverses orientation: swap two vertices
    return np.hstack([p, q]), np.hstack([t, t2]), {k: np.hstack(v) for k, v in out_b.items()}


def _quarter(planes, size, journal_d, pin_d, radius, journal_len, web_t, pin_len, web_w):
    zs = np.cumsum([-(journal_len + web_t + pin_len / 2), journal_len, web_t, pin_len, web_t, journal_len])
    big = 1.0
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        parts = [
            occ.addCylinder(0, 0, zs[0], 0, 0, journal_len, journal_d / 2),
            occ.addBox(-web_w / 2, -journal_d * 0.7, zs[1], web_w, radius + journal_d * 1.4, web_t),
            occ.addCylinder(0, radius, zs[2], 0, 0, pin_len, pin_d / 2),
            occ.addBox(-web_w / 2, -journal_d * 0.7, zs[3], web_w, radius + journal_d * 1.4, web_t),
            occ.addCylinder(0, 0, zs[4], 0, 0, journal_len, journal_d / 2),
        ]
        body, _ = occ.fuse([(3, parts[0])], [(3, k) for k in parts[1:]])
        x0 = 0.0 if 0 in planes else -big
        z1 = 0.0 if 2 in planes else big
        cut = occ.addBox(x0, -big, -big, big - x0, 2 * big, z1 + big)
        occ.intersect(body, [(3, cut)])
        occ.synchronize()
        groups: dict[str, list[int]] = {}
        for _, tag in gmsh.model.getEntities(2):
            bb = np.array(gmsh.model.getBoundingBox(2, tag))
            c = np.array(occ.getCenterOfMass(2, tag))
            flat = [a for a in range(3) if bb[a + 3] - bb[a] < 1e-6]
            if any(a in planes and abs(bb[a]) < 1e-6 for a in flat):
                continue  # a cut face: interior after mirroring
            if 2 in flat and abs(bb[2] - zs[0]) < 1e-6:
                name = "end_1"
            elif 2 in flat and abs(bb[2] - zs[5]) < 1e-6:
                name = "end_2"
            elif gmsh.model.getType(2, tag) == "Cylinder":
                name = "crankpin" if zs[1] < c[2] < zs[4] else ("journal_1" if c[2] < 0 else "journal_2")
            else:
                name = "other"
            groups.setdefault(name, []).append(tag)
        for name, tags in groups.items():
            gmsh.model.addPhysicalGroup(2, tags, name=name)
        gmsh.model.addPhysicalGroup(3, [t for _, t in gmsh.model.getEntities(3)], name="body")
        gmsh.option.setNumber("Mesh.MeshSizeMin", size * 0.5)
        gmsh.option.setNumber("Mesh.MeshSizeMax", size)
        gmsh.model.mesh.generate(3)
        tags, coords, _ = gmsh.model.mesh.getNodes()
        index = np.zeros(int(tags.max()) + 1, int)
        index[tags.astype(int)] = np.arange(tags.size)
        p = coords.reshape(-1, 3).T
        t = np.hstack(
            [
                index[np.asarray(n, int)].reshape(-1, 4).T
                for _, tg in gmsh.model.getEntities(3)
                for ty, _, n in zip(*gmsh.model.mesh.getElements(3, tg))
                if ty == 4
            ]
        )
        bnd = {}
        for dim, ptag in gmsh.model.getPhysicalGroups(2):
            name = gmsh.model.getPhysicalName(dim, ptag)
            tri = [
                index[np.asarray(n, int)].reshape(-1, 3).T
                for ent in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag)
                for ty, _, n in zip(*gmsh.model.mesh.getElements(2, ent))
                if ty == 2
            ]
            bnd[name] = np.hstack(tri)
    used = np.unique(t)  # nodes of the tetrahedra only
    renum = np.full(p.shape[1], -1)
    renum[used] = np.arange(used.size)
    return p[:, used], renum[t], {k: renum[v] for k, v in bnd.items()}


def mirrored_throw(
    planes=(0, 2),
    *,
    size=0.012,
    journal_d=0.05,
    pin_d=0.045,
    radius=0.045,
    journal_len=0.03,
    web_t=0.02,
    pin_len=0.03,
    web_w=0.08,
) -> ThrowMesh:
    """The body meshed on its part behind ``planes`` (0: x = 0, 2: z = 0) and mirrored (module doc)."""
    from skfem import MeshTet1, MeshTet2

    p, t, bnd = _quarter(tuple(planes), size, journal_d, pin_d, radius, journal_len, web_t, pin_len, web_w)
    for a in planes:
        p, t, bnd = mirror(p, t, bnd, a)
    m1 = MeshTet1(p, t)
    n = p.shape[1]
    fkey = {tuple(f): i for i, f in enumerate(np.sort(m1.facets, axis=0).T.tolist())}
    named = {k: np.array([fkey[tuple(f)] for f in np.sort(v, axis=0).T.tolist()]) for k, v in bnd.items()}
    assert all(np.isin(f, m1.boundary_facets()).all() for f in named.values()) and n == m1.p.shape[1]
    m2 = MeshTet2.from_mesh(m1).with_boundaries(named)
    return as_throw_mesh(m2, symmetry=tuple(sorted(planes)), throw="mirrored")
