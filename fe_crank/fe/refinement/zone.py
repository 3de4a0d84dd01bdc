"""A submodel of one hot-spot zone, driven by the assessed mesh's solution.

The zone (``mesh.zone``: the throw's solid inside a ball round a hot spot, meshed at a
finer fillet size) is solved for linear elasticity (P2, the throw model's material and
integration order) with

* the displacement of the assessed (global) solution prescribed on its cut boundary (the
  ball's faces) and on the support and end faces inside it (the journals' surfaces, the
  end faces: where the global model's reactions and couplings act), interpolated from
  the assessed mesh's P2 field (:func:`interpolate`: the element holding the point, its
  isoparametric map inverted by Newton's method, the P2 shape functions there);
* the loads that act inside the zone applied as in the global model: the crankpin's
  cosine pressure with the global unit case's own peak pressure and arc
  (``loads.PinPressure``) on the zone's part of the pin surface, the body forces
  (``loads.BODY_CASES``) on its volume;
* every other face free (the fillets, the oil bore, the web faces).

Every load set of the study is a right-hand side of one factorisation (the prescribed
values enter as -K_fd u_d; ``ZoneSystem``).  The mirror image of the zone across ``z = 0``
(``mesh.zone.mirror_zone``: node i of the image is node i of the zone with ``z`` negated)
has the stiffness D K D, D the reflection of the ``z`` components, so it is solved with the
same factorisation (``ZoneSystem.mirror_fields``): D times the zone's solution under D
times the image's own loads and driven displacements, whatever the load.  This is the classical cut-boundary displacement submodel
(Cormier, Smallwood, Sinclair & Meda, "Aggressive submodelling of stress
concentrations", Int. J. Numer. Meth. Engng 46 (1999) 889-909): its error is the
error of the global displacement on the cut, which decays away from the hot spot, and is
measured by solving the zone at two radii (docs/fe.md, "Hot-spot convergence").
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.spatial import cKDTree
from skfem import ElementTetP2

from fe_crank.errors import MeshError
from fe_crank.fe.core.assembly import assemble_stiffness, assemble_surface_load, upper_triangle
from fe_crank.fe.core.bases import cell_basis, facet_basis
from fe_crank.fe.core.loads import BODY_CASES, SURFACE_INTORDER, PinPressure
from fe_crank.fe.core.stress import stress_at_selected_nodes, von_mises
from fe_crank.fe.linalg.choice import choose_method
from fe_crank.fe.linalg.factorise import factorise
from fe_crank.fe.throw.options import FeOptions, Material
from fe_crank.fe.throw.pin_directions import pin_direction
from fe_crank.mesh.zone import CUT, ZoneMesh

#: candidate elements examined for each point (nearest by centroid)
CANDIDATES = 24
#: Newton iterations of the isoparametric inverse map
NEWTON = 4


def boundary_samples(mesh) -> tuple[np.ndarray, list[str]]:
    """(centroids (n, 3) of the boundary facets of ``mesh``, each one's boundary name, "" unnamed)."""
    facets = mesh.boundary_facets()
    label = np.full(mesh.facets.shape[1], -1)
    names = sorted(mesh.boundaries or {})
    for i, name in enumerate(names):
        label[mesh.boundaries[name]] = i
    x = mesh.p[:, mesh.facets[:, facets]].mean(axis=1).T
    return x, [names[k] if k >= 0 else "" for k in label[facets]]


class Interpolator:
    """The P2 field of a (curved) tetrahedral mesh at arbitrary points (module docstring)."""

    def __init__(self, mesh, dofs, points: np.ndarray):
        self.ed = np.asarray(dofs.element_dofs)  # (10, ne)
        self.x = np.asarray(points)  # (3, n) the P2 nodes (the dofs' locations)
        self.vert = mesh.p[:, mesh.t[:4]]  # (3, 4, ne)
        self.tree = cKDTree(self.vert.mean(axis=1).T)
        self.elem = ElementTetP2()

    def locate(self, pts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(element (n,), reference coordinates (3, n)) of points (3, n)."""
        k = min(CANDIDATES, self.vert.shape[2])
        _, cand = self.tree.query(pts.T, k=k)
        cand = np.atleast_2d(cand)
        v = self.vert[:, :, cand]  # (3, 4, n, k)
        A = np.stack([v[:, 1] - v[:, 0], v[:, 2] - v[:, 0], v[:, 3] - v[:, 0]], axis=-1)  # (3, n, k, 3)
        A = np.moveaxis(A, 0, -2)  # (n, k, 3, 3)
        b = (pts[:, :, None] - v[:, 0]).transpose(1, 2, 0)[..., None]  # (n, k, 3, 1)
        lam = np.linalg.solve(A, b)[..., 0]  # (n, k, 3)
        inside = np.minimum(lam.min(axis=-1), 1.0 - lam.sum(axis=-1))
        best = np.argmax(inside, axis=1)
        rows = np.arange(pts.shape[1])
        e = cand[rows, best]
        X = lam[rows, best].T.copy()  # (3, n) reference coordinates of the straight element
        P = self.x[:, self.ed[:, e]]  # (3, 10, n)
        for _ in range(NEWTON):  # the isoparametric map's inverse
            phi, dphi = self._basis(X)
            r = np.einsum("ian,an->in", P, phi) - pts
            J = np.einsum("ian,jan->nij", P, dphi)
            X = X - np.linalg.solve(J, r.T[..., None])[..., 0].T
        return e, X

    def _basis(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        out = [self.elem.lbasis(X, a) for a in range(10)]
        return np.stack([o[0] for o in out]), np.stack([o[1] for o in out], axis=1)  # (10, n), (3, 10, n)

    def values(self, pts: np.ndarray, fields: list[np.ndarray]) -> list[np.ndarray]:
        """Each interleaved P2 displacement field at points (3, n): (3, n) each."""
        e, X = self.locate(pts)
        phi, _ = self._basis(X)
        d = self.ed[:, e]  # (10, n)
        return [np.stack([np.einsum("an,an->n", phi, u[3 * d + i]) for i in range(3)]) for u in fields]


def driven_boundaries(options: FeOptions) -> tuple[str, ...]:
    """The zone's faces whose displacement is prescribed: the cut, the supports' surfaces, the end faces."""
    return (CUT, *options.journals, options.reaction_face, options.torque_face)


def _pin_traction(fb, pin: PinPressure):
    """The traction of a global pin unit case (``loads.pin_pressure_load``) on the zone's pin facets."""
    x = np.asarray(fb.global_coordinates())
    n = np.array(fb.normals)
    n[2] = 0.0
    nr = np.sqrt(n[0] ** 2 + n[1] ** 2)
    n = np.where(nr > 1e-6, n / np.maximum(nr, 1e-300), 0.0)
    c = pin.centre
    ang = np.arctan2(x[0] - c[0], x[1] - c[1])
    psi = np.angle(np.exp(1j * (ang - pin.arc_centre)))
    sh = np.where(np.abs(psi) < pin.half_angle, np.cos(0.5 * np.pi * psi / pin.half_angle), 0.0)
    return lambda xq, nq: -pin.peak_pressure * sh[None] * n


def held_nodes(zone: ZoneMesh, basis, options: FeOptions) -> np.ndarray:
    """The zone's nodes whose displacement is prescribed (``driven_boundaries``), ascending."""
    mesh = zone.mesh
    held_facets = [mesh.boundaries[b] for b in dict.fromkeys(driven_boundaries(options)) if b in mesh.boundaries]
    return np.unique(basis.get_dofs(np.concatenate(held_facets)).all())


def zone_loads(
    zone: ZoneMesh, basis, material: Material, options: FeOptions, pins: dict[str, PinPressure], loads
) -> np.ndarray:
    """(3 N, load sets) the loads that act inside the zone (module docstring), interleaved."""
    mesh = zone.mesh
    names = list(loads)
    F = np.zeros((3 * basis.N, len(names)))
    pin_fb = None
    body: dict[str, np.ndarray] = {}
    for j, name in enumerate(names):
        for case, w in loads[name].items():
            if case in BODY_CASES:
                if case not in body:
                    body[case] = BODY_CASES[case][0](basis, material.density)
                F[:, j] += w * body[case]
            elif pin_direction(case) is not None:
                if options.pin_boundary not in (mesh.boundaries or {}):
                    continue  # no pin surface in the zone
                if pin_fb is None:
                    pin_fb = facet_basis(
                        mesh, basis.elem, mesh.boundaries[options.pin_boundary], SURFACE_INTORDER, "the zone's pin load"
                    )
                F[:, j] += w * assemble_surface_load(pin_fb, _pin_traction(pin_fb, pins[case]))
            elif case != "torque":  # the torque enters at an end face: driven where the zone holds it
                raise MeshError(f"the hot-spot zone cannot apply the unit case {case!r}")
    return F


def factorise_free(A: sp.csr_matrix):
    """``factorise(A, "auto")`` of a zone's free block, handed only its upper triangle where
    the method reads no more (``fe.core.assembly.upper_triangle``: no whole-matrix
    ``scipy.sparse.triu``)."""
    A = sp.csr_matrix(A)
    A.sort_indices()
    if choose_method("auto", A.shape[0]) in ("pardiso", "pardiso_ooc", "cholmod"):
        return factorise(upper_triangle(A), "auto", upper=True)
    return factorise(A, "auto")


class ZoneSystem:
    """A zone's stiffness split at its driven dofs, the free block factorised once, for any
    number of load sets (``solve``) and for the zone's mirror image (``solve_mirror``)."""

    def __init__(self, zone: ZoneMesh, material: Material, options: FeOptions):
        self.zone, self.material, self.options = zone, material, options
        basis = self.basis = cell_basis(zone.mesh, options.intorder)
        K = sp.csr_matrix(assemble_stiffness(basis, material.youngs_modulus, material.poisson_ratio))
        self.n = 3 * basis.N
        self.nodes = held_nodes(zone, basis, options)
        self.held = (3 * self.nodes[:, None] + np.arange(3)).ravel()
        self.free = np.setdiff1d(np.arange(self.n), self.held)
        rows = K[self.free]
        self.K_fh = rows[:, self.held]
        self.factor = factorise_free(rows[:, self.free])

    def solve(self, F: np.ndarray, G: np.ndarray) -> np.ndarray:
        """(3 N, k) displacements under loads F (3 N, k) with the driven nodes' displacements
        G (3, n_held, k)."""
        U = np.zeros((self.n, F.shape[1]))
        U[self.held] = G.transpose(1, 0, 2).reshape(-1, F.shape[1])
        U[self.free] = self.factor.solve(F[self.free] - self.K_fh @ U[self.held]).reshape(-1, F.shape[1])
        return U

    def fields(self, pins, loads, driven, interpolator) -> dict[str, np.ndarray]:
        """{load set: the zone's displacement} (``solve_zone``)."""
        return self.fields_and_mirror(None, pins, loads, driven, interpolator)[0]

    def mirror_fields(self, image: ZoneMesh, pins, loads, driven, interpolator):
        """({load set: displacement}, basis) of the zone's mirror image ``image``
        (``mesh.zone.mirror_zone``) with its own loads and driven displacements, solved with
        this factorisation: node i of the image is node i of the zone reflected by D
        (z -> -z), so its stiffness is D K D and its solution D times the zone's solution
        under D times its loads and driven displacements.  None when the image's nodes or
        driven nodes are not the zone's reflected (then solve the image as a zone of its own)."""
        data = self._mirror_data(image, pins, loads, driven, interpolator)
        if data is None:
            return None
        F, g, flip, basis = data
        U = flip * self.solve(F, g)
        return {name: U[:, j] for j, name in enumerate(loads)}, basis

    def fields_and_mirror(self, image: ZoneMesh | None, pins, loads, driven, interpolator):
        """(``fields``, ``mirror_fields(image, ...)`` or None without ``image``), every
        right-hand side of both in one solve."""
        names = list(loads)
        k = len(names)
        F = zone_loads(self.zone, self.basis, self.material, self.options, pins, loads)
        g = np.stack(interpolator.values(self.basis.doflocs[:, self.nodes], [driven[n] for n in names]), axis=-1)
        data = None if image is None else self._mirror_data(image, pins, loads, driven, interpolator)
        if data is not None:
            F, g = np.hstack([F, data[0]]), np.concatenate([g, data[1]], axis=-1)
        U = self.solve(F, g)
        own = {name: U[:, j] for j, name in enumerate(names)}
        if data is None:
            return own, None
        V = data[2] * U[:, k:]
        return own, ({name: V[:, j] for j, name in enumerate(names)}, data[3])

    def _mirror_data(self, image: ZoneMesh, pins, loads, driven, interpolator):
        """(D F, D g, D as a column, basis) of the image's own loads F and driven
        displacements g, or None (``mirror_fields``)."""
        basis = cell_basis(image.mesh, self.options.intorder)
        x, y = self.basis.doflocs, basis.doflocs
        tol = 1e-12 * float(np.ptp(x, axis=1).max())
        if x.shape != y.shape or np.abs(x[:2] - y[:2]).max() > tol or np.abs(x[2] + y[2]).max() > tol:
            return None
        if not np.array_equal(held_nodes(image, basis, self.options), self.nodes):
            return None
        flip = np.tile([1.0, 1.0, -1.0], self.n // 3)[:, None]  # D on interleaved vectors
        F = flip * zone_loads(image, basis, self.material, self.options, pins, loads)
        g = np.stack(interpolator.values(y[:, self.nodes], [driven[n] for n in loads]), axis=-1)
        g[2] *= -1.0
        return F, g, flip, basis

    def release(self) -> None:
        self.factor.free()


def solve_zone(
    zone: ZoneMesh,
    material: Material,
    options: FeOptions,
    pins: dict[str, PinPressure],
    loads: dict[str, dict[str, float]],
    driven: dict[str, np.ndarray],
    interpolator: Interpolator,
):
    """Zone displacements {load set: interleaved vector} and the zone's scalar basis.

    ``loads``: {load set: {unit case: weight}}; ``driven``: {load set: the assessed
    solution of that load set} (interleaved, on the interpolator's mesh); ``pins``: the
    global pin unit cases' pressures."""
    system = ZoneSystem(zone, material, options)
    try:
        return system.fields(pins, loads, driven, interpolator), system.basis
    finally:
        system.release()


def zone_peaks(
    zone: ZoneMesh, basis, material: Material, fields: dict[str, np.ndarray], surfaces, reach: float, spots=None
) -> dict[str, dict[str, float]]:
    """{load set: {surface: peak averaged nodal von Mises, Pa}} on the zone's ``surfaces``
    at the nodes within ``reach`` x a ball's radius of its centre (away from the cut);
    ``spots``: (centres, radii) read round instead of the zone's balls."""
    mesh = zone.mesh
    x = basis.doflocs
    centres, radii = (zone.centres, zone.radii) if spots is None else spots
    groups = {}
    for name in surfaces:
        if name in (mesh.boundaries or {}):
            nodes = basis.get_dofs(mesh.boundaries[name]).all()
            near = np.zeros(nodes.size, bool)
            for c, r in zip(centres, radii):
                near |= np.linalg.norm(x[:, nodes] - np.asarray(c)[:, None], axis=0) <= reach * r
            if near.any():
                groups[name] = nodes[near]
    if not groups:
        return {k: {} for k in fields}
    ids = np.unique(np.concatenate(list(groups.values())))
    s = stress_at_selected_nodes(
        mesh, list(fields.values()), material.youngs_modulus, material.poisson_ratio, ids, dofs=basis.dofs
    )
    out = {}
    for j, key in enumerate(fields):
        vm = von_mises(s[j])
        out[key] = {name: float(vm[np.searchsorted(ids, nodes)].max()) for name, nodes in groups.items()}
    return out


__all__ = [
    "Interpolator",
    "ZoneSystem",
    "boundary_samples",
    "driven_boundaries",
    "factorise_free",
    "held_nodes",
    "solve_zone",
    "zone_loads",
    "zone_peaks",
]
