"""fe-crank against CalculiX on the same mesh and model: wall time, peak memory, answers.

    .venv/bin/python benchmarks/verification/calculix_compare.py --preset test
    .venv/bin/python benchmarks/verification/calculix_compare.py --preset medium --sets one all --ccx-sets one --json bench.json

For one unit case (``pin_y``, set ``one``) and for all unit cases of the FE stage (set
``all``), each code runs in a process of its own (peak memory = that process's maximum
resident set, from wait4):

* fe-crank: ``solve_unit_cases`` of the throw mesh (assembly, one factorisation, every
  case; on the mesh's symmetry components when it is mirrored, as the check solves it)
  and the unit stresses at the assessed nodes (``unit_nodal_stress``) -- what the check
  computes before superposing the cycle;
* CalculiX (``ccx``): the same C3D10 mesh, material, supports and nodal loads written by
  ``ccx_deck.write_deck``, one *STEP per case, displacements and nodal stresses written
  at the assessed nodes only.

``--sets`` chooses the sets fe-crank runs, ``--ccx-sets`` those CalculiX runs among them
(CalculiX factorises once per step: at 1M DOF its 14 steps take hours, so ``--ccx-sets
one`` there); the JSON record names both.

CalculiX comes from the OS package manager: if ``ccx`` is not on PATH the script runs
``apt-get update`` and ``apt-get install -y calculix-ccx`` (Debian/Ubuntu, as root) and
says so; elsewhere install CalculiX 2.20 yourself and put ``ccx`` on PATH.
Wall time and CPU time (user + system of all threads; less sensitive to other jobs on a
shared machine) are reported for both.  Both codes get the same threads (``--threads``,
default 2: OMP_NUM_THREADS, MKL's and CCX_NPROC_EQUATION_SOLVER).

Answers, at the assessed nodes: the largest displacement difference relative to the
largest displacement; the largest von Mises difference relative to the largest, over all
nodes and per assessed group (``ccx_groups``: relative to the group's largest and
locally, with the node's place -- mirror plane, point constraint, group edge, curved
elements); with every unit case, the static peak over the cycle and the Goodman safety
of each group computed by the check's own ``assess_group`` from each code's unit
stresses, at the node the check reports.  CalculiX's nodal recovery reproduced on
fe-crank's displacements (``ccx_recovery``) is compared with CalculiX's own, to show
that the stress difference is the recovery (CalculiX extrapolates its 4 integration
points linearly to the corners; fe-crank evaluates the P2 field at the node; the two
agree wherever every element at the node is straight-sided).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

ONE = ("pin_y",)


def ensure_ccx() -> str:
    """Path of ccx; installs the Debian package when it is missing and apt-get is there."""
    found = shutil.which("ccx")
    if found:
        print(f"CalculiX: {found}", flush=True)
        return found
    if shutil.which("apt-get") and os.geteuid() == 0:
        print(
            "CalculiX (ccx) not found: installing the OS package calculix-ccx "
            "(apt-get update; apt-get install -y calculix-ccx)",
            flush=True,
        )
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        subprocess.run(["apt-get", "update", "-qq"], check=True, env=env)
        subprocess.run(["apt-get", "install", "-y", "-qq", "calculix-ccx"], check=True, env=env)
        found = shutil.which("ccx")
    if not found:
        raise SystemExit(
            "CalculiX (ccx) is not installed and could not be installed here: install CalculiX 2.20 "
            "(Debian/Ubuntu: apt-get install calculix-ccx) and put ccx on PATH"
        )
    return found


def _threads_env(n: int) -> dict:
    return dict(
        os.environ,
        OMP_NUM_THREADS=str(n),
        MKL_NUM_THREADS=str(n),
        CCX_NPROC_EQUATION_SOLVER=str(n),
        OPENBLAS_NUM_THREADS="1",
    )


def _cpu(ru) -> float:
    return ru.ru_utime + ru.ru_stime


def run_measured(cmd, cwd, env, *, quiet=True) -> tuple[float, float, int, float]:
    """(wall s, peak RSS GB, exit code, CPU s of all its threads) of one child process."""
    t0 = time.perf_counter()
    log = open(Path(cwd or ".") / "last_run.log", "w") if quiet else None
    p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=log or None, stderr=subprocess.STDOUT if quiet else None)
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    p.returncode = os.waitstatus_to_exitcode(status)
    return wall, ru.ru_maxrss / 1024**2, p.returncode, _cpu(ru)


def worker(args) -> int:
    """fe-crank side in its own process; writes <work>/fe_<which>.npz (and the decks)."""
    from fe_crank.assess import assessed_groups
    from fe_crank.assess.superpose import unit_nodal_stress
    from fe_crank.fe import FeOptions, solve_unit_cases
    from fe_crank.fe.throw.unit_cases import CASES
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw

    work = Path(args.work)
    lc = load_loadcase(args.loadcase)
    tm = mesh_throw(lc.geometry, size=args.preset, cache_dir=".cache/meshes")
    cases = ONE if args.worker == "one" else CASES
    base = lc.fe or FeOptions()
    opts = FeOptions(**{**base.__dict__, "cases": cases})
    t0, c0 = time.perf_counter(), _cpu(resource.getrusage(resource.RUSAGE_SELF))
    units = solve_unit_cases(tm, lc.material, opts)  # with the mesh's symmetry, as the check
    t_solve = time.perf_counter() - t0
    ids = np.unique(np.concatenate(list(assessed_groups(units).values())))
    t1 = time.perf_counter()
    S = unit_nodal_stress(units, cases, ids)
    t_rec = time.perf_counter() - t1
    cpu = _cpu(resource.getrusage(resource.RUSAGE_SELF)) - c0
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    U = np.stack([units.displacement(c).reshape(-1, 3)[ids] for c in cases])
    info = {
        "dof": int(units.n_dof),
        "elements": int(tm.mesh.t.shape[1]),
        "nodes": int(units.points.shape[1]),
        "assessed_nodes": int(ids.size),
        "solver": units.solver_description,
        "fe_s": t_solve,
        "recovery_s": t_rec,
        "fe_total_s": t_solve + t_rec,
        "fe_cpu_s": cpu,
        "peak_gb": peak,
        "timings": {k: float(v) for k, v in units.timings.items()},
    }
    # where the two codes may differ (after the measurement: not in fe-crank's time or peak)
    from ccx_recovery import calculix_nodal_stress, edge_nodes, places

    groups = assessed_groups(units)
    flags = places(units, ids, getattr(tm, "symmetry", None) or ())
    flags["edge"] = np.isin(ids, np.concatenate([edge_nodes(units, g) for g in groups]))
    SX = calculix_nodal_stress(units, [units.displacement(c) for c in cases], ids)
    info["groups"] = {g: np.searchsorted(ids, n).tolist() for g, n in groups.items()}
    info["mirror_axes"] = list(getattr(tm, "symmetry", None) or ())
    info["torque_mz"] = float(units.cases["torque"].applied[5]) if "torque" in units.cases else -1.0
    if args.worker == "all":
        info["check"] = check_peaks(lc, tm, units)
    from ccx_deck import plane_nodes, unit_loads, write_deck

    # the deck's nodes are fe-crank's: one node where the mirrored halves meet
    info["deck_nodes"] = plane_nodes(units.system.basis.element_dofs, units.points, info["mirror_axes"])
    np.savez(
        work / f"fe_{args.worker}.npz",
        ids=ids,
        U=U,
        S=S,
        SX=SX,
        cases=np.array(cases),
        points=np.asarray(units.points)[:, ids],
        **flags,
    )
    (work / f"fe_{args.worker}.json").write_text(json.dumps(info))
    write_deck(work / f"ccx_{args.worker}.inp", units, unit_loads(units), ids)
    return 0


def check_peaks(lc, tm, units) -> dict:
    """The check's own assessment (``assess_case``) of this model: per throw and group, the
    node and value of the static peak it reports (the reference the comparison uses)."""
    from fe_crank.assess import AssessInputs, assess_case
    from fe_crank.assess.throw_geometry import parametric_throws
    from fe_crank.balance.analysis import analyse_balance
    from fe_crank.geometry.mass import throw_solids
    from fe_crank.mechanism.cycles import engine_cycles
    from fe_crank.mesh.plan import throw_keys
    from fe_crank.torsion.loads import assessed_loads

    keys = throw_keys(lc.geometry, tuple(t.name for t in lc.engine.throws))
    if len(keys) != 1:  # the benchmark meshes one throw
        return {}
    key, name = next(iter(keys.items()))
    cycles = engine_cycles(lc.engine, lc.operating)
    balance = analyse_balance(lc.engine, lc.operating.speed, lc.balance)
    cws = tuple(t.name for t in lc.geometry.throws if t.counterweights)
    a = assess_case(
        AssessInputs(
            case=lc.name,
            source_file=lc.source_file,
            engine=lc.engine,
            operating=lc.operating,
            material=lc.material,
            criteria=lc.criteria,
            cycles=cycles,
            dynamics=cycles.operating,
            loads=assessed_loads(lc.engine, cycles, reaction=lc.fe.torque_reaction),
            balance=analyse_balance(lc.engine, lc.operating.speed, lc.balance),
            models={key: name},
            unit_solutions={key: units},
            throw_geometry=parametric_throws(
                lc.geometry,
                {key: name},
                lc.engine,
                throw_solids(lc.geometry, cws) if cws else None,
                balance.design if balance is not None else None,
            ),
        )
    )
    return {
        t.name: {
            g.group: {
                "node": g.max_von_mises.node,
                "static": g.max_von_mises.value,
                "goodman": None if g.fatigue_safety is None else g.fatigue_safety.value,
            }
            for g in t.groups
        }
        for t in a.throws
    }


def compare(work: Path, which: str, ccx: str | None, threads: int, loadcase: str) -> dict:
    """CalculiX on the deck of ``which`` (None: fe-crank's figures only) and the answers
    compared: globally, per assessed group and, with every unit case, over the cycle
    (``ccx_groups``)."""
    from ccx_deck import read_dat_displacements, read_frd_stresses
    from ccx_groups import PLACE_FLAGS, cycle_table, unit_case_table, von_mises_cases

    from fe_crank.assess.superpose import UnitStresses

    fe = np.load(work / f"fe_{which}.npz")
    info = json.loads((work / f"fe_{which}.json").read_text())
    groups = {g: np.asarray(p) for g, p in info.pop("groups").items()}
    out = {"cases": len(fe["cases"]), "fe_crank": info, "ccx_run": ccx is not None}
    if ccx is None:
        return out
    wall, peak, rc, cpu = run_measured([ccx, "-i", f"ccx_{which}"], work, _threads_env(threads))
    if rc != 0:
        raise SystemExit(f"ccx failed on {work / f'ccx_{which}.inp'} (exit {rc}); see {work}")
    disp, strs = read_dat_displacements(work / f"ccx_{which}.dat"), read_frd_stresses(work / f"ccx_{which}.frd")
    ids, cases = fe["ids"], [str(c) for c in fe["cases"]]
    U = np.stack([np.array([disp[k][i + 1] for i in ids]) for k in range(len(cases))])
    C = np.stack([np.array([strs[k][i + 1] for i in ids]).T for k in range(len(cases))])
    du = max(np.abs(U[k] - fe["U"][k]).max() / np.abs(fe["U"][k]).max() for k in range(len(cases)))
    vf, vc, vx = von_mises_cases(fe["S"]), von_mises_cases(C), von_mises_cases(fe["SX"])
    top = vf.max(axis=1, keepdims=True)
    straight = fe["curvature"] <= 1e-9
    flags = {f: fe[f] for f in PLACE_FLAGS + ("curvature",)}
    out.update(
        {
            "ccx": {"wall_s": wall, "cpu_s": cpu, "peak_gb": peak},
            "ratio_time": wall / info["fe_total_s"],
            "ratio_cpu": cpu / info["fe_cpu_s"],
            "ratio_memory": peak / info["peak_gb"],
            "max_rel_displacement_difference": du,
            "max_rel_von_mises_difference": float((np.abs(vc - vf) / top).max()),
            # the whole difference is the recovery: CalculiX's, reproduced on fe-crank's u, is CalculiX's
            "max_rel_von_mises_ccx_vs_ccx_recovery_of_fe_u": float((np.abs(vc - vx) / top).max()),
            "max_rel_von_mises_difference_straight_element_nodes": float((np.abs(vc - vf) / top)[:, straight].max())
            if straight.any()
            else None,
            "nodes_with_curved_elements": int((~straight).sum()),
            "groups": unit_case_table(vf, vc, groups, flags, cases),
        }
    )
    if which == "all":
        unit = UnitStresses(
            stress=fe["S"],
            points=fe["points"],
            groups=groups,
            node_ids=ids,
            cases=tuple(cases),
            torque_mz=info["torque_mz"],
        )
        cyc = cycle_table(
            loadcase, unit, {"fe-crank": fe["S"], "CalculiX": C, "CalculiX recovery of fe-crank u": fe["SX"]}, flags
        )
        for t, rows in info.get("check", {}).items():  # the same peaks the check reports
            for g, r in rows.items():
                mine = cyc[t][g]
                if mine["node"] != r["node"] or abs(mine["static"]["fe-crank"]["peak"] / r["static"] - 1) > 1e-9:
                    raise SystemExit(f"benchmark: group {g} of throw {t}: not the check's peak")
        out["cycle"] = cyc
    return out


SETS = ("one", "all")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loadcase", default="loadcases/single_cylinder.toml")
    ap.add_argument("--preset", default="test")
    ap.add_argument("--work", default=None, help="folder for decks and results (default .cache/ccx_<preset>)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--json", default=None, help="append the result to this file")
    ap.add_argument(
        "--sets",
        nargs="+",
        choices=SETS,
        default=list(SETS),
        help="case sets fe-crank runs: one (pin_y) and/or all (every unit case); default both",
    )
    ap.add_argument(
        "--ccx-sets",
        nargs="*",
        choices=SETS,
        default=None,
        help="case sets CalculiX runs, among --sets (default: the same; none: fe-crank only)",
    )
    ap.add_argument("--worker", choices=SETS, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    args.work = args.work or f".cache/ccx_{args.preset}"
    if args.worker:
        return worker(args)
    import ccx_groups

    sets = [s for s in SETS if s in args.sets]
    ccx_sets = sets if args.ccx_sets is None else [s for s in SETS if s in args.ccx_sets]
    if not set(ccx_sets) <= set(sets):
        ap.error(
            f"--ccx-sets {' '.join(ccx_sets)}: CalculiX runs the decks fe-crank writes, so only sets of "
            f"--sets ({' '.join(sets)})"
        )
    ccx = ensure_ccx() if ccx_sets else None
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    # mesh once (cached) so that neither side's time includes meshing
    subprocess.run(
        [
            sys.executable,
            "-c",
            "from fe_crank.io.loadcase import load_loadcase;"
            "from fe_crank.mesh import mesh_throw;"
            f"mesh_throw(load_loadcase({args.loadcase!r}).geometry, size={args.preset!r}, "
            "cache_dir='.cache/meshes')",
        ],
        check=True,
    )
    result = {
        "loadcase": args.loadcase,
        "preset": args.preset,
        "threads": args.threads,
        "sets": sets,
        "ccx_sets": ccx_sets,
        "load_average": os.getloadavg(),
    }
    for which in sets:
        wall, peak, rc, _ = run_measured(
            [
                sys.executable,
                __file__,
                "--worker",
                which,
                "--loadcase",
                args.loadcase,
                "--preset",
                args.preset,
                "--work",
                str(work),
            ],
            None,
            _threads_env(args.threads),
            quiet=False,
        )
        if rc != 0:
            raise SystemExit(f"fe-crank worker failed ({which})")
        r = compare(work, which, ccx if which in ccx_sets else None, args.threads, args.loadcase)
        r["fe_crank"]["process_wall_s"] = wall
        result[which] = r
        f = r["fe_crank"]
        line = f"{which:>3} ({r['cases']:2d} cases, {f['dof']} dof): fe-crank {f['fe_total_s']:7.1f} s {f['peak_gb']:5.2f} GB"
        if r["ccx_run"]:
            line += (
                f" | CalculiX {r['ccx']['wall_s']:7.1f} s {r['ccx']['peak_gb']:5.2f} GB | time ratio "
                f"{r['ratio_time']:5.1f} (CPU {r['ratio_cpu']:5.1f}) | memory ratio {r['ratio_memory']:4.2f} | "
                f"max du {r['max_rel_displacement_difference']:.1e}, max dvM {r['max_rel_von_mises_difference']:.1e}"
                f" (CalculiX vs its recovery of fe-crank's u {r['max_rel_von_mises_ccx_vs_ccx_recovery_of_fe_u']:.1e})"
            )
        else:
            line += " | CalculiX not run (--ccx-sets)"
        print(line, flush=True)
        ccx_groups.print_groups(r)
    result["load_average_after"] = os.getloadavg()
    if args.json:
        with open(args.json, "a") as fh:
            fh.write(json.dumps(result, default=_plain) + "\n")
    return 0


def _plain(o):
    """numpy scalars and arrays in the JSON record."""
    return o.tolist() if hasattr(o, "tolist") else str(o)


if __name__ == "__main__":
    raise SystemExit(main())
