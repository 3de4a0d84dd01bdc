"""A node group's worst values over one cycle, evaluated only at the nodes that can hold
them: the speeds of a full-load sweep need each criterion's extreme, not every node's
value (``assess_group`` keeps those for the operating speed's report).

With the history S(t) = sum_c a_c(t) U_c (``superpose``), let h_c and m_c be the half
range and the mid range of the coefficient a_c over a run of the cycle (consecutive
angles with the same unit cases loaded), C = sum_c m_c U_c and rho_j = sum_c h_c |U_c,j|
per stress component j.  Then every component of S(t) lies in [C_j - rho_j, C_j + rho_j]
during the run, and in the union of these boxes over the cycle.  Three bounds of each
node's path (``bounds``), each tighter and dearer than the one before: that box (from
the unit stresses and the coefficients alone, no history); the component-wise range
[lo_j, hi_j] of the history itself (one pass over it); and the radius R_0 about the
mid-range tensor with the chord of the path.  From a box of half widths r_j and largest
magnitudes M_j = max(|lo_j|, |hi_j|):

* von Mises: sigma_v(X)^2 = ((x-y)^2 + (y-z)^2 + (z-x)^2)/2 + 3 (xy^2 + yz^2 + zx^2)
  <= ((r_x+r_y)^2 + (r_y+r_z)^2 + (r_z+r_x)^2)/2 + 3 (r_xy^2 + r_yz^2 + r_zx^2) for
  |X_j| <= r_j (``bounds.box_von_mises``);
* the amplitude ``fatigue.amplitude_mean`` returns is the radius about the mid-range
  tensor or a smaller one, so sigma_a' <= box_von_mises(r) and <= R_0; its mean tensor
  lies in the box (the mid range, or a convex combination of it and points of the
  path), so sigma_m' <= max(box_von_mises(M), Gershgorin's bound of the largest
  principal stress max_i (M_ii + sum_{k != i} M_ik)); with R_0, the minimum
  circumscribed ball's property R(c)^2 >= R*^2 + |c - c*|^2 bounds the centre's
  distance from the mid range (``bounds.goodman_radius_lower``); so Goodman's safety is
  at least 1 / (sigma_a'^+ / sigma_e + sigma_m'^+ / R_m);
* Gough-Pollard: the bending and torsion stresses are components of the tensor in a
  unit direction, bounded by its Frobenius norm; their half ranges by
  max_r sum_c h_c |U_c|_F + max_{r,s} |C_r - C_s|_F / 2 (or the box's), their means
  by max_r (|C_r|_F + sum_c h_c |U_c|_F).

The nodes are taken in increasing order of the first bound, ``block`` at a time; a
block's history gives the second and third bounds, and only the nodes whose bounds can
reach the tie band of the least value found (``peak.TIE_RTOL``; every bound widened by
``peak.BOUND_RTOL`` for rounding) are evaluated exactly, by the same functions as
``assess_group``, in increasing third bound.  The search stops when the first bound of
every node left lies above that band; a group (or a later throw) of the same load state
starts from the least value of those searched before (``Running``).  So the group's
extreme -- value, first node of the tie band -- is the one an evaluation of every node
gives, wherever it can govern the state's criterion.  The static peak uses
``peak.group_peak`` on the nodes whose box bound can reach the peak of the nodes of the
largest box bounds, searched in decreasing ``bounds.window_peak_bound`` (the path at a
few sample angles and each coefficient's departure from its chord between them) where
many are left.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fe_crank.assess import fatigue
from fe_crank.assess.factors import factors, location_of
from fe_crank.assess.group.assessment import (
    Extreme,
    GroupResult,
    axis_for,
    fatigue_assessed,
    node_extreme,
)
from fe_crank.assess.group.bounds import (
    box_von_mises,
    coefficient_box,
    frobenius,
    goodman_lower,
    goodman_radius_lower,
    gough_pollard_lower,
    window_peak_bound,
)
from fe_crank.assess.group.peak import BOUND_RTOL, TIE_RTOL, group_peak, max_over_cycle
from fe_crank.assess.group.reference import PathBounds, ReferenceBalls
from fe_crank.assess.stress import von_mises_planes
from fe_crank.assess.superpose import UnitStresses, iter_planes
from fe_crank.io.material import Material

#: nodes of one exact fatigue evaluation within a block: the least value found narrows
#: the band for the next ones
SUB_BLOCK = 32
#: nodes per exact evaluation of the static peak (its bound is tight: few blocks)
STATIC_BLOCK = 32
#: more nodes than this left after the box bound: the peak's search orders them by
#: ``bounds.window_peak_bound`` (the path at a few sample angles), which rules out most of
#: them at a fraction of their evaluation
WINDOW_MIN = 4 * STATIC_BLOCK


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


def _search(
    lower: np.ndarray, block: int, evaluate: Callable[[np.ndarray, float], float], start: float = np.inf
) -> float:
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


def _static_peak(
    unit: UnitStresses,
    coefficients: np.ndarray,
    nodes: np.ndarray,
    bound: np.ndarray,
    block: int,
    ordered: bool = False,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``peak.group_peak`` on the nodes whose bound ``bound`` of the peak can reach the
    tie band of the largest peak of the ``block`` nodes of the largest bounds (the
    others can neither hold the group's peak nor tie with it); positions into ``nodes``.
    ``ordered``: ``bound`` is tight (a reference history's, ``reference``): it orders
    ``group_peak``'s search over every node directly."""
    bound = bound * (1 + BOUND_RTOL)
    if ordered:
        return group_peak(unit, coefficients, nodes, STATIC_BLOCK, bound)
    seed = np.argsort(-bound, kind="stable")[:STATIC_BLOCK]
    ((_, planes),) = iter_planes(unit, coefficients, nodes[seed], seed.size)
    best = float(max_over_cycle(von_mises_planes(planes))[0].max())
    keep = np.flatnonzero(bound >= best - TIE_RTOL * abs(best)) if np.isfinite(best) else np.arange(nodes.size)
    tight = window_peak_bound(unit, coefficients, nodes[keep]) if keep.size > WINDOW_MIN else None
    pos, vm, arg = group_peak(unit, coefficients, nodes[keep], STATIC_BLOCK, tight)
    return keep[pos], vm, arg


