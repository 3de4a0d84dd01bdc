"""Fatigue of a node from its stress history over the cycle.

Two criteria, both on the endurance limits of the material multiplied by the surface,
size and treatment factors k = k_surface k_size k_treatment (Marin, Shigley's
Mechanical Engineering Design, 10th ed., eq. 6-18): sigma_e = k sigma_W,
tau_e = k tau_W.

1. **Equivalent von Mises + modified Goodman** (Shigley eq. 6-46 on von Mises
   equivalents, eqs. 6-66/6-67 generalised to a multiaxial history): the amplitude is the
   radius of the smallest ball in the von Mises norm that contains the stress path
   S(t), and the mean tensor is its centre -- the minimum circumscribed ball of the
   deviatoric path of Dang Van (1989) and Papadopoulos et al. (Int. J. Fatigue 19(3),
   1997, 219-235), sigma_a' = sqrt(3 J2,a).  For proportional loading
   S(t) = S_0 + lambda(t) A the ball is centred on the mid-range tensor and
   sigma_a' = vM(A) (lambda_max - lambda_min)/2 exactly, with the signs of the
   components kept (reversed shear s_xx = +t, s_yy = -t gives sqrt(3) t).  See
   ``amplitude_mean``.  The signed equivalent mean is sigma_m' = max(vM(S_m), s_1(S_m))
   when the largest principal mean stress s_1 is tensile (a shear or hydrostatic-tension
   mean counts against the part) and -vM(S_m) when no principal mean stress is tensile.
   Safety n from 1/n = sigma_a'/sigma_e + max(sigma_m', 0)/R_m: a compressive mean earns
   no credit (Shigley 6-46 is not extended into compression).
2. **Gough-Pollard** for combined bending and torsion (Gough & Pollard, Proc. IMechE
   131, 1935; ellipse quadrant), with Goodman-corrected limits:
   (sigma_a/sigma_e')^2 + (tau_a/tau_e')^2 = 1/n^2,
   sigma_e' = sigma_e (1 - max(sigma_m, 0)/R_m), tau_e' = tau_e (1 - |tau_m|/tau_u),
   tau_u = R_m/sqrt(3).  ``sigma`` is the normal stress along the surface in the
   meridional plane of the local axis (bending), ``tau`` the shear on that direction
   along the circumference (torsion): see ``bending_torsion``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fe_crank.assess.stress import cylindrical, principal, von_mises, von_mises_planes
from fe_crank.io.material import Material

#: nodes per block of ``amplitude_mean`` (a block's path, 720 x 6 x 128 x 8 B = 4.4 MB, and
#: its scratch arrays stay in the processor's cache)
NODE_BLOCK = 128


@dataclass(frozen=True)
class FatigueLimits:
    """The material properties the fatigue criteria take, Pa: the specimen's fully reversed
    bending fatigue limit sigma_W and the tensile strength R_m (both criteria), the torsional
    fatigue limit tau_W (Gough-Pollard; None: the material gives none)."""

    bending: float
    tensile: float
    torsion: float | None


def fatigue_limits(material: Material) -> FatigueLimits | None:
    """The fatigue properties of ``material``; None when it lacks sigma_W or R_m (no
    fatigue criterion is evaluated then)."""
    if material.fatigue_limit_bending is None or material.tensile_strength is None:
        return None
    return FatigueLimits(material.fatigue_limit_bending, material.tensile_strength, material.fatigue_limit_torsion)


def half_range(history: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(S_a, S_m): half range and mid range over axis 0 of a scalar history (n_t, ...)."""
    hi = history.max(axis=0)
    lo = history.min(axis=0)
    return 0.5 * (hi - lo), 0.5 * (hi + lo)


