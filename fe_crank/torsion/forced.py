"""Forced damped response of the chain to the cylinders' harmonic torques (direct
frequency response, every order at every speed).

For an order ``n`` at crank speed ``omega`` the excitation frequency is
``Omega = n omega`` and the complex angle amplitudes solve (Den Hartog sec. 5.8;
the hysteretic segments as complex stiffness)::

    (K (1 + i eta) - Omega^2 J + i Omega C) Theta_n = T_n,

``T_n`` the vector of the order-``n`` harmonics of the cylinder torques summed on their
throws' masses.  The segment torque amplitude is
``(k (1 + i eta) + i Omega c) (Theta_i - Theta_{i+1})``.  Order 0 (the mean torque) is
not a vibration: the driven machine takes the mean torque, so each segment carries the
mean torque of the cylinders before it, the quasi-static value of the dynamics stage.

The time history over the cycle is the harmonic synthesis
``T_seg(theta) = T_mean + Re sum_n T_seg,n exp(i n theta)`` (IACS UR M53 2.2.2: orders
0.5 .. 12 for four-stroke, 1 .. 15 for two-stroke engines).  The *vibratory* torque of
a segment is this synthesis less the quasi-static torque of the same orders (the
rigid-shaft cumulative cylinder torque of the dynamics stage): what the elasticity and
inertia of the shaft add.  The assessment takes the dynamics stage's exact quasi-static
torque plus this vibratory part, so the orders above the synthesis are kept unamplified.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from fe_crank.torsion.excitation import CylinderHarmonics
from fe_crank.torsion.model import TorsionModel


def m53_orders(strokes: int) -> np.ndarray:
    """Orders of IACS UR M53 2.2.2: 0.5 .. 12 (four-stroke), 1 .. 15 (two-stroke)."""
    return np.arange(1, 25) * 0.5 if strokes == 4 else np.arange(1, 16) * 1.0


def receptance(model: TorsionModel, frequency: float) -> np.ndarray:
    """``(K (1 + i eta) - Omega^2 J + i Omega C)`` at ``Omega = frequency`` rad/s."""
    return (
        model.stiffness_matrix(hysteretic=True)
        - frequency**2 * model.mass_matrix()
        + 1j * frequency * model.damping_matrix()
    )


@dataclass(frozen=True)
class ForcedResponse:
    """Response over ``speeds`` (rad/s) for ``orders``.

    ``segment[s, o, i]``: complex torque amplitude of segment ``i``, order ``o``, speed ``s``;
    ``angle[s, o, m]``: complex angle amplitude of mass ``m``.  ``mean_torque[i]`` the
    mean (order-0) torque of segment ``i`` at each speed ``[s, i]``.
    """

    speeds: np.ndarray
    orders: np.ndarray
    segment: np.ndarray
    angle: np.ndarray
    mean_torque: np.ndarray
    _phases: dict = field(default_factory=dict, repr=False, compare=False)

    def _phase(self, theta) -> np.ndarray:
        """``exp(i n theta)`` (n_orders, n_theta), kept for the grid last asked for."""
        theta = np.asarray(theta, float)
        key = (theta.size, float(theta[0]), float(theta[-1]))
        if key not in self._phases:
            self._phases.clear()
            self._phases[key] = np.exp(1j * np.outer(self.orders, theta))
        return self._phases[key]

    def synthesis(self, s: int, theta: np.ndarray) -> np.ndarray:
        """Segment torques (n_seg, n_theta) over the cycle at speed index ``s``."""
        ph = self._phase(theta)
        seg = np.ascontiguousarray(self.segment[s].T)
        return self.mean_torque[s][:, None] + seg.real @ ph.real - seg.imag @ ph.imag

    def synthesis_all(self, theta: np.ndarray) -> np.ndarray:
        """Segment torques (n_speeds, n_seg, n_theta) at every speed (real matrix products)."""
        ph = self._phase(theta)
        re = np.einsum("son,ot->snt", self.segment.real, ph.real, optimize=True)
        im = np.einsum("son,ot->snt", self.segment.imag, ph.imag, optimize=True)
        return self.mean_torque[:, :, None] + re - im

    def angle_synthesis(self, s: int, theta: np.ndarray) -> np.ndarray:
        return np.real(self.angle[s].T @ self._phase(theta))

    def velocity_synthesis(self, s: int, theta: np.ndarray) -> np.ndarray:
        """Vibratory angular velocity of every mass (n, n_theta), rad/s."""
        w = 1j * self.orders[:, None] * self.speeds[s]
        return np.real((w * self.angle[s]).T @ self._phase(theta))


def forced_response(model: TorsionModel, harmonics: CylinderHarmonics, speeds, orders=None) -> ForcedResponse:
    """Direct frequency response (module docstring) for every speed and order.

    ``orders`` default: every harmonic of ``harmonics`` except 0 up to the IACS UR M53
    limit (12 four-stroke, 15 two-stroke); they must be harmonics of the cycle."""
    speeds = np.atleast_1d(np.asarray(speeds, float))
    if orders is None:
        top = 12.0 if np.isclose(harmonics.cycle, 4 * np.pi) else 15.0
        orders = harmonics.orders[(harmonics.orders > 0) & (harmonics.orders <= top + 1e-9)]
    orders = np.asarray(orders, float)
    index = [int(np.argmin(np.abs(harmonics.orders - o))) for o in orders]
    if not np.allclose(harmonics.orders[index], orders):
        raise ValueError("orders must be harmonics of the engine cycle")
    # per-mass excitation, gas parts (one per diagram of a full-load curve) and inertia part (n_mass, n_harmonics)
    parts = harmonics.gas_parts()
    gas_parts = np.zeros((len(parts), model.size, harmonics.orders.size), complex)
    inertia = np.zeros(gas_parts.shape[1:], complex)
    for cyl, throw in harmonics.throw_of.items():
        for j, part in enumerate(parts):
            gas_parts[j, model.throw_mass[throw]] += part[cyl]
        inertia[model.throw_mass[throw]] += harmonics.inertia[cyl]
    kh, jm, cm = model.stiffness_matrix(hysteretic=True), model.mass_matrix(), model.damping_matrix()
    k = np.asarray(model.stiffness, float)
    ks = (k * (1 + 1j * np.asarray(model.loss_factor, float)))[None, :]
    cs = np.asarray(model.segment_damping, float)[None, :]
    seg = np.zeros((speeds.size, orders.size, model.size - 1), complex)
    ang = np.zeros((speeds.size, orders.size, model.size), complex)
    mean = np.zeros((speeds.size, model.size - 1))
    for s, w in enumerate(speeds):
        gas = np.tensordot(harmonics.gas_weights(w), gas_parts, axes=1)
        t = gas + (w / harmonics.reference_speed) ** 2 * inertia
        mean[s] = np.cumsum(np.real(t[:, 0]))[:-1]
        f = (orders * w)[:, None, None]
        a = kh[None] - f**2 * jm[None] + 1j * f * cm[None]  # (n_orders, n, n)
        x = np.linalg.solve(a, t[:, index].T[:, :, None])[:, :, 0]  # (n_orders, n)
        ang[s] = x
        seg[s] = (ks + 1j * f[:, :, 0] * cs) * (x[:, :-1] - x[:, 1:])
    return ForcedResponse(speeds, orders, seg, ang, mean)
