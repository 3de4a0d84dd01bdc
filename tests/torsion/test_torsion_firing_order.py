"""Two firing orders of the inline-6 that the major-order phase sums cannot tell apart
(1-5-3-6-2-4 and 1-2-3-6-5-4 fire at the same set of angles), against a harmonic
synthesis written here from scratch: the reference cylinder's torque from the dynamics
stage at each speed, shifted to each cylinder's firing angle, its discrete Fourier
coefficients by explicit sums, the chain's dynamic stiffness assembled here, and the
segment torques synthesised over the cycle."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank import model
from fe_crank.io.engine import load_engine
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.torques import cylinder_torques
from fe_crank.torsion.excitation import cylinder_harmonics, order_phase_sum
from fe_crank.torsion.forced import forced_response
from fe_crank.torsion.model import TorsionModel

ROOT = Path(__file__).resolve().parents[2]
J_THROW, K_PITCH, ETA, C_CYL = 0.02, 6.0e5, 0.03, 0.2  # kg m^2, N m/rad, -, N m s/rad
J_FLY, K_FLY = 0.4, 8.0e5
SPEEDS = np.radians(6.0) * np.array([900.0, 1500.0, 2100.0, 2700.0, 3300.0, 3900.0])  # rpm -> rad/s
ORDERS = np.arange(1, 25) * 0.5  # UR M53 2.2.2: 0.5 .. 12 (four-stroke)


def inline6(order: str) -> model.Engine:
    """engines/inline6.toml (1-5-3-6-2-4) with the seed 001 indicator diagram lent to it,
    or the same crank firing 1-2-3-6-5-4 (the offsets of cylinders 2/5 and 3/4 exchanged
    as the file had them)."""
    e = load_engine(ROOT / "engines" / "inline6.toml")
    gas = load_loadcase(ROOT / "loadcases" / "single_cylinder.toml").engine.gas
    e = dataclasses.replace(e, gas=gas)
    if order == "1-5-3-6-2-4":
        return e
    deg = {"1": 0, "2": 120, "3": 240, "4": 600, "5": 480, "6": 360}
    cyls = tuple(dataclasses.replace(c, firing_offset=np.radians(deg[c.name])) for c in e.cylinders)
    return dataclasses.replace(e, cylinders=cyls)


def chain() -> TorsionModel:
    names = ("1", "2", "3", "4", "5", "6", "flywheel")
    return TorsionModel(
        names,
        np.array([J_THROW] * 6 + [J_FLY]),
        np.array([K_PITCH] * 5 + [K_FLY]),
        np.full(6, ETA),
        np.zeros(6),
        np.array([C_CYL] * 6 + [0.0]),
        ("1-2", "2-3", "3-4", "4-5", "5-6", "6-flywheel"),
        {n: i for i, n in enumerate(names[:6])},
    )


def independent_segment_torques(engine: model.Engine, speed: float, theta: np.ndarray) -> np.ndarray:
    """Segment torques (6, n_theta) at ``speed`` (module docstring), no fe_crank.torsion."""
    one = dataclasses.replace(
        engine,
        throws=(dataclasses.replace(engine.throw("1"), angle=0.0),),
        cylinders=(dataclasses.replace(engine.cylinder("1"), firing_offset=0.0),),
    )
    t_ref = dynamics.analyse(one, model.OperatingPoint(speed)).cylinders["1"].torque  # 1 deg grid
    n = theta.size
    j_vec = np.array([J_THROW] * 6 + [J_FLY])
    k_vec = np.array([K_PITCH] * 5 + [K_FLY]) * (1 + 1j * ETA)
    c_vec = np.array([C_CYL] * 6 + [0.0])
    k_mat = np.zeros((7, 7), complex)
    for i, k in enumerate(k_vec):
        k_mat[np.ix_([i, i + 1], [i, i + 1])] += k * np.array([[1, -1], [-1, 1]])
    force = np.zeros((ORDERS.size, 7), complex)
    mean = np.zeros(7)
    for c in engine.cylinders:
        shift = int(round(np.degrees(c.firing_offset)))  # the cylinder fires shift degrees after cylinder 1
        t_c = np.roll(t_ref, shift)
        mass = int(c.throw) - 1
        mean[mass] += t_c.mean()
        for o, order in enumerate(ORDERS):
            force[o, mass] += 2.0 / n * np.sum(t_c * np.exp(-1j * order * theta))
    out = np.tile(np.cumsum(mean)[:-1, None], (1, n)).astype(float)
    for o, order in enumerate(ORDERS):
        w = order * speed
        x = np.linalg.solve(k_mat - w**2 * np.diag(j_vec) + 1j * w * np.diag(c_vec), force[o])
        seg = k_vec * (x[:-1] - x[1:])
        out += np.real(seg[:, None] * np.exp(1j * order * theta)[None, :])
    return out


@pytest.fixture(scope="module")
def responses():
    out = {}
    for order in ("1-5-3-6-2-4", "1-2-3-6-5-4"):
        e = inline6(order)
        h = cylinder_harmonics(cylinder_torques(e, model.OperatingPoint(SPEEDS[-1])))
        out[order] = (e, forced_response(chain(), h, SPEEDS, ORDERS))
    return out


def test_the_two_orders_have_the_same_phase_sums():
    """Same set of firing angles: every order's phase sum is the same, so the phase-sum
    table (majors 3, 6, 9, 12 add) cannot tell these orders apart."""
    a, b = inline6("1-5-3-6-2-4"), inline6("1-2-3-6-5-4")
    for n in ORDERS:
        assert order_phase_sum(a, n) == pytest.approx(order_phase_sum(b, n), abs=1e-12)


@pytest.mark.parametrize("order", ["1-5-3-6-2-4", "1-2-3-6-5-4"])
def test_segment_torques_against_the_independent_synthesis(responses, order):
    e, r = responses[order]
    theta = 4 * np.pi * np.arange(720) / 720
    syn = r.synthesis_all(theta)
    for s, w in enumerate(SPEEDS):
        ref = independent_segment_torques(e, w, theta)
        scale = np.abs(ref).max()
        np.testing.assert_allclose(syn[s], ref, rtol=0, atol=1e-8 * scale)


def test_the_orders_differ_in_an_inner_segment(responses):
    """The vibratory torque of the middle journal (3-4) is not the same for the two
    orders: M_TN differs by more than 10 % at some speed of the range."""
    theta = 4 * np.pi * np.arange(720) / 720
    m = {k: 0.5 * np.ptp(r.synthesis_all(theta)[:, 2], axis=1) for k, (_, r) in responses.items()}
    ratio = m["1-2-3-6-5-4"] / m["1-5-3-6-2-4"]
    assert np.max(np.abs(ratio - 1.0)) > 0.10
