"""Bounds of a node's stress path from the path of another load history on the same unit
stresses: what a series of load histories that differ little (the counterweight
candidates of a study in one engine state) searches by, instead of each history's own.

A reference history S_0(t) = sum_c W0_c(t) U_c is evaluated once at every node of a group
(``reference_path``): its peak von Mises stress P_0, the von Mises and hydrostatic stress
of its mid-range tensor mid_0, the radius R_0 about mid_0, half the chord L_0 from its
point farthest from mid_0 (the quantities of ``bounds.goodman_radius_lower``) and its
largest hydrostatic stress p_0, kept in single precision rounded outwards; or bounds of
these from the history computed in single precision (``single_reference_path``, about
half the cost: every bound below holds with them in place of the path's own values).
Another history W of the same angles differs by D(t) = W(t) - W0(t); with m_c and h_c the
mid range and the half range of D_c over the cycle, S(t) = S_0(t) + M + V(t) with the
constant tensor M = sum_c m_c U_c and |V_j(t)| <= r_j = sum_c h_c |U_c,j| per component
(``reference_bounds``).  With box_von_mises(r) = v (the largest von Mises stress within
the box, ``bounds.box_von_mises``), von Mises a seminorm:

* peak: sigma_v(S(t)) <= sigma_v(S_0(t) + M) + sigma_v(V(t)), and sigma_v(S_0(t) + M)
  is at most P_0 + sigma_v(M) and at most sqrt(P_0^2 + 2 max_box (Q M) . S_0 +
  sigma_v(M)^2), with Q von Mises' quadratic form and the box one of S_0's path kept with
  the reference (``single_reference_path``: its computed mid range m and half widths,
  ``_shifted``): the shift's own direction against the path's, tighter where the
  shift lowers the stress;
* the mid range of S is mid_0 + M + e with |e_j| <= r_j, so the radius about it
  R <= R_0 + 2 v, its von Mises stress <= sigma_v(mid_0) + sigma_v(M) + v (and, with the
  box, <= sigma_v(m + M) + sigma_v's bound of mid_0 - m + v), and half the distance
  between the two points of S at the angles of L_0 is at least L_0 - v: a lower bound
  of the minimum circumscribed ball's radius, as L_0 is of S_0's;
* the hydrostatic stress of S(t) <= p_0 + p(M) + (r_x + r_y + r_z)/3, of its mid range
  <= p(mid_0) + p(M) + (r_x + r_y + r_z)/3;

and Goodman's safety is at least ``bounds.goodman_radius_lower``'s expression of these
(its argument, with the bounds in place of the path's own values).  Rounding: r_j is
widened by 1e-12 (max_c max_t |W_c| + max_c max_t |W0_c|) sum_c |U_c,j| (``bounds``'s
allowance; each computed component is within ~n_cases x 1.1e-16 of sum_c |W_c| |U_c,j|),
every bound by ``peak.BOUND_RTOL``.  The bounds only order and skip nodes of ``extremes``' searches, which
evaluate the history itself at every node that can govern: the extremes found are those
of an evaluation of every node, whichever reference is taken (a closer one skips more).
Nothing above asks W0 to be close to W: any history of the same angles bounds any other
(a study's candidate of another placement, its counterweight cases zero or scaled,
bounds a group until the group's own reference is built), only less tightly the
farther it is.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.assess import fatigue
from fe_crank.assess.group.bounds import ROUNDING, box_von_mises
from fe_crank.assess.group.peak import BOUND_RTOL
from fe_crank.assess.stress import von_mises, von_mises_planes
from fe_crank.assess.superpose import UnitStresses, iter_planes


@dataclass(frozen=True)
class ReferencePath:
    """The reference history's values at the nodes of one group (module docstring), Pa,
    stored in single precision rounded outwards (upper bounds up, the chord down):
    ``weights`` (n_t, n_cases) its coefficients (not copied: not to be changed); per
    node ``peak`` P_0, ``mid_vm`` sigma_v(mid_0), ``mid_hydro`` p(mid_0), ``radius`` R_0,
    ``chord`` L_0, ``hydro`` p_0 (the last five None: peak only)."""

    weights: np.ndarray
    peak: np.ndarray
    mid_vm: np.ndarray | None = None
    mid_hydro: np.ndarray | None = None
    radius: np.ndarray | None = None
    chord: np.ndarray | None = None
    hydro: np.ndarray | None = None
    #: (6, n) a tensor m and (6, n) half widths h with |S_0,j(t) - m_j| <= h_j at every
    #: angle, and (n,) box_von_mises of the bound of |mid_0 - m| (``single_reference_path``;
    #: None: not kept): what ``reference_bounds`` takes the shift's direction into account by
    box_mid: np.ndarray | None = None
    box_half: np.ndarray | None = None
    mid_slack: np.ndarray | None = None
    #: (n,) sigma_v(m)^2 of ``box_mid`` and the magnitudes of its terms (double precision)
    box_mid_vm2: np.ndarray | None = None
    box_mid_mag: np.ndarray | None = None


def _up(x: np.ndarray) -> np.ndarray:
    """Single precision, at least ``x``."""
    out: np.ndarray = np.nextafter(x.astype(np.float32), np.float32(np.inf))
    return out


def _down(x: np.ndarray) -> np.ndarray:
    """Single precision, at most ``x``."""
    out: np.ndarray = np.nextafter(x.astype(np.float32), np.float32(-np.inf))
    return out


@dataclass(frozen=True)
class PathBounds:
    """Upper bounds of a history's values at the nodes of one group (module docstring), Pa:
    ``peak`` of the peak von Mises stress; ``amplitude`` and ``mean`` of Goodman's
    equivalent amplitude and signed mean (None: peak only)."""

    peak: np.ndarray
    amplitude: np.ndarray | None = None
    mean: np.ndarray | None = None

    def goodman_lower(self, endurance: float, tensile: float, additional: float = 0.0) -> np.ndarray:
        """Goodman's safety is at least this at each node (``additional``: UR M53's
        sigma_add on the amplitude, as ``bounds.goodman_lower``)."""
        if self.amplitude is None or self.mean is None:
            raise ValueError("these bounds hold the peak only")
        return fatigue.goodman_safety(self.amplitude + additional, self.mean, endurance, tensile)


def reference_path(
    unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, *, fatigue_values: bool = True, block: int = 128
) -> ReferencePath:
    """The reference history ``coefficients`` evaluated at ``nodes`` (module docstring),
    on the same history planes as every criterion (``superpose.iter_planes``);
    ``fatigue_values`` False: the peak alone."""
    c = np.atleast_2d(np.asarray(coefficients, float))
    nodes = np.asarray(nodes)
    n = nodes.size
    peak = np.empty(n)
    vals = np.empty((5, n)) if fatigue_values else None  # mid_vm, mid_hydro, radius, chord, hydro
    for s in range(0, n, block):
        ((_, planes),) = iter_planes(unit, c, nodes[s : s + block], block)
        k = slice(s, s + planes.shape[-1])
        peak[k] = von_mises_planes(planes).max(axis=0)
        if vals is None:
            continue
        m = 0.5 * (planes.max(axis=1) + planes.min(axis=1))
        r0, far = fatigue.max_and_first(von_mises_planes(planes, m))
        cols = np.arange(planes.shape[-1])
        vals[0, k], vals[1, k], vals[2, k] = von_mises(m), (m[0] + m[1] + m[2]) / 3.0, r0
        vals[3, k] = 0.5 * von_mises_planes(planes, planes[:, far, cols]).max(axis=0)
        vals[4, k] = ((planes[0] + planes[1] + planes[2]) / 3.0).max(axis=0)
    if vals is None:
        return ReferencePath(c, _up(peak))
    return ReferencePath(c, _up(peak), _up(vals[0]), _up(vals[1]), _up(vals[2]), _down(vals[3]), _up(vals[4]))


#: von Mises' quadratic form on (xx, yy, zz, xy, yz, xz): sigma_v(X)^2 = X . Q X
_Q = np.array(
    [
        [1.0, -0.5, -0.5, 0.0, 0.0, 0.0],
        [-0.5, 1.0, -0.5, 0.0, 0.0, 0.0],
        [-0.5, -0.5, 1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 3.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 3.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 3.0],
    ]
)


_ABS_Q = np.abs(_Q)

#: unit roundoff of single precision
_U32 = float(np.finfo(np.float32).eps) / 2


def _peak32(planes: np.ndarray, scratch: np.ndarray) -> np.ndarray:
    """max_t of von Mises' stress of the single-precision path ``planes`` (6, n_t, n), every
    operation in single precision, as ``stress.von_mises_planes`` orders them; the square
    root taken of the largest square (the same value: the rounded square root is
    monotone); ``scratch`` (>= 4 planes) is overwritten."""
    x, y, z = planes[0], planes[1], planes[2]
    acc, tmp, sq = scratch[0], scratch[1], scratch[2]
    np.subtract(x, y, out=acc)
    np.multiply(acc, acc, out=acc)
    np.subtract(y, z, out=tmp)
    np.multiply(tmp, tmp, out=tmp)
    acc += tmp
    np.subtract(z, x, out=tmp)
    np.multiply(tmp, tmp, out=tmp)
    acc += tmp
    acc *= np.float32(0.5)
    np.multiply(planes[3], planes[3], out=sq)
    np.multiply(planes[4], planes[4], out=tmp)
    sq += tmp
    np.multiply(planes[5], planes[5], out=tmp)
    sq += tmp
    sq *= np.float32(3.0)
    acc += sq
    out: np.ndarray = np.sqrt(acc.max(axis=0))
    return out


@dataclass(frozen=True)
class GroupUnits:
    """The unit stresses of one group's nodes in single precision, contiguous
    (``group_units``): what ``single_reference_path`` multiplies, taken once for every
    reference of the group (each reference otherwise gathers and converts them anew)."""

    nodes: np.ndarray
    stress32: np.ndarray  # (n_cases, 6, n) float32


def group_units(unit: UnitStresses, nodes: np.ndarray) -> GroupUnits:
    """``unit``'s stresses at ``nodes`` rounded to single precision (``GroupUnits``)."""
    nodes = np.asarray(nodes)
    return GroupUnits(nodes, np.ascontiguousarray(unit.stress[:, :, nodes], dtype=np.float32))


