"""Endurance-limit factors (fe_crank.assess.factors) against Shigley's Mechanical
Engineering Design, 10th ed.: eq. 6-19 with table 6-2 (surface), eq. 6-20 (size),
table 6-5 (reliability); arithmetic shown per case.  Tolerance 1e-4 relative: the
table values are given to 3-4 digits; a wrong exponent or coefficient row is > 5 % off."""

from __future__ import annotations

import json

import jsonschema
import numpy as np
import pytest

from fe_crank.assess import ThrowContext, assess_throw, to_json
from fe_crank.assess.case import Assessment
from fe_crank.assess.factors import factors, reliability_factor, size_factor, surface_factor
from fe_crank.assess.results import load_schema
from fe_crank.assess.superpose import UnitStresses
from fe_crank.errors import InputError
from fe_crank.io.material import load_material
from fe_crank.rules.m53.calculation import M53Geometry


def test_surface_factor_table_6_2():
    # machined, R_m = 900 MPa: 4.51 * 900^-0.265 = 4.51 * exp(-0.265 * 6.80239) = 4.51 * 0.164868 = 0.74355
    assert surface_factor("machined", 900e6) == pytest.approx(0.74355, rel=1e-4)
    # ground, R_m = 580 MPa: 1.58 * exp(-0.085 * 6.36303) = 1.58 * 0.582237 = 0.91993
    assert surface_factor("ground", 580e6) == pytest.approx(0.91993, rel=1e-4)
    # as-forged, 580 MPa: 272 * exp(-0.995 * 6.36303) = 272 * 0.0017785 = 0.48376
    assert surface_factor("as_forged", 580e6) == pytest.approx(0.48376, rel=1e-3)
    # hot-rolled, 520 MPa: 57.7 * exp(-0.718 * 6.25383) = 57.7 * 0.0112179 = 0.64727
    assert surface_factor("hot_rolled", 520e6) == pytest.approx(0.64727, rel=1e-4)
    # capped at 1: ground, 300 MPa would give 1.58 * 300^-0.085 = 1.0 (0.9997..) -> never above 1
    assert surface_factor("ground", 100e6) == 1.0


def test_size_factor_eq_6_20():
    # 40 mm: 1.24 * exp(-0.107 * ln 40) = 1.24 * exp(-0.394710) = 1.24 * 0.673882 = 0.83561
    assert size_factor(0.040) == pytest.approx(0.83561, rel=1e-4)
    # 55 mm: 1.51 * exp(-0.157 * ln 55) = 1.51 * exp(-0.629151) = 1.51 * 0.533055 = 0.80491
    assert size_factor(0.055) == pytest.approx(0.80491, rel=1e-4)
    # 32 mm: 1.24 * exp(-0.107 * 3.46574) = 1.24 * 0.690163 = 0.85580
    # (the unrounded form (32/7.62)^-0.107 = 0.85767 differs by the rounding of 1.24)
    assert size_factor(0.032) == pytest.approx(0.85580, rel=1e-4)
    assert size_factor(0.002) == 1.0
    # unknown diameter and above 254 mm: the 254-mm value 1.51 * exp(-0.157 * 5.53733) = 1.51 * 0.419223 = 0.63303
    assert size_factor(None) == size_factor(0.4) == pytest.approx(0.63303, rel=1e-4)


def test_reliability_table_6_5():
    for r, ke in ((0.5, 1.000), (0.9, 0.897), (0.95, 0.868), (0.99, 0.814), (0.999, 0.753), (0.9999, 0.702)):
        assert reliability_factor(r) == pytest.approx(ke, abs=6e-4)


