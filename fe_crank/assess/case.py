"""One load case: every throw's groups, UR M53, counterweights, criteria -> ``Assessment``."""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from fe_crank.assess import m53, m53_oil_bore, m53_rods
from fe_crank.assess.counterweight import CounterweightCheck, CounterweightData, check_counterweight
from fe_crank.assess.superpose import UnitStresses, cycle_coefficients
from fe_crank.assess.throw import SIGMA_ADD_GROUPS, STATIC_ONLY_PREFIXES, GroupResult, assess_group, section_diameter
from fe_crank.assess.verdict import CriterionResult, judge
from fe_crank.errors import InputError

SCHEMA_VERSION = "1.1"  # 1.1: optional provenance and warnings (written by the report)


@dataclass(frozen=True)
class ThrowAssessment:
    name: str
    groups: tuple[GroupResult, ...]
    m53: tuple[m53.M53Fillet, ...] = ()
    m53_nominal: m53.NominalStresses | None = None
    counterweights: tuple[CounterweightCheck, ...] = ()
    n_angles: int = 0


@dataclass(frozen=True)
class Assessment:
    """Everything the assessment found for one load case."""

    case: str
    source_file: str
    speed: float  # rad/s
    overspeed: float | None
    material: object
    throws: tuple[ThrowAssessment, ...]
    criteria: tuple[CriterionResult, ...]
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def passed(self) -> bool:
        return all(c.passed for c in self.criteria)


def fe_scfs(scf) -> dict[str, dict[str, float]]:
    """The ``fe_scf`` dictionaries of ``m53.assess_fillet`` from the SCF mode of the UR M53
    FE appendix (``fe_crank.assess.scf.ScfResult``): alpha_B, alpha_T for the pin,
    beta_B, beta_Q (method 1 of App. III 3.3.3), beta_T for the journal fillet, from the
    appendix's own models and stress measures -- not from the cycle model's stresses,
    whose supports and single radial case give neither the nominal-stress basis nor the
    bending/shear split of UR M53.
    """
    return scf.for_assessment()


def assess_throw(
    name: str,
    unit: UnitStresses,
    theta: np.ndarray,
    pin_force: np.ndarray,
    torque: np.ndarray,
    *,
    omega: float,
    sense: int = 1,
    overspeed: float | None,
    material,
    crank_radius: float,
    m53_geometry: m53.M53Geometry | None = None,
    m53_additional: float = 10e6,
    m53_ke: float = 1.0,
    fe_scf: dict[str, dict[str, float]] | None = None,
    scf=None,
    counterweights: tuple[CounterweightData, ...] = (),
    torque_rear: np.ndarray | None = None,
    overspeed_loads: tuple[np.ndarray, np.ndarray] | list | None = None,
    threads: int = 1,
    rod_loads: tuple | None = None,
) -> ThrowAssessment:
    """Assess one throw from plain arrays: unit stresses, the pin force (n, 2) in the
    throw frame and the torque through the front journal (n,) over the cycle angles
    ``theta``.  UR M53 takes the journal torque (front or rear, ``torque_rear``) with the
    larger alternating part, the one the throw's fillets carry.  Outside the validity
    range of the empirical SCFs UR M53 takes FE SCFs: ``fe_scf`` as given, else
    ``scf()`` (a callable returning the SCF mode's ``assess.scf.ScfResult``, called only then).
    ``m53_additional``: UR M53 4's sigma_add, Pa, on the fillets' alternating bending stress in
    both routes (the FE route: ``assess_group``'s ``additional_bending``).
    ``m53_ke``: UR M53 2.1.2.1's K_e on the web's nominal stresses (``m53.ke_factor``:
    0.8 two-stroke, 1.0 four-stroke); the M53 route only, the FE route's stresses are not scaled.

    ``overspeed_loads`` = (pin force, front torque) of the cycle recomputed at the
    overspeed (``assess_case`` runs the dynamics at omega_os with the load case's
    ``overspeed_gas``).  Without it the operating pin force and torque are scaled by
    (omega_os/omega)^2 whole: exact for the inertia part, an over-estimate of the gas
    part (which does not grow with speed), so on the safe side.  A list of such pairs
    (several gas states of the overspeed condition, ``assess.overspeed.overspeed_cycles``)
    is checked as one longer history: the overspeed result is the worst over all of them.
    ``threads``: each group's node blocks on that many threads (``assess_group``).
    ``rod_loads``: (force (n, 2), place on the pin m) per rod (``fe.pin_patches``): UR M53's
    moments rod by rod and, where the FE model has patch cases, each rod on its band; an
    overspeed cycle is then (pin force, torque, rod loads)."""
    coeffs = cycle_coefficients(unit, pin_force, torque, omega, sense=sense, rod_loads=rod_loads)
    coeffs_os = None
    if overspeed is not None:
        if overspeed_loads is None:
            scale = (overspeed / omega) ** 2 if omega > 0 else 1.0
            rods_os = None if rod_loads is None else tuple((scale * np.asarray(f, float), e) for f, e in rod_loads)
            overspeed_loads = (scale * np.asarray(pin_force, float), scale * np.asarray(torque, float), rods_os)
        cycles = overspeed_loads if isinstance(overspeed_loads, list) else [overspeed_loads]
        coeffs_os = np.vstack(
            [
                cycle_coefficients(unit, c[0], c[1], overspeed, sense=sense, rod_loads=c[2] if len(c) > 2 else None)
                for c in cycles
            ]
        )
        theta_os = np.tile(np.asarray(theta), len(cycles))  # the angle of the worst row, whichever cycle
    dp = m53_geometry.pin_diameter if m53_geometry is not None else None
    dj = m53_geometry.journal_diameter if m53_geometry is not None else None
    groups = tuple(
        assess_group(
            unit,
            g,
            coeffs,
            np.asarray(theta) if coeffs_os is None else theta_os,
            material,
            crank_radius=crank_radius,
            overspeed=overspeed,
            overspeed_coefficients=coeffs_os,
            diameter=section_diameter(g, dp, dj),
            threads=threads,
            additional_bending=m53_additional if g.startswith(SIGMA_ADD_GROUPS) else 0.0,
        )
        for g in sorted(unit.groups)
        if len(unit.groups[g])
    )
    fillets, nominal = (), None
    if m53_geometry is not None and material.tensile_strength is not None and material.m53_k is not None:
        scf_note = None
        if (
            fe_scf is None
            and scf is not None
            and any(m53.out_of_range(m53_geometry.related(f)) for f in ("pin", "journal"))
        ):
            result = scf()
            fe_scf, scf_note = fe_scfs(result), result.summary()
        m53_torque = torque
        if torque_rear is not None and m53.half_range(torque_rear) > m53.half_range(torque):
            m53_torque = torque_rear
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
                    f, scf_source=f"{scf_note}; outside the UR M53 validity range: " + "; ".join(f.out_of_range)
                )
                if f.out_of_range
                else f
                for f in fillets
            )
        outlet = m53_oil_bore.assess_outlet(
            m53_geometry, nominal, pin_force, tensile=material.tensile_strength, k=material.m53_k, rod_loads=rod_loads
        )
        fillets += (outlet,) if outlet is not None else ()
    cws = tuple(check_counterweight(c, omega, overspeed) for c in counterweights)
    return ThrowAssessment(name, groups, fillets, nominal, cws, int(len(theta)))


