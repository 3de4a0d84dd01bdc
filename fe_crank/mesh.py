"""Quadratic tetrahedral meshes of one crank throw, graded into the fillets, cached on disk.

:func:`mesh_throw` builds the throw (``fe_crank.geometry.throw.add_throw``), meshes it
with gmsh (second-order tetrahedra, curved isoparametric geometry), converts it to a
scikit-fem ``MeshTet2`` with named boundaries and subdomains
(``fe_crank.gmsh_io.model_to_skfem``), checks it and writes ``.msh`` and ``.vtu``.

Element size: a ``Distance`` + ``Threshold`` size field around every fillet surface
sets the element edge there to ``r / fillet_divisions`` (times a safety factor, since
gmsh's edges scatter around the target); IACS UR M53 (appendix, FE guidance) asks for
at most ``r/4`` in the fillets, which the ``coarse``/``medium``/``fine`` presets keep.
Away from the fillets the size grows linearly with the distance (``grading``) to
``size_max``.  Only the ``test`` preset relaxes the fillet rule (edge about ``r``) so that other
stages' unit tests mesh a whole throw in a few seconds.

Cache: ``cache_dir/<key>/`` with ``key`` = SHA-256 of the geometry (dimensions only,
not its name or file), the throw, the mesh options, the fe-crank and gmsh versions and
the cache format.  Entries are written to a temporary folder
(``.<key>.partial-<pid>-*``) and renamed into place (atomic on POSIX), so a reader never
sees half an entry; temporary folders of killed processes are removed by the next
run, and an entry that cannot be read back whole is discarded and rebuilt.
"""

from __future__ import annotations

import atexit
import dataclasses
import hashlib
import json
import os
import shutil
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from fe_crank.errors import MeshError
from fe_crank.geometry.spec import CrankGeometry, ThrowSpec

CACHE_FORMAT = 2  # 2: Netgen optimisation and straightening of poorly curved elements (minSJ <= 0.1)
DEFAULT_CACHE_DIR = Path(".cache") / "meshes"
_SAFETY = 0.65  # target edge = SAFETY * r / fillet_divisions: gmsh's surface edges exceed the target by up to ~40 %


@dataclass(frozen=True)
class MeshOptions:
    """Mesh size controls.

    ``size_max = crankpin_diameter / coarse_divisions`` unless given (m).  Fillet
    element edge ``<= r / fillet_divisions``; size grows away from the fillets by
    ``grading`` m per m of distance.
    """

    coarse_divisions: float = 4.0
    fillet_divisions: float = 4.0
    grading: float = 0.35
    size_max: float | None = None
    bore_divisions: float = 6.0  # elements round the oil bore circumference / pi
    optimize_high_order: bool = False  # gmsh's HighOrder optimiser can abort the process (uncaught C++ error)

    def __post_init__(self):
        for name in ("coarse_divisions", "fillet_divisions", "grading", "bore_divisions"):
            v = getattr(self, name)
            if not (np.isfinite(v) and v > 0):
                raise MeshError(f"mesh option {name} must be positive (got {v})")
        if self.size_max is not None and not self.size_max > 0:
            raise MeshError(f"mesh option size_max must be positive (got {self.size_max})")


PRESETS: dict[str, MeshOptions] = {
    "test": MeshOptions(coarse_divisions=1.5, fillet_divisions=1.0, grading=2.0),
    "coarse": MeshOptions(coarse_divisions=3.0, fillet_divisions=4.0, grading=1.5),
    "medium": MeshOptions(coarse_divisions=4.0, fillet_divisions=5.0, grading=1.0),
    "fine": MeshOptions(coarse_divisions=6.0, fillet_divisions=8.0, grading=0.7),
}


@dataclass(frozen=True)
class MeshStats:
    nodes: int
    elements: int
    p2_dofs: int  # 3 displacement components per node of the quadratic mesh
    min_quality: float  # gmsh minSICN of the linear tetrahedra (1 ideal, <= 0 inverted)
    straightened: int  # quadratic elements whose mid-edge nodes were moved to the midpoints (see _straighten_poor)
    min_jacobian_ratio: float  # min/max of the quadratic map's Jacobian over each element, worst element
    fillet_max_edge: dict[str, float]  # m, longest triangle edge on each fillet surface
    fillet_radii: dict[str, float]
    build_seconds: float
    from_cache: bool = False


