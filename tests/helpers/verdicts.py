"""Hand-built assessment results of two throws for the criteria and verdict tests."""

from __future__ import annotations

import math

from fe_crank.assess.counterweight import CounterweightCheck
from fe_crank.assess.group.assessment import Extreme, GroupResult
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.rules.m53.calculation import M53Fillet


def extreme(value, group, node, angle=None):
    return Extreme(value, group, node, (0.001 * node, 0.0, 0.002), angle)


def group_result(name, node, vm, vm_os, fat, gp):
    return GroupResult(
        group=name,
        n_nodes=3,
        max_von_mises=extreme(vm, name, node, math.radians(30)),
        max_von_mises_overspeed=extreme(vm_os, name, node, math.radians(60)),
        static_safety=650e6 / vm,
        overspeed_safety=650e6 / vm_os,
        fatigue_safety=None if fat is None else extreme(fat, name, node + 1),
        gough_pollard_safety=None if gp is None else extreme(gp, name, node + 2),
    )


def m53_fillet(name, q):
    return M53Fillet(name, "empirical (UR M53 3.2/3.3)", 1.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0, q)


def two_throws():
    # throw "1": fillet 100 MPa (static 6.5), fatigue 2.0, GP 2.5; counterweight 40 MPa
    # throw "2": fillet 130 MPa (static 5.0), fatigue 1.6, GP 3.0; junction 55 MPa, at overspeed 70
    t1 = ThrowAssessment(
        "1",
        (
            group_result("crankpin_fillet_1", 10, 100e6, 120e6, 2.0, 2.5),
            group_result("counterweight_1", 20, 40e6, 60e6, None, None),
        ),
        m53=(m53_fillet("pin", 1.4), m53_fillet("journal", 1.3)),
        counterweights=(CounterweightCheck("cw_a", 0.03, 0.031, 0.02, 5e3, 0.25),),
    )
    t2 = ThrowAssessment(
        "2",
        (
            group_result("journal_fillet_2", 30, 130e6, 140e6, 1.6, 3.0),
            group_result("junction_2", 40, 55e6, 70e6, None, None),
        ),
        m53=(m53_fillet("pin", 1.35), m53_fillet("oil_bore", 1.5)),
        counterweights=(
            CounterweightCheck("cw_b", 0.02, None, None, 8e3, 0.4),
            CounterweightCheck("cw_c", 0.02, 0.021, 0.05, None, None),
        ),
    )
    return (t1, t2)
