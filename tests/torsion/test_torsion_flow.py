"""Torque flow through the throws: entering and leaving torques for either power take-off
end by hand, the vibration's inertia torque, and the FE throw in equilibrium with the
torsional stage's rear journal torque (a real mesh and solve)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank import model
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.torques import cylinder_torques
from fe_crank.torsion import analyse_torsion
from fe_crank.torsion.flow import fe_loads, torque_flow

ROOT = Path(__file__).resolve().parents[2]
GENSET = ROOT / "loadcases" / "inline4_genset_torsion.toml"


@pytest.fixture(scope="module")
def genset():
    lc = load_loadcase(GENSET)
    return lc, dynamics.analyse(lc.engine, lc.operating)


def test_quasi_static_flow_for_either_end_by_hand(genset):
    """Four throws in axial order 1..4, T_i = the sum of each throw's cylinder torques
    (R F_t): rear take-off, throw 2 receives T1 and passes T1 + T2 on; front take-off,
    throw 2 receives T3 + T4 at its rear journal and passes T2 + T3 + T4 on; throw 4
    receives nothing; the leaving torque of throw 1 with front take-off is the engine's."""
    lc, dyn = genset
    t = {n: sum(c.torque for c in dyn.cylinders.values() if c.throw == n) for n in "1234"}
    rear = torque_flow(dyn, lc.engine, reaction="end_2")
    front = torque_flow(dyn, lc.engine, reaction="end_1")
    np.testing.assert_allclose(rear["2"].torque_in, t["1"], atol=1e-9)
    np.testing.assert_allclose(rear["2"].torque_out, t["1"] + t["2"], atol=1e-9)
    np.testing.assert_allclose(front["2"].torque_in, t["3"] + t["4"], atol=1e-9)
    np.testing.assert_allclose(front["2"].torque_out, t["2"] + t["3"] + t["4"], atol=1e-9)
    np.testing.assert_allclose(front["4"].torque_in, 0.0, atol=0)
    np.testing.assert_allclose(front["1"].torque_out, dyn.torque, atol=1e-9)
    for n in "1234":  # the rear take-off is the dynamics stage's determinate journal torque
        np.testing.assert_allclose(rear[n].torque_in, dyn.throws[n].torque_front, atol=1e-9)
        np.testing.assert_allclose(rear[n].torque_out - rear[n].torque_in, t[n], atol=1e-9)


def test_front_take_off_with_a_torsional_chain_is_refused(genset):
    lc, dyn = genset
    res = analyse_torsion(lc, cylinder_torques(lc.engine, lc.operating), inertias=dict.fromkeys("1234", 0.012))
    with pytest.raises(InputError, match="contradicts") as err:
        torque_flow(dyn, lc.engine, reaction="end_1", torsion=res)
    assert err.value.key == "fe.torque_reaction"


def spectral_second_derivative(values: np.ndarray, cycle: float) -> np.ndarray:
    """d^2/dtheta^2 of a periodic sample on the uniform grid (exact for its harmonics)."""
    k = np.fft.rfftfreq(values.size, d=cycle / values.size) * 2 * np.pi
    return np.fft.irfft(-(k**2) * np.fft.rfft(values), n=values.size)


def test_vibration_adds_the_throws_inertia_and_damping_torque(genset):
    """At a speed of the grid: the entering and leaving torques are the torsional stage's
    journal torques there, the angular acceleration is omega^2 d^2(angle)/dtheta^2 of the
    throw's synthesised vibration angle (spectral derivative, written here), and
    T_out - T_in = T_own - J alpha - c theta' (the throw mass's equation of motion)."""
    lc, _ = genset
    res = analyse_torsion(lc, cylinder_torques(lc.engine, lc.operating), inertias=dict.fromkeys("1234", 0.012))
    s = res.index(2600 * np.pi / 30)
    w = float(res.response.speeds[s])
    dyn = dynamics.analyse(lc.engine, model.OperatingPoint(w))
    flow = torque_flow(dyn, lc.engine, torsion=res)
    vib = res.vibratory(s)
    for n in "1234":
        f = flow[n]
        front, rear = res.journal_segments(n)
        np.testing.assert_allclose(f.torque_in, dyn.throws[n].torque_front + vib[front], atol=1e-9)
        np.testing.assert_allclose(f.torque_out, dyn.throws[n].torque_rear + vib[rear], atol=1e-9)
        angle = res.response.angle_synthesis(s, res.theta)[res.model.throw_mass[n]]
        alpha = w**2 * spectral_second_derivative(angle, res.theta[-1] + res.theta[1])
        np.testing.assert_allclose(f.angular_acceleration, alpha, rtol=0, atol=1e-8 * np.abs(alpha).max())
        assert f.inertia == pytest.approx(0.012)
        lhs = f.torque_out - f.torque_in
        rhs = f.own - f.inertia * f.angular_acceleration - f.damping_torque
        np.testing.assert_allclose(lhs, rhs, rtol=0, atol=1e-7 * np.abs(f.own).max())
        assert np.abs(f.inertia * f.angular_acceleration).max() > 0.02 * np.abs(f.own).max()


