"""A node group's worst values over one cycle, evaluated only at the nodes that can hold
them: the speeds of a full-load sweep need each criterion's extreme, not every node's
value (``assess_group`` keeps those for the operating speed's report).

With the history S(t) = sum_c a_c(t) U_c (``superpose``), let h_c and m_c be the half
range and the mid range of the coefficient a_c over the cycle, C = sum_c m_c U_c and
rho_j = sum_c h_c |U_c,j| per stress component j.  Then every component of S(t) lies in
[C_j - rho_j, C_j + rho_j].  Two boxes bound each node's path: that one (from the unit
stresses and the coefficients alone, no history), and the component-wise range
[lo_j, hi_j] of the history itself (one pass over it).  From a box of half widths r_j
and largest magnitudes M_j = max(|lo_j|, |hi_j|):

* von Mises: sigma_v(X)^2 = ((x-y)^2 + (y-z)^2 + (z-x)^2)/2 + 3 (xy^2 + yz^2 + zx^2)
  <= ((r_x+r_y)^2 + (r_y+r_z)^2 + (r_z+r_x)^2)/2 + 3 (r_xy^2 + r_yz^2 + r_zx^2) for
  |X_j| <= r_j (``box_von_mises``);
* the amplitude ``fatigue.amplitude_mean`` returns is the radius about the mid-range
  tensor or a smaller one, so sigma_a' <= box_von_mises(r); its mean tensor lies in the
  box (the mid range, or a convex combination of it and points of the path), so
  sigma_m' <= max(box_von_mises(M), Gershgorin's bound of the largest principal
  stress max_i (M_ii + sum_{k != i} M_ik)); so Goodman's safety is at least
  1 / (sigma_a'^+ / sigma_e + sigma_m'^+ / R_m);
* Gough-Pollard: the bending and torsion stresses are components of the tensor in a
  unit direction, bounded by its Frobenius norm; their half ranges by
  sum_c h_c |U_c|_F (or the box's), their means by |C|_F + that.

The nodes are taken in increasing order of the first bound, ``block`` at a time; a
block's history gives the second bound, and only the nodes whose second bound can reach
the tie band of the least value found (``peak.TIE_RTOL``; both bounds widened by
``peak.BOUND_RTOL`` for rounding) are evaluated exactly, by the same functions as
``assess_group``.  The search stops when the first bound of every node left lies above
that band.  So the group's extreme -- value, first node of the tie band -- is the one
an evaluation of every node gives.  The static peak uses ``peak.group_peak``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.assess import fatigue
from fe_crank.assess.factors import factors
from fe_crank.assess.group import (
    STATIC_ONLY_PREFIXES,
    GroupResult,
    _axis_for,
    _extreme,
)
from fe_crank.assess.peak import BOUND_RTOL, TIE_RTOL, group_peak, max_over_cycle
from fe_crank.assess.stress import von_mises, von_mises_planes
from fe_crank.assess.superpose import UnitStresses, iter_planes

#: nodes of one exact fatigue evaluation within a block: the least value found narrows
#: the band for the next ones
SUB_BLOCK = 32
#: nodes per exact evaluation of the static peak (its bound is tight: few blocks)
STATIC_BLOCK = 32
#: shear components (xy, yz, zx) count twice in a tensor's Frobenius norm
_WEIGHTS = np.array([1.0, 1.0, 1.0, 2.0, 2.0, 2.0])[:, None]


@dataclass(frozen=True)
class Wanted:
    """Which extremes the criteria need besides the static peak (always found)."""

    fatigue: bool = True
    gough_pollard: bool = True


@dataclass
class Running:
    """The least Goodman and Gough-Pollard safety found so far in one load state, over
    the groups and throws searched before (private to one state's evaluation)."""

    fatigue: float = np.inf
    gough_pollard: float = np.inf


def box_von_mises(r: np.ndarray) -> np.ndarray:
    """The largest von Mises stress of a tensor whose components lie within +-r (6, n)."""
    x, y, z, xy, yz, zx = r
    return np.sqrt(0.5 * ((x + y) ** 2 + (y + z) ** 2 + (z + x) ** 2) + 3.0 * (xy**2 + yz**2 + zx**2))


def box_principal(m: np.ndarray) -> np.ndarray:
    """Gershgorin's bound of the largest principal stress of a tensor whose components
    lie within +-m (6, n)."""
    x, y, z, xy, yz, zx = m
    return np.maximum(np.maximum(x + xy + zx, y + xy + yz), z + yz + zx)


def _frobenius(r: np.ndarray) -> np.ndarray:
    return np.sqrt(np.sum(_WEIGHTS * r**2, axis=0))


def _goodman_lower(r: np.ndarray, m: np.ndarray, endurance: float, tensile: float) -> np.ndarray:
    """Goodman's safety is at least this at a node whose path lies in a box of half widths
    ``r`` and largest magnitudes ``m`` (module docstring)."""
    amp = box_von_mises(r)
    mean = np.maximum(box_von_mises(m), box_principal(m))
    return fatigue.goodman_safety(amp * (1 + BOUND_RTOL), mean * (1 + BOUND_RTOL), endurance, tensile)


def _goodman_radius_lower(planes: np.ndarray, mid: np.ndarray, endurance: float, tensile: float) -> np.ndarray:
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
    max(sigma_v, p + 2/3 sigma_v) of these bounds."""
    d0 = von_mises_planes(planes, mid)
    radius, far = fatigue.max_and_first(d0)
    cols = np.arange(planes.shape[-1])
    chord = 0.5 * von_mises_planes(planes, planes[:, far, cols]).max(axis=0)
    up, down = 1 + BOUND_RTOL, 1 - BOUND_RTOL
    shift = 2.0 * np.sqrt(np.maximum((radius * up) ** 2 - (chord * down) ** 2, 0.0))
    vm = von_mises(mid) * up + shift
    hydro = np.maximum((mid[0] + mid[1] + mid[2]) / 3.0, ((planes[0] + planes[1] + planes[2]) / 3.0).max(axis=0))
    mean = np.maximum(vm, hydro + np.abs(hydro) * BOUND_RTOL + 2.0 / 3.0 * vm)
    return fatigue.goodman_safety(radius * up, mean * up, endurance, tensile)


def _gough_pollard_lower(amp, mean, endurance_b: float, endurance_t: float, tensile: float) -> np.ndarray:
    """Gough-Pollard's safety is at least this where both half ranges are <= ``amp`` and
    both means' magnitudes <= ``mean`` (module docstring)."""
    amp = amp * (1 + BOUND_RTOL)
    mean = mean * (1 + BOUND_RTOL)
    return fatigue.gough_pollard_safety(amp, mean, amp, mean, endurance_b, endurance_t, tensile)


def _runs(coefficients: np.ndarray) -> np.ndarray:
    """Run index of every angle: consecutive angles with the same unit cases loaded (the
    same pair of pin directions bracketing the force) form one run."""
    loaded = coefficients != 0
    change = np.any(loaded[1:] != loaded[:-1], axis=1)
    return np.concatenate([[0], np.cumsum(change)])


def _coefficient_box(
    unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, *, runs: bool = True, directional: bool = False
):
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


def _search(lower: np.ndarray, block: int, evaluate, start: float = np.inf) -> float:
    """Evaluate blocks of positions in increasing ``lower`` (``evaluate(positions,
    threshold)`` evaluates those whose bound can reach ``threshold`` and returns the least
    value it found, or inf) until every bound left exceeds the threshold: the tie band of
    the least value found or of ``start`` (the least of the groups searched before),
    widened by the band once more, so that a group that reaches ``start``'s band has its
    own band complete.  Returns the least value found (inf: none)."""
    order = np.argsort(lower, kind="stable")
    found = np.inf
    for s in range(0, order.size, block):
        threshold = _band(_band(min(found, start)))
        if lower[order[s]] > threshold:
            break  # bounds ascend: no node left can reach the band
        found = min(found, evaluate(order[s : s + block], threshold))
    return found


def _band(best: float) -> float:
    return best + TIE_RTOL * abs(best) if np.isfinite(best) else np.inf


def _static_peak(unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, bound: np.ndarray, block: int):
    """``peak.group_peak`` on the nodes whose box bound ``bound`` of the peak can reach the
    tie band of the largest peak of the ``block`` nodes of the largest bounds (the
    others can neither hold the group's peak nor tie with it); positions into ``nodes``."""
    bound = bound * (1 + BOUND_RTOL)
    seed = np.argsort(-bound, kind="stable")[:STATIC_BLOCK]
    ((_, planes),) = iter_planes(unit, coefficients, nodes[seed], seed.size)
    best = float(max_over_cycle(von_mises_planes(planes))[0].max())
    keep = np.flatnonzero(bound >= best - TIE_RTOL * abs(best)) if np.isfinite(best) else np.arange(nodes.size)
    pos, vm, arg = group_peak(unit, coefficients, nodes[keep], STATIC_BLOCK)
    return keep[pos], vm, arg


def _least(values: np.ndarray, done: np.ndarray, nodes: np.ndarray, unit: UnitStresses, group: str):
    """The group's least value and its node among the evaluated positions ``done``: every
    node of the tie band is among them, so it is the one of an evaluation of all."""
    return _extreme(values[done], nodes[done], unit, group, worst="min")


def group_extremes(
    unit: UnitStresses,
    group: str,
    coefficients: np.ndarray,
    theta: np.ndarray,
    material,
    *,
    crank_radius: float,
    diameter: float | None = None,
    wanted: Wanted = Wanted(),
    running: Running | None = None,
    block: int = fatigue.NODE_BLOCK,
) -> GroupResult:
    """``assess_group``'s extremes of one node group at one speed (static peak, least
    Goodman and Gough-Pollard safety with their nodes; no overspeed, no per-node fields),
    each evaluated only where it can occur (module docstring).  ``running``: the least
    fatigue values of the groups and throws of the same load state searched before; a
    group whose least value cannot reach their tie band has ``fatigue_safety`` (or
    ``gough_pollard_safety``) None: it cannot govern the state's criterion."""
    running = Running() if running is None else running
    nodes = np.asarray(unit.groups[group])
    if nodes.size == 0:
        raise ValueError(f"node group {group!r} is empty")
    do_fatigue = (
        wanted.fatigue
        and not group.startswith(STATIC_ONLY_PREFIXES)
        and material.fatigue_limit_bending is not None
        and material.tensile_strength is not None
    )
    axis = _axis_for(group, crank_radius)
    do_gp = (
        wanted.gough_pollard
        and not group.startswith(STATIC_ONLY_PREFIXES)
        and material.fatigue_limit_bending is not None
        and material.tensile_strength is not None
        and axis is not None
        and material.fatigue_limit_torsion is not None
    )
    # the fatigue groups' box of the runs (the fatigue search's first bound); the static
    # groups' one box of the whole cycle (only the peak's prefilter)
    rho, big, fro_h, fro_c = _coefficient_box(unit, coefficients, nodes, runs=do_fatigue or do_gp, directional=do_gp)
    pos, vm, arg = _static_peak(unit, coefficients, nodes, box_von_mises(big), block)
    worst = _extreme(vm, nodes[pos], unit, group, worst="max", angles=np.asarray(theta)[arg])
    ys = material.yield_strength
    static = ys / worst.value if (ys is not None and worst.value > 0) else np.inf
    ff = factors(material, diameter) if (do_fatigue or do_gp) else None
    k = ff.product if ff is not None else 1.0
    fat = gpe = None
    amp = mean = None
    if do_fatigue:
        se, rm = k * material.fatigue_limit_bending, material.tensile_strength
        good = np.full(nodes.size, np.inf)
        sa, sm = np.zeros(nodes.size), np.zeros(nodes.size)
        done = np.zeros(nodes.size, bool)

        def fatigue_block(p: np.ndarray, band: float) -> float:
            ((_, planes),) = iter_planes(unit, coefficients, nodes[p], p.size)
            hi, lo = planes.max(axis=1), planes.min(axis=1)
            big2 = np.maximum(np.abs(hi), np.abs(lo))
            keep = _goodman_lower(0.5 * (hi - lo), big2, se, rm) <= band
            if not keep.any():
                return np.inf
            # the radius about the mid range and the centre's distance from it (MCB)
            planes, p = planes[:, :, keep], p[keep]
            lower = _goodman_radius_lower(planes, 0.5 * (hi + lo)[:, keep], se, rm)
            found = np.inf
            order = np.argsort(lower, kind="stable")
            for s in range(0, order.size, SUB_BLOCK):  # in increasing bound: the band narrows as it goes
                band = min(band, _band(_band(found)))
                sub = order[s : s + SUB_BLOCK]
                sub = np.sort(sub[lower[sub] <= band])
                if sub.size == 0:
                    break
                a, m = fatigue.equivalent_amplitude_mean(planes[:, :, sub].transpose(1, 0, 2))
                q = p[sub]
                sa[q], sm[q] = a, m
                good[q] = fatigue.goodman_safety(a, m, se, rm)
                done[q] = True
                found = min(found, float(good[q].min()))
            return found

        start = running.fatigue
        least = _search(_goodman_lower(rho, big, se, rm), block, fatigue_block, start)
        if least <= _band(start):  # the group can hold the state's least value
            fat = _least(good, done, nodes, unit, group)
            j = int(np.argmin(good))
            amp, mean = float(sa[j]), float(sm[j])
            running.fatigue = min(start, least)
    if do_gp:
        eb, et, rm = k * material.fatigue_limit_bending, k * material.fatigue_limit_torsion, material.tensile_strength
        gp = np.full(nodes.size, np.inf)
        gp_done = np.zeros(nodes.size, bool)

        def gp_block(p: np.ndarray, band: float) -> float:
            ((_, planes),) = iter_planes(unit, coefficients, nodes[p], p.size)
            hi, lo = planes.max(axis=1), planes.min(axis=1)
            big2 = np.maximum(np.abs(hi), np.abs(lo))
            lower = _gough_pollard_lower(_frobenius(0.5 * (hi - lo)), _frobenius(big2), eb, et, rm)
            keep = lower <= band
            if not keep.any():
                return np.inf
            hist = planes[:, :, keep].transpose(1, 0, 2)
            sig, tau = fatigue.bending_torsion(hist, unit.points[:, nodes[p[keep]]], axis)
            s_a, s_m = fatigue.half_range(sig)
            t_a, t_m = fatigue.half_range(tau)
            q = p[keep]
            gp[q] = fatigue.gough_pollard_safety(s_a, s_m, t_a, t_m, eb, et, rm)
            gp_done[q] = True
            return float(gp[q].min())

        start = running.gough_pollard
        least = _search(_gough_pollard_lower(fro_h, fro_c, eb, et, rm), block, gp_block, start)
        if least <= _band(start):
            gpe = _least(gp, gp_done, nodes, unit, group)
            running.gough_pollard = min(start, least)
    return GroupResult(
        group, int(nodes.size), worst, None, float(static), None, fat, gpe, amp, mean, ff if do_fatigue else None
    )


__all__ = ["Wanted", "Running", "group_extremes", "box_von_mises", "box_principal"]
