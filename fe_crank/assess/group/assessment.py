"""Assessment of one throw from its unit stresses and its load history (plain arrays).

Static: sigma_v,max over the cycle at every assessed node.  Overspeed: the same over the
cycle recomputed at the overspeed (``overspeed_coefficients``: the crank's own body force
at omega_os^2 and the rod and piston forces of the overspeed cycle, whose inertia part
scales with omega_os^2), the worst angle of that cycle.  Safety n_s = R_e / sigma_v,max.
Fatigue: ``fatigue.py``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from fe_crank.assess import fatigue
from fe_crank.assess.factors import FatigueFactors, factors, location_of
from fe_crank.assess.group.peak import TIE_RTOL, group_peak, max_over_cycle
from fe_crank.assess.stress import von_mises_planes
from fe_crank.assess.superpose import UnitStresses, iter_planes
from fe_crank.assess.workers import Scratch, run_blocks, scratch_array
from fe_crank.fe.throw.node_groups import GroupKind, group_kind
from fe_crank.io.material import Material

#: groups assessed for fatigue with Gough-Pollard need a local axis: these kinds lie on
#: the crankpin, axis (x, y) = (0, R); the journal fillets on the crank axis (0, 0)
PIN_AXIS_KINDS: tuple[GroupKind, ...] = ("crankpin_fillet", "oil_bore", "crankpin")
JOURNAL_AXIS_KINDS: tuple[GroupKind, ...] = ("journal_fillet",)
#: groups belonging to a counterweight: its stress criteria take their largest von Mises
COUNTERWEIGHT_KINDS: tuple[GroupKind, ...] = ("counterweight_fillet", "counterweight", "junction")
#: of these, the ones not assessed for fatigue (their own stress criteria apply); the
#: counterweight's transition fillet is, its stress cycling with the pin force like the web's
STATIC_ONLY_KINDS: tuple[GroupKind, ...] = ("counterweight", "junction")
#: the shaft fillets, where UR M53 section 4's additional bending stress sigma_add
#: (misalignment, bedplate deformation, axial and bending vibration: loads no single-throw
#: model carries) is added to the alternating bending stress, in the FE route as in the M53
#: route (5.2); not at the oil-bore outlet (5.2 has no sigma_add there)
SIGMA_ADD_KINDS: tuple[GroupKind, ...] = ("crankpin_fillet", "journal_fillet")


def fatigue_assessed(group: str) -> bool:
    """Whether the group is assessed for fatigue (every kind but ``STATIC_ONLY_KINDS``)."""
    return group_kind(group) not in STATIC_ONLY_KINDS


def of_counterweight(group: str) -> bool:
    """Whether the group belongs to a counterweight (``COUNTERWEIGHT_KINDS``)."""
    return group_kind(group) in COUNTERWEIGHT_KINDS


def sigma_add_applies(group: str) -> bool:
    """Whether UR M53's sigma_add is added at the group (``SIGMA_ADD_KINDS``)."""
    return group_kind(group) in SIGMA_ADD_KINDS


@dataclass(frozen=True)
class Extreme:
    """A worst value and where it occurs."""

    value: float
    group: str
    node: int  # mesh node id
    point: tuple[float, float, float]
    angle: float | None = None  # rad, cycle angle where it occurs (None: not angle-bound)


@dataclass(frozen=True)
class GroupResult:
    """Results of one node group (fillet, oil bore, counterweight, junction)."""

    group: str
    n_nodes: int
    max_von_mises: Extreme  # over the cycle
    max_von_mises_overspeed: Extreme | None
    static_safety: float
    overspeed_safety: float | None
    fatigue_safety: Extreme | None  # von Mises + Goodman (min over the group)
    gough_pollard_safety: Extreme | None
    amplitude_at_critical: float | None = None  # sigma_a' at the fatigue-critical node, Pa
    mean_at_critical: float | None = None  # sigma_m' there, Pa
    fatigue_factors: FatigueFactors | None = None  # applied to the specimen fatigue limits
    additional_bending: float = 0.0  # Pa, UR M53 sigma_add added to the amplitudes (SIGMA_ADD_KINDS)
    #: per-node arrays for reports/VTU (not in the JSON): "node_ids", "max_von_mises",
    #: "amplitude", "mean" (equivalent sigma_a', signed sigma_m'), "fatigue_safety",
    #: "gough_pollard_safety" (inf where not computed)
    fields: dict[str, np.ndarray] = field(default_factory=dict, repr=False, compare=False)


