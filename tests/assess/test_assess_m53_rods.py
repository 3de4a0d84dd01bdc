"""Two connecting rods on one crankpin (UR M53 2.1: each rod's bending-moment triangle at its
own axial place and phase, superposed): the dynamics stage's force per rod, the rods'
places on the pin, UR M53's web moments rod by rod on the shipped V4 by hand, the oil bore's
moment at the pin's middle, and the FE pin loaded per rod place (patches)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from fe_crank import model
from fe_crank.assess.adapters import m53_geometry_of
from fe_crank.errors import InputError
from fe_crank.fe.throw.pin_patches import patch_bands, patch_forces, pin_patch_options, rod_positions
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.rules.m53 import calculation as m53
from fe_crank.rules.m53 import oil_bore as m53_oil_bore
from fe_crank.rules.m53 import rods as m53_rods

V4 = "loadcases/v4_90_pneumatic_operating.toml"


@pytest.fixture(scope="module")
def v4():
    lc = load_loadcase(V4)
    return lc, dynamics.analyse(lc.engine, lc.operating)


def test_dynamics_gives_each_rods_force_and_their_sum(v4):
    lc, dyn = v4
    for name, tl in dyn.throws.items():
        assert [r.cylinder for r in tl.rods] == [c.name for c in lc.engine.cylinders if c.throw == name]
        np.testing.assert_allclose(sum(r.pin_force for r in tl.rods), tl.pin_force, rtol=0, atol=1e-9)
        for r in tl.rods:
            cf = dyn.cylinders[r.cylinder]
            np.testing.assert_array_equal(r.pin_force[:, 1], cf.radial)
            np.testing.assert_array_equal(r.pin_force[:, 0], cf.tangential)  # sense +1


def test_rod_places_on_the_pin(v4):
    lc, _ = v4
    # side by side on the 44 mm pin, in the engine's order, the first at the front: -+L/4
    assert rod_positions(lc.engine, "A", 0.044) == pytest.approx({"4": -0.011, "1": 0.011})
    np.testing.assert_allclose(patch_bands([-0.011, 0.011], 0.044), [(-0.022, 0.0), (0.0, 0.022)], atol=1e-15)
    # stated places win; a forked pair (both at the middle) is one place: no patches
    cyls = tuple(dataclasses.replace(c, pin_position=0.0) for c in lc.engine.cylinders)
    forked = dataclasses.replace(lc.engine, cylinders=cyls)
    assert set(rod_positions(forked, "A", 0.044).values()) == {0.0}
    assert pin_patch_options(None, forked, lc.geometry.crankpin_length).pin_patches == ()
    split = pin_patch_options(None, lc.engine, lc.geometry.crankpin_length)
    np.testing.assert_allclose(split.pin_patches, [(-0.022, 0.0), (0.0, 0.022)], atol=1e-15)
    assert len(split.cases) == 2 + 24 and "pin_030@2" in split.cases
    # an articulated rod bears through its master's big end
    master = model.Cylinder("m", "A", 0.08, model.Rod(0.2, 1.0, 0.05), 1.0, pin_position=0.01)
    link = model.Cylinder(
        "l", "A", 0.08, model.Rod(0.2, 1.0, 0.05), 1.0, articulation=model.Articulation("m", 0.05, 1.0)
    )
    radial = dataclasses.replace(lc.engine, cylinders=(master, link))
    assert rod_positions(radial, "A", 0.044) == {"m": 0.01, "l": 0.01}
    off = dataclasses.replace(lc.engine, cylinders=(dataclasses.replace(master, pin_position=0.03),))
    with pytest.raises(InputError, match="off the 44 mm crankpin"):
        rod_positions(off, "A", 0.044)
    # the rods' forces go to the band of their place
    f = np.ones((3, 2))
    pf = patch_forces([(f, -0.011), (2 * f, 0.011), (3 * f, 0.012)], ((-0.022, 0.0), (0.0, 0.022)))
    np.testing.assert_array_equal(pf[1], f) and np.testing.assert_array_equal(pf[2], 5 * f)


def test_v4_web_moment_rod_by_rod_by_hand(v4):
    """Shipped V4 (geometry/v4_90_pneumatic on its engine): web W = 19 mm, pin L = 44 mm,
    throws 128 mm apart, so the bearing centres sit (128 - 44 - 2 x 19)/2 = 23 mm from the
    webs; a = 23 + 9.5 = 32.5 mm, span S = 2 (23 + 19) + 44 = 128 mm; rods at -+11 mm.
    Front web: R_1 = F_4 (1/2 + 11/128) + F_1 (1/2 - 11/128) = 0.5859375 F_4 + 0.4140625 F_1,
    M_1 = a R_1; rear web the mirror.  The half range of the more loaded web's moment is
    4 % above the summed force's at mid-pin, (F_4 + F_1)/2 x a (measured 1.0395)."""
    lc, dyn = v4
    geo = m53_geometry_of(lc.geometry)
    assert geo.bearing_to_web == pytest.approx(0.0325) and m53_rods.span(geo) == pytest.approx(0.128)
    tl = dyn.throws["A"]
    f4, f1 = (r.pin_force[:, 1] for r in tl.rods)
    a, s = 0.0325, 0.128
    m_front = a * (f4 * (0.5 + 0.011 / s) + f1 * (0.5 - 0.011 / s))
    m_rear = a * (f4 * (0.5 - 0.011 / s) + f1 * (0.5 + 0.011 / s))
    m_sum = a * 0.5 * (f4 + f1)
    hr = m53.half_range
    worst = max(hr(m_front), hr(m_rear))
    assert worst / hr(m_sum) == pytest.approx(1.0395, abs=5e-4)
    rods = tuple((r.pin_force, e) for r, e in zip(tl.rods, (-0.011, 0.011)))
    nom, web = m53_rods.nominal_stresses_by_rod(geo, rods, tl.torque_front, ke=1.0)
    w_eq = geo.web_width * geo.web_thickness**2 / 6
    assert nom.bending == pytest.approx(worst / w_eq, rel=1e-12)
    assert nom.shear == pytest.approx(worst / a / (geo.web_width * geo.web_thickness), rel=1e-12)
    old = m53.nominal_stresses(geo, tl.pin_force[:, 1], tl.torque_front)
    assert nom.bending / old.bending == pytest.approx(worst / hr(m_sum), rel=1e-12)
    assert nom.torsion_pin == old.torsion_pin


