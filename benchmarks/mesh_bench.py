"""Meshing time and size of a crank throw at several refinement levels.

Each level runs in its own process (peak memory measured with ``getrusage``), without
the cache.  Usage::

    .venv/bin/python benchmarks/mesh_bench.py [GEOMETRY.toml] [--levels coarse medium fine]
        [--mem-limit-gb 4] [--markdown table.md]   (figures in docs/performance.md)

Prints one line per level: preset, fillet rule, nodes, quadratic tets, P2 DOFs, largest
fillet edge / r, min quality, straightened elements, gmsh+conversion time, peak RSS.
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

ROOT = Path(__file__).resolve().parents[1]


def _child(geometry: str, level: str) -> None:
    from fe_crank.io.geometry import load_geometry
    from fe_crank.mesh import PRESETS, mesh_throw

    g = load_geometry(geometry)
    t0 = time.perf_counter()
    tm = mesh_throw(g, size=level, cache_dir=None)
    wall = time.perf_counter() - t0
    s = tm.stats
    ratio = max(h / s.fillet_radii[k] for k, h in s.fillet_max_edge.items())
    out = {
        "level": level,
        "fillet_divisions": PRESETS[level].fillet_divisions,
        "nodes": s.nodes,
        "elements": s.elements,
        "p2_dofs": s.p2_dofs,
        "fillet_edge_over_r": ratio,
        "min_quality": s.min_quality,
        "straightened": s.straightened,
        "seconds": wall,
        "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
    }
    print("RESULT " + json.dumps(out))


def _machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    mem = ""
    try:
        kb = int(Path("/proc/meminfo").read_text().split()[1])
        mem = f", {kb / 1024**2:.0f} GB RAM"
    except (OSError, ValueError, IndexError):
        pass
    import gmsh

    return f"{cpu}, {os.cpu_count()} cores{mem}, Python {platform.python_version()}, gmsh {gmsh.__version__}"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("geometry", nargs="?", default=str(ROOT / "geometry" / "v4_90_pneumatic_seed003.toml"))
    ap.add_argument("--levels", nargs="+", default=["test", "coarse", "medium", "fine"])
    ap.add_argument("--mem-limit-gb", type=float, default=6.0, help="address-space limit of each child")
    ap.add_argument("--timeout", type=float, default=900.0)
    ap.add_argument("--markdown", default=None, help="append a Markdown table to this file")
    ap.add_argument("--child", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        _child(args.geometry, args.child)
        return 0
    rows = []
    for level in args.levels:
        limit = int(args.mem_limit_gb * 1024**3)

        def _limit(limit=limit):
            resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

        try:
            proc = subprocess.run(
                [sys.executable, __file__, args.geometry, "--child", level],
                capture_output=True,
                text=True,
                timeout=args.timeout,
                preexec_fn=_limit,
                env={**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"},
            )
        except subprocess.TimeoutExpired:
            print(f"{level}: timed out after {args.timeout:.0f} s")
            rows.append({"level": level, "failed": f"timeout {args.timeout:.0f} s"})
            continue
        line = next((x for x in proc.stdout.splitlines() if x.startswith("RESULT ")), None)
        if line is None:
            tail = (proc.stderr or proc.stdout).strip().splitlines()[-1:] or ["no output"]
            print(f"{level}: failed (rc {proc.returncode}): {tail[0]}")
            rows.append({"level": level, "failed": f"rc {proc.returncode}: {tail[0][:120]}"})
            continue
        r = json.loads(line[len("RESULT ") :])
        rows.append(r)
        print(
            f"{level:7s} r/{r['fillet_divisions']:<4g} nodes {r['nodes']:>8d} tets {r['elements']:>8d} "
            f"P2 DOFs {r['p2_dofs']:>8d} fillet edge r/{1 / r['fillet_edge_over_r']:.2f} "
            f"minSICN {r['min_quality']:.3f} straightened {r['straightened']:>5d} "
            f"{r['seconds']:7.1f} s {r['peak_rss_mb']:7.0f} MB"
        )
    machine = _machine()
    print(machine)
    if args.markdown:
        lines = [
            "",
            f"### {Path(args.geometry).name}, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}",
            "",
            f"Machine: {machine}.  Command: `.venv/bin/python benchmarks/mesh_bench.py {Path(args.geometry).relative_to(ROOT) if Path(args.geometry).is_relative_to(ROOT) else args.geometry} --levels {' '.join(args.levels)}`",
            "",
            "| preset | fillet rule | nodes | quadratic tets | P2 DOFs | largest fillet edge | min SICN | straightened | time (s) | peak RSS (MB) |",
            "|---|---|---|---|---|---|---|---|---|---|",
        ]
        for r in rows:
            if "failed" in r:
                lines.append(f"| {r['level']} | | | | | | | | failed: {r['failed']} | |")
            else:
                lines.append(
                    f"| {r['level']} | r/{r['fillet_divisions']:g} | {r['nodes']} | {r['elements']} | {r['p2_dofs']} | "
                    f"r/{1 / r['fillet_edge_over_r']:.2f} | {r['min_quality']:.3f} | {r['straightened']} | "
                    f"{r['seconds']:.1f} | {r['peak_rss_mb']:.0f} |"
                )
        with open(args.markdown, "a") as fh:
            fh.write("\n".join(lines) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
