"""Bounds of a node's stress path over one cycle that need no (or one cheap pass over
its) history: what ``extremes`` searches by (its module docstring gives the argument).

* ``coefficient_box``: every stress component lies in a box, from the unit stresses and
  the range of each load coefficient over each run of the cycle with the same unit cases
  loaded;
* ``box_von_mises``, ``box_principal``: von Mises and the largest principal stress of a
  tensor within a box;
* ``goodman_lower`` (a box), ``goodman_radius_lower`` (the path's radius about its
  mid-range tensor and the minimum circumscribed ball's centre bounded by its distance
  from it), ``gough_pollard_lower``: lower bounds of the safety factors of
  ``fatigue``, each widened by ``peak.BOUND_RTOL`` for rounding.
"""

from __future__ import annotations

import numpy as np

from fe_crank.assess import fatigue
from fe_crank.assess.group.peak import BOUND_RTOL
from fe_crank.assess.stress import von_mises, von_mises_planes
from fe_crank.assess.superpose import UnitStresses, iter_planes

#: shear components (xy, yz, zx) count twice in a tensor's Frobenius norm
_WEIGHTS = np.array([1.0, 1.0, 1.0, 2.0, 2.0, 2.0])[:, None]


def box_von_mises(r: np.ndarray) -> np.ndarray:
    """The largest von Mises stress of a tensor whose components lie within +-r (6, n)."""
    x, y, z, xy, yz, zx = r
    out: np.ndarray = np.sqrt(0.5 * ((x + y) ** 2 + (y + z) ** 2 + (z + x) ** 2) + 3.0 * (xy**2 + yz**2 + zx**2))
    return out


def box_principal(m: np.ndarray) -> np.ndarray:
    """Gershgorin's bound of the largest principal stress of a tensor whose components
    lie within +-m (6, n)."""
    x, y, z, xy, yz, zx = m
    out: np.ndarray = np.maximum(np.maximum(x + xy + zx, y + xy + yz), z + yz + zx)
    return out


def _frobenius(r: np.ndarray) -> np.ndarray:
    out: np.ndarray = np.sqrt(np.sum(_WEIGHTS * r**2, axis=0))
    return out


def goodman_lower(
    r: np.ndarray, m: np.ndarray, endurance: float, tensile: float, additional: float = 0.0
) -> np.ndarray:
    """Goodman's safety is at least this at a node whose path lies in a box of half widths
    ``r`` and largest magnitudes ``m`` (module docstring); ``additional``: a stress added to
    the amplitude (UR M53's sigma_add; the safety falls as the amplitude grows)."""
    amp = box_von_mises(r)
    mean = np.maximum(box_von_mises(m), box_principal(m))
    return fatigue.goodman_safety(amp * (1 + BOUND_RTOL) + additional, mean * (1 + BOUND_RTOL), endurance, tensile)


def goodman_radius_lower(
    planes: np.ndarray, mid: np.ndarray, endurance: float, tensile: float, additional: float = 0.0
) -> np.ndarray:
    """Goodman's safety is at least this at each node of the path ``planes`` (6, n_t, n)
    with mid-range tensor ``mid`` (6, n).  The amplitude returned by
    ``fatigue.amplitude_mean`` is the radius R_0 about ``mid`` or smaller, with the centre
    ``mid`` or one c of smaller radius.  In von Mises' (Euclidean, deviatoric) metric the
    minimum circumscribed ball (centre c*, radius R*) has R(c)^2 >= R*^2 + |c - c*|^2 for
    every centre c, and R* >= L, half the chord from the point farthest from ``mid`` to
    the point farthest from it; so sigma_v(c) <= sigma_v(mid) + 2 sqrt(R_0^2 - L^2).  c is
    ``mid`` or a convex combination of it and points of the path, so its hydrostatic
    stress p is at most the largest of ``mid``'s and the path's; and the largest principal
    stress is at most p + 2/3 sigma_v.  The signed mean sigma_m' is at most
    max(sigma_v, p + 2/3 sigma_v) of these bounds.  ``additional`` as in ``goodman_lower``."""
    d0 = von_mises_planes(planes, mid)
    radius, far = fatigue.max_and_first(d0)
    cols = np.arange(planes.shape[-1])
    chord = 0.5 * von_mises_planes(planes, planes[:, far, cols]).max(axis=0)
    up, down = 1 + BOUND_RTOL, 1 - BOUND_RTOL
    shift = 2.0 * np.sqrt(np.maximum((radius * up) ** 2 - (chord * down) ** 2, 0.0))
    vm = von_mises(mid) * up + shift
    hydro = np.maximum((mid[0] + mid[1] + mid[2]) / 3.0, ((planes[0] + planes[1] + planes[2]) / 3.0).max(axis=0))
    mean = np.maximum(vm, hydro + np.abs(hydro) * BOUND_RTOL + 2.0 / 3.0 * vm)
    return fatigue.goodman_safety(radius * up + additional, mean * up, endurance, tensile)


