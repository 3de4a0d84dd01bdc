"""One load case end to end: ``run_case(path, out_dir, options) -> CaseResult``.

Reads top to bottom: the stages (``fe_crank.pipeline.stages.run_stages``: load -> dynamics
-> balance -> geometry -> mesh -> FE -> torsion -> assessment -> convergence), the
verdict (``fe_crank.pipeline.verdict.decide``, built once from every criterion), the notes
beside it (``fe_crank.pipeline.notes``), the provenance, the report.  Every stage is timed.
Any ``FeCrankError`` becomes a result with status ``"error"`` and its message; the batch
never crashes on one bad case.  The case folder is published atomically
(``fe_crank.pipeline.publish``).
"""

from __future__ import annotations

import json
import os
import shutil
import tempfile
import time
import traceback
from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

from fe_crank.errors import FeCrankError
from fe_crank.files import write_atomic
from fe_crank.mesh.plan import SIGN_OFF_RULE, preset_of
from fe_crank.notes import WARNING, Note
from fe_crank.pipeline.notes import case_notes
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.provenance import collect
from fe_crank.pipeline.publish import PARTIAL_MARK, case_slug, publish_folder
from fe_crank.pipeline.stages import Run, run_stages
from fe_crank.pipeline.verdict import Verdict, decide
from fe_crank.records import CaseResult, now_utc
from fe_crank.report import write_case_report
from fe_crank.report.html import write_error_report
from fe_crank.results import STATUS_ERROR


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
    run = Run(path, options, on_stage=on_stage)
    t0 = time.perf_counter()
    out_dir.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{slug}{PARTIAL_MARK}{os.getpid()}-", dir=out_dir))
    os.chmod(tmp, 0o755)
    error, trace = "", ""
    started = now_utc()
    try:
        try:
            run_stages(run)
        except FeCrankError as exc:
            error = str(exc)
        except Exception as exc:  # a bug: report it, keep the batch going
            error = f"internal error in the {run.stage or 'pipeline'} stage: {type(exc).__name__}: {exc}"
            trace = traceback.format_exc()
        out = run.out
        verdict = decide(out, error)
        lc = out.loadcase
        files = lc.inputs if lc is not None else tuple(run.files_read)
        preset = None if lc is None else preset_of(lc.mesh, options.mesh_size)
        prov = collect(path, out, files, preset, started=started)
        try:
            notes = case_notes(out, preset=preset, sign_off=prov.mesh.sign_off, rule=SIGN_OFF_RULE, solver=prov.solver)
        except FeCrankError as exc:  # a note that cannot be computed is itself a warning
            notes = (Note(f"quality checks incomplete: {exc}"),)
        partial = CaseResult(
            name=lc.name if lc is not None else path.stem,
            source=str(path),
            status=verdict.status,
            message=verdict.message,
            criteria=verdict.criteria,
            timings=tuple(run.timings),
            folder="",
            seconds=0.0,
            error_stage=run.stage if verdict.status == STATUS_ERROR else "",
            started=started,
            provenance=prov,
            warnings=tuple(n for n in notes if n.level == WARNING),
            planned_criteria=tuple(lim.key for lim in lc.criteria.limits) if lc is not None and lc.criteria else (),
        )
        try:
            run.timed("report", write_case_report, tmp, partial, out, notes, options=options, trace=trace)
        except FeCrankError as exc:
            partial = _as_error(partial, f"report: {exc}", "report")
            write_error_report(tmp, partial, "")
        except Exception as exc:
            partial = _as_error(partial, f"internal error in the report stage: {type(exc).__name__}: {exc}", "report")
            write_error_report(tmp, partial, traceback.format_exc())
        final = replace(
            partial, timings=tuple(run.timings), seconds=time.perf_counter() - t0, folder=str(out_dir / slug)
        )
        write_atomic(tmp / "case.json", json.dumps(final.to_dict(), indent=2, default=_json_default, allow_nan=False))
        publish_folder(tmp, out_dir / slug)
        return final
    finally:
        if tmp.exists():
            shutil.rmtree(tmp, ignore_errors=True)


def _as_error(r: CaseResult, message: str, stage: str) -> CaseResult:
    return replace(r, status=STATUS_ERROR, message=message, error_stage=stage)


def _json_default(o: object) -> object:
    import numpy as np

    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(f"not JSON serialisable: {type(o).__name__}")


__all__ = ["Verdict", "run_case"]