@dataclass(frozen=True)
class ThrowMesh:
    """A meshed throw: scikit-fem ``MeshTet2`` with named boundaries/subdomains (throw frame)."""

    mesh: object
    stats: MeshStats
    fillet_radii: dict[str, float]
    msh_path: Path
    vtu_path: Path
    throw: str
    key: str
    options: MeshOptions = field(default_factory=MeshOptions)


def resolve_options(size: str | MeshOptions) -> MeshOptions:
    if isinstance(size, MeshOptions):
        return size
    try:
        return PRESETS[size]
    except KeyError:
        raise MeshError(f"unknown mesh size {size!r}; pick one of {sorted(PRESETS)} or pass MeshOptions") from None


def cache_key(geometry: CrankGeometry, throw: ThrowSpec, options: MeshOptions) -> str:
    """SHA-256 (hex, 20 chars) of everything that changes the mesh."""
    import gmsh

    from fe_crank import __version__

    geo = dataclasses.asdict(geometry)
    for k in ("name", "description", "source", "file", "throws"):
        geo.pop(k, None)
    th = dataclasses.asdict(throw)
    th.pop("angle", None)  # the throw frame does not depend on the throw's angle
    th.pop("name", None)
    for cw in th["counterweights"]:
        cw.pop("bolted", None)  # bolt data do not change the solid
    payload = {
        "geometry": geo,
        "throw": th,
        "options": dataclasses.asdict(options),
        "fe_crank": __version__,
        "gmsh": gmsh.__version__,
        "format": CACHE_FORMAT,
    }
    text = json.dumps(payload, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def _fillet_distance(g: CrankGeometry, name: str) -> str:
    """gmsh MathEval expression: distance from (x, y, z) to the fillet's torus.

    The rolling-ball fillet of radius ``r_f`` between a cylinder of radius ``r`` and a
    web face is part of the torus whose spine circle (radius ``r + r_f``, about the
    cylinder's axis) lies ``r_f - u`` off the web face (``u`` the undercut); distance to the torus =
    ``| dist(x, spine) - r_f |`` (exact, unlike sampled ``Distance`` fields).
    """
    zp = g.crankpin_length / 2
    zw = zp + g.web_thickness
    if name.startswith("crankpin_fillet"):
        rf, a, cy = g.crankpin_fillet, g.crankpin_diameter / 2 + g.crankpin_fillet, g.crank_radius
        off = rf - g.crankpin_undercut
        zc = -zp + off if name.endswith("1") else zp - off
    else:
        rf, a, cy = g.journal_fillet, g.journal_diameter / 2 + g.journal_fillet, 0.0
        off = rf - g.journal_undercut
        zc = -zw - off if name.endswith("1") else zw + off
    rho = f"Sqrt(x*x + (y - ({cy!r}))*(y - ({cy!r})))"
    spine = f"Sqrt(({rho} - {a!r})*({rho} - {a!r}) + (z - ({zc!r}))*(z - ({zc!r})))"
    return f"Fabs({spine} - {rf!r})"


def _set_size_fields(gmsh, geometry: CrankGeometry, surfaces: dict[str, list[int]], fillet_radii: dict[str, float], opt: MeshOptions) -> float:
    size_max = opt.size_max if opt.size_max is not None else geometry.crankpin_diameter / opt.coarse_divisions
    fields = []
    for name, r in fillet_radii.items():
        h = _SAFETY * r / opt.fillet_divisions
        d = gmsh.model.mesh.field.add("MathEval")
        gmsh.model.mesh.field.setString(d, "F", _fillet_distance(geometry, name))
        th = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(th, "InField", d)
        gmsh.model.mesh.field.setNumber(th, "SizeMin", h)
        gmsh.model.mesh.field.setNumber(th, "SizeMax", size_max)
        gmsh.model.mesh.field.setNumber(th, "DistMin", 0.0)
        gmsh.model.mesh.field.setNumber(th, "DistMax", max(size_max - h, 0.0) / opt.grading)
        fields.append(th)
    if "oil_bore" in surfaces and geometry.oil_bore is not None:
        h = np.pi * geometry.oil_bore.diameter / (2 * opt.bore_divisions)
        d = gmsh.model.mesh.field.add("Distance")
        gmsh.model.mesh.field.setNumbers(d, "SurfacesList", surfaces["oil_bore"])
        th = gmsh.model.mesh.field.add("Threshold")
        gmsh.model.mesh.field.setNumber(th, "InField", d)
        gmsh.model.mesh.field.setNumber(th, "SizeMin", min(h, size_max))
        gmsh.model.mesh.field.setNumber(th, "SizeMax", size_max)
        gmsh.model.mesh.field.setNumber(th, "DistMin", 0.0)
        gmsh.model.mesh.field.setNumber(th, "DistMax", max(size_max - h, 0.0) / opt.grading)
        fields.append(th)
    if fields:
        mn = gmsh.model.mesh.field.add("Min")
        gmsh.model.mesh.field.setNumbers(mn, "FieldsList", fields)
        gmsh.model.mesh.field.setAsBackgroundMesh(mn)
    gmsh.option.setNumber("Mesh.MeshSizeMax", size_max)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 12)  # 12 elements per 2 pi on curved faces
    return size_max