def gough_pollard_lower(
    amp: np.ndarray, mean: np.ndarray, endurance_b: float, endurance_t: float, tensile: float, additional: float = 0.0
) -> np.ndarray:
    """Gough-Pollard's safety is at least this where both half ranges are <= ``amp`` and
    both means' magnitudes <= ``mean`` (module docstring); ``additional``: a stress added
    to the bending amplitude (UR M53's sigma_add)."""
    amp = amp * (1 + BOUND_RTOL)
    mean = mean * (1 + BOUND_RTOL)
    return fatigue.gough_pollard_safety(amp + additional, mean, amp, mean, endurance_b, endurance_t, tensile)


def _runs(coefficients: np.ndarray) -> np.ndarray:
    """Run index of every angle: consecutive angles with the same unit cases loaded (the
    same pair of pin directions bracketing the force) form one run."""
    loaded = coefficients != 0
    change = np.any(loaded[1:] != loaded[:-1], axis=1)
    return np.concatenate([[0], np.cumsum(change)])


def coefficient_box(
    unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, *, runs: bool = True, directional: bool = False
) -> tuple[np.ndarray, np.ndarray, np.ndarray | None, np.ndarray | None]:
    """(half widths, largest magnitudes (6, n) of the box of the path; with
    ``directional`` also bounds of the half range and of the magnitude of any component
    of the tensor in a unit direction (n,), else None) of ``nodes`` (module docstring).
    With ``runs`` the box of the whole cycle is the union of the boxes of its runs
    (``_runs``: within a run only the cases loaded there vary, so each run's box is
    tighter), else the whole cycle is one run.  Within run r the tensor lies within
    sum_c h_c |U_c|_F = f_r of C_r (Frobenius), so a directional component's half range
    is at most max_r f_r + max_{r,s} |C_r - C_s|_F / 2 and its magnitude at most
    max_r (|C_r|_F + f_r)."""
    c = np.atleast_2d(np.asarray(coefficients, float))
    run = _runs(c) if runs else np.zeros(c.shape[0], dtype=int)
    n_runs = int(run[-1]) + 1
    hi = np.full((n_runs, c.shape[1]), -np.inf)
    lo = np.full((n_runs, c.shape[1]), np.inf)
    np.maximum.at(hi, run, c)
    np.minimum.at(lo, run, c)
    h, m = 0.5 * (hi - lo), 0.5 * (hi + lo)  # (n_runs, n_cases)
    u = unit.stress[:, :, nodes]
    shape = (n_runs, 6, nodes.size)
    rho_r = (h @ np.abs(u).reshape(u.shape[0], -1)).reshape(shape)
    centre_r = (m @ u.reshape(u.shape[0], -1)).reshape(shape)
    top, bottom = (centre_r + rho_r).max(axis=0), (centre_r - rho_r).min(axis=0)
    rho = 0.5 * (top - bottom)
    big = np.maximum(np.abs(top), np.abs(bottom))
    if not directional:
        return rho, big, None, None
    fro_u = np.sqrt(np.einsum("j,cjn->cn", _WEIGHTS[:, 0], u**2))
    fro_r = h @ fro_u  # (n_runs, n): |S(t) - C_r|_F within run r
    spread = _frobenius(centre_r.max(axis=0) - centre_r.min(axis=0))  # >= |C_r - C_s|_F
    fro_h = fro_r.max(axis=0) + 0.5 * spread
    fro_c = (np.sqrt(np.sum(_WEIGHTS * centre_r**2, axis=1)) + fro_r).max(axis=0)
    return rho, big, fro_h, fro_c


