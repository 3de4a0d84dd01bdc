"""How the FE stage's cost grows with the mesh: time and memory vs DOF, fitted exponents.

    .venv/bin/python benchmarks/scaling.py --levels 0 1 2              # small sizes
    .venv/bin/python benchmarks/scaling.py --levels 0 1 2 3 4 --plot docs/img/scaling.png

Each level is a mesh of the load case's throw (``LEVELS``: from the ``test`` preset to
``medium`` and ``fine``, fillet and bulk divisions refined together), meshed first in a
process of its own (cached), then solved in another so that the peak memory (ru_maxrss)
is the FE stage's: ``solve_unit_cases`` with all unit cases and the unit stresses at the
assessed nodes (``unit_nodal_stress``).  Stages: assembly (stiffness and supports),
factorisation, solves (all cases), recovery.  The exponent b of t = a n^b is the
least-squares slope of log t against log n over the levels run (n = DOF solved).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time

import numpy as np

#: (coarse_divisions, fillet_divisions, grading) per level; 0 = "test", 3 = "coarse", 4 = "medium", 5 = "fine"
LEVELS = [(1.5, 1.0, 2.0), (2.0, 2.0, 1.8), (2.5, 3.0, 1.6), (3.0, 4.0, 1.5), (4.0, 5.0, 1.0), (6.0, 8.0, 0.7)]
STAGES = ("assembly", "factorisation", "solves", "recovery")


def _options(level: int):
    from fe_crank.mesh import MeshOptions

    c, f, g = LEVELS[level]
    return MeshOptions(coarse_divisions=c, fillet_divisions=f, grading=g)


def mesh_only(loadcase: str, level: int) -> None:
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw

    mesh_throw(load_loadcase(loadcase).geometry, size=_options(level), cache_dir=".cache/meshes")


def solve_level(loadcase: str, level: int, solver: str, full_recovery: bool = False) -> dict:
    from fe_crank.assess import assessed_groups
    from fe_crank.assess.superpose import unit_nodal_stress
    from fe_crank.fe import FeOptions, solve_unit_cases
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mesh import mesh_throw

    lc = load_loadcase(loadcase)
    tm = mesh_throw(lc.geometry, size=_options(level), cache_dir=".cache/meshes")
    base = lc.fe or FeOptions()
    units = solve_unit_cases(tm, lc.material, FeOptions(**{**base.__dict__, "solver": solver}))  # with its symmetry
    ids = np.unique(np.concatenate(list(assessed_groups(units).values())))
    t0 = time.perf_counter()
    unit_nodal_stress(units, list(units.cases), ids)
    t_rec = time.perf_counter() - t0
    extra = {}
    if full_recovery:  # the former route: whole-mesh nodal stress of every case, then the assessed nodes
        t0 = time.perf_counter()
        full = np.stack([units.stress_at_nodes(units.displacement(c))[:, ids] for c in units.cases])
        extra["recovery_whole_mesh"] = time.perf_counter() - t0
        again = unit_nodal_stress(units, list(units.cases), ids)
        extra["recovery_max_rel_difference"] = float(np.abs(again - full).max() / np.abs(full).max())
    t = units.timings
    return {
        **extra,
        "level": level,
        "dof": int(units.n_dof),
        "elements": int(tm.mesh.t.shape[1]),
        "assessed_nodes": int(ids.size),
        "cases": len(units.cases),
        "solver": units.solver,
        "assembly": t["assembly"] + t["constraints"],
        "factorisation": t["factorisation"],
        "solves": t["loads"] + t["solve"],
        "recovery": t_rec,
        "fe_total": t["total"] + t_rec,
        "peak_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2,
        "load_average": os.getloadavg(),
    }


def fit(rows: list[dict], key: str) -> float | None:
    """Slope b of log(value) = log(a) + b log(dof) (least squares), None with < 2 levels."""
    pts = [(r["dof"], r[key]) for r in rows if r[key] > 0]
    if len(pts) < 2:
        return None
    n, v = np.log(np.array(pts, float)).T
    return float(np.polyfit(n, v, 1)[0])


def plot(rows: list[dict], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = np.array([r["dof"] for r in rows], float)
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    for key in STAGES + ("fe_total",):
        b = fit(rows, key)
        a1.loglog(n, [r[key] for r in rows], "o-", label=f"{key} (n^{b:.2f})" if b is not None else key)
    a1.set_xlabel("degrees of freedom")
    a1.set_ylabel("time [s]")
    a1.legend(fontsize=8)
    a1.grid(True, which="both", alpha=0.3)
    b = fit(rows, "peak_gb")
    a2.loglog(n, [r["peak_gb"] for r in rows], "s-", label=f"peak RSS (n^{b:.2f})" if b is not None else "peak RSS")
    a2.set_xlabel("degrees of freedom")
    a2.set_ylabel("peak memory [GB]")
    a2.legend(fontsize=8)
    a2.grid(True, which="both", alpha=0.3)
    fig.suptitle("FE stage cost vs size (all unit cases, recovery at the assessed nodes)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loadcase", default="loadcases/single_cylinder_seed001.toml")
    ap.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--json", default=None, help="append one line per level; with --plot, read earlier lines too")
    ap.add_argument("--plot", default=None, help="PNG of time and memory vs DOF")
    ap.add_argument(
        "--full-recovery",
        action="store_true",
        help="also time the whole-mesh recovery of every case (the former route) and compare",
    )
    ap.add_argument("--one", type=int, default=None, help=argparse.SUPPRESS)
    ap.add_argument("--mesh-only", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.one is not None:
        if args.mesh_only:
            mesh_only(args.loadcase, args.one)
        else:
            print(json.dumps(solve_level(args.loadcase, args.one, args.solver, args.full_recovery)))
        return 0
    rows = []
    for level in args.levels:
        base = [sys.executable, __file__, "--one", str(level), "--loadcase", args.loadcase, "--solver", args.solver]
        base += ["--full-recovery"] if args.full_recovery else []
        subprocess.run(base[:8] + ["--mesh-only"], check=True)
        out = subprocess.run(base, check=True, capture_output=True, text=True)
        row = json.loads(out.stdout.strip().splitlines()[-1])
        rows.append(row)
        print(json.dumps(row), flush=True)
        if args.json:
            with open(args.json, "a") as fh:
                fh.write(json.dumps(row) + "\n")
    if args.json and args.plot and os.path.exists(args.json):
        seen = {}
        for line in open(args.json):
            r = json.loads(line)
            seen[r["dof"]] = r
        rows = sorted(seen.values(), key=lambda r: r["dof"])
    for key in STAGES + ("fe_total", "peak_gb"):
        b = fit(rows, key)
        print(f"exponent {key}: {'-' if b is None else f'{b:.2f}'}")
    if args.plot:
        plot(rows, args.plot)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
