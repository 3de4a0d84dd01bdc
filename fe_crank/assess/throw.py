"""One throw: its groups' static, overspeed and fatigue results, UR M53, counterweights."""

from __future__ import annotations

import dataclasses
from dataclasses import KW_ONLY, dataclass
from typing import Any

import numpy as np

from fe_crank.assess.counterweight import CounterweightCheck, CounterweightData, check_counterweight
from fe_crank.assess.cw_joint import JointCheck, check_joints
from fe_crank.assess.group.assessment import GroupResult, assess_groups, section_diameter, sigma_add_applies
from fe_crank.assess.group.extremes import Running, Wanted, group_extremes
from fe_crank.assess.superpose import UnitStresses, cycle_coefficients
from fe_crank.errors import InputError
from fe_crank.io.material import Material
from fe_crank.rules.m53 import calculation as m53
from fe_crank.rules.m53 import oil_bore as m53_oil_bore
from fe_crank.rules.m53 import rods as m53_rods
from fe_crank.rules.m53 import scf_empirical
from fe_crank.rules.m53.calculation import M53Fillet, NominalStresses, RodLoads
from fe_crank.rules.m53.scf_mode import ScfResult

#: the loads of an overspeed cycle: (pin force (n, 2), front torque (n,)[, rod loads])
OverspeedLoads = tuple[Any, ...]


@dataclass(frozen=True)
class ThrowAssessment:
    name: str
    groups: tuple[GroupResult, ...]
    m53: tuple[m53.M53Fillet, ...] = ()
    m53_nominal: NominalStresses | None = None
    counterweights: tuple[CounterweightCheck, ...] = ()
    n_angles: int = 0
    joints: tuple[JointCheck, ...] = ()  # VDI 2230 of the bolted counterweights (when checked)


def fe_scfs(scf: ScfResult) -> dict[str, dict[str, float]]:
    """The ``fe_scf`` dictionaries of ``m53.assess_fillet`` from the SCF mode of the UR M53
    FE appendix (``fe_crank.rules.m53.scf_mode.ScfResult``): alpha_B, alpha_T for the pin,
    beta_B, beta_Q (method 1 of App. III 3.3.3), beta_T for the journal fillet, from the
    appendix's own models and stress measures -- not from the cycle model's stresses,
    whose supports and single radial case give neither the nominal-stress basis nor the
    bending/shear split of UR M53.
    """
    return scf.for_assessment()