def frobenius(r: np.ndarray) -> np.ndarray:
    """The Frobenius norm of a (6, n) tensor array (shears counted twice)."""
    return _frobenius(r)


#: angles between two samples of ``window_peak_bound`` within one run
WINDOW_STRIDE = 8
#: rounding allowance of ``window_peak_bound`` (and ``reference``), relative to
#: sum_c max_t |a_c| |U_c|_F (each computed component of S(t) is within ~n_cases x 1.1e-16
#: of that sum)
ROUNDING = 1e-12


def window_peak_bound(
    unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, stride: int = WINDOW_STRIDE, chunk: int = 2048
) -> np.ndarray:
    """An upper bound of each node's computed peak von Mises stress over the cycle,
    max_t sigma_v(S(t)) (``peak.group_peak``'s value), from the path at sample angles
    alone: the first and last angle of every run (``_runs``) and every ``stride``-th
    angle within it.  Between two consecutive samples a < b, S(t) = (1 - l) S(a) +
    l S(b) + sum_c R_c(t) U_c with l = (t - a)/(b - a) and R_c(t) the coefficient's
    departure from its chord; von Mises is a seminorm (convex), so sigma_v(S(t)) <=
    max(sigma_v(S(a)), sigma_v(S(b))) + sum_c max_t |R_c(t)| sigma_v(U_c).  Each node's
    bound is the largest over the windows plus a rounding allowance (``ROUNDING``: both the sampled and the evaluated values are sums of
    rounded products) and widened by ``BOUND_RTOL``."""
    c = np.atleast_2d(np.asarray(coefficients, float))
    nodes = np.asarray(nodes)
    n_t = c.shape[0]
    run = _runs(c)
    t = np.arange(n_t)
    first = np.concatenate([[True], run[1:] != run[:-1]])
    last = np.concatenate([run[1:] != run[:-1], [True]])
    run_start = np.maximum.accumulate(np.where(first, t, 0))
    k = np.flatnonzero(first | last | ((t - run_start) % stride == 0))
    # each angle's window [k_j, k_{j+1}]: its departure from the chord of the coefficients
    j = np.clip(np.searchsorted(k, t, side="right") - 1, 0, max(k.size - 2, 0))
    if k.size > 1:
        a, b = k[j], k[j + 1]
        lam = ((t - a) / (b - a))[:, None]
        dep = np.abs(c - ((1.0 - lam) * c[a] + lam * c[b]))
        departure = np.maximum.reduceat(dep, k[:-1], axis=0)  # (n_k - 1, n_cases)
        same = run[k[:-1]] == run[k[1:]]
    else:
        departure = np.zeros((0, c.shape[1]))
        same = np.zeros(0, bool)
    absmax = np.abs(c).max(axis=0)
    out = np.empty(nodes.size)
    for s in range(0, nodes.size, chunk):
        idx = nodes[s : s + chunk]
        u = unit.stress[:, :, idx]
        vmu = von_mises(u)  # (n_cases, k)
        fro_u = np.sqrt(np.einsum("j,cjn->cn", _WEIGHTS[:, 0], u**2))
        ((_, planes),) = iter_planes(unit, c[k], idx, idx.size)
        vs = von_mises_planes(planes)  # (n_k, k)
        windowed = vs.max(axis=0)
        if same.any():
            w = np.maximum(vs[:-1], vs[1:]) + departure @ vmu
            windowed = np.maximum(windowed, w[same].max(axis=0))
        # windows across a run boundary hold no angle between their samples (both
        # samples are a run's last and the next run's first): the samples cover them
        out[s : s + chunk] = windowed + ROUNDING * (absmax @ fro_u)
    return out * (1 + BOUND_RTOL)
