"""Small meshes with closed-form answers, for the FE verification tests and the benchmark.

Built with gmsh (second order) through :func:`fe_crank.gmsh_io.model_to_skfem`, so the
curved surfaces are quadratic (isoparametric).  Dimensions in metres.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fe_crank.gmsh_io import gmsh_session, model_to_skfem
from fe_crank.mesh.types import MeshStats, ThrowMesh


@dataclass(frozen=True)
class Steel:
    """Structural steel for the verification models (SI)."""

    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3
    density: float = 7850.0


def as_throw_mesh(mesh, *, symmetry: tuple[int, ...] = (), throw: str = "verification") -> ThrowMesh:
    """A ``ThrowMesh`` of a mesh built here (no files, no fillet sizes), as the FE stage takes it.

    ``symmetry``: the axes across which ``mesh`` is an exact mirror image (``ThrowMesh.symmetry``).
    """
    n, ne = mesh.p.shape[1], mesh.t.shape[1]
    stats = MeshStats(
        nodes=n,
        elements=ne,
        p2_dofs=3 * n,
        min_quality=float("nan"),
        straightened=0,
        min_jacobian_ratio=float("nan"),
        fillet_max_edge={},
        fillet_radii={},
        build_seconds=0.0,
        symmetry=tuple(symmetry),
    )
    return ThrowMesh(mesh, stats, {}, Path(), Path(), throw, key="", symmetry=tuple(symmetry))


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


def round_bar(
    diameter: float = 0.02, length: float = 0.08, size: float = 0.004, *, centre=(0.0, 0.0), lateral: str = "surface"
):
    """Solid round bar parallel to z through ``centre`` (x, y), from z = 0 to ``length``:
    boundaries end_1, end_2 and ``lateral`` (the cylindrical surface)."""
    with gmsh_session() as gmsh:
        gmsh.model.occ.addCylinder(centre[0], centre[1], 0, 0, 0, length, diameter / 2)
        gmsh.model.occ.synchronize()

        def classify(kind, c, bb):
            if abs(c[2]) < 1e-9:
                return "end_1"
            if abs(c[2] - length) < 1e-9:
                return "end_2"
            return lateral

        _name_surfaces(gmsh, classify)
        return _mesh(gmsh, size * 0.5, size)


def simple_throw(
    *,
    journal_d=0.05,
    pin_d=0.045,
    radius=0.045,
    journal_len=0.03,
    web_t=0.02,
    pin_len=0.03,
    web_w=0.08,
    size=0.008,
    fillet=0.0,
    fillet_size=None,
):
    """A crank throw with box webs (throw frame: crank axis z, pin centre on +y at ``radius``).

    Boundaries: journal_1, journal_2, crankpin, end_1, end_2, other; with ``fillet`` > 0 also
    crankpin_fillet_1/2 and journal_fillet_1/2 (element size ``fillet_size``, default r/2).
    """
    z0 = -(journal_len + web_t + pin_len / 2)
    zs = [
        z0,
        z0 + journal_len,
        z0 + journal_len + web_t,
        z0 + journal_len + web_t + pin_len,
        z0 + journal_len + 2 * web_t + pin_len,
        z0 + 2 * journal_len + 2 * web_t + pin_len,
    ]
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        j1 = occ.addCylinder(0, 0, zs[0], 0, 0, journal_len, journal_d / 2)
        w1 = occ.addBox(-web_w / 2, -journal_d * 0.7, zs[1], web_w, radius + journal_d * 1.4, web_t)
        p = occ.addCylinder(0, radius, zs[2], 0, 0, pin_len, pin_d / 2)
        w2 = occ.addBox(-web_w / 2, -journal_d * 0.7, zs[3], web_w, radius + journal_d * 1.4, web_t)
        j2 = occ.addCylinder(0, 0, zs[4], 0, 0, journal_len, journal_d / 2)
        out, _ = occ.fuse([(3, j1)], [(3, w1), (3, p), (3, w2), (3, j2)])
        occ.synchronize()
        fillet_names = {}
        if fillet > 0:
            wanted = {
                (zs[1], 0.0, journal_d / 2): "journal_fillet_1",
                (zs[2], radius, pin_d / 2): "crankpin_fillet_1",
                (zs[3], radius, pin_d / 2): "crankpin_fillet_2",
                (zs[4], 0.0, journal_d / 2): "journal_fillet_2",
            }
            edges = []
            for _, c in gmsh.model.getEntities(1):
                bb = np.array(gmsh.model.getBoundingBox(1, c))
                for z, yc, rad in wanted:
                    if (
                        abs(bb[2] - z) < 1e-6
                        and abs(bb[5] - z) < 1e-6
                        and abs(bb[3] - rad) < 1e-6
                        and abs(0.5 * (bb[1] + bb[4]) - yc) < 1e-6
                    ):
                        edges.append(c)
            occ.fillet([out[0][1]], edges, [fillet])
            occ.synchronize()
            fillet_names = wanted

        def classify(kind, c, bb):
            if abs(bb[2] - zs[0]) < 1e-6 and abs(bb[5] - zs[0]) < 1e-6:
                return "end_1"
            if abs(bb[2] - zs[5]) < 1e-6 and abs(bb[5] - zs[5]) < 1e-6:
                return "end_2"
            if kind not in ("Cylinder", "Plane") and fillet_names:
                for (z, yc, _rad), name in fillet_names.items():
                    if abs(c[2] - z) < 2 * fillet and abs(0.5 * (bb[1] + bb[4]) - yc) < 2 * fillet:
                        return name
            if kind == "Cylinder":
                if c[2] < zs[1]:
                    return "journal_1"
                if c[2] > zs[4]:
                    return "journal_2"
                return "crankpin"
            return "other"

        _name_surfaces(gmsh, classify)
        if fillet > 0:
            fs = fillet_size if fillet_size is not None else fillet / 2
            surf = [t for (_, t) in gmsh.model.getEntities(2) if gmsh.model.getType(2, t) not in ("Cylinder", "Plane")]
            return _mesh(gmsh, min(fs, size), size, refine={"surfaces": surf, "size": fs, "dist_max": 4 * fillet})
        return _mesh(gmsh, size * 0.5, size)


def _mapped_tensor_mesh(u, v, w, mapping, boundaries):
    """A P2 tensor-product tetrahedral mesh on (u, v, w), its nodes mapped by ``mapping``.

    Mapping every P2 node (vertices and mid-edges) makes the geometry quadratic along
    curved coordinate lines (isoparametric).  ``boundaries``: name -> predicate on the
    parameter coordinates (3, n_facets) of the facet midpoints.
    """
    from dataclasses import replace

    from skfem import MeshTet1, MeshTet2

    m1 = MeshTet1.init_tensor(u, v, w)
    m1 = m1.with_boundaries(boundaries)
    m2 = MeshTet2.from_mesh(m1)
    m2 = m2.with_boundaries(dict(m1.boundaries))
    return replace(m2, doflocs=mapping(m2.doflocs))


def annulus_sector(r_inner=0.05, r_outer=0.15, thickness=0.005, angle=np.pi / 2, *, nr=8, nt=12, nz=1):
    """Quarter (by default) of a flat annular disk, 0 <= z <= thickness, theta from +x.

    Radial spacing is geometric (equal steps in log r), the natural grading of the
    Lamé stress field.  Boundaries: ``bore`` (r = r_inner), ``rim``, ``sym_x`` (theta = 0: the plane y = 0),
    ``sym_y`` (theta = angle: x = 0 for a quarter), ``bottom`` (z = 0), ``top``.
    """
    r = r_inner * (r_outer / r_inner) ** np.linspace(0.0, 1.0, nr + 1)  # geometric: fine at the bore
    t = np.linspace(0.0, angle, nt + 1)
    z = np.linspace(0.0, thickness, nz + 1)
    tol = 1e-12

    def mapping(p):
        return np.vstack([p[0] * np.cos(p[1]), p[0] * np.sin(p[1]), p[2]])

    return _mapped_tensor_mesh(
        r,
        t,
        z,
        mapping,
        {
            "bore": lambda x: np.abs(x[0] - r_inner) < tol,
            "rim": lambda x: np.abs(x[0] - r_outer) < tol,
            "sym_x": lambda x: np.abs(x[1]) < tol,
            "sym_y": lambda x: np.abs(x[1] - angle) < tol,
            "bottom": lambda x: np.abs(x[2]) < tol,
            "top": lambda x: np.abs(x[2] - thickness) < tol,
        },
    )


def box_beam(length=0.2, height=0.02, width=0.02, *, nx=20, ny=2, nz=2):
    """Straight beam 0 <= x <= length, 0 <= y <= width, 0 <= z <= height.

    Boundaries: ``root`` (x = 0), ``tip`` (x = length), ``top`` (z = height), ``bottom``.
    """
    tol = 1e-12
    return _mapped_tensor_mesh(
        np.linspace(0, length, nx + 1),
        np.linspace(0, width, ny + 1),
        np.linspace(0, height, nz + 1),
        lambda p: p,
        {
            "root": lambda x: np.abs(x[0]) < tol,
            "tip": lambda x: np.abs(x[0] - length) < tol,
            "top": lambda x: np.abs(x[2] - height) < tol,
            "bottom": lambda x: np.abs(x[2]) < tol,
        },
    )


def stepped_shaft(d=0.02, D=0.03, r=0.003, *, len_small=0.04, len_large=0.045, size=0.004, fillet_size=None):
    """Round shaft with a shoulder: diameter d on 0 <= z <= len_small, D beyond, fillet r.

    Boundaries: ``end_1`` (z = 0, small end), ``end_2``, ``fillet`` (the toroidal fillet
    surface), ``surface`` (the rest).  ``fillet_size``: element size on the fillet
    (default r / 4, the M53 guidance), growing to ``size`` within 2 r of it.
    """
    fs = fillet_size if fillet_size is not None else r / 4
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        a = occ.addCylinder(0, 0, 0, 0, 0, len_small, d / 2)
        b = occ.addCylinder(0, 0, len_small, 0, 0, len_large, D / 2)
        out, _ = occ.fuse([(3, a)], [(3, b)])
        occ.synchronize()
        vol = out[0][1]
        # the shoulder's inner circular edge: radius d/2 at z = len_small
        edge = None
        for _, c in gmsh.model.getEntities(1):
            bb = np.array(gmsh.model.getBoundingBox(1, c))
            if abs(bb[2] - len_small) < 1e-6 and abs(bb[5] - len_small) < 1e-6 and abs(bb[3] - d / 2) < 1e-6:
                edge = c
        out = occ.fillet([vol], [edge], [r])
        occ.synchronize()

        def classify(kind, c, bb):
            if abs(bb[2]) < 1e-6 and abs(bb[5]) < 1e-6:
                return "end_1"
            if abs(bb[2] - len_small - len_large) < 1e-6 and abs(bb[5] - len_small - len_large) < 1e-6:
                return "end_2"
            if kind not in ("Cylinder", "Plane"):
                return "fillet"
            return "surface"

        _name_surfaces(gmsh, classify)
        fillet = [t for (dim, t) in gmsh.model.getEntities(2) if gmsh.model.getType(2, t) not in ("Cylinder", "Plane")]
        return _mesh(
            gmsh, min(fs, size), size, refine={"surfaces": fillet, "size": fs, "dist_min": 0.0, "dist_max": 4 * r}
        )
