"""The stages of one load case, in the order they run (``run_stages``).

load -> dynamics (operating and overspeed cycles) -> balance -> geometry (mesh plan, UR
M53 dimensions, CAD mass properties) -> mesh (cached) -> FE unit cases -> SCF mode (only
where UR M53's empirical SCFs are out of range) -> torsion (with a ``[torsion]``
section) -> whole shaft (several throws on one shaft, or a ``[shaft]`` section:
``check.shaft_stage``) -> assessment -> hot-spot convergence study (sign-off meshes).  Each stage is a
plain typed call into its package, timed on its own; no stage computes what another
owns, and each reads only the outputs of the stages before it (``CaseOutputs``).
"""

from __future__ import annotations

import dataclasses
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TypeVar

from fe_crank.assess import m53
from fe_crank.assess.adapters import m53_geometry_of
from fe_crank.assess.case import AssessInputs, Assessment, assess_case
from fe_crank.assess.scf import ScfResult, compute_scf, scf_mesh, web_centres_of
from fe_crank.assess.workers import threads
from fe_crank.balance.analysis import analyse_balance
from fe_crank.check import shaft_stage
from fe_crank.check.options import CheckOptions
from fe_crank.errors import InputError
from fe_crank.fe import convergence, solve_unit_cases
from fe_crank.fe.unit_cases import UnitSolutions
from fe_crank.geometry.mass import throw_solids
from fe_crank.io.base import InputFile
from fe_crank.io.loadcase import LoadCase, load_loadcase
from fe_crank.mechanism.cycles import EngineCycles, engine_cycles
from fe_crank.mesh import mesh_throw
from fe_crank.mesh.plan import plan_meshes
from fe_crank.mesh.types import ThrowMesh
from fe_crank.outputs import CaseOutputs, FeModels, GeometryModel, TorsionOutput
from fe_crank.results import StageTime
from fe_crank.torsion.analysis import analyse_torsion, with_vibratory_torque
from fe_crank.torsion.build import throw_inertias
from fe_crank.torsion.stiffness import fe_throw_stiffness

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

    def timed(self, stage: str, fn: Callable[..., T], *args, **kwargs) -> T:
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

    def keep(self, **outputs) -> None:
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
    geo = run.timed("geometry", geometry_stage, lc, opts)
    run.keep(geometry=geo)
    meshes = run.timed("mesh", mesh_stage, lc, geo)
    run.keep(meshes=meshes)
    unit_solutions = run.timed("fe", fe_stage, lc, meshes)
    run.keep(fe=FeModels(unit_solutions))
    if needs_scf(lc, geo):
        run.keep(fe=FeModels(unit_solutions, run.timed("scf", scf_stage, lc, geo, meshes)))
    cycles = run.out.cycles
    assert cycles is not None
    if lc.torsion is not None:  # torsional vibration (docs/torsion.md): only with a [torsion] section
        run.keep(torsion=run.timed("torsion", torsion_stage, lc, geo, unit_solutions, cycles))
    if shaft_stage.wanted(lc):  # the whole shaft on its bearings (docs/shaft.md)
        with threads(assess_threads_of(opts)):
            shaft = run.timed(
                "whole_shaft", shaft_stage.whole_shaft_stage, lc, geo, run.out, opts.render or opts.write_vtu
            )
        run.keep(whole_shaft=shaft)
    with threads(assess_threads_of(opts)):
        assessment = run.timed("assess", assess_stage, lc, run.out, opts.render or opts.write_vtu)
    run.keep(assessment=assessment)
    if convergence.wanted(opts.convergence if opts.convergence is not None else lc.mesh.convergence, geo.plan.preset):
        run.keep(
            convergence=run.timed(
                "convergence",
                convergence.check_studies,
                lc.geometry,
                lc.material,
                lc.fe,
                meshes,
                cycles.operating,
                cache_dir=geo.plan.cache_dir,
                unit_solutions=unit_solutions,
            )
        )


def assess_threads_of(options: CheckOptions) -> int:
    """The assess stage's threads: the options' (resolved by the batch), else every core."""
    from fe_crank.check.options import assess_threads

    return assess_threads(options)


def _require_geometry(lc: LoadCase):
    if lc.geometry is None:
        raise InputError(
            'the stress check needs a crank geometry: add geometry = "../geometry/<file>.toml"',
            file=lc.source_file,
            key="geometry",
        )
    return lc.geometry


def geometry_stage(lc: LoadCase, options: CheckOptions) -> GeometryModel:
    """The mesh plan (resolved once: preset, sizes, symmetry, which throw model for which
    engine throw), the UR M53 dimensions, and the CAD mass properties of the throws
    whose counterweights (assessment) or inertias (torsion) are needed."""
    g = _require_geometry(lc)
    plan = plan_meshes(
        g,
        tuple(t.name for t in lc.engine.throws),
        lc.mesh,
        size=options.mesh_size,
        max_elements=options.max_elements,
        cache_dir=options.cache_dir,
        file=lc.source_file,
    )
    if shaft_stage.wanted(lc):  # the per-throw model meshes the whole shaft's throws (one cached mesh each)
        plan = dataclasses.replace(plan, options=shaft_stage.throw_mesh_options(lc, plan.options))
    wanted = tuple(sorted({t.name for t in g.throws if t.counterweights}))
    if lc.torsion is not None:
        wanted = tuple(t.name for t in g.throws)
    solids = throw_solids(g, wanted) if wanted else None
    return GeometryModel(plan, m53_geometry_of(g), solids)


