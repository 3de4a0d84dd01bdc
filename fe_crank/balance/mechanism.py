"""Exact piston positions of every cylinder of an engine, in the engine frame.

Conventions of ``fe_crank.model``: a direction at angle ``psi`` (from ``+y`` towards
``+x``) is ``u(psi) = (sin psi, cos psi)``.  The crankpin of a throw on a shaft with
``sense s``, ``phase p`` and ``speed_ratio n`` lies at::

    psi(theta) = p + s (n theta + angle_throw)

from the shaft centre.  A cylinder's axis ``e = u(bank)``; its normal
``n' = s u(bank + 90 deg)`` points to where the crankpin goes after TDC.  The piston pin
lies on the line ``centre + offset n' + x e`` with::

    x = (C - centre).e + sqrt(l^2 - ((C - centre).n' - offset)^2)

(``C`` the big-end centre).  An articulated rod's big end is the link pin on its master
rod, ``L = C + rho u(gamma_m + link_angle)``, ``gamma_m`` the direction of the master rod
from big end to small end; ``link_angle`` is measured in the engine's angle sense.
The crank angle of a cylinder from the crank-along-axis position is
``phi = s (psi - bank)`` (the TDC of an offset mechanism differs slightly from this).
"""

from __future__ import annotations

import numpy as np

from fe_crank.errors import InputError
from fe_crank.model import Cylinder, Engine, crank_angle_global

__all__ = ["big_end", "crank_angle_global", "direction", "piston_positions", "reciprocating_mass", "rotating_mass"]


def direction(angle) -> np.ndarray:
    """``u(angle) = (sin, cos)`` stacked on the last axis."""
    angle = np.asarray(angle, dtype=float)
    return np.stack([np.sin(angle), np.cos(angle)], axis=-1)


def _slider(rel: np.ndarray, cyl: Cylinder, sense: int) -> np.ndarray:
    """Distance along the cylinder axis of the piston pin for big-end positions ``rel``."""
    e = direction(cyl.bank_angle)
    n = sense * direction(cyl.bank_angle + np.pi / 2.0)
    across = rel @ n - cyl.pin_offset
    root = cyl.rod.length**2 - across**2
    if np.any(root <= 0.0):
        raise InputError(
            f"cylinder {cyl.name!r}: the connecting rod ({cyl.rod.length * 1e3:.4g} mm) cannot reach "
            "the cylinder axis at every crank angle; check rod length, offset and articulation",
            key=f"cylinders.{cyl.name}",
        )
    return rel @ e + np.sqrt(root)


def piston_positions(engine: Engine, cylinder: str, theta) -> np.ndarray:
    """Exact distance ``x`` (m) of the piston pin from the shaft centre along the axis."""
    cyl = engine.cylinder(cylinder)
    sh = engine.shaft(engine.throw(cyl.throw).shaft)
    return _slider(big_end(engine, cyl.name, theta), cyl, sh.sense)


def big_end(engine: Engine, cylinder: str, theta) -> np.ndarray:
    """Big-end centre of a cylinder's rod relative to its shaft centre, shape (n, 2)."""
    cyl = engine.cylinder(cylinder)
    t = engine.throw(cyl.throw)
    sh = engine.shaft(t.shaft)
    crank = t.crank_radius * direction(crank_angle_global(engine, t.name, theta))
    if cyl.articulation is None:
        return crank
    master = engine.cylinder(cyl.articulation.master)
    if master.articulation is not None:
        raise InputError(
            f"cylinder {cyl.name!r}: its master {master.name!r} is itself articulated",
            key=f"cylinders.{cyl.name}.articulation.master",
        )
    if master.throw != cyl.throw:
        raise InputError(
            f"cylinder {cyl.name!r}: master {master.name!r} runs on another throw",
            key=f"cylinders.{cyl.name}.articulation.master",
        )
    xm = _slider(crank, master, sh.sense)
    pin = xm[..., None] * direction(master.bank_angle) + master.pin_offset * sh.sense * direction(
        master.bank_angle + np.pi / 2.0
    )
    rod = pin - crank
    gamma = np.arctan2(rod[..., 0], rod[..., 1])
    return crank + cyl.articulation.link_radius * direction(gamma + cyl.articulation.link_angle)


def reciprocating_mass(cyl: Cylinder) -> float:
    """Piston group plus the small-end share of the rod (static two-mass split)."""
    return cyl.piston_mass + cyl.rod.mass * cyl.rod.reciprocating_fraction


def rotating_mass(engine: Engine, throw: str) -> float:
    """Throw's own unbalanced mass plus the big-end share of every rod on its pin.

    Articulated rods' big-end shares are put on the crankpin too (their link pins stay
    within ``link_radius`` of it): the usual approximation for radial engines.
    """
    t = engine.throw(throw)
    rods = sum(c.rod.mass * (1.0 - c.rod.reciprocating_fraction) for c in engine.cylinders if c.throw == throw)
    return t.rotating_mass + rods
