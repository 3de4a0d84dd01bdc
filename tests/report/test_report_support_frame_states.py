"""The displacement the report writes and draws is in the frame of the supports: the
assessment's drawn states (hot spot and overspeed) have the rigid motion of the
determinate solve removed -- the main-bearing centres at rest, the torque face not
turning -- while their stresses are unchanged, and the report's ``.vtu`` carries exactly
that field (the report only formats)."""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np
import pytest
from helpers.pipeline import stage_outputs, write_report

from fe_crank.fe.core.stress import von_mises
from fe_crank.fe.core.support_frame import support_displacements
from fe_crank.pipeline.options import CheckOptions

DATA = Path(__file__).resolve().parents[1] / "data"


@pytest.mark.heavy
def test_drawn_states_are_in_the_support_frame_and_written_as_such(tmp_path, mesh_cache):
    out = stage_outputs(DATA / "small_pass.toml", mesh_cache, render=False, write_vtu=True)
    units = next(iter(out.fe.unit_solutions.values()))
    sup = units.system.determinate
    (st,) = out.assessment.states
    for u in (st.displacement, st.overspeed.displacement):
        scale = np.abs(u).max()
        d = support_displacements(u, sup.G)
        # bearing centres' x, y and the axial journal's z (m), the torque face's turn (rad x 0.1 m)
        assert np.abs(d[:-1]).max() < 1e-10 * scale and abs(d[-1]) * 0.1 < 1e-10 * scale
    # what was removed is rigid: the state's stress is the assessment's (the solve's own
    # unit stresses superposed), at the node of the drawn group's largest von Mises
    (t,) = out.assessment.throws
    ext = next(g for g in t.groups if g.group == st.hotspot.group).max_von_mises
    assert von_mises(st.stress[:, int(ext.node)]) == pytest.approx(ext.value, rel=1e-9)
    write_report(tmp_path / "report", out, CheckOptions(render=False, write_vtu=True))
    (vtu,) = sorted((tmp_path / "report").glob("*.vtu"))
    m = meshio.read(vtu)
    np.testing.assert_array_equal(m.point_data["displacement_m"], st.displacement.reshape(-1, 3))
