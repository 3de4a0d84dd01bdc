"""The check: load cases end to end and batches of them (the top of the package).

``options`` (``CheckOptions``), ``stages`` (the stages of one case, in order),
``verdict`` (the verdict, built once from every criterion), ``notes`` (the warnings
beside it), ``provenance`` (what produced a result), ``case`` (``run_case``: one case
and its report folder), ``batch`` (``run_cases``: local processes or Dask),
``publish`` (atomic publication of a case folder), ``discovery`` (load-case files and
their folder names), ``api`` (the Python API: ``fe_crank.run_check``,
``fe_crank.load_case``).  The record of a case is ``fe_crank.records.CaseResult``.
"""

from __future__ import annotations

from fe_crank.pipeline.batch import batch_exit_code, run_cases
from fe_crank.pipeline.case import run_case
from fe_crank.pipeline.discovery import find_loadcases, is_loadcase_file, unique_slugs
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.publish import case_slug, clean_stale_partials

__all__ = [
    "CheckOptions",
    "batch_exit_code",
    "case_slug",
    "clean_stale_partials",
    "find_loadcases",
    "is_loadcase_file",
    "run_case",
    "run_cases",
    "unique_slugs",
]
