"""FE stage: P2 elasticity against closed-form solutions (Lame disk, beam, round bar)."""

from __future__ import annotations

import numpy as np
import pytest
from helpers.verification_meshes import annulus_sector, box_beam, round_bar
from skfem import ElementTetP2, FacetBasis

from fe_crank.fe import Coupling, Dirichlet, build_system
from fe_crank.fe.core.assembly import assemble_surface_load
from fe_crank.fe.core.loads import centrifugal_load
from fe_crank.fe.core.stress import stress_at_nodes

E, NU, RHO = 210e9, 0.3, 7850.0
ALL6 = ("ux", "uy", "uz", "rx", "ry", "rz")


def test_rotating_annular_disk_hoop_stress_at_bore_matches_lame():
    """Thin rotating disk with a bore, plane stress (Timoshenko & Goodier, Theory of
    Elasticity, 3rd ed., sec. 32): sigma_t(a) = (3 + nu)/4 rho w^2 (b^2 + (1 - nu)/(3 + nu) a^2)."""
    a, b, w = 0.05, 0.15, 1000.0
    mesh = annulus_sector(a, b, 0.005, nr=8, nt=12)  # quarter, half thickness: 3.3k dof
    s = build_system(
        mesh,
        E,
        NU,
        solver="superlu",
        dirichlet=[Dirichlet("sym_x", (1,)), Dirichlet("sym_y", (0,)), Dirichlet("bottom", (2,))],
    )
    f = centrifugal_load(s.basis, RHO, w)
    u = s.solve(f)
    sig = stress_at_nodes(mesh, u, E, NU)
    bore = s.basis.get_dofs(mesh.boundaries["bore"]).all()
    x = s.points[:, bore]
    th = np.arctan2(x[1], x[0])
    hoop = sig[0, bore] * np.sin(th) ** 2 + sig[1, bore] * np.cos(th) ** 2 - 2 * sig[3, bore] * np.sin(th) * np.cos(th)
    exact = (3 + NU) / 4 * RHO * w**2 * (b**2 + (1 - NU) / (3 + NU) * a**2)
    assert np.abs(hoop / exact - 1).max() < 0.01
    assert abs(hoop.mean() / exact - 1) < 0.003
    # bore radial displacement u_r(a) = a sigma_t(a) / E (sigma_r(a) = 0)
    ur = u.reshape(-1, 3)[bore, 0] * np.cos(th) + u.reshape(-1, 3)[bore, 1] * np.sin(th)
    assert np.abs(ur / (a * exact / E) - 1).max() < 1e-3
    assert s.equilibrium_error(u, f)[0] < 1e-9


def test_cantilever_tip_deflection_and_bending_stress_match_beam_theory():
    """Tip load P on a clamped square beam, L/h = 20: Timoshenko beam
    delta = P L^3 / (3 E I) + P L / (kappa G A), kappa = 5/6; sigma(L/2) = P (L/2) (h/2) / I."""
    L, h, P = 0.4, 0.02, 1000.0
    mesh = box_beam(L, h, h, nx=40, ny=2, nz=2)  # 6k dof
    s = build_system(mesh, E, NU, solver="superlu", dirichlet=[Dirichlet("root")])
    fb = FacetBasis(mesh, ElementTetP2(), facets=mesh.boundaries["tip"], intorder=4)
    f = assemble_surface_load(fb, lambda x, n: np.stack([0 * x[0], 0 * x[0], np.full_like(x[0], -P / h**2)]))
    u = s.solve(f)
    I, A, G = h**4 / 12, h**2, E / (2 * (1 + NU))
    delta = P * L**3 / (3 * E * I) + P * L / (5 / 6 * G * A)
    tip = s.basis.get_dofs(mesh.boundaries["tip"]).all()
    assert -u.reshape(-1, 3)[tip, 2].mean() == pytest.approx(delta, rel=0.01)
    sig = stress_at_nodes(mesh, u, E, NU)
    x = s.points
    mid_top = np.flatnonzero((np.abs(x[0] - L / 2) < 1e-9) & (np.abs(x[2] - h) < 1e-9))
    np.testing.assert_allclose(sig[0, mid_top], P * (L / 2) * (h / 2) / I, rtol=0.01)
    err, reac = s.equilibrium_error(u, f)
    assert err < 1e-9
    assert reac["dirichlet"][2] == pytest.approx(P, rel=1e-9)


@pytest.fixture(scope="module")
def bar():
    d, length = 0.02, 0.08
    mesh = round_bar(d, length, size=0.003)  # 22k dof
    s = build_system(mesh, E, NU, couplings=[Coupling("end_1", fixed=ALL6), Coupling("end_2")])
    return d, length, mesh, s


def _mid_surface_nodes(bar):
    d, length, mesh, s = bar
    surf = s.basis.get_dofs(mesh.boundaries["surface"]).all()
    return surf[np.abs(s.points[2, surf] - length / 2) < 0.25 * d]


def test_round_bar_in_pure_bending(bar):
    """sigma = 32 M / (pi d^3) at the surface (elementary beam theory), M applied through
    rigid end-face couplings (IACS UR M53 FE appendix style)."""
    d, length, mesh, s = bar
    M = 10.0
    load = {"end_2": np.array([0, 0, 0, M, 0, 0.0])}
    zero = np.zeros(3 * s.basis.N)
    u = s.solve(zero, [load])
    sig = stress_at_nodes(mesh, u, E, NU)
    sel = _mid_surface_nodes(bar)
    th = np.arctan2(s.points[1, sel], s.points[0, sel])
    keep = np.abs(np.sin(th)) > 0.5  # away from the neutral axis
    # M_x > 0 stretches the fibres at +y: sigma_zz = M y / I
    ratio = sig[2, sel][keep] / (32 * M / (np.pi * d**3) * np.sin(th[keep]))
    assert np.abs(ratio - 1).max() < 0.01
    err, reac = s.equilibrium_error(u, zero, load)
    assert err < 1e-6
    assert reac["end_1"][3] == pytest.approx(-M, rel=1e-6)


def test_round_bar_in_torsion(bar):
    """tau = 16 T / (pi d^3) at the surface (Saint-Venant torsion of a circular shaft)."""
    d, length, mesh, s = bar
    T = 10.0
    load = {"end_2": np.array([0, 0, 0, 0, 0, T])}
    zero = np.zeros(3 * s.basis.N)
    u = s.solve(zero, [load])
    sig = stress_at_nodes(mesh, u, E, NU)
    sel = _mid_surface_nodes(bar)
    th = np.arctan2(s.points[1, sel], s.points[0, sel])
    tau = -sig[5, sel] * np.sin(th) + sig[4, sel] * np.cos(th)  # e_theta . sigma . e_z
    np.testing.assert_allclose(tau, 16 * T / (np.pi * d**3), rtol=0.01)
    # twist angle over the free length: phi = T L / (G J), J = pi d^4 / 32 (rigid end faces)
    err, reac = s.equilibrium_error(u, zero, load)
    assert err < 1e-6
    assert reac["end_1"][5] == pytest.approx(-T, rel=1e-6)
