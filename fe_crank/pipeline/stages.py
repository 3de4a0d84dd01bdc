"""The stages of one load case, in the order they run (``run_stages``).

load -> dynamics (operating and overspeed cycles) -> balance -> geometry (mesh plan, UR
M53 dimensions, CAD mass properties, the whole shaft placed) -> mesh (every model of the
plan, the whole shaft's too: ``cad.source.mesh_models``, cached) -> FE unit
cases -> SCF mode (only where UR M53's empirical SCFs are out of range) -> torsion (with
a ``[torsion]`` section) -> whole shaft (several throws on one shaft, or a ``[shaft]``
section: ``pipeline.shaft_stage``) -> hot-spot convergence study (sign-off meshes; both models'
load sets: ``convergence_stage``) -> assessment (both models, every speed, the study's factors:
``assess.case``) -> the whole
shaft's fields at its governing angle (for the report).  Each stage is a plain typed call
into its package, timed on its own; no stage computes what another owns, and each reads
only the outputs of the stages before it (``CaseOutputs``).
"""

from __future__ import annotations

import dataclasses
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeVar

from fe_crank.assess.case import Assessment, assess_case
from fe_crank.assess.inputs import AssessInputs
from fe_crank.assess.shaft import WholeShaftOutput
from fe_crank.assess.throw_geometry import parametric_throws
from fe_crank.assess.workers import threads
from fe_crank.balance.analysis import BalanceResult, analyse_balance
from fe_crank.cad.config import CadInput
from fe_crank.cad.source import GeometrySource, Meshes, mesh_models
from fe_crank.errors import InputError
from fe_crank.fe import solve_unit_cases
from fe_crank.fe.refinement import convergence
from fe_crank.fe.refinement.levels import ConvergenceStudy
from fe_crank.fe.shaft.refinement import shaft_load_sets
from fe_crank.fe.throw.options import FeOptions
from fe_crank.fe.throw.pin_patches import pin_patch_options
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.geometry.mass import throw_solids
from fe_crank.geometry.shaft import ShaftLayout, engine_shaft_layout, whole_shaft_wanted
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.base import InputFile
from fe_crank.io.loadcase import LoadCase, check_study_fillets, load_loadcase
from fe_crank.mechanism.cycles import EngineCycles, engine_cycles
from fe_crank.mesh.plan import plan_meshes
from fe_crank.mesh.types import ThrowMesh
from fe_crank.outputs import CaseOutputs, FeModels, GeometryModel
from fe_crank.pipeline import shaft_stage
from fe_crank.pipeline.cad_geometry import cad_geometry_stage
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.torsion_stage import torsion_stage
from fe_crank.results import StageTime
from fe_crank.rules.m53.calculation import scf_mode_needed
from fe_crank.rules.m53.scf_mode import ScfResult
from fe_crank.rules.m53.scf_refine import accepted_scf
from fe_crank.throw_scope import throws_of
from fe_crank.torsion.loads import assessed_loads

log = logging.getLogger(__name__)

T = TypeVar("T")


@dataclass
class Run:
    """The running state of one case (private to ``run_stages``; its outputs are frozen):
    the outputs so far, the stage timings, the stage running, the files read."""

    path: Path
    options: CheckOptions
    on_stage: Callable[[str, str], None] | None = None
    out: CaseOutputs = field(default_factory=CaseOutputs)
    timings: list[StageTime] = field(default_factory=list)
    stage: str = ""
    files_read: list[InputFile] = field(default_factory=list)

    def timed(self, stage: str, fn: Callable[..., T], *args: Any, **kwargs: Any) -> T:
        self.stage = stage
        if self.on_stage is not None:
            self.on_stage(str(self.path), stage)
        t0 = time.perf_counter()
        ok = False
        try:
            result = fn(*args, **kwargs)
            ok = True
            return result
        finally:
            dt = time.perf_counter() - t0
            self.timings.append(StageTime(stage, dt))
            log.info("%s: %s %s in %.1f s", self.path.stem, stage, "done" if ok else "stopped", dt)

    def keep(self, **outputs: Any) -> None:
        self.out = dataclasses.replace(self.out, **outputs)


