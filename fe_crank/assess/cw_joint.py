"""The bolted counterweight checked as VDI 2230 Part 1 (2015) checks a bolted joint, with its
eccentric clamping and loading; its loads per bolt are ``assess.joint_loads``'s.

Check (``check_joint``), VDI 2230's steps with n the load introduction factor, over the
corners of the working cycle's box of (F_A, M_B) and at the overspeed (the bolt stress is
linear in both, so its extremes lie on the corners of any box that holds the cycle's path):
* R3 load factors Phi_en*, Phi_m* (eccentric; Phi_K = delta_P/(delta_S + delta_P) centric);
* R7 assembly: nu = sigma_red,M(F_M,max) / R_p0.2 <= 0.9 at the thread friction mu_G; F_M,max
  the stated preload or F_M,zul, F_M,min = F_M,max / alpha_A (R1, tightening factor);
* R8 working stress at the overspeed: S_F = R_p0.2 / sigma_red,B, sigma_z = F_M,max/A_s plus the
  additional bolt load's stress Phi_en* F_A/A_s + Phi_m* M_B/A_s and, on the safe side, the
  bolt's bending stress;
* R9 fatigue: S_D = sigma_AS / sigma_a, sigma_a = (sigma_SAb,o - sigma_SAb,u)/2 at the bolt's
  more loaded fibre with sigma_SAb of the eccentric loading (axial and bending), over the
  cycle's range of F_A and M_B or a start and stop (0 to the working values: any number of
  starts taken as endurance cycles);
* R2/R5 opening: the residual clamp load F_KR = F_M,min - F_Z - (1 - Phi_en*') F_A against the
  opening limit F_Kab of either edge: S_sep = (F_M,min - F_Z) / ((1 - Phi_en*') F_A + F_Kab)
  (>= 1: the joint does not open; centric F_Kab = 0);
* R12 slip: S_G = F_KR,min mu_T q_F / F_Q,max, q_F = 1 interface, mu_T the interface's friction
  (the thread's mu_G enters R7/R8 and the head's mu_K the tightening torque, R13).
Phi = n Phi_K for the bolt's loads and Phi' = n Phi_K for the clamp's, where n is stated
(VDI 2230 5.2.2); without it the bounds: n = 1 for the bolt (the largest additional bolt
load) and n = 0 for the clamp (the whole F_A relieves the interface).

Default limits (``DEFAULT_LIMITS``, ``with_default_limits``): a load case whose geometry has
bolted counterweights and whose criteria name none of the VDI 2230 quantities is checked
with VDI 2230's usual limits, each verdict line saying the limit is a default.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from fe_crank.assess.counterweight import CounterweightData
from fe_crank.assess.joint_loads import JointLoads, fe_section_loads, joint_loads, stated, web_moments
from fe_crank.assess.superpose import UnitStresses
from fe_crank.geometry.spec import BoltedJoint
from fe_crank.rules import vdi2230 as v
from fe_crank.rules.m53.calculation import RodLoads

E_BOLT = 205e9  # Pa, steel bolts (VDI 2230)


@dataclass(frozen=True)
class JointCheck:
    """VDI 2230 results of one bolted counterweight (per bolt, SI)."""

    name: str
    preload_max: float  # F_M,max
    preload_min: float  # F_M,min
    embedding_loss: float  # F_Z
    load_factor: float  # Phi_K (centric)
    tightening_torque: float  # M_A at F_M,max and the stated friction, N m
    assembly_utilisation: float  # R7, nu
    working_safety: float  # R8, S_F at the overspeed
    fatigue_amplitude: float  # sigma_a, Pa
    endurance_limit: float  # sigma_AS, Pa
    fatigue_safety: float  # R9, S_D
    residual_clamp: float  # F_KR,min at the overspeed, N
    separation_safety: float  # S_sep (R2/R5: against opening)
    slip_safety: float  # R12, S_G
    loads: JointLoads
    eccentric_load_factor: float = math.nan  # Phi_en* (bolt side; = n Phi_K centric)
    moment_load_factor: float = 0.0  # Phi_m*, 1/m
    opening_limit: float = 0.0  # F_Kab, N (the largest over the cycle and the overspeed)
    bending_amplitude: float = 0.0  # the bending part of sigma_a, Pa
    friction: tuple[float, float, float] = (math.nan, math.nan, math.nan)  # mu_G, mu_K, mu_T


def yield_point(joint: BoltedJoint) -> float:
    """R_p0.2 of the bolt: given, or by its ISO 898-1 property class."""
    if joint.yield_strength is not None:
        return joint.yield_strength
    if joint.property_class is None:
        raise ValueError("the VDI 2230 bolt check needs the bolt's yield_strength or property_class")
    lo, hi = v.PROPERTY_CLASS_RP02[joint.property_class]
    return lo if joint.diameter <= 0.016 + 1e-12 else hi


def _corners(loads: JointLoads) -> tuple[list[tuple[float, float]], list[tuple[float, float]]]:
    """(F_A, M_B) corners of the working cycle's box and of the overspeed (both signs of M_B)."""
    work = [(f, m) for f in (loads.axial_min, loads.axial_max) for m in (loads.moment_min, loads.moment_max)]
    over = [(loads.axial_overspeed, m) for m in (-loads.moment_overspeed, loads.moment_overspeed)]
    return work, over


