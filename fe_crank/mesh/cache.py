"""Mesh cache: the key of an entry (SHA-256 of everything that changes the mesh) and
the entry's files (``mesh.npz``, ``stats.json``).

Entries are built in ``.<key>.partial-<pid>-*`` and renamed into place; the temporary
folders of killed processes are removed by the next writer, and an entry that cannot
be read back whole is discarded (``load_cache_entry``) to be rebuilt."""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import re
import shutil
from pathlib import Path

import numpy as np

from fe_crank.geometry.spec import CrankGeometry, ThrowSpec
from fe_crank.mesh.options import CACHE_FORMAT, GENERATE_OPTIONS, MeshOptions
from fe_crank.mesh.planes import mesh_planes
from fe_crank.mesh.types import MeshStats


def mesher_key() -> dict[str, object]:
    """What every mesh depends on beside its geometry and mesh options: the gmsh options
    it is generated with (``gmsh_io.SESSION_OPTIONS``, ``options.GENERATE_OPTIONS``, the
    straightening threshold), the versions of gmsh and of fe-crank and the cache format;
    part of every mesh cache key."""
    import gmsh

    from fe_crank.gmsh_io import SESSION_OPTIONS
    from fe_crank.mesh.quality import STRAIGHTEN_BELOW
    from fe_crank.version import __version__

    return {
        "gmsh_options": {**SESSION_OPTIONS, **GENERATE_OPTIONS, "straighten_below": STRAIGHTEN_BELOW},
        "fe_crank": __version__,
        "gmsh": gmsh.__version__,
        "format": CACHE_FORMAT,
    }


def cache_key(geometry: CrankGeometry, throw: ThrowSpec, options: MeshOptions) -> str:
    """SHA-256 (hex, 20 chars) of everything that changes the mesh: the geometry of the
    throw, the mesh options, the gmsh options the mesh is generated with
    (``gmsh_io.SESSION_OPTIONS``, ``options.GENERATE_OPTIONS``, the straightening
    threshold), the versions of gmsh and of fe-crank, and the cache format
    (``mesher_key``)."""
    geo = dataclasses.asdict(geometry)
    for k in ("name", "description", "source", "file", "throws", "shaft"):  # shaft: ends and bearings
        geo.pop(k, None)
    th = dataclasses.asdict(throw)
    th.pop("angle", None)  # the throw frame does not depend on the throw's angle
    th.pop("name", None)
    for cw in th["counterweights"]:
        cw.pop("bolted", None)  # bolt data do not change the solid
        if cw.get("offset") == 0.0:
            del cw["offset"]  # a counterweight opposite its pin keeps the key it had before offsets
    opts = dataclasses.asdict(options)
    if opts["web_divisions"] is None:  # the meshes made before the web control keep their keys
        del opts["web_divisions"]
    if opts["interface_sectors"] == 1:
        del opts["interface_sectors"]  # the key of every mesh without sectors stays as it was
    payload = {
        **mesher_key(),
        "geometry": geo,
        "throw": th,
        "options": opts,
        "planes": list(mesh_planes(geometry, throw)) if options.symmetric else [],
    }
    text = json.dumps(payload, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:20]


def save_npz(path: Path, mesh) -> None:
    """Write a mesh (nodes, elements, boundaries, subdomains) as the cache's npz file."""
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


def stats_to_json(s: MeshStats) -> dict:
    """The mesh statistics as the cache's JSON dictionary."""
    return dataclasses.asdict(s)


def _stats_from_json(d: dict) -> MeshStats:
    d = dict(d)
    d["from_cache"] = True
    d["symmetry"] = tuple(int(a) for a in d.get("symmetry", ()))
    return MeshStats(**d)


TMP_MARK = ".partial-"


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