def _radius(planes: np.ndarray, centre: np.ndarray, buf: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """max_t vM(S(t) - c) per node and the angle index where it is reached; the path as
    component planes (6, n_t, n)."""
    d = von_mises_planes(planes, centre, buf)
    return max_and_first(d)


def max_and_first(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(d.max(axis=0), d.argmax(axis=0))`` of a (n_t, n) array: the first index of the
    maximum found as the first row equal to it (a comparison is cheaper than numpy's
    argmax along a non-contiguous axis, which copies the array).  Exactly the same
    values; a column holding a NaN falls back to ``argmax`` (its first NaN)."""
    r = d.max(axis=0)
    first = (d == r).argmax(axis=0)
    if not np.isfinite(r).all():
        bad = ~np.isfinite(r)
        first[bad] = d[:, bad].argmax(axis=0)
    return r, first


def amplitude_mean(
    history: np.ndarray, iterations: int = 16, stride: int = 4, block: int = NODE_BLOCK
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Amplitude, mean tensor and a lower bound of the amplitude of a stress path.

    ``history`` (n_t, 6, n).  The amplitude is the radius R(c) = max_t vM(S(t) - c) of a
    ball about a centre c that contains the whole path (von Mises norm = sqrt(3 J2) of
    the deviatoric difference); the minimum over c is the minimum circumscribed ball
    (MCB) of Dang Van / Papadopoulos.  Every R(c) is an upper bound of the MCB radius,
    so the value returned is never below it (on the safe side):

    * start: c_0 = the component-wise mid-range tensor.  For proportional loading this is
      the MCB centre and R(c_0) the exact amplitude (the path is a segment through c_0);
      for a circle or ellipse centred on the mid-range it is exact as well;
    * refinement where R(c_0) exceeds the lower bound: Badoiu-Clarkson iterations
      c_{k+1} = c_k + (S_far - c_k)/(k + 2) (S_far the farthest point of the path;
      Badoiu & Clarkson, "Smaller core-sets for balls", SODA 2003) on every ``stride``-th
      sample; the best of the last centres is then measured on the whole path and kept
      if its radius is smaller than R(c_0).

    The lower bound is half the longest chord found, vM(S(t_1) - S(t_2))/2 with t_1, t_2
    the farthest point from c_0 and the farthest point from it (any half chord <= MCB
    radius).  Returns (sigma_a', mean tensor (6, n), lower bound).

    Every node is computed on its own path only, so the nodes are taken ``block`` at a
    time, each block as its six component planes (6, n_t, block) (the temporaries of a
    block stay in the processor's cache; the values do not depend on the block size nor
    on the memory layout of ``history``).
    """
    n = history.shape[-1]
    planes = history.transpose(1, 0, 2)  # (6, n_t, n) view
    if n <= block:
        return _amplitude_block(np.ascontiguousarray(planes), iterations, stride)
    amp: np.ndarray
    mean: np.ndarray
    lower: np.ndarray
    amp, mean, lower = np.empty(n), np.empty((6, n)), np.empty(n)
    for s in range(0, n, block):
        sl = slice(s, s + block)
        amp[sl], mean[:, sl], lower[sl] = _amplitude_block(np.ascontiguousarray(planes[:, :, sl]), iterations, stride)
    return amp, mean, lower


def _amplitude_block(planes: np.ndarray, iterations: int, stride: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``amplitude_mean`` of one block of nodes given as contiguous planes (6, n_t, n)."""
    lo, hi = planes.min(axis=1), planes.max(axis=1)
    c = 0.5 * (lo + hi)
    buf = np.empty(planes.shape)
    d0 = von_mises_planes(planes, c, buf)  # (n_t, n), about the mid-range
    best_r, far = max_and_first(d0)
    best_c = c.copy()
    cols = np.arange(planes.shape[-1])
    p1 = planes[:, far, cols]
    lower = 0.5 * _radius(planes, p1, buf)[0]
    todo = best_r > lower * (1.0 + 1e-9)
    if np.any(todo):
        h = planes if todo.all() else planes[:, :, todo]
        # search on a sub-sampled path (a contiguous copy: the same values, faster passes)
        step = stride if h.shape[1] >= 8 * stride else 1
        hs = np.ascontiguousarray(h[:, ::step]) if step > 1 else h
        sbuf = np.empty(hs.shape)
        cc = c[:, todo]
        # the start's distances on the sub-sampled path are rows of the whole path's
        r, far = max_and_first(d0[::step] if todo.all() else d0[::step][:, todo])
        cands, radii = [cc], [r]  # radius of each candidate on the sub-sampled path
        sub = np.arange(h.shape[-1])
        for k in range(iterations):
            cc = cc + (hs[:, far, sub] - cc) / (k + 2.0)
            r, far = _radius(hs, cc, sbuf)
            cands.append(cc)
            radii.append(r)
        # the candidate with the smallest radius on the sub-sampled path (of the last four
        # and the start), then its true radius on the whole path (the upper bound returned)
        rs = np.stack(radii[-4:] + [radii[0]])
        pick = np.argmin(rs, axis=0)
        pool = np.stack(cands[-4:] + [cands[0]])  # (5, 6, m)
        cb = pool[pick, :, sub].T
        rb, _ = _radius(h, cb, buf if h is planes else None)
        better = rb < best_r[todo]
        idx = np.flatnonzero(todo)[better]
        best_r[idx] = rb[better]
        best_c[:, idx] = cb[:, better]
    return best_r, best_c, lower


def signed_mean(mean: np.ndarray) -> np.ndarray:
    """sigma_m' = max(vM(S_m), s_1(S_m)) if s_1(S_m) > 0 else -vM(S_m); mean (6, n)."""
    vm = von_mises(mean)
    s1 = principal(mean[None])[0].max(axis=0)  # largest principal stress, whatever the order
    return np.where(s1 > 0, np.maximum(vm, s1), -vm)


def equivalent_amplitude_mean(history: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """sigma_a' (MCB radius, ``amplitude_mean``) and the signed sigma_m' (``signed_mean``)
    per node; history (n_t, 6, n)."""
    amp, mean, _ = amplitude_mean(history)
    return amp, signed_mean(mean)


def goodman_safety(sigma_a: np.ndarray, sigma_m: np.ndarray, endurance: float, tensile: float) -> np.ndarray:
    """Modified-Goodman safety factor, 1/n = sigma_a/sigma_e + max(sigma_m, 0)/R_m (Shigley eq. 6-46)."""
    sigma_a = np.asarray(sigma_a, float)
    demand = sigma_a / endurance + np.maximum(np.asarray(sigma_m, float), 0.0) / tensile
    with np.errstate(divide="ignore"):
        return np.where(demand > 0, 1.0 / np.where(demand > 0, demand, 1.0), np.inf)


def gough_pollard_safety(
    sigma_a: ArrayLike,
    sigma_m: ArrayLike,
    tau_a: ArrayLike,
    tau_m: ArrayLike,
    endurance_bending: float,
    endurance_torsion: float,
    tensile: float,
) -> np.ndarray:
    """n from (sigma_a/sigma_e')^2 + (tau_a/tau_e')^2 = 1/n^2 with Goodman-corrected limits.

    sigma_e' = sigma_e (1 - max(sigma_m, 0)/R_m), tau_e' = tau_e (1 - |tau_m|/tau_u),
    tau_u = R_m/sqrt(3).  A mean stress at or beyond the ultimate gives n = 0.
    """
    s_a, s_m, t_a, t_m = (np.asarray(v, float) for v in (sigma_a, sigma_m, tau_a, tau_m))
    fb = 1.0 - np.maximum(s_m, 0.0) / tensile
    ft = 1.0 - np.abs(t_m) / (tensile / np.sqrt(3.0))
    ok = (fb > 0) & (ft > 0)
    se = endurance_bending * np.where(ok, fb, 1.0)
    te = endurance_torsion * np.where(ok, ft, 1.0)
    demand = np.sqrt((s_a / se) ** 2 + (t_a / te) ** 2)
    with np.errstate(divide="ignore"):
        n = np.where(demand > 0, 1.0 / np.where(demand > 0, demand, 1.0), np.inf)
    return np.where(ok, n, 0.0)


def bending_torsion(
    history: np.ndarray, points: np.ndarray, axis_point: tuple[float, float]
) -> tuple[np.ndarray, np.ndarray]:
    """Bending normal stress and torsional shear histories at surface nodes near an axis.

    In the cylindrical frame of the local axis (parallel to z through ``axis_point``),
    the meridional sub-tensor [[s_rr, s_rz], [s_rz, s_zz]] of the largest deviation
    from the cycle mean (a signed amplitude tensor; exact for proportional loading) gives,
    per node, the unit direction t = (t_r, t_z) of its eigenvalue of largest
    magnitude (at a traction-free fillet surface: the direction along the surface).
    Then sigma(t) = t . S_meridional . t and tau(t) = s_rt t_r + s_tz t_z: the normal
    stress along t and the circumferential shear on the plane normal to t.  For a
    straight bar under bending and torsion these are exactly s_zz and s_tz.

    Returns (sigma_history, tau_history), each (n_t, n).
    """
    c = cylindrical(history, points, axis_point, ("rr", "zz", "rz", "rt", "tz"))
    # signed variation tensor: the deviation from the time mean where it is largest
    dev = {k: v - v.mean(axis=0) for k, v in c.items() if k in ("rr", "zz", "rz")}
    size = np.sqrt(dev["rr"] ** 2 + dev["zz"] ** 2 + 2 * dev["rz"] ** 2)
    at = max_and_first(size)[1]  # first angle of the largest
    cols = np.arange(size.shape[1])
    rr_a, zz_a, rz_a = (dev[k][at, cols] for k in ("rr", "zz", "rz"))
    # eigenvector of the largest-magnitude eigenvalue of [[rr, rz], [rz, zz]]
    mean = 0.5 * (rr_a + zz_a)
    rad = np.sqrt((0.5 * (rr_a - zz_a)) ** 2 + rz_a**2)
    lam = np.where(np.abs(mean + rad) >= np.abs(mean - rad), mean + rad, mean - rad)
    # (rz, lam - rr) is an eigenvector unless both vanish; then fall back to (lam - zz, rz)
    v1 = np.stack([rz_a, lam - rr_a])
    v2 = np.stack([lam - zz_a, rz_a])
    use1 = np.hypot(*v1) >= np.hypot(*v2)
    v = np.where(use1, v1, v2)
    norm = np.hypot(*v)
    t_r = np.where(norm > 0, v[0] / np.where(norm > 0, norm, 1.0), 0.0)
    t_z = np.where(norm > 0, v[1] / np.where(norm > 0, norm, 1.0), 1.0)
    sigma = t_r**2 * c["rr"] + 2 * t_r * t_z * c["rz"] + t_z**2 * c["zz"]
    tau = c["rt"] * t_r + c["tz"] * t_z
    return sigma, tau
