"""IACS UR M53 Rev.1 3.1-3.3: the bore and recess factors of the empirical SCFs and the
validity range at its limits, by hand.

The bore factors f(d_G), f(d_H) and f(recess) multiply the SCFs, so a bored, recessed
throw's SCF divided by the same throw's unbored one is a ratio of those factors alone,
whatever the other factors: that ratio is checked against the polynomials of 3.2 / 3.3 evaluated by
hand (to 1e-6: the hand values carry 7 digits; a change of any coefficient by 0.01 moves
a ratio by 1e-3 or more).
"""

from __future__ import annotations

import math

import pytest

from fe_crank.rules.m53 import calculation as m53

BASE = {"s": 0.2, "w": 0.3, "b": 1.5, "r": 0.05, "dG": 0.0, "dH": 0.0, "tH": 0.0, "tG": 0.0}
BORED = {**BASE, "dG": 0.4, "dH": 0.3}
RECESSED = {**BORED, "tH": 0.1, "tG": 0.05}


def test_bore_factors_by_hand():
    """d_G = 0.4, d_H = 0.3 (UR M53 3.2 crankpin, 3.3 journal):
    alpha_B  f(d_G) = 0.9993 + 0.27*0.4 - 1.0211*0.16 + 0.5306*0.064 = 0.9993 + 0.108 - 0.163376
                      + 0.0339584 = 0.9778824
             f(d_H) = 0.9978 + 0.3145*0.3 - 1.5241*0.09 + 2.4147*0.027 = 0.9978 + 0.09435 - 0.137169
                      + 0.0651969 = 1.0201779
    beta_B   f(d_G) = 1.0012 - 0.6441*0.4 + 1.2265*0.16 = 1.0012 - 0.25764 + 0.19624 = 0.9398
             f(d_H) = 1.0022 - 0.1903*0.3 + 0.0073*0.09 = 1.0022 - 0.05709 + 0.000657 = 0.945767
    beta_Q   f(d_H) = 0.9937 - 1.1949*0.3 + 1.7373*0.09 = 0.9937 - 0.35847 + 0.156357 = 0.791587
    The unbored factors are the constant terms (0.9993, 0.9978; 1.0012, 1.0022; 0.9937),
    so the ratios are f(0.4)/f(0) and f(0.3)/f(0); alpha_T has no bore factor (ratio 1)."""
    assert m53.alpha_b(BORED) / m53.alpha_b(BASE) == pytest.approx(0.9778824 / 0.9993 * 1.0201779 / 0.9978, rel=1e-6)
    assert m53.beta_b(BORED) / m53.beta_b(BASE) == pytest.approx(0.9398 / 1.0012 * 0.945767 / 1.0022, rel=1e-6)
    assert m53.beta_q(BORED) / m53.beta_q(BASE) == pytest.approx(0.791587 / 0.9937, rel=1e-6)
    assert m53.alpha_t(BORED) == m53.alpha_t(BASE)


def test_recess_factor_by_hand():
    """f(recess) = 1 + (t_H + t_G)(1.8 + 3.2 s) = 1 + 0.15 (1.8 + 0.64) = 1 + 0.15 * 2.44 = 1.366
    for t_H = 0.1, t_G = 0.05, s = 0.2, on alpha_B, beta_B and beta_Q alike; negative
    recesses would give 1 - 0.2 * 2.44 = 0.512 but the factor is not taken below 1."""
    for scf in (m53.alpha_b, m53.beta_b, m53.beta_q):
        assert scf(RECESSED) / scf(BORED) == pytest.approx(1.366, rel=1e-12)
        assert scf({**BORED, "tH": -0.1, "tG": -0.1}) == scf(BORED)
    # the recess enters with s: at s = -0.25, 1 + 0.15 (1.8 - 0.8) = 1.15
    rel = {**RECESSED, "s": -0.25}
    assert m53.alpha_b(rel) / m53.alpha_b({**BORED, "s": -0.25}) == pytest.approx(1.15, rel=1e-12)


LIMITS = [
    ("w", 0.2, 0.8),
    ("b", 1.1, 2.2),
    ("r", 0.03, 0.13),
    ("dG", 0.0, 0.8),
    ("dH", 0.0, 0.8),
    ("tH", -0.3, 0.3),
    ("tG", -0.3, 0.3),
]


@pytest.mark.parametrize("key, lo, hi", LIMITS)
def test_validity_range_at_both_limits(key, lo, hi):
    """UR M53 3.1: the limits themselves are inside (a 1e-12 allowance for round-off of
    the ratios); 0.01 beyond is outside, reported as "<key> = <value> not in [lo, hi]"."""
    assert m53.out_of_range({**BASE, key: lo}) == []
    assert m53.out_of_range({**BASE, key: hi}) == []
    assert m53.out_of_range({**BASE, key: lo - 0.01}) == [f"{key} = {lo - 0.01:.4g} not in [{lo}, {hi}]"]
    assert m53.out_of_range({**BASE, key: hi + 0.01}) == [f"{key} = {hi + 0.01:.4g} not in [{lo}, {hi}]"]


def test_overlap_limit_and_its_floor():
    """s <= 0.5 (3.1); there is no lower limit: below -0.5 the SCFs are evaluated at
    s = -0.5.  D = 100 mm, D_G = 120 mm: crank radius 60 mm gives S = 110 - 60 = 50 mm,
    s = 0.5 (inside); 61 mm gives s = 0.49; 59 mm s = 0.51 (outside); 200 mm gives
    S = -90 mm, s = -0.9, taken as -0.5."""
    assert m53.out_of_range({**BASE, "s": 0.5}) == []
    assert m53.out_of_range({**BASE, "s": 0.51}) == ["s = 0.51 not in [-inf, 0.5]"]
    assert m53.out_of_range({**BASE, "s": -5.0}) == []

    def geo(radius):
        return m53.M53Geometry(
            pin_diameter=0.1,
            journal_diameter=0.12,
            crank_radius=radius,
            web_thickness=0.03,
            web_width=0.15,
            pin_fillet_radius=0.005,
            journal_fillet_radius=0.006,
            bearing_to_web=0.06,
        )

    assert geo(0.06).related("pin")["s"] == pytest.approx(0.5, rel=1e-12)
    assert geo(0.2).related("pin")["s"] == -0.5
    assert geo(0.2).overlap == pytest.approx(-0.09, rel=1e-12)
    assert math.isinf(m53.VALIDITY["s"][0])
