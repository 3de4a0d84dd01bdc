"""The FE system's reactions, applied resultants and sparse building blocks against
their definitions written out on whole arrays, bit for bit.

Each reference below is the quantity's definition written on the whole vector (3 N
entries): the residual K u + K_s u - (f + G R) over every dof, then read at the
constrained rows; the resultant of the applied loads from a copy of every node's force
and position; the half's stiffness from a basis on the half's elements; the selection of
the free dofs as a COO matrix; the rigid motion built whole, then subtracted; the upper
triangle by ``scipy.sparse.triu``.  The code forms the same sums on the constrained rows
only (or in place, or from the whole basis), in the same order, so the comparison is
exact (``array_equal``, no tolerance): any change of a term or of its summation order
shows as a difference in the last bits.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.verification_meshes import Steel, as_throw_mesh, simple_throw

from fe_crank.fe import solve_unit_cases
from fe_crank.fe.core import symmetric
from fe_crank.fe.core.loads import centrifugal_load, pin_pressure_load
from fe_crank.fe.core.supports import Coupling, Foundation
from fe_crank.fe.core.system import build_system


@pytest.fixture(scope="module")
def throw():
    return simple_throw(size=0.012)


def _resultant_whole(v, x, sdofs):
    fn = v.reshape(-1, 3)[sdofs]
    xs = x[:, sdofs].T
    return np.concatenate([fn.sum(axis=0), np.cross(xs, fn).sum(axis=0)])


def _applied_whole(system, f):
    x = system.points
    fn = f.reshape(-1, 3)
    res = _resultant_whole(f, x, np.arange(x.shape[1]))
    return res, np.linalg.norm(fn, axis=1).sum(), np.linalg.norm(np.cross(x.T, fn), axis=1).sum()


def _reactions_whole(system, u, f):
    """The reactions by the whole-vector residual (determinate supports and foundations)."""
    x = system.points
    out = {}
    if system.determinate is not None:
        R = system.determinate.reactions(f)
        f = f + np.asarray(system.determinate.G @ R).reshape(f.shape)
        out.update(system.determinate.reaction_resultants(R))
    rs = -(system.Ks @ u)
    for name, sdofs in system.foundation_dofs.items():
        out[name] = _resultant_whole(rs, x, sdofs)
    resid = np.zeros_like(u)
    resid[system.rows] = system.K_rows @ u + (system.Ks @ u)[system.rows] - f[system.rows]
    for c in system.couplings:
        out[c.boundary] = _resultant_whole(resid, x, system.slave_dofs[c.boundary])
    if system.point_dofs.size:
        rp = np.zeros_like(u)
        pos = np.searchsorted(system.rows, system.point_dofs)
        rp[system.point_dofs] = system.K_rows[pos] @ u + (system.Ks @ u)[system.point_dofs] - f[system.point_dofs]
        out["point_constraints"] = _resultant_whole(rp, x, np.unique(system.point_dofs // 3))
    return out


def _assert_same(a: dict, b: dict):
    assert set(a) == set(b)
    for k in a:
        assert np.array_equal(a[k], b[k]), k


def test_determinate_reactions_and_applied_equal_the_whole_vector_formulas(throw):
    unit = solve_unit_cases(as_throw_mesh(throw), Steel())
    system = unit.system
    basis = system.basis
    for f in (centrifugal_load(basis, 7850.0, 1.0), pin_pressure_load(basis, (3.0e4, -5.0e4))[0]):
        u = system.solve(f)
        res, fs, ms = system.applied(f)
        ref = _applied_whole(system, f)
        assert np.array_equal(res, ref[0]) and fs == ref[1] and ms == ref[2]
        _assert_same(system.reactions(u, f), _reactions_whole(system, u, f))
        err, _ = system.equilibrium_error(u, f)
        assert err == system.equilibrium_error(u, f, applied=ref)[0] < 1e-9
    for name, case in unit.cases.items():  # the records of the stage itself
        assert np.array_equal(case.applied, _applied_whole(system, _load(unit, name))[0]), name


def _load(unit, name):
    basis = unit.system.basis
    if name == "centrifugal":
        return centrifugal_load(basis, 7850.0, 1.0)
    from fe_crank.fe.core.loads import face_torque_load
    from fe_crank.fe.core.loads import pin_pressure_load as ppl
    from fe_crank.fe.throw.pin_directions import unit_force

    if name == "torque":
        return face_torque_load(basis, -1.0, boundary=unit.options.torque_face)
    return ppl(basis, unit_force(name), boundary=unit.options.pin_boundary, half_angle=unit.options.pin_half_angle)[0]


def test_foundation_and_coupling_reactions_equal_the_whole_vector_formulas(throw):
    mesh = getattr(throw, "mesh", throw)
    system = build_system(
        mesh,
        210e9,
        0.3,
        foundations=[Foundation("journal_1", 1e13), Foundation("journal_2", 1e13)],
        couplings=[Coupling("end_2", fixed=("uz", "rz"))],
    )
    f = pin_pressure_load(system.basis, (1.0e4, 2.0e4))[0]
    u = system.solve(f)
    _assert_same(system.reactions(u, f), _reactions_whole(system, u, f))


@pytest.fixture(scope="module")
def shipped(tmp_path_factory):
    """The shipped single-cylinder throw at ``test``: curved P2 elements, mirrored across z = 0."""
    from helpers.paths import ROOT

    from fe_crank.io.geometry import load_geometry
    from fe_crank.mesh import mesh_throw

    return mesh_throw(
        load_geometry(ROOT / "geometry" / "single_cylinder.toml"),
        size="test",
        cache_dir=tmp_path_factory.mktemp("meshes"),
    )


def test_part_stiffness_equals_the_part_basis_route(shipped):
    """The symmetric path's half stiffness: from the whole basis in the part's numbering
    (``assembly.part_stiffness``) against a basis on the part's elements assembled in the
    whole numbering and indexed down, K[ldofs][:, ldofs] -- the same CSR bit for bit."""
    import scipy.sparse as sp
    from skfem import Basis

    from fe_crank.fe.core.assembly import assemble_stiffness, part_stiffness
    from fe_crank.fe.core.bases import cell_basis

    mesh = shipped.mesh
    basis = cell_basis(mesh, 2)
    el = basis.element_dofs
    part = np.flatnonzero(basis.doflocs[2, el[:4]].mean(axis=0) > 0)
    nodes = np.unique(el[:, part])
    ldofs = (3 * nodes[:, None] + np.arange(3)).ravel()
    pb = Basis(mesh, basis.elem, mapping=basis.mapping, quadrature=(basis.X, basis.W), dofs=basis.dofs, elements=part)
    defined = sp.triu(assemble_stiffness(pb, 210e9, 0.3)[ldofs][:, ldofs], format="csr")
    defined.sort_indices()
    got = sp.triu(part_stiffness(basis, part, nodes, 210e9, 0.3), format="csr")
    got.sort_indices()
    assert defined.shape == got.shape
    for a in ("indptr", "indices", "data"):
        assert np.array_equal(getattr(defined, a), getattr(got, a)), a


def test_selection_equals_the_coo_route():
    import scipy.sparse as sp

    from fe_crank.fe.core.system import selection

    n, held = 3000, np.array([5, 6, 17, 1200, 2999, 0])
    rows = np.unique(held)
    free = np.setdiff1d(np.arange(n), rows)
    defined = sp.csr_matrix((np.ones(free.size), (free, np.arange(free.size))), shape=(n, free.size))
    got = selection(n, rows)
    assert defined.shape == got.shape
    for a in ("indptr", "indices", "data"):
        assert np.array_equal(getattr(defined, a), getattr(got, a)), a


def test_rigid_motion_removed_in_place_equals_the_whole_array_route():
    """``symmetric._remove_rigid_fit`` (blocks of nodes, in place) against U - B a with the
    whole rigid motion built, then subtracted: the same bits, on a node count that is not
    a multiple of the block, and the held dofs end at zero to round-off."""
    rng = np.random.default_rng(7)
    N, k = 3 * symmetric.RIGID_BLOCK + 17, 5
    x = rng.uniform(-0.1, 0.1, (3, N))
    U = rng.normal(size=(3 * N, k))
    held = np.array([0, 1, 2, 3 * 40 + 1, 3 * 40 + 2, 3 * 977])
    defined = U - _rigid_fit_whole(x, held, U)
    got = U.copy()
    symmetric._remove_rigid_fit(x, held, got)
    assert np.array_equal(defined, got)
    assert np.abs(got[held]).max() < 1e-12 * np.abs(U).max()


def test_component_matrices_equal_the_masked_half_triangle():
    """Each symmetry component's matrix (plane conditions and held dofs as unit rows with
    explicit-zero couplings) against a masking of the half's triangle -- a copy of it
    per component, the entry's row from an nnz-long row array: the same CSR bit for bit."""
    import scipy.sparse as sp
    from helpers.symmetric_meshes import mirrored_throw

    from fe_crank.fe.core.assembly import part_stiffness
    from fe_crank.fe.core.bases import cell_basis
    from fe_crank.fe.core.symmetric import build_symmetric_solver, mesh_mirror

    throw = mirrored_throw((0, 2), size=0.016)
    basis = cell_basis(throw.mesh, 2)
    mirror = mesh_mirror(throw.mesh, basis, throw.symmetry)
    solver = build_symmetric_solver(basis, mirror, 210e9, 0.3, np.arange(6), "auto")
    el = basis.element_dofs
    centroid = basis.doflocs[:, el[:4]].mean(axis=1)
    part = np.flatnonzero(np.all([centroid[a] > 0 for a in mirror.axes], axis=0))
    nodes = np.unique(el[:, part])
    Kq = sp.triu(part_stiffness(basis, part, nodes, 210e9, 0.3), format="csr")
    Kq.sort_indices()
    rows = np.repeat(np.arange(Kq.shape[0]), np.diff(Kq.indptr))
    assert len(solver.components) == 4
    for comp in solver.components:
        A = Kq.copy()
        A.data[comp.constrained[rows] | comp.constrained[A.indices]] = 0.0
        A.data[A.indptr[:-1][comp.constrained]] = 1.0
        if comp.factor.matrix is None:  # PARDISO, CHOLMOD: the upper triangle
            want, got = A, comp.factor._upper
        else:  # SuperLU: the whole matrix
            want, got = (A + A.T - sp.diags(A.diagonal())).tocsr(), comp.factor.matrix.tocsr()
            want.sort_indices()
            got.sort_indices()
        for a in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(want, a), getattr(got, a)), a


