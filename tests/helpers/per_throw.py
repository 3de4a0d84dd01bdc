"""The check's stages of one load case without the whole shaft: for a test whose
assertions read the per-throw model's results alone (the bolted joints, for one: the
whole shaft's throws carry no joints, ``assess.shaft.assess_shaft_throws``, so its
criteria are the per-throw model's with or without it).

The stage functions of ``fe_crank.pipeline.stages`` in ``run_stages``' order, with the
plan the geometry stage makes (with the whole shaft, its mesh options are the shaft's,
``mesh.plan.mesh_plan``: the throws are meshed as ``fe-crank check`` meshes them) and
the whole shaft then left out of the plan: neither meshed, solved nor assessed."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from fe_crank.balance.analysis import analyse_balance
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.outputs import CaseOutputs, FeModels
from fe_crank.pipeline.options import CheckOptions
from fe_crank.pipeline.stages import assess_stage, fe_stage, geometry_stage, mesh_stage, needs_scf, scf_stage
from fe_crank.pipeline.torsion_stage import torsion_stage


def per_throw_outputs(path: str | Path, cache_dir: str | Path, *, mesh_size: str = "test") -> CaseOutputs:
    """The outputs of the check's stages of one load case at ``mesh_size`` (no hot-spot
    convergence study, no fields drawn) but the whole shaft's (module doc)."""
    opts = CheckOptions(mesh_size=mesh_size, cache_dir=str(cache_dir), convergence=False, render=False, write_vtu=False)
    lc = load_loadcase(Path(path))
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    balance = analyse_balance(lc.engine, lc.operating.speed, lc.balance)
    geo = geometry_stage(lc, opts, balance)
    geo = dataclasses.replace(geo, plan=dataclasses.replace(geo.plan, shaft=None))
    meshes = mesh_stage(lc, geo)
    units = fe_stage(lc, geo, meshes.throws)
    fe = FeModels(units, scf_stage(lc, geo, meshes.throws)) if needs_scf(lc, geo) else FeModels(units)
    out = CaseOutputs(loadcase=lc, cycles=cycles, balance=balance, geometry=geo, meshes=meshes, fe=fe)
    if lc.torsion is not None:
        out = dataclasses.replace(out, torsion=torsion_stage(lc, geo, units, cycles))
    return dataclasses.replace(out, assessment=assess_stage(lc, out, False))
