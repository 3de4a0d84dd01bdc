"""``assess.group.assessment`` on hand-built unit stresses: the tie rule of ``first_extreme``, the
section of each group, and ``assess_group``'s static, overspeed and fatigue results
against hand values (uniaxial and pure-shear unit states: von Mises |sigma| or
sqrt(3) |tau|).  Tie-band values sit 5e-10 (inside) and 2e-9 (outside) relative from the
extreme of the 1e-9 band; other values are exact to a few roundings (1e-12 relative).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from fe_crank.assess.factors import factors
from fe_crank.assess.group.assessment import assess_group, first_extreme, section_diameter
from fe_crank.assess.superpose import UnitStresses
from fe_crank.io.material import load_material

MAT = load_material("42CrMo4")  # R_e = 650 MPa (library)
THETA = np.deg2rad([0.0, 90.0, 180.0, 270.0])


def test_first_extreme_tie_band_for_max_and_min_along_either_axis():
    """max: 2 at index 2, 2 (1 - 5e-10) at index 1 inside the band -> 1; min: -3 at 3,
    -3 (1 - 5e-10) = -2.9999999985 at 0 inside -> 0; outside the band (2e-9) -> the exact
    extreme's index."""
    v = np.array([1.0, 2 * (1 - 5e-10), 2.0, 0.5])
    assert first_extreme(v) == 1 and first_extreme(v, "max") == 1
    assert first_extreme(np.array([1.0, 2 * (1 - 2e-9), 2.0])) == 2
    w = np.array([-3 * (1 - 5e-10), 1.0, 0.0, -3.0])
    assert first_extreme(w, "min") == 0
    assert first_extreme(np.array([-3 * (1 - 2e-9), -3.0]), "min") == 1
    # positive minimum: 1 (1 + 5e-10) inside the band of 1 -> index 0
    assert first_extreme(np.array([1 + 5e-10, 1.0]), "min") == 0
    # along axis 1: rows (1, 2, 2) and (5, 4, 5 (1 - 5e-10))
    m = np.array([[1.0, 2.0, 2.0], [5.0, 4.0, 5 * (1 - 5e-10)]])
    np.testing.assert_array_equal(first_extreme(m, "max", axis=1), [1, 0])
    np.testing.assert_array_equal(first_extreme(m.T, "min", axis=0), [0, 1])
    # integer input
    assert first_extreme(np.array([1, 3, 3])) == 1


def test_section_of_each_group():
    assert section_diameter("crankpin_fillet_1", 0.1, 0.12) == 0.1
    assert section_diameter("oil_bore", 0.1, 0.12) == 0.1
    assert section_diameter("journal_fillet_2", 0.1, 0.12) == 0.12
    assert section_diameter("counterweight_1", 0.1, 0.12) is None
    assert section_diameter("junction_1", 0.1, 0.12) is None


def _unit(sxx, txy=None, groups=None, node_ids=True, points=None):
    """One unit case per column of ``sxx`` (sigma_xx per node) and, if given, ``txy``."""
    sxx = np.atleast_2d(np.asarray(sxx, float))
    n_cases, n = sxx.shape
    s = np.zeros((n_cases, 6, n))
    s[:, 0] = sxx
    if txy is not None:
        s[:, 3] = np.atleast_2d(txy)
    pts = np.zeros((3, n)) if points is None else points
    return UnitStresses(
        stress=s,
        points=pts,
        groups=groups or {},
        cases=tuple(f"c{i}" for i in range(n_cases)),
        node_ids=np.arange(10, 10 + n) if node_ids else None,
    )


