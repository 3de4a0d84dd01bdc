"""MKL PARDISO out of core (``[fe] solver = "pardiso_ooc"``, and ``auto`` above
``solver_choice.OOC_MIN_DOF`` unknowns): the factor is kept in files when it does not fit the
in-core budget.

MKL takes its out-of-core settings from environment variables only
(``MKL_PARDISO_OOC_PATH``, ``MKL_PARDISO_OOC_MAX_CORE_SIZE``, ``MKL_PARDISO_OOC_KEEP_FILE``;
Intel oneMKL reference, "PARDISO OOC"), so this is the one place where the package sets
process environment, and only when the out-of-core solver is chosen.
"""

from __future__ import annotations

import os
import tempfile

#: in-core budget of an out-of-core factorisation, share of the machine's memory
OOC_CORE_SHARE = 0.6


def out_of_core(solver) -> str:
    """Switch a PyPardisoSolver to MKL PARDISO's out-of-core mode; returns the folder of its
    factor files.

    MKL reads user iparm values only when iparm(1) = 1 (otherwise it fills in its
    defaults and ignores the rest), so the defaults of a real SPD matrix are stated
    (Intel oneMKL reference, ``pardiso`` iparm): iparm(2) = 2 nested dissection (METIS),
    iparm(10) = 8 pivot perturbation 1e-8 (unused without pivoting), iparm(18) = -1 report
    the factor's non-zeros, and iparm(60) = 1: in core when the factor fits
    ``MKL_PARDISO_OOC_MAX_CORE_SIZE`` MB, else out of core.  ``MKL_PARDISO_OOC_PATH`` is a
    prefix: it must end with a separator to put the files into the folder.
    """
    folder = tempfile.mkdtemp(prefix="fe-crank-pardiso-", dir=os.environ.get("FE_CRANK_OOC_DIR") or None)
    os.environ["MKL_PARDISO_OOC_PATH"] = os.path.join(folder, "")
    if "MKL_PARDISO_OOC_MAX_CORE_SIZE" not in os.environ:
        os.environ["MKL_PARDISO_OOC_MAX_CORE_SIZE"] = str(int(OOC_CORE_SHARE * _memory_bytes() / 2**20))
    os.environ.setdefault("MKL_PARDISO_OOC_KEEP_FILE", "0")  # files deleted when the factor is released
    solver.iparm[0] = 1
    solver.iparm[1] = 2
    solver.iparm[9] = 8
    solver.iparm[17] = -1
    solver.iparm[59] = 1
    return folder


def _memory_bytes() -> int:
    """Physical memory of the machine (bytes)."""
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
