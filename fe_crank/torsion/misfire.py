"""The torsional forced response with a misfiring cylinder: each cylinder motored in
turn, judged against the continuous-operation limits (``fe_crank.mechanism.misfire.READING``,
the tool's reading, docs/mechanism.md).

The misfiring cylinder's gas torque is that of its motored pressure (or zero gauge
pressure where the gas data give no motored curve, ``fe_crank.mechanism.misfire.motored_gas``);
its inertia torque and every other cylinder's torque are unchanged.  The dynamics stage
gives the cylinders' torques with the misfiring cylinder motored in every diagram of a
full-load curve (``EngineCycles.torques``, ``fe_crank.mechanism.torques``) and the whole
torsional stage is run again on them (``analyse_misfire``: each misfire case in turn).  A
misfire breaks the firing symmetry: orders that cancel with all cylinders firing (the
minor orders of an in-line engine) are excited, so a resonance that is harmless in
normal firing can govern.  ``MisfireTorsion.governing`` gives per segment the largest
``M_TN`` of all cases and speeds with the case and the speed; ``journal_torques``
hands over, per journal, the worst history of all cases (``handover``).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from fe_crank.mechanism.torques import CylinderTorques
from fe_crank.torsion.analysis import TorsionResult, analyse_torsion
from fe_crank.torsion.handover import JournalTorque
from fe_crank.torsion.handover import journal_torques as _journal_torques

FIRING = "all cylinders firing"


@dataclass(frozen=True)
class MisfireCase:
    cylinder: str
    gas: str  # the misfiring cylinder's pressure, in words
    result: TorsionResult


@dataclass(frozen=True)
class Governing:
    """The largest M_TN of a segment over the speed range and all cases."""

    segment: str
    m_tn: float  # N m
    speed: float  # rad/s
    case: str  # FIRING or "cylinder <name> misfiring"


@dataclass(frozen=True)
class MisfireTorsion:
    firing: TorsionResult
    cases: tuple[MisfireCase, ...]

    def all_cases(self) -> list[tuple[str, TorsionResult]]:
        return [(FIRING, self.firing)] + [(f"cylinder {c.cylinder} misfiring", c.result) for c in self.cases]

    def governing(self, segment: str) -> Governing:
        """Which case and speed give ``segment`` its largest M_TN over the range."""
        i = self.firing.model.segment_names.index(segment)
        best = None
        for label, res in self.all_cases():
            s = res.governing(i)
            m = float(res.half_range[s, i])
            if best is None or m > best.m_tn:
                best = Governing(segment, m, float(res.response.speeds[s]), label)
        assert best is not None  # the firing case is always there
        return best

    def journal_torques(self) -> dict[str, JournalTorque]:
        """Per segment the handed-over history (``handover.journal_torques``) of the case
        with the largest half range, labelled with its case."""
        found: dict[str, list[JournalTorque]] = {}
        for label, res in self.all_cases():
            for name, jt in _journal_torques(res).items():
                found.setdefault(name, []).append(dataclasses.replace(jt, case=label))
        return {
            name: dataclasses.replace(max(js, key=lambda j: j.half_range), max_m_tn=max(j.max_m_tn for j in js))
            for name, js in found.items()
        }


def analyse_misfire(loadcase, torques: tuple[CylinderTorques, ...], *, cylinders=None, **kwargs) -> MisfireTorsion:
    """The torsional stage with all cylinders firing and with each of ``cylinders``
    (default every misfire case of ``torques``) misfiring in turn, on the dynamics
    stage's cylinder torques ``torques`` (``EngineCycles.torques``: every cylinder firing
    and each misfire case); ``kwargs`` as ``analyse_torsion`` (``inertias``,
    ``fe_stiffness``, ``settings``)."""
    firing = next(t for t in torques if not t.misfire)
    by_cylinder = {t.misfire: t for t in torques if t.misfire}
    cylinders = tuple(by_cylinder) if cylinders is None else tuple(cylinders)
    missing = [c for c in cylinders if c not in by_cylinder]
    if missing:
        raise ValueError(f"the dynamics stage has no cycle with cylinder(s) {', '.join(missing)} misfiring")
    cases = tuple(
        MisfireCase(c, by_cylinder[c].gas, analyse_torsion(loadcase, by_cylinder[c], **kwargs)) for c in cylinders
    )
    return MisfireTorsion(analyse_torsion(loadcase, firing, **kwargs), cases)


__all__ = ["MisfireCase", "MisfireTorsion", "Governing", "analyse_misfire", "FIRING"]
