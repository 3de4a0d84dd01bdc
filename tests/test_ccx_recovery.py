"""benchmarks/ccx_recovery.py: CalculiX's C3D10 nodal-stress recovery reproduced on a P2
field, the tool that explains the difference between fe-crank's and CalculiX's nodal
stresses (docs/performance.md, "fe-crank vs CalculiX on the same model").

Checked against a closed form (a linear stress field, recovered exactly by the linear
extrapolation), CalculiX's tabulated coefficients (``extrapolate.f``, array ``a4``) and
fe-crank's own recovery, which it must equal on straight-sided elements and differ from
on curved ones -- the claim the comparison rests on.
"""

import sys
from pathlib import Path

import numpy as np
from skfem import ElementTetP2, MeshTet, MeshTet2
from skfem.assembly import Dofs

from fe_crank.fe.stress import stress_at_selected_nodes

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from ccx_recovery import GAUSS_A, GAUSS_B, calculix_recovery

E, NU = 210e9, 0.3


def _mesh() -> MeshTet2:
    """Straight-sided P2 tetrahedra on a 2 x 1.5 x 1 box (24 elements, 75 nodes)."""
    return MeshTet2.from_mesh(MeshTet.init_tensor([0.0, 1.0, 2.0], [0.0, 1.5], [0.0, 0.7, 1.0]))


def test_extrapolation_coefficients_are_calculix_table():
    # linear fit through the 4-point rule (a at the own corner, b at the others):
    # L_k = ((1 - b) v_k - b sum_{j != k} v_j) / (a - b); CalculiX tabulates 1.92705 and
    # -0.30902 (5 digits): both must agree to their last digit (5e-6 catches a swapped a/b)
    assert abs((1.0 - GAUSS_B) / (GAUSS_A - GAUSS_B) - 1.92705) < 5e-6
    assert abs(-GAUSS_B / (GAUSS_A - GAUSS_B) + 0.30902) < 5e-6
    assert abs(GAUSS_A + 3.0 * GAUSS_B - 1.0) < 1e-15  # barycentric coordinates sum to 1


def test_linear_stress_recovered_exactly():
    # u = (x^2, x y, z^2 + y z): eps_xx = 2x, eps_yy = x, eps_zz = 2z + y, eps_xy = y/2,
    # eps_yz = (0 + z)/2 = z/2, eps_zx = 0; sigma = 2 mu eps + lam tr(eps) I, linear in x,
    # so the extrapolation from the integration points and the mid-edge means are exact
    # at every node; a wrong coefficient or mid-edge pair gives errors of the field's size
    m = _mesh()
    dofs = Dofs(m, ElementTetP2())
    x, y, z = m.doflocs
    u = np.stack([x**2, x * y, z**2 + y * z], axis=1).ravel()
    nodes = np.arange(m.doflocs.shape[1])
    s = calculix_recovery(m, dofs, E, NU, [u], nodes)[0]
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    exx, eyy, ezz, exy, eyz = 2 * x, x, 2 * z + y, y / 2, z / 2
    tr = exx + eyy + ezz
    expected = np.stack(
        [
            2 * mu * exx + lam * tr,
            2 * mu * eyy + lam * tr,
            2 * mu * ezz + lam * tr,
            2 * mu * exy,
            2 * mu * eyz,
            np.zeros_like(x),
        ]
    )
    assert np.abs(s - expected).max() < 1e-9 * np.abs(expected).max()


def test_equals_fe_crank_on_straight_elements_and_differs_on_curved():
    # any P2 field: on straight-sided tets the stress is linear per element, so both
    # recoveries give the same element values and the same mean (to round-off); moving
    # one interior mid-edge node by 5 % of the box curves the elements around that edge
    # and the two part (by far more than round-off)
    rng = np.random.default_rng(1)
    m = _mesh()
    nodes = np.arange(m.doflocs.shape[1])
    u = rng.standard_normal(3 * nodes.size) * 1e-4
    for curved in (False, True):
        P = np.array(m.doflocs)
        if curved:
            inner = np.flatnonzero(np.all((P > 1e-9) & (P < np.array([[2.0], [1.5], [1.0]]) - 1e-9), axis=0))
            mid = inner[inner >= m.nvertices][0]
            P[:, mid] += 0.05
        mesh = MeshTet2(P, np.asarray(m.dofs.element_dofs))
        dofs = Dofs(mesh, ElementTetP2())
        ccx = calculix_recovery(mesh, dofs, E, NU, [u], nodes)[0]
        fe = stress_at_selected_nodes(mesh, [u], E, NU, nodes, dofs=dofs)[0]
        rel = np.abs(ccx - fe).max() / np.abs(fe).max()
        if curved:
            assert rel > 1e-3
        else:
            assert rel < 1e-10
