"""Counterweight strategies, annular-sector synthesis and its refusals, balance shafts."""

import math

import numpy as np
import pytest
from helpers.balance import engine

from fe_crank import model
from fe_crank.balance import (
    BalanceStrategy,
    annular_sector,
    balance_shafts,
    counterweight_mass,
    free_forces,
    size_counterweights,
    solve_sector,
)
from fe_crank.balance.mechanism import reciprocating_mass, rotating_mass
from fe_crank.errors import InputError

W = 400.0


def single():
    return model.Engine(
        "single",
        4,
        (model.Shaft("main"),),
        (model.Throw("1", "main", 0.0, 0.05, 0.0, 2.0),),
        (model.Cylinder("1", "1", 0.09, model.Rod(0.2, 1.0, 0.05), 1.5),),
    )


def test_single_cylinder_fraction_of_first_order():
    """U = (m_rot + f m_j) R opposite the pin; the residual first order along the cylinder axis
    is (1 - f) m_j R omega^2 and across it f m_j R omega^2 (the classical trade)."""
    e = single()
    mj, mr = reciprocating_mass(e.cylinders[0]), rotating_mass(e, "1")
    for f in (0.0, 0.5, 1.0):
        d = size_counterweights(e, BalanceStrategy(1.0, f), W)
        (cw,) = d.counterweights
        assert cw.unbalance == pytest.approx((mr + f * mj) * 0.05)
        assert abs(cw.angle_on_shaft) == pytest.approx(math.pi)
        (a, b), (c, dd) = d.residual.total(1).force
        assert math.hypot(c, dd) == pytest.approx((1 - f) * mj * 0.05 * W**2)  # along y (cylinder)
        assert math.hypot(a, b) == pytest.approx(f * mj * 0.05 * W**2)  # across


def test_per_throw_webs_split_and_whole_shaft_two_plane_balance():
    e = engine("inline3.toml")
    per = size_counterweights(e, BalanceStrategy(1.0, 0.0, web_offset=0.02), W)
    assert len(per.counterweights) == 6
    whole = size_counterweights(e, BalanceStrategy(1.0, 0.0, "whole_shaft", planes=(-0.1, 0.12)), W)
    assert len(whole.counterweights) == 2
    for d in (per, whole):
        t = d.residual.total(1, ("rotating", "counterweights"))
        assert t.force_hodograph().kind == "zero" and t.moment_hodograph().kind == "zero"
    # whole-shaft needs far less than the per-throw sum: inline-3 rotating forces cancel, only a couple
    assert sum(c.unbalance for c in whole.counterweights) < sum(c.unbalance for c in per.counterweights)


def test_counterweight_mass_formula():
    assert counterweight_mass(1000.0, 0.1, 100.0) == pytest.approx(1000.0 / (0.1 * 100.0**2))


@pytest.mark.parametrize(
    "bad",
    [
        dict(reciprocating_fraction=-0.1),
        dict(rotating_fraction=-1.0),
        dict(reciprocating_fraction=1.5),
        dict(couple="sideways"),
        dict(couple="whole_shaft", planes=(0.1,)),
    ],
)
def test_bad_strategy_is_refused(bad):
    with pytest.raises(InputError):
        BalanceStrategy(**bad)


def test_sector_general_angle_against_numerical_integration():
    r1, r2, b, a, rho = 0.08, 0.03, 0.015, math.radians(130), 7800.0
    s = annular_sector(r1, r2, b, a, rho)
    r = np.linspace(r2, r1, 2001)
    t = np.linspace(-a / 2, a / 2, 2001)
    rr, tt = np.meshgrid(r, t)
    dm = rho * b * rr  # polar area element r dr dt
    mass = np.trapezoid(np.trapezoid(dm, r, axis=1), t)
    my = np.trapezoid(np.trapezoid(dm * rr * np.cos(tt), r, axis=1), t)
    assert s.mass == pytest.approx(mass, rel=1e-6)
    assert s.unbalance == pytest.approx(my, rel=1e-6)
    assert s.centroid_radius == pytest.approx(2 * math.sin(a / 2) / (3 * a / 2) * (r1**3 - r2**3) / (r1**2 - r2**2))
    full = annular_sector(r1, r2, b, 2 * math.pi, rho)
    assert full.unbalance == pytest.approx(0.0, abs=1e-15)


@pytest.mark.parametrize("free", ["r_outer", "r_inner", "thickness", "angle"])
def test_sector_inverse_round_trip(free):
    ref = annular_sector(0.07, 0.03, 0.02, math.radians(150), 7400.0)
    given = dict(r_outer=0.07, r_inner=0.03, thickness=0.02, angle=math.radians(150))
    given[free] = None
    s = solve_sector(ref.unbalance, free=free, density=7400.0, **given)
    for k in ("r_outer", "r_inner", "thickness", "angle", "mass", "unbalance"):
        assert getattr(s, k) == pytest.approx(getattr(ref, k), rel=1e-9)


