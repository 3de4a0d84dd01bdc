"""``assess.superpose``: the unit cases' load coefficients over the cycle and the
superposition of their stresses.

* On a round bar (real scikit-fem solve): the superposition equals a direct FE solve with
  the combined load at the same crank angle (linear elasticity), to 1e-9 relative.
* On hand-built inputs, each against a hand calculation: the centrifugal omega^2, the
  torque's sign and scale, the column of each pin case, the refusals, the node selection
  and the chunking of the histories.  Values are exact small numbers, so the tolerances
  (1e-12 relative) only absorb the rounding of a handful of products; any wrong term
  moves a value by O(1).
* On a filleted throw: the history in component planes (``iter_planes``) equals
  ``stress_history`` to round-off (a matrix product: 1e-14 of the largest value, far
  below a wrong case or node, which moves it by O(1)).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers.verification_meshes import as_throw_mesh
from skfem import MeshTet, MeshTet2

import fe_crank.fe.throw.unit_cases as fe
from fe_crank.assess import unit_stresses
from fe_crank.assess.superpose import (
    UNIT_CASES,
    UnitStresses,
    combine,
    iter_histories,
    iter_planes,
    load_coefficients,
    stress_history,
)
from fe_crank.fe.core.loads import centrifugal_load, face_torque_load, pin_pressure_load
from fe_crank.fe.throw.pin_directions import pin_direction
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
    units = fe.solve_unit_cases(as_throw_mesh(mesh), mat, fe.FeOptions(solver="superlu"))
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
    from fe_crank.fe.throw.pin_directions import pin_direction, unit_force

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
    from fe_crank.fe.throw.pin_directions import pin_case_weights

    with pytest.raises(ValueError, match="gap of 180"):
        pin_case_weights(np.array([[1.0, 1.0]]), ["pin_x", "pin_y", "pin_-y"])
    with pytest.raises(ValueError, match="only forces along it"):
        pin_case_weights(np.array([[1.0, 1.0]]), ["pin_y"])
    with pytest.raises(ValueError, match="parallel"):
        pin_case_weights(np.array([[1.0, 1.0]]), ["pin_y", "pin_-y"])
    with pytest.raises(ValueError, match="not pin unit cases"):
        pin_case_weights(np.array([[1.0, 1.0]]), ["pin_400", "pin_y"])


def _pin_column(deg):
    """Column of the pin case at ``deg`` in the default cases (the FE stage's names)."""
    return [i for i, c in enumerate(UNIT_CASES) if pin_direction(c) == deg][0]


def test_default_cases_centrifugal_pin_and_torque_by_hand():
    """Default cases: centrifugal, 12 pin directions 30 deg apart, torque.

    omega = 3 rad/s -> centrifugal coefficient omega^2 = 9 (omega * 2 = 6 and omega^3 = 27
    would differ by 3 and 18).  A 1000 N force at 45 deg lies between the 30 and 60 deg
    cases: w30 e30 + w60 e60 = F, Cramer's rule with det = sin(60 - 30) = 0.5:
    w30 = 1000 sin(60 - 45) / sin 30 = 1000 x 0.2588190 / 0.5 = 517.6381 N = w60.
    A force along 90 deg (0, -250 N is 270 deg) is carried by that case alone.
    Torque: the FE case is M_z = -1 N m (torque_mz), sense +1 -> coefficient = -1 x T / -1 = T.
    """
    pin = np.array([[1000 * math.cos(math.pi / 4), 1000 * math.sin(math.pi / 4)], [0.0, -250.0]])
    c = load_coefficients(pin, np.array([40.0, -7.0]), 3.0)
    assert c.shape == (2, len(UNIT_CASES)) and UNIT_CASES[0] == "centrifugal" and UNIT_CASES[-1] == "torque"
    np.testing.assert_allclose(c[:, 0], [9.0, 9.0], rtol=1e-15)
    w = 1000 * math.sin(math.radians(15.0)) / math.sin(math.radians(30.0))
    assert w == pytest.approx(517.6381, abs=1e-4)
    expected_pins = np.zeros((2, 12))
    expected_pins[0, [_pin_column(30) - 1, _pin_column(60) - 1]] = w
    expected_pins[1, _pin_column(270) - 1] = 250.0
    np.testing.assert_allclose(c[:, 1:-1], expected_pins, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(c[:, -1], [40.0, -7.0], rtol=1e-15)


def test_torque_coefficient_sign_and_scale():
    """coefficient = -sense T / torque_mz: T = 12 N m, torque_mz = -4 -> 3 (sense +1) and
    -3 (sense -1); torque_mz = +0.5 -> -24 (sense +1).  A product in place of the quotient
    would give 48 / -6: off by a factor 16."""
    pin = np.zeros((1, 2))
    cases = ("pin_x", "pin_y", "torque")
    assert load_coefficients(pin, np.array([12.0]), 1.0, cases=cases, torque_mz=-4.0)[0, 2] == 3.0
    assert load_coefficients(pin, np.array([12.0]), 1.0, cases=cases, sense=-1, torque_mz=-4.0)[0, 2] == -3.0
    assert load_coefficients(pin, np.array([12.0]), 1.0, cases=cases, torque_mz=0.5)[0, 2] == -24.0
    # the defaults: sense +1 and the FE stage's M_z = -1 N m
    assert load_coefficients(pin, np.array([12.0]), 1.0, cases=cases)[0, 2] == 12.0


def test_integer_inputs_give_the_float_coefficients():
    """Integer arrays (a TOML table of whole newtons) give the same coefficients as floats:
    F = (3, -4) N on pin_x/pin_y is (3, -4); T = 5 N m -> 5; omega 2 -> 4."""
    c = load_coefficients(np.array([[3, -4]]), np.array([5]), 2, cases=("centrifugal", "pin_x", "pin_y", "torque"))
    assert c.dtype == float
    np.testing.assert_allclose(c, [[4.0, 3.0, -4.0, 5.0]], rtol=1e-12)  # the 2x2 solve rounds


def test_bad_shapes_and_unknown_cases_are_refused():
    good_pin, good_t = np.zeros((2, 2)), np.zeros(2)
    msg = "pin_force must be (n, 2) and torque (n,); got"
    with pytest.raises(ValueError) as e:
        load_coefficients(np.zeros((2, 3)), good_t, 1.0)
    assert str(e.value) == f"{msg} (2, 3), (2,)"
    with pytest.raises(ValueError) as e:
        load_coefficients(good_pin, np.zeros(3), 1.0)
    assert str(e.value) == f"{msg} (2, 2), (3,)"
    with pytest.raises(ValueError) as e:
        load_coefficients(good_pin, good_t, 1.0, cases=("centrifugal", "pin_x", "pin_y", "bending"))
    assert str(e.value) == "unknown unit case 'bending'"


def _unit(n=3):
    """Three unit cases at ``n`` nodes: case c, component j, node k holds
    100 c + 10 j + k (small exact integers)."""
    c, j, k = np.meshgrid(np.arange(3), np.arange(6), np.arange(n), indexing="ij")
    return UnitStresses(stress=(100.0 * c + 10.0 * j + k), points=np.zeros((3, n)), cases=("a", "b", "c"))


def test_combine_is_the_hand_sum_of_coefficients_times_unit_stresses():
    """Node 1, component xx (j = 0) at t = 0 with coefficients (2, -1, 0.5):
    2 x 1 - 1 x 101 + 0.5 x 201 = 2 - 101 + 100.5 = 1.5; at t = 1, (0, 0, 3): 3 x 201 = 603.
    Component yz (j = 4) of node 2 at t = 0: 2 x 42 - 142 + 0.5 x 242 = 84 - 142 + 121 = 63."""
    unit = _unit()
    co = np.array([[2.0, -1.0, 0.5], [0.0, 0.0, 3.0]])
    s = combine(unit.stress, co)
    assert s.shape == (2, 6, 3)
    assert s[0, 0, 1] == 1.5 and s[1, 0, 1] == 603.0 and s[0, 4, 2] == 63.0
    # one angle given as a 1-D row: a leading axis of 1
    one = combine(unit.stress, co[0])
    assert one.shape == (1, 6, 3) and one[0, 4, 2] == 63.0
    # displacement vectors (n_cases, n_dof): 2 (1, 2) - (3, 4) + 0.5 (6, 8) = (2, 4)
    d = combine(np.array([[1.0, 2.0], [3.0, 4.0], [6.0, 8.0]]), co[:1])
    np.testing.assert_array_equal(d, [[2.0, 4.0]])
    with pytest.raises(ValueError) as e:
        combine(unit.stress, co[:, :2])
    assert str(e.value) == "2 coefficients for 3 unit cases"


def test_stress_history_at_selected_nodes_and_in_chunks():
    """History at nodes [2, 0]: the values of nodes 2 and 0 in that order (t = 0, xx:
    node 2: 2 x 2 - 102 + 0.5 x 202 = 3; node 0: 2 x 0 - 100 + 100 = 0).  The chunked
    iterators yield every node once, in order, with those values, ``chunk`` / ``block``
    nodes at a time (the defaults bound the memory: 2048 and 128 nodes)."""
    unit = _unit(5)
    co = np.array([[2.0, -1.0, 0.5], [0.0, 0.0, 3.0]])
    h = stress_history(unit, co, np.array([2, 0]))
    assert h.shape == (2, 6, 2) and h[0, 0, 0] == 3.0 and h[0, 0, 1] == 0.0
    full = stress_history(unit, co)
    assert full.shape == (2, 6, 5) and unit.n_nodes == 5
    np.testing.assert_array_equal(full[:, :, [2, 0]], h)
    nodes = np.array([4, 1, 3, 0, 2])
    got = list(iter_histories(unit, co, nodes, chunk=2))
    assert [list(i) for i, _ in got] == [[4, 1], [3, 0], [2]]
    for idx, hist in got:
        np.testing.assert_array_equal(hist, full[:, :, idx])
    planes = list(iter_planes(unit, co, nodes, block=2))
    assert [list(i) for i, _ in planes] == [[4, 1], [3, 0], [2]]
    for idx, p in planes:
        assert p.shape == (6, 2, idx.size)
        np.testing.assert_array_equal(p, full[:, :, idx].transpose(1, 0, 2))
    with pytest.raises(ValueError) as e:
        next(iter_planes(unit, co[:, :2], nodes))
    assert str(e.value) == "2 coefficients for 3 unit cases"
    # the default chunk sizes
    big = UnitStresses(stress=np.ones((3, 6, 2049)), points=np.zeros((3, 2049)), cases=("a", "b", "c"))
    assert [i.size for i, _ in iter_histories(big, co, np.arange(2049))] == [2048, 1]
    assert [i.size for i, _ in iter_planes(big, co, np.arange(129))] == [128, 1]
    # one angle as a 1-D row of coefficients
    ((idx, p),) = iter_planes(unit, co[1], np.array([1]))
    assert p.shape == (6, 1, 1) and p[0, 0, 0] == 3 * 201.0


def test_integer_tables_combine_to_float_stresses():
    """Whole-number unit stresses and coefficients (as a hand-written table gives them)
    combine to float arrays with the hand values: node 0, xx: 2 x 0 + 3 x 100 + 1 x 200 = 500;
    the per-component planes are float too (written into a float array)."""
    stress = (100 * np.arange(3)[:, None, None] + np.zeros((3, 6, 2), dtype=int)).astype(int)
    unit = UnitStresses(stress=stress, points=np.zeros((3, 2)), cases=("a", "b", "c"))
    co = np.array([[2, 3, 1]])
    s = combine(unit.stress, co)
    assert s.dtype == float and s[0, 0, 0] == 500.0
    ((idx, planes),) = iter_planes(unit, co, np.arange(2))
    assert planes.dtype == float and planes[0, 0, 0] == 500.0


@pytest.mark.heavy
def test_history_planes_equal_the_stress_history(filleted_throw_cycle):
    us, co = filleted_throw_cycle
    nodes = us.groups["journal_fillet_1"]
    ref = stress_history(us, co, nodes)
    got, seen = [], []
    for idx, planes in iter_planes(us, co, nodes, block=50):
        got.append(planes.transpose(1, 0, 2))
        seen.append(idx)
    np.testing.assert_array_equal(np.concatenate(seen), nodes)
    got = np.concatenate(got, axis=-1)
    assert np.abs(got - ref).max() <= 1e-14 * np.abs(ref).max()
