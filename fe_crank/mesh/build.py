"""Build and mesh one throw with gmsh, through the cache: ``mesh_throw``."""

from __future__ import annotations

import time
from pathlib import Path

from fe_crank.geometry.spec import CrankGeometry, ThrowSpec
from fe_crank.mesh.cache import cache_key
from fe_crank.mesh.generate import finish, generate, through_cache
from fe_crank.mesh.interface import imprint_sectors
from fe_crank.mesh.mirror import mirror_all, swap_side
from fe_crank.mesh.msh import write_model, write_msh
from fe_crank.mesh.options import DEFAULT_CACHE_DIR, MeshOptions, resolve_options
from fe_crank.mesh.planes import mesh_planes
from fe_crank.mesh.sizing import set_size_fields
from fe_crank.mesh.types import ThrowMesh


def _build(
    geometry: CrankGeometry, spec: ThrowSpec, opt: MeshOptions, folder: Path | None, planes: tuple[int, ...] = ()
):
    """Mesh the throw, or with ``planes`` its fundamental part, mirrored across them
    (``fe_crank.mesh.mirror``); the stats and ``throw.msh`` (in ``folder``; None: no file)
    are of the whole mesh."""
    from fe_crank.geometry.throw import add_throw
    from fe_crank.gmsh_io import gmsh_session, model_to_skfem

    t0 = time.perf_counter()
    with gmsh_session() as gmsh:
        model = add_throw(geometry, spec, cut=planes)
        model = imprint_sectors(gmsh, model, opt.interface_sectors)
        set_size_fields(gmsh, geometry, model.surfaces, model.fillet_radii, opt, model.volumes)
        min_quality, straightened = generate(gmsh, spec.name, geometry.name, opt)
        mesh = model_to_skfem()
        if not planes and folder is not None:
            write_model(gmsh, folder / "throw.msh")
    surfaces, volumes = set(model.surfaces), set(model.volumes)
    if planes:
        mesh = mirror_all(mesh, planes)
        straightened *= 2 ** len(planes)  # each straightened element and its images
        if 2 in planes:
            surfaces |= {swap_side(n) for n in surfaces}
            volumes |= {swap_side(n) for n in volumes}
        if folder is not None:
            write_msh(folder / "throw.msh", mesh)
    stats = finish(
        mesh,
        (surfaces, volumes),
        model.fillet_radii,
        opt,
        min_quality=min_quality,
        straightened=straightened,
        t0=t0,
        planes=planes,
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
        Folder of the mesh cache; ``None`` meshes without caching and writes no file
        (``.msh_path`` and ``.vtu_path`` are then None).

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
    return through_cache(key, cache_dir, lambda folder: _build(geometry, spec, opt, folder, planes), spec.name, opt)
