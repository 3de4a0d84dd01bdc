"""Endurance-limit factors at the edges of Shigley's ranges (10th ed., eq. 6-20 and table
6-5), which value wins in ``factors``, and the report rows, by hand."""

from __future__ import annotations

import dataclasses

import pytest

from fe_crank.assess.factors import factors, material_rows, reliability_factor, size_factor, surface_factor
from fe_crank.assess.fatigue import fatigue_limits
from fe_crank.io.material import Surface, load_material


def test_size_factor_at_the_range_ends():
    """Eq. 6-20 holds for 2.79 <= d <= 51 mm (first form) and 51 < d <= 254 mm (second).
    At d = 51 mm the two forms differ by 0.04 %, so 1e-6 tells them apart; at 2.79 mm the
    formula (1.111) and the small-diameter value 1 differ by 11 %."""
    # 2.79 mm: 1.24 * exp(-0.107 * 1.026042) = 1.24 * 0.896026 = 1.11107
    assert size_factor(0.00279) == pytest.approx(1.11107, rel=1e-5)
    assert size_factor(0.00278) == 1.0
    # 51 mm, first form: 1.24 * exp(-0.107 * 3.931826) = 1.24 * 0.656584 = 0.814164
    # (the second form would give 1.51 * exp(-0.157 * 3.931826) = 1.51 * 0.539404 = 0.814500)
    assert size_factor(0.051) == pytest.approx(0.814164, rel=1e-6)
    # just above 51 mm: the second form
    assert size_factor(0.0511) == pytest.approx(1.51 * 51.1**-0.157, rel=1e-12)
    # 254 mm and above: the 254-mm value 0.633021, also for no diameter
    assert size_factor(0.254) == size_factor(0.255) == size_factor(1.0) == size_factor(None)
    assert size_factor(0.254) == pytest.approx(0.633021, rel=1e-6)


def test_surface_factor_full_precision():
    """k_a = a (R_m / 1 MPa)^b with the table's a, b as exact numbers (rel 1e-12: R_m
    converted with any other factor than 1e6 Pa/MPa is caught, even 1 ppm off)."""
    assert surface_factor("machined", 900e6) == pytest.approx(4.51 * 900.0**-0.265, rel=1e-12)
    assert surface_factor("as_forged", 580e6) == pytest.approx(272.0 * 580.0**-0.995, rel=1e-12)


def test_reliability_range():
    """k_e = 1 - 0.08 z_a: 50 % is the mean (z = 0, k_e = 1 exactly); 100 % has no
    quantile, below 50 % would raise the mean limit: both refused."""
    assert reliability_factor(0.5) == 1.0
    for bad in (0.4999, 1.0, 1.2):
        with pytest.raises(ValueError, match=r"reliability must be in \[0.5, 1\)"):
            reliability_factor(bad)


def test_given_factors_win_and_no_tensile_strength_gives_no_surface_factor():
    m = load_material(
        "C45", surface_factor=0.8, size_factor=0.9, reliability=0.9, treatment_factor=1.2, notch_support_factor=1.1
    )
    f = factors(m, 0.04)
    # given size factor: no diameter is recorded for it; product 0.8 * 0.9 * 0.89748 * 1.2 * 1.1
    assert (f.surface, f.size, f.treatment, f.notch_support, f.diameter) == (0.8, 0.9, 1.2, 1.1, None)
    assert f.reliability == pytest.approx(1 - 0.08 * 1.281552, rel=1e-6)
    assert f.product == pytest.approx(0.8 * 0.9 * 0.897476 * 1.2 * 1.1, rel=1e-6)
    # computed size factor: the section's diameter is recorded
    assert factors(load_material("C45"), 0.04).diameter == 0.04
    # no tensile strength: the surface factor (a function of R_m) cannot be computed: 1
    bare = dataclasses.replace(load_material("C45"), tensile_strength=None, surface_factor=None)
    assert factors(bare, 0.04).surface == 1.0


def test_report_rows():
    # 42CrMo4 defaults: machined at 900 MPa 0.74355, per-section size, 99 %: 0.81389
    # surfaces per location: the fillets machined by default, the oil bore drilled (table 6-2's
    # machined constants), the counterweight fillet as forged: 272 x 900^-0.995 = 0.3131
    assert material_rows(load_material("42CrMo4")) == [
        ["surface factor k_a, crankpin fillet", "0.744 (machined, Shigley eq. 6-19)"],
        ["surface factor k_a, journal fillet", "0.744 (machined, Shigley eq. 6-19)"],
        ["surface factor k_a, oil bore", "0.744 (drilled, Shigley eq. 6-19)"],
        ["surface factor k_a, counterweight fillet", "0.313 (as_forged, Shigley eq. 6-19)"],
        ["size factor k_b", "per section from its diameter (Shigley eq. 6-20; see the fatigue table)"],
        ["reliability factor k_e", "0.814 (0.99, Shigley table 6-5)"],
        ["treatment factor", "1.000"],
        ["notch support factor", "1.000 (FE route; 1 = no credit)"],
    ]
    rows = material_rows(
        load_material("C45", surface_factor=0.8, size_factor=0.9, reliability=0.9, treatment_factor=1.2)
    )
    assert rows[:2] == [
        ["surface factor k_a, crankpin fillet", "0.800 (given 0.8: material.surface_factor, every shaft fillet)"],
        ["surface factor k_a, journal fillet", "0.800 (given 0.8: material.surface_factor, every shaft fillet)"],
    ]
    assert rows[4:7] == [
        ["size factor k_b", "0.900 (given)"],
        ["reliability factor k_e", "0.897 (0.9, Shigley table 6-5)"],
        ["treatment factor", "1.200"],
    ]
    assert material_rows(None) == [] and material_rows(object()) == []


def test_fatigue_limits_present_or_none():
    """The fatigue criteria run on a material that gives sigma_W and R_m (tau_W optional:
    Gough-Pollard); without either no fatigue criterion is evaluated."""
    mat = load_material("42CrMo4")
    limits = fatigue_limits(mat)
    assert limits is not None
    assert (limits.bending, limits.tensile, limits.torsion) == (
        mat.fatigue_limit_bending,
        mat.tensile_strength,
        mat.fatigue_limit_torsion,
    )
    assert fatigue_limits(dataclasses.replace(mat, fatigue_limit_torsion=None)).torsion is None
    assert fatigue_limits(dataclasses.replace(mat, fatigue_limit_bending=None)) is None
    assert fatigue_limits(dataclasses.replace(mat, tensile_strength=None)) is None


def test_a_surface_without_finish_or_factor_is_refused():
    """A surface entry gives a finish or a factor (``io.material``); one built without either
    is an error naming the material and the location, not a lookup of no finish."""
    mat = dataclasses.replace(load_material("42CrMo4"), surfaces=(Surface("oil_bore"),))
    with pytest.raises(
        ValueError, match="material 42CrMo4: the surface at oil_bore gives neither a finish nor a factor"
    ):
        factors(mat, None, "oil_bore")