def _fillet_max_edge(mesh, names) -> dict[str, float]:
    out = {}
    p = mesh.p
    for name in names:
        f = mesh.facets[:, mesh.boundaries[name]]
        e = np.concatenate([np.linalg.norm(p[:, f[i]] - p[:, f[j]], axis=0) for i, j in ((0, 1), (1, 2), (0, 2))])
        out[name] = float(e.max())
    return out


def _jacobian_ratio(mesh) -> float:
    from fe_crank.gmsh_io import corner_jacobians

    J = corner_jacobians(mesh)
    if np.any(J <= 0):
        bad = int(np.sum(np.any(J <= 0, axis=1)))
        raise MeshError(f"{bad} inverted or degenerate quadratic tetrahedra (Jacobian <= 0)")
    return float(np.min(J.min(axis=1) / J.max(axis=1)))


def _save_npz(path: Path, mesh) -> None:
    arrays = {"doflocs": mesh.doflocs, "t": mesh.t}
    for k, v in (mesh.boundaries or {}).items():
        arrays[f"b::{k}"] = v
    for k, v in (mesh.subdomains or {}).items():
        arrays[f"s::{k}"] = v
    with open(path, "wb") as fh:
        np.savez(fh, **arrays)


def _load_npz(path: Path):
    from skfem import MeshTet2

    with np.load(path) as z:
        mesh = MeshTet2(z["doflocs"], z["t"])
        b = {k[3:]: z[k] for k in z.files if k.startswith("b::")}
        s = {k[3:]: z[k] for k in z.files if k.startswith("s::")}
    return mesh.with_boundaries(b).with_subdomains(s)


def write_vtu(path: Path, mesh) -> None:
    """Write a ``MeshTet2`` as VTK quadratic tetrahedra with a ``subdomain`` cell array."""
    import meshio

    cells = mesh.dofs.element_dofs.T  # vertex dofs then edge dofs: VTK_QUADRATIC_TETRA order
    sub = np.full(mesh.nelements, -1, dtype=np.int32)
    names = sorted(mesh.subdomains or {})
    for i, name in enumerate(names):
        sub[mesh.subdomains[name]] = i
    m = meshio.Mesh(mesh.doflocs.T, [("tetra10", cells)], cell_data={"subdomain": [sub]})
    m.field_data = {name: np.array([i, 3]) for i, name in enumerate(names)}
    meshio.write(str(path), m, file_format="vtu")


def _stats_to_json(s: MeshStats) -> dict:
    return dataclasses.asdict(s)


def _stats_from_json(d: dict) -> MeshStats:
    d = dict(d)
    d["from_cache"] = True
    return MeshStats(**d)


def _tet_tags(gmsh) -> np.ndarray:
    _, etags, _ = gmsh.model.mesh.getElements(3)
    return np.concatenate([np.asarray(t, dtype=np.int64) for t in etags]) if etags else np.zeros(0, dtype=np.int64)


#: quadratic tetrahedra whose scaled Jacobian (gmsh ``minSJ``: min over the element of
#: det J / (product of the edge-vector norms), normalised) is at or below this are made straight-sided
STRAIGHTEN_BELOW = 0.1


