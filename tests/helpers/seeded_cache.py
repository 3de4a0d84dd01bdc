"""A test's own mesh cache holding one entry of the run's (``helpers.shared``): for a test
that damages or inspects its cache, its first mesh read from the run's instead of built
again (the entry's files copied whole: an entry is a function of its key alone,
``fe_crank.mesh.cache``)."""

from __future__ import annotations

import shutil
from pathlib import Path

from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh import mesh_throw


def seed(dest: Path, mesh_cache: Path, geometry: CrankGeometry, size: str = "test") -> str:
    """Copy the run's cache entry of ``geometry``'s throw at ``size`` (built there when
    missing) into the cache folder ``dest``; its key."""
    tm = mesh_throw(geometry, size=size, cache_dir=mesh_cache)
    dest.mkdir(parents=True, exist_ok=True)
    shutil.copytree(Path(mesh_cache) / tm.key, dest / tm.key)
    return tm.key
