"""One order of a free force and its moment as Fourier coefficients (``OrderTerm``),
and the terms of a point force and of a rotating force.

``F(theta) = F_cos cos k theta + F_sin sin k theta`` (Fx, Fy) and likewise ``M``
(Mx, My, Mz) about the reference point; see ``fe_crank.balance.forces``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.balance.hodograph import Hodograph, hodograph


def order_key(order: float) -> float:
    """An order rounded to 9 digits, to compare and group orders computed differently."""
    return round(float(order), 9)


@dataclass(frozen=True)
class OrderTerm:
    """One source's resultant at one order (coefficients in N and N m)."""

    source: str
    order: float
    force: np.ndarray  # (2, 2): rows Fx, Fy; columns cos, sin
    moment: np.ndarray  # (3, 2): rows Mx, My, Mz; columns cos, sin

    def evaluate(self, theta) -> tuple[np.ndarray, np.ndarray]:
        """Force (n, 2) and moment (n, 3) at cycle angles ``theta``."""
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        cs = np.stack([np.cos(self.order * th), np.sin(self.order * th)])
        return (self.force @ cs).T, (self.moment @ cs).T

    def force_hodograph(self) -> Hodograph:
        (a, b), (c, d) = self.force
        return hodograph(a, b, c, d)

    def moment_hodograph(self) -> Hodograph:
        """Ellipse of the pitch/yaw couple vector ``(Mx, My)``."""
        (a, b), (c, d) = self.moment[:2]
        return hodograph(a, b, c, d)

    def __add__(self, other: OrderTerm) -> OrderTerm:
        return OrderTerm(self.source, self.order, self.force + other.force, self.moment + other.moment)


def zero_term(source: str, order: float) -> OrderTerm:
    return OrderTerm(source, float(order), np.zeros((2, 2)), np.zeros((3, 2)))


def point_term(source: str, order: float, force: np.ndarray, point: tuple[float, float, float]) -> OrderTerm:
    """Term of a force with coefficients ``force`` (2, 2) acting at ``point``; ``M = r x F``."""
    rx, ry, rz = point
    fx, fy = force
    moment = np.stack([-rz * fy, rz * fx, rx * fy - ry * fx])
    return OrderTerm(source, float(order), np.asarray(force, float), moment)


def rotating_force(magnitude: float, psi0: float, sense: int) -> np.ndarray:
    """Coefficients (2, 2) of ``magnitude u(psi0 + sense k theta)``.

    ``u(psi) = (sin psi, cos psi)``: ``Fx = sin psi0 cos + s cos psi0 sin``,
    ``Fy = cos psi0 cos - s sin psi0 sin`` (times ``magnitude``).
    """
    s = float(sense)
    return magnitude * np.array([[np.sin(psi0), s * np.cos(psi0)], [np.cos(psi0), -s * np.sin(psi0)]])
