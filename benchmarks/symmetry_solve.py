"""Benchmark: the unit cases of a mirror-symmetric throw, full model vs symmetry components.

The mesh is ``mirrored_throw`` of ``tests/symmetric_meshes.py`` (meshed on its quarter and
mirrored across x = 0 and z = 0).  Each variant runs in its own process (its own peak
memory and CPU clock): ``full`` (``FeOptions(symmetry=False)``), ``sym`` (4 components,
the first component's PARDISO ordering reused by the others), ``sym_own_order`` (each
component reordered by itself).  CPU seconds are user + sys of the FE stage (the mesh
excluded); the split is the stage's own timings (wall).

    .venv/bin/python benchmarks/symmetry_solve.py --size 5e-3
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from pathlib import Path

VARIANTS = ("full", "sym", "sym_own_order")


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def run_one(size: float, variant: str, planes: tuple[int, ...]) -> dict:
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
    from symmetric_meshes import mirrored_throw
    from verification_meshes import Steel

    from fe_crank.fe import FeOptions, solve_unit_cases, symsolve

    throw = mirrored_throw(planes, size=size)
    symsolve.SHARE_ORDERING = variant != "sym_own_order"
    c0, t0 = _cpu(), time.perf_counter()
    sol = solve_unit_cases(throw, Steel(), FeOptions(symmetry=variant != "full"))
    cpu, wall = _cpu() - c0, time.perf_counter() - t0
    t = sol.timings
    return {
        "variant": variant,
        "planes": list(planes),
        "dof": int(sol.n_dof),
        "cpu_s": round(cpu, 2),
        "wall_s": round(wall, 2),
        "assembly_s": round(t["assembly"] + t["constraints"], 2),
        "analysis_s": round(t["analysis"], 2),
        "factorisation_s": round(t["factorisation"], 2),
        "numeric_s": round(t["factorisation"] - t["analysis"], 2),
        "loads_s": round(t["loads"], 2),
        "solves_s": round(t["solve"], 2),
        "cases": len(sol.cases),
        "max_equilibrium_error": float(max(c.equilibrium_error for c in sol.cases.values())),
        "peak_rss_gb": round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2, 2),
        "solver": sol.solver_description,
        "load_avg": os.getloadavg()[0],
    }


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", type=float, default=5e-3, help="element size, m")
    p.add_argument("--planes", default="0,2", help="mirror axes, e.g. 0,2 or 2")
    p.add_argument("--variant", action="append", choices=VARIANTS)
    p.add_argument("--one", action="store_true", help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    planes = tuple(int(a) for a in args.planes.split(","))
    if args.one:
        print(json.dumps(run_one(args.size, args.variant[0], planes)))
        return 0
    rows = []
    for v in args.variant or VARIANTS:
        out = subprocess.run(
            [sys.executable, __file__, "--one", "--size", str(args.size), "--variant", v, "--planes", args.planes],
            capture_output=True,
            text=True,
        )
        if out.returncode != 0:
            print(out.stderr, file=sys.stderr)
            return out.returncode
        rows.append(json.loads(out.stdout.strip().splitlines()[-1]))
        print(json.dumps(rows[-1]), flush=True)
    full = next((r for r in rows if r["variant"] == "full"), None)
    if full:
        for r in rows:
            if r is not full:
                print(
                    f"{r['variant']}: CPU {r['cpu_s']:.1f} s vs full {full['cpu_s']:.1f} s, "
                    f"ratio {r['cpu_s'] / full['cpu_s']:.2f}"
                )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
