"""``study.screen``'s stress screening, its references built only where needed, against a
search of every group without any reference (independent: each group's own extremes by
``assess.group.extremes.group_extremes`` and ``assess.group.peak.group_peak``, the state's
reported value the largest peak or least safety, its place the first throw and group in
their order holding it).

A small shaft of synthetic unit stresses (random, one dominant component as at a fillet;
the second throw a copy of the first, so that every value ties exactly between the two
throws and the place reported must be the first throw's), two states, candidates of two
placements (every web's counterweight loaded; one web's left out): the screened peaks,
safeties and places equal the independent ones, and the second placement's candidate
builds its own references for only some of the groups (the others bounded by the first
placement's, rigorous as well: ``tests/assess/test_assess_reference.py``).
"""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

from fe_crank.assess.group.assessment import of_counterweight, section_diameter, sigma_add_applies
from fe_crank.assess.group.extremes import Wanted, group_extremes
from fe_crank.assess.group.peak import group_peak, peak_bound
from fe_crank.assess.group.reference import abs_sum, reference_bounds, reference_shift, single_reference_path
from fe_crank.assess.stress import von_mises
from fe_crank.assess.superpose import UnitStresses, stress_history
from fe_crank.assess.workers import threads
from fe_crank.io.material import load_material
from fe_crank.study.bodies import body_base, body_bound
from fe_crank.study.screen import (
    REFERENCE_BLOCK,
    EngineState,
    StateLoads,
    StressScreen,
    StudyShaft,
    candidate_overspeed,
    candidate_stresses,
    seed_references,
)

MAT = load_material("42CrMo4")
CASES = ("pin_x", "pin_y", "torque", "centrifugal", "bearing", "cw_1@1", "cw_2@1", "cw_1@2", "cw_2@2")
GROUPS = {
    "crankpin_fillet_1": 40,
    "journal_fillet_2": 40,
    "oil_bore": 30,
    "counterweight_fillet_1": 20,
    "junction_2": 20,
}
DIAMETERS = (0.05, 0.06)
ADD = 5e6


def _unit(rng) -> UnitStresses:
    n = sum(GROUPS.values())
    s = rng.normal(0.0, 30e6, (len(CASES), 6, n))
    s[:, 0] *= 3.0  # a dominant component, as at a fillet
    groups, k = {}, 0
    for g, m in GROUPS.items():
        groups[g] = np.arange(k, k + m)
        k += m
    return UnitStresses(stress=s, points=np.zeros((3, n)), groups=groups, cases=CASES, node_ids=np.arange(n))


def _shaft(rng) -> StudyShaft:
    unit = _unit(rng)
    layout = SimpleNamespace(geometry=SimpleNamespace(crank_radius=0.05))  # the screening reads its crank radius
    return StudyShaft(layout, SimpleNamespace(names=CASES), {}, [], 0, stresses=(("1", unit), ("2", unit)))


def _weights(t: np.ndarray, cw: tuple[float, ...], phase: float) -> np.ndarray:
    """Pin force, torque, centrifugal and a varying redundant bearing's force over the
    cycle, the counterweights' constant cases ``cw``."""
    w = np.zeros((t.size, len(CASES)))
    w[:, 0] = 2.0 * np.cos(t + phase) + 3.0 * np.exp(-(((t - 1.0) / 0.2) ** 2))
    w[:, 1] = np.sin(2 * t + phase)
    w[:, 2] = 0.5 + 0.3 * np.sin(t)
    w[:, 3] = 1.2
    w[:, 4] = 0.4 * np.cos(t) + 0.1 * sum(cw)
    w[:, 5:] = cw
    return w


def _loads(cw: tuple[float, ...]) -> list[StateLoads]:
    out = []
    for label, phase in (("full load", 0.0), ("no load", 0.7)):
        t = np.linspace(0.0, 4 * np.pi, 96, endpoint=False)
        state = EngineState(label, 300.0, SimpleNamespace(theta=t))  # the screening reads the angles
        out.append(StateLoads(state, np.zeros(0), np.zeros(0), None, _weights(t, cw, phase)))
    return out


def _bounds(unit, ref_w, w, g, fatigue_values):
    nodes = np.asarray(unit.groups[g])
    ref = single_reference_path(unit, ref_w, nodes, fatigue_values=fatigue_values)
    return reference_bounds(ref, *(a[:, nodes] for a in reference_shift(ref_w, unit, w, abs_sum(unit))))


