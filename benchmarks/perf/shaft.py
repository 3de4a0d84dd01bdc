"""Benchmark: the whole-shaft model (mesh, condensation, unit cases, cycle, the stress
assessment of every assessed group of every throw) and its cost growth.

One run per process (its own peak memory): the shaft of a geometry and an engine at a mesh
preset, the engine's own operating speed from a load case, or the inertia loads of a
made-up small engine for the growth study (``--throws n``: the small test shaft of
tests/data/geometry_small_shaft.toml with n throws at 0/180 deg alternately).

    .venv/bin/python benchmarks/perf/shaft.py --loadcase loadcases/inline4_rated.toml --preset coarse
    .venv/bin/python benchmarks/perf/shaft.py --throws 4 --preset test
    .venv/bin/python benchmarks/perf/shaft.py --growth 1 2 4 6 --preset test

Prints the stage times (wall), the CPU seconds, the peak resident memory and the unknowns.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def _peak_gb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def run(args) -> dict:
    import numpy as np

    from fe_crank import model
    from fe_crank.assess.shaft import assess_shaft_throws
    from fe_crank.assess.workers import threads
    from fe_crank.fe.shaft.whole_shaft import analyse_whole_shaft, throw_masses
    from fe_crank.geometry.shaft import shaft_layout
    from fe_crank.mechanism.dynamics import analyse
    from fe_crank.mesh.shaft import mesh_shaft

    t0 = time.perf_counter()
    if args.loadcase:
        from fe_crank.io.loadcase import load_loadcase

        lc = load_loadcase(args.loadcase)
        g, e, material, op = lc.geometry, lc.engine, lc.material, lc.operating
        if args.geometry:
            from fe_crank.io.geometry import load_geometry

            g = load_geometry(args.geometry)
        if args.engine:
            from fe_crank.io.engine import load_engine

            e = load_engine(args.engine)
    else:
        sys.path.insert(0, str(ROOT / "tests"))
        from helpers.shaft import small_engine, small_geometry

        from fe_crank.io.material import load_material

        angles = [0.0 if i % 2 == 0 else np.pi for i in range(args.throws)]
        g, e, material = small_geometry(angles), small_engine(angles), load_material("42CrMo4")
        op = model.OperatingPoint(speed=4000 * 2 * np.pi / 60)
    layout = shaft_layout(g, e, geometry_file=str(g.file), engine_file=str(args.engine or "engine"))
    dyn = analyse(e, op)
    t_mesh = time.perf_counter()
    sm = mesh_shaft(layout, size=args.preset, cache_dir=args.cache)
    t_mesh = time.perf_counter() - t_mesh
    result, cases = analyse_whole_shaft(sm, material, dyn, mass=throw_masses(layout))
    result = dataclasses.replace(result, timings={"mesh": t_mesh, **result.timings})
    t1 = time.perf_counter()
    with threads(2):
        throws, _ = assess_shaft_throws(cases, result, dyn.theta, material, crank_radius=g.crank_radius, overspeed=None)
    result.timings["assessment"] = time.perf_counter() - t1
    out = {
        "groups": sum(len(t.groups) for t in throws),
        "throws": len(layout.throws),
        "preset": args.preset,
        "n_dof": result.n_dof,
        "interface_dofs": cases.model.n_interface,
        "wall_s": time.perf_counter() - t0,
        "cpu_s": _cpu(),
        "peak_gb": _peak_gb(),
        "timings": {k: round(v, 2) for k, v in result.timings.items()},
        "peak_bearing_load_n": {b.name: round(b.with_counterweights.peak_n, 1) for b in result.bearings},
    }
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--loadcase")
    ap.add_argument("--geometry")
    ap.add_argument("--engine")
    ap.add_argument("--throws", type=int, default=4)
    ap.add_argument("--growth", type=int, nargs="*")
    ap.add_argument("--preset", default="test")
    ap.add_argument("--cache", default=str(ROOT / ".cache" / "meshes"))
    args = ap.parse_args()
    if args.growth:
        for n in args.growth:
            cmd = [sys.executable, __file__, "--throws", str(n), "--preset", args.preset, "--cache", args.cache]
            print(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout.strip())
        return
    print(json.dumps(run(args)))


if __name__ == "__main__":
    main()