@dataclass(frozen=True)
class ThrowContext:
    """What one throw is assessed from (``assess_throw``), frozen: unit stresses, the pin
    force (n, 2) in the throw frame and the torque through the front journal (n,) over the
    cycle angles ``theta`` (plain arrays).  UR M53 takes the journal torque (front or rear, ``torque_rear``) with the
    larger alternating part, the one the throw's fillets carry.  Outside the validity
    range of the empirical SCFs UR M53 takes FE SCFs: ``fe_scf`` as given, else those of
    ``scf`` (the SCF mode's ``rules.m53.scf_mode.ScfResult``, which the FE stage solves for such a throw).
    ``m53_additional``: UR M53 4's sigma_add, Pa, on the fillets' alternating bending stress in
    both routes (the FE route: ``assess_group``'s ``additional_bending``).
    ``m53_ke``: UR M53 2.1.2.1's K_e on the web's nominal stresses (``m53.ke_factor``:
    0.8 two-stroke, 1.0 four-stroke); the M53 route only, the FE route's stresses are not scaled.

    ``overspeed_loads`` = (pin force, front torque) of the cycle recomputed at the
    overspeed (``fe_crank.mechanism.cycles``: the dynamics at omega_os with the load case's
    ``overspeed_gas``).  Without it the operating pin force and torque are scaled by
    (omega_os/omega)^2 whole: exact for the inertia part, an over-estimate of the gas
    part (which does not grow with speed), so on the safe side.  A list of such pairs
    (several gas states of the overspeed condition, ``mechanism.cycles.overspeed_cycles``)
    is checked as one longer history: the overspeed result is the worst over all of them.

    With torsional vibration (``fe_crank.torsion.flow``): ``angular_acceleration`` (n,)
    of the throw (the ``angular_acceleration`` unit case's coefficient) and
    ``fe_pin_force``, the pin force the FE pin cases carry (the rods' ``pin_force`` with
    the cylinders' vibratory inertia torque as a tangential force); ``m53_torques``: more
    journal torque histories for UR M53 (the torsional hand-over's, the largest over the
    speed range), of which, with ``torque`` and ``torque_rear``, it takes the one with the
    largest alternating part.  ``extremes``: only each group's extremes
    (``extremes.group_extremes``: no overspeed, no per-node fields), for the speeds of a
    sweep other than the operating one; ``running``: the least fatigue values of the
    throws of the same load state assessed before (``extremes.Running``).
    ``rod_loads``: (force (n, 2), place on the pin m) per rod (``fe.throw.pin_patches``): UR M53's
    moments rod by rod and, where the FE model has patch cases, each rod on its band; an
    overspeed cycle is then (pin force, torque, rod loads).  ``fe_rod_loads``: the rods'
    loads the FE patch cases take with torsional vibration (each rod's force with its share
    of the vibratory tangential force, ``assess.loads.ThrowCycle.fe_rods``); without them a
    model loaded per rod place is refused with a vibratory pin force
    (``superpose.cycle_coefficients``).
    ``joint_speed``: (delta, max |alpha|) of the cycle (``joint_loads.cycle_speed_data``):
    the bolted counterweights' joints are checked by VDI 2230 at ``omega`` (and the
    overspeed) (``cw_joint.check_joints``, an ``InputError`` naming the keys a joint lacks,
    in ``geometry_file``), with the web's bending moment from ``pin_force`` (or ``rod_loads``)
    and the overspeed cycles' pin force; None: not checked."""

    name: str
    unit: UnitStresses
    theta: np.ndarray
    pin_force: np.ndarray
    torque: np.ndarray
    _: KW_ONLY
    omega: float
    sense: int = 1
    overspeed: float | None
    material: Material
    crank_radius: float
    m53_geometry: m53.M53Geometry | None = None
    m53_additional: float = 10e6
    m53_ke: float = 1.0
    fe_scf: dict[str, dict[str, float]] | None = None
    scf: ScfResult | None = None
    counterweights: tuple[CounterweightData, ...] = ()
    torque_rear: np.ndarray | None = None
    overspeed_loads: OverspeedLoads | list[OverspeedLoads] | None = None
    angular_acceleration: np.ndarray | None = None
    fe_pin_force: np.ndarray | None = None
    m53_torques: tuple[np.ndarray, ...] = ()
    extremes: Wanted | None = None
    running: Running | None = None
    rod_loads: RodLoads | None = None
    fe_rod_loads: RodLoads | None = None
    joint_speed: tuple[float, float] | None = None
    geometry_file: str = ""


def fe_coefficients(
    unit: UnitStresses,
    pin_force: np.ndarray,
    torque: np.ndarray,
    omega: float,
    *,
    sense: int,
    rod_loads: RodLoads | None = None,
    angular_acceleration: np.ndarray | None = None,
    fe_pin_force: np.ndarray | None = None,
    fe_rod_loads: RodLoads | None = None,
) -> np.ndarray:
    """The unit cases' coefficients over one cycle of a throw (``superpose
    .cycle_coefficients``), with the torsional vibration when there is one (``ThrowContext``:
    ``angular_acceleration``, the FE pin force and the rods' FE loads); ``assess_throw``
    and the counterweight study (``fe_crank.study``) take them."""
    return cycle_coefficients(
        unit,
        pin_force if fe_pin_force is None else fe_pin_force,
        torque,
        omega,
        sense=sense,
        rod_loads=rod_loads if fe_rod_loads is None else fe_rod_loads,
        angular_acceleration=angular_acceleration,
        vibration=fe_pin_force is not None and fe_rod_loads is None,
    )