def run_stages(run: Run) -> None:
    """Run the stages of ``run.path`` in order, keeping each stage's output in
    ``run.out`` as it finishes (so that a case that stops still reports what did run)."""
    opts = run.options
    lc = run.timed(
        "load", load_loadcase, run.path, allow_outside_paths=opts.allow_outside_paths, files_read=run.files_read
    )
    run.keep(loadcase=lc)
    run.keep(cycles=run.timed("dynamics", engine_cycles, lc.engine, lc.operating, file=lc.source_file))
    run.keep(balance=run.timed("balance", analyse_balance, lc.engine, lc.operating.speed, lc.balance))
    geo = run.timed("geometry", geometry_stage, lc, opts, run.out.balance)
    run.keep(geometry=geo)
    meshes = run.timed("mesh", mesh_stage, lc, geo)
    run.keep(meshes=meshes)
    unit_solutions = run.timed("fe", fe_stage, lc, geo, meshes.throws)
    run.keep(fe=FeModels(unit_solutions))
    if needs_scf(lc, geo):
        run.keep(fe=FeModels(unit_solutions, run.timed("scf", scf_stage, lc, geo, meshes.throws)))
    cycles = run.out.cycles
    assert cycles is not None
    if lc.torsion is not None:  # torsional vibration (docs/torsion.md): only with a [torsion] section
        run.keep(torsion=run.timed("torsion", torsion_stage, lc, geo, unit_solutions, cycles))
    study = convergence.wanted(
        opts.convergence if opts.convergence is not None else lc.mesh.convergence, geo.plan.preset
    )
    fields = opts.render or opts.write_vtu
    if geo.shaft is not None:  # the whole shaft on its bearings (docs/shaft.md); before the study, which reads it
        with threads(assess_threads_of(opts)):
            shaft = run.timed("whole_shaft", shaft_stage.whole_shaft_stage, lc, geo, meshes, run.out, fields or study)
        run.keep(whole_shaft=shaft)
    if study:
        ws = run.out.whole_shaft
        try:
            run.keep(
                convergence=run.timed("convergence", convergence_stage, lc, geo, meshes, unit_solutions, cycles, ws)
            )
        finally:
            if ws is not None and ws.cases is not None and not fields:
                ws.cases.model.free_factors()  # the study's piece fields read them; the report draws no field
    with threads(assess_threads_of(opts)):
        assessment = run.timed("assess", assess_stage, lc, run.out, fields)
    run.keep(assessment=assessment)
    ws = run.out.whole_shaft
    if ws is not None:
        hot_spot = assessment.shaft.governing if assessment.shaft is not None else None
        if fields and hot_spot is not None:
            with threads(assess_threads_of(opts)):
                picture = run.timed("shaft_fields", shaft_stage.shaft_fields_stage, lc, ws, hot_spot)
            run.keep(shaft_fields=picture)
        else:
            assert ws.cases is not None
            ws.cases.model.free_factors()
        # the shaft's unit cases are read: the record keeps its results, not its working
        # model (its unit cases and its mesh)
        run.keep(whole_shaft=dataclasses.replace(ws, cases=None), meshes=dataclasses.replace(meshes, shaft=None))


def convergence_stage(
    lc: LoadCase,
    geo: GeometryModel,
    meshes: Meshes,
    unit_solutions: dict[str, UnitSolutions],
    cycles: EngineCycles,
    ws: WholeShaftOutput | None,
) -> dict[str, ConvergenceStudy]:
    """The hot-spot convergence study of every throw mesh (``fe.refinement.convergence.check_studies``)
    under the per-throw model's load sets and, with the whole shaft (``ws``, the whole-shaft
    stage's output), the whole shaft's own (``fe.shaft.refinement.shaft_load_sets``: its
    states of the largest crankpin force and journal torque, read on the throw piece),
    solved in the same zones."""
    material = lc.material
    assert material is not None  # the fe stage ran
    driven = None
    if ws is not None and ws.cases is not None:
        driven = shaft_load_sets(ws.cases, ws.result.cycles[0].weights, ws.dynamics, material, lc.fe.solver)
    return convergence.check_studies(
        _require_geometry(lc),
        material,
        lc.fe,
        meshes.throws,
        cycles.operating,
        cache_dir=geo.plan.cache_dir,
        unit_solutions=unit_solutions,
        driven=driven,
    )


