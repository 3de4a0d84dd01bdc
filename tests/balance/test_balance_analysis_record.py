"""The balance stage's one call (``fe_crank.balance.analysis``) on a one-cylinder engine
whose every figure follows by hand: free forces by source, the counterweights and
their sectors, two balance-shaft requests in sequence, the residual, the forces table,
the exact reciprocating peak and the JSON record (``balance.json``) key by key.

Engine: one shaft; throw "0" (no mass, no cylinder) at z = -0.1 m and 180 deg, throw "1"
at z = +0.1 m, R = 0.05 m, own rotating mass 2.0 kg; one cylinder along +y on throw "1",
rod l = 0.2 m (lambda = 1/4), 1.0 kg with its centre 0.05 m from the big end (a quarter
reciprocating), piston 1.5 kg: m_rot = 2.0 + 0.75 = 2.75 kg, m_j = 1.5 + 0.25 = 1.75 kg.
omega = 400 rad/s, moments about z_r = 0.05 m (lever of throw "1": 0.05 m).

* rotating, order 1: 2.75 * 0.05 * 400^2 = 22000 N, a circle; couple 0.05 * 22000 = 1100 N m;
* reciprocating, order 1: 1.75 * 0.05 * 400^2 = 14000 N along y (A_1 = 1 exactly for a
  central slider crank: the rest of x(phi) has period pi), couple 700 N m;
  order 2: F_2 = 14000 A_2, A_2 = lambda + lambda^3/4 + 15 lambda^5/128 = 0.25402069
  (the lambda^7 term is below 2e-5 of it): 3556.29 N;
* counterweights, per throw, all the rotating and half the first-order reciprocating mass:
  U = (2.75 + 0.5 * 1.75) 0.05 = 0.18125 kg m opposite the pin (180 deg) at z = 0.1 m;
  throw "0" gets U = 0 (angle 0) and no sector; residual order 1: 22000 + 7000 (a
  circle with the crank) against 7000 + 7000 (the line): 7000 N turning against the
  crank, couple 350 N m;
* sector of throw "1" (180 deg, r = 100 / 50 mm, 7500 kg/m^3, thickness free):
  U = (2/3) rho b (r1^3 - r2^3) = 5000 * 0.000875 b = 4.375 b -> b = 41.428571 mm;
* force shafts, order 2, offset 80 mm: U (2 omega)^2 = F_2 / 2, U = F_2 / 1.28e6 kg m,
  at (+-0.08, 0) m in the reference plane, speed ratios +2 and -2;
* then couple shafts, order 2, span 150 mm: the order-2 couple left is M_x = -0.05 F_2
  cos 2 theta (P = Q = -0.025 F_2 i), U = 0.025 F_2 / (0.15 * 800^2) = F_2 / 3.84e6 kg m
  at z_r +- 75 mm, U e^{i psi} = -i P / (L (2 omega)^2) < 0 (180 deg), placed across the
  major axis (-90 deg): (0, +-0.1) m.
"""

import json
import math

import numpy as np
import pytest

from fe_crank import model
from fe_crank.balance.analysis import analyse_balance, exact_peak, forces_table, result_to_dict
from fe_crank.balance.counterweights import BalanceStrategy
from fe_crank.errors import InputError
from fe_crank.io.balance import BalanceSettings, CounterweightSpec, ShaftRequest

W = 400.0
A2 = 0.25 + 0.25**3 / 4 + 15 * 0.25**5 / 128
F2 = 14000.0 * A2
SERIES = 1e-4  # relative tolerance on figures through A_2 (series truncation < 2e-5)


def _engine(sense=1, bank=0.0, throw_angle=0.0):
    throws = (model.Throw("0", "main", math.pi, 0.05, -0.1, 0.0), model.Throw("1", "main", throw_angle, 0.05, 0.1, 2.0))
    cyl = model.Cylinder("1", "1", 0.09, model.Rod(0.2, 1.0, 0.05), 1.5, bank_angle=bank)
    return model.Engine("hand-one", 4, (model.Shaft("main", sense=sense),), throws, (cyl,))


