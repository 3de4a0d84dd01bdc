"""Balance stage input checks, each by message and key (the key is what the CLI prints
next to the file), with the boundary values that must still be accepted, and the
lever rule of the Nordberg rocker counterweight (seed 000, eq. 166) by hand."""

import math

import numpy as np
import pytest

from fe_crank import model
from fe_crank.balance import (
    BalanceStrategy,
    counterweight_mass,
    free_forces,
    rocker_counterweight_force,
    size_counterweights,
)
from fe_crank.errors import InputError


def _single():
    return model.Engine(
        "single",
        4,
        (model.Shaft("main"),),
        (model.Throw("1", "main", 0.0, 0.05, 0.0, 2.0),),
        (model.Cylinder("1", "1", 0.09, model.Rod(0.2, 1.0, 0.05), 1.5),),
    )


@pytest.mark.parametrize(
    "kwargs, message, key",
    [
        (dict(rotating_fraction=-1.0), "must be a fraction >= 0", "balance.rotating_fraction"),
        (dict(rotating_fraction=math.inf), "must be a fraction >= 0", "balance.rotating_fraction"),
        (dict(reciprocating_fraction=math.nan), "must be a fraction >= 0", "balance.reciprocating_fraction"),
        (dict(reciprocating_fraction=-0.1), "must be a fraction >= 0", "balance.reciprocating_fraction"),
        (dict(reciprocating_fraction=1.5), "cannot exceed 1", "balance.reciprocating_fraction"),
        (dict(couple="sideways"), "'sideways' is not one of", "balance.couple"),
        (dict(couple="whole_shaft", planes=(0.1,)), "needs at least two counterweight planes", "balance.planes"),
        (dict(web_offset=-0.01), "web_offset cannot be negative", "balance.web_offset"),
    ],
)
def test_bad_strategy_is_refused_by_message_and_key(kwargs, message, key):
    with pytest.raises(InputError, match=message) as err:
        BalanceStrategy(**kwargs)
    assert err.value.key == key


def test_strategy_boundaries_are_accepted():
    """Fractions 0 and 1 (none and all of the first order), two planes, no web offset."""
    BalanceStrategy(rotating_fraction=0.0, reciprocating_fraction=1.0)
    BalanceStrategy(rotating_fraction=2.0, reciprocating_fraction=0.0)  # over-balance of the rotating mass
    BalanceStrategy(couple="whole_shaft", planes=(-0.1, 0.1), web_offset=0.0)


def test_coincident_counterweight_planes_are_refused():
    with pytest.raises(InputError, match="two or more distinct axial positions") as err:
        size_counterweights(_single(), BalanceStrategy(couple="whole_shaft", planes=(0.1, 0.1)), 400.0)
    assert err.value.key == "balance.planes"


@pytest.mark.parametrize("radius, omega", [(0.0, 100.0), (0.1, 0.0), (-0.1, 100.0)])
def test_counterweight_mass_needs_positive_radius_and_speed(radius, omega):
    with pytest.raises(InputError, match="counterweight radius and speed must be positive") as err:
        counterweight_mass(1000.0, radius, omega)
    assert err.value.key == "balance"


def test_rocker_counterweight_lever_rule_and_its_refusals():
    """P_pr l_pr = P_ya l_ya (seed 000, eq. 166): 1000 N at 0.3 m balanced at 0.2 m needs
    1000 * 0.3 / 0.2 = 1500 N."""
    assert rocker_counterweight_force(1000.0, 0.3, 0.2) == pytest.approx(1500.0, rel=1e-15)
    for arms in ((0.0, 0.2), (0.3, 0.0), (-0.3, 0.2)):
        with pytest.raises(InputError, match="rocker arms must be positive") as err:
            rocker_counterweight_force(1000.0, *arms)
        assert err.value.key == "yoke"


@pytest.mark.parametrize("speed", [0.0, -10.0, math.nan])
def test_free_forces_need_a_positive_speed(speed):
    with pytest.raises(InputError, match="speed must be positive") as err:
        free_forces(_single(), speed)
    assert err.value.key == "operating.speed"


def test_empty_engine_and_idle_shaft_are_refused_by_key():
    e = _single()
    with pytest.raises(InputError, match="the engine has no cylinders: nothing to balance") as err:
        free_forces(model.Engine("empty", 4, e.shafts, e.throws, ()), 400.0)
    assert err.value.key == "cylinders"
    idle = model.Engine("idle", 4, e.shafts + (model.Shaft("spare"),), e.throws, e.cylinders)
    with pytest.raises(InputError, match="shaft 'spare' drives no cylinder") as err:
        free_forces(idle, 400.0)
    assert err.value.key == "shafts.spare"


@pytest.mark.parametrize(
    "angle, wrapped",
    [
        (0.5, 0.5),
        (1.5 * math.pi, -0.5 * math.pi),
        (-1.5 * math.pi, 0.5 * math.pi),
        (math.pi, math.pi),
        (-math.pi, math.pi),
        (4.5 * math.pi, 0.5 * math.pi),
        (-4.5 * math.pi, -0.5 * math.pi),
    ],
)
def test_counterweight_angles_are_wrapped_into_minus_pi_to_pi(angle, wrapped):
    """Counterweight angles are reported in (-pi, pi]: 3 pi/2 is -pi/2, -pi is pi, 9 pi/2 is
    pi/2 (subtract whole turns of 2 pi by hand)."""
    from fe_crank.balance.counterweights import _wrap

    assert _wrap(angle) == pytest.approx(wrapped, abs=1e-12)


def test_whole_shaft_balance_in_three_asymmetric_planes_by_hand():
    """One throw at z = 0 with U = 2.75 kg * 0.05 m = 0.1375 kg m (rotating part, the pin at
    angle 0), planes z = -0.1, 0, 0.3 m (mean 1/15 m, signs -, -, +): U_i = A + sgn_i B with
    3 A - B = -U and -0.1 (A - B) + 0.3 (A + B) = 0.2 A + 0.4 B = 0, so A = -2B, B = U/7 and
    U_i = -3U/7, -3U/7, -U/7: 0.0589286, 0.0589286, 0.0196429 kg m, all opposite the pin
    (angle pi).  Sum -U and first moment 0.3 U/7 - 0.3 U/7 = 0, so the residual rotating
    first order is zero."""
    d = size_counterweights(_single(), BalanceStrategy(couple="whole_shaft", planes=(-0.1, 0.0, 0.3)), 400.0)
    u = 0.1375
    np.testing.assert_allclose([c.unbalance for c in d.counterweights], [3 * u / 7, 3 * u / 7, u / 7], rtol=1e-12)
    np.testing.assert_allclose([c.z for c in d.counterweights], [-0.1, 0.0, 0.3], rtol=0, atol=0)
    for c in d.counterweights:
        assert c.angle == pytest.approx(math.pi, abs=1e-12)
    res = d.residual.total(1, sources=("rotating", "counterweights"))
    assert res.force_hodograph().kind == "zero" and res.moment_hodograph().kind == "zero"