def check_joint(name: str, joint: BoltedJoint, loads: JointLoads, e_clamped: float) -> JointCheck:
    """VDI 2230 checks of one bolt of ``joint`` (``geometry.spec.BoltedJoint``) under ``loads``;
    ``e_clamped``: Young's modulus of the counterweight and web (and of the tapped thread).
    With ``loads.eccentric`` VDI 2230's eccentric clamping and loading (R2, R3, R5, R9),
    without it the centric joint (module docstring)."""
    d, p, lk = joint.diameter, joint.thread_pitch, stated(joint.clamp_length, name, "clamp_length")
    d_w = stated(joint.bearing_diameter, name, "bearing_diameter")
    d_h = stated(joint.hole_diameter, name, "hole_diameter")
    d_a = stated(joint.clamped_diameter, name, "clamped_diameter")
    alpha_a = stated(joint.tightening_factor, name, "tightening_factor")
    tapped = joint.tapped
    rp = yield_point(joint)
    t = v.thread(d, p)
    ds = v.bolt_resilience(
        d, p, lk, E_BOLT, e_clamped, tapped=tapped, shank_length=joint.shank_length, shank_diameter=joint.shank_diameter
    )
    dp = v.plate_resilience(lk, d_w, d_h, d_a, e_clamped, tapped=tapped)
    phi_k = dp / (ds + dp)
    n = joint.load_introduction
    n_bolt, n_clamp = (1.0, 0.0) if n is None else (n, n)
    ecc = loads.eccentric
    if ecc is None:  # centric (R3): Phi = n Phi_K, no moment, no bending, F_Kab = 0
        phi_en, phi_m = n_bolt * phi_k, 0.0
        phi_en_c, phi_m_c = n_clamp * phi_k, 0.0
        k_f, k_m, b_f, b_m = phi_en / t["As"], 0.0, 0.0, 0.0
        i_bt = a_d = math.nan
    else:
        i_bt, a_d = v.interface_section(ecc, d_h)
        if not (i_bt > 0 and a_d > 0):
            raise ValueError(f"{name}: the joint's interface is smaller than its bolt hole")
        phi_en, phi_m = v.eccentric_load_factors(ds, dp, ecc, lk, e_clamped, i_bt, n_bolt)
        phi_en_c, phi_m_c = v.eccentric_load_factors(ds, dp, ecc, lk, e_clamped, i_bt, n_clamp)
        l_ers = v.bending_length(d, p, lk, joint.shank_length, joint.shank_diameter)
        k_f, k_m, b_f, b_m = v.bending_stress_coefficients(ecc, phi_en, phi_m, d, p, lk, l_ers, E_BOLT, e_clamped, i_bt)
    work, over = _corners(loads)
    loading = "shear" if loads.transverse_max > 0 else "tension"
    f_z = v.embedding(joint.roughness, loading, tapped=tapped) / (ds + dp)
    mu_g = joint.thread_friction
    f_m_max = joint.preload if joint.preload is not None else v.permissible_preload(d, p, rp, mu_g)
    f_m_min = f_m_max / alpha_a
    red_m = v.assembly_stress(d, p, f_m_max, mu_g)[2]
    # R8 at the overspeed: the largest bolt stress, axial + bending on the safe side
    fibres = ((k_f + b_f, k_m + b_m), (k_f - b_f, k_m - b_m))
    sigma_b = max(f_m_max / t["As"] + cf * f + cm * m for cf, cm in fibres for f, m in over + work)
    red_b = math.hypot(sigma_b, math.sqrt(3.0) * v.K_TAU * v.working_torsion(d, p, f_m_max, mu_g))
    # R9: the range of each load over the cycle or a start and stop (0 to the working values)
    d_fa = max(loads.axial_max, 0.0) - min(loads.axial_min, 0.0)
    d_mb = max(loads.moment_max, 0.0) - min(loads.moment_min, 0.0)
    sigma_a = max(abs(cf) * d_fa + abs(cm) * d_mb for cf, cm in fibres) / 2.0
    bending_a = (abs(b_f) * d_fa + abs(b_m) * d_mb) / 2.0
    f_mean = f_m_max + phi_en * 0.5 * loads.axial_max
    limit = v.endurance_limit(
        d, rolled_after_heat_treatment=joint.rolled_after_heat_treatment, mean_over_yield_load=f_mean / (t["As"] * rp)
    )
    # R2/R5: the clamp load the working loads take off and the opening limit, at each corner
    avail = f_m_min - f_z
    worst_sep, worst_relief, f_kab_max = math.inf, 0.0, 0.0
    for f, m in over + work:
        relief = (1.0 - phi_en_c) * f + abs(phi_m_c * m)
        f_kab = 0.0 if ecc is None else v.opening_limit_both_edges(f, m, ecc, i_bt, a_d)
        f_kab_max = max(f_kab_max, f_kab)
        worst_relief = max(worst_relief, relief)
        need = relief + f_kab
        worst_sep = min(worst_sep, avail / need if need > 0 else math.inf)
    f_kr = avail - worst_relief
    d_km = 0.5 * (d_w + d_h)
    mu_t = joint.interface_friction
    return JointCheck(
        name=name,
        preload_max=f_m_max,
        preload_min=f_m_min,
        embedding_loss=f_z,
        load_factor=phi_k,
        tightening_torque=v.tightening_torque(d, p, f_m_max, mu_g, joint.head_friction, d_km),
        assembly_utilisation=red_m / rp,
        working_safety=rp / red_b,
        fatigue_amplitude=sigma_a,
        endurance_limit=limit,
        fatigue_safety=limit / sigma_a if sigma_a > 0 else math.inf,
        residual_clamp=f_kr,
        separation_safety=worst_sep,
        slip_safety=max(f_kr, 0.0) * mu_t / loads.transverse_max if loads.transverse_max > 0 else math.inf,
        loads=loads,
        eccentric_load_factor=phi_en,
        moment_load_factor=phi_m,
        opening_limit=f_kab_max,
        bending_amplitude=bending_a,
        friction=(mu_g, joint.head_friction, mu_t),
    )


