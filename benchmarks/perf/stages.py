"""The stages timed by ``benchmarks/perf/run.py``, each called in a process of its own so
that its peak resident memory (``ru_maxrss``) is its own.

* ``mesh``: the load case's first throw meshed at a preset without the cache (gmsh and
  the conversion to a quadratic scikit-fem mesh): size, quality, seconds;
* ``fe``: the FE stage as the check runs it (the load case's ``[fe]`` options, its
  symmetry, every unit case, the unit stresses at the assessed nodes): assembly,
  factorisation, solves, recovery, in wall seconds and CPU seconds;
* ``cycle``: the 720-degree cycle of the load case assessed by superposing the unit
  cases, against solving each crank angle directly (a few angles timed, the whole cycle
  extrapolated), and how far the superposition is from the direct solve of the same load
  (round-off) and from one cosine arc centred on the actual pin force (the load model's
  difference, docs/performance.md);
* ``fatigue``: the fatigue amplitude (minimum circumscribed ball) and the von Mises forms
  of the assessment on synthetic 720-angle paths shaped like the check's, and optionally
  the assessment of one group on 1 and on N threads.
"""

from __future__ import annotations

import dataclasses
import os
import resource
import time

import numpy as np


def peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def cpu_seconds() -> float:
    """User + system CPU seconds of this process, all threads."""
    t = os.times()
    return t.user + t.system


def _case(loadcase: str):
    from fe_crank.io.loadcase import load_loadcase

    return load_loadcase(loadcase)


def _fe_options(lc, solver: str, symmetry: bool):
    from fe_crank.fe import FeOptions

    base = lc.fe or FeOptions()
    return dataclasses.replace(base, solver=solver, symmetry=base.symmetry and symmetry)


def mesh(loadcase: str, preset: str) -> dict:
    from fe_crank.mesh import PRESETS, mesh_throw

    g = _case(loadcase).geometry
    t0 = time.perf_counter()
    tm = mesh_throw(g, size=preset, cache_dir=None)
    wall = time.perf_counter() - t0
    s = tm.stats
    return {
        "preset": preset,
        "fillet_divisions": PRESETS[preset].fillet_divisions,
        "nodes": s.nodes,
        "elements": s.elements,
        "p2_dofs": s.p2_dofs,
        "largest_fillet_edge_over_r": max(h / s.fillet_radii[k] for k, h in s.fillet_max_edge.items()),
        "min_quality": s.min_quality,
        "straightened": s.straightened,
        "seconds": wall,
        "peak_rss_mb": peak_rss_mb(),
    }


def warm(loadcase: str, preset: str, cache: str) -> dict:
    """Mesh into the cache, so that the stages after it read the mesh."""
    from fe_crank.mesh import mesh_throw

    tm = mesh_throw(_case(loadcase).geometry, size=preset, cache_dir=cache)
    return {"preset": preset, "from_cache": tm.stats.from_cache}


def fe(loadcase: str, preset: str, cache: str, solver: str, symmetry: bool) -> dict:
    from fe_crank.assess import assessed_groups
    from fe_crank.assess.superpose import unit_nodal_stress
    from fe_crank.fe import solve_unit_cases
    from fe_crank.mesh import mesh_throw

    lc = _case(loadcase)
    tm = mesh_throw(lc.geometry, size=preset, cache_dir=cache)
    c0 = cpu_seconds()
    units = solve_unit_cases(tm, lc.material, _fe_options(lc, solver, symmetry))
    ids = np.unique(np.concatenate(list(assessed_groups(units).values())))
    t0 = time.perf_counter()
    unit_nodal_stress(units, list(units.cases), ids)
    t_rec = time.perf_counter() - t0
    t = units.timings
    return {
        "preset": preset,
        "dof": int(units.n_dof),
        "elements": int(tm.mesh.t.shape[1]),
        "assessed_nodes": int(ids.size),
        "unit_cases": len(units.cases),
        "solver": units.solver_description,
        "assembly_s": t["assembly"] + t["constraints"],
        "factorisation_s": t["factorisation"],
        "solves_s": t["loads"] + t["solve"],
        "recovery_s": t_rec,
        "fe_total_s": t["total"] + t_rec,
        "fe_cpu_s": cpu_seconds() - c0,
        "max_equilibrium_error": float(max(c.equilibrium_error for c in units.cases.values())),
        "peak_rss_mb": peak_rss_mb(),
    }


