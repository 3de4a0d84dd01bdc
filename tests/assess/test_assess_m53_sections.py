"""IACS UR M53 Rev.1: bored sections (2.2.2), the journal fillet's own diameter and radius
in the fatigue strength (6), the full-precision fatigue strength, the fillet record's
fields and messages, and Q for a vanishing equivalent stress -- by hand."""

from __future__ import annotations

import dataclasses
import math

import pytest

from fe_crank.rules.m53 import calculation as m53

# D = 100, D_G = 120, crank radius 90 mm, W = 30, B = 150, R_H = 5, R_G = 6 mm (s = 0.2,
# w = 0.3, b = 1.5, r = 0.05 / 0.06: inside 3.1), bores D_BH = 30, D_BG = 40 mm
GEO = m53.M53Geometry(
    pin_diameter=0.1,
    journal_diameter=0.12,
    crank_radius=0.09,
    web_thickness=0.03,
    web_width=0.15,
    pin_fillet_radius=0.005,
    journal_fillet_radius=0.006,
    bearing_to_web=0.06,
)
BORED = dataclasses.replace(GEO, pin_bore=0.03, journal_bore=0.04, pin_recess=0.005, journal_recess=0.002)


def test_bored_sections_by_hand():
    """W_P = pi/16 (D^4 - D_BH^4)/D = pi/16 (1e-4 - 8.1e-7)/0.1 = pi/16 * 9.919e-4
    = 1.9475911e-4 m^3 (pin); pi/16 (2.0736e-4 - 2.56e-6)/0.12 = pi/16 * 1.7066667e-3
    = 3.3510322e-4 m^3 (journal).  A torque amplitude of 2 kN m: tau_N = 10.269096 MPa
    (pin), 5.968310 MPa (journal).  W_eqw = B W^2/6 = 0.15 * 9e-4 / 6 = 2.25e-5 m^3,
    F = B W = 4.5e-3 m^2."""
    assert m53.polar_section_modulus(BORED, "pin") == pytest.approx(1.9475911e-4, rel=1e-7)
    assert m53.polar_section_modulus(BORED, "journal") == pytest.approx(3.3510322e-4, rel=1e-7)
    assert m53.polar_section_modulus(GEO, "pin") == pytest.approx(math.pi / 16 * 1e-3, rel=1e-12)
    assert m53.web_section_modulus(BORED) == pytest.approx(2.25e-5, rel=1e-12)
    assert m53.web_area(BORED) == pytest.approx(4.5e-3, rel=1e-12)
    nom = m53.nominal_stresses(BORED, [-10e3, 40e3], [-2e3, 2e3])
    assert nom.torsion_pin == pytest.approx(10.269096e6, rel=1e-7)
    assert nom.torsion_journal == pytest.approx(5.968310e6, rel=1e-7)


def test_related_dimensions_of_bores_and_recesses():
    """d_G = 40/100 = 0.4, d_H = 30/100 = 0.3, t_H = 5/100 = 0.05, t_G = 2/100 = 0.02
    (all divided by the crankpin diameter D, 3.1)."""
    rel = BORED.related("journal")
    assert (rel["dG"], rel["dH"], rel["tH"], rel["tG"]) == pytest.approx((0.4, 0.3, 0.05, 0.02), rel=1e-12)


def test_fatigue_strength_to_full_precision():
    """UR M53 6, R_m = 800 MPa, K = 1.05, (0.42 * 800 + 39.3) = 375.3:
    pin D = 100 mm, R_X = 5 mm: 0.264 + 1.073 * 100^-0.2 (0.4271689940) - 15/4900 (0.0030612245)
      + 0.245 sqrt(1/5) (0.1095673309) = 0.7976751004 -> 1.05 * 375.3 * 0.7976751004 = 314.33583844 MPa;
    journal D_G = 120 mm, R_X = 6 mm: 1.073 * 120^-0.2 = 0.4118731420, 0.245 sqrt(1/6) = 0.1000208312
      -> 0.7728327486 -> 304.54633709 MPa.
    To 1e-9: a 1 ppm slip in a unit conversion or a constant (4901 for 4900) moves these
    by 0.3 ppm or more."""
    assert m53.fatigue_strength(800e6, 0.1, 0.005, 1.05) == pytest.approx(314.33583844e6, rel=1e-9)
    assert m53.fatigue_strength(800e6, 0.12, 0.006, 1.05) == pytest.approx(304.54633709e6, rel=1e-9)


