"""The bolted counterweights' VDI 2230 criteria at every speed of the full-load curve: the
shipped inline-4 (two radial M10 bolts on the counterweights of throws 1 and 4) over 3000,
4500 and 6000 rpm without its full-load gas curve.  Its loads are the inertia forces alone, so the engine torque's excess
energy and its swing about the mean grow with omega^2: with the one flywheel (sized at
6000 rpm for delta = 0.01) the speed fluctuation is 0.01 at every speed and the angular
acceleration grows with omega^2 -- so does each bolt's axial and transverse load.

The case's joint criteria are taken out: every bolted joint that exists is still checked,
with VDI 2230's usual limits, each verdict line saying so.

The check's stages run but the whole shaft's (``helpers.per_throw``): the joints are the
per-throw model's alone (the whole shaft's throws carry none), so every criterion read
here is the one ``fe-crank check`` reports."""

from __future__ import annotations

import math
import re
import shutil
from pathlib import Path

import numpy as np
import pytest

from fe_crank.assess.cw_joint import check_joint, check_joints
from fe_crank.assess.joint_criteria import DEFAULT_LIMITS, DEFAULT_WORDS, JOINT_QUANTITIES
from fe_crank.report.locations import criterion_location

ROOT = Path(__file__).resolve().parents[2]
SPEEDS = (3000, 4500, 6000)


@pytest.fixture(scope="module")
def swept_inline4(tmp_path_factory, mesh_cache):
    from helpers.per_throw import per_throw_outputs

    folder = tmp_path_factory.mktemp("inline4_sweep")
    for sub in ("engines", "geometry"):
        shutil.copytree(ROOT / sub, folder / sub)
    (folder / "loadcases").mkdir()
    text = (ROOT / "loadcases" / "inline4_rated.toml").read_text()
    rpm = ", ".join(f'"{w} rpm"' for w in SPEEDS)
    # the shipped case without its full-load gas curve: the inertia loads alone
    curve = text[text.index("speed_range = ") : text.index("[material]")]
    text = text.replace(curve, f"speeds = [{rpm}]\n\n", 1)
    # no joint criteria: the joints are checked with the default limits
    text = re.sub(r"(?m)^(max|min)_bolt_\w+ = .*\n", "", text)
    assert "bolt_" not in text
    # the whole shaft is not modelled here (module doc): its oil film's criterion goes
    text = re.sub(r"(?m)^min_oil_film_thickness = .*\n", "", text)
    assert "oil_film" not in text
    p = folder / "loadcases" / "inline4_swept.toml"
    p.write_text(text)
    # what is asserted is the assessment's: the drawn states' fields are not computed
    return per_throw_outputs(p, mesh_cache)


