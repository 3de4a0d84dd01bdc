"""Build and mesh one throw with gmsh, through the cache: ``mesh_throw``."""

from __future__ import annotations

import atexit
import json
import os
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

from fe_crank.errors import MeshError
from fe_crank.geometry.spec import CrankGeometry, ThrowSpec
from fe_crank.mesh.cache import (
    TMP_MARK,
    _save_npz,
    _stats_to_json,
    cache_key,
    clean_stale_cache_temps,
    load_cache_entry,
)
from fe_crank.mesh.export import write_vtu
from fe_crank.mesh.interface import imprint_sectors
from fe_crank.mesh.mirror import mirror_all, swap_side
from fe_crank.mesh.msh import write_msh
from fe_crank.mesh.options import DEFAULT_CACHE_DIR, MeshOptions, resolve_options
from fe_crank.mesh.planes import mesh_planes
from fe_crank.mesh.quality import _fillet_max_edge, _jacobian_ratio, _straighten_poor, _tet_tags
from fe_crank.mesh.sizing import _set_size_fields
from fe_crank.mesh.types import MeshStats, ThrowMesh


def _build(geometry: CrankGeometry, spec: ThrowSpec, opt: MeshOptions, folder: Path, planes: tuple[int, ...] = ()):
    """Mesh the throw, or with ``planes`` its fundamental part, mirrored across them
    (``fe_crank.mesh.mirror``); the stats and ``throw.msh`` are of the whole mesh."""
    from fe_crank.geometry.throw import add_throw
    from fe_crank.gmsh_io import gmsh_session, model_to_skfem

    t0 = time.perf_counter()
    with gmsh_session() as gmsh:
        model = add_throw(geometry, spec, cut=planes)
        model = imprint_sectors(gmsh, model, opt.interface_sectors)
        _set_size_fields(gmsh, geometry, model.surfaces, model.fillet_radii, opt)
        gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
        gmsh.option.setNumber("Mesh.Optimize", 1)
        gmsh.option.setNumber(
            "Mesh.OptimizeNetgen", 1
        )  # removes most boundary slivers (single-cylinder throw, coarse: 3866 -> 98 elements with Jacobian ratio < 0.1)
        gmsh.option.setNumber("Mesh.ElementOrder", 1)
        try:
            gmsh.model.mesh.generate(3)
            tags = _tet_tags(gmsh)
            if tags.size == 0:
                raise MeshError(f"gmsh produced no tetrahedra for throw {spec.name!r}")
            q = np.asarray(gmsh.model.mesh.getElementQualities(tags, "minSICN"))
            min_quality = float(q.min())
            if min_quality <= 0.0:
                raise MeshError(
                    f"{int(np.sum(q <= 0))} inverted linear tetrahedra (gmsh minSICN <= 0) in throw {spec.name!r}"
                )
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
        if not planes:
            gmsh.write(str(folder / "throw.msh"))
    expected = (set(model.surfaces), set(model.volumes))
    if planes:
        mesh = mirror_all(mesh, planes)
        straightened *= 2 ** len(planes)  # each straightened element and its images
        if 2 in planes:
            expected = tuple(s | {swap_side(n) for n in s} for s in expected)
        write_msh(folder / "throw.msh", mesh)
    missing = [n for n in sorted(expected[0]) if n not in mesh.boundaries or mesh.boundaries[n].size == 0]
    missing += [n for n in sorted(expected[1]) if n not in mesh.subdomains or mesh.subdomains[n].size == 0]
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
        symmetry=tuple(planes),
    )
    if opt.fillet_divisions >= 4.0:
        for name, h in stats.fillet_max_edge.items():
            r = model.fillet_radii[name]
            if h > r / opt.fillet_divisions * (1 + 1e-9):
                raise MeshError(
                    f"fillet {name!r}: largest element edge {h * 1e3:.3g} mm exceeds r/{opt.fillet_divisions:g} = {r / opt.fillet_divisions * 1e3:.3g} mm"
                )
    return mesh, stats


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
    from fe_crank.geometry.estimate import check_element_budget

    check_geometry(geometry)
    spec = throw if isinstance(throw, ThrowSpec) else geometry.throw(throw)
    opt = resolve_options(size)
    check_element_budget(geometry, spec, opt, max_elements)
    key = cache_key(geometry, spec, opt)
    planes = mesh_planes(geometry, spec) if opt.symmetric else ()
    if cache_dir is None:
        folder = Path(tempfile.mkdtemp(prefix="fe-crank-mesh-"))
        atexit.register(shutil.rmtree, folder, True)  # no cache: the files live as long as the process
        mesh, stats = _build(geometry, spec, opt, folder, planes)
        write_vtu(folder / "throw.vtu", mesh)
        return ThrowMesh(
            mesh,
            stats,
            dict(stats.fillet_radii),
            folder / "throw.msh",
            folder / "throw.vtu",
            spec.name,
            key,
            opt,
            stats.symmetry,
        )
    root = Path(cache_dir)
    final = root / key
    hit = load_cache_entry(final)
    if hit is not None:
        mesh, stats = hit
        return ThrowMesh(
            mesh,
            stats,
            dict(stats.fillet_radii),
            final / "throw.msh",
            final / "throw.vtu",
            spec.name,
            key,
            opt,
            stats.symmetry,
        )
    root.mkdir(parents=True, exist_ok=True)
    clean_stale_cache_temps(root)
    tmp = Path(tempfile.mkdtemp(prefix=f".{key}{TMP_MARK}{os.getpid()}-", dir=root))
    try:
        mesh, stats = _build(geometry, spec, opt, tmp, planes)
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
    return ThrowMesh(
        mesh,
        stats,
        dict(stats.fillet_radii),
        final / "throw.msh",
        final / "throw.vtu",
        spec.name,
        key,
        opt,
        stats.symmetry,
    )
