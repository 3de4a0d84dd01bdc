"""Benchmark of the FE stage: DOFs, assembly, factorisation, per-case solve, peak memory.

Each mesh size runs in its own process so that its peak memory (ru_maxrss) is its own.

    .venv/bin/python benchmarks/fe_solve.py                       # sizes 8, 5, 3.2 mm
    .venv/bin/python benchmarks/fe_solve.py --size 2.6e-3         # one size (~1M dof)
    .venv/bin/python benchmarks/fe_solve.py --solver amg --size 5e-3
    .venv/bin/python benchmarks/fe_solve.py --geometry geometry/v4_90_pneumatic_seed003.toml --preset medium

With ``--geometry``, the real throw of that geometry file is meshed by ``mesh_throw``
(filleted, graded to the fillets by the preset: coarse = r/4 of IACS UR M53, medium = r/5)
instead of the fillet-less uniform test throw.

The geometry is ``simple_throw`` of ``tests/verification_meshes.py`` (journals d 50 mm,
pin d 45 mm, R 45 mm, webs 20 mm, no fillets), uniform element size, P2 tetrahedra.
Results are printed as one JSON line per size (and appended to --json if given).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import subprocess
import sys
import time
from pathlib import Path


def run_one(size: float, solver: str, geometry: str | None = None, preset: str = "coarse") -> dict:
    from dataclasses import dataclass

    from fe_crank.fe import FeOptions, solve_unit_cases

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from verification_meshes import simple_throw  # the test geometry (tests/verification_meshes.py)

    @dataclass(frozen=True)
    class Steel:
        youngs_modulus: float = 210e9
        poisson_ratio: float = 0.3
        density: float = 7850.0

    t0 = time.perf_counter()
    if geometry:
        from fe_crank.io.geometry import load_geometry
        from fe_crank.mesh import mesh_throw

        mesh = mesh_throw(load_geometry(geometry), size=preset, cache_dir=".cache/meshes").mesh
    else:
        mesh = simple_throw(size=size)
    t_mesh = time.perf_counter() - t0
    sol = solve_unit_cases(mesh, Steel(), FeOptions(solver=solver))
    t0 = time.perf_counter()
    u = sol.combine({"centrifugal": 1e4, "pin_-y": 5e4, "torque": 1e3})
    s = sol.stress_at_nodes(u)
    vm = float(sol.von_mises(s).max())
    t_stress = time.perf_counter() - t0
    t = sol.timings
    return {
        "model": f"{geometry} ({preset})" if geometry else f"simple_throw({size})",
        "solver": sol.solver,
        "elements": int(mesh.nelements),
        "dof": int(sol.n_dof),
        "nnz": sol.system.factorisation.nnz,
        "mesh_s": round(t_mesh, 2),
        "assembly_s": round(t["assembly"] + t["constraints"], 2),
        "factorisation_s": round(t["factorisation"], 2),
        "loads_s": round(t["loads"], 2),
        "solve_6_cases_s": round(t["solve"], 2),
        "solve_per_case_s": round(t["solve_per_case"], 3),
        "stress_recovery_s": round(t_stress, 2),
        "fe_total_s": round(t["total"], 2),
        "max_equilibrium_error": float(max(c.equilibrium_error for c in sol.cases.values())),
        "peak_rss_gb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2, 2),
        "vm_max_pa": vm,
        "cpus": os.cpu_count(),
        "machine": platform.processor() or platform.machine(),
    }


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", type=float, action="append", help="element size, m (repeatable)")
    p.add_argument("--solver", default="auto")
    p.add_argument("--geometry", help="a geometry file: benchmark its real (filleted) first throw")
    p.add_argument("--preset", default="coarse", help="mesh preset with --geometry (test, coarse, medium, fine)")
    p.add_argument("--json", help="append results to this file")
    p.add_argument("--one", action="store_true", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    sizes = args.size or [8e-3, 5e-3, 3.2e-3]
    if args.one:
        print(json.dumps(run_one(sizes[0], args.solver, args.geometry, args.preset)))
        return 0
    if args.geometry:
        sizes = sizes[:1]
    for size in sizes:
        extra = ["--geometry", args.geometry, "--preset", args.preset] if args.geometry else []
        out = subprocess.run(
            [sys.executable, __file__, "--one", "--size", str(size), "--solver", args.solver, *extra],
            capture_output=True,
            text=True,
        )
        if out.returncode != 0:
            print(out.stderr, file=sys.stderr)
            return out.returncode
        line = out.stdout.strip().splitlines()[-1]
        print(line, flush=True)
        if args.json:
            with open(args.json, "a") as fh:
                fh.write(line + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
