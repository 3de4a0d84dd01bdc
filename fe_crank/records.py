"""The record of one checked load case: ``CaseResult`` and its ``Provenance``.

``CaseResult`` is what ``fe_crank.pipeline.case.run_case`` returns and the batch, the CLI's
summary, ``case.json`` and the JUnit XML read: the verdict, the criteria, the stage
timings, the warnings beside the verdict and what produced the result.  Frozen and
picklable (it travels back from worker processes).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from datetime import UTC, datetime
from typing import Any

from fe_crank.cad.features import CadFeatures
from fe_crank.cad.record import cad_record
from fe_crank.mesh.types import MeshStats
from fe_crank.notes import Note
from fe_crank.results import STATUS_ERROR, STATUS_FAIL, STATUS_PASS, CriterionResult, StageTime, Status

_EXIT = {STATUS_PASS: 0, STATUS_FAIL: 1, STATUS_ERROR: 2}


def now_utc() -> str:
    """The current time, ISO 8601 in UTC to the second (``2026-11-23T17:20:05+00:00``)."""
    return datetime.now(UTC).isoformat(timespec="seconds")


@dataclass(frozen=True)
class InputRecord:
    """One input file: its path relative to the load case's folder and its SHA-256."""

    path: str
    sha256: str


@dataclass(frozen=True)
class InputHash:
    """SHA-256 over the load case and every file it was read from, each hashed as
    ``<path relative to the load case's folder>\\0<bytes>`` in sorted order of the
    resolved paths; ``error``: why the inputs could not be hashed (None when they were)."""

    sha256: str | None
    files: tuple[InputRecord, ...]
    error: str | None = None


@dataclass(frozen=True)
class MeshRecord:
    """The mesh preset, whether it meets the sign-off rule, and per meshed model key the
    mesh statistics."""

    preset: str | None
    sign_off: bool
    sign_off_rule: str
    throws: dict[str, MeshStats] = field(default_factory=dict)


@dataclass(frozen=True)
class SolverRecord:
    """The linear solvers used, the one asked for, whether the fast direct solver (MKL
    PARDISO) was available, and the solves in words."""

    used: tuple[str, ...]
    requested: str
    fast_available: bool
    described: tuple[str, ...]


@dataclass(frozen=True)
class SupportRecord:
    """The support model of one FE model key."""

    throw: str
    support: str
    bearing_stiffness: float | None
    model: str


@dataclass(frozen=True)
class Provenance:
    """What produced a result: version, date, input hash, mesh, solver, support model;
    for a CAD geometry, the file (name, SHA-256, unit) and everything recognised in it."""

    version: str
    started: str
    python: str
    platform: str
    input: InputHash
    mesh: MeshRecord
    solver: SolverRecord | None = None
    support: tuple[SupportRecord, ...] = ()
    cad: CadFeatures | None = None

    def to_dict(self) -> dict[str, Any]:
        """The ``provenance`` record of results.json and case.json (docs/results.md)."""
        inputs: dict[str, Any] = {"sha256": self.input.sha256, "files": [asdict(f) for f in self.input.files]}
        if self.input.error is not None:
            inputs["error"] = self.input.error
        out = {
            "package": "fe-crank",
            "version": self.version,
            "started": self.started,
            "python": self.python,
            "platform": self.platform,
            "input": inputs,
            "mesh": {
                "preset": self.mesh.preset,
                "sign_off": self.mesh.sign_off,
                "sign_off_rule": self.mesh.sign_off_rule,
                "throws": {str(k): _plain(asdict(v)) for k, v in self.mesh.throws.items()},
            },
            "solver": None
            if self.solver is None
            else {
                "used": list(self.solver.used),
                "requested": self.solver.requested,
                "fast_available": self.solver.fast_available,
                "described": list(self.solver.described),
            },
            "support": [asdict(s) for s in self.support],
        }
        if self.cad is not None:
            out["cad"] = _plain(cad_record(self.cad))
        return out


def _plain(x: Any) -> Any:
    """numpy scalars and tuples of the statistics -> plain JSON values."""
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    if hasattr(x, "item"):
        return x.item()
    return x


@dataclass(frozen=True)
class CaseResult:
    """Outcome of one load case.  Frozen and picklable (plain data only)."""

    name: str
    source: str
    status: Status
    message: str = ""
    criteria: tuple[CriterionResult, ...] = ()
    timings: tuple[StageTime, ...] = ()
    folder: str = ""  # the finished case folder, "" when none could be written
    seconds: float = 0.0
    error_stage: str = ""
    started: str = ""  # ISO 8601 UTC
    provenance: Provenance | None = field(default=None, compare=False)
    warnings: tuple[Note, ...] = ()  # warnings shown beside the verdict (fe_crank.pipeline.notes)
    planned_criteria: tuple[str, ...] = ()  # the load case's criteria (listed as errored when the case errors)

    @property
    def exit_code(self) -> int:
        """0 pass, 1 a criterion failed, 2 an input or computation error."""
        return _EXIT[self.status]

    @property
    def worst(self) -> CriterionResult | None:
        """The criterion with the smallest margin (None without criteria)."""
        if not self.criteria:
            return None
        return min(self.criteria, key=lambda c: (c.margin, c.name))

    def to_dict(self) -> dict[str, Any]:
        """``case.json``: the record with its exit code and worst criterion."""
        d: dict[str, Any] = {
            "name": self.name,
            "source": self.source,
            "status": self.status,
            "message": self.message,
            "criteria": [_finite(_criterion(c)) for c in self.criteria],
            "timings": [asdict(t) for t in self.timings],
            "folder": self.folder,
            "seconds": self.seconds,
            "error_stage": self.error_stage,
            "started": self.started,
            "provenance": None if self.provenance is None else _finite(self.provenance.to_dict()),
            "warnings": [n.to_dict() for n in self.warnings],
            "planned_criteria": list(self.planned_criteria),
            "exit_code": self.exit_code,
        }
        w = self.worst
        d["worst"] = w.name if w else None
        return d


def _criterion(c: CriterionResult) -> dict[str, Any]:
    """A criterion of case.json: its verdict line's words (``location``), not the typed
    ``where`` and ``remarks`` they were made from."""
    d = asdict(c)
    d.pop("where")
    d.pop("remarks")
    for p in d["per_speed"]:
        p.pop("where")
    return d


def _finite(x: Any) -> Any:
    """Non-finite floats (an unloaded part's infinite safety) -> None, for strict JSON."""
    if isinstance(x, float):
        return x if math.isfinite(x) else None
    if isinstance(x, dict):
        return {k: _finite(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [_finite(v) for v in x]
    return x
