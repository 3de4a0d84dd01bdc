"""Safety factors on a hand-checkable case: a plain round bar (diameter d) under fully
reversed bending M_a sin(theta) and a steady torque T_m, equal to the closed forms

    sigma_a = 32 M_a / (pi d^3),  tau_m = 16 T_m / (pi d^3)
    static:        n = R_e / sqrt(sigma_a^2 + 3 tau_m^2)
    vM + Goodman:  1/n = sigma_a / (k sigma_W) + sqrt(3) tau_m / R_m     (Shigley 6-66, 6-67, 6-46)
    Gough-Pollard: n = k sigma_W / sigma_a   (no normal mean, no shear amplitude)

and the results document validates against its schema; ``max_and_first`` is numpy's
max and argmax (first index of ties and of NaN)."""

from __future__ import annotations

import json

import jsonschema
import numpy as np
import pytest

from fe_crank.assess import ThrowContext, assess_throw, evaluate_criteria, to_json
from fe_crank.assess.case import Assessment
from fe_crank.assess.fatigue import goodman_safety, gough_pollard_safety, max_and_first
from fe_crank.assess.results import load_schema
from fe_crank.assess.superpose import UnitStresses
from fe_crank.io.criteria import build_criteria
from fe_crank.io.material import load_material

D = 0.05
M_A, T_M = 2000.0, 3000.0  # N m


def _bar_units(n=36):
    """Surface nodes of the bar round its circumference; unit cases: 'pin_x' = 1 N m of
    bending about x (sigma_zz = M y / I), 'torque' = 1 N m (tau_theta_z = T r / J)."""
    a = D / 2
    phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
    x, y = a * np.cos(phi), a * np.sin(phi)
    I, J = np.pi * D**4 / 64, np.pi * D**4 / 32
    s = np.zeros((3, 6, n))
    s[0, 2] = y / I  # pin_x case used as the bending unit: sigma_zz
    tau = a / J
    s[2, 5] = -tau * np.sin(phi)  # xz
    s[2, 4] = tau * np.cos(phi)  # yz
    pts = np.vstack([x, y, np.zeros(n)])
    return UnitStresses(
        stress=s,
        points=pts,
        groups={"journal_fillet_1": np.arange(n)},
        node_ids=np.arange(n) + 100,
        cases=("pin_x", "pin_y", "torque"),
        torque_mz=1.0,
    )


def test_bar_bending_plus_mean_torsion_closed_form():
    # reliability 0.5: k_e = 1 - 0.08 * 0 = 1 (Shigley table 6-5), so k = k_a k_b
    mat = load_material("42CrMo4", surface_factor=0.9, size_factor=0.95, reliability=0.5)
    k = 0.9 * 0.95
    theta = np.deg2rad(np.arange(720.0))
    pin = np.column_stack([M_A * np.sin(theta), np.zeros_like(theta)])
    # torque coefficient is -sense * torque_front / torque_mz: sense -1 gives +T_m on the unit case
    t = assess_throw(
        ThrowContext(
            "1",
            _bar_units(),
            theta,
            pin,
            np.full(theta.size, T_M),
            omega=0.0,
            sense=-1,
            overspeed=None,
            material=mat,
            crank_radius=0.0,
            m53_additional=0.0,  # the FE model's own stresses (UR M53 sigma_add: test_assess_m53_basis.py)
        )
    )
    g = t.groups[0]
    sa = 32 * M_A / (np.pi * D**3)
    tm = 16 * T_M / (np.pi * D**3)
    assert g.static_safety == pytest.approx(650e6 / np.hypot(sa, np.sqrt(3) * tm), rel=1e-12)
    assert g.fatigue_safety.value == pytest.approx(1 / (sa / (k * 450e6) + np.sqrt(3) * tm / 900e6), rel=1e-12)
    assert g.gough_pollard_safety.value == pytest.approx(k * 450e6 / sa, rel=1e-12)
    assert g.amplitude_at_critical == pytest.approx(sa, rel=1e-12)
    assert g.mean_at_critical == pytest.approx(np.sqrt(3) * tm, rel=1e-12)
    # per-node fields: amplitude sigma_a |sin phi| round the circumference, mean sqrt3 tau_m everywhere
    pts = _bar_units().points
    phi = np.arctan2(pts[1], pts[0])
    np.testing.assert_allclose(g.fields["amplitude"], sa * np.abs(np.sin(phi)), rtol=1e-9, atol=1e-6 * sa)
    np.testing.assert_allclose(g.fields["mean"], np.sqrt(3) * tm, rtol=1e-9)
    # worst node at the top or bottom fibre (phi = 90 or 270 deg), max at theta = 90 deg (or 450)
    assert abs(g.fatigue_safety.point[1]) == pytest.approx(D / 2)
    assert np.rad2deg(g.max_von_mises.angle) % 360 in (90.0, 270.0)

    crit = build_criteria(
        {"min_static_safety": 1.5, "min_fatigue_safety": 2.0, "min_gough_pollard_safety": 1.5}, "t.toml"
    )
    verdicts = evaluate_criteria(crit, (t,), file="t.toml")
    by = {v.quantity: v for v in verdicts}
    # by hand: sigma_a = 32 * 2000 / (pi 0.05^3) = 162.97 MPa, tau_m = 122.23 MPa
    # static n = 650 / sqrt(162.97^2 + 3 * 122.23^2) = 650 / 267.17 = 2.433 >= 1.5: passes
    # Goodman 1/n = 162.97 / (0.855 * 450) + sqrt3 * 122.23 / 900 = 0.42358 + 0.23523
    #   -> n = 1.5179 < 2: fails, margin n/2 - 1 = -0.2410
    # Gough-Pollard n = 0.855 * 450 / 162.97 = 2.3609 >= 1.5: passes, margin 0.5739
    n_goodman = 1 / (sa / (k * 450e6) + np.sqrt(3) * tm / 900e6)
    assert n_goodman == pytest.approx(1.5179, abs=1e-4)
    assert by["fatigue_safety"].margin == pytest.approx(n_goodman / 2.0 - 1, rel=1e-12)
    assert not by["fatigue_safety"].passed
    assert by["static_safety"].value == pytest.approx(2.433, abs=1e-3) and by["static_safety"].passed
    assert by["static_safety"].margin == pytest.approx(650e6 / np.hypot(sa, np.sqrt(3) * tm) / 1.5 - 1, rel=1e-12)
    assert by["gough_pollard_safety"].margin == pytest.approx(k * 450e6 / sa / 1.5 - 1, rel=1e-12)
    assert by["gough_pollard_safety"].passed
    a = Assessment("bar", "t.toml", 100.0, None, mat, (t,), verdicts)
    doc = json.loads(json.dumps(to_json(a)))
    jsonschema.validate(doc, load_schema())
    assert doc["passed"] is False  # the fatigue criterion fails
    assert [c["passed"] for c in doc["criteria"]] == [True, False, True]