def single_reference_path(
    unit: UnitStresses,
    coefficients: np.ndarray,
    nodes: np.ndarray,
    *,
    fatigue_values: bool = True,
    block: int = 128,
    units: GroupUnits | None = None,
) -> ReferencePath:
    """Bounds of the values of ``reference_path`` from the history computed in single
    precision (the matrix products and the passes over the path at about half the cost).
    Each computed component X~_j(t) = fl32(sum_c fl32(a_c) fl32(U_c,j)) is within
    gamma_n sum_c |a_c U_c,j| (1 + 2u) + 2u |a_c U_c,j| of the exact one (u = 2^-24, n
    the number of cases: Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed.,
    section 3.1, in any order of summation), so within a_j = 2 (n + 8) u A_j,
    A_j = sum_c max_t |a_c(t)| |U_c,j| (a factor 2 kept in hand).  The von Mises stress
    of a computed tensor (differences, squares, sums of non-negative terms, a square
    root) is within 16 u of its exact value relatively.  So, with box_von_mises(a) = v_a:

    * peak P_0 <= max_t sigma_v~(X~(t)) (1 + 16 u) + v_a;
    * the mid range mid_0 of the exact path: the computed range [lo~, hi~] taken to
      double precision, m = (hi~ + lo~) / 2 is within a_j of mid_0; sigma_v(mid_0) <=
      sigma_v(m) + v_a, p(mid_0) <= p(m) + (a_x + a_y + a_z) / 3;
    * the radius R_0 about mid_0 <= the computed largest distance of X~ from m (m
      rounded to single precision: within u |m_j|) times (1 + 16 u) plus
      box_von_mises(2 a + u |m|);
    * the chord: half the computed distance between two computed points of the path,
      times (1 - 16 u), less v_a (each point within a of the exact one);
    * the largest hydrostatic stress p_0 <= the computed one + (a_x + a_y + a_z) / 3
      + 4 u (A_x + A_y + A_z) / 3 (the sum of three and the division rounded).

    A few parts in a million looser than ``reference_path``'s values, kept in single
    precision rounded outwards as they are.

    The product takes only the cases that vary over the cycle, and the constant ones
    summed beforehand into one term: K_j = sum_c a_c fl32(U_c,j) over the constant cases
    in double precision (within 1e-15 relatively of its exact value), rounded to single
    precision (within u |K_j|), enters with the coefficient 1.  That is the sum of n' <= n
    computed terms whose magnitudes sum to at most A_j (1 + 2u), each within 2u of its
    exact value, so the computed component is again within gamma_n' A_j (1 + 2u)^2 +
    2u A_j <= a_j of the exact one; a case of coefficient zero throughout adds exactly
    nothing and is left out.

    Kept besides (``ReferencePath.box_mid`` ...): the computed mid range m (exact in
    double precision) in single precision, m' = fl32(m), and the half widths
    (hi~ - lo~) / 2 + a_j + u |m_j| rounded up: every component of the exact path lies
    within them of m' (the computed range within a_j of the exact one); and
    box_von_mises(a + u |m|) rounded up, a bound of sigma_v(mid_0 - m') (mid_0 within a_j
    of m).  ``units``: the group's stresses in single precision
    (``group_units``, at ``nodes``), else taken here; A_j then summed in single precision
    from them (within (n + 2) u relatively, widened by 2 (n + 4) u)."""
    c = np.atleast_2d(np.asarray(coefficients, float))
    nodes = np.asarray(nodes)
    if units is None:
        units = group_units(unit, nodes)
    elif units.stress32.shape[-1] != nodes.size:
        raise ValueError("single_reference_path: units are not of these nodes")
    u_all = units.stress32
    n = nodes.size
    n_cases = c.shape[1]
    err = 2.0 * (n_cases + 8) * _U32
    absmax = np.abs(c).max(axis=0)
    absmax32 = _up(absmax)
    used = absmax > 0.0
    const = used & (c.max(axis=0) == c.min(axis=0))
    var = np.flatnonzero(used & ~const)
    kc = np.flatnonzero(const)
    c32 = np.ascontiguousarray(c[:, var], dtype=np.float32)
    if kc.size:
        c32 = np.hstack([c32, np.ones((c.shape[0], 1), np.float32)])
    widen = 1.0 + 2.0 * (n_cases + 4) * _U32
    up32 = 1.0 + 16.0 * _U32
    peak = np.empty(n)
    vals = np.empty((5, n)) if fatigue_values else None  # mid_vm, mid_hydro, radius, chord, hydro
    box = np.empty((2, 6, n))  # the computed mid range m, the half widths about fl32(m)
    slack = np.empty(n)
    for s in range(0, n, block):
        u32 = u_all[:, :, s : s + block]
        b = u32.shape[-1]
        big = (absmax32 @ np.abs(u32).reshape(n_cases, -1)).reshape(6, b).astype(float) * widen  # >= A_j
        a = err * big
        v_a = box_von_mises(a)
        terms = u32[var]
        if kc.size:
            k = np.einsum("c,cjn->jn", c[0, kc], u32[kc].astype(float)).astype(np.float32)
            terms = np.concatenate([terms, k[None]], axis=0)
        planes = np.empty((6, c.shape[0], b), np.float32)
        for j in range(6):
            np.dot(c32, terms[:, j, :], out=planes[j])
        scratch = np.empty_like(planes)
        peak[s : s + b] = _peak32(planes, scratch).astype(float) * up32 + v_a
        hi, lo = planes.max(axis=1).astype(float), planes.min(axis=1).astype(float)
        m = 0.5 * (hi + lo)  # exact: sums and halves of single-precision values
        box[0, :, s : s + b] = m
        box[1, :, s : s + b] = 0.5 * (hi - lo) + a + _U32 * np.abs(m)
        slack[s : s + b] = box_von_mises(a + _U32 * np.abs(m))
        if vals is None:
            continue
        r0, far = fatigue.max_and_first(von_mises_planes(planes, m.astype(np.float32), buf=scratch))
        cols = np.arange(b)
        chord = 0.5 * von_mises_planes(planes, planes[:, far, cols], buf=scratch).max(axis=0).astype(float)
        p0 = ((planes[0] + planes[1] + planes[2]) / np.float32(3.0)).max(axis=0).astype(float)
        p_a = (a[0] + a[1] + a[2]) / 3.0
        vals[0, s : s + b] = von_mises(m) + v_a
        vals[1, s : s + b] = (m[0] + m[1] + m[2]) / 3.0 + p_a
        vals[2, s : s + b] = r0.astype(float) * up32 + box_von_mises(2.0 * a + _U32 * np.abs(m))
        vals[3, s : s + b] = chord * (1.0 - 16.0 * _U32) - v_a
        vals[4, s : s + b] = p0 + p_a + 4.0 * _U32 * (big[0] + big[1] + big[2]) / 3.0
    up, down = 1 + BOUND_RTOL, 1 - BOUND_RTOL
    mid32 = box[0].astype(np.float32)
    m = mid32.astype(float)
    kept = {
        "box_mid": mid32,
        "box_half": _up(box[1] * up),
        "mid_slack": _up(slack * up),
        "box_mid_vm2": np.einsum("jn,jn->n", _Q @ m, m),
        "box_mid_mag": 2.0 * np.einsum("j,jn->n", np.diag(_Q), m * m),
    }
    if vals is None:
        return ReferencePath(c, _up(peak * up), **kept)
    mid_hydro = vals[1] + np.abs(vals[1]) * BOUND_RTOL
    hydro = vals[4] + np.abs(vals[4]) * BOUND_RTOL
    chord = np.maximum(vals[3], 0.0) * down
    return ReferencePath(
        c, _up(peak * up), _up(vals[0] * up), _up(mid_hydro), _up(vals[2] * up), _down(chord), _up(hydro), **kept
    )