def _where(throw: str, ext) -> str:
    if ext is None:
        return ""
    p = ", ".join(f"{c * 1e3:.1f}" for c in ext.point)
    s = f"throw {throw}, {ext.group}, node {ext.node} at ({p}) mm"
    if ext.angle is not None:
        s += f", {math.degrees(ext.angle):.0f} deg"
    return s


def _pick(throws, getter, worst):
    """(value, location) of the worst non-None value of getter(throw, group) over all groups."""
    best = None
    for t in throws:
        for g in t.groups:
            got = getter(g)
            if got is None:
                continue
            value, ext = got
            if best is None or (value < best[0] if worst == "min" else value > best[0]):
                best = (value, _where(t.name, ext))
    return best


def evaluate_criteria(
    criteria, throws: tuple[ThrowAssessment, ...], *, file: str = "", overspeed: float | None = None
) -> tuple[CriterionResult, ...]:
    """Each limit of ``criteria`` -> a verdict.  A criterion that cannot be evaluated
    (no data for it) is an InputError naming its key: it never passes silently."""
    from fe_crank.io.criteria import QUANTITIES

    out = []
    for lim in criteria.limits:
        q = lim.quantity
        got = None
        unit = ""
        if q == "static_safety":
            got = _pick(throws, lambda g: (g.static_safety, g.max_von_mises), "min")
        elif q == "overspeed_safety":
            if overspeed is None:
                raise InputError("needs operating.overspeed", file=file, key=lim.key)
            got = _pick(throws, lambda g: (g.overspeed_safety, g.max_von_mises_overspeed), "min")
        elif q == "fatigue_safety":
            got = _pick(
                throws,
                lambda g: None if g.fatigue_safety is None else (g.fatigue_safety.value, g.fatigue_safety),
                "min",
            )
        elif q == "gough_pollard_safety":
            got = _pick(
                throws,
                lambda g: (
                    None if g.gough_pollard_safety is None else (g.gough_pollard_safety.value, g.gough_pollard_safety)
                ),
                "min",
            )
        elif q in ("counterweight_stress", "counterweight_overspeed_stress"):
            unit = "Pa"
            if q == "counterweight_overspeed_stress" and overspeed is None:
                raise InputError("needs operating.overspeed", file=file, key=lim.key)
            attr = "max_von_mises" if q == "counterweight_stress" else "max_von_mises_overspeed"
            got = _pick(
                throws,
                lambda g, attr=attr: (
                    (getattr(g, attr).value, getattr(g, attr)) if g.group.startswith(STATIC_ONLY_PREFIXES) else None
                ),
                "max",
            )
        elif q == "m53_acceptability":
            vals = [
                (f.acceptability, f"throw {t.name}, {m53_oil_bore.where(f.fillet)} ({f.scf_source})")
                for t in throws
                for f in t.m53
            ]
            got = min(vals) if vals else None
        elif q in ("unbalance_error", "bolt_utilisation"):
            attr = q
            vals = [
                (getattr(c, attr), f"throw {t.name}, {c.name}")
                for t in throws
                for c in t.counterweights
                if getattr(c, attr) is not None
            ]
            got = max(vals) if vals else None
        if got is None:
            raise InputError(
                f"cannot be evaluated: the model gives no {q.replace('_', ' ')} "
                "(missing geometry, mesh group, balance requirement or bolt data)",
                file=file,
                key=lim.key,
            )
        value, where = got
        out.append(
            judge(lim.key, q, lim.sense, value, lim.value, unit=unit, location=where, description=QUANTITIES[q].meaning)
        )
    return tuple(out)
