"""Counterweight sizing: required unbalance ``m r`` in each counterweight plane.

Target of each throw (a vector turning with its crankpin, opposite to it)::

    U_t = (f_rot m_rot + f_rec sum_j m_j) R

``m_rot`` is the throw's rotating mass (own + rods' big ends), ``m_j`` the reciprocating
masses of the cylinders on the pin and ``f_rec`` the balanced fraction of their
first-order force.  A line oscillation ``m_j R omega^2 cos phi`` is the sum of a
co-rotating and a counter-rotating vector of ``m_j R omega^2 / 2`` each; a counterweight
``f_rec m_j R`` removes ``2 f_rec`` of the co-rotating one.  With ``f_rec = 1/2`` a V90
pin (whose first order is purely co-rotating) and a radial star (``P = P_omega + (i/2) P_I``,
Liventsev eq. 160-161) are balanced completely.

* ``per_throw``: each throw carries its own ``U_t``, split equally between its webs
  (planes ``z_t +- web_offset``): every throw is balanced in itself (no internal couple).
* ``whole_shaft``: the throws' sum ``S = sum U_t e^{i beta_t}`` and moment
  ``M = sum z_t U_t e^{i beta_t}`` are cancelled by counterweights in the given planes
  ``z_i``, ``U_i = A + sgn(z_i - z_mean) B``: a common part and an antisymmetric part,
  two complex unknowns from ``sum U_i = -S`` and ``sum z_i U_i = -M``.  With two planes
  this is the classical two-plane balance; with symmetric planes it gives equal
  counterweights, as in Voronkov's V4-90 pneumatic engine (four equal counterweights at the outer and inner webs:
  ``m r_c (L1 + L2) = (m_A + m_B) R l``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

from fe_crank.balance.forces import FreeForces, free_forces, point_term, rotating_force
from fe_crank.balance.mechanism import reciprocating_mass, rotating_mass
from fe_crank.errors import InputError
from fe_crank.model import Engine

#: where the counterweights balance the couples: within each throw, or over the whole shaft's planes
CoupleBalance = Literal["per_throw", "whole_shaft"]

COUPLE_MODES = ("per_throw", "whole_shaft")


@dataclass(frozen=True)
class BalanceStrategy:
    """What the crankshaft counterweights balance."""

    rotating_fraction: float = 1.0
    reciprocating_fraction: float = 0.0
    couple: CoupleBalance = "per_throw"
    planes: tuple[float, ...] = ()  # m, axial positions for ``whole_shaft``
    web_offset: float = 0.0  # m, per_throw: webs at z_t +- web_offset

    def __post_init__(self):
        for name in ("rotating_fraction", "reciprocating_fraction"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0.0):
                raise InputError(f"must be a fraction >= 0 (got {v})", key=f"balance.{name}")
        if self.reciprocating_fraction > 1.0:
            raise InputError(
                f"cannot exceed 1 (got {self.reciprocating_fraction})", key="balance.reciprocating_fraction"
            )
        if self.couple not in COUPLE_MODES:
            raise InputError(f"{self.couple!r} is not one of {COUPLE_MODES}", key="balance.couple")
        if self.couple == "whole_shaft" and len(self.planes) < 2:
            raise InputError("whole_shaft couple balance needs at least two counterweight planes", key="balance.planes")
        if self.web_offset < 0.0:
            raise InputError("web_offset cannot be negative", key="balance.web_offset")


@dataclass(frozen=True)
class Counterweight:
    """Required unbalance in one plane of one shaft.

    ``angle`` is the direction of the counterweight's centre of mass at ``theta = 0`` in
    the engine frame (from ``+y`` towards ``+x``); ``angle_on_shaft`` the same measured
    on the shaft from its reference throw, in its sense of rotation.
    """

    shaft: str
    z: float
    unbalance: float  # kg m
    angle: float
    angle_on_shaft: float

    def mass_at(self, radius: float) -> float:
        """``m = U / r``: the counterweight mass with its centroid at ``radius``."""
        return self.unbalance / radius


@dataclass(frozen=True)
class CounterweightDesign:
    strategy: BalanceStrategy
    counterweights: tuple[Counterweight, ...]
    before: FreeForces
    residual: FreeForces
    sectors: tuple = field(default_factory=tuple)  # SectorProperties per counterweight, when synthesised

    def nearest(self, shaft: str, z: float) -> Counterweight | None:
        """The counterweight of ``shaft`` whose plane is closest to ``z`` (for the geometry and
        assessment stages, which know their webs' axial positions); ``None`` if the shaft has none."""
        own = [c for c in self.counterweights if c.shaft == shaft]
        return min(own, key=lambda c: abs(c.z - z)) if own else None


def _wrap(angle: float) -> float:
    """Angle in (-pi, pi]."""
    a = math.fmod(angle, 2.0 * math.pi)
    a = a - 2.0 * math.pi if a > math.pi else a
    return a + 2.0 * math.pi if a <= -math.pi else a


def counterweight_mass(force: float, radius: float, omega: float) -> float:
    """``m_pr = P / (r_pr omega^2)`` (Liventsev, eq. 161)."""
    if not (radius > 0.0 and omega > 0.0):
        raise InputError("counterweight radius and speed must be positive", key="balance")
    return force / (radius * omega**2)


def radial_counterweight_mass(engine: Engine, throw: str, speed: float, radius: float) -> float:
    """Radial engine: ``P = P_omega + (i/2) P_I``, ``m_pr = P / (r_pr omega^2)`` (Liventsev, eq. 158-161)."""
    t = engine.throw(throw)
    cyls = [c for c in engine.cylinders if c.throw == throw]
    p_rot = rotating_mass(engine, throw) * t.crank_radius * speed**2
    p_first = sum(reciprocating_mass(c) for c in cyls) / 2.0 * t.crank_radius * speed**2
    return counterweight_mass(p_rot + p_first, radius, speed)


def _throw_targets(engine: Engine, strategy: BalanceStrategy, shaft: str):
    sh = engine.shaft(shaft)
    out = []
    for t in engine.throws:
        if t.shaft != shaft:
            continue
        mj = sum(reciprocating_mass(c) for c in engine.cylinders if c.throw == t.name)
        u = (
            strategy.rotating_fraction * rotating_mass(engine, t.name) + strategy.reciprocating_fraction * mj
        ) * t.crank_radius
        out.append((t, u * np.exp(1j * (sh.phase + sh.sense * t.angle))))  # pin direction at theta = 0
    return out


def _planes_for_shaft(engine: Engine, strategy: BalanceStrategy, shaft: str) -> list[tuple[float, complex]]:
    targets = _throw_targets(engine, strategy, shaft)
    if strategy.couple == "per_throw":
        out = []
        for t, u in targets:
            if strategy.web_offset > 0.0:
                out += [
                    (t.axial_position - strategy.web_offset, -u / 2.0),
                    (t.axial_position + strategy.web_offset, -u / 2.0),
                ]
            else:
                out.append((t.axial_position, -u))
        return out
    s_tot = sum(u for _, u in targets)
    m_tot = sum(t.axial_position * u for t, u in targets)
    z = np.asarray(strategy.planes, dtype=float)
    sgn = np.sign(z - z.mean())
    mat = np.array([[len(z), sgn.sum()], [z.sum(), (sgn * z).sum()]], dtype=complex)
    if abs(np.linalg.det(mat)) < 1e-12 * max(1.0, float(np.abs(z).max()) ** 2):
        raise InputError("counterweight planes must lie at two or more distinct axial positions", key="balance.planes")
    a, b = np.linalg.solve(mat, np.array([-s_tot, -m_tot]))
    return [(zi, a + si * b) for zi, si in zip(z, sgn)]


def size_counterweights(
    engine: Engine,
    strategy: BalanceStrategy,
    speed: float,
    *,
    reference_z: float = 0.0,
    forces: FreeForces | None = None,
) -> CounterweightDesign:
    """Required ``m r`` per counterweight plane and the residual free forces/moments.

    The counterweights enter the residual as rotating masses (source ``counterweights``).
    """
    before = forces if forces is not None else free_forces(engine, speed, reference_z=reference_z)
    cws, terms = [], []
    for sh in engine.shafts:
        for z, uc in _planes_for_shaft(engine, strategy, sh.name):
            mag = abs(uc)
            psi = math.atan2(uc.imag, uc.real) if mag > 0 else 0.0
            on_shaft = _wrap(sh.sense * (psi - sh.phase))
            cws.append(Counterweight(sh.name, float(z), float(mag), _wrap(psi), on_shaft))
            if mag == 0.0:
                continue
            force = rotating_force(mag * (sh.speed_ratio * speed) ** 2, psi, sh.sense)
            terms.append(
                point_term(
                    "counterweights", sh.speed_ratio, force, (sh.centre[0], sh.centre[1], z - before.reference_z)
                )
            )
    return CounterweightDesign(strategy, tuple(cws), before, before.with_terms(terms))