def axis_for(group: str, crank_radius: float) -> tuple[float, float] | None:
    """Axis (x, y) of the cylinder a group lies on (the crankpin's or the journal's); None
    for the groups not on a cylinder."""
    kind = group_kind(group)
    if kind in PIN_AXIS_KINDS:
        return (0.0, crank_radius)
    if kind in JOURNAL_AXIS_KINDS:
        return (0.0, 0.0)
    return None


def first_extreme(values: np.ndarray, worst: str = "max", axis: int = 0) -> np.ndarray:
    """Index of the first value within ``TIE_RTOL`` of the max (min) along ``axis``."""
    v = np.asarray(values, float)
    e = v.max(axis=axis, keepdims=True) if worst == "max" else v.min(axis=axis, keepdims=True)
    tol = TIE_RTOL * np.abs(e)
    near = v >= e - tol if worst == "max" else v <= e + tol
    first: np.ndarray = np.argmax(near, axis=axis)
    return first


def section_diameter(group: str, pin_diameter: float | None, journal_diameter: float | None) -> float | None:
    """Diameter of the section a group belongs to, for the size factor: the crankpin's
    for its fillets and the oil bore, the journal's for the journal fillets."""
    kind = group_kind(group)
    if kind in PIN_AXIS_KINDS:
        return pin_diameter
    if kind in JOURNAL_AXIS_KINDS:
        return journal_diameter
    return None


def node_extreme(
    values: np.ndarray, idx: np.ndarray, unit: UnitStresses, group: str, *, worst: str, angles: np.ndarray | None = None
) -> Extreme:
    """The group's worst node of ``values`` (its first within ``TIE_RTOL`` when all are finite) as
    an ``Extreme`` with node id, point and, given ``angles``, crank angle."""
    k = (
        int(first_extreme(values, worst))
        if np.isfinite(values).all()
        else int(np.argmax(values) if worst == "max" else np.argmin(values))
    )
    node = int(unit.node_ids[idx[k]]) if unit.node_ids is not None else int(idx[k])
    x, y, z = (float(c) for c in unit.points[:, idx[k]])
    pt = (x, y, z)
    ang = float(angles[k]) if angles is not None else None
    return Extreme(float(values[k]), group, node, pt, ang)


