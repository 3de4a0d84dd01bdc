"""Harmonic components of each cylinder's torque: gas part and inertia part.

The dynamics stage gives a cylinder's torque ``T(theta)`` over one cycle at constant
speed, without gas and with each diagram at the reference speed
(``EngineCycles.torques``, ``fe_crank.mechanism.torques``).  At constant speed the
inertia forces of the exact slider-crank scale exactly with ``omega^2`` (``a, beta''``
and the rod's accelerations are ``omega^2`` times functions of the crank angle), the gas force does not depend on speed (the same
indicator diagram at every speed: the full-load diagram over the whole speed range,
as IACS UR M53 2.2.2 asks for the synthesis), so::

    T(theta; omega) = T_gas(theta) + (omega / omega_0)^2 T_inertia(theta; omega_0)

``T_inertia`` is the torque of the engine run without gas pressure, ``T_gas`` the rest.
Fourier series over the cycle (``N`` equal steps, cycle ``Theta`` = 4 pi four-stroke,
2 pi two-stroke)::

    T(theta) = Re sum_j c_j exp(i j 2 pi theta / Theta),
    c_0 = mean,  c_j = (2/N) sum_m T_m exp(-i j 2 pi theta_m / Theta)

Harmonic ``j`` is the order ``n = j 2 pi / Theta`` per crank revolution (0.5, 1, 1.5 ...
for a four-stroke); it excites at ``n omega``.  Each cylinder's own firing phase is in
its ``c_j`` (the dynamics stage places each cylinder on the cycle by its firing offset).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from fe_crank import model
from fe_crank.mechanism.torques import CylinderTorques, gas_weights


@dataclass(frozen=True)
class CylinderHarmonics:
    """Complex harmonics per cylinder: ``gas[c]`` and ``inertia[c]`` (n_orders,), the
    latter at ``reference_speed``; ``orders`` (n_orders,) per revolution, 0 first.

    With a full-load curve of per-speed diagrams (``gas_speeds``, ``gas_nodes``: the gas
    harmonics of each diagram) the gas part at a speed is interpolated linearly between
    the two diagrams that bracket it: exact, since the gas torque is linear in the
    pressure and the pressure is interpolated linearly in speed
    (``fe_crank.model.FullLoadCurve``); ``gas`` is then the reference speed's."""

    orders: np.ndarray
    gas: dict
    inertia: dict
    reference_speed: float
    cycle: float
    throw_of: dict  # cylinder -> throw name
    gas_speeds: tuple[float, ...] = ()
    gas_nodes: tuple[dict, ...] = ()

    def gas_weights(self, speed: float) -> np.ndarray:
        """Weights of ``gas_nodes`` at ``speed`` (``[1.0]`` for the one diagram ``gas``)."""
        return gas_weights(self.gas_speeds, speed)

    def gas_parts(self) -> tuple[dict, ...]:
        """The gas harmonics the weights of ``gas_weights`` apply to."""
        return self.gas_nodes if self.gas_speeds else (self.gas,)

    def gas_at(self, cylinder: str, speed: float) -> np.ndarray:
        return sum(wk * part[cylinder] for wk, part in zip(self.gas_weights(speed), self.gas_parts(), strict=True))

    def at_speed(self, cylinder: str, speed: float) -> np.ndarray:
        return self.gas_at(cylinder, speed) + (speed / self.reference_speed) ** 2 * self.inertia[cylinder]

    def synthesise(self, cylinder: str, speed: float, theta: np.ndarray, orders=None) -> np.ndarray:
        """``T(theta)`` of one cylinder from its harmonics (all, or those in ``orders``)."""
        c = self.at_speed(cylinder, speed)
        keep = np.ones(self.orders.size, bool) if orders is None else np.isin(self.orders, orders)
        phase = np.exp(1j * np.outer(np.asarray(theta, float), self.orders))
        return np.real(phase[:, keep] @ c[keep])


def fourier(values: np.ndarray, cycle: float) -> tuple[np.ndarray, np.ndarray]:
    """(orders, c) of a periodic sample on the uniform grid ``cycle * arange(N)/N``."""
    values = np.asarray(values, float)
    n = values.size
    c = np.fft.rfft(values) / n
    c[1:] *= 2.0
    if n % 2 == 0:
        c[-1] /= 2.0  # the Nyquist term appears once
    orders = np.arange(c.size) * 2 * np.pi / cycle
    return orders, c


def cylinder_harmonics(torques: CylinderTorques) -> CylinderHarmonics:
    """Gas and inertia harmonics of every cylinder's torque (module docstring) from the
    dynamics stage's cycles (``fe_crank.mechanism.torques.CylinderTorques``: without gas and
    with each diagram at the reference speed, every cylinder firing or one misfiring);
    with the per-speed diagrams of a full-load curve the gas part of each."""
    inertia = {}
    for name, t in torques.inertia.items():
        orders, inertia[name] = fourier(t, torques.cycle)
    if not inertia:
        raise ValueError("the engine has no cylinder")
    nodes = tuple({n: fourier(t, torques.cycle)[1] - inertia[n] for n, t in part.items()} for part in torques.loaded)
    speed = torques.reference_speed
    if not torques.gas_speeds:
        return CylinderHarmonics(orders, nodes[0], inertia, speed, torques.cycle, dict(torques.throw_of))
    h = CylinderHarmonics(orders, {}, inertia, speed, torques.cycle, dict(torques.throw_of), torques.gas_speeds, nodes)
    return dataclasses.replace(h, gas={c: h.gas_at(c, speed) for c in inertia})


def order_phase_sum(engine: model.Engine, order: float) -> float:
    """|sum_c exp(-i n phi_c)| / number of cylinders for order ``n``: the relative
    phase sum of the firing (``phi_c`` the cycle angle of cylinder ``c``'s firing TDC,
    its ``firing_offset``).  1 for a major order (all cylinders in phase), 0 when the
    cylinders cancel (a minor order that sums to zero), the classical vector sum of
    Ker Wilson vol. 1 / Den Hartog sec. 5.8 for a uniform shaft (mode amplitudes equal)."""
    z = sum(np.exp(-1j * order * c.firing_offset) for c in engine.cylinders)
    return float(abs(z) / len(engine.cylinders))
