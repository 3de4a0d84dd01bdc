"""The FE stage's linear solvers (``fe.linalg.factorise``): which solver runs, and the memory of
its factor.

Solver choice: without pypardiso the run says so and falls back to CHOLMOD (cholespy).
The missing package is real: ``sys.modules["pypardiso"] = None`` makes ``import pypardiso``
fail exactly as on a machine without it.  The fallback's solution is checked against a
dense solve (numpy LAPACK), an independent method, to 1e-10 relative (the system's
condition number is ~1e4, so round-off stays far below; a wrong triangle or a dropped
entry gives errors of order one).

A PARDISO factor lives in MKL's own memory, outside Python's; it must be released when
its Factorisation is dropped, or a process that solves several models (a batch of load
cases, the convergence study, the test suite) keeps every factor.  Measured by the
resident memory (/proc/self/statm) of a fresh Python process (so that memory freed
earlier in this one cannot be reused and hide the growth) around factorisations of a 3D
7-point Laplacian (SPD, 27 000 unknowns, a factor of tens of MB with nested dissection):
the growth after several factorise-and-drop cycles must stay below half of one live
factor's footprint; keeping every factor grows by one footprint per cycle (4 cycles:
about 4 footprints).
"""

from __future__ import annotations

import importlib.util
import json
import logging
import subprocess
import sys

import numpy as np
import pytest
from skfem import Basis, ElementTetP2, MeshTet2

from fe_crank.errors import SolverError
from fe_crank.fe.core.assembly import assemble_stiffness
from fe_crank.fe.linalg import choice as solver_choice
from fe_crank.fe.linalg import factorise as linalg

needs_cholmod = pytest.mark.skipif(importlib.util.find_spec("cholespy") is None, reason="cholespy not installed")
needs_pardiso = pytest.mark.skipif(importlib.util.find_spec("pypardiso") is None, reason="pypardiso not installed")


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


@needs_cholmod
def test_without_pardiso_auto_falls_back_to_cholmod_and_says_so(system, monkeypatch, caplog):
    K, f = system
    monkeypatch.setitem(sys.modules, "pypardiso", None)
    monkeypatch.setattr(linalg, "_warned", set())
    assert not solver_choice.pardiso_available()
    with caplog.at_level(logging.WARNING, logger="fe_crank.fe.linalg.factorise"):
        fac = linalg.factorise(K, "auto")
    assert fac.method == "cholmod"
    assert "pypardiso (MKL PARDISO) is not installed" in fac.note
    assert "CHOLMOD" in fac.description and fac.note in fac.description
    assert any("not installed" in r.getMessage() for r in caplog.records)
    x = fac.solve(f)
    x_ref = np.linalg.solve(K.toarray(), f)
    assert np.abs(x - x_ref).max() < 1e-10 * np.abs(x_ref).max()
    # the warning is given once per process, the note every time
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="fe_crank.fe.linalg.factorise"):
        again = linalg.factorise(K, "auto")
    assert again.note == fac.note and not caplog.records


def test_pardiso_present_means_no_note(system):
    pytest.importorskip("pypardiso")
    fac = linalg.factorise(system[0], "auto")
    assert fac.method == "pardiso" and fac.note is None
    assert fac.description.startswith("MKL PARDISO")


def test_neither_direct_solver_falls_back_to_iterative_with_a_note(system, monkeypatch):
    monkeypatch.setitem(sys.modules, "pypardiso", None)
    monkeypatch.setitem(sys.modules, "cholespy", None)
    monkeypatch.setattr(linalg, "_warned", set())
    assert solver_choice.choose_method("auto", 10) == "superlu"
    assert solver_choice.choose_method("auto", 10**6) == "amg"
    assert "much slower" in solver_choice.fallback_note("auto", 10**6)
    assert solver_choice.fallback_note("superlu", 10**6) is None  # asked for: no fallback


