"""The FE load vectors of ``fe_crank.fe.core.loads`` on tiny meshes, against closed forms.

* centrifugal load on a box (scikit-fem tensor mesh, straight P2 tets: volume, centroid
  and second moments exact): resultant rho omega^2 V r_perp(c) and moment about the axis
  point rho omega^2 a x (S a), S = int d d^T dV = V [(c - p)(c - p)^T + diag(L^2)/12];
  the nodal sums equal these integrals exactly (sum_a N_a = 1, sum_a N_a x_a = x, and the
  integrands are polynomials of degree <= 2 that the order-2 rule integrates exactly), so
  the tolerance is round-off (1e-12 relative);
* pin pressure on a gmsh cylinder (R 20 mm, L 30 mm, axis off the origin at (4, 45) mm):
  the peak pressure of the cosine law p0 cos(pi psi / (2 psi0)) on a perfect cylinder,
  F = p0 R L int_-psi0^psi0 cos(pi psi / (2 psi0)) cos psi dpsi, the integral being
  sin((k-1) a)/(k-1) + sin((k+1) a)/(k+1), k = pi/(2a): 6/5 at a = 60 deg (1 + 1/5),
  2 sqrt(2)/3 at 45 deg (sqrt(2)/2 + sqrt(2)/6); the load vector against scikit-fem's own
  facet assembly of that traction law written out here;
* end-face torque: moment about the axis equal to T to round-off, no net force (to the
  mesh's centroid error), J against pi R^4 / 2;
* on a throw (gmsh, curved P2): the crankpin surface prepared once (``pin_surface``) gives
  every pin direction the load vector that ``pin_pressure_load`` builds with its own facet
  basis and centre, to round-off (1e-14 of the largest entry; a wrong centre, normal or
  angle array changes entries by percent); each vector's resultant is the unit force
  (sum of nodal forces = int t dA, the P2 shape functions sum to one), to 1e-12 N.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.verification_meshes import box_beam, round_bar, simple_throw
from skfem import Basis, ElementTetP2, ElementVector, FacetBasis, LinearForm, asm
from skfem.helpers import dot

from fe_crank.errors import InputError, MeshError
from fe_crank.fe.core.loads import (
    SURFACE_INTORDER,
    centrifugal_load,
    face_torque_load,
    pin_centre,
    pin_pressure_load,
    pin_surface,
)
from fe_crank.fe.throw.pin_directions import pin_cases, unit_force

RHO, OMEGA = 7850.0, 30.0
R, L, CX, CY = 0.020, 0.030, 0.004, 0.045


@pytest.fixture(scope="module")
def box():
    # 0 <= x <= 0.2, 0 <= y <= 0.02, 0 <= z <= 0.02 (box_beam: width along y, height along z)
    return Basis(box_beam(0.2, 0.02, 0.02, nx=4, ny=1, nz=1), ElementTetP2(), intorder=2)


def _cylinder(size=0.008):
    """Solid cylinder radius R on the axis (CX, CY), 0 <= z <= L: crankpin (lateral), end_1, end_2."""
    return round_bar(2 * R, L, size, centre=(CX, CY), lateral="crankpin")


@pytest.fixture(scope="module")
def pin():
    return Basis(_cylinder(), ElementTetP2(), intorder=2)


def _moment(f, x, about):
    F = f.reshape(-1, 3)
    return np.cross(x.T - about, F).sum(axis=0)


def test_centrifugal_resultant_and_moment_about_the_crank_axis(box):
    # V = 0.2 x 0.02 x 0.02 = 8e-5 m^3, centroid (0.1, 0.01, 0.01) m;
    # rho omega^2 V = 7850 x 900 x 8e-5 = 565.2 N/m.
    # Axis z through the origin: F = 565.2 (0.1, 0.01, 0) = (56.52, 5.652, 0) N;
    # M = rho omega^2 int (x, y, 0) x ... = rho omega^2 (-int y z, int x z, 0)
    #   = 565.2 (-0.01 x 0.01, 0.1 x 0.01, 0) = (-0.05652, 0.5652, 0) N m
    f = centrifugal_load(box, RHO, OMEGA)
    np.testing.assert_allclose(f.reshape(-1, 3).sum(axis=0), (56.52, 5.652, 0.0), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(_moment(f, box.doflocs, np.zeros(3)), (-0.05652, 0.5652, 0.0), rtol=1e-12, atol=1e-13)
    # low density and speed are valid too: rho omega^2 = 0.5 x 0.25 = 0.125 -> F = 0.125 V (0.1, 0.01, 0)
    g = centrifugal_load(box, 0.5, 0.5)
    np.testing.assert_allclose(g.reshape(-1, 3).sum(axis=0), (1e-6, 1e-7, 0.0), rtol=1e-12, atol=1e-20)


def test_centrifugal_about_an_inclined_offset_axis(box):
    """Axis direction (2, 4, 4) (not unit: a = (1, 2, 2)/3) through p = (0.05, -0.02, 0.03)."""
    p = np.array([0.05, -0.02, 0.03])
    a = np.array([1.0, 2.0, 2.0]) / 3.0
    V, c, Ls = 8e-5, np.array([0.1, 0.01, 0.01]), np.array([0.2, 0.02, 0.02])
    k = RHO * OMEGA**2
    d = c - p
    F_ref = k * V * (d - a * (a @ d))
    S = V * (np.outer(d, d) + np.diag(Ls**2) / 12)  # int (x - p)(x - p)^T dV
    M_ref = k * np.cross(a, S @ a)  # int (x-p) x [d - a (a.d)] = int (a.d)(a x d)
    f = centrifugal_load(box, RHO, OMEGA, axis_point=tuple(p), axis=(2.0, 4.0, 4.0))
    F = f.reshape(-1, 3).sum(axis=0)
    np.testing.assert_allclose(F, F_ref, rtol=1e-12, atol=1e-12 * np.abs(F_ref).max())
    np.testing.assert_allclose(_moment(f, box.doflocs, p), M_ref, rtol=1e-12, atol=1e-12 * np.abs(M_ref).max())
    assert abs(F @ a) < 1e-12 * np.linalg.norm(F)  # no force along the axis


def test_centrifugal_refusals_name_the_key():
    for density, text in ((0.0, "0.0"), (-7850.0, "-7850.0"), (float("nan"), "nan")):
        with pytest.raises(InputError) as e:
            centrifugal_load(None, density, OMEGA)
        assert e.value.key == "material.density"
        assert e.value.reason == f"density must be > 0, got {text}"
    for omega in (0.0, -1.0):
        with pytest.raises(InputError) as e:
            centrifugal_load(None, RHO, omega)
        assert e.value.key == "operating.speed"
        assert e.value.reason == f"a centrifugal load needs a speed > 0, got omega = {omega!r} rad/s"


def test_pin_centre_and_surface(pin):
    # the area centroid of the lateral surface lies on the axis (measured within 1e-8 m here;
    # 1e-6 m, 5e-5 of the radius, catches a wrong weighting or axis by far)
    np.testing.assert_allclose(pin_centre(pin.mesh), (CX, CY), rtol=0, atol=1e-6)
    s = pin_surface(pin)
    np.testing.assert_allclose(s.centre, (CX, CY), rtol=0, atol=1e-6)
    assert s.n_r.shape == s.x.shape == (3,) + s.angle.shape
    assert np.all(s.n_r[2] == 0.0)
    np.testing.assert_allclose(np.hypot(s.n_r[0], s.n_r[1]), 1.0, rtol=1e-14)
    # radial within the facetting of the P2 surface (measured 4e-4 at 8 mm elements; a normal
    # turned by a wrong component is off by order 1)
    radial = (s.x[:2] - np.array([CX, CY])[:, None, None]) / R
    assert np.abs(s.n_r[:2] - radial).max() < 2e-3
    # with a given centre the angle is atan2(x - cx, y - cy): from +y towards +x
    g = pin_surface(pin, "crankpin", centre=(CX, CY))
    np.testing.assert_array_equal(g.centre, (CX, CY))
    np.testing.assert_allclose(g.angle, np.arctan2(g.x[0] - CX, g.x[1] - CY), rtol=0, atol=1e-15)
    # a point on +x of the axis is at +90 deg, on -y at 180 deg
    i = np.unravel_index(np.argmax(g.x[0]), g.x[0].shape)
    assert g.angle[i] == pytest.approx(np.pi / 2, abs=0.2)


def _traction_vector(pin, p0, arc, half):
    """The documented traction t = -p0 cos(pi psi/(2 psi0)) n_r, assembled by scikit-fem."""
    fb = FacetBasis(
        pin.mesh, ElementVector(ElementTetP2()), facets=pin.mesh.boundaries["crankpin"], intorder=SURFACE_INTORDER
    )

    @LinearForm
    def form(v, w):
        x, n = w.x, w.n
        nr = np.stack([n[0], n[1], 0 * n[2]]) / np.sqrt(n[0] ** 2 + n[1] ** 2)
        psi = np.angle(np.exp(1j * (np.arctan2(x[0] - CX, x[1] - CY) - arc)))
        p = np.where(np.abs(psi) < half, p0 * np.cos(np.pi * psi / (2 * half)), 0.0)
        return dot(-p * nr, v)

    return asm(form, fb)


@pytest.mark.parametrize(
    "force, half, integral",
    [
        ((300.0, -400.0), None, 1.2),  # default 60 deg: 1 + 1/5
        ((-150.0, 80.0), np.deg2rad(45.0), 2 * np.sqrt(2) / 3),  # 45 deg: sqrt(2)/2 + sqrt(2)/6
    ],
)
def test_pin_pressure_against_the_cosine_law(pin, force, half, integral):
    F = np.array(force)
    kw = {} if half is None else {"half_angle": half}
    f, info = pin_pressure_load(pin, force, centre=(CX, CY), **kw)
    psi0 = np.pi / 3 if half is None else half
    assert info.half_angle == psi0
    assert info.centre == (CX, CY)
    # resultant: exactly the force (the code solves p0 and the arc centre for it)
    np.testing.assert_allclose(f.reshape(-1, 3).sum(axis=0), (*F, 0.0), rtol=0, atol=1e-12 * np.linalg.norm(F))
    np.testing.assert_allclose(info.resultant, (*F, 0.0), rtol=0, atol=1e-12 * np.linalg.norm(F))
    # peak pressure of the perfect cylinder: |F| / (integral R L); the P2 surface's area
    # error at 8 mm elements is about 1e-4 (measured 1e-6 at 60 deg, 1e-4 at 45 deg): 1e-3, so
    # that a 1 % error in p0 (e.g. the arc's half angle off by a degree) fails
    assert info.peak_pressure == pytest.approx(np.linalg.norm(F) / (integral * R * L), rel=1e-3)
    # arc centre opposite the force, angles from +y towards +x; off by the mesh asymmetry only
    fdir = np.arctan2(F[0], F[1])
    assert abs(np.angle(np.exp(1j * (info.arc_centre - fdir - np.pi)))) < 5e-4  # measured 2.3e-5 rad
    # the load vector is the documented traction law, assembled independently
    ref = _traction_vector(pin, info.peak_pressure, info.arc_centre, psi0)
    assert np.abs(f - ref).max() < 1e-12 * np.abs(ref).max()
    # no torque about the pin axis (the traction is radial) -- up to the facetting of the normals
    # (measured 1.6e-6 F R)
    m = _moment(f, pin.doflocs, np.array([CX, CY, 0.0]))
    assert abs(m[2]) < 1e-4 * np.linalg.norm(F) * R


def test_pin_pressure_with_a_prepared_surface_and_the_default_centre(pin):
    surf = pin_surface(pin)
    f1, i1 = pin_pressure_load(pin, (0.0, -1000.0), surface=surf)
    f2, i2 = pin_pressure_load(pin, (0.0, -1000.0))
    np.testing.assert_array_equal(f1, f2)
    assert i1.centre == pytest.approx((CX, CY), abs=1e-6)
    # F along -y: the arc centre is at +y (angle 0 from +y)
    assert abs(np.angle(np.exp(1j * i1.arc_centre))) < 5e-3
    np.testing.assert_allclose(f1.reshape(-1, 3).sum(axis=0), (0.0, -1000.0, 0.0), atol=1e-9)


def test_pin_pressure_refusals(pin):
    for bad, text in (
        ((1.0, 2.0, 3.0), "(1.0, 2.0, 3.0)"),
        ((float("nan"), 1.0), "(nan, 1.0)"),
        ((1.0, float("inf")), "(1.0, inf)"),
        ((0.0, 0.0), "(0.0, 0.0)"),
    ):
        with pytest.raises(InputError) as e:
            pin_pressure_load(pin, bad)
        assert str(e.value) == f"pin force must be a non-zero finite (Fx, Fy), got {text}"
    # an end face has no radial normal: the cosine pressure gives no force, in any direction
    for F in ((0.0, 1.0), (-1.0, -1.0), (2.0, -0.5)):
        with pytest.raises(MeshError) as e:
            pin_pressure_load(pin, F, boundary="end_1")
        assert str(e.value) == "boundary 'end_1': cosine pressure does not produce a force (not a pin surface?)"


def test_face_torque_is_the_round_shaft_shear_flow(pin):
    T = 12.0
    c = np.array([CX, CY, L])
    f = face_torque_load(pin, T, boundary="end_2", centre=(CX, CY))
    m = _moment(f, pin.doflocs, c)
    assert m[2] == pytest.approx(T, rel=1e-12)
    assert np.abs(m[:2]).max() < 1e-12 * T  # in-plane forces on the plane z = L
    # net force: T/J int (-dy, dx) dA = 2 T A e / (pi R^4) for a centroid error e; the
    # facetted disk's centroid lies on the axis to round-off here (measured 4e-14 N), while a
    # wrong sign or centre gives forces of order T / R = 600 N
    F = f.reshape(-1, 3).sum(axis=0)
    assert np.abs(F).max() < 1e-9 and F[2] == 0.0
    # the shear flow itself: t = T r e_theta / J, J = pi R^4 / 2 = 2.513274e-7 m^4 for R = 20 mm
    J = np.pi * R**4 / 2
    fb = FacetBasis(
        pin.mesh, ElementVector(ElementTetP2()), facets=pin.mesh.boundaries["end_2"], intorder=SURFACE_INTORDER
    )

    @LinearForm
    def form(v, w):
        x = w.x
        return (T / J) * (-(x[1] - CY) * v[0] + (x[0] - CX) * v[1])

    ref = asm(form, fb)
    # J of the facetted disk vs pi R^4 / 2: the P2 boundary's error, measured 4e-5 of the
    # largest entry; 1e-4, so that a 1 % error in J or the shear flow fails
    assert np.abs(f - ref).max() < 1e-4 * np.abs(ref).max()
    # about the origin (default centre) the same face takes T as well, its lever being (CX, CY)
    g = face_torque_load(pin, T, boundary="end_2")
    assert _moment(g, pin.doflocs, np.zeros(3))[2] == pytest.approx(T, rel=1e-12)
    assert np.linalg.norm(g.reshape(-1, 3).sum(axis=0)) > 0.1 * T / R  # off-axis: J about the origin


@pytest.fixture(scope="module")
def throw():
    return Basis(simple_throw(size=0.012), ElementTetP2(), intorder=2)


def test_one_surface_for_all_directions_equals_a_surface_per_direction(throw):
    surf = pin_surface(throw)
    np.testing.assert_allclose(surf.centre, pin_centre(throw.mesh), rtol=0, atol=1e-15)
    for name in pin_cases():
        F = unit_force(name)
        f_ref, p_ref = pin_pressure_load(throw, F)
        f, p = pin_pressure_load(throw, F, surface=surf)
        assert np.abs(f - f_ref).max() <= 1e-14 * np.abs(f_ref).max(), name
        assert p.peak_pressure == pytest.approx(p_ref.peak_pressure, rel=1e-14)
        assert p.arc_centre == pytest.approx(p_ref.arc_centre, abs=1e-14)
        np.testing.assert_allclose(p.resultant[:2], F, rtol=0, atol=1e-12)
        assert abs(p.resultant[2]) < 1e-12


def test_a_given_centre_is_kept_by_the_prepared_surface(throw):
    c = pin_centre(throw.mesh)
    surf = pin_surface(throw, centre=(c[0], c[1]))
    f, p = pin_pressure_load(throw, (0.0, 1.0), surface=surf)
    f_ref, _ = pin_pressure_load(throw, (0.0, 1.0), centre=(c[0], c[1]))
    assert p.centre == (c[0], c[1])
    assert np.abs(f - f_ref).max() <= 1e-14 * np.abs(f_ref).max()
