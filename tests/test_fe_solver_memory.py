"""FE solvers: a PARDISO factor lives in MKL's own memory, outside Python's; it must be
released when its Factorisation is dropped, or a process that solves several models (a
batch of load cases, the convergence study, the test suite) keeps every factor.

Measured by the resident memory (/proc/self/statm) of a fresh Python process (so that
memory freed earlier in this one cannot be reused and hide the growth) around
factorisations of a 3D 7-point Laplacian (SPD, 27 000 unknowns, a factor of tens of MB
with nested dissection): the growth after several factorise-and-drop cycles must stay
below half of one live factor's footprint; keeping every factor grows by one footprint
per cycle (4 cycles: about 4 footprints).
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

pytest.importorskip("pypardiso")

_SCRIPT = r"""
import gc, json, sys
import numpy as np
import scipy.sparse as sp
from fe_crank.fe.solvers import factorise
from fe_crank.fe.symsolve import _pardiso_shared

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
    facs = _pardiso_shared([U1, U2])
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


@pytest.mark.parametrize("kind", ["single", "shared"])
def test_a_dropped_pardiso_factor_is_released(kind):
    m = _measure(kind)
    assert m["footprint"] > 20e6  # the measurement sees the factor at all
    assert m["growth"] < 0.5 * m["footprint"]  # kept factors: about 4 footprints


def test_free_then_drop_releases_once():
    import gc

    import numpy as np
    import scipy.sparse as sp

    from fe_crank.fe.solvers import factorise

    K = (sp.diags([-np.ones(99), 2.5 * np.ones(100), -np.ones(99)], [-1, 0, 1])).tocsr()
    fac = factorise(K, "pardiso")
    fac.free()
    assert not fac._finalizer.alive  # the release ran, and will not run again
    del fac
    gc.collect()  # no second phase -1 on the released handle