def test_static_and_overspeed_extremes_by_hand():
    """Three nodes, sigma_xx = 1, 3, 2 Pa per unit load, a(t) = (10, -40, 20, 0) MPa:
    node 1 peaks at 3 x 40 = 120 MPa at 90 deg -> static safety 650 / 120 = 5.4167.
    Overspeed coefficients (x 1.5): 180 MPa at 90 deg, safety 650 / 180."""
    pts = np.array([[0.001, 0.002, 0.003], [0.0, 0.1, 0.0], [0.0, 0.0, 0.2]])
    unit = _unit([[1.0, 3.0, 2.0]], groups={"counterweight_1": np.array([0, 1, 2])}, points=pts)
    co = np.array([[10e6], [-40e6], [20e6], [0.0]])
    g = assess_group(
        unit, "counterweight_1", co, THETA, MAT, crank_radius=0.05, overspeed=1.0, overspeed_coefficients=1.5 * co
    )
    assert g.group == "counterweight_1" and g.n_nodes == 3
    e = g.max_von_mises
    assert e.value == pytest.approx(120e6, rel=1e-12) and e.node == 11 and e.point == (0.002, 0.1, 0.0)
    assert e.angle == pytest.approx(math.pi / 2, rel=1e-15) and e.group == "counterweight_1"
    assert g.static_safety == pytest.approx(650 / 120, rel=1e-12)
    o = g.max_von_mises_overspeed
    assert o.value == pytest.approx(180e6, rel=1e-12) and o.node == 11 and o.angle == pytest.approx(math.pi / 2)
    assert g.overspeed_safety == pytest.approx(650 / 180, rel=1e-12)
    np.testing.assert_allclose(g.fields["max_von_mises"], [40e6, 120e6, 80e6], rtol=1e-12)
    np.testing.assert_array_equal(g.fields["node_ids"], [10, 11, 12])
    # counterweights are static-only: no fatigue
    assert g.fatigue_safety is None and g.gough_pollard_safety is None and g.fatigue_factors is None
    assert g.amplitude_at_critical is None and np.all(np.isinf(g.fields["fatigue_safety"]))
    # without node ids the node is the index into the assessed nodes
    u2 = dataclasses.replace(unit, node_ids=None)
    g2 = assess_group(u2, "counterweight_1", co, THETA, MAT, crank_radius=0.05, overspeed=None)
    assert g2.max_von_mises.node == 1 and g2.max_von_mises_overspeed is None and g2.overspeed_safety is None
    # chunk of one node: the same
    g3 = assess_group(
        unit,
        "counterweight_1",
        co,
        THETA,
        MAT,
        crank_radius=0.05,
        overspeed=1.0,
        overspeed_coefficients=1.5 * co,
        chunk=1,
    )
    assert g3.max_von_mises == e and g3.max_von_mises_overspeed == o


def test_zero_stress_and_no_yield_strength_give_an_infinite_static_safety():
    unit = _unit([[0.0, 0.0]], groups={"junction_1": np.array([0, 1])})
    co = np.zeros((4, 1))
    g = assess_group(unit, "junction_1", co, THETA, MAT, crank_radius=0.05, overspeed=1.0, overspeed_coefficients=co)
    assert g.static_safety == math.inf and g.overspeed_safety == math.inf and g.max_von_mises.value == 0.0
    unit = _unit([[1.0, 2.0]], groups={"junction_1": np.array([0, 1])})
    co = np.array([[1e6], [0.0], [0.0], [0.0]])
    g = assess_group(
        unit,
        "junction_1",
        co,
        THETA,
        dataclasses.replace(MAT, yield_strength=None),
        crank_radius=0.05,
        overspeed=1.0,
        overspeed_coefficients=co,
    )
    assert g.static_safety == math.inf and g.overspeed_safety == math.inf and g.max_von_mises.value == 2e6


def test_refusals_in_full():
    unit = _unit([[1.0]], groups={"counterweight_1": np.array([0]), "junction_1": np.array([], int)})
    co = np.ones((4, 1))
    with pytest.raises(ValueError) as e:
        assess_group(unit, "junction_1", co, THETA, MAT, crank_radius=0.05, overspeed=None)
    assert str(e.value) == "node group 'junction_1' is empty"
    with pytest.raises(ValueError) as e:
        assess_group(unit, "counterweight_1", co, THETA, MAT, crank_radius=0.05, overspeed=2.0)
    assert str(e.value) == "overspeed given without the overspeed cycle's coefficients"


