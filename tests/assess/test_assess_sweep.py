"""The check over the full-load curve: the cycle at every speed against a hand calculation,
every criterion's per-speed values against single-speed checks of the same case run one
by one (the sweep's pruned evaluation against the exhaustive one), misfire as part of
each speed's worst case, the UR M53 marking, the box bounds and the input the wiring
needs (torsion: tests/torsion/test_torsion_sweep.py)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from helpers.pipeline import assess_inputs
from helpers.sweep import SWEPT

from fe_crank.assess.case import AssessInputs, assess_case
from fe_crank.assess.criteria.judge import NOT_CONFORM, evaluate_criteria
from fe_crank.assess.criteria.qualifiers import criterion_qualifiers
from fe_crank.assess.speeds import StateResults
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.errors import InputError
from fe_crank.io.criteria import build_criteria
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.report.locations import criterion_location, location_text
from fe_crank.rules.m53.basis import m53_basis
from fe_crank.rules.m53.calculation import M53Fillet
from fe_crank.torsion.loads import assessed_loads

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"
RPM = math.pi / 30


def test_pin_force_at_both_tdcs_by_hand_at_two_speeds():
    """The shipped single-cylinder case over its full-load curve.  At a TDC the rod lies
    on the cylinder axis, its angular acceleration vanishes and it turns at lambda omega:
    the piston decelerates with r w^2 (1 + lambda) and the rod's centre of mass (c from
    the big end) with r w^2 (1 + lambda c / l), so the rod pushes the pin towards the
    axis with F_g - m_p r w^2 (1 + lambda) - m_rod r w^2 (1 + lambda c / l), and nothing
    tangentially.  At 1000 and 2800 rpm, firing and gas-exchange TDC."""
    lc = load_loadcase(ROOT / "loadcases" / "single_cylinder.toml")
    cycles = engine_cycles(lc.engine, lc.operating)
    assert [round(w / RPM) for w in cycles.speeds] == list(range(1000, 2801, 100))
    assert cycles.sweep[cycles.operating_index].firing is cycles.operating
    r, l_rod, c, m_p, m_rod = 0.064, 0.307, 0.138, 1.1, 1.9
    lam = r / l_rod
    by_rpm = {round(s.speed / RPM): s for s in cycles.sweep}
    pins = {}
    for rpm in (1000, 2800):
        dyn = by_rpm[rpm].firing
        w = rpm * RPM
        assert dyn.speed == pytest.approx(w, rel=1e-12)
        for k in (0, dyn.theta.size // 2):  # 0 and 360 deg of the 720-deg cycle
            gas = dyn.cylinders["1"].gas[k]  # (p - p_cc) A of the diagram (the input, the same at each speed)
            inward = gas - m_p * r * w**2 * (1 + lam) - m_rod * r * w**2 * (1 + lam * c / l_rod)
            pin = dyn.throws["1"].pin_force[k]
            assert pin[1] == pytest.approx(-inward, rel=1e-9, abs=1e-6)
            assert abs(pin[0]) < 1e-6 * abs(inward)
            pins[(rpm, k)] = pin[1]
    # the same diagram at every speed: the gas force at the firing TDC is the same, the inertia falls
    assert by_rpm[1000].firing.cylinders["1"].gas[0] == by_rpm[2800].firing.cylinders["1"].gas[0]
    assert pins[(1000, 0)] < 0 < pins[(2800, 0)]  # the gas force governs the firing TDC at low speed only
    assert 0 < pins[(1000, 360)] < pins[(2800, 360)]


SPEEDS = (1200, 1900, 2500, 3000)


def _case(folder: Path, name: str, sweep: str) -> Path:
    (folder / "geometry_small.toml").write_text((DATA / "geometry_small.toml").read_text())
    p = folder / f"{name}.toml"
    p.write_text(SWEPT.format(sweep=sweep))
    return p


def _inputs(lc, out) -> AssessInputs:
    """The assessment's inputs of ``lc`` on the FE solution of the stage outputs ``out``
    (the same mesh and unit solutions: they do not depend on speed)."""
    return assess_inputs(
        lc,
        out.fe.unit_solutions,
        models=out.geometry.plan.throws,
        balance=out.balance,
        throw_geometry=out.geometry.throws,
    )


@pytest.fixture(scope="module")
def swept(tmp_path_factory, mesh_cache):
    from helpers.pipeline import stage_outputs

    folder = tmp_path_factory.mktemp("sweep")
    rpm = ", ".join(f'"{w} rpm"' for w in SPEEDS)
    # what is asserted is the assessment's: the drawn states' fields are not computed
    out = stage_outputs(_case(folder, "swept", f"speeds = [{rpm}]"), mesh_cache, render=False, write_vtu=False)
    return folder, out


@pytest.mark.heavy
def test_each_speeds_value_is_that_of_a_single_speed_check(swept):
    """Every criterion's per-speed value equals the check of the same case at that speed
    alone (the single-speed path, every node evaluated, the misfire case included) to
    1e-9; its verdict is the worst of them, reported with that speed; the overspeed
    criterion has the overspeed's one value."""
    folder, out = swept
    crit = {c.name: c for c in out.assessment.criteria}
    singles = {}
    for w in SPEEDS:
        p = _case(folder, f"at_{w}", "")
        p.write_text(p.read_text().replace('speed = "3000 rpm"', f'speed = "{w} rpm"'))
        lc = load_loadcase(p)
        assert lc.operating.full_load is None and lc.operating.misfire == ("1",)
        singles[w] = {c.name: c for c in assess_case(_inputs(lc, out)).criteria}
    for name in ("criteria.min_static_safety", "criteria.min_fatigue_safety", "criteria.min_gough_pollard_safety"):
        c = crit[name]
        assert [round(p.speed_rpm) for p in c.per_speed] == list(SPEEDS)
        for p in c.per_speed:
            assert p.value == pytest.approx(singles[round(p.speed_rpm)][name].value, rel=1e-9)
        worst = min(SPEEDS, key=lambda w: singles[w][name].value)
        assert c.value == pytest.approx(singles[worst][name].value, rel=1e-9)
        assert c.speed_rpm == pytest.approx(worst, rel=1e-9)
        assert criterion_location(c).endswith(f"; {worst} rpm")
    os_ = crit["criteria.min_overspeed_safety"]
    assert [round(p.speed_rpm) for p in os_.per_speed] == [3600]
    assert os_.value == pytest.approx(singles[3000]["criteria.min_overspeed_safety"].value, rel=1e-12)