def _unit_loads(units, density: float) -> dict[str, np.ndarray]:
    """The unit load vectors of the FE stage, rebuilt from its options (checked against
    the resultants the stage recorded)."""
    from fe_crank.fe.core.loads import centrifugal_load, face_torque_load, pin_pressure_load
    from fe_crank.fe.throw.pin_directions import unit_force

    basis, o = units.system.basis, units.options
    out = {}
    for name, case in units.cases.items():
        if name == "centrifugal":
            f = centrifugal_load(basis, density, 1.0)
        elif name == "torque":
            f = face_torque_load(basis, -1.0, boundary=o.torque_face)
        else:
            f = pin_pressure_load(basis, unit_force(name), boundary=o.pin_boundary, half_angle=o.pin_half_angle)[0]
        got = units.system.applied(f)[0]
        scale = max(np.abs(case.applied).max(), 1e-30)
        assert np.abs(got - case.applied).max() <= 1e-9 * scale, f"unit load {name} rebuilt differently"
        out[name] = f
    return out


def cycle(loadcase: str, preset: str, cache: str, solver: str, angles: int) -> dict:
    from fe_crank.assess import unit_stresses
    from fe_crank.assess.stress import von_mises
    from fe_crank.assess.superpose import load_coefficients, stress_history
    from fe_crank.assess.throw import ThrowContext, assess_throw
    from fe_crank.fe import solve_unit_cases
    from fe_crank.fe.core.loads import pin_pressure_load
    from fe_crank.mechanism.dynamics import analyse
    from fe_crank.mesh import mesh_throw

    lc = _case(loadcase)
    dyn = analyse(lc.engine, lc.operating)
    tm = mesh_throw(lc.geometry, size=preset, cache_dir=cache)
    tl = dyn.throws.get(tm.throw) or next(iter(dyn.throws.values()))
    units = solve_unit_cases(tm, lc.material, _fe_options(lc, solver, True))
    t = units.timings
    out = {"preset": preset, "dof": int(units.n_dof), "angles": int(dyn.theta.size)}
    out["fe_before_solves_s"] = t["assembly"] + t["constraints"] + t["factorisation"]
    out["unit_solves_s"] = t["loads"] + t["solve"]
    t0 = time.perf_counter()
    unit = unit_stresses(units)
    out["unit_stress_recovery_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    assess_throw(
        ThrowContext(
            tm.throw,
            unit,
            dyn.theta,
            tl.pin_force,
            tl.torque_front,
            omega=lc.operating.speed,
            overspeed=lc.operating.overspeed,
            material=lc.material,
            crank_radius=lc.geometry.crank_radius,
        )
    )
    out["superposition_and_assessment_s"] = time.perf_counter() - t0
    out["assessed_nodes"] = int(unit.n_nodes)
    coeffs = load_coefficients(
        tl.pin_force, tl.torque_front, lc.operating.speed, cases=unit.cases, torque_mz=unit.torque_mz
    )
    loads = _unit_loads(units, lc.material.density)
    unit_f = np.stack([loads[c] for c in unit.cases])
    other = [i for i, c in enumerate(unit.cases) if not c.startswith("pin")]
    fillets = np.concatenate([unit.groups[g] for g in unit.groups if "fillet" in g])
    sup = stress_history(unit, coeffs)
    direct_s, linear, one_arc = [], [], []
    for k in np.linspace(0, dyn.theta.size - 1, angles).astype(int):
        t0 = time.perf_counter()  # an angle solved directly: one arc on the pin force's resultant
        f = coeffs[k, other] @ unit_f[other] + pin_pressure_load(units.system.basis, tl.pin_force[k])[0]
        s = units.stress_at_nodes(units.system.solve(f))[:, unit.node_ids]
        direct_s.append(time.perf_counter() - t0)
        vm_arc, vm_sup = (von_mises(x[:, fillets][None])[0] for x in (s, sup[k]))
        one_arc.append(float(np.abs(vm_arc - vm_sup).max() / vm_arc.max()))
        s_lin = units.stress_at_nodes(units.system.solve(coeffs[k] @ unit_f))[:, unit.node_ids]
        linear.append(float(np.abs(s_lin - sup[k]).max() / np.abs(s_lin).max()))
    out["direct_per_angle_s"] = float(np.mean(direct_s))
    out["direct_whole_cycle_extrapolated_s"] = out["direct_per_angle_s"] * dyn.theta.size
    out["superposition_route_s"] = out["fe_before_solves_s"] + sum(
        out[k] for k in ("unit_solves_s", "unit_stress_recovery_s", "superposition_and_assessment_s")
    )
    out["direct_route_s"] = out["fe_before_solves_s"] + out["direct_whole_cycle_extrapolated_s"]
    out["superposition_vs_direct_same_load_max_rel"] = max(linear)
    out["superposition_vs_one_arc_fillet_von_mises_max_rel"] = max(one_arc)
    out["peak_rss_mb"] = peak_rss_mb()
    return out


