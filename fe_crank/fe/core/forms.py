"""Weak-form factories in the scikit-fem style (reference forms and material constants).

The fast assembly in :mod:`fe_crank.fe.core.assembly` builds the same bilinear form from the
scalar basis gradients; these forms are the reference it is tested against.
"""

from __future__ import annotations

import numpy as np
from skfem import BilinearForm, LinearForm
from skfem.helpers import ddot, dot, eye, sym_grad, trace

from fe_crank.errors import InputError


def lame_parameters(youngs_modulus: float, poisson_ratio: float) -> tuple[float, float]:
    """Lamé constants of an isotropic solid.

    lambda = E nu / ((1 + nu)(1 - 2 nu)),  mu = E / (2 (1 + nu))
    (any elasticity text, e.g. Timoshenko & Goodier, Theory of Elasticity, ch. 1).
    """
    if not youngs_modulus > 0:
        raise InputError(f"Young's modulus must be > 0, got {youngs_modulus!r}", key="material.youngs_modulus")
    if not -1.0 < poisson_ratio < 0.5:
        raise InputError(f"Poisson's ratio must lie in (-1, 0.5), got {poisson_ratio!r}", key="material.poisson_ratio")
    lam = youngs_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio))
    mu = youngs_modulus / (2.0 * (1.0 + poisson_ratio))
    return lam, mu


def elasticity(youngs_modulus: float, poisson_ratio: float) -> BilinearForm:
    """Bilinear form of isotropic linear elasticity, a(u, v) = int sigma(u) : eps(v) dV.

    sigma = 2 mu eps + lambda tr(eps) I (Hooke's law).  Use with an
    ``ElementVector(ElementTetP2())`` basis; :func:`fe_crank.fe.core.assembly.assemble_stiffness`
    assembles the same form much faster.
    """
    lam, mu = lame_parameters(youngs_modulus, poisson_ratio)

    @BilinearForm
    def form(u, v, w):
        eps_u = sym_grad(u)
        sig = 2.0 * mu * eps_u + lam * eye(trace(eps_u), 3)
        return ddot(sig, sym_grad(v))

    return form


def centrifugal(density: float, omega: float, axis_point=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)) -> LinearForm:
    """Linear form of the centrifugal body force, l(v) = int rho omega^2 r_perp . v dV.

    r_perp is the position vector's component perpendicular to the rotation axis
    (d'Alembert force in the rotating frame).
    """
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    p = np.asarray(axis_point, float)

    @LinearForm
    def form(v, w):
        x = w.x - p.reshape(3, *([1] * (w.x.ndim - 1)))
        along = np.einsum("i...,i->...", x, a)
        r_perp = x - a.reshape(3, *([1] * (x.ndim - 1))) * along
        return density * omega**2 * dot(r_perp, v)

    return form


def bearing_support(stiffness: float) -> BilinearForm:
    """Bilinear form of an elastic radial foundation, k int (u . n_r)(v . n_r) dA.

    ``stiffness`` is the spring stiffness per area (N/m^3); n_r the unit normal with its
    axial (z) part removed, so the foundation acts radially on a journal surface
    (Winkler foundation, e.g. Hetenyi, Beams on Elastic Foundation, 1946).
    """

    @BilinearForm
    def form(u, v, w):
        nx, ny = np.asarray(w.n[0]), np.asarray(w.n[1])
        nr2 = nx**2 + ny**2
        return stiffness * (u[0] * nx + u[1] * ny) * (v[0] * nx + v[1] * ny) / nr2

    return form
