"""What produced a result: package version, input hash, mesh, solver, support, date.

``collect(path, stage_out, options, started=...)`` gives a plain dict written into
results.json (``provenance``), case.json, the report header and the JUnit properties,
so a result can be traced to its inputs without git:

* ``input.sha256``: SHA-256 over the load-case file and every file it refers to (a
  string value naming an existing ``.toml``/``.csv`` file relative to the referring
  file, followed recursively: engine, geometry, pressure tables), each file hashed as
  ``<path relative to the load case's folder>\\0<bytes>`` in sorted order; ``input.files``
  lists them with their own hashes.
* ``mesh``: the preset and whether it meets the sign-off rule (``coarse`` or finer:
  fillet elements <= r/4, IACS UR M53 Appendix (FE) guidance on fillet resolution),
  and per meshed throw the statistics of ``fe_crank.mesh.MeshStats``.
* ``solver``: the linear solver used and whether the fast direct solver (MKL PARDISO
  through pypardiso) was available.
"""

from __future__ import annotations

import hashlib
import os
import platform
from dataclasses import asdict, is_dataclass
from datetime import UTC, datetime
from pathlib import Path

from fe_crank.errors import InputError
from fe_crank.io.base import read_toml
from fe_crank.version import __version__

#: mesh presets whose verdicts may be signed off (fillet elements <= r/4)
SIGN_OFF_PRESETS = ("coarse", "medium", "fine")


def now_utc() -> str:
    """The current time, ISO 8601 in UTC to the second (``2026-11-23T17:20:05+00:00``)."""
    return datetime.now(UTC).isoformat(timespec="seconds")


def _references(path: Path, data) -> list[Path]:
    out = []
    if isinstance(data, dict):
        for v in data.values():
            out += _references(path, v)
    elif isinstance(data, list):
        for v in data:
            out += _references(path, v)
    elif isinstance(data, str) and data.lower().endswith((".toml", ".csv")) and "\n" not in data:
        p = path.parent / data
        if p.is_file():
            out.append(p)
    return out


def _resolved(p: str | Path) -> Path:
    """``Path.resolve`` that survives a symbolic-link loop (then the absolute path)."""
    try:
        return Path(p).resolve()
    except (OSError, RuntimeError):
        return Path(os.path.abspath(p))


def input_files(path: str | Path) -> list[Path]:
    """The load case and every file it refers to, recursively (resolved, sorted)."""
    todo, seen = [_resolved(path)], set()
    while todo:
        p = todo.pop()
        if p in seen or not p.is_file():
            continue
        seen.add(p)
        if p.suffix == ".toml":
            try:  # the bounded reader: size, nesting and encoding limits of the load stage
                todo += [_resolved(q) for q in _references(p, read_toml(p))]
            except (InputError, OSError, RecursionError):
                pass  # the load stage reports it; the bytes are still hashed
    return sorted(seen)


def _rel(p: Path, base: Path) -> str:
    try:
        return p.relative_to(base).as_posix()
    except ValueError:
        return Path(os.path.relpath(p, base)).as_posix()


def input_hash(path: str | Path) -> dict:
    """``{"sha256": ..., "files": [{"path", "sha256"}]}`` of ``input_files(path)``."""
    base = _resolved(path).parent
    total = hashlib.sha256()
    files = []
    for p in input_files(path):
        rel = _rel(p, base)
        total.update(rel.encode() + b"\0")
        one = hashlib.sha256()
        with p.open("rb") as fh:  # in blocks: an input of any size is hashed in bounded memory
            for block in iter(lambda: fh.read(1 << 20), b""):
                total.update(block)
                one.update(block)
        files.append({"path": rel, "sha256": one.hexdigest()})
    return {"sha256": total.hexdigest(), "files": files}


def _plain(x):
    if is_dataclass(x):
        x = asdict(x)
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    if hasattr(x, "item"):
        return x.item()
    return x


def mesh_preset(stage_out: dict, options) -> str | None:
    """The preset the case was (or would have been) meshed with: ``--mesh-size``, else
    the load case's ``[mesh] size``, else "coarse"; None before the load case was read."""
    if getattr(options, "mesh_size", None):
        return options.mesh_size
    lc = stage_out.get("loadcase")
    if lc is None:
        return None
    section = (getattr(lc, "extras", None) or {}).get("mesh")
    return getattr(section, "size", None) or "coarse"


def solver_info(stage_out: dict) -> dict:
    from fe_crank.fe.solvers import pardiso_available

    used = sorted({u.solver for u in (stage_out.get("units") or {}).values()})
    lc = stage_out.get("loadcase")
    requested = getattr(getattr(lc, "fe", None), "solver", None) or "auto"
    described = sorted({getattr(u, "solver_description", u.solver) for u in (stage_out.get("units") or {}).values()})
    return {
        "used": used,
        "requested": requested,
        "fast_available": bool(pardiso_available()),
        "described": described,
    }  # in words: fallback notes, "solved on 4 symmetry components ..."


def support_info(stage_out: dict) -> list[dict]:
    out = []
    for key, u in (stage_out.get("units") or {}).items():
        opts = getattr(u, "options", None)
        out.append(
            {
                "throw": key,
                "support": getattr(opts, "support", None),
                "bearing_stiffness": getattr(u, "bearing_stiffness", None),
                "model": getattr(u, "support_model", None),
            }
        )
    return out


def collect(path: str | Path, stage_out: dict, options, *, started: str) -> dict:
    """The provenance record of one case (plain JSON data)."""
    preset = mesh_preset(stage_out, options)
    meshes = {key: _plain(getattr(m, "stats", None)) for key, m in (stage_out.get("meshes") or {}).items()}
    try:
        inputs = input_hash(path)
    except OSError as exc:
        inputs = {"sha256": None, "files": [], "error": exc.strerror or str(exc)}
    return {
        "package": "fe-crank",
        "version": __version__,
        "started": started,
        "python": platform.python_version(),
        "platform": platform.platform(terse=True),
        "input": inputs,
        "mesh": {
            "preset": preset,
            "sign_off": preset in SIGN_OFF_PRESETS if preset else False,
            "sign_off_rule": "coarse or finer, fillet elements <= r/4",
            "throws": meshes,
        },
        "solver": solver_info(stage_out) if stage_out.get("units") else None,
        "support": support_info(stage_out),
    }
