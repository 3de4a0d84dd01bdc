"""The whole crankshaft's mesh as pieces joined node to node at the main-bearing centres.

``mesh_shaft(layout, size=...)`` meshes each distinct throw once (``mesh_throw``, cached;
the journal stubs reach the bearing centres, ``geometry.engine_fit.throw_at_bearings``, and the
end faces are split into rotated-copy sectors, ``mesh.interface``, so that throws turned
by the engine's angles meet with the same nodes) and builds the outer halves of the end
journals by extruding the end throws' faces (``mesh.extrude``).  Pieces front to rear:
[front end journal], throw 1, ..., throw n, [rear end journal]; piece k's ``end_2`` meets
piece k+1's ``end_1`` at a main-bearing centre plane.  A piece's local frame goes into the
shaft frame (the engine frame at crank angle zero) turned by ``angle`` from +y towards +x
and shifted by ``z`` along the axis.

``ShaftMesh.whole()`` is the conforming mesh of the whole shaft (the pieces placed and
their common nodes merged, for pictures and output): boundaries named ``<name>@<throw>``
for every throw boundary (``crankpin_fillet_1@2``: throw "2"), ``journal@<bearing>`` for
each main bearing's journal surface (both halves), ``end_front``/``end_rear``.  The nose
and flange of ``[shaft]`` are not meshed: beyond the end bearings they carry no load but
the torque, which leaves through the end journal's face as the exact shear flow of a
round shaft (docs/shaft.md).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

import numpy as np
from scipy.spatial import cKDTree
from skfem import Mesh

from fe_crank.errors import InputError, MeshError
from fe_crank.geometry.shaft import PlacedThrow, ShaftLayout
from fe_crank.mesh.build import mesh_throw
from fe_crank.mesh.cache import cache_key
from fe_crank.mesh.extrude import extrude, face_disc
from fe_crank.mesh.interface import MAX_SECTORS, sectors_for
from fe_crank.mesh.options import DEFAULT_CACHE_DIR, MeshOptions, resolve_options
from fe_crank.mesh.types import ThrowMesh

#: a piece of the shaft: a throw, or an end (nose, flange and the end journals)
PieceKind = Literal["throw", "end"]

#: nodes closer than this fraction of the journal radius are the same node of two pieces
JOIN_TOL = 1e-9


@dataclass(frozen=True)
class Piece:
    name: str  # "throw 1", "front end", "rear end"
    kind: PieceKind
    mesh: str  # key into ShaftMesh.meshes
    angle: float  # rad, local frame -> shaft frame, from +y towards +x
    z: float  # m, local origin on the axis
    throw: str | None = None
    #: (surface, journal index) of each of its surfaces that is half a main bearing's journal
    bearing_surfaces: tuple[tuple[str, int], ...] = ()


@dataclass(frozen=True)
class ShaftMesh:
    layout: ShaftLayout
    meshes: dict[str, Mesh]  # key -> skfem MeshTet2 (local frame)
    throw_meshes: dict[str, ThrowMesh]  # key -> the cached throw mesh
    pieces: tuple[Piece, ...]
    sectors: int
    options: MeshOptions

    @property
    def n_dof(self) -> int:
        """Unknowns of the joined whole mesh (3 per P2 node, common nodes once)."""
        total = sum(3 * self.meshes[p.mesh].doflocs.shape[1] for p in self.pieces)
        shared = sum(3 * _face_nodes(self.meshes[p.mesh], "end_2").size for p in self.pieces[:-1])
        return total - shared

    def placed_points(self, k: int) -> np.ndarray:
        """(3, N) node coordinates of piece k in the shaft frame."""
        p = self.pieces[k]
        return place(np.asarray(self.meshes[p.mesh].doflocs), p.angle, p.z)

    def whole(self):
        """The joined conforming mesh of the whole shaft (module doc)."""
        return join(self)


def rotation(angle: float) -> np.ndarray:
    """3x3: local -> shaft frame, turned by ``angle`` from +y towards +x about z."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def place(x: np.ndarray, angle: float, z: float) -> np.ndarray:
    out = rotation(angle) @ x
    out[2] += z
    return out


def _face_nodes(mesh, name: str) -> np.ndarray:
    """P2 node numbers of a named face: its vertices and its edges' nodes (the doflocs of a
    ``MeshTet2`` are the vertices, then one node per edge in ``mesh.edges`` order)."""
    f = np.asarray(mesh.boundaries[name])
    return np.unique(np.concatenate([mesh.facets[:, f].ravel(), mesh.nvertices + mesh.f2e[:, f].ravel()]))


def throw_angles(layout: ShaftLayout) -> list[float]:
    """Each throw's angle in the shaft frame (from +y towards +x): sense x angle."""
    return [layout.sense * t.angle for t in layout.throws]


