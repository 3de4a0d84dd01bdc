"""The explicit lumped torsional model and the untuned viscous (Houdaille) damper:
Den Hartog's optimum damper against the forced response, a two-station case by hand
through the input file, and bad station input refused with the file and the key."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from fe_crank import model
from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.torques import cylinder_torques
from fe_crank.torsion import analyse_torsion
from fe_crank.torsion.excitation import CylinderHarmonics
from fe_crank.torsion.forced import forced_response
from fe_crank.torsion.free import holzer_frequencies, natural_modes
from fe_crank.torsion.model import TorsionModel

ROOT = Path(__file__).resolve().parents[2]
RPM = np.pi / 30


def houdaille(mu: float, zeta: float, j: float = 0.05, k: float = 4e5) -> TorsionModel:
    """Ring J_d = mu J on the main disc by a viscous film c = 2 zeta J_d omega_n alone;
    the main disc on a shaft k to a disc heavy enough to stand still."""
    wn = np.sqrt(k / j)
    c = 2 * zeta * mu * j * wn
    return TorsionModel(
        ("ring", "main", "ground"),
        np.array([mu * j, j, 1e10]),
        np.array([0.0, k]),
        np.zeros(2),
        np.array([c, 0.0]),
        np.zeros(3),
        ("ring-main", "main-ground"),
        {"main": 1},
    )


def main_disc_amplitude(m: TorsionModel, g: np.ndarray, k: float = 4e5) -> np.ndarray:
    """|theta_main| / (T0 / k) for a torque T0 on the main disc at Omega = g omega_n."""
    wn = np.sqrt(k / m.inertia[1])
    h = CylinderHarmonics(np.array([0.0, 1.0]), {"c": np.array([0.0, 1.0])}, {"c": np.zeros(2)}, 1.0, 2 * np.pi, {})
    h = CylinderHarmonics(h.orders, h.gas, h.inertia, 1.0, h.cycle, {"c": "main"})
    r = forced_response(m, h, g * wn, [1.0])
    return np.abs(r.angle[:, 0, 1] - r.angle[:, 0, 2]) * k


@pytest.mark.parametrize("mu", [0.25, 0.5])
def test_houdaille_damper_fixed_point_and_den_hartog_optimum(mu):
    """Den Hartog, *Mechanical Vibrations*, 4th ed., sec. 3.9 (untuned viscous damper):
    every damping passes through the point g_P^2 = 2 / (2 + mu) at amplitude
    1 + 2 / mu times static; the optimum damping zeta_opt = 1 / sqrt(2 (1 + mu)(2 + mu))
    (c = 2 zeta J_d omega_n) makes that point the peak, and any other damping a higher
    peak.  zeta -> 0 (free ring) and zeta -> oo (locked ring) bound the response."""
    g_p = np.sqrt(2 / (2 + mu))
    z_opt = 1 / np.sqrt(2 * (1 + mu) * (2 + mu))
    for z in (0.05, z_opt, 1.0):
        assert main_disc_amplitude(houdaille(mu, z), np.array([g_p]))[0] == pytest.approx(1 + 2 / mu, rel=1e-6)
    g = np.linspace(0.6, 1.3, 7001)
    peak = main_disc_amplitude(houdaille(mu, z_opt), g).max()
    assert peak == pytest.approx(1 + 2 / mu, rel=1e-5)
    for f in (0.7, 1.4):
        assert main_disc_amplitude(houdaille(mu, f * z_opt), g).max() > 1.005 * peak


def test_houdaille_ring_is_a_free_body_of_the_undamped_chain():
    """Without its film the ring turns freely: two rigid-body modes, and the one elastic
    mode is the main disc's sqrt(k / J) (ground 1e10 kg m^2); Holzer agrees."""
    m = houdaille(0.25, 0.2)
    modes = natural_modes(m)
    assert modes.rigid == 2
    np.testing.assert_allclose(modes.elastic_omega, [np.sqrt(4e5 / 0.05)], rtol=1e-6)
    np.testing.assert_allclose(holzer_frequencies(m, 2 * modes.omega[-1]), modes.elastic_omega, rtol=1e-9)


TWO_STATIONS = """\
name = "one cylinder on a two-station lumped chain"

[operating]
speed = "2000 rpm"

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

[engine.gas]
model = "wiebe"
compression_ratio = 10.0
intake_pressure = "0.1 MPa"
exhaust_pressure = "0.11 MPa"
heat_released = "0.6 kJ"
combustion_start = "-15 deg"
combustion_duration = "50 deg"

[torsion]
model = "lumped"
speed_range = ["1000 rpm", "3000 rpm"]
speed_steps = 21

[[torsion.stations]]
name = "crank"
inertia = "0.02 kg*m^2"
cylinders = ["1"]

[[torsion.stations]]
name = "flywheel"
inertia = "0.3 kg*m^2"
stiffness = "2e5 N*m/rad"
loss_factor = 0.03
"""
J1, J2, K, ETA = 0.02, 0.3, 2e5, 0.03


def write(tmp_path, text=TWO_STATIONS) -> Path:
    p = tmp_path / "case.toml"
    p.write_text(text)
    return p