@pytest.mark.heavy
def test_misfire_is_part_of_each_speeds_worst_case(swept):
    """At each speed the value is the worse of all cylinders firing and the misfire
    (the single cylinder motored): recomputed here state by state, each in full."""
    folder, out = swept
    lc = load_loadcase(folder / "swept.toml")
    a = _inputs(lc, out)
    c = {x.name: x for x in out.assessment.criteria}["criteria.min_fatigue_safety"]
    for i, states in enumerate(a.loads.speeds):
        assert [s.case for s in states] == ["all cylinders firing", "cylinder 1 misfiring"]
        values = []
        for s in states:  # the state alone, as the operating speed's: every node evaluated
            one = dataclasses.replace(a.loads, speeds=((s,),), operating=0)
            values.append(
                {x.name: x for x in assess_case(dataclasses.replace(a, loads=one)).criteria}[
                    "criteria.min_fatigue_safety"
                ].value
            )
        assert c.per_speed[i].value == pytest.approx(min(values), rel=1e-9)
        assert ("misfiring" in location_text(c.per_speed[i].where)) == (values[1] < values[0])
    # the notes say what the misfire states are: what the tool does, not a rule's clause
    (sweep,) = [n.text for n in out.assessment.notes if n.text.startswith("full-load curve")]
    assert "1 misfire case(s) (each cylinder motored in turn, judged against the continuous-operation limits)" in sweep