def test_moment_at_the_pin_middle_by_hand():
    """One rod of 1 kN (radial) at e = -10 mm on a 100 mm span: R_1 = 1000 (1/2 + 0.1) =
    600 N, M(middle) = 600 x 0.05 - 1000 x 0.010 = 20 N m (= R_2 x 0.05 = 400 x 0.05).
    Two equal rods (200, 1000) N at -+10 mm: R_1 = 1000 (0.6 + 0.4) = 1000 N radial, M = 1000 x 0.05 - 1000 x 0.01
    = 40 N m, 4/5 of the summed force's 2000/2 x 0.05 = 50 N m at mid-pin; tangential
    200 x 0.05 - 200 x 0.01 = 8 N m (against 10).
    Rods at the middle give the summed force's moment."""
    geo = m53.M53Geometry(0.05, 0.06, 0.04, 0.02, 0.08, 0.003, 0.003, bearing_to_web=0.02, pin_length=0.04)
    assert m53_rods.span(geo) == pytest.approx(0.1)
    one = ((np.array([[0.0, 1000.0]]), -0.010),)
    assert m53_rods.moment_at_pin_middle(geo, one)[0] == pytest.approx([0.0, 20.0])
    two = ((np.array([[200.0, 1000.0]]), -0.010), (np.array([[200.0, 1000.0]]), 0.010))
    assert m53_rods.moment_at_pin_middle(geo, two)[0] == pytest.approx([8.0, 40.0])
    bored = dataclasses.replace(geo, oil_bore_diameter=0.006, oil_bore_angle=0.0)
    f = np.array([[200.0, 1000.0], [-100.0, -500.0]])
    by_rod = m53_oil_bore.nominal_bending(bored, None, ((0.5 * f, 0.0), (0.5 * f, 0.0)))
    assert by_rod == pytest.approx(m53_oil_bore.nominal_bending(bored, f), rel=1e-12)


def test_pin_position_input():
    from fe_crank.io.engine import build_engine

    cyl = {
        "name": "1",
        "throw": "1",
        "bore": "90 mm",
        "rod_length": "200 mm",
        "rod_mass": "1 kg",
        "rod_cg_from_big_end": "50 mm",
        "piston_mass": "1 kg",
    }
    data = {"name": "e", "strokes": 4, "throws": [{"name": "1", "stroke": "100 mm"}], "cylinders": [cyl]}
    e = build_engine({**data, "cylinders": [{**cyl, "pin_position": "-11 mm"}]}, "e.toml")
    assert e.cylinders[0].pin_position == pytest.approx(-0.011)
    for bad in ("11", "11 kg", float("nan")):
        with pytest.raises(InputError) as err:
            build_engine({**data, "cylinders": [{**cyl, "pin_position": bad}]}, "e.toml")
        assert err.value.key == "cylinders[0].pin_position"