def assess_throw(ctx: ThrowContext) -> ThrowAssessment:
    """Assess one throw (``ThrowContext`` says from what)."""
    overspeed_loads = ctx.overspeed_loads
    coeffs = fe_coefficients(
        ctx.unit,
        ctx.pin_force,
        ctx.torque,
        ctx.omega,
        sense=ctx.sense,
        rod_loads=ctx.rod_loads,
        angular_acceleration=ctx.angular_acceleration,
        fe_pin_force=ctx.fe_pin_force,
        fe_rod_loads=ctx.fe_rod_loads,
    )
    coeffs_os = None
    if ctx.overspeed is not None and ctx.extremes is None:
        if overspeed_loads is None:
            scale = (ctx.overspeed / ctx.omega) ** 2 if ctx.omega > 0 else 1.0
            rods_os = (
                None if ctx.rod_loads is None else tuple((scale * np.asarray(f, float), e) for f, e in ctx.rod_loads)
            )
            overspeed_loads = (scale * np.asarray(ctx.pin_force, float), scale * np.asarray(ctx.torque, float), rods_os)
        cycles = overspeed_loads if isinstance(overspeed_loads, list) else [overspeed_loads]
        coeffs_os = np.vstack(
            [
                cycle_coefficients(
                    ctx.unit, c[0], c[1], ctx.overspeed, sense=ctx.sense, rod_loads=c[2] if len(c) > 2 else None
                )
                for c in cycles
            ]
        )
    dp = ctx.m53_geometry.pin_diameter if ctx.m53_geometry is not None else None
    dj = ctx.m53_geometry.journal_diameter if ctx.m53_geometry is not None else None
    if ctx.extremes is not None:
        groups = tuple(
            group_extremes(
                ctx.unit,
                g,
                coeffs,
                np.asarray(ctx.theta),
                ctx.material,
                crank_radius=ctx.crank_radius,
                diameter=section_diameter(g, dp, dj),
                wanted=ctx.extremes,
                running=ctx.running,
                additional_bending=ctx.m53_additional if sigma_add_applies(g) else 0.0,
            )
            for g in sorted(ctx.unit.groups)
            if len(ctx.unit.groups[g])
        )
    else:
        groups = assess_groups(
            ctx.unit,
            coeffs,
            ctx.theta,
            ctx.material,
            crank_radius=ctx.crank_radius,
            overspeed=ctx.overspeed,
            overspeed_coefficients=coeffs_os,
            pin_diameter=dp,
            journal_diameter=dj,
            additional_bending=ctx.m53_additional,
        )
    fillets, nominal = m53_fillets(
        ctx.name,
        ctx.m53_geometry,
        ctx.material,
        ctx.pin_force,
        (ctx.torque, *(() if ctx.torque_rear is None else (ctx.torque_rear,)), *ctx.m53_torques),
        fe_scf=ctx.fe_scf,
        scf=ctx.scf,
        additional=ctx.m53_additional,
        ke=ctx.m53_ke,
        rod_loads=ctx.rod_loads,
    )
    cws = tuple(check_counterweight(c, ctx.omega, ctx.overspeed) for c in ctx.counterweights)
    joints: tuple[JointCheck, ...] = ()
    if ctx.joint_speed is not None:
        joints = throw_joints(
            ctx.unit,
            ctx.counterweights,
            ctx.pin_force,
            ctx.torque,
            omega=ctx.omega,
            sense=ctx.sense,
            overspeed=ctx.overspeed,
            material=ctx.material,
            joint_speed=ctx.joint_speed,
            coeffs=coeffs,
            coeffs_os=coeffs_os,
            rod_loads=ctx.rod_loads,
            overspeed_loads=overspeed_loads,
            geometry_file=ctx.geometry_file,
        )
    return ThrowAssessment(ctx.name, groups, fillets, nominal, cws, int(len(ctx.theta)), joints)


