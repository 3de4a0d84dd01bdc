"""Fatigue of a node from its stress history over the cycle.

Two criteria, both on the endurance limits of the material multiplied by the surface,
size and treatment factors k = k_surface k_size k_treatment (Marin, Shigley's
Mechanical Engineering Design, 10th ed., eq. 6-18): sigma_e = k sigma_W,
tau_e = k tau_W.

1. **Equivalent von Mises + modified Goodman** (Shigley eqs. 6-66, 6-67 and 6-46):
   the half-range tensor S_a = (max_t S - min_t S) / 2 and the mid-range tensor
   S_m = (max_t S + min_t S) / 2, taken component by component, give the equivalent
   amplitude sigma_a' = vM(S_a) and the signed equivalent mean
   sigma_m' = sign(tr S_m) vM(S_m).  Safety n from 1/n = sigma_a'/sigma_e + sigma_m'/R_m
   for sigma_m' >= 0 and n = sigma_e / sigma_a' for a compressive mean (no credit taken).
   For proportional loading the half-range tensor is the exact amplitude tensor.
2. **Gough-Pollard** for combined bending and torsion (Gough & Pollard, Proc. IMechE
   131, 1935; ellipse quadrant), with Goodman-corrected limits:
   (sigma_a/sigma_e')^2 + (tau_a/tau_e')^2 = 1/n^2,
   sigma_e' = sigma_e (1 - max(sigma_m, 0)/R_m), tau_e' = tau_e (1 - |tau_m|/tau_u),
   tau_u = R_m/sqrt(3).  ``sigma`` is the normal stress along the surface in the
   meridional plane of the local axis (bending), ``tau`` the shear on that direction
   along the circumference (torsion): see ``bending_torsion``.
"""

from __future__ import annotations

import numpy as np

from fe_crank.assess.stress import cylindrical, von_mises


def half_range(history: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(S_a, S_m): half range and mid range over axis 0 of a history (n_t, ...)."""
    hi = history.max(axis=0)
    lo = history.min(axis=0)
    return 0.5 * (hi - lo), 0.5 * (hi + lo)


def equivalent_amplitude_mean(history: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """sigma_a' = vM(S_a) and signed sigma_m' = sign(tr S_m) vM(S_m) per node; history (n_t, 6, n)."""
    sa, sm = half_range(history)
    trace = sm[0] + sm[1] + sm[2]
    sign = np.where(trace < 0, -1.0, 1.0)
    return von_mises(sa), sign * von_mises(sm)


def goodman_safety(sigma_a: np.ndarray, sigma_m: np.ndarray, endurance: float, tensile: float) -> np.ndarray:
    """Modified-Goodman safety factor, 1/n = sigma_a/sigma_e + max(sigma_m, 0)/R_m (Shigley eq. 6-46)."""
    sigma_a = np.asarray(sigma_a, float)
    demand = sigma_a / endurance + np.maximum(np.asarray(sigma_m, float), 0.0) / tensile
    with np.errstate(divide="ignore"):
        return np.where(demand > 0, 1.0 / np.where(demand > 0, demand, 1.0), np.inf)


def gough_pollard_safety(sigma_a, sigma_m, tau_a, tau_m, endurance_bending: float, endurance_torsion: float,
                         tensile: float) -> np.ndarray:
    """n from (sigma_a/sigma_e')^2 + (tau_a/tau_e')^2 = 1/n^2 with Goodman-corrected limits.

    sigma_e' = sigma_e (1 - max(sigma_m, 0)/R_m), tau_e' = tau_e (1 - |tau_m|/tau_u),
    tau_u = R_m/sqrt(3).  A mean stress at or beyond the ultimate gives n = 0.
    """
    sigma_a, sigma_m, tau_a, tau_m = (np.asarray(v, float) for v in (sigma_a, sigma_m, tau_a, tau_m))
    fb = 1.0 - np.maximum(sigma_m, 0.0) / tensile
    ft = 1.0 - np.abs(tau_m) / (tensile / np.sqrt(3.0))
    ok = (fb > 0) & (ft > 0)
    se = endurance_bending * np.where(ok, fb, 1.0)
    te = endurance_torsion * np.where(ok, ft, 1.0)
    demand = np.sqrt((sigma_a / se) ** 2 + (tau_a / te) ** 2)
    with np.errstate(divide="ignore"):
        n = np.where(demand > 0, 1.0 / np.where(demand > 0, demand, 1.0), np.inf)
    return np.where(ok, n, 0.0)


def bending_torsion(history: np.ndarray, points: np.ndarray, axis_point: tuple[float, float]):
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
    c = cylindrical(history, points, axis_point)
    # signed variation tensor: the deviation from the time mean where it is largest
    dev = {k: v - v.mean(axis=0) for k, v in c.items() if k in ("rr", "zz", "rz")}
    size = np.sqrt(dev["rr"] ** 2 + dev["zz"] ** 2 + 2 * dev["rz"] ** 2)
    at = np.argmax(size, axis=0)
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
