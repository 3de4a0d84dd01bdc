"""Timing harness of fe-crank's stages: the figures of docs/performance.md, with the machine.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/perf/run.py --preset test \\
        [--preset coarse ...] [--only mesh,fe,cycle,fatigue,sweep] [--loadcase FILE] [--json FILE]

For each preset, each of ``mesh``, ``fe`` and ``cycle`` runs in a process of its own
(its own peak memory) on the load case's first throw; ``fatigue`` runs once on synthetic
paths (``stages.py`` says what each one times); ``sweep`` checks the load case at its
operating speed and over ``--sweep-speeds`` speeds of ``--sweep-range`` on the same
mesh (``sweep.py``: what the full-load sweep adds to the check).  With two presets or more, the exponent
b of t = a n^b (least squares of log t on log n, n = DOF) is fitted to each FE figure,
and ``--plot FILE`` draws them.  Prints one line per stage and preset as it finishes and
writes every figure, the command, the date, the git commit and the machine (CPU, cores,
memory, load average before and after, library versions) to ``--json`` (default
reports/perf.json).  Timings depend on the machine's load: run it on an idle machine and
compare figures from one JSON, not across machines.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
STAGES = ("mesh", "fe", "cycle", "fatigue", "sweep")
FE_FIGURES = ("assembly_s", "factorisation_s", "solves_s", "recovery_s", "fe_total_s", "peak_rss_mb")


def machine() -> dict:
    """What the figures were measured on."""
    import gmsh
    import scipy
    import skfem

    cpu = platform.processor() or platform.machine()
    try:
        cpu = next(
            x.split(":", 1)[1].strip()
            for x in Path("/proc/cpuinfo").read_text().splitlines()
            if x.startswith("model name")
        )
    except (OSError, StopIteration):
        pass
    try:
        mem_gb = int(Path("/proc/meminfo").read_text().split()[1]) / 1024**2
    except (OSError, ValueError, IndexError):
        mem_gb = None
    try:
        import pypardiso  # noqa: F401

        pardiso = True
    except ImportError:
        pardiso = False
    return {
        "cpu": cpu,
        "cores": os.cpu_count(),
        "cores_of_this_process": len(os.sched_getaffinity(0)),
        "memory_gb": mem_gb,
        "os": platform.platform(),
        "python": platform.python_version(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "scikit_fem": getattr(skfem, "__version__", "unknown"),
        "gmsh": gmsh.__version__,
        "pypardiso": pardiso,
        "threads_env": {k: os.environ.get(k) for k in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS")},
    }


def _commit() -> str | None:
    try:
        rev = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True, check=True).stdout
        dirty = subprocess.run(["git", "status", "--porcelain"], cwd=ROOT, capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    return rev.strip() + (" (modified)" if dirty.strip() else "")


def fit(rows: list[dict], key: str) -> float | None:
    """Slope b of log(value) = log(a) + b log(dof) (least squares); None with < 2 points."""
    pts = [(r["dof"], r[key]) for r in rows if r.get(key, 0) > 0]
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
    for key in FE_FIGURES[:-1]:
        b = fit(rows, key)
        a1.loglog(n, [r[key] for r in rows], "o-", label=key if b is None else f"{key} (n^{b:.2f})")
    b = fit(rows, "peak_rss_mb")
    a2.loglog(
        n, [r["peak_rss_mb"] / 1024 for r in rows], "s-", label="peak RSS" if b is None else f"peak RSS (n^{b:.2f})"
    )
    for ax, label in ((a1, "time [s]"), (a2, "peak memory [GB]")):
        ax.set_xlabel("degrees of freedom")
        ax.set_ylabel(label)
        ax.legend(fontsize=8)
        ax.grid(True, which="both", alpha=0.3)
    fig.suptitle("FE stage cost vs size (all unit cases, recovery at the assessed nodes)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def _child(args) -> dict:
    sys.path.insert(0, str(HERE))
    import stages

    stage, preset = args.child
    if stage == "mesh":
        return stages.mesh(args.loadcase, preset)
    if stage == "warm":
        return stages.warm(args.loadcase, preset, args.cache_dir)
    if stage == "fe":
        return stages.fe(args.loadcase, preset, args.cache_dir, args.solver, not args.no_symmetry)
    if stage == "cycle":
        return stages.cycle(args.loadcase, preset, args.cache_dir, args.solver, args.angles)
    if stage == "sweep":
        import sweep

        lo, hi = (float(x) for x in args.sweep_range.split(","))
        return sweep.sweep(args.loadcase, preset, args.cache_dir, args.sweep_speeds, lo, hi, args.repeat)
    return stages.fatigue(args.nodes, args.repeat, args.threads)


def _run(stage: str, preset: str, args) -> dict:
    """One stage in a fresh process; its figures, or the reason it failed."""
    cmd = [
        sys.executable,
        __file__,
        "--child",
        stage,
        preset,
        "--loadcase",
        args.loadcase,
        "--cache-dir",
        args.cache_dir,
    ]
    cmd += ["--solver", args.solver, "--angles", str(args.angles), "--nodes", str(args.nodes)]
    cmd += ["--sweep-speeds", str(args.sweep_speeds), "--sweep-range", args.sweep_range]
    cmd += ["--repeat", str(args.repeat), "--threads", str(args.threads)] + (
        ["--no-symmetry"] if args.no_symmetry else []
    )
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout)
    except subprocess.TimeoutExpired:
        return {"preset": preset, "failed": f"timed out after {args.timeout:.0f} s"}
    line = next((x for x in reversed(p.stdout.splitlines()) if x.startswith("RESULT ")), None)
    if line is None:
        tail = (p.stderr or p.stdout).strip().splitlines()[-1:] or ["no output"]
        return {"preset": preset, "failed": f"exit {p.returncode}: {tail[0][:200]}"}
    return json.loads(line[len("RESULT ") :])


def _line(stage: str, r: dict) -> str:
    if "failed" in r:
        return f"{stage:8s} {r.get('preset', '')}: FAILED {r['failed']}"
    skip = {"preset", "solver", "assess_group_threads"}
    items = [f"{k} {v:.4g}" if isinstance(v, float) else f"{k} {v}" for k, v in r.items() if k not in skip]
    return f"{stage:8s} {r.get('preset', '')}: " + ", ".join(items)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0], allow_abbrev=False)
    ap.add_argument(
        "--preset", nargs="+", action="extend", help="mesh presets (test, coarse, medium, fine); default test"
    )
    ap.add_argument("--only", default=",".join(STAGES), help=f"stages to run, comma-separated ({','.join(STAGES)})")
    ap.add_argument("--loadcase", default=str(ROOT / "loadcases" / "single_cylinder.toml"))
    ap.add_argument(
        "--cache-dir", default=str(ROOT / ".cache" / "meshes"), help="mesh cache of the fe and cycle stages"
    )
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--no-symmetry", action="store_true", help="fe stage: the whole model, not the symmetry components")
    ap.add_argument("--angles", type=int, default=3, help="cycle stage: crank angles solved directly")
    ap.add_argument("--nodes", type=int, default=4096, help="fatigue stage: synthetic nodes")
    ap.add_argument("--repeat", type=int, default=3, help="fatigue and sweep stages: best of this many runs")
    ap.add_argument("--sweep-speeds", type=int, default=20, help="sweep stage: speeds of the sweep")
    ap.add_argument("--sweep-range", default="1000,2800", help="sweep stage: lowest,highest speed in rpm")
    ap.add_argument("--threads", type=int, default=0, help="fatigue stage: also one group on 1 and on N threads")
    ap.add_argument("--timeout", type=float, default=3600.0, help="seconds per stage and preset")
    ap.add_argument("--json", default=str(ROOT / "reports" / "perf.json"), help="where the figures go")
    ap.add_argument("--plot", help="PNG of the FE figures against DOF (two presets or more)")
    ap.add_argument("--child", nargs=2, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.child:
        print("RESULT " + json.dumps(_child(args)), flush=True)
        return 0
    only = [s.strip() for s in args.only.split(",") if s.strip()]
    bad = [s for s in only if s not in STAGES]
    if bad:
        ap.error(f"unknown stage(s) {', '.join(bad)}; choose from {', '.join(STAGES)}")
    presets = args.preset or ["test"]
    doc: dict = {
        "command": " ".join([Path(sys.argv[0]).name, *(argv if argv is not None else sys.argv[1:])]),
        "date_utc": time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime()),
        "commit": _commit(),
        "machine": machine(),
        "load_average_before": os.getloadavg(),
        "loadcase": args.loadcase,
        "presets": presets,
    }
    failed = False
    for stage in (s for s in STAGES if s in only):
        rows = []
        for preset in presets if stage != "fatigue" else ["-"]:
            if stage in ("fe", "cycle"):
                _run("warm", preset, args)  # the mesh read from the cache: not in this stage's memory
            r = _run(stage, preset, args)
            failed |= "failed" in r
            rows.append(r)
            print(_line(stage, r), flush=True)
        doc[stage] = rows if stage != "fatigue" else rows[0]
    fe_rows = [r for r in doc.get("fe", []) if "failed" not in r]
    if len(fe_rows) >= 2:
        doc["fe_exponents"] = {k: fit(fe_rows, k) for k in FE_FIGURES}
        print(
            "exponents of the FE figures against DOF: "
            + ", ".join(f"{k} {v:.2f}" for k, v in doc["fe_exponents"].items() if v is not None)
        )
        if args.plot:
            plot(fe_rows, args.plot)
    doc["load_average_after"] = os.getloadavg()
    out = Path(args.json)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"{doc['machine']['cpu']}, {doc['machine']['cores']} cores; figures in {out}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