def _settings(journal_radius=0.04, free="thickness", r_inner=0.05, shafts=None):
    spec = CounterweightSpec(
        7500.0,
        free,
        0.1,
        None if free == "r_inner" else r_inner,
        0.0414285714 if free == "r_inner" else None,
        math.pi,
        None,
        journal_radius,
    )
    if shafts is None:
        shafts = (ShaftRequest("force", 2, 0.08, 0.2), ShaftRequest("couple", 2, 0.1, 0.15))
    return BalanceSettings(BalanceStrategy(1.0, 0.5, "per_throw"), 0.05, spec, shafts)


@pytest.fixture(scope="module")
def res():
    return analyse_balance(_engine(), W, _settings())


def test_result_fields_by_hand(res):
    assert (res.engine, res.speed, res.forces.reference_z) == ("hand-one", W, 0.05)
    assert res.design.before is res.forces  # counterweights sized on the same record
    cw0, cw1 = res.design.counterweights
    assert (cw0.z, cw0.unbalance, cw1.z) == (-0.1, 0.0, 0.1)
    assert cw1.unbalance == pytest.approx(0.18125, rel=1e-14)
    assert res.sectors[0] is None and len(res.sectors) == 2
    assert res.sectors[1].thickness == pytest.approx(0.18125 / 4.375, rel=1e-12)
    assert res.sectors[1].unbalance == pytest.approx(0.18125, rel=1e-12)
    force, couple = res.shafts
    assert [s.unbalance for s in force.shafts] == pytest.approx([F2 / 1.28e6] * 2, rel=SERIES)
    np.testing.assert_allclose([s.position for s in force.shafts], [(0.08, 0.0), (-0.08, 0.0)], atol=1e-15)
    assert [s.unbalance for s in couple.shafts] == pytest.approx([F2 / 3.84e6] * 2, rel=SERIES)
    np.testing.assert_allclose([s.z for s in couple.shafts], [(0.125, -0.025)] * 2, atol=1e-15)
    assert res.residual is couple.residual
    r1, r2 = res.residual.total(1), res.residual.total(2)
    h = r1.force_hodograph()
    assert (h.kind, h.major, h.counter_magnitude) == (
        "circle",
        pytest.approx(7000.0, rel=1e-9),
        pytest.approx(7000.0, rel=1e-9),
    )
    assert r1.moment_hodograph().major == pytest.approx(350.0, rel=1e-9)
    assert r2.force_hodograph().kind == "zero" and r2.moment_hodograph().kind == "zero"


def test_forces_table_rows_by_hand(res):
    rows = forces_table(res.forces)
    assert [(r["source"], r["order"]) for r in rows] == [
        ("rotating", 1.0),
        ("reciprocating", 1.0),
        ("reciprocating", 2.0),
        ("reciprocating", 4.0),
        ("reciprocating", 6.0),
        ("total", 1.0),
        ("total", 2.0),
        ("total", 4.0),
        ("total", 6.0),
    ]
    assert set(rows[0]) == {
        "source",
        "order",
        "force_max",
        "force_min",
        "force_kind",
        "force_tilt_deg",
        "moment_max",
        "moment_min",
        "moment_kind",
    }
    expect = {  # force max, min, kind; couple max, min, kind
        ("rotating", 1.0): (22000.0, 22000.0, "circle", 1100.0, 1100.0, "circle"),
        ("reciprocating", 1.0): (14000.0, 0.0, "line", 700.0, 0.0, "line"),
        ("total", 1.0): (36000.0, 22000.0, "ellipse", 1800.0, 1100.0, "ellipse"),
    }
    for r in rows:
        if (r["source"], r["order"]) in expect:
            fmax, fmin, fk, mmax, mmin, mk = expect[(r["source"], r["order"])]
            assert (r["force_max"], r["force_min"], r["moment_max"], r["moment_min"]) == pytest.approx(
                (fmax, fmin, mmax, mmin), rel=1e-9, abs=1e-6
            )
            assert (r["force_kind"], r["moment_kind"]) == (fk, mk)
    rec2 = rows[2]
    assert (rec2["force_max"], rec2["moment_max"]) == pytest.approx((F2, 0.05 * F2), rel=SERIES)
    assert rec2["force_tilt_deg"] == pytest.approx(90.0, abs=1e-9)  # along +y: 90 deg from +x
    # the first order of the rotating source is always listed
    assert [(r["source"], r["order"]) for r in forces_table(res.forces, orders=(2.0,))] == [
        ("rotating", 1.0),
        ("reciprocating", 2.0),
        ("total", 2.0),
    ]
    assert [(r["source"], r["order"]) for r in forces_table(res.forces, orders=(4.0,))] == [
        ("rotating", 1.0),
        ("reciprocating", 4.0),
        ("total", 4.0),
    ]


