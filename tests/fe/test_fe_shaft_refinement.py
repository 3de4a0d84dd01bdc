"""The whole shaft's load sets of the hot-spot convergence study (``fe.shaft.refinement``):
its pattern coefficients as the loads inside a zone.  The study of the whole shaft's own
states inside the check: tests/pipeline/test_pipeline_shaft.py."""

from __future__ import annotations

import numpy as np

from fe_crank.fe.shaft.refinement import zone_loads


def test_zone_loads_maps_the_shaft_patterns_to_the_zone_cases():
    """Pin patterns as themselves, the spin-up as the angular acceleration (the same body
    force rho (-y, x, 0)), the throw's and its counterweights' centrifugal force as the
    whole throw's when their coefficients agree, as the parts otherwise; the bearing
    surfaces' and end faces' patterns (driven faces) left out."""
    names = ("pin_x", "pin_030", "centrifugal", "centrifugal_cw", "spin_up", "journal_1.P0", "torque_end_2")
    got = zone_loads(names, np.array([2.0, 0.0, 5.0, 5.0, -3.0, 7.0, 11.0]))
    assert got == {"pin_x": 2.0, "angular_acceleration": -3.0, "centrifugal": 5.0}
    got = zone_loads(names, np.array([2.0, 0.0, 5.0, 0.0, 0.0, 7.0, 11.0]))
    assert got == {"pin_x": 2.0, "centrifugal_throw": 5.0}
    got = zone_loads(names, np.array([0.0, 1.0, 5.0, 4.0, 0.0, 0.0, 0.0]))
    assert got == {"pin_030": 1.0, "centrifugal_throw": 5.0, "centrifugal_cw_1": 4.0, "centrifugal_cw_2": 4.0}