def test_journal_fillet_record_by_hand():
    """Journal fillet (3.3; fatigue strength with D_G and R_G): nominal stresses given,
    sigma_BN = 50 MPa, sigma_QN = 5 MPa, tau_N(journal) = 15 MPa.  beta_T (3.3): alpha_T's
    formula with r = R_G/D_G = 6/120 = 0.05: 0.8 * 0.05^-0.2408 (2.0572545) * f(b) (1.0792)
    * 0.3^-0.145 (1.1907413) = 2.1149367; tau = 2.1149367 * 15 = 31.724050 MPa;
    sigma_DW = 304.54633709 MPa (above); Q = sigma_DW / sigma_V."""
    nom = m53.NominalStresses(bending=50e6, shear=5e6, torsion_pin=20e6, torsion_journal=15e6)
    j = m53.assess_fillet(GEO, nom, "journal", tensile=800e6, k=1.05, additional=10e6)
    assert j.fillet == "journal"
    assert j.scf_torsion == pytest.approx(2.1149367, rel=1e-7)
    assert j.torsion == pytest.approx(31.724050e6, rel=1e-7)
    assert j.fatigue_strength == pytest.approx(304.54633709e6, rel=1e-9)
    assert j.acceptability == pytest.approx(304.54633709e6 / j.equivalent, rel=1e-9)
    assert j.equivalent == pytest.approx(math.sqrt((j.bending + 10e6) ** 2 + 3 * j.torsion**2), rel=1e-12)


def test_beta_q_web_width_factor():
    """beta_Q's f_Q(b) = b - 0.5 (3.3): from b = 1.5 to b = 2.0 it goes from 1.0 to 1.5,
    so beta_Q grows by exactly 1.5 (the other factors do not depend on b)."""
    rel = GEO.related("journal")
    assert m53.beta_q({**rel, "b": 2.0}) / m53.beta_q(rel) == pytest.approx(1.5, rel=1e-12)


def test_out_of_range_record_and_messages_in_full():
    """w = 15/100 = 0.15 < 0.2 and b = 230/100 = 2.3 > 2.2: with FE SCFs the source lists
    both, separated by "; ", and the record keeps them; without, the ValueError names them."""
    bad = dataclasses.replace(GEO, web_thickness=0.015, web_width=0.23)
    nom = m53.NominalStresses(bending=50e6, shear=5e6, torsion_pin=20e6, torsion_journal=15e6)
    both = "w = 0.15 not in [0.2, 0.8]; b = 2.3 not in [1.1, 2.2]"
    r = m53.assess_fillet(bad, nom, "pin", tensile=800e6, k=1.05, fe_scf={"bending": 3.0, "torsion": 2.0})
    assert r.scf_source == f"FE (geometry outside the UR M53 validity range: {both})"
    assert r.out_of_range == ("w = 0.15 not in [0.2, 0.8]", "b = 2.3 not in [1.1, 2.2]")
    assert (r.scf_bending, r.scf_shear, r.scf_torsion) == (3.0, 0.0, 2.0)
    with pytest.raises(ValueError) as err:
        m53.assess_fillet(bad, nom, "pin", tensile=800e6, k=1.05)
    assert str(err.value) == (
        f"pin fillet outside the UR M53 validity range ({both}) and no FE stress concentration factors given"
    )


def test_q_for_a_vanishing_equivalent_stress():
    """No load and no additional stress: sigma_V = 0 and Q is infinite (no division by
    zero); sigma_add = 0.5 Pa alone: sigma_V = 0.5 Pa, Q = 314.33583844e6 / 0.5."""
    zero = m53.NominalStresses(0.0, 0.0, 0.0, 0.0)
    r = m53.assess_fillet(GEO, zero, "pin", tensile=800e6, k=1.05, additional=0.0)
    assert r.equivalent == 0.0 and math.isinf(r.acceptability)
    r = m53.assess_fillet(GEO, zero, "pin", tensile=800e6, k=1.05, additional=0.5)
    assert r.equivalent == 0.5
    assert r.acceptability == pytest.approx(314.33583844e6 / 0.5, rel=1e-9)


def test_the_tolerance_at_the_range_limits_is_inside():
    """The 1e-12 allowance of 3.1's limits is itself inside the range (ratios of lengths
    given in mm carry round-off of that order)."""
    base = GEO.related("pin")
    assert m53.out_of_range({**base, "w": 0.8 + 1e-12}) == []
    assert m53.out_of_range({**base, "w": 0.2 - 1e-12}) == []