def test_forces_table_of_the_residual_keeps_every_total_row(res):
    """Counterweights 0.18125 * 400^2 = 29000 N (couple 1450 N m); the balance shafts' own
    order 2 is F_2 along y (their couples cancel the engine's 0.05 F_2); the total rows of
    every reported order stay, the cancelled order 2 among them with zeros."""
    rows = forces_table(res.residual)
    keys = [(r["source"], r["order"]) for r in rows]
    assert keys == [
        ("rotating", 1.0),
        ("reciprocating", 1.0),
        ("reciprocating", 2.0),
        ("reciprocating", 4.0),
        ("reciprocating", 6.0),
        ("counterweights", 1.0),
        ("balance_shafts", 2.0),
        ("total", 1.0),
        ("total", 2.0),
        ("total", 4.0),
        ("total", 6.0),
    ]
    cw = rows[5]
    assert (cw["force_max"], cw["moment_max"]) == pytest.approx((29000.0, 1450.0), rel=1e-12)
    assert rows[6]["force_max"] == pytest.approx(F2, rel=SERIES)
    assert rows[6]["moment_max"] == pytest.approx(0.05 * F2, rel=SERIES)
    assert (rows[8]["force_max"], rows[8]["moment_max"], rows[8]["force_kind"]) == (0.0, 0.0, "zero")


def test_exact_peak_at_a_tdc_on_the_half_degree_grid():
    """Cylinder at bank 30 deg on a throw at -30.5 deg: TDC at theta = 30 + 30.5 = 60.5 deg,
    a point of the 721-point grid (every 0.5 deg).  The largest inertia force of a central
    slider crank is at TDC, m_j R omega^2 (1 + lambda) = 1.75 * 0.05 * 400^2 * 1.25 =
    17500 N along the cylinder axis (both x and y parts non-zero), its couple about
    z_r = 0.05 m, 0.05 * 17500 = 875 N m.  The sum of 24 orders is exact to 1e-12; a grid
    that misses 60.5 deg by 0.08 deg or more reads at least 1.5e-6 low, checked to 1e-7.
    The rotating source (not asked for) would add 22000 N."""
    from fe_crank.balance import free_forces

    ff = free_forces(_engine(bank=math.radians(30), throw_angle=math.radians(-30.5)), W, reference_z=0.05)
    peak = exact_peak(ff)
    assert set(peak) == {"force_max", "moment_max"}
    assert peak["force_max"] == pytest.approx(17500.0, rel=1e-7)
    assert peak["moment_max"] == pytest.approx(875.0, rel=1e-7)


