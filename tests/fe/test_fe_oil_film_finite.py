"""The finite bearing's oil film (fe_crank.fe.oil_film: the short bearing over the
finite-length factor R_fit) against an independent finite-difference solution of
Reynolds' equation written here.

The reference solves the full Reynolds equation of a rigid journal turning at omega in a
fixed bearing, with the half-Sommerfeld condition the model uses (the negative pressures
of the solution dropped), in its physical form: the wedge term of the journal's surface
speed and the squeeze term of the centre's velocity, not Booker's squeeze velocity.  The
points are off the factor's fitting grid (other widths and eccentricities, grids of other
sizes)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import spsolve

from fe_crank.fe.oil_film import FIT_MAX_ECCENTRICITY, MAX_LAND_ASPECT, film_force, finite_factor, periodic_orbits
from fe_crank.geometry.shaft import MAX_FILM_ASPECT


def reynolds_force(eps, deps, spin, lam, nt, nz=16):
    """The film's force on the bearing over mu omega R^4 / c^2 of a bearing of width /
    diameter ``lam`` at eccentricity ratio ``eps`` (x, y), centre velocity ``deps`` (per
    unit omega) and journal speed ``spin`` (omega's multiple, turning from +x to +y):
    d/dth (h^3 dp/dth) + d/dz (h^3 dp/dz) = 6 spin dh/dth + 12 dh/dtau on z = Z/R in
    (-lam, lam), h = 1 - eps . n(th), p = 0 at the edges, periodic in th; half-Sommerfeld:
    the negative pressures dropped; central differences, nt x nz nodes."""
    th = np.arange(nt) * 2 * np.pi / nt
    dth = th[1]
    dz = 2 * lam / (nz + 1)
    ex, ey = eps

    def h3(t):
        return (1 - ex * np.cos(t) - ey * np.sin(t)) ** 3

    i, j = np.meshgrid(np.arange(nt), np.arange(nz), indexing="ij")
    k, ii, jj = (i * nz + j).ravel(), i.ravel(), j.ravel()
    hp, hm, hc = h3(th + dth / 2)[ii], h3(th - dth / 2)[ii], h3(th)[ii]
    rows, cols = [k, k, k], [((ii + 1) % nt) * nz + jj, ((ii - 1) % nt) * nz + jj, k]
    vals = [hp / dth**2, hm / dth**2, -(hp + hm) / dth**2 - 2 * hc / dz**2]
    for dj in (1, -1):
        ok = (jj + dj >= 0) & (jj + dj < nz)
        rows.append(k[ok])
        cols.append((ii * nz + jj + dj)[ok])
        vals.append((hc / dz**2)[ok])
    a = coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(nt * nz,) * 2)
    dh_dth = ex * np.sin(th) - ey * np.cos(th)
    dh_dtau = -(deps[0] * np.cos(th) + deps[1] * np.sin(th))
    p = np.maximum(spsolve(a.tocsc(), (6 * spin * dh_dth + 12 * dh_dtau)[ii]), 0.0).reshape(nt, nz)
    return np.array([(p * np.cos(th)[:, None]).sum(), (p * np.sin(th)[:, None]).sum()]) * dth * dz


def _nt(eps):
    return 720 if eps < 0.9 else 1440


def short_force(eps, u, lam):
    """The short bearing's force (``film_force``) in the reference's scale: k0 = mu R B^3 / c^2
    with B = 2 lam R."""
    return film_force(np.asarray(eps, float), np.asarray(u, float)) * (2 * lam) ** 3


@pytest.mark.parametrize("lam", [0.12, 0.35])
@pytest.mark.parametrize("eps", [0.5, 0.85, 0.96])
def test_finite_factor_against_reynolds(lam, eps):
    """R_fit is the short bearing's over-estimate of the steady (wedge) film, within the
    fit's 2 % (3 % allowed with the reference's own discretisation); for a squeeze velocity
    along the line of centres or turned 60 and 120 deg from it the over-estimate is
    smaller: the model's force is at most the finite bearing's there (on the safe side)."""
    r_fit = float(finite_factor(np.array(eps), np.array(lam))[0])
    steady = reynolds_force((eps, 0.0), (0.0, 0.0), 1.0, lam, _nt(eps))
    u_steady = (0.0, -0.5 * eps)  # Booker: u = d eps/dt - omega/2 e_z x eps
    r = np.linalg.norm(short_force((eps, 0.0), u_steady, lam)) / np.linalg.norm(steady)
    assert r_fit / r == pytest.approx(1.0, abs=0.03)
    for psi in (0.0, 60.0, 120.0):
        u = (math.cos(math.radians(psi)), math.sin(math.radians(psi)))
        fd = reynolds_force((eps, 0.0), u, 0.0, lam, _nt(eps))
        model = short_force((eps, 0.0), u, lam) / r_fit
        assert np.linalg.norm(model) <= 1.03 * np.linalg.norm(fd)
        assert np.linalg.norm(model) >= 0.5 * np.linalg.norm(fd)


@pytest.mark.parametrize(("lam", "eps"), [(0.15, 0.6), (0.15, 0.95), (0.3, 0.9)])
def test_steady_load_eccentricity_and_attitude_against_reynolds(lam, eps):
    """Under the steady load the finite-difference bearing carries at eccentricity ratio
    ``eps`` (its attitude angle from the load), the model's journal (periodic orbit under
    that constant load) settles at nearly the same film: h_min within 3 % of the
    reference's, never thicker by more than 1 %, the attitude angle within 4 deg."""
    fd = reynolds_force((eps, 0.0), (0.0, 0.0), 1.0, lam, _nt(eps))
    load = fd / (2 * lam) ** 3  # over k0 omega
    orbit = periodic_orbits(
        np.tile(load, (1, 36, 1)), 1.0, mean_speed=0.5, start=np.array([[eps, 0.0]]), aspect=np.array([lam])
    )
    assert orbit.converged[0]
    e = orbit.eps[0, -1]
    h_model, h_fd = 1 - np.hypot(*e), 1 - eps
    assert h_model / h_fd == pytest.approx(1.0, abs=0.03)
    assert h_model <= 1.01 * h_fd
    attitude = lambda v: math.degrees(math.atan2(v[1], v[0]) - math.atan2(load[1], load[0]))
    assert abs(attitude(e) - attitude((eps, 0.0))) < 4.0


