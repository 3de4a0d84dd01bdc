"""The hand-checked VDI 2230 example joint (one radial M12 10.9 bolt, tests/assess/test_assess_cw_joint.py) and its counterweight loads."""

from __future__ import annotations

import math

from fe_crank.assess.joint_loads import counterweight_loads
from fe_crank.geometry.spec import BoltedJoint

JOINT = BoltedJoint(
    count=1,
    diameter=0.012,
    pitch_radius=0.06,
    property_class="10.9",
    clamp_length=0.030,
    bearing_diameter=0.017,
    hole_diameter=0.013,
    clamped_diameter=0.030,
    tightening_factor=1.6,
)


W = 3000 * math.pi / 30


W_OS = 3600 * math.pi / 30


def joint_loads(joint=JOINT):
    return counterweight_loads(
        2.0,
        0.06,
        joint.count,
        joint.direction,
        omega=W,
        overspeed=W_OS,
        speed_fluctuation=0.02,
        angular_acceleration=1000.0,
    )
