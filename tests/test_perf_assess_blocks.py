"""The assessment's block-wise fast paths against independent plain computations.

* nodal stresses at selected nodes (``fe.stress.stress_at_selected_nodes``: gradients from
  one inverse Jacobian per chunk, the stress only at the averaged (element, node) pairs)
  against scikit-fem's own ``CellBasis`` with the nodes as quadrature points, grad u by
  ``np.einsum``, Hooke's law and the average over every element at each node.  Both make
  the same floating-point operations in the same order, so they must agree bit for bit;
  a missing element, a wrong node or a transposed gradient changes the values at O(1);
* von Mises of a path in component planes and the first maximum found by comparison
  against the plain formula and ``argmax``: the same operations, bit for bit;
* the history planes against ``stress_history`` (a matrix product: equal to round-off,
  1e-14 of the largest value, far below any wrong case or node, which moves it by O(1));
* the recovery check reading the unit stresses against its own recovery;
* ``assess_group`` in blocks of 128 nodes against one block holding every node;
* the overspeed peak evaluated where it can occur (``assess.peak``) against every node.

Real gmsh mesh with real fillets, real scikit-fem solves.
"""

from __future__ import annotations

import numpy as np
import pytest
from skfem import Basis, ElementTetP2
from verification_meshes import Steel, simple_throw

from fe_crank.assess import assessed_groups, unit_stresses
from fe_crank.assess.fatigue import max_and_first
from fe_crank.assess.group import assess_group, first_extreme
from fe_crank.assess.peak import group_peak, max_over_cycle, peak_bound
from fe_crank.assess.recovery import recovery_ratios
from fe_crank.assess.stress import von_mises, von_mises_planes
from fe_crank.assess.superpose import iter_planes, load_coefficients, stress_history
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.forms import lame_parameters
from fe_crank.fe.stress import elements_of_nodes, node_gradients, stress_at_selected_nodes
from fe_crank.io.material import load_material


@pytest.fixture(scope="module")
def units():
    mesh = simple_throw(size=0.012, fillet=0.004, fillet_size=0.004)
    cases = ("centrifugal", "pin_x", "pin_y", "pin_-x", "pin_-y", "torque")
    return solve_unit_cases(mesh, Steel(), FeOptions(solver="superlu", cases=cases))


def _reference_nodal_stress(units, u, nodes):
    """Average over every element sharing each node of the element's stress there, with
    scikit-fem's CellBasis (quadrature points = the element's nodes) and np.einsum."""
    mesh, dofs = units.mesh, units.system.basis.dofs
    e = ElementTetP2()
    X = np.asarray(e.doflocs, float).T
    els = elements_of_nodes(dofs.element_dofs, nodes, units.points.shape[1])
    nb = Basis(mesh, e, quadrature=(X, np.full(X.shape[1], 0.1)), elements=els, dofs=dofs, disable_doflocs=True)
    G = np.stack([b[0].grad for b in nb.basis])  # (10, 3, ne, 10)
    ed = nb.element_dofs
    H = np.einsum("aei,ajeq->ijeq", u.reshape(-1, 3)[ed], G)
    eps = 0.5 * (H + H.transpose(1, 0, 2, 3))
    lam, mu = lame_parameters(units.material.youngs_modulus, units.material.poisson_ratio)
    tr = eps[0, 0] + eps[1, 1] + eps[2, 2]
    s = np.stack(
        [
            2 * mu * eps[i, j] + (lam * tr if i == j else 0.0)
            for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0))
        ]
    )  # (6, ne, 10)
    local = np.full(units.points.shape[1], -1)
    local[nodes] = np.arange(nodes.size)
    loc = local[ed.T]
    keep = loc >= 0
    count = np.bincount(loc[keep], minlength=nodes.size)
    return np.stack([np.bincount(loc[keep], s[k][keep], minlength=nodes.size) for k in range(6)]) / count


