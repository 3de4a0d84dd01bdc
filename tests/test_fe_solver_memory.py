"""FE solvers: a PARDISO factor lives in MKL's own memory, outside Python's; it must be
released when its Factorisation is dropped, or a process that solves several models (a
batch of load cases, the convergence study, the test suite) keeps every factor.

Measured by the process's resident memory (/proc/self/statm) around factorisations of a
3D 7-point Laplacian (SPD, 27 000 unknowns, a factor of tens of MB with nested
dissection): the growth after several factorise-and-drop cycles must stay below half of
one live factor's footprint; keeping every factor would grow by one footprint per cycle.
"""

from __future__ import annotations

import gc

import numpy as np
import pytest
import scipy.sparse as sp

pytest.importorskip("pypardiso")

from fe_crank.fe.solvers import factorise  # noqa: E402
from fe_crank.fe.symsolve import _pardiso_shared  # noqa: E402

N1 = 30                                       # grid points per direction


def _rss() -> float:
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * 4096.0


def _laplacian(n: int, shift: float = 0.0) -> sp.csr_matrix:
    one = sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1])
    eye = sp.identity(n)
    K = sp.kron(sp.kron(one, eye), eye) + sp.kron(sp.kron(eye, one), eye) + sp.kron(sp.kron(eye, eye), one)
    return (K + shift * sp.identity(n**3)).tocsr()


def _cycles(make, count: int = 4) -> tuple[float, float]:
    """(footprint of one live factor, growth after ``count`` factorise-and-drop cycles);
    one cycle first, so that loading MKL and its thread buffers is not counted."""
    warm = make()
    del warm
    gc.collect()
    base = _rss()
    live = make()
    footprint = _rss() - base
    del live
    for _ in range(count - 1):
        f = make()
        del f
    gc.collect()
    return footprint, _rss() - base


def test_a_dropped_pardiso_factor_is_released():
    K = _laplacian(N1)
    b = np.ones(K.shape[0])

    def make():
        fac = factorise(K, "pardiso")
        assert np.allclose(K @ fac.solve(b), b)
        return fac

    footprint, growth = _cycles(make)
    assert footprint > 20e6                   # the measurement sees the factor at all
    assert growth < 0.5 * footprint           # kept factors would give ~4 footprints


def test_free_then_drop_releases_once():
    K = _laplacian(12)
    fac = factorise(K, "pardiso")
    fac.free()
    assert not fac._finalizer.alive           # the release ran, and will not run again
    del fac
    gc.collect()                              # no second phase -1 on the released handle


def test_the_shared_analysis_handle_is_released_with_its_last_member():
    K1, K2 = _laplacian(N1), _laplacian(N1, shift=0.5)     # one sparsity pattern, two factors
    U1, U2 = sp.triu(K1, format="csr"), sp.triu(K2, format="csr")
    U1.sort_indices()
    U2.sort_indices()
    b = np.ones(K1.shape[0])

    def make():
        facs = _pardiso_shared([U1, U2])
        assert np.allclose(K2 @ facs[1].solve(b), b)
        return facs

    footprint, growth = _cycles(make)
    assert footprint > 20e6
    assert growth < 0.5 * footprint
