"""Running the check's own stages in a test, to hand their typed outputs to the
assessment, the report or a check of their own (no fakes: the stage functions of
``fe_crank.pipeline.stages``, the same calls ``fe-crank check`` makes)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from fe_crank.assess.case import AssessInputs
from fe_crank.assess.throw_geometry import parametric_throws
from fe_crank.geometry.mass import throw_solids
from fe_crank.io.loadcase import LoadCase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.mesh.plan import SIGN_OFF_RULE, mesh_plan
from fe_crank.outputs import CaseOutputs, FeModels, GeometryModel
from fe_crank.pipeline.notes import case_notes
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.stages import Run, run_stages
from fe_crank.pipeline.stages import assess_inputs as stage_assess_inputs
from fe_crank.pipeline.verdict import decide
from fe_crank.records import CaseResult
from fe_crank.report import write_case_report


def stage_outputs(path: str | Path, cache_dir: str | Path, *, mesh_size: str = "test", **options) -> CaseOutputs:
    """The outputs of every stage of one load case, as ``fe-crank check`` computes them
    (the hot-spot convergence study off unless asked for)."""
    options.setdefault("convergence", False)
    run = Run(Path(path), CheckOptions(mesh_size=mesh_size, cache_dir=str(cache_dir), **options))
    run_stages(run)
    return run.out


def write_report(folder: Path, out: CaseOutputs, options: CheckOptions | None = None) -> CaseResult:
    """The case report of ``out`` in ``folder`` as the check writes it; the record returned."""
    assert out.loadcase is not None
    verdict = decide(out)
    preset = out.geometry.plan.preset if out.geometry is not None else None
    sign_off = out.geometry.plan.sign_off if out.geometry is not None else False
    notes = case_notes(out, preset=preset, sign_off=sign_off, rule=SIGN_OFF_RULE, solver=None)
    res = CaseResult(
        out.loadcase.name, out.loadcase.source_file, verdict.status, verdict.message, criteria=verdict.criteria
    )
    folder.mkdir(parents=True, exist_ok=True)
    write_case_report(folder, res, out, notes, options=options or CheckOptions())
    return res


def assess_inputs(
    lc: LoadCase, unit_solutions: dict, *, models: dict | None = None, balance=None, **kw
) -> AssessInputs:
    """``AssessInputs`` of a load case for hand-picked FE unit solutions (key -> solution),
    by the check's own ``pipeline.stages.assess_inputs`` on the outputs of the stages they stand
    in for: the cycles by the dynamics stage's ``engine_cycles``, each throw's geometry (the
    counterweights' mass properties, the UR M53 dimensions) as the geometry stage gives it;
    ``kw``: fields of ``AssessInputs`` to set instead."""
    assert lc.material is not None and lc.criteria is not None
    cycles = engine_cycles(lc.engine, lc.operating)
    g = lc.geometry
    models = models or dict.fromkeys(unit_solutions, g.throws[0].name if g is not None else "")
    throw_geometry = kw.pop("throw_geometry", None)
    if throw_geometry is None:  # else the geometry stage's, as given
        names = tuple(t.name for t in g.throws if t.counterweights) if g is not None else ()
        solids = throw_solids(g, names) if g is not None and names else None
        design = balance.design if balance is not None else None
        throw_geometry = parametric_throws(g, models, lc.engine, solids, design) if g is not None else {}
    plan = mesh_plan(models, lc.mesh, size="test")
    out = CaseOutputs(
        loadcase=lc,
        cycles=cycles,
        balance=balance,
        geometry=GeometryModel(plan, throw_geometry),
        fe=FeModels(unit_solutions),
    )
    return dataclasses.replace(stage_assess_inputs(lc, out), **kw)
