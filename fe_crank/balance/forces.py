"""Free forces and moments of a whole engine, by source and by order.

Every term of order ``k`` (``k`` counted per revolution of the reference shaft, so a
shaft geared at ``n`` times the speed contributes orders ``n k``) is stored as Fourier
coefficients::

    F(theta) = F_cos cos k theta + F_sin sin k theta     (Fx, Fy)
    M(theta) = M_cos cos k theta + M_sin sin k theta     (Mx, My, Mz)

with the moments taken about the reference point ``(0, 0, reference_z)`` on the crank
axis, ``M = r x F`` and ``r`` the point of action: the shaft centre (shifted by the pin
offset across the cylinder axis) at the throw's axial position.  The roll moment ``Mz``
therefore only holds the offsets of the lines of action (several shafts, desaxe pins);
the inertia torque of the rods is a matter of the dynamics stage.

Sources:

* ``rotating``: ``m_rot R (n omega)^2 u(psi)`` of every throw (its own unbalanced mass and
  the big-end shares of its rods), order ``n``;
* ``reciprocating``: ``m_j x''`` along each cylinder axis from the exact piston motion,
  split into orders by ``fe_crank.balance.harmonics`` (all orders up to ``kmax`` are kept,
  so their sum is the exact force to spectral accuracy);
* ``yoke``: the Nordberg synchronising yoke where the engine has one (Liventsev, eq. 162-164).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from fe_crank.balance import harmonics
from fe_crank.balance.mechanism import direction, piston_positions, reciprocating_mass, rotating_mass
from fe_crank.balance.nordberg import yoke_terms
from fe_crank.balance.terms import OrderTerm, order_key, point_term, rotating_force, zero_term
from fe_crank.errors import InputError
from fe_crank.model import Engine

#: orders reported in tables
REPORTED_ORDERS = (1.0, 2.0, 4.0, 6.0)
SOURCES = ("rotating", "reciprocating", "yoke", "counterweights", "balance_shafts")

__all__ = [
    "REPORTED_ORDERS",
    "SOURCES",
    "FreeForces",
    "OrderTerm",
    "free_forces",
    "point_term",
    "reciprocating_terms",
    "rotating_force",
    "rotating_terms",
    "zero_term",
]


@dataclass(frozen=True)
class FreeForces:
    """All free forces and moments of an engine at one speed."""

    engine: str
    speed: float  # rad/s of the reference shaft
    reference_z: float  # m: moments are about (0, 0, reference_z)
    terms: tuple[OrderTerm, ...] = field(default_factory=tuple)
    force_scale: float = 0.0  # N: sum of first-order amplitudes, for round-off
    length_scale: float = 1.0  # m: largest lever

    def _clean(self, t: OrderTerm) -> OrderTerm:
        ftol = ROUNDOFF * self.force_scale
        mtol = ftol * max(self.length_scale, 1e-3)
        return OrderTerm(
            t.source,
            t.order,
            np.where(np.abs(t.force) < ftol, 0.0, t.force),
            np.where(np.abs(t.moment) < mtol, 0.0, t.moment),
        )

    @property
    def sources(self) -> tuple[str, ...]:
        return tuple(s for s in SOURCES if any(t.source == s for t in self.terms))

    @property
    def orders(self) -> tuple[float, ...]:
        return tuple(sorted({order_key(t.order) for t in self.terms}))

    def term(self, source: str, order: float) -> OrderTerm:
        out = zero_term(source, order)
        for t in self.terms:
            if t.source == source and order_key(t.order) == order_key(order):
                out = out + t
        return self._clean(out)

    def total(self, order: float, sources=None) -> OrderTerm:
        """Sum over ``sources`` (default all) at one order."""
        out = zero_term("total", order)
        for t in self.terms:
            if order_key(t.order) == order_key(order) and (sources is None or t.source in sources):
                out = out + replace(t, source="total")
        return self._clean(out)

    def evaluate(self, theta, sources=None, orders=None) -> tuple[np.ndarray, np.ndarray]:
        """Time-domain force (n, 2) and moment (n, 3): sum of the chosen terms."""
        th = np.atleast_1d(np.asarray(theta, dtype=float))
        f = np.zeros((th.size, 2))
        m = np.zeros((th.size, 3))
        keys = None if orders is None else {order_key(o) for o in orders}
        for t in self.terms:
            if (sources is None or t.source in sources) and (keys is None or order_key(t.order) in keys):
                ft, mt = t.evaluate(th)
                f += ft
                m += mt
        return f, m

    def with_terms(self, extra) -> FreeForces:
        """A copy with more terms (counterweights, balance shafts) added."""
        return replace(self, terms=self.terms + tuple(extra))


def _check_engine(engine: Engine) -> None:
    if not engine.cylinders:
        raise InputError("the engine has no cylinders: nothing to balance", key="cylinders")
    for sh in engine.shafts:
        throws = {t.name for t in engine.throws if t.shaft == sh.name}
        if not any(c.throw in throws for c in engine.cylinders):
            raise InputError(
                f"shaft {sh.name!r} drives no cylinder; remove it or attach a throw with a cylinder",
                key=f"shafts.{sh.name}",
            )


def rotating_terms(engine: Engine, speed: float, reference_z: float = 0.0) -> list[OrderTerm]:
    """Centrifugal forces of the throws: ``m_rot R (n omega)^2 u(psi)``, order ``n``,
    ``psi = phase + s (n theta + angle)``."""
    out = []
    for t in engine.throws:
        sh = engine.shaft(t.shaft)
        mag = rotating_mass(engine, t.name) * t.crank_radius * (sh.speed_ratio * speed) ** 2
        if mag == 0.0:
            continue
        force = rotating_force(mag, sh.phase + sh.sense * t.angle, sh.sense)
        out.append(
            point_term("rotating", sh.speed_ratio, force, (sh.centre[0], sh.centre[1], t.axial_position - reference_z))
        )
    return out


def reciprocating_terms(engine: Engine, speed: float, reference_z: float = 0.0, kmax: int = 24) -> list[OrderTerm]:
    """Inertia forces ``-m_j x''`` of the reciprocating masses along their axes, by order."""
    tau = harmonics.sample_angles()
    out = []
    for cyl in engine.cylinders:
        t = engine.throw(cyl.throw)
        sh = engine.shaft(t.shaft)
        mj = reciprocating_mass(cyl)
        if mj == 0.0:
            continue
        # sample over one revolution of this shaft: theta = tau / n
        x = piston_positions(engine, cyl.name, tau / sh.speed_ratio)
        acc = harmonics.acceleration_coefficients(x, kmax)  # d2x/dtau2 per order
        e = direction(cyl.bank_angle)
        off = cyl.pin_offset * sh.sense * direction(cyl.bank_angle + np.pi / 2.0)
        point = (sh.centre[0] + off[0], sh.centre[1] + off[1], t.axial_position - reference_z)
        w2 = (sh.speed_ratio * speed) ** 2
        for k in range(1, kmax + 1):
            coef = -mj * w2 * acc[k]  # along e: cos, sin of k tau = k n theta
            if not np.any(np.abs(coef) > 0.0):
                continue
            force = np.outer(e, coef)
            out.append(point_term("reciprocating", k * sh.speed_ratio, force, point))
    return out


#: coefficients below this share of the engine's force scale are round-off: set to zero
ROUNDOFF = 1e-11


def _merge(terms: list[OrderTerm], force_scale: float, length_scale: float) -> tuple[OrderTerm, ...]:
    """Sum terms of equal source and order; clear round-off so that cancelled orders read
    exactly zero (and their hodographs ``zero``, not a noise ellipse)."""
    merged: dict[tuple[str, float], OrderTerm] = {}
    for t in terms:
        key = (t.source, order_key(t.order))
        merged[key] = merged[key] + t if key in merged else t
    ftol = ROUNDOFF * force_scale
    mtol = ftol * max(length_scale, 1e-3)
    out = []
    for t in merged.values():
        f = np.where(np.abs(t.force) < ftol, 0.0, t.force)
        m = np.where(np.abs(t.moment) < mtol, 0.0, t.moment)
        out.append(OrderTerm(t.source, t.order, f, m))
    return tuple(out)


def _scales(engine: Engine, speed: float) -> tuple[float, float]:
    """Sum of all first-order force amplitudes (N) and the engine's largest lever (m)."""
    f = 0.0
    for t in engine.throws:
        sh = engine.shaft(t.shaft)
        w2 = (sh.speed_ratio * speed) ** 2
        f += rotating_mass(engine, t.name) * t.crank_radius * w2
        f += sum(reciprocating_mass(c) for c in engine.cylinders if c.throw == t.name) * t.crank_radius * w2
    lev = max(
        [abs(t.axial_position) for t in engine.throws] + [abs(v) for s in engine.shafts for v in s.centre] + [0.0]
    )
    return max(f, 1e-300), lev


