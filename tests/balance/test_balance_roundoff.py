"""Round-off clearing and order bookkeeping of fe_crank.balance.forces / terms, by hand.

The free forces clear coefficients below ``ROUNDOFF = 1e-11`` of the engine's force scale
(N) and moment coefficients below that times ``max(length_scale, 1e-3 m)`` (N m), once
when the terms are merged (``FreeForces.terms``, what ``evaluate`` sums) and again on every
``term()`` / ``total()``.  The thresholds are probed with hand-built terms at force scale
1e11 N, where the force threshold is 1e-11 * 1e11 = 1 N; each probe sits a factor of 2 or
more from the threshold on the side it tests, or exactly on it (kept: the test is ``<``).
"""

import math

import numpy as np
import pytest

from fe_crank import model
from fe_crank.balance import free_forces
from fe_crank.balance.forces import ROUNDOFF, FreeForces, _merge
from fe_crank.balance.terms import OrderTerm, point_term
from fe_crank.errors import InputError

SCALE = 1e11  # N: force threshold ROUNDOFF * SCALE = 1 N


def _term(source, order, f, m):
    return OrderTerm(source, float(order), np.full((2, 2), float(f)), np.full((3, 2), float(m)))


def _by_source(terms):
    return {(t.source, t.order): t for t in terms}


def test_merge_thresholds_by_hand():
    """force scale 1e11 N -> force threshold 1 N.  Length scale 2 m -> moment threshold
    1 * max(2, 1e-3) = 2 N m; length scale 1e-4 m -> 1 * max(1e-4, 1e-3) = 1e-3 N m.
    A force of 0.5 N is cleared, one of 3 N kept, one exactly at the threshold kept; a
    moment of 1.5 N m is cleared at 2 N m and kept at 1e-3 N m; one exactly at the moment
    threshold is kept.  Equal source and order are summed: 0.5 + 0.25 = 0.75 N (cleared).
    With the 1e-3 N m moment threshold a moment of 0.5 N m is kept."""
    ftol = ROUNDOFF * SCALE
    assert ftol == pytest.approx(1.0, rel=1e-15)
    terms = [
        _term("rotating", 1, 0.5, 1.5),
        _term("reciprocating", 2, 3.0, 2.0 * ftol),
        _term("yoke", 1, ftol, 4.0),
        _term("rotating", 2, 0.5, 0.0),
        _term("rotating", 2, 0.25, 0.0),
    ]
    out = _by_source(_merge(terms, SCALE, 2.0))
    assert len(out) == 4
    np.testing.assert_array_equal(out[("rotating", 1.0)].force, 0.0)  # 0.5 N < 1 N
    np.testing.assert_array_equal(out[("rotating", 1.0)].moment, 0.0)  # 1.5 N m < 2 N m
    np.testing.assert_array_equal(out[("reciprocating", 2.0)].force, 3.0)
    np.testing.assert_array_equal(out[("reciprocating", 2.0)].moment, 2.0 * ftol)  # at the threshold: kept
    np.testing.assert_array_equal(out[("yoke", 1.0)].force, ftol)  # at the threshold: kept
    np.testing.assert_array_equal(out[("rotating", 2.0)].force, 0.0)  # 0.75 N summed, then cleared
    small = _by_source(_merge([_term("rotating", 1, 3.0, 0.5)], SCALE, 1e-4))
    np.testing.assert_array_equal(small[("rotating", 1.0)].moment, 0.5)  # 0.5 N m > 1e-3 N m (a 1 m floor clears it)


def test_term_and_total_clear_with_the_same_thresholds_by_hand():
    """``term()``/``total()`` clear again (the sum of several terms may cancel): the same
    hand thresholds as above, on a record built directly (force scale 1e11 N, length scale
    2 m: 1 N and 2 N m; length scale 1e-4 m: 1 N and 1e-3 N m)."""
    ftol = ROUNDOFF * SCALE
    terms = (_term("rotating", 1, 0.5, 1.5), _term("reciprocating", 1, ftol, 2.0 * ftol))
    ff = FreeForces("hand", 100.0, 0.0, terms, SCALE, 2.0)
    rot = ff.term("rotating", 1)
    np.testing.assert_array_equal(rot.force, 0.0)
    np.testing.assert_array_equal(rot.moment, 0.0)  # 1.5 < 2 N m
    rec = ff.term("reciprocating", 1)
    np.testing.assert_array_equal(rec.force, ftol)
    np.testing.assert_array_equal(rec.moment, 2.0 * ftol)
    # total = 0.5 + 1 = 1.5 N (kept), moments 1.5 + 2 = 3.5 N m (kept)
    np.testing.assert_allclose(ff.total(1).force, 0.5 + ftol, rtol=1e-15)
    np.testing.assert_allclose(ff.total(1).moment, 1.5 + 2.0 * ftol, rtol=1e-15)
    near = FreeForces("hand", 100.0, 0.0, (_term("rotating", 1, 3.0, 0.5),), SCALE, 1e-4)
    np.testing.assert_array_equal(near.term("rotating", 1).moment, 0.5)  # 0.5 > 1e-3 N m
    np.testing.assert_array_equal(near.total(1).moment, 0.5)


