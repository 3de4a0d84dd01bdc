"""Exact planar dynamics of one slider-crank (piston and rigid rod) at constant crank speed.

Model (Kolchin & Demidov, *Design of automotive engines*, ch. 4-5; Heywood,
*Internal Combustion Engine Fundamentals*, sec. 2.2 and 13.2):

* piston: gas force ``F_g = (p - p_cc) A`` towards the crank axis, mass ``m_p``;
* rod: a rigid body of mass ``m``, centre of mass at ``c`` from the big end and
  moment of inertia ``J`` about it.  Without a given ``J`` the dynamically
  equivalent two-mass value ``J = m c (l - c)`` is used, which makes the result
  identical to the classical two-mass split (``m c/l`` reciprocating at the small
  end, ``m (l-c)/l`` rotating at the big end);
* the piston equation along the axis and the rod's three equations give the force
  of the rod on the piston pin, the side thrust and the force of the rod on the
  crankpin exactly (no lambda series).

Frames as in ``fe_crank.mechanism.kinematics``: ``u`` along the cylinder axis towards the head,
``w`` towards the side the crankpin moves to just after TDC.  The quantities returned
(``rod_force``, ``side_thrust``, ``tangential``, ``radial``, ``torque``) are defined in
``fe_crank.mechanism.dynamics``, which applies this solution to every cylinder of an engine.
"""

from __future__ import annotations

import numpy as np

from fe_crank.mechanism.kinematics import piston_motion

__all__ = ["solve_cylinder"]


def solve_cylinder(
    phi,
    *,
    r: float,
    l: float,
    omega: float,
    gas_force,
    piston_mass: float,
    rod_mass: float,
    rod_cg: float,
    rod_inertia: float | None = None,
    offset: float = 0.0,
):
    """Exact planar dynamics of one slider-crank at constant ``omega``.

    Piston along ``u`` (Newton): ``m_p (-a) = -F_g + P_u``; rod (Newton-Euler about the
    big end ``A``, rod vector ``d = B - A = l (cos b, -sin b)``, angular acceleration
    ``-b''`` in the u-w orientation)::

        d x (-P) = -J b'' + (G - A) x (m a_G)
        Q = m a_G + P

    ``P`` is the force of the rod on the piston, ``Q`` the force of the crankpin on the
    rod.  Returns a dict with ``motion``, ``rod_force``, ``side_thrust``, ``tangential``,
    ``radial``, ``torque`` (defined in ``fe_crank.mechanism.dynamics``), each of the shape of ``phi``.
    """
    J = rod_mass * rod_cg * (l - rod_cg) if rod_inertia is None else rod_inertia
    m = piston_motion(phi, r, l, omega, offset=offset, rod_cg=rod_cg)
    phi = m.phi
    fg = np.broadcast_to(np.asarray(gas_force, dtype=float), phi.shape)
    sb, cb = np.sin(m.beta), np.cos(m.beta)
    pu = fg - piston_mass * m.a
    # G - A in (u, w)
    k = rod_cg / l
    gu, gw = k * l * cb, -k * l * sb
    ag = m.rod_cg_acceleration
    cross_g = gu * rod_mass * ag[..., 1] - gw * rod_mass * ag[..., 0]
    pw = (J * m.beta_ddot - cross_g - l * sb * pu) / (l * cb)
    P = np.stack([pu, pw], axis=-1)
    Q = rod_mass * ag + P
    F = -Q  # force of the rod on the crankpin
    sphi, cphi = np.sin(phi), np.cos(phi)
    tangential = -F[..., 0] * sphi + F[..., 1] * cphi
    radial = F[..., 0] * cphi + F[..., 1] * sphi
    return {
        "motion": m,
        "rod_force": pu * cb - pw * sb,
        "side_thrust": pw,
        "tangential": tangential,
        "radial": radial,
        "torque": tangential * r,
    }