def test_two_station_chain_by_hand(tmp_path):
    """Torque T_n on disc 1 of two discs: the shaft torque is
    T_n k* J2 / (k* (J1 + J2) - Omega^2 J1 J2), k* = k (1 + i eta), Omega = n omega
    (from the 2 x 2 dynamic stiffness); with the mean torque the synthesis over the
    cycle.  T_n from a dynamics run at each speed and an explicit Fourier sum."""
    lc = load_loadcase(write(tmp_path))
    res = analyse_torsion(lc, cylinder_torques(lc.engine, lc.operating))
    assert res.model.names == ("crank", "flywheel") and res.model.throw_mass == {"1": 0}
    assert res.modes.elastic_omega[0] == pytest.approx(np.sqrt(K * (J1 + J2) / (J1 * J2)), rel=1e-12)
    assert res.stiffness["used"] == "lumped" and "carter" not in res.stiffness
    theta = res.theta
    for rpm in (1000.0, 1900.0, 3000.0):
        s = res.index(rpm * RPM)
        w = res.response.speeds[s]
        t = dynamics.analyse(lc.engine, model.OperatingPoint(w)).cylinders["1"].torque
        hand = np.full(theta.size, t.mean())
        for n in res.response.orders:
            tn = 2.0 / t.size * np.sum(t * np.exp(-1j * n * theta))
            ks = K * (1 + 1j * ETA)
            hand += np.real(tn * ks * J2 / (ks * (J1 + J2) - (n * w) ** 2 * J1 * J2) * np.exp(1j * n * theta))
        np.testing.assert_allclose(res.response.synthesis(s, theta)[0], hand, rtol=0, atol=1e-8 * np.abs(hand).max())
        assert res.half_range[s, 0] == pytest.approx(0.5 * np.ptp(hand), rel=1e-8)


BAD = [
    ('inertia = "0.3 kg*m^2"\n', "", "torsion.stations[1].inertia", "a station needs its inertia"),
    ('inertia = "0.3 kg*m^2"', 'inertia = "0 kg*m^2"', "torsion.stations[1].inertia", "inertia must be positive"),
    (
        "loss_factor = 0.03",
        'loss_factor = 0.03\ndamping = "-2 N*m*s/rad"',
        "torsion.stations[1].damping",
        "damping must not",
    ),
    ('stiffness = "2e5 N*m/rad"', 'stiffness = "-2e5 N*m/rad"', "torsion.stations[1].stiffness", "stiffness must not"),
    ('stiffness = "2e5 N*m/rad"', 'stiffness = "2e5 N*m"', "torsion.stations[1].stiffness", "per angle"),
    ('stiffness = "2e5 N*m/rad"\nloss_factor = 0.03\n', "", "torsion.stations[1]", "needs its connection"),
    ('cylinders = ["1"]', 'cylinders = ["1"]\nstiffness = "1e5 N*m/rad"', "torsion.stations[0]", "first station"),
    ('cylinders = ["1"]', 'cylinders = ["7"]', "torsion.stations[0].cylinders[0]", "names cylinder '7'"),
    ('cylinders = ["1"]', "", "torsion.stations", "act on no station"),
    ("loss_factor = 0.03", "loss_factor = 0.0", "torsion.stations", "no station or connection has damping"),
    ('name = "flywheel"', 'name = "crank"', "torsion.stations[1].name", "duplicate station name"),
    ("speed_steps = 21", "speed_steps = 21\nshaft_loss_factor = 0.02", "torsion.shaft_loss_factor", "unknown key"),
    ("speed_steps = 21", 'speed_steps = 21\nflywheel_station = "rotor"', "torsion.flywheel_station", "not defined"),
]


@pytest.mark.parametrize("old, new, key, reason", BAD, ids=[b[3][:24] for b in BAD])
def test_bad_stations_are_refused_with_file_and_key(tmp_path, capsys, old, new, key, reason):
    assert old in TWO_STATIONS
    p = write(tmp_path, TWO_STATIONS.replace(old, new, 1))
    with pytest.raises(InputError) as err:
        load_loadcase(p)
    assert err.value.file == str(p)
    assert err.value.key == key
    assert reason in str(err.value)
    assert main(["validate", str(p)]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_cad_model_takes_a_viscous_damper_without_stiffness(tmp_path):
    """The shipped genset with its rubber damper replaced by a Houdaille ring (no
    stiffness): parsed with a zero-stiffness film, the ring a free body of the
    undamped chain, the damped response bounded."""
    text = (ROOT / "loadcases" / "inline4_genset_torsion.toml").read_text()
    old = 'stiffness = "2.0e4 N*m/rad"\ndamping = "3 N*m*s/rad"\nloss_factor = 0.15'
    assert old in text
    (tmp_path / "geometry").mkdir()
    (tmp_path / "geometry" / "inline4.toml").write_text((ROOT / "geometry" / "inline4.toml").read_text())
    (tmp_path / "loadcases").mkdir()
    p = tmp_path / "loadcases" / "case.toml"
    p.write_text(text.replace(old, 'damping = "30 N*m*s/rad"'))
    lc = load_loadcase(p)
    t = lc.torsion
    assert t.damper.stiffness == 0.0 and t.damper.damping == pytest.approx(30.0)
    res = analyse_torsion(lc, cylinder_torques(lc.engine, lc.operating), inertias=dict.fromkeys("1234", 0.012))
    assert res.modes.rigid == 2
    assert np.all(np.isfinite(res.half_range)) and res.half_range.max() < 1e4
    p.write_text(text.replace(old, 'damping = "0 N*m*s/rad"'))
    with pytest.raises(InputError, match="needs a positive damping") as err:
        load_loadcase(p)
    assert err.value.key == "torsion.damper"
