"""The centrifugal unit case split into the throw's own part and each counterweight body's
(``fe.core.loads.BODY_CASES``): their sum is the whole throw's case to round-off, as load
vectors and as solved displacements; each body's resultant is its m r omega^2 integrated
here by quadrature over its elements."""

from __future__ import annotations

import numpy as np
import pytest
from helpers.bar_throw import bar_throw
from helpers.verification_meshes import as_throw_mesh

from fe_crank import fe
from fe_crank.errors import InputError
from fe_crank.fe.core.loads import BODY_CASES, CENTRIFUGAL_PARTS, centrifugal_load, element_basis
from fe_crank.io.material import load_material

PARTS = ("centrifugal_throw", "centrifugal_cw_1", "centrifugal_cw_2")


@pytest.fixture(scope="module")
def mesh():
    m = bar_throw()
    return m.translated((0.0, 0.01, 0.0))  # off the axis: a resultant to compare


def test_parts_sum_to_the_whole_case_and_each_body_is_its_m_r(mesh):
    assert PARTS == CENTRIFUGAL_PARTS
    mat = load_material("42CrMo4")
    units = fe.solve_unit_cases(as_throw_mesh(mesh), mat, fe.FeOptions(solver="superlu", cases=(*PARTS, "torque")))
    whole = fe.solve_unit_cases(as_throw_mesh(mesh), mat, fe.FeOptions(solver="superlu", cases=("centrifugal",)))
    basis = units.system.basis
    f = {c: BODY_CASES[c][0](basis, mat.density) for c in (*PARTS, "centrifugal")}
    scale = np.abs(f["centrifugal"]).max()
    assert np.abs(f[PARTS[0]] + f[PARTS[1]] + f[PARTS[2]] - f["centrifugal"]).max() <= 1e-13 * scale
    assert not f["centrifugal_cw_2"].any()  # the bar has no second counterweight body
    # the body's resultant: rho int (x, y) dV over its elements, by the same quadrature
    cw = np.asarray(mesh.subdomains["counterweight_1"])
    sub = element_basis(basis, cw)
    x = np.asarray(sub.global_coordinates())
    m_r = mat.density * np.einsum("ieq,eq->i", x, sub.dx)
    res = f["centrifugal_cw_1"].reshape(-1, 3).sum(axis=0)
    np.testing.assert_allclose(res[:2], m_r[:2], rtol=0.0, atol=1e-12 * m_r[1])
    assert m_r[1] > 0
    np.testing.assert_array_equal(centrifugal_load(basis, mat.density, 1.0), f["centrifugal"])
    # solved: linear, so the parts' displacements sum to the whole case's
    u = sum(units.displacement(c) for c in PARTS)
    ref = whole.displacement("centrifugal")
    assert np.abs(u - ref).max() <= 1e-10 * np.abs(ref).max()


def test_whole_and_parts_together_are_refused(mesh):
    with pytest.raises(InputError, match="centrifugal is the sum"):
        fe.solve_unit_cases(
            as_throw_mesh(mesh),
            load_material("42CrMo4"),
            fe.FeOptions(solver="superlu", cases=("centrifugal", "centrifugal_cw_1")),
        )
