"""Cylinder torque harmonics: synthesis against the dynamics stage's time-domain torque,
and the firing-order phase sums of in-line engines against the textbook table."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from fe_crank import model
from fe_crank.io.engine import load_engine
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.torques import cylinder_torques
from fe_crank.torsion.excitation import cylinder_harmonics, order_phase_sum

ROOT = Path(__file__).resolve().parents[2]
CASE = ROOT / "loadcases" / "inline4_genset_torsion.toml"


@pytest.fixture(scope="module")
def case():
    return load_loadcase(CASE)


def test_synthesis_reproduces_the_dynamics_torque(case):
    """All harmonics of the 720-point grid give back T(theta) of fe_crank.mechanism.dynamics to
    round-off (the discrete Fourier pair is exact), at the reference speed."""
    w = case.operating.speed
    h = cylinder_harmonics(cylinder_torques(case.engine, model.OperatingPoint(w)))
    res = dynamics.analyse(case.engine, case.operating)
    for name, cf in res.cylinders.items():
        syn = h.synthesise(name, w, res.theta)
        assert np.abs(syn - cf.torque).max() < 1e-9 * np.abs(cf.torque).max()


def test_speed_scaling_against_an_independent_dynamics_run(case):
    """T(omega) = T_gas + (omega/omega_0)^2 T_inertia: harmonics taken at 3000 rpm give
    the torque the dynamics stage computes directly at 1300 rpm (exact slider-crank at
    constant speed: inertia forces scale with omega^2)."""
    h = cylinder_harmonics(cylinder_torques(case.engine, model.OperatingPoint(case.operating.speed)))
    w2 = 1300 * np.pi / 30
    res = dynamics.analyse(case.engine, model.OperatingPoint(w2))
    for name, cf in res.cylinders.items():
        assert np.abs(h.synthesise(name, w2, res.theta) - cf.torque).max() < 1e-9 * np.abs(cf.torque).max()


def test_truncated_synthesis_to_order_12_is_close(case):
    """The UR M53 orders (0.5 .. 12) keep the torque within 5 % of its peak for this
    Wiebe cycle (the steep pressure rise carries content above order 12)."""
    w = case.operating.speed
    h = cylinder_harmonics(cylinder_torques(case.engine, model.OperatingPoint(w)))
    res = dynamics.analyse(case.engine, case.operating)
    keep = h.orders[h.orders <= 12]
    cf = res.cylinders["1"]
    err = np.abs(h.synthesise("1", w, res.theta, orders=keep) - cf.torque).max()
    assert err < 0.05 * np.abs(cf.torque).max()


@pytest.mark.parametrize(
    "engine_file, majors", [("inline4.toml", (2, 4, 6, 8, 10, 12)), ("inline6.toml", (3, 6, 9, 12))]
)
def test_inline_phase_sums_major_orders_add_minor_cancel(engine_file, majors):
    """Four-stroke in-line engines with even firing (Ker Wilson vol. 2; Den Hartog sec. 5.8
    'phase diagrams'): with equal amplitudes the order-n vectors of all cylinders add for
    the major orders n = k * (cylinders / 2) and cancel for every other order 0.5 .. 12
    (inline-4 firing 1-3-4-2, inline-6 firing 1-5-3-6-2-4)."""
    engine = load_engine(ROOT / "engines" / engine_file)
    for n in np.arange(1, 25) * 0.5:
        s = order_phase_sum(engine, n)
        if any(np.isclose(n, m) for m in majors):
            assert s == pytest.approx(1.0, abs=1e-12), n
        else:
            assert s == pytest.approx(0.0, abs=1e-12), n
