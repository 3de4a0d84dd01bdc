"""The dynamics stage's cylinder torques for the torsional stage: at any speed of the range,
for every cylinder firing and each misfire case, they are the torques of the exact
slider-crank run directly at that speed with that speed's interpolated diagram."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank import model
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.mechanism.misfire import motored_gas
from fe_crank.mechanism.torques import engine_torques

ROOT = Path(__file__).resolve().parents[2]
RPM = np.pi / 30


@pytest.fixture(scope="module")
def engine():
    return load_loadcase(ROOT / "loadcases" / "inline4_genset_torsion.toml").engine


def curve_of(engine, speeds_rpm):
    """Two diagrams: the engine's at 1000 rpm, 1.4 times its gauge pressure at 3000 rpm."""
    gas = engine.gas
    hot = dataclasses.replace(gas, pressure=gas.crankcase_pressure + 1.4 * (gas.pressure - gas.crankcase_pressure))
    return model.FullLoadCurve(
        tuple(r * RPM for r in speeds_rpm), (1000 * RPM, 3000 * RPM), (gas, hot), engine.gas, engine.cycle_angle
    )


def test_torques_at_any_speed_are_the_dynamics_run_at_that_speed(engine):
    """omega^2 scaling of the inertia torque and linear interpolation of the gas torque
    between the diagrams are exact: against independent runs at 1000, 1700, 2600 and
    3000 rpm, every cylinder firing and cylinder 3 motored in its speed's diagram."""
    curve = curve_of(engine, (1000, 2000, 3000))
    op = model.OperatingPoint(2000 * RPM, full_load=curve, misfire=("3",))
    torques = engine_torques(engine, op)
    assert [t.misfire for t in torques] == ["", "3"]
    for rpm in (1000.0, 1700.0, 2600.0, 3000.0):
        w = rpm * RPM
        diagram = curve.gas_at(w)
        for t in torques:
            own = {t.misfire: motored_gas(diagram)[0]} if t.misfire else None
            ref = dynamics.analyse(dataclasses.replace(engine, gas=diagram), model.OperatingPoint(w), cylinder_gas=own)
            got = t.at(w)
            for name, cf in ref.cylinders.items():
                scale = np.abs(cf.torque).max()
                np.testing.assert_allclose(got[name], cf.torque, rtol=0, atol=1e-9 * scale)


def test_engine_cycles_carry_the_torques_of_each_state(engine):
    """The dynamics stage's EngineCycles hold the torques with every cylinder firing and
    each misfire case; at a speed of the sweep they equal its cycles there (the engine's
    gas the diagram at the operating speed, as the load case gives it)."""
    curve = curve_of(engine, (1000, 2000, 3000))
    op = model.OperatingPoint(2000 * RPM, full_load=curve, misfire=("1", "4"))
    engine = dataclasses.replace(engine, gas=curve.gas_at(op.speed))
    cycles = engine_cycles(engine, op)
    assert cycles.firing_torques.misfire == "" and [t.misfire for t in cycles.misfire_torques] == ["1", "4"]
    for sc in cycles.sweep:
        states = [(cycles.firing_torques, sc.firing)]
        states += [(t, m.dynamics) for t, m in zip(cycles.misfire_torques, sc.misfire, strict=True)]
        for t, dyn in states:
            got = t.at(sc.speed)
            for name, cf in dyn.cylinders.items():
                np.testing.assert_allclose(got[name], cf.torque, rtol=0, atol=1e-9 * np.abs(cf.torque).max())


def test_speed_outside_the_diagrams_is_refused(engine):
    curve = curve_of(engine, (1000, 3000))
    t = engine_torques(engine, model.OperatingPoint(2000 * RPM, full_load=curve))[0]
    with pytest.raises(ValueError, match="never extrapolated"):
        t.at(900 * RPM)