def throw_joints(
    unit: UnitStresses,
    counterweights: tuple[CounterweightData, ...],
    pin_force: np.ndarray,
    torque: np.ndarray,
    *,
    omega: float,
    sense: int,
    overspeed: float | None,
    material: Material,
    joint_speed: tuple[float, float],
    coeffs: np.ndarray,
    coeffs_os: np.ndarray | None = None,
    rod_loads: RodLoads | None = None,
    overspeed_loads: OverspeedLoads | list[OverspeedLoads] | None = None,
    geometry_file: str = "",
) -> tuple[JointCheck, ...]:
    """VDI 2230 of the bolted ``counterweights`` of one throw in one load state
    (``cw_joint.check_joints``), as ``assess_throw`` checks them (``ThrowContext``'s
    ``joint_speed``): the web's moment from ``pin_force`` (``rod_loads``) and the overspeed
    cycles (``overspeed_loads``; None: the operating loads scaled by (omega_os/omega)^2),
    the FE section from ``unit`` with the cycle's ``coeffs`` and the overspeed cycles'
    ``coeffs_os`` (None: formed here from ``overspeed_loads``).  ``assess_throw`` calls it
    with the throw's context; the counterweight study (``fe_crank.study.joints``) with a
    candidate's counterweights."""
    delta, alpha = joint_speed
    if overspeed_loads is None:  # the web's moment at the overspeed: the operating loads scaled
        scale = (overspeed / omega) ** 2 if overspeed is not None and omega > 0 else 1.0
        rods_os = None if rod_loads is None else tuple((scale * np.asarray(f, float), e) for f, e in rod_loads)
        overspeed_loads = (scale * np.asarray(pin_force, float), scale * np.asarray(torque, float), rods_os)
    web_cycles = overspeed_loads if isinstance(overspeed_loads, list) else [overspeed_loads]
    joint_os = coeffs_os
    if joint_os is None and overspeed is not None:
        joint_os = np.vstack(
            [
                cycle_coefficients(unit, c[0], c[1], overspeed, sense=sense, rod_loads=c[2] if len(c) > 2 else None)
                for c in web_cycles
            ]
        )
    return tuple(
        j
        for c in counterweights
        for j in check_joints(
            c,
            omega=omega,
            overspeed=overspeed,
            e_clamped=material.youngs_modulus,
            speed_fluctuation=delta,
            angular_acceleration=alpha,
            file=geometry_file,
            pin_force=pin_force,
            rod_loads=rod_loads,
            overspeed_loads=web_cycles,
            fe=(unit, coeffs, joint_os),
        )
    )


def m53_fillets(
    name: str,
    m53_geometry: m53.M53Geometry | None,
    material: Material,
    pin_force: np.ndarray,
    torques: tuple[np.ndarray, ...],
    *,
    fe_scf: dict[str, dict[str, float]] | None,
    scf: ScfResult | None,
    additional: float,
    ke: float,
    rod_loads: RodLoads | None = None,
) -> tuple[tuple[M53Fillet, ...], NominalStresses | None]:
    """UR M53 of one throw (its fillets' and oil-bore outlet's results, and the nominal
    stresses): the radial pin force's bending and, of the journal torque histories
    ``torques``, the one with the largest alternating part (the first of equals).
    ``assess_throw`` calls it with the throw's context; the counterweight study
    (``fe_crank.study.m53``) with the same loads, without the FE model."""
    fillets: tuple[M53Fillet, ...] = ()
    nominal: NominalStresses | None = None
    m53_additional, m53_ke = additional, ke
    if m53_geometry is not None and material.tensile_strength is not None and material.m53_k is not None:
        scf_note, accepted = None, True
        if (
            fe_scf is None
            and scf is not None
            and any(scf_empirical.out_of_range(m53_geometry.related(f)) for f in ("pin", "journal"))
        ):
            fe_scf, scf_note, accepted = fe_scfs(scf), scf.summary(), scf.mesh_ok
        m53_torque = torques[0]
        for t in torques[1:]:
            if m53.half_range(t) > m53.half_range(m53_torque):
                m53_torque = t
        if rod_loads is None:
            nominal = m53.nominal_stresses(m53_geometry, np.asarray(pin_force)[:, 1], m53_torque, ke=m53_ke)
        else:  # each rod's bending-moment triangle at its own place (UR M53 2.1, m53_rods)
            nominal = m53_rods.nominal_stresses_by_rod(m53_geometry, rod_loads, m53_torque, ke=m53_ke)[0]
        try:
            fillets = tuple(
                m53.assess_fillet(
                    m53_geometry,
                    nominal,
                    f,
                    tensile=material.tensile_strength,
                    k=material.m53_k,
                    additional=m53_additional,
                    fe_scf=(fe_scf or {}).get(f),
                )
                for f in ("pin", "journal")
            )
        except ValueError as exc:  # outside the range and no FE SCFs
            raise InputError(f"throw {name}: {exc}", key="geometry") from None
        if scf_note:  # say which FE SCFs: the appendix's SCF mode and its mesh verdict
            fillets = tuple(
                dataclasses.replace(
                    f,
                    scf_source=f"{scf_note}; outside the UR M53 validity range: " + "; ".join(f.out_of_range),
                    scf_accepted=accepted,
                )
                if f.out_of_range
                else f
                for f in fillets
            )
        outlet = m53_oil_bore.assess_outlet(
            m53_geometry, nominal, pin_force, tensile=material.tensile_strength, k=material.m53_k, rod_loads=rod_loads
        )
        fillets += (outlet,) if outlet is not None else ()
    return fillets, nominal
