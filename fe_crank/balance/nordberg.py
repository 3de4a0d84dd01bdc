"""Nordberg radial engine: inertia of the synchronising yoke and its rocker counterweights.

Liventsev, engines with complex kinematic schemes, sec. 21, eqs. 162-166, example 16.  The
yoke's centre of mass circles with the crank at the mean radius ``R_cp`` and oscillates along its axis
``zz`` with the half-stroke ``S/2 = l_ya sin(beta_max)`` (eq. 163), harmonically at the
crank speed, so (eq. 162, 164)::

    P_omega_ya = m_ya R_cp omega^2            (turning with the crank)
    P'_ya      = m_ya (S/2) omega^2 sin(alpha) (along zz; alpha from cylinder 1's TDC)

Example 16: ``l_ya = 0.176 m``, ``beta_max = 14 deg 44 min``, ``m_ya = 100 kg``,
``omega^2 = 1740 s^-2``, ``R_cp = 0.2035 m`` -> ``S/2 = 45 mm``, ``P'_ya = 7.83 kN``,
``P_omega_ya = 35.4 kN`` (Liventsev rounds ``S/2`` to 45 mm before multiplying; with the
unrounded 44.76 mm the force is 7.79 kN).  The rocker counterweights cancel the yoke's
pull on the rocker pins by the lever rule ``P_omega_pr l' = P_omega_ya l''`` (eq. 166).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fe_crank.balance.mechanism import direction
from fe_crank.balance.terms import OrderTerm, point_term, rotating_force
from fe_crank.errors import InputError
from fe_crank.model import Engine, Yoke


@dataclass(frozen=True)
class YokeInertia:
    half_stroke: float  # m, S/2
    oscillating_amplitude: float  # N, P'_ya
    centrifugal: float  # N, P_omega_ya


def yoke_inertia(yoke: Yoke, omega: float) -> YokeInertia:
    """Amplitudes of the yoke's inertia forces (eqs. 162-164)."""
    half = yoke.arm * math.sin(yoke.beta_max)
    return YokeInertia(half, yoke.mass * half * omega**2, yoke.mass * yoke.orbit_radius * omega**2)


def rocker_counterweight_force(yoke_force: float, arm_yoke: float, arm_counterweight: float) -> float:
    """Centrifugal force a rocker counterweight needs: ``P_pr = P_ya l_ya / l_pr`` (eq. 166)."""
    if not (arm_yoke > 0.0 and arm_counterweight > 0.0):
        raise InputError("rocker arms must be positive", key="yoke")
    return yoke_force * arm_yoke / arm_counterweight


def yoke_terms(engine: Engine, yoke: Yoke, speed: float, reference_z: float = 0.0) -> list[OrderTerm]:
    """Order-1 terms (source ``yoke``) on the throw of the engine's first cylinder."""
    cyl = engine.cylinders[0]
    t = engine.throw(cyl.throw)
    sh = engine.shaft(t.shaft)
    w = sh.speed_ratio * speed
    amp = yoke_inertia(yoke, w)
    point = (sh.centre[0], sh.centre[1], yoke.axial_position - reference_z)
    rot = rotating_force(amp.centrifugal, sh.phase + sh.sense * t.angle, sh.sense)
    # alpha = phi of cylinder 1 = theta n + phi0, phi0 = s (phase - bank) + angle
    phi0 = sh.sense * (sh.phase - cyl.bank_angle) + t.angle
    e = direction(yoke.axis_angle)
    osc = np.outer(e, amp.oscillating_amplitude * np.array([math.sin(phi0), math.cos(phi0)]))
    return [point_term("yoke", sh.speed_ratio, rot + osc, point)]
