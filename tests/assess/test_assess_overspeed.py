"""Overspeed cycle (fe_crank.mechanism.cycles) against a hand calculation.

Slider-crank at TDC (exact kinematics): piston acceleration a = r omega^2 (1 + lambda),
lambda = r/l.  The rod as its dynamically equivalent two masses (no rod_inertia given:
J = m c (l - c)): m_rec = m c/l at the small end, m_rot = m (l - c)/l at the big end.
Force of the rod on the crankpin at TDC, radially outward (y of the throw frame):

    F = [(m_p + m_rec)(1 + lambda) + m_rot] r omega^2

r = 50 mm, l = 200 mm (lambda = 0.25), m_p = 1.2 kg, rod 0.8 kg with c = 50 mm
(m_rec = 0.8 * 0.25 = 0.2 kg, m_rot = 0.6 kg):
F = [1.4 * 1.25 + 0.6] * 0.05 * omega^2 = 0.1175 omega^2 N
    at 3500 rpm (omega = 366.519 rad/s, omega^2 = 134336.3):  15784.5 N
    at 4200 rpm (omega = 439.823 rad/s, omega^2 = 193444.3):  22729.7 N  (x 1.44)

Motored gas (no combustion), closed form of the polytrope p V^n = const from BDC:
p_TDC = p_0 eps^n = 0.1 MPa x 9^1.35 = 0.1 x exp(1.35 ln 9) = 0.1 x exp(2.966253) = 0.1 x 19.41902
= 1.941902 MPa (eps = 9, p_0 = 0.1 MPa, n = 1.35 = the Wiebe input's default k);
gas force at the firing TDC (p_TDC - p_cc) A, A = pi/4 0.08^2 = 5.02655e-3 m^2:
(1.941902 - 0.101325) MPa x A = 9251.8 N, towards the axis.

Around the hand calculation: which cycles the overspeed check runs, on which grid, the
note that says so (in full for each gas state), and the refusals.
"""

from __future__ import annotations

import math
import textwrap
from dataclasses import replace

import numpy as np
import pytest

from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import describe, overspeed_cycles
from fe_crank.mechanism.dynamics import analyse

CASE = """
name = "hand"
[operating]
speed = "3500 rpm"
overspeed = "4200 rpm"
{extra}
[engine]
name = "single"
strokes = 4
[[engine.throws]]
name = "1"
crank_radius = "50 mm"
[[engine.cylinders]]
name = "1"
throw = "1"
bore = "80 mm"
rod_length = "200 mm"
rod_mass = "0.8 kg"
rod_cg_from_big_end = "50 mm"
piston_mass = "1.2 kg"
[engine.gas]
model = "wiebe"
compression_ratio = 9.0
intake_pressure = "0.1 MPa"
exhaust_pressure = "0.1013 MPa"
heat_released = "1.2 kJ"
combustion_start = "-10 deg"
combustion_duration = "50 deg"
"""


def _case(tmp_path, extra=""):
    p = tmp_path / "c.toml"
    p.write_text(textwrap.dedent(CASE.format(extra=extra)))
    return load_loadcase(p)


def _hand(rpm):
    w = rpm * math.pi / 30
    return (1.4 * 1.25 + 0.6) * 0.05 * w**2


def test_hand_values():
    assert _hand(3500) == pytest.approx(15784.5, abs=0.1)
    assert _hand(4200) == pytest.approx(22729.7, abs=0.1)


def _p_tdc():
    return 0.1e6 * 9.0**1.35


