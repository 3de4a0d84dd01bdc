"""Gas-pressure input: a p(phi) table inline, or a CSV file beside the input file.

Units are explicit: the table states its angle and pressure units
(``angle_unit = "deg"``, ``pressure_unit = "MPa"``); a CSV states them in its
header (``angle [deg], pressure [MPa]``).  Pressures are absolute.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from fe_crank.io.base import Strict
from fe_crank.io.units import Pressure, ureg


class GasTableInput(Strict):
    model: Literal["table"] = "table"
    angle_unit: str = Field(description="unit of the first column, e.g. 'deg'")
    pressure_unit: str = Field(description="unit of the second column, e.g. 'MPa' (absolute)")
    points: list[tuple[float, float]] = Field(min_length=2)
    crankcase_pressure: Pressure = 101325.0
    source: str = ""

    @model_validator(mode="after")
    def _check(self):
        try:
            a = ureg.Quantity(1.0, self.angle_unit)
        except Exception:
            raise ValueError(f"angle_unit {self.angle_unit!r} is not a unit") from None
        if not a.dimensionless:
            raise ValueError(f"angle_unit {self.angle_unit!r} is not an angle unit (deg or rad)")
        try:
            p = ureg.Quantity(1.0, self.pressure_unit)
        except Exception:
            raise ValueError(f"pressure_unit {self.pressure_unit!r} is not a unit") from None
        if not p.check("[pressure]"):
            raise ValueError(f"pressure_unit {self.pressure_unit!r} is not a pressure unit (Pa, kPa, MPa, bar)")
        ang = np.array([pt[0] for pt in self.points])
        if np.any(np.diff(ang) <= 0):
            raise ValueError("points: angles must increase strictly")
        if any(pt[1] < 0 for pt in self.points):
            raise ValueError("points: absolute pressure cannot be negative")
        return self

    def arrays_si(self) -> tuple[np.ndarray, np.ndarray]:
        ang = np.array([pt[0] for pt in self.points], dtype=float)
        prs = np.array([pt[1] for pt in self.points], dtype=float)
        ang = ureg.Quantity(ang, self.angle_unit).to("rad").magnitude
        prs = ureg.Quantity(prs, self.pressure_unit).to("Pa").magnitude
        return np.asarray(ang, float), np.asarray(prs, float)
