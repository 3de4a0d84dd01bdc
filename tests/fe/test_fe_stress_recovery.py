"""Nodal stress recovery at the assessed nodes against independent computations.

* ``fe.core.stress.stress_at_selected_nodes`` visits only the elements that share a node with
  the assessed groups.  References: the whole-mesh recovery (every element's nodal
  stress averaged over all elements at each node, then read at the assessed nodes; the
  two differ only in the order of the additions of each average, a few ulp, so 1e-12
  relative to the largest stress catches any missing or extra element and any wrong
  node mapping), and scikit-fem's own ``CellBasis`` with the element nodes as quadrature
  points, grad u by ``np.einsum``, Hooke's law and the average (the same floating-point
  operations in the same order: bit for bit).
* The UR M53 averaging check and the recovery ratios against the same check on every
  element.
* CalculiX's C3D10 recovery (tests/helpers/calculix_recovery.py: linear extrapolation from the
  4 integration points) against a closed form and CalculiX's tabulated coefficients;
  fe-crank's recovery must equal it on straight-sided elements and differ from it on
  curved ones.

Real gmsh mesh with real fillets, real scikit-fem solves (the FE stage's unit cases).
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.calculix_recovery import GAUSS_A, GAUSS_B, calculix_recovery
from skfem import Basis, ElementTetP2, MeshTet, MeshTet2
from skfem.assembly import Dofs

from fe_crank.assess import assessed_groups, unit_stresses
from fe_crank.assess.recovery import recovery_ratios
from fe_crank.assess.stress import von_mises as vm_nodes
from fe_crank.fe.core.forms import lame_parameters
from fe_crank.fe.core.stress import (
    averaging_indicator,
    element_nodal_stress,
    elements_of_nodes,
    node_gradients,
    stress_at_nodes,
    stress_at_quadrature,
    stress_at_selected_nodes,
    von_mises,
)

REL = 1e-12
E, NU = 210e9, 0.3


def _full(filleted_throw, case):
    m = filleted_throw.material
    return stress_at_nodes(
        filleted_throw.mesh,
        filleted_throw.displacement(case),
        m.youngs_modulus,
        m.poisson_ratio,
        dofs=filleted_throw.system.basis.dofs,
    )


@pytest.mark.heavy
def test_selected_nodes_equal_the_whole_mesh_average(filleted_throw):
    groups = assessed_groups(filleted_throw)
    assert {"crankpin_fillet_1", "journal_fillet_2"} <= set(groups)
    ids = np.unique(np.concatenate(list(groups.values())))
    m = filleted_throw.material
    cases = list(filleted_throw.cases)
    part = stress_at_selected_nodes(
        filleted_throw.mesh,
        [filleted_throw.displacement(c) for c in cases],
        m.youngs_modulus,
        m.poisson_ratio,
        ids,
        dofs=filleted_throw.system.basis.dofs,
        chunk=97,
    )  # many chunks
    for j, c in enumerate(cases):
        ref = _full(filleted_throw, c)[:, ids]
        assert np.abs(part[j] - ref).max() <= REL * np.abs(ref).max(), c
    # the assessment's unit stresses are the restricted ones: same numbers
    us = unit_stresses(filleted_throw)
    for j, c in enumerate(us.cases):
        ref = _full(filleted_throw, c)[:, us.node_ids]
        assert np.abs(us.stress[j] - ref).max() <= REL * np.abs(ref).max(), c


@pytest.mark.heavy
def test_restriction_visits_fewer_elements_but_all_neighbours(filleted_throw):
    """Every element that has an assessed node is visited; on this throw that is a minority."""
    groups = {k: v for k, v in assessed_groups(filleted_throw).items() if "fillet" in k}
    ids = np.unique(np.concatenate(list(groups.values())))
    ed = filleted_throw.system.basis.element_dofs
    els = elements_of_nodes(ed, ids, filleted_throw.points.shape[1])
    brute = [e for e in range(ed.shape[1]) if np.intersect1d(ed[:, e], ids).size]
    np.testing.assert_array_equal(els, brute)
    assert els.size < 0.6 * ed.shape[1]


def _indicator_whole_mesh(filleted_throw, u, groups):
    """The M53 averaging check computed on every element (the reference)."""
    m = filleted_throw.material
    dofs = filleted_throw.system.basis.dofs
    s_el, nodes = element_nodal_stress(filleted_throw.mesh, u, m.youngs_modulus, m.poisson_ratio, dofs=dofs)
    n = u.size // 3
    cnt = np.bincount(nodes.ravel(), minlength=n)
    avg = np.stack([np.bincount(nodes.ravel(), s_el[k].ravel(), minlength=n) for k in range(6)]) / np.maximum(cnt, 1)
    vm_avg = von_mises(avg)
    vm_max = np.zeros(n)
    np.maximum.at(vm_max, nodes.ravel(), von_mises(s_el).ravel())
    out = {}
    for g in groups:
        fn = dofs.get_facet_dofs(filleted_throw.mesh.boundaries[g]).all()
        i = fn[np.argmax(vm_avg[fn])]
        out[g] = (vm_max[i] - vm_avg[i]) / vm_avg[i]
    return out


@pytest.mark.heavy
def test_averaging_indicator_equals_the_whole_mesh_check(filleted_throw):
    fillets = ["crankpin_fillet_1", "crankpin_fillet_2", "journal_fillet_1", "journal_fillet_2"]
    u = filleted_throw.combine({"pin_y": 1e4, "torque": 300.0, "centrifugal": 1e4})
    m = filleted_throw.material
    got = averaging_indicator(
        filleted_throw.mesh, u, m.youngs_modulus, m.poisson_ratio, fillets, dofs=filleted_throw.system.basis.dofs
    )
    ref = _indicator_whole_mesh(filleted_throw, u, fillets)
    for g in fillets:
        # the indicator is a difference of two stresses of a similar size: compare it with an
        # absolute 1e-10 (the stresses agree to 1e-12 relative; their difference is ~1e-2 of them)
        assert got[g] == pytest.approx(ref[g], abs=1e-10), g


@pytest.mark.heavy
def test_recovery_ratios_equal_the_whole_mesh_ratios(filleted_throw):
    groups = {k: v for k, v in assessed_groups(filleted_throw).items() if "fillet" in k}
    got = recovery_ratios(filleted_throw, groups)
    m = filleted_throw.material
    basis = filleted_throw.system.basis
    ref = {}
    for case in ("pin_y", "torque"):
        u = filleted_throw.displacement(case)
        nodal = _full(filleted_throw, case)
        quad = stress_at_quadrature(basis, u, m.youngs_modulus, m.poisson_ratio)
        for g, nodes in groups.items():
            els = np.unique(filleted_throw.mesh.f2t[0, filleted_throw.mesh.boundaries[g]])
            q = vm_nodes(quad[:, els].reshape(6, -1)[None])[0].max()
            n = vm_nodes(nodal[:, nodes][None])[0].max()
            ref[g] = max(ref.get(g, 0.0), n / q)
    assert set(got) == set(ref)
    for g in ref:
        assert got[g] == pytest.approx(ref[g], rel=REL), g


def _reference_nodal_stress(filleted_throw, u, nodes):
    """Average over every element sharing each node of the element's stress there, with
    scikit-fem's CellBasis (quadrature points = the element's nodes) and np.einsum."""
    mesh, dofs = filleted_throw.mesh, filleted_throw.system.basis.dofs
    e = ElementTetP2()
    X = np.asarray(e.doflocs, float).T
    els = elements_of_nodes(dofs.element_dofs, nodes, filleted_throw.points.shape[1])
    nb = Basis(mesh, e, quadrature=(X, np.full(X.shape[1], 0.1)), elements=els, dofs=dofs, disable_doflocs=True)
    G = np.stack([b[0].grad for b in nb.basis])  # (10, 3, ne, 10)
    ed = nb.element_dofs
    H = np.einsum("aei,ajeq->ijeq", u.reshape(-1, 3)[ed], G)
    eps = 0.5 * (H + H.transpose(1, 0, 2, 3))
    lam, mu = lame_parameters(filleted_throw.material.youngs_modulus, filleted_throw.material.poisson_ratio)
    tr = eps[0, 0] + eps[1, 1] + eps[2, 2]
    s = np.stack(
        [
            2 * mu * eps[i, j] + (lam * tr if i == j else 0.0)
            for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0))
        ]
    )  # (6, ne, 10)
    local = np.full(filleted_throw.points.shape[1], -1)
    local[nodes] = np.arange(nodes.size)
    loc = local[ed.T]
    keep = loc >= 0
    count = np.bincount(loc[keep], minlength=nodes.size)
    return np.stack([np.bincount(loc[keep], s[k][keep], minlength=nodes.size) for k in range(6)]) / count


@pytest.mark.heavy
def test_node_gradients_are_scikit_fems_basis_gradients(filleted_throw):
    mesh, dofs = filleted_throw.mesh, filleted_throw.system.basis.dofs
    e = ElementTetP2()
    X = np.asarray(e.doflocs, float).T
    els = np.arange(0, mesh.t.shape[1], 3)
    idx, G, ed = next(node_gradients(mesh, dofs, chunk=10**9, elements=els))
    nb = Basis(mesh, e, quadrature=(X, np.full(X.shape[1], 0.1)), elements=els, dofs=dofs, disable_doflocs=True)
    np.testing.assert_array_equal(idx, els)
    np.testing.assert_array_equal(ed, nb.element_dofs)
    assert np.array_equal(G, np.stack([b[0].grad for b in nb.basis]))


@pytest.mark.heavy
def test_selected_nodal_stress_equals_the_plain_computation_bitwise(filleted_throw):
    groups = assessed_groups(filleted_throw)
    ids = np.unique(np.concatenate(list(groups.values())))
    m = filleted_throw.material
    cases = list(filleted_throw.cases)
    got = stress_at_selected_nodes(
        filleted_throw.mesh,
        [filleted_throw.displacement(c) for c in cases],
        m.youngs_modulus,
        m.poisson_ratio,
        ids,
        dofs=filleted_throw.system.basis.dofs,
    )
    for j, c in enumerate(cases):
        ref = _reference_nodal_stress(filleted_throw, filleted_throw.displacement(c), ids)
        assert np.array_equal(got[j], ref), c


@pytest.mark.heavy
def test_recovery_ratios_from_the_unit_stresses_equal_their_own_recovery(filleted_throw):
    groups = assessed_groups(filleted_throw)
    boundary = {k: v for k, v in groups.items() if "fillet" in k}
    us = unit_stresses(filleted_throw, groups)
    own = recovery_ratios(filleted_throw, boundary)
    read = recovery_ratios(filleted_throw, boundary, unit=us)
    assert set(own) == set(read) and own
    for g in own:
        assert read[g] == pytest.approx(own[g], rel=1e-12), g


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


def test_calculix_recovery_of_a_linear_stress_is_exact():
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


def test_calculix_recovery_equals_fe_crank_on_straight_elements_and_differs_on_curved():
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
