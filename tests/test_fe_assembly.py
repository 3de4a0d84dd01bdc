"""FE stage: vectorised assembly equals scikit-fem's generic assembly; solvers agree."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import Basis, ElementTetP2, ElementVector, FacetBasis, MeshTet2, asm
from skfem.models.elasticity import lame_parameters as skfem_lame, linear_elasticity

from fe_crank.errors import InputError, SolverError
from fe_crank.fe import bearing_support, centrifugal, elasticity, factorise
from fe_crank.fe.assembly import assemble_foundation, assemble_stiffness
from fe_crank.fe.loads import centrifugal_load
from fe_crank.fe.supports import radial_direction
from fe_crank.fe.forms import lame_parameters

E, NU = 210e9, 0.3


@pytest.fixture(scope="module")
def ball():
    """Isoparametric (curved) P2 ball: exercises the non-affine mapping."""
    return MeshTet2.init_ball(nrefs=1)


def test_stiffness_equals_skfem_linear_elasticity(ball):
    b = Basis(ball, ElementTetP2(), intorder=2)
    vb = Basis(ball, ElementVector(ElementTetP2()), intorder=2)
    K = assemble_stiffness(b, E, NU, chunk=37)                  # several chunks
    K_ref = asm(linear_elasticity(*skfem_lame(E, NU)), vb)
    assert abs(K - K_ref).max() < 1e-12 * abs(K_ref).max()
    K_form = asm(elasticity(E, NU), vb)                          # our reference form too
    assert abs(K - K_form).max() < 1e-12 * abs(K_ref).max()


def test_centrifugal_load_equals_linear_form(ball):
    b = Basis(ball, ElementTetP2(), intorder=4)
    vb = Basis(ball, ElementVector(ElementTetP2()), intorder=4)
    f = centrifugal_load(b, 7850.0, 300.0)
    f_ref = asm(centrifugal(7850.0, 300.0), vb)
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-12 * np.abs(f_ref).max())


def test_foundation_equals_bilinear_form(ball):
    # keep away from the poles, where the radial (xy) part of the normal vanishes
    band = ball.facets_satisfying(lambda p: np.abs(p[2]) < 0.5, boundaries_only=True)
    fb = FacetBasis(ball, ElementTetP2(), facets=band, intorder=4)
    vfb = FacetBasis(ball, ElementVector(ElementTetP2()), facets=band, intorder=4)
    K = assemble_foundation(fb, 1e12, radial_direction)
    K_ref = asm(bearing_support(1e12), vfb)
    assert abs(K - K_ref).max() < 1e-12 * abs(K_ref).max()


def test_lame_parameters_closed_form_and_bad_input():
    lam, mu = lame_parameters(E, NU)
    assert lam == pytest.approx(E * NU / ((1 + NU) * (1 - 2 * NU)))
    assert mu == pytest.approx(E / 2.6)
    with pytest.raises(InputError, match="Poisson"):
        lame_parameters(E, 0.5)
    with pytest.raises(InputError, match="Young"):
        lame_parameters(-1.0, 0.3)


@pytest.mark.parametrize("method", ["superlu", "amg", "pardiso", "cholmod"])
def test_solvers_reach_the_same_solution(ball, method):
    """Clamped ball surface cap, body load: each method against a dense solve."""
    b = Basis(ball, ElementTetP2(), intorder=2)
    K = assemble_stiffness(b, E, NU).tocsr()
    f = centrifugal_load(b, 7850.0, 100.0)
    fixed = (3 * b.get_dofs(ball.facets_satisfying(lambda p: p[2] < -0.5, boundaries_only=True)).all()[:, None]
             + np.arange(3)).ravel()
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    Kr = K[free][:, free]
    x_ref = np.linalg.solve(Kr.toarray(), f[free])
    if method in ("pardiso", "cholmod"):
        pytest.importorskip({"pardiso": "pypardiso", "cholmod": "cholespy"}[method])
    fac = factorise(Kr, method)
    x = fac.solve(np.column_stack([f[free], 2 * f[free]]))
    assert np.abs(x[:, 0] - x_ref).max() < 1e-7 * np.abs(x_ref).max()
    assert np.abs(x[:, 1] - 2 * x_ref).max() < 1e-7 * np.abs(x_ref).max()


def test_singular_matrix_and_nan_are_solver_errors(ball):
    b = Basis(ball, ElementTetP2(), intorder=2)
    K = assemble_stiffness(b, E, NU)
    f = np.zeros(K.shape[0])
    f[::3] = 1.0                                  # unbalanced load on a free body
    with pytest.raises(SolverError):
        factorise(K, "superlu").solve(f)
    with pytest.raises(SolverError, match="NaN"):
        factorise(K + _identity(K), "superlu").solve(np.full(K.shape[0], np.nan))


def _identity(K):
    import scipy.sparse as sp

    return sp.identity(K.shape[0], format="csr")
