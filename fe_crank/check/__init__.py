"""The check: load cases end to end and batches of them (the top of the package).

``options`` (``CheckOptions``), ``stages`` (the computational stages of one case),
``case`` (``run_case``: one case and its report folder), ``batch`` (``run_cases``:
local processes or Dask), ``publish`` (atomic publication of a case folder),
``discovery`` (load-case files and their folder names).  Result types are in
``fe_crank.results``, the atomic writer in ``fe_crank.files``.

The package is also callable: ``fe_crank.check(paths, output=..., mesh_size=...)`` is
``fe_crank.check.api.check`` (the top-level Python API, with ``load_case``).
"""

from __future__ import annotations

import sys
import types

from fe_crank.check import api
from fe_crank.check.batch import batch_exit_code, run_cases
from fe_crank.check.case import run_case
from fe_crank.check.discovery import find_loadcases, is_loadcase_file, unique_slugs
from fe_crank.check.options import STAGES, CheckOptions
from fe_crank.check.publish import case_slug, clean_stale_partials
from fe_crank.check.stages import throw_keys


class _CallablePackage(types.ModuleType):
    """``fe_crank.check(...)`` runs ``fe_crank.check.api.check``; the package stays a package."""

    def __call__(self, *args, **kwargs):
        return api.check(*args, **kwargs)


sys.modules[__name__].__class__ = _CallablePackage

__all__ = [
    "STAGES",
    "CheckOptions",
    "batch_exit_code",
    "case_slug",
    "clean_stale_partials",
    "find_loadcases",
    "is_loadcase_file",
    "run_case",
    "run_cases",
    "throw_keys",
    "unique_slugs",
]
