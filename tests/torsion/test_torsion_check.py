"""The torsional stage inside `fe-crank check`: the journal torques of the assessment carry
the vibratory torque, the report has the section and torsion.json; a case without
[torsion] says it is quasi-static."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from fe_crank.cli import main
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.torques import cylinder_torques
from fe_crank.outputs import CaseOutputs
from fe_crank.report.sections import torsion_section
from fe_crank.torsion.analysis import analyse_torsion, with_vibratory_torque

DATA = Path(__file__).resolve().parents[1] / "data"
CASE = DATA / "small_torsion.toml"


def test_report_says_quasi_static_without_a_torsion_section(tmp_path):
    lc = load_loadcase(DATA / "small_pass.toml")
    parts = torsion_section(tmp_path, CaseOutputs(loadcase=lc), None)
    assert "no [torsion] section" in parts[0] and "quasi-static" in parts[0]
    assert lc.torsion is None


@pytest.mark.heavy
def test_check_uses_quasi_static_plus_vibratory_journal_torque(tmp_path, mesh_cache):
    """UR M53 tau_N of the journal = M_TN / W_P with M_TN the half range of the journal
    torque that the check handed to the assessment; here recomputed from the torsional
    stage directly (independent of the assessment code): the larger of the two
    journals of throw 1, quasi-static + vibratory at the governing speed."""
    out = tmp_path / "reports"
    code = main(
        [
            "check",
            str(CASE),
            "-o",
            str(out),
            "--mesh-size",
            "test",
            "--cache-dir",
            str(mesh_cache),  # the run's: the small twin's throw is meshed by other tests too
            "--no-render",
            "--no-vtu",
        ]
    )
    assert code in (0, 1)
    folder = out / "small_torsion"
    tv = json.loads((folder / "torsion.json").read_text())
    assert tv["natural_frequencies_hz"] and tv["segments_governing"]
    html = (folder / "report.html").read_text()
    assert "Torsional vibration of the crank train" in html and "campbell.png" in html
    assert (folder / "campbell.png").exists()
    res = json.loads((folder / "results.json").read_text())

    lc = load_loadcase(CASE)
    tors = analyse_torsion(
        lc, cylinder_torques(lc.engine, lc.operating)
    )  # Carter stiffness: the case says so; the FE value is only reported
    dyn = with_vibratory_torque(dynamics.analyse(lc.engine, lc.operating), tors)
    quasi = dynamics.analyse(lc.engine, lc.operating)
    wp = math.pi / 16 * 0.032**3
    t1 = dyn.throws["1"]
    m_tn = max(0.5 * np.ptp(t1.torque_front), 0.5 * np.ptp(t1.torque_rear))
    m_qs = 0.5 * np.ptp(quasi.throws["1"].torque_rear)
    assert m_tn != pytest.approx(m_qs, rel=1e-3)  # the vibration changes it
    nominal = res["throws"][0]["m53_nominal"]["torsion_journal"]
    assert nominal == pytest.approx(m_tn / wp, rel=1e-6)
    assert "carter" in tv["throw_stiffness"] and "fe" in tv["throw_stiffness"]