def test_sector_that_cannot_fit_is_refused_with_a_clear_reason():
    with pytest.raises(InputError, match="beyond the envelope"):
        solve_sector(0.05, free="r_outer", r_inner=0.03, thickness=0.02, angle=math.pi, density=7400.0, envelope=0.08)
    with pytest.raises(InputError, match="inside the journal"):
        solve_sector(
            0.03, free="r_inner", r_outer=0.07, thickness=0.02, angle=math.pi, density=7400.0, journal_radius=0.04
        )
    with pytest.raises(InputError, match="cannot fit"):
        solve_sector(0.5, free="angle", r_outer=0.07, r_inner=0.03, thickness=0.02, density=7400.0)
    with pytest.raises(InputError, match="360"):
        annular_sector(0.07, 0.03, 0.02, math.radians(400), 7400.0)


def test_empty_engine_and_idle_shaft_are_refused():
    e = single()
    with pytest.raises(InputError, match="no cylinders"):
        free_forces(model.Engine("empty", 4, e.shafts, e.throws, ()), W)
    idle = model.Engine("idle", 4, e.shafts + (model.Shaft("spare"),), e.throws, e.cylinders)
    with pytest.raises(InputError, match="spare"):
        free_forces(idle, W)


@pytest.mark.parametrize(
    "layout, component, order",
    [
        ("inline4.toml", "force", 2),  # Lanchester: two shafts at +-2 omega
        ("single", "force", 1),
        ("v4_90_base.toml", "couple", 1),  # one shaft at -omega plus a crank pair (seed 002)
        ("inline2_180.toml", "couple", 2),
        ("napier_deltic_section.toml", "force", 1),
    ],
)
def test_balance_shafts_cancel_the_targeted_component(layout, component, order):
    e = single() if layout == "single" else engine(layout)
    ff = free_forces(e, W)
    before = ff.total(order)
    d = balance_shafts(ff, component, order, reference_sense=e.shafts[0].sense)
    after = d.residual.total(order)
    if component == "force":
        assert after.force_hodograph().kind == "zero"
        assert np.allclose(after.moment[:2], before.moment[:2])  # couples untouched
    else:
        assert after.moment_hodograph().kind == "zero"
        assert np.allclose(after.force, before.force)
    assert all(abs(s.speed_ratio) == order for s in d.shafts)
    # a straight-line force needs two equal counter-rotating unbalances (seed 002)
    if ff.total(order).force_hodograph().kind == "line" and component == "force":
        plus, minus = d.shafts
        assert plus.speed_ratio == -minus.speed_ratio and plus.unbalance == pytest.approx(minus.unbalance)
        assert plus.position == pytest.approx(tuple(-p for p in minus.position))
        # symmetric about the crank axis across the force line: no roll moment is added
        assert np.allclose(d.residual.total(order).moment[2], before.moment[2], atol=1e-9 * abs(plus.unbalance) * W**2)


def test_first_order_couple_uses_one_shaft_and_a_crank_pair():
    e = engine("v4_90_base.toml")
    d = balance_shafts(free_forces(e, W), "couple", 1, sources=("reciprocating",))
    kinds = sorted((s.on_crankshaft, s.speed_ratio) for s in d.shafts)
    assert kinds == [(False, -1), (True, 1)]
    # each carries half the line couple sqrt(2) m_A R omega^2 l: U = M / (2 span omega^2)
    m = math.sqrt(2) * 0.62 * 0.033 * W**2 * 0.128
    for s in d.shafts:
        assert s.unbalance == pytest.approx(m / 2 / (0.2 * W**2), rel=2e-4)


def test_balance_shaft_input_errors():
    ff = free_forces(single(), W)
    with pytest.raises(InputError):
        balance_shafts(ff, "torque", 1)
    with pytest.raises(InputError):
        balance_shafts(ff, "force", 3)


def test_nearest_counterweight_lookup_for_later_stages():
    e = engine("inline3.toml")
    d = size_counterweights(e, BalanceStrategy(1.0, 0.0, web_offset=0.02), W)
    t = e.throws[1]
    cw = d.nearest("main", t.axial_position + 0.019)
    assert cw.z == pytest.approx(t.axial_position + 0.02)
    assert cw.unbalance == pytest.approx(rotating_mass(e, t.name) * t.crank_radius / 2)
    assert d.nearest("nope", 0.0) is None
