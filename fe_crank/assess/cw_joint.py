"""The bolted counterweight checked as VDI 2230 Part 1 (2015) checks a bolted joint.

Loads (per bolt, ``counterweight_loads``).  A counterweight of mass m with its centre of
mass at r_c turns with the shaft: the centrifugal force m r_c omega^2 pulls it off the web,
the tangential inertia m r_c alpha (alpha the shaft's angular acceleration) shears it.  With
``direction = "radial"`` bolts (their axis through the crank axis) the centrifugal force is
the axial load F_A and the tangential one the transverse load F_Q; with ``"axial"`` bolts
(parallel to the crank axis, the counterweight against the web's face) both are transverse,
F_A = 0 from the counterweight.  Over the working cycle the speed varies by the coefficient
delta (omega (1 -+ delta/2)) and alpha = (T - T_mean)/J with the dynamics stage's torque and
flywheel inertia; each start and stop cycles F_A between 0 and its working value.  At the
overspeed omega_os the centrifugal force alone (an event, not a cycle).  The joint is
assumed to share the loads equally among its bolts; the web's own deformation under the
pin force (the joint's interface opening and closing) is not computed: the FE model fuses
the counterweight to the web (``docs/assessment.md``).

Check (``check_joint``), VDI 2230's rules with n the load introduction factor:
* R7 assembly: nu = sigma_red,M(F_M,max) / R_p0.2 <= 0.9; F_M,max the stated preload or
  F_M,zul, F_M,min = F_M,max / alpha_A (tightening factor);
* R8 working stress at the overspeed: S_F = R_p0.2 / sigma_red,B, F_S,max = F_M,max + Phi F_A,os;
* R9 fatigue: S_D = sigma_AS / sigma_a, sigma_a = Phi dF_A / (2 A_s), dF_A the larger of the
  working cycle's range and the start-stop range (0 to the working F_A,max: any number of
  starts taken as endurance cycles);
* residual clamp load F_KR,min = F_M,min - F_Z - (1 - Phi') F_A,max at the overspeed against
  opening (S_sep = (F_M,min - F_Z) / ((1 - Phi') F_A,max) >= 1) and against slip
  (R12: S_G = F_KR,min mu_T q_F / F_Q,max, q_F = 1 interface).
Phi = n Phi_K for the bolt's loads and Phi' = n Phi_K for the clamp's, where n is stated
(VDI 2230 5.2.2); without it the bounds: n = 1 for the bolt (the largest additional bolt
load) and n = 0 for the clamp (the whole F_A relieves the interface).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from fe_crank.assess import vdi2230 as v

E_BOLT = 205e9  # Pa, steel bolts (VDI 2230)


@dataclass(frozen=True)
class JointLoads:
    """Per bolt, N: the axial load's range over the working cycle, its overspeed value, the
    largest transverse load (working cycle and overspeed)."""

    axial_max: float
    axial_min: float
    axial_overspeed: float
    transverse_max: float


@dataclass(frozen=True)
class JointCheck:
    """VDI 2230 results of one bolted counterweight (per bolt, SI)."""

    name: str
    preload_max: float  # F_M,max
    preload_min: float  # F_M,min
    embedding_loss: float  # F_Z
    load_factor: float  # Phi_K
    tightening_torque: float  # M_A at F_M,max and the stated friction, N m
    assembly_utilisation: float  # R7, nu
    working_safety: float  # R8, S_F at the overspeed
    fatigue_amplitude: float  # sigma_a, Pa
    endurance_limit: float  # sigma_AS, Pa
    fatigue_safety: float  # R9, S_D
    residual_clamp: float  # F_KR,min at the overspeed, N
    separation_safety: float  # S_sep
    slip_safety: float  # R12, S_G
    loads: JointLoads


def counterweight_loads(
    mass: float,
    radius: float,
    count: int,
    direction: str,
    *,
    omega: float,
    overspeed: float | None,
    speed_fluctuation: float = 0.0,
    angular_acceleration: float = 0.0,
) -> JointLoads:
    """Per-bolt loads of a counterweight (module doc).  ``angular_acceleration``: the largest
    |alpha| over the working cycle, rad/s^2; ``speed_fluctuation``: delta."""
    mr = mass * radius
    f_hi = mr * (omega * (1.0 + 0.5 * speed_fluctuation)) ** 2
    f_lo = mr * (omega * (1.0 - 0.5 * speed_fluctuation)) ** 2
    f_os = mr * (overspeed if overspeed is not None else omega) ** 2
    f_t = mr * abs(angular_acceleration)
    if direction == "radial":
        return JointLoads(f_hi / count, f_lo / count, max(f_os, f_hi) / count, f_t / count)
    if direction == "axial":
        return JointLoads(0.0, 0.0, 0.0, math.hypot(max(f_os, f_hi), f_t) / count)
    raise ValueError(f"bolt direction must be 'radial' or 'axial', not {direction!r}")


def yield_point(joint) -> float:
    """R_p0.2 of the bolt: given, or by its ISO 898-1 property class."""
    if joint.yield_strength is not None:
        return joint.yield_strength
    lo, hi = v.PROPERTY_CLASS_RP02[joint.property_class]
    return lo if joint.diameter <= 0.016 + 1e-12 else hi


def check_joint(name: str, joint, loads: JointLoads, e_clamped: float) -> JointCheck:
    """VDI 2230 checks of one bolt of ``joint`` (``geometry.spec.BoltedJoint``) under ``loads``;
    ``e_clamped``: Young's modulus of the counterweight and web (and of the tapped thread)."""
    d, p, lk = joint.diameter, joint.thread_pitch, joint.clamp_length
    tapped = joint.tapped
    rp = yield_point(joint)
    t = v.thread(d, p)
    ds = v.bolt_resilience(
        d, p, lk, E_BOLT, e_clamped, tapped=tapped, shank_length=joint.shank_length, shank_diameter=joint.shank_diameter
    )
    dp = v.plate_resilience(
        lk, joint.bearing_diameter, joint.hole_diameter, joint.clamped_diameter, e_clamped, tapped=tapped
    )
    phi_k = dp / (ds + dp)
    n = joint.load_introduction
    phi_bolt = phi_k * (1.0 if n is None else n)
    phi_clamp = phi_k * (0.0 if n is None else n)
    loading = "shear" if loads.transverse_max > 0 else "tension"
    f_z = v.embedding(joint.roughness, loading, tapped=tapped) / (ds + dp)
    f_m_max = joint.preload if joint.preload is not None else v.permissible_preload(d, p, rp, joint.thread_friction)
    f_m_min = f_m_max / joint.tightening_factor
    red_m = v.assembly_stress(d, p, f_m_max, joint.thread_friction)[2]
    sigma_b = (f_m_max + phi_bolt * loads.axial_overspeed) / t["As"]
    red_b = math.hypot(sigma_b, math.sqrt(3.0) * v.K_TAU * v.working_torsion(d, p, f_m_max, joint.thread_friction))
    d_fa = max(loads.axial_max - loads.axial_min, loads.axial_max)  # working cycle or start-stop
    sigma_a = phi_bolt * d_fa / (2.0 * t["As"])
    f_mean = f_m_max + phi_bolt * 0.5 * loads.axial_max
    limit = v.endurance_limit(
        d, rolled_after_heat_treatment=joint.rolled_after_heat_treatment, mean_over_yield_load=f_mean / (t["As"] * rp)
    )
    relief = (1.0 - phi_clamp) * loads.axial_overspeed
    f_kr = f_m_min - f_z - relief
    d_km = 0.5 * (joint.bearing_diameter + joint.hole_diameter)
    return JointCheck(
        name=name,
        preload_max=f_m_max,
        preload_min=f_m_min,
        embedding_loss=f_z,
        load_factor=phi_k,
        tightening_torque=v.tightening_torque(d, p, f_m_max, joint.thread_friction, joint.head_friction, d_km),
        assembly_utilisation=red_m / rp,
        working_safety=rp / red_b,
        fatigue_amplitude=sigma_a,
        endurance_limit=limit,
        fatigue_safety=limit / sigma_a if sigma_a > 0 else math.inf,
        residual_clamp=f_kr,
        separation_safety=(f_m_min - f_z) / relief if relief > 0 else math.inf,
        slip_safety=max(f_kr, 0.0) * joint.interface_friction / loads.transverse_max
        if loads.transverse_max > 0
        else math.inf,
        loads=loads,
    )


