"""``assess.group.reference``: bounds of a history's path from a reference history's.

By hand: one node, uniaxial unit stresses, a history that differs from the reference by
a constant coefficient: the path is the reference's shifted by M, so the peak bound is
P_0 + sigma_v(M) (exact here: the shift is along the peak) and the amplitude bound R_0.

Against an independent evaluation: on random unit stresses and histories that differ from
the reference by constants and a small varying part, every node's peak, Goodman
amplitude and signed mean (``fatigue.equivalent_amplitude_mean`` on the full history) lie
under the bounds, and ``group_extremes`` searched by them gives the same result as
without them.

The reference computed in single precision (``single_reference_path``) against the full
path's values in double precision: its upper bounds above them, its chord below the
full path's radius, the bounds of other histories from it holding, the search by them
the same.

A history that differs from the reference by constants alone is the reference's path
translated: its Goodman balls are the reference's moved by M, against each history's own.
"""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.assess import fatigue
from fe_crank.assess.group.bounds import box_von_mises
from fe_crank.assess.group.extremes import Wanted, group_extremes
from fe_crank.assess.group.reference import (
    ReferenceBalls,
    abs_sum,
    is_translation,
    reference_bounds,
    reference_path,
    reference_shift,
    single_reference_path,
)
from fe_crank.assess.stress import von_mises
from fe_crank.assess.superpose import UnitStresses, stress_history
from fe_crank.io.material import load_material

MAT = load_material("42CrMo4")


def _unit(stress: np.ndarray, group: str) -> UnitStresses:
    n = stress.shape[-1]
    return UnitStresses(
        stress=stress,
        points=np.zeros((3, n)),
        groups={group: np.arange(n)},
        cases=tuple(f"c{i}" for i in range(stress.shape[0])),
        node_ids=np.arange(n),
    )


def _fillet_stress(rng: np.random.Generator, n_cases: int, n: int) -> np.ndarray:
    """Random unit stresses (n_cases, 6, n) with a dominant component, as at a fillet."""
    s = rng.normal(0.0, 30e6, (n_cases, 6, n))
    s[:, 0] *= 3.0
    return s


def test_a_constant_shift_by_hand():
    """Case 0: sigma_xx 100 MPa per unit, a(t) = cos t (reference); case 1: sigma_xx
        50 MPa per unit, coefficient 0 in the reference and 0.2 in the history: M = 10 MPa.
        Reference peak 100 MPa, radius 100 MPa about 0; the history's peak 110 MPa, its
        amplitude 100 MPa: bounds 110 and 100 MPa (to the single precision of the reference's
    values)."""
    s = np.zeros((2, 6, 1))
    s[0, 0, 0], s[1, 0, 0] = 100e6, 50e6
    unit = _unit(s, "crankpin_fillet_1")
    t = np.linspace(0.0, 2 * np.pi, 73)
    w0 = np.column_stack([np.cos(t), np.zeros_like(t)])
    w = w0.copy()
    w[:, 1] = 0.2
    ref = reference_path(unit, w0, np.array([0]))
    # kept in single precision, rounded outwards (upper bounds up)
    assert 100e6 <= ref.peak[0] <= 100e6 * (1 + 2**-22) and 100e6 <= ref.radius[0] <= 100e6 * (1 + 2**-22)
    shift, r = reference_shift(w0, unit, w, abs_sum(unit))
    assert shift[0, 0] == pytest.approx(10e6, rel=1e-15) and np.all(r < 1e-3)
    b = reference_bounds(ref, shift, r)
    assert 110e6 <= b.peak[0] <= 110e6 * (1 + 2**-22)
    assert 100e6 <= b.amplitude[0] <= 100e6 * (1 + 2**-22)
    amp, mean = fatigue.equivalent_amplitude_mean(stress_history(unit, w, np.array([0])))
    assert amp[0] == pytest.approx(100e6, rel=1e-12) and mean[0] <= b.mean[0]
    assert reference_shift(w0, unit, w[:-1], abs_sum(unit)) is None  # other angles


def _bounds_hold(unit, group, ref, w0, t, nodes, changes, varied: int) -> None:
    """For each (constant shift of the last case, amplitude of a 3rd-order ripple on case
    ``varied``): the bounds from ``ref`` hold over the brute-force history at every node, and
    the search with them finds the same extremes as without."""
    sums = abs_sum(unit)
    for shift_const, vary in changes:
        w = w0.copy()
        w[:, -1] += shift_const
        w[:, varied] += vary * np.sin(3 * t)
        b = reference_bounds(ref, *reference_shift(w0, unit, w, sums))
        h = stress_history(unit, w, nodes)
        assert np.all(von_mises(h).max(axis=0) <= b.peak)
        amp, mean = fatigue.equivalent_amplitude_mean(h)
        assert np.all(amp <= b.amplitude) and np.all(mean <= b.mean)
        kw = dict(crank_radius=0.05, diameter=0.06, wanted=Wanted(gough_pollard=False), block=16)
        assert group_extremes(unit, group, w, t, MAT, reference=b, **kw) == group_extremes(unit, group, w, t, MAT, **kw)


