"""The whole shaft condensed onto the main-bearing centre planes, and its bearings' couplings.

``build_shaft_model(shaft_mesh, material, options)`` condenses every distinct piece once
(``fe.shaft.substructure``: identical throws share one factorisation; the throws' local
patterns, ``fe.shaft.patterns``), places each piece's condensed stiffness in the shaft
frame (rotation R about z, shift along z) and sums them on the interface unknowns (the
P2 nodes of every bearing-centre plane and of the two free end faces):

    S_G = sum_k P_k^T R_k S_k R_k^T P_k,

a dense matrix of a few thousand unknowns with the six rigid-body modes of the free shaft.

Each main bearing is a reference point on the axis at its centre, coupled to its journal
surface (the two halves that meet at the centre plane) by a distributing coupling (RBE3:
nodal forces f_i = (a_i/A) [F + theta x (x_i - c)], I theta = (x_ref - c) x F, with a_i
the consistent nodal areas, c their centroid and I = sum (a_i/A)(|d_i|^2 1 - d_i d_i^T),
as ``fe.core.determinate``): no stiffness, and the reference point's motion is the work-
conjugate average u_ref . e = sum_i f_i(e) . u_i.  Both are combinations of the surface
patterns P_k, Q_k of ``fe.shaft.patterns`` with the coefficients ``BearingCoupling.terms``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from fe_crank.errors import MeshError
from fe_crank.fe.core.bases import cell_basis
from fe_crank.fe.shaft.patterns import end_patterns, surface_patterns, throw_patterns
from fe_crank.fe.shaft.substructure import Condensed, condense
from fe_crank.fe.throw.node_groups import node_groups
from fe_crank.mesh.shaft import PieceKind, ShaftMesh, joints, rotation


@dataclass(frozen=True)
class ShaftFeOptions:
    solver: str = "auto"
    pin_half_angle: float = np.deg2rad(60.0)
    #: further throw boundaries whose nodes (and their elements' nodes) keep the condensed
    #: fields, beside the assessed groups (``fe.throw.node_groups``: fillets, oil bore,
    #: counterweight fillets and junctions)
    recover: tuple[str, ...] | None = None
    symmetry: bool = True  # mirrored throws condensed on their two symmetry components
    #: keep each distinct piece's factorisation after its condensation, for whole fields
    #: (``fe.shaft.fields``; ``ShaftModel.free_factors`` releases them)
    keep_factors: bool = False
    #: each web's counterweight as a centrifugal pattern of its own (``centrifugal_cw_1``,
    #: ``centrifugal_cw_2``: a counterweight study's per-web mass factors)
    counterweight_webs: bool = False


@dataclass
class PlacedPiece:
    index: int
    name: str
    kind: PieceKind
    throw: str | None
    cond: Condensed
    R: np.ndarray  # (3, 3) local -> shaft frame
    z: float
    dofs: np.ndarray  # (nb,) interface unknowns of cond.b

    def to_shaft(self, v: np.ndarray) -> np.ndarray:
        """Nodal vectors (3 n, ...) from the local frame to the shaft frame."""
        s = v.reshape(-1, 3, *v.shape[1:])
        return np.einsum("ij,nj...->ni...", self.R, s).reshape(v.shape)

    def to_local(self, v: np.ndarray) -> np.ndarray:
        s = v.reshape(-1, 3, *v.shape[1:])
        return np.einsum("ji,nj...->ni...", self.R, s).reshape(v.shape)

    def placed_resultant(self, res: np.ndarray) -> np.ndarray:
        """(6, k) force and moment about the shaft origin of local resultants (6, k)."""
        F = self.R @ res[:3]
        M = self.R @ res[3:] + np.cross(np.array([0.0, 0.0, self.z])[:, None], F, axis=0)
        return np.vstack([F, M])


@dataclass(frozen=True)
class BearingCoupling:
    name: str
    z: float
    #: per unit force direction (x, y, z in the shaft frame): {(piece, pattern): coefficient}
    terms: tuple[dict[tuple[int, str], float], ...]
    area: float  # m^2, the coupled journal surface
    #: per unit moment about x and y (shaft frame), the same coupling's nodal forces: their
    #: work on the surface's displacements is the reference point's rotation (the journal's
    #: mean tilt, ``ShaftCases.slope``)
    rotations: tuple[dict[tuple[int, str], float], ...] = ()


@dataclass
class ShaftModel:
    mesh: ShaftMesh
    pieces: list[PlacedPiece]
    n_interface: int
    S: np.ndarray
    points: np.ndarray  # (3, n_interface / 3) interface nodes, shaft frame
    bearings: list[BearingCoupling]
    torque_term: tuple[int, str]  # where the torque leaves
    moments: dict[tuple[int, str], tuple] = field(default_factory=dict)  # (piece, surface) -> (m0, m1, m2), local
    timings: dict[str, float] = field(default_factory=dict)

    def coupling(self, name: str, z: float, members: list[tuple[int, str]]) -> BearingCoupling:
        """The distributing coupling of a reference point on the axis at ``z`` to the
        surfaces ``members`` ((piece, surface) whose patterns were condensed)."""
        return _coupling(name, z, [(self.pieces[k], s) for k, s in members], self.moments)

    @property
    def n_dof(self) -> int:
        return self.mesh.n_dof

    def free_factors(self) -> None:
        """Release the factorisations kept for whole fields (``ShaftFeOptions.keep_factors``)."""
        for pp in self.pieces:
            pp.cond.free()

    def release_recovery(self) -> None:
        """Drop the condensed fields at the recovery nodes (``Condensed.X_rec``, the model's
        largest arrays) once the stresses there are taken; ``ShaftCases.recover`` then no
        longer works."""
        for pp in self.pieces:
            pp.cond.X_rec = np.zeros((0, pp.cond.X_rec.shape[1]))


def _recovery_nodes(basis, mesh, names) -> np.ndarray:
    """The nodes of every element touching an assessed group's nodes (``fe.throw.node_groups``,
    the counterweight bodies left out: their stress is their own centrifugal load, the
    per-throw model's) or the named boundaries' nodes."""
    from fe_crank.fe.core.stress import elements_of_nodes

    on = [np.asarray(mesh.boundaries[n]) for n in names if n in (mesh.boundaries or {})]
    parts = [basis.get_dofs(np.concatenate(on)).all()] if on else []
    parts += list(node_groups(mesh, basis, bodies=False).values())
    if not parts:
        return np.zeros(0, int)
    nodes = np.unique(np.concatenate(parts))
    el = elements_of_nodes(basis.element_dofs, nodes, basis.N)
    return np.unique(basis.element_dofs[:, el])


def _condense_piece(mesh, kind: PieceKind, stubs, torque_faces, material, opt: ShaftFeOptions, mirrored: bool):
    basis = cell_basis(mesh, 2)
    rho = material.density
    if kind == "throw":
        pats = throw_patterns(basis, rho, opt.pin_half_angle, torque_faces, opt.counterweight_webs)
        rec = _recovery_nodes(basis, mesh, opt.recover or ())
    else:
        pats = end_patterns(basis, rho, torque_faces)
        rec = np.zeros(0, int)
    moments = {}
    for s in stubs:
        p, moments[s] = surface_patterns(basis, s)
        pats.update(p)
    functionals = {k: v for k, v in pats.items() if k.split(".")[0] in stubs}
    cond = condense(
        mesh,
        material.youngs_modulus,
        material.poisson_ratio,
        pats,
        functionals,
        rec,
        basis=basis,
        mirrored=mirrored,
        solver=opt.solver,
        keep=opt.keep_factors,
    )
    return cond, moments


def _coupling(name, z, members, moments) -> BearingCoupling:
    """RBE3 coefficients of a bearing (module doc); members: [(placed piece, surface)]."""
    A, m1, m2 = 0.0, np.zeros(3), np.zeros((3, 3))
    for pp, s in members:
        a, b, c = moments[(pp.index, s)]
        R, zz = pp.R, np.array([0.0, 0.0, pp.z])
        b_g = R @ b + a * zz
        A += a
        m1 += b_g
        m2 += R @ c @ R.T + np.outer(R @ b, zz) + np.outer(zz, R @ b) + a * np.outer(zz, zz)
    c = m1 / A
    M2c = m2 - A * np.outer(c, c)
    inertia = (np.trace(M2c) * np.eye(3) - M2c) / A
    ref = np.array([0.0, 0.0, z])

    def distributed(e: np.ndarray, theta: np.ndarray) -> dict[tuple[int, str], float]:
        t: dict[tuple[int, str], float] = {}
        for pp, s in members:
            w = np.cross(theta, np.array([0.0, 0.0, pp.z]) - c)
            p_coef, q_coef = pp.R.T @ (e + w) / A, pp.R.T @ theta / A
            for m in range(3):
                t[(pp.index, f"{s}.P{m}")] = t.get((pp.index, f"{s}.P{m}"), 0.0) + p_coef[m]
                t[(pp.index, f"{s}.Q{m}")] = t.get((pp.index, f"{s}.Q{m}"), 0.0) + q_coef[m]
        return t

    terms = []
    for k in range(3):
        e = np.zeros(3)
        e[k] = 1.0
        terms.append(distributed(e, np.linalg.solve(inertia, np.cross(ref - c, e))))
    # a unit moment M about x or y: f_i = (a_i / A) theta x (x_i - c), I theta = M
    rotations = tuple(distributed(np.zeros(3), np.linalg.solve(inertia, np.eye(3)[k])) for k in range(2))
    return BearingCoupling(name, z, tuple(terms), A, rotations)


def build_shaft_model(
    sm: ShaftMesh,
    material,
    options: ShaftFeOptions | None = None,
    extra_surfaces: dict | None = None,
    condensed: dict | None = None,
) -> ShaftModel:
    """Condense, place and sum the pieces; couple the bearings (module doc).
    ``extra_surfaces``: mesh key -> further surfaces whose coupling patterns to condense
    (loads by ``ShaftModel.coupling``).  ``condensed``: the throw pieces' condensations
    shared between models of the same throw mesh (its key, ``mesh.cache.cache_key``, names
    its content) placed at other angles or in another sense, by the same material and
    options: read where present, this model's added.  A throw's condensation is made in
    its own frame and does not depend on where the piece is placed; shared, the models
    hold the same arrays (``ShaftModel.release_recovery`` releases them for all)."""
    extra_surfaces = extra_surfaces or {}
    opt = options or ShaftFeOptions()
    t0 = time.perf_counter()
    layout = sm.layout
    last = len(sm.pieces) - 1
    pto = 0 if layout.power_takeoff == "front" else last
    pto_face = "end_1" if layout.power_takeoff == "front" else "end_2"  # a single piece has both
    faces = ("end_1", "end_2")  # torque patterns on both end faces of every piece: one condensation per mesh
    done: dict[tuple, tuple] = {}
    made: list[Condensed] = []  # the condensations made for this model (its timings)
    pieces, moments = [], {}
    for k, p in enumerate(sm.pieces):
        stubs = tuple(s for s, _ in p.bearing_surfaces) + tuple(extra_surfaces.get(p.mesh, ()))
        key = (p.mesh,)
        if key not in done:
            mirrored = opt.symmetry and p.kind == "throw" and 2 in sm.throw_meshes[p.mesh].symmetry
            shared = (p.mesh, stubs, mirrored, material, opt)
            if condensed is not None and p.kind == "throw" and shared in condensed:
                done[key] = condensed[shared]
            else:
                done[key] = _condense_piece(sm.meshes[p.mesh], p.kind, stubs, faces, material, opt, mirrored)
                made.append(done[key][0])
                if condensed is not None and p.kind == "throw":
                    condensed[shared] = done[key]
        cond, mom = done[key]
        pieces.append(PlacedPiece(k, p.name, p.kind, p.throw, cond, rotation(p.angle), p.z, np.zeros(0, int)))
        for s, m in mom.items():
            moments[(k, s)] = m
    t1 = time.perf_counter()
    # interface numbering: piece 0's end_1, then each joint (piece k's end_2 = piece k+1's end_1), last end_2
    pairs = joints(sm)
    nodes_of = []  # per piece: global node number of each of its face nodes (end_1 then end_2 order)
    first = pieces[0].cond.faces["end_1"]
    start = {0: np.arange(first.size)}
    count = first.size
    for k, pp in enumerate(pieces):
        f2 = pp.cond.faces["end_2"]
        g1 = start[k]
        if k < last:
            na, nb = pairs[k]
            g2 = count + np.arange(f2.size)
            count += f2.size
            pos_b = np.searchsorted(pieces[k + 1].cond.faces["end_1"], nb)
            nxt = np.empty(nb.size, np.int64)
            nxt[pos_b] = g2[np.searchsorted(f2, na)]
            start[k + 1] = nxt
        else:
            g2 = count + np.arange(f2.size)
            count += f2.size
        nodes_of.append(np.concatenate([g1, g2]))
    n = 3 * count
    S = np.zeros((n, n))
    pts = np.zeros((3, count))
    for k, pp in enumerate(pieces):
        g = nodes_of[k]
        pp.dofs = (3 * g[:, None] + np.arange(3)).ravel()
        m = g.size
        Rb = np.kron(np.eye(m), pp.R)
        S[np.ix_(pp.dofs, pp.dofs)] += Rb @ pp.cond.S @ Rb.T
        loc = pp.cond.basis.doflocs[:, np.concatenate([pp.cond.faces["end_1"], pp.cond.faces["end_2"]])]
        pts[:, g] = pp.R @ loc + np.array([[0.0], [0.0], [pp.z]])
    bearings = []
    for b in layout.bearings:
        members = _members(pieces, sm, b.journal)
        if not members:
            raise MeshError(f"bearing {b.name!r}: its journal is not part of the model")
        bearings.append(_coupling(b.name, b.z, members, moments))
    model = ShaftModel(sm, pieces, n, 0.5 * (S + S.T), pts, bearings, (pto, f"torque_{pto_face}"), moments)
    model.timings = {"condensation": t1 - t0, "assembly": time.perf_counter() - t1}
    for cond in made:
        for name, v in cond.timings.items():
            model.timings[name] = model.timings.get(name, 0.0) + v
    return model


def _members(pieces, sm: ShaftMesh, journal: int):
    """The (piece, surface) halves of journal ``journal``'s bearing surface."""
    return [(pp, s) for pp, p in zip(pieces, sm.pieces) for s, j in p.bearing_surfaces if j == journal]