def test_motored_curve_closed_form():
    """fe_crank.mechanism.gas.motored_cycle against p = p_0 (V_BDC/V)^n: p_TDC = p_0 eps^n, p_BDC = p_0,
    and at 90 deg the volume ratio from the exact slider-crank by hand."""
    from fe_crank.mechanism.gas import motored_cycle

    assert _p_tdc() == pytest.approx(1.941902e6, rel=1e-6)
    g = motored_cycle(
        bore=0.08, r=0.05, l=0.2, compression_ratio=9.0, intake_pressure=0.1e6, n_poly=1.35, strokes=4, n=1441
    )
    deg = np.rad2deg(g.angle)
    # tolerance 1e-12: closed form at the grid points; an exponent 1.3 instead of 1.35 is 10 % off
    assert g.pressure[0] == pytest.approx(_p_tdc(), rel=1e-12)  # firing TDC
    assert g.pressure[-1] == pytest.approx(_p_tdc(), rel=1e-12)  # same TDC, end of cycle
    assert g.pressure[np.argmin(abs(deg - 180))] == pytest.approx(0.1e6, rel=1e-12)  # BDC
    # 90 deg after TDC: s = r + l - (r cos 90 + sqrt(l^2 - r^2)) = 0.25 - 0.193649 = 0.056351 m;
    # V_s = A 0.1, V_c = V_s/8; V_BDC/V = (9/8 0.1)/(0.1/8 + 0.056351) = 0.1125/0.068851 = 1.633963
    i = int(np.argmin(abs(deg - 90)))
    assert g.pressure[i] == pytest.approx(0.1e6 * 1.633963**1.35, rel=1e-5)
    # gas exchange of the four-stroke at the intake pressure (no exhaust pressure given)
    assert np.all(g.pressure[(deg > 180.5) & (deg < 539.5)] == 0.1e6)
    two = motored_cycle(bore=0.08, r=0.05, l=0.2, compression_ratio=9.0, intake_pressure=0.1e6, strokes=2, n=721)
    assert two.angle[-1] == pytest.approx(2 * np.pi) and two.pressure.max() == pytest.approx(_p_tdc(), rel=1e-12)


def test_motored_overspeed_checks_the_compression_curve_and_zero_gas(tmp_path):
    """Two overspeed cycles: the motored curve (firing TDC: inertia minus the compression
    force 9251.9 N by hand) and zero gas (both TDCs: inertia only); the notes name both."""
    from fe_crank.mechanism.cycles import describe, overspeed_cycles

    lc = _case(tmp_path)
    dyn = analyse(lc.engine, lc.operating)
    cycles = overspeed_cycles(lc.engine, lc.operating, dyn)
    assert len(cycles) == 2 and "p_0 (V_BDC/V)^n" in cycles[0].gas and "zero gauge" in cycles[1].gas
    pin = cycles[0].dynamics.throws["1"].pin_force
    deg = np.rad2deg(cycles[0].dynamics.theta)
    area = math.pi / 4 * 0.08**2
    assert (_p_tdc() - 101325.0) * area == pytest.approx(9251.8, abs=0.1)
    i = int(np.argmin(np.abs(deg - 0.0)))
    # tolerance 1e-9: exact at TDC; leaving the compression out is 9252 N = 41 % off
    assert pin[i, 1] == pytest.approx(_hand(4200) - (_p_tdc() - 101325.0) * area, rel=1e-9)
    # gas-exchange TDC: exhaust pressure 0.1013 MPa, (0.1013e6 - 101325) A = -0.1257 N
    i = int(np.argmin(np.abs(deg - 360.0)))
    assert pin[i, 1] == pytest.approx(_hand(4200) - (0.1013e6 - 101325.0) * area, rel=1e-9)
    np.testing.assert_array_equal(overspeed_cycles(lc.engine, lc.operating, dyn)[0].dynamics.throws["1"].pin_force, pin)
    note = describe(lc.engine, lc.operating)
    assert "eps = 9" in note and "n = 1.35" in note and "zero gauge" in note and "the worse of the two" in note


def test_motored_overspeed_pin_force_at_both_tdcs_equals_hand_value(tmp_path):
    """The zero-gas cycle of the motored condition: inertia only at both TDCs."""
    from fe_crank.mechanism.cycles import overspeed_cycles

    lc = _case(tmp_path)
    assert lc.operating.overspeed_gas == "motored"
    dyn = analyse(lc.engine, lc.operating)
    os = overspeed_cycles(lc.engine, lc.operating, dyn)[-1].dynamics
    pin = os.throws["1"].pin_force
    deg = np.rad2deg(os.theta)
    for tdc in (0.0, 360.0):
        i = int(np.argmin(np.abs(deg - tdc)))
        # tolerance 1e-9: the model is exact at TDC; a missing (1 + lambda) is 25 % off,
        # a missing rod share 0.6/2.35 = 26 %
        assert pin[i, 1] == pytest.approx(_hand(4200), rel=1e-9)
        assert abs(pin[i, 0]) < 1e-6 * _hand(4200)
    # gas-exchange TDC of the operating cycle: inertia only (exhaust/intake pressure ~ crankcase)
    i = int(np.argmin(np.abs(deg - 360.0)))
    assert dyn.throws["1"].pin_force[i, 1] == pytest.approx(_hand(3500), rel=2e-3)
    # no combustion: the largest outward pin force of the overspeed cycle is the TDC value
    assert pin[:, 1].max() == pytest.approx(_hand(4200), rel=1e-9)