def test_bounds_hold_and_the_search_by_them_finds_the_same_extremes():
    rng = np.random.default_rng(7)
    n_cases, n, n_t = 6, 300, 90
    s = _fillet_stress(rng, n_cases, n)
    group = "journal_fillet_1"
    unit = _unit(s, group)
    t = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    w0 = np.column_stack([np.cos(t + k) * (1 + k) for k in range(n_cases)])
    w0[:, -1] = 1.5  # a constant case (centrifugal)
    nodes = np.arange(n)
    ref = reference_path(unit, w0, nodes)
    _bounds_hold(unit, group, ref, w0, t, nodes, ((0.0, 0.0), (0.4, 0.0), (-1.2, 0.0), (0.3, 0.05)), 1)


def test_the_single_precision_reference_bounds_the_full_paths_values():
    """The reference computed in single precision against the full path's values in
    double precision (brute force): its upper bounds above, its chord below the radius,
    and the bounds of other histories from it holding and searched by as before."""
    rng = np.random.default_rng(11)
    n_cases, n, n_t = 24, 200, 360
    s = _fillet_stress(rng, n_cases, n)
    group = "journal_fillet_1"
    unit = _unit(s, group)
    t = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    w0 = np.column_stack([np.cos(t + k) * (1 + k % 5) for k in range(n_cases)])
    w0[:, 2] += 3.0 * np.exp(-(((t - 2.0) / 0.05) ** 2))  # a sharp rise, as the gas force's
    w0[:, -1] = 1.5
    nodes = np.arange(n)
    full = reference_path(unit, w0, nodes)
    single = single_reference_path(unit, w0, nodes)
    for f in ("peak", "mid_vm", "mid_hydro", "radius", "hydro"):
        assert np.all(getattr(single, f) >= getattr(full, f)), f
        assert np.all(getattr(single, f) <= getattr(full, f) + 1e-2 * full.peak), f  # a few parts in a thousand
    assert np.all(single.chord <= full.radius) and np.all(single.chord >= 0.99 * full.chord - 1e-2 * full.peak)
    assert np.all(single_reference_path(unit, w0, nodes, fatigue_values=False).peak == single.peak)
    _bounds_hold(unit, group, single, w0, t, nodes, ((0.0, 0.0), (0.4, 0.0), (0.3, 0.05)), 3)


def test_another_placements_reference_bounds_the_history():
    """The bound a study's screening takes for a group whose own placement's reference is
    not built: another placement's reference (counterweight cases left out or scaled,
    constants here, and the redundant bearing's force changed over the cycle).  Brute
    force: every node's peak, Goodman amplitude and signed mean lie under the bounds."""
    rng = np.random.default_rng(3)
    n_cases, n, n_t = 8, 120, 96
    s = _fillet_stress(rng, n_cases, n)
    unit = _unit(s, "crankpin_fillet_1")
    t = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    w0 = np.column_stack([np.cos(t + k) * (1 + k % 3) for k in range(n_cases)])
    w0[:, -3:] = 1.5  # three counterweights' centrifugal cases (constant)
    w = w0.copy()
    w[:, -2] = 0.0  # one left out
    w[:, -1] = 2.4  # one scaled
    w[:, 1] += 0.2 * np.sin(t)  # the redundant bearing's force changed
    nodes = np.arange(n)
    for ref in (reference_path(unit, w0, nodes), single_reference_path(unit, w0, nodes)):
        b = reference_bounds(ref, *reference_shift(w0, unit, w, abs_sum(unit)))
        h = stress_history(unit, w, nodes)
        assert np.all(von_mises(h).max(axis=0) <= b.peak)
        amp, mean = fatigue.equivalent_amplitude_mean(h)
        assert np.all(amp <= b.amplitude) and np.all(mean <= b.mean)
        assert np.all(b.peak <= 3.0 * von_mises(h).max(axis=0))  # and not vacuous here


