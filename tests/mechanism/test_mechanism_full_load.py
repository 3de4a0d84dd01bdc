"""The full-load curve's input: the speeds of the sweep, the gas pressure per speed
(interpolated in speed, never extrapolated), one dynamics result per speed on one cycle
grid; bad input refused with the file and the key."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank import model
from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.full_load import dynamics_sweep, sweep_speeds
from fe_crank.mechanism.torques import cylinder_torques

RPM = np.pi / 30

CASE = """\
name = "full-load sweep"

[engine]
name = "single"
strokes = 4

[[engine.throws]]
name = "1"
crank_radius = "40 mm"

[[engine.cylinders]]
name = "1"
throw = "1"
bore = "80 mm"
rod_length = "140 mm"
rod_mass = "0.5 kg"
rod_cg_from_big_end = "35 mm"
piston_mass = "0.4 kg"

[operating]
speed = "2000 rpm"
{operating}
"""
TABLE = """
[[operating.gas]]
speed = "{rpm} rpm"
angle_unit = "deg"
pressure_unit = "MPa"
points = {points}
"""
FLAT = "[[0, 1.0], [720, 1.0]]"
PEAK = "[[0, 3.0], [360, 1.0], [720, 3.0]]"


def write(tmp_path, operating: str) -> Path:
    p = tmp_path / "case.toml"
    p.write_text(CASE.format(operating=operating))
    return p


def two_tables(lo=1000, hi=3000, extra="") -> str:
    return extra + TABLE.format(rpm=lo, points=FLAT) + TABLE.format(rpm=hi, points=PEAK)


def test_single_speed_case_is_unchanged(tmp_path):
    lc = load_loadcase(write(tmp_path, ""))
    assert lc.operating.full_load is None and sweep_speeds(lc.operating) == (lc.operating.speed,)


def test_speed_list_and_range_with_step(tmp_path):
    """The operating speed joins the sweep; a range's last speed is kept when the step
    does not reach it exactly."""
    lc = load_loadcase(write(tmp_path, 'speeds = ["1000 rpm", "1500 rpm", "2500 rpm"]'))
    assert np.allclose(np.array(lc.operating.full_load.speeds) / RPM, [1000, 1500, 2000, 2500])
    lc = load_loadcase(write(tmp_path, 'speed_range = ["1000 rpm", "2900 rpm"]\nspeed_step = "400 rpm"'))
    assert np.allclose(np.array(lc.operating.full_load.speeds) / RPM, [1000, 1400, 1800, 2000, 2200, 2600, 2900])


def test_per_speed_diagrams_interpolate_linearly_in_speed(tmp_path):
    """Diagrams at 1000 rpm (1 MPa throughout) and 3000 rpm (3 MPa at TDC firing, 1 MPa
    at 360 deg): at 2000 rpm halfway, 2 MPa at TDC; at the given speeds the diagrams
    themselves; outside them nothing.  The engine's gas is the diagram at the operating
    speed."""
    lc = load_loadcase(write(tmp_path, 'speeds = ["1000 rpm", "3000 rpm"]' + two_tables()))
    curve = lc.operating.full_load
    g = curve.gas_at(2000 * RPM)
    assert np.interp(0.0, g.angle, g.pressure) == pytest.approx(2.0e6)
    assert np.interp(np.pi, g.angle, g.pressure) == pytest.approx(1.5e6)
    assert np.interp(2 * np.pi, g.angle, g.pressure) == pytest.approx(1.0e6)
    assert curve.gas_at(3000 * RPM) is curve.diagrams[1]
    assert np.interp(0.0, lc.engine.gas.angle, lc.engine.gas.pressure) == pytest.approx(2.0e6)
    with pytest.raises(ValueError, match="never extrapolated"):
        curve.gas_at(3500 * RPM)


def test_one_dynamics_result_per_speed_on_one_grid(tmp_path):
    """Each speed's cycle is the dynamics stage's at that speed with that speed's diagram
    (an independent run with the interpolated table), all on one angle grid."""
    lc = load_loadcase(write(tmp_path, 'speeds = ["1000 rpm", "1500 rpm", "3000 rpm"]' + two_tables()))
    runs = dynamics_sweep(lc.engine, lc.operating)
    speeds = lc.operating.full_load.speeds
    assert [r.speed for r in runs] == list(speeds)
    for r, w in zip(runs, speeds, strict=True):
        np.testing.assert_array_equal(r.theta, runs[0].theta)
        ref = dynamics.analyse(
            dataclasses.replace(lc.engine, gas=lc.operating.full_load.gas_at(w)), model.OperatingPoint(w)
        )
        np.testing.assert_allclose(r.throws["1"].pin_force, ref.throws["1"].pin_force, rtol=0, atol=1e-9)


def test_one_diagram_serves_every_speed(tmp_path):
    """Without per-speed diagrams the engine's diagram is used at every speed: the gas
    force is the same at each, the inertia force scales with omega^2."""
    gas = '\n[engine.gas]\nangle_unit = "deg"\npressure_unit = "MPa"\npoints = ' + PEAK + "\n"
    text = CASE.format(operating='speeds = ["1000 rpm", "3000 rpm"]').replace("\n[operating]", gas + "\n[operating]")
    p = tmp_path / "case.toml"
    p.write_text(text)
    lc = load_loadcase(p)
    a, b, c = dynamics_sweep(lc.engine, lc.operating)
    np.testing.assert_array_equal(a.cylinders["1"].gas, c.cylinders["1"].gas)
    np.testing.assert_allclose(c.cylinders["1"].inertia, 9.0 * a.cylinders["1"].inertia, rtol=1e-12, atol=1e-9)


BAD = [
    ('speeds = ["1000 rpm", "2500 rpm", "1500 rpm"]', "operating.speeds", "speeds must increase: entry 2"),
    ('speeds = ["1000 rpm", "1000 rpm"]', "operating.speeds", "speeds must increase"),
    ('speeds = ["1000 rpm"]\nspeed_range = ["1000 rpm", "2000 rpm"]\nspeed_step = "100 rpm"', "operating", "not both"),
    ('speed_range = ["1000 rpm", "2000 rpm"]', "operating", "go together"),
    ('speed_range = ["2000 rpm", "1000 rpm"]\nspeed_step = "100 rpm"', "operating.speed_range", "increasing"),
    ('speed_range = ["1000 rpm", "2000 rpm"]\nspeed_step = "-100 rpm"', "operating.speed_step", "positive"),
    ('speed_range = ["100 rpm", "9000 rpm"]\nspeed_step = "1 rpm"', "operating.speed_step", "more than 200"),
    ('speeds = ["1000 rpm", "3000"]', "operating.speeds[1]", "unit"),
    (two_tables(1000, 1800), "operating.gas", "no gas pressure for 2000 rpm (the operating speed)"),
    ('speeds = ["500 rpm"]' + two_tables(), "operating.gas", "no gas pressure for 500 rpm (of the sweep)"),
    (two_tables(3000, 1000), "operating.gas[1].speed", "must increase"),
    ('\n[[operating.gas]]\nangle_unit = "deg"\n', "operating.gas[0].speed", "with its speed"),
    (TABLE.format(rpm=2000, points="[[0, -1.0], [720, 1.0]]"), "operating.gas[0]", "cannot be negative"),
]


@pytest.mark.parametrize("operating, key, reason", BAD, ids=[b[2][:30] for b in BAD])
def test_bad_full_load_input_is_refused_with_file_and_key(tmp_path, capsys, operating, key, reason):
    p = write(tmp_path, operating)
    with pytest.raises(InputError) as err:
        load_loadcase(p)
    assert err.value.file == str(p)
    assert err.value.key == key
    assert reason in str(err.value)
    assert main(["validate", str(p)]) == 2
    assert "Traceback" not in capsys.readouterr().err


RIGID = """
[torsion]
model = "lumped"
speed_range = ["{lo} rpm", "3000 rpm"]
speed_steps = 11

