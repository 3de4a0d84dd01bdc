"""Unit cases solved on the symmetry components of a mirror-symmetric mesh (fe.core.symmetric).

The independent method is the full model on the same mesh (``FeOptions(symmetry=False)``):
both are direct solves of the same Galerkin equations, so they agree to the round-off of
two factorisations (measured ~1e-12 here); a wrong plane condition, load weight or
reflection sign changes the answer at O(1), a wrong rigid-body correction at the size of
the rigid motion (comparable to u).  Hence 1e-10 relative in displacement and in the
averaged nodal stress.
"""

from __future__ import annotations

import logging

import numpy as np
import pytest
from helpers.symmetric_meshes import mirrored_throw
from helpers.verification_meshes import Steel, as_throw_mesh, simple_throw

from fe_crank.errors import InputError, SolverError
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.core.supports import rigid_body_modes
from fe_crank.fe.core.symmetric import component, mode_characters, reflect, verify_mirror
from fe_crank.fe.input import parse_fe

REL = 1e-10


@pytest.fixture(scope="module", params=[(0, 2), (0,), (2,)], ids=["x_and_z", "x_only", "z_only"])
def pair(request):
    throw = mirrored_throw(request.param, size=0.014)
    sym = solve_unit_cases(throw, Steel())
    full = solve_unit_cases(throw, Steel(), FeOptions(symmetry=False))
    return request.param, throw, sym, full


def test_symmetric_solve_equals_full_solve(pair):
    planes, throw, sym, full = pair
    k = len(planes)
    assert f"solved on {2**k} symmetry components of the {'half' if k == 1 else 'quarter'}" in sym.solver_description
    assert "symmetry" not in full.solver_description
    assert sym.n_dof == full.n_dof
    assert set(sym.cases) == set(full.cases)
    for name in full.cases:
        us, uf = sym.displacement(name), full.displacement(name)
        assert np.abs(us - uf).max() <= REL * np.abs(uf).max(), name
        ss, sf = sym.stress_at_nodes(us), full.stress_at_nodes(uf)
        assert np.abs(ss - sf).max() <= REL * np.abs(sf).max(), name
        assert sym.cases[name].equilibrium_error < 1e-8
        for who, r in full.cases[name].reactions.items():
            if who != "point_constraints":  # the determinate reactions are those of the load
                np.testing.assert_allclose(
                    sym.cases[name].reactions[who], r, rtol=0, atol=1e-9 * np.abs(full.cases[name].applied).max()
                )


def test_mirror_is_exact_and_names_map(pair):
    planes, throw, sym, _ = pair
    basis = sym.system.basis
    mirror, why = verify_mirror(basis.doflocs, basis.element_dofs, planes)
    assert mirror is not None, why
    x = basis.doflocs
    tol = 1e-15 * np.ptp(x, axis=1).max()  # round-off of the dof locations (found: 2e-17 of the size)
    for a in planes:
        p = mirror.perm[a]
        y = x[:, p]
        assert np.abs(y[a] + x[a]).max() <= tol  # the image of a node is its mirror point
        others = [c for c in range(3) if c != a]
        assert np.abs(y[others] - x[others]).max() <= tol
        assert np.abs(x[a, mirror.on_plane[a]]).max() <= tol
        assert np.all(p[p] == np.arange(p.size))
    if 2 in planes:  # the z mirror swaps journal_1 and journal_2: equal areas (same facets mirrored)
        m = throw.mesh
        assert m.boundaries["journal_1"].size == m.boundaries["journal_2"].size


def test_symmetric_load_has_no_antisymmetric_component(pair):
    """Closed form: v(x) = (x, y, 0) (the centrifugal pattern) is symmetric about x = 0 and
    z = 0 (v(S x) = S v(x)), so every other component is zero and the symmetric one is v;
    the uniform field e_z is antisymmetric about z = 0 and symmetric about x = 0."""
    planes, _, sym, _ = pair
    basis = sym.system.basis
    mirror, _ = verify_mirror(basis.doflocs, basis.element_dofs, planes)
    x = basis.doflocs
    tol = 1e-15 * np.ptp(x, axis=1).max()  # round-off of the dof locations (v is a position)
    v = np.stack([x[0], x[1], np.zeros_like(x[0])], axis=1).ravel()
    ez = np.zeros((x.shape[1], 3))
    ez[:, 2] = 1.0
    ez = ez.ravel()
    total = np.zeros_like(v)
    for chars in mirror.characters:
        c = component(v, mirror, chars)
        total += c
        if all(e == 1 for e in chars.values()):
            np.testing.assert_allclose(c, v, rtol=0, atol=tol)
        else:
            assert np.abs(c).max() <= tol
        expect_ez = all(e == (-1 if a == 2 else 1) for a, e in chars.items())
        np.testing.assert_array_equal(component(ez, mirror, chars), ez if expect_ez else 0.0 * ez)
    np.testing.assert_allclose(total, v, rtol=0, atol=tol)


def test_rigid_mode_characters_match_the_reflections(pair):
    """The hand table of ``mode_characters`` against reflecting the modes themselves: R B_m = chi_m B_m."""
    planes, _, sym, _ = pair
    basis = sym.system.basis
    mirror, _ = verify_mirror(basis.doflocs, basis.element_dofs, planes)
    B = rigid_body_modes(basis.doflocs)
    chars = mode_characters(mirror.axes)
    for j, a in enumerate(mirror.axes):
        s = np.ones(3)
        s[a] = -1.0
        RB = reflect(B, mirror.perm[a], s)
        for m in range(6):
            np.testing.assert_allclose(RB[:, m], chars[m, j] * B[:, m], atol=1e-15)
    # translations along x (tx) are antisymmetric about x = 0; rotations about z (rz) too
    if 0 in mirror.axes:
        assert chars[0, mirror.axes.index(0)] == -1 and chars[5, mirror.axes.index(0)] == -1


