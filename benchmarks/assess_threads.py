"""The assess stage of one load case on 1 thread and on N threads, in one process.

Runs the stages before ``assess`` once (load, dynamics, balance, mesh (cached), FE with
the factor released, as ``fe-crank check`` does), then ``assess_case`` alternately with
``threads=1`` and ``threads=N``, ``--repeat`` times, and prints for each its best wall
and CPU seconds (user + system of all threads, ``os.times``), the parallelism CPU / wall
and the peak resident memory while it ran (VmRSS sampled every 20 ms) above the memory
held before it.  Then checks that the two assessments are the same bit for bit: every
group's extremes, safety factors and per-node fields (``np.array_equal``), every
criterion, the notes.  The load average is printed at the start and the end.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/assess_threads.py \
        loadcases/single_cylinder_seed001.toml --preset coarse --threads 2 [--repeat 2]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from check_profile import RssSampler


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def same_assessment(a, b) -> list[str]:
    """Where two assessments differ (empty: the same bit for bit)."""
    diff = []
    if a.criteria != b.criteria:
        diff.append("criteria")
    if a.notes != b.notes:
        diff.append("notes")
    for ta, tb in zip(a.throws, b.throws, strict=True):
        if (ta.m53, ta.m53_nominal, ta.counterweights) != (tb.m53, tb.m53_nominal, tb.counterweights):
            diff.append(f"throw {ta.name}: UR M53 or counterweights")
        for ga, gb in zip(ta.groups, tb.groups, strict=True):
            if ga != gb:
                diff.append(f"throw {ta.name} {ga.group}: results")
            for k in ga.fields:
                if not np.array_equal(ga.fields[k], gb.fields[k]):
                    diff.append(f"throw {ta.name} {ga.group}: field {k}")
    return diff


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("loadcase")
    ap.add_argument("--preset", default="coarse")
    ap.add_argument("--cache-dir", default=".cache/meshes")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)

    from fe_crank.assess import assess_case
    from fe_crank.check.options import CheckOptions
    from fe_crank.check.stages import _balance_stage, _dynamics_stage, _fe_stage, _mesh_stage
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.torsion.stage import dynamics_for_assessment, torsion_stage

    print(
        f"load average at the start {os.getloadavg()[0]:.2f}; cores of this process {len(os.sched_getaffinity(0))}",
        flush=True,
    )
    lc = load_loadcase(args.loadcase)
    dyn = _dynamics_stage(lc)
    bal = _balance_stage(lc)
    meshes = _mesh_stage(lc, CheckOptions(mesh_size=args.preset, cache_dir=args.cache_dir))
    units = _fe_stage(lc, meshes)
    if "torsion" in lc.extras:
        dyn = dynamics_for_assessment(dyn, torsion_stage(lc, units))
    dofs = sum(3 * np.asarray(u.points).shape[1] for u in {id(u): u for u in units.values()}.values())
    sampler = RssSampler(period=0.02)
    sampler.start()
    best, out = {}, {}
    for _ in range(args.repeat):
        for k in (1, args.threads):
            sampler.mark()
            base = sampler.rss()
            w, c = time.perf_counter(), _cpu()
            out[k] = assess_case(lc, dyn, bal, meshes, units, threads=k)
            w, c = time.perf_counter() - w, _cpu() - c
            peak = sampler.mark() - base
            b = best.get(k, (np.inf, np.inf, 0))
            best[k] = (min(b[0], w), min(b[1], c), max(b[2], peak))
    sampler.stop = True
    print(f"{args.loadcase} --preset {args.preset}: {dofs} DOF; assess_case best of {args.repeat}")
    print(f"{'threads':>8} {'wall s':>8} {'cpu s':>8} {'cpu/wall':>9} {'peak above start GB':>20}")
    for k in (1, args.threads):
        w, c, p = best[k]
        print(f"{k:>8} {w:8.2f} {c:8.2f} {c / w:9.2f} {p / 1e9:20.3f}")
    print(f"wall ratio {best[1][0] / best[args.threads][0]:.2f}x, CPU ratio {best[1][1] / best[args.threads][1]:.2f}x")
    diff = same_assessment(out[1], out[args.threads])
    print("identical bit for bit" if not diff else "DIFFERENT: " + "; ".join(diff))
    print(f"load average at the end {os.getloadavg()[0]:.2f}")
    return 0 if not diff else 1


if __name__ == "__main__":
    sys.exit(main())
