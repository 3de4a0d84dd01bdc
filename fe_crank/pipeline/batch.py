"""Batches of load cases: in this process, in local processes or on Dask.

``run_cases(paths, out_dir, options, jobs=..., scheduler=...)`` runs many cases in
this process, in local processes (``concurrent.futures`` with the ``spawn`` start
method) or on an existing Dask distributed cluster; the results are the same
whichever way they run (they are computed by the same ``run_case``).
"""

from __future__ import annotations

import hashlib
import logging
import os
import time
from collections.abc import Callable, Sequence
from concurrent.futures import Future
from dataclasses import asdict
from pathlib import Path
from typing import Any

from fe_crank.errors import InputError
from fe_crank.notes import verdict_remarks
from fe_crank.pipeline.case import run_case
from fe_crank.pipeline.discovery import unique_slugs
from fe_crank.pipeline.options import CheckOptions, assess_threads
from fe_crank.pipeline.publish import clean_stale_partials
from fe_crank.records import CaseResult
from fe_crank.results import STATUS_ERROR

log = logging.getLogger(__name__)


def _run_case_job(path: str, out_dir: str, options: CheckOptions, slug: str) -> CaseResult:
    """Top-level (picklable) job for process pools and Dask workers."""
    return run_case(path, out_dir, options, slug=slug)


def run_cases(
    paths: Sequence[str | Path],
    out_dir: str | Path,
    options: CheckOptions | None = None,
    *,
    jobs: int = 1,
    scheduler: str | object | None = None,
    on_result: Callable[[CaseResult], None] | None = None,
    on_stage: Callable[[str, str], None] | None = None,
) -> list[CaseResult]:
    """Run a batch; results in the order of ``paths``.

    ``jobs == 1`` and no scheduler: in this process (``on_stage`` reports each stage
    as it starts).  ``jobs > 1``: a ``ProcessPoolExecutor`` with the ``spawn`` start
    method (safe with gmsh, VTK and threaded BLAS).  ``scheduler``: the address of
    a running Dask distributed scheduler (or a ``distributed.Client``); each case is
    one task.  ``on_result`` is called in this process as each case finishes.
    """
    options = options or CheckOptions()
    # one mesh cache for every worker: a relative folder is resolved here, not in each
    # worker's own working directory (docs/usage.md)
    options = CheckOptions(**{**asdict(options), "cache_dir": str(Path(options.cache_dir).resolve())})
    files = [Path(p) for p in paths]
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    clean_stale_partials(out_dir)
    slugs = unique_slugs(files)
    results: list[CaseResult | None] = [None] * len(files)

    def done(i: int, r: CaseResult) -> None:
        results[i] = r
        w = r.worst
        remarks = verdict_remarks(r.warnings)
        log.log(
            logging.WARNING if r.status == STATUS_ERROR else logging.INFO,
            "%s: %s%s in %.1f s%s",
            slugs[i],
            r.status.upper(),
            f" (worst {w.name}, margin {100 * w.margin:+.1f} %)"
            if w
            else f": {r.message.splitlines()[0]}"
            if r.message
            else "",
            r.seconds,
            f" [{remarks}]" if remarks and r.status != STATUS_ERROR else "",
        )
        if on_result is not None:
            on_result(r)

    if scheduler is not None:
        # a Dask worker may run several cases at once on cores this process cannot see:
        # one assess thread per case unless the options say otherwise
        if options.assess_threads is None:
            options = CheckOptions(**{**asdict(options), "assess_threads": 1})
        _run_dask(files, slugs, out_dir, options, scheduler, done)
    elif jobs > 1 and len(files) > 1:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor, as_completed

        # the cases' processes share the cores: each case's assess stage takes its share
        options = CheckOptions(**{**asdict(options), "assess_threads": assess_threads(options, min(jobs, len(files)))})

        ctx = multiprocessing.get_context("spawn")
        with ProcessPoolExecutor(max_workers=min(jobs, len(files)), mp_context=ctx) as pool:
            futs = {
                pool.submit(_run_case_job, str(p), str(out_dir.resolve()), options, s): i
                for i, (p, s) in enumerate(zip(files, slugs))
            }
            for fut in as_completed(futs):
                i = futs[fut]
                done(i, _result_or_crash(fut, files[i]))
    else:
        for i, (p, s) in enumerate(zip(files, slugs)):
            done(i, run_case(p, out_dir, options, slug=s, on_stage=on_stage))
    return [r for r in results if r is not None]


def _result_or_crash(fut: Future[CaseResult], path: Path) -> CaseResult:
    """A worker that died (killed, out of memory) is an error result for its case."""
    try:
        return fut.result()
    except Exception as exc:
        return CaseResult(
            name=path.stem,
            source=str(path),
            status=STATUS_ERROR,
            message=f"the worker running this case stopped: {type(exc).__name__}: {exc}",
            error_stage="worker",
        )


def _run_dask(
    files: Sequence[Path],
    slugs: Sequence[str],
    out_dir: Path,
    options: CheckOptions,
    scheduler: Any,
    done: Callable[[int, CaseResult], None],
) -> None:
    try:
        from distributed import Client, as_completed
    except ModuleNotFoundError:  # pragma: no cover - distributed is a dependency
        raise InputError("--dask-scheduler needs the 'distributed' package") from None
    own = not hasattr(scheduler, "submit")
    try:
        client: Any = Client(scheduler, timeout="20s") if own else scheduler  # type: ignore[no-untyped-call]
    except OSError as exc:
        raise InputError(f"cannot connect to the Dask scheduler {scheduler!r}: {exc}") from None
    try:
        futs = {}
        for i, (p, s) in enumerate(zip(files, slugs)):
            f = client.submit(
                _run_case_job,
                os.path.abspath(p),
                str(out_dir.resolve()),
                options,
                s,
                key=f"fe-crank-{s}-{hashlib.sha1(os.path.abspath(p).encode()).hexdigest()[:8]}-{time.time_ns()}",
                pure=False,
            )
            futs[f] = i
        for fut in as_completed(list(futs)):  # type: ignore[no-untyped-call]
            i = futs[fut]
            done(i, _result_or_crash(fut, files[i]))
    finally:
        if own:
            client.close()


def batch_exit_code(results: Sequence[CaseResult]) -> int:
    """2 if any case errored, else 1 if any failed, else 0 (an empty batch is 2)."""
    if not results:
        return 2
    return max(r.exit_code for r in results)
