"""The torsional forced response with a misfiring cylinder (IACS UR M53 2.2.2: the
vibratory torque is to be considered with misfiring).

The misfiring cylinder's gas torque is that of its motored pressure (or zero gauge
pressure where the gas data give no motored curve, ``fe_crank.mechanism.misfire.motored_gas``);
its inertia torque and every other cylinder's torque are unchanged.  The harmonics are
computed with the misfiring cylinder motored (``misfire_harmonics``, with every diagram
of a full-load curve) and the whole torsional stage is run again on them (``analyse_misfire``: each named cylinder in turn).  A
misfire breaks the firing symmetry: orders that cancel with all cylinders firing (the
minor orders of an in-line engine) are excited, so a resonance that is harmless in
normal firing can govern.  ``MisfireTorsion.governing`` gives per segment the largest
``M_TN`` of all cases and speeds with the case and the speed; ``journal_torques``
hands over, per journal, the worst history of all cases (``handover``).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from fe_crank import model
from fe_crank.mechanism.misfire import motored_gas
from fe_crank.torsion.analysis import TorsionResult, analyse_torsion
from fe_crank.torsion.excitation import CylinderHarmonics, cylinder_harmonics
from fe_crank.torsion.handover import JournalTorque
from fe_crank.torsion.handover import journal_torques as _journal_torques

FIRING = "all cylinders firing"


def misfire_harmonics(
    engine: model.Engine,
    speed: float,
    cylinder: str,
    *,
    step: float = np.radians(1.0),
    full_load: model.FullLoadCurve | None = None,
) -> tuple[CylinderHarmonics, str]:
    """The cylinders' harmonics at reference ``speed`` with ``cylinder`` motored (its
    motored curve of each diagram, or zero gauge pressure; ``fe_crank.mechanism.misfire``), and
    the misfiring cylinder's pressure in words."""
    h = cylinder_harmonics(
        engine, speed, step=step, full_load=full_load, cylinder_gas={cylinder: lambda d: motored_gas(d)[0]}
    )
    return h, motored_gas(engine.gas)[1]


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


def analyse_misfire(loadcase, *, cylinders=None, step: float = np.radians(1.0), **kwargs) -> MisfireTorsion:
    """The torsional stage with all cylinders firing and with each of ``cylinders``
    (default the load case's ``[operating] misfire``) misfiring in turn; ``kwargs`` as
    ``analyse_torsion`` (``inertias``, ``fe_stiffness``, ``settings``)."""
    cylinders = loadcase.operating.misfire if cylinders is None else tuple(cylinders)
    firing = analyse_torsion(loadcase, step=step, **kwargs)
    op = loadcase.operating
    cases = []
    for c in cylinders:
        h, words = misfire_harmonics(loadcase.engine, op.speed, c, step=step, full_load=op.full_load)
        cases.append(MisfireCase(c, words, analyse_torsion(loadcase, step=step, harmonics=h, **kwargs)))
    return MisfireTorsion(firing, tuple(cases))


__all__ = ["MisfireCase", "MisfireTorsion", "Governing", "analyse_misfire", "misfire_harmonics", "FIRING"]
