"""FE stage: unit load cases on a simple throw -- equilibrium, load integrals, errors."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest
from helpers.verification_meshes import Steel, as_throw_mesh, simple_throw

from fe_crank.errors import InputError, MeshError, SolverError
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.core.loads import centrifugal_load, pin_pressure_load
from fe_crank.fe.linalg.factorise import factorise


@pytest.fixture(scope="module")
def throw():
    return simple_throw(size=0.01)


@pytest.fixture(scope="module")
def unit(throw):
    return solve_unit_cases(as_throw_mesh(throw), Steel())


def test_every_unit_case_balances_its_reactions(unit):
    assert set(unit.cases) == {
        "centrifugal",
        "torque",
        "pin_x",
        "pin_030",
        "pin_060",
        "pin_y",
        "pin_120",
        "pin_150",
        "pin_-x",
        "pin_210",
        "pin_240",
        "pin_-y",
        "pin_300",
        "pin_330",
    }
    for case in unit.cases.values():
        assert case.equilibrium_error < 1e-6
        total = case.applied + sum(case.reactions.values())
        assert np.linalg.norm(total[:3]) < 1e-6 * max(1.0, np.linalg.norm(case.applied[:3]))


def test_pin_pressure_integrates_exactly_to_the_force(throw, unit):
    basis = unit.system.basis
    for force in [(1.0, 0.0), (0.0, -1.0), (3.0e4, -5.0e4), (-2.0, 7.0)]:
        f, info = pin_pressure_load(basis, force)
        res = f.reshape(-1, 3).sum(axis=0)
        np.testing.assert_allclose(res[:2], force, rtol=1e-12, atol=1e-12 * np.linalg.norm(force))
        assert abs(res[2]) < 1e-12 * np.linalg.norm(force)
        # the pressure arc lies on the side of the pin facing away from the force
        away = np.arctan2(-force[0], -force[1])
        assert abs(np.angle(np.exp(1j * (info.arc_centre - away)))) < 0.02
    # closed form: F = p0 L (d/2) int_{-psi0}^{psi0} cos(pi psi / (2 psi0)) cos(psi) dpsi,
    # pin d = 45 mm, L = 30 mm (the faceted mesh surface gives ~0.1 % less area)
    psi0 = np.deg2rad(60.0)
    a = np.pi / (2 * psi0)
    integral = np.sin((a - 1) * psi0) / (a - 1) + np.sin((a + 1) * psi0) / (a + 1)
    p0_expected = 1.0 / (0.03 * 0.0225 * integral)
    assert unit.pin["pin_y"].peak_pressure == pytest.approx(p0_expected, rel=0.01)


def test_centrifugal_resultant_is_mass_times_centroid_radius(throw, unit):
    """Sum of the centrifugal nodal loads = m omega^2 r_G (omega = 1) with m, r_G by quadrature."""
    basis = unit.system.basis
    f = centrifugal_load(basis, 7850.0, 1.0).reshape(-1, 3).sum(axis=0)
    x = np.asarray(basis.global_coordinates())
    m_rg = 7850.0 * np.einsum("ieq,eq->i", x, basis.dx)
    np.testing.assert_allclose(f[:2], m_rg[:2], rtol=0, atol=1e-12 * abs(m_rg[1]))
    # throw is symmetric about x = 0 (up to the unstructured mesh): no x force, +y force
    assert abs(f[0]) < 1e-5 * abs(f[1]) and f[1] > 0


def test_torque_reaction_and_pin_torque(unit):
    # torque case: M_z = -1 N m (positive sense of rotation) applied, +1 N m reacted at end_2
    # (determinate supports: the whole torque, the bearings take none)
    assert unit.cases["torque"].applied[5] == pytest.approx(-1.0, rel=1e-12)
    assert unit.cases["torque"].reactions["end_2"][5] == pytest.approx(1.0, rel=1e-9)
    # 1 N along +x at the pin (R = 45 mm): M_z = x Fy - y Fx = -0.045 N m, reacted at end_2
    assert unit.cases["pin_x"].applied[5] == pytest.approx(-0.045, rel=1e-6)
    assert unit.cases["pin_x"].reactions["end_2"][5] == pytest.approx(0.045, rel=1e-6)


def test_solvers_agree(throw, unit):
    other = solve_unit_cases(as_throw_mesh(throw), Steel(), FeOptions(solver="superlu", cases=("pin_y", "torque")))
    for name in other.cases:
        u0, u1 = unit.displacement(name), other.displacement(name)
        assert np.abs(u0 - u1).max() < 1e-8 * np.abs(u0).max()


def test_superposition_of_pin_cases(unit):
    # a force along a unit-case direction is that case alone
    assert unit.pin_weights(0.0, -2.0) == {"pin_-y": 2.0}
    # (3, -2) N is at 326.3 deg: between pin_300 and pin_330, sine rule
    w = unit.pin_weights(3.0, -2.0)
    F, psi = np.hypot(3.0, 2.0), np.arctan2(-2.0, 3.0) + 2 * np.pi
    a300 = F * np.sin(np.deg2rad(330) - psi) / np.sin(np.pi / 6)
    a330 = F * np.sin(psi - np.deg2rad(300)) / np.sin(np.pi / 6)
    assert set(w) == {"pin_300", "pin_330"}
    assert w["pin_300"] == pytest.approx(a300) and w["pin_330"] == pytest.approx(a330)
    u = unit.combine(w)
    np.testing.assert_allclose(u, a300 * unit.displacement("pin_300") + a330 * unit.displacement("pin_330"))
    # the resultant of the combined load is the force
    applied = sum(wk * unit.cases[k].applied[:2] for k, wk in w.items())
    np.testing.assert_allclose(applied, [3.0, -2.0], atol=1e-9)


def test_missing_boundary_is_a_clear_error(throw):
    mesh = type(throw)(throw.doflocs, throw.t)  # no named groups
    with pytest.raises(MeshError, match="no boundary 'journal_1'"):
        solve_unit_cases(as_throw_mesh(mesh), Steel())


def test_zero_speed_centrifugal_is_an_input_error(unit):
    with pytest.raises(InputError, match="speed > 0"):
        centrifugal_load(unit.system.basis, 7850.0, 0.0)


def test_unsupported_rigid_mode_is_a_solver_error(unit):
    from fe_crank.fe.core.assembly import assemble_stiffness

    K = assemble_stiffness(unit.system.basis, 210e9, 0.3)  # elastic stiffness alone: six rigid-body modes
    with pytest.raises(SolverError):
        fac = factorise(K, "superlu")
        f = np.zeros(K.shape[0])
        f[0] = 1.0  # unbalanced load
        fac.solve(f)


def test_bad_options_are_input_errors(throw):
    with pytest.raises(InputError, match="unknown solver"):
        solve_unit_cases(as_throw_mesh(throw), Steel(), FeOptions(solver="mumps"))
    with pytest.raises(InputError, match="unknown unit cases"):
        solve_unit_cases(as_throw_mesh(throw), Steel(), FeOptions(cases=("gravity",)))


def test_unsupported_body_is_a_mesh_error():
    from skfem import MeshTri

    with pytest.raises(MeshError, match="unsupported body"):
        solve_unit_cases(as_throw_mesh(MeshTri()), Steel())


def test_material_without_density_is_an_input_error(throw):
    @dataclass(frozen=True)
    class NoDensity:
        youngs_modulus: float = 210e9
        poisson_ratio: float = 0.3

    with pytest.raises(InputError, match="density"):
        solve_unit_cases(as_throw_mesh(throw), NoDensity())


def test_foundation_support_carries_the_same_resultants(throw, unit):
    """The explicit foundation option: loads still balance exactly, each journal about half."""
    found = solve_unit_cases(
        as_throw_mesh(throw), Steel(), FeOptions(support="foundation", bearing_stiffness=4.2e12, cases=("pin_-y",))
    )
    assert found.bearing_stiffness == 4.2e12 and unit.bearing_stiffness is None
    c = found.cases["pin_-y"]
    assert c.equilibrium_error < 1e-6
    fy = c.reactions["journal_1"][1] + c.reactions["journal_2"][1]
    assert fy == pytest.approx(1.0, rel=1e-6)  # the load is -1 N along y
    # symmetric throw: each journal carries about half
    assert c.reactions["journal_1"][1] == pytest.approx(0.5, rel=0.05)


def test_foundation_on_the_loaded_arc_only(throw):
    """Arc-limited foundation: springs act only within the arc; reactions still balance."""
    from fe_crank.fe import Coupling, Foundation, build_system
    from fe_crank.fe.core.loads import pin_pressure_load

    k = 210e9 / 0.05
    arc = (np.pi, np.deg2rad(60))  # -y side: the pin is pushed towards -y
    s = build_system(
        throw,
        210e9,
        0.3,
        solver="superlu",
        foundations=[Foundation("journal_1", k, arc), Foundation("journal_2", k, arc)],
        couplings=[Coupling("end_2", fixed=("ux", "uz", "rz"))],
    )
    f, _ = pin_pressure_load(s.basis, (0.0, -1000.0))
    u = s.solve(f)
    err, reac = s.equilibrium_error(u, f)
    assert err < 1e-6
    assert reac["journal_1"][1] + reac["journal_2"][1] == pytest.approx(1000.0, rel=1e-6)
    rs = -(s.Ks @ u).reshape(-1, 3)
    loaded = np.flatnonzero(np.linalg.norm(rs, axis=1) > 0)
    ang = np.arctan2(s.points[0, loaded], s.points[1, loaded])
    assert np.all(np.abs(np.angle(np.exp(1j * (ang - np.pi)))) < np.deg2rad(90))  # arc + one element


def test_explicit_pin_centre_gives_the_same_load(throw, unit):
    """The pin axis given as (0, R) reproduces the centroid-based pressure of this full pin."""
    other = solve_unit_cases(as_throw_mesh(throw), Steel(), FeOptions(cases=("pin_y",), pin_centre=(0.0, 0.045)))
    assert other.pin["pin_y"].peak_pressure == pytest.approx(unit.pin["pin_y"].peak_pressure, rel=1e-4)
    np.testing.assert_allclose(other.pin["pin_y"].resultant[:2], (0.0, 1.0), atol=1e-12)