#: the largest half range over the cycle of a history's departure from the reference,
#: relative to the largest coefficient of either, for which the history is taken as the
#: reference's translated by a constant tensor (``is_translation``): the departure's
#: variation then moves each stress component by at most this times sum_c |U_c,j|, the
#: order of ``bounds.ROUNDING``'s allowance for the rounding of the sums themselves
TRANSLATION_RTOL = 1e-12


def is_translation(weights: np.ndarray, coefficients: np.ndarray) -> bool:
    """Whether the history ``coefficients`` is the reference ``weights`` plus a constant
    (per case, over the cycle; ``TRANSLATION_RTOL``): then S(t) = S_0(t) + M at every
    node, with M = sum_c D_c U_c (``reference_shift`` with ``small`` 0), as for the
    counterweight candidates of one engine state on linear bearing laws (their
    counterweights' centrifugal cases constant in the shaft's frame, the redundant
    bearing forces changed by a constant)."""
    c = np.atleast_2d(np.asarray(coefficients, float))
    if c.shape != weights.shape:
        return False
    d = c - weights
    top = float(np.abs(c).max(initial=0.0)) + float(np.abs(weights).max(initial=0.0))
    return bool((0.5 * (d.max(axis=0) - d.min(axis=0))).max(initial=0.0) <= TRANSLATION_RTOL * top)