def free_forces(engine: Engine, speed: float, *, reference_z: float = 0.0, kmax: int = 24) -> FreeForces:
    """Free forces and moments of ``engine`` at ``speed`` (rad/s of the reference shaft).

    Parameters
    ----------
    engine : fe_crank.model.Engine
    speed : float
        Angular speed of the reference shaft, rad/s.
    reference_z : float
        Axial position (m) of the point on the crank axis about which moments are taken.
    kmax : int
        Highest order kept per shaft; the sum of all orders is the exact force to
        spectral accuracy (orders above 24 are below 1e-12 of the first for l/r > 2.5).

    Returns
    -------
    FreeForces
        Terms by source (``rotating``, ``reciprocating``, ``yoke``) and order.

    Raises
    ------
    InputError
        An empty engine, a shaft without cylinders, a non-positive speed.
    """
    if not speed > 0.0:
        raise InputError(f"speed must be positive (got {speed} rad/s)", key="operating.speed")
    _check_engine(engine)
    terms = rotating_terms(engine, speed, reference_z) + reciprocating_terms(engine, speed, reference_z, kmax)
    if engine.yoke is not None:
        terms += yoke_terms(engine, engine.yoke, speed, reference_z)
    fscale, lscale = _scales(engine, speed)
    lscale = max(lscale, abs(reference_z))
    return FreeForces(engine.name, float(speed), float(reference_z), _merge(terms, fscale, lscale), fscale, lscale)