@pytest.mark.parametrize(("lam", "eps"), [(0.1, 0.9), (0.25, 0.8), (0.4, 0.95)])
def test_pure_squeeze_against_reynolds(lam, eps):
    """Pure squeeze (no rotation, the centre approaching along the line of centres): the
    model's film force at the reference's velocity is the reference's within -15 % / +3 %
    (smaller: under a given load the model's journal approaches faster, on the safe side),
    and along the same line."""
    fd = reynolds_force((eps, 0.0), (1.0, 0.0), 0.0, lam, _nt(eps))
    model = short_force((eps, 0.0), (1.0, 0.0), lam) / float(finite_factor(np.array(eps), np.array(lam))[0])
    assert 0.85 <= np.linalg.norm(model) / np.linalg.norm(fd) <= 1.03
    assert abs(math.atan2(model[1], model[0])) < 1e-9 and abs(math.atan2(fd[1], fd[0])) < 1e-9


def test_factor_is_one_for_the_short_bearing_and_the_range_is_the_geometrys():
    """R_fit = 1 at zero width (the short bearing) at every eccentricity, its eps-derivative
    against a central difference, and the geometry refuses lands beyond the fitted range."""
    e = np.linspace(0.0, FIT_MAX_ECCENTRICITY, 12)
    r, dr = finite_factor(e, np.zeros_like(e))
    assert np.all(r == 1.0) and np.all(dr == 0.0)
    lam = np.full_like(e, 0.3)
    d = 1e-6
    numeric = (finite_factor(e + d, lam)[0] - finite_factor(e - d, lam)[0]) / (2 * d)
    assert finite_factor(e, lam)[1] == pytest.approx(numeric, rel=1e-6)
    assert MAX_FILM_ASPECT == MAX_LAND_ASPECT
