"""fe-crank against CalculiX on the same mesh and model: wall time, peak memory, answers.

    .venv/bin/python benchmarks/calculix_compare.py --preset test
    .venv/bin/python benchmarks/calculix_compare.py --loadcase loadcases/single_cylinder_seed001.toml \
        --preset coarse --json bench.json

For one unit case (``pin_y``) and for all unit cases of the FE stage, each code runs in a
process of its own (peak memory = that process's maximum resident set, from wait4):

* fe-crank: ``solve_unit_cases`` (assembly, one factorisation, every case) and the unit
  stresses at the assessed nodes (``unit_nodal_stress``) -- what the check computes
  before superposing the cycle;
* CalculiX (``ccx``): the same C3D10 mesh, material, supports and nodal loads written by
  ``ccx_deck.write_deck``, one *STEP per case, displacements and nodal stresses written
  at the assessed nodes only.

CalculiX comes from the OS package manager: if ``ccx`` is not on PATH the script runs
``apt-get update`` and ``apt-get install -y calculix-ccx`` (Debian/Ubuntu, as root) and
says so; elsewhere install CalculiX 2.20 yourself and put ``ccx`` on PATH.
Wall time and CPU time (user + system of all threads; less sensitive to other jobs on a
shared machine) are reported for both.  Both codes get the same threads (``--threads``, default 2: OMP_NUM_THREADS, MKL's and
CCX_NPROC_EQUATION_SOLVER).  The answers are compared at the assessed nodes: largest
displacement difference relative to the largest displacement, and largest von Mises
difference relative to the largest von Mises (CalculiX extrapolates its 4 integration
points to the nodes, fe-crank evaluates the P2 field there: they differ by the
discretisation, most at the fillets).
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
        print("CalculiX (ccx) not found: installing the OS package calculix-ccx "
              "(apt-get update; apt-get install -y calculix-ccx)", flush=True)
        env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
        subprocess.run(["apt-get", "update", "-qq"], check=True, env=env)
        subprocess.run(["apt-get", "install", "-y", "-qq", "calculix-ccx"], check=True, env=env)
        found = shutil.which("ccx")
    if not found:
        raise SystemExit("CalculiX (ccx) is not installed and could not be installed here: install CalculiX 2.20 "
                         "(Debian/Ubuntu: apt-get install calculix-ccx) and put ccx on PATH")
    return found


def _threads_env(n: int) -> dict:
    return dict(os.environ, OMP_NUM_THREADS=str(n), MKL_NUM_THREADS=str(n), CCX_NPROC_EQUATION_SOLVER=str(n),
                OPENBLAS_NUM_THREADS="1")


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


def unit_loads(units) -> dict[str, np.ndarray]:
    """The load vectors of the solved unit cases, rebuilt as the FE stage builds them and
    checked against its solutions (a mismatch stops the benchmark)."""
    from fe_crank.fe.loads import centrifugal_load, face_torque_load, pin_pressure_load, pin_surface
    from fe_crank.fe.pin_directions import unit_force

    basis, opt = units.system.basis, units.options
    surf, loads = None, {}
    for name in units.cases:
        if name == "centrifugal":
            loads[name] = centrifugal_load(basis, units.material.density, 1.0)
        elif name == "torque":
            loads[name] = face_torque_load(basis, -1.0, boundary=opt.torque_face)
        else:
            surf = surf or pin_surface(basis, opt.pin_boundary, opt.pin_centre)
            loads[name] = pin_pressure_load(basis, unit_force(name), half_angle=opt.pin_half_angle, surface=surf)[0]
    loads = _with_determinate_reactions(units, loads)
    for name, f in loads.items():
        u = units.system.solve(f)
        ref = units.cases[name].displacement
        if np.abs(u - ref).max() > 1e-8 * np.abs(ref).max():
            raise SystemExit(f"benchmark: the rebuilt load of {name} is not the one the FE stage solved")
    return loads


def _with_determinate_reactions(units, loads: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """With the statically determinate support model the FE stage's ``System.solve`` adds
    to each load its distributed reactions (``System.determinate``), held by six point
    constraints only: CalculiX gets the same self-equilibrated nodal loads."""
    sup = getattr(units.system, "determinate", None)
    if sup is None:
        return loads
    return {name: sup.self_equilibrated(f)[0] for name, f in loads.items()}


def worker(args) -> int:
    """fe-crank side in its own process; writes <work>/fe_<which>.npz (and the decks)."""
    from fe_crank.assess import assessed_groups
    from fe_crank.assess.superpose import unit_nodal_stress
    from fe_crank.fe import FeOptions, solve_unit_cases
    from fe_crank.fe.unit_cases import CASES
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw

    work = Path(args.work)
    lc = load_loadcase(args.loadcase)
    tm = mesh_throw(lc.geometry, size=args.preset, cache_dir=".cache/meshes")
    cases = ONE if args.worker == "one" else CASES
    base = lc.fe or FeOptions()
    opts = FeOptions(**{**base.__dict__, "cases": cases})
    t0, c0 = time.perf_counter(), _cpu(resource.getrusage(resource.RUSAGE_SELF))
    units = solve_unit_cases(tm.mesh, lc.material, opts)
    t_solve = time.perf_counter() - t0
    ids = np.unique(np.concatenate(list(assessed_groups(units).values())))
    t1 = time.perf_counter()
    S = unit_nodal_stress(units, cases, ids)
    t_rec = time.perf_counter() - t1
    cpu = _cpu(resource.getrusage(resource.RUSAGE_SELF)) - c0
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    U = np.stack([units.displacement(c).reshape(-1, 3)[ids] for c in cases])
    info = {"dof": int(units.n_dof), "elements": int(tm.mesh.t.shape[1]), "nodes": int(units.points.shape[1]),
            "assessed_nodes": int(ids.size), "solver": units.solver_description, "fe_s": t_solve,
            "recovery_s": t_rec, "fe_total_s": t_solve + t_rec, "fe_cpu_s": cpu, "peak_gb": peak,
            "timings": {k: float(v) for k, v in units.timings.items()}}
    np.savez(work / f"fe_{args.worker}.npz", ids=ids, U=U, S=S, cases=np.array(cases))
    (work / f"fe_{args.worker}.json").write_text(json.dumps(info))
    from ccx_deck import write_deck

    write_deck(work / f"ccx_{args.worker}.inp", units, unit_loads(units), ids)
    return 0


def compare(work: Path, which: str, ccx: str, threads: int) -> dict:
    from ccx_deck import read_dat_displacements, read_frd_stresses
    from fe_crank.fe.stress import von_mises

    wall, peak, rc, cpu = run_measured([ccx, "-i", f"ccx_{which}"], work, _threads_env(threads))
    if rc != 0:
        raise SystemExit(f"ccx failed on {work / f'ccx_{which}.inp'} (exit {rc}); see {work}")
    fe = np.load(work / f"fe_{which}.npz")
    info = json.loads((work / f"fe_{which}.json").read_text())
    disp = read_dat_displacements(work / f"ccx_{which}.dat")
    strs = read_frd_stresses(work / f"ccx_{which}.frd")
    ids = fe["ids"]
    du = dv = 0.0
    for k in range(len(fe["cases"])):
        uc = np.array([disp[k][i + 1] for i in ids])
        du = max(du, np.abs(uc - fe["U"][k]).max() / np.abs(fe["U"][k]).max())
        sc = np.array([strs[k][i + 1] for i in ids]).T
        vf, vc = von_mises(fe["S"][k]), von_mises(sc)
        dv = max(dv, np.abs(vc - vf).max() / vf.max())
    return {"cases": len(fe["cases"]), "fe_crank": info, "ccx": {"wall_s": wall, "cpu_s": cpu, "peak_gb": peak},
            "ratio_time": wall / info["fe_total_s"], "ratio_cpu": cpu / info["fe_cpu_s"],
            "ratio_memory": peak / info["peak_gb"],
            "max_rel_displacement_difference": du, "max_rel_von_mises_difference": dv}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loadcase", default="loadcases/single_cylinder_seed001.toml")
    ap.add_argument("--preset", default="test")
    ap.add_argument("--work", default=None, help="folder for decks and results (default .cache/ccx_<preset>)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--json", default=None, help="append the result to this file")
    ap.add_argument("--worker", choices=("one", "all"), help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    args.work = args.work or f".cache/ccx_{args.preset}"
    if args.worker:
        return worker(args)
    ccx = ensure_ccx()
    work = Path(args.work)
    work.mkdir(parents=True, exist_ok=True)
    # mesh once (cached) so that neither side's time includes meshing
    subprocess.run([sys.executable, "-c", "from fe_crank.io.loadcase import load_loadcase;"
                    "from fe_crank.mesh import mesh_throw;"
                    f"mesh_throw(load_loadcase({args.loadcase!r}).geometry, size={args.preset!r}, "
                    "cache_dir='.cache/meshes')"], check=True)
    result = {"loadcase": args.loadcase, "preset": args.preset, "threads": args.threads,
              "load_average": os.getloadavg()}
    for which in ("one", "all"):
        wall, peak, rc, _ = run_measured([sys.executable, __file__, "--worker", which, "--loadcase", args.loadcase,
                                       "--preset", args.preset, "--work", str(work)], None, _threads_env(args.threads),
                                       quiet=False)
        if rc != 0:
            raise SystemExit(f"fe-crank worker failed ({which})")
        r = compare(work, which, ccx, args.threads)
        r["fe_crank"]["process_wall_s"] = wall
        result[which] = r
        f = r["fe_crank"]
        print(f"{which:>3} ({r['cases']:2d} cases, {f['dof']} dof): fe-crank {f['fe_total_s']:7.1f} s "
              f"{f['peak_gb']:5.2f} GB | CalculiX {r['ccx']['wall_s']:7.1f} s {r['ccx']['peak_gb']:5.2f} GB | "
              f"time ratio {r['ratio_time']:5.1f} (CPU {r['ratio_cpu']:5.1f}) | memory ratio {r['ratio_memory']:4.2f} | "
              f"max du {r['max_rel_displacement_difference']:.1e}, max dvM {r['max_rel_von_mises_difference']:.1e}",
              flush=True)
    result["load_average_after"] = os.getloadavg()
    if args.json:
        with open(args.json, "a") as fh:
            fh.write(json.dumps(result) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