def test_the_kept_box_bounds_a_shift_by_its_direction():
    """The single-precision reference keeps a box of its path (``box_mid``, ``box_half``):
    brute force, the exact path lies in it at every angle.  A history shifted by large
    constants (a counterweight's case scaled up and down, as a study's balance rates, and
    one left out) has its peak, Goodman amplitude and signed mean under the bounds from
    it; the peak bound is never above the one without the box (P_0 + sigma_v(M) + v) and
    well below it where the shift lowers the stress; the search by the bounds finds the
    same extremes as without any."""
    rng = np.random.default_rng(19)
    n_cases, n, n_t = 8, 150, 120
    s = _fillet_stress(rng, n_cases, n)
    s[-1] = 0.8 * s[0]  # the counterweight's stress along the pin's: a shift can lower the peak
    group = "crankpin_fillet_1"
    unit = _unit(s, group)
    t = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    w0 = np.column_stack([np.cos(t + k) * (1 + k % 3) for k in range(n_cases)])
    w0[:, 0] += 2.0  # a mean along the counterweight's stress
    w0[:, -2:] = 1.0  # two counterweights' centrifugal cases (constant)
    nodes = np.arange(n)
    ref = single_reference_path(unit, w0, nodes)
    assert ref.box_mid is not None and ref.box_half is not None and ref.mid_slack is not None
    h0 = stress_history(unit, w0, nodes)  # (n_t, 6, n)
    assert np.all(np.abs(h0 - ref.box_mid.astype(float)) <= ref.box_half)
    sums = abs_sum(unit)
    kw = dict(crank_radius=0.05, diameter=0.06, wanted=Wanted(gough_pollard=False), block=16)
    lower = False
    for k_cw in (-2.5, -1.0, 0.0, 0.6, 2.0):
        w = w0.copy()
        w[:, -1] = k_cw
        w[:, 1] += 0.05 * np.sin(t)  # a redundant bearing's force changed a little
        shift, r = reference_shift(w0, unit, w, sums)
        b = reference_bounds(ref, shift, r)
        h = stress_history(unit, w, nodes)
        peak = von_mises(h).max(axis=0)
        assert np.all(peak <= b.peak)
        amp, mean = fatigue.equivalent_amplitude_mean(h)
        assert np.all(amp <= b.amplitude) and np.all(mean <= b.mean)
        plain = (ref.peak + von_mises(shift) + box_von_mises(r)) * (1 + 1e-9)
        assert np.all(b.peak <= plain)
        lower |= bool(np.any(b.peak < 0.8 * plain))
        assert group_extremes(unit, group, w, t, MAT, reference=b, **kw) == group_extremes(unit, group, w, t, MAT, **kw)
    assert lower


def test_a_translated_history_takes_the_references_balls():
    """Histories that differ from the reference by constants alone (a study's candidates of
    one placement and state on linear bearing laws) are the reference's path translated by
    M: ``ReferenceBalls`` moved by M give every node's Goodman amplitude and mean tensor of
    ``fatigue.amplitude_mean`` on the history's own path to rounding, and the search by them
    (one set of balls kept across the histories, as the study keeps it across its
    candidates) the same extremes as the search on each history's own path."""
    group, n_cases, nodes = "crankpin_fillet_1", 8, np.arange(250)
    unit = _unit(_fillet_stress(np.random.default_rng(5), n_cases, nodes.size), group)
    t = np.linspace(0.0, 4 * np.pi, 120, endpoint=False)
    w0 = np.column_stack([np.cos(t + k) * (1 + k % 3) for k in range(n_cases)])
    w0[:, -2:] = 1.5  # two constant cases (counterweights' centrifugal)
    ref = single_reference_path(unit, w0, nodes)
    balls = ReferenceBalls(unit, w0, nodes)
    sums = abs_sum(unit)
    kw = dict(crank_radius=0.05, diameter=0.06, wanted=Wanted(gough_pollard=False), block=16)
    ripple = w0.copy()
    ripple[:, 1] += 1e-6 * np.sin(3 * t)
    assert not is_translation(w0, ripple) and not is_translation(w0, w0[:-1])
    for d in ((0.0, 0.0, 0.0), (0.4, -0.3, 0.0), (-1.2, 0.5, 0.02), (0.7, 0.7, -0.01)):
        w = w0.copy()
        w[:, -2] += d[0]
        w[:, -1] += d[1]
        w[:, 0] += d[2]  # a varying case moved by a constant (a redundant bearing force)
        assert is_translation(w0, w)
        shift, r = reference_shift(w0, unit, w, sums, 0.0)
        own = group_extremes(unit, group, w, t, MAT, reference=reference_bounds(ref, shift, r), **kw)
        moved = group_extremes(
            unit, group, w, t, MAT, reference=reference_bounds(ref, shift, r), translated=(balls, shift), **kw
        )
        assert moved.max_von_mises == own.max_von_mises  # the peak: from the history itself
        assert moved.fatigue_safety.value == pytest.approx(own.fatigue_safety.value, rel=1e-12)
        assert moved.fatigue_safety.node == own.fatigue_safety.node
        assert moved.amplitude_at_critical == pytest.approx(own.amplitude_at_critical, rel=1e-12)
        assert moved.mean_at_critical == pytest.approx(own.mean_at_critical, rel=1e-12)
        radius, centre = balls.balls(nodes)
        amp, mean, _ = fatigue.amplitude_mean(stress_history(unit, w, nodes))
        scale = np.abs(stress_history(unit, w, nodes)).max()
        assert np.allclose(radius, amp, rtol=1e-12, atol=1e-12 * scale)
        assert np.allclose(centre + shift, mean, rtol=0, atol=1e-12 * scale)