def assess_threads_of(options: CheckOptions) -> int:
    """The assess stage's threads: the options' (resolved by the batch), else every core."""
    from fe_crank.pipeline.options import assess_threads

    return assess_threads(options)


def _require_geometry(lc: LoadCase) -> GeometrySource:
    if lc.geometry is None:
        raise InputError(
            'the stress check needs a crank geometry: add geometry = "../geometry/<file>.toml"',
            file=lc.source_file,
            key="geometry",
        )
    return lc.geometry


def geometry_stage(lc: LoadCase, options: CheckOptions, balance: BalanceResult | None = None) -> GeometryModel:
    """The mesh plan (resolved once: preset, sizes, symmetry, which throw model for which
    engine throw) and each engine throw's geometry for the assessment (UR M53 dimensions,
    counterweights' built m r from the B-rep mass properties against ``balance``'s
    required m r); the mass properties of the throws whose inertias the torsional stage
    needs.  A CAD geometry: ``pipeline.cad_geometry`` (recognised here, once)."""
    g = _require_geometry(lc)
    if isinstance(g, CadInput):
        return cad_geometry_stage(lc, g, options, balance)
    plan = plan_meshes(
        g,
        tuple(t.name for t in lc.engine.throws),
        lc.mesh,
        size=options.mesh_size,
        max_elements=options.max_elements,
        cache_dir=options.cache_dir,
        file=lc.source_file,
        shaft=shaft_layout(lc),
    )
    # the study's finest level at the command line's size (validate: at the load case's)
    check_study_fillets(g, lc.mesh, plan.preset, options.convergence, lc.source_file)
    wanted = tuple(sorted({t.name for t in g.throws if t.counterweights}))
    if lc.torsion is not None:
        wanted = tuple(t.name for t in g.throws)
    solids = throw_solids(g, wanted) if wanted else None
    design = balance.design if balance is not None else None
    return GeometryModel(plan, parametric_throws(g, plan.throws, lc.engine, solids, design), solids)


def shaft_layout(lc: LoadCase) -> ShaftLayout | None:
    """The shaft of the load case placed by its engine (``geometry.shaft.engine_shaft_layout``;
    a geometry of one throw stands for every throw) when the whole shaft is modelled:
    several throws on one shaft, or a ``[shaft]`` section (``whole_shaft_wanted``), for a
    load case with a material and a parametric geometry (a CAD geometry's throws are meshed
    from the file one by one, on the journals' middles it recognises: the per-throw model
    alone, docs/shaft.md); None otherwise."""
    g = lc.geometry
    if lc.material is None or not isinstance(g, CrankGeometry) or not whole_shaft_wanted(g, lc.engine):
        return None
    return engine_shaft_layout(
        g, lc.engine, geometry_file=g.file or lc.source_file, engine_file=lc.engine_file or lc.source_file
    )


def mesh_stage(lc: LoadCase, geo: GeometryModel) -> Meshes:
    """Quadratic tetrahedral meshes of every model of the plan: each throw model and the
    whole shaft when the plan holds it (``cad.source.mesh_models``, the one entry point;
    cached by the hash of its inputs: equal throws are meshed once, for both models)."""
    return mesh_models(_require_geometry(lc), geo.plan, geo.cad)


def fe_options(lc: LoadCase) -> FeOptions:
    """The FE stage's options: the load case's, with the ``angular_acceleration`` unit case
    when the torsional stage runs (the throw's vibratory inertia torque as a body force,
    ``fe_crank.torsion.flow``)."""
    if lc.torsion is None or "angular_acceleration" in lc.fe.cases:
        return lc.fe
    return dataclasses.replace(lc.fe, cases=(*lc.fe.cases, "angular_acceleration"))