@needs_cholmod
def test_cholmod_refuses_an_indefinite_matrix():
    import scipy.sparse as sp

    K = sp.csr_matrix(np.array([[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]))
    with pytest.raises(SolverError, match="not positive definite"):
        linalg.factorise(K, "cholmod")


@needs_cholmod
def test_free_releases_the_factor_and_refuses_a_later_solve(system):
    """The check frees the factor after the unit solves; what the report reads stays."""
    K, f = system
    fac = linalg.factorise(K, "auto")
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
    fac = linalg.factorise(sp_triu(K), "pardiso_ooc", upper=True)
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
    assert solver_choice.choose_method("auto", solver_choice.OOC_MIN_DOF) == "pardiso"  # medium (1.0-1.15M DOF)
    assert solver_choice.choose_method("auto", solver_choice.OOC_MIN_DOF + 1) == "pardiso_ooc"  # fine (2.9M DOF)


def sp_triu(K):
    import scipy.sparse as sp

    return sp.triu(K, format="csr")


_SCRIPT = r"""
import gc, json, sys
import numpy as np
import scipy.sparse as sp
from fe_crank.fe.linalg.factorise import factorise, factorise_shared

def rss():
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * 4096.0

def laplacian(n, shift=0.0):
    one = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1])
    eye = sp.identity(n)
    K = sp.kron(sp.kron(one, eye), eye) + sp.kron(sp.kron(eye, one), eye) + sp.kron(sp.kron(eye, eye), one)
    return (K + shift * sp.identity(n ** 3)).tocsr()

K1, K2 = laplacian(30), laplacian(30, shift=0.5)        # one sparsity pattern, two factors
b = np.ones(K1.shape[0])

def single():
    fac = factorise(K1, "pardiso")
    assert np.allclose(K1 @ fac.solve(b), b)
    return fac

def shared():
    U1, U2 = sp.triu(K1, format="csr"), sp.triu(K2, format="csr")
    U1.sort_indices(); U2.sort_indices()
    facs = factorise_shared([U1, U2])
    assert np.allclose(K2 @ facs[1].solve(b), b)
    return facs

make = {"single": single, "shared": shared}[sys.argv[1]]
warm = make(); del warm; gc.collect()                    # MKL loaded, its thread buffers made
base = rss()
live = make()
footprint = rss() - base
del live
for _ in range(3):
    f = make(); del f
gc.collect()
print(json.dumps({"footprint": footprint, "growth": rss() - base}))
"""


def _measure(kind: str) -> dict:
    out = subprocess.run(
        [sys.executable, "-c", _SCRIPT, kind],
        capture_output=True,
        text=True,
        timeout=300,
        env={"OPENBLAS_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"},
    )
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout.strip().splitlines()[-1])


@needs_pardiso
@pytest.mark.parametrize("kind", ["single", "shared"])
def test_a_dropped_pardiso_factor_is_released(kind):
    m = _measure(kind)
    assert m["footprint"] > 20e6  # the measurement sees the factor at all
    assert m["growth"] < 0.5 * m["footprint"]  # kept factors: about 4 footprints


@needs_pardiso
def test_free_then_drop_releases_once():
    import gc

    import numpy as np
    import scipy.sparse as sp

    from fe_crank.fe.linalg.factorise import factorise

    K = (sp.diags([-np.ones(99), 2.5 * np.ones(100), -np.ones(99)], [-1, 0, 1])).tocsr()
    fac = factorise(K, "pardiso")
    fac.free()
    assert not fac._finalizer.alive  # the release ran, and will not run again
    del fac
    gc.collect()  # no second phase -1 on the released handle


@needs_pardiso
@pytest.mark.heavy
def test_pardiso_gives_the_same_bits_on_every_factorisation():
    """An elastic P2 cube of 19k unknowns factorised five times in one process (three in
    core, two on one shared-analysis handle): the solutions are bit-identical.  MKL PARDISO's
    default threaded factorisation is not reproducible at this size (four solutions
    differed in their last bits); its reproducible mode (``CNR_THREADS``) is."""
    import scipy.sparse as sp
    from skfem import Basis, ElementTetP2, ElementVector, MeshTet, asm
    from skfem.models.elasticity import lame_parameters, linear_elasticity

    from fe_crank.fe.linalg.factorise import factorise, factorise_shared

    mesh = MeshTet.init_tensor(*(np.linspace(0.0, 1.0, 10),) * 3)
    basis = Basis(mesh, ElementVector(ElementTetP2()))
    K = asm(linear_elasticity(*lame_parameters(1.0, 0.3)), basis)
    free = np.setdiff1d(np.arange(K.shape[0]), basis.get_dofs(lambda x: x[0] < 1e-9).all())
    A = K[free][:, free].tocsr()
    f = np.cos(0.37 * np.arange(A.shape[0]))
    solutions = []
    for _ in range(3):
        fac = factorise(A, "pardiso")
        solutions.append(fac.solve(f))
        fac.free()
    upper = sp.triu(A, format="csr")  # the shared handle takes the upper triangle, sorted
    upper.sort_indices()
    for fac in factorise_shared([upper, upper]):
        solutions.append(fac.solve(f))
        fac.free()
    assert all(np.array_equal(x, solutions[0]) for x in solutions[1:])
