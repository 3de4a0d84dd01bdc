"""A misfiring cylinder: input keys, the motored cylinder in the dynamics (closed forms
of the motored cycle), and the torsional response with the cutout (rigid limit against
an independent dynamics run; the minor orders a misfire excites)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.misfire import ZERO_GAUGE, misfire_cycles
from fe_crank.mechanism.torques import engine_torques
from fe_crank.torsion.misfire import analyse_misfire

ROOT = Path(__file__).resolve().parents[2]
GENSET = ROOT / "loadcases" / "inline4_genset_torsion.toml"


def variant(tmp_path, name: str, old: str, new: str) -> Path:
    """A shipped load case with one text change, in a copy of the repository layout."""
    text = (ROOT / "loadcases" / name).read_text()
    assert old in text
    for folder in ("geometry", "engines", "loadcases"):
        (tmp_path / folder).mkdir(exist_ok=True)
    for folder in ("geometry", "engines"):
        for f in (ROOT / folder).glob("*.toml"):
            (tmp_path / folder / f.name).write_text(f.read_text())
    p = tmp_path / "loadcases" / name
    p.write_text(text.replace(old, new, 1))
    return p


SPEED = 'speed = "3000 rpm"\n'


@pytest.mark.parametrize(
    "value, expected",
    [('"each"', ("1", "2", "3", "4")), ('["3"]', ("3",)), ('["4", "1"]', ("4", "1"))],
)
def test_misfire_key_names_the_cylinders(tmp_path, value, expected):
    p = variant(tmp_path, "inline4_genset_torsion.toml", SPEED, f"{SPEED}misfire = {value}\n")
    assert load_loadcase(p).operating.misfire == expected


@pytest.mark.parametrize(
    "value, key, reason",
    [
        ('["7"]', "operating.misfire[0]", "names cylinder '7', which the engine does not have"),
        ('["2", "2"]', "operating.misfire[1]", "named twice"),
        ("[]", "operating.misfire", "name the misfiring cylinders"),
        ('"all"', "operating.misfire", "each"),
    ],
)
def test_bad_misfire_is_refused_with_file_and_key(tmp_path, capsys, value, key, reason):
    p = variant(tmp_path, "inline4_genset_torsion.toml", SPEED, f"{SPEED}misfire = {value}\n")
    with pytest.raises(InputError) as err:
        load_loadcase(p)
    assert err.value.file == str(p) and err.value.key == key and reason in str(err.value)
    assert main(["validate", str(p)]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_misfire_without_gas_pressure_is_refused(tmp_path):
    """engines/inline4.toml has no gas pressure: without the load case's full-load curve
    nothing fires, so nothing can misfire."""
    text = (ROOT / "loadcases" / "inline4_rated.toml").read_text()
    curve = text[text.index("speed_range = ") : text.index("[material]")]
    p = variant(tmp_path, "inline4_rated.toml", curve, 'misfire = "each"\n\n')
    with pytest.raises(InputError, match="needs the engine's gas pressure") as err:
        load_loadcase(p)
    assert err.value.key == "operating.misfire"


@pytest.fixture(scope="module")
def genset_misfire(tmp_path_factory):
    p = variant(tmp_path_factory.mktemp("mf"), "inline4_genset_torsion.toml", SPEED, f'{SPEED}misfire = ["3"]\n')
    return load_loadcase(p)


def test_misfiring_cylinder_is_motored_in_the_dynamics(genset_misfire):
    """Cylinder 3 motored (the Wiebe data give the motored curve): its pressure peaks at
    p_0 eps^n = 0.1 MPa x 10^1.35 at its firing TDC; its p-V loop is the gas exchange
    alone, -(p_ex - p_0) V_s (compression and expansion on one polytrope cancel); the
    other cylinders are those of the firing engine."""
    lc = genset_misfire
    (cyc,) = misfire_cycles(lc.engine, lc.operating)
    assert cyc.cylinder == "3" and cyc.gas.startswith("motored")
    full = dynamics.analyse(lc.engine, lc.operating)
    mis = cyc.dynamics
    c3 = mis.cylinders["3"]
    assert c3.pressure.max() == pytest.approx(0.1e6 * 10**1.35, rel=1e-9)
    assert c3.pressure[np.argmin(np.abs(c3.gas_angle))] == pytest.approx(c3.pressure.max(), rel=1e-12)
    v_s = np.pi / 4 * 0.086**2 * 0.086
    w3 = mis.indicated_work - 0.75 * full.indicated_work
    assert w3 == pytest.approx(-(0.11e6 - 0.1e6) * v_s, rel=0.02)
    for c in ("1", "2", "4"):
        np.testing.assert_array_equal(mis.cylinders[c].torque, full.cylinders[c].torque)
    assert mis.mean_torque < 0.76 * full.mean_torque


def test_misfire_without_a_motored_curve_is_zero_gauge_pressure(tmp_path):
    """A pressure table without compression ratio (the seed table with its motored curve
    taken away): the misfiring cylinder's gas force is zero, its torque the inertia torque
    of the engine run without gas."""
    p = variant(tmp_path, "single_cylinder.toml", "[operating]\n", '[operating]\nmisfire = "each"\n')
    lc = load_loadcase(p)
    engine = dataclasses.replace(lc.engine, gas=dataclasses.replace(lc.engine.gas, motored=None))
    (cyc,) = misfire_cycles(engine, lc.operating)
    assert cyc.gas == ZERO_GAUGE
    np.testing.assert_allclose(cyc.dynamics.cylinders["1"].gas, 0.0, atol=0)
    no_gas = dynamics.analyse(dataclasses.replace(engine, gas=None), lc.operating)
    np.testing.assert_allclose(cyc.dynamics.cylinders["1"].torque, no_gas.cylinders["1"].torque, atol=1e-9)


def test_rigid_limit_of_the_misfire_synthesis_is_the_misfire_dynamics(genset_misfire):
    """Throws of negligible inertia on a rigid crank before a heavy flywheel: the torsional
    synthesis with cylinder 3 misfiring gives back the journal torques of a dynamics run
    with cylinder 3 motored (an independent computation), to 1e-6."""
    lc = genset_misfire
    t = lc.torsion
    rigid = dataclasses.replace(
        t,
        damper=None,
        pulley=None,
        driven=(),
        flywheel=dataclasses.replace(t.flywheel, stiffness=1e12, inertia=10.0),
        speed_steps=11,
        cylinder_damping=0.0,
        assess_speed="operating",
        throw_stiffness="fe",
    )
    mt = analyse_misfire(
        lc,
        engine_torques(lc.engine, lc.operating),
        settings=rigid,
        inertias=dict.fromkeys("1234", 1e-9),
        fe_stiffness=1e12,
    )
    (case,) = mt.cases
    res = case.result
    s = res.index(lc.operating.speed)
    syn = res.response.synthesis(s, res.theta)
    (cyc,) = misfire_cycles(lc.engine, lc.operating)
    # the synthesis keeps orders <= 12; compare with those orders of the dynamics' journal torque
    for throw, tl in cyc.dynamics.throws.items():
        rear = res.journal_segments(throw)[1]
        ref = np.fft.rfft(tl.torque_rear)
        ref[25:] = 0.0  # harmonic j = 2 n: orders above 12 dropped
        ref = np.fft.irfft(ref, n=tl.torque_rear.size)
        np.testing.assert_allclose(syn[rear], ref, rtol=0, atol=1e-6 * np.abs(ref).max())


def test_misfire_can_govern_a_journal_and_says_which_cylinder_and_speed(tmp_path):
    """Inline-4 firing 1-3-4-2: the orders 0.5, 1, 1.5 ... of the four cylinders cancel;
    a misfire leaves them uncancelled.  On the genset (throws of 0.012 kg m^2) each
    cylinder misfiring in turn: the rear crank journal (4-flywheel) has its largest M_TN
    with cylinder 3 misfiring, 3.5 % above normal firing; the handed-over torque of every
    journal is the worst case's, never below the largest M_TN of all cases."""
    p = variant(tmp_path, "inline4_genset_torsion.toml", SPEED, f'{SPEED}misfire = "each"\n')
    lc = load_loadcase(p)
    mt = analyse_misfire(lc, engine_torques(lc.engine, lc.operating), inertias=dict.fromkeys("1234", 0.012))
    assert [c.cylinder for c in mt.cases] == ["1", "2", "3", "4"]
    g = mt.governing("4-flywheel")
    i = mt.firing.model.segment_names.index("4-flywheel")
    assert g.case == "cylinder 3 misfiring"
    assert g.m_tn > 1.02 * mt.firing.half_range[:, i].max()
    assert mt.firing.speed_range[0] <= g.speed <= mt.firing.speed_range[1]
    handed = mt.journal_torques()
    assert handed["4-flywheel"].case == "cylinder 3 misfiring"
    for jt in handed.values():
        assert jt.half_range >= jt.max_m_tn * (1 - 1e-12)
        assert jt.max_m_tn == pytest.approx(mt.governing(jt.segment).m_tn, rel=1e-12)
