"""Averaged nodal stresses of many fields in one pass (``fe.nodal_stress``) against the
per-field recovery (``fe.stress.stress_at_selected_nodes``) on a real curved P2 mesh."""

from __future__ import annotations

import numpy as np
import pytest
from verification_meshes import round_bar

from fe_crank.errors import MeshError
from fe_crank.fe.nodal_stress import stress_of_fields
from fe_crank.fe.stress import elements_of_nodes, stress_at_selected_nodes


def test_many_fields_at_once_equal_one_at_a_time():
    mesh = round_bar(0.02, 0.05, size=0.006)
    n = mesh.doflocs.shape[1]
    rng = np.random.default_rng(3)
    U = rng.standard_normal((3 * n, 5)) * 1e-5
    x = mesh.doflocs
    U[:, 0] = np.column_stack([1e-4 * x[1] * x[2], -2e-4 * x[0], 3e-4 * x[2] ** 2]).ravel()  # a smooth field
    nodes = np.flatnonzero(np.abs(x[2] - 0.025) < 0.004)
    ref = stress_at_selected_nodes(mesh, list(U.T), 210e9, 0.3, nodes)
    # the fields given only on the nodes of the elements around the selected ones
    from skfem import ElementTetP2
    from skfem.assembly import Dofs

    ed = Dofs(mesh, ElementTetP2()).element_dofs
    rows = np.unique(ed[:, elements_of_nodes(ed, nodes, n)])
    Ur = U.reshape(n, 3, -1)[rows].reshape(3 * rows.size, -1)
    got = stress_of_fields(mesh, rows, Ur, 210e9, 0.3, nodes)
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12 * np.abs(ref).max())
    with pytest.raises(MeshError, match="missing"):
        stress_of_fields(mesh, rows[1:], Ur[3:], 210e9, 0.3, nodes)
