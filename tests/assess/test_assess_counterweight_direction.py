"""The ``unbalance_error`` criterion compares the built and the required m r as vectors:
a counterweight turned from its balance plane's required direction is off by
|U_b - U_r| = sqrt((U_b - U_r)^2 + 2 U_b U_r (1 - cos d)) (law of cosines), not by the
magnitudes alone.  Hand calculations and the shipped V4-90 (its whole-shaft couple
balance requires 180 deg on throw A's side and 0 deg on throw B's, each opposite its
pin)."""

from __future__ import annotations

import dataclasses
import math

import pytest
from helpers.paths import ROOT

from fe_crank.assess.counterweight import CounterweightData, check_counterweight, direction_error
from fe_crank.assess.throw_geometry import parametric_throws
from fe_crank.balance.analysis import analyse_balance
from fe_crank.balance.counterweights import Counterweight
from fe_crank.geometry.mass import throw_solids
from fe_crank.io.loadcase import load_loadcase
from fe_crank.study.candidates import turned_geometry


def _required(angle_on_shaft: float) -> Counterweight:
    return Counterweight("main", 0.0, 0.01, angle_on_shaft, angle_on_shaft)


def test_direction_by_hand():
    """Throw frame: the pin on +y, a direction from +y towards +x; on the shaft it lies at
    the throw's angle plus sense times that (docs/contracts.md)."""
    down = (0.0, -1.0)  # opposite the pin
    assert direction_error(down, _required(math.pi), 0.0, 1) == pytest.approx(0.0, abs=1e-15)
    assert direction_error(down, _required(0.0), math.pi, 1) == pytest.approx(0.0, abs=1e-15)
    assert direction_error(down, _required(0.0), 0.0, 1) == pytest.approx(math.pi, abs=1e-15)
    off = math.radians(20.0)  # turned 20 deg from -y towards +x: at 160 deg in the throw frame
    turned = (math.sin(off), -math.cos(off))
    # throw at 90 deg, sense +1: 250 deg on the shaft; sense -1: 90 - 160 = -70 deg
    assert direction_error(turned, _required(math.radians(250.0)), math.pi / 2, 1) == pytest.approx(0.0, abs=1e-12)
    assert direction_error(turned, _required(math.radians(-70.0)), math.pi / 2, -1) == pytest.approx(0.0, abs=1e-12)
    assert direction_error(turned, _required(math.radians(270.0)), math.pi / 2, 1) == pytest.approx(off, abs=1e-12)


def test_error_of_equal_magnitudes_turned_is_the_chord():
    """|U_b| = |U_r| turned by d apart: the error is the chord 2 sin(d/2); in line, the
    magnitudes' difference exactly."""
    base = CounterweightData("cw", mass=1.0, centroid_radius=0.05, required_unbalance=0.05)
    for deg in (0.0, 10.0, 60.0, 180.0):
        d = math.radians(deg)
        c = check_counterweight(dataclasses.replace(base, direction_error=d), 100.0, None)
        assert c.unbalance_error == pytest.approx(2.0 * math.sin(d / 2.0), rel=1e-12, abs=1e-15)
    short = dataclasses.replace(base, mass=0.9, direction_error=0.0)
    assert check_counterweight(short, 100.0, None).unbalance_error == abs(0.9 * 0.05 - 0.05) / 0.05


def test_the_v4_turned_counterweights_miss_their_requirement_by_their_turn():
    """The shipped V4-90's counterweights sit opposite their pins, where its balance design
    wants them: the error is the magnitudes' (as before); turned 15 deg, the law of
    cosines with d the turn of the solids' exact m r vector (15 deg within its transition
    fillets' share), U_b from their exact mass properties."""
    lc = load_loadcase(ROOT / "loadcases" / "v4_90_pneumatic_operating.toml")
    assert lc.geometry is not None and lc.balance is not None
    design = analyse_balance(lc.engine, lc.operating.speed, lc.balance).design
    off = math.radians(15.0)
    for turn in (0.0, off):
        g = turned_geometry(lc.geometry, turn)
        names = tuple(t.name for t in g.throws)
        solids = throw_solids(g, names)
        got = parametric_throws(g, {n: n for n in names}, lc.engine, solids, design)
        for name in names:
            for cw in got[name].counterweights:
                assert cw.required_unbalance is not None and cw.direction_error is not None
                # the sector turns rigidly; its transition fillet follows the web's outline,
                # which does not turn: the m r vector turns by the offset within 0.05 deg
                assert cw.direction_error == pytest.approx(turn, abs=math.radians(0.05))
                b, r = cw.built_unbalance, cw.required_unbalance
                err = check_counterweight(cw, lc.operating.speed, None).unbalance_error
                assert err == pytest.approx(
                    math.sqrt((b - r) ** 2 + 2 * b * r * (1 - math.cos(cw.direction_error))) / r, rel=1e-12
                )
                if turn == 0.0:
                    assert err == abs(b - r) / r
                else:
                    assert err > abs(b - r) / r + 0.2  # 2 sin(7.5 deg) = 0.26 of the turn alone
