"""Hot-spot convergence study: the peak stress at the throw's hot spots as their elements are refined.

IACS UR M53 (FE appendix, element size): the fillet elements must resolve the stress
gradient; the rule of thumb r/4 is a minimum, not a proof.  A sign-off therefore meshes
the throw at successively finer fillet sizes -- element edge r/(n f) for the factors f of
``FACTORS`` (1, 1.5, 2: r/4, r/6, r/8 from the ``coarse`` preset's n = 4), the oil bore's
elements refined by the same factor (``bore_divisions`` n_b f: pi d / (2 n_b f) round its
circumference), the rest of the size field unchanged -- solves the same loads on each
mesh and compares the peak von Mises stress on the hot-spot surfaces (averaged nodal
stress, the value the assessment reads).  The first level is the check's own mesh (the
assessed one).  The study is "converged" when, for every load set, the finest level's peak
differs from the assessed mesh's by at most ``TOLERANCE`` (5 %),

    assessed change = |sigma_finest - sigma_assessed| / sigma_finest;

the change of each step, |sigma_k - sigma_(k-1)| / sigma_k, is reported beside it (a
monotone, roughly geometric sequence puts the remaining error of the finest level at
most about the last change).  The assessment takes the finest level's values (or their
Richardson extrapolation, ``estimate``) in place of the assessed mesh's
(``fe_crank.assess.refinement``).

``estimate``: sigma_est / sigma_assessed of one load set, sigma_est the finest level's
peak, or, where the three levels h_1 > h_2 > h_3 (h = r/n) give a monotone rising sequence
with shrinking steps, its Richardson extrapolation
sigma_3 + (sigma_3 - sigma_2) h_3^p / (h_2^p - h_3^p), the order p solved from
(sigma_2 - sigma_1)/(sigma_3 - sigma_2) = (h_1^p - h_2^p)/(h_2^p - h_3^p) in
[P_MIN, P_MAX] (``richardson``).

The counterweights' transition fillets (``counterweight_fillet_<web>`` surfaces, present
when the geometry states ``counterweight.fillet_radius``; the mesh grades them to
``r / fillet_divisions`` like the shaft fillets) are the counterweights' hot spot: their
peak is tracked as a load set of its own, named ``COUNTERWEIGHT_PREFIX + load set``, with
the same tolerance, so a counterweight stress that still moves with the mesh fails the
study as a shaft fillet does.  The oil-bore outlet (surface ``oil_bore``) likewise, named
``OIL_BORE_PREFIX + load set``.
"""

from __future__ import annotations

import dataclasses
import logging
import time

import numpy as np

from fe_crank.cad.config import CadInput
from fe_crank.fe.refinement.levels import (  # noqa: F401 (the study's types and constants, named here too)
    COUNTERWEIGHT_PREFIX,
    FACTORS,
    OIL_BORE_PREFIX,
    P_MAX,
    P_MIN,
    TOLERANCE,
    ConvergenceLevel,
    ConvergenceStudy,
    level_peaks,
)
from fe_crank.fe.refinement.loads import DEFAULT_LOADS, check_loads
from fe_crank.fe.throw.options import Material
from fe_crank.fe.throw.surface_peaks import (  # noqa: F401 (FILLETS, peak_fillet_stress: the study's measures, named here too)
    COUNTERWEIGHT_FILLETS,
    FILLETS,
    OIL_BORE,
    peak_fillet_stress,
    peak_fillet_stresses,
)
from fe_crank.fe.throw.unit_cases import FeOptions, UnitSolutions, solve_unit_cases
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mechanism.dynamics import DynamicsResult
from fe_crank.mesh.types import ThrowMesh

log = logging.getLogger(__name__)


