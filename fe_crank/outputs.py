"""What the stages of one load case produce, one typed field per stage (``CaseOutputs``).

The stages run in order (``fe_crank.pipeline.stages``); each takes the frozen outputs of
the stages before it and returns its own frozen result, which ``CaseOutputs`` collects.
``WholeShaftOutput`` and ``ShaftHotSpot`` are the assessment's types (``assess.shaft``),
named here too.
A case that stops keeps the outputs of the stages that ran, so its report shows them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from fe_crank.assess.case import Assessment
from fe_crank.assess.loads import AssessedLoads
from fe_crank.assess.shaft import ShaftHotSpot, WholeShaftOutput
from fe_crank.assess.throw_geometry import ThrowGeometry
from fe_crank.balance.analysis import BalanceResult
from fe_crank.cad.features import CadFeatures
from fe_crank.cad.source import Meshes
from fe_crank.fe.refinement.convergence import ConvergenceStudy
from fe_crank.fe.shaft.fields import ShaftFields
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.geometry.mass import ThrowSolids
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.io.loadcase import LoadCase
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult
from fe_crank.mesh.plan import MeshPlan
from fe_crank.rules.m53.calculation import M53Geometry
from fe_crank.rules.m53.scf_mode import ScfResult
from fe_crank.throw_scope import throws_of
from fe_crank.torsion.analysis import TorsionResult
from fe_crank.torsion.misfire import MisfireTorsion


@dataclass(frozen=True)
class GeometryModel:
    """The geometry stage: the mesh plan (which throw model stands for which engine
    throw, meshed how), each engine throw's geometry as the assessment reads it (UR M53
    dimensions, counterweights, rods' places, ``assess.throw_geometry``), the B-rep mass
    properties of the parametric throws whose inertias the torsional stage needs (None:
    none needed) and for a CAD geometry everything recognised in the file."""

    plan: MeshPlan
    throws: dict[str, ThrowGeometry]
    solids: ThrowSolids | None = None
    cad: CadFeatures | None = None

    @property
    def shaft(self) -> ShaftLayout | None:
        """The whole shaft placed by the engine when it is modelled too (the plan's; None:
        the per-throw model alone, ``pipeline.stages.shaft_layout``)."""
        return self.plan.shaft

    def of_model(self, key: str) -> ThrowGeometry | None:
        """The geometry of the throw model ``key`` (of the plan): that of the first
        engine throw it stands for (the throws a model stands for share its geometry)."""
        names = throws_of(key, self.throws)
        return self.throws[names[0]] if names else None

    def m53_of(self, key: str) -> M53Geometry | None:
        """The UR M53 dimensions of the throw model ``key``."""
        tg = self.of_model(key)
        return tg.m53 if tg is not None else None


@dataclass(frozen=True)
class FeModels:
    """The FE stage: unit solutions per model key (keys sharing one mesh share one
    solution), and the UR M53 SCF mode's result per key where the empirical SCFs are
    out of range."""

    unit_solutions: dict[str, UnitSolutions]
    scf: dict[str, ScfResult] = field(default_factory=dict)


@dataclass(frozen=True)
class TorsionOutput:
    """The torsional stage: its result with every cylinder firing, the operating cycle
    whose journal torques are UR M53's hand-over (the largest half range over the speed
    range and every case, ``torsion.handover``), the misfire cases (None without), and
    the loads of every speed of the sweep with their vibration (what the assessment
    superposes, ``torsion.loads``)."""

    result: TorsionResult
    dynamics: DynamicsResult
    misfire: MisfireTorsion | None = None
    loads: AssessedLoads | None = None


@dataclass(frozen=True)
class CaseOutputs:
    """The outputs of one load case's stages (None: the stage did not run)."""

    loadcase: LoadCase | None = None
    cycles: EngineCycles | None = None
    balance: BalanceResult | None = None
    geometry: GeometryModel | None = None
    meshes: Meshes | None = None
    fe: FeModels | None = None
    torsion: TorsionOutput | None = None
    whole_shaft: WholeShaftOutput | None = None
    convergence: dict[str, ConvergenceStudy] | None = None
    assessment: Assessment | None = None
    shaft_fields: ShaftFields | None = None  # the whole mesh's state at the whole shaft's governing angle

    @property
    def assessed_dynamics(self) -> DynamicsResult | None:
        """The operating cycle the assessment used: with the vibratory journal torque
        when the torsional stage ran."""
        if self.torsion is not None:
            return self.torsion.dynamics
        return self.cycles.operating if self.cycles is not None else None

    @property
    def unit_solutions(self) -> dict[str, UnitSolutions]:
        return self.fe.unit_solutions if self.fe is not None else {}


__all__ = [
    "CaseOutputs",
    "FeModels",
    "GeometryModel",
    "ShaftHotSpot",
    "TorsionOutput",
    "WholeShaftOutput",
]