def _every_group(
    shaft: StudyShaft, loads: list[StateLoads], ref_loads: list[StateLoads], fatigue: bool = True
) -> StressScreen:
    """Each group searched on its own (no state's running value, nothing skipped), by the
    bounds of its placement's first candidate ``ref_loads`` (the search's node blocks as
    the screening's)."""
    best = {"shaft": (0.0, ""), "cw": (0.0, "")}
    static, fat = math.inf, None
    for sl, ref in zip(loads, ref_loads, strict=True):
        at = f"{sl.state.label} at {sl.state.speed * 30 / math.pi:.0f} rpm"
        for name, unit in shaft.stresses:
            for g in sorted(unit.groups):
                shaft_group = not of_counterweight(g)
                with_fatigue = shaft_group and fatigue
                r = group_extremes(
                    unit,
                    g,
                    sl.weights,
                    sl.state.dynamics.theta,
                    MAT,
                    crank_radius=0.05,
                    diameter=section_diameter(g, *DIAMETERS),
                    wanted=Wanted(fatigue=with_fatigue, gough_pollard=False),
                    additional_bending=ADD if sigma_add_applies(g) else 0.0,
                    reference=_bounds(unit, ref.weights, sl.weights, g, with_fatigue),
                    block=REFERENCE_BLOCK,
                )
                key = "shaft" if shaft_group else "cw"
                if r.max_von_mises.value > best[key][0]:
                    best[key] = (r.max_von_mises.value, f"throw {name} {g}, {at}")
                if shaft_group:
                    static = min(static, r.static_safety)
                    if fatigue and (fat is None or r.fatigue_safety.value < fat[0]):
                        fat = (r.fatigue_safety.value, f"throw {name} {g}, {at}")
    least, where = (None, "") if fat is None else fat
    return StressScreen(best["shaft"][0], best["shaft"][1], static, least, where, best["cw"][0], best["cw"][1])


def _same(got: StressScreen, expected: StressScreen) -> None:
    """Equal, the least Goodman safety to rounding: a candidate that is its placement's
    reference translated takes the reference's balls moved (``assess.group.reference.
    ReferenceBalls``), the search of every group its own path."""
    assert dataclasses.replace(got, fatigue_safety=None) == dataclasses.replace(expected, fatigue_safety=None)
    assert (got.fatigue_safety is None) == (expected.fatigue_safety is None)
    if got.fatigue_safety is not None:
        assert got.fatigue_safety == pytest.approx(expected.fatigue_safety, rel=1e-12)


def test_lazy_references_give_every_groups_values_and_places():
    shaft = _shaft(np.random.default_rng(5))
    candidates = [(1.0, 1.0, 1.0, 1.0), (1.3, 1.3, 1.3, 1.3), (1.6, 0.0, 1.6, 0.0)]  # two placements
    placements: dict[tuple, list[StateLoads]] = {}
    for cw in candidates:
        loads = _loads(cw)
        ref_loads = placements.setdefault(tuple(c != 0.0 for c in cw), loads)
        got = candidate_stresses(shaft, loads, MAT, additional_bending=ADD, diameters=DIAMETERS)
        _same(got, _every_group(shaft, loads, ref_loads))
        assert got.shaft_peak_where.startswith("throw 1 ") and got.fatigue_where.startswith("throw 1 ")  # the ties
        # overspeed: every group's peak, the largest and its place
        os = candidate_overspeed(shaft, loads, MAT)
        w, ref_w = (np.vstack([sl.weights for sl in x]) for x in (loads, ref_loads))
        peaks = [
            (float(group_peak(u, w, u.groups[g], bound=_bounds(u, ref_w, w, g, False).peak)[1].max()), name, g)
            for name, u in shaft.stresses
            for g in sorted(u.groups)
        ]
        top = max(p[0] for p in peaks)
        first = next(p for p in peaks if p[0] == top)
        cw_top = max(p[0] for p in peaks if of_counterweight(p[2]))
        cw_first = next(p for p in peaks if p[0] == cw_top and of_counterweight(p[2]))
        assert os is not None and (os.peak, os.peak_where) == (top, f"throw {first[1]} {first[2]}")
        assert (os.counterweight_peak, os.counterweight_where) == (cw_top, f"throw {cw_first[1]} {cw_first[2]}")
        assert os.safety == MAT.yield_strength / top
    # the second placement: its own references for some groups only (the others bounded by
    # the first placement's and unable to reach the state's extremes)
    n_groups = 2 * len(GROUPS)
    own = [len(r) - 1 for k, r in shaft.references.items() if k[0] != "overspeed"]
    assert len(own) == 4 and max(own) == n_groups and min(own) < n_groups