def _straighten_poor(gmsh, throw_name: str, threshold: float = STRAIGHTEN_BELOW, passes: int = 4) -> int:
    """Move the mid-edge nodes of poorly curved quadratic tetrahedra to their edge midpoints.

    Placing the mid-edge nodes of a curved element on the geometry can fold a flat
    element whose four vertices lie on a curved face (a boundary sliver whose height is
    of the order of the sagitta): its Jacobian falls to ~1e-3 of its maximum at a corner.
    The displacement solution barely notices, but stresses evaluated at such a corner
    (the nodal stresses the assessment reads) are extrapolations that overshoot by
    10-100x; on the seed-001 throw 3.6 % of the elements were like that.  Elements with
    gmsh ``minSJ <= threshold`` are therefore made straight-sided, which is valid whenever
    the linear tetrahedron is (checked before); the geometric error is the sagitta
    ``h^2 / (8 r)`` of their curved edges (0.5 % of r at the r/4 fillet rule).  Measured
    on the seed-001 throw (coarse): peak fillet stresses within 2 % of gmsh's high-order
    optimiser, at a fraction of its time.  Returns the number of elements changed.
    """
    changed: set[int] = set()
    for _ in range(passes):
        tags = _tet_tags(gmsh)
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
    tags = _tet_tags(gmsh)
    q = np.asarray(gmsh.model.mesh.getElementQualities(tags, "minSICN"))
    if np.any(q <= 0.0):
        raise MeshError(f"{int(np.sum(q <= 0))} invalid quadratic tetrahedra remain in throw {throw_name!r} after straightening")
    return len(changed)


def _build(geometry: CrankGeometry, spec: ThrowSpec, opt: MeshOptions, folder: Path):
    from fe_crank.geometry.throw import add_throw
    from fe_crank.gmsh_io import gmsh_session, model_to_skfem

    t0 = time.perf_counter()
    with gmsh_session() as gmsh:
        model = add_throw(geometry, spec)
        _set_size_fields(gmsh, geometry, model.surfaces, model.fillet_radii, opt)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.option.setNumber("Mesh.OptimizeNetgen", 1)  # removes most boundary slivers (seed-001 coarse: 3866 -> 98 elements with Jacobian ratio < 0.1)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        try:
            gmsh.model.mesh.generate(3)
            tags = _tet_tags(gmsh)
            if tags.size == 0:
                raise MeshError(f"gmsh produced no tetrahedra for throw {spec.name!r}")
            q = np.asarray(gmsh.model.mesh.getElementQualities(tags, "minSICN"))
            min_quality = float(q.min())
            if min_quality <= 0.0:
                raise MeshError(f"{int(np.sum(q <= 0))} inverted linear tetrahedra (gmsh minSICN <= 0) in throw {spec.name!r}")
            gmsh.model.mesh.setOrder(2)
            if opt.optimize_high_order:
                gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)
                gmsh.model.mesh.optimize("HighOrder")
        except MeshError:
            raise
        except Exception as exc:  # gmsh raises bare Exception
            raise MeshError(f"gmsh could not mesh throw {spec.name!r} of {geometry.name!r}: {exc}") from None
        straightened = _straighten_poor(gmsh, spec.name)
        mesh = model_to_skfem()
        gmsh.write(str(folder / "throw.msh"))
    missing = [n for n in model.surfaces if n not in mesh.boundaries or mesh.boundaries[n].size == 0]
    missing += [n for n in model.volumes if n not in mesh.subdomains or mesh.subdomains[n].size == 0]
    if missing:
        raise MeshError(f"named groups missing or empty after meshing: {missing}")
    ratio = _jacobian_ratio(mesh)
    stats = MeshStats(
        nodes=int(mesh.doflocs.shape[1]),
        elements=int(mesh.nelements),
        p2_dofs=int(3 * mesh.doflocs.shape[1]),
        min_quality=min_quality,
        straightened=straightened,
        min_jacobian_ratio=ratio,
        fillet_max_edge=_fillet_max_edge(mesh, model.fillet_radii),
        fillet_radii=dict(model.fillet_radii),
        build_seconds=time.perf_counter() - t0,
    )
    if opt.fillet_divisions >= 4.0:
        for name, h in stats.fillet_max_edge.items():
            r = model.fillet_radii[name]
            if h > r / opt.fillet_divisions * (1 + 1e-9):
                raise MeshError(f"fillet {name!r}: largest element edge {h * 1e3:.3g} mm exceeds r/{opt.fillet_divisions:g} = {r / opt.fillet_divisions * 1e3:.3g} mm")
    return mesh, stats


_TMP_MARK = ".partial-"


def load_cache_entry(folder: Path):
    """``(mesh, stats)`` of a complete cache entry, or None.  Any entry that cannot be
    read back whole (truncated ``mesh.npz``, damaged ``stats.json``, a missing file,
    arrays that do not form a mesh) is discarded, to be rebuilt."""
    if not (folder / "complete").exists():
        return None
    try:
        mesh = _load_npz(folder / "mesh.npz")
        stats = _stats_from_json(json.loads((folder / "stats.json").read_text()))
        for name in ("throw.msh", "throw.vtu"):
            if not (folder / name).is_file():
                raise FileNotFoundError(name)
        return mesh, stats
    except Exception:  # zipfile.BadZipFile, EOFError, OSError, ValueError, ...: rebuild
        shutil.rmtree(folder, ignore_errors=True)
        return None


