"""What produced a result (``fe_crank.records.Provenance``), from the stages' outputs.

* ``input``: SHA-256 over the load-case file and every file it was read from (the files
  ``fe_crank.io`` opened: engine, geometry, pressure tables; ``LoadCase.inputs``, or the
  files read before a load case was refused), each hashed as ``<path relative to the
  load case's folder>\\0<bytes>`` in sorted order of the resolved paths; ``files`` lists
  them with their own hashes (taken when they were read; a file changed since is said so).
* ``mesh``: the preset and whether it meets the sign-off rule (``coarse`` or finer:
  fillet elements <= r/4, IACS UR M53 Appendix III guidance on fillet resolution), and
  per meshed model the mesh statistics.
* ``solver``: the linear solver used and whether the fast direct solver (MKL PARDISO
  through pypardiso) was available; ``support``: each FE model's support model.
* ``cad``: for a CAD geometry, the file (name, SHA-256, format, unit) and every feature
  recognised in it (``fe_crank.cad.record.cad_record``); the file itself is among the
  ``input`` files.
"""

from __future__ import annotations

import hashlib
import os
import platform
from functools import partial
from pathlib import Path

from fe_crank.fe.linalg.choice import pardiso_available
from fe_crank.io.base import InputFile
from fe_crank.mesh.plan import SIGN_OFF_RULE
from fe_crank.outputs import CaseOutputs
from fe_crank.records import InputHash, InputRecord, MeshRecord, Provenance, SolverRecord, SupportRecord
from fe_crank.version import __version__


def _rel(p: Path, base: Path) -> str:
    try:
        return p.relative_to(base).as_posix()
    except ValueError:
        return Path(os.path.relpath(p, base)).as_posix()


def _resolved(p: str | Path) -> Path:
    """``Path.resolve`` that survives a symbolic-link loop (then the absolute path)."""
    try:
        return Path(p).resolve()
    except (OSError, RuntimeError):
        return Path(os.path.abspath(p))


def input_hash(path: str | Path, files: tuple[InputFile, ...] | list[InputFile]) -> InputHash:
    """The ``input`` record of the files a load case was read from (module docstring)."""
    base = _resolved(path).parent
    total = hashlib.sha256()
    records: list[InputRecord] = []
    try:
        for f in sorted(files, key=lambda f: f.path):
            rel = _rel(f.path, base)
            total.update(rel.encode() + b"\0")
            one = hashlib.sha256()
            with f.path.open("rb") as fh:  # in blocks: an input of any size is hashed in bounded memory
                for block in iter(partial(fh.read, 1 << 20), b""):
                    total.update(block)
                    one.update(block)
            if one.hexdigest() != f.sha256:
                return InputHash(None, tuple(records), f"{rel} changed while the case was checked")
            records.append(InputRecord(rel, f.sha256))
    except OSError as exc:
        return InputHash(None, tuple(records), exc.strerror or str(exc))
    return InputHash(total.hexdigest(), tuple(records))


def collect(
    path: str | Path,
    out: CaseOutputs,
    files: tuple[InputFile, ...] | list[InputFile],
    preset: str | None,
    *,
    started: str,
) -> Provenance:
    """The provenance of one case; ``files``: the input files read (``LoadCase.inputs``
    or, when the load case was refused, those read before); ``preset``: the mesh preset
    the case was (or would have been) meshed with, None before the load case was read."""
    meshes = out.meshes.throws if out.meshes is not None else {}
    unit_solutions = out.unit_solutions
    solver = None
    if unit_solutions:
        solver = SolverRecord(
            used=tuple(sorted({u.solver for u in unit_solutions.values()})),
            requested=out.loadcase.fe.solver if out.loadcase is not None else "auto",
            fast_available=bool(pardiso_available()),
            described=tuple(sorted({u.solver_description for u in unit_solutions.values()})),
        )
    support = tuple(
        SupportRecord(str(key), u.options.support, u.bearing_stiffness, u.support_model)
        for key, u in unit_solutions.items()
    )
    return Provenance(
        version=__version__,
        started=started,
        python=platform.python_version(),
        platform=platform.platform(terse=True),
        input=input_hash(path, files),
        mesh=MeshRecord(
            preset=preset,
            sign_off=out.geometry.plan.sign_off if out.geometry is not None else _sign_off(preset),
            sign_off_rule=SIGN_OFF_RULE,
            throws={str(k): m.stats for k, m in meshes.items()},
        ),
        solver=solver,
        support=support,
        cad=out.geometry.cad if out.geometry is not None else None,
    )


def _sign_off(preset: str | None) -> bool:
    from fe_crank.mesh.plan import SIGN_OFF_PRESETS

    return preset in SIGN_OFF_PRESETS if preset else False
