"""Superposition of the FE stage's unit cases over the cycle equals a direct FE solve
with the combined load at the same crank angle (linear elasticity), to 1e-9 relative."""

from __future__ import annotations

import numpy as np
import pytest
from skfem import MeshTet, MeshTet2

import fe_crank.fe.unit_cases as fe
from fe_crank.assess import unit_stresses
from fe_crank.assess.superpose import combine, load_coefficients, stress_history
from fe_crank.fe.loads import centrifugal_load, face_torque_load, pin_pressure_load
from fe_crank.io.material import load_material

RADIUS, LENGTH = 0.02, 0.12


def _bar_throw():
    """A round bar standing in for a throw: journals at the ends, 'crankpin' in the middle."""
    m = MeshTet.init_tensor(np.linspace(-1, 1, 5), np.linspace(-1, 1, 5), np.linspace(0, 1, 13))
    x, y, z = m.p
    p = np.array([RADIUS * x * np.sqrt(1 - y**2 / 2), RADIUS * y * np.sqrt(1 - x**2 / 2), LENGTH * z])
    m2 = MeshTet2.from_mesh(MeshTet(p, m.t))
    eps = 1e-9
    lateral = lambda x: (x[2] > eps) & (x[2] < LENGTH - eps)
    return m2.with_boundaries(
        {
            "end_1": lambda x: np.abs(x[2]) < eps,
            "end_2": lambda x: np.abs(x[2] - LENGTH) < eps,
            "journal_1": lambda x: lateral(x) & (x[2] < LENGTH / 3),
            "journal_2": lambda x: lateral(x) & (x[2] > 2 * LENGTH / 3),
            "crankpin": lambda x: lateral(x) & (x[2] > LENGTH / 3) & (x[2] < 2 * LENGTH / 3),
        }
    )


@pytest.fixture(scope="module")
def solved():
    mesh = _bar_throw()
    mat = load_material("42CrMo4")
    units = fe.solve_unit_cases(mesh, mat, fe.FeOptions(solver="superlu"))
    return mesh, mat, units


def test_superposition_equals_direct_solve(solved):
    mesh, mat, units = solved
    assert units.cases["torque"].applied[5] == pytest.approx(-1.0)  # the FE stage's convention
    basis = units.system.basis
    nodes = np.unique(basis.get_dofs(facets=mesh.boundaries["crankpin"]).all())
    groups = {
        "crankpin_fillet_1": nodes,
        "journal_fillet_1": np.unique(basis.get_dofs(facets=mesh.boundaries["journal_1"]).all()),
    }
    unit = unit_stresses(units, groups)
    loads = {
        "centrifugal": centrifugal_load(basis, mat.density, 1.0),
        "torque": face_torque_load(basis, unit.torque_mz, boundary="end_1"),
    }
    for name, force in fe.PIN_FORCES.items():
        loads[name] = pin_pressure_load(basis, force)[0]
    omega = 300.0
    # a load history with every sign of F_x, F_y and the torque
    theta = np.deg2rad(np.arange(0, 720))
    pin = np.column_stack([8e3 * np.sin(theta) + 1e3, -2e4 * np.cos(theta / 2) + 3e3])
    torque = 400.0 * np.sin(theta) - 50.0
    coeffs = load_coefficients(pin, torque, omega, cases=unit.cases, sense=1, torque_mz=unit.torque_mz)
    hist = stress_history(unit, coeffs)
    for deg in (0, 37, 181, 400, 719):
        f = combine(np.stack([loads[c] for c in unit.cases]), coeffs[deg])[0]
        u = units.system.solve(f)
        direct = units.stress_at_nodes(u)[:, unit.node_ids]
        err = np.max(np.abs(hist[deg] - direct)) / np.max(np.abs(direct))
        assert err < 1e-9, (deg, err)


def test_coefficients_split_by_sign_and_torque_sense():
    pin = np.array([[3.0, -4.0], [-1.0, 2.0]])
    four = ("centrifugal", "pin_x", "pin_y", "pin_-x", "pin_-y", "torque")
    c = load_coefficients(pin, np.array([10.0, -5.0]), 2.0, sense=1, cases=four)
    # four axis directions: each component on the case whose arc is on its loaded side
    # FE torque case: M_z = -1 N m (sense of rotation of a sense +1 shaft) -> coefficient = torque_front
    np.testing.assert_allclose(c, [[4.0, 3.0, 0.0, 0.0, 4.0, 10.0], [4.0, 0.0, 2.0, 1.0, 0.0, -5.0]], atol=1e-12)
    c2 = load_coefficients(
        pin, np.array([10.0, -5.0]), 2.0, cases=("pin_x", "pin_y", "torque"), sense=-1, torque_mz=2.0
    )
    np.testing.assert_allclose(c2, [[3.0, -4.0, 5.0], [-1.0, 2.0, -2.5]], atol=1e-12)


def test_default_twelve_directions_bracket_every_force():
    """Default pin cases 30 deg apart: each force on the two directions that bracket it,
    non-negative weights whose resultant is the force (over a full turn of directions)."""
    from fe_crank.assess.superpose import UNIT_CASES
    from fe_crank.fe.pin_directions import pin_direction, unit_force

    ang = np.deg2rad(np.arange(0.0, 360.0, 0.7))
    pin = 1e4 * np.column_stack([np.cos(ang), np.sin(ang)])
    c = load_coefficients(pin, np.zeros(ang.size), 1.0)
    pins = [i for i, n in enumerate(UNIT_CASES) if pin_direction(n) is not None]
    assert len(pins) == 12
    w = c[:, pins]
    assert np.all(w >= 0.0) and np.all((w > 0).sum(axis=1) <= 2)
    E = np.array([unit_force(UNIT_CASES[i]) for i in pins])
    np.testing.assert_allclose(w @ E, pin, atol=1e-8)
    # the two cases used are the neighbours of the force direction
    for k, row in enumerate(w):
        used = [pin_direction(UNIT_CASES[pins[i]]) for i in np.nonzero(row)[0]]
        d = np.rad2deg(ang[k])
        assert all(min(abs(u - d), 360 - abs(u - d)) <= 30.0 + 1e-9 for u in used)


def test_pin_direction_sets_that_cannot_carry_a_force_are_refused():
    from fe_crank.fe.pin_directions import pin_case_weights

    with pytest.raises(ValueError, match="gap of 180"):
        pin_case_weights(np.array([[1.0, 1.0]]), ["pin_x", "pin_y", "pin_-y"])
    with pytest.raises(ValueError, match="only forces along it"):
        pin_case_weights(np.array([[1.0, 1.0]]), ["pin_y"])
    with pytest.raises(ValueError, match="parallel"):
        pin_case_weights(np.array([[1.0, 1.0]]), ["pin_y", "pin_-y"])
    with pytest.raises(ValueError, match="not pin unit cases"):
        pin_case_weights(np.array([[1.0, 1.0]]), ["pin_400", "pin_y"])
