"""The largest von Mises stress of a node group over a cycle, evaluated only where it
can occur.

The overspeed check needs, per group, only the largest sigma_v over the overspeed
cycle and where it occurs (``throw.assess_group``), not every node's peak.  With
S(t) = sum_c a_c(t) U_c (``superpose``), von Mises is a seminorm: sigma_v(S) =
sqrt(3/2) |dev S| (Frobenius norm of the deviator, a linear map of S), so the triangle
inequality and homogeneity give

    sigma_v(S(t)) <= sum_c |a_c(t)| sigma_v(U_c)        and so
    max_t sigma_v(S(t)) <= B = max_t sum_c |a_c(t)| sigma_v(U_c)   at every node.

The nodes are evaluated exactly (the same history planes and von Mises as every other
criterion) in decreasing order of B, ``block`` at a time, until the bound of every node
left, widened by 1e-12 for the rounding of both sides, lies below the tie band of the
largest peak found (peak - ``TIE_RTOL`` x peak, ``group.first_extreme``): such a node
can neither be the maximum nor tie with it, so the group's extreme -- value, first node
of the tie band, first angle -- is the one an evaluation of every node gives.
"""

from __future__ import annotations

import numpy as np

from fe_crank.assess.stress import von_mises, von_mises_planes
from fe_crank.assess.superpose import UnitStresses, iter_planes

#: values within this relative distance of an extreme count as ties; ties go to the
#: first (node, angle), so serial, process and Dask runs (whose solvers may differ in
#: the last digits) name the same place
TIE_RTOL = 1e-9
#: relative widening of the bound B for the rounding of B and of the evaluated peaks
#: (each a sum of at most a few dozen rounded terms: ~1e-15 relative)
BOUND_RTOL = 1e-12


def max_over_cycle(vm: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(max over axis 0, first index within ``TIE_RTOL`` of it) of a (n_t, n) array."""
    e = vm.max(axis=0)
    near = vm >= e - TIE_RTOL * np.abs(e)
    return e, np.argmax(near, axis=0)


def peak_bound(unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, chunk: int = 2048) -> np.ndarray:
    """B per node of ``nodes``: max_t sum_c |a_c(t)| sigma_v(U_c) (module docstring)."""
    a = np.abs(np.atleast_2d(np.asarray(coefficients, float)))
    out = np.empty(len(nodes))
    for s in range(0, len(nodes), chunk):
        v = von_mises(unit.stress[:, :, nodes[s : s + chunk]])  # (n_cases, k)
        out[s : s + chunk] = (a @ v).max(axis=0)
    return out


def group_peak(
    unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, block: int = 128, bound: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(positions in ``nodes`` evaluated, ascending; their peak sigma_v over the cycle;
    the first angle index within ``TIE_RTOL`` of it) -- every node that can hold the
    group's largest peak or tie with it (module docstring).  ``bound``: an upper bound of
    each node's evaluated peak, rounding included (``bounds.window_peak_bound``), in place
    of B."""
    nodes = np.asarray(nodes)
    bound = peak_bound(unit, coefficients, nodes) * (1.0 + BOUND_RTOL) if bound is None else np.asarray(bound)
    order = np.argsort(-bound, kind="stable") if np.isfinite(bound).all() else np.arange(nodes.size)
    done, peaks, args = [], [], []
    best = -np.inf
    buf = None
    for s in range(0, nodes.size, block):
        if np.isfinite(best) and bound[order[s]] < best - TIE_RTOL * abs(best):
            break  # bounds descend: no node left can reach the band
        pos = order[s : s + block]
        for _idx, planes in iter_planes(unit, coefficients, nodes[pos], block):
            buf = buf if buf is not None and buf.shape == planes.shape else np.empty(planes.shape)
            p, a = max_over_cycle(von_mises_planes(planes, buf=buf))
        done.append(pos)
        peaks.append(p)
        args.append(a)
        best = max(best, float(p.max()))
    pos = np.concatenate(done)
    keep = np.argsort(pos)
    return pos[keep], np.concatenate(peaks)[keep], np.concatenate(args)[keep]
