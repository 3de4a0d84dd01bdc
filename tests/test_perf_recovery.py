"""Stress recovery restricted to the assessed nodes equals the whole-mesh recovery.

The restricted routines (``stress_at_selected_nodes``, the restricted averaging check and
recovery ratios) visit only the elements that share a node with the assessed groups.
The reference here is the independent whole-mesh computation: every element's nodal
stress, averaged over all elements at each node, then read at the assessed nodes.
The two differ only in the order of the floating-point additions of each average
(at most ~10 terms of one sign-mixed sum), i.e. by a few ulp; 1e-12 relative to the
largest stress would catch any missing or extra element in an average (one element of
~10 changes an average by percent) and any wrong node mapping.
Real gmsh mesh with real fillets, real scikit-fem solves (the FE stage's unit cases).
"""

from __future__ import annotations

import numpy as np
import pytest
from verification_meshes import Steel, simple_throw

from fe_crank.assess import assessed_groups, unit_stresses
from fe_crank.assess.recovery import recovery_ratios
from fe_crank.assess.stress import von_mises as vm_nodes
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.stress import (
    averaging_indicator,
    element_nodal_stress,
    elements_of_nodes,
    stress_at_nodes,
    stress_at_quadrature,
    stress_at_selected_nodes,
    von_mises,
)

REL = 1e-12


@pytest.fixture(scope="module")
def units():
    mesh = simple_throw(size=0.012, fillet=0.004, fillet_size=0.004)
    cases = ("centrifugal", "pin_x", "pin_y", "pin_-x", "pin_-y", "torque")
    return solve_unit_cases(mesh, Steel(), FeOptions(solver="superlu", cases=cases))


def _full(units, case):
    m = units.material
    return stress_at_nodes(
        units.mesh, units.displacement(case), m.youngs_modulus, m.poisson_ratio, dofs=units.system.basis.dofs
    )


def test_selected_nodes_equal_the_whole_mesh_average(units):
    groups = assessed_groups(units)
    assert {"crankpin_fillet_1", "journal_fillet_2"} <= set(groups)
    ids = np.unique(np.concatenate(list(groups.values())))
    m = units.material
    cases = list(units.cases)
    part = stress_at_selected_nodes(
        units.mesh,
        [units.displacement(c) for c in cases],
        m.youngs_modulus,
        m.poisson_ratio,
        ids,
        dofs=units.system.basis.dofs,
        chunk=97,
    )  # many chunks
    for j, c in enumerate(cases):
        ref = _full(units, c)[:, ids]
        assert np.abs(part[j] - ref).max() <= REL * np.abs(ref).max(), c
    # the assessment's unit stresses are the restricted ones: same numbers
    us = unit_stresses(units)
    for j, c in enumerate(us.cases):
        ref = _full(units, c)[:, us.node_ids]
        assert np.abs(us.stress[j] - ref).max() <= REL * np.abs(ref).max(), c


def test_restriction_visits_fewer_elements_but_all_neighbours(units):
    """Every element that has an assessed node is visited; on this throw that is a minority."""
    groups = {k: v for k, v in assessed_groups(units).items() if "fillet" in k}
    ids = np.unique(np.concatenate(list(groups.values())))
    ed = units.system.basis.element_dofs
    els = elements_of_nodes(ed, ids, units.points.shape[1])
    brute = [e for e in range(ed.shape[1]) if np.intersect1d(ed[:, e], ids).size]
    np.testing.assert_array_equal(els, brute)
    assert els.size < 0.6 * ed.shape[1]


def _indicator_whole_mesh(units, u, groups):
    """The M53 averaging check computed on every element (the reference)."""
    m = units.material
    dofs = units.system.basis.dofs
    s_el, nodes = element_nodal_stress(units.mesh, u, m.youngs_modulus, m.poisson_ratio, dofs=dofs)
    n = u.size // 3
    cnt = np.bincount(nodes.ravel(), minlength=n)
    avg = np.stack([np.bincount(nodes.ravel(), s_el[k].ravel(), minlength=n) for k in range(6)]) / np.maximum(cnt, 1)
    vm_avg = von_mises(avg)
    vm_max = np.zeros(n)
    np.maximum.at(vm_max, nodes.ravel(), von_mises(s_el).ravel())
    out = {}
    for g in groups:
        fn = dofs.get_facet_dofs(units.mesh.boundaries[g]).all()
        i = fn[np.argmax(vm_avg[fn])]
        out[g] = (vm_max[i] - vm_avg[i]) / vm_avg[i]
    return out


def test_averaging_indicator_equals_the_whole_mesh_check(units):
    fillets = ["crankpin_fillet_1", "crankpin_fillet_2", "journal_fillet_1", "journal_fillet_2"]
    u = units.combine({"pin_y": 1e4, "torque": 300.0, "centrifugal": 1e4})
    m = units.material
    got = averaging_indicator(units.mesh, u, m.youngs_modulus, m.poisson_ratio, fillets, dofs=units.system.basis.dofs)
    ref = _indicator_whole_mesh(units, u, fillets)
    for g in fillets:
        # the indicator is a difference of two stresses of a similar size: compare it with an
        # absolute 1e-10 (the stresses agree to 1e-12 relative; their difference is ~1e-2 of them)
        assert got[g] == pytest.approx(ref[g], abs=1e-10), g


def test_recovery_ratios_equal_the_whole_mesh_ratios(units):
    groups = {k: v for k, v in assessed_groups(units).items() if "fillet" in k}
    got = recovery_ratios(units, groups)
    m = units.material
    basis = units.system.basis
    ref = {}
    for case in ("pin_y", "torque"):
        u = units.displacement(case)
        nodal = _full(units, case)
        quad = stress_at_quadrature(basis, u, m.youngs_modulus, m.poisson_ratio)
        for g, nodes in groups.items():
            els = np.unique(units.mesh.f2t[0, units.mesh.boundaries[g]])
            q = vm_nodes(quad[:, els].reshape(6, -1)[None])[0].max()
            n = vm_nodes(nodal[:, nodes][None])[0].max()
            ref[g] = max(ref.get(g, 0.0), n / q)
    assert set(got) == set(ref)
    for g in ref:
        assert got[g] == pytest.approx(ref[g], rel=REL), g
