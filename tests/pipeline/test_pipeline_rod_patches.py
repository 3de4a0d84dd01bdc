"""The check loads the FE pin per rod place where rods bear at more than one place (a V
twin on one crankpin), and the states the report draws use the assessment's own
coefficients (each rod's force on its band): the drawn state at the angle of a group's
largest von Mises reaches the assessment's value at its node."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from helpers.pipeline import stage_outputs

from fe_crank.assess.states import von_mises_at
from fe_crank.fe.throw.pin_directions import patch_case

DATA = Path(__file__).resolve().parents[1] / "data"

V_TWIN = """
[[engine.cylinders]]
name = "2"
throw = "1"
bore = "50 mm"
rod_length = "80 mm"
rod_mass = "0.20 kg"
rod_cg_from_big_end = "22 mm"
piston_mass = "0.15 kg"
bank_angle = "45 deg"
"""


@pytest.fixture(scope="module")
def v_twin(tmp_path_factory, mesh_cache):
    d = tmp_path_factory.mktemp("vtwin")
    text = (DATA / "small_pass.toml").read_text()
    text = text.replace('piston_mass = "0.15 kg"\n', 'piston_mass = "0.15 kg"\nbank_angle = "-45 deg"\n', 1)
    text = text.replace("[material]", V_TWIN + "\n[material]")
    (d / "vtwin.toml").write_text(text)
    (d / "geometry_small.toml").write_text((DATA / "geometry_small.toml").read_text())
    return stage_outputs(d / "vtwin.toml", mesh_cache)


@pytest.mark.heavy
def test_two_rods_side_by_side_load_two_bands_and_the_drawn_state_agrees(v_twin):
    out = v_twin
    units = next(iter(out.fe.unit_solutions.values()))
    # the 18 mm pin in two bands of 9 mm, each with its own pin cases
    np.testing.assert_allclose(units.options.pin_patches, ((-0.009, 0.0), (0.0, 0.009)), atol=1e-12)
    assert {patch_case(c)[0] for c in units.cases if patch_case(c) is not None} == {1, 2}
    a = out.assessment
    (st,) = a.states
    (t,) = a.throws
    g = next(g for g in t.groups if g.group == st.hotspot.group)
    ext = g.max_von_mises
    # the state is drawn at the angle of this group's largest von Mises: at its node the
    # drawn field's von Mises is the assessment's value (the same superposition)
    assert np.degrees(ext.angle) == pytest.approx(st.angle_deg, abs=1e-9)
    assert von_mises_at(units, st.displacement, int(ext.node)) == pytest.approx(ext.value, rel=1e-9)