def test_material_defaults_are_on_the_safe_side_and_product():
    m = load_material("42CrMo4")
    assert (m.surface_finish, m.surface_factor, m.size_factor, m.reliability) == ("machined", None, None, 0.99)
    ff = factors(m, 0.055)
    # 0.74355 (machined, 900 MPa) * 0.80491 (55 mm) * 0.81389 (99 %) * 1 * 1 = 0.48712
    assert ff.product == pytest.approx(0.74355 * 0.80491 * 0.81389, rel=1e-4)
    g = factors(load_material("42CrMo4", surface_finish="ground", notch_support_factor=1.1, reliability=0.9), 0.055)
    # ground 900 MPa: 1.58 * exp(-0.085 * 6.80239) = 1.58 * 0.561100 = 0.88654; 0.897 (90 %)
    assert g.product == pytest.approx(0.88623 * 0.80491 * 0.89748 * 1.1, rel=1e-4)


@pytest.mark.parametrize(
    "key,value",
    [("reliability", 0.3), ("notch_support_factor", 0.9), ("surface_finish", "polished"), ("size_factor", 1.2)],
)
def test_bad_factor_is_an_input_error(key, value):
    with pytest.raises(InputError) as e:
        load_material("C45", **{key: value})
    assert f"material.{key}" in str(e.value)


def test_size_factor_per_section_in_the_assessment():
    """Round bar d = 50 mm, alternating bending sigma_a at a 'journal_fillet' group and the
    same at a 'crankpin_fillet' group; M53 dimensions give D = 40 mm (pin), D_G = 55 mm
    (journal): n = k sigma_W / sigma_a with k of each section's diameter."""
    d = 0.05
    n = 24
    phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
    x, y = d / 2 * np.cos(phi), d / 2 * np.sin(phi)
    s = np.zeros((3, 6, 2 * n))
    s[0, 2] = np.concatenate([y, y]) / (np.pi * d**4 / 64)
    pts = np.vstack([np.concatenate([x, x]), np.concatenate([y, y + 0.1]), np.zeros(2 * n)])
    unit = UnitStresses(
        stress=s,
        points=pts,
        groups={"journal_fillet_1": np.arange(n), "crankpin_fillet_1": np.arange(n, 2 * n)},
        cases=("pin_x", "pin_y", "torque"),
    )
    geo = M53Geometry(
        pin_diameter=0.040,
        journal_diameter=0.055,
        crank_radius=0.1,
        web_thickness=0.02,
        web_width=0.08,
        pin_fillet_radius=0.003,
        journal_fillet_radius=0.003,
        bearing_to_web=0.03,
    )
    mat = load_material("42CrMo4", surface_finish="ground", reliability=0.99)
    theta = np.deg2rad(np.arange(360.0))
    pin = np.column_stack([1000.0 * np.sin(theta), np.zeros_like(theta)])
    t = assess_throw(
        ThrowContext(
            "1",
            unit,
            theta,
            pin,
            np.zeros(360),
            omega=0.0,
            overspeed=None,
            material=mat,
            crank_radius=0.1,
            m53_geometry=geo,
            m53_additional=0.0,  # the FE model's own stresses (UR M53 sigma_add: test_assess_m53_basis.py)
        )
    )
    sa = 32 * 1000.0 / (np.pi * d**3)
    by = {g.group: g for g in t.groups}
    ka, ke = 0.88623, 0.81389  # ground 900 MPa (above); 99 %: 1 - 0.08 * 2.32635 = 0.81389
    j, p = by["journal_fillet_1"], by["crankpin_fillet_1"]
    assert j.fatigue_factors.diameter == 0.055 and p.fatigue_factors.diameter == 0.040
    assert j.fatigue_safety.value == pytest.approx(ka * 0.80491 * ke * 450e6 / sa, rel=1e-4)
    assert p.fatigue_safety.value == pytest.approx(ka * 0.83561 * ke * 450e6 / sa, rel=1e-4)
    doc = json.loads(json.dumps(to_json(Assessment("bar", "t.toml", 100.0, None, mat, (t,), ()))))
    jsonschema.validate(doc, load_schema())
    assert doc["material"]["reliability_factor"] == pytest.approx(ke, rel=1e-4)
    assert doc["material"]["size_factor"] is None
    assert doc["throws"][0]["groups"][1]["fatigue_factors"]["size"] == pytest.approx(0.80491, rel=1e-4)
