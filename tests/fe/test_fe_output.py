"""FE stage: VTU output round trip, stress recovery identities."""

from __future__ import annotations

import meshio
import numpy as np
import pytest
from helpers.verification_meshes import annulus_sector
from skfem import Basis, ElementTetP2

from fe_crank.fe import Dirichlet, build_system, max_shear, principal, von_mises
from fe_crank.fe.core.loads import centrifugal_load
from fe_crank.fe.core.result_fields import write_fields
from fe_crank.fe.core.stress import averaging_indicator, stress_at_nodes, stress_at_quadrature

E, NU = 210e9, 0.3


def test_invariants_of_a_known_tensor():
    # sigma = diag(3, 1, -2) rotated: invariants do not depend on the frame
    rng = np.random.default_rng(1)
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    S = Q @ np.diag([3.0, 1.0, -2.0]) @ Q.T
    v = np.array([S[0, 0], S[1, 1], S[2, 2], S[0, 1], S[1, 2], S[2, 0]])
    np.testing.assert_allclose(principal(v), [3.0, 1.0, -2.0], atol=1e-12)
    assert von_mises(v) == pytest.approx(np.sqrt(0.5 * ((3 - 1) ** 2 + (1 + 2) ** 2 + (-2 - 3) ** 2)))
    assert max_shear(v) == pytest.approx(2.5)


@pytest.fixture(scope="module")
def disk():
    mesh = annulus_sector(0.05, 0.15, 0.005, nr=4, nt=6)
    s = build_system(
        mesh,
        E,
        NU,
        solver="superlu",
        dirichlet=[Dirichlet("sym_x", (1,)), Dirichlet("sym_y", (0,)), Dirichlet("bottom", (2,))],
    )
    u = s.solve(centrifugal_load(s.basis, 7850.0, 1000.0))
    return mesh, s, u


def test_vtu_round_trip(tmp_path, disk):
    mesh, s, u = disk
    sig = stress_at_nodes(mesh, u, E, NU)
    path = write_fields(tmp_path / "disk.vtu", s.basis, u, sig)
    back = meshio.read(path)
    assert back.cells[0].type == "tetra10"
    # the same cells, some with corners 1 and 2 (and their edges) swapped to a positive volume
    np.testing.assert_array_equal(np.sort(back.cells[0].data, axis=1), np.sort(s.basis.element_dofs.T, axis=1))
    p = back.points
    c = back.cells[0].data
    vol = np.einsum("ij,ij->i", np.cross(p[c[:, 1]] - p[c[:, 0]], p[c[:, 2]] - p[c[:, 0]]), p[c[:, 3]] - p[c[:, 0]])
    assert (vol > 0).all()
    np.testing.assert_allclose(back.points, s.basis.doflocs.T)
    np.testing.assert_allclose(back.point_data["displacement_m"], u.reshape(-1, 3))
    np.testing.assert_allclose(back.point_data["von_mises_Pa"], von_mises(sig))
    # VTK tetra10 node order = scikit-fem's: mid-edge node 4 lies between corners 0 and 1
    c = back.cells[0].data[0]
    mid = 0.5 * (back.points[c[0]] + back.points[c[1]])
    assert np.linalg.norm(back.points[c[4]] - mid) < 0.05 * np.linalg.norm(back.points[c[1]] - back.points[c[0]])


def test_quadrature_and_nodal_stress_agree_on_a_smooth_field(disk):
    mesh, s, u = disk
    b = Basis(mesh, ElementTetP2(), intorder=2)
    sq = stress_at_quadrature(b, u, E, NU)
    sn = stress_at_nodes(mesh, u, E, NU)
    # integrals of sigma_xx + sigma_yy (= sigma_r + sigma_t) over the body agree
    vol_q = np.sum((sq[0] + sq[1]) * b.dx)
    nodal = (sn[0] + sn[1])[b.element_dofs]  # (10, ne) at the nodes
    # interpolate the nodal field and integrate it with the same rule
    vals = sum(nodal[a][:, None] * np.asarray(b.basis[a][0]) for a in range(10))
    vol_n = np.sum(vals * b.dx)
    assert vol_n == pytest.approx(vol_q, rel=0.01)
    assert abs(averaging_indicator(mesh, u, E, NU, ["bore"])["bore"]) < 0.05