def fe_stage(lc: LoadCase, geo: GeometryModel, meshes: dict[str, ThrowMesh]) -> dict[str, UnitSolutions]:
    """Unit load cases on one assembled stiffness per distinct throw mesh (throws with the
    same mesh key share one solution); ``fe_options`` says which; with rods at more than
    one place on the pin of a throw the mesh stands for, one pressure patch per place
    (``fe.throw.pin_patches.pin_patch_options``, the pin length of the geometry stage)."""
    if lc.material is None:
        raise InputError("the stress check needs a [material] section", file=lc.source_file, key="material")
    options = fe_options(lc)
    solved: dict[str, UnitSolutions] = {}
    out = {}
    for key, m in meshes.items():
        if m.key not in solved:
            # each rod on its own band of the pin where rods bear at more than one place
            names = [t.name for t in lc.engine.throws]
            throws = [t for k, other in meshes.items() if other.key == m.key for t in throws_of(k, names)]
            tg = geo.of_model(key)
            opts = pin_patch_options(options, lc.engine, tg.crankpin_length if tg is not None else None, throws)
            solved[m.key] = solve_unit_cases(m, lc.material, opts)
            # every unit case is solved: later stages combine displacements and never solve
            # again, so the factor (the largest allocation of the run) goes now
            solved[m.key].system.factorisation.free()
        out[key] = solved[m.key]
    return out


def needs_scf(lc: LoadCase, geo: GeometryModel) -> bool:
    """Whether the SCF stage runs: UR M53's empirical SCFs out of range for a throw model of
    the plan (``rules.m53.calculation.scf_mode_needed``)."""
    return scf_mode_needed(lc.material, [geo.m53_of(key) for key in geo.plan.throws])


def scf_stage(lc: LoadCase, geo: GeometryModel, meshes: dict[str, ThrowMesh]) -> dict[str, ScfResult]:
    """The SCF mode's three FE load cases on each distinct throw mesh (re-meshed at r/4 in
    the fillets when the check's mesh is coarser, then refined until UR M53 App. III accepts
    the mesh, bounded: ``rules.m53.scf_refine.accepted_scf``), the nominal stresses at the
    webs' mid-planes of the geometry stage."""
    g = _require_geometry(lc)
    assert lc.material is not None
    done: dict[str, ScfResult] = {}
    out = {}
    for key, m in meshes.items():
        tg = geo.of_model(key)
        if tg is None or tg.m53 is None:
            continue
        if m.key not in done:
            done[m.key] = accepted_scf(m, g, lc.material, tg.m53, web_centres=tg.web_centres, solver=lc.fe.solver)
        out[key] = done[m.key]
    return out


def assess_inputs(lc: LoadCase, out: CaseOutputs) -> AssessInputs:
    """What the assessment reads (``assess.case.AssessInputs``), from the load case and the
    outputs of the stages before it: the cycles, the loads of every speed and load state
    (the torsional stage's, with its vibration, else the rigid shaft's torque flow), the
    balance, the mesh plan's models, the unit solutions and SCF results, each throw's
    geometry, the whole shaft's model and the convergence study when they ran.  A load case
    without a material or a limit is an ``InputError`` (checked here, once)."""
    if lc.material is None:
        raise InputError("the assessment needs a [material] section", file=lc.source_file, key="material")
    if lc.criteria is None or not lc.criteria.limits:
        raise InputError(
            "the assessment needs a [criteria] section with at least one limit", file=lc.source_file, key="criteria"
        )
    assert out.cycles is not None and out.geometry is not None and out.fe is not None
    loads = out.torsion.loads if out.torsion is not None else None
    if loads is None:  # rigid shaft: the torque flow of each speed and state for the power take-off end
        loads = assessed_loads(lc.engine, out.cycles, reaction=lc.fe.torque_reaction)
    return AssessInputs(
        case=lc.name,
        source_file=lc.source_file,
        engine=lc.engine,
        operating=lc.operating,
        material=lc.material,
        criteria=lc.criteria,
        cycles=out.cycles,
        dynamics=out.cycles.operating,
        loads=loads,
        balance=out.balance,
        models=out.geometry.plan.throws,
        unit_solutions=out.fe.unit_solutions,
        throw_geometry=out.geometry.throws,
        scf=out.fe.scf,
        geometry_file=str(lc.geometry.file) if lc.geometry is not None else "",
        shaft=out.whole_shaft,
        convergence=out.convergence or None,
    )


def assess_stage(lc: LoadCase, out: CaseOutputs, fields: bool) -> Assessment:
    """Stresses, safety factors and the load case's criteria, both models, every speed
    (``assess.case.assess_case``); ``fields``: also the whole-mesh stress of the states the
    report draws."""
    return assess_case(assess_inputs(lc, out), fields=fields)