def test_orders_are_told_apart_to_the_ninth_decimal():
    """Orders 1.5 (a shaft geared at 1.5) and 2 are distinct orders, and 2 and 2 + 1e-12 the
    same one (float noise of ``k n``)."""
    f = np.array([[1.0, 0.0], [0.0, 1.0]])
    terms = (
        point_term("rotating", 1.5, f, (0.0, 0.0, 0.0)),
        point_term("rotating", 2.0, 2 * f, (0.0, 0.0, 0.0)),
        point_term("rotating", 2.0 + 1e-12, 3 * f, (0.0, 0.0, 0.0)),
    )
    ff = FreeForces("hand", 100.0, 0.0, terms, 1.0, 1.0)
    assert ff.orders == (1.5, 2.0)
    np.testing.assert_array_equal(ff.term("rotating", 1.5).force, f)
    np.testing.assert_array_equal(ff.term("rotating", 2).force, 5 * f)


def _single():
    rod = model.Rod(0.2, 1.0, 0.05)  # l = 0.2 m, c/l = 0.25: m_j = 1.5 + 0.25 = 1.75 kg
    return model.Engine(
        "single",
        4,
        (model.Shaft("main"),),
        (model.Throw("1", "main", 0.0, 0.05, 0.0, 2.0),),
        (model.Cylinder("1", "1", 0.09, rod, 1.5),),
    )


def test_kmax_limits_the_reciprocating_orders_and_keeps_the_highest():
    """lambda = R/l = 0.05/0.2 = 1/4.  The exact piston acceleration's orders (centred
    slider-crank: no odd order above 1) are, per m_j R omega^2 = 1.75 * 0.05 * 400^2 =
    14000 N:  A1 = 1, A2 = lambda + lambda^3/4 + 15 lambda^5/128 = 0.25 + 0.00390625 +
    0.00011444 = 0.25402069, A4 = lambda^3/4 + 3 lambda^5/16 = 0.00390625 + 0.00018311 =
    0.00408936 (the neglected lambda^7 terms: 35 lambda^7/256 = 8.3e-6 in A4, 0.2 %).
    With kmax = 4 the record holds orders 1 ... 4 (3 cleared as round-off) and nothing
    above; order 4 is 14000 * 0.00408936 = 57.25 N, checked to 1 % (the 0.2 % series error;
    the neighbouring orders are 3556 N and 0.96 N)."""
    ff = free_forces(_single(), 400.0, kmax=4)
    rec = {t.order: float(np.max(np.abs(t.force))) for t in ff.terms if t.source == "reciprocating"}
    assert max(rec) == 4.0
    assert rec[1.0] == pytest.approx(14000.0, rel=1e-6)
    assert rec[2.0] == pytest.approx(14000.0 * 0.25402069, rel=1e-4)
    assert rec.get(3.0, 0.0) == 0.0
    assert rec[4.0] == pytest.approx(14000.0 * 0.00408936, rel=0.01)
    full = free_forces(_single(), 400.0)
    assert max(t.order for t in full.terms if t.source == "reciprocating") > 4.0  # default kmax 24
    lam = 0.25
    assert 0.00408936 == pytest.approx(lam**3 / 4 + 3 * lam**5 / 16, rel=2e-6)  # 8 digits typed
    assert math.isclose(0.25402069, lam + lam**3 / 4 + 15 * lam**5 / 128, rel_tol=1e-7)


def test_empty_engine_refusal_in_full():
    e = model.Engine("empty", 4, (model.Shaft("main"),), (model.Throw("1", "main", 0.0, 0.05),), ())
    with pytest.raises(InputError) as err:
        free_forces(e, 100.0)
    assert (err.value.key, err.value.reason) == ("cylinders", "the engine has no cylinders: nothing to balance")