@pytest.mark.heavy
def test_bolt_criteria_at_every_speed(swept_inline4):
    out = swept_inline4
    a = out.assessment
    crit = {c.quantity: c for c in a.criteria}
    assert set(JOINT_QUANTITIES) <= set(crit)
    by_speed = {round(s.speed * 30 / math.pi): s.throws for s in a.sweep}
    assert sorted(by_speed) == list(SPEEDS)
    op = out.cycles.operating
    j_fly = op.flywheel_inertia
    material = out.loadcase.material
    for s in out.cycles.sweep:
        rpm = round(s.speed * 30 / math.pi)
        dyn = s.firing
        # the same flywheel: delta = dE / (J omega^2), alpha = max |T - T_mean| / J
        delta = dyn.excess_energy / (j_fly * dyn.speed**2)
        alpha = float(np.max(np.abs(dyn.torque - dyn.mean_torque))) / j_fly
        assert delta == pytest.approx(0.01, rel=1e-6)  # inertia only: dE grows with omega^2
        for t in by_speed[rpm]:
            cws = out.geometry.throws[t.name].counterweights
            want = [
                j
                for c in cws
                for j in check_joints(
                    c,
                    omega=dyn.speed,
                    overspeed=out.loadcase.operating.overspeed,
                    e_clamped=material.youngs_modulus,
                    speed_fluctuation=delta,
                    angular_acceleration=alpha,
                )
            ]
            assert [j.name for j in t.joints] == [j.name for j in want]
            joints = {b.name: b.joint for c in cws for b in c.joints}
            for got, exp in zip(t.joints, want):
                # the speed's delta and alpha: the transverse load (the web's deformation adds none)
                assert got.loads.transverse_max == pytest.approx(exp.loads.transverse_max, rel=1e-12)
                # the web's deformation (the FE section) adds to the centrifugal axial load and brings a
                # moment that varies over the cycle (its sign at the least is the mesh's: near zero)
                assert got.loads.web_model.startswith("FE") and got.loads.moment_max > 0
                assert got.loads.moment_max > got.loads.moment_min
                assert got.loads.axial_max >= exp.loads.axial_max
                again = check_joint(got.name, joints[got.name], got.loads, material.youngs_modulus)
                assert got.fatigue_safety == pytest.approx(again.fatigue_safety, rel=1e-12)
                assert got.slip_safety == pytest.approx(again.slip_safety, rel=1e-12)
    # each bolt's loads against the operating speed's, by omega^2
    op_joints = {(t.name, j.name): j for t in by_speed[6000] for j in t.joints}
    assert op_joints
    for rpm in SPEEDS:
        ratio = (rpm / 6000) ** 2
        for t in by_speed[rpm]:
            for j in t.joints:
                ref = op_joints[(t.name, j.name)]
                assert j.loads.axial_max == pytest.approx(ratio * ref.loads.axial_max, rel=1e-9)
                assert j.loads.transverse_max == pytest.approx(ratio * ref.loads.transverse_max, rel=1e-9)
                assert j.loads.moment_max == pytest.approx(ratio * ref.loads.moment_max, rel=1e-9)
    # each criterion per speed, the worst speed reported: the highest for fatigue and slip
    for q, (attr, sense) in JOINT_QUANTITIES.items():
        c = crit[q]
        assert [round(p.speed_rpm) for p in c.per_speed] == list(SPEEDS)
        for p in c.per_speed:
            vals = [getattr(j, attr) for t in by_speed[round(p.speed_rpm)] for j in t.joints]
            assert p.value == pytest.approx(min(vals) if sense == "min" else max(vals), rel=1e-12)
    for q in ("bolt_fatigue_safety", "bolt_slip_safety"):
        assert crit[q].speed_rpm == pytest.approx(6000) and criterion_location(crit[q]).endswith(
            f"(per bolt); 6000 rpm; friction mu_G 0.10, mu_K 0.10, mu_T 0.10; {DEFAULT_WORDS}"
        )
        assert crit[q].per_speed[0].value > crit[q].per_speed[-1].value


@pytest.mark.heavy
def test_joints_without_criteria_are_checked_with_the_default_limits(swept_inline4):
    out = swept_inline4
    a = out.assessment
    got = {c.quantity: c for c in a.criteria if c.quantity in JOINT_QUANTITIES}
    assert set(got) == set(DEFAULT_LIMITS)
    joints = [j for t in a.throws for j in t.joints]
    assert len(joints) == 4  # two bolted counterweights on each of throws 1 and 4
    swept = [j for s in a.sweep for t in s.throws for j in t.joints]  # every speed's joints
    assert len(swept) == 4 * len(SPEEDS)
    for q, c in got.items():
        attr, sense = JOINT_QUANTITIES[q]
        assert c.limit == DEFAULT_LIMITS[q] and c.name == f"criteria.{sense}_{q}"
        assert criterion_location(c).endswith(f"friction mu_G 0.10, mu_K 0.10, mu_T 0.10; {DEFAULT_WORDS}")
        vals = [getattr(j, attr) for j in swept]  # the worst speed's worst joint
        assert c.value == pytest.approx(min(vals) if sense == "min" else max(vals), rel=1e-12)
    assert any("default limits" in n.text for n in a.notes)
