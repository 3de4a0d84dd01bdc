"""Balance shafts placed freely in the cross-section: the roll moment of a pair offset in
height (F * Delta h), an asymmetric pair, and the placements that are refused."""

from __future__ import annotations

import math

import pytest
from helpers.balance import engine

from fe_crank.balance import balance_shafts, free_forces
from fe_crank.balance.analysis import analyse_balance
from fe_crank.errors import InputError
from fe_crank.io.balance import parse_balance

W = 400.0


@pytest.fixture(scope="module")
def second_order():
    """Inline-4 (flat crank): the order-2 free force is a straight line along the cylinder
    axis (+y), amplitude F2 = |P| + |Q|; each Lanchester shaft turns one half of it."""
    e = engine("inline4.toml")
    ff = free_forces(e, W)
    h = ff.total(2).force_hodograph()
    assert h.kind == "line"
    return e, ff, h.major


def mz_amplitude(term) -> float:
    return math.hypot(term.moment[2, 0], term.moment[2, 1])


def test_pair_offset_in_height_gives_the_roll_moment_f_delta_h(second_order):
    """Shafts at x = +-60 mm, heights +40 and -20 mm: the forces cancel, their x parts
    act 60 mm apart in height, M_z amplitude = (F2 / 2) * 0.060 (one shaft's force times
    the height offset; seed 002's offset second-order pair)."""
    e, ff, f2 = second_order
    before = ff.total(2)
    d = balance_shafts(ff, "force", 2, positions=[(0.06, 0.04), (-0.06, -0.02)])
    after = d.residual.total(2)
    assert after.force_hodograph().kind == "zero"
    expected = 0.5 * f2 * 0.060
    assert d.roll_moment == pytest.approx(expected, rel=1e-9)
    assert mz_amplitude(before) < 1e-9 * expected  # the engine itself has no order-2 M_z
    assert mz_amplitude(after) == pytest.approx(expected, rel=1e-9)  # carried as a free moment
    for s in d.shafts:
        assert s.unbalance * (2 * W) ** 2 == pytest.approx(0.5 * f2, rel=1e-9)


def test_symmetric_pair_has_no_roll_moment(second_order):
    e, ff, f2 = second_order
    d = balance_shafts(ff, "force", 2, positions=[(0.07, 0.03), (-0.07, 0.03)])
    assert d.roll_moment < 1e-9 * f2 * 0.07


def test_asymmetric_pair(second_order):
    """Shafts at (90, 50) and (-30, -70) mm: with F_y,1 = F_y,2 = (F2/2) cos 2 theta and
    F_x,1 = -F_x,2 = +-(F2/2) sin 2 theta,
    M_z = (F2/2) [(x1 + x2) cos 2 theta -+ (y1 - y2) sin 2 theta], amplitude
    (F2/2) hypot(0.060, 0.120); the force is still cancelled."""
    e, ff, f2 = second_order
    d = balance_shafts(ff, "force", 2, positions=[(0.09, 0.05), (-0.03, -0.07)])
    assert d.residual.total(2).force_hodograph().kind == "zero"
    assert d.roll_moment == pytest.approx(0.5 * f2 * math.hypot(0.060, 0.120), rel=1e-9)
    assert [s.position for s in d.shafts] == [(0.09, 0.05), (-0.03, -0.07)]


@pytest.mark.parametrize(
    "positions, reason",
    [
        ([(0.06, 0.04)], "needs 2 shaft(s)"),
        ([(0.06, 0.04), (0.0, 0.0)], "cannot sit on the crank axis"),
    ],
)
def test_placements_that_cannot_cancel_are_refused(second_order, positions, reason):
    e, ff, f2 = second_order
    with pytest.raises(InputError) as err:
        balance_shafts(ff, "force", 2, positions=positions)
    assert reason in str(err.value)


def test_crank_pair_must_stay_on_the_crank_axis():
    e = engine("v4_90_base.toml")
    with pytest.raises(InputError, match="counterweight pair on the crankshaft"):
        balance_shafts(free_forces(e, W), "couple", 1, sources=("reciprocating",), positions=[(0.05, 0.0), (0.0, 0.1)])


def test_balance_section_positions_and_roll_moment_reported(second_order, tmp_path):
    """[[balance.shafts]] positions in mm -> SI; the analysis reports the roll moment and
    names the section's key when the placement is refused."""
    e, ff, f2 = second_order
    table = {"shafts": [{"component": "force", "order": 2, "positions": [["60 mm", "40 mm"], ["-60 mm", "-20 mm"]]}]}
    settings = parse_balance(table, tmp_path / "case.toml")
    assert settings.shafts[0].positions == ((0.06, 0.04), (-0.06, -0.02))
    res = analyse_balance(e, W, settings)
    assert res.shafts[0].roll_moment == pytest.approx(0.5 * f2 * 0.06, rel=1e-6)
    bad = parse_balance(
        {"shafts": [{"component": "force", "order": 2, "positions": [["60 mm", "40 mm"]]}]}, tmp_path / "case.toml"
    )
    with pytest.raises(InputError) as err:
        analyse_balance(e, W, bad)
    assert err.value.key == "balance.shafts[0].positions"
    with pytest.raises(InputError, match="length"):
        parse_balance(
            {"shafts": [{"component": "force", "order": 2, "positions": [["60", "40 mm"]]}]}, tmp_path / "case.toml"
        )
