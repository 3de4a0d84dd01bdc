"""``assess.stress`` in the assessment layout (..., 6, n) against closed forms and hand
values: von Mises, principal stresses, the 3x3 matrix and the cylindrical components.

Every array has distinct sizes on its axes (2 angles, 6 components, 3 nodes) so that a
wrong axis is a wrong shape or a wrong value, never a coincidence.  Tolerances: 1e-12
relative (a few roundings of numbers below 1e3); a wrong term changes a value by O(1).

The forms the assessment evaluates a cycle with, ``von_mises_path`` (into reused
buffers) and ``von_mises_planes`` (on component planes), equal the plain formula bit for
bit: they change where temporaries live, not the arithmetic.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers.cycles import cycle_paths

from fe_crank.assess.stress import cylindrical, principal, to_matrix, von_mises, von_mises_path, von_mises_planes

# a general state, components (xx, yy, zz, xy, yz, xz) in MPa:
# vM^2 = ((100 + 50)^2 + (-50 - 30)^2 + (30 - 100)^2) / 2 + 3 (20^2 + (-10)^2 + 40^2)
#      = (22500 + 6400 + 4900) / 2 + 3 (400 + 100 + 1600) = 16900 + 6300 = 23200
GENERAL = np.array([100.0, -50.0, 30.0, 20.0, -10.0, 40.0])
VM_GENERAL = math.sqrt(23200.0)  # 152.3155
# uniaxial 7 -> 7; pure shear tau_yz = 5 -> sqrt(3) 5; hydrostatic 10 -> 0
UNIAXIAL = np.array([7.0, 0, 0, 0, 0, 0])
SHEAR = np.array([0, 0, 0, 0, 5.0, 0])
HYDRO = np.array([10.0, 10.0, 10.0, 0, 0, 0])


def _stacked():
    """(2 angles, 6, 3 nodes): angle 0 = (GENERAL, UNIAXIAL, SHEAR), angle 1 = (HYDRO, -GENERAL, 2 UNIAXIAL)."""
    return np.stack([np.stack([GENERAL, UNIAXIAL, SHEAR], -1), np.stack([HYDRO, -GENERAL, 2 * UNIAXIAL], -1)])


def test_von_mises_closed_forms_in_the_stacked_layout():
    vm = von_mises(_stacked())
    expected = [[VM_GENERAL, 7.0, math.sqrt(3.0) * 5.0], [0.0, VM_GENERAL, 14.0]]
    assert vm.shape == (2, 3)
    np.testing.assert_allclose(vm, expected, rtol=1e-12, atol=1e-12)


def test_von_mises_path_and_planes_about_a_centre():
    """About the centre c = UNIAXIAL at every node: GENERAL - c = (93, -50, 30, 20, -10, 40):
    ((143)^2 + (-80)^2 + (-63)^2)/2 + 6300 = (20449 + 6400 + 3969)/2 + 6300 = 21709."""
    h = _stacked()
    centre = np.repeat(UNIAXIAL[:, None], 3, axis=1)
    about = von_mises_path(h, centre)
    assert about.shape == (2, 3)
    assert about[0, 0] == pytest.approx(math.sqrt(21709.0), rel=1e-12)
    assert about[0, 1] == 0.0 and about[1, 2] == 7.0
    np.testing.assert_allclose(von_mises_path(h), von_mises(h), rtol=1e-15, atol=0)
    planes = np.ascontiguousarray(h.transpose(1, 0, 2))
    # a scratch array and an output array, about zero and about the centre
    buf, out = np.full(planes.shape, np.nan), np.full((2, 3), np.nan)
    got = von_mises_planes(planes, None, buf, out)
    assert got is out
    np.testing.assert_allclose(
        got, [[VM_GENERAL, 7.0, math.sqrt(75.0)], [0.0, VM_GENERAL, 14.0]], rtol=1e-12, atol=1e-12
    )
    np.testing.assert_array_equal(von_mises_planes(planes, centre, buf), about)
    assert np.array_equal(planes, h.transpose(1, 0, 2))  # the input is left as it was


def test_to_matrix_places_each_component():
    s = np.arange(1.0, 7.0)[:, None] * np.array([1.0, 10.0])  # (6, 2): node 1 is ten times node 0
    m = to_matrix(np.stack([s, -s]))  # (2, 2 nodes, 3, 3)
    assert m.shape == (2, 2, 3, 3)
    # (xx, yy, zz, xy, yz, xz) = (1, 2, 3, 4, 5, 6)
    np.testing.assert_array_equal(m[0, 0], [[1, 4, 6], [4, 2, 5], [6, 5, 3]])
    np.testing.assert_array_equal(m[1, 1], -10 * np.array([[1, 4, 6], [4, 2, 5], [6, 5, 3]]))
    # two leading axes (cycles x angles): (2, 2, 6, 2) -> (2, 2, 2 nodes, 3, 3)
    m4 = to_matrix(np.stack([np.stack([s, -s]), np.stack([2 * s, 3 * s])]))
    assert m4.shape == (2, 2, 2, 3, 3)
    np.testing.assert_array_equal(m4[1, 1, 1], 30 * np.array([[1, 4, 6], [4, 2, 5], [6, 5, 3]]))


def test_principal_stresses_by_hand_in_the_stacked_layout():
    """Principal stresses, descending: GENERAL's from its cubic's roots checked by the
    invariants (sum = I1 = 80; product = det), UNIAXIAL (7, 0, 0), pure shear (5, 0, -5),
    HYDRO (10, 10, 10), a diagonal state (1, 3, 2) -> (3, 2, 1)."""
    h = _stacked()
    h[1, :, 2] = [1.0, 3.0, 2.0, 0, 0, 0]
    p = principal(h)
    assert p.shape == (2, 3, 3)
    np.testing.assert_allclose(p[0, :, 1], [7, 0, 0], atol=1e-12)
    np.testing.assert_allclose(p[0, :, 2], [5, 0, -5], atol=1e-12)
    np.testing.assert_allclose(p[1, :, 0], [10, 10, 10], rtol=1e-12)
    np.testing.assert_allclose(p[1, :, 2], [3, 2, 1], rtol=1e-12)
    g = p[0, :, 0]
    assert g[0] >= g[1] >= g[2]
    # I1 = 100 - 50 + 30 = 80; det = 100(-50 x 30 - 100) - 20(20 x 30 - (-10) 40) + 40(20 (-10) - (-50) 40)
    #    = 100 (-1600) - 20 (1000) + 40 (1800) = -160000 - 20000 + 72000 = -108000
    assert g.sum() == pytest.approx(80.0, rel=1e-12)
    assert np.prod(g) == pytest.approx(-108000.0, rel=1e-12)
    np.testing.assert_allclose(p[1, :, 1], -g[::-1], rtol=1e-12)  # -GENERAL: the negated roots


def _rotated(s, a):
    """Q s Q^T with rows e_r = (cos a, sin a, 0), e_t = (-sin a, cos a, 0), e_z: an
    independent evaluation by matrix products."""
    xx, yy, zz, xy, yz, xz = s
    m = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
    q = np.array([[math.cos(a), math.sin(a), 0], [-math.sin(a), math.cos(a), 0], [0, 0, 1]])
    r = q @ m @ q.T
    return {"rr": r[0, 0], "tt": r[1, 1], "zz": r[2, 2], "rt": r[0, 1], "tz": r[1, 2], "rz": r[0, 2]}


def test_cylindrical_components_by_hand_and_by_rotation():
    """Axis through (1, 2).  Node 0 at 30 deg from it, uniaxial xx = 100: sigma_rr = 100
    cos^2 30 = 75, sigma_tt = 100 sin^2 30 = 25, sigma_rt = -100 cos 30 sin 30 = -43.30127.
    Node 1 at 120 deg (radius 2) and node 2 on the axis (the x direction stands for e_r
    there): GENERAL against Q s Q^T."""
    a0, a1 = math.radians(30.0), math.radians(120.0)
    pts = np.array(
        [
            [1 + 0.5 * math.cos(a0), 1 + 2 * math.cos(a1), 1.0],
            [2 + 0.5 * math.sin(a0), 2 + 2 * math.sin(a1), 2.0],
            [0.3, -0.1, 0.0],
        ]
    )
    s = np.stack([UNIAXIAL * 100 / 7, GENERAL, GENERAL], -1)
    cyl = cylindrical(np.stack([s, 2 * s]), pts, (1.0, 2.0))
    assert list(cyl) == ["rr", "tt", "zz", "rt", "tz", "rz"]
    assert cyl["rr"][0, 0] == pytest.approx(75.0, rel=1e-12)
    assert cyl["tt"][0, 0] == pytest.approx(25.0, rel=1e-12)
    assert cyl["rt"][0, 0] == pytest.approx(-43.30127019, rel=1e-9)
    for k in ("zz", "tz", "rz"):
        assert abs(cyl[k][0, 0]) < 1e-12
    for node, a in ((1, a1), (2, 0.0)):
        ref = _rotated(GENERAL, a)
        for k, v in ref.items():
            assert cyl[k][0, node] == pytest.approx(v, rel=1e-12, abs=1e-12), (node, k)
            assert cyl[k][1, node] == pytest.approx(2 * v, rel=1e-12, abs=1e-12), (node, k)
    sub = cylindrical(s, pts, (1.0, 2.0), which=("tz", "rr"))
    assert list(sub) == ["rr", "tz"]
    np.testing.assert_array_equal(sub["tz"], cyl["tz"][0])


def test_von_mises_path_hand_values():
    # uniaxial 100 MPa: vM = 100 MPa; pure shear 50 MPa: vM = sqrt(3) 50 = 86.60 MPa;
    # about a centre of uniaxial 40 MPa the uniaxial 100 MPa state is 60 MPa away
    h = np.zeros((2, 6, 2))
    h[0, 0, 0] = 100e6
    h[1, 3, 1] = 50e6
    vm = von_mises_path(h)
    assert vm[0, 0] == 100e6
    assert abs(vm[1, 1] - np.sqrt(3.0) * 50e6) <= 1e-15 * 86.6e6 * 4
    centre = np.zeros((6, 2))
    centre[0, 0] = 40e6
    assert von_mises_path(h, centre)[0, 0] == 60e6


def test_von_mises_path_equals_plain_formula_bitwise():
    h = cycle_paths()
    c = 0.5 * (h.min(axis=0) + h.max(axis=0))
    assert np.array_equal(von_mises_path(h), von_mises(h))
    assert np.array_equal(von_mises_path(h, c), von_mises(h - c[None]))


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
