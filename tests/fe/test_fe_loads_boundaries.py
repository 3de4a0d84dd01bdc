"""A load or support on a boundary the mesh lacks, or on a degenerate one: one MeshError that
names the boundary and what needed it (``fe.core.loads``, ``fe.core.determinate``), in full."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from helpers.square_bar import square_bar as _square_bar
from skfem import Basis, ElementTetP2

from fe_crank.errors import MeshError
from fe_crank.fe.core.determinate import DeterminateLayout, bearing_surface_load, determinate_support, face_centre
from fe_crank.fe.core.loads import face_torque_load, pin_centre, pin_pressure_load, pin_surface

HAVE = "crankpin, end_1, end_2, journal_1, journal_2"


@pytest.fixture(scope="module")
def bar():
    return Basis(_square_bar(), ElementTetP2(), intorder=2)


def _missing(needed_by):
    return f"mesh has no boundary 'nope', needed by {needed_by}; it has: {HAVE}"


def test_missing_boundaries_are_named_with_what_needed_them(bar):
    cases = [
        (lambda: pin_surface(bar, "nope"), "the crankpin load"),
        (lambda: pin_centre(bar.mesh, "nope"), "the crankpin load"),
        (lambda: pin_pressure_load(bar, (0.0, 1.0), boundary="nope"), "the crankpin load"),
        (lambda: face_torque_load(bar, 1.0, boundary="nope"), "the torque load"),
        (lambda: bearing_surface_load(bar, "nope"), "a bearing support"),
        (lambda: face_centre(bar, "nope"), "a main-bearing centre"),
        (
            lambda: determinate_support(bar, DeterminateLayout(), candidate_faces=("end_1", "nope")),
            "the point constraints",
        ),
        (lambda: determinate_support(bar, DeterminateLayout(centre_faces=("end_1", "nope"))), "a main-bearing centre"),
        (lambda: determinate_support(bar, DeterminateLayout(torque_face="nope")), "the torque load"),
    ]
    for call, needed_by in cases:
        with pytest.raises(MeshError) as e:
            call()
        assert str(e.value) == _missing(needed_by)


def test_default_boundaries_are_the_crankpin_and_the_end_faces(bar):
    # the square bar's "crankpin" is its middle: the defaults find it (pin_surface, pin_centre,
    # pin_pressure_load) and the point constraints sit on end_1 / end_2 (determinate_support)
    np.testing.assert_allclose(pin_centre(bar.mesh), (0.0, 0.0), atol=1e-15)
    np.testing.assert_allclose(pin_surface(bar).centre, (0.0, 0.0), atol=1e-15)
    f, info = pin_pressure_load(bar, (0.0, -1.0))
    np.testing.assert_allclose(f.reshape(-1, 3).sum(axis=0), (0.0, -1.0, 0.0), atol=1e-12)


def test_a_degenerate_pin_surface_is_a_mesh_error():
    """Vertices of the first layer (z < -30 mm) moved onto z = -30 mm: their tetrahedra are flat
    (the mid-edge nodes left in place), and mapping the journal_1 facet points must fail."""
    m = _square_bar()
    p = m.doflocs.copy()
    nv = m.p.shape[1]
    p[2, :nv] = np.maximum(p[2, :nv], -0.03)
    flat = replace(m, doflocs=p)
    with pytest.raises(MeshError) as e:
        pin_centre(flat, "journal_1")
    assert str(e.value) == (
        "the crankpin load: the curved elements under the surface are too distorted to map "
        "its quadrature points (a degenerate element (vertices in one plane)); remesh with a "
        "finer or better-shaped mesh"
    )
