"""The computational stages of one load case, in the order they run.

Each stage is a plain call into its package: dynamics -> balance -> mesh (cached)
-> FE unit cases -> cycle assessment.
"""

from __future__ import annotations

import dataclasses
import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from fe_crank.assess import assess_case
from fe_crank.balance.analysis import analyse_balance
from fe_crank.check.options import CheckOptions, assess_threads
from fe_crank.errors import FeCrankError, InputError
from fe_crank.fe import convergence, solve_unit_cases
from fe_crank.io.loadcase import load_loadcase
from fe_crank.io.mesh import MeshSection
from fe_crank.mechanism.dynamics import analyse
from fe_crank.mesh import mesh_throw, resolve_options
from fe_crank.results import CriterionResult, StageTime
from fe_crank.throw_scope import ALL_THROWS
from fe_crank.torsion.stage import dynamics_for_assessment, torsion_stage

log = logging.getLogger(__name__)


@dataclass
class _Run:
    """Mutable state of one run (private; the result is frozen)."""

    path: Path
    timings: list = field(default_factory=list)
    stage: str = ""
    on_stage: Callable[[str, str], None] | None = None

    def timed(self, stage: str, fn: Callable, *args, **kwargs):
        self.stage = stage
        if self.on_stage is not None:
            self.on_stage(str(self.path), stage)
        t0 = time.perf_counter()
        ok = False
        try:
            out = fn(*args, **kwargs)
            ok = True
            return out
        finally:
            dt = time.perf_counter() - t0
            self.timings.append(StageTime(stage, dt))
            log.info("%s: %s %s in %.1f s", self.path.stem, stage, "done" if ok else "stopped", dt)


def _compute(run: _Run, options: CheckOptions, out: dict) -> dict:
    """Run the computational stages, filling ``out`` with each stage's output as it
    finishes (so that a report of a case that stopped shows what did run)."""
    lc = out["loadcase"] = run.timed("load", load_loadcase, run.path, allow_outside_paths=options.allow_outside_paths)
    out["dynamics"] = run.timed("dynamics", _dynamics_stage, lc)
    out["balance"] = run.timed("balance", _balance_stage, lc)
    out["meshes"] = run.timed("mesh", _mesh_stage, lc, options)
    out["units"] = run.timed("fe", _fe_stage, lc, out["meshes"])
    if "torsion" in lc.extras:  # torsional vibration (docs/torsion.md): only with a [torsion] section
        out["torsion"] = run.timed("torsion", torsion_stage, lc, out["units"])
    out["assessment"] = run.timed("assess", _assess_stage, lc, out, assess_threads(options))
    section = lc.extras.get("mesh") or MeshSection()
    flag = options.convergence if options.convergence is not None else section.convergence
    if convergence.wanted(flag, options.mesh_size or section.size):
        out["mesh_convergence"] = run.timed(
            "convergence",
            convergence.check_studies,
            lc,
            out["meshes"],
            out["dynamics"],
            cache_dir=options.cache_dir,
            units=out["units"],
        )
    return out


def _dynamics_stage(lc):
    """Forces and torques over the whole cycle at the operating speed."""
    res = analyse(lc.engine, lc.operating)
    refuse_non_finite_dynamics(res, lc.source_file)
    return res


def refuse_non_finite_dynamics(res, file) -> None:
    """Forces and torques over the cycle must be finite: a NaN or inf (an input at the
    edge of what the mechanism allows) is an error of the case, never a result."""
    import numpy as np

    arrays = {"torque": res.torque}
    arrays.update({f"throw {n} pin force": t.pin_force for n, t in res.throws.items()})
    for what, a in arrays.items():
        if not np.all(np.isfinite(a)):
            raise FeCrankError(f"{file}: the dynamics gave a non-finite {what} (NaN or inf); check the engine data")


def _assess_stage(lc, out, threads: int = 1):
    """Stresses, safety factors and the load case's criteria (journal torques with the
    vibratory torque when the torsional stage ran); node blocks on ``threads`` threads."""
    dyn = dynamics_for_assessment(out["dynamics"], out.get("torsion"))
    return assess_case(lc, dyn, out["balance"], out["meshes"], out["units"], threads=threads)