def cycle_speed_data(dynamics, flywheel_inertia: float | None = None) -> tuple[float, float]:
    """(delta, max |alpha|) of a cycle from the dynamics stage, the largest angular
    acceleration alpha = (T - T_mean) / J (torque reduced to the reference shaft).

    Without ``flywheel_inertia``: the operating cycle, J its flywheel inertia sized for the
    coefficient of speed fluctuation delta.  With it (the operating cycle's J: the one
    flywheel), a cycle at another speed of the full-load curve or a misfire case: that
    cycle's delta = dE / (J omega^2) with dE its excess energy (the same flywheel at another
    speed and torque)."""
    if flywheel_inertia is None:
        j, delta = float(dynamics.flywheel_inertia), float(dynamics.speed_fluctuation)
    else:
        j = float(flywheel_inertia)
        delta = float(dynamics.excess_energy) / (j * float(dynamics.speed) ** 2) if j > 0 else 0.0
    if not j > 0:
        return delta, 0.0
    return delta, float(max(abs(dynamics.torque - dynamics.mean_torque))) / j


def check_joints(
    cw,
    *,
    omega: float,
    overspeed: float | None,
    e_clamped: float,
    speed_fluctuation: float = 0.0,
    angular_acceleration: float = 0.0,
    file: str = "",
) -> tuple[JointCheck, ...]:
    """VDI 2230 checks of every bolted counterweight of ``cw`` (``CounterweightData``); a
    joint without the data the check needs is an InputError naming the missing keys."""
    from fe_crank.errors import InputError

    out = []
    for b in cw.joints:
        missing = b.joint.vdi_missing()
        if missing:
            raise InputError(
                f"{b.name}: the VDI 2230 bolt check needs {', '.join(missing)} (docs/assessment.md)",
                file=file,
                key="counterweight.bolted",
            )
        loads = counterweight_loads(
            b.mass,
            b.radius,
            b.joint.count,
            b.joint.direction,
            omega=omega,
            overspeed=overspeed,
            speed_fluctuation=speed_fluctuation,
            angular_acceleration=angular_acceleration,
        )
        out.append(check_joint(b.name, b.joint, loads, e_clamped))
    return tuple(out)


#: criterion quantity -> (JointCheck field, sense); the worst over the joints is judged
JOINT_QUANTITIES = {
    "bolt_assembly_utilisation": ("assembly_utilisation", "max"),
    "bolt_working_safety": ("working_safety", "min"),
    "bolt_fatigue_safety": ("fatigue_safety", "min"),
    "bolt_separation_safety": ("separation_safety", "min"),
    "bolt_slip_safety": ("slip_safety", "min"),
}


__all__ = [
    "E_BOLT",
    "JOINT_QUANTITIES",
    "JointLoads",
    "JointCheck",
    "counterweight_loads",
    "yield_point",
    "check_joint",
    "check_joints",
    "cycle_speed_data",
]