def test_node_gradients_are_scikit_fems_basis_gradients(units):
    mesh, dofs = units.mesh, units.system.basis.dofs
    e = ElementTetP2()
    X = np.asarray(e.doflocs, float).T
    els = np.arange(0, mesh.t.shape[1], 3)
    idx, G, ed = next(node_gradients(mesh, dofs, chunk=10**9, elements=els))
    nb = Basis(mesh, e, quadrature=(X, np.full(X.shape[1], 0.1)), elements=els, dofs=dofs, disable_doflocs=True)
    np.testing.assert_array_equal(idx, els)
    np.testing.assert_array_equal(ed, nb.element_dofs)
    assert np.array_equal(G, np.stack([b[0].grad for b in nb.basis]))


def test_selected_nodal_stress_equals_the_plain_computation_bitwise(units):
    groups = assessed_groups(units)
    ids = np.unique(np.concatenate(list(groups.values())))
    m = units.material
    cases = list(units.cases)
    got = stress_at_selected_nodes(
        units.mesh,
        [units.displacement(c) for c in cases],
        m.youngs_modulus,
        m.poisson_ratio,
        ids,
        dofs=units.system.basis.dofs,
    )
    for j, c in enumerate(cases):
        ref = _reference_nodal_stress(units, units.displacement(c), ids)
        assert np.array_equal(got[j], ref), c


def test_von_mises_planes_is_the_plain_formula_bitwise():
    rng = np.random.default_rng(7)
    planes = rng.normal(size=(6, 50, 9)) * 1e8
    hist = planes.transpose(1, 0, 2)  # (n_t, 6, n)
    centre = rng.normal(size=(6, 9)) * 1e8
    assert np.array_equal(von_mises_planes(planes), von_mises(hist))
    assert np.array_equal(von_mises_planes(planes, centre), von_mises(hist - centre[None]))
    buf = np.empty(planes.shape)
    for c in (None, centre, None):  # a reused scratch array
        ref = von_mises(hist) if c is None else von_mises(hist - c[None])
        assert np.array_equal(von_mises_planes(planes, c, buf), ref)
    # a non-contiguous view of the planes gives the same
    assert np.array_equal(von_mises_planes(planes[:, ::2]), von_mises(hist[::2]))
    # hand value: uniaxial 100 MPa about a uniaxial 40 MPa centre is 60 MPa; pure shear
    # 50 MPa about zero is sqrt(3) 50 MPa
    p = np.zeros((6, 1, 2))
    p[0, 0, 0], p[3, 0, 1] = 100e6, 50e6
    c = np.zeros((6, 2))
    c[0, 0] = 40e6
    assert von_mises_planes(p, c)[0, 0] == 60e6
    assert von_mises_planes(p)[0, 1] == pytest.approx(np.sqrt(3.0) * 50e6, rel=1e-15)


def test_max_and_first_is_max_and_argmax():
    rng = np.random.default_rng(3)
    d = np.round(rng.random((40, 30)) * 4)  # many exact ties
    d[5, 7] = np.nan
    r, first = max_and_first(d)
    assert np.array_equal(r, d.max(axis=0), equal_nan=True)
    np.testing.assert_array_equal(first, d.argmax(axis=0))
    assert first[7] == 5  # a NaN column: its first NaN, as argmax


def _coefficients(units, us, n=72):
    th = np.linspace(0.0, 4 * np.pi, n, endpoint=False)
    pin = np.column_stack([3e3 * np.sin(th), 2e4 * np.cos(th) + 5e3])
    return load_coefficients(pin, 400.0 * np.sin(2 * th), 300.0, cases=us.cases, torque_mz=us.torque_mz)


def test_history_planes_equal_the_stress_history(units):
    us = unit_stresses(units)
    co = _coefficients(units, us)
    nodes = us.groups["journal_fillet_1"]
    ref = stress_history(us, co, nodes)
    got, seen = [], []
    for idx, planes in iter_planes(us, co, nodes, block=50):
        got.append(planes.transpose(1, 0, 2))
        seen.append(idx)
    np.testing.assert_array_equal(np.concatenate(seen), nodes)
    got = np.concatenate(got, axis=-1)
    assert np.abs(got - ref).max() <= 1e-14 * np.abs(ref).max()