def clean_stale_cache_temps(root: Path) -> list[Path]:
    """Remove temporary cache folders (``.<key>.partial-<pid>-*``) whose process is
    gone (killed while meshing).  Returns what was removed."""
    import re

    removed = []
    for p in root.iterdir():
        m = re.match(r"^\..+\.partial-(\d+)-", p.name)
        if not (m and p.is_dir()):
            continue
        try:
            os.kill(int(m.group(1)), 0)
            continue  # still running
        except ProcessLookupError:
            pass
        except (PermissionError, OverflowError):
            continue
        shutil.rmtree(p, ignore_errors=True)
        removed.append(p)
    return removed


def mesh_throw(
    geometry: CrankGeometry,
    throw: ThrowSpec | str | int | None = None,
    *,
    size: str | MeshOptions = "coarse",
    cache_dir: str | Path | None = DEFAULT_CACHE_DIR,
    max_elements: int | None = None,
) -> ThrowMesh:
    """Mesh one throw with quadratic tetrahedra (cached).

    Parameters
    ----------
    geometry
        The crankshaft (``fe_crank.io.geometry.load_geometry``).
    throw
        Throw name, 0-based index, ``ThrowSpec`` or ``None`` for the first throw.
    size
        ``"test"`` (fast, fillet edge about r: NOT for stress results), ``"coarse"`` (r/4), ``"medium"`` (r/5),
        ``"fine"`` (r/8) or a ``MeshOptions``.
    max_elements
        Limit on the element count estimated before meshing
        (``fe_crank.geometry.estimate``; default ``MAX_ELEMENTS``).
    cache_dir
        Folder of the mesh cache; ``None`` meshes into a temporary folder without caching
        (the ``.msh``/``.vtu`` paths then point into that folder, which is removed when
        the process exits: copy the files to keep them).

    Returns
    -------
    ThrowMesh
        ``.mesh`` (scikit-fem ``MeshTet2``, boundaries and subdomains named as in
        docs/contracts.md), ``.stats``, ``.fillet_radii``, ``.msh_path``, ``.vtu_path``.

    Raises
    ------
    GeometryError
        Impossible geometry (before gmsh runs).
    MeshError
        gmsh failed, inverted elements, a named group empty, a fillet too coarse.
    """
    from fe_crank.geometry.checks import check_geometry

    check_geometry(geometry)
    spec = throw if isinstance(throw, ThrowSpec) else geometry.throw(throw)
    opt = resolve_options(size)
    from fe_crank.geometry.estimate import check_element_budget

    check_element_budget(geometry, spec, opt, max_elements)
    key = cache_key(geometry, spec, opt)
    if cache_dir is None:
        folder = Path(tempfile.mkdtemp(prefix="fe-crank-mesh-"))
        atexit.register(shutil.rmtree, folder, True)  # no cache: the files live as long as the process
        mesh, stats = _build(geometry, spec, opt, folder)
        write_vtu(folder / "throw.vtu", mesh)
        return ThrowMesh(mesh, stats, dict(stats.fillet_radii), folder / "throw.msh", folder / "throw.vtu", spec.name, key, opt)
    root = Path(cache_dir)
    final = root / key
    hit = load_cache_entry(final)
    if hit is not None:
        mesh, stats = hit
        return ThrowMesh(mesh, stats, dict(stats.fillet_radii), final / "throw.msh", final / "throw.vtu", spec.name, key, opt)
    root.mkdir(parents=True, exist_ok=True)
    clean_stale_cache_temps(root)
    tmp = Path(tempfile.mkdtemp(prefix=f".{key}{_TMP_MARK}{os.getpid()}-", dir=root))
    try:
        mesh, stats = _build(geometry, spec, opt, tmp)
        _save_npz(tmp / "mesh.npz", mesh)
        write_vtu(tmp / "throw.vtu", mesh)
        (tmp / "stats.json").write_text(json.dumps(_stats_to_json(stats), indent=1))
        (tmp / "complete").write_text(key)
        try:
            os.rename(tmp, final)
        except OSError:  # another process finished the same entry first: use theirs
            shutil.rmtree(tmp, ignore_errors=True)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return ThrowMesh(mesh, stats, dict(stats.fillet_radii), final / "throw.msh", final / "throw.vtu", spec.name, key, opt)
