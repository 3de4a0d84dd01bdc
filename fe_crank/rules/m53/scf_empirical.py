"""IACS UR M53 section 3: the empirical stress concentration factors and their validity range.

Formulas of UR M53 Rev.1 (Dec 2004), unchanged in Rev.2 (Jan 2011); checked against the rule
text as the Korean Register reproduces it clause by clause (Rules for the Classification of
Steel Ships, Pt 5, Annex 5-3, 2025).  Related dimensions (3.1) are the ``rel`` dictionaries of
``M53Geometry.related``: r, s, w, b, d_G, d_H, t_H, t_G, all divided by the crankpin
diameter D.

* 3.2 crankpin fillet: alpha_B, alpha_T;
* 3.3 journal fillet: beta_B, beta_Q, and beta_T, which is alpha_T's formula with the journal
  fillet radius related to the journal diameter, r = R_G/D_G, where pin and journal differ
  in diameter or fillet radius (3.3; KR Annex 5-3 3.(3)(C)(b)); beta_T = alpha_T where they
  are equal (then R_G/D_G = R_H/D).

alpha_T's f(b) = 7.8955 - 10.654 b + 5.3482 b^2 - 0.85 b^3 as the Korean Register's
reproduction prints it (``F_B_CUBIC``; an earlier version of this code had -0.857, of
unrecorded origin; no second copy of the rule text could be read, and 0.85 is the
conservative one: docs/assessment.md, "alpha_T's b^3 coefficient").
"""

from __future__ import annotations

import math

#: (low, high) of each related dimension, UR M53 Rev.1 section 3.1
VALIDITY = {
    "s": (-math.inf, 0.5),  # below -0.5: evaluated at s = -0.5 (3.1)
    "w": (0.2, 0.8),
    "b": (1.1, 2.2),
    "r": (0.03, 0.13),
    "dG": (0.0, 0.8),
    "dH": (0.0, 0.8),
    "tH": (-0.3, 0.3),
    "tG": (-0.3, 0.3),
}


#: the b^3 coefficient of alpha_T's (and beta_T's) f(b), UR M53 3.2, as KR Pt 5 Annex 5-3
#: prints it (docs/assessment.md, "alpha_T's b^3 coefficient": the texts sought, why 0.85)
F_B_CUBIC = 0.85


def out_of_range(rel: dict[str, float]) -> list[str]:
    """Related dimensions outside the validity range, as readable strings."""
    bad = []
    for k, (lo, hi) in VALIDITY.items():
        v = rel[k]
        if not lo - 1e-12 <= v <= hi + 1e-12:
            bad.append(f"{k} = {v:.4g} not in [{lo}, {hi}]")
    return bad


def _recess(rel: dict[str, float]) -> float:
    """f(recess) = 1 + (t_H + t_G)(1.8 + 3.2 s), not below 1 (3.2, 3.3)."""
    return max(1.0, 1.0 + (rel["tH"] + rel["tG"]) * (1.8 + 3.2 * rel["s"]))


def alpha_b(rel: dict[str, float]) -> float:
    """Crankpin fillet bending SCF alpha_B = 2.6914 f(s,w) f(w) f(b) f(r) f(d_G) f(d_H) f(recess) (3.2)."""
    s, w, b, r, dg, dh = (rel[k] for k in ("s", "w", "b", "r", "dG", "dH"))
    u = 1.0 - s
    fsw = (
        -4.1883
        + 29.2004 * w
        - 77.5925 * w**2
        + 91.9454 * w**3
        - 40.0416 * w**4
        + u * (9.5440 - 58.3480 * w + 159.3415 * w**2 - 192.5846 * w**3 + 85.2916 * w**4)
        + u**2 * (-3.8399 + 25.0444 * w - 70.5571 * w**2 + 87.0328 * w**3 - 39.1832 * w**4)
    )
    fw = 2.1790 * w**0.7171
    fb = 0.6840 - 0.0077 * b + 0.1473 * b**2
    fr = 0.2081 * r ** (-0.5231)
    fdg = 0.9993 + 0.27 * dg - 1.0211 * dg**2 + 0.5306 * dg**3
    fdh = 0.9978 + 0.3145 * dh - 1.5241 * dh**2 + 2.4147 * dh**3
    value: float = 2.6914 * fsw * fw * fb * fr * fdg * fdh * _recess(rel)
    return value


def alpha_t(rel: dict[str, float]) -> float:
    """Torsional SCF alpha_T = 0.8 f(r,s) f(b) f(w) (3.2; with r = R_G/D it is beta_T of 3.3)."""
    s, w, b, r = (rel[k] for k in ("s", "w", "b", "r"))
    frs = r ** (-0.322 + 0.1015 * (1.0 - s))
    fb = 7.8955 - 10.654 * b + 5.3482 * b**2 - F_B_CUBIC * b**3
    fw = w ** (-0.145)
    value: float = 0.8 * frs * fb * fw
    return value


def beta_t(rel: dict[str, float], journal_fillet_over_journal_diameter: float) -> float:
    """Journal fillet torsional SCF beta_T = 0.8 f(r,s) f(b) f(w) with r = R_G/D_G (UR M53 3.3):
    alpha_T's functions (3.2) with s, w, b related to the crankpin diameter as usual but the
    journal fillet radius related to the journal diameter.  ``rel``: the journal fillet's
    related dimensions (``M53Geometry.related("journal")``)."""
    return alpha_t({**rel, "r": journal_fillet_over_journal_diameter})


def beta_b(rel: dict[str, float]) -> float:
    """Journal fillet bending SCF beta_B = 2.7146 f_B(s,w) f_B(w) f_B(b) f_B(r) f_B(d_G) f_B(d_H) f(recess) (3.3)."""
    s, w, b, r, dg, dh = (rel[k] for k in ("s", "w", "b", "r", "dG", "dH"))
    u = 1.0 - s
    fsw = (
        -1.7625
        + 2.9821 * w
        - 1.5276 * w**2
        + u * (5.1169 - 5.8089 * w + 3.1391 * w**2)
        + u**2 * (-2.1567 + 2.3297 * w - 1.2952 * w**2)
    )
    fw = 2.2422 * w**0.7548
    fb = 0.5616 + 0.1197 * b + 0.1176 * b**2
    fr = 0.1908 * r ** (-0.5568)
    fdg = 1.0012 - 0.6441 * dg + 1.2265 * dg**2
    fdh = 1.0022 - 0.1903 * dh + 0.0073 * dh**2
    value: float = 2.7146 * fsw * fw * fb * fr * fdg * fdh * _recess(rel)
    return value


def beta_q(rel: dict[str, float]) -> float:
    """Journal fillet SCF for the radial (shear) force beta_Q = 3.0128 f_Q(s) f_Q(w) f_Q(b) f_Q(r) f_Q(d_H) f(recess) (3.3)."""
    s, w, b, r, dh = (rel[k] for k in ("s", "w", "b", "r", "dH"))
    u = 1.0 - s
    fs = 0.4368 + 2.1630 * u - 1.5212 * u**2
    fw = w / (0.0637 + 0.9369 * w)
    fb = -0.5 + b
    fr = 0.5331 * r ** (-0.2038)
    fdh = 0.9937 - 1.1949 * dh + 1.7373 * dh**2
    value: float = 3.0128 * fs * fw * fb * fr * fdh * _recess(rel)
    return value
