"""IACS UR M53: the outlet of the crankpin oil bore.

Checked against the rule text as public class rules reproduce it clause by clause (Korean
Register, Rules for the Classification of Steel Ships, Pt 5, Annex 5-3 "Guidance for
calculation of crankshaft stress", 2025 edition, which follows UR M53's numbering);
every formula and coefficient below agrees with that text.  UR M53 clauses:

* 2.1.1.2 / 2.1.2.2, nominal alternating bending stress at the outlet:
  sigma_BON = M_BON / W_e, W_e = pi/32 (D^4 - D_BH^4)/D, M_BON the half range over the
  cycle of the bending moment in the crankpin section through the oil bore, in the plane
  of the outlet: M_BO = M_BTO cos(psi) + M_BRO sin(psi), psi the angular position of the
  bore (2.1.2.2, its Fig. "crankpin section through the oil bore"), measured from the
  tangential direction.  With ``OilBore.angle`` a measured from the radial (+y) towards
  the tangential (+x) direction, sin(psi) = cos(a) and cos(psi) = sin(a).  No K_e here:
  2.1.2.1's K_e multiplies the web's nominal stresses only.  Statically determinate
  throw (2.1.1; supports at the main-bearing centres, the pin at mid-span):
  M_BRO = (F_R/2) L/2, M_BTO = (F_T/2) L/2, L/2 = bearing centre to pin centre
  = a_web + W/2 + L_pin/2.
* 2.1.4: sigma_BO = gamma_B sigma_BON;  2.2.3: sigma_TO = gamma_T tau_N (tau_N of the
  axially bored crankpin, 2.2.2; the rule writes the outlet's torsional term as a normal
  stress, the largest principal stress, hence sigma_TO; here ``tau_TO``).
* 3.1, definitions: gamma_B, gamma_T are the ratio of the largest principal stress at the
  outlet to the nominal stress of the bored crankpin section (ESDU data, radially
  drilled holes only); related dimension d_O = D_O/D, valid for 0 <= d_O <= 0.2.
* 3.4, stress concentration factors:
  gamma_B = 3 - 5.88 d_O + 34.6 d_O^2,  gamma_T = 4 - 6 d_O + 30 d_O^2.
* 5.1 / 5.2, equivalent alternating stress at the outlet (the largest principal stress
  of bending and torsion taken in phase):
  sigma_V = sigma_BO/3 [1 + 2 sqrt(1 + 9/4 (sigma_TO/sigma_BO)^2)]
          = sigma_BO/3 + 2/3 sqrt(sigma_BO^2 + 9/4 sigma_TO^2)   (no sigma_add: 4 is for fillets).
* 6, fatigue strength with R_X = D_O/2 (not below 2 mm); "values of K greater than 1 are
  only applicable to the fatigue strength in the fillet area", so the outlet uses min(K, 1).
* 7, acceptability Q = sigma_DW / sigma_V.

No published worked example of the outlet was found; the test checks a hand calculation.

Outside 0 <= d_O <= 0.2 the empirical factors do not apply and UR M53 Appendix III
(FE) does not cover oil bores (its 1.1.5): the outlet is then assessed by the FE route
only (the ``oil_bore`` surface group), and the result says so.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from fe_crank.rules.m53.calculation import (
    M53Fillet,
    M53Geometry,
    NominalStresses,
    RodLoads,
    fatigue_strength,
    half_range,
)
from fe_crank.rules.m53.rods import moment_at_pin_middle

#: d_O = D_O/D range of UR M53 3.1
D_O_RANGE = (0.0, 0.2)
SOURCE = "empirical, UR M53 3.4 (oil-bore outlet)"


def gamma_b(d_o: float) -> float:
    """gamma_B = 3 - 5.88 d_O + 34.6 d_O^2, d_O = D_O/D (UR M53 3.4; d_O of 3.1)."""
    return 3.0 - 5.88 * d_o + 34.6 * d_o**2


def gamma_t(d_o: float) -> float:
    """gamma_T = 4 - 6 d_O + 30 d_O^2, d_O = D_O/D (UR M53 3.4; d_O of 3.1)."""
    return 4.0 - 6.0 * d_o + 30.0 * d_o**2


def in_range(geo: M53Geometry) -> str | None:
    """None if d_O is inside UR M53 3.4's range, else a readable reason."""
    d_o = geo.oil_bore_diameter / geo.pin_diameter
    lo, hi = D_O_RANGE
    if lo <= d_o <= hi + 1e-12:
        return None
    return f"d_O = D_O/D = {d_o:.4g} not in [{lo}, {hi}] (UR M53 3.1)"


