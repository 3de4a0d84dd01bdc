"""The torsional stage end to end: rigid limit, the journal torques handed to the
assessment, the flywheel speed fluctuation, and the CLI's JSON and pictures."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from fe_crank.cli import main
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.full_load import dynamics_at
from fe_crank.mechanism.torques import cylinder_torques
from fe_crank.torsion import analyse_torsion, with_vibratory_torque
from fe_crank.torsion.handover import journal_torques

ROOT = Path(__file__).resolve().parents[2]
CASE = ROOT / "loadcases" / "inline4_genset_torsion.toml"


@pytest.fixture(scope="module")
def case():
    return load_loadcase(CASE)


def rigid_settings(case):
    """Crank and flywheel joints 1e6 times stiffer, no damper/pulley/driven machine, no
    damping to ground (it would take torque from the rigid-body speed fluctuation)."""
    t = case.torsion
    fly = dataclasses.replace(t.flywheel, stiffness=1e12, inertia=10.0)
    return dataclasses.replace(
        t,
        damper=None,
        pulley=None,
        driven=(),
        flywheel=fly,
        speed_steps=11,
        cylinder_damping=0.0,
        assess_speed="operating",
        throw_stiffness="fe",
    )


def test_rigid_limit_gives_back_the_quasi_static_journal_torque(case):
    """Throws of negligible inertia on a rigid crank in front of a heavy flywheel: the
    synthesised segment torque is the cumulative cylinder torque (the statically
    determinate journal torque of the dynamics stage, UR M53 2.1), the vibratory part
    vanishes (relative 1e-6: throw inertia 1e-9 kg m^2 x (12 omega)^2 / k terms)."""
    throws = [t.name for t in case.engine.throws]
    res = analyse_torsion(
        case,
        cylinder_torques(case.engine, case.operating),
        settings=rigid_settings(case),
        inertias=dict.fromkeys(throws, 1e-09),
        fe_stiffness=1e12,
    )
    dyn = dynamics.analyse(case.engine, case.operating)
    new = with_vibratory_torque(dyn, res)
    for name, tl in dyn.throws.items():
        scale = np.abs(tl.torque_rear).max()
        assert np.abs(new.throws[name].torque_rear - tl.torque_rear).max() < 1e-6 * scale
        assert np.abs(new.throws[name].torque_front - tl.torque_front).max() < 1e-6 * scale
    # the flywheel speed fluctuation of the rigid train: Delta E / (J omega^2) of the
    # dynamics stage (orders <= 12 of the excess work; same within 2 %)
    j_total = 10.0 + 4e-9
    assert res.flywheel_fluctuation == pytest.approx(dyn.excess_energy / (j_total * dyn.speed**2), rel=0.02)


def test_journal_torques_with_vibration(case):
    """The shipped genset: the journal torques handed to the assessment keep the
    quasi-static mean and add a vibratory part; at the governing speed of each journal
    the total M_TN is the largest of the range."""
    res = analyse_torsion(
        case, cylinder_torques(case.engine, case.operating), inertias=dict.fromkeys(("1", "2", "3", "4"), 0.012)
    )
    dyn = dynamics.analyse(case.engine, case.operating)
    new = with_vibratory_torque(dyn, res)
    handed = journal_torques(res)
    for name in dyn.throws:
        # the mean of the history is the dynamics stage's at the speed it is taken at (that
        # speed's full-load diagram: an independent run)
        jt = handed[res.model.segment_names[res.journal_segments(name)[1]]]
        ref = dynamics_at(case.engine, case.operating, jt.speed).throws[name].torque_rear
        assert new.throws[name].torque_rear.mean() == pytest.approx(ref.mean(), rel=1e-9, abs=1e-6)
    seg = res.journal_segments("2")[1]
    g = res.governing(seg)
    assert res.half_range[g, seg] == pytest.approx(res.half_range[:, seg].max())
    # eigen and Holzer agree on every elastic mode below 1.5 x the highest
    np.testing.assert_allclose(res.holzer_hz, res.modes.frequencies_hz[1:], rtol=1e-8)


@pytest.mark.heavy
def test_cli_writes_json_and_pictures(tmp_path, capsys):
    out = tmp_path / "tv"
    assert main(["torsion", str(CASE), "-o", str(out)]) == 0
    data = json.loads((out / "torsion.json").read_text())
    assert len(data["natural_frequencies_hz"]) == 7
    assert set(data["vibratory_torque_vs_speed"]) == {
        "damper-pulley",
        "pulley-1",
        "1-2",
        "2-3",
        "3-4",
        "4-flywheel",
        "flywheel-generator",
    }
    assert len(data["speeds_rpm"]) == len(data["vibratory_torque_vs_speed"]["1-2"])
    assert data["mode_shapes"]["mode_1"][0] == pytest.approx(1.0) or max(map(abs, data["mode_shapes"]["mode_1"])) == 1
    for png in ("campbell.png", "torsion_response.png", "torsion_modes.png"):
        assert (out / png).stat().st_size > 5000
    assert "natural frequencies" in capsys.readouterr().out
