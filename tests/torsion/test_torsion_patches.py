"""Rods at two places on one pin with torsional vibration: the FE model's patch cases carry
each rod's own force plus its cylinder's share of the vibratory tangential force
(``torsion.loads.vibratory_shares``): shares by the cylinders' inertias in the chain, the
rods' FE forces summing to the pin force the whole-pin cases would carry, and the FE throw
in equilibrium with the torque flow at every speed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.dynamics import RodLoad
from fe_crank.torsion.build import reciprocating_inertia
from fe_crank.torsion.loads import vibratory_shares

DATA = Path(__file__).resolve().parents[1] / "data"

#: tests/data/small_torsion.toml's twin made a V4 (90 deg banks): two rods side by side on each pin
V_CYLINDERS = """[[engine.cylinders]]
name = "1"
throw = "1"
bank_angle = "-45 deg"
firing_offset = "0 deg"

[[engine.cylinders]]
name = "3"
throw = "1"
bank_angle = "45 deg"
firing_offset = "270 deg"

[[engine.cylinders]]
name = "2"
throw = "2"
bank_angle = "-45 deg"
firing_offset = "360 deg"

[[engine.cylinders]]
name = "4"
throw = "2"
bank_angle = "45 deg"
firing_offset = "630 deg"
"""


def _v4_case(folder: Path, piston_mass_3: str | None = None) -> Path:
    text = (DATA / "small_torsion.toml").read_text()
    start, end = text.index("[[engine.cylinders]]"), text.index("[engine.gas]")
    cylinders = V_CYLINDERS
    if piston_mass_3 is not None:
        cylinders = cylinders.replace('name = "3"\n', f'name = "3"\npiston_mass = "{piston_mass_3}"\n')
    text = text[:start] + cylinders + "\n" + text[end:]
    text = text.replace('speed = "3000 rpm"\n', 'speed = "3000 rpm"\nspeeds = ["2000 rpm", "3000 rpm"]\n')
    (folder / "geometry_small.toml").write_text((DATA / "geometry_small.toml").read_text())
    p = folder / "v4_torsion.toml"
    p.write_text(text)
    return p


def test_shares_follow_the_cylinders_inertias(tmp_path):
    """Two rods on a pin, one piston 50 % heavier: each rod takes J_i / (J_1 + J_3) of the
    vibratory tangential force, J = m_rot R^2 + m_j R^2 (1/2 + lambda^2/8) to second order in
    lambda (Den Hartog 5.2); the rods' forces with their shares sum to the FE pin force."""
    lc = load_loadcase(_v4_case(tmp_path, "0.225 kg"))
    r, l_rod, m_rod, c = 0.020, 0.080, 0.20, 0.022
    lam = r / l_rod

    def hand(m_piston):
        m_j = m_piston + m_rod * c / l_rod
        return m_rod * (l_rod - c) / l_rod * r**2 + m_j * r**2 * (0.5 + lam**2 / 8)

    cyl = {x.name: x for x in lc.engine.cylinders}
    assert reciprocating_inertia(cyl["3"], r) == pytest.approx(hand(0.225), rel=2e-3)
    rng = np.random.default_rng(1)
    rods = (RodLoad("1", rng.normal(size=(5, 2))), RodLoad("3", rng.normal(size=(5, 2))))
    extra = np.column_stack([rng.normal(size=5), np.zeros(5)])
    shared = vibratory_shares(lc.engine, "1", rods, extra)
    w3 = hand(0.225) / (hand(0.15) + hand(0.225))
    np.testing.assert_allclose(shared[1].pin_force - rods[1].pin_force, w3 * extra, rtol=2e-3, atol=1e-12)
    np.testing.assert_allclose(sum(s.pin_force for s in shared), sum(x.pin_force for x in rods) + extra, atol=1e-12)
    assert [s.cylinder for s in shared] == ["1", "3"]


@pytest.fixture(scope="module")
def v4_torsion(tmp_path_factory, mesh_cache):
    from helpers.per_throw import per_throw_outputs

    folder = tmp_path_factory.mktemp("v4_torsion")
    # what is asserted is the per-throw model's FE loads and its assessment's inputs: the
    # V4's whole shaft is not solved, no fields are drawn
    return per_throw_outputs(_v4_case(folder), mesh_cache)


@pytest.mark.heavy
def test_patch_model_with_torsion_is_in_equilibrium_at_every_speed(v4_torsion):
    """Through the check's stages: the FE model loads the pin per rod place and carries the
    angular-acceleration case; at every speed each rod takes half the vibratory tangential
    force (identical cylinders), the patch cases' resultant is the FE pin force, and the
    torque reacted at the rear face equals the torque flow leaving the throw at every angle."""
    out = v4_torsion
    assert out.assessment is not None and out.torsion is not None and out.torsion.loads.torsion
    units = next(iter(out.fe.unit_solutions.values()))
    assert len(units.options.pin_patches) == 2 and "angular_acceleration" in units.cases
    from fe_crank.assess.state_throws import places_of
    from fe_crank.assess.superpose import UnitStresses, cycle_coefficients
    from fe_crank.fe.throw.pin_directions import patch_case, unit_force

    cases = tuple(units.cases)
    mz = np.array([units.cases[k].reactions["end_2"][5] for k in cases])
    unit = UnitStresses(
        np.zeros((len(cases), 6, 0)),
        np.zeros((3, 0)),
        cases=cases,
        torque_mz=float(units.cases["torque"].applied[5]),
        pin_patches=tuple(units.options.pin_patches),
    )
    a = _inputs_like(out)
    for states in out.torsion.loads.speeds:
        for state in states:
            for name, tc in state.throws.items():
                extra = tc.fe_pin - tc.pin_force
                assert np.abs(extra).max() > 0
                for rod, fe_rod in zip(tc.rods, tc.fe_rods):
                    np.testing.assert_allclose(fe_rod.pin_force - rod.pin_force, 0.5 * extra, rtol=1e-12, atol=1e-9)
                places = places_of(a, name)
                c = cycle_coefficients(
                    unit,
                    tc.fe_pin,
                    tc.torque_in,
                    state.speed,
                    rod_loads=tc.fe_rod_loads(places),
                    angular_acceleration=tc.angular_acceleration,
                )
                # the patch cases' resultant force: each patch case is a unit force in its direction
                force = np.zeros_like(tc.fe_pin)
                for k, case in enumerate(cases):
                    if patch_case(case) is not None:
                        force += np.outer(c[:, k], unit_force(case))
                np.testing.assert_allclose(force, tc.fe_pin, rtol=0, atol=1e-9 * np.abs(tc.fe_pin).max())
                scale = max(np.abs(tc.torque_out).max(), np.abs(tc.torque_in).max(), 0.020 * np.abs(tc.fe_pin).max())
                np.testing.assert_allclose(c @ mz, tc.torque_out, rtol=0, atol=1e-6 * scale)
    with pytest.raises(ValueError, match="vibratory pin force"):
        tc = out.torsion.loads.operating_state.throws["1"]
        cycle_coefficients(
            unit,
            tc.fe_pin,
            tc.torque_in,
            1.0,
            rod_loads=tuple((r.pin_force, e) for r, e in zip(tc.rods, (-0.01, 0.01))),
            vibration=True,
        )


def _inputs_like(out):
    """The assessment's inputs of the stage outputs (the check's own)."""
    from fe_crank.pipeline.stages import assess_inputs

    return assess_inputs(out.loadcase, out)
