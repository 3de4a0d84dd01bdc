"""The statically determinate support (``fe_crank.fe.core.determinate``) on tiny meshes, by statics.

The main model is a square bar (scikit-fem tensor mesh, straight P2 tets: every area,
centroid and resultant is exact to round-off) along z from -50 to +50 mm, 20 x 20 mm:
``journal_1`` / ``journal_2`` are its four side faces over -50..-30 mm / 30..50 mm,
``end_1`` / ``end_2`` its end faces.  The reference points of IACS UR M53 2.1 (simple
supports at the main-bearing centres, here the end-face centres (0, 0, -+0.05) m) give
reactions that follow from the six equilibrium equations alone; they are worked out by
hand for a point force below and the code must reproduce them to round-off (1e-12 of the
load: the arithmetic is a 6 x 6 solve on exact resultants).  A gmsh round bar checks the
same on curved (isoparametric) surfaces, to its mesh asymmetry.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla
from helpers.square_bar import LJ, Z1, Z2
from helpers.square_bar import square_bar as _square_bar
from helpers.verification_meshes import _mesh, _name_surfaces
from skfem import Basis, ElementTetP2

from fe_crank.errors import MeshError, SolverError
from fe_crank.fe.core.assembly import assemble_stiffness
from fe_crank.fe.core.determinate import (
    DeterminateLayout,
    _resultants,
    bearing_surface_load,
    determinate_support,
    face_centre,
    point_constraints,
    transfer_moment_load,
)
from fe_crank.fe.core.loads import pin_pressure_load
from fe_crank.fe.core.supports import rigid_body_modes
from fe_crank.gmsh_io import gmsh_session

TOL = 1e-12


@pytest.fixture(scope="module")
def bar():
    return Basis(_square_bar(), ElementTetP2(), intorder=2)


@pytest.fixture
def support(bar):
    # function scope: built inside each test that uses it (mutation testing maps each
    # function to the tests that call it; a module fixture would credit the first only)
    return determinate_support(bar, DeterminateLayout())


def _resultant(f, x, about=(0.0, 0.0, 0.0)):
    """(F, M about ``about``) of a nodal load vector, written out here."""
    F = f.reshape(-1, 3)
    return np.concatenate([F.sum(axis=0), np.cross(x.T - np.asarray(about), F).sum(axis=0)])


def test_layout_defaults_are_the_documented_ones():
    lay = DeterminateLayout()
    assert lay.journals == ("journal_1", "journal_2")
    assert lay.torque_face == "end_2"
    assert lay.axial == "journal_2"
    assert lay.centre_faces == ("end_1", "end_2")


def test_bearing_weights_are_the_p2_facet_integrals(bar):
    """journal_1: four sides 20 x 20 mm, A = 4 x 0.02 x 0.02 = 1.6e-3 m^2, in 16 right
    triangles of 1e-4 m^2 (each side: 2 x 1 rectangles, split in 2).  On a flat P2 triangle
    int N_i dA is 0 at the corners and A_t / 3 at the mid-edge nodes, so each mid-edge node
    weighs (1e-4 / 3) / 1.6e-3 = 1/48 per triangle it touches: 1/48 or 1/24."""
    w, c, area = bearing_surface_load(bar, "journal_1")
    assert area == pytest.approx(1.6e-3, rel=TOL)
    np.testing.assert_allclose(c, (0.0, 0.0, -0.04), rtol=0, atol=1e-15)
    assert w.sum() == pytest.approx(1.0, rel=TOL)
    nz = w[np.abs(w) > 1e-14]
    assert np.all(np.isclose(nz, 1 / 48, rtol=1e-12) | np.isclose(nz, 1 / 24, rtol=1e-12))
    n48, n24 = np.isclose(nz, 1 / 48, rtol=1e-12).sum(), np.isclose(nz, 1 / 24, rtol=1e-12).sum()
    assert n48 + 2 * n24 == 16 * 3  # 16 triangles x 3 mid-edge nodes
    # the weights' centroid is the area centroid (P2 interpolates x exactly)
    np.testing.assert_allclose(bar.doflocs @ w, c, rtol=0, atol=1e-15)
    np.testing.assert_allclose(face_centre(bar, "end_1"), (0.0, 0.0, Z1), rtol=0, atol=1e-15)
    np.testing.assert_allclose(face_centre(bar, "end_2"), (0.0, 0.0, Z2), rtol=0, atol=1e-15)
    np.testing.assert_allclose(face_centre(bar, "journal_2"), (0.0, 0.0, 0.04), rtol=0, atol=1e-15)


def test_transfer_moment_load_by_hand():
    """Four unit-distance points about c with weights 1/4 (and a fifth of weight 0):
    I = sum w (|d|^2 1 - d d^T) = 1 - diag(1/2, 1/2, 0) = diag(1/2, 1/2, 1).
    M = (0, 0, 2): theta = (0, 0, 2); f_i = w_i theta x d_i, e.g. at d = (1, 0, 0):
    (0, 0, 2) x (1, 0, 0) / 4 = (0, 0.5, 0).  M = (1, 0, 0): theta = (2, 0, 0), at
    d = (0, 1, 0): (2, 0, 0) x (0, 1, 0) / 4 = (0, 0, 0.5), at d = (1, 0, 0): 0."""
    c = np.array([5.0, -3.0, 2.0])  # anywhere: only d = x - c matters
    d = np.array([[1.0, 0, 0], [0, 1.0, 0], [-1.0, 0, 0], [0, -1.0, 0], [0.3, 0.7, 0.1]])
    x = (d + c).T
    w = np.array([0.25, 0.25, 0.25, 0.25, 0.0])
    f = transfer_moment_load(w, x, c, np.array([0.0, 0.0, 2.0])).reshape(-1, 3)
    np.testing.assert_allclose(f, [[0, 0.5, 0], [-0.5, 0, 0], [0, -0.5, 0], [0.5, 0, 0], [0, 0, 0]], atol=1e-15)
    f = transfer_moment_load(w, x, c, np.array([1.0, 0.0, 0.0])).reshape(-1, 3)
    np.testing.assert_allclose(f, [[0, 0, 0], [0, 0, 0.5], [0, 0, 0], [0, 0, -0.5], [0, 0, 0]], atol=1e-15)
    # a general moment: no force, the moment about c (and so about any point)
    M = np.array([0.3, -1.1, 0.7])
    f = transfer_moment_load(w, x, c, M)
    np.testing.assert_allclose(_resultant(f, x, c), (0, 0, 0, *M), atol=1e-15)
    np.testing.assert_allclose(_resultant(f, x, np.array([9.0, 1.0, -4.0])), (0, 0, 0, *M), atol=1e-14)


def test_resultants_by_hand():
    # nodes (1, 0, 0) and (0, 2, 0) with forces (0, 3, 0) and (1, 0, 5):
    # F = (1, 3, 5); M = (1,0,0) x (0,3,0) + (0,2,0) x (1,0,5) = (0,0,3) + (10, 0, -2) = (10, 0, 1)
    x = np.array([[1.0, 0.0], [0.0, 2.0], [0.0, 0.0]])
    f = np.array([0.0, 3.0, 0.0, 1.0, 0.0, 5.0])
    np.testing.assert_array_equal(_resultants(f, x), [1, 3, 5, 10, 0, 1])
    two = _resultants(np.column_stack([f, -2 * f]), x)
    assert two.shape == (6, 2)
    np.testing.assert_array_equal(two[:, 1], [-2, -6, -10, -20, 0, -2])


def _point_load(bar, at, P):
    i = int(np.flatnonzero(np.all(np.isclose(bar.doflocs.T, at, atol=1e-12), axis=1))[0])
    f = np.zeros(3 * bar.N)
    f[3 * i : 3 * i + 3] = P
    return f


# P = (3, -4, 2) N at rp = (0.01, 0.01, 0.01) m; supports on the axis at z1 = -0.05 (x, y),
# z2 = +0.05 (x, y, z), torque about z at end_2.  Moments about r1 = (0, 0, z1), L = 0.1 m,
# rp - r1 = (0.01, 0.01, 0.06):
#   x: 0.01 x 2 - 0.06 x (-4) - L R2y = 0 -> R2y = 0.26 / 0.1 = 2.6
#   y: 0.06 x 3 - 0.01 x 2 + L R2x = 0 -> R2x = -0.16 / 0.1 = -1.6
#   z: 0.01 x (-4) - 0.01 x 3 + Mz = 0 -> Mz = 0.07
#   forces: R1x = -3 - R2x = -1.4, R1y = 4 - R2y = 1.4, R2z = -2
AT, P = (0.01, 0.01, 0.01), (3.0, -4.0, 2.0)
R_HAND = (-1.4, 1.4, -1.6, 2.6, -2.0, 0.07)


def test_columns_reactions_and_their_resultants_by_statics(bar, support):
    s = support
    assert s.layout == DeterminateLayout()
    np.testing.assert_array_equal(s.points, bar.doflocs)
    assert s.names == ("journal_1.Fx", "journal_1.Fy", "journal_2.Fx", "journal_2.Fy", "journal_2.Fz", "end_2.Mz")
    assert s.owner == ("journal_1", "journal_1", "journal_2", "journal_2", "journal_2", "end_2")
    np.testing.assert_allclose(s.centres["journal_1"], (0, 0, Z1), atol=1e-15)
    np.testing.assert_allclose(s.centres["journal_2"], (0, 0, Z2), atol=1e-15)
    # each column: a unit force at its bearing centre, moment r x e = (-z e_y, z e_x, 0); the torque (0,..,1)
    A_hand = np.array(
        [
            [1, 0, 0, 0, Z1, 0],
            [0, 1, 0, -Z1, 0, 0],
            [1, 0, 0, 0, Z2, 0],
            [0, 1, 0, -Z2, 0, 0],
            [0, 0, 1, 0, 0, 0],
            [0, 0, 0, 0, 0, 1],
        ],
        float,
    ).T
    np.testing.assert_allclose(s.A, A_hand, rtol=0, atol=TOL)
    G = s.G.toarray()
    for k in range(6):
        np.testing.assert_allclose(_resultant(G[:, k], bar.doflocs), A_hand[:, k], rtol=0, atol=TOL)
    f = _point_load(bar, AT, P)
    R = s.reactions(f)
    np.testing.assert_allclose(R, R_HAND, rtol=0, atol=TOL * 5)
    # per support (F, M about the origin): journal_1 (-1.4, 1.4, 0) at z1: M = (-z1 Ry, z1 Rx, 0) = (0.07, 0.07, 0)
    # journal_2 (-1.6, 2.6, -2) at z2: M = (-0.05 x 2.6, 0.05 x (-1.6), 0) = (-0.13, -0.08, 0); end_2: Mz = 0.07
    rr = s.reaction_resultants(R)
    assert set(rr) == {"journal_1", "journal_2", "end_2"}
    np.testing.assert_allclose(rr["journal_1"], (-1.4, 1.4, 0, 0.07, 0.07, 0), atol=TOL * 5)
    np.testing.assert_allclose(rr["journal_2"], (-1.6, 2.6, -2.0, -0.13, -0.08, 0), atol=TOL * 5)
    np.testing.assert_allclose(rr["end_2"], (0, 0, 0, 0, 0, 0.07), atol=TOL * 5)
    # with them applied the load is self-equilibrated, about any point
    g, R2 = s.self_equilibrated(f)
    np.testing.assert_array_equal(R2, R)
    for about in (np.zeros(3), np.array([0.3, -0.2, 1.0])):
        assert np.abs(_resultant(g, bar.doflocs, about)).max() < TOL * 5
    np.testing.assert_array_equal(g - f, s.G @ R)
    # several loads at once: column by column the same
    F2 = np.column_stack([f, -3 * f])
    np.testing.assert_allclose(s.reactions(F2), np.column_stack([R, -3 * R]), rtol=0, atol=TOL * 20)
    g2, _ = s.self_equilibrated(F2)
    np.testing.assert_allclose(g2[:, 1], -3 * g, rtol=0, atol=TOL * 20)


def test_other_layouts_move_the_reactions_as_statics_says(bar):
    # axial support and torque at the first journal / end: R1z = -2, Mz = 0.07 at end_1, the rest unchanged
    s = determinate_support(bar, DeterminateLayout(torque_face="end_1", axial="journal_1"))
    assert s.names == ("journal_1.Fx", "journal_1.Fy", "journal_1.Fz", "journal_2.Fx", "journal_2.Fy", "end_1.Mz")
    R = s.reactions(_point_load(bar, AT, P))
    np.testing.assert_allclose(R, (-1.4, 1.4, -2.0, -1.6, 2.6, 0.07), rtol=0, atol=TOL * 5)
    # reference points at the journals' own centroids (z = -+0.04): L = 0.08, rp - r1 = (0.01, 0.01, 0.05):
    #   R2y = (0.01 x 2 + 0.05 x 4) / 0.08 = 2.75,  R2x = -(0.05 x 3 - 0.01 x 2) / 0.08 = -1.625
    #   R1x = -3 + 1.625 = -1.375,  R1y = 4 - 2.75 = 1.25
    s = determinate_support(bar, DeterminateLayout(centre_faces=None))
    np.testing.assert_allclose(s.centres["journal_1"], (0, 0, -0.04), atol=1e-15)
    R = s.reactions(_point_load(bar, AT, P))
    np.testing.assert_allclose(R, (-1.375, 1.25, -1.625, 2.75, -2.0, 0.07), rtol=0, atol=TOL * 5)


def test_six_point_constraints_remove_the_rigid_body_modes_and_carry_nothing(bar, support):
    x = bar.doflocs
    held = support.held
    assert held.shape == (6,) and len(set(held.tolist())) == 6
    # on the end faces (the candidates)
    assert np.all(np.isclose(np.abs(x[2, held // 3]), Z2, atol=1e-15))
    # the rigid-body modes restricted to the held dofs are independent: u[held] = 0 admits no rigid motion
    B = rigid_body_modes(x)[held]
    sv = np.linalg.svd(B / np.abs(B).max(axis=0), compute_uv=False)
    assert sv.min() > 1e-3 * sv.max()
    # a real solve: K (E = 210 GPa) without the held dofs is positive definite, and the
    # self-equilibrated load leaves no reaction at the held dofs (round-off of the load scale)
    K = assemble_stiffness(bar, 210e9, 0.3).tocsc()
    free = np.setdiff1d(np.arange(3 * bar.N), held)
    Kff = K[free][:, free]
    assert np.linalg.eigvalsh(Kff.toarray()).min() > 1e-6 * spla.norm(Kff, 1)
    g, _ = support.self_equilibrated(_point_load(bar, AT, P))
    u = np.zeros(3 * bar.N)
    u[free] = spla.spsolve(Kff, g[free])
    reaction = K[held] @ u - g[held]
    assert np.abs(reaction).max() < 1e-9 * np.linalg.norm(P)


def test_three_points_take_a_3_2_1_set():
    """Nodes (0,0,0), (1,0,0), (0,1,0): six independent dofs exist among their nine (e.g. z at
    all three: no z translation, no rotation about x or y; y at the two on the x axis: no y
    translation, no rotation about z; x at the third: no x translation).  The chosen six must
    be such a set: the rigid-body modes at them form a nonsingular 6 x 6 matrix."""
    P = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]])
    held = point_constraints(P, np.arange(3))
    assert held.shape == (6,) and len(set(held.tolist())) == 6 and held.max() < 9
    assert held.dtype.kind == "i"
    assert abs(np.linalg.det(rigid_body_modes(P)[held])) > 0.1  # |det| of a 3-2-1 set here: 1


def test_point_constraint_choice_does_not_depend_on_the_unit_of_length(bar):
    x = bar.doflocs
    cand = np.flatnonzero(np.abs(np.abs(x[2]) - Z2) < 1e-12)
    held = point_constraints(x, cand)
    for scale in (1e3, 1e-3):
        np.testing.assert_array_equal(point_constraints(x * scale, cand), held)
    assert np.all(np.isin(held // 3, cand))


def test_refusals(bar):
    with pytest.raises(MeshError) as e:
        determinate_support(bar, DeterminateLayout(axial="journal_3"))
    assert str(e.value) == "axial support 'journal_3' is not one of the journals ('journal_1', 'journal_2')"
    # both bearing centres at end_1: the two x (and y) reactions act on one line
    with pytest.raises(SolverError) as e:
        determinate_support(bar, DeterminateLayout(centre_faces=("end_1", "end_1")))
    assert str(e.value) == "determinate supports cannot balance every load (bearing centres coincide?)"
    # candidates on one line (the nodes on the bar's axis): the rotation about it stays free
    x = bar.doflocs
    line = np.flatnonzero((np.abs(x[0]) < 1e-12) & (np.abs(x[1]) < 1e-12))
    assert line.size >= 6
    with pytest.raises(MeshError) as e:
        point_constraints(x, line)
    assert str(e.value) == ("cannot pick six point constraints against the rigid-body modes (end faces degenerate?)")
    with pytest.raises(MeshError, match="boundary 'end_3'"):
        determinate_support(bar, DeterminateLayout(), candidate_faces=("end_1", "end_3"))


def _round_bar(size=0.008):
    """Round bar R 20 mm on the z axis, -50..50 mm: journal_1 / crankpin / journal_2 lateral faces."""
    with gmsh_session() as gmsh:
        occ = gmsh.model.occ
        a = occ.addCylinder(0, 0, Z1, 0, 0, LJ, 0.02)
        b = occ.addCylinder(0, 0, Z1 + LJ, 0, 0, 0.06, 0.02)
        c = occ.addCylinder(0, 0, Z2 - LJ, 0, 0, LJ, 0.02)
        occ.fragment([(3, a)], [(3, b), (3, c)])  # three conformal volumes: the side faces stay apart
        occ.synchronize()

        def classify(kind, cm, bb):
            if abs(bb[5] - Z1) < 1e-6:
                return "end_1"
            if abs(bb[2] - Z2) < 1e-6:
                return "end_2"
            if kind == "Cylinder":
                return "journal_1" if cm[2] < Z1 + LJ else "journal_2" if cm[2] > Z2 - LJ else "crankpin"
            return None

        _name_surfaces(gmsh, classify)
        return _mesh(gmsh, size * 0.5, size)


def test_round_bar_pin_load_is_shared_by_the_lever_rule():
    """Cosine pressure of F = (0, -1000) N centred at z = 0 between bearing centres at -+50 mm:
    R1 = R2 = +500 N in y; no x, z or torque reaction (a radial traction about the crank axis).
    To the mesh's asymmetry: 1e-4 of the load and of F R for the torque (measured 1.6e-5 and
    1.5e-6 at 8 mm elements); a reference point off by one element (8 mm) moves R by 8 %."""
    basis = Basis(_round_bar(), ElementTetP2(), intorder=2)
    s = determinate_support(basis, DeterminateLayout())
    np.testing.assert_allclose(s.centres["journal_1"], (0, 0, Z1), atol=1e-6)
    f, _ = pin_pressure_load(basis, (0.0, -1000.0))
    R = s.reactions(f)
    np.testing.assert_allclose(R[:5], (0.0, 500.0, 0.0, 500.0, 0.0), atol=0.05)
    assert abs(R[5]) < 1e-4 * 1000 * 0.02
    g, _ = s.self_equilibrated(f)
    res = _resultant(g, basis.doflocs)
    assert np.abs(res[:3]).max() < 1e-9 * 1000 and np.abs(res[3:]).max() < 1e-9 * 1000 * 0.05
