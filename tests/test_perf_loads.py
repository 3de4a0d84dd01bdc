"""The crankpin surface built once serves every pin direction with the same load vectors.

Reference: ``pin_pressure_load`` without a prepared surface (it builds its own facet
basis and pin centre, as every direction did before).  The computations are the same
operations on the same arrays, so the vectors agree to round-off (1e-14 of the largest
entry; a wrong centre, normal or angle array would change entries by percent).  The
resultant of each vector is the unit force (sum of nodal forces = int t dA, because the
P2 shape functions sum to one), to 1e-12 N.
"""

from __future__ import annotations

import numpy as np
import pytest
from skfem import Basis, ElementTetP2
from verification_meshes import simple_throw

from fe_crank.fe.loads import pin_centre, pin_pressure_load, pin_surface
from fe_crank.fe.pin_directions import pin_cases, unit_force


@pytest.fixture(scope="module")
def basis():
    return Basis(simple_throw(size=0.012), ElementTetP2(), intorder=2)


def test_one_surface_for_all_directions_equals_a_surface_per_direction(basis):
    surf = pin_surface(basis)
    np.testing.assert_allclose(surf.centre, pin_centre(basis.mesh), rtol=0, atol=1e-15)
    for name in pin_cases():
        F = unit_force(name)
        f_ref, p_ref = pin_pressure_load(basis, F)
        f, p = pin_pressure_load(basis, F, surface=surf)
        assert np.abs(f - f_ref).max() <= 1e-14 * np.abs(f_ref).max(), name
        assert p.peak_pressure == pytest.approx(p_ref.peak_pressure, rel=1e-14)
        assert p.arc_centre == pytest.approx(p_ref.arc_centre, abs=1e-14)
        np.testing.assert_allclose(p.resultant[:2], F, rtol=0, atol=1e-12)
        assert abs(p.resultant[2]) < 1e-12


def test_given_centre_is_kept(basis):
    c = pin_centre(basis.mesh)
    surf = pin_surface(basis, centre=(c[0], c[1]))
    f, p = pin_pressure_load(basis, (0.0, 1.0), surface=surf)
    f_ref, _ = pin_pressure_load(basis, (0.0, 1.0), centre=(c[0], c[1]))
    assert p.centre == (c[0], c[1])
    assert np.abs(f - f_ref).max() <= 1e-14 * np.abs(f_ref).max()
