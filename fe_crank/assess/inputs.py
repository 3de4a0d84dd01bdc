"""``AssessInputs``: what the assessment of one load case (``assess.case.assess_case``)
reads, from the load case and the earlier stages (typed)."""

from __future__ import annotations

from dataclasses import dataclass, field

from fe_crank import model
from fe_crank.assess.loads import AssessedLoads
from fe_crank.assess.shaft import WholeShaftOutput
from fe_crank.assess.throw_geometry import ThrowGeometry
from fe_crank.balance.analysis import BalanceResult
from fe_crank.fe.refinement.levels import ConvergenceStudy
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.io.criteria import Criteria
from fe_crank.io.material import Material
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult
from fe_crank.rules.m53.scf_mode import ScfResult


@dataclass(frozen=True)
class AssessInputs:
    """Everything ``assess_case`` reads, from the load case and the earlier stages.

    ``dynamics``: the operating cycle the stresses follow (its journal torques carry the
    vibratory torque when the torsional stage ran); ``cycles``: the operating and
    overspeed cycles of the dynamics stage; ``loads``: what the assessment superposes at
    every speed and load state (``assess.loads``); ``models``: FE model key -> geometry throw
    name (the mesh plan); ``unit_solutions``: key -> unit solutions (keys sharing one
    mesh share one object); ``throw_geometry``: engine throw name -> its geometry (the
    geometry stage's; a throw without one, a model that is no throw of a crank geometry,
    has its rods at mid-pin, no UR M53 route and no counterweights); ``scf``: key -> the
    SCF mode's result, for the models whose UR M53 dimensions are outside the empirical range;
    ``geometry_file``: the file of the geometry ("" for none); ``shaft``: the whole-shaft
    stage's model (``pipeline.shaft_stage``), whose throws the assessment assesses as the
    per-throw model's, each criterion the worse of both models; ``convergence``: the
    hot-spot convergence study per model key (None: it did not run), whose factors the FE
    stress criteria are taken at (``assess.refinement``)."""

    case: str
    source_file: str
    engine: model.Engine
    operating: model.OperatingPoint
    material: Material
    criteria: Criteria
    cycles: EngineCycles
    dynamics: DynamicsResult
    loads: AssessedLoads
    balance: BalanceResult | None
    models: dict[str, str]
    unit_solutions: dict[str, UnitSolutions]
    throw_geometry: dict[str, ThrowGeometry] = field(default_factory=dict)
    scf: dict[str, ScfResult] = field(default_factory=dict)
    geometry_file: str = ""  # the geometry's file (named in the bolted joints' input errors)
    shaft: WholeShaftOutput | None = None  # the whole-shaft stage's model, when it ran
    convergence: dict[str, ConvergenceStudy] | None = None