def nominal_bending(geo: M53Geometry, pin_force: ArrayLike, rod_loads: RodLoads | None = None) -> float:
    """sigma_BON [Pa]: half range of M_BO / W_e over the cycle (UR M53 2.1.2.2, no K_e).

    ``pin_force`` (n, 2): (tangential, radial) force on the crankpin in the throw frame, at
    the pin's middle; ``rod_loads`` ((force (n, 2), place m) per rod): each rod at its own
    place instead (``m53_rods.moment_at_pin_middle``, 2.1)."""
    a = geo.oil_bore_angle
    if rod_loads is not None:
        m = moment_at_pin_middle(geo, rod_loads)
        m_bo = m[:, 1] * math.cos(a) + m[:, 0] * math.sin(a)
    else:
        f = np.asarray(pin_force, float)
        arm = geo.bearing_to_web + 0.5 * geo.web_thickness + 0.5 * geo.pin_length  # L/2
        m_bo = 0.5 * arm * (f[:, 1] * math.cos(a) + f[:, 0] * math.sin(a))
    w_e = math.pi / 32.0 * (geo.pin_diameter**4 - geo.pin_bore**4) / geo.pin_diameter
    return half_range(m_bo) / w_e


def equivalent_stress(bending: float, torsion: float) -> float:
    """sigma_V = sigma_BO/3 [1 + 2 sqrt(1 + 9/4 (sigma_TO/sigma_BO)^2)]
    = sigma_BO/3 + 2/3 sqrt(sigma_BO^2 + 9/4 sigma_TO^2) (UR M53 5.2, outlet of the oil bore)."""
    b = abs(bending)
    return b / 3.0 + 2.0 / 3.0 * math.sqrt(b**2 + 2.25 * torsion**2)


def assess_outlet(
    geo: M53Geometry,
    nominal: NominalStresses,
    pin_force: ArrayLike,
    *,
    tensile: float,
    k: float,
    rod_loads: RodLoads | None = None,
) -> M53Fillet | None:
    """UR M53 result at the oil-bore outlet (``fillet`` = "oil_bore"), or None when the
    geometry has no oil bore or d_O is outside 3.4's range (see ``in_range``)."""
    if geo.oil_bore_diameter <= 0 or in_range(geo) is not None:
        return None
    d_o = geo.oil_bore_diameter / geo.pin_diameter
    gb, gt = gamma_b(d_o), gamma_t(d_o)
    s_bo = gb * nominal_bending(geo, pin_force, rod_loads)
    t_to = gt * nominal.torsion_pin
    sv = equivalent_stress(s_bo, t_to)
    sdw = fatigue_strength(tensile, geo.pin_diameter, 0.5 * geo.oil_bore_diameter, min(k, 1.0))
    return M53Fillet("oil_bore", SOURCE, gb, 0.0, gt, s_bo, t_to, sv, sdw, sdw / sv if sv > 0 else math.inf, ())


__all__ = ["D_O_RANGE", "gamma_b", "gamma_t", "in_range", "nominal_bending", "equivalent_stress", "assess_outlet"]


def where(fillet: str) -> str:
    """Readable location of an M53 result: "pin fillet", "journal fillet", "oil-bore outlet"."""
    return "oil-bore outlet" if fillet == "oil_bore" else f"{fillet} fillet"
