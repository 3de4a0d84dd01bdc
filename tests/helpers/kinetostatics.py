"""Kinetostatics of the single-cylinder slider-crank (seed 004, section 6).

D'Alembert's principle at a crank position (Artobolevsky, *Theory of mechanisms and
machines*, ch. on force analysis): inertia forces ``-m a_S`` and couples ``-J eps``
are added to the external loads and each part is solved as a static problem:

1. the Assur group rod 2 + piston 3: unknown ``R12`` (crank on rod at ``A``) and
   ``R03`` (frame on piston, normal to the guide).  The sum of forces on the group
   along the guide gives ``R12_u``; moments on the rod about ``B`` give ``R12_w``;
   forces normal to the guide give ``R03``; the piston alone gives ``R23``;
2. the crank 1: moments about ``O`` give the balancing moment ``M_b`` (the couple on
   the crank that holds it in equilibrium; for an engine ``-M_b`` is the torque
   delivered), the balancing force ``P_b = M_b / r`` normal to the crank at ``A``,
   and with it the frame reaction ``R01``.

``M_b`` is computed two more ways: by virtual power, ``M_b omega + sum F.v + sum
M omega_i = 0``, and by Zhukovsky's lever (the velocity plan turned through 90 deg
loaded with all forces, couples replaced by force pairs).  All three agree to
round-off; the seed's 311.5 vs 298.9 N m (4 %) is a drawing error.

Vectors are in the cylinder frame ``(u, w)`` of ``fe_crank.mechanism.kinematics`` (u along the
guide towards the head, w towards the side the crankpin moves to just after TDC);
moments are positive in the sense of rotation.  ``gravity`` is the vector ``g`` in
that frame (default: vertical cylinder, head up, ``(-9.81, 0)``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.errors import InputError
from fe_crank.mechanism.kinematics import PistonMotion, piston_motion

__all__ = [
    "KinetostaticResult",
    "analyse_position",
    "zhukovsky_moment",
    "virtual_power_moment",
    "FrictionLosses",
    "mechanical_efficiency",
]


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _rot90(v):
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


@dataclass(frozen=True)
class KinetostaticResult:
    """Joint reactions and balancing load at one or many crank positions (vectors (..., 2))."""

    phi: np.ndarray
    omega: float
    motion: PistonMotion
    points: dict  # "O", "A", "B", "S1", "S2" positions (..., 2)
    velocities: dict  # same keys: velocities (..., 2)
    loads: dict  # name -> (point key, force (..., 2)) for every applied force (gas, weights, inertia)
    couples: dict  # name -> (link angular velocity (...,), moment (...,)) for applied couples
    R12: np.ndarray  # crank on rod, at A
    R03: np.ndarray  # frame on piston (normal to the guide)
    R23: np.ndarray  # rod on piston, at B
    R01: np.ndarray  # frame on crank at O, with the balancing FORCE applied at A
    R01_couple: np.ndarray  # frame on crank at O, with the balancing MOMENT (couple)
    balancing_moment: np.ndarray  # N m on the crank, positive in the sense of rotation
    balancing_force: np.ndarray  # N, at A normal to the crank, positive in the sense of rotation


def analyse_position(
    phi,
    *,
    r: float,
    l: float,
    omega: float,
    gas_force,
    piston_mass: float,
    rod_mass: float,
    rod_cg: float,
    rod_inertia: float,
    crank_mass: float = 0.0,
    crank_cg: float = 0.0,
    offset: float = 0.0,
    gravity=(-9.81, 0.0),
) -> KinetostaticResult:
    """Force analysis of the slider-crank at crank angle(s) ``phi`` (module docstring).

    Parameters
    ----------
    phi : array_like
        Crank angle from the cylinder axis (TDC without offset), rad.
    r, l, omega, offset : float
        Crank radius, rod length (m), constant crank speed (rad/s), pin offset (m).
    gas_force : array_like
        Gas force on the piston, N, positive towards the crank axis.
    piston_mass, rod_mass, crank_mass : float
        Masses of piston 3, rod 2 and crank 1, kg.
    rod_cg, crank_cg : float
        Centre of mass of the rod from the big end ``A`` and of the crank from ``O``, m.
    rod_inertia : float
        Rod moment of inertia about its centre of mass, kg m^2.
    gravity : (2,) sequence
        Gravity vector in the cylinder frame, m/s^2.
    """
    if rod_inertia < 0 or rod_mass < 0 or piston_mass < 0 or crank_mass < 0:
        raise InputError("masses and inertia cannot be negative")
    m = piston_motion(phi, r, l, omega, offset=offset, rod_cg=rod_cg)
    phi = m.phi
    shape = phi.shape
    g = np.broadcast_to(np.asarray(gravity, dtype=float), shape + (2,))
    er = np.stack([np.cos(phi), np.sin(phi)], axis=-1)
    et = _rot90(er)
    O = np.zeros(shape + (2,))
    A = r * er
    x = r * np.cos(phi) + l * np.cos(m.beta)
    B = np.stack([x, np.full(shape, float(offset))], axis=-1)
    S2 = A + rod_cg / l * (B - A)
    S1 = crank_cg * er
    vB = np.stack([-m.v, np.zeros(shape)], axis=-1)
    aB = np.stack([-m.a, np.zeros(shape)], axis=-1)
    vel = {"O": O, "A": m.crankpin_velocity, "B": vB, "S1": crank_cg * omega * et, "S2": m.rod_cg_velocity}
    omega2 = -m.beta_dot  # rod angular velocity in the u-w orientation
    eps2 = -m.beta_ddot

    fg = np.broadcast_to(np.asarray(gas_force, dtype=float), shape)
    F_gas = np.stack([-fg, np.zeros(shape)], axis=-1)
    F_I3 = -piston_mass * aB
    G3 = piston_mass * g
    F_I2 = -rod_mass * m.rod_cg_acceleration
    G2 = rod_mass * g
    M_I2 = -rod_inertia * eps2
    F_I1 = crank_mass * crank_cg * omega**2 * er  # -m1 a_S1, a_S1 = -c w^2 e_r
    G1 = crank_mass * g

    # Assur group 2 + 3
    f3 = F_gas + F_I3 + G3
    f2 = F_I2 + G2
    R12u = -(f3[..., 0] + f2[..., 0])
    d = A - B
    c = -(_cross(S2 - B, f2) + M_I2)
    R12w = (c + d[..., 1] * R12u) / d[..., 0]
    R12 = np.stack([R12u, R12w], axis=-1)
    R03 = np.stack([np.zeros(shape), -(f3[..., 1] + f2[..., 1] + R12w)], axis=-1)
    R23 = -(R03 + f3)
    # crank 1
    R21 = -R12
    f1 = F_I1 + G1
    Mb = -(_cross(A, R21) + _cross(S1, f1))
    Pb = Mb / r
    R01 = -(R21 + f1 + Pb[..., None] * et)
    R01c = -(R21 + f1)
    loads = {
        "gas": ("B", F_gas),
        "inertia_3": ("B", F_I3),
        "weight_3": ("B", G3),
        "inertia_2": ("S2", F_I2),
        "weight_2": ("S2", G2),
        "inertia_1": ("S1", F_I1),
        "weight_1": ("S1", G1),
    }
    couples = {"inertia_2": (omega2, M_I2, "A", "B")}
    return KinetostaticResult(
        phi=phi,
        omega=omega,
        motion=m,
        points={"O": O, "A": A, "B": B, "S1": S1, "S2": S2},
        velocities=vel,
        loads=loads,
        couples=couples,
        R12=R12,
        R03=R03,
        R23=R23,
        R01=R01,
        R01_couple=R01c,
        balancing_moment=Mb,
        balancing_force=Pb,
    )


def virtual_power_moment(res: KinetostaticResult) -> np.ndarray:
    """Balancing moment from virtual power: ``M_b = -(sum F.v + sum M omega_i) / omega``."""
    power = 0.0
    for pt, F in res.loads.values():
        power = power + np.sum(F * res.velocities[pt], axis=-1)
    for om, M, *_ in res.couples.values():
        power = power + M * om
    return -power / res.omega


def zhukovsky_moment(res: KinetostaticResult) -> np.ndarray:
    """Balancing moment by Zhukovsky's lever.

    The velocity plan is turned through 90 deg (each point's image at ``rot90(v)``
    from the pole) and treated as a rigid lever pivoted at the pole; every force is
    applied at the image of its point and couples ``M`` on a link ``AB`` are replaced
    by the pair ``+f`` at ``B``, ``-f`` at ``A`` with ``f = M rot90(B - A) / |AB|^2``.
    Equilibrium of the lever with the balancing force ``P_b`` normal to the crank at
    the image of ``A`` gives ``P_b`` and ``M_b = P_b r``.
    """
    total = 0.0
    img = {k: _rot90(v) for k, v in res.velocities.items()}
    for pt, F in res.loads.values():
        total = total + _cross(img[pt], F)
    for _om, M, a_key, b_key in res.couples.values():
        ab = res.points[b_key] - res.points[a_key]
        f = (M / np.sum(ab * ab, axis=-1))[..., None] * _rot90(ab)
        total = total + _cross(img[b_key], f) - _cross(img[a_key], f)
    A = res.points["A"]
    r = np.linalg.norm(A, axis=-1)
    et = _rot90(A / r[..., None])
    # lever equilibrium: total + cross(img_A, P_b e_t) = 0
    arm = _cross(img["A"], et)  # = -r omega
    Pb = -total / arm
    return Pb * r


@dataclass(frozen=True)
class FrictionLosses:
    """Friction power in the joints averaged over the cycle and the resulting efficiency."""

    power_O1: float
    power_A: float
    power_B: float
    power_O3: float
    driving_power: float
    efficiency: float

    @property
    def friction_power(self) -> float:
        return self.power_O1 + self.power_A + self.power_B + self.power_O3


def mechanical_efficiency(
    res: KinetostaticResult,
    *,
    friction_coefficient: float,
    d_O1: float,
    d_A: float,
    d_B: float,
) -> FrictionLosses:
    """Mechanical efficiency of the slider-crank from joint friction (seed 004, eqs. 110-115).

    Over a full revolution sampled uniformly in ``res.phi``::

        N_O1 = f |R01| d_O1/2 |omega|            (main journal)
        N_A  = f |R12| d_A/2 |omega - omega_2|   (crankpin)
        N_B  = f |R23| d_B/2 |omega_2|           (piston pin)
        N_O3 = f |R03| |v_B|                     (piston on the guide)
        eta  = 1 - mean(N_O1 + N_A + N_B + N_O3) / mean(P_gas)

    with ``P_gas`` the power of the gas force on the piston (mean = indicated power;
    sample ``phi`` uniformly over the whole cycle, 0 .. 4 pi for a four-stroke).  The
    frame reaction is the one with the balancing couple (``R01_couple``).
    """
    if friction_coefficient < 0 or min(d_O1, d_A, d_B) < 0:
        raise InputError("friction coefficient and journal diameters cannot be negative")
    f = friction_coefficient
    om = res.omega
    om2 = -res.motion.beta_dot
    n = lambda v: np.linalg.norm(v, axis=-1)
    pO1 = float(np.mean(f * n(res.R01_couple) * d_O1 / 2 * abs(om)))
    pA = float(np.mean(f * n(res.R12) * d_A / 2 * np.abs(om - om2)))
    pB = float(np.mean(f * n(res.R23) * d_B / 2 * np.abs(om2)))
    pO3 = float(np.mean(f * n(res.R03) * np.abs(res.motion.v)))
    gas = res.loads["gas"][1]
    p_in = float(np.mean(np.sum(gas * res.velocities["B"], axis=-1)))
    if not p_in > 0:
        raise InputError("no driving power: the gas force does no positive work over these positions")
    eta = 1.0 - (pO1 + pA + pB + pO3) / p_in
    return FrictionLosses(pO1, pA, pB, pO3, p_in, eta)