class ReferenceBalls:
    """The reference history's Goodman ball at each node of one group -- the radius and
    centre ``fatigue.amplitude_mean`` returns, computed from the reference's own path (the
    same history planes as every criterion) when first asked for and kept.

    A history that is the reference's translated by a constant tensor M
    (``is_translation``) has the same balls translated by M: ``amplitude_mean`` starts at
    the component-wise mid range (which moves by M), measures distances between points
    of the path or from a centre (unchanged), and moves its centres towards points of the
    path (by M with them); so its amplitude is the reference's radius and its mean tensor
    the reference's centre plus M, to rounding (the sums of the two histories are rounded
    apart, as the study's superposition and a full solve of the same shaft are).  One
    reference's balls thus give every candidate of its placement and state its Goodman
    values at the nodes evaluated before, at the cost of a tensor sum."""

    def __init__(self, unit: UnitStresses, weights: np.ndarray, nodes: np.ndarray):
        self.unit, self.weights, self.nodes = unit, weights, np.asarray(nodes)
        self._slot = np.full(self.nodes.size, -1, dtype=np.int64)
        self._radius = np.empty(0)
        self._centre = np.empty((6, 0))

    def known(self, positions: np.ndarray) -> np.ndarray:
        """Which of ``positions`` (into the group's nodes) hold a ball already."""
        out: np.ndarray = self._slot[positions] >= 0
        return out

    def balls(self, positions: np.ndarray, planes: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
        """(radius (k,), centre (6, k)) at ``positions``, those not yet known computed now
        from the reference's path (``planes`` (6, n_t, k'): that path at the unknown
        positions, in their order, where the caller has it)."""
        positions = np.asarray(positions)
        missing = positions[self._slot[positions] < 0]  # positions are distinct
        if missing.size:
            if planes is None or planes.shape[-1] != missing.size:
                ((_, planes),) = iter_planes(self.unit, self.weights, self.nodes[missing], missing.size)
            assert planes is not None
            radius, centre, _ = fatigue.amplitude_mean(planes.transpose(1, 0, 2))
            self._slot[missing] = self._radius.size + np.arange(missing.size)
            self._radius = np.concatenate([self._radius, radius])
            self._centre = np.concatenate([self._centre, centre], axis=1)
        s = self._slot[positions]
        return self._radius[s], self._centre[:, s]


def abs_sum(unit: UnitStresses) -> np.ndarray:
    """sum_c |U_c,j| (6, n) at every assessed node of ``unit``: what ``reference_shift``
    bounds the small terms by."""
    out: np.ndarray = np.abs(unit.stress).sum(axis=0)
    return out


def reference_shift(
    weights: np.ndarray, unit: UnitStresses, coefficients: np.ndarray, sums: np.ndarray, small: float = 1e-9
) -> tuple[np.ndarray, np.ndarray] | None:
    """(M, r) (6, n) at every assessed node of ``unit`` of the history ``coefficients``
    against the reference history ``weights`` (module docstring); ``sums``: ``abs_sum``
    of ``unit``.  The cases whose mid range or half range of D is at most ``small`` times
    the largest coefficient enter r alone, by max_c (|m_c| + h_c) sum_c |U_c,j| (as the
    rounding allowance, by max_c (max_t |W_c| + max_t |W0_c|)), and so do the half ranges
    of the others that are at most ``TRANSLATION_RTOL`` times it (a translation's, whose
    product with |U_c| would cost as much as M's); None where the histories' angles
    differ."""
    c = np.atleast_2d(np.asarray(coefficients, float))
    if c.shape != weights.shape:
        return None
    d = c - weights
    hi, lo = d.max(axis=0), d.min(axis=0)
    m, h = 0.5 * (hi + lo), 0.5 * (hi - lo)
    top = float(np.abs(c).max(initial=0.0)) + float(np.abs(weights).max(initial=0.0))
    big = (np.abs(m) + h) > small * top
    # the cases that vary by more than a translation's allowance enter r one by one, the
    # others by their largest half range times sum_c |U_c,j|
    varied = big & (h > TRANSLATION_RTOL * top)
    u = unit.stress.reshape(unit.stress.shape[0], -1)
    rest = float((np.abs(m) + h)[~big].max(initial=0.0)) + float(h[big & ~varied].max(initial=0.0))
    r = (rest + ROUNDING * top) * sums
    shift = (m[big] @ u[big]).reshape(sums.shape) if big.any() else np.zeros_like(sums)
    if varied.any():
        r += (h[varied] @ np.abs(u[varied])).reshape(sums.shape)
    return shift, r


def _shifted(ref: ReferencePath, shift: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bounds of max_t sigma_v(S_0(t) + M) and of sigma_v(m + M) from the reference's peak
    P_0 and its box (|S_0,j(t) - m_j| <= h_j, ``ReferencePath.box_mid``, ``box_half``).
    Von Mises' stress is the root of a positive semi-definite quadratic form Q, so
    sigma_v(S_0 + M)^2 = sigma_v(S_0)^2 + 2 (Q M) . S_0 + sigma_v(M)^2, whose linear term
    is largest over the box at (Q M) . m + |Q M| . h, and sigma_v(m + M)^2 =
    sigma_v(m)^2 + 2 (Q M) . m + sigma_v(M)^2 (``box_mid_vm2``: sigma_v(m)^2).  Each sum
    widened by 1e-12 of its terms' magnitudes (``box_mid_mag``: those of sigma_v(m)^2) for
    its rounding (a few dozen operations of ~1.1e-16 each).  Returns the two bounds and
    one of sigma_v(M)."""
    assert ref.box_mid is not None and ref.box_half is not None
    assert ref.box_mid_vm2 is not None and ref.box_mid_mag is not None
    q = _Q @ shift
    big = _ABS_Q @ np.abs(shift)  # >= |Q M| and the magnitudes of its terms
    m = ref.box_mid
    qm = np.einsum("jn,jn->n", q, m)
    qh = np.einsum("jn,jn->n", np.abs(q), ref.box_half)
    lin = np.einsum("jn,jn->n", big, np.abs(m) + ref.box_half)  # the magnitudes of both terms
    s2 = np.einsum("jn,jn->n", q, shift)  # sigma_v(M)^2
    s2_mag = np.einsum("jn,jn->n", big, np.abs(shift))
    p2 = ref.peak.astype(float) ** 2
    peak = np.sqrt(np.maximum(p2 + 2.0 * (qm + qh) + s2 + 1e-12 * (p2 + 2.0 * lin + s2_mag), 0.0))
    mid = ref.box_mid_vm2 + 2.0 * qm + s2 + 1e-12 * (ref.box_mid_mag + 2.0 * lin + s2_mag)
    return peak, np.sqrt(np.maximum(mid, 0.0)), np.sqrt(np.maximum(s2 + 1e-12 * s2_mag, 0.0))


def reference_bounds(reference: ReferencePath, shift: np.ndarray, r: np.ndarray) -> PathBounds:
    """Bounds of a history at the nodes of ``reference`` from the reference's values and
    the history's ``reference_shift`` (M, r) at those nodes (module docstring)."""
    v = box_von_mises(r)
    up, down = 1 + BOUND_RTOL, 1 - BOUND_RTOL
    ref = reference
    mid_vm = None
    if ref.box_mid is not None and ref.mid_slack is not None:
        shifted, mid_shifted, vm_shift = _shifted(ref, shift)
        peak = np.minimum(ref.peak + vm_shift * up, shifted)
        mid_vm = mid_shifted * up + ref.mid_slack
    else:
        vm_shift = von_mises(shift)
        peak = ref.peak + vm_shift * up
    peak = (peak + v) * up
    if ref.mid_vm is None or ref.mid_hydro is None or ref.radius is None or ref.chord is None or ref.hydro is None:
        return PathBounds(peak)
    radius = (ref.radius + 2.0 * v) * up
    chord = np.maximum(ref.chord - v, 0.0) * down
    mid_vm = ref.mid_vm + vm_shift if mid_vm is None else np.minimum(mid_vm, ref.mid_vm + vm_shift)
    vm = (mid_vm + v) * up + 2.0 * np.sqrt(np.maximum(radius**2 - chord**2, 0.0))
    p_shift = (shift[0] + shift[1] + shift[2]) / 3.0
    p_r = (r[0] + r[1] + r[2]) / 3.0
    hydro = np.maximum(ref.mid_hydro, ref.hydro) + p_shift
    hydro = hydro + np.abs(hydro) * BOUND_RTOL + p_r
    mean = np.maximum(vm, hydro + 2.0 / 3.0 * vm)
    return PathBounds(peak, radius * up, mean * up)


__all__ = [
    "ReferencePath",
    "PathBounds",
    "GroupUnits",
    "group_units",
    "abs_sum",
    "reference_path",
    "single_reference_path",
    "reference_shift",
    "reference_bounds",
    "TRANSLATION_RTOL",
    "is_translation",
    "ReferenceBalls",
]
