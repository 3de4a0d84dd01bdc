"""``assess.overspeed``: which cycles the overspeed check runs, on which grid, and the
note that says so, for the one-cylinder case of ``test_assess_overspeed.py`` (its hand
calculation of the pin force is there; these tests check the wording and the bookkeeping
around it in full)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
from test_assess_overspeed import _case, _hand, _table_case

from fe_crank.assess.overspeed import describe, overspeed_cycles, overspeed_dynamics
from fe_crank.mechanism.dynamics import analyse


def test_note_in_full_for_each_gas_state(tmp_path):
    """4200 rpm = 439.823 rad/s, printed back as 439.823 x 30 / pi = 4200 rpm."""
    head = (
        "overspeed: whole cycle recomputed at 4200 rpm (rod and piston inertia and crank body force at "
        "omega_os^2; gas: "
    )
    lc = _case(tmp_path, 'overspeed_gas = "as_operating"')
    assert describe(lc) == head + "the operating gas pressure table); worst angle"
    lc = _table_case(tmp_path)
    assert describe(lc) == head + (
        "no combustion, zero gauge gas pressure (the gas data give no compression "
        "ratio and intake pressure for a motored curve)); worst angle"
    )
    lc = _case(tmp_path)
    src = lc.engine.gas.motored.source
    assert describe(lc) == head + (
        f"(no combustion, {src}) and (no combustion, zero gauge gas pressure), the worse of the two); worst angle"
    )


def test_cycles_and_their_order_grid_and_gas(tmp_path):
    """Motored with the curve: (curve, zero gas), in that order, on the operating grid;
    as_operating: one cycle with the operating table; no overspeed: none."""
    lc = _case(tmp_path)
    dyn = analyse(lc.engine, lc.operating)
    cycles = overspeed_cycles(lc, dyn)
    assert [c.gas for c in cycles] == [
        f"no combustion, {lc.engine.gas.motored.source}",
        "no combustion, zero gauge gas pressure",
    ]
    for c in cycles:
        np.testing.assert_array_equal(c.dynamics.theta, dyn.theta)
        assert c.dynamics.speed == lc.operating.overspeed
    # the zero-gas cycle: no gas force in any cylinder
    assert np.all(cycles[1].dynamics.cylinders["1"].gas == 0.0)
    # the first cycle is the one overspeed_dynamics returns
    assert overspeed_dynamics(lc, dyn) is not None
    np.testing.assert_array_equal(
        overspeed_dynamics(lc, dyn).throws["1"].pin_force, cycles[0].dynamics.throws["1"].pin_force
    )
    lc_op = _case(tmp_path, 'overspeed_gas = "as_operating"')
    (one,) = overspeed_cycles(lc_op, dyn)
    assert one.gas == "the operating gas pressure table"
    # the operating gas at the firing TDC is in the overspeed cycle too (inertia x 1.44 minus gas)
    i = int(np.argmin(np.abs(np.rad2deg(dyn.theta))))
    gas = dyn.cylinders["1"].gas[i]
    assert one.dynamics.throws["1"].pin_force[i, 1] == pytest.approx(_hand(4200) - gas, rel=1e-9)
    none = replace(lc, operating=replace(lc.operating, overspeed=None))
    assert overspeed_cycles(none, dyn) == () and overspeed_dynamics(none, dyn) is None


def test_overspeed_grid_follows_a_coarser_operating_grid(tmp_path):
    """An operating cycle on a 2-deg grid (360 angles over 720 deg): the overspeed cycles
    use the same 360 angles."""
    lc = _case(tmp_path)
    dyn = analyse(lc.engine, lc.operating, step=math.radians(2.0))
    assert dyn.theta.size == 360
    for c in overspeed_cycles(lc, dyn):
        np.testing.assert_allclose(c.dynamics.theta, dyn.theta, rtol=0, atol=1e-12)


def test_unknown_gas_mode_is_refused_in_full(tmp_path):
    lc = _case(tmp_path)
    bad = replace(lc, operating=replace(lc.operating, overspeed_gas="full"))
    dyn = analyse(lc.engine, lc.operating)
    with pytest.raises(ValueError) as e:
        overspeed_cycles(bad, dyn)
    assert str(e.value) == "overspeed_gas must be one of ('motored', 'as_operating'), not 'full'"


def test_an_operating_cycle_of_another_length_is_refused(tmp_path):
    """The operating dynamics of a two-stroke version of the engine (360 angles over 360
    deg) against the four-stroke load case: the overspeed cycle on the same step has 720
    angles, not 360 -- refused rather than paired angle by angle."""
    lc = _case(tmp_path)
    two = analyse(replace(lc.engine, strokes=2), lc.operating)
    assert two.theta.size == 360
    with pytest.raises(ValueError) as e:
        overspeed_cycles(lc, two)
    assert str(e.value) == "overspeed cycle grid differs from the operating one"