def test_recovery_ratios_from_the_unit_stresses_equal_their_own_recovery(units):
    groups = assessed_groups(units)
    boundary = {k: v for k, v in groups.items() if "fillet" in k}
    us = unit_stresses(units, groups)
    own = recovery_ratios(units, boundary)
    read = recovery_ratios(units, boundary, unit=us)
    assert set(own) == set(read) and own
    for g in own:
        assert read[g] == pytest.approx(own[g], rel=1e-12), g


def test_assess_group_does_not_depend_on_the_block(units):
    """128-node blocks against one block of every node: the per-node results to 1e-12
    (the history products may differ in the last bit between block sizes)."""
    us = unit_stresses(units)
    co = _coefficients(units, us)
    theta = np.linspace(0.0, 4 * np.pi, co.shape[0], endpoint=False)
    mat = load_material("42CrMo4")
    kw = dict(crank_radius=0.045, overspeed=360.0, overspeed_coefficients=1.44 * co)
    for g in ("journal_fillet_1", "crankpin_fillet_2"):
        a = assess_group(us, g, co, theta, mat, **kw)
        b = assess_group(us, g, co, theta, mat, chunk=10**6, **kw)
        assert a.max_von_mises == b.max_von_mises and a.max_von_mises_overspeed == b.max_von_mises_overspeed
        for k in ("max_von_mises", "amplitude", "mean", "fatigue_safety", "gough_pollard_safety"):
            x, y = a.fields[k], b.fields[k]
            fin = np.isfinite(y)
            np.testing.assert_array_equal(np.isfinite(x), fin)
            assert np.abs(x[fin] - y[fin]).max() <= 1e-12 * np.abs(y[fin]).max(), (g, k)


def test_group_peak_bound_holds_and_the_extreme_is_the_full_evaluations(units):
    """peak.py: B >= every node's peak (the seminorm's triangle inequality), and the
    pruned evaluation finds the same largest peak, first node of its tie band and first
    angle as evaluating every node, bit for bit (the evaluated nodes' values are the same
    operations)."""
    us = unit_stresses(units)
    co = 1.44 * _coefficients(units, us)
    for g in ("journal_fillet_1", "crankpin_fillet_2", "counterweight_1"):
        nodes = us.groups.get(g)
        if nodes is None:
            continue
        full, full_arg = max_over_cycle(von_mises(stress_history(us, co, nodes)))
        bound = peak_bound(us, co, nodes)
        assert np.all(full <= bound * (1 + 1e-12)), g
        pos, peak, arg = group_peak(us, co, nodes)
        assert pos.size < nodes.size, g  # it did prune
        k_full = int(first_extreme(full, "max"))
        k = int(first_extreme(peak, "max"))
        assert pos[k] == k_full and peak[k] == full[k_full] and arg[k] == full_arg[k_full], g


def test_peak_bound_hand_value():
    """Two unit states, uniaxial 100 MPa and pure shear 50 MPa (vM 100 and 86.60 MPa),
    with coefficients (1, 1) and (1, -2): B = max(100 + 86.60, 100 + 173.21) = 273.21 MPa;
    the true peaks are vM(100, shear 50) = sqrt(100^2 + 3 50^2) = 132.29 MPa and
    vM(100, shear -100) = sqrt(100^2 + 3 100^2) = 200 MPa."""
    from fe_crank.assess.superpose import UnitStresses

    s = np.zeros((2, 6, 1))
    s[0, 0, 0], s[1, 3, 0] = 100e6, 50e6
    unit = UnitStresses(stress=s, points=np.zeros((3, 1)), cases=("a", "b"))
    co = np.array([[1.0, 1.0], [1.0, -2.0]])
    assert peak_bound(unit, co, np.array([0]))[0] == pytest.approx(100e6 + 2 * np.sqrt(3) * 50e6, rel=1e-15)
    pos, peak, arg = group_peak(unit, co, np.array([0]))
    assert peak[0] == pytest.approx(200e6, rel=1e-15) and arg[0] == 1
