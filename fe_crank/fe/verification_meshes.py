"""Small meshes with closed-form answers, for the FE verification tests and the benchmark.

Built with gmsh (second order) through :func:`fe_crank.gmsh_io.model_to_skfem`, so the
curved surfaces are quadratic (isoparametric).  Dimensions in metres.
"""

from __future__ import annotations

import numpy as np

from fe_crank.gmsh_io import gmsh_session, model_to_skfem


def _mesh(gmsh, size_min: float, size_max: float, refine: dict | None = None):
    gmsh.option.setNumber("Mesh.MeshSizeMin", size_min)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size_max)
    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 0)
    gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
    if refine:
        f = gmsh.model.mesh.field
        fid = f.add("Distance")
        f.setNumbers(fid, "SurfacesList", refine["surfaces"])
        th = f.add("Threshold")
        f.setNumber(th, "InField", fid)
        f.setNumber(th, "SizeMin", refine["size"])
        f.setNumber(th, "SizeMax", size_max)
        f.setNumber(th, "DistMin", refine.get("dist_min", 0.0))
        f.setNumber(th, "DistMax", refine["dist_max"])
        f.setAsBackgroundMesh(th)
        gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
        gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.model.mesh.generate(3)
    gmsh.model.mesh.setOrder(2)
    return model_to_skfem()


def _name_surfaces(gmsh, classify):
    """Physical groups for surfaces: ``classify(type, centre, bbox) -> name | None``."""
    groups: dict[str, list[int]] = {}
    for _, tag in gmsh.model.getEntities(2):
        kind = gmsh.model.getType(2, tag)
        c = np.array(gmsh.model.occ.getCenterOfMass(2, tag))
        bb = np.array(gmsh.model.getBoundingBox(2, tag))
        name = classify(kind, c, bb)
        if name:
            groups.setdefault(name, []).append(tag)
    for name, tags in groups.items():
        gmsh.model.addPhysicalGroup(2, tags, name=name)
    vols = [t for _, t in gmsh.model.getEntities(3)]
    gmsh.model.addPhysicalGroup(3, vols, name="body")


def round_bar(diameter: float = 0.02, length: float = 0.08, size: float = 0.004):
    """Solid round bar on the z axis from z = 0 to ``length``: boundaries end_1, end_2, surface."""
    with gmsh_session() as gmsh:
        gmsh.model.occ.addCylinder(0, 0, 0, 0, 0, length, diameter / 2)
        gmsh.model.occ.synchronize()

        def classify(kind, c, bb):
            if abs(c[2]) < 1e-9:
                return "end_1"
            if abs(c[2] - length) < 1e-9:
                return "end_2"
            return "surface"

        _name_surfaces(gmsh, classify)
        return _mesh(gmsh, size * 0.5, size)


def simple_throw(*, journal_d=0.05, pin_d=0.045, radius=0.045, journal_len=0.03, web_t=0.02,
                 pin_len=0.03, web_w=0.08, size=0.008):
    """A crank throw without fillets (throw frame: crank axis z, pin centre on +y at ``radius``).

    Boundaries: journal_1, journal_2, crankpin, end_1, end_2, other.
    """
    z0 = -(journal_len + web_t + pin_len / 2)
    zs = [z0, z0 + journal_len, z0 + journal_len + web_t, z0 + journal_len + web_t + pin_len,
          z0 + journal_len + 2 * web_t + pin_len, z0 + 2 * journal_len + 2 * web_t + pin_len]
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        j1 = occ.addCylinder(0, 0, zs[0], 0, 0, journal_len, journal_d / 2)
        w1 = occ.addBox(-web_w / 2, -journal_d * 0.7, zs[1], web_w, radius + journal_d * 1.4, web_t)
        p = occ.addCylinder(0, radius, zs[2], 0, 0, pin_len, pin_d / 2)
        w2 = occ.addBox(-web_w / 2, -journal_d * 0.7, zs[3], web_w, radius + journal_d * 1.4, web_t)
        j2 = occ.addCylinder(0, 0, zs[4], 0, 0, journal_len, journal_d / 2)
        occ.fuse([(3, j1)], [(3, w1), (3, p), (3, w2), (3, j2)])
        occ.synchronize()

        def classify(kind, c, bb):
            if abs(bb[2] - zs[0]) < 1e-6 and abs(bb[5] - zs[0]) < 1e-6:
                return "end_1"
            if abs(bb[2] - zs[5]) < 1e-6 and abs(bb[5] - zs[5]) < 1e-6:
                return "end_2"
            if kind == "Cylinder":
                if c[2] < zs[1]:
                    return "journal_1"
                if c[2] > zs[4]:
                    return "journal_2"
                return "crankpin"
            return "other"

        _name_surfaces(gmsh, classify)
        return _mesh(gmsh, size * 0.5, size)