def fillet_convergence(
    geometry,
    material,
    *,
    throw=None,
    base=None,
    factors=FACTORS,
    loads=None,
    fe_options: FeOptions | None = None,
    tolerance: float = TOLERANCE,
    cache_dir=None,
    first=None,
) -> ConvergenceStudy:
    """Mesh ``throw`` of ``geometry`` (parametric or a CAD file) at fillet sizes r/(n f) (and oil-bore divisions n_b f),
    f in ``factors``, and compare peaks.

    ``base``: the ``MeshOptions`` (or preset name) of the first level, n its
    ``fillet_divisions``; ``loads``: {load set: {unit case: weight}} (default
    ``DEFAULT_LOADS``); ``fe_options``: support model etc. of the check (only the unit
    cases the loads need are solved).  ``first``: (throw mesh, unit solutions) already
    solved, e.g. the check's own; a level whose mesh options equal that mesh's (same
    inputs, so the same mesh: the cache key) takes that solution instead of meshing and
    solving again, when it holds every unit case the loads need and was solved with the
    same support model.  Returns a :class:`ConvergenceStudy`.
    """
    from fe_crank.cad.source import mesh_source_throw
    from fe_crank.mesh import PRESETS, MeshOptions

    if len(factors) < 2:
        raise ValueError("a convergence study needs at least two levels")
    base = PRESETS[base or "coarse"] if not isinstance(base, MeshOptions) else base
    loads = {k: dict(v) for k, v in (loads or DEFAULT_LOADS).items()}
    needed = tuple(sorted({c for w in loads.values() for c in w}))
    opts = dataclasses.replace(fe_options or FeOptions(), cases=needed)
    levels = []
    for f in factors:
        t0 = time.perf_counter()
        mopt = dataclasses.replace(
            base, fillet_divisions=base.fillet_divisions * f, bore_divisions=base.bore_divisions * f
        )
        reuse = _reusable(first, mopt, opts)
        if reuse:
            tm, unit_solutions = first
        else:
            tm = mesh_source_throw(geometry, throw, size=mopt, cache_dir=cache_dir)
            unit_solutions = solve_unit_cases(tm, material, opts)
        fields = {name: unit_solutions.combine(w) for name, w in loads.items()}
        got = level_peaks(unit_solutions, fields)
        peaks = {name: v[0] for name, v in got.items()}
        where = {name: v[1] for name, v in got.items()}
        levels.append(
            ConvergenceLevel(
                fillet_divisions=mopt.fillet_divisions,
                n_dof=unit_solutions.n_dof,
                fillet_max_edge=dict(tm.stats.fillet_max_edge),
                peaks=peaks,
                where=where,
                seconds=time.perf_counter() - t0,
                reused=reuse,
                bore_divisions=mopt.bore_divisions,
            )
        )
        lv = levels[-1]
        log.info(
            "convergence level r/%g: %d DOF, %.1f s%s",
            lv.fillet_divisions,
            lv.n_dof,
            lv.seconds,
            " (the check's own mesh and solution)" if reuse else "",
        )
        if not reuse:
            unit_solutions.system.factorisation.free()
            del unit_solutions
    changes = {
        name: [abs(b.peaks[name] - a.peaks[name]) / b.peaks[name] for a, b in zip(levels, levels[1:])]
        for name in levels[0].peaks
    }
    return ConvergenceStudy(levels=tuple(levels), loads=loads, tolerance=tolerance, changes=changes)


def _reusable(first, mesh_options, fe_options: FeOptions) -> bool:
    """Can ``first`` = (throw mesh, unit solutions) stand for the level meshed with
    ``mesh_options`` and solved with ``fe_options``?  Same mesh options (the mesh is a
    function of the geometry, the throw and these, ``fe_crank.mesh``), the same support
    model and integration order, and every unit case needed."""
    if first is None:
        return False
    tm, unit_solutions = first
    if tm.options != mesh_options:
        return False
    done = unit_solutions.options
    same = all(
        getattr(done, k) == getattr(fe_options, k)
        for k in (
            "support",
            "bearing_stiffness",
            "torque_reaction",
            "journals",
            "pin_boundary",
            "pin_centre",
            "pin_half_angle",
            "intorder",
        )
    )
    return same and all(c in unit_solutions.cases for c in fe_options.cases)


def wanted(flag: bool | None, preset: str) -> bool:
    """Run the study?  An explicit flag wins; by default for every preset but ``test``."""
    return bool(flag) if flag is not None else preset != "test"