def assess_group(
    unit: UnitStresses,
    group: str,
    coefficients: np.ndarray,
    theta: np.ndarray,
    material: Material,
    *,
    crank_radius: float,
    overspeed: float | None,
    chunk: int = fatigue.NODE_BLOCK,
    overspeed_coefficients: np.ndarray | None = None,
    diameter: float | None = None,
    additional_bending: float = 0.0,
) -> GroupResult:
    """Static and fatigue results of one node group.  ``material`` needs yield strength
    for the static part and the fatigue properties for the fatigue part (None skips).
    ``overspeed_coefficients`` (n_angles, n_cases): the unit-case coefficients of the
    cycle at the overspeed (``load_coefficients`` of the overspeed pin force and torque
    at omega_os); required when ``overspeed`` is given.  ``diameter``: the section
    diameter for the size factor (``factors.factors``; None: its fallback).  The node
    blocks run on the context's threads (``workers.run_blocks``: the same results bit for
    bit as one thread).  ``additional_bending``: UR M53 4's sigma_add (Pa), added to
    the alternating bending stress as 5.2 does: to the Gough-Pollard normal-stress amplitude
    sigma_a, and to the equivalent amplitude sigma_a' of the Goodman criterion (the von Mises
    amplitude of the path plus a uniaxial sigma_add is at most sigma_a' + sigma_add, so this is
    an upper bound); the per-node ``amplitude`` field stays the FE's own."""
    nodes = np.asarray(unit.groups[group])
    if nodes.size == 0:
        raise ValueError(f"node group {group!r} is empty")
    limits = fatigue.fatigue_limits(material) if fatigue_assessed(group) else None
    do_fatigue = limits is not None
    axis = axis_for(group, crank_radius)
    torsion = limits.torsion if limits is not None and axis is not None else None
    do_gp = torsion is not None
    ff = factors(material, diameter, location_of(group)) if do_fatigue else None
    k = ff.product if ff is not None else 1.0
    vm_max = np.empty(nodes.size)
    vm_arg = np.empty(nodes.size, dtype=int)
    good = np.full(nodes.size, np.inf)
    sa_eq = np.zeros(nodes.size)
    sm_eq = np.zeros(nodes.size)
    gp = np.full(nodes.size, np.inf)

    def block(pos: int, scratch: Scratch) -> None:
        # every criterion reads the same history, ``chunk`` nodes at a time as its six
        # component planes (6, n_t, k): cache-resident and contiguous for every pass; the
        # block writes its own slice only (``workers.run_blocks``)
        idx = nodes[pos : pos + chunk]
        sl = slice(pos, pos + idx.size)
        ((_, planes),) = iter_planes(unit, coefficients, idx, chunk)  # one block
        buf = scratch_array(scratch, "buf", planes.shape)
        hist = planes.transpose(1, 0, 2)  # (n_t, 6, k) view
        vm_max[sl], vm_arg[sl] = max_over_cycle(von_mises_planes(planes, buf=buf))  # over (n_t, k)
        if limits is not None:
            a, m = fatigue.equivalent_amplitude_mean(hist)
            sa_eq[sl], sm_eq[sl] = a, m
            good[sl] = fatigue.goodman_safety(a + additional_bending, m, k * limits.bending, limits.tensile)
        if limits is not None and torsion is not None and axis is not None:
            sig, tau = fatigue.bending_torsion(hist, unit.points[:, idx], axis)
            s_a, s_m = fatigue.half_range(sig)
            t_a, t_m = fatigue.half_range(tau)
            gp[sl] = fatigue.gough_pollard_safety(
                s_a + additional_bending,
                s_m,
                t_a,
                t_m,
                k * limits.bending,
                k * torsion,
                limits.tensile,
            )

    run_blocks(block, range(0, nodes.size, chunk))
    worst = node_extreme(vm_max, nodes, unit, group, worst="max", angles=theta[vm_arg])
    ys = material.yield_strength
    static = ys / worst.value if (ys is not None and worst.value > 0) else np.inf
    os_ext, os_safety = None, None
    if overspeed is not None:
        if overspeed_coefficients is None:
            raise ValueError("overspeed given without the overspeed cycle's coefficients")
        # only the group's largest peak is reported: evaluated where it can occur (peak.py)
        pos, vm_os, os_arg = group_peak(unit, overspeed_coefficients, nodes, chunk)
        os_ext = node_extreme(vm_os, nodes[pos], unit, group, worst="max", angles=theta[os_arg])
        os_safety = ys / os_ext.value if (ys is not None and os_ext.value > 0) else np.inf
    fat = gpe = None
    amp = mean = None
    if do_fatigue:
        fat = node_extreme(good, nodes, unit, group, worst="min")
        j = int(np.argmin(good))
        amp, mean = float(sa_eq[j]), float(sm_eq[j])
    if do_gp:
        gpe = node_extreme(gp, nodes, unit, group, worst="min")
    ids = unit.node_ids[nodes] if unit.node_ids is not None else nodes
    fields = {
        "node_ids": ids,
        "max_von_mises": vm_max,
        "amplitude": sa_eq,
        "mean": sm_eq,
        "fatigue_safety": good,
        "gough_pollard_safety": gp,
    }
    return GroupResult(
        group,
        int(nodes.size),
        worst,
        os_ext,
        float(static),
        None if os_safety is None else float(os_safety),
        fat,
        gpe,
        amp,
        mean,
        ff,
        fields=fields,
        additional_bending=additional_bending if do_fatigue else 0.0,
    )


def assess_groups(
    unit: UnitStresses,
    coefficients: np.ndarray,
    theta: np.ndarray,
    material: Material,
    *,
    crank_radius: float,
    overspeed: float | None,
    overspeed_coefficients: np.ndarray | None,
    pin_diameter: float | None,
    journal_diameter: float | None,
    additional_bending: float,
) -> tuple[GroupResult, ...]:
    """``assess_group`` of every non-empty assessed group of ``unit``, each with its section
    diameter and, on the shaft fillets, UR M53's additional bending stress; the overspeed
    rows (one or more cycles of ``len(theta)`` angles) keep the angle of their row."""
    theta = np.asarray(theta)
    theta_os = theta
    if overspeed_coefficients is not None:
        theta_os = np.tile(theta, overspeed_coefficients.shape[0] // max(1, theta.size))
    return tuple(
        assess_group(
            unit,
            g,
            coefficients,
            theta_os,
            material,
            crank_radius=crank_radius,
            overspeed=overspeed,
            overspeed_coefficients=overspeed_coefficients,
            diameter=section_diameter(g, pin_diameter, journal_diameter),
            additional_bending=additional_bending if sigma_add_applies(g) else 0.0,
        )
        for g in sorted(unit.groups)
        if len(unit.groups[g])
    )
