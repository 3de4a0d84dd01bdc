"""UR M53 oil-bore outlet (fe_crank.rules.m53.oil_bore) against a hand calculation
with the rule's formulas (3.1, 3.4, 2.1.2.2, 2.2.3, 5.2, 6, 7), arithmetic shown.  The
coefficients are those of the rule text as reproduced clause by clause in the Korean
Register's Rules for the Classification of Steel Ships, Pt 5, Annex 5-3 (2025):
gamma_B = 3 - 5.88 d_O + 34.6 d_O^2, gamma_T = 4 - 6 d_O + 30 d_O^2, 0 <= d_O = D_O/D <= 0.2,
sigma_V = sigma_BO/3 [1 + 2 sqrt(1 + 9/4 (sigma_TO/sigma_BO)^2)].  No published worked
example of the outlet was found; a wrong coefficient moves gamma_B or gamma_T by more
than the 1e-12 tolerance of the hand values.

Geometry: D = 50 mm, no pin bore, D_O = 6 mm (d_O = 0.12), bore at a = 30 deg from the
radial direction; bearing centre to web centre 30 mm, W = 20 mm, L_pin = 40 mm, so the
bearing-to-pin-centre arm L/2 = 30 + 10 + 20 = 60 mm.  Loads over the cycle:
F_R = 20 kN cos(theta), F_T = 5 kN sin(theta), torque 500 N m sin(theta).
42CrMo4: R_m = 900 MPa, K = 1.05 (taken as 1 at the outlet)."""

from __future__ import annotations

import numpy as np
import pytest
from helpers.oil_bore import GEO, PIN, TH, TQ

from fe_crank.assess.superpose import UnitStresses
from fe_crank.assess.throw import ThrowContext, assess_throw
from fe_crank.io.material import load_material
from fe_crank.report.locations import criterion_location
from fe_crank.rules.m53 import calculation as m53
from fe_crank.rules.m53 import oil_bore as ob


def test_scfs_by_hand():
    # gamma_B = 3 - 5.88 * 0.12 + 34.6 * 0.0144 = 3 - 0.7056 + 0.49824 = 2.79264
    assert ob.gamma_b(0.12) == pytest.approx(2.79264, rel=1e-12)
    # gamma_T = 4 - 6 * 0.12 + 30 * 0.0144 = 4 - 0.72 + 0.432 = 3.712
    assert ob.gamma_t(0.12) == pytest.approx(3.712, rel=1e-12)


def test_nominal_bending_by_hand():
    """M_BO = (F/2)(L/2) along the outlet direction: (F_R cos 30 + F_T sin 30)/2 * 0.06;
    amplitude of 17320.5 cos + 2500 sin is sqrt(3e8 + 6.25e6) = 17500 N, so
    M_BON = 8750 * 0.06 = 525 N m;  W_e = pi/32 * 0.05^3 = 1.2271846e-5 m^3;
    sigma_BON = 525 / 1.2271846e-5 = 42.7808 MPa.  (Bore at 90 deg, the shipped
    geometry's: only F_T bends the outlet.)"""
    assert ob.nominal_bending(GEO, PIN) == pytest.approx(42.7808e6, rel=1e-5)


def test_equivalent_stress_limits():
    # pure bending: sigma_V = sigma_BO; pure torsion: sigma_V = tau_TO (5.2 as sigma_BO -> 0)
    assert ob.equivalent_stress(100e6, 0.0) == pytest.approx(100e6)
    assert ob.equivalent_stress(0.0, 80e6) == pytest.approx(80e6)


def test_outlet_q_by_hand():
    """sigma_BO = 2.79264 * 42.7808 = 119.472 MPa
    tau_N = 500 / (pi/16 * 0.05^3) = 500 / 2.4543693e-5 = 20.3718 MPa; tau_TO = 3.712 * 20.3718 = 75.620 MPa
    sigma_V = 119.472/3 + 2/3 sqrt(119.472^2 + 2.25 * 75.620^2) = 39.824 + 2/3 * 164.743 = 149.653 MPa
    sigma_DW (R_X = D_O/2 = 3 mm, K = 1): (0.42 * 900 + 39.3) = 417.3;
      0.264 + 1.073 * 50^-0.2 + (785 - 900)/4900 + (196/900) sqrt(1/3)
      = 0.264 + 1.073 * 0.457305 - 0.0234694 + 0.217778 * 0.577350 = 0.856953
      sigma_DW = 417.3 * 0.856953 = 357.61 MPa;  Q = 357.61 / 149.653 = 2.3896"""
    nom = m53.nominal_stresses(GEO, PIN[:, 1], TQ)
    assert nom.torsion_pin == pytest.approx(20.3718e6, rel=1e-5)
    r = ob.assess_outlet(GEO, nom, PIN, tensile=900e6, k=1.05)
    assert r.fillet == "oil_bore" and "3.4" in r.scf_source
    assert r.bending == pytest.approx(119.472e6, rel=1e-4)
    assert r.torsion == pytest.approx(75.620e6, rel=1e-4)
    assert r.equivalent == pytest.approx(149.653e6, rel=1e-4)
    assert r.fatigue_strength == pytest.approx(357.61e6, rel=1e-4)
    assert r.acceptability == pytest.approx(2.3896, rel=2e-4)


def test_validity_range_d_o():
    import dataclasses

    big = dataclasses.replace(GEO, oil_bore_diameter=0.011)  # d_O = 0.22 > 0.2
    assert "not in [0.0, 0.2]" in ob.in_range(big)
    nom = m53.nominal_stresses(big, PIN[:, 1], TQ)
    assert ob.assess_outlet(big, nom, PIN, tensile=900e6, k=1.05) is None
    assert ob.in_range(dataclasses.replace(GEO, oil_bore_diameter=0.010)) is None  # d_O = 0.2: inside


def test_outlet_in_the_throw_assessment_and_q_criterion():
    """assess_throw adds the outlet beside the fillets; the M53 Q criterion takes the
    smallest Q of the three and names the outlet when it governs."""
    from fe_crank.assess.criteria.judge import evaluate_criteria
    from fe_crank.io.criteria import build_criteria

    n = 8
    unit = UnitStresses(
        stress=np.zeros((3, 6, n)),
        points=np.zeros((3, n)),
        groups={"crankpin_fillet_1": np.arange(4), "journal_fillet_1": np.arange(4, n)},
        cases=("pin_x", "pin_y", "torque"),
    )
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            TH,
            PIN,
            TQ,
            omega=0.0,
            overspeed=None,
            material=load_material("42CrMo4"),
            crank_radius=0.064,
            m53_geometry=GEO,
        )
    )
    by = {f.fillet: f for f in t.m53}
    assert set(by) == {"pin", "journal", "oil_bore"}
    assert by["oil_bore"].acceptability == pytest.approx(2.3896, rel=2e-4)
    v = evaluate_criteria(build_criteria({"min_m53_acceptability": 1.15}, "t.toml"), (t,))[0]
    assert v.value == min(f.acceptability for f in t.m53)
    if v.value == by["oil_bore"].acceptability:
        assert "oil-bore outlet" in criterion_location(v)