def test_upper_triangle_equals_scipy_triu(shipped):
    """``assembly.upper_triangle`` against ``scipy.sparse.triu``: the shipped throw's
    stiffness (explicit zeros and all), and a small matrix with empty rows at both ends."""
    import scipy.sparse as sp

    from fe_crank.fe.core.assembly import assemble_stiffness, upper_triangle
    from fe_crank.fe.core.bases import cell_basis

    K = assemble_stiffness(cell_basis(shipped.mesh, 2), 210e9, 0.3)
    S = sp.csr_matrix(
        (np.array([1.0, 0.0, 2.0, 3.0, 4.0, 5.0]), np.array([1, 2, 0, 3, 1, 2]), np.array([0, 0, 2, 4, 6, 6, 6])),
        shape=(6, 6),
    )
    for M in (K, S):
        want, got = sp.triu(M, format="csr"), upper_triangle(M)
        assert want.shape == got.shape
        for a in ("indptr", "indices", "data"):
            assert np.array_equal(getattr(want, a), getattr(got, a)), a


def _rigid_fit_whole(x, held, U):
    """The rigid motion B a with (B a)[held] = U[held], built whole."""
    a = symmetric._rigid_coefficients(x, held, U)
    Un = np.zeros((x.shape[1], 3, U.shape[1]))
    Un += a[None, :3, :]
    Un += np.cross(a[3:].T[:, None, :], x.T[None, :, :]).transpose(1, 2, 0)  # theta x x
    return Un.reshape(U.shape)