def _least(values: np.ndarray, done: np.ndarray, nodes: np.ndarray, unit: UnitStresses, group: str) -> Extreme:
    """The group's least value and its node among the evaluated positions ``done``: every
    node of the tie band is among them, so it is the one of an evaluation of all."""
    return node_extreme(values[done], nodes[done], unit, group, worst="min")


def group_extremes(
    unit: UnitStresses,
    group: str,
    coefficients: np.ndarray,
    theta: np.ndarray,
    material: Material,
    *,
    crank_radius: float,
    diameter: float | None = None,
    wanted: Wanted = Wanted(),
    running: Running | None = None,
    block: int = fatigue.NODE_BLOCK,
    additional_bending: float = 0.0,
    reference: PathBounds | None = None,
    translated: tuple[ReferenceBalls, np.ndarray] | None = None,
) -> GroupResult:
    """``assess_group``'s extremes of one node group at one speed (static peak, least
    Goodman and Gough-Pollard safety with their nodes; no overspeed, no per-node fields),
    each evaluated only where it can occur (module docstring).  ``running``: the least
    fatigue values of the groups and throws of the same load state searched before; a
    group whose least value cannot reach their tie band has ``fatigue_safety`` (or
    ``gough_pollard_safety``) None: it cannot govern the state's criterion.
    ``additional_bending``: UR M53 4's sigma_add on the alternating bending stress, as in
    ``assess_group`` (Goodman: sigma_a' + sigma_add; Gough-Pollard: sigma_a + sigma_add).
    ``reference``: bounds of this history at the group's nodes from a reference history's
    values (``reference.reference_bounds``), searched by in place of the coefficient box
    (and of the Goodman search's box with it, the larger of the two lower bounds), the
    same extremes.  ``translated``: (the reference's balls at the group's nodes, M (6, n)):
    this history is that reference's translated by the constant tensor M
    (``reference.is_translation``), so its Goodman values at a node are the reference's
    ball moved by M (``reference.ReferenceBalls``: computed once per node, at the first
    history that needs it, and kept for the others), the same values to rounding."""
    running = Running() if running is None else running
    nodes = np.asarray(unit.groups[group])
    if nodes.size == 0:
        raise ValueError(f"node group {group!r} is empty")
    limits = fatigue.fatigue_limits(material) if fatigue_assessed(group) else None
    axis = axis_for(group, crank_radius)
    # the limits of each criterion wanted and evaluable here (None: not evaluated)
    goodman = limits if wanted.fatigue else None
    torsion = limits.torsion if limits is not None and wanted.gough_pollard and axis is not None else None
    do_fatigue = goodman is not None
    do_gp = torsion is not None
    # the fatigue groups' box of the runs (the fatigue search's first bound); the static
    # groups' one box of the whole cycle (only the peak's prefilter)
    boxed = reference is None or do_gp or (do_fatigue and reference.amplitude is None)
    rho = big = fro_h = fro_c = None
    if boxed:
        rho, big, fro_h, fro_c = coefficient_box(unit, coefficients, nodes, runs=do_fatigue or do_gp, directional=do_gp)
    if reference is not None:
        peak_bound = reference.peak if big is None else np.minimum(reference.peak, box_von_mises(big))
    else:
        assert big is not None
        peak_bound = box_von_mises(big)
    pos, vm, arg = _static_peak(unit, coefficients, nodes, peak_bound, block, ordered=reference is not None)
    worst = node_extreme(vm, nodes[pos], unit, group, worst="max", angles=np.asarray(theta)[arg])
    ys = material.yield_strength
    static = ys / worst.value if (ys is not None and worst.value > 0) else np.inf
    ff = factors(material, diameter, location_of(group)) if (do_fatigue or do_gp) else None
    k = ff.product if ff is not None else 1.0
    fat = gpe = None
    amp = mean = None
    if goodman is not None:
        se, rm = k * goodman.bending, goodman.tensile
        good = np.full(nodes.size, np.inf)
        sa, sm = np.zeros(nodes.size), np.zeros(nodes.size)
        done = np.zeros(nodes.size, bool)

        def translated_block(p: np.ndarray, band: float) -> float:
            assert translated is not None
            balls, shift = translated
            new = p[~balls.known(p)]
            if new.size:  # the reference's path there, moved by M, filtered as below
                ((_, planes0),) = iter_planes(unit, balls.weights, nodes[new], new.size)
                planes = planes0 + shift[:, None, new]
                hi, lo = planes.max(axis=1), planes.min(axis=1)
                big2 = np.maximum(np.abs(hi), np.abs(lo))
                keep = goodman_lower(0.5 * (hi - lo), big2, se, rm, additional_bending) <= band
                if keep.any():
                    k = np.flatnonzero(keep)
                    lower = goodman_radius_lower(planes[:, :, k], 0.5 * (hi + lo)[:, k], se, rm, additional_bending)
                    keep[k[lower > band]] = False
                if keep.any():
                    balls.balls(new[keep], planes0[:, :, keep])
            q = p[balls.known(p)]
            if q.size == 0:
                return np.inf
            radius, centre = balls.balls(q)
            a, m = radius, fatigue.signed_mean(centre + shift[:, q])
            sa[q], sm[q] = a, m
            good[q] = fatigue.goodman_safety(a + additional_bending, m, se, rm)
            done[q] = True
            return float(good[q].min())

        def fatigue_block(p: np.ndarray, band: float) -> float:
            if translated is not None:
                return translated_block(p, band)
            ((_, planes),) = iter_planes(unit, coefficients, nodes[p], p.size)
            hi, lo = planes.max(axis=1), planes.min(axis=1)
            big2 = np.maximum(np.abs(hi), np.abs(lo))
            keep = goodman_lower(0.5 * (hi - lo), big2, se, rm, additional_bending) <= band
            if not keep.any():
                return np.inf
            # the radius about the mid range and the centre's distance from it (MCB)
            planes, p = planes[:, :, keep], p[keep]
            lower = goodman_radius_lower(planes, 0.5 * (hi + lo)[:, keep], se, rm, additional_bending)
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
                good[q] = fatigue.goodman_safety(a + additional_bending, m, se, rm)
                done[q] = True
                found = min(found, float(good[q].min()))
            return found

        start = running.fatigue
        if reference is not None and reference.amplitude is not None:
            first = reference.goodman_lower(se, rm, additional_bending)
            if rho is not None and big is not None:
                first = np.maximum(first, goodman_lower(rho, big, se, rm, additional_bending))
        else:
            assert rho is not None and big is not None
            first = goodman_lower(rho, big, se, rm, additional_bending)
        least = _search(first, block, fatigue_block, start)
        if least <= _band(start):  # the group can hold the state's least value
            fat = _least(good, done, nodes, unit, group)
            j = int(np.argmin(good))
            amp, mean = float(sa[j]), float(sm[j])
            running.fatigue = min(start, least)
    if limits is not None and torsion is not None and axis is not None:
        if fro_h is None or fro_c is None:
            raise RuntimeError("coefficient_box gave no directional bounds for the Gough-Pollard search")
        eb, et, rm = k * limits.bending, k * torsion, limits.tensile
        gp = np.full(nodes.size, np.inf)
        gp_done = np.zeros(nodes.size, bool)

        def gp_block(p: np.ndarray, band: float) -> float:
            ((_, planes),) = iter_planes(unit, coefficients, nodes[p], p.size)
            hi, lo = planes.max(axis=1), planes.min(axis=1)
            big2 = np.maximum(np.abs(hi), np.abs(lo))
            lower = gough_pollard_lower(frobenius(0.5 * (hi - lo)), frobenius(big2), eb, et, rm, additional_bending)
            keep = lower <= band
            if not keep.any():
                return np.inf
            hist = planes[:, :, keep].transpose(1, 0, 2)
            sig, tau = fatigue.bending_torsion(hist, unit.points[:, nodes[p[keep]]], axis)
            s_a, s_m = fatigue.half_range(sig)
            t_a, t_m = fatigue.half_range(tau)
            q = p[keep]
            gp[q] = fatigue.gough_pollard_safety(s_a + additional_bending, s_m, t_a, t_m, eb, et, rm)
            gp_done[q] = True
            return float(gp[q].min())

        start = running.gough_pollard
        least = _search(gough_pollard_lower(fro_h, fro_c, eb, et, rm, additional_bending), block, gp_block, start)
        if least <= _band(start):
            gpe = _least(gp, gp_done, nodes, unit, group)
            running.gough_pollard = min(start, least)
    return GroupResult(
        group,
        int(nodes.size),
        worst,
        None,
        float(static),
        None,
        fat,
        gpe,
        amp,
        mean,
        ff if do_fatigue else None,
        additional_bending=additional_bending if (do_fatigue or do_gp) else 0.0,
    )


__all__ = ["Wanted", "Running", "group_extremes"]
