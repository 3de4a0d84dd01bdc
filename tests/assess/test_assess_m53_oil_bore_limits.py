"""UR M53 oil-bore outlet (fe_crank.rules.m53.oil_bore): the bored pin section, K at the
outlet, the range of d_O at both ends and without a bore, the record's texts -- by hand.
Geometry and loads as in tests/assess/test_assess_m53_oil_bore.py (D = 50 mm, D_O = 6 mm at
30 deg, arm L/2 = 60 mm, F_R = 20 kN cos, F_T = 5 kN sin, 500 N m sin)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers.oil_bore import GEO, PIN, TH, TQ  # the same throw and cycle as the hand calculations there

from fe_crank.rules.m53 import calculation as m53
from fe_crank.rules.m53 import oil_bore as ob


def test_nominal_bending_of_a_bored_pin_by_hand():
    """D_BH = 20 mm: W_e = pi/32 (D^4 - D_BH^4)/D = pi/32 (6.25e-6 - 1.6e-7)/0.05
    = pi/32 * 1.218e-4 = 1.1957687e-5 m^3 against pi/32 * 1.25e-4 unbored: the same moment
    M_BON (525 N m) gives sigma_BON larger by 6.25e-6 / 6.09e-6 = 1.0262726 exactly (the
    ratio removes the 1-degree sampling of the moment's peak, 7e-6 below 525 N m)."""
    bored = dataclasses.replace(GEO, pin_bore=0.020)
    assert ob.nominal_bending(bored, PIN) / ob.nominal_bending(GEO, PIN) == pytest.approx(6.25 / 6.09, rel=1e-12)
    assert ob.nominal_bending(bored, PIN) == pytest.approx(525.0 / 1.1957687e-5, rel=2e-5)


def test_k_below_one_applies_at_the_outlet_above_one_does_not():
    """UR M53 6: K > 1 only for the fillets, so the outlet takes min(K, 1): K = 1.05 and
    K = 1 give the same sigma_DW (357.61 MPa by hand in the companion test), K = 0.9 gives
    0.9 times it (sigma_DW is proportional to K)."""
    nom = m53.nominal_stresses(GEO, PIN[:, 1], TQ)
    r105 = ob.assess_outlet(GEO, nom, PIN, tensile=900e6, k=1.05)
    r100 = ob.assess_outlet(GEO, nom, PIN, tensile=900e6, k=1.0)
    r090 = ob.assess_outlet(GEO, nom, PIN, tensile=900e6, k=0.9)
    assert r105.fatigue_strength == r100.fatigue_strength == pytest.approx(357.61e6, rel=1e-4)
    assert r090.fatigue_strength == pytest.approx(0.9 * 357.61e6, rel=1e-4)
    assert r090.fatigue_strength / r100.fatigue_strength == pytest.approx(0.9, rel=1e-12)
    assert r105.scf_source == "empirical, UR M53 3.4 (oil-bore outlet)"
    assert (r105.scf_shear, r105.out_of_range) == (0.0, ())


def test_range_of_d_o_and_no_bore():
    """d_O = D_O/D: 0 (no bore) gives no outlet result; 0.2 (D_O = 10 mm) is inside; 0.22
    (11 mm) is outside with the reason in full."""
    nom = m53.nominal_stresses(GEO, PIN[:, 1], TQ)
    none = dataclasses.replace(GEO, oil_bore_diameter=0.0)
    assert ob.assess_outlet(none, nom, PIN, tensile=900e6, k=1.05) is None
    edge = dataclasses.replace(GEO, oil_bore_diameter=0.010)
    assert ob.assess_outlet(edge, nom, PIN, tensile=900e6, k=1.05) is not None
    big = dataclasses.replace(GEO, oil_bore_diameter=0.011)
    assert ob.in_range(big) == "d_O = D_O/D = 0.22 not in [0.0, 0.2] (UR M53 3.1)"
    assert (
        ob.in_range(dataclasses.replace(GEO, oil_bore_diameter=-0.001))
        == "d_O = D_O/D = -0.02 not in [0.0, 0.2] (UR M53 3.1)"
    )


def test_equivalent_stress_takes_the_bending_magnitude():
    """5.2 with sigma_BO = 3, sigma_TO = 4 (MPa): 3/3 + 2/3 sqrt(9 + 2.25 * 16) =
    1 + 2/3 sqrt(45) = 1 + 4.472136 = 5.472136 MPa; the sign of sigma_BO does not matter."""
    assert ob.equivalent_stress(3e6, 4e6) == pytest.approx(5.472136e6, rel=1e-7)
    assert ob.equivalent_stress(-3e6, 4e6) == ob.equivalent_stress(3e6, 4e6)


def test_readable_locations():
    assert [ob.where(f) for f in ("pin", "journal", "oil_bore")] == ["pin fillet", "journal fillet", "oil-bore outlet"]


def test_in_phase_tangential_and_radial_forces_add_at_the_outlet():
    """M_BO = M_BTO sin(a) + M_BRO cos(a) (2.1.2.2 with psi = 90 deg - a): with F_R =
    20 kN cos(theta) and F_T = 5 kN cos(theta) in phase, at a = 30 deg the amplitude is
    0.5 * 0.06 * (20000 * 0.8660254 + 5000 * 0.5) = 0.03 * 19820.508 = 594.6152 N m;
    W_e = pi/32 * 0.05^3 = 1.2271846e-5 m^3: sigma_BON = 48.45361 MPa.  The 1-degree grid
    holds theta = 0, the peak."""
    pin = np.column_stack([5e3 * np.cos(TH), 20e3 * np.cos(TH)])
    assert ob.nominal_bending(GEO, pin) == pytest.approx(594.6152 / 1.2271846e-5, rel=1e-6)


def test_outlet_record_fields_and_q_for_vanishing_stress():
    """The record carries gamma_B = 2.79264 and gamma_T = 3.712 (d_O = 0.12, by hand in the
    companion test) as its SCFs.  Without load sigma_V = 0 and Q is infinite; with a radial
    force of 0.1 mN amplitude sigma_V is below 1 Pa and Q = sigma_DW / sigma_V, finite."""
    nom = m53.nominal_stresses(GEO, PIN[:, 1], TQ)
    r = ob.assess_outlet(GEO, nom, PIN, tensile=900e6, k=1.05)
    assert (r.scf_bending, r.scf_torsion) == pytest.approx((2.79264, 3.712), rel=1e-12)
    zero = m53.NominalStresses(0.0, 0.0, 0.0, 0.0)
    r0 = ob.assess_outlet(GEO, zero, np.zeros((4, 2)), tensile=900e6, k=1.05)
    assert r0.equivalent == 0.0 and math.isinf(r0.acceptability)
    tiny = np.column_stack([np.zeros(720), 1e-4 * np.cos(TH)])
    rt = ob.assess_outlet(GEO, zero, tiny, tensile=900e6, k=1.05)
    assert 0.0 < rt.equivalent < 1.0
    assert rt.acceptability == pytest.approx(rt.fatigue_strength / rt.equivalent, rel=1e-12)


def test_range_limits_of_d_o_exactly():
    """d_O = 0 (no bore) and d_O = 0.2 + 1e-12 (the allowance; D = 1 m so that D_O/D is
    exact) are inside 3.1's range."""
    assert ob.in_range(dataclasses.replace(GEO, oil_bore_diameter=0.0)) is None
    edge = dataclasses.replace(GEO, pin_diameter=1.0, oil_bore_diameter=0.2 + 1e-12)
    assert ob.in_range(edge) is None
