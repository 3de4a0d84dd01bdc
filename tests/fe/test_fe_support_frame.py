"""Displacements in the frame of the determinate supports (``fe_crank.fe.core.support_frame``):
after the removal the main-bearing centres do not move (radially at both, axially at the
torque end's journal) and the torque face does not turn; a known rigid motion added to a
field is removed exactly; the removed part is rigid (stresses unchanged)."""

from __future__ import annotations

import numpy as np
import pytest
from helpers.verification_meshes import Steel, as_throw_mesh, simple_throw

from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.core.support_frame import (
    in_support_frame,
    rigid_motion_at_supports,
    support_displacements,
    unit_case_in_support_frame,
)
from fe_crank.fe.core.supports import rigid_body_modes


@pytest.fixture(scope="module")
def units():
    return solve_unit_cases(
        as_throw_mesh(simple_throw(size=0.012)),
        Steel(),
        FeOptions(cases=("centrifugal", "pin_y", "pin_x", "torque"), symmetry=False),
    )


def test_a_pure_rigid_motion_is_removed_entirely(units):
    sup = units.system.determinate
    a = np.array([1e-4, -2e-4, 3e-5, 2e-3, -1e-3, 4e-3])  # m and rad
    r = rigid_body_modes(sup.points) @ a
    np.testing.assert_allclose(rigid_motion_at_supports(r, sup.G, sup.A), a, rtol=1e-10, atol=1e-16)
    assert np.abs(in_support_frame(r, sup.G, sup.A, sup.points)).max() < 1e-10 * np.abs(r).max()


@pytest.mark.parametrize("case", ["pin_y", "pin_x", "torque", "centrifugal"])
def test_supports_at_rest_and_a_known_rigid_part_removed_exactly(units, case):
    sup = units.system.determinate
    u = units.displacement(case)
    scale = np.abs(u).max()
    u1 = unit_case_in_support_frame(units, case)
    # the six support displacements (bearing centres' x, y; the axial journal's z; the
    # torque face's turn), each the work conjugate of its reaction component, are zero
    d = support_displacements(u1, sup.G)
    assert np.abs(d[:-1]).max() < 1e-10 * scale  # m
    # the turn of the torque face (rad) times the model's length: a displacement
    assert abs(d[-1]) * 0.15 < 1e-10 * scale
    # what was removed is a rigid motion (no strain): B a fits u - u1 to round-off
    B = rigid_body_modes(sup.points)
    a, *_ = np.linalg.lstsq(B, u - u1, rcond=None)
    assert np.abs(B @ a - (u - u1)).max() < 1e-10 * scale
    # a known rigid part added to the support-frame field is taken off exactly
    known = np.array([2.0, -1.0, 0.5, 30.0, -20.0, 10.0]) * scale * np.array([1, 1, 1, 1e-1, 1e-1, 1e-1])
    u2 = u1 + B @ known
    np.testing.assert_allclose(rigid_motion_at_supports(u2, sup.G, sup.A), known, rtol=1e-9, atol=1e-12 * scale)
    assert np.abs(in_support_frame(u2, sup.G, sup.A, sup.points) - u1).max() < 1e-10 * scale
    # several fields at once, as columns
    both = in_support_frame(np.column_stack([u, u2]), sup.G, sup.A, sup.points)
    assert np.abs(both[:, 0] - u1).max() < 1e-10 * scale and np.abs(both[:, 1] - u1).max() < 1e-10 * scale


def test_bearing_centre_of_a_symmetric_solve_too():
    """The symmetry-component solve returns the full model's field: the same removal applies."""
    units = solve_unit_cases(as_throw_mesh(simple_throw(size=0.012)), Steel(), FeOptions(cases=("pin_y", "torque")))
    sup = units.system.determinate
    u1 = unit_case_in_support_frame(units, "pin_y")
    assert np.abs(support_displacements(u1, sup.G)[:-1]).max() < 1e-10 * np.abs(u1).max()
