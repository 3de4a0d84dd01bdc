"""The check over the full-load curve with torsional vibration and misfire: the FE
model of each throw in equilibrium with the torque flow at every speed and misfire case,
UR M53's torsion the largest M_TN of every case, and each speed's values those of
single-speed checks of the same torsional case (two throws)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles

DATA = Path(__file__).resolve().parents[1] / "data"


def _torsion_case(folder: Path, speed: str, sweep: str) -> Path:
    """tests/data/small_torsion.toml at ``speed`` with each cylinder misfiring, fatigue
    criteria and the full-load keys ``sweep``."""
    text = (DATA / "small_torsion.toml").read_text()
    text = text.replace('speed = "3000 rpm"\n', f'speed = "{speed}"\n{sweep}misfire = "each"\n')
    text = text.replace("min_static_safety = 1.5\n", "min_static_safety = 1.5\nmin_fatigue_safety = 1.0\n")
    text = text.replace("min_fatigue_safety = 1.0\n", "min_fatigue_safety = 1.0\nmin_gough_pollard_safety = 1.0\n")
    (folder / "geometry_small.toml").write_text((DATA / "geometry_small.toml").read_text())
    p = folder / f"torsion_{speed.split()[0]}.toml"
    p.write_text(text)
    return p


@pytest.fixture(scope="module")
def torsion_swept(tmp_path_factory, mesh_cache):
    from helpers.per_throw import per_throw_outputs

    folder = tmp_path_factory.mktemp("torsion_sweep")
    p = _torsion_case(folder, "3000 rpm", 'speeds = ["1500 rpm", "2400 rpm"]\n')
    # what is asserted is the per-throw model's assessment: the twin's whole shaft is not
    # solved, no fields are drawn
    return folder, per_throw_outputs(p, mesh_cache)


@pytest.mark.heavy
def test_fe_throw_carries_the_torque_flow_at_every_speed_and_misfire(torsion_swept):
    """tests/data/small_torsion.toml over a full-load curve with each cylinder misfiring,
    through the check's stages: at every speed and in every state the torque the FE
    model of each throw reacts at its rear face (the superposed unit cases' reactions)
    equals the torque flow leaving that throw, vibration included, at every angle; and
    UR M53's torsional stress of each throw is that of the largest M_TN of its journals
    over the speed range and all cases."""
    _, out = torsion_swept
    loads = out.torsion.loads
    assert loads.torsion and len(loads.speeds) == 3 and all(len(s) == 3 for s in loads.speeds)
    from fe_crank.assess.superpose import load_coefficients

    units = next(iter(out.fe.unit_solutions.values()))
    cases = tuple(units.cases)
    assert "angular_acceleration" in cases
    mz = np.array([units.cases[k].reactions["end_2"][5] for k in cases])
    for states in loads.speeds:
        for state in states:
            for tc in state.throws.values():
                c = load_coefficients(
                    tc.fe_pin,
                    tc.torque_in,
                    state.speed,
                    cases=cases,
                    torque_mz=float(units.cases["torque"].applied[5]),
                    angular_acceleration=tc.angular_acceleration,
                )
                reacted = c @ mz
                # to the unit cases' equilibrium (1e-6) of the largest torque through the throw
                scale = max(np.abs(tc.torque_out).max(), np.abs(tc.torque_in).max(), 0.020 * np.abs(tc.fe_pin).max())
                np.testing.assert_allclose(reacted, tc.torque_out, rtol=0, atol=1e-6 * scale)
    mis = out.torsion.misfire
    assert mis is not None and [c.cylinder for c in mis.cases] == ["1", "2"]
    wp = math.pi / 16 * 0.032**3
    res = mis.firing
    names = res.model.segment_names
    for t in out.assessment.throws:
        front, rear = res.journal_segments(t.name)
        segs = [names[i] for i in (front, rear) if 0 <= i < len(names)]
        largest = max(mis.governing(s).m_tn for s in segs)
        assert t.m53_nominal.torsion_journal * wp >= largest * (1 - 1e-9)


@pytest.mark.heavy
def test_torsional_sweep_values_are_those_of_single_speed_checks(torsion_swept):
    """Two throws with torsional vibration and misfire: each speed's static, Goodman and
    Gough-Pollard values of the per-throw model (the least over both throws, all their
    groups and all three states, searched with the pruning across groups and throws) equal
    the per-throw model's check of the same case at that speed alone, every node evaluated
    (its own torsional stage on the same FE solution).  (The whole shaft's states are
    checked likewise in ``test_shaft_check``.)"""
    from fe_crank.assess.criteria.judge import evaluate_criteria
    from fe_crank.pipeline.stages import assess_stage, torsion_stage

    folder, out = torsion_swept
    a = out.assessment
    per_throw = evaluate_criteria(out.loadcase.criteria, a.throws, overspeed=a.overspeed, sweep=a.sweep)
    crit = {c.name: c for c in per_throw}
    for rpm in (1500, 2400, 3000):
        lc = load_loadcase(_torsion_case(folder, f"{rpm} rpm", ""))
        cycles = engine_cycles(lc.engine, lc.operating)
        tors = torsion_stage(lc, out.geometry, out.fe.unit_solutions, cycles)
        single = dataclasses.replace(out, loadcase=lc, cycles=cycles, torsion=tors, whole_shaft=None)
        got = {c.name: c for c in assess_stage(lc, single, False).criteria}
        for name in ("criteria.min_static_safety", "criteria.min_fatigue_safety", "criteria.min_gough_pollard_safety"):
            (p,) = [x for x in crit[name].per_speed if round(x.speed_rpm) == rpm]
            assert p.value == pytest.approx(got[name].value, rel=1e-9), (name, rpm)
