"""FE stage: vectorised assembly equals scikit-fem's generic assembly; solvers agree."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import Basis, ElementTetP2, ElementVector, FacetBasis, MeshTet2, asm
from skfem.models.elasticity import lame_parameters as skfem_lame
from skfem.models.elasticity import linear_elasticity

from fe_crank.errors import InputError, SolverError
from fe_crank.fe import bearing_support, centrifugal, elasticity, factorise
from fe_crank.fe.core.assembly import assemble_foundation, assemble_stiffness
from fe_crank.fe.core.forms import lame_parameters
from fe_crank.fe.core.loads import centrifugal_load
from fe_crank.fe.core.supports import radial_direction

E, NU = 210e9, 0.3


@pytest.fixture(scope="module")
def ball():
    """Isoparametric (curved) P2 ball: exercises the non-affine mapping."""
    return MeshTet2.init_ball(nrefs=1)


def test_stiffness_equals_skfem_linear_elasticity(ball):
    """The hand kernel against scikit-fem's generic assembly of its own linear-elasticity
    form (an independent implementation) on a curved P2 mesh: equal to 1e-14 of the
    largest entry (measured 2.8e-16, i.e. round-off of sums of a few hundred products;
    a wrong index or factor shows at 1e-2 or more) and symmetric to round-off (7e-17)."""
    b = Basis(ball, ElementTetP2(), intorder=2)
    vb = Basis(ball, ElementVector(ElementTetP2()), intorder=2)
    K = assemble_stiffness(b, E, NU, chunk=37)  # several chunks
    K_ref = asm(linear_elasticity(*skfem_lame(E, NU)), vb)
    assert abs(K - K_ref).max() < 1e-14 * abs(K_ref).max()
    assert abs(K - K.T).max() < 1e-14 * abs(K_ref).max()
    K_form = asm(elasticity(E, NU), vb)  # our reference form too
    assert abs(K - K_form).max() < 1e-14 * abs(K_ref).max()


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
    # E = 210 GPa, nu = 0.3: lambda = 210 * 0.3 / (1.3 * 0.4) = 63 / 0.52 = 121.1538 GPa,
    # mu = 210 / 2.6 = 80.7692 GPa; scikit-fem's own lame_parameters as a second source
    lam, mu = lame_parameters(E, NU)
    assert lam == pytest.approx(121.153846e9, rel=1e-8) and mu == pytest.approx(80.769231e9, rel=1e-8)
    assert (lam, mu) == pytest.approx(skfem_lame(E, NU), rel=1e-14)
    # the open interval -1 < nu < 0.5 and E > 0: the ends are refused, the inside accepted
    for nu in (0.5, -1.0, 0.6):
        with pytest.raises(InputError, match="Poisson's ratio must lie in") as e:
            lame_parameters(E, nu)
        assert e.value.key == "material.poisson_ratio"
    assert lame_parameters(E, 0.499)[0] == pytest.approx(E * 0.499 / (1.499 * 0.002), rel=1e-12)
    assert lame_parameters(E, -0.99)[1] == pytest.approx(E / 0.02, rel=1e-12)
    assert lame_parameters(0.5, 0.3)[1] == pytest.approx(0.5 / 2.6, rel=1e-12)  # any E > 0, in Pa
    for e_mod in (0.0, -1.0):
        with pytest.raises(InputError, match="Young's modulus must be > 0") as e:
            lame_parameters(e_mod, 0.3)
        assert e.value.key == "material.youngs_modulus"


def test_centrifugal_about_an_offset_axis(ball):
    """Axis through p = (0.1, 0.2, 0) along 2 e_z (not a unit vector): the resultant is
    rho omega^2 V (c - p)_perp with c = 0 the ball's centroid and V its volume
    (quadrature), i.e. -rho omega^2 V (0.1, 0.2, 0); the form and the fast load agree."""
    b = Basis(ball, ElementTetP2(), intorder=4)
    vb = Basis(ball, ElementVector(ElementTetP2()), intorder=4)
    kw = dict(axis_point=(0.1, 0.2, 0.0), axis=(0.0, 0.0, 2.0))
    f = centrifugal_load(b, 7850.0, 300.0, **kw)
    f_ref = asm(centrifugal(7850.0, 300.0, **kw), vb)
    np.testing.assert_allclose(f, f_ref, rtol=0, atol=1e-12 * np.abs(f_ref).max())
    volume = float(b.dx.sum())
    total = f.reshape(-1, 3).sum(axis=0)
    expected = -7850.0 * 300.0**2 * volume * np.array([0.1, 0.2, 0.0])
    np.testing.assert_allclose(total, expected, rtol=0, atol=1e-9 * np.abs(expected).max())


@pytest.mark.parametrize("method", ["superlu", "amg", "pardiso", "cholmod"])
def test_solvers_reach_the_same_solution(ball, method):
    """Clamped ball surface cap, body load: each method against a dense solve."""
    b = Basis(ball, ElementTetP2(), intorder=2)
    K = assemble_stiffness(b, E, NU).tocsr()
    f = centrifugal_load(b, 7850.0, 100.0)
    fixed = (
        3 * b.get_dofs(ball.facets_satisfying(lambda p: p[2] < -0.5, boundaries_only=True)).all()[:, None]
        + np.arange(3)
    ).ravel()
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
    f[::3] = 1.0  # unbalanced load on a free body
    with pytest.raises(SolverError):
        factorise(K, "superlu").solve(f)
    with pytest.raises(SolverError, match="NaN"):
        factorise(K + _identity(K), "superlu").solve(np.full(K.shape[0], np.nan))


def _identity(K):
    import scipy.sparse as sp

    return sp.identity(K.shape[0], format="csr")


@pytest.mark.parametrize("bound", [1000, 2**60])
def test_unique_inverse_equals_numpy_unique(bound):
    """The packed-sort unique (and, keys too wide to pack, its np.unique fallback)
    against numpy's own ``np.unique(return_inverse=True)`` on random keys with repeats."""
    from fe_crank.fe.core.assembly import unique_inverse

    key = np.random.default_rng(3).integers(0, bound, size=5000, dtype=np.int64)
    uniq, inv = unique_inverse(key, bound)
    ref_u, ref_inv = np.unique(key, return_inverse=True)
    assert np.array_equal(uniq, ref_u) and np.array_equal(inv, ref_inv)
    assert np.array_equal(uniq[inv], key)
