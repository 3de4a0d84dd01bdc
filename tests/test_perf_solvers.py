"""Solver choice: without pypardiso the run says so and falls back to CHOLMOD (cholespy).

The missing package is real: ``sys.modules["pypardiso"] = None`` makes ``import pypardiso``
fail exactly as on a machine without it.  The fallback's solution is checked against a
dense solve (numpy LAPACK), an independent method, to 1e-10 relative (the system's
condition number is ~1e4, so round-off stays far below; a wrong triangle or a dropped
entry gives errors of order one).
"""

from __future__ import annotations

import logging
import sys

import numpy as np
import pytest
from skfem import Basis, ElementTetP2, MeshTet2

from fe_crank.errors import SolverError
from fe_crank.fe import solvers
from fe_crank.fe.assembly import assemble_stiffness

pytest.importorskip("cholespy")


@pytest.fixture(scope="module")
def system():
    """Curved P2 ball, clamped on a cap: a small SPD stiffness and a load."""
    ball = MeshTet2.init_ball(nrefs=1)
    b = Basis(ball, ElementTetP2(), intorder=2)
    K = assemble_stiffness(b, 210e9, 0.3).tocsr()
    fixed = (
        3 * b.get_dofs(ball.facets_satisfying(lambda p: p[2] < -0.5, boundaries_only=True)).all()[:, None]
        + np.arange(3)
    ).ravel()
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    f = np.random.default_rng(3).normal(size=(free.size, 3))
    return K[free][:, free], f


def test_without_pardiso_auto_falls_back_to_cholmod_and_says_so(system, monkeypatch, caplog):
    K, f = system
    monkeypatch.setitem(sys.modules, "pypardiso", None)
    monkeypatch.setattr(solvers, "_warned", set())
    assert not solvers.pardiso_available()
    with caplog.at_level(logging.WARNING, logger="fe_crank.fe.solvers"):
        fac = solvers.factorise(K, "auto")
    assert fac.method == "cholmod"
    assert "pypardiso (MKL PARDISO) is not installed" in fac.note
    assert "CHOLMOD" in fac.description and fac.note in fac.description
    assert any("not installed" in r.getMessage() for r in caplog.records)
    x = fac.solve(f)
    x_ref = np.linalg.solve(K.toarray(), f)
    assert np.abs(x - x_ref).max() < 1e-10 * np.abs(x_ref).max()
    # the warning is given once per process, the note every time
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="fe_crank.fe.solvers"):
        again = solvers.factorise(K, "auto")
    assert again.note == fac.note and not caplog.records


def test_pardiso_present_means_no_note(system):
    pytest.importorskip("pypardiso")
    fac = solvers.factorise(system[0], "auto")
    assert fac.method == "pardiso" and fac.note is None
    assert fac.description.startswith("MKL PARDISO")


def test_neither_direct_solver_falls_back_to_iterative_with_a_note(system, monkeypatch):
    monkeypatch.setitem(sys.modules, "pypardiso", None)
    monkeypatch.setitem(sys.modules, "cholespy", None)
    monkeypatch.setattr(solvers, "_warned", set())
    assert solvers.choose_method("auto", 10) == "superlu"
    assert solvers.choose_method("auto", 10**6) == "amg"
    assert "much slower" in solvers.fallback_note("auto", 10**6)
    assert solvers.fallback_note("superlu", 10**6) is None  # asked for: no fallback


def test_cholmod_refuses_an_indefinite_matrix():
    import scipy.sparse as sp

    K = sp.csr_matrix(np.array([[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]))
    with pytest.raises(SolverError, match="not positive definite"):
        solvers.factorise(K, "cholmod")


def test_free_releases_the_factor_and_refuses_a_later_solve(system):
    """The check frees the factor after the unit solves; what the report reads stays."""
    K, f = system
    fac = solvers.factorise(K, "auto")
    x = fac.solve(f)
    nnz, desc = fac.nnz, fac.description
    assert nnz == K.nnz
    fac.free()
    assert fac.nnz == nnz and fac.description == desc
    with pytest.raises(SolverError, match="released"):
        fac.solve(f)
    fac.free()  # twice is harmless
    assert np.all(np.isfinite(x))


def test_pardiso_out_of_core_writes_its_factor_to_disk_and_solves_as_in_core(system, tmp_path, monkeypatch):
    """MKL PARDISO out of core (iparm(60) = 1) with a 1-MB in-core budget: the factor of
    this system (~5 MB) must go to files in the run's own folder; the solution is checked
    against a dense LAPACK solve (an independent method) to 1e-10 relative, as the
    in-core methods are; the files go with ``free``."""
    pytest.importorskip("pypardiso")
    K, f = system
    monkeypatch.setenv("FE_CRANK_OOC_DIR", str(tmp_path))
    monkeypatch.setenv("MKL_PARDISO_OOC_MAX_CORE_SIZE", "1")
    monkeypatch.delenv("MKL_PARDISO_OOC_PATH", raising=False)
    fac = solvers.factorise(sp_triu(K), "pardiso_ooc", upper=True)
    folder = fac._ooc_dir
    assert folder.startswith(str(tmp_path)) and any(p.name.endswith(".bin") for p in tmp_path.rglob("*"))
    x = fac.solve(f)
    x_ref = np.linalg.solve(K.toarray(), f)
    assert np.abs(x - x_ref).max() < 1e-10 * np.abs(x_ref).max()
    assert fac.description.startswith("MKL PARDISO") and "out of core" in fac.description
    fac.free()
    assert not any(tmp_path.iterdir())


def test_auto_goes_out_of_core_only_above_the_threshold():
    pytest.importorskip("pypardiso")
    assert solvers.choose_method("auto", solvers.OOC_MIN_DOF) == "pardiso"  # medium (1.0-1.15M DOF)
    assert solvers.choose_method("auto", solvers.OOC_MIN_DOF + 1) == "pardiso_ooc"  # fine (2.9M DOF)


def sp_triu(K):
    import scipy.sparse as sp

    return sp.triu(K, format="csr")