def test_fatigue_of_a_fully_reversed_bending_node_by_hand():
    """A crankpin-fillet node on the pin axis's x side (x = 0.01, y = R = 0.05: radial
    direction x), sigma_xx = 1 Pa per unit, a(t) = (+100, 0, -100, 0) MPa: amplitude
    100 MPa, mean 0.  Goodman with zero mean: n = k sigma_f / sigma_a, k the product of
    the Marin factors for the pin diameter (``factors``, checked in test_assess_factors*.py).
    No shear: Gough-Pollard gives the same as the bending-only Goodman.  A journal fillet uses
    the crank axis, a material without a torsion fatigue limit gives no Gough-Pollard."""
    pts = np.array([[0.01], [0.05], [0.0]])
    unit = _unit([[1.0]], groups={"crankpin_fillet_1": np.array([0]), "journal_fillet_1": np.array([0])}, points=pts)
    co = np.array([[100e6], [0.0], [-100e6], [0.0]])
    g = assess_group(unit, "crankpin_fillet_1", co, THETA, MAT, crank_radius=0.05, overspeed=None, diameter=0.1)
    ff = factors(MAT, 0.1)
    assert g.fatigue_factors == ff
    assert g.amplitude_at_critical == pytest.approx(100e6, rel=1e-12) and abs(g.mean_at_critical) < 1e-3
    expected = ff.product * MAT.fatigue_limit_bending / 100e6
    assert g.fatigue_safety.value == pytest.approx(expected, rel=1e-12) and g.fatigue_safety.node == 10
    assert g.fatigue_safety.angle is None
    assert g.gough_pollard_safety.value == pytest.approx(expected, rel=1e-9)
    # the diameter reaches the size factor: 0.1 m and the fallback differ
    g_none = assess_group(unit, "crankpin_fillet_1", co, THETA, MAT, crank_radius=0.05, overspeed=None)
    assert g_none.fatigue_factors == factors(MAT, None)
    # journal fillet: radius about the crank axis
    gj = assess_group(unit, "journal_fillet_1", co, THETA, MAT, crank_radius=0.05, overspeed=None, diameter=0.1)
    assert gj.gough_pollard_safety is not None and gj.fatigue_safety.value == pytest.approx(expected, rel=1e-12)
    no_tors = dataclasses.replace(MAT, fatigue_limit_torsion=None)
    g4 = assess_group(unit, "crankpin_fillet_1", co, THETA, no_tors, crank_radius=0.05, overspeed=None, diameter=0.1)
    assert g4.gough_pollard_safety is None and g4.fatigue_safety.value == pytest.approx(expected, rel=1e-12)
    for field in ("fatigue_limit_bending", "tensile_strength"):
        g5 = assess_group(
            unit,
            "crankpin_fillet_1",
            co,
            THETA,
            dataclasses.replace(MAT, **{field: None}),
            crank_radius=0.05,
            overspeed=None,
            diameter=0.1,
        )
        assert g5.fatigue_safety is None and g5.gough_pollard_safety is None and g5.fatigue_factors is None


def test_first_extreme_with_a_zero_extreme_and_rows():
    """A band of width 0 (extreme exactly 0): the first index of the extreme itself --
    max of (-1, 0, 0) at 1, min of (1, 0, 0) at 1; min along axis 1 of (2, 3) rows."""
    assert first_extreme(np.array([-1.0, 0.0, 0.0])) == 1
    assert first_extreme(np.array([1.0, 0.0, 0.0]), "min") == 1
    m = np.array([[1.0, 2.0, 1.0], [5.0, 4.0, 4 * (1 + 5e-10)]])
    np.testing.assert_array_equal(first_extreme(m, "min", axis=1), [0, 1])


def _torsion_group(points, component, group, scale=(0.0, 1.0, 0.5)):
    """Three nodes of ``group``, one unit case of pure shear ``component`` (5 = xz, 4 = yz)
    scaled 0, 1, 0.5 per node."""
    s = np.zeros((1, 6, 3))
    s[0, component] = scale
    return UnitStresses(
        stress=s, points=points, groups={group: np.array([0, 1, 2])}, cases=("c0",), node_ids=np.array([10, 11, 12])
    )


