"""The Python API in three calls, for notebooks and scripts.

    import fe_crank
    lc = fe_crank.load_case("loadcases/single_cylinder.toml")
    results = fe_crank.run_check("loadcases/", output="reports/", mesh_size="test")
    results[0].status, results[0].worst, results[0].folder

The same functions as ``fe-crank validate`` / ``fe-crank check``;
no process-wide state is changed (no logging configuration: the caller's applies).
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from fe_crank.io.loadcase import LoadCase, load_loadcase
from fe_crank.pipeline.batch import run_cases
from fe_crank.pipeline.discovery import find_loadcases
from fe_crank.pipeline.options import CheckOptions
from fe_crank.records import CaseResult
from fe_crank.report.junit import write_junit


def load_case(path: str | Path) -> LoadCase:
    """Read and validate one load-case file -> ``fe_crank.io.loadcase.LoadCase`` (SI inside).
    Raises ``fe_crank.errors.InputError`` naming the file, the key and the reason."""
    return load_loadcase(path)


def run_check(
    paths: str | Path | Iterable[str | Path],
    output: str | Path = "reports",
    *,
    mesh_size: str | None = None,
    cache_dir: str | Path = ".cache/meshes",
    jobs: int = 1,
    scheduler: object = None,
    render: bool = True,
    write_vtu: bool = True,
    junit: str | Path | None = None,
) -> list[CaseResult]:
    """Check load cases end to end, as ``fe-crank check`` does; returns one
    ``CaseResult`` per case (``.status`` "pass" | "fail" | "error", ``.criteria``,
    ``.worst``, ``.folder`` with report.html, results.json, the ``.vtu`` fields).

    ``paths``: a file, a folder (every ``*.toml`` with an ``[operating]`` table) or
    several; ``mesh_size`` overrides the load cases' ``[mesh] size``; ``junit`` also
    writes JUnit XML.  Bad cases become "error" results; a path that does not exist
    raises ``InputError``."""
    if isinstance(paths, (str, Path)):
        paths = [paths]
    files = find_loadcases(paths)
    opts = CheckOptions(mesh_size=mesh_size, cache_dir=str(cache_dir), render=render, write_vtu=write_vtu)
    results = run_cases(files, output, opts, jobs=jobs, scheduler=scheduler)
    if junit is not None:
        write_junit(junit, results)
    return results