def _balance_stage(lc):
    """Free forces by order, counterweights sized by the ``[balance]`` strategy,
    balance shafts, residual (``fe_crank.balance.analysis.analyse_balance``)."""
    return analyse_balance(lc.engine, lc.operating.speed, lc.balance)


def throw_keys(lc) -> dict[str, str]:
    """Which geometry throw to mesh for each key handed to the assessment.

    A geometry with a single throw stands for every throw of the engine (key
    ``ALL_THROWS``, ``fe_crank.throw_scope``, which ``assess_case`` applies to each throw with its own loads);
    so do several throws that differ only in name and angle; otherwise the geometry's
    throw names must be the engine's throw names, so that no throw goes unchecked.
    """
    g = lc.geometry
    names = [t.name for t in g.throws]
    engine = [t.name for t in lc.engine.throws]
    if len(names) == 1:
        return {names[0] if engine == names else ALL_THROWS: names[0]}
    if sorted(names) != sorted(engine) and _all_equal(g.throws):
        # equal throws under other names (e.g. "1", "2" for the engine's "A", "B"):
        # one model stands for every throw, each assessed with its own loads
        return {ALL_THROWS: names[0]}
    if sorted(names) != sorted(engine):
        raise InputError(
            f"the geometry's throws {names} must be the engine's throws {engine} "
            "(or give one throw that stands for all)",
            file=lc.source_file,
            key="geometry",
        )
    return {n: n for n in engine}


def _all_equal(throws) -> bool:
    """Throws that differ only in name and angle give the same throw model."""
    import dataclasses

    norm = [dataclasses.replace(t, name="", angle=0.0) for t in throws]
    return all(n == norm[0] for n in norm)


def _mesh_stage(lc, options: CheckOptions):
    """Quadratic tetrahedral mesh of each throw (``fe_crank.mesh.mesh_throw``, cached
    by the hash of its inputs: equal throws are meshed once)."""
    if lc.geometry is None:
        raise InputError(
            'the stress check needs a crank geometry: add geometry = "../geometry/<file>.toml"',
            file=lc.source_file,
            key="geometry",
        )
    section = lc.extras.get("mesh") or MeshSection()
    kwargs = {
        "cache_dir": options.cache_dir,
        "size": options.mesh_size or section.size,
        "max_elements": options.max_elements or section.max_elements,
    }
    if not section.symmetric:  # [mesh] symmetric = false: mesh a symmetric throw whole (docs/geometry.md)
        kwargs["size"] = dataclasses.replace(resolve_options(kwargs["size"]), symmetric=False)
    return {key: mesh_throw(lc.geometry, throw=name, **kwargs) for key, name in throw_keys(lc).items()}


def _fe_stage(lc, meshes):
    """Unit load cases on one assembled stiffness per distinct throw mesh (throws
    with the same mesh key share one solution)."""
    if lc.material is None:
        raise InputError("the stress check needs a [material] section", file=lc.source_file, key="material")
    solved, out = {}, {}
    for key, m in meshes.items():
        mk = getattr(m, "key", None) or id(m)
        if mk not in solved:
            solved[mk] = solve_unit_cases(m, lc.material, lc.fe)
            # every unit case is solved: later stages combine displacements and never solve
            # again, so the factor (the largest allocation of the run) goes now
            solved[mk].system.factorisation.free()
        out[key] = solved[mk]
    return out


def _criteria_of(assessment) -> tuple[CriterionResult, ...]:
    """The assessment's criteria as ``CriterionResult`` (plain, picklable)."""
    out = []
    for c in getattr(assessment, "criteria", ()):
        out.append(
            CriterionResult(
                name=str(c.name),
                passed=bool(c.passed),
                value=float(c.value),
                limit=float(c.limit),
                margin=float(c.margin),
                description=str(getattr(c, "description", "")),
                location=str(getattr(c, "location", "")),
                unit=str(getattr(c, "unit", "")),
                quantity=str(getattr(c, "quantity", "")),
                sense=str(getattr(c, "sense", "")),
            )
        )
    return tuple(out)