def test_m53_with_the_quasi_static_torque_is_marked_not_conform(tmp_path):
    """``m53_quasi_static_torque = true``: the M53 verdict says it is not UR M53-conform
    in its location (the verdict line's words, after the worst speed) and description,
    over the speeds."""
    crit = build_criteria({"min_m53_acceptability": 1.15, "m53_quasi_static_torque": True}, tmp_path / "c.toml")
    lc = load_loadcase(ROOT / "loadcases" / "inline4_rated.toml")
    words = criterion_qualifiers(m53_basis(lc.engine, lc.material, None), crit, torsion=False)
    fillet = M53Fillet("journal", "empirical", 1.0, 1.0, 1.0, 1e7, 1e7, 2e7, 4e7, 2.0)
    throws = (ThrowAssessment("1", (), (fillet,)),)
    sweep = (StateResults(100.0, "all cylinders firing", throws), StateResults(200.0, "all cylinders firing", throws))
    (v,) = evaluate_criteria(crit, throws, sweep=sweep, qualifiers=words)
    assert NOT_CONFORM in criterion_location(v) and NOT_CONFORM in v.description
    assert criterion_location(v).startswith("throw 1, journal fillet (empirical); 955 rpm; ")
    assert v.value == 2.0 and [p.value for p in v.per_speed] == [2.0, 2.0]
    (plain,) = evaluate_criteria(
        build_criteria({"min_m53_acceptability": 1.15}, tmp_path / "c.toml"), throws, sweep=sweep
    )
    assert NOT_CONFORM not in criterion_location(plain) + plain.description


def _variant(tmp_path: Path, case: str, old: str, new: str) -> Path:
    text = (ROOT / "loadcases" / case).read_text()
    assert old in text
    for sub in ("engines", "geometry", "loadcases"):
        (tmp_path / sub).mkdir(exist_ok=True)
        for f in (ROOT / sub).glob("*.toml"):
            (tmp_path / sub / f.name).write_text(f.read_text())
    p = tmp_path / "loadcases" / case
    p.write_text(text.replace(old, new, 1))
    return p


def test_a_sweep_speed_outside_the_torsional_range_is_refused(tmp_path):
    p = _variant(
        tmp_path,
        "inline4_genset_torsion.toml",
        'speed_range = ["800 rpm", "3600 rpm"]',
        'speed_range = ["1000 rpm", "3600 rpm"]',
    )
    with pytest.raises(InputError, match="800 rpm lies outside the speed range") as err:
        load_loadcase(p)
    assert err.value.file == str(p) and err.value.key == "torsion.speed_range"


def test_front_take_off_without_torsion_takes_the_torque_from_the_rear(tmp_path):
    """Without [torsion] a front power take-off on the inline-4 is checked: the torque
    entering each throw's FE model (at its rear face) is the sum of the cylinder torques
    behind it, and the one leaving at the front face adds its own."""
    p = _variant(tmp_path, "inline4_rated.toml", "[fe]\n", '[fe]\ntorque_reaction = "end_1"\n')
    lc = load_loadcase(p)
    assert lc.fe.torque_reaction == "end_1" and lc.torsion is None
    cycles = engine_cycles(lc.engine, lc.operating)
    state = assessed_loads(lc.engine, cycles, reaction="end_1").operating_state
    dyn = cycles.operating
    names = [t.name for t in sorted(lc.engine.throws, key=lambda t: t.axial_position)]
    for i, n in enumerate(names):
        behind = sum((dyn.throws[m].torque for m in names[i + 1 :]), np.zeros_like(dyn.theta))
        np.testing.assert_allclose(state.throws[n].torque_in, behind, atol=1e-9)
        np.testing.assert_allclose(state.throws[n].torque_out, behind + dyn.throws[n].torque, atol=1e-9)
    np.testing.assert_allclose(state.throws[names[0]].torque_out, dyn.torque, atol=1e-9)


def test_box_bounds_of_von_mises_and_the_largest_principal_stress():
    """Closed forms: a uniaxial box gives sigma_v = r exactly, a pure shear box sqrt(3) t;
    and for random tensors inside a random box neither bound is ever exceeded."""
    from fe_crank.assess.group.bounds import box_principal, box_von_mises
    from fe_crank.assess.stress import von_mises
    from fe_crank.fe.core.stress import principal

    assert box_von_mises(np.array([[5.0], [0], [0], [0], [0], [0]]))[0] == pytest.approx(5.0, rel=1e-15)
    assert box_von_mises(np.array([[0.0], [0], [0], [2.0], [0], [0]]))[0] == pytest.approx(2 * math.sqrt(3), rel=1e-15)
    rng = np.random.default_rng(7)
    box = rng.uniform(0.1, 3.0, size=(6, 500))
    for _ in range(20):
        s = box * rng.uniform(-1.0, 1.0, size=box.shape)
        assert np.all(von_mises(s) <= box_von_mises(box) * (1 + 1e-12))
        assert np.all(principal(s).max(axis=0) <= box_principal(box) * (1 + 1e-12) + 1e-12)
