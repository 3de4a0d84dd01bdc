"""A main bearing's oil film as the geometry file states it, and the oil's viscosity law.

``FilmSpec`` is plain data (SI) for ``fe_crank.fe.oil_film``: the bearing's diameter
(None: the journal's), its radial clearance, the oil's dynamic viscosity, the groove
(``"none"`` or ``"full"``: a full circumferential groove of ``groove_width`` at the
bearing's middle).  The bearing's width is the main bearing's own (``MainBearing.width``).

The viscosity is stated directly, or from the oil's kinematic viscosities at 40 and
100 degC (its data sheet), its density and the film temperature by Walther's equation as
ASTM D341 writes it (the standard viscosity-temperature relation of petroleum oils):

    log10(log10(nu + 0.7)) = A - B log10(T),   nu in mm^2/s (cSt), T in K,

A and B fitted through the two stated points; eta = rho nu.  The film is isoviscous: one
temperature for the whole film and cycle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: ASTM D341's shift of the kinematic viscosity in Walther's equation, mm^2/s
WALTHER_SHIFT = 0.7
T40 = 313.15  # K
T100 = 373.15  # K


@dataclass(frozen=True)
class FilmSpec:
    clearance: float  # m, radial
    viscosity: float  # Pa s, dynamic, at the film temperature
    groove: str = "none"  # "none" | "full"
    groove_width: float = 0.0  # m, "full" only
    diameter: float | None = None  # m; None: the journal's diameter
    oil: str = ""  # how the viscosity was found, for the report


def walther_viscosity(nu40: float, nu100: float, density: float, temperature: float) -> float:
    """Dynamic viscosity (Pa s) at ``temperature`` (K) of an oil of kinematic viscosity
    ``nu40`` at 40 degC and ``nu100`` at 100 degC (m^2/s) and ``density`` (kg/m^3), by
    Walther's equation (ASTM D341, module doc)."""
    w40 = math.log10(math.log10(nu40 * 1e6 + WALTHER_SHIFT))
    w100 = math.log10(math.log10(nu100 * 1e6 + WALTHER_SHIFT))
    b = (w40 - w100) / (math.log10(T100) - math.log10(T40))
    a = w40 + b * math.log10(T40)
    nu = 10.0 ** (10.0 ** (a - b * math.log10(temperature))) - WALTHER_SHIFT  # mm^2/s
    return density * nu * 1e-6
