"""The torsional stage on a single-cylinder engine: the crank throw and the flywheel, a
two-mass system, against its closed form.

Throw ``J1`` (excited by the cylinder torque ``T``), flywheel ``J2``, shaft of stiffness
``k`` with loss factor ``eta`` (``k* = k (1 + i eta)``), no other damping.  For the
order ``n`` at crank speed ``omega`` (``Omega = n omega``)::

    J1 Theta1'' + k* (Theta1 - Theta2) = T_n,   J2 Theta2'' + k* (Theta2 - Theta1) = 0
    M_n = k* (Theta1 - Theta2) = T_n J2 / (J1 + J2) / (1 - Omega^2 / omega*^2),
    omega*^2 = k* (J1 + J2) / (J1 J2)

(Den Hartog, *Mechanical Vibrations*, sec. 2.4 for the undamped two-mass system).  The
quasi-static torque of the rigid shaft is ``T_n`` itself (the whole cylinder torque passes
the journal), so the vibratory torque of the order is ``T_n (J2 / (J1 + J2) / (1 - ...) - 1)``.
``T_n``: numpy's FFT of the dynamics stage's cylinder torque at that speed.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

from fe_crank import model
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism import dynamics
from fe_crank.mechanism.torques import cylinder_torques
from fe_crank.torsion import analyse_torsion

ROOT = Path(__file__).resolve().parents[2]
J1, J2, K, ETA = 0.02, 0.6, 2.0e4, 0.02  # kg m^2, kg m^2, N m/rad, -


def test_single_cylinder_vibratory_torque_is_the_two_mass_closed_form():
    lc = load_loadcase(ROOT / "loadcases" / "single_cylinder.toml")
    t = lc.torsion
    two_mass = dataclasses.replace(
        t,
        pulley=None,
        damper=None,
        driven=(),
        cylinder_damping=0.0,
        shaft_loss_factor=ETA,
        flywheel=dataclasses.replace(t.flywheel, inertia=J2, stiffness=K),
    )
    res = analyse_torsion(lc, cylinder_torques(lc.engine, lc.operating), settings=two_mass, inertias={"1": J1})
    assert res.model.names == ("1", "flywheel") and res.model.segment_names == ("1-flywheel",)
    w_star2 = K * (1 + 1j * ETA) * (J1 + J2) / (J1 * J2)
    # in range: omega* / n for n = 3.5, 4, 4.5 ... (162 Hz): resonances crossed
    assert any(r.in_range for r in res.resonances)
    for rpm in (800.0, 1500.0, 2430.0, 2600.0, 2800.0):
        s = res.index(rpm * np.pi / 30)
        w = float(res.response.speeds[s])
        torque = dynamics.analyse(lc.engine, model.OperatingPoint(w)).cylinders["1"].torque
        n_theta = torque.size
        c = np.fft.rfft(torque) / n_theta * 2.0
        orders = np.arange(c.size) * 2 * np.pi / lc.engine.cycle_angle
        keep = (orders > 0) & (orders <= 12 + 1e-9)
        factor = J2 / (J1 + J2) / (1.0 - (orders[keep] * w) ** 2 / w_star2) - 1.0
        phase = np.exp(1j * np.outer(res.theta, orders[keep]))
        expected = np.real(phase @ (c[keep] * factor))
        got = res.vibratory(s)[0]
        np.testing.assert_allclose(got, expected, rtol=0, atol=1e-6 * np.abs(expected).max())
