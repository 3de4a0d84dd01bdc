"""The journal torques handed to the assessment: one consistent synthesis per journal,
never below the largest UR M53 M_TN of its segment over the speed range."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank.io.engine import load_engine
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.full_load import dynamics_at
from fe_crank.mechanism.torques import cylinder_torques
from fe_crank.torsion import analyse_torsion, with_vibratory_torque
from fe_crank.torsion.handover import ALL_ORDERS, journal_torques, segment_histories

ROOT = Path(__file__).resolve().parents[2]
GENSET = ROOT / "loadcases" / "inline4_genset_torsion.toml"


def inline6_genset():
    """engines/inline6.toml (pitch 92 mm like geometry/inline4.toml) with the genset's gas,
    torsional train and throw geometry: an inline-6 generating set at 3000 rpm."""
    lc = load_loadcase(GENSET)
    e6 = dataclasses.replace(load_engine(ROOT / "engines" / "inline6.toml"), gas=lc.engine.gas)
    return dataclasses.replace(lc, engine=e6)


@pytest.fixture(scope="module", params=["inline-4 genset", "inline-6 genset"])
def handed(request):
    lc = load_loadcase(GENSET) if request.param == "inline-4 genset" else inline6_genset()
    res = analyse_torsion(
        lc, cylinder_torques(lc.engine, lc.operating), inertias={t.name: 0.012 for t in lc.engine.throws}
    )
    dyn = dynamics.analyse(lc.engine, lc.operating)
    return lc, res, dyn, with_vibratory_torque(dyn, res)


def test_handed_torque_is_never_below_the_largest_m_tn_of_its_segment(handed):
    """UR M53 2.2.2: the highest M_TN over the speed range; each journal's history's half
    range is at least that (to round-off)."""
    _, res, _, new = handed
    names = res.model.segment_names
    for throw, tl in new.throws.items():
        front, rear = res.journal_segments(throw)
        for seg, hist in ((front, tl.torque_front), (rear, tl.torque_rear)):
            if seg < 0:
                continue
            m_tn = res.half_range[:, seg].max()
            assert 0.5 * np.ptp(hist) >= m_tn * (1 - 1e-12), (throw, names[seg])


def test_each_history_is_one_synthesis_at_one_speed(handed):
    """The history of a journal is the synthesis (UR M53 orders, or all quasi-static
    orders + the vibratory ones) at the speed it names, both parts at that speed; with
    all orders the rigid-shaft part is the dynamics stage's cumulative torque at that
    speed (an independent dynamics run)."""
    lc, res, _, _ = handed
    for name, jt in journal_torques(res).items():
        s = res.index(jt.speed)
        seg = res.model.segment_names.index(name)
        syn, full = segment_histories(res, s)
        np.testing.assert_allclose(jt.history, (full if jt.form == ALL_ORDERS else syn)[seg], rtol=0, atol=1e-9)
    # the all-orders quasi-static part at another speed, against the dynamics stage there
    s = res.index(2000 * np.pi / 30)
    w = float(res.response.speeds[s])
    syn, full = segment_histories(res, s)
    quasi = full - (syn - res.quasi_static(s))
    dyn = dynamics_at(lc.engine, lc.operating, w)  # that speed's full-load diagram
    for throw, tl in dyn.throws.items():
        rear = res.journal_segments(throw)[1]
        scale = np.abs(tl.torque_rear).max()
        np.testing.assert_allclose(quasi[rear], tl.torque_rear, rtol=0, atol=1e-9 * scale)


def test_mixing_speeds_was_below_m_tn_on_the_inline_6():
    """The earlier hand-over, quasi-static at the operating speed + vibratory at the
    governing speed, falls below the largest M_TN on some journal of the inline-6 set;
    the consistent synthesis does not (the test above)."""
    lc = inline6_genset()
    res = analyse_torsion(
        lc, cylinder_torques(lc.engine, lc.operating), inertias={t.name: 0.012 for t in lc.engine.throws}
    )
    dyn = dynamics.analyse(lc.engine, lc.operating)
    worst = 1.0
    for throw, tl in dyn.throws.items():
        seg = res.journal_segments(throw)[1]
        g = res.governing(seg)
        mixed = tl.torque_rear + res.vibratory(g)[seg]
        worst = min(worst, 0.5 * np.ptp(mixed) / res.half_range[:, seg].max())
    assert worst < 0.99
