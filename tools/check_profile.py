"""Where time and memory go in the real ``fe-crank check`` path, stage by stage.

Runs ``run_case`` of one load case in this process (as ``fe-crank check`` does with
``-j 1``), and records for every stage its wall time, its CPU time (user + system of
all threads, ``os.times``) and the peak resident memory while it ran (``/proc/self/status``
VmRSS sampled every 50 ms by a thread, and the process's ``ru_maxrss``).  Optional:
``--profile FILE`` writes a cProfile of the whole run (read it with ``pstats``),
``--top N`` prints the N most expensive functions by cumulative time.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python tools/check_profile.py \
        loadcases/single_cylinder.toml --preset coarse [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import sys
import tempfile
import threading
import time
from pathlib import Path


class RssSampler(threading.Thread):
    """Peak VmRSS (bytes) since the last ``mark``, sampled every ``period`` seconds."""

    def __init__(self, period: float = 0.05):
        super().__init__(daemon=True)
        self.period = period
        self.peak = 0
        self.stop = False

    @staticmethod
    def rss() -> int:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) * 1024
        return 0

    def mark(self) -> int:
        """Return the peak since the last mark and restart from the current RSS."""
        p = max(self.peak, self.rss())
        self.peak = self.rss()
        return p

    def run(self):
        while not self.stop:
            self.peak = max(self.peak, self.rss())
            time.sleep(self.period)


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("loadcase")
    ap.add_argument("--preset", default="coarse")
    ap.add_argument("--cache-dir", default=".cache/meshes")
    ap.add_argument("--convergence", action="store_true", help="run the hot-spot convergence study too")
    ap.add_argument("--profile", help="write a cProfile of the run here")
    ap.add_argument("--top", type=int, default=0, help="print the N functions with the largest cumulative time")
    ap.add_argument("--json", help="write the per-stage figures here")
    ap.add_argument("--out", help="report folder (default: a temporary one)")
    args = ap.parse_args(argv)

    import logging

    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(message)s", datefmt="%H:%M:%S")
    from fe_crank.pipeline.case import run_case
    from fe_crank.pipeline.options import CheckOptions

    sampler = RssSampler()
    sampler.start()
    rows = []
    state = {"stage": None, "wall": time.perf_counter(), "cpu": _cpu()}

    def close():
        if state["stage"] is not None:
            rows.append(
                {
                    "stage": state["stage"],
                    "wall_s": time.perf_counter() - state["wall"],
                    "cpu_s": _cpu() - state["cpu"],
                    "peak_rss_gb": sampler.mark() / 1e9,
                }
            )

    def on_stage(_path, stage):
        close()
        state.update(stage=stage, wall=time.perf_counter(), cpu=_cpu())

    opts = CheckOptions(
        mesh_size=args.preset,
        cache_dir=args.cache_dir,
        render=False,
        write_vtu=False,
        convergence=bool(args.convergence),
    )
    out = args.out or tempfile.mkdtemp(prefix="check_profile-")
    t0, c0 = time.perf_counter(), _cpu()
    prof = None
    if args.profile or args.top:
        import cProfile

        prof = cProfile.Profile()
        prof.enable()
    result = run_case(args.loadcase, out, opts, on_stage=on_stage)
    if prof is not None:
        prof.disable()
    close()
    total = {
        "wall_s": time.perf_counter() - t0,
        "cpu_s": _cpu() - c0,
        "ru_maxrss_gb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024 / 1e9,
    }
    sampler.stop = True
    print(f"{args.loadcase} --preset {args.preset}: status {result.status} {result.message}")
    print(f"{'stage':<12} {'wall s':>8} {'cpu s':>8} {'peak RSS GB':>12}")
    for r in rows:
        print(f"{r['stage']:<12} {r['wall_s']:8.1f} {r['cpu_s']:8.1f} {r['peak_rss_gb']:12.2f}")
    print(f"{'total':<12} {total['wall_s']:8.1f} {total['cpu_s']:8.1f} {total['ru_maxrss_gb']:12.2f} (ru_maxrss)")
    print(f"load average at the end: {os.getloadavg()[0]:.2f}")
    if prof is not None:
        if args.profile:
            prof.dump_stats(args.profile)
        if args.top:
            import pstats

            pstats.Stats(prof, stream=sys.stdout).sort_stats("cumulative").print_stats(args.top)
    if args.json:
        Path(args.json).write_text(
            json.dumps(
                {
                    "loadcase": args.loadcase,
                    "preset": args.preset,
                    "stages": rows,
                    "total": total,
                    "status": result.status,
                },
                indent=2,
            )
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