@pytest.mark.heavy
def test_fe_throw_carries_the_torsional_rear_journal_torque(mesh_cache):
    """tests/data/small_torsion.toml on its test mesh with the angular-acceleration unit
    case: the unit case's moment about the axis is the mesh's J_z (the B-rep value of the
    geometry stage within 1 %), and the superposed torque reacted at the rear face
    equals the torsional stage's rear journal torque at every angle: the FE model in
    equilibrium with each journal's own torque."""
    from fe_crank.assess.superpose import load_coefficients
    from fe_crank.fe import CASES, FeOptions, solve_unit_cases
    from fe_crank.geometry.mass import mass_properties
    from fe_crank.mesh import mesh_throw

    lc = load_loadcase(ROOT / "tests" / "data" / "small_torsion.toml")
    tm = mesh_throw(lc.geometry, size="test", cache_dir=mesh_cache)  # the run's: the check's own small twin mesh
    cases = (*CASES, "angular_acceleration")
    units = solve_unit_cases(tm, lc.material, dataclasses.replace(lc.fe or FeOptions(), cases=cases))
    j_fe = float(units.cases["angular_acceleration"].applied[5])
    j_cad = mass_properties(lc.geometry, lc.geometry.throws[0]).total.inertia_axis
    assert j_fe == pytest.approx(j_cad, rel=0.01)
    res = analyse_torsion(lc, cylinder_torques(lc.engine, lc.operating), inertias={"1": 3 * j_fe, "2": 3 * j_fe})
    s = res.index(3300 * np.pi / 30)
    w = float(res.response.speeds[s])
    dyn = dynamics.analyse(lc.engine, model.OperatingPoint(w))
    flow = torque_flow(dyn, lc.engine, torsion=res)
    for n in ("1", "2"):
        f = flow[n]
        loads = fe_loads(f, dyn.throws[n].pin_force, fe_inertia=j_fe, crank_radius=0.020, sense=1)
        c = load_coefficients(
            loads.pin_force, loads.torque, w, cases=cases, angular_acceleration=loads.angular_acceleration
        )
        mz = np.array([units.cases[k].reactions["end_2"][5] for k in cases])
        reacted = c @ mz  # moment of the rear face's reaction about +z = torque passed on in the sense of rotation
        np.testing.assert_allclose(reacted, f.torque_out, rtol=0, atol=1e-6 * np.abs(f.torque_out).max())
        assert np.abs(f.torque_out - f.torque_in - f.own).max() > 0.01 * np.abs(f.own).max()


def _copy_case(tmp_path, name: str, old: str, new: str) -> Path:
    text = (ROOT / "loadcases" / name).read_text()
    assert old in text
    (tmp_path / "geometry").mkdir(exist_ok=True)
    for g in (ROOT / "geometry").glob("*.toml"):
        (tmp_path / "geometry" / g.name).write_text(g.read_text())
    (tmp_path / "engines").mkdir(exist_ok=True)
    for e in (ROOT / "engines").glob("*.toml"):
        (tmp_path / "engines" / e.name).write_text(e.read_text())
    (tmp_path / "loadcases").mkdir(exist_ok=True)
    p = tmp_path / "loadcases" / name
    p.write_text(text.replace(old, new))
    return p


def test_front_take_off_on_a_multi_throw_engine_is_refused_at_input(tmp_path):
    """The check sums journal torques from the front: a front take-off on the inline-4
    is refused with the file and the key; on a single throw it is accepted."""
    p = _copy_case(tmp_path, "inline4_genset_torsion.toml", "[fe]\n", '[fe]\ntorque_reaction = "end_1"\n')
    with pytest.raises(InputError, match="front power take-off on a shaft with 4 throws") as err:
        load_loadcase(p)
    assert err.value.file == str(p) and err.value.key == "fe.torque_reaction"
    one = _copy_case(tmp_path, "single_cylinder.toml", "[fe]\n", '[fe]\ntorque_reaction = "end_1"\n')
    assert load_loadcase(one).fe.torque_reaction == "end_1"