def test_as_operating_keeps_the_gas_load(tmp_path):
    lc = _case(tmp_path, 'overspeed_gas = "as_operating"')
    dyn = analyse(lc.engine, lc.operating)
    os = overspeed_cycles(lc.engine, lc.operating, dyn)[0].dynamics
    deg = np.rad2deg(os.theta)
    i = int(np.argmin(np.abs(deg - 0.0)))
    # firing TDC: the gas force (p - p_cc) A pushes the pin inward against the inertia pull
    gas = dyn.cylinders["1"].gas[i]
    assert gas > 1e4
    assert os.throws["1"].pin_force[i, 1] == pytest.approx(_hand(4200) - gas, rel=1e-9)


def test_bad_overspeed_gas_is_an_input_error(tmp_path):
    with pytest.raises(InputError) as e:
        _case(tmp_path, 'overspeed_gas = "full"')
    assert "operating.overspeed_gas" in str(e.value)


TABLE_GAS = """
[engine.gas]
model = "table"
angle_unit = "deg"
pressure_unit = "MPa"
points = [[0, 5.0], [360, 0.1], [720, 5.0]]
{motored}
"""


def _table_case(tmp_path, motored=""):
    text = CASE[: CASE.index("[engine.gas]")] + TABLE_GAS.format(motored=motored)
    p = tmp_path / "t.toml"
    p.write_text(textwrap.dedent(text.format(extra="")))
    return load_loadcase(p)


def test_table_gas_motored_curve_only_with_its_data(tmp_path):
    """A p(phi) table gives no motored curve unless it states compression ratio and intake
    pressure: then zero gas alone, and the note says why; with both keys the curve is the
    closed form; one key alone is refused, naming the file and key."""
    from fe_crank.mechanism.cycles import describe, overspeed_cycles

    lc = _table_case(tmp_path)
    assert lc.engine.gas.motored is None
    dyn = analyse(lc.engine, lc.operating)
    assert len(overspeed_cycles(lc.engine, lc.operating, dyn)) == 1
    assert "no compression ratio and intake pressure" in describe(lc.engine, lc.operating)
    lc = _table_case(tmp_path, 'compression_ratio = 9.0\nintake_pressure = "0.1 MPa"')
    assert lc.engine.gas.motored.pressure.max() == pytest.approx(_p_tdc(), rel=1e-12)
    with pytest.raises(InputError) as e:
        _table_case(tmp_path, "compression_ratio = 9.0")
    assert "t.toml" in str(e.value) and "engine.gas" in str(e.value) and "intake_pressure" in str(e.value)


def test_overspeed_takes_the_worse_of_several_cycles():
    """``assess_throw`` with two overspeed cycles: one node, sigma_xx = 1 Pa per N of pin_y;
    cycle A peaks at +100 N, cycle B at -300 N: von Mises 300 Pa, at B's angle."""
    from fe_crank.assess.superpose import UnitStresses
    from fe_crank.assess.throw import ThrowContext, assess_throw
    from fe_crank.io.material import load_material

    stress = np.zeros((3, 6, 1))
    stress[1, 0, 0] = 1.0
    unit = UnitStresses(
        stress=stress,
        points=np.zeros((3, 1)),
        groups={"crankpin_fillet_1": np.array([0])},
        cases=("pin_x", "pin_y", "torque"),
    )
    theta = np.deg2rad([0.0, 90.0, 180.0, 270.0])
    a = np.column_stack([np.zeros(4), [100.0, 0.0, -50.0, 0.0]])
    b = np.column_stack([np.zeros(4), [0.0, 0.0, -300.0, 10.0]])
    kw = dict(omega=1.0, overspeed=1.0, material=load_material("42CrMo4"), crank_radius=0.05)
    one = assess_throw(ThrowContext("1", unit, theta, a, np.zeros(4), overspeed_loads=[(a, np.zeros(4))], **kw))
    both = assess_throw(
        ThrowContext("1", unit, theta, a, np.zeros(4), overspeed_loads=[(a, np.zeros(4)), (b, np.zeros(4))], **kw)
    )
    assert one.groups[0].max_von_mises_overspeed.value == pytest.approx(100.0, rel=1e-12)
    ext = both.groups[0].max_von_mises_overspeed
    assert ext.value == pytest.approx(300.0, rel=1e-12) and np.rad2deg(ext.angle) == pytest.approx(180.0)


