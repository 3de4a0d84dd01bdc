"""The small single-cylinder case over its full-load curve (``{sweep}`` takes the speeds' key)."""

from __future__ import annotations

from helpers.cad_files import SMALL_ENGINE

SWEPT = (
    """\
name = "small single over its full-load curve"
geometry = "geometry_small.toml"

[operating]
speed = "3000 rpm"
overspeed = "3600 rpm"
{sweep}
misfire = "each"
"""
    + SMALL_ENGINE.format(radius="20 mm")
    + """
[engine.gas]
model = "wiebe"
compression_ratio = 9.0
intake_pressure = "0.1 MPa"
exhaust_pressure = "0.11 MPa"
heat_released = "0.25 kJ"
combustion_start = "-15 deg"
combustion_duration = "50 deg"

[material]
name = "42CrMo4"

[criteria]
min_static_safety = 1.5
min_fatigue_safety = 1.3
min_gough_pollard_safety = 1.3
min_overspeed_safety = 1.5
"""
)
