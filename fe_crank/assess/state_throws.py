"""Every throw of a load case in one load state (``assess_state``), for ``assess.case``:
the loads of the state (``assess.loads``), each rod at its place on the pin, the bolted
joints with the state's speed data.  ``places_of``: the rods' places of a throw;
``state_dynamics``: the dynamics stage's cycle of each load state; ``joint_speed``: what
the joints take of it."""

from __future__ import annotations

import numpy as np

from fe_crank.assess.group.extremes import Running, Wanted
from fe_crank.assess.inputs import AssessInputs
from fe_crank.assess.joint_loads import cycle_speed_data
from fe_crank.assess.loads import FIRING, LoadState, misfire_label
from fe_crank.assess.superpose import UnitStresses
from fe_crank.assess.throw import ThrowAssessment, ThrowContext, assess_throw
from fe_crank.fe.throw.pin_patches import rod_loads, rod_positions
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult
from fe_crank.rules.m53.basis import M53Basis
from fe_crank.throw_scope import throws_of


def places_of(a: AssessInputs, throw: str) -> dict[str, float]:
    """Each rod's place on the throw's pin (UR M53 2.1, ``fe.throw.pin_patches``); {} without a
    throw geometry (the summed force at mid-pin)."""
    tg = a.throw_geometry.get(throw)
    return rod_positions(a.engine, throw, tg.crankpin_length) if tg is not None else {}


def state_dynamics(a: AssessInputs) -> dict[tuple[float, str], DynamicsResult]:
    """(speed, case) of a load state (``LoadState.speed``, ``.case``) -> the dynamics
    stage's cycle of it: every speed of the sweep firing and with each misfire case, and
    the operating cycle (``cycle_dynamics`` of the case's cycles)."""
    return cycle_dynamics(a.cycles)


def cycle_dynamics(cycles: EngineCycles) -> dict[tuple[float, str], DynamicsResult]:
    """``state_dynamics`` of the engine's ``cycles`` (``mechanism.cycles.EngineCycles``)."""
    out = {(cycles.operating.speed, FIRING): cycles.operating}
    for sc in cycles.sweep:
        out[sc.speed, FIRING] = sc.firing
        out.update({(sc.speed, misfire_label(m.cylinder)): m.dynamics for m in sc.misfire})
    return out


def joint_speed(a: AssessInputs, dynamics: DynamicsResult, alpha: np.ndarray | None) -> tuple[float, float]:
    """(delta, max |alpha|) the bolted joints take in one load state: the cycle's speed
    fluctuation and rigid angular acceleration with the operating cycle's flywheel
    (``joint_loads.cycle_speed_data``), plus the largest torsional angular acceleration of the
    throw (``alpha``, None without [torsion]): the sum of the two maxima bounds the
    largest of their sum."""
    return speed_data(dynamics, a.cycles.operating.flywheel_inertia, alpha)


def speed_data(dynamics: DynamicsResult, flywheel_inertia: float, alpha: np.ndarray | None) -> tuple[float, float]:
    """``joint_speed`` of a cycle with the flywheel inertia ``flywheel_inertia`` (kg m^2)."""
    delta, rigid = cycle_speed_data(dynamics, flywheel_inertia)
    return delta, rigid + (float(max(abs(alpha))) if alpha is not None else 0.0)


def assess_state(
    a: AssessInputs,
    units: dict[int, UnitStresses],
    state: LoadState,
    senses: dict[str, int],
    basis: M53Basis,
    extremes: Wanted | None,
    cycles: dict[tuple[float, str], DynamicsResult] | None = None,
) -> tuple[ThrowAssessment, ...]:
    """Every throw in one load state: in full (``extremes`` None: the operating speed's
    firing state, with the overspeed cycles) or its extremes only.  Each rod bears at its
    place on the pin (UR M53 2.1, ``fe.throw.pin_patches``); without a throw geometry, the
    summed force at mid-pin.  ``cycles``: ``state_dynamics`` when the bolted joints are
    checked (with the state's cycle, ``joint_speed``); None: not checked."""
    dynamics = None
    if cycles is not None:
        dynamics = cycles.get((state.speed, state.case))
        if dynamics is None:
            raise ValueError(f"no dynamics cycle of the load state {state.case} at {state.speed:.6g} rad/s")
    running = Running()  # the state's least fatigue values so far (extremes only)
    out = []
    for key, unit_solutions in a.unit_solutions.items():
        unit = units[id(unit_solutions)]
        for tname in throws_of(key, a.dynamics.throws):
            tc = state.throws[tname]
            throw = a.engine.throw(tname)
            tg = a.throw_geometry.get(tname)
            places = places_of(a, tname)
            overspeed_loads = [
                (s.throws[tname].pin_force, s.throws[tname].torque_in, rod_loads(s.throws[tname], places))
                for s in a.loads.overspeed
            ]
            out.append(
                assess_throw(
                    ThrowContext(
                        tname,
                        unit,
                        state.theta,
                        tc.pin_force,
                        tc.torque_in,
                        omega=state.speed,
                        sense=senses[tname],
                        overspeed=a.operating.overspeed,
                        material=a.material,
                        crank_radius=throw.crank_radius,
                        m53_geometry=tg.m53 if tg is not None else None,
                        m53_additional=basis.additional,
                        m53_ke=basis.ke,
                        counterweights=tg.counterweights if tg is not None else (),
                        torque_rear=tc.torque_out,
                        overspeed_loads=overspeed_loads or None,
                        scf=a.scf.get(key),
                        angular_acceleration=tc.angular_acceleration,
                        fe_pin_force=tc.fe_pin_force,
                        m53_torques=a.loads.m53_torques.get(tname, ()),
                        extremes=extremes,
                        running=running,
                        rod_loads=rod_loads(tc, places),
                        fe_rod_loads=tc.fe_rod_loads(places) if tc.fe_rods else None,
                        joint_speed=None if dynamics is None else joint_speed(a, dynamics, tc.angular_acceleration),
                        geometry_file=a.geometry_file or a.source_file,
                    )
                )
            )
    return tuple(out)


__all__ = ["places_of", "state_dynamics", "cycle_dynamics", "joint_speed", "speed_data", "assess_state"]