def test_note_in_full_for_each_gas_state(tmp_path):
    """4200 rpm = 439.823 rad/s, printed back as 439.823 x 30 / pi = 4200 rpm."""
    head = (
        "overspeed: whole cycle recomputed at 4200 rpm (rod and piston inertia and crank body force at "
        "omega_os^2; gas: "
    )
    lc = _case(tmp_path, 'overspeed_gas = "as_operating"')
    assert describe(lc.engine, lc.operating) == head + "the operating gas pressure table); worst angle"
    lc = _table_case(tmp_path)
    assert describe(lc.engine, lc.operating) == head + (
        "no combustion, zero gauge gas pressure (the gas data give no compression "
        "ratio and intake pressure for a motored curve)); worst angle"
    )
    lc = _case(tmp_path)
    src = lc.engine.gas.motored.source
    assert describe(lc.engine, lc.operating) == head + (
        f"(no combustion, {src}) and (no combustion, zero gauge gas pressure), the worse of the two); worst angle"
    )


def test_cycles_and_their_order_grid_and_gas(tmp_path):
    """Motored with the curve: (curve, zero gas), in that order, on the operating grid;
    as_operating: one cycle with the operating table; no overspeed: none."""
    lc = _case(tmp_path)
    dyn = analyse(lc.engine, lc.operating)
    cycles = overspeed_cycles(lc.engine, lc.operating, dyn)
    assert [c.gas for c in cycles] == [
        f"no combustion, {lc.engine.gas.motored.source}",
        "no combustion, zero gauge gas pressure",
    ]
    for c in cycles:
        np.testing.assert_array_equal(c.dynamics.theta, dyn.theta)
        assert c.dynamics.speed == lc.operating.overspeed
    # the zero-gas cycle: no gas force in any cylinder
    assert np.all(cycles[1].dynamics.cylinders["1"].gas == 0.0)
    np.testing.assert_array_equal(
        overspeed_cycles(lc.engine, lc.operating, dyn)[0].dynamics.throws["1"].pin_force,
        cycles[0].dynamics.throws["1"].pin_force,
    )
    lc_op = _case(tmp_path, 'overspeed_gas = "as_operating"')
    (one,) = overspeed_cycles(lc_op.engine, lc_op.operating, dyn)
    assert one.gas == "the operating gas pressure table"
    # the operating gas at the firing TDC is in the overspeed cycle too (inertia x 1.44 minus gas)
    i = int(np.argmin(np.abs(np.rad2deg(dyn.theta))))
    gas = dyn.cylinders["1"].gas[i]
    assert one.dynamics.throws["1"].pin_force[i, 1] == pytest.approx(_hand(4200) - gas, rel=1e-9)
    none = replace(lc, operating=replace(lc.operating, overspeed=None))
    assert overspeed_cycles(none.engine, none.operating, dyn) == ()


def test_overspeed_grid_follows_a_coarser_operating_grid(tmp_path):
    """An operating cycle on a 2-deg grid (360 angles over 720 deg): the overspeed cycles
    use the same 360 angles."""
    lc = _case(tmp_path)
    dyn = analyse(lc.engine, lc.operating, step=math.radians(2.0))
    assert dyn.theta.size == 360
    for c in overspeed_cycles(lc.engine, lc.operating, dyn):
        np.testing.assert_allclose(c.dynamics.theta, dyn.theta, rtol=0, atol=1e-12)


def test_unknown_gas_mode_is_refused_in_full(tmp_path):
    lc = _case(tmp_path)
    bad = replace(lc, operating=replace(lc.operating, overspeed_gas="full"))
    dyn = analyse(lc.engine, lc.operating)
    with pytest.raises(ValueError) as e:
        overspeed_cycles(bad.engine, bad.operating, dyn)
    assert str(e.value) == "overspeed_gas must be one of ('motored', 'as_operating'), not 'full'"


def test_an_operating_cycle_of_another_length_is_refused(tmp_path):
    """The operating dynamics of a two-stroke version of the engine (360 angles over 360
    deg) against the four-stroke load case: the overspeed cycle on the same step has 720
    angles, not 360 -- refused rather than paired angle by angle."""
    lc = _case(tmp_path)
    two = analyse(replace(lc.engine, strokes=2), lc.operating)
    assert two.theta.size == 360
    with pytest.raises(ValueError) as e:
        overspeed_cycles(lc.engine, lc.operating, two)
    assert str(e.value) == "overspeed cycle grid differs from the operating one"