[[torsion.stations]]
name = "crank"
inertia = "1e-9 kg*m^2"
cylinders = ["1"]

[[torsion.stations]]
name = "flywheel"
inertia = "10 kg*m^2"
stiffness = "1e12 N*m/rad"
loss_factor = 0.02
"""


def test_torsional_excitation_follows_the_full_load_curve(tmp_path):
    """A crank of negligible inertia rigidly on a heavy flywheel: the shaft torque of the
    synthesis at a speed between two diagrams is the cylinder torque of the dynamics
    stage at that speed with the interpolated diagram (orders <= 12, an independent
    run), not the operating speed's diagram."""
    from fe_crank.mechanism.full_load import dynamics_at
    from fe_crank.torsion import analyse_torsion

    lc = load_loadcase(write(tmp_path, 'speeds = ["1000 rpm", "3000 rpm"]' + two_tables() + RIGID.format(lo=1000)))
    res = analyse_torsion(lc, cylinder_torques(lc.engine, lc.operating))
    for rpm in (1000.0, 1400.0, 2600.0):
        s = res.index(rpm * RPM)
        w = float(res.response.speeds[s])
        t = dynamics_at(lc.engine, lc.operating, w).cylinders["1"].torque
        spec = np.fft.rfft(t)
        spec[25:] = 0.0  # harmonic j = 2 n: orders above 12 dropped
        ref = np.fft.irfft(spec, n=t.size)
        syn = res.response.synthesis(s, res.theta)[0]
        np.testing.assert_allclose(syn, ref, rtol=0, atol=1e-6 * np.abs(ref).max())
    assert np.abs(res.vibratory(res.index(1400 * RPM))).max() < 1e-5 * np.abs(ref).max()


def test_torsional_speed_range_beyond_the_diagrams_is_refused(tmp_path):
    p = write(tmp_path, 'speeds = ["1000 rpm", "3000 rpm"]' + two_tables() + RIGID.format(lo=800))
    with pytest.raises(InputError, match="beyond the full-load diagrams") as err:
        load_loadcase(p)
    assert err.value.key == "torsion.speed_range"


def test_the_torsional_grid_holds_every_speed_of_the_sweep(tmp_path):
    from fe_crank.torsion import analyse_torsion

    lc = load_loadcase(
        write(tmp_path, 'speeds = ["1000 rpm", "1234 rpm", "2777 rpm"]' + two_tables() + RIGID.format(lo=1000))
    )
    res = analyse_torsion(lc, cylinder_torques(lc.engine, lc.operating))
    for w in lc.operating.full_load.speeds:
        assert res.response.speeds[res.index(w)] == pytest.approx(w, rel=1e-12)