def test_lazy_static_screening_gives_every_groups_peaks():
    """The static peaks alone (``fatigue`` False): groups skipped by their peak bound alone."""
    shaft = _shaft(np.random.default_rng(8))
    placements: dict[tuple, list[StateLoads]] = {}
    for cw in [(1.0, 1.0, 1.0, 1.0), (1.4, 0.0, 1.4, 0.0), (2.0, 2.0, 2.0, 2.0)]:
        loads = _loads(cw)
        ref_loads = placements.setdefault(tuple(c != 0.0 for c in cw), loads)
        got = candidate_stresses(shaft, loads, MAT, additional_bending=ADD, diameters=DIAMETERS, fatigue=False)
        assert got == _every_group(shaft, loads, ref_loads, fatigue=False) and got.fatigue_safety is None
        assert got.shaft_peak_where.startswith("throw 1 ")
    own = [len(r) - 1 for r in shaft.references.values()]
    assert max(own) == 2 * len(GROUPS) and min(own) < 2 * len(GROUPS)


def test_a_seeded_reference_gives_the_same_values_and_places():
    """The references of a placement seeded with its middle candidate's history
    (``seed_references``) before any candidate is screened: every candidate's values and
    places equal those of every group's own search and of the screening without the seed
    (the least Goodman safety to rounding: each translates its own reference's balls), and
    the references built are the middle candidate's."""
    candidates = [(0.6, 0.6, 0.6, 0.6), (1.3, 1.3, 1.3, 1.3), (2.2, 2.2, 2.2, 2.2)]
    plain, seeded = _shaft(np.random.default_rng(13)), _shaft(np.random.default_rng(13))
    middle = _loads(candidates[1])
    seed_references(seeded, middle, middle)
    for cw in candidates:
        loads = _loads(cw)
        got = candidate_stresses(seeded, loads, MAT, additional_bending=ADD, diameters=DIAMETERS)
        _same(got, candidate_stresses(plain, loads, MAT, additional_bending=ADD, diameters=DIAMETERS))
        _same(got, _every_group(seeded, loads, middle))
        assert candidate_overspeed(seeded, loads, MAT) == candidate_overspeed(plain, loads, MAT)
    expected = {sl.state.label: sl.weights for sl in middle}
    for key, refs in seeded.references.items():
        if key[0] == "overspeed":
            assert np.array_equal(refs["weights"], np.vstack(list(expected.values())))
        else:
            assert refs["weights"] is expected[key[0]]


def test_the_counterweight_bodies_bound_holds_and_searches_alike():
    """``study.bodies``: the bound of a candidate's coefficients formed from the state's
    counterweight-free part (``body_base``, ``body_bound``) lies above every node's peak
    (brute force: the whole history), equals ``peak.peak_bound``'s to rounding, and
    ``group_peak`` searched by it finds the same peak; a counterweight's column that
    varies over the cycle gives no bound."""
    rng = np.random.default_rng(23)
    cases = ("pin_x", "pin_y", "torque", "centrifugal", "centrifugal_cw_1", "centrifugal_cw_2")
    n, n_t = 90, 72
    s = rng.normal(0.0, 30e6, (len(cases), 6, n))
    unit = UnitStresses(
        stress=s,
        points=np.zeros((3, n)),
        groups={"counterweight_1": np.arange(60), "junction_2": np.arange(60, n)},
        cases=cases,
        node_ids=np.arange(n),
    )
    t = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    C0 = np.column_stack(
        [np.cos(t), np.sin(2 * t), 0.3 + np.sin(t), np.full(n_t, 2.0), np.full(n_t, 2.0), np.full(n_t, 2.0)]
    )
    base = body_base(unit, C0)
    for k1, k2 in ((1.0, 1.0), (0.0, 2.5), (-0.7, 0.3)):
        C = C0.copy()
        C[:, 4] *= k1
        C[:, 5] *= k2
        for g, nodes in unit.groups.items():
            bound = body_bound(base, g, C)
            brute = von_mises(stress_history(unit, C, nodes)).max(axis=0)
            assert bound is not None and np.all(brute <= bound)
            assert np.allclose(bound, peak_bound(unit, C, nodes), rtol=1e-11, atol=0.0)
            assert group_peak(unit, C, nodes, bound=bound)[1].max() == group_peak(unit, C, nodes)[1].max()
    C = C0.copy()
    C[:, 4] = np.cos(t)
    assert body_bound(base, "junction_2", C) is None


def test_the_states_on_two_threads_give_the_serial_screening():
    """The states screened on two threads (``assess.workers.threads``: each its own
    references, bounds and searches) give the serial screening's values and places exactly."""
    serial, threaded = _shaft(np.random.default_rng(21)), _shaft(np.random.default_rng(21))
    for cw in [(1.0, 1.0, 1.0, 1.0), (1.5, 1.5, 1.5, 1.5), (1.2, 0.0, 1.2, 0.0)]:
        loads = _loads(cw)
        expected = candidate_stresses(serial, loads, MAT, additional_bending=ADD, diameters=DIAMETERS)
        with threads(2):
            got = candidate_stresses(threaded, loads, MAT, additional_bending=ADD, diameters=DIAMETERS)
        assert got == expected