def test_non_symmetric_mesh_falls_back_and_says_why(caplog):
    throw = simple_throw(size=0.014)  # meshed whole: not an exact mirror image
    with caplog.at_level(logging.WARNING, logger="fe_crank.fe.core.symmetric"):
        sol = solve_unit_cases(as_throw_mesh(throw, symmetry=(0, 2)), Steel(), FeOptions(cases=("pin_y", "torque")))
    assert "symmetry" not in sol.solver_description
    assert "not" in caplog.text and "solving the full model" in caplog.text
    assert sol.cases["pin_y"].equilibrium_error < 1e-8


def test_a_moved_node_breaks_the_mirror():
    throw = mirrored_throw((0,), size=0.02)
    from skfem import Basis, ElementTetP2

    basis = Basis(throw.mesh, ElementTetP2())
    x = basis.doflocs.copy()
    i = int(np.argmax(x[0]))
    x[1, i] += 1e-7  # 1e-7 m: far above round-off, far below an element
    mirror, why = verify_mirror(x, basis.element_dofs, (0,))
    assert mirror is None and "no mirror image" in why
    mirror, why = verify_mirror(basis.doflocs, basis.element_dofs, (0,))
    assert mirror is not None
    # one element left out: its mirror image has no image any more
    mirror, why = verify_mirror(basis.doflocs, basis.element_dofs[:, 1:], (0,))
    assert mirror is None and "elements do not map" in why


def test_foundation_support_is_solved_on_the_full_model():
    throw = mirrored_throw((0, 2), size=0.02)
    sol = solve_unit_cases(
        throw,
        Steel(),
        FeOptions(support="foundation", bearing_stiffness=4.2e12, cases=("pin_-y", "centrifugal", "torque")),
    )
    assert "symmetry" not in sol.solver_description


def test_free_releases_every_component():
    throw = mirrored_throw((0, 2), size=0.02)
    sol = solve_unit_cases(throw, Steel(), FeOptions(cases=("pin_y", "centrifugal", "torque")))
    f = np.zeros(3 * sol.system.basis.N)
    sol.system.factorisation.free()
    assert sol.system.factorisation.nnz > 0
    with pytest.raises(SolverError, match="released"):
        sol.system.solve(f)


def test_symmetry_switch_is_read_from_the_fe_section():
    assert parse_fe({"symmetry": False}, "case.toml").symmetry is False
    assert parse_fe({}, "case.toml").symmetry is True
    with pytest.raises(InputError) as err:  # a string is refused, not read as a boolean
        parse_fe({"symmetry": "no"}, "case.toml")
    assert err.value.key == "fe.symmetry" and "case.toml" in str(err.value)


def test_one_shared_analysis_equals_separate_factorisations(monkeypatch):
    """The components on one PARDISO handle (one analysis, maxfct = 4) against each component
    factorised on its own (phase 12 each): the same factors, so the same answer to round-off."""
    from fe_crank.fe.core import symmetric

    throw = mirrored_throw((0, 2), size=0.02)
    opts = FeOptions(cases=("pin_030", "centrifugal", "torque"))
    shared = solve_unit_cases(throw, Steel(), opts)
    assert shared.timings["analysis"] > 0
    monkeypatch.setattr(symmetric, "SHARE_ORDERING", False)
    own = solve_unit_cases(throw, Steel(), opts)
    for name in opts.cases:
        u0, u1 = shared.displacement(name), own.displacement(name)
        assert np.abs(u0 - u1).max() <= REL * np.abs(u1).max()
    shared.system.factorisation.free()
    own.system.factorisation.free()


@pytest.mark.parametrize("method", ["superlu", "cholmod"])
def test_other_direct_solvers_on_the_components(method):
    from fe_crank.fe.linalg.choice import cholmod_available

    if method == "cholmod" and not cholmod_available():
        pytest.skip("cholespy not installed")
    throw = mirrored_throw((0, 2), size=0.02)
    cases = ("pin_-y", "centrifugal", "torque")
    sym = solve_unit_cases(throw, Steel(), FeOptions(solver=method, cases=cases))
    full = solve_unit_cases(throw, Steel(), FeOptions(symmetry=False, cases=cases))
    assert "symmetry components" in sym.solver_description and sym.solver == method
    for name in cases:
        u0, u1 = sym.displacement(name), full.displacement(name)
        assert np.abs(u0 - u1).max() <= REL * np.abs(u1).max()


def test_a_load_symmetric_about_every_plane_factorises_its_component_alone():
    """The centrifugal load alone lies in the component symmetric about both planes (its parts
    in the other three are round-off): only that component is factorised and solved, and the
    displacement is the full model's; a pin load beside it needs every component."""
    throw = mirrored_throw((0, 2), size=0.02)
    spin = solve_unit_cases(throw, Steel(), FeOptions(cases=("centrifugal",)))
    assert spin.system.symmetric is not None and spin.system.symmetric.factorised == 1
    full = solve_unit_cases(throw, Steel(), FeOptions(symmetry=False, cases=("centrifugal",)))
    u0, u1 = spin.displacement("centrifugal"), full.displacement("centrifugal")
    assert np.abs(u0 - u1).max() <= REL * np.abs(u1).max()
    both = solve_unit_cases(throw, Steel(), FeOptions(cases=("pin_030", "centrifugal")))
    assert both.system.symmetric is not None and both.system.symmetric.factorised == 4
    for sol in (spin, full, both):
        sol.system.factorisation.free()
