"""The crankpin loaded per rod place: each patch case is 1 N of cosine pressure on its band
of the pin, acting at the band's middle; the determinate reactions are the simply supported
beam's for a load at that place; superposing the patch cases with each rod's force on its
band equals a direct solve of the same load (linear elasticity), to 1e-9."""

from __future__ import annotations

import numpy as np
import pytest
from helpers.verification_meshes import Steel, as_throw_mesh, simple_throw

from fe_crank.assess import unit_stresses
from fe_crank.assess.superpose import combine, cycle_coefficients, stress_history
from fe_crank.fe import FeOptions, solve_unit_cases
from fe_crank.fe.core.loads import centrifugal_load, face_torque_load, pin_pressure_load, pin_surface
from fe_crank.fe.throw.pin_directions import patch_case, patch_cases, unit_force

BANDS = ((-0.015, 0.0), (0.0, 0.015))  # the 30 mm pin of simple_throw, two rods side by side
Z1, Z2 = -0.065, 0.065  # the bearing centres (end faces)


@pytest.fixture(scope="module")
def solved():
    mesh = simple_throw(size=0.006)
    cases = ("centrifugal",) + patch_cases(2) + ("torque",)
    units = solve_unit_cases(as_throw_mesh(mesh), Steel(), FeOptions(cases=cases, pin_patches=BANDS, symmetry=False))
    return mesh, units


@pytest.mark.heavy
def test_patch_loads_act_at_their_band_and_react_as_a_beam(solved):
    _, units = solved
    basis = units.system.basis
    x = basis.doflocs
    for k, (lo, hi) in enumerate(BANDS, start=1):
        for base in ("pin_y", "pin_-y", "pin_x", "pin_030"):
            name = f"{base}@{k}"
            F = np.array(unit_force(name))
            f, _ = pin_pressure_load(basis, F, band=(lo, hi), surface=pin_surface(basis))
            fn = f.reshape(-1, 3)
            np.testing.assert_allclose(fn.sum(axis=0)[:2], F, atol=1e-12)
            # axial place of the resultant: M = sum z f (about the x and y axes through the pin)
            zc = float(np.dot(x[2], fn[:, 0] * F[0] + fn[:, 1] * F[1]))
            assert zc == pytest.approx(0.5 * (lo + hi), abs=0.01 * (hi - lo)), (name, zc)  # measured 0.02 mm
            c = units.cases[name]
            r1, r2 = c.reactions["journal_1"], c.reactions["journal_2"]
            for j in (0, 1):  # the beam's reactions of the load as distributed, exactly (statics)
                assert r1[j] == pytest.approx(-np.dot(fn[:, j], Z2 - x[2]) / (Z2 - Z1), abs=1e-9)
                assert r2[j] == pytest.approx(-np.dot(fn[:, j], x[2] - Z1) / (Z2 - Z1), abs=1e-9)
            # ... which is the load at the band's middle to 0.3 % of |F|
            assert r1[:2] == pytest.approx(-F * (Z2 - 0.5 * (lo + hi)) / (Z2 - Z1), abs=3e-3)


@pytest.mark.heavy
def test_superposition_per_rod_place_equals_a_direct_solve(solved):
    mesh, units = solved
    basis = units.system.basis
    nodes = (
        np.unique(basis.get_dofs(facets=mesh.boundaries["crankpin_fillet_1"]).all())
        if ("crankpin_fillet_1" in mesh.boundaries)
        else np.unique(basis.get_dofs(facets=mesh.boundaries["crankpin"]).all())
    )
    unit = unit_stresses(units, {"crankpin_fillet_1": nodes})
    assert unit.pin_patches == BANDS and sum(patch_case(c) is not None for c in unit.cases) == 24
    surface = pin_surface(basis)
    loads = {
        "centrifugal": centrifugal_load(basis, 7850.0, 1.0),
        "torque": face_torque_load(basis, -1.0, boundary="end_1"),
    }
    for c in unit.cases:
        if patch_case(c) is not None:
            loads[c] = pin_pressure_load(basis, unit_force(c), band=BANDS[patch_case(c)[0] - 1], surface=surface)[0]
    theta = np.deg2rad(np.arange(0, 360, 3))
    front = np.column_stack([5e3 * np.sin(theta), 2e4 * np.cos(theta) - 4e3])
    rear = np.column_stack([-3e3 * np.cos(theta), 1.5e4 * np.sin(theta + 1.0) + 2e3])
    rods = ((front, -0.0075), (rear, 0.0075))
    coeffs = cycle_coefficients(unit, front + rear, 300.0 * np.sin(theta), 200.0, rod_loads=rods)
    hist = stress_history(unit, coeffs)
    for i in (0, 17, 61, 100):
        f = combine(np.stack([loads[c] for c in unit.cases]), coeffs[i])[0]
        direct = units.stress_at_nodes(units.system.solve(f))[:, unit.node_ids]
        assert np.max(np.abs(hist[i] - direct)) / np.max(np.abs(direct)) < 1e-9
    with pytest.raises(ValueError, match="rods' forces"):
        cycle_coefficients(unit, front + rear, 300.0 * np.sin(theta), 200.0)