def check_studies(
    geometry: CrankGeometry | CadInput,
    material: Material,
    fe_options: FeOptions,
    meshes: dict[str, ThrowMesh],
    dynamics: DynamicsResult,
    *,
    cache_dir=None,
    unit_solutions: dict[str, UnitSolutions] | None = None,
    method: str = "zones",
    driven: dict[str, dict[str, tuple[np.ndarray, dict[str, float]]]] | None = None,
) -> dict[str, ConvergenceStudy]:
    """The check stage's study for each distinct throw mesh (``meshes``: key -> ThrowMesh).

    Loads from ``check_loads`` (the throws the key stands for: the engine throw of that
    name, else all of them) at the speed of ``dynamics``; the first level uses the
    check's own mesh options, and with ``unit_solutions`` (key -> the check's
    ``UnitSolutions``) the check's own solution on that mesh (one mesh and one
    factorisation fewer).  ``method``: "zones" (``fe.refinement.zone_study``: only the hot spots
    re-meshed, driven by the check's solution; where ``zones_apply``), else "full" (the
    whole throw re-meshed and re-solved per level, ``fillet_convergence``).  ``driven``:
    another model's load sets of a throw mesh, by its ``ThrowMesh.key`` (the whole shaft's,
    ``fe.shaft.refinement.shaft_load_sets``), solved in the same zones as the check's own
    (``zone_convergence``); the full method studies the check's own load sets only.
    """
    out: dict[str, ConvergenceStudy] = {}
    done: dict[str, ConvergenceStudy] = {}
    for other in sorted(set(driven or {}) - {tm.key for tm in meshes.values()}):
        log.info(
            "the other model's load sets of the throw mesh %s: no throw model of that mesh to study them on", other
        )
    for key, tm in meshes.items():
        if tm.key in done:
            out[key] = done[tm.key]
            continue
        tls = [dynamics.throws[key]] if key in dynamics.throws else list(dynamics.throws.values())
        first = (tm, unit_solutions[key]) if unit_solutions and key in unit_solutions else None
        loads = check_loads(tls, dynamics.speed)
        if method == "zones" and zones_apply(geometry, first, loads, fe_options):
            from fe_crank.fe.refinement.zone_study import zone_convergence

            assert first is not None
            out[key] = done[tm.key] = zone_convergence(
                geometry, material, first[0], first[1], loads, driven=(driven or {}).get(tm.key)
            )
            continue
        if driven and tm.key in driven:
            log.info("the whole throw re-meshed per level: the other model's load sets of %s are not studied", key)
        study = fillet_convergence(
            geometry,
            material,
            throw=tm.throw,
            base=tm.options,
            loads=loads,
            fe_options=fe_options,
            cache_dir=cache_dir,
            first=first,
        )
        out[key] = done[tm.key] = study
    return out


def zones_apply(geometry, first, loads: dict[str, dict[str, float]], fe_options: FeOptions) -> bool:
    """Can the zone study run?  A parametric or a drawn geometry (the zones are cut from its
    throw's solid, ``fe.refinement.zone_study.zone_solid``), and the check's own solution
    holding every unit case of ``loads`` on the whole pin."""
    if not isinstance(geometry, CrankGeometry | CadInput) or first is None:
        return False
    needed = tuple(sorted({c for w in loads.values() for c in w}))
    return _reusable(first, first[0].options, dataclasses.replace(fe_options, cases=needed))


def richardson(h, s) -> tuple[float, float] | None:
    """(extrapolated value, order p) of three levels h_1 > h_2 > h_3 with peaks s; None when
    the sequence is not monotone with shrinking steps or p falls outside [P_MIN, P_MAX]."""
    if len(s) != 3 or len(h) != 3:
        return None
    d1, d2 = s[1] - s[0], s[2] - s[1]
    if d1 == 0 or d2 == 0 or (d1 > 0) != (d2 > 0) or abs(d2) >= abs(d1):
        return None
    target = d1 / d2

    def f(p):
        return (h[0] ** p - h[1] ** p) / (h[1] ** p - h[2] ** p) - target

    lo, hi = P_MIN, P_MAX
    if f(lo) * f(hi) > 0:
        return None
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    p = 0.5 * (lo + hi)
    return s[2] + d2 * h[2] ** p / (h[1] ** p - h[2] ** p), p


def estimate(study: ConvergenceStudy, name: str) -> tuple[float, str]:
    """(sigma_est / sigma_assessed, the estimate in words) of load set ``name`` (module doc):
    the Richardson extrapolation of a rising sequence where it exists, else the finest level."""
    lv = study.levels
    s = [x.peaks[name] for x in lv]
    h = [1.0 / x.fillet_divisions for x in lv]
    sizes = ", ".join(f"r/{x.fillet_divisions:g}" for x in lv)
    ext = richardson(h, s) if s[-1] > s[0] else None
    if ext is not None:
        return ext[0] / s[0], f"Richardson extrapolation of {sizes}, order {ext[1]:.2f}"
    return s[-1] / s[0], f"finest level r/{lv[-1].fillet_divisions:g} of {sizes}"
