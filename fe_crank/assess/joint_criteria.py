"""The bolted counterweights' joints in the criteria table: the VDI 2230 quantities a load
case may limit (``JOINT_QUANTITIES``), the usual limits taken when it names none
(``DEFAULT_LIMITS``), and the words their verdict lines carry.  The joints themselves are
checked in ``assess.cw_joint``."""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping

from fe_crank.assess.throw_geometry import ThrowGeometry
from fe_crank.io.criteria import Criteria
from fe_crank.results import Sense

#: criterion quantity -> (JointCheck field, sense); the worst over the joints is judged
JOINT_QUANTITIES: dict[str, tuple[str, Sense]] = {
    "bolt_assembly_utilisation": ("assembly_utilisation", "max"),
    "bolt_working_safety": ("working_safety", "min"),
    "bolt_fatigue_safety": ("fatigue_safety", "min"),
    "bolt_separation_safety": ("separation_safety", "min"),
    "bolt_slip_safety": ("slip_safety", "min"),
}


#: VDI 2230's usual limits, taken when a load case with bolted counterweights names none of
#: the joint quantities: R7 nu <= 0.9 (the utilisation F_M,zul is defined by), R8 S_F >= 1.0,
#: R9 S_D >= 1.2, opening S_sep >= 1.0 (no opening), R12 S_G >= 1.8 (VDI 2230's value for an
#: alternating transverse load, which the counterweight's tangential inertia is; 1.2 static)
DEFAULT_LIMITS = {
    "bolt_assembly_utilisation": 0.9,
    "bolt_working_safety": 1.0,
    "bolt_fatigue_safety": 1.2,
    "bolt_separation_safety": 1.0,
    "bolt_slip_safety": 1.8,
}
DEFAULT_WORDS = "default limit (VDI 2230's usual value; the load case names no bolted-joint criterion)"


def has_joints(throw_geometry: Mapping[str, ThrowGeometry | None]) -> bool:
    """Whether any throw's geometry (``ThrowGeometry`` by name) has a bolted counterweight."""
    return any(c.joints for tg in throw_geometry.values() if tg is not None for c in tg.counterweights)


def unchecked_joints(throw_geometry: Mapping[str, ThrowGeometry | None]) -> list[str]:
    """ "throw <name>: <counterweight>" of every bolted counterweight that carries no joint data
    (a CAD geometry's bolted bodies): VDI 2230 cannot check them, which the case must say."""
    return [
        f"throw {name}: {c.name}"
        for name, tg in throw_geometry.items()
        if tg is not None
        for c in tg.counterweights
        if c.bolted and not c.joints
    ]


def with_default_limits(criteria: Criteria, file: str = "") -> tuple[Criteria, tuple[str, ...]]:
    """``criteria`` (``io.criteria.Criteria``) with ``DEFAULT_LIMITS`` added when it names none of
    the joint quantities; (criteria, the quantities added)."""
    from fe_crank.io.criteria import Limit

    if any(lim.quantity in JOINT_QUANTITIES for lim in criteria.limits):
        return criteria, ()
    added = tuple(
        Limit(q, JOINT_QUANTITIES[q][1], value, f"criteria.{JOINT_QUANTITIES[q][1]}_{q}")
        for q, value in DEFAULT_LIMITS.items()
    )
    return dataclasses.replace(criteria, limits=criteria.limits + added), tuple(q for q in DEFAULT_LIMITS)


def joint_qualifiers(
    throw_geometry: Mapping[str, ThrowGeometry | None], defaulted: tuple[str, ...] = ()
) -> dict[str, str]:
    """quantity -> the words each joint criterion's verdict line carries: the friction
    coefficients the joints were checked with (thread mu_G, head mu_K, interface mu_T) and,
    where the limit is a default, that it is one."""
    sets = sorted(
        {
            (j.joint.thread_friction, j.joint.head_friction, j.joint.interface_friction)
            for tg in throw_geometry.values()
            if tg is not None
            for c in tg.counterweights
            for j in c.joints
        }
    )
    if not sets:
        return {}
    words = "; ".join(f"mu_G {g:.2f}, mu_K {k:.2f}, mu_T {t:.2f}" for g, k, t in sets)
    return {
        q: "; ".join(w for w in (f"friction {words}", DEFAULT_WORDS if q in defaulted else "") if w)
        for q in JOINT_QUANTITIES
    }


__all__ = [
    "DEFAULT_LIMITS",
    "DEFAULT_WORDS",
    "JOINT_QUANTITIES",
    "has_joints",
    "joint_qualifiers",
    "unchecked_joints",
    "with_default_limits",
]
