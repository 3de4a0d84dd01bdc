"""UR M53's nominal moments rod by rod: each rod's bending-moment triangle at its own place.

IACS UR M53 2.1 (2.1.1, its figure of the statically determinate throw): the throw is a
beam simply supported at the main-bearing centres; with several rods on one crankpin
(V engines) the bending moments of each rod's force, at its own axial place and with its
own phase over the cycle, are superposed.  Span S = 2 (a + W/2 + L_pin/2) between the
bearing centres (a = ``bearing_to_web``: bearing centre to web centre), the pin's middle at
S/2; a rod at e (from the pin's middle, + to the rear web) with radial force F_R:

    reactions R_1 = F_R (1/2 - e/S) (front), R_2 = F_R (1/2 + e/S) (rear),
    web-centre moments M_1 = a R_1, M_2 = a R_2, web shear forces Q = R.

Summed over the rods, the half range over the cycle of each web's moment is its M_BRFN
(2.1.2.1); the web with the larger one governs both fillets of the throw (the same web
carries the larger shear force, Q = M/a).  With every rod at e = 0 this is the summed force
at mid-pin, M = (F_R/2) a.  The oil bore at the pin's middle (2.1.2.2) takes the moment there,
M(S/2) = R_1 S/2 - sum over rods in front (e < 0) of F (-e), for the radial and the
tangential forces alike.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from fe_crank.rules.m53.calculation import M53Geometry, NominalStresses, RodLoads, half_range, nominal_stresses


def span(geo: M53Geometry) -> float:
    """S = 2 (a + W/2 + L_pin/2): main-bearing centre to main-bearing centre."""
    return 2.0 * (geo.bearing_to_web + 0.5 * geo.web_thickness + 0.5 * geo.pin_length)


def web_reactions(geo: M53Geometry, rod_loads: RodLoads, component: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Support reactions (R_1, R_2) (n,) of the rods' forces' ``component`` (1 radial, 0
    tangential); ``rod_loads``: (force (n, 2), place e m) per rod."""
    s = span(geo)
    r1 = sum(np.asarray(f, float)[:, component] * (0.5 - e / s) for f, e in rod_loads)
    r2 = sum(np.asarray(f, float)[:, component] * (0.5 + e / s) for f, e in rod_loads)
    return np.asarray(r1, float), np.asarray(r2, float)


def nominal_stresses_by_rod(
    geo: M53Geometry, rod_loads: RodLoads, torque: ArrayLike, *, ke: float = 1.0
) -> tuple[NominalStresses, int]:
    """UR M53 nominal stresses of the web with the larger alternating moment (and which: 1
    front, 2 rear) from each rod's force at its place; torsion as ``m53.nominal_stresses``."""
    r1, r2 = web_reactions(geo, rod_loads)
    web, r = (1, r1) if half_range(r1) >= half_range(r2) else (2, r2)
    # M = a R and Q = R of that web: m53.nominal_stresses takes F_R = 2 R (its (F_R/2) a)
    return nominal_stresses(geo, 2.0 * r, torque, ke=ke), web


def moment_at_pin_middle(geo: M53Geometry, rod_loads: RodLoads) -> np.ndarray:
    """(n, 2) bending moments (about the tangential and the radial direction's axes: the
    tangential and the radial forces' moments) at the pin's middle: R_1 S/2 minus the
    moments of the rods in front of it, sum_{e < 0} F (-e)."""
    s = span(geo)
    out = []
    for comp in (0, 1):
        r1, _ = web_reactions(geo, rod_loads, comp)
        m = r1 * 0.5 * s
        for f, e in rod_loads:
            if e < 0:
                m = m - np.asarray(f, float)[:, comp] * (-e)
        out.append(m)
    return np.column_stack(out)


__all__ = ["span", "web_reactions", "nominal_stresses_by_rod", "moment_at_pin_middle"]
