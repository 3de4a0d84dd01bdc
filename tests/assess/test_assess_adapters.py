"""What the assessment takes from the geometry and balance stages: UR M53 dimensions,
counterweight m r (checked against the annular-sector closed form) and bolt capacity.

The counterweights' mass properties (an OpenCASCADE build of the throw and its B-rep
integrals, ``geometry.mass``) are computed once per distinct solid: throws that differ
only in name and angle are one solid, because ``geometry.throw.add_throw`` builds a throw
in its own frame from the geometry and the throw's counterweights.  Checked on the
shipped inline-four geometry (throws 1 and 4 carry bolted counterweights at 0 deg, throws
2 and 3 the default ones at 180 deg): two builds for four throws, and every throw's
counterweight data equal (dataclass equality, exact) to its own build (``throw_solids``,
the geometry stage's)."""

from __future__ import annotations

import dataclasses
import math

import pytest

import fe_crank.balance.sector as sector
import fe_crank.geometry.spec as spec
import fe_crank.io.geometry as geo_io
from fe_crank.assess.adapters import counterweights_of, m53_geometry_of, stress_area
from fe_crank.geometry.mass import mass_properties, throw_solids
from fe_crank.rules.m53.calculation import out_of_range


@pytest.fixture(scope="module")
def seed001(root):
    return geo_io.load_geometry(root / "geometry" / "single_cylinder.toml")


@pytest.fixture(scope="module")
def root():
    from pathlib import Path

    return Path(__file__).resolve().parents[2]


def test_m53_dimensions_of_seed001_crank(seed001):
    m = m53_geometry_of(seed001)
    # stadium web 80 mm wide; the journal is half a main bearing, so its end face is the
    # bearing centre: a = journal length 25 + web 22 / 2 = 36 mm
    assert m.web_width == pytest.approx(0.080) and m.bearing_to_web == pytest.approx(0.036)
    rel = m.related("pin")
    # s = ((50 + 60)/2 - 64)/50 = -0.18, w = 22/50, b = 80/50, r = 4/50
    assert rel["s"] == pytest.approx(-0.18) and rel["w"] == pytest.approx(0.44)
    assert rel["b"] == pytest.approx(1.6) and rel["r"] == pytest.approx(0.08)
    assert out_of_range(rel) == []
    assert m53_geometry_of(None) is None


def test_pear_web_width_at_mid_overlap(seed001):
    pear = dataclasses.replace(seed001, web=spec.WebOutline("pear", 0.05, 0.03))
    m = m53_geometry_of(pear)
    y_mid = 0.5 * ((0.064 - 0.025) + 0.030)  # middle of the overlap, 34.5 mm
    assert m.web_width == pytest.approx(2 * (0.05 + (0.03 - 0.05) * y_mid / 0.064))


class _Plane:
    unbalance = 0.2


class _Design:
    plane = _Plane()

    def nearest(self, shaft, z):
        return self.plane


def _counterweights(g, design, throw=None, z=0.0, props=None):
    spec = g.throw(throw)
    return counterweights_of(spec, props or mass_properties(g, spec), z, "main", design)


def test_counterweight_mr_against_sector_closed_form_and_bolts(seed001):
    # the closed form is the sector's: the counterweights without their transition fillets
    seed001 = dataclasses.replace(
        seed001,
        throws=tuple(
            dataclasses.replace(
                t, counterweights=tuple(dataclasses.replace(c, fillet_radius=None) for c in t.counterweights)
            )
            for t in seed001.throws
        ),
    )
    cw = seed001.throw().counterweights[0]
    s = sector.annular_sector(cw.outer_radius, cw.inner_radius, cw.thickness, cw.angle, seed001.density)
    (data,) = _counterweights(seed001, _Design())
    # both webs' sectors serve the one balance plane: m r adds
    assert data.built_unbalance == pytest.approx(2 * s.unbalance, rel=1e-9)
    assert data.required_unbalance == 0.2 and not data.bolted
    bolt = spec.BoltedJoint(count=2, diameter=0.012, pitch_radius=0.05, yield_strength=640e6)
    cws = tuple(dataclasses.replace(c, bolted=bolt) for c in seed001.throw().counterweights)
    g2 = dataclasses.replace(seed001, throws=(dataclasses.replace(seed001.throw(), counterweights=cws),))
    (d2,) = _counterweights(g2, _Design())
    # two counterweights x 2 bolts M12 (A_s = 84.3 mm^2, ISO 898-1) x 640 MPa
    assert d2.bolted and d2.bolt_capacity == pytest.approx(4 * 84.3e-6 * 640e6)
    # without a balance design each web stands alone, with no requirement
    per_web = _counterweights(g2, None)
    assert [d.name for d in per_web] == ["counterweight_1", "counterweight_2"]
    assert all(d.required_unbalance is None and d.bolt_capacity == pytest.approx(2 * 84.3e-6 * 640e6) for d in per_web)


def test_stress_area_table_and_fallback():
    assert stress_area(0.016) == pytest.approx(157e-6)
    assert stress_area(0.0165) == pytest.approx(math.pi / 4 * (0.88 * 0.0165) ** 2)


@pytest.fixture(scope="module")
def inline4(root):
    return geo_io.load_geometry(root / "geometry" / "inline4.toml")


def test_equal_throw_solids_are_built_once_with_the_same_counterweight_data(inline4):
    names = [t.name for t in inline4.throws]
    assert names == ["1", "2", "3", "4"]
    solids = throw_solids(inline4)
    by = solids.by_throw
    assert by["1"] is by["4"] and by["2"] is by["3"] and by["1"] is not by["2"]  # {1, 4} and {2, 3}
    for i, n in enumerate(names):
        shared = _counterweights(inline4, None, n, 0.1 * i, solids.of(n))
        own = _counterweights(inline4, None, n, 0.1 * i)
        assert shared == own and own, n


def test_a_different_counterweight_is_another_solid(inline4):
    t1 = inline4.throw("1")
    cw = tuple(dataclasses.replace(c, outer_radius=c.outer_radius - 0.005) for c in t1.counterweights)
    g = dataclasses.replace(inline4, throws=inline4.throws + (dataclasses.replace(t1, name="5", counterweights=cw),))
    solids = throw_solids(g, ("1", "5"))
    assert solids.of("1") is not solids.of("5")
    a = _counterweights(g, None, "1", 0.0, solids.of("1"))
    b = _counterweights(g, None, "5", 0.0, solids.of("5"))
    assert b[0].built_unbalance < a[0].built_unbalance  # the smaller sector, its own build