def test_json_record_key_by_key(res):
    data = result_to_dict(res)
    json.dumps(data)  # plain JSON types only
    assert set(data) == {
        "engine",
        "speed_rad_s",
        "reference_z_m",
        "free_forces",
        "exact_reciprocating",
        "strategy",
        "counterweights",
        "balance_shafts",
        "residual",
    }
    assert (data["engine"], data["speed_rad_s"], data["reference_z_m"]) == ("hand-one", W, 0.05)
    assert data["strategy"] == {
        "rotating_fraction": 1.0,
        "reciprocating_fraction": 0.5,
        "couple": "per_throw",
        "planes_m": [],
    }
    assert data["exact_reciprocating"] == pytest.approx({"force_max": 17500.0, "moment_max": 875.0}, rel=1e-9)
    # free forces by source: only the orders a source has
    ff = data["free_forces"]
    assert set(ff) == {"rotating", "reciprocating", "total"}
    assert [t["order"] for t in ff["rotating"]] == [1.0]
    assert [t["order"] for t in ff["reciprocating"]] == [1.0, 2.0, 4.0, 6.0]
    assert [t["order"] for t in ff["total"]] == [1.0, 2.0, 4.0, 6.0]
    rot = ff["rotating"][0]
    assert set(rot) == {"order", "force", "moment"}
    assert (rot["force"]["kind"], rot["force"]["semi_major"]) == ("circle", pytest.approx(22000.0, rel=1e-12))
    assert rot["moment"]["semi_major"] == pytest.approx(1100.0, rel=1e-12)
    assert rot["moment"]["mz"] == {"cos": 0.0, "sin": 0.0}
    assert ff["total"][0]["force"]["semi_major"] == pytest.approx(36000.0, rel=1e-9)
    # counterweights with their sectors
    c0, c1 = data["counterweights"]
    assert set(c1) == {"shaft", "z_m", "unbalance_kg_m", "angle_deg", "angle_on_shaft_deg", "sector"}
    assert (c0["shaft"], c0["z_m"], c0["unbalance_kg_m"], c0["angle_deg"], c0["angle_on_shaft_deg"], c0["sector"]) == (
        "main",
        -0.1,
        0.0,
        0.0,
        0.0,
        None,
    )
    assert (c1["z_m"], c1["angle_deg"], c1["angle_on_shaft_deg"]) == (0.1, pytest.approx(180.0), pytest.approx(180.0))
    assert c1["unbalance_kg_m"] == pytest.approx(0.18125, rel=1e-14)
    assert c1["sector"]["thickness_mm"] == pytest.approx(41.428571, rel=1e-7)
    # balance shafts
    fs, cs = data["balance_shafts"]
    assert set(fs) == {"component", "order", "shafts", "roll_moment_n_m"}
    assert (fs["component"], fs["order"], cs["component"], cs["order"]) == ("force", 2, "couple", 2)
    assert fs["roll_moment_n_m"] == pytest.approx(0.0, abs=1e-9)
    plus = fs["shafts"][0]
    assert set(plus) == {
        "name",
        "speed_ratio",
        "unbalance_kg_m",
        "angle_deg",
        "z_m",
        "position_m",
        "on_crankshaft",
        "constraint",
    }
    assert (plus["name"], plus["speed_ratio"], plus["on_crankshaft"], plus["z_m"]) == ("force2_plus", 2, False, [0.05])
    assert plus["unbalance_kg_m"] == pytest.approx(F2 / 1.28e6, rel=SERIES)
    assert abs(plus["angle_deg"]) == pytest.approx(180.0, abs=1e-12)
    assert plus["position_m"] == pytest.approx([0.08, 0.0], abs=1e-15)
    assert plus["constraint"].startswith("axes parallel to the crank axis")
    cplus = cs["shafts"][0]
    assert (cplus["name"], cplus["z_m"]) == ("couple2_plus", pytest.approx([0.125, -0.025], abs=1e-15))
    assert cplus["position_m"] == pytest.approx([0.0, 0.1], abs=1e-15)
    # residual: every reported order of the total
    resid = data["residual"]
    assert [t["order"] for t in resid] == [1.0, 2.0, 4.0, 6.0]
    assert resid[0]["force"]["semi_major"] == pytest.approx(7000.0, rel=1e-9)
    assert resid[1]["force"]["kind"] == "zero" and resid[1]["moment"]["kind"] == "zero"