def _paths(n: int, n_t: int = 720, seed: int = 1) -> np.ndarray:
    """(n_t, 6, n) stress paths of 14 unit cases combined with cycle coefficients
    (centrifugal, 12 half-wave pin weights, torque): most paths not proportional."""
    rng = np.random.default_rng(seed)
    th = np.linspace(0.0, 4 * np.pi, n_t, endpoint=False)
    coeff = np.column_stack(
        [np.full(n_t, 1e4)]
        + [np.maximum(0.0, np.cos(th * k / 2 + k)) * 1e4 for k in range(12)]
        + [1e3 * np.sin(3 * th)]
    )
    return np.tensordot(coeff, rng.normal(size=(14, 6, n)), axes=(1, 0))


def _best(fn, repeat: int) -> tuple[float, float, object]:
    """Best wall and best CPU seconds of ``repeat`` calls, and the last result."""
    wall, cpu, out = np.inf, np.inf, None
    for _ in range(repeat):
        w, c = time.perf_counter(), cpu_seconds()
        out = fn()
        wall, cpu = min(wall, time.perf_counter() - w), min(cpu, cpu_seconds() - c)
    return wall, cpu, out


def fatigue(nodes: int, repeat: int, threads: int) -> dict:
    from fe_crank.assess import fatigue as fat
    from fe_crank.assess.stress import von_mises, von_mises_path, von_mises_planes

    h = _paths(nodes)
    centre = 0.5 * (h.min(axis=0) + h.max(axis=0))
    planes = np.ascontiguousarray(h.transpose(1, 0, 2))  # (6, n_t, n), as the assessment holds them
    out: dict = {"nodes": nodes, "angles": h.shape[0]}
    _, out["amplitude_mean_cpu_s"], _ = _best(lambda: fat.amplitude_mean(h), repeat)
    _, out["von_mises_plain_cpu_s"], plain = _best(lambda: von_mises(h - centre[None]), repeat)
    _, out["von_mises_path_cpu_s"], path = _best(lambda: von_mises_path(h, centre), repeat)
    _, out["von_mises_planes_cpu_s"], pl = _best(lambda: von_mises_planes(planes, centre), repeat)
    out["von_mises_forms_identical"] = bool(np.array_equal(plain, path) and np.array_equal(plain, pl))
    if threads > 1:
        out["assess_group_threads"] = _group_on_threads(nodes, repeat, threads)
    out["peak_rss_mb"] = peak_rss_mb()
    return out


def _group_on_threads(n: int, repeat: int, threads: int) -> dict:
    """One group of ``n`` synthetic nodes assessed (superposition, static, both fatigue
    criteria, overspeed peak) on 1 and on ``threads`` threads (``assess.workers``)."""
    from fe_crank.assess import workers
    from fe_crank.assess.group.assessment import assess_group
    from fe_crank.assess.superpose import UnitStresses, load_coefficients
    from fe_crank.fe.throw.unit_cases import CASES
    from fe_crank.io.material import load_material

    rng = np.random.default_rng(2)
    a = np.linspace(0, 2 * np.pi, n)
    pts = np.vstack([0.03 * np.cos(a), 0.03 * np.sin(a), np.linspace(-0.01, 0.01, n)])
    us = UnitStresses(
        stress=rng.normal(size=(len(CASES), 6, n)) * 1e3,
        points=pts,
        groups={"journal_fillet_1": np.arange(n)},
        node_ids=np.arange(n),
        cases=CASES,
    )
    th = np.linspace(0.0, 4 * np.pi, 720, endpoint=False)
    pin = np.column_stack([3e3 * np.sin(th), 2e4 * np.cos(th) + 5e3])
    co = load_coefficients(pin, 400.0 * np.sin(2 * th) + 150.0, 293.0, cases=CASES, torque_mz=-1.0)
    mat = load_material("42CrMo4")

    def run(k):
        with workers.threads(k):
            return assess_group(
                us,
                "journal_fillet_1",
                co,
                th,
                mat,
                crank_radius=0.0,
                overspeed=330.0,
                overspeed_coefficients=1.3 * co,
            )

    w1, c1, one = _best(lambda: run(1), repeat)
    wn, cn, many = _best(lambda: run(threads), repeat)
    same = one == many and all(np.array_equal(one.fields[k], many.fields[k]) for k in one.fields)
    return {"threads": threads, "wall_1_s": w1, "wall_n_s": wn, "cpu_1_s": c1, "cpu_n_s": cn, "identical": bool(same)}
