"""The meshing steps every throw model shares (parametric and CAD): quadratic
tetrahedra from the current gmsh model, their checks and statistics, and the trip
through the mesh cache.

* :func:`generate`: Delaunay tetrahedra improved by gmsh's and Netgen's optimisers,
  refused when a linear tetrahedron is inverted (gmsh minSICN <= 0), raised to order 2,
  poorly curved ones made straight-sided (``fe_crank.mesh.quality.straighten_poor``);
* :func:`finish`: every named group present and non-empty, the quadratic map's Jacobian
  ratio, the statistics, and the fillet edge rule (``<= r / fillet_divisions`` on every
  fillet of ``fillet_radii`` for presets with at least 4 divisions: IACS UR M53 App. III);
* :func:`through_cache`: a ``ThrowMesh`` from the cache entry of ``key`` or built into a
  temporary folder and renamed into place (``fe_crank.mesh.cache``); without a cache, built
  in memory (no ``.msh``/``.vtu`` file).
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from fe_crank.errors import MeshError, environment_fault
from fe_crank.mesh.cache import TMP_MARK, clean_stale_cache_temps, load_cache_entry, save_npz, stats_to_json
from fe_crank.mesh.export import write_vtu
from fe_crank.mesh.options import GENERATE_OPTIONS, MeshOptions
from fe_crank.mesh.quality import STRAIGHTEN_BELOW, fillet_max_edge, jacobian_ratio, straighten_poor, tet_tags
from fe_crank.mesh.types import MeshStats, ThrowMesh


def generate(
    gmsh, throw_name: str, label: str, opt: MeshOptions, *, netgen: bool = True, straighten: float = STRAIGHTEN_BELOW
) -> tuple[float, int]:
    """Mesh the current model (its size fields set) with quadratic tetrahedra.

    Returns gmsh's smallest minSICN of the linear tetrahedra and the number of quadratic
    elements made straight-sided.  ``label`` names the model in messages.  ``netgen``
    False: gmsh's own optimiser only, without Netgen's (which is about four fifths of
    the 3D meshing's time; the checks below are the same).  ``straighten``: the quadratic
    elements of gmsh ``minSJ`` at or below it are made straight-sided (``straighten_poor``)."""
    for name, value in GENERATE_OPTIONS.items():
        gmsh.option.setNumber(name, value)
    if not netgen:
        gmsh.option.setNumber("Mesh.OptimizeNetgen", 0)
    try:
        gmsh.model.mesh.generate(3)
        tags = tet_tags(gmsh)
        if tags.size == 0:
            raise MeshError(f"gmsh produced no tetrahedra for throw {throw_name!r}")
        # gmsh can leave a volume without elements and raise nothing (seen on a hot-spot
        # zone's piece of a ball); the mesh would then lack that part of the solid
        empty = [t for _, t in gmsh.model.getEntities(3) if not len(gmsh.model.mesh.getElementTypes(3, t))]
        if empty:
            raise MeshError(f"gmsh left {len(empty)} volume(s) of throw {throw_name!r} without tetrahedra")
        q = np.asarray(gmsh.model.mesh.getElementQualities(tags, "minSICN"))
        min_quality = float(q.min())
        if min_quality <= 0.0:
            raise MeshError(
                f"{int(np.sum(q <= 0))} inverted linear tetrahedra (gmsh minSICN <= 0) in throw {throw_name!r}"
            )
        gmsh.model.mesh.setOrder(2)
        if opt.optimize_high_order:
            gmsh.option.setNumber("Mesh.HighOrderOptimize", 2)
            gmsh.model.mesh.optimize("HighOrder")
    except MeshError:
        raise
    except Exception as exc:  # gmsh raises bare Exception
        raise MeshError(f"gmsh could not mesh throw {throw_name!r} of {label!r}: {exc}") from None
    straightened = straighten_poor(gmsh, throw_name, straighten)
    return min_quality, straightened


def finish(
    mesh,
    expected: tuple[set[str], set[str]],
    fillet_radii: dict[str, float],
    opt: MeshOptions,
    *,
    min_quality: float,
    straightened: int,
    t0: float,
    planes: tuple[int, ...] = (),
) -> MeshStats:
    """Check the named groups (boundaries, subdomains in ``expected``) and the fillet
    edges, and return the statistics."""
    missing = [n for n in sorted(expected[0]) if n not in mesh.boundaries or mesh.boundaries[n].size == 0]
    missing += [n for n in sorted(expected[1]) if n not in mesh.subdomains or mesh.subdomains[n].size == 0]
    if missing:
        raise MeshError(f"named groups missing or empty after meshing: {missing}")
    ratio = jacobian_ratio(mesh)
    stats = MeshStats(
        nodes=int(mesh.doflocs.shape[1]),
        elements=int(mesh.nelements),
        p2_dofs=int(3 * mesh.doflocs.shape[1]),
        min_quality=min_quality,
        straightened=straightened,
        min_jacobian_ratio=ratio,
        fillet_max_edge=fillet_max_edge(mesh, fillet_radii),
        fillet_radii=dict(fillet_radii),
        build_seconds=time.perf_counter() - t0,
        symmetry=tuple(planes),
    )
    if opt.fillet_divisions >= 4.0:
        for name, h in stats.fillet_max_edge.items():
            r = fillet_radii[name]
            if h > r / opt.fillet_divisions * (1 + 1e-9):
                raise MeshError(
                    f"fillet {name!r}: largest element edge {h * 1e3:.3g} mm exceeds r/{opt.fillet_divisions:g} = {r / opt.fillet_divisions * 1e3:.3g} mm"
                )
    return stats


def _throw_mesh(mesh, stats: MeshStats, folder: Path | None, throw_name: str, key: str, opt: MeshOptions) -> ThrowMesh:
    return ThrowMesh(
        mesh,
        stats,
        dict(stats.fillet_radii),
        None if folder is None else folder / "throw.msh",
        None if folder is None else folder / "throw.vtu",
        throw_name,
        key,
        opt,
        stats.symmetry,
    )


def through_cache(
    key: str,
    cache_dir: str | Path | None,
    build: Callable[[Path | None], tuple[object, MeshStats]],
    throw_name: str,
    opt: MeshOptions,
    *,
    needs_folder: bool = False,
) -> ThrowMesh:
    """The cached mesh of ``key``, or ``build(folder)`` (which writes ``throw.msh`` into
    ``folder`` and returns the mesh and its statistics) cached under ``key``.

    ``cache_dir`` None: nothing is cached and no file is kept; ``build(None)`` writes no file
    (the ``ThrowMesh``'s ``msh_path`` and ``vtu_path`` are None), or with ``needs_folder``
    ``build`` gets a temporary folder, removed when it returns."""
    if cache_dir is None:
        if not needs_folder:
            mesh, stats = build(None)
            return _throw_mesh(mesh, stats, None, throw_name, key, opt)
        try:
            scratch = Path(tempfile.mkdtemp(prefix="fe-crank-mesh-"))
        except OSError as exc:
            raise environment_fault(exc, "creating a temporary mesh folder", tempfile.gettempdir()) from None
        try:
            mesh, stats = build(scratch)
        finally:
            shutil.rmtree(scratch, ignore_errors=True)
        return _throw_mesh(mesh, stats, None, throw_name, key, opt)
    root = Path(cache_dir)
    final = root / key
    hit = load_cache_entry(final)
    if hit is not None:
        mesh, stats = hit
        return _throw_mesh(mesh, stats, final, throw_name, key, opt)
    try:
        root.mkdir(parents=True, exist_ok=True)
        clean_stale_cache_temps(root)
        tmp = Path(tempfile.mkdtemp(prefix=f".{key}{TMP_MARK}{os.getpid()}-", dir=root))
    except OSError as exc:  # a full disk, a folder without write permission, a read-only file system
        raise environment_fault(exc, "creating the mesh cache", root) from None
    try:
        mesh, stats = build(tmp)
        save_npz(tmp / "mesh.npz", mesh)
        write_vtu(tmp / "throw.vtu", mesh)
        (tmp / "stats.json").write_text(json.dumps(stats_to_json(stats), indent=1))
        (tmp / "complete").write_text(key)
        try:
            os.rename(tmp, final)
        except OSError:  # another process finished the same entry first: use theirs
            shutil.rmtree(tmp, ignore_errors=True)
    except OSError as exc:
        shutil.rmtree(tmp, ignore_errors=True)
        raise environment_fault(exc, "writing the mesh cache", tmp) from None
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return _throw_mesh(mesh, stats, final, throw_name, key, opt)
