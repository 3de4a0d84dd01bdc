"""Mirror symmetry of a P2 mesh: verification, the reflection group, its load components.

A reflection across the plane x_a = 0 (``a`` = 0 for x = 0, 2 for z = 0) acts on an
interleaved nodal vector as (R v)[3 p(i) + c] = s_c v[3 i + c], with p the node
permutation (node i's mirror image is node p(i)) and s_c = -1 for c = a, +1 otherwise.
R is orthogonal and an involution.  On a mesh that maps onto itself under R (and one
homogeneous material) the stiffness commutes with it, K R = R K, so with k planes the
space of nodal vectors splits into 2^k invariant components, one per character
e = (e_a) in {+1, -1}^k (R_a v = e_a v for every plane):

    v_e = 2^-k sum_g chi_e(g) (g v),  summed over the 2^k products g of the reflections,
    chi_e(g) = prod of e_a over the reflections in g,

and K u = f splits into K u_e = f_e (Zienkiewicz & Taylor, The Finite Element Method,
vol. 1, the section on symmetry and repeatability; the projection is that of the group
representation theory of the reflections).  ``symsolve`` solves each component on the
fundamental part of the mesh.
"""

from __future__ import annotations

import itertools
import logging
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

log = logging.getLogger(__name__)

#: coordinates closer than this fraction of the model size are the same point (round-off)
MATCH_TOL = 1e-10
AXIS_NAMES = {0: "x", 1: "y", 2: "z"}


@dataclass(frozen=True)
class Mirror:
    """The verified reflections of a mesh.  ``perm[a]`` (N,): node image under plane a."""

    axes: tuple[int, ...]
    perm: dict[int, np.ndarray]
    on_plane: dict[int, np.ndarray]  # (N,) bool: node on plane a (its own image)

    @property
    def group(self) -> list[tuple[tuple[int, ...], np.ndarray, np.ndarray]]:
        """Every product g of the reflections: (the planes in it, node permutation, signs (3,))."""
        out = []
        n = next(iter(self.perm.values())).size
        for k in range(len(self.axes) + 1):
            for sub in itertools.combinations(self.axes, k):
                p = np.arange(n)
                s = np.ones(3)
                for a in sub:
                    p = self.perm[a][p]
                    s[a] = -s[a]
                out.append((sub, p, s))
        return out

    @property
    def characters(self) -> list[dict[int, int]]:
        """The 2^k components, e.g. {0: +1, 2: -1}: symmetric about x = 0, antisymmetric about z = 0."""
        return [dict(zip(self.axes, e)) for e in itertools.product((1, -1), repeat=len(self.axes))]

    def describe(self) -> str:
        return " and ".join(f"{AXIS_NAMES[a]} = 0" for a in self.axes)


def character_of(chars: dict[int, int], planes: tuple[int, ...]) -> int:
    """chi_e(g) for g the product of the reflections ``planes``."""
    return int(np.prod([chars[a] for a in planes])) if planes else 1


def reflect(v: np.ndarray, perm: np.ndarray, signs: np.ndarray) -> np.ndarray:
    """g v for interleaved nodal vector(s) v (3 N,) or (3 N, k)."""
    V = v.reshape(perm.size, 3, -1)
    out = np.empty_like(V)
    out[perm] = V * signs[None, :, None]
    return out.reshape(v.shape)


def component(v: np.ndarray, mirror: Mirror, chars: dict[int, int]) -> np.ndarray:
    """v_e = 2^-k sum_g chi_e(g) (g v) (module doc)."""
    out = np.zeros_like(v)
    for planes, p, s in mirror.group:
        out += character_of(chars, planes) * reflect(v, p, s)
    return out / 2 ** len(mirror.axes)


def verify_mirror(points: np.ndarray, element_nodes: np.ndarray, axes) -> tuple[Mirror | None, str]:
    """Check that the nodes ``points`` (3, N) and elements (all their P2 nodes, (10, ne): the
    image of an element's edge node must be the edge node of its image) map onto themselves
    across each plane x_a = 0 of ``axes``; returns (Mirror, "") or (None, the reason it does not).

    Nodes are matched by coordinates to ``MATCH_TOL`` of the model size (a k-d tree); the
    map must be a permutation, fix exactly the nodes on the plane, and take the set of
    elements onto itself; no element may be its own image (it would straddle the plane,
    and the mesh would not split into mirror halves).
    """
    axes = tuple(sorted({int(a) for a in axes}))
    if not axes:
        return None, "the mesh states no mirror plane"
    bad = [a for a in axes if a not in (0, 1, 2)]
    if bad:
        return None, f"unknown mirror axes {bad}"
    x = np.asarray(points, float)
    N = x.shape[1]
    scale = float(np.ptp(x, axis=1).max()) or 1.0
    tol = MATCH_TOL * scale
    tree = cKDTree(x.T)
    el = np.sort(np.asarray(element_nodes), axis=0)
    keys = _element_keys(el, N)
    perm, on = {}, {}
    for a in axes:
        y = x.copy()
        y[a] = -y[a]
        d, idx = tree.query(y.T, distance_upper_bound=tol)
        name = f"{AXIS_NAMES[a]} = 0"
        if np.any(~np.isfinite(d)):
            return None, (
                f"{np.count_nonzero(~np.isfinite(d))} of {N} nodes have no mirror image across "
                f"{name} within {MATCH_TOL:g} of the model size"
            )
        if np.any(idx[idx] != np.arange(N)):
            return None, f"the node map across {name} is not an involution (coincident nodes?)"
        fixed = idx == np.arange(N)
        if np.any(fixed != (np.abs(x[a]) <= tol)):
            return None, f"nodes off the plane {name} map onto themselves (coincident nodes?)"
        mapped = _element_keys(np.sort(idx[el], axis=0), N)
        if not np.array_equal(np.sort(mapped), np.sort(keys)):
            return None, f"the elements do not map onto elements across {name}"
        if np.any(mapped == keys):
            return None, f"elements straddle the plane {name} (their own mirror images)"
        perm[a], on[a] = idx, fixed
    return Mirror(axes=axes, perm=perm, on_plane=on), ""


def _element_keys(el: np.ndarray, N: int) -> np.ndarray:
    """One key per element from its sorted nodes (m, ne): the m node numbers as bytes (exact)."""
    words = np.ascontiguousarray(el.T.astype(np.int64))
    return words.view(np.dtype((np.void, 8 * el.shape[0]))).ravel()


def mesh_mirror(mesh, basis, axes) -> Mirror | None:
    """The verified mirror of ``basis`` (its P2 nodes) across ``axes``, or None (logged why)."""
    if not axes:
        return None
    mirror, why = verify_mirror(basis.doflocs, basis.element_dofs, axes)
    if mirror is None:
        log.warning(
            "fe-crank: the mesh was meant to be mirror-symmetric (%s) but is not: %s; solving the full model",
            ", ".join(f"{AXIS_NAMES.get(a, a)} = 0" for a in axes),
            why,
        )
    return mirror
