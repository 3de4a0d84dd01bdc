"""FE stage: the [fe] load-case section (units at the edge, strict keys)."""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.errors import InputError
from fe_crank.fe.input import parse_fe
from fe_crank.fe.throw.unit_cases import FeOptions


def test_fe_section_parses_units_to_si():
    opt = parse_fe(
        {
            "support": "foundation",
            "bearing_stiffness": "5e3 N/mm^3",
            "pin_half_angle": "45 deg",
            "solver": "superlu",
            "torque_reaction": "end_1",
        },
        "case.toml",
    )
    assert opt.support == "foundation" and opt.torque_reaction == "end_1" and opt.torque_face == "end_2"
    assert isinstance(opt, FeOptions)
    assert opt.bearing_stiffness == pytest.approx(5e12)
    assert opt.pin_half_angle == pytest.approx(np.pi / 4)
    assert opt.solver == "superlu"


def test_fe_section_defaults():
    assert parse_fe({}, "case.toml") == FeOptions()
    opt = FeOptions()
    assert opt.support == "determinate" and opt.torque_reaction == "end_2" and opt.bearing_stiffness is None
    four = ("centrifugal", "pin_x", "pin_y", "pin_-x", "pin_-y", "torque")  # the first design's set
    assert parse_fe({"cases": list(four)}, "case.toml").cases == four


@pytest.mark.parametrize(
    "value, match",
    [
        ({"bearing_stiffnes": "1e12 N/m^3"}, "fe.bearing_stiffnes: unknown key"),
        ({"bearing_stiffness": 1e12}, "fe.bearing_stiffness"),
        ({"bearing_stiffness": "1e12 Pa"}, "fe.bearing_stiffness"),
        ({"solver": "mumps"}, "fe.solver"),
        ({"cases": ["gravity"]}, "unknown unit cases"),
        ({"support": "determinate", "bearing_stiffness": "1e12 N/m^3"}, "applies to support"),
        ({"bearing_stiffness": "1e12 N/m^3"}, "applies to support"),
        ({"support": "foundation"}, "needs bearing_stiffness"),
        ({"support": "elastic"}, "fe.support: support = 'elastic' is no longer offered"),
        ({"support": "rigid"}, "fe.support: support = 'rigid' is no longer offered"),
        ({"support": "clamped"}, "fe.support"),
        ({"torque_reaction": "flywheel"}, "fe.torque_reaction"),
        ({"cases": ["centrifugal", "pin_y", "torque"]}, "cannot carry a crankpin force in every direction"),
        ({"cases": ["centrifugal", "pin_x", "pin_y", "pin_-y", "torque"]}, "gap of 180"),
        ({"cases": ["pin_x", "pin_y", "pin_-x", "pin_-y", "torque"]}, "needs the unit cases"),
    ],
)
def test_fe_section_errors_name_file_and_key(value, match):
    with pytest.raises(InputError, match=match) as exc:
        parse_fe(value, "case.toml")
    assert "case.toml" in str(exc.value)