def shaft_options(layout: ShaftLayout, size: str | MeshOptions = "coarse", min_sectors: int = 1) -> MeshOptions:
    """The throws' mesh options on the shaft: ``size``'s with the end faces split into the
    sectors that let the turned throws meet node to node (module doc); the per-throw
    model meshed with these shares the whole shaft's throw meshes (cache).  ``min_sectors``:
    at least so many (a drawn throw's end faces are split into two at least, so that its
    rear face's mesh is a translated copy of its front face's, ``fe_crank.cad.whole``)."""
    angles = throw_angles(layout)
    steps = [b - a for a, b in zip(angles, angles[1:])]
    n = sectors_for(steps)
    if n == 0:
        raise InputError(
            f"the angles between adjacent throws ({', '.join(f'{math.degrees(a):g}' for a in steps)} deg) are "
            f"not multiples of 360/{MAX_SECTORS} deg: the throws' meshes cannot be joined node to node",
            file=layout.geometry_file,
            key="throws",
        )
    if n < min_sectors:  # a multiple of n: every angle stays a multiple of 2 pi / n
        n *= -(-min_sectors // n)
    return dataclasses.replace(resolve_options(size), interface_sectors=n)


def mesh_shaft(
    layout: ShaftLayout,
    *,
    size: str | MeshOptions = "coarse",
    cache_dir=DEFAULT_CACHE_DIR,
    max_elements: int | None = None,
    throw_mesh: Callable[[PlacedThrow, MeshOptions], tuple[str, ThrowMesh]] | None = None,
    min_sectors: int = 1,
) -> ShaftMesh:
    """Mesh the whole shaft as joined pieces (module doc).  ``throw_mesh``: (key, mesh)
    of a placed throw meshed with the given options (its end faces split into their
    sectors), for a shaft whose throws are not the layout's parametric ones (a drawn
    shaft, ``fe_crank.cad.whole``); default ``mesh_throw`` of the layout's geometry;
    ``min_sectors``: ``shaft_options``'s."""
    angles = throw_angles(layout)
    opt = shaft_options(layout, size, min_sectors)
    n = opt.interface_sectors
    g = layout.geometry
    meshes, throw_meshes, pieces = {}, {}, []
    keys = []
    for t, a in zip(layout.throws, angles):
        if throw_mesh is not None:
            key, tm = throw_mesh(t, opt)
            meshes[key], throw_meshes[key] = tm.mesh, tm
        else:
            key = cache_key(g, t.spec, opt)
        if key not in meshes:
            tm = mesh_throw(g, t.spec, size=opt, cache_dir=cache_dir, max_elements=max_elements)
            meshes[key], throw_meshes[key] = tm.mesh, tm
        keys.append(key)
        i = t.index
        pieces.append(Piece(f"throw {t.name}", "throw", key, a, t.z, t.name, (("journal_1", i), ("journal_2", i + 1))))
    first, last = layout.journals[0], layout.journals[-1]
    h = _disc_edge(meshes[keys[0]])
    ends = []
    if first.centre - first.z0 > JOIN_TOL * g.journal_diameter:  # an outer half beyond the bearing
        ends.append(("front end", 0, first.z0, first.centre, "end_1"))
    if last.z1 - last.centre > JOIN_TOL * g.journal_diameter:
        ends.append(("rear end", -1, last.centre, last.z1, "end_2"))
    for name, k, z0, z1, face in ends:
        t = layout.throws[k]
        disc = face_disc(meshes[keys[k]], face)
        levels = np.linspace(z0, z1, max(1, math.ceil((z1 - z0) / h)) + 1)
        key = f"{name}@{keys[k]}"
        meshes[key] = extrude(disc, levels)
        journal = 0 if k == 0 else len(layout.throws)
        piece = Piece(name, "end", key, angles[k], 0.0, None, (("surface", journal),))
        pieces.insert(0 if k == 0 else len(pieces), piece)
    sm = ShaftMesh(layout, meshes, throw_meshes, tuple(pieces), n, opt)
    _check_joints(sm)
    return sm


def _disc_edge(mesh) -> float:
    d = face_disc(mesh, "end_1")
    e = d.xy[d.edges[:, 0]] - d.xy[d.edges[:, 1]]
    return float(np.mean(np.hypot(e[:, 0], e[:, 1])))


def _joint(sm: ShaftMesh, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes of piece k's end_2 and, in the same order, piece k+1's end_1 (numbers local to each)."""
    a, b = sm.pieces[k], sm.pieces[k + 1]
    na = _face_nodes(sm.meshes[a.mesh], "end_2")
    nb = _face_nodes(sm.meshes[b.mesh], "end_1")
    xa = sm.placed_points(k)[:, na].T
    xb = sm.placed_points(k + 1)[:, nb].T
    r = float(np.max(np.hypot(xa[:, 0], xa[:, 1])))
    d, idx = cKDTree(xb).query(xa)
    if na.size != nb.size or np.any(d > JOIN_TOL * r) or np.unique(idx).size != idx.size:
        raise MeshError(
            f"the end faces of {a.name} and {b.name} do not carry the same nodes (largest gap "
            f"{float(np.max(d)):.3g} m): they cannot be joined"
        )
    return na, nb[idx]


def joints(sm: ShaftMesh) -> list[tuple[np.ndarray, np.ndarray]]:
    return [_joint(sm, k) for k in range(len(sm.pieces) - 1)]


def _check_joints(sm: ShaftMesh) -> None:
    joints(sm)


def join(sm: ShaftMesh):
    """One MeshTet2 of the whole shaft in the shaft frame (module doc)."""
    from skfem import MeshTet2

    pairs = joints(sm)
    offsets, v_parts, m_parts, t_parts = [], [], [], []
    # vertices first (every piece's vertices, then every piece's mid-edge nodes)
    nv_tot = sum(sm.meshes[p.mesh].nvertices for p in sm.pieces)
    glob, v_off, m_off = [], 0, nv_tot
    for k, p in enumerate(sm.pieces):
        m = sm.meshes[p.mesh]
        N, nv = m.doflocs.shape[1], m.nvertices
        g = np.empty(N, np.int64)
        g[:nv] = v_off + np.arange(nv)
        g[nv:] = m_off + np.arange(N - nv)
        v_off += nv
        m_off += N - nv
        glob.append(g)
        x = sm.placed_points(k)
        v_parts.append(x[:, :nv])
        m_parts.append(x[:, nv:])
    X = np.hstack(v_parts + m_parts)
    # merge: piece k+1's end_1 nodes become piece k's end_2 nodes
    target = np.arange(X.shape[1])
    for k, (na, nb) in enumerate(pairs):
        target[glob[k + 1][nb]] = glob[k][na]
    keep = np.flatnonzero(target == np.arange(X.shape[1]))
    new = np.full(X.shape[1], -1)
    new[keep] = np.arange(keep.size)
    final = new[target]
    for k, p in enumerate(sm.pieces):
        t_parts.append(final[glob[k][tet10(sm.meshes[p.mesh])]])
        offsets.append(sum(t.shape[1] for t in t_parts[:-1]))
    T = np.hstack(t_parts)
    whole = MeshTet2(X[:, keep].copy(), T.astype(np.int32))
    return whole.with_boundaries(_names(sm, whole, offsets))


def node_maps(sm: ShaftMesh, whole) -> list[np.ndarray]:
    """Per piece: the joined mesh's node number of each of its nodes (by position)."""
    tree = cKDTree(np.asarray(whole.doflocs).T)
    out = []
    for k in range(len(sm.pieces)):
        x = sm.placed_points(k).T
        d, idx = tree.query(x)
        if np.any(d > JOIN_TOL * np.ptp(x, axis=0).max()):
            raise MeshError(f"{sm.pieces[k].name}: a node is not in the joined mesh")
        out.append(idx)
    return out


def tet10(mesh) -> np.ndarray:
    """(10, ne) P2 node numbers of the elements, scikit-fem order (corners, then edges)."""
    return np.vstack([mesh.t, mesh.nvertices + mesh.t2e])


def _names(sm: ShaftMesh, whole, offsets) -> dict[str, np.ndarray]:
    """Boundary facets of the joined mesh by name (module doc), found by their vertex triples."""
    nvw = np.int64(whole.nvertices)
    f = np.sort(whole.facets, axis=0).astype(np.int64)
    fkey = (f[0] * nvw + f[1]) * nvw + f[2]
    order = np.argsort(fkey)
    out: dict[str, list[np.ndarray]] = {}
    bearing_of = {}
    for b in sm.layout.bearings:
        bearing_of[b.journal] = b.name
    for k, p in enumerate(sm.pieces):
        m = sm.meshes[p.mesh]
        t_local = m.t  # (4, ne) vertices
        t_whole = whole.t[:, offsets[k] : offsets[k] + m.nelements]
        vmap = np.zeros(m.nvertices, np.int64)
        vmap[t_local.ravel()] = t_whole.ravel()
        for name, facets in (m.boundaries or {}).items():
            tri = np.sort(vmap[m.facets[:, facets]], axis=0).astype(np.int64)
            key = (tri[0] * nvw + tri[1]) * nvw + tri[2]
            pos = np.minimum(np.searchsorted(fkey[order], key), fkey.size - 1)
            found = order[pos][fkey[order][pos] == key]
            label = _label(sm, k, p, name, bearing_of)
            if label:
                out.setdefault(label, []).append(found)
    bf = set(whole.boundary_facets().tolist())
    return {k: np.array(sorted(set(np.concatenate(v).tolist()) & bf), dtype=np.int64) for k, v in out.items()}


def _label(sm: ShaftMesh, k: int, p: Piece, name: str, bearing_of: dict[int, str]) -> str | None:
    for surface, journal in p.bearing_surfaces:
        if surface == name:
            return f"journal@{bearing_of.get(journal, journal)}"
    if name == "end_1" and k == 0:
        return "end_front"
    if name == "end_2" and k == len(sm.pieces) - 1:
        return "end_rear"
    if name.startswith("end_") or p.kind != "throw":
        return None
    return f"{name}@{p.throw}"
