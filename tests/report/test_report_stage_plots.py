"""Stage pictures: hodographs only of what is there (fe_crank.report.stage_plots)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fe_crank.balance.analysis import analyse_balance
from fe_crank.io.loadcase import load_loadcase
from fe_crank.report.stage_plots import HODOGRAPH_NOISE, plot_hodographs

ROOT = Path(__file__).resolve().parents[2]


def test_inline4_hodographs_leave_out_the_orders_that_cancel(tmp_path):
    # flat-plane inline-4 (crank 0-180-180-0): the first-order forces and all couples
    # cancel by symmetry, the second-order forces of the four cylinders add up
    # (4 m_rec r omega^2 lambda); the sixth-order term is ~lambda^5 smaller than the
    # second: below 0.1 % of the largest amplitude, so not drawn either
    lc = load_loadcase(ROOT / "loadcases" / "inline4_rated.toml")
    res = analyse_balance(lc.engine, lc.operating.speed, lc.balance)
    free1 = np.linalg.norm(res.forces.total(1).force)
    free2 = np.linalg.norm(res.forces.total(2).force)
    assert free1 < HODOGRAPH_NOISE * free2  # cancelled (rounding level)
    names = sorted(p.name for p in plot_hodographs(res, tmp_path))
    assert "hodograph_order2.png" in names
    assert "hodograph_order6.png" not in names
    for p in names:
        assert (tmp_path / p).read_bytes()[:4] == b"\x89PNG"


def test_no_process_wide_matplotlib_state(tmp_path):
    import matplotlib

    before = matplotlib.get_backend()
    lc = load_loadcase(ROOT / "loadcases" / "inline4_rated.toml")
    plot_hodographs(analyse_balance(lc.engine, lc.operating.speed, lc.balance), tmp_path)
    import matplotlib.pyplot as plt

    assert matplotlib.get_backend() == before and plt.get_fignums() == []