def test_pure_torsion_gough_pollard_and_goodman():
    """Fully reversed torsion tau_a: GP n = k tau_W / tau_a; vM-Goodman n = k sigma_W / (sqrt3 tau_a)."""
    mat = load_material("C45", surface_factor=1.0, size_factor=1.0, reliability=0.5)  # k = 1
    theta = np.deg2rad(np.arange(360.0))
    tq = 500.0 * np.cos(theta)
    t = assess_throw(
        ThrowContext(
            "1",
            _bar_units(),
            theta,
            np.zeros((360, 2)),
            tq,
            omega=0.0,
            overspeed=None,
            material=mat,
            crank_radius=0.0,
            m53_additional=0.0,  # the FE model's own stresses
        )
    )
    ta = 16 * 500.0 / (np.pi * D**3)
    g = t.groups[0]
    assert g.gough_pollard_safety.value == pytest.approx(167e6 / ta, rel=1e-9)
    assert g.fatigue_safety.value == pytest.approx(290e6 / (np.sqrt(3) * ta), rel=1e-9)


def test_goodman_and_gough_pollard_scalars():
    assert goodman_safety(100e6, -50e6, 200e6, 800e6) == pytest.approx(2.0)  # compressive mean: no credit
    assert goodman_safety(100e6, 400e6, 200e6, 800e6) == pytest.approx(1.0)
    assert goodman_safety(0.0, 0.0, 200e6, 800e6) == np.inf
    # ellipse quadrant: sigma_a/sigma_e = 0.3, tau_a/tau_e = 0.4 -> n = 1/0.5
    assert gough_pollard_safety(60e6, 0.0, 40e6, 0.0, 200e6, 100e6, 800e6) == pytest.approx(2.0)
    # Goodman-corrected limits: sigma_m = R_m/2 halves sigma_e
    assert gough_pollard_safety(50e6, 400e6, 0.0, 0.0, 200e6, 100e6, 800e6) == pytest.approx(2.0)
    assert gough_pollard_safety(50e6, 900e6, 0.0, 0.0, 200e6, 100e6, 800e6) == 0.0


def test_max_and_first_is_max_and_argmax():
    rng = np.random.default_rng(3)
    d = np.round(rng.random((40, 30)) * 4)  # many exact ties
    d[5, 7] = np.nan
    r, first = max_and_first(d)
    assert np.array_equal(r, d.max(axis=0), equal_nan=True)
    np.testing.assert_array_equal(first, d.argmax(axis=0))
    assert first[7] == 5  # a NaN column: its first NaN, as argmax