def check_joints(
    cw: CounterweightData,
    *,
    omega: float,
    overspeed: float | None,
    e_clamped: float,
    speed_fluctuation: float = 0.0,
    angular_acceleration: float = 0.0,
    file: str = "",
    pin_force: ArrayLike | None = None,
    rod_loads: RodLoads | None = None,
    overspeed_loads: Sequence[tuple[Any, ...]] = (),
    fe: tuple[UnitStresses, np.ndarray, np.ndarray | None] | None = None,
) -> tuple[JointCheck, ...]:
    """VDI 2230 checks of every bolted counterweight of ``cw`` (``CounterweightData``); a
    joint without the data the check needs is an InputError naming the missing keys.
    ``pin_force`` (n, 2) of the working cycle in the throw frame (``rod_loads``: each rod's
    force at its place) and the ``overspeed_loads``: the web's bending moment at the joints
    (``web_moments``); None: no web moment.  ``fe``: (unit stresses, working cycle's
    coefficients, overspeed cycles' coefficients or None): a radial joint takes the web's
    deformation from the FE model's section (``fe_section_loads``) where it can be fitted."""
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
        web = section = None
        if b.geometry is not None and pin_force is not None:
            web = web_moments(b.geometry, pin_force, rod_loads, overspeed_loads)
        if b.geometry is not None and fe is not None and b.joint.direction == "radial":
            section = fe_section_loads(fe[0], b.name, b.geometry, b.joint, fe[1], fe[2])
        loads = joint_loads(
            b,
            omega=omega,
            overspeed=overspeed,
            speed_fluctuation=speed_fluctuation,
            angular_acceleration=angular_acceleration,
            web=web,
            section=section,
        )
        try:
            out.append(check_joint(b.name, b.joint, loads, e_clamped))
        except ValueError as exc:
            raise InputError(str(exc), file=file, key="counterweight.bolted") from None
    return tuple(out)


__all__ = [
    "E_BOLT",
    "JointCheck",
    "yield_point",
    "check_joint",
    "check_joints",
]