def test_fully_reversed_torsion_at_the_fillets_by_hand():
    """tau_a = 100 MPa of torsion, zero mean, at the fillet (node 1; node 2 half of it, node
    0 unloaded): von Mises amplitude sqrt(3) 100 MPa -> Goodman n = k sigma_f / 173.205 MPa;
    Gough-Pollard with no bending: n = k tau_f / 100 MPa (tau_f the torsion limit).  The
    torsion is tau_tz about the fillet's own axis: at the crankpin node (0, 60, 0) mm about
    the pin axis (0, R = 50 mm) it is -tau_xz; at the journal node (60, 0, 0) mm about the
    crank axis it is tau_yz.  About a wrong axis (1 m off) the same stress is tau_rz and
    the torsion amplitude near zero.  The unloaded node has infinite safeties and is not
    the critical one; blocks of 2 nodes (2 + 1)."""
    co = np.array([[100e6], [0.0], [-100e6], [0.0]])
    for group, pts, comp, dia in (
        ("crankpin_fillet_1", [[0.0] * 3, [0.06] * 3, [0.0] * 3], 5, 0.1),
        ("journal_fillet_2", [[0.06] * 3, [0.0] * 3, [0.0] * 3], 4, 0.12),
    ):
        unit = _torsion_group(np.array(pts), comp, group)
        g = assess_group(unit, group, co, THETA, MAT, crank_radius=0.05, overspeed=None, diameter=dia, chunk=2)
        k = factors(MAT, dia).product
        good = k * MAT.fatigue_limit_bending / (math.sqrt(3.0) * 100e6)
        gp = k * MAT.fatigue_limit_torsion / 100e6
        assert g.fatigue_safety.value == pytest.approx(good, rel=1e-9) and g.fatigue_safety.node == 11
        assert g.fatigue_safety.group == group
        assert g.amplitude_at_critical == pytest.approx(math.sqrt(3.0) * 100e6, rel=1e-9)
        assert abs(g.mean_at_critical) < 1e-3
        gpe = g.gough_pollard_safety
        assert gpe.value == pytest.approx(gp, rel=1e-9) and gpe.node == 11 and gpe.group == group
        np.testing.assert_allclose(
            g.fields["amplitude"], [0.0, math.sqrt(3.0) * 100e6, math.sqrt(3.0) * 50e6], rtol=1e-9, atol=1e-3
        )
        assert np.all(np.abs(g.fields["mean"]) < 1e-3)
        assert g.fields["fatigue_safety"][0] == math.inf
        np.testing.assert_allclose(g.fields["gough_pollard_safety"][1:], [gp, 2 * gp], rtol=1e-9)
        assert g.fields["gough_pollard_safety"][0] == math.inf


def test_static_extreme_ties_nan_and_stresses_below_one_pascal():
    """Static extreme: 120 (1 - 5e-10) MPa at node 0 ties with 120 MPa at node 1 -> node 0
    (the first of the band); a NaN stress at node 1 is the extreme (it must not pass
    unseen); a peak of 0.5 Pa gives the safety 650e6 / 0.5 = 1.3e9, not infinity."""
    co = np.array([[1.0], [0.0], [-1.0], [0.0]])
    unit = _unit([[120e6 * (1 - 5e-10), 120e6, 1.0]], groups={"junction_1": np.array([0, 1, 2])})
    g = assess_group(unit, "junction_1", co, THETA, MAT, crank_radius=0.05, overspeed=1.0, overspeed_coefficients=co)
    assert g.max_von_mises.node == 10 and g.max_von_mises_overspeed.node == 10
    unit = _unit([[1.0, np.nan, 2.0]], groups={"junction_1": np.array([0, 1, 2])})
    g = assess_group(unit, "junction_1", co, THETA, MAT, crank_radius=0.05, overspeed=None)
    assert g.max_von_mises.node == 11 and np.isnan(g.max_von_mises.value)
    unit = _unit([[0.5]], groups={"junction_1": np.array([0])})
    g = assess_group(unit, "junction_1", co, THETA, MAT, crank_radius=0.05, overspeed=1.0, overspeed_coefficients=co)
    assert g.static_safety == pytest.approx(1.3e9, rel=1e-12)
    assert g.overspeed_safety == pytest.approx(1.3e9, rel=1e-12)


def test_the_least_safe_of_loaded_nodes_is_the_fatigue_extreme():
    """Every node loaded (torsion 1, 0.5, 0.25 x 100 MPa, all safeties finite): the
    fatigue and Gough-Pollard extremes are the minimum, node 10, not the maximum.  At a
    journal node (0, 60, 0) mm the torsion about the crank axis is -tau_xz."""
    co = np.array([[100e6], [0.0], [-100e6], [0.0]])
    for group, pts, comp, dia in (
        ("crankpin_fillet_1", [[0.0] * 3, [0.06] * 3, [0.0] * 3], 5, 0.1),
        ("journal_fillet_1", [[0.0] * 3, [0.06] * 3, [0.0] * 3], 5, 0.12),
    ):
        unit = _torsion_group(np.array(pts), comp, group, scale=(1.0, 0.5, 0.25))
        g = assess_group(unit, group, co, THETA, MAT, crank_radius=0.05, overspeed=None, diameter=dia)
        k = factors(MAT, dia).product
        assert g.fatigue_safety.node == 10 and g.gough_pollard_safety.node == 10
        assert g.fatigue_safety.value == pytest.approx(
            k * MAT.fatigue_limit_bending / (math.sqrt(3.0) * 100e6), rel=1e-9
        )
        assert g.gough_pollard_safety.value == pytest.approx(k * MAT.fatigue_limit_torsion / 100e6, rel=1e-9)
