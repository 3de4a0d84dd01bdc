"""The throw with an oil bore and the 720-deg cycle of the UR M53 oil-bore hand calculations (tests/assess/test_assess_m53_oil_bore.py): F_R = 20 kN cos(theta), F_T = 5 kN sin(theta), torque 500 N m sin(theta)."""

from __future__ import annotations

import math

import numpy as np

from fe_crank.rules.m53 import calculation as m53

GEO = m53.M53Geometry(
    pin_diameter=0.050,
    journal_diameter=0.060,
    crank_radius=0.064,
    web_thickness=0.020,
    web_width=0.080,
    pin_fillet_radius=0.004,
    journal_fillet_radius=0.004,
    bearing_to_web=0.030,
    pin_length=0.040,
    oil_bore_diameter=0.006,
    oil_bore_angle=math.radians(30.0),
)


TH = np.deg2rad(np.arange(720.0))


PIN = np.column_stack([5e3 * np.sin(TH), 20e3 * np.cos(TH)])


TQ = 500.0 * np.sin(TH)