def test_roll_moment_of_placed_shafts_in_the_record():
    """Force shafts placed at (80, 40) and (-80, -20) mm: their x parts, (F_2/2) sin 2 theta
    in opposite senses, act 60 mm apart in height: M_z = 0.03 F_2 sin 2 theta (the plus
    shaft's F_x = -(F_2/2) sin 2 theta at y = 0.04, the minus shaft's +(F_2/2) sin 2 theta
    at y = -0.02: -(0.04)(-F_2/2) + (0.02)(F_2/2) = 0.03 F_2)."""
    shafts = (ShaftRequest("force", 2, 0.08, 0.2, ((0.08, 0.04), (-0.08, -0.02))),)
    data = result_to_dict(analyse_balance(_engine(), W, _settings(shafts=shafts)))
    assert data["balance_shafts"][0]["roll_moment_n_m"] == pytest.approx(0.03 * F2, rel=SERIES)
    mz = data["residual"][1]["moment"]["mz"]
    assert mz["cos"] == pytest.approx(0.0, abs=1e-9)
    assert mz["sin"] == pytest.approx(0.03 * F2, rel=SERIES)


def test_without_settings_rotating_masses_per_throw_and_nothing_else():
    """No settings: BalanceStrategy() (all the rotating mass per throw, no reciprocating
    share), moments about z = 0, no sectors, no shafts; the residual is the reciprocating
    force alone: 14000 N along y at order 1, couple 0.1 * 14000 = 1400 N m."""
    r = analyse_balance(_engine(), W)
    assert (r.forces.reference_z, r.sectors, r.shafts) == (0.0, (None, None), ())
    assert r.design.counterweights[1].unbalance == pytest.approx(2.75 * 0.05, rel=1e-14)
    t = r.residual.total(1)
    assert t.force_hodograph().major == pytest.approx(14000.0, rel=1e-9)
    assert t.moment_hodograph().major == pytest.approx(1400.0, rel=1e-9)


def test_backward_turning_engine_names_the_shafts_by_speed_relative_to_it():
    """Shaft sense -1: the part of the order-2 force turning in the engine's positive sense
    turns against this crankshaft: the first shaft has speed ratio -2."""
    r = analyse_balance(_engine(sense=-1), W, _settings(shafts=(ShaftRequest("force", 2, 0.08, 0.2),)))
    assert [(s.name, s.speed_ratio) for s in r.shafts[0].shafts] == [("force2_minus", -2), ("force2_plus", 2)]


def test_sector_refusal_names_the_plane():
    """r_inner free with the journal radius 60 mm: the solved inner radius
    (r1^3 - U/K)^(1/3) = (0.001 - 0.18125 / (5000 * 0.0414285714))^(1/3) = 0.05 m lies
    inside it; the key names plane 2 of the shaft at z = 100 mm."""
    with pytest.raises(InputError) as err:
        analyse_balance(_engine(), W, _settings(journal_radius=0.06, free="r_inner"))
    assert err.value.key == "balance.counterweight (plane 2, z = 100 mm, shaft 'main')"
    assert err.value.reason.startswith("needs an inner radius of 50 mm, inside the journal radius 60 mm")


def test_placement_refusal_keeps_its_reason_and_names_the_request():
    shafts = (ShaftRequest("force", 2, 0.08, 0.2), ShaftRequest("force", 1, 0.08, 0.2, ((0.1, 0.0), (-0.1, 0.0))))
    with pytest.raises(InputError) as err:
        analyse_balance(_engine(), W, _settings(shafts=shafts))
    assert err.value.key == "balance.shafts[1].positions"
    assert err.value.reason == ("the order-1 force needs 1 shaft(s) (force1_minus); give one position each")


def test_first_order_rows_of_counterweights_and_yoke_are_always_listed(res):
    """Asked for order 2 only, the table still lists the first order of the sources that
    have one by construction: the counterweights (29000 N, above) and, on the Nordberg
    radial engine of seed 000 (example 16's yoke), the synchronising yoke."""
    from helpers.balance import engine

    from fe_crank.balance import free_forces

    keys = [(r["source"], r["order"]) for r in forces_table(res.residual, orders=(2.0,))]
    assert ("counterweights", 1.0) in keys and ("rotating", 1.0) in keys
    yoke = [
        r for r in forces_table(free_forces(engine("nordberg_radial.toml"), W), orders=(2.0,)) if r["source"] == "yoke"
    ]
    assert [r["order"] for r in yoke][0] == 1.0 and yoke[0]["force_max"] > 0.0