def mesh_stage(lc: LoadCase, geo: GeometryModel) -> dict[str, ThrowMesh]:
    """Quadratic tetrahedral mesh of each throw model of the plan (``mesh_throw``, cached
    by the hash of its inputs: equal throws are meshed once)."""
    g = _require_geometry(lc)
    p = geo.plan
    return {
        key: mesh_throw(g, throw=name, size=p.options, cache_dir=p.cache_dir, max_elements=p.max_elements)
        for key, name in p.throws.items()
    }


def fe_stage(lc: LoadCase, meshes: dict[str, ThrowMesh]) -> dict[str, UnitSolutions]:
    """Unit load cases on one assembled stiffness per distinct throw mesh (throws with the
    same mesh key share one solution)."""
    if lc.material is None:
        raise InputError("the stress check needs a [material] section", file=lc.source_file, key="material")
    solved: dict[str, UnitSolutions] = {}
    out = {}
    fe = lc.fe
    if lc.torsion is not None and "angular_acceleration" not in fe.cases:  # the throws' vibratory inertia torque
        fe = dataclasses.replace(fe, cases=(*fe.cases, "angular_acceleration"))
    for key, m in meshes.items():
        if m.key not in solved:
            solved[m.key] = solve_unit_cases(m, lc.material, fe)
            # every unit case is solved: later stages combine displacements and never solve
            # again, so the factor (the largest allocation of the run) goes now
            solved[m.key].system.factorisation.free()
        out[key] = solved[m.key]
    return out


def needs_scf(lc: LoadCase, geo: GeometryModel) -> bool:
    """UR M53 route outside its empirical SCFs' validity range: the SCF mode of the FE
    appendix (App. III) gives the factors (``assess.scf``)."""
    mat, g = lc.material, geo.m53
    if g is None or mat is None or mat.tensile_strength is None or mat.m53_k is None:
        return False
    return any(m53.out_of_range(g.related(f)) for f in ("pin", "journal"))


def scf_stage(lc: LoadCase, geo: GeometryModel, meshes: dict[str, ThrowMesh]) -> dict[str, ScfResult]:
    """The SCF mode's three FE load cases on each distinct throw mesh (re-meshed at r/4 in
    the fillets when the check's mesh is coarser, ``assess.scf.scf_mesh``)."""
    g = _require_geometry(lc)
    assert lc.material is not None and geo.m53 is not None
    done: dict[str, ScfResult] = {}
    out = {}
    for key, m in meshes.items():
        if m.key not in done:
            done[m.key] = compute_scf(
                scf_mesh(m, g), lc.material, geo.m53, web_centres=web_centres_of(g), solver=lc.fe.solver
            )
        out[key] = done[m.key]
    return out


def torsion_stage(
    lc: LoadCase, geo: GeometryModel, unit_solutions: dict[str, UnitSolutions], cycles: EngineCycles
) -> TorsionOutput:
    """The torsional forced response (``torsion.analysis``) with the throws' inertias from
    the geometry stage's CAD mass properties; the FE throw stiffness is measured from the
    torque unit case when it is there (the report shows it beside Carter's; it is used
    when ``throw_stiffness = "fe"``)."""
    settings = lc.torsion
    assert settings is not None
    first = next(iter(unit_solutions.values()), None)
    k_fe = fe_throw_stiffness(first) if first is not None and "torque" in first.cases else None
    if settings.throw_stiffness == "fe" and k_fe is None:
        raise InputError(
            "throw_stiffness = 'fe' needs the FE torque unit case", file=lc.source_file, key="torsion.throw_stiffness"
        )
    result = analyse_torsion(lc, inertias=throw_inertias(lc, geo.solids), fe_stiffness=k_fe)
    return TorsionOutput(result, with_vibratory_torque(cycles.operating, result))


def assess_stage(lc: LoadCase, out: CaseOutputs, fields: bool) -> Assessment:
    """Stresses, safety factors and the load case's criteria; ``fields``: also the
    whole-mesh stress of the states the report draws."""
    if lc.material is None:
        raise InputError("the assessment needs a [material] section", file=lc.source_file, key="material")
    if lc.criteria is None or not lc.criteria.limits:
        raise InputError(
            "the assessment needs a [criteria] section with at least one limit", file=lc.source_file, key="criteria"
        )
    assert out.cycles is not None and out.geometry is not None and out.fe is not None
    dyn = out.assessed_dynamics
    assert dyn is not None
    inputs = AssessInputs(
        case=lc.name,
        source_file=lc.source_file,
        engine=lc.engine,
        operating=lc.operating,
        material=lc.material,
        criteria=lc.criteria,
        geometry=_require_geometry(lc),
        cycles=out.cycles,
        dynamics=dyn,
        balance=out.balance,
        models=out.geometry.plan.throws,
        unit_solutions=out.fe.unit_solutions,
        solids=out.geometry.solids,
        m53_geometry=out.geometry.m53,
        scf=out.fe.scf,
        torsion=out.torsion is not None,
        shaft=out.whole_shaft.assessment if out.whole_shaft is not None else None,
    )
    return assess_case(inputs, fields=fields)
