"""One load case end to end: ``run_case(path, out_dir, options) -> CaseResult``.

Reads top to bottom: load case -> dynamics -> balance -> mesh (cached) -> FE unit
cases -> cycle assessment -> verdict -> report.  Every stage is timed.  Any
``FeCrankError`` becomes a result with status ``"error"`` and its message; the
batch never crashes on one bad case.  The case folder is published atomically
(``fe_crank.check.publish``).
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
import time
import traceback
from collections.abc import Callable
from pathlib import Path

from fe_crank.check.options import CheckOptions
from fe_crank.check.publish import PARTIAL_MARK, _publish, case_slug
from fe_crank.check.stages import _compute, _criteria_of, _Run
from fe_crank.errors import FeCrankError
from fe_crank.fe import convergence
from fe_crank.files import write_atomic
from fe_crank.notes import Note
from fe_crank.provenance import collect, now_utc
from fe_crank.report import write_case_report
from fe_crank.report.html import write_error_report
from fe_crank.report.quality import case_notes
from fe_crank.results import STATUS_ERROR, STATUS_FAIL, STATUS_PASS, CaseResult


def _refuse_nan(criteria) -> None:
    """A NaN in a criterion is an error of the case, never a verdict or a JSON value
    (an infinite safety factor of an unloaded part is legitimate and is kept)."""
    for c in criteria:
        if any(x != x for x in (c.value, c.limit, c.margin)):
            raise FeCrankError(f"criterion {c.name}: the computation gave NaN (not a number); the case is not assessed")


def run_case(
    path: str | Path,
    out_dir: str | Path,
    options: CheckOptions | None = None,
    *,
    slug: str | None = None,
    on_stage: Callable[[str, str], None] | None = None,
) -> CaseResult:
    """Check one load case and write its report folder ``out_dir/<slug>``.

    Returns a ``CaseResult``; never raises for a bad case: a ``FeCrankError`` (bad
    input, failed mesh or solve, missing stage) gives status ``"error"`` with its
    message, any other exception (a bug) gives status ``"error"`` with the
    exception type and the traceback saved in ``error.txt``.
    """
    options = options or CheckOptions()
    path = Path(path)
    out_dir = Path(out_dir)
    slug = slug or case_slug(path)
    run = _Run(path, on_stage=on_stage)
    t0 = time.perf_counter()
    out_dir.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{slug}{PARTIAL_MARK}{os.getpid()}-", dir=out_dir))
    os.chmod(tmp, 0o755)
    name, status, message, criteria, trace, stage_out = path.stem, STATUS_ERROR, "", (), "", {}
    started = now_utc()
    try:
        try:
            _compute(run, options, stage_out)
            name = stage_out["loadcase"].name
            criteria = _criteria_of(stage_out["assessment"])
            _refuse_nan(criteria)
            if stage_out.get("mesh_convergence"):
                criteria += (convergence.criterion(stage_out["mesh_convergence"]),)
            status = STATUS_PASS if all(c.passed for c in criteria) else STATUS_FAIL
            if not criteria:
                status, message = STATUS_ERROR, "the assessment returned no criteria: nothing was checked"
        except FeCrankError as exc:
            message = str(exc)
        except Exception as exc:  # a bug: report it, keep the batch going
            message = f"internal error in the {run.stage or 'pipeline'} stage: {type(exc).__name__}: {exc}"
            trace = traceback.format_exc()
        error_stage = run.stage if status == STATUS_ERROR else ""
        if "loadcase" in stage_out:
            name = stage_out["loadcase"].name
        prov, notes, planned = _provenance(path, stage_out, options, started)
        partial = CaseResult(
            name=name,
            source=str(path),
            status=status,
            message=message,
            criteria=criteria,
            timings=tuple(run.timings),
            folder="",
            seconds=0.0,
            error_stage=error_stage,
            started=started,
            provenance=prov,
            warnings=notes,
            planned_criteria=planned,
        )
        try:
            run.timed("report", _write_report, tmp, partial, stage_out, options, trace)
        except FeCrankError as exc:
            partial = _as_error(partial, f"report: {exc}", "report")
            _write_minimal(tmp, partial, "")
        except Exception as exc:
            partial = _as_error(partial, f"internal error in the report stage: {type(exc).__name__}: {exc}", "report")
            _write_minimal(tmp, partial, traceback.format_exc())
        final = CaseResult(
            **{
                **_fields(partial),
                "timings": tuple(run.timings),
                "seconds": time.perf_counter() - t0,
                "folder": str(out_dir / slug),
            }
        )
        write_atomic(tmp / "case.json", json.dumps(final.to_dict(), indent=2, default=_json_default, allow_nan=False))
        _publish(tmp, out_dir / slug)
        return final
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)


def _provenance(path: Path, stage_out: dict, options, started: str):
    """(provenance, warning texts, planned criterion names) of a case; the notes are
    kept in ``stage_out["notes"]`` for the report.  Never fails the case."""
    prov = collect(path, stage_out, options, started=started)
    try:
        stage_out["notes"] = case_notes(stage_out, prov)
    except FeCrankError as exc:  # a note that cannot be computed is itself a warning
        stage_out["notes"] = [Note(f"quality checks incomplete: {exc}")]
    lc = stage_out.get("loadcase")
    planned = tuple(lim.key for lim in getattr(getattr(lc, "criteria", None), "limits", ()) or ())
    return prov, tuple(n.text for n in stage_out["notes"] if n.level == "warning"), planned


def _fields(r: CaseResult) -> dict:
    return {f: getattr(r, f) for f in r.__dataclass_fields__}


def _as_error(r: CaseResult, message: str, stage: str) -> CaseResult:
    return CaseResult(**{**_fields(r), "status": STATUS_ERROR, "message": message, "error_stage": stage})


def _json_default(o):
    import numpy as np

    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


def _write_minimal(folder: Path, result: CaseResult, trace: str) -> None:
    write_error_report(folder, result, trace)


def _write_report(folder: Path, result: CaseResult, stage_out: dict, options: CheckOptions, trace: str) -> None:
    write_case_report(folder, result, stage_out, options=options, trace=trace)
